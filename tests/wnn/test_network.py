"""Tests of filterwnn.wnn: wavelets, pack/unpack, batched forward, analytic Jacobian."""

import numpy as np
import pytest

from filterwnn import wnn

WAVELETS = ["morlet", "mexican_hat"]


@pytest.fixture
def net(rng):
    X = rng.uniform(-1, 1, size=(7, 5))
    theta = wnn.init_paper(5, 4, rng=rng)
    theta[-8:-4] = rng.choice([-1, 1], 4) * rng.uniform(0.3, 1.5, 4)  # dilations of both signs
    return theta, X


@pytest.mark.parametrize("wavelet", WAVELETS)
def test_wavelet_derivative_matches_finite_differences(wavelet):
    psi, dpsi = wnn.WAVELETS[wavelet]
    t = np.linspace(-4, 4, 41)
    h = 1e-6
    np.testing.assert_allclose(dpsi(t), (psi(t + h) - psi(t - h)) / (2 * h), atol=1e-8)
    np.testing.assert_allclose(psi(t), psi(-t))  # even


def test_morlet_closed_form():
    t = np.array([0.0, 1.0])
    np.testing.assert_allclose(wnn.morlet(t), [1.0, np.cos(1.75) * np.exp(-0.5)])


def test_n_params_and_layout():
    assert wnn.n_params(5, 20) == 160
    W = np.arange(6.0).reshape(2, 3)
    theta = wnn.pack(W, [10.0, 11.0], [20.0, 21.0], [30.0, 31.0])
    np.testing.assert_array_equal(theta, [0, 1, 2, 3, 4, 5, 10, 11, 20, 21, 30, 31])


def test_pack_unpack_round_trip(rng):
    theta = rng.standard_normal((3, 2, 160))
    W, v, a, b = wnn.unpack(theta, 5)
    assert W.shape == (3, 2, 20, 5) and v.shape == a.shape == b.shape == (3, 2, 20)
    np.testing.assert_array_equal(wnn.pack(W, v, a, b), theta)


def test_unpack_rejects_bad_length():
    with pytest.raises(ValueError, match="multiple of n_inputs"):
        wnn.unpack(np.zeros(17), 5)


def test_forward_closed_form(net):
    theta, X = net
    W, v, a, b = wnn.unpack(theta, 5)
    expected = np.array(
        [sum(v[j] * wnn.morlet((W[j] @ x - b[j]) / abs(a[j])) for j in range(4)) for x in X]
    )
    np.testing.assert_allclose(wnn.forward(theta, X), expected, rtol=1e-12)


@pytest.mark.parametrize("wavelet", WAVELETS)
def test_batched_forward_equals_one_at_a_time(rng, wavelet):
    X = rng.uniform(-1, 1, size=(6, 5))
    thetas = rng.standard_normal((3, 4, 160))
    batched = wnn.forward(thetas, X, wavelet)
    assert batched.shape == (3, 4, 6)
    for i in range(3):
        for j in range(4):
            single = [wnn.forward(thetas[i, j], x, wavelet)[0] for x in X]
            np.testing.assert_allclose(batched[i, j], single, rtol=1e-12, atol=1e-14)
    J = wnn.jacobian(thetas, X, wavelet)
    assert J.shape == (3, 4, 6, 160)
    np.testing.assert_allclose(J[2, 1], wnn.jacobian(thetas[2, 1], X, wavelet), rtol=1e-12)


@pytest.mark.parametrize("wavelet", WAVELETS)
def test_jacobian_equals_finite_differences(net, wavelet):
    theta, X = net
    J = wnn.jacobian(theta, X, wavelet)
    h = 1e-6
    E = np.eye(theta.size)
    fd = np.stack(
        [(wnn.forward(theta + h * e, X, wavelet) - wnn.forward(theta - h * e, X, wavelet)) / (2 * h) for e in E],
        axis=1,
    )
    np.testing.assert_allclose(J, fd, atol=1e-7, rtol=1e-6)


def test_dilation_floor_bounds_division():
    X = np.ones((2, 1))
    theta = wnn.pack(np.ones((1, 1)), [1.0], [0.0], [0.0])  # a = 0
    y = wnn.forward(theta, X)
    assert np.all(np.isfinite(y))
    np.testing.assert_allclose(y, wnn.morlet(1.0 / wnn.DILATION_FLOOR))
    J = wnn.jacobian(theta, X)
    assert np.all(np.isfinite(J)) and J[0, 2] == 0.0  # no gradient for a below the floor
    # psi is even: a negative dilation gives the same output as its magnitude
    t_neg = wnn.pack(np.ones((1, 1)), [1.0], [-0.7], [0.2])
    t_pos = wnn.pack(np.ones((1, 1)), [1.0], [0.7], [0.2])
    np.testing.assert_allclose(wnn.forward(t_neg, X), wnn.forward(t_pos, X))


def test_unknown_wavelet():
    with pytest.raises(ValueError, match="wavelet"):
        wnn.forward(np.zeros(8), np.zeros((1, 1)), wavelet="haar")


def test_inits(rng):
    X = rng.uniform(-1, 1, size=(50, 5)) * [1, 1, 3, 3, 3]
    t = wnn.init_scaled(X, 20, rng=1)
    assert t.shape == (160,)
    np.testing.assert_array_equal(t, wnn.init_scaled(X, 20, rng=1))
    W, v, a, b = wnn.unpack(t, 5)
    assert np.all(a > wnn.DILATION_FLOOR)
    S = X @ W.T
    assert np.all((b >= S.min(0)) & (b <= S.max(0)))  # translations inside the data range
    p = wnn.init_paper(5, 20, rng=2)
    assert p.min() >= 0 and p.max() <= 1
