"""Batched Kalman proposals: pinned to filterpy's UKF/EKF per particle, and their sampling."""

import numpy as np
import pytest
from filterpy.kalman import JulierSigmaPoints, MerweScaledSigmaPoints, UnscentedKalmanFilter
from scipy.stats import multivariate_normal

from filterwnn import MinimalSkewSigmaPoints, SphericalSimplexSigmaPoints
from filterwnn._validation import NumericalError
from filterwnn.monte_carlo.proposals import (
    ExtendedKalmanProposal,
    PriorProposal,
    ProposalModel,
    UnscentedKalmanProposal,
)
from filterwnn.kalman.sigma_points import unit_sigma_points, unit_transpose_apply

ATOL = 1e-10


def fx(x, dt):
    return np.stack(
        [x[..., 0] + dt * x[..., 1], np.sin(x[..., 1]), 0.9 * x[..., 2], x[..., 3] + 0.1 * x[..., 0]], axis=-1
    )


def FJ(x, dt):
    return np.array(
        [[1, dt, 0, 0], [0, np.cos(x[1]), 0, 0], [0, 0, 0.9, 0], [0.1, 0, 0, 1]], dtype=float
    )


def hx(x):
    return np.stack([x[..., 0] ** 2 / 10, np.arctan2(x[..., 1], 1 + x[..., 2] ** 2)], axis=-1)


def hx1(x):
    return hx(x)[..., :1]


def HJ1(x):
    return np.array([[x[0] / 5, 0.0, 0.0, 0.0]])


def _model(dim_z=2, vectorized=True):
    return ProposalModel(
        dim_x=4,
        dim_z=dim_z,
        dt=0.5,
        fx=fx,
        hx=hx if dim_z == 2 else hx1,
        vectorized=vectorized,
        FJacobian=FJ,
        HJacobian=HJ1,
        Q=0.1 * np.eye(4),
        R=np.diag([0.2, 0.3][:dim_z]),
    )


def _cloud(rng, N=3):
    x = rng.standard_normal((N, 4))
    A = rng.standard_normal((N, 4, 4))
    return x, A @ np.swapaxes(A, 1, 2) + np.eye(4)


POINTS = [
    MerweScaledSigmaPoints(4, 0.5, 2.0, 0.0),
    SphericalSimplexSigmaPoints(4),
    MinimalSkewSigmaPoints(4, beta=2.0),
    JulierSigmaPoints(4, 1.0),
]


@pytest.mark.parametrize("points", POINTS, ids=lambda p: type(p).__name__)
def test_unit_transpose_apply_equals_dense_product(points, rng):
    Z = unit_sigma_points(points)
    B = rng.standard_normal((3, Z.shape[0], 2))
    np.testing.assert_allclose(unit_transpose_apply(points, Z, B), np.matmul(Z.T, B), atol=1e-12)


@pytest.mark.parametrize("points", POINTS[:2], ids=lambda p: type(p).__name__)
@pytest.mark.parametrize("vectorized", [True, False])
def test_unscented_proposal_equals_filterpy_ukf_per_particle(points, vectorized, rng):
    model = _model(2, vectorized)
    x, P = _cloud(rng)
    prop = UnscentedKalmanProposal(points)
    z = np.array([0.3, -0.2])
    pred = prop.kalman_predict(model, x, P, {})
    upd = prop.kalman_update(model, pred, z, {})
    for i in range(x.shape[0]):
        ukf = UnscentedKalmanFilter(4, 2, 0.5, hx, fx, points)
        ukf.x, ukf.P, ukf.Q, ukf.R = x[i].copy(), P[i].copy(), model.Q, model.R
        ukf.predict()
        np.testing.assert_allclose(pred.x[i], ukf.x, atol=ATOL)
        np.testing.assert_allclose(pred.P[i], ukf.P, atol=ATOL)
        ukf.update(z)
        np.testing.assert_allclose(upd.x[i], ukf.x, atol=ATOL)
        np.testing.assert_allclose(upd.P[i], ukf.P, atol=ATOL)
        assert upd.log_likelihood[i] == pytest.approx(ukf.log_likelihood, abs=1e-10)


def test_extended_proposal_equals_ekf_equations(rng):
    model = _model(1)
    x, P = _cloud(rng)
    prop = ExtendedKalmanProposal()
    model.vectorized = False
    pred = prop.kalman_predict(model, x, P, {})
    upd = prop.kalman_update(model, pred, np.array([0.4]), {})
    for i in range(x.shape[0]):
        F = FJ(x[i], 0.5)
        xp, Pp = fx(x[i], 0.5), F @ P[i] @ F.T + model.Q
        H = HJ1(xp)
        S = H @ Pp @ H.T + model.R
        K = np.linalg.solve(S, H @ Pp).T
        np.testing.assert_allclose(upd.x[i], xp + K @ (np.array([0.4]) - hx1(xp)), atol=ATOL)
        np.testing.assert_allclose(upd.P[i], Pp - K @ S @ K.T, atol=ATOL)


@pytest.mark.parametrize("dim_z", [1, 2])
@pytest.mark.parametrize("kind", ["unscented", "extended"])
def test_sample_log_density_is_the_gaussian_proposal(dim_z, kind, rng):
    """Samples' log q equals scipy's N(x_hat, P_hat) log-density (rank-1 path for dim_z=1)."""
    model = _model(dim_z)
    model.vectorized = kind == "unscented"
    if kind == "extended" and dim_z == 2:
        model.vectorized = True
        model.HJacobian = lambda X: np.stack([np.stack([X[:, 0] / 5, 0 * X[:, 0], 0 * X[:, 0], 0 * X[:, 0]], -1)] * 2, 1)
        model.hx = lambda X: np.stack([X[:, 0] ** 2 / 10] * 2, -1)
    model.FJacobian = lambda X, dt: np.eye(4)
    x, P = _cloud(rng)
    prop = UnscentedKalmanProposal(SphericalSimplexSigmaPoints(4)) if kind == "unscented" else ExtendedKalmanProposal()
    pred = prop.kalman_predict(model, x, P, {})
    upd = prop.kalman_update(model, pred, np.full(dim_z, 0.3), {})
    s, log_q = prop.sample(upd, rng, P_prior=pred.P)
    for i in range(x.shape[0]):
        ref = multivariate_normal(upd.x[i], upd.P[i]).logpdf(s[i])
        assert log_q[i] == pytest.approx(ref, abs=1e-9)
    np.testing.assert_allclose(prop.logpdf(upd, s, P_prior=pred.P), log_q, atol=1e-9)


def test_rank1_samples_have_the_posterior_moments():
    """Mean/covariance of 40,000 rank-1 draws match (x_hat, P_hat).

    Tolerance: 5 standard errors, sqrt(P_jj / n) for the mean and
    sqrt((P_ij^2 + P_ii P_jj) / n) for the covariance entries.
    """
    gen = np.random.default_rng(4)
    model = _model(1)
    x, P = _cloud(gen, N=2)
    prop = UnscentedKalmanProposal(MerweScaledSigmaPoints(4, 1.0, 2.0, 0.0))
    pred = prop.kalman_predict(model, x, P, {})
    upd = prop.kalman_update(model, pred, np.array([0.4]), {})
    n = 40000
    rep = upd._replace(
        x=np.repeat(upd.x[:1], n, 0),
        P=np.repeat(upd.P[:1], n, 0),
        S=np.repeat(upd.S[:1], n, 0),
        Pxy=np.repeat(upd.Pxy[:1], n, 0),
        L_prior=np.repeat(upd.L_prior[:1], n, 0),
        LinvPxy=np.repeat(upd.LinvPxy[:1], n, 0),
        z_pred=np.repeat(upd.z_pred[:1], n, 0),
        log_likelihood=np.repeat(upd.log_likelihood[:1], n, 0),
    )
    s, _ = prop.sample(rep, gen)
    Ph = upd.P[0]
    d = np.diag(Ph)
    np.testing.assert_array_less(np.abs(s.mean(0) - upd.x[0]), 5 * np.sqrt(d / n))
    se = np.sqrt((Ph**2 + np.outer(d, d)) / n)
    np.testing.assert_array_less(np.abs(np.cov(s.T) - Ph), 5 * se)


def test_not_positive_definite_covariance_raises_numerical_error(rng):
    model = _model(1)
    x, P = _cloud(rng)
    P[1] = -np.eye(4)
    prop = UnscentedKalmanProposal(SphericalSimplexSigmaPoints(4))
    with pytest.raises(NumericalError, match=r"P is not positive definite at step 7 \(particle 1\)"):
        prop.kalman_predict(model, x, P, {}, step=7)


def test_prior_proposal_uses_process_sampler(rng):
    model = _model(1)
    model.process_sampler = lambda X, g: X + 1.0
    x, _ = _cloud(rng)
    np.testing.assert_allclose(PriorProposal().predict(model, x, None, {}, rng).particles, x + 1.0)
    model.process_sampler = None
    model.Q = np.zeros((4, 4))
    np.testing.assert_allclose(model.sample_transition(x, {}, rng), fx(x, 0.5))


def test_points_protocol_checked():
    with pytest.raises(TypeError, match="points must follow filterpy's sigma-point protocol"):
        UnscentedKalmanProposal(object())


@pytest.mark.parametrize("points", POINTS + [SphericalSimplexSigmaPoints(4, alpha=0.5, w0=0.3)], ids=lambda p: type(p).__name__)
def test_batched_sigma_points_equal_the_sigma_point_sets(points, rng):
    from filterwnn.kalman.sigma_points import batched_sigma_points

    x, P = _cloud(rng, N=3)
    sig = batched_sigma_points(points, x, np.linalg.cholesky(P))
    for i in range(3):
        np.testing.assert_allclose(sig[i], points.sigma_points(x[i], P[i]), atol=1e-12)


def test_batched_sigma_points_large_staircase_path(rng):
    from filterwnn.kalman.sigma_points import batched_sigma_points

    pts = SphericalSimplexSigmaPoints(24, alpha=0.7)
    x = rng.standard_normal((2, 24))
    A = rng.standard_normal((2, 24, 24))
    P = A @ np.swapaxes(A, 1, 2) + np.eye(24)
    sig = batched_sigma_points(pts, x, np.linalg.cholesky(P))
    for i in range(2):
        np.testing.assert_allclose(sig[i], pts.sigma_points(x[i], P[i]), atol=1e-11)
