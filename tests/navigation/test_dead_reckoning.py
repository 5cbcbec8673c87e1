"""Tests of the DR and GPS/DR models: Jacobians, kinematics, heading wrap, missing GPS."""

import numpy as np
import pytest
from filterpy.kalman import ExtendedKalmanFilter, MerweScaledSigmaPoints

from filterwnn.navigation.dead_reckoning import (
    DRModel,
    GPSDRModel,
    dr_fx,
    dr_HJacobian,
    dr_hx,
    dr_residual,
    dr_z_mean,
    transition_matrix,
    wrap_angle,
)
from filterwnn.navigation.scenarios import SCENARIOS, Scenario, simulate_scenario
from filterwnn.navigation.gpsdr import GPSDRFilter
from filterwnn.kalman.sigma_points import SphericalSimplexSigmaPoints
from filterwnn.kalman.unscented import UnscentedKalmanFilter

ATOL = 1e-7
# the GPS/DR tests here drive the deprecated GPSDRModel.update on purpose (it must keep working);
# tests/navigation/test_gpsdr.py covers GPSDRFilter, which replaces it
pytestmark = pytest.mark.filterwarnings("ignore:GPSDRModel.update is deprecated:DeprecationWarning")


def _fd_jacobian(f, x, eps=1e-6):
    cols = []
    for i in range(len(x)):
        d = np.zeros_like(x)
        d[i] = eps
        diff = dr_residual(f(x + d), f(x - d)) if f(x).shape[-1] in (2, 4) else f(x + d) - f(x - d)
        cols.append(diff / (2 * eps))
    return np.stack(cols, axis=-1)


def _random_states(rng, n, dim):
    X = rng.normal(0, 5, (n, dim))
    X[:, [1, 4]] = rng.normal(0, 8, (n, 2))
    if dim == 8:
        X[:, 6] = rng.uniform(0.9, 1.1, n)
        X[:, 7] = rng.uniform(-0.1, 0.1, n)
    return X


def test_dr_jacobian_matches_finite_differences(rng):
    m = DRModel(dt=0.1, zeta=1.03)
    for x in _random_states(rng, 20, 6):
        np.testing.assert_allclose(m.HJacobian(x), _fd_jacobian(m.hx, x), atol=ATOL, rtol=1e-6)


@pytest.mark.parametrize("augmented", [False, True])
@pytest.mark.parametrize("gps", [False, True])
def test_gpsdr_jacobian_matches_finite_differences(rng, augmented, gps):
    m = GPSDRModel(dt=0.1, augmented=augmented)
    for x in _random_states(rng, 20, m.dim_x):
        J = m.HJacobian(x, gps=gps)
        assert J.shape == (4 if gps else 2, m.dim_x)
        np.testing.assert_allclose(J, _fd_jacobian(lambda v: m.hx(v, gps=gps), x), atol=ATOL, rtol=1e-6)


def test_jacobian_zero_speed_guard():
    H = dr_HJacobian(np.zeros(6), 0.1, min_speed=0.1)
    assert np.all(np.isfinite(H))
    H8 = GPSDRModel(augmented=True).HJacobian(np.r_[np.zeros(6), 1.0, 0.0])
    assert np.all(np.isfinite(H8))
    assert np.all(np.isfinite(dr_hx(np.zeros(6), 0.1)))


def test_constant_acceleration_integrated_exactly():
    dt, k = 0.1, 137
    x0 = np.array([1.0, 2.0, 0.3, -4.0, -1.5, -0.2])
    x = x0.copy()
    for _ in range(k):
        x = dr_fx(x, dt)
    t = k * dt
    expected = np.array([1 + 2 * t + 0.3 * t**2 / 2, 2 + 0.3 * t, 0.3,
                         -4 - 1.5 * t - 0.2 * t**2 / 2, -1.5 - 0.2 * t, -0.2])
    np.testing.assert_allclose(x, expected, rtol=1e-12, atol=1e-9)
    F = transition_matrix(dt)
    np.testing.assert_allclose(np.linalg.matrix_power(F, k) @ x0, expected, rtol=1e-12, atol=1e-9)
    # the paper's printed T^2 is not the kinematics
    xp = x0.copy()
    for _ in range(k):
        xp = dr_fx(xp, dt, accel_term="paper")
    assert abs(xp[0] - expected[0]) > 1e-3
    np.testing.assert_allclose(transition_matrix(dt, "paper")[0, 2], dt**2)


def test_vectorized_forms_equal_rowwise(rng):
    m8 = GPSDRModel(augmented=True)
    X = _random_states(rng, 7, 8)
    np.testing.assert_allclose(m8.fx(X), np.stack([m8.fx(x) for x in X]))
    np.testing.assert_allclose(m8.hx(X), np.stack([m8.hx(x) for x in X]))
    np.testing.assert_allclose(m8.HJacobian(X), np.stack([m8.HJacobian(x) for x in X]))
    np.testing.assert_allclose(m8.fx(X), X @ m8.F.T)
    m = DRModel()
    np.testing.assert_allclose(m.hx(X[:, :6]), np.stack([m.hx(x) for x in X[:, :6]]))


def test_heading_convention_and_wrap():
    assert np.isclose(dr_hx([0, 1, 0, 0, 0, 0], 0.1)[0], np.pi / 2)      # east
    assert np.isclose(dr_hx([0, 0, 0, 0, -1, 0], 0.1)[0], -np.pi)       # south -> -pi
    assert np.isclose(dr_hx([0, -1, 0, 0, -1, 0], 0.1)[0], -3 * np.pi / 4)  # quadrant kept
    a = np.linspace(-10, 10, 101)
    w = wrap_angle(a)
    assert np.all(w >= -np.pi) and np.all(w < np.pi)
    np.testing.assert_allclose(np.sin(w), np.sin(a), atol=1e-12)
    r = dr_residual(np.array([np.pi - 0.01, 2.0, 1e4, 3.0]), np.array([-np.pi + 0.01, 1.0, 0.0, 0.0]))
    np.testing.assert_allclose(r, [-0.02, 1.0, 1e4, 3.0], atol=1e-12)
    sig = np.array([[np.pi - 0.1, 1.0], [-np.pi + 0.1, 3.0]])
    zm = dr_z_mean(sig, np.array([0.5, 0.5]))
    assert np.isclose(abs(zm[0]), np.pi) and np.isclose(zm[1], 2.0)


def _run_ekf(run, model, residual):
    kf = model.ekf(x0=run.x0)
    out = []
    for z in run.z_dr:
        kf.predict()
        kf.update(z, model.HJacobian, model.hx, residual=residual)
        out.append(kf.x.copy())
    return np.array(out)


def test_run_through_180_degrees_does_not_blow_up():
    sc = SCENARIOS["heading180"](duration=60.0)
    run = simulate_scenario(sc, rng=3)
    headings = np.degrees(np.arctan2(run.x_true[:, 1], run.x_true[:, 4]))
    assert headings.min() < -170 and headings.max() > 170  # it does cross 180
    m = DRModel()
    est = _run_ekf(run, m, dr_residual)
    err = np.hypot(*(est[:, [0, 3]] - run.x_true[:, [0, 3]]).T)
    assert np.all(np.isfinite(est)) and err[-1] < 5.0
    bad = _run_ekf(run, m, np.subtract)  # without the wrap: diverges
    assert np.hypot(*(bad[-1, [0, 3]] - run.x_true[-1, [0, 3]])) > 50.0


def _noise_free(name="straight", **kw):
    return SCENARIOS[name](sigma_heading=1e-6, sigma_odometer=1e-8, factor=1.0, **kw)


@pytest.mark.parametrize("name", ["straight", "turns", "heading180"])
def test_noise_free_run_tracked_by_kalman_filters(name):
    run = simulate_scenario(_noise_free(name, duration=60.0), rng=1)
    m = DRModel()
    ekf = _run_ekf(run, m, dr_residual)
    filters = {"EKF": ekf}
    for label, pts in [("UKF", MerweScaledSigmaPoints(6, 0.5, 2.0, 0.0)),
                       ("SUKF", SphericalSimplexSigmaPoints(6, w0=0.2))]:
        f = UnscentedKalmanFilter(6, 2, m.dt, m.hx, m.fx, pts, z_mean_fn=dr_z_mean,
                                  residual_z=dr_residual, vectorized=True)
        f.x, f.P, f.Q, f.R = run.x0.copy(), m.P0.copy(), m.Q, m.R
        means = []
        for z in run.z_dr:
            f.predict()
            f.update(z)
            means.append(f.x.copy())
        filters[label] = np.array(means)
    for label, est in filters.items():
        err = np.hypot(*(est[:, [0, 3]] - run.x_true[:, [0, 3]]).T)
        assert err.max() < 0.5, (label, err.max())


def test_simulation_is_reproducible_and_shaped():
    sc = SCENARIOS["gpsdr"]()
    a, b = simulate_scenario(sc, rng=5), simulate_scenario(sc, rng=5)
    np.testing.assert_array_equal(a.z_dr, b.z_dr)
    np.testing.assert_array_equal(a.z_gps, b.z_gps)
    assert a.z_gps.shape == (len(a.gps_steps), 2)
    t_fix = a.t[a.gps_steps]
    assert not np.any((t_fix >= 50) & (t_fix < 80)) and not np.any((t_fix >= 120) & (t_fix < 170))
    assert np.all(np.isfinite(a.z_gps)) and np.all(np.isfinite(a.z_dr))
    gl = a.gps_list()
    assert sum(g is not None for g in gl) == len(a.gps_steps)
    assert np.all(a.z_dr[:, 0] >= -np.pi) and np.all(a.z_dr[:, 0] < np.pi)
    with pytest.raises(TypeError, match="scenario"):
        simulate_scenario("straight", rng=0)
    with pytest.raises(ValueError, match="accel_term"):
        DRModel(accel_term="quadratic")


def test_noise_rises_at_switch():
    run = simulate_scenario(SCENARIOS["straight"](), rng=0)
    before = run.t < 150
    np.testing.assert_allclose(np.sqrt(run.R_true[~before, 0] / run.R_true[before, 0][0]), 20.0)


def _gpsdr_run(filt, run, gps_list):
    out = []
    for k in range(len(run.t)):
        filt.predict()
        filt.update(run.z_dr[k], gps_list[k])
        out.append(filt.x.copy())
    return np.array(out)


@pytest.mark.parametrize("kind", ["ekf", "ukf"])
def test_missing_gps_never_nan(kind):
    # starts at standstill, then drives; GPS missing for most of the time
    sc = Scenario(name="stop", duration=40.0, speed=0.0, speed_changes=((10.0, 20.0, 10.0),),
                  gps_rate=1.0, outages=((0.0, 15.0), (25.0, 40.0)))
    run = simulate_scenario(sc, rng=2)
    m = GPSDRModel(augmented=True)
    x0 = np.r_[run.x0, 1.0, 0.0]
    f = GPSDRFilter(m, "ekf" if kind == "ekf" else "sukf", x0=x0)
    est = _gpsdr_run(f, run, run.gps_list())
    assert np.all(np.isfinite(est)) and np.all(np.isfinite(f.P))
    with pytest.raises(ValueError, match="finite"):
        f.update([np.nan, 1.0], None)
    with pytest.raises(ValueError, match="finite"):
        f.update([0.1, 1.0], [np.nan, 0.0])


def test_eight_state_filter_recovers_scale_and_bias():
    sc = SCENARIOS["gpsdr"](outages=())
    run = simulate_scenario(sc, rng=11)
    m = GPSDRModel(augmented=True)
    f = GPSDRFilter(m, x0=np.r_[run.x0, 1.0, 0.0])
    est8 = _gpsdr_run(f, run, run.gps_list())
    assert abs(f.x[6] - 1.02) < 0.005
    assert abs(np.degrees(f.x[7]) - 2.0) < 0.3
    # the 6-state filter cannot: it stays metres off even with GPS
    est6 = _gpsdr_run(GPSDRFilter(GPSDRModel(), x0=run.x0), run, run.gps_list())
    e6 = np.hypot(*(est6[-500:, [0, 3]] - run.x_true[-500:, [0, 3]]).T).mean()
    e8 = np.hypot(*(est8[-500:, [0, 3]] - run.x_true[-500:, [0, 3]]).T).mean()
    assert e8 < 0.5 * e6


def test_gpsdr_helpers():
    m = GPSDRModel(sigma_gps=2.0)
    assert m.R_for(True).shape == (4, 4) and m.R_for(False).shape == (2, 2)
    assert m.R_for(False, stationary=True)[0, 0] == m.R[0, 0] * m.stationary_inflation
    z, has = m.measurement([0.1, 1.0])
    assert z.shape == (2,) and not has
    z, has = m.measurement([0.1, 1.0], [3.0, 4.0])
    assert z.shape == (4,) and has
    assert isinstance(m.ekf(), ExtendedKalmanFilter)


def test_pulling_away_from_rest_needs_the_low_speed_update():
    """From standstill the odometer's Jacobian is 0: only the velocity-vector form picks up speed."""
    sc = Scenario(name="pull-away", duration=25.0, speed=0.0, heading=120.0,
                  speed_changes=((5.0, 15.0, 10.0),))
    run = simulate_scenario(sc, rng=4)
    assert np.all(run.z_dr[run.t < 5.0, 1] == 0.0)          # odometer reads 0 at rest
    m = GPSDRModel(augmented=True)

    def go(use_flags, **kw):  # standstill below 1e-9 m/s, the velocity form below 1 m/s; or neither
        f = GPSDRFilter(m, x0=np.r_[run.x0, 1.0, 0.0], hold_without_gps=False,
                        standstill_speed=1e-9 if use_flags else 0.0, low_speed=1.0 if use_flags else 0.0, **kw)
        for k in range(len(run.t)):
            f.predict()
            f.update(run.z_dr[k], None)
        return f.x

    x = go(True)
    assert np.all(np.isfinite(x))
    assert np.hypot(x[1] - run.x_true[-1, 1], x[4] - run.x_true[-1, 4]) < 0.5
    stuck = go(False, heading_linear_limit=None)
    assert np.hypot(stuck[1], stuck[4]) < 1.0                # never picks up speed
    with pytest.warns(RuntimeWarning, match="the measured heading is"):
        x = go(False)  # the far-heading rule alone: a standing filter's heading is far from any, velocity form
    assert np.hypot(x[1] - run.x_true[-1, 1], x[4] - run.x_true[-1, 4]) < 0.5


def test_velocity_measurement_is_polar_to_cartesian():
    m = GPSDRModel(augmented=True, dt=0.1)
    v_true = 5.0 * np.array([np.sin(np.deg2rad(45)), np.cos(np.deg2rad(45))])
    x = np.array([0, v_true[0], 0, 0, v_true[1], 0, 1.02, np.deg2rad(2.0)])
    w, Rw = m.velocity_measurement([np.deg2rad(47.0), 0.1 * 1.02 * 5.0])
    np.testing.assert_allclose(m.hx(x, gps=False, velocity=True), w, atol=1e-12)
    np.linalg.cholesky(Rw)
    for xx in _random_states(np.random.default_rng(0), 5, 8):
        f = lambda v: m.hx(v, gps=True, velocity=True)  # noqa: E731
        cols = [(f(xx + d) - f(xx - d)) / 2e-6 for d in 1e-6 * np.eye(8)]
        np.testing.assert_allclose(m.HJacobian(xx, gps=True, velocity=True), np.stack(cols, -1), atol=1e-6)
