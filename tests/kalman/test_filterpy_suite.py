"""filterpy's own ``kalman/tests/test_ukf.py``, run with filterwnn's classes renamed in.

A filterpy user swaps a class by one import line and changes nothing else; so does this
test: it reads the copy (``filterpy_test_ukf.py``, MIT licence, header kept), rewrites only
the import lines and runs every ``test_*`` function in it. The renames:

``ukf``
    ``from filterwnn import UnscentedKalmanFilter`` in place of filterpy's;
``minimal-skew``, ``spherical-simplex``
    that, and ``from filterwnn import <set> as MerweScaledSigmaPoints``: every
    ``MerweScaledSigmaPoints(n, alpha, beta, kappa)`` call of the file (``kappa`` in
    ``{-1, 0, 0.1, 1, 3 - n}``, positionally and by keyword) builds an ``n + 2`` set.

filterpy's tests drew from NumPy's global random state (some seed it, some do not); the
copy draws from one explicit generator instead (its header says how), which is reseeded
here before each test, so a failure reproduces and nothing touches the global state.
"""

import pathlib
import types
import warnings

import numpy as np
import pytest

SOURCE = pathlib.Path(__file__).with_name("filterpy_test_ukf.py")
UKF_LINE = "from filterpy.kalman import UnscentedKalmanFilter\n"
MERWE_LINE = "from filterpy.kalman import (unscented_transform, MerweScaledSigmaPoints,\n"


def _renames(points=None):
    out = {UKF_LINE: "from filterwnn import UnscentedKalmanFilter\n"}
    if points is not None:
        out[MERWE_LINE] = (f"from filterwnn import {points} as MerweScaledSigmaPoints\n"
                           "from filterpy.kalman import (unscented_transform,\n")
    return out


RENAMES = {
    "ukf": _renames(),
    "minimal-skew": _renames("MinimalSkewSigmaPoints"),
    "spherical-simplex": _renames("SphericalSimplexSigmaPoints"),
}
_MODULES = {}


def _module(label):
    """The copy with ``RENAMES[label]`` applied, executed as a module (cached)."""
    if label not in _MODULES:
        text = SOURCE.read_text()
        for old, new in RENAMES[label].items():
            assert text.count(old) == 1, f"the import line {old!r} is not in the copy"
            text = text.replace(old, new)
        mod = types.ModuleType(f"filterpy_test_ukf_{label.replace('-', '_')}")
        mod.__file__ = str(SOURCE)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", (DeprecationWarning, SyntaxWarning))  # its '\k' in a label
            exec(compile(text, str(SOURCE), "exec"), mod.__dict__)
        _MODULES[label] = mod
    return _MODULES[label]


def _test_names():
    text = SOURCE.read_text()
    return [line[4:line.index("(")] for line in text.splitlines() if line.startswith("def test_")]


def test_the_copy_holds_filterpys_sixteen_tests():
    assert len(_test_names()) == 16


@pytest.mark.parametrize("label", list(RENAMES))
def test_the_rename_reaches_the_classes(label):
    mod = _module(label)
    assert mod.UnscentedKalmanFilter.__module__ == "filterwnn.kalman.unscented"
    expected = {"ukf": "filterpy.kalman.sigma_points"}.get(label, "filterwnn.kalman.sigma_points")
    assert mod.MerweScaledSigmaPoints.__module__ == expected


def _global_state():
    """NumPy's global generator state as comparable values (the key, the position, the cached normal)."""
    _, key, pos, has_gauss, gauss = np.random.get_state()
    return key.tobytes(), pos, has_gauss, gauss


@pytest.mark.parametrize("name", _test_names())
@pytest.mark.parametrize("label", list(RENAMES))
def test_filterpy_test_ukf_passes_with_a_plain_rename(label, name):
    mod = _module(label)
    fn = getattr(mod, name)
    mod._seed(0)  # the copy's own generator (never NumPy's global state), reseeded per test
    before = _global_state()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        fn()
    assert _global_state() == before, "the test drew from NumPy's global state"
