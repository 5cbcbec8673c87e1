"""Reduced sigma-point sets: identities, filterpy protocol, KF equivalence, errors."""

import warnings

import numpy as np
import pytest
from filterpy.kalman import (
    JulierSigmaPoints,
    MerweScaledSigmaPoints,
    UnscentedKalmanFilter as FilterpyUKF,
)
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.linalg import cholesky

from filterwnn import MinimalSkewSigmaPoints, SphericalSimplexSigmaPoints
from filterwnn.kalman.sigma_points import sigma_deviations, unit_sigma_points

RTOL = 1e-9  # moments are reproduced to this relative accuracy
CLASSES = [MinimalSkewSigmaPoints, SphericalSimplexSigmaPoints]


def random_spd(rng, n, cond=1e2):
    """A random SPD matrix with condition number ``cond``."""
    Q, _ = np.linalg.qr(rng.standard_normal((n, n)))
    ev = np.logspace(0, np.log10(cond), n)
    return (Q * ev) @ Q.T


def moments(points, sig):
    m = points.Wm @ sig
    d = sig - m
    return m, (d.T * points.Wc) @ d


@pytest.mark.parametrize("cls", CLASSES)
@pytest.mark.parametrize("n", [1, 2, 3, 5, 8])
def test_weights_sum_to_one_and_count(cls, n):
    p = cls(n, alpha=0.8, beta=2.0, w0=0.25)
    assert p.num_sigmas() == n + 2
    assert p.Wm.shape == p.Wc.shape == (n + 2,)
    np.testing.assert_allclose(p.Wm.sum(), 1.0, rtol=1e-12)
    np.testing.assert_allclose(p.Wc.sum(), 1.0 + 1 - 0.8**2 + 2.0, rtol=1e-12)


def test_minimal_skew_weights_are_julier_uhlmann_2002():
    n, w0 = 4, 0.2
    p = MinimalSkewSigmaPoints(n, w0=w0)
    W1 = (1 - w0) / 2**n
    expected = [w0, W1, W1, 2 * W1, 4 * W1, 8 * W1]
    np.testing.assert_allclose(p.Wm, expected, rtol=1e-14)


def test_spherical_simplex_points_lie_on_sphere():
    n, w0 = 7, 0.3
    p = SphericalSimplexSigmaPoints(n, w0=w0)
    sig = p.sigma_points(np.zeros(n), np.eye(n))
    np.testing.assert_allclose(np.linalg.norm(sig[1:], axis=1), np.sqrt(n / (1 - w0)), rtol=1e-12)
    np.testing.assert_allclose(p.Wm[1:], (1 - w0) / (n + 1), rtol=1e-14)


def test_subclass_and_repr():
    p = SphericalSimplexSigmaPoints(3)
    assert isinstance(p, MerweScaledSigmaPoints)
    r = repr(p)
    assert r.startswith("SphericalSimplexSigmaPoints object") and "w0" in r and "Wm" in r


@settings(max_examples=40, deadline=None)
@given(
    n=st.integers(1, 40),
    seed=st.integers(0, 2**32 - 1),
    log_cond=st.floats(0, 8),
    alpha=st.floats(0.1, 2.0),
    w0=st.floats(0, 0.9),
    which=st.sampled_from(CLASSES),
)
def test_points_reproduce_mean_and_covariance(n, seed, log_cond, alpha, w0, which):
    rng = np.random.default_rng(seed)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # minimal skew above n = 20
        p = which(n, alpha=alpha, beta=0.0, w0=w0)
    P = random_spd(rng, n, 10**log_cond)
    x = rng.standard_normal(n) * 10
    sig = p.sigma_points(x, P)
    assert sig.shape == (p.num_sigmas(), n)
    m, C = moments(p, sig)
    # relative to the scale of x and of P (entries of P near 0 have no relative scale)
    np.testing.assert_allclose(m, x, rtol=0, atol=RTOL * max(np.abs(x).max(), np.sqrt(np.abs(P).max())))
    np.testing.assert_allclose(C, P, rtol=0, atol=RTOL * np.abs(P).max())


@settings(max_examples=30, deadline=None)
@given(n=st.integers(1, 30), seed=st.integers(0, 2**32 - 1))
def test_structured_deviations_equal_dense_product(n, seed):
    rng = np.random.default_rng(seed)
    P = random_spd(rng, n, 1e3)
    U = cholesky(P)
    for p in (
        SphericalSimplexSigmaPoints(n, alpha=0.5),
        MerweScaledSigmaPoints(n, 0.3, 2.0, 3.0 - n),
        JulierSigmaPoints(n, kappa=1.0),
    ):
        D = sigma_deviations(p, U)
        np.testing.assert_allclose(D, unit_sigma_points(p) @ U, atol=1e-12 * np.abs(U).max())
        np.testing.assert_allclose(np.zeros(n) + D, p.sigma_points(np.zeros(n), P), atol=1e-10 * np.abs(U).max())
    # batched over leading axes
    Us = np.stack([U, 2 * U])
    p = SphericalSimplexSigmaPoints(n)
    np.testing.assert_allclose(sigma_deviations(p, Us)[1], 2 * sigma_deviations(p, U), rtol=1e-12, atol=1e-14)


def test_near_singular_covariance_still_reproduced():
    rng = np.random.default_rng(3)
    n = 6
    P = random_spd(rng, n, 1e12)
    p = SphericalSimplexSigmaPoints(n)
    m, C = moments(p, p.sigma_points(np.ones(n), P))
    np.testing.assert_allclose(C, P, atol=1e-9 * np.abs(P).max())


@pytest.mark.parametrize("cls", CLASSES)
def test_filterpy_ukf_with_reduced_points_equals_kalman_filter(cls, linear_model):
    m = linear_model
    xs, zs = m.simulate(40, rng=11)
    kf = m.kalman_filter()
    ukf = FilterpyUKF(m.dim_x, m.dim_z, 1.0, m.hx, m.fx, cls(m.dim_x, alpha=0.9, beta=2.0, w0=0.1))
    ukf.x, ukf.P, ukf.Q, ukf.R = m.x0.copy(), m.P0.copy(), m.Q, m.R
    for z in zs:
        kf.predict()
        ukf.predict()
        np.testing.assert_allclose(ukf.x, kf.x, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(ukf.P, kf.P, rtol=1e-9, atol=1e-9)
        kf.update(z)
        ukf.update(z)
        np.testing.assert_allclose(ukf.x, kf.x, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(ukf.P, kf.P, rtol=1e-9, atol=1e-9)


def test_custom_subtract_is_used():
    calls = []

    def subtract(a, b):
        calls.append(1)
        return np.subtract(a, b)

    p = SphericalSimplexSigmaPoints(2, subtract=subtract)
    sig = p.sigma_points(np.zeros(2), np.eye(2))
    assert len(calls) == 4 and sig.shape == (4, 2)


@pytest.mark.parametrize("cls", CLASSES)
@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"n": 0}, "n must be >= 1, got 0"),
        ({"n": 2.5}, "n must be an integer"),
        ({"n": 2, "alpha": 0.0}, r"alpha must be > 0, got 0.0"),
        ({"n": 2, "alpha": -1.0}, r"alpha must be > 0, got -1.0"),
        ({"n": 2, "w0": 1.0}, r"w0 must satisfy w0 < 1 \(the outer points share 1 - w0\), got 1.0"),
        ({"n": 2, "kappa": -2.0}, r"kappa must satisfy n \+ kappa > 0 .* got kappa=-2.0 with n=2; .* w0="),
        ({"n": 2, "kappa": 1.0, "w0": 0.2}, r"give kappa .* or w0=, not both; got kappa=1.0 and w0=0.2"),
        ({"n": 2, "kappa": float("inf")}, "kappa must be a finite real number, got inf"),
        ({"n": 2, "beta": float("nan")}, "beta must be a finite real number"),
    ],
)
def test_constructor_errors(cls, kwargs, match):
    with pytest.raises((ValueError, TypeError), match=match):
        cls(**kwargs)


@pytest.mark.parametrize("cls", CLASSES)
def test_sigma_points_errors(cls):
    p = cls(3)
    with pytest.raises(ValueError, match="x must have size n=3, got size 2"):
        p.sigma_points(np.zeros(2), np.eye(3))
    with pytest.raises(ValueError, match=r"P must have shape \(3, 3\), got \(2, 2\)"):
        p.sigma_points(np.zeros(3), np.eye(2))
    with pytest.raises(ValueError, match="P must be finite"):
        p.sigma_points(np.zeros(3), np.full((3, 3), np.nan))
    with pytest.raises(ValueError, match="P must be positive definite"):
        p.sigma_points(np.zeros(3), -np.eye(3))
    with pytest.raises(ValueError, match="x must be finite"):
        p.sigma_points(np.array([0.0, np.inf, 0.0]), np.eye(3))


def test_minimal_skew_warns_above_20_and_refuses_overflow():
    with pytest.warns(UserWarning, match="use SphericalSimplexSigmaPoints"):
        MinimalSkewSigmaPoints(21)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        MinimalSkewSigmaPoints(20)
    with pytest.raises(ValueError, match="n <= 1021"):
        MinimalSkewSigmaPoints(1100)


@pytest.mark.parametrize("cls", CLASSES)
@pytest.mark.parametrize("n", [2, 5, 32, 33, 40])
def test_fast_sigma_points_equal_unit_points_times_cholesky(cls, n):
    """The hot path (dense Z @ U up to n = 32, staircase above) is x + Z @ chol(P).T."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        pts = cls(n, alpha=0.7, beta=2.0, w0=0.1)
    rng = np.random.default_rng(n)
    P, x = random_spd(rng, n), rng.standard_normal(n)
    sig = pts.sigma_points(x, P)
    np.testing.assert_allclose(sig, x + pts.Z @ cholesky(P), rtol=1e-10, atol=1e-10)
    # filterpy's accepted inputs: a column x, a list, a scalar P
    np.testing.assert_allclose(pts.sigma_points(x.reshape(-1, 1), P.tolist()), sig, rtol=0, atol=0)
    np.testing.assert_allclose(pts.sigma_points(x, 2.0), x + pts.Z * np.sqrt(2.0), rtol=1e-12)


@pytest.mark.parametrize("cls", CLASSES)
def test_fast_path_still_refuses_asymmetric_and_custom_sqrt_is_used(cls):
    P = np.array([[2.0, 0.5], [0.0, 1.0]])
    with pytest.raises(ValueError, match="P must be symmetric"):
        cls(2).sigma_points(np.zeros(2), P)
    calls = []
    pts = cls(2, sqrt_method=lambda M: calls.append(1) or cholesky(M))
    pts.sigma_points(np.zeros(2), np.eye(2))
    assert calls == [1]


@pytest.mark.parametrize("cls", CLASSES)
@pytest.mark.parametrize("n, alpha, beta, kappa", [(1, 1.0, 2.0, 0.1), (2, 0.1, 2.0, 1.0), (4, 0.1, 2.0, -1.0),
                                                   (3, 0.5, 2.0, 0.0), (6, 1.0, 0.0, 3.0 - 6)])
def test_filterpys_arguments_mean_what_they_mean_in_merwes_set(cls, n, alpha, beta, kappa):
    """Positional (n, alpha, beta, kappa) as filterpy's: Merwe's centre weights, the moments exact."""
    ours, merwe = cls(n, alpha, beta, kappa), MerweScaledSigmaPoints(n, alpha, beta, kappa)
    assert (ours.alpha, ours.beta, ours.kappa) == (alpha, beta, kappa)
    np.testing.assert_allclose([ours.Wm[0], ours.Wc[0]], [merwe.Wm[0], merwe.Wc[0]], rtol=1e-12)
    np.testing.assert_allclose(ours.w0, kappa / (n + kappa), rtol=1e-15)
    P = random_spd(np.random.default_rng(n), n)
    m, C = moments(ours, ours.sigma_points(np.ones(n), P))
    np.testing.assert_allclose(m, np.ones(n), atol=1e-12)
    np.testing.assert_allclose(C, P, rtol=1e-8, atol=1e-10)
    if cls is SphericalSimplexSigmaPoints:  # the outer points on Merwe's sphere
        sig = ours.sigma_points(np.zeros(n), np.eye(n))
        np.testing.assert_allclose(np.linalg.norm(sig[1:], axis=1), alpha * np.sqrt(n + kappa), rtol=1e-12)


@pytest.mark.parametrize("cls", CLASSES)
def test_kappa_zero_and_the_default_are_the_old_w0_zero_bit_for_bit(cls):
    a, b, c = cls(3, 0.5, 2.0), cls(3, 0.5, 2.0, 0.0), cls(3, 0.5, 2.0, w0=0.0)
    assert np.array_equal(a.Wm, b.Wm) and np.array_equal(a.Wm, c.Wm) and np.array_equal(a.Z, c.Z)
    assert cls(3, w0=0.2).kappa == 0.0 and "kappa" in repr(b)


@pytest.mark.parametrize("cls", CLASSES)
def test_a_signature_mistake_names_the_public_class(cls):
    with pytest.raises(TypeError, match=cls.__name__):
        cls(2, 1.0, 2.0, 0.0, None, None, 0.2)  # w0 is keyword-only
