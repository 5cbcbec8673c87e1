"""The examples of Labbe's "Kalman and Bayesian Filters in Python", chapters 10-11, as a
filterpy user has them, with filterwnn's classes swapped in.

Each problem is written here from the book's description (not copied): a constant-velocity
tracker whose first ``fx`` fills ``np.empty_like(x)`` entry by entry; a radar tracking a
climbing aircraft by slant range and elevation; a robot with a steering model that measures
range and bearing to landmarks, with the book's angle residuals (``if y > pi``) and
``atan2`` means; a scalar ``hx``; a batch run with the RTS smoother. The functions are
written the book's way, for one point. In loop mode our filter must give filterpy's
numbers bit for bit; with ``vectorized=True`` the one-point functions must be caught on the
first call by one error that names them, and the last-axis rewrites must agree with loop
mode. The reduced sets take filterpy's ``(n, alpha, beta, kappa)`` and must track as well as
Merwe's set at the same settings. (The chapter-12 particle filter is in
``tests/monte_carlo/test_filterpy_book_pf.py``.)
"""

import math

import numpy as np
import pytest
from filterpy.common import Q_discrete_white_noise
from filterpy.kalman import KalmanFilter, MerweScaledSigmaPoints
from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF

from filterwnn import MinimalSkewSigmaPoints, SphericalSimplexSigmaPoints, UnscentedKalmanFilter
from filterwnn.angles import angle_residual

SETS = {"merwe": MerweScaledSigmaPoints, "minimal-skew": MinimalSkewSigmaPoints,
        "spherical-simplex": SphericalSimplexSigmaPoints}


def run(ukf, zs, **update_args):
    xs = []
    for z in zs:
        ukf.predict()
        ukf.update(z, **update_args)
        xs.append(ukf.x.copy())
    return np.array(xs)


def rmse(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)))


# --------------------------------------------------------------------------- ch. 10: first UKF
def cv_fx(x, dt):
    """Constant velocity in x and y, state [x, vx, y, vy]: written for one point."""
    out = np.empty_like(x)
    out[0] = x[1] * dt + x[0]
    out[1] = x[1]
    out[2] = x[3] * dt + x[2]
    out[3] = x[3]
    return out


def cv_hx(x):
    return x[[0, 2]]


def cv_data(n=40, seed=1):
    rng = np.random.default_rng(seed)
    truth = np.array([[0.1 * k, 1.0, 0.05 * k, 0.5] for k in range(n)])
    return truth, truth[:, [0, 2]] + rng.normal(0, 0.3, (n, 2))


def cv_filter(cls, points, **kw):
    f = cls(4, 2, 0.1, cv_hx, cv_fx, points, **kw)
    f.x = np.array([0.0, 0.9, 0.0, 0.4])
    f.P *= 0.2
    f.R = np.diag([0.09, 0.09])
    f.Q = np.kron(np.eye(2), Q_discrete_white_noise(2, dt=0.1, var=0.02))
    return f


@pytest.mark.parametrize("name", list(SETS))
def test_first_ukf_equals_the_kalman_filter_with_every_point_set(name):
    """A linear model: the UKF with any exact set is the KF (the book's check)."""
    _, zs = cv_data()
    kf = KalmanFilter(4, 2)
    kf.F = np.kron(np.eye(2), np.array([[1.0, 0.1], [0.0, 1.0]]))
    kf.H = np.array([[1.0, 0, 0, 0], [0, 0, 1.0, 0]])
    ukf = cv_filter(UnscentedKalmanFilter, SETS[name](4, 0.1, 2.0, -1.0))
    kf.x, kf.P, kf.R, kf.Q = ukf.x.copy(), ukf.P.copy(), ukf.R.copy(), ukf.Q.copy()
    xs_kf = []
    for z in zs:
        kf.predict(); kf.update(z); xs_kf.append(kf.x.copy())
    np.testing.assert_allclose(run(ukf, zs), np.array(xs_kf), atol=1e-8)


def test_first_ukf_in_loop_mode_is_filterpys_bit_for_bit():
    _, zs = cv_data()
    a = run(cv_filter(FilterpyUKF, MerweScaledSigmaPoints(4, 0.1, 2.0, -1.0)), zs)
    b = run(cv_filter(UnscentedKalmanFilter, MerweScaledSigmaPoints(4, 0.1, 2.0, -1.0)), zs)
    assert np.array_equal(a, b)


def test_the_one_point_fx_is_caught_in_vectorized_mode():
    """The issue's silent failure: empty_like + x[0] gives the right shape and wrong numbers."""
    _, zs = cv_data()
    ukf = cv_filter(UnscentedKalmanFilter, MerweScaledSigmaPoints(4, 0.1, 2.0, -1.0), vectorized=True)
    x, P = ukf.x.copy(), ukf.P.copy()
    with pytest.raises(ValueError, match=r"vectorized fx looks written for one point: row \d+, entry \d+ of "
                                         r"the batch .* when that row is passed alone.*Fix: index the last "
                                         r"axis \(x\[\.\.\., 1\], not x\[1\]\)"):
        ukf.predict()
    assert np.array_equal(ukf.x, x) and np.array_equal(ukf.P, P) and ukf.step == 0


def test_the_one_point_hx_is_caught_in_vectorized_mode():
    ukf = cv_filter(UnscentedKalmanFilter, MerweScaledSigmaPoints(4, 0.1, 2.0, -1.0), vectorized=True)
    ukf.fx = lambda X, dt: X @ np.kron(np.eye(2), np.array([[1.0, 0.1], [0.0, 1.0]])).T
    ukf.predict()
    with pytest.raises(ValueError, match=r"vectorized hx looks written for one point: .*got \(2, 4\).*"
                                         r"return shape \(n_sigmas, dim_z\)"):
        ukf.update(np.array([0.1, 0.0]))


# --------------------------------------------------------------------------- ch. 10: radar
RADAR_POS = np.array([0.0, 0.0])


def radar_fx(x, dt):
    """State [downrange, velocity, altitude]: constant velocity, constant altitude."""
    F = np.array([[1.0, dt, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    return F @ x


def radar_hx(x):
    """Slant range and elevation angle, for one point (a list, as the book returns it)."""
    dx, dy = x[0] - RADAR_POS[0], x[2] - RADAR_POS[1]
    return [math.sqrt(dx**2 + dy**2), math.atan2(dy, dx)]


def radar_hx_rows(X):
    dx, dy = X[..., 0] - RADAR_POS[0], X[..., 2] - RADAR_POS[1]
    return np.stack([np.hypot(dx, dy), np.arctan2(dy, dx)], axis=-1)


def radar_fx_rows(X, dt):
    return X @ np.array([[1.0, dt, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).T


def radar_data(n=60, dt=3.0, seed=2):
    rng = np.random.default_rng(seed)
    x = np.array([0.0, 100.0, 1000.0])
    truth, zs = [], []
    for _ in range(n):
        x = radar_fx(x, dt) + np.array([0.0, rng.normal(0, 0.02), rng.normal(0, 0.1)])
        truth.append(x.copy())
        zs.append(np.array(radar_hx(x)) + rng.normal(0, [5.0, math.radians(0.5)]))
    return np.array(truth), np.array(zs)


def radar_filter(cls, points, fx=radar_fx, hx=radar_hx, **kw):
    f = cls(3, 2, 3.0, hx, fx, points, **kw)
    f.x = np.array([0.0, 90.0, 1100.0])
    f.P = np.diag([300.0**2, 30.0**2, 150.0**2])
    f.R = np.diag([5.0**2, math.radians(0.5) ** 2])
    f.Q = np.zeros((3, 3))
    f.Q[0:2, 0:2] = Q_discrete_white_noise(2, dt=3.0, var=0.1)
    f.Q[2, 2] = 0.1
    return f


def test_radar_in_loop_mode_is_filterpys_bit_for_bit():
    _, zs = radar_data()
    a = run(radar_filter(FilterpyUKF, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0)), zs)
    b = run(radar_filter(UnscentedKalmanFilter, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0)), zs)
    assert np.array_equal(a, b)


@pytest.mark.parametrize("name", ["minimal-skew", "spherical-simplex"])
def test_radar_the_reduced_sets_track_as_well_as_merwes_at_the_same_settings(name):
    truth, zs = radar_data()
    ref = rmse(run(radar_filter(FilterpyUKF, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0)), zs)[10:], truth[10:])
    ours = rmse(run(radar_filter(UnscentedKalmanFilter, SETS[name](3, 0.1, 2.0, 0.0)), zs)[10:], truth[10:])
    assert ours < 1.1 * ref


def test_radar_the_one_point_hx_is_caught_and_the_rewrite_agrees_with_loop_mode():
    _, zs = radar_data()
    bad = radar_filter(UnscentedKalmanFilter, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0), fx=radar_fx_rows,
                       vectorized=True)
    bad.predict()
    with pytest.raises(ValueError, match="vectorized hx looks written for one point"):
        bad.update(zs[0])
    loop = run(radar_filter(UnscentedKalmanFilter, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0)), zs)
    vec = run(radar_filter(UnscentedKalmanFilter, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0), fx=radar_fx_rows,
                           hx=radar_hx_rows, vectorized=True), zs)
    np.testing.assert_allclose(vec, loop, rtol=1e-9, atol=1e-6)


def test_batch_filter_and_rts_smoother_are_filterpys():
    _, zs = radar_data(30)
    runs = []
    for cls in (FilterpyUKF, UnscentedKalmanFilter):
        f = radar_filter(cls, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0))
        mu, cov = f.batch_filter(zs)
        runs.append((mu, cov) + tuple(f.rts_smoother(mu, cov)))
    for a, b in zip(*runs):
        assert np.array_equal(a, b)


# --------------------------------------------------------------------------- ch. 10: robot
LANDMARKS = np.array([[5.0, 10.0], [10.0, 5.0], [15.0, 15.0]])
WHEELBASE = 0.5


def normalize_angle(x):
    """The book's habit: a scalar wrap with an if (fails on arrays)."""
    x = x % (2 * np.pi)
    if x > np.pi:
        x -= 2 * np.pi
    return x


def robot_fx(x, dt, u):
    """Bicycle model: state [x, y, heading], control u = [velocity, steering angle]."""
    heading, v, alpha = x[2], u[0], u[1]
    dist = v * dt
    if abs(alpha) > 1e-3:
        beta = dist / WHEELBASE * math.tan(alpha)
        r = WHEELBASE / math.tan(alpha)
        return x + np.array([-r * math.sin(heading) + r * math.sin(heading + beta),
                             r * math.cos(heading) - r * math.cos(heading + beta), beta])
    return x + np.array([dist * math.cos(heading), dist * math.sin(heading), 0.0])


def robot_hx(x, landmarks=LANDMARKS):
    out = []
    for lx, ly in landmarks:
        dx, dy = lx - x[0], ly - x[1]
        out.extend([math.sqrt(dx**2 + dy**2), normalize_angle(math.atan2(dy, dx) - x[2])])
    return np.array(out)


def residual_x(a, b):
    y = a - b
    y[2] = normalize_angle(y[2])
    return y


def residual_h(a, b):
    y = a - b
    for i in range(0, len(y), 2):
        y[i + 1] = normalize_angle(y[i + 1])
    return y


def state_mean(sigmas, Wm):
    x = np.zeros(3)
    x[0] = np.sum(np.dot(sigmas[:, 0], Wm))
    x[1] = np.sum(np.dot(sigmas[:, 1], Wm))
    x[2] = math.atan2(np.sum(np.dot(np.sin(sigmas[:, 2]), Wm)), np.sum(np.dot(np.cos(sigmas[:, 2]), Wm)))
    return x


def z_mean(sigmas, Wm):
    z_count = sigmas.shape[1]
    x = np.zeros(z_count)
    for z in range(0, z_count, 2):
        x[z] = np.sum(np.dot(sigmas[:, z], Wm))
        x[z + 1] = math.atan2(np.sum(np.dot(np.sin(sigmas[:, z + 1]), Wm)),
                              np.sum(np.dot(np.cos(sigmas[:, z + 1]), Wm)))
    return x


def robot_fx_rows(X, dt, u):
    return np.array([robot_fx(x, dt, u) for x in np.atleast_2d(X)]).reshape(np.shape(X))


def robot_hx_rows(X, landmarks=LANDMARKS):
    d = landmarks[None, :, :] - np.atleast_2d(X)[:, None, :2]
    bearing = np.arctan2(d[..., 1], d[..., 0]) - np.atleast_2d(X)[:, None, 2]
    out = np.stack([np.hypot(d[..., 0], d[..., 1]), (bearing + np.pi) % (2 * np.pi) - np.pi], axis=-1)
    return out.reshape(np.shape(X)[:-1] + (2 * len(landmarks),))


def robot_data(n=40, dt=1.0, seed=3):
    rng = np.random.default_rng(seed)
    x, us, zs, truth = np.array([2.0, 6.0, 0.3]), [], [], []
    for k in range(n):
        u = np.array([1.1, 0.01 if k < 20 else 0.25])
        x = robot_fx(x, dt, u)
        us.append(u); truth.append(x.copy())
        zs.append(robot_hx(x) + rng.normal(0, np.tile([0.3, 0.1], len(LANDMARKS))))
    return np.array(truth), np.array(us), np.array(zs)


def robot_filter(cls, points, fx=robot_fx, hx=robot_hx, rx=residual_x, rz=residual_h, **kw):
    f = cls(3, 2 * len(LANDMARKS), 1.0, hx, fx, points, x_mean_fn=state_mean, z_mean_fn=z_mean,
            residual_x=rx, residual_z=rz, **kw)
    f.x = np.array([2.0, 6.0, 0.3])
    f.P = np.diag([0.1, 0.1, 0.05])
    f.R = np.diag(np.tile([0.3**2, 0.1**2], len(LANDMARKS)))
    f.Q = np.eye(3) * 1e-4
    return f


def run_robot(f, us, zs):
    xs = []
    for u, z in zip(us, zs):
        f.predict(u=u)
        f.update(z)
        xs.append(f.x.copy())
    return np.array(xs)


def test_robot_with_angle_residuals_in_loop_mode_is_filterpys_bit_for_bit():
    _, us, zs = robot_data()
    a = run_robot(robot_filter(FilterpyUKF, MerweScaledSigmaPoints(3, 0.00001, 2.0, 0.0)), us, zs)
    b = run_robot(robot_filter(UnscentedKalmanFilter, MerweScaledSigmaPoints(3, 0.00001, 2.0, 0.0)), us, zs)
    assert np.array_equal(a, b)


@pytest.mark.parametrize("name", ["minimal-skew", "spherical-simplex"])
def test_robot_the_reduced_sets_track_as_well_as_merwes(name):
    truth, us, zs = robot_data()
    ref = rmse(run_robot(robot_filter(FilterpyUKF, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0)), us, zs)[:, :2],
               truth[:, :2])
    ours = rmse(run_robot(robot_filter(UnscentedKalmanFilter, SETS[name](3, 0.1, 2.0, 0.0)), us, zs)[:, :2],
                truth[:, :2])
    assert ours < 1.1 * ref


def test_robot_the_books_residuals_are_caught_in_vectorized_mode():
    """The book's residual_x raises on a batch ('truth value of an array'): one error names it."""
    f = robot_filter(UnscentedKalmanFilter, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0), fx=robot_fx_rows,
                     hx=robot_hx_rows, vectorized=True)
    with pytest.raises(ValueError, match=r"vectorized residual_x looks written for one point: on all 7 sigma "
                                         r"points it raised ValueError.*y\[\.\.\., 2\] = wrap"):
        f.predict(u=np.array([1.1, 0.01]))


def test_robot_filterwnns_angle_residuals_work_in_both_modes_and_agree():
    _, us, zs = robot_data()
    rz = angle_residual(list(range(1, 2 * len(LANDMARKS), 2)))
    pts = lambda: SphericalSimplexSigmaPoints(3, 0.1, 2.0, 0.0)  # noqa: E731
    loop = run_robot(robot_filter(UnscentedKalmanFilter, pts(), rx=angle_residual(2), rz=rz), us, zs)
    vec = run_robot(robot_filter(UnscentedKalmanFilter, pts(), fx=robot_fx_rows, hx=robot_hx_rows,
                                 rx=angle_residual(2), rz=rz, vectorized=True), us, zs)
    np.testing.assert_allclose(vec, loop, atol=1e-8)


# --------------------------------------------------------------------------- a scalar hx
def test_a_scalar_hx_gets_a_clear_error_not_filterpys_alignment_error():
    def hx(x):
        return x[0]  # the book's one-dimensional habit: a scalar, not [x[0]]

    pts = MerweScaledSigmaPoints(2, 0.1, 2.0, 1.0)
    ref = FilterpyUKF(2, 1, 1.0, hx, lambda x, dt: x, pts)
    ref.predict()
    with pytest.raises(ValueError, match="not aligned"):
        ref.update(np.array([1.0]))
    ours = UnscentedKalmanFilter(2, 1, 1.0, hx, lambda x, dt: x, pts)
    ours.predict()
    with pytest.raises(ValueError, match=r"hx must return an array of shape \(1,\) for one point, got a "
                                         r"scalar; return a 1-D array, e.g. np.array\(\[x\[0\]\]\)"):
        ours.update(np.array([1.0]))
