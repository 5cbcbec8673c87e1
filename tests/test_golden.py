"""The studies' numbers stay what they were: a refactor must not change them.

``tests/data/golden_*.json`` were written by ``tests/data/make_golden.py`` from a tiny WNN study
(every row of both tables, the settings search, a sweep point, a reference) and a tiny DR study
(every filter on a DR-only and a GPS/DR scenario), before the module refactor. Timings are left out.

On a machine that rounds like the one that wrote them (the same ``blas_fingerprint``: its BLAS
results, NumPy's SIMD targets and a digest of its elementwise functions), every number must
match to 1e-9 (relative). Elsewhere OpenBLAS picks other kernels, whose
last-bit differences some trainings amplify by orders of magnitude (measured with
``OPENBLAS_CORETYPE=Sandybridge``/``Prescott``: the paper-settings rows at Q = 1, the scikit-learn
reference, the EPF and BP's search up to 100 %, every other number below 1e-7): there the
numbers that are stable across kernels must match to 1e-6, which any change to an algorithm
exceeds, and the amplifying ones are not compared. A change meant to alter the numbers
regenerates the files and says so.
"""
import json
import math
import os
import sys

import pytest

HERE = os.path.join(os.path.dirname(__file__), "data")
sys.path.insert(0, HERE)
import make_golden  # noqa: E402

STRICT, LOOSE = 1e-9, 1e-6


def _amplifying(row):
    """Rows whose training amplifies last-bit BLAS differences (see the module docstring)."""
    if row.get("table") in ("paper", "reference"):
        return True
    if row.get("table") == "tuning" or "candidate" in row:
        return row.get("trainer") in ("bp", "epf")
    return row.get("trainer") == "epf"


def _compare(got, want, rtol, path="$"):
    if isinstance(want, dict):
        assert isinstance(got, dict), path
        assert sorted(got) == sorted(want), f"{path}: keys {sorted(got)} != {sorted(want)}"
        for k in want:
            _compare(got[k], want[k], rtol, f"{path}.{k}")
    elif isinstance(want, list):
        assert isinstance(got, list) and len(got) == len(want), f"{path}: length {len(got)} != {len(want)}"
        for i, (g, w) in enumerate(zip(got, want)):
            _compare(g, w, rtol, f"{path}[{i}]")
    elif isinstance(want, float) and not isinstance(want, bool):
        if math.isnan(want):
            assert isinstance(got, float) and math.isnan(got), f"{path}: {got!r} != nan"
        else:
            assert got == pytest.approx(want, rel=rtol, abs=1e-12), f"{path}: {got!r} != {want!r}"
    else:
        assert got == want, f"{path}: {got!r} != {want!r}"


def _stable_part(data):
    """``data`` without the amplifying rows (and the training curves of the runs among them)."""
    out = dict(data)
    if "runs" in data:
        keep = [not _amplifying(r) for r in data["runs"]]
        out["runs"] = [r for r, k in zip(data["runs"], keep) if k]
        out["curves"] = [c for c, k in zip(data["curves"], keep) if k]
        out["table"] = [r for r in data["table"] if not _amplifying(r)]
        out["tuning"] = [r for r in data["tuning"] if not _amplifying(r)]
    return out


@pytest.mark.parametrize("name, fn", [("golden_wnn.json", make_golden.wnn_numbers),
                                      ("golden_dr.json", make_golden.dr_numbers)])
def test_study_numbers_unchanged(name, fn):
    with open(os.path.join(HERE, name)) as f:
        want = json.load(f)
    same_blas = want.pop("fingerprint") == make_golden.blas_fingerprint()
    got = json.loads(json.dumps(make_golden._plain(fn())))
    if same_blas:
        _compare(got, want, STRICT)
    else:
        _compare(_stable_part(got), _stable_part(want), LOOSE)


def test_the_loose_comparison_still_catches_a_real_change():
    with open(os.path.join(HERE, "golden_wnn.json")) as f:
        want = _stable_part(json.load(f))
    got = json.loads(json.dumps(want))
    row = next(r for r in got["table"] if r["trainer"] == "ekf")
    row["test_mse_median"] *= 1 + 1e-4
    with pytest.raises(AssertionError, match="test_mse_median"):
        _compare(got, want, LOOSE)
    assert len(want["runs"]) > 10 and len(want["tuning"]) > 30  # most of the study is still compared
