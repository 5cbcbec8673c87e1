"""Tests of filterwnn.wnn.weight_model: the WNN weight-state model."""

import numpy as np
import pytest
from filterpy.kalman import ExtendedKalmanFilter

from filterwnn import wnn
from filterwnn.wnn.weight_model import WNNWeightModel


@pytest.fixture
def model():
    return WNNWeightModel(n_inputs=3, n_hidden=4, Q=1e-4, R=0.1, P0=0.1)


def test_sizes_and_noise(model):
    assert model.dim_x == 24 and model.dim_z == 1
    np.testing.assert_array_equal(model.Q, 1e-4 * np.eye(24))
    assert model.R.shape == (1, 1)
    m = WNNWeightModel(3, 4, Q=np.full(24, 2.0))
    np.testing.assert_array_equal(np.diag(m.Q), 2.0)


def test_hx_vectorized_equals_rowwise(model, rng):
    thetas = rng.standard_normal((6, 24))
    x = rng.uniform(-1, 1, 3)
    out = model.hx(thetas, x=x)
    assert out.shape == (6, 1)
    for th, o in zip(thetas, out):
        np.testing.assert_allclose(model.hx(th, x=x), o, rtol=1e-13)
        np.testing.assert_allclose(o[0], wnn.forward(th, x[None])[0], rtol=1e-13)


def test_hjacobian_finite_differences(model, rng):
    theta = rng.standard_normal(24)
    theta[16:20] = rng.uniform(0.5, 1.5, 4)
    x = rng.uniform(-1, 1, 3)
    H = model.HJacobian(theta, x=x)
    assert H.shape == (1, 24)
    h = 1e-6
    fd = np.array([(model.hx(theta + h * e, x=x) - model.hx(theta - h * e, x=x))[0] / (2 * h) for e in np.eye(24)])
    np.testing.assert_allclose(H[0], fd, atol=1e-7)
    assert model.HJacobian(np.stack([theta, theta]), x=x).shape == (2, 1, 24)


def test_random_walk_fx(model, rng):
    thetas = rng.standard_normal((5, 24))
    np.testing.assert_array_equal(model.fx(thetas, 1.0), thetas)
    np.testing.assert_array_equal(model.FJacobian(thetas[0]), np.eye(24))


def test_hx_requires_input(model):
    with pytest.raises(TypeError, match="x=x_k"):
        model.hx(np.zeros(24))


def test_simulate_and_filterpy_ekf_tracks_outputs(rng):
    model = WNNWeightModel(n_inputs=2, n_hidden=3, Q=0.0, R=1e-4, P0=0.01)
    X = rng.uniform(-1, 1, (300, 2))
    truth = wnn.init_scaled(X, 3, rng=1)
    thetas, zs = model.simulate(300, rng=2, x0=truth, X=X)
    assert thetas.shape == (300, 15) and zs.shape == (300, 1)
    np.testing.assert_allclose(thetas, np.tile(truth, (300, 1)))  # Q = 0: constant weights
    ekf = ExtendedKalmanFilter(model.dim_x, model.dim_z)
    ekf.x = truth + 0.05 * rng.standard_normal(15)
    ekf.P = model.P0.copy()
    ekf.R = model.R.copy()
    ekf.Q = model.Q.copy()
    def train_mse():
        return np.mean((np.array([model.hx(ekf.x, x=x)[0] for x in X]) - zs[:, 0]) ** 2)

    err0 = train_mse()
    for x, z in zip(X, zs):
        ekf.predict()
        ekf.update(z, lambda th, x=x: model.HJacobian(th, x=x), lambda th, x=x: model.hx(th, x=x))
    assert train_mse() < 0.2 * err0


# ---------------------------------------------------------------- posterior pieces (issue 13)
def _fd_grad(f, theta, h=1e-6):
    return np.array([(f(theta + h * e) - f(theta - h * e)) / (2 * h) for e in np.eye(theta.size)])


def test_log_likelihood_closed_form_and_batch(model, rng):
    thetas = rng.standard_normal((5, 24))
    thetas[:, 16:20] = rng.uniform(0.5, 1.5, (5, 4))
    X, y = rng.uniform(-1, 1, (7, 3)), rng.standard_normal(7)
    ll = model.log_likelihood(thetas, X, y)
    assert ll.shape == (5,)
    for th, l in zip(thetas, ll):
        f = wnn.forward(th, X)
        ref = np.sum(-0.5 * (y - f) ** 2 / 0.1 - 0.5 * np.log(2 * np.pi * 0.1))
        np.testing.assert_allclose(model.log_likelihood(th, X, y), ref, rtol=1e-12)
        np.testing.assert_allclose(l, ref, rtol=1e-12)


def test_grad_log_likelihood_finite_differences(model, rng):
    thetas = rng.standard_normal((3, 24))
    thetas[:, 16:20] = rng.uniform(0.5, 1.5, (3, 4))
    X, y = rng.uniform(-1, 1, (6, 3)), rng.standard_normal(6)
    G = model.grad_log_likelihood(thetas, X, y)
    ll, G2 = model.log_likelihood_and_grad(thetas, X, y)
    assert G.shape == (3, 24)
    np.testing.assert_array_equal(G, G2)
    np.testing.assert_allclose(ll, model.log_likelihood(thetas, X, y), rtol=1e-13)
    for th, g in zip(thetas, G):
        fd = _fd_grad(lambda t: model.log_likelihood(t, X, y), th)
        np.testing.assert_allclose(g, fd, rtol=1e-6, atol=1e-5)
        np.testing.assert_allclose(model.grad_log_likelihood(th, X, y), g, rtol=1e-12)


def test_log_prior_and_gradient(rng):
    A = rng.standard_normal((24, 24))
    P0 = A @ A.T / 24 + 0.1 * np.eye(24)
    x0 = rng.standard_normal(24)
    m = WNNWeightModel(3, 4, R=0.1, x0=x0, P0=P0)
    thetas = rng.standard_normal((4, 24))
    from scipy.stats import multivariate_normal

    np.testing.assert_allclose(m.log_prior(thetas), multivariate_normal(x0, P0).logpdf(thetas), rtol=1e-10)
    G = m.grad_log_prior(thetas)
    assert G.shape == (4, 24)
    np.testing.assert_allclose(G[0], _fd_grad(m.log_prior, thetas[0]), rtol=1e-6, atol=1e-6)
    assert isinstance(m.log_prior(thetas[0]), float)


def test_posterior_pieces_reject_bad_rows(model):
    with pytest.raises(ValueError, match="X must have shape"):
        model.log_likelihood(np.zeros(24), np.zeros((4, 5)), np.zeros(4))
    with pytest.raises(ValueError, match="y must have one entry per row"):
        model.log_likelihood(np.zeros(24), np.zeros((4, 3)), np.zeros(3))
    singular = WNNWeightModel(3, 4, P0=np.zeros(24))
    with pytest.raises(ValueError, match="P0 must be positive definite"):
        singular.log_prior(np.zeros(24))


def test_scaled_prior_matches_scaled_start(rng):
    from filterwnn.wnn.weight_model import scaled_prior

    X = rng.uniform(-1, 1, (200, 3)) * np.array([1.0, 2.0, 0.5]) + np.array([0.0, 1.0, 0.0])
    x0, var = scaled_prior(X, n_hidden=4, output_scale=0.1)
    draws = np.stack([wnn.init_scaled(X, 4, rng=rng) for _ in range(4000)])
    W, v, a, b = wnn.unpack(draws, 3)
    W0, v0, a0, b0 = wnn.unpack(var, 3)
    # W and v: the start's exact law; b: its second moment; a: mean about 1
    np.testing.assert_allclose(W.var(axis=0), W0, rtol=0.1)
    np.testing.assert_allclose(v.var(axis=0), v0, rtol=0.1)
    np.testing.assert_allclose(np.mean(b**2, axis=0), b0, rtol=0.15)
    assert 0.7 < a.mean() < 1.3 and np.all(a0 == 0.25)
