"""filterwnn.angles: wrapped residuals and circular means, the same in both call modes."""

import numpy as np
import pytest
from filterpy.kalman import MerweScaledSigmaPoints
from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF

from filterwnn import SphericalSimplexSigmaPoints, UnscentedKalmanFilter
from filterwnn.angles import angle_mean, angle_residual, wrap


def test_wrap_range():
    a = np.linspace(-20, 20, 401)
    w = wrap(a)
    assert np.all(w >= -np.pi) and np.all(w < np.pi)
    np.testing.assert_allclose(np.sin(w), np.sin(a), atol=1e-12)
    np.testing.assert_allclose(np.cos(w), np.cos(a), atol=1e-12)


def test_residual_rows_equal_array():
    rng = np.random.default_rng(0)
    A, b = rng.uniform(-4, 4, (7, 3)), rng.uniform(-4, 4, 3)
    r = angle_residual([0, 2])
    rows = np.array([r(a, b) for a in A])
    np.testing.assert_array_equal(r(A, b), rows)
    np.testing.assert_array_equal(rows[:, 1], A[:, 1] - b[1])  # not an angle column
    assert np.all(np.abs(rows[:, [0, 2]]) <= np.pi)


def test_residual_does_not_modify_inputs():
    A, b = np.array([[3.0, 1.0]]), np.array([-3.0, 0.0])
    angle_residual(0)(A, b)
    assert A[0, 0] == 3.0 and b[0] == -3.0


def test_mean_is_circular_across_pi():
    m = angle_mean([1])
    sig = np.array([[1.0, np.pi - 0.05], [3.0, -np.pi + 0.05], [2.0, np.pi - 0.05]])
    out = m(sig, np.array([0.25, 0.25, 0.5]))
    w, a = np.array([0.25, 0.25, 0.5]), sig[:, 1]
    assert out[1] == pytest.approx(np.arctan2(w @ np.sin(a), w @ np.cos(a)), abs=1e-15)
    assert abs(wrap(out[1] - (np.pi - 0.025))) < 1e-4  # the linear mean would be ~1.55
    assert out[0] == pytest.approx(2.0)


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: angle_residual([]), "columns must be a non-empty sequence of ints"),
        (lambda: angle_residual(1.5), "columns must be an int or a sequence of ints"),
        (lambda: angle_residual([1])(np.zeros(1), np.zeros(1)), r"needs at least 2 entries"),
        (lambda: angle_mean([2])(np.zeros((3, 2)), np.ones(3) / 3), r"needs sigmas of shape"),
    ],
)
def test_bad_arguments(make, match):
    with pytest.raises((ValueError, TypeError), match=match):
        make()


# a range-bearing tracker whose bearing crosses +-pi: both helpers are needed
F = np.array([[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 1], [0, 0, 0, 1]], dtype=float)


def fx(x, dt):
    return x @ F.T


def hx(x):
    return np.stack([np.hypot(x[..., 0], x[..., 2]), np.arctan2(x[..., 2], x[..., 0])], axis=-1)


def run(cls, points, **kw):
    ukf = cls(4, 2, 1.0, hx, fx, points, residual_z=angle_residual(1), z_mean_fn=angle_mean(1), **kw)
    ukf.x = np.array([-20.0, 0.0, 2.0, -0.5])  # moving south across the -x axis: bearing wraps
    ukf.P = np.diag([1.0, 0.1, 1.0, 0.1])
    ukf.Q = np.eye(4) * 1e-3
    ukf.R = np.diag([0.1, 0.01])
    rng = np.random.default_rng(1)
    x = ukf.x.copy()
    for _ in range(10):
        x = F @ x
        z = hx(x) + rng.normal(0, [0.3, 0.1])
        z[1] = wrap(z[1])
        ukf.predict()
        ukf.update(z)
    return ukf


@pytest.mark.parametrize("points", [lambda: MerweScaledSigmaPoints(4, 1.0, 2.0, 0.0),
                                    lambda: SphericalSimplexSigmaPoints(4)])
def test_helpers_give_filterpy_numbers_in_both_modes(points):
    ref = run(FilterpyUKF, points())
    for vectorized in (False, True):
        ours = run(UnscentedKalmanFilter, points(), vectorized=vectorized)
        np.testing.assert_allclose(ours.x, ref.x, atol=1e-9)
        np.testing.assert_allclose(ours.P, ref.P, atol=1e-9)


def test_angles_is_the_one_home_of_the_dr_heading_arithmetic():
    from filterwnn.navigation import dead_reckoning as dr

    assert dr.wrap_angle is wrap
    rng = np.random.default_rng(7)
    a, b = rng.uniform(-4, 4, (9, 4)), rng.uniform(-4, 4, 4)
    np.testing.assert_array_equal(dr.dr_residual(a, b), angle_residual(0)(a, b))
    sig, w = rng.uniform(-4, 4, (9, 2)), rng.dirichlet(np.ones(9))
    # bit for bit the former DR formula (one dot product per angle column)
    want = w @ sig
    want[0] = np.arctan2(w @ np.sin(sig[:, 0]), w @ np.cos(sig[:, 0]))
    np.testing.assert_array_equal(dr.dr_z_mean(sig, w), want)
    np.testing.assert_array_equal(angle_mean([0])(sig, w), want)
