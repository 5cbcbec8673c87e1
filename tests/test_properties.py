"""Property-based tests (hypothesis) of what the per-module tests pin only by example
(issue 8, part 5).

Sigma-point sets (mean/covariance reproduction, nearly singular covariances, structured
deviations) and resampling schemes (valid indices, count bounds) have their hypothesis
tests in ``tests/kalman/test_sigma_points.py`` and ``tests/monte_carlo/test_resampling.py``; this file does
not repeat them. Here: the unscented filter equals the Kalman filter on random
linear-Gaussian models with ill-conditioned covariances, the boundary check of
covariances, NEES, effective sample size and log-weight normalisation, and heading
wrapping.
"""

import numpy as np
import pytest
from filterpy.kalman import MerweScaledSigmaPoints
from hypothesis import given, settings
from hypothesis import strategies as st

from filterwnn import (
    LinearGaussianModel,
    MinimalSkewSigmaPoints,
    SphericalSimplexSigmaPoints,
    UnscentedKalmanFilter,
)
from filterwnn._validation import check_covariance
from filterwnn.navigation.dead_reckoning import dr_residual, wrap_angle
from filterwnn.metrics import effective_sample_size, nees
from filterwnn.monte_carlo.resampling import normalize_log_weights

SEEDS = st.integers(0, 2**32 - 1)


def spd(n, seed, log_cond):
    """A random SPD matrix with condition number ``10**log_cond`` and unit largest eigenvalue."""
    rng = np.random.default_rng(seed)
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    ev = np.logspace(-log_cond, 0.0, n)
    return (Q * ev) @ Q.T


POINTS = {
    "merwe": lambda n: MerweScaledSigmaPoints(n, alpha=1.0, beta=2.0, kappa=0.0),
    "simplex": lambda n: SphericalSimplexSigmaPoints(n),
    "minimal-skew": lambda n: MinimalSkewSigmaPoints(n),
}


@settings(max_examples=40, deadline=None)
@given(
    dim_x=st.integers(1, 6),
    dim_z=st.integers(1, 3),
    seed=SEEDS,
    log_cond=st.floats(0.0, 8.0),
    points=st.sampled_from(sorted(POINTS)),
    vectorized=st.booleans(),
)
def test_ukf_equals_kalman_filter_on_random_linear_models(dim_x, dim_z, seed, log_cond, points, vectorized):
    """On any linear-Gaussian model the UKF's (x, P) after predict/update are the KF's,
    including a prior covariance with condition number up to 1e8."""
    m = LinearGaussianModel.random(dim_x, dim_z, rng=seed)
    m.P0 = spd(dim_x, seed + 1, log_cond)
    _, zs = m.simulate(3, rng=seed + 2)
    kf = m.kalman_filter()
    ukf = UnscentedKalmanFilter(dim_x, dim_z, 1.0, m.hx, m.fx, POINTS[points](dim_x), vectorized=vectorized)
    ukf.x, ukf.P, ukf.Q, ukf.R = m.x0.copy(), m.P0.copy(), m.Q.copy(), m.R.copy()
    for z in zs:
        kf.predict()
        ukf.predict()
        np.testing.assert_allclose(ukf.x, kf.x, rtol=1e-7, atol=1e-9)
        np.testing.assert_allclose(ukf.P, kf.P, rtol=1e-6, atol=1e-9)
        kf.update(z)
        ukf.update(z)
        np.testing.assert_allclose(ukf.x, kf.x, rtol=1e-6, atol=1e-8)
        np.testing.assert_allclose(ukf.P, kf.P, rtol=1e-6, atol=1e-8)
        if vectorized:  # symmetric by construction
            np.testing.assert_array_equal(ukf.P, ukf.P.T)


@settings(max_examples=60, deadline=None)
@given(n=st.integers(1, 12), seed=SEEDS, log_cond=st.floats(0.0, 12.0), log_scale=st.floats(-200.0, 200.0))
def test_check_covariance_accepts_every_spd_matrix_at_any_scale(n, seed, log_cond, log_scale):
    P = spd(n, seed, log_cond) * 10.0**log_scale
    P = 0.5 * (P + P.T)
    out = check_covariance(P, "P", n, require_pd=log_cond < 10)
    np.testing.assert_array_equal(out, P)


@settings(max_examples=60, deadline=None)
@given(n=st.integers(1, 12), seed=SEEDS, log_scale=st.floats(-200.0, 200.0), k=st.integers(0, 11))
def test_check_covariance_rejects_a_negative_eigenvalue_at_any_scale(n, seed, log_scale, k):
    rng = np.random.default_rng(seed)
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    ev = rng.uniform(0.5, 1.0, n)
    ev[k % n] = -0.1
    P = ((Q * ev) @ Q.T) * 10.0**log_scale
    P = 0.5 * (P + P.T)
    with pytest.raises(ValueError, match="P must be positive definite"):
        check_covariance(P, "P", n)
    with pytest.raises(ValueError, match="Q must be positive semi-definite"):
        check_covariance(P, "Q", n, require_pd=False)


@settings(max_examples=60, deadline=None)
@given(n=st.integers(1, 12), seed=SEEDS, log_cond=st.floats(0.0, 10.0), batch=st.integers(0, 4))
def test_nees_of_a_whitened_error_is_its_squared_norm(n, seed, log_cond, batch):
    """``nees(x + L u, x, L L^T) = |u|^2``, batched or not, for ill-conditioned P."""
    rng = np.random.default_rng(seed)
    P = spd(n, seed, log_cond)
    L = np.linalg.cholesky(P)
    shape = (batch, n) if batch else (n,)
    u = rng.standard_normal(shape)
    x = rng.standard_normal(shape)
    e = u @ L.T
    Pb = np.broadcast_to(P, shape + (n,)) if batch else P
    np.testing.assert_allclose(nees(x + e, x, Pb), np.sum(u * u, axis=-1), rtol=1e-6 * 10 ** (log_cond / 2))


@settings(max_examples=80, deadline=None)
@given(
    w=st.lists(st.one_of(st.just(0.0), st.floats(1e-6, 1e6)), min_size=1, max_size=60).filter(
        lambda v: sum(v) > 0
    ),
    scale=st.floats(1e-100, 1e100),
)
def test_effective_sample_size_bounds_and_scale_invariance(w, scale):
    w = np.asarray(w)
    ess = effective_sample_size(w)
    assert 1.0 - 1e-9 <= ess <= len(w) * (1 + 1e-9)
    assert ess == pytest.approx(effective_sample_size(w * scale), rel=1e-9)
    assert effective_sample_size(np.full(len(w), 3.0)) == pytest.approx(len(w))


@settings(max_examples=80, deadline=None)
@given(
    lw=st.lists(st.floats(-1e3, 1e3), min_size=1, max_size=60),
    shift=st.floats(-1e300, 1e300),
)
def test_normalize_log_weights_is_shift_invariant_without_underflow(lw, shift):
    """Weights from log-weights shifted by up to 1e300 are finite, sum to 1 and do not
    depend on the shift (where the shift is representable)."""
    lw = np.asarray(lw)
    w, lse = normalize_log_weights(lw)
    assert np.all(np.isfinite(w)) and np.sum(w) == pytest.approx(1.0, abs=1e-12)
    assert np.isfinite(lse)
    shifted = lw + shift
    if abs(shift) < 1e6:  # shifted log-weights keep ~1e-10 absolute precision
        w2, lse2 = normalize_log_weights(shifted)
        np.testing.assert_allclose(w2, w, rtol=1e-8, atol=1e-12)
        assert lse2 == pytest.approx(lse + shift, rel=1e-12, abs=1e-6)


@settings(max_examples=100, deadline=None)
@given(a=st.floats(-1e4, 1e4), b=st.floats(-1e4, 1e4), s=st.floats(0.0, 100.0))
def test_heading_residual_is_wrapped_and_congruent(a, b, s):
    d = dr_residual(np.array([a, s]), np.array([b, 0.0]))
    assert -np.pi <= d[0] < np.pi
    turns = (a - b - d[0]) / (2 * np.pi)
    assert abs(turns - round(turns)) < 1e-6
    assert d[1] == s
    assert -np.pi <= wrap_angle(a) < np.pi
