"""The unscented bank's compiled kernels (numba) against its NumPy step and filterpy's UKF.

The kernels sum in another order than the NumPy step, so the two agree to rounding (1e-12,
the bank's tolerance against filterpy), not bit for bit; what must hold exactly is that a
member's numbers do not depend on where it sits in the bank (the kernels work in blocks).
"""

import numpy as np
import pytest
from filterpy.kalman import JulierSigmaPoints, MerweScaledSigmaPoints
from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF

from filterwnn import NumericalError
from filterwnn.kalman import SphericalSimplexSigmaPoints, UnscentedKalmanFilterBank
from filterwnn.kalman import _compiled
from filterwnn.kalman.batched import UnscentedStep

pytestmark = pytest.mark.skipif(not _compiled.available(), reason="numba is not installed (pip install '.[fast]')")

TOL = 1e-12
DT = 0.1


def _fx(X, dt):
    """A nonlinear transition of any width n >= 2 on the last axis (one point or rows)."""
    Y = 0.97 * X
    Y[..., 0] = X[..., 0] + dt * X[..., 1] * np.cos(X[..., -1])
    Y[..., 1] = X[..., 1] + dt * np.sin(X[..., 0])
    return Y


def _hx(m):
    def hx(X):
        cols = [np.sqrt(1.0 + X[..., 0] ** 2 + X[..., -1] ** 2)] + [np.arctan(X[..., j]) for j in range(1, m)]
        return np.stack(cols, axis=-1)
    return hx


def _problem(Bn, n, m, n_steps, seed=0):
    g = np.random.default_rng(seed)
    x0 = g.normal(0.0, 0.5, (Bn, n))
    A = g.normal(0.0, 0.3, (Bn, n, n))
    P0 = np.matmul(A, np.swapaxes(A, 1, 2)) + 0.2 * np.eye(n)
    Q = np.stack([np.eye(n) * q for q in np.linspace(1e-3, 5e-3, Bn)])
    R = np.stack([np.eye(m) * r + 0.01 * np.ones((m, m)) for r in np.linspace(0.02, 0.1, Bn)])
    zs = g.normal(0.0, 0.3, (n_steps, Bn, m)) + 1.0
    if Bn > 3:
        zs[1, 2] = np.nan  # one member misses a step
    return x0, P0, Q, R, zs


def _run(compiled, points, prob, m, shared=False, hx=None, fx=_fx, **kw):
    """A bank on ``prob = (x0, P0, Q, R, zs)`` (``shared``: member 0's noise and measurements for
    all) -> ``(bank, [(x, P, log_likelihood) after each step])``."""
    x0, P0, Q, R, zs = prob
    Bn, n = x0.shape
    bank = UnscentedKalmanFilterBank(Bn, n, m, DT, _hx(m) if hx is None else hx, fx, points, compiled=compiled, **kw)
    bank.x, bank.P = x0, P0
    bank.Q, bank.R = (Q[0], R[0]) if shared else (Q, R)
    out = []
    for z in zs:
        bank.predict()
        bank.update(z[0] if shared else z)
        out.append((bank.x.copy(), bank.P.copy(), bank.log_likelihood.copy()))
    return bank, out


POINTS = {
    "merwe": lambda n: MerweScaledSigmaPoints(n, alpha=0.5, beta=2.0, kappa=3.0 - n),
    "julier": lambda n: JulierSigmaPoints(n, kappa=1.0),
    "simplex": lambda n: SphericalSimplexSigmaPoints(n, beta=2.0),
}


@pytest.mark.parametrize("kind", list(POINTS))
@pytest.mark.parametrize("n, m, Bn", [(2, 1, 7), (3, 2, 64), (6, 3, 130), (8, 2, 300)])
def test_the_compiled_bank_equals_the_numpy_bank(kind, n, m, Bn):
    """x, P and the log-likelihoods after every step of 6, per-member Q and R, one member missing
    a step; banks of one partial block, one full block, and several with a remainder."""
    prob = _problem(Bn, n, m, 6)
    bank, got = _run(True, POINTS[kind](n), prob, m)
    assert bank._step.compiled
    _, ref = _run(False, POINTS[kind](n), prob, m)
    for (x, P, ll), (xr, Pr, llr) in zip(got, ref):
        np.testing.assert_allclose(x, xr, rtol=0, atol=TOL)
        np.testing.assert_allclose(P, Pr, rtol=0, atol=TOL)
        np.testing.assert_allclose(ll, llr, rtol=0, atol=TOL)
        assert np.array_equal(P, np.swapaxes(P, 1, 2))  # exactly symmetric
    assert np.array_equal(got[1][2][2], 0.0)  # the member that missed step 2 has no likelihood there


def test_the_compiled_bank_with_a_shared_measurement_and_noise_equals_filterpys_ukf():
    prob = _problem(70, 4, 2, 5, seed=4)
    pts = POINTS["merwe"](4)
    _, got = _run(True, pts, prob, 2, shared=True)
    x0, P0, Q, R, zs = prob
    for i in (0, 33, 64, 69):  # both blocks and the remainder
        f = FilterpyUKF(4, 2, DT, _hx(2), _fx, pts)
        f.x, f.P, f.Q, f.R = x0[i].copy(), P0[i].copy(), Q[0], R[0]
        for k, z in enumerate(zs):
            f.predict()
            f.update(z[0])
            np.testing.assert_allclose(got[k][0][i], f.x, rtol=0, atol=TOL)
            np.testing.assert_allclose(got[k][1][i], f.P, rtol=0, atol=TOL)
            assert abs(got[k][2][i] - f.log_likelihood) <= TOL


def test_a_members_numbers_do_not_depend_on_its_place_in_the_bank():
    """Blocks of 64, a vectorized body and a remainder: the same member gives the same bits
    wherever it sits (the bank reversed, and the member alone)."""
    prob = _problem(150, 6, 3, 4, seed=2)
    pts = POINTS["simplex"](6)
    _, fwd = _run(True, pts, prob, 3)
    rev = tuple(a[::-1].copy() for a in prob[:4]) + (prob[4][:, ::-1].copy(),)
    _, bwd = _run(True, pts, rev, 3)
    one = tuple(a[77:78] for a in prob[:4]) + (prob[4][:, 77:78],)
    _, alone = _run(True, pts, one, 3)
    for (x, P, ll), (xb, Pb, llb), (xa, Pa, lla) in zip(fwd, bwd, alone):
        assert np.array_equal(x, xb[::-1]) and np.array_equal(P, Pb[::-1]) and np.array_equal(ll, llb[::-1])
        assert np.array_equal(x[77], xa[0]) and np.array_equal(P[77], Pa[0]) and ll[77] == lla[0]


def test_the_compiled_path_is_taken_for_every_model_up_to_eight_states(monkeypatch):
    """dim_x > 8 keeps the NumPy step (the kernels are not called), and so does a bank without
    numba (compiled=None), while compiled=True then says how to get numba; mean and residual
    functions of the user's are called in NumPy and the kernels take their deviations."""
    calls = []
    real = _compiled.kernels()
    monkeypatch.setattr(_compiled, "kernels", lambda: calls.append(1) or real)
    prob = _problem(20, 3, 2, 2)
    for kw in ({}, {"residual_z": np.subtract}, {"residual_z": lambda a, b: a - b},
               {"x_mean_fn": lambda s, w: w @ s, "vectorized": False}):
        calls.clear()
        _run(True, POINTS["merwe"](3), prob, 2, **kw)
        assert calls, kw
    calls.clear()
    _run(True, POINTS["merwe"](9), _problem(20, 9, 2, 2), 2)
    assert not calls
    bank = UnscentedKalmanFilterBank(4, 3, 2, DT, _hx(2), _fx, POINTS["merwe"](3))
    assert bank.compiled  # what a user reads
    assert UnscentedKalmanFilterBank(4, 3, 2, DT, _hx(2), _fx, POINTS["merwe"](3), residual_z=np.add).compiled
    assert not UnscentedKalmanFilterBank(4, 9, 2, DT, _hx(2), _fx, POINTS["merwe"](9)).compiled
    assert not UnscentedKalmanFilterBank(4, 3, 2, DT, _hx(2), _fx, POINTS["merwe"](3), compiled=False).compiled
    with pytest.raises(AttributeError):
        bank.compiled = False
    monkeypatch.setattr(_compiled, "available", lambda: False)
    bank = UnscentedKalmanFilterBank(4, 3, 2, DT, _hx(2), _fx, POINTS["merwe"](3))
    assert not bank.compiled and not bank._step.compiled and "compiled" not in repr(bank._step)
    with pytest.raises(ImportError, match=r'compiled=True needs numba: pip install "filterwnn\[fast\]"'):
        UnscentedKalmanFilterBank(4, 3, 2, DT, _hx(2), _fx, POINTS["merwe"](3), compiled=True)


def _wrap(a):
    return (a + np.pi) % (2.0 * np.pi) - np.pi


def _bearing_hx(X):
    """Range and bearing from the origin to (X[0], X[1]) (a heading state X[3] rides along)."""
    return np.stack([np.hypot(X[..., 0], X[..., 1]), np.arctan2(X[..., 1], X[..., 0])], axis=-1)


def _bearing_fx(X, dt):
    """A car at (x, y) with speed X[2] and heading X[3] (an angle, wrapped)."""
    Y = X.copy()
    Y[..., 0] = X[..., 0] + dt * X[..., 2] * np.cos(X[..., 3])
    Y[..., 1] = X[..., 1] + dt * X[..., 2] * np.sin(X[..., 3])
    Y[..., 3] = _wrap(X[..., 3] + 0.3 * dt)
    return Y


def _residual_z(a, b):
    d = np.subtract(a, b)
    d[..., 1] = _wrap(d[..., 1])
    return d


def _residual_x(a, b):
    d = np.subtract(a, b)
    d[..., 3] = _wrap(d[..., 3])
    return d


def _mean_angle(points, w, col):
    m = w @ points
    m[col] = np.arctan2(w @ np.sin(points[:, col]), w @ np.cos(points[:, col]))
    return m


def test_angle_residuals_and_circular_means_on_the_compiled_path_equal_filterpys_ukf():
    """A range-bearing tracker whose heading and bearing cross +-pi: the user's residual and
    circular-mean functions on the compiled bank, the NumPy bank and filterpy's UKF agree to
    1e-12 over 12 steps (every member's bearing passes the cut)."""
    Bn, steps = 70, 12
    g = np.random.default_rng(5)
    x0 = np.column_stack([-20.0 + g.normal(0, 0.5, Bn), g.normal(0, 0.5, Bn), np.full(Bn, 3.0),
                          np.pi - 0.2 + g.normal(0, 0.05, Bn)])
    P0 = np.diag([0.5, 0.5, 0.1, 0.02])
    Q, R = np.diag([0.01, 0.01, 0.01, 1e-3]), np.diag([0.3, 0.01])
    zs = np.stack([_bearing_hx(x0 + [0.0, 0.3 * (k - 6), 0.0, 0.0]) for k in range(steps)])
    zs[:, :, 1] = _wrap(zs[:, :, 1] + g.normal(0, 0.05, (steps, Bn)))
    kw = dict(residual_x=_residual_x, residual_z=_residual_z, x_mean_fn=lambda p, w: _mean_angle(p, w, 3),
              z_mean_fn=lambda p, w: _mean_angle(p, w, 1))
    pts = POINTS["merwe"](4)
    out = []
    for compiled in (True, False):
        bank, got = _run(compiled, pts, (x0, P0, Q, R, zs), 2, hx=_bearing_hx, fx=_bearing_fx, **kw)
        assert bank.compiled == compiled
        out.append(got)
    assert np.ptp(np.sign(np.array([g_[0][:, 1] for g_ in out[0]]))) > 0  # the bearings crossed the cut
    for (x, P, ll), (xr, Pr, llr) in zip(*out):
        np.testing.assert_allclose(x, xr, rtol=0, atol=TOL)
        np.testing.assert_allclose(P, Pr, rtol=0, atol=TOL)
        np.testing.assert_allclose(ll, llr, rtol=0, atol=TOL)
    for i in (0, 64, 69):
        f = FilterpyUKF(4, 2, DT, _bearing_hx, _bearing_fx, pts, **kw)
        f.x, f.P, f.Q, f.R = x0[i].copy(), P0.copy(), Q, R
        for k, z in enumerate(zs):
            f.predict()
            f.update(z[i])
            np.testing.assert_allclose(out[0][k][0][i], f.x, rtol=0, atol=TOL)
            np.testing.assert_allclose(out[0][k][1][i], f.P, rtol=0, atol=TOL)


def test_compiled_errors_are_the_numpy_steps_errors():
    """A member's P not positive definite at predict, or S at update: the kernels hand over to
    the NumPy step, which raises its own error naming the member and the step."""
    prob = _problem(100, 3, 2, 2)
    msgs = []
    for compiled in (True, False):
        bank = UnscentedKalmanFilterBank(100, 3, 2, DT, _hx(2), _fx, POINTS["merwe"](3), compiled=compiled)
        bank.x, bank.P, bank.Q, bank.R = prob[0], prob[1], prob[2], prob[3]
        bank._P[70] = -np.eye(3)  # corrupted past the checked setter
        with pytest.raises(NumericalError) as exc:
            bank.predict()
        msgs.append(str(exc.value))
        nan_hx = lambda X: np.where(np.abs(X[:, :1]) > 50.0, np.nan, _hx(2)(X))  # noqa: E731
        bank = UnscentedKalmanFilterBank(100, 3, 2, DT, nan_hx, None, POINTS["merwe"](3), compiled=compiled)
        x0 = prob[0].copy()
        x0[41] = 100.0
        bank.x, bank.P = x0, prob[1]
        bank.predict()
        with pytest.raises(NumericalError) as exc:
            bank.update(prob[4][0])
        msgs.append(str(exc.value))
    assert msgs[:2] == msgs[2:]
    assert "member 70" in msgs[0] and "particle 41" in msgs[1]


def test_a_step_pickled_before_the_compiled_option_loads_as_the_numpy_step():
    step = UnscentedStep(POINTS["merwe"](3))
    del step.__dict__["compiled"]
    assert step._compiled_for(3) is None and "compiled" not in repr(step)
    assert "compiled=True" in repr(UnscentedStep(POINTS["merwe"](3), compiled=True))


def test_numba_switched_off_for_debugging_means_the_numpy_step(monkeypatch):
    """NUMBA_DISABLE_JIT=1 would run the kernels as plain Python (minutes for a bank): the
    default then takes the NumPy step."""
    monkeypatch.setenv("NUMBA_DISABLE_JIT", "1")
    assert not _compiled.available()
    assert not UnscentedKalmanFilterBank(4, 3, 2, DT, _hx(2), _fx, POINTS["merwe"](3))._step.compiled
    monkeypatch.setenv("NUMBA_DISABLE_JIT", "0")
    assert _compiled.available()


def test_the_kernels_cache_outside_the_installed_package(tmp_path):
    """numba's cache beside the module outlived `pip uninstall` in site-packages/filterwnn, and an editable
    install made afterwards imported that leftover folder instead of the package: it goes to the user's
    cache folder, numba's own setting is left as it was, and NUMBA_CACHE_DIR, when set, wins."""
    import os
    import subprocess
    import sys

    code = (
        "import numba, os\n"
        "from filterwnn.kalman import _compiled\n"
        "k = _compiled.kernels()\n"
        "print(repr(numba.config.CACHE_DIR), _compiled.cache_dir())\n"
        "print(k[0]._cache._cache_path)\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env=dict(env, XDG_CACHE_HOME=str(tmp_path / "xdg")))
    first, path = run.stdout.split("\n")[:2]
    assert first.startswith("'' ") and first.split()[1] == str(tmp_path / "xdg" / "filterwnn" / "numba")
    assert path.startswith(str(tmp_path / "xdg" / "filterwnn" / "numba"))
    assert not path.startswith(os.path.dirname(_compiled.__file__))
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env=dict(env, NUMBA_CACHE_DIR=str(tmp_path / "numba")))
    assert run.stdout.split("\n")[1].startswith(str(tmp_path / "numba"))


def test_a_new_process_loads_the_kernels_from_numbas_cache():
    """Compiled once, then loaded: kernels defined in a closure missed the cache in every new
    process and compiled again (about 5 s each)."""
    import subprocess
    import sys

    code = (
        "import numpy as np\n"
        "from filterpy.kalman import MerweScaledSigmaPoints\n"
        "from filterwnn.kalman import UnscentedKalmanFilterBank, _compiled\n"
        "b = UnscentedKalmanFilterBank(70, 3, 2, 0.1, lambda X: X[:, :2], lambda X, dt: 0.9 * X,\n"
        "                              MerweScaledSigmaPoints(3, 1.0, 2.0, 0.0), compiled=True)\n"
        "b.predict(); b.update(np.zeros(2))\n"
        "print(min(sum(k.stats.cache_hits.values()) for k in _compiled.kernels()))\n"
    )
    runs = [subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
            for _ in range(2)]
    assert int(runs[1].stdout.split()[-1]) >= 1, [r.stdout + r.stderr for r in runs]
