"""The studies' numbers stay what they were: a refactor must not change them.

``tests/data/golden_*.json`` were written by ``tests/data/make_golden.py`` from a tiny WNN study
(every row of both tables, the settings search, a sweep point, a reference) and a tiny DR study
(every filter on a DR-only and a GPS/DR scenario). Timings are left out; every other number must
match to 1e-9 (relative). A change meant to alter the numbers regenerates them and says so.
"""
import json
import math
import os
import sys

import pytest

HERE = os.path.join(os.path.dirname(__file__), "data")
sys.path.insert(0, HERE)
import make_golden  # noqa: E402

RTOL = 1e-9


def _compare(got, want, path="$"):
    if isinstance(want, dict):
        assert isinstance(got, dict), path
        assert sorted(got) == sorted(want), f"{path}: keys {sorted(got)} != {sorted(want)}"
        for k in want:
            _compare(got[k], want[k], f"{path}.{k}")
    elif isinstance(want, list):
        assert isinstance(got, list) and len(got) == len(want), f"{path}: length {len(got)} != {len(want)}"
        for i, (g, w) in enumerate(zip(got, want)):
            _compare(g, w, f"{path}[{i}]")
    elif isinstance(want, float) and not isinstance(want, bool):
        if math.isnan(want):
            assert isinstance(got, float) and math.isnan(got), f"{path}: {got!r} != nan"
        else:
            assert got == pytest.approx(want, rel=RTOL, abs=1e-12), f"{path}: {got!r} != {want!r}"
    else:
        assert got == want, f"{path}: {got!r} != {want!r}"


@pytest.mark.parametrize("name, fn", [("golden_wnn.json", make_golden.wnn_numbers),
                                      ("golden_dr.json", make_golden.dr_numbers)])
def test_study_numbers_unchanged(name, fn):
    with open(os.path.join(HERE, name)) as f:
        want = json.load(f)
    got = json.loads(json.dumps(make_golden._plain(fn())))
    _compare(got, want)
