"""Filter banks and the batched Kalman step: a bank of B equals B independent filters (1e-12)."""

import numpy as np
import pytest
from filterpy.kalman import ExtendedKalmanFilter, KalmanFilter, MerweScaledSigmaPoints
from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF

from filterwnn import NumericalError
from filterwnn.kalman import (ExtendedKalmanFilterBank, KalmanFilterBank, SphericalSimplexSigmaPoints,
                              UnscentedKalmanFilterBank)
from filterwnn.kalman.batched import KalmanModel, KalmanPrediction, UnscentedStep, batched_step
from filterwnn.kalman.unscented import UnscentedKalmanFilter

TOL = 1e-12  # the issue's: a bank agrees with B independent filters
B, N_STEPS, DT = 5, 12, 0.1


@pytest.fixture(autouse=True, params=["numpy", "compiled"])
def bank_path(request, monkeypatch):
    """Every test here runs on both paths of the unscented bank: the NumPy step and the compiled
    kernels (``compiled=None`` takes them when numba is installed)."""
    from filterwnn.kalman import _compiled

    if request.param == "compiled":
        if not _compiled.available():
            pytest.skip("numba is not installed (pip install '.[fast]')")
    else:
        monkeypatch.setattr(_compiled, "available", lambda: False)
    return request.param


from _nonlinear_model import fx, hx  # noqa: E402  (on the last axis: one point or rows)


def FJ(x, dt):
    J = np.zeros(x.shape[:-1] + (3, 3))
    J[..., 0, 0], J[..., 0, 1] = 1.0, dt
    J[..., 1, 0], J[..., 1, 1] = dt * 0.5 * np.cos(x[..., 0]), 1.0
    J[..., 2, 0], J[..., 2, 1], J[..., 2, 2] = 0.1 * x[..., 1], 0.1 * x[..., 0], 0.9
    return J


def HJ(x):
    r = np.sqrt(1.0 + x[..., 0] ** 2 + x[..., 2] ** 2)
    J = np.zeros(x.shape[:-1] + (2, 3))
    J[..., 0, 0], J[..., 0, 2] = x[..., 0] / r, x[..., 2] / r
    J[..., 1, 1] = 1.0 / (1.0 + x[..., 1] ** 2)
    return J


@pytest.fixture
def problem():
    """B starting states and covariances, per-member Q and R, and measurements with gaps."""
    g = np.random.default_rng(3)
    x0 = g.normal(0.0, 0.5, (B, 3))
    A = g.normal(0.0, 0.3, (B, 3, 3))
    P0 = np.matmul(A, np.swapaxes(A, 1, 2)) + 0.2 * np.eye(3)
    Q = np.stack([np.eye(3) * q for q in np.linspace(1e-3, 5e-3, B)])
    R = np.stack([np.diag([0.05, 0.02]) * r for r in np.linspace(0.5, 2.0, B)])
    zs = g.normal(0.0, 0.3, (N_STEPS, B, 2)) + np.array([1.2, 0.0])
    zs[2, 1] = np.nan  # member 1 misses step 3, member 4 steps 5 and 6
    zs[4:6, 4] = np.nan
    return x0, P0, Q, R, zs


def _run_singles(make, x0, P0, Q, R, zs, update):
    means = np.empty((N_STEPS, B, 3))
    covs = np.empty((N_STEPS, B, 3, 3))
    lls = np.zeros((N_STEPS, B))
    for i in range(B):
        f = make()
        f.x, f.P, f.Q, f.R = x0[i].copy(), P0[i].copy(), Q[i].copy(), R[i].copy()
        for k in range(N_STEPS):
            f.predict()
            if not np.isnan(zs[k, i, 0]):
                update(f, zs[k, i])
                lls[k, i] = f.log_likelihood
            means[k, i], covs[k, i] = f.x, f.P
    return means, covs, lls


def _run_bank(bank, x0, P0, Q, R, zs):
    bank.x, bank.P, bank.Q, bank.R = x0, P0, Q, R
    lls = np.zeros((N_STEPS, B))
    means = np.empty((N_STEPS, B, 3))
    covs = np.empty((N_STEPS, B, 3, 3))
    for k in range(N_STEPS):
        bank.predict()
        bank.update(zs[k])
        means[k], covs[k], lls[k] = bank.x, bank.P, bank.log_likelihood
    return means, covs, lls


POINTS = [MerweScaledSigmaPoints(3, alpha=1.0, beta=2.0, kappa=0.0), SphericalSimplexSigmaPoints(3, beta=2.0)]


@pytest.mark.parametrize("points", POINTS, ids=["ukf-merwe", "sukf-simplex"])
@pytest.mark.parametrize("single", [FilterpyUKF, UnscentedKalmanFilter], ids=["filterpy", "filterwnn"])
def test_ukf_bank_equals_independent_ukfs(points, single, problem):
    x0, P0, Q, R, zs = problem
    ref = _run_singles(lambda: single(3, 2, DT, hx, fx, points), x0, P0, Q, R, zs, lambda f, z: f.update(z))
    got = _run_bank(UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, points), x0, P0, Q, R, zs)
    for a, b in zip(got, ref):
        np.testing.assert_allclose(a, b, rtol=0, atol=TOL)


def test_ukf_bank_with_per_point_callables_equals_the_vectorized_one(problem):
    x0, P0, Q, R, zs = problem
    vec = _run_bank(UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, POINTS[1]), x0, P0, Q, R, zs)
    loop = _run_bank(UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, POINTS[1], vectorized=False), x0, P0, Q, R, zs)
    for a, b in zip(vec, loop):
        np.testing.assert_allclose(a, b, rtol=0, atol=TOL)


class _NonlinearEKF(ExtendedKalmanFilter):
    def predict_x(self, u=0):
        self.x = fx(self.x, DT)


def test_ekf_bank_equals_independent_filterpy_ekfs(problem):
    x0, P0, Q, R, zs = problem

    def make():
        f = _NonlinearEKF(3, 2)
        f.predict_F = f.predict
        return f

    def step_predict(f):
        f.F = FJ(f.x, DT)
        f.predict_F()

    def run_one(make_f):
        f = make_f()
        f.predict = lambda: step_predict(f)
        return f

    ref = _run_singles(lambda: run_one(make), x0, P0, Q, R, zs,
                       lambda f, z: f.update(z, lambda x: HJ(x), lambda x: hx(x)))
    got = _run_bank(ExtendedKalmanFilterBank(B, 3, 2, DT, hx, fx, FJ, HJ), x0, P0, Q, R, zs)
    for a, b in zip(got[:2], ref[:2]):
        np.testing.assert_allclose(a, b, rtol=0, atol=TOL)


def test_kalman_filter_bank_equals_independent_filterpy_kalman_filters(problem):
    x0, P0, Q, R, zs = problem
    F = np.array([[1.0, DT, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.9]])
    H = np.array([[1.0, 0.0, 1.0], [0.0, 1.0, 0.0]])

    def make():
        f = KalmanFilter(3, 2)
        f.F, f.H = F, H
        return f

    ref = _run_singles(make, x0, P0, Q, R, zs, lambda f, z: f.update(z))
    bank = KalmanFilterBank(B, 3, 2)
    bank.F, bank.H = F, H
    got = _run_bank(bank, x0, P0, Q, R, zs)
    for a, b in zip(got, ref):
        np.testing.assert_allclose(a, b, rtol=0, atol=TOL)


def test_batch_filter_equals_the_step_loop_and_shared_noise_broadcasts(problem):
    x0, P0, _, _, zs = problem
    a = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, POINTS[0])
    a.x, a.P, a.Q, a.R = x0, P0, 1e-3 * np.eye(3), np.diag([0.05, 0.02])
    means, covs = a.batch_filter(zs)
    b = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, POINTS[0])
    b.x, b.P = x0, P0
    b.Q, b.R = np.broadcast_to(1e-3 * np.eye(3), (B, 3, 3)), np.broadcast_to(np.diag([0.05, 0.02]), (B, 2, 2))
    m2, c2, _ = _run_bank(b, x0, P0, b.Q, b.R, zs)
    np.testing.assert_allclose(means, m2, rtol=0, atol=TOL)
    np.testing.assert_allclose(covs, c2, rtol=0, atol=TOL)
    assert means.shape == (N_STEPS, B, 3) and covs.shape == (N_STEPS, B, 3, 3) and a.step == N_STEPS


def test_missing_members_keep_their_prediction_with_a_mask_or_none(problem):
    x0, P0, Q, R, zs = problem
    bank = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, POINTS[1])
    bank.x, bank.P, bank.Q, bank.R = x0, P0, Q, R
    bank.predict()
    prior = bank.x.copy(), bank.P.copy()
    mask = np.array([True, False, True, False, True])
    bank.update(zs[0], mask=mask)
    assert np.array_equal(bank.x[~mask], prior[0][~mask]) and np.array_equal(bank.P[~mask], prior[1][~mask])
    assert np.all(bank.log_likelihood[~mask] == 0) and np.all(bank.log_likelihood[mask] != 0)
    assert not np.allclose(bank.x[mask], prior[0][mask])
    before = bank.x.copy()
    bank.update(None)
    assert np.array_equal(bank.x, before) and np.all(bank.log_likelihood == 0)


def test_shared_measurement_equals_the_same_row_for_every_member_bit_for_bit(problem):
    x0, P0, Q, R, _ = problem
    model = KalmanModel(3, 2, DT, fx, hx, Q=1e-3 * np.eye(3), R=np.diag([0.05, 0.02]), vectorized=True)
    for kind, points in (("ukf", POINTS[0]), ("sukf", POINTS[1]), ("ekf", None)):
        model.FJacobian, model.HJacobian = FJ, HJ
        step = batched_step(kind, points)
        pred = step.predict(model, x0, P0, {})
        z = np.array([1.1, 0.2])
        shared = step.update(model, pred, z, {})
        rows = step.update(model, pred, np.tile(z, (B, 1)), {})
        for a, b in zip(shared[:6], rows[:6]):
            assert np.array_equal(a, b), kind


def test_mask_equals_running_the_observed_members_alone(problem):
    x0, P0, Q, R, zs = problem
    model = KalmanModel(3, 2, DT, fx, hx, Q=1e-3 * np.eye(3), vectorized=True)
    step = UnscentedStep(POINTS[1])
    pred = step.predict(model, x0, P0, {}, Q=Q)
    mask = np.array([False, True, True, False, True])
    full = step.update(model, pred, zs[0], {}, R=R, mask=mask)
    sub = step.update(model, KalmanPrediction(pred.x[mask], pred.P[mask]), zs[0][mask], {}, R=R[mask])
    assert np.array_equal(full.x[mask], sub.x) and np.array_equal(full.log_likelihood[mask], sub.log_likelihood)
    assert np.all(np.isnan(full.z_pred[~mask])) and np.array_equal(full.x[~mask], pred.x[~mask])


def test_errors_name_the_member_and_the_step(problem):
    x0, P0, Q, R, zs = problem
    bank = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, POINTS[0])
    bad = P0.copy()
    bad[3] = -np.eye(3)
    with pytest.raises(ValueError, match=r"P must be positive definite \(member 3\)"):
        bank.P = bad
    with pytest.raises(ValueError, match=r"R must be positive definite \(member 2\)"):
        bank.R = np.stack([np.eye(2)] * 2 + [-np.eye(2)] + [np.eye(2)] * 2)
    with pytest.raises(ValueError, match=r"Q must have shape \(3, 3\) \(shared\) or \(5, 3, 3\)"):
        bank.Q = np.eye(2)
    with pytest.raises(ValueError, match=r"z of member 2 must be finite, or all NaN"):
        bank.update(np.array([[1.0, 0.0], [1.0, 0.0], [np.nan, 0.0], [1.0, 0.0], [1.0, 0.0]]))
    bank.x, bank.P = x0, P0
    bank.predict()
    bank._P[4] = -np.eye(3)  # a corrupted member (not through the checked setter)
    with pytest.raises(NumericalError, match=r"UnscentedKalmanFilterBank.update at step 1, member 4: "):
        bank.update(zs[0])
    nan_fx = lambda X, dt: np.where(np.arange(X.shape[0])[:, None] >= 7 * 2, np.nan, fx(X, dt))  # noqa: E731
    bank2 = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, nan_fx, POINTS[0])
    with pytest.raises(NumericalError, match=r"predict at step 1: non-finite result for member 2 \(check fx"):
        bank2.predict()


def test_constructor_checks():
    with pytest.raises(ValueError, match="points.n must equal dim_x=3"):
        UnscentedKalmanFilterBank(2, 3, 1, 1.0, hx, fx, MerweScaledSigmaPoints(2, 1.0, 2.0, 0.0))
    with pytest.raises(TypeError, match="hx must be callable"):
        UnscentedKalmanFilterBank(2, 3, 1, 1.0, None, fx, POINTS[0])
    with pytest.raises(ValueError, match="needs FJacobian when fx is given"):
        ExtendedKalmanFilterBank(2, 3, 2, 1.0, hx, fx, None, HJ)
    with pytest.raises(ValueError, match="B must be"):
        KalmanFilterBank(0, 3, 2)


def test_random_walk_bank_and_a_per_update_R_equal_single_filters(problem):
    x0, P0, Q, R, zs = problem
    bank = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, None, POINTS[1])
    bank.x, bank.P, bank.Q = x0, P0, Q
    bank.predict()
    bank.update(zs[0], R=R)
    for i in range(B):
        f = UnscentedKalmanFilter(3, 2, DT, hx, None, POINTS[1], vectorized=True)
        f.x, f.P, f.Q, f.R = x0[i].copy(), P0[i].copy(), Q[i], R[i]
        f.predict()
        f.update(zs[0, i])
        np.testing.assert_allclose(bank.x[i], f.x, rtol=0, atol=TOL)
        np.testing.assert_allclose(bank.P[i], f.P, rtol=0, atol=TOL)


def test_a_pickled_bank_continues_identically(problem):
    import pickle

    x0, P0, Q, R, zs = problem
    bank = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, POINTS[0])
    bank.x, bank.P, bank.Q, bank.R = x0, P0, Q, R
    bank.batch_filter(zs[:3])
    clone = pickle.loads(pickle.dumps(bank))
    a, _ = bank.batch_filter(zs[3:])
    b, _ = clone.batch_filter(zs[3:])
    assert np.array_equal(a, b) and clone.step == bank.step == N_STEPS


def test_a_one_point_fx_is_caught_on_its_first_call(problem):
    """The book's habit (``out[0] = x[0] + ...``) on all members' sigma points is silently wrong
    without the check (it ran to 1.8e7 on a 4-state tracker); it must name fx and the fix."""
    x0, P0, Q, R, zs = problem

    def fx_one(x, dt):
        out = np.empty_like(x)
        out[0], out[1], out[2] = x[0] + dt * x[1], x[1], 0.9 * x[2]
        return out

    bank = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx_one, POINTS[0])
    bank.x, bank.P, bank.Q, bank.R = x0, P0, Q, R
    with pytest.raises(ValueError, match=r"vectorized fx looks written for one point: .*Fix: index the last axis"):
        bank.predict()


# --- a long bank: the column path (small n, many members) --------------------------------------

from filterwnn._linalg import COLUMNS_MIN_STACK, columns_layout  # noqa: E402

B_LONG = COLUMNS_MIN_STACK + 8  # one member missing still leaves a stack on the column path


def _long_problem(seed=5):
    g = np.random.default_rng(seed)
    x0 = g.normal(0.0, 0.5, (B_LONG, 3))
    A = g.normal(0.0, 0.3, (B_LONG, 3, 3))
    P0 = np.matmul(A, np.swapaxes(A, 1, 2)) + 0.2 * np.eye(3)
    zs = g.normal(0.0, 0.3, (3, B_LONG, 2)) + np.array([1.2, 0.0])
    zs[1, 17] = np.nan
    return x0, P0, np.eye(3) * 2e-3, np.diag([0.05, 0.02]), zs


@pytest.mark.parametrize("points", POINTS, ids=["ukf-merwe", "sukf-simplex"])
def test_a_long_bank_on_the_column_path_equals_independent_filterpy_ukfs(points):
    assert columns_layout(B_LONG - 1, 3)  # else this test would not reach the column path
    x0, P0, Q, R, zs = _long_problem()
    _assert_bank_equals_filterpy(hx, points, x0, P0, Q, R, zs, range(B_LONG))


def _assert_bank_equals_filterpy(h, points, x0, P0, Q, R, zs, members):
    """Run a bank of ``len(x0)`` UKFs over ``zs (n_steps, B, dim_z)`` (NaN rows: not observed) and
    check each of ``members`` against filterpy's UKF on its own data: x, P and the
    log-likelihood (0 where not observed) after every step, to ``TOL``."""
    dim_z = zs.shape[-1]
    bank = UnscentedKalmanFilterBank(len(x0), 3, dim_z, DT, h, fx, points)
    bank.x, bank.P, bank.Q, bank.R = x0, P0, Q, R
    got = []
    for z in zs:
        bank.predict()
        bank.update(z)
        got.append((bank.x.copy(), bank.P.copy(), bank.log_likelihood.copy()))
    for i in members:
        f = FilterpyUKF(3, dim_z, DT, h, fx, points)
        f.x, f.P, f.Q, f.R = x0[i].copy(), P0[i].copy(), Q, R
        for k, z in enumerate(zs):
            f.predict()
            if not np.isnan(z[i, 0]):
                f.update(z[i])
            x, P, ll = got[k]
            np.testing.assert_allclose(x[i], f.x, rtol=0, atol=TOL)
            np.testing.assert_allclose(P[i], f.P, rtol=0, atol=TOL)
            assert abs(ll[i] - (f.log_likelihood if not np.isnan(z[i, 0]) else 0.0)) <= TOL


@pytest.mark.parametrize("n_members", [B, B_LONG], ids=["lapack", "columns"])
def test_errors_name_the_member_on_both_paths(n_members):
    x0, P0, Q, R, zs = _long_problem()
    x0, P0, z = x0[:n_members], P0[:n_members], zs[0, :n_members]
    bank = UnscentedKalmanFilterBank(n_members, 3, 2, DT, hx, fx, POINTS[0])
    bank.x, bank.P = x0, P0
    bank._P[3] = -np.eye(3)  # corrupted, not through the checked setter
    with pytest.raises(NumericalError, match=r"UnscentedKalmanFilterBank.predict at step 1, member 3: P is not "
                                             r"positive definite at step 1 \(particle 3\); check Q"):
        bank.predict()
    bank.P = P0
    bank.predict()
    bank._P[4] = np.nan
    with pytest.raises(NumericalError, match=r"update at step 1, member 4: P_prior is not positive definite"):
        bank.update(z)
    # a model that returns NaN for one member (by its value, not its row) is named, never passed on
    far = lambda X, dt: np.where(X[:, :1] > 50.0, np.nan, fx(X, dt))  # noqa: E731
    bank2 = UnscentedKalmanFilterBank(n_members, 3, 2, DT, hx, far, POINTS[0])
    bank2.x, bank2.P = np.where(np.arange(n_members)[:, None] == 2, 100.0, x0), P0
    with pytest.raises(NumericalError, match=r"predict at step 1: non-finite result for member 2 \(check fx"):
        bank2.predict()
    nan_hx = lambda X: np.where(X[:, :1] > 50.0, np.nan, hx(X))  # noqa: E731
    bank3 = UnscentedKalmanFilterBank(n_members, 3, 2, DT, nan_hx, None, POINTS[0])
    bank3.x, bank3.P = np.where(np.arange(n_members)[:, None] == 2, 100.0, x0), P0
    bank3.predict()
    with pytest.raises(NumericalError, match=r"update at step 1, a member: S is not positive definite at step 1 "
                                             r"\(particle 2\)"):
        bank3.update(z)


def test_a_long_bank_with_per_point_callables_equals_the_vectorized_one():
    x0, P0, Q, R, zs = _long_problem(6)
    out = []
    for vectorized in (True, False):
        bank = UnscentedKalmanFilterBank(B_LONG, 3, 2, DT, hx, fx, POINTS[1], vectorized=vectorized)
        bank.x, bank.P, bank.Q, bank.R = x0, P0, Q, R
        for z in zs[:2]:
            bank.predict()
            bank.update(z)
        out.append((bank.x, bank.P, bank.log_likelihood))
    for a, b in zip(*out):
        np.testing.assert_allclose(a, b, rtol=0, atol=TOL)


def test_the_steps_row_helpers_equal_the_plain_broadcasts_bit_for_bit():
    from filterwnn.kalman.batched import _residual, _times_weights

    g = np.random.default_rng(7)
    a = g.normal(0.0, 1e3, (40, 13, 6))
    b = g.normal(0.0, 1e3, (40, 1, 6))
    W = g.normal(0.0, 1.0, 13)
    assert np.array_equal(_residual(None, a, b, True), a - b)  # the repeated-rows path is exact
    assert np.array_equal(_residual(None, a, b[:1], True), a - b[:1])  # a shared b: the plain broadcast
    assert np.array_equal(_times_weights(a, W), a * W[:, None])
    bad = b.copy()
    bad[3, 0, 2] = np.nan
    assert np.isnan(_residual(None, a, bad, True)[3]).any() and np.isfinite(_residual(None, a, bad, True)[4]).all()


def test_prior_and_posterior_copies_made_when_read_are_the_eager_ones(problem):
    """``x_prior``/``P_prior``/``x_post``/``P_post`` are copied at their first read (or that of
    ``x``/``P``): read every step or only at the end, they hold the values of that moment, and
    an edit in place of one array never reaches another."""
    x0, P0, Q, R, zs = problem
    seen = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, POINTS[0])
    late = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, POINTS[0])
    for bank in (seen, late):
        bank.x, bank.P, bank.Q, bank.R = x0, P0, Q, R
    for k in range(4):
        seen.predict()
        xp, Pp = seen.x_prior, seen.P_prior
        assert np.array_equal(xp, seen.x) and xp is not seen.x and Pp is not seen.P
        seen.update(zs[k])
        assert np.array_equal(seen.x_post, seen.x) and np.array_equal(seen.P_post, seen.P)
        assert np.array_equal(seen.x_prior, xp) and np.array_equal(seen.P_prior, Pp)
        late.predict()
        late.update(zs[k])
    for name in ("x_prior", "P_prior", "x_post", "P_post", "x", "P"):
        assert np.array_equal(getattr(late, name), getattr(seen, name)), name
    late.x[0] += 1.0  # an edit in place of x reaches neither copy
    late.x_post[1] += 2.0
    assert np.array_equal(late.x_post[0], seen.x_post[0]) and np.array_equal(late.x[1], seen.x[1])
    late.predict()
    late.x_prior[0] = 0.0  # nor an edit of a copy the state
    assert not np.array_equal(late.x[0], late.x_prior[0])


def test_a_bank_pickled_with_plain_prior_and_posterior_attributes_loads(problem):
    x0, P0, Q, R, zs = problem
    bank = UnscentedKalmanFilterBank(B, 3, 2, DT, hx, fx, POINTS[0])
    bank.x, bank.P, bank.Q, bank.R = x0, P0, Q, R
    bank.predict()
    bank.update(zs[0])
    want = {name: getattr(bank, name).copy() for name in ("x_prior", "P_prior", "x_post", "P_post")}
    state = dict(bank.__dict__)
    for name in want:  # the layout before these were copied when read
        state[name] = state.pop("_" + name)
    state.pop("_pending")
    old = UnscentedKalmanFilterBank.__new__(UnscentedKalmanFilterBank)
    old.__setstate__(state)
    for name, value in want.items():
        assert np.array_equal(getattr(old, name), value), name


def test_a_long_bank_with_one_measurement_on_the_column_path_equals_filterpy_ukfs():
    """``dim_z = 1`` on the column path (P_xy a view of the solve's right-hand side, the rank-1
    downdate): every member as filterpy's UKF, to 1e-12."""
    x0, P0, Q, R, zs = _long_problem(seed=6)
    hx1 = lambda X: hx(X)[..., :1]  # noqa: E731
    _assert_bank_equals_filterpy(hx1, POINTS[0], x0, P0, Q, R[:1, :1], zs[:, :, :1], range(0, B_LONG, 7))


# --- what a user holds: a later step never changes it (guards any reuse of arrays) ----------


def _long_bank(points=POINTS[0], n=B_LONG, seed=5):
    x0, P0, Q, R, zs = _long_problem(seed)
    bank = UnscentedKalmanFilterBank(n, 3, 2, DT, hx, fx, points)
    bank.x, bank.P, bank.Q, bank.R = x0[:n], P0[:n], Q, R
    return bank, zs[:, :n]


@pytest.mark.parametrize("points", POINTS, ids=["ukf-merwe", "sukf-simplex"])
def test_results_held_from_a_step_are_never_changed_by_later_steps(points):
    """x, P, the prior and posterior copies and the log-likelihoods a user holds after a step
    (every member observed, or some missing) keep their values through later steps."""
    bank, zs = _long_bank(points)
    assert columns_layout(B_LONG, 3)  # the column path
    held = []
    for k in range(6):
        bank.predict()
        held.append({"x_prior": bank.x_prior, "P_prior": bank.P_prior, "x": bank.x, "P": bank.P})
        bank.update(zs[k % 3])
        held.append({"x": bank.x, "P": bank.P, "x_post": bank.x_post, "P_post": bank.P_post,
                     "log_likelihood": bank.log_likelihood})
        held.append({"x": bank._x, "P": bank._P})  # the arrays themselves, not read through the properties
    values = [{k: v.copy() for k, v in h.items()} for h in held]
    for _ in range(3):
        bank.predict()
        bank.update(zs[1])
    for h, v in zip(held, values):
        for name in h:
            assert np.array_equal(h[name], v[name]), name


def test_a_failed_update_on_the_column_path_leaves_the_bank_as_it_was():
    """An update that fails (a non-PD P_prior of one member) or is refused (a z of the wrong
    shape) changes neither x, P nor the last log-likelihoods, and the next good step gives what
    a bank that never failed gives, bit for bit."""
    bank, zs = _long_bank()
    ref, _ = _long_bank()
    for b in (bank, ref):
        b.predict()
        b.update(zs[0])
        b.predict()
    x, P, ll = bank.x.copy(), bank.P.copy(), bank.log_likelihood.copy()
    assert np.all(ll != 0.0)
    good = bank._P
    bad = good.copy()
    bad[7] = -np.eye(3)
    bank._P = bad
    with pytest.raises(NumericalError, match=r"update at step 2, member 7"):
        bank.update(zs[1])
    assert bank._P is bad and np.array_equal(bank.x, x)
    assert np.array_equal(bank.log_likelihood, ll)  # the last good update's, not zeros
    with pytest.raises(ValueError):
        bank.update(np.ones((bank.B, bank.dim_z + 1)))  # a refused z leaves it too
    assert np.array_equal(bank.log_likelihood, ll)
    bank._P = good
    assert np.array_equal(bank.P, P)
    bank.update(zs[1])
    ref.update(zs[1])
    assert np.array_equal(bank.x, ref.x) and np.array_equal(bank.P, ref.P)
    assert np.array_equal(bank.log_likelihood, ref.log_likelihood)
