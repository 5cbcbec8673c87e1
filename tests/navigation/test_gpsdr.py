"""Tests of GPSDRFilter: starts and stops handled by default, per-fix GPS sigma, the three kinds."""

import copy
import dataclasses
import os
import re
import sys
import typing
import warnings

import numpy as np
import pytest
from filterpy.kalman import ExtendedKalmanFilter

from filterwnn.navigation.dead_reckoning import GPSDRModel, dr_residual
from filterwnn.navigation.gpsdr import KINDS, LOW_SPEED, MIN_FIX_INTERVAL, STANDSTILL_SPEED, GPSDRFilter
from filterwnn.navigation.scenarios import SCENARIOS, Scenario, simulate_scenario

# starts from rest, turns, stops at a light for 10 s, pulls away again, then a 30 s tunnel;
# 2 % odometer scale and a 2-degree heading bias, 1 Hz GPS of 3 m
FROM_REST = Scenario(name="from rest", duration=120.0, speed=0.0, heading=60.0,
                     speed_changes=((10.0, 20.0, 12.0), (60.0, 66.0, -12.0), (76.0, 84.0, 10.0)),
                     turns=((30.0, 40.0, 90.0),), gps_rate=1.0, sigma_gps=3.0, odometer_scale=1.02,
                     heading_bias=2.0, outages=((90.0, 120.0),))


def _end_error(run, est):
    return float(np.hypot(*(est[-1, [0, 3]] - run.x_true[-1, [0, 3]])))


@pytest.fixture(scope="module")
def rest_run():
    return simulate_scenario(FROM_REST, rng=0)


@pytest.mark.parametrize("kind", KINDS)
def test_drive_from_rest_with_defaults_ends_close(rest_run, kind):
    """The issue: with the old defaults a drive from rest ends tens to hundreds of metres off."""
    run = rest_run
    m = GPSDRModel(augmented=True)
    f = GPSDRFilter(m, kind, x0=np.r_[run.x0, 1.0, 0.0])
    est = f.batch_filter(run.z_dr, run.gps_list())
    assert np.all(np.isfinite(est)) and np.all(np.isfinite(f.P))
    assert _end_error(run, est) < 5.0
    assert abs(est[-1, 6] - 1.02) < 0.01 and abs(np.degrees(est[-1, 7]) - 2.0) < 0.5


def test_switching_the_logic_off_fails_from_rest(rest_run):
    """The same filter without the standstill/low-speed logic and the far-heading rule: its heading bias runs
    past the specification (it used to end > 50 m off; the bound and the gate now hold it, with a warning). The
    far-heading rule alone takes a standing car's samples (0 m/s, its heading far from a standing filter's) as
    velocity vectors, zero: near the filter with the logic."""
    run = rest_run
    m = GPSDRModel(augmented=True)
    x0 = np.r_[run.x0, 1.0, 0.0]
    off = GPSDRFilter(m, "ekf", x0=x0, standstill_speed=0.0, low_speed=0.0, heading_linear_limit=None)
    with pytest.warns(RuntimeWarning, match="heading bias state ran past 3 sigma of its specification at step"):
        est = off.batch_filter(run.z_dr, run.gps_list())
    on = GPSDRFilter(m, "ekf", x0=x0).batch_filter(run.z_dr, run.gps_list())
    assert _end_error(run, est) > 3 * _end_error(run, on)
    with pytest.warns(RuntimeWarning, match="at step 0: the measured heading is"):
        rule = GPSDRFilter(m, "ekf", x0=x0, standstill_speed=0.0, low_speed=0.0).batch_filter(run.z_dr, run.gps_list())
    assert _end_error(run, rule) < 3 * _end_error(run, on) < _end_error(run, est)


def test_motion_thresholds_are_speeds_not_exact_zero():
    m = GPSDRModel(dt=0.1)
    f = GPSDRFilter(m)
    assert f.standstill_speed == STANDSTILL_SPEED and f.low_speed == LOW_SPEED
    creep = 0.03 * 0.44704  # 0.03 mph, what a standing car's CAN speed reads
    assert f.classify([0.3, creep * 0.1]) == "still"
    assert f.classify([0.3, 0.0]) == "still"
    assert f.classify([0.3, 1.0 * 0.1]) == "slow"
    assert f.classify([0.3, 10.0 * 0.1]) == "moving"
    f.update([0.3, creep * 0.1])
    assert f.motion == "still"
    g = GPSDRFilter(m, standstill_speed=0.0, low_speed=0.0)
    assert g.classify([0.3, 0.0]) == "moving"


def test_creeping_can_speed_holds_the_car():
    """A standing car whose odometer creeps at 0.01-0.03 mph stays put (zero-velocity updates)."""
    m = GPSDRModel(dt=0.1, augmented=True)
    f = GPSDRFilter(m, x0=np.r_[np.zeros(6), 1.0, 0.0])
    rng = np.random.default_rng(1)
    for _ in range(600):
        f.predict()
        f.update([rng.uniform(-np.pi, np.pi), rng.uniform(0.0, 0.0013)])
    assert np.hypot(f.x[0], f.x[3]) < 0.05 and np.hypot(f.x[1], f.x[4]) < 0.01


def test_per_fix_gps_sigma_is_the_noise():
    m = GPSDRModel(dt=0.1, sigma_gps=3.0)
    z, R, kw = m.measurement_for([0.5, 1.0], [1.0, 2.0], gps_sigma=7.0)
    assert kw["gps"] and np.allclose(R[2:, 2:], 49.0 * np.eye(2)) and R[0, 0] == m.R[0, 0]
    _, R0, _ = m.measurement_for([0.5, 1.0], [1.0, 2.0])
    assert np.allclose(R0[2:, 2:], 9.0 * np.eye(2))
    # a fix said to be poor moves the estimate less
    moves = []
    for sd in (1.0, 30.0):
        f = GPSDRFilter(m, x0=np.array([0.0, 10.0, 0.0, 0.0, 10.0, 0.0]))
        f.P = np.diag([100.0, 0.25, 0.01, 100.0, 0.25, 0.01])
        f.predict()
        f.update([np.pi / 4, np.sqrt(2.0)], [20.0, 20.0], gps_sigma=sd)
        moves.append(np.hypot(f.x[0] - 1.0, f.x[3] - 1.0))
    assert moves[0] > 5 * moves[1]
    with pytest.raises(ValueError, match="gps_sigma"):
        m.measurement_for([0.5, 1.0], [1.0, 2.0], gps_sigma=-1.0)


def test_study_numbers_are_the_old_update_path():
    """With the full update, GPSDRFilter equals a filterpy EKF updated by hand with the study's old flags."""
    run = simulate_scenario(SCENARIOS["gpsdr"](duration=30.0), rng=3)
    m = GPSDRModel(augmented=True)
    x0 = np.r_[run.x0, 1.0, 0.0]
    new = GPSDRFilter(m, "ekf", x0=x0, hold_without_gps=False).batch_filter(run.z_dr, run.gps_list())
    kf = m.ekf(x0=x0)
    old = []
    for k, g in enumerate(run.gps_list()):  # the update the study used to write by hand
        kf.predict()
        slow = run.z_dr[k, 1] < LOW_SPEED * m.dt
        z, R, kw = m.measurement_for(run.z_dr[k], g, low_speed=bool(slow), zupt=bool(run.z_dr[k, 1] <= 0))
        args = (kw["gps"], kw["velocity"])
        kf.update(z, m.HJacobian, m.hx, R=R, args=args, hx_args=args,
                  residual=np.subtract if kw["velocity"] else dr_residual)
        old.append(kf.x.copy())
    np.testing.assert_allclose(new, np.array(old), rtol=1e-12, atol=1e-12)


def test_filter_api_and_bad_arguments():
    m = GPSDRModel(augmented=True)
    f = GPSDRFilter(m, "sukf")
    assert f.x.shape == (8,) and f.P.shape == (8, 8)
    assert isinstance(GPSDRFilter(m).kf, ExtendedKalmanFilter)
    with pytest.raises(ValueError, match="kind"):
        GPSDRFilter(m, "pf")
    with pytest.raises(TypeError, match="model must be a GPSDRModel"):
        GPSDRFilter("model")
    with pytest.raises(ValueError, match="standstill_speed"):
        GPSDRFilter(m, standstill_speed=-1.0)
    with pytest.raises(ValueError, match="finite"):
        f.update([np.nan, 1.0])
    with pytest.raises(ValueError, match="z_dr must have shape"):
        f.batch_filter(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="one entry per DR sample"):
        f.batch_filter(np.zeros((3, 2)), [None])
    with pytest.raises(ValueError, match="x0 must have length 8"):
        GPSDRFilter(m, x0=np.zeros(6))
    with pytest.raises(ValueError, match="calibration_error_z"):
        GPSDRFilter(m, calibration_error_z=0.0)
    assert GPSDRFilter(m, calibration_error_z=None).calibration_error_z is None
    assert GPSDRFilter(m).calibration_error_z == pytest.approx(3.2905, abs=1e-4) and f.n_calibration_error == 0
    with pytest.raises(ValueError, match="heading_jump_z"):
        GPSDRFilter(m, heading_jump_z=-1.0)
    assert GPSDRFilter(m, heading_jump_z=None).heading_jump_z is None
    assert GPSDRFilter(m).heading_jump_z == 6.1 and f.n_heading_jumps == 0 and f.heading_jumps == []


def _turning_drive():
    sc = Scenario(name="turning", duration=300.0, speed=15.0, heading=30.0, sigma_heading=0.5, gps_rate=1.0,
                  sigma_gps=5.0, turns=((60.0, 80.0, 30.0), (150.0, 170.0, -40.0)))
    return simulate_scenario(sc, rng=3)


@pytest.mark.parametrize("kind", KINDS)
def test_a_heading_that_steps_while_the_car_moves_is_found_and_its_bias_learnt_again(kind):
    """A plain drive at 15 m/s with two turns, 1 Hz fixes of 5 m, the phone grade: the measured heading steps
    by 6 deg at 200 s. The heading-jump detector finds it within 20 s (its onset within 10 s of the step),
    warns once, and the heading bias is learnt again: 6 +- 1 deg at the end. Without it the bias has
    learnt less than a third of the step by then, and the fixes were lost for a while (a re-acquisition)."""
    run = _turning_drive()
    z = run.z_dr.copy()
    z[2000:, 0] += np.deg2rad(6.0)
    m = GPSDRModel.from_grade("phone", 0.1)
    ends = {}
    for gate in (6.1, None):
        f = GPSDRFilter(m, kind, x0=np.r_[run.x0, 1.0, 0.0, 0.0], heading_jump_z=gate)
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            est = f.batch_filter(z, run.gps_list())
        said = [str(w.message) for w in record if "the heading stepped by" in str(w.message)]
        ends[gate] = np.degrees(est[-1, 7]), f, said
    bias, f, said = ends[6.1]
    assert f.n_heading_jumps == 1 and len(said) == 1 and "while the car moved" in said[0]
    assert "odometer-latency" not in said[0]  # the speed's remedy only after the speed was found late
    found, onset, size, z_score = f.heading_jumps[0]
    assert 2000 < found < 2200 and abs(onset - 2000) <= 100 and np.degrees(size) > 3.0 and z_score > 6.1
    assert abs(bias - 6.0) < 1.0
    bias, f, said = ends[None]
    assert f.n_heading_jumps == 0 and not said and bias < 2.0 and f.n_reacquired >= 1


def test_a_step_taken_leaves_every_hypothesis_as_the_joint_system_would():
    """When the detector takes a step, the monitor's hypotheses keep what the fixes told of them beyond it (their
    system conditioned on the step, a Schur complement), the speed's latency among them: their estimates and
    sandwich variances afterwards equal those of the joint system with the step as one more unknown. (Until
    stop 48 the speed's latency kept the step's share: its onset cross terms were not tracked.)"""
    run = _turning_drive()
    z = run.z_dr.copy()
    z[2000:, 0] += np.deg2rad(6.0)
    f = GPSDRFilter(GPSDRModel.from_grade("phone", 0.1), x0=np.r_[run.x0, 1.0, 0.0, 0.0])
    take, seen = f._take_jump, []

    def block(A, cross, own, b, o, d):
        return np.block([[A, cross[:, None], b[:, None]], [cross[None, :], np.array([[own, o]])],
                         [b[None, :], np.array([[o, d]])]])

    def taken(j, theta, var, z_score):
        b, o, d, c = f._jB[:, j], f._jo[j], f._jd[j], f._jc[j]
        joint = GPSDRFilter._solve(block(f._I, f._Ixo, f._Ioo, b, o, d), block(f._J, f._Jxo, f._Joo, c * b, c * o, c * d),
                                   np.r_[f._u, f._uo, f._ju[j]])
        take(j, theta, var, z_score)
        I = np.block([[f._I, f._Ixo[:, None]], [f._Ixo[None, :], np.array([[f._Ioo]])]])
        J = np.block([[f._J, f._Jxo[:, None]], [f._Jxo[None, :], np.array([[f._Joo]])]])
        seen.append((joint, GPSDRFilter._solve(I, J, np.r_[f._u, f._uo])))

    f._take_jump = taken
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        f.batch_filter(z, run.gps_list())
    assert len(seen) == 1
    (theta, var), (theta_c, var_c) = seen[0]
    assert np.allclose(theta[:-1], theta_c, rtol=1e-6, atol=1e-12) and np.allclose(var[:-1], var_c, rtol=1e-6)
    assert abs(theta_c[-1]) > 0.1  # the speed's latency's estimate is one the step's share would move


@pytest.mark.parametrize("whiteness_window", [60.0, 0.0])
def test_an_outage_starts_the_heading_jump_onsets_again(whiteness_window):
    """The fixes after an outage carry the dead reckoning's error over it, which the filter's covariance
    accounts for: an onset before or in it would read that as a step, so the first fix after it drops them.
    With the fixes' whiteness off too (the gap is found where the fixes reach the filter)."""
    run = _turning_drive()
    gps = [None if 1000 <= k < 1300 else g for k, g in enumerate(run.gps_list())]
    f = GPSDRFilter(GPSDRModel.from_grade("phone", 0.1), x0=np.r_[run.x0, 1.0, 0.0, 0.0],
                    whiteness_window=whiteness_window)
    for k in range(1320):
        f.predict()
        f.update(run.z_dr[k], gps[k])
        if k == 999:
            assert len(f._jt) == 12 and f._jt[-1] - f._jt[0] == 550  # one every 5 s over the last minute
    assert f._jt and min(f._jt) >= 1300

@pytest.mark.parametrize("kind", KINDS)
def test_without_gps_only_velocity_and_acceleration_move(rest_run, kind):
    """Position and calibration are consider states between fixes; a fix updates everything. The
    one exception is the zero angular rate update when a stop ends (the car stands for its first
    10 s): it measures the rate bias, which moves with what correlates with it."""
    run = rest_run
    m = GPSDRModel(augmented=True, rate_bias=True)
    f = GPSDRFilter(m, kind, x0=np.r_[run.x0, m.x0[6:]])
    stop_ends = []
    for k in range(150):
        f.predict()
        before = f.x.copy()
        n = len(f.zero_rate_steps)
        f.update(run.z_dr[k], None)
        if len(f.zero_rate_steps) > n:
            stop_ends.append(k)
            assert f.x[8] != before[8]
        else:
            np.testing.assert_array_equal(f.x[f.held_states], before[f.held_states])
    assert len(stop_ends) == 1 and 95 <= stop_ends[0] <= 105
    assert np.all(np.linalg.eigvalsh(f.P) > 0)
    before = f.x.copy()
    f.predict()
    f.update(run.z_dr[150], run.x_true[150, [0, 3]] + 2.0)
    assert np.all(f.x[[0, 3]] != before[[0, 3]])


def test_an_outage_from_the_first_second():
    """The sample drive with 30 s without GPS from the start (a garage): the full update trades speed
    against scale and track against heading bias and ends far off; the held update stays near the raw DR."""
    from filterwnn.navigation.drives import read_drive_csv, sample_drive_path

    run = read_drive_csv(sample_drive_path())
    m = GPSDRModel(augmented=True, q=2.0, sigma_gps=1.0, q_scale=1e-6, q_bias=1e-6)
    cut = run.gps_list()
    cut[:300] = [None] * 300
    ends = {}
    for hold in (True, False):
        est = GPSDRFilter(m, x0=np.r_[run.x0, 1.0, 0.0], hold_without_gps=hold).batch_filter(run.z_dr[:300], cut[:300])
        ends[hold] = float(np.hypot(*(est[-1, [0, 3]] - run.x_true[299, [0, 3]])))
    z = run.z_dr[:300]
    p = run.x0[[0, 3]] + np.sum(z[:, 1:] * np.stack([np.sin(z[:, 0]), np.cos(z[:, 0])], 1), axis=0)
    raw = float(np.hypot(*(p - run.x_true[299, [0, 3]])))
    assert ends[True] < raw + 3.0 and ends[False] > 5 * ends[True], (ends, raw)


def test_grades_map_specifications_to_settings():
    from filterwnn.navigation.dead_reckoning import SENSOR_GRADES

    phone = GPSDRModel.from_grade("phone", dt=0.1)
    spec = SENSOR_GRADES["phone"]
    assert phone.dim_x == 9 and phone.rate_bias
    assert phone.sigma_gps == spec["gps_sigma_m"]
    assert np.isclose(phone.sigma_heading, np.deg2rad(spec["heading_noise_deg"]))
    assert np.isclose(phone.q_bias, (np.deg2rad(spec["gyro_arw_deg_rt_h"]) / 60) ** 2)
    assert np.isclose(np.sqrt(phone.P0[8, 8]), np.deg2rad(spec["gyro_bias_deg_s"]))
    survey = GPSDRModel.from_grade("survey")
    assert survey.dim_x == 8 and survey.sigma_gps == 1.5
    own = GPSDRModel.from_grade({"gps_sigma_m": 2.5, "rate_bias": False}, augmented=True)
    assert own.dim_x == 8 and own.sigma_gps == 2.5
    assert GPSDRModel.from_grade("phone", q=0.5).q == 0.5          # overrides win
    assert GPSDRModel.from_grade("phone", augmented=False, rate_bias=False).dim_x == 6
    with pytest.raises(ValueError, match="grade must be one of"):
        GPSDRModel.from_grade("military")
    with pytest.raises(ValueError, match="unknown keys"):
        GPSDRModel.from_grade({"gps_sigma": 2.0})
    with pytest.raises(ValueError, match="rate_bias=True needs augmented=True"):
        GPSDRModel(rate_bias=True)


def test_rate_bias_state_jacobians_and_transition():
    m = GPSDRModel(augmented=True, rate_bias=True, dt=0.1)
    x = np.array([1.0, 5.0, 0.1, 2.0, 7.0, -0.1, 1.02, 0.03, 0.001])
    np.testing.assert_allclose(m.fx(x), m.F @ x, atol=1e-12)
    assert m.fx(x)[7] == pytest.approx(0.03 + 0.1 * 0.001)
    for gps in (False, True):
        for velocity in (False, True):
            f = lambda v: m.hx(v, gps=gps, velocity=velocity)  # noqa: E731
            cols = [(f(x + d) - f(x - d)) / 2e-6 for d in 1e-6 * np.eye(9)]
            np.testing.assert_allclose(m.HJacobian(x, gps=gps, velocity=velocity), np.stack(cols, -1), atol=1e-6)


def test_rate_bias_state_follows_a_drifting_gyro():
    """A MEMS gyro's 0.05 deg/s residual bias: the 9-state filter estimates it and ends a later outage closer."""
    sc = SCENARIOS["gpsdr"](heading_drift=0.05, heading_bias=0.0, outages=((150.0, 180.0),),
                            duration=180.0, sigma_gps=5.0)
    errs = {False: [], True: []}
    for seed in (0, 1):
        run = simulate_scenario(sc, rng=seed)
        for rate in (False, True):
            m = GPSDRModel.from_grade("phone", rate_bias=rate)
            est = GPSDRFilter(m, "ekf", x0=np.r_[run.x0, m.x0[6:]]).batch_filter(run.z_dr, run.gps_list())
            errs[rate].append(_end_error(run, est))
            if rate:
                assert abs(np.degrees(est[-1, 8]) - 0.05) < 0.01
    assert np.mean(errs[True]) < 0.5 * np.mean(errs[False])


@pytest.mark.parametrize("true_sigma", [1.0, 8.0])
def test_gps_noise_estimated_from_innovations(true_sigma):
    """Fixes without an accuracy of their own: the filter learns their noise (the model says 3 m)."""
    sc = SCENARIOS["gpsdr"](sigma_gps=true_sigma, outages=(), duration=150.0)
    run = simulate_scenario(sc, rng=0)
    f = GPSDRFilter(GPSDRModel(augmented=True, sigma_gps=3.0), x0=np.r_[run.x0, 1.0, 0.0], gps_window=60)
    f.batch_filter(run.z_dr, run.gps_list())
    assert abs(f.gps_sigma_est / true_sigma - 1.0) < 0.25
    assert GPSDRFilter(GPSDRModel()).gps_sigma_est is None
    with pytest.raises(ValueError, match="gps_window must be >= 0"):
        GPSDRFilter(GPSDRModel(), gps_window=-1)


# ----------------------------------------------------------------------------- integrity (issue 23)


def _steady(kind="ekf", **kw):
    """A filter on a straight 14 m/s road, told the truth at the start."""
    run = simulate_scenario(SCENARIOS["gpsdr"](duration=60.0, outages=()), rng=1)
    f = GPSDRFilter(GPSDRModel(augmented=True), kind, x0=np.r_[run.x0, 1.0, 0.0], **kw)
    return run, f


def test_gate_defaults_are_chi_square_points():
    from scipy.stats import chi2

    from filterwnn.navigation.gpsdr import GATE, REJECT_GATE

    assert GATE == pytest.approx(chi2.ppf(0.999, 2)) and REJECT_GATE == pytest.approx(chi2.isf(1e-9, 2))
    f = GPSDRFilter(GPSDRModel())
    assert (f.gate, f.reject_gate) == (GATE, REJECT_GATE)
    assert GPSDRFilter(GPSDRModel(), gate=np.inf).reject_gate == np.inf
    with pytest.raises(ValueError, match="gate must be > 0"):
        GPSDRFilter(GPSDRModel(), gate=0.0)
    with pytest.raises(ValueError, match="reject_gate must be >= gate"):
        GPSDRFilter(GPSDRModel(), reject_gate=1.0)


@pytest.mark.parametrize("kind", KINDS)
def test_a_jumped_fix_is_rejected_and_counted(kind):
    run, f = _steady(kind)
    gps = run.gps_list()
    k_jump = int(run.gps_steps[20])
    for k in range(len(run.t)):
        f.predict()
        z = gps[k] if k != k_jump else gps[k] + np.array([60.0, 0.0])
        f.update(run.z_dr[k], z)
        if k == k_jump:
            assert f.fix_status == "rejected" and f.nis > f.reject_gate
            err = abs(f.x[0] - run.x_true[k, 0])
            assert err < 3.0  # the 60 m jump did not move the estimate
    assert f.n_rejected == 1 and f.rejected_steps == [k_jump] and f.n_fixes == len(run.gps_steps)
    assert 1.0 < f.nis_mean < 3.5  # consistent on the good fixes


def test_a_moderate_outlier_is_down_weighted():
    run, f = _steady()
    gps = run.gps_list()
    k_out = int(run.gps_steps[20])
    for k in range(k_out + 1):
        f.predict()
        if k == k_out:  # NIS between the gates: a fix about 5 sigma off
            sd = np.sqrt(f.P[0, 0] + f.model.sigma_gps**2)
            gps[k] = f.x[[0, 3]] + np.array([5.0 * sd, 0.0])
        f.update(run.z_dr[k], gps[k])
    assert f.fix_status == "down-weighted" and f.gate < f.nis <= f.reject_gate and f.n_downweighted == 1


def test_a_run_of_rejections_reacquires():
    """The filter starts 200 m off with a tight P: it rejects the first fixes, then re-acquires."""
    run, _ = _steady()
    x0 = np.r_[run.x0, 1.0, 0.0]
    x0[0] += 200.0
    f = GPSDRFilter(GPSDRModel(augmented=True), x0=x0)
    with pytest.warns(RuntimeWarning, match=r"re-acquires at step \d+: 5 fixes in a row failed its gate, and "
                                            r"this one is 1\d\d m from its prediction") as rec:
        est = f.batch_filter(run.z_dr, run.gps_list())
    assert f.n_rejected == f.reacquire_after and f.n_reacquired >= 1
    assert abs(est[-1, 0] - run.x_true[-1, 0]) < 5.0
    assert sum("re-acquires" in str(w.message) for w in rec) == 1  # later ones are counted


def test_a_receiver_re_sending_its_last_fix_is_not_followed():
    """10 s of the same fix, to the bit, at 12 m/s: taken for fixes, they failed the gate, re-acquired
    the filter onto the position left behind, and the errors reached 110 m (11 m without them)."""
    run = _at_rate(1.0, 0)
    fixes, sigmas = list(run.gps_list()), list(run.gps_sigma_list())
    k0 = run.gps_steps[100]
    for k in run.gps_steps[101:111]:
        fixes[k], sigmas[k] = fixes[k0], sigmas[k0]
    f, g = _phone_filter(run), _phone_filter(run)
    with pytest.warns(RuntimeWarning, match=r"the fix at step \d+ repeats the last one to the bit after the car "
                                            r"drove 1\d.\d m: a receiver re-sending") as rec:
        a = f.batch_filter(run.z_dr, fixes, sigmas)
    assert sum("re-sending" in str(w.message) for w in rec) == 1
    assert f.n_stale == 10 and f.n_rejected == f.n_reacquired == 0 and f.n_fixes == len(run.gps_steps) - 10
    # the same as a filter without those fixes
    gone = [None if k in run.gps_steps[101:111] else z for k, z in enumerate(fixes)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        np.testing.assert_array_equal(a, g.batch_filter(run.z_dr, gone, sigmas))
    # a standing car's receiver may repeat its fix: used, as the car drove less than its sigma
    h = _phone_filter(run)
    h.update([0.3, 0.0], [1.0, 2.0], 5.0)
    h.update([0.3, 0.0], [1.0, 2.0], 5.0)
    assert h.n_stale == 0 and h.fix_status != "stale"


def test_calibration_holds_while_standing_and_is_bounded_by_its_specification():
    run, f = _steady()
    f.update([0.3, 0.0], f.x[[0, 3]] + [1.0, -1.0])  # standing: a fix says nothing about scale or bias
    assert f.motion == "still" and f.fix_status == "accepted"
    np.testing.assert_array_equal(f.x[6:], [1.0, 0.0])
    g = GPSDRFilter(GPSDRModel(augmented=True, sd_bias=np.deg2rad(1.0)))
    x = g.x.copy()
    x[7] = np.deg2rad(10.0)
    g.kf.x = x
    with pytest.warns(RuntimeWarning, match=r"heading bias state ran past 3 sigma of its specification at step 0"):
        g.predict().update([0.0, 1.0])
    assert abs(g.x[7]) <= 3 * np.sqrt(g._cal_P[1, 1]) + 1e-12


@pytest.mark.parametrize("kind", KINDS)
def test_the_heading_bias_is_an_angle_kept_within_half_a_turn(kind):
    """A heading bias one turn and 1 degree from its prior mean is 1 degree from it: within the bound, not
    held at it with a warning, and the state is kept in [-pi, pi); 10 degrees one turn away is held at the
    bound."""
    m = GPSDRModel(augmented=True, sd_bias=np.deg2rad(1.0))
    g = GPSDRFilter(m, kind, heading_linear_limit=None)  # (a heading of 0 is 46 degrees from the prior's)
    x = g.x.copy()
    x[7] = np.deg2rad(361.0)
    g.kf.x = x
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        g.predict().update([0.0, 1.0])
    assert -np.pi <= g.x[7] < np.pi and abs(g.x[7] - np.deg2rad(1.0)) < 1e-3
    assert g._cal_warned == set()
    x = g.x.copy()
    x[7] = np.deg2rad(-350.0)
    g.kf.x = x
    with pytest.warns(RuntimeWarning, match=r"heading bias state ran past 3 sigma .* \(\+0.175 from its prior mean"):
        g.predict().update([0.0, 1.0])
    assert g.x[7] == pytest.approx(3 * np.sqrt(g._cal_P[1, 1]), abs=1e-12)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("dt", [0.05, 1.0])
def test_P_stays_positive_definite_at_any_rate(kind, dt):
    sc = FROM_REST.with_(dt=dt, duration=120.0)
    run = simulate_scenario(sc, rng=2)
    for grade in ("survey", "phone"):
        m = GPSDRModel.from_grade(grade, dt)
        f = GPSDRFilter(m, kind, x0=np.r_[run.x0, m.x0[6:]])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            est = f.batch_filter(run.z_dr, run.gps_list())
        assert np.all(np.isfinite(est))
        np.linalg.cholesky(f.P)
        np.testing.assert_array_equal(f.P, f.P.T)
        assert _end_error(run, est) < 10.0, (grade, kind, dt)


def test_the_consistency_monitor_warns_with_the_step_and_a_remedy():
    """The remedy names the fixes' accuracy and the grade; with a rate-bias state, the gyro's bias instability
    too (a gyro whose bias moved: ``test_held_out_drives.py``), as the model has it."""
    run, f = _steady(nis_window=10)
    fixes = [None if g is None else g + 3.0 * np.random.default_rng(k).standard_normal(2) * 2.0
             for k, g in enumerate(run.gps_list())]  # noise 3x what the model says
    with pytest.warns(RuntimeWarning, match=r"inconsistent at step \d+: the mean NIS of the last 10 fixes .* "
                                            r"pass the receiver's accuracy as gps_sigma") as seen:
        f.batch_filter(run.z_dr, fixes)
    assert f.nis_warnings and not any("bias instability" in str(w.message) for w in seen)
    m = GPSDRModel.from_grade({"gyro_bias_instability_deg_h": 30.0}, run.scenario.dt)
    g = GPSDRFilter(m, x0=np.r_[run.x0, m.x0[6:]], nis_window=10)
    with pytest.warns(RuntimeWarning, match=r"inconsistent at step \d+: .* gyro_bias_instability_deg_h in the "
                                            r"grade \(--gyro-bias-instability DEG_H; the model's 30\)"):
        g.batch_filter(run.z_dr, fixes)


@pytest.mark.parametrize("scale, bias", [(1.05, 0.0), (1.03, 2.0)])
def test_a_six_state_filters_inconsistency_names_the_calibration_it_lacks(scale, bias):
    """A 6-state model has no odometer scale or heading bias: a speed 5 % off (or 3 % and a 2 degree heading bias)
    makes it inconsistent, and the warning names the 8-state model before the fixes' accuracy (stop 72: it named
    only the fixes' accuracy and the grade, where the 8-state model on the same drive is consistent)."""
    sc = Scenario(name="scaled", duration=600.0, speed=15.0, heading=30.0,
                  turns=((100, 110, 90), (300, 310, -90), (450, 460, 45)), gps_rate=1.0, odometer_scale=scale,
                  heading_bias=bias, sigma_heading=0.2, sigma_odometer=0.02)
    run = simulate_scenario(sc, rng=1)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        six = GPSDRFilter(GPSDRModel(sigma_heading=0.2), kind="ekf", x0=run.x0)
        six.batch_filter(run.z_dr, run.gps_list())
    said = [str(w.message) for w in seen if "inconsistent" in str(w.message)]
    assert said and re.search(r"no odometer scale or heading bias \(6 states\).*GPSDRModel\(augmented=True\).*"
                              r"Else the fixes' reported accuracy is optimistic", said[0])
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        eight = GPSDRFilter(GPSDRModel(augmented=True, sigma_heading=0.2), kind="ekf", x0=np.r_[run.x0, 1.0, 0.0])
        eight.batch_filter(run.z_dr, run.gps_list())
    assert not [w for w in seen if "inconsistent" in str(w.message)] and eight.nis_mean < 2.5 < six.nis_mean


def test_batch_filter_folds_a_warning_that_repeats_into_one_line_with_its_steps():
    """The monitor warns each time the window re-enters inconsistency: step by step, each time; over a
    batch, one line with the first step and the steps of the others (there were 37 anonymous lines on a
    1 Hz drive with a gyro outside its grade)."""
    def bursts():
        run, f = _steady(nis_window=5)
        rng = np.random.default_rng(3)
        # 10 s of fixes 4x noisier than the model says in every 20: the window keeps re-entering
        return run, f, [None if g is None else g + (4.0 if (k // 100) % 2 else 1.0) * 2.0 * rng.standard_normal(2)
                        for k, g in enumerate(run.gps_list())]

    run, f, fixes = bursts()
    with warnings.catch_warnings(record=True) as each:
        warnings.simplefilter("always")
        for k in range(len(run.z_dr)):
            f.predict()
            f.update(run.z_dr[k], fixes[k])
    steps = f.nis_warnings
    assert len(steps) >= 2, steps
    assert sum("inconsistent" in str(w.message) for w in each) == len(steps)

    run, f, fixes = bursts()
    with warnings.catch_warnings(record=True) as folded:
        warnings.simplefilter("always")
        f.batch_filter(run.z_dr, fixes)
    assert f.nis_warnings == steps
    lines = [str(w.message) for w in folded if "inconsistent" in str(w.message)]
    assert len(lines) == 1
    assert lines[0].startswith(f"GPSDRFilter is inconsistent at step {steps[0]}:")
    rest = ", ".join(str(s) for s in steps[1:9]) + (", ..." if len(steps) > 9 else "")
    assert lines[0].endswith(f"(and {len(steps) - 1} more like it, at step{'s' if len(steps) > 2 else ''} {rest})")
    assert folded[0].filename == __file__  # it points at the caller of batch_filter


@pytest.mark.parametrize("kind", ["ekf", "ukf", "sukf"])
def test_an_overflowing_distance_or_fix_is_refused_and_changes_nothing(kind):
    """A DR distance of 1e308 used to give x = inf silently; now a ValueError, the state unchanged."""
    model = GPSDRModel.from_grade("phone", 0.1)
    f = GPSDRFilter(model, kind)
    f.predict()
    x, P = f.x.copy(), f.P.copy()
    with pytest.raises(ValueError, match="z_dr must have entries of magnitude"):
        f.update(np.array([0.1, 1e308]))
    with pytest.raises(ValueError, match="z_gps must have entries of magnitude"):
        f.update(np.array([0.1, 1.0]), np.array([1e200, 0.0]), 3.0)
    np.testing.assert_array_equal(f.x, x)
    np.testing.assert_array_equal(f.P, P)


# ----------------------------------------------------------------------------- correlated fixes (issue 23)
_STRAIGHTISH = Scenario(name="correlated fixes", duration=400.0, dt=0.5, speed=12.0, heading=30.0,
                        turns=((100.0, 110.0, 60.0), (250.0, 260.0, -90.0)), gps_rate=1.0, sigma_gps=5.0,
                        odometer_scale=1.02, heading_bias=1.0, sigma_heading=0.5)


def _with_fix_errors(run, phi, rng):
    """``run`` with its fixes replaced by truth + AR(1) errors of 5 m per axis and lag-one
    correlation ``phi`` (0: white), each reporting its true 5 m."""
    err = np.empty((len(run.z_gps), 2))
    err[0] = rng.standard_normal(2)
    for j in range(1, len(err)):
        err[j] = phi * err[j - 1] + np.sqrt(1 - phi * phi) * rng.standard_normal(2)
    z = run.x_true[run.gps_steps][:, [0, 3]] + 5.0 * err
    return run._replace(z_gps=z, gps_sigma=np.full(len(z), 5.0))


def _phone_filter(run, **kw):
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    return GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]], **kw)


def test_white_fixes_leave_the_filter_as_it_was():
    run = _with_fix_errors(simulate_scenario(_STRAIGHTISH, rng=3), 0.0, np.random.default_rng(3))
    f, g = _phone_filter(run), _phone_filter(run, whiteness_window=0)
    a = f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    b = g.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    assert f.gps_correlation < 1.5 and 1.0 <= f.gps_correlation_mean < 1.5
    # where the estimate stayed at 1 the two filters agree to the last bit
    assert np.array_equal(a[:60], b[:60])


def test_correlated_fixes_are_found_and_teach_the_heading_bias_less():
    run = _with_fix_errors(simulate_scenario(_STRAIGHTISH, rng=4), 0.97, np.random.default_rng(4))
    f, g = _phone_filter(run), _phone_filter(run, whiteness_window=0)
    a = f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    b = g.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    assert f.gps_correlation > 3.0, f.gps_correlation
    assert g.gps_correlation == 1.0
    # the drive table's figure: the mean over the fixes; not estimated with whiteness_window=0
    assert f.gps_correlation_mean > 2.0 and g.gps_correlation_mean is None
    # the heading bias and rate bias move less from the drifting errors; the scale is not held back
    assert np.std(np.diff(a[:, 7])) < np.std(np.diff(b[:, 7]))
    assert np.std(np.diff(a[:, 8])) < np.std(np.diff(b[:, 8]))
    assert abs(a[-1, 6] - 1.02) < 0.02


def _at_rate(rate, seed, phi_per_second=0.95):
    """The straightish drive at dt = 0.2 s with ``rate`` fixes a second whose errors are AR(1) with
    lag-one correlation ``phi_per_second`` over one second, whatever the rate."""
    sc = dataclasses.replace(_STRAIGHTISH, dt=0.2, gps_rate=rate)
    return _with_fix_errors(simulate_scenario(sc, rng=seed), phi_per_second ** (1.0 / rate),
                            np.random.default_rng(seed))


def _median_correlation(f, run):
    """Run ``f`` over ``run`` step by step: the median of its ``gps_correlation`` at the fixes after
    the first quarter (the end value alone swings with the last minute's errors)."""
    cs = []
    for z, g, s in zip(run.z_dr, run.gps_list(), run.gps_sigma_list()):
        f.predict()
        f.update(z, g, s)
        if g is not None:
            cs.append(f.gps_correlation)
    return float(np.median(cs[len(cs) // 4:]))


def test_the_whiteness_window_spans_seconds_at_any_fix_rate():
    one, five = _at_rate(1.0, 0), _at_rate(5.0, 0)
    f1 = _phone_filter(one)
    f5, f12 = (_phone_filter(five, min_fix_interval=0.0, whiteness_window=w) for w in (60.0, 12.0))
    assert f1.whiteness_window == f5.whiteness_window == 60.0 and f1.whiteness_fixes is None
    c1, c5, c12 = _median_correlation(f1, one), _median_correlation(f5, five), _median_correlation(f12, five)
    # 60 s of fixes: 60 at 1 Hz, 300 at 5 Hz (60 fixes at 5 Hz would span 12 s, under the errors' 20 s)
    assert (f1.whiteness_fixes, f5.whiteness_fixes, f12.whiteness_fixes) == (60, 300, 60)
    assert (f1._white.maxlen, f5._white.maxlen) == (60, 300)
    # the same errors in seconds give about the same correlation time in seconds (seeds 0-5: 0.67-1.17)
    assert 0.5 < (c5 / 5.0) / c1 < 2.0, (c1, c5)
    # a window of 60 fixes at 5 Hz sees too few lags and counts the fixes as worth more (0.28-0.41)
    assert c12 < 0.6 * c5, (c12, c5)


class _Fixes(typing.NamedTuple):
    """A drive's DR samples with other fixes: what ``_median_correlation`` reads."""
    z_dr: np.ndarray
    fixes: list
    sigmas: list

    def gps_list(self):
        return self.fixes

    def gps_sigma_list(self):
        return self.sigmas


def test_the_whiteness_window_forgets_a_doubled_fix_and_follows_a_change_of_rate():
    one = _at_rate(1.0, 0)
    c1 = _median_correlation(_phone_filter(one), one)
    # one fix sent twice, the second 0.2 s later: the shortest gap ever seen was 0.2 s, every later 1 s
    # gap looked like a break, and the correlation read 1 for the rest of the drive
    fixes, sigmas = list(one.gps_list()), list(one.gps_sigma_list())
    k = one.gps_steps[20]
    fixes[k + 1], sigmas[k + 1] = fixes[k], sigmas[k]
    f = _phone_filter(one)
    c = _median_correlation(f, _Fixes(one.z_dr, fixes, sigmas))
    assert f.whiteness_fixes == 60 and 0.8 * c1 < c < 1.25 * c1, (c, c1)  # 15.3 against 15.0
    # a receiver that goes from 5 Hz to 1 Hz halfway: the window goes from 300 fixes to 60, and the
    # correlation is measured on the 1 Hz fixes (it read 1 there, each fix after a break)
    five = _at_rate(5.0, 0)
    fixes, sigmas = list(five.gps_list()), list(five.gps_sigma_list())
    half = len(fixes) // 2
    nth = np.cumsum([g is not None for g in fixes]) - 1
    for i in range(half, len(fixes)):
        if fixes[i] is not None and nth[i] % 5:
            fixes[i] = sigmas[i] = None
    f = _phone_filter(five)
    seen = []
    for z, g, s in zip(five.z_dr, fixes, sigmas):
        f.predict()
        f.update(z, g, s)
        if g is not None:
            seen.append((f.step, f.whiteness_fixes, f.gps_correlation))
    assert [w for step, w, _ in seen if step < half][-1] == 300 and f.whiteness_fixes == 60
    late = np.median([c for step, _, c in seen if step > 1.5 * half])
    assert 0.5 * c1 < late < 2.0 * c1, (late, c1)  # 18.1 against 15.0


def test_fixes_faster_than_one_a_second_are_thinned_with_a_warning():
    five = _at_rate(5.0, 0)
    assert _phone_filter(five).min_fix_interval == 0.0  # off by default
    f = _phone_filter(five, min_fix_interval=MIN_FIX_INTERVAL)
    assert f.min_fix_interval == 1.0
    with pytest.warns(RuntimeWarning, match=r"thins its fixes from step \d+: they come every 0.2 s, and it uses "
                                            r"one every 1 s \(min_fix_interval\)") as rec:
        a = f.batch_filter(five.z_dr, five.gps_list(), five.gps_sigma_list())
    assert sum("thins its fixes" in str(w.message) for w in rec) == 1
    # one fix in five is used (the first, then every fifth), and only those are tested
    n = len(five.gps_steps)
    assert f.n_thinned == n - (n + 4) // 5 and f.n_fixes == (n + 4) // 5
    # the same as a filter given only those fixes
    keep = [g if g is not None and j % 5 == 0 else None
            for j, g in zip(np.cumsum([g is not None for g in five.gps_list()]) - 1, five.gps_list())]
    sig = [s if k is not None else None for s, k in zip(five.gps_sigma_list(), keep)]
    g = _phone_filter(five, min_fix_interval=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        b = g.batch_filter(five.z_dr, keep, sig)
    np.testing.assert_array_equal(a, b)
    assert g.n_thinned == 0 and g.n_fixes == f.n_fixes
    # 1 Hz fixes, with a jitter of up to 0.4 s, are all used
    one = _at_rate(1.0, 0)
    jitter = list(one.gps_list())
    for k in one.gps_steps[3::7]:
        jitter[k - 2], jitter[k] = jitter[k], None  # 0.4 s early
    h = _phone_filter(one, min_fix_interval=MIN_FIX_INTERVAL)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)  # not even the thinning warning
        warnings.filterwarnings("ignore", "GPSDRFilter is inconsistent", RuntimeWarning)
        # (the drive's odometer, 0.02 m a sample, is noisier than the phone grade's 0.01: the filter says so)
        warnings.filterwarnings("ignore", "GPSDRFilter: the odometer is noisier than the grade", RuntimeWarning)
        h.batch_filter(one.z_dr, jitter, one.gps_sigma_list())
    assert h.n_thinned == 0 and h.n_fixes == len(one.gps_steps)


def test_fast_correlated_fixes_warn_with_the_remedy():
    correlated, white = _at_rate(5.0, 0), _at_rate(5.0, 0, phi_per_second=0.0)
    f = _phone_filter(correlated)
    with pytest.warns(RuntimeWarning, match=r"fixes come every 0.2 s and are correlated at step \d+: each carries "
                                            r"1/\d+ of an independent fix .* pass min_fix_interval=1 \(--min-fix-interval 1\) to use one") as rec:
        f.batch_filter(correlated.z_dr, correlated.gps_list(), correlated.gps_sigma_list())
    # measured over a full window (60 s: 300 fixes at 0.2 s, steps counted from 0), not the first seconds
    step = int(re.search(r"correlated at step (\d+)", next(str(w.message) for w in rec
                                                           if "correlated at step" in str(w.message))).group(1))
    assert step >= 299
    for run, kw in ((white, {}), (correlated, {"min_fix_interval": MIN_FIX_INTERVAL}), (_at_rate(1.0, 0), {})):
        g = _phone_filter(run, **kw)
        with warnings.catch_warnings(record=True) as rec:
            warnings.simplefilter("always")
            g.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
        assert not any("and are correlated at step" in str(w.message) for w in rec), kw
    # 1 Hz fixes on a dt read from Unix-epoch times (0.0999999046 s before the reader rounded it): the
    # fixes came every 0.999999 s, and the warning took them for fast
    one = _at_rate(1.0, 0)
    model = GPSDRModel.from_grade("phone", one.scenario.dt * (1.0 - 1e-6))
    g = GPSDRFilter(model, "ekf", x0=np.r_[one.x0, model.x0[6:]])
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        g.batch_filter(one.z_dr, one.gps_list(), one.gps_sigma_list())
    assert g.gps_correlation > 5.0 and not any("and are correlated at step" in str(w.message) for w in rec)


def test_min_fix_interval_is_checked():
    with pytest.raises(ValueError, match="min_fix_interval must be >= 0"):
        GPSDRFilter(GPSDRModel(augmented=True), min_fix_interval=-1.0)


def test_whiteness_window_is_checked():
    with pytest.raises(ValueError, match="whiteness_window must be >= 0"):
        GPSDRFilter(GPSDRModel(augmented=True), whiteness_window=-1)


def test_correlated_fixes_is_checked_and_defaults_to_the_calibrations_share():
    assert GPSDRFilter(GPSDRModel(augmented=True)).correlated_fixes == "calibration"
    with pytest.raises(ValueError, match="correlated_fixes"):
        GPSDRFilter(GPSDRModel(augmented=True), correlated_fixes="ignore")


def test_inflated_correlated_fixes_count_as_the_independent_fixes_they_are_worth():
    """``correlated_fixes="inflate"``: white fixes leave the filter as the default has it, bit for bit
    while the estimate is 1. The first fix after the estimate passes 1 is tested as reported (the same
    NIS as the default's), and its update takes ``gps_correlation`` times its covariance: the position
    variance it leaves is that of an update with the fix's variance times the estimate."""
    white = _with_fix_errors(simulate_scenario(_STRAIGHTISH, rng=3), 0.0, np.random.default_rng(3))
    f, g = _phone_filter(white), _phone_filter(white, correlated_fixes="inflate")
    a = f.batch_filter(white.z_dr, white.gps_list(), white.gps_sigma_list())
    b = g.batch_filter(white.z_dr, white.gps_list(), white.gps_sigma_list())
    assert np.array_equal(a[:60], b[:60])

    run = _with_fix_errors(simulate_scenario(_STRAIGHTISH, rng=4), 0.97, np.random.default_rng(4))
    g = _phone_filter(run, correlated_fixes="inflate")
    gps, sig = run.gps_list(), run.gps_sigma_list()
    for k in range(len(run.z_dr)):
        c = g.gps_correlation
        g.predict()
        if gps[k] is not None and c > 1.0:
            break
        g.update(run.z_dr[k], gps[k], sig[k])
    # the same update by a filter that takes the fix as independent, given the fix's sigma times sqrt(c)
    h = copy.deepcopy(g)
    h.correlated_fixes, h.whiteness_window, h.gps_correlation = "calibration", 0, 1.0
    x_prior, P_prior = g.x.copy(), g.P.copy()
    g.update(run.z_dr[k], gps[k], sig[k])
    h.update(run.z_dr[k], gps[k], sig[k] * np.sqrt(c))
    assert g.fix_status == "accepted" and c > 1.5
    np.testing.assert_allclose(g.x, h.x, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(g.P, h.P, rtol=1e-12, atol=1e-15)
    pos = [0, 3]
    Pp, y = P_prior[np.ix_(pos, pos)], gps[k] - x_prior[pos]
    assert g.nis == pytest.approx(y @ np.linalg.solve(Pp + sig[k] ** 2 * np.eye(2), y), rel=1e-9)  # as reported
    assert h.nis < g.nis


# ----------------------------------------------------------------------------- the fixes' covariance scale (issue 23)
def _scaled_fixes(run, true_sigma, reported, rng):
    """``run`` with white fixes of ``true_sigma`` per axis (an array: per fix), each reporting ``reported``."""
    true_sigma = np.broadcast_to(np.asarray(true_sigma, dtype=float), (len(run.z_gps),))
    z = run.x_true[run.gps_steps][:, [0, 3]] + true_sigma[:, None] * rng.standard_normal((len(run.z_gps), 2))
    return run._replace(z_gps=z, gps_sigma=np.full(len(z), float(reported)))


def test_gps_scale_mle_is_the_maximum_likelihood_scale():
    from filterwnn.navigation.gpsdr import gps_scale_loglik, gps_scale_mle

    rng = np.random.default_rng(0)
    n, lam = 2000, 3.0
    R = np.broadcast_to(np.diag([4.0, 9.0]), (n, 2, 2))
    P = np.broadcast_to(np.array([[2.0, 0.5], [0.5, 1.0]]), (n, 2, 2))
    y = np.einsum("ij,nj->ni", np.linalg.cholesky(P[0] + lam * R[0]), rng.standard_normal((n, 2)))
    est = gps_scale_mle(y, P, R)
    # its standard error is at most lam / sqrt(n) (the P = 0 case: a mean of 2 n chi-square(1) / 2)
    assert abs(est - lam) < 4 * lam / np.sqrt(n)
    ll = gps_scale_loglik(y, P, R, est)
    assert ll > gps_scale_loglik(y, P, R, 1.001 * est) and ll > gps_scale_loglik(y, P, R, 0.999 * est)
    # without P it is the mean NIS against R per dimension
    nis = np.einsum("ni,ni->n", y, np.linalg.solve(R, y[..., None])[..., 0])
    assert gps_scale_mle(y, np.zeros_like(P), R, iterations=200, rtol=1e-12) == pytest.approx(nis.mean() / 2, rel=1e-9)


def test_gps_scale_is_off_by_default_and_checked():
    from scipy.stats import chi2

    from filterwnn.navigation.gpsdr import SCALE_TEST

    assert SCALE_TEST == pytest.approx(chi2.ppf(1 - 2e-3, 1), rel=1e-9)  # the one-sided 0.1 % point
    f = GPSDRFilter(GPSDRModel(augmented=True))
    assert f.scale_window == 0 and f.gps_scale == 1.0 and f.gps_scale_mean is None
    with pytest.raises(ValueError, match="scale_window must be >= 0"):
        GPSDRFilter(GPSDRModel(augmented=True), scale_window=-1)


def test_honest_fixes_keep_their_reported_sigma():
    from filterwnn.navigation.gpsdr import SCALE_WINDOW

    run = _scaled_fixes(simulate_scenario(_STRAIGHTISH, rng=5), 5.0, 5.0, np.random.default_rng(5))
    f, g = _phone_filter(run, scale_window=SCALE_WINDOW), _phone_filter(run)
    a = f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    b = g.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    # the scale departs from 1 only when a window tells it from 1 at the 0.1 % level: not here
    assert f.gps_scale_mean == 1.0 and len(f.gps_scales) == len(run.gps_steps)
    np.testing.assert_array_equal(a, b)  # bit for bit as with the estimate off


@pytest.mark.filterwarnings("ignore:GPSDRFilter is inconsistent")  # before the scale is learnt
def test_fixes_with_a_twice_optimistic_sigma_get_a_scale_of_four():
    from scipy.stats import chi2

    from filterwnn.navigation.gpsdr import SCALE_WINDOW

    run = _scaled_fixes(simulate_scenario(_STRAIGHTISH, rng=6), 10.0, 5.0, np.random.default_rng(6))
    f = _phone_filter(run, scale_window=SCALE_WINDOW)
    f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    # one estimate per window that shares no fix with the others, over the second half of the drive
    s = np.array(f.gps_scales)
    ends = np.arange(len(s) // 2 + SCALE_WINDOW, len(s), SCALE_WINDOW)
    m = len(ends)
    # with P small against R, each is 4 chi-square(2 W) / (2 W); their mean 4 chi-square(2 W m) / (2 W m):
    # inside its two-sided 99.9 % interval
    dof = 2 * SCALE_WINDOW * m
    lo, hi = 4.0 * chi2.ppf([0.0005, 0.9995], dof) / dof
    assert lo < s[ends].mean() < hi, (s[ends].mean(), lo, hi)


def test_a_jump_does_not_stick():
    from filterwnn.navigation.gpsdr import GATE, SCALE_WINDOW

    run = _scaled_fixes(simulate_scenario(_STRAIGHTISH, rng=7), 5.0, 5.0, np.random.default_rng(7))
    f = _phone_filter(run, scale_window=SCALE_WINDOW)
    gps, sig = run.gps_list(), run.gps_sigma_list()
    jumps = [int(run.gps_steps[i]) for i in (100, 200)]
    for k in range(len(run.t)):
        f.predict()
        if k == jumps[0]:  # 5 sigma off: down-weighted, and enters the window clipped at the gate
            sd = np.sqrt(f.P[0, 0] + 25.0)
            gps[k] = f.x[[0, 3]] + np.array([5.0 * sd, 0.0])
        if k == jumps[1]:  # 80 m off: rejected, and never enters the window
            gps[k] = gps[k] + np.array([80.0, 0.0])
        f.update(run.z_dr[k], gps[k], sig[k])
        if k in jumps:
            assert f.fix_status == ("down-weighted" if k == jumps[0] else "rejected")
    s = np.array(f.gps_scales)
    # a fix clipped at the gate moves the window's scale by at most (gate - 2) / (2 W), for W fixes
    assert s.max() <= 1.0 + (GATE - 2.0) / (2 * SCALE_WINDOW)
    assert np.all(s[101 + SCALE_WINDOW:] == 1.0)


@pytest.mark.filterwarnings("ignore:GPSDRFilter is inconsistent")  # before the scale is learnt
def test_a_run_of_optimistic_fixes_raises_the_scale_and_it_comes_back():
    from filterwnn.navigation.gpsdr import SCALE_WINDOW

    base = simulate_scenario(_STRAIGHTISH, rng=8)
    n = len(base.z_gps)
    true = np.where(np.arange(n) < n // 2, 10.0, 5.0)  # 2x optimistic for the first half, honest after
    run = _scaled_fixes(base, true, 5.0, np.random.default_rng(8))
    f = _phone_filter(run, scale_window=SCALE_WINDOW)
    f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    s = np.array(f.gps_scales)
    assert np.median(s[SCALE_WINDOW:n // 2]) > 2.0
    assert np.all(s[n // 2 + 2 * SCALE_WINDOW:] == 1.0)


@pytest.mark.filterwarnings("ignore:GPSDRFilter is inconsistent")  # before the scale is learnt
def test_a_scale_past_its_plausible_bound_warns_once_with_the_step():
    from filterwnn.navigation.gpsdr import SCALE_WARN, SCALE_WINDOW

    run = _scaled_fixes(simulate_scenario(_STRAIGHTISH, rng=9), 20.0, 5.0, np.random.default_rng(9))
    f = _phone_filter(run, scale_window=SCALE_WINDOW)
    with pytest.warns(RuntimeWarning, match=r"covariance scale reached .* at step \d+.*scale_window=0") as rec:
        f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    assert max(f.gps_scales) > SCALE_WARN  # 4x optimistic: a scale of about 16
    assert sum("covariance scale reached" in str(w.message) for w in rec) == 1
    # 2x optimistic (a scale of about 4) is inside the bound: no such warning
    run = _scaled_fixes(simulate_scenario(_STRAIGHTISH, rng=6), 10.0, 5.0, np.random.default_rng(6))
    g = _phone_filter(run, scale_window=SCALE_WINDOW)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        g.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    assert not any("covariance scale reached" in str(w.message) for w in rec)


def test_fixes_as_an_array_with_nan_rows_are_the_fixes_as_a_list_with_none():
    """A user's fixes as an ``(n_steps, 2)`` array, NaN where there is none (pandas' way), run as the list of
    fixes and None; a fix with one coordinate NaN is refused."""
    run, f = _steady()
    fixes = run.gps_list()
    rows = np.array([[np.nan, np.nan] if g is None else g for g in fixes])
    sigmas = np.where(np.isnan(rows[:, 0]), np.nan, 2.0)
    a = f.batch_filter(run.z_dr, fixes, [None if g is None else 2.0 for g in fixes])
    b = _steady()[1].batch_filter(run.z_dr, rows, sigmas)
    np.testing.assert_array_equal(a, b)
    g = _steady()[1]
    g.predict()
    with pytest.raises(ValueError, match=r"z_gps must be finite"):
        g.update(run.z_dr[0], [1.0, np.nan])


def _pull_away_glitch(tmp_path):
    """The 1 Hz analog (seed 0) as read, with one heading sample turned by 90 degrees as the car pulls away at
    3 m/s (past the drive reader, which would interpolate it), its fixes and their sigmas, and the phone grade's
    8-state model."""
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    import _held_out_drives as held_out

    from filterwnn.navigation.drives import read_drive_csv

    run = read_drive_csv(held_out.write_csv(tmp_path / "d.csv", held_out.columns("one_hz", 0)))
    z = run.z_dr.copy()
    assert 2.5 < z[124, 1] / run.scenario.dt < 3.5 and z[125, 1] / run.scenario.dt > LOW_SPEED
    z[124, 0] = np.mod(z[124, 0] + np.pi / 2, 2 * np.pi)
    return run, z, GPSDRModel.from_grade("phone", run.scenario.dt, augmented=True)


def _speed_errors(run, z, model, kind, steps=170, **kw):
    f = GPSDRFilter(model, kind, x0=np.concatenate([run.x0, model.x0[6:]]), **kw)
    gps, sig, err = run.gps_list(), run.gps_sigma_list(), []
    for k in range(steps):
        f.predict()
        f.update(z[k], gps[k], sig[k])
        err.append(np.hypot(f.x[1] - run.x_true[k, 1], f.x[4] - run.x_true[k, 4]))
    return f, np.array(err)


@pytest.mark.parametrize("kind", KINDS)
def test_a_heading_far_from_the_filters_enters_as_a_velocity_vector(tmp_path, kind):
    """The [heading, distance] update is linearised about the filter's heading: one sample 90 degrees off as a
    1 Hz car pulls away sent the filters' velocity into an oscillation that grew to 40-50 m/s off (an outage
    then ended 815 m off, stop 50). Taken as the measured velocity vector, it is one sample's error."""
    run, z, model = _pull_away_glitch(tmp_path)
    with pytest.warns(RuntimeWarning, match=r"at step 125: the measured heading is -93 degrees from the filter's "
                                            r"at 5\.3 m/s by the odometer.*velocity vector"):
        f, err = _speed_errors(run, z, model, kind)
    assert f.n_heading_far == 1
    # the glitch's own sample (3 m/s turned by 90 degrees: 4.2 m/s), then within the odometer's noise
    assert err.max() < 5.0 and err[126:].max() < 1.5, (err.max(), err[126:].max())
    if kind == "ekf":  # the test can fail: the filter as it was
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            off, err_off = _speed_errors(run, z, model, kind, heading_linear_limit=None)
        assert off.n_heading_far == 0 and err_off.max() > 30.0


def test_the_velocity_form_without_the_low_speed_noise():
    """``measurement_for(velocity=True)``: the measured velocity vector with its first-order covariance, without
    the low-speed form's extra noise."""
    model = GPSDRModel.from_grade("phone", 0.1, augmented=True)
    z_dr = np.array([0.3, 1.2])
    z, R, kw = model.measurement_for(z_dr, velocity=True)
    w, Rw = model.velocity_measurement(z_dr)
    np.testing.assert_array_equal(z, w)
    np.testing.assert_array_equal(R, Rw)
    assert kw == {"gps": False, "velocity": True}
    _, R_low, _ = model.measurement_for(z_dr, low_speed=True)
    np.testing.assert_allclose(R_low - R, model.sigma_low_speed**2 * np.eye(2))


def test_a_fix_reporting_far_better_than_those_before_it_is_floored():
    """Fixes of 3 m, one of them reporting 0.1 m: it is taken as a quarter of the fixes' reported sigma before it
    (the lower of the medians of the last three and of the last thirty, so two placeholders of 9999 m in a row do
    not floor the honest fixes after them), once with a warning naming the step and the remedy (``gps_sigma_floor=0``), and counted; with
    ``gps_sigma_floor=0`` it is taken as reported. Fixes whose reported sigma wanders (1-4 m) are taken as
    reported, to the bit."""
    run, f = _steady(kind="ekf")
    fixes, sigmas = list(run.gps_list()), [None if z is None else 3.0 for z in run.gps_list()]
    k = run.gps_steps[30]
    sigmas[k] = 0.1
    for j in run.gps_steps[40:42]:  # two placeholders in a row (no fix: 9999 m) raise no floor on the fixes after
        sigmas[j] = 9999.0
    seen = {}
    orig = f._check_fix

    def check(z, s, **kw):
        seen[f.step] = s
        return orig(z, s, **kw)

    f._check_fix = check
    said = (rf"takes the fix at step {k} as 0.75 m, not the 0.1 m it reports: under 0.25 of the fixes' reported "
            r"sigma before it \(3 m, the lower of the medians of the last 3 and the last 30 reported, this one's among "
            r"them\).*gps_sigma_floor=0")
    with pytest.warns(RuntimeWarning, match=said) as rec:
        f.batch_filter(run.z_dr, fixes, sigmas)
    assert seen[k] == pytest.approx(0.75) and f.n_floored == 1 and f.floored_steps == [k]
    assert sum("takes the fix" in str(w.message) for w in rec) == 1
    _, off = _steady(kind="ekf", gps_sigma_floor=0, floor_on_detection=False)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        off.batch_filter(run.z_dr, fixes, sigmas)
    assert off.n_floored == 0 and not any("takes the fix" in str(w.message) for w in rec)
    # honest sigmas that wander (1-4 m) stay as reported: the same estimates as with the floor off
    wander = [None if z is None else 1.0 + 3.0 * np.random.default_rng(k).random() for k, z in enumerate(fixes)]
    _, a = _steady(kind="ekf", floor_on_detection=False)  # (1 m for 3 m fixes: the monitor names them)
    _, b = _steady(kind="ekf", gps_sigma_floor=0, floor_on_detection=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # 1-4 m for 3 m fixes: inconsistent, as it warns
        assert np.array_equal(a.batch_filter(run.z_dr, fixes, wander), b.batch_filter(run.z_dr, fixes, wander))
    assert a.n_floored == 0


@pytest.mark.parametrize("bad", [-0.1, 1.5, np.nan])
def test_gps_sigma_floor_is_checked(bad):
    with pytest.raises(ValueError, match="gps_sigma_floor must be in"):
        _steady(gps_sigma_floor=bad)


@pytest.mark.parametrize("n", [1, 2, 3, 4, 29, 30])
def test_the_floors_median_is_numpys_to_the_bit(n):
    from filterwnn.navigation.gpsdr import _median

    for seed in range(20):
        v = np.exp(np.random.default_rng(seed).normal(1.0, 1.0, n)).tolist()
        assert _median(v) == np.median(v)


def _monitor_warnings(z_gps, sigma, run):
    from filterwnn.navigation.dead_reckoning import GPSDRModel

    model = GPSDRModel.from_grade("survey", run.scenario.dt)
    f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
    gps = [None] * len(run.t)
    for k, z in zip(run.gps_steps, z_gps):
        gps[k] = z
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        f.batch_filter(run.z_dr, gps, [None if g is None else sigma for g in gps])
    return [str(w.message) for w in rec if "is inconsistent" in str(w.message)]


def test_the_inconsistency_warning_says_when_a_few_fixes_carry_it():
    """A user's car reversing out of a parking space (an unsigned speed) made five of the window's fixes carry 71 %
    of its NIS while its median stayed a consistent filter's; the warning blamed the fixes' accuracy, and its
    remedy changed nothing (stop 69). Five fixes that jump 12 m in a drive whose 3 m fixes are reported right are
    named with their steps; fixes whose reported sigma is a third of their error throughout are not."""
    from filterwnn.navigation.gpsdr import FEW_FIXES
    from filterwnn.navigation.scenarios import Scenario, simulate_scenario

    run = simulate_scenario(Scenario(name="plain", duration=120.0, speed=12.0, heading=60.0, gps_rate=1.0,
                                     sigma_gps=3.0), rng=3)
    z = run.z_gps.copy()
    jumped = np.arange(40, 80, 8)[:FEW_FIXES]
    z[jumped, 0] += 12.0
    said = _monitor_warnings(z, 3.0, run)
    assert said and said[0].startswith("GPSDRFilter is inconsistent in a few fixes at step ")  # (folded apart)
    assert "most of it is in 5 of the 30 fixes" in said[0]
    import re

    at = int(re.search(r"inconsistent in a few fixes at step (\d+)", said[0]).group(1))
    named = {int(k) for k in re.search(r"the fixes at steps ([\d, ]+)\)", said[0]).group(1).split(", ")}
    assert {int(k) for k in run.gps_steps[jumped] if k <= at} <= named  # every jump the window holds
    assert "else the fixes' reported accuracy is optimistic" in said[0]
    said = _monitor_warnings(run.z_gps, 1.0, run)  # optimistic throughout: the median says so
    assert said and said[0].startswith("GPSDRFilter is inconsistent at step ") and "most of it is in" not in said[0]


@pytest.mark.parametrize("kind", ["EKF", "EKF-8", "UKF-8", "SUKF-8"])
def test_a_speed_that_jumps_from_rest_past_low_speed_starts_the_filter(kind):
    """A user's drive from a parked start, its speed 0 for 5 s and then 7.8 m/s at once: the [heading, distance]
    update's Jacobian vanishes at rest, so the EKF and EKF-8 stood for the whole first outage (239 m off, dead
    reckoning 6 m), and the UKF-8, started badly, held its heading bias at its bound (stop 69). Such a sample now
    enters as the measured velocity vector, with a warning at its step."""
    from filterwnn.navigation.scenarios import DRRun
    from filterwnn.studies.dr import real_drive_outages

    t = np.arange(0.0, 300.05, 0.1)
    north = 10.0 * np.maximum(t - 5.0, 0.0)
    gps_t = np.arange(1.0, 300.5, 1.0)
    rng = np.random.default_rng(1)
    run = DRRun.from_arrays(t, np.full(t.size, 0.3), speed=np.where(t < 5.0, 0.0, 10.0), gps_t=gps_t,
                            east=rng.normal(0.0, 2.0, gps_t.size),
                            north=np.interp(gps_t, t, north) + rng.normal(0.0, 2.0, gps_t.size), gps_sigma=2.0,
                            truth=np.stack([np.zeros(t.size), north], axis=1), checks=False)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        res = real_drive_outages(run, starts=[0.0, 100.0], filters=("DR-mech", kind), grade="phone",
                                 use_gps_sigma=True)
    said = [str(w.message) for w in rec if "where the filter stands" in str(w.message)]
    assert said and "at step 49" in said[0] and "past low_speed (5 m/s) in one sample" in said[0]
    assert res[kind][0] < 3 * res["DR-mech"][0] + 5.0, (res[kind], res["DR-mech"])  # it moved: 250 m of driving
    assert res["integrity"][kind]["n_from_rest"] >= 1
