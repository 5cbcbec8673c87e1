"""Tests of filterwnn.weight_model: the WNN weight-state model."""

import numpy as np
import pytest
from filterpy.kalman import ExtendedKalmanFilter

from filterwnn import wnn
from filterwnn.weight_model import WNNWeightModel


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
