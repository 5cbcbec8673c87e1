"""A gyro's scale factor error (issue 23): a tenth state, from the grade's ``gyro_scale_sd``.

A MEMS gyro's sensitivity is good to a few per cent, and a phone's calibration removes its bias, not
its scale: its heading turns ``1 + k`` times the car. The held-out analogs had no such error; with
one of 3 % the 1 Hz analog's outages ended up to 41 m off (9 states, phone grade) against its 30 m
target. A grade with ``gyro_scale_sd`` above 0 (0.01: a +-3 % tolerance as three sigmas) estimates
``k``, and every measured turn carries it into the heading bias. Off in the shipped grades: without
such an error it costs (docs/study-outputs/dr/gyro-scale/RUN.md).
"""

import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.gpsdr import GYRO_SCALE, HEADING_BIAS, GPSDRFilter
from filterwnn.studies.dr import real_drive_outages

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import _held_out_drives as held_out  # noqa: E402

KINDS8 = ("EKF-8", "UKF-8", "SUKF-8")


K = {"gyro_scale_sd": 0.01}  # the phone grade, with the state


def test_a_grade_with_gyro_scale_sd_estimates_the_gyros_scale_factor():
    m = GPSDRModel.from_grade(K)
    assert m.dim_x == 10 and m.gyro_scale and m.P0[9, 9] == pytest.approx(0.01**2) and m.x0[9] == 0.0
    assert GPSDRModel.from_grade("phone").dim_x == 9 and GPSDRModel.from_grade("survey").dim_x == 8
    np.testing.assert_array_equal(m.F[9], np.eye(10)[9])  # constant, but for its random walk
    with pytest.raises(ValueError, match="gyro_scale=True needs rate_bias=True"):
        GPSDRModel(augmented=True, gyro_scale=True)
    with pytest.raises(ValueError, match=r"gyro_scale_sd'\] > 0 needs a rate-bias state"):
        GPSDRModel.from_grade({**K, "rate_bias": False})


@pytest.mark.parametrize("kind", ["ekf", "ukf", "sukf"])
def test_a_measured_turn_carries_the_scale_error_into_the_heading_bias(kind):
    """A turn of ``d`` maps the state by ``T = I + d e_b e_k^T``: ``b += k d``, ``P -> T P T^T``, and the
    calibration's prior (which bounds ``b``) alike; no turn, no change."""
    m = GPSDRModel.from_grade(K)
    f = GPSDRFilter(m, kind)
    x = f.x.copy()
    x[GYRO_SCALE] = 0.02
    f.kf.x = x
    P = f.P.copy()
    P[HEADING_BIAS, GYRO_SCALE] = P[GYRO_SCALE, HEADING_BIAS] = 1e-5
    f.kf.P = P
    f._turn(0.3)
    np.testing.assert_array_equal(f.x, x)  # the first heading: nothing to compare with
    cal = f._cal_P.copy()
    f._turn(0.3 + 1.5)
    T = np.eye(10)
    T[HEADING_BIAS, GYRO_SCALE] = 1.5
    np.testing.assert_allclose(f.x, T @ x, rtol=0, atol=1e-15)
    np.testing.assert_allclose(f.P, T @ P @ T.T, rtol=1e-12, atol=1e-18)
    Tc = T[6:, 6:]
    np.testing.assert_allclose(f._cal_P, Tc @ cal @ Tc.T, rtol=1e-12, atol=1e-18)
    f._turn(0.3 + 1.5 - 2 * np.pi)  # the same heading, wrapped: no turn
    np.testing.assert_allclose(f.x, T @ x, rtol=0, atol=1e-15)


@pytest.fixture(scope="module")
def one_hz_3_percent(tmp_path_factory):
    """The 1 Hz analog (seed 0) with a gyro that turns 3 % too far, scored as the command scores it
    (phone grade, 20 outages of 30 s): with the scale state from the start (``gyro_scale_sd`` 0.01), with
    the phone grade's default (the state added when the monitor finds the error), and without it."""
    path = held_out.write_csv(tmp_path_factory.mktemp("gyro") / "one_hz_k3.csv",
                              held_out.columns("one_hz", 0, gyro_scale=0.03))
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        run = read_drive_csv(path)
        for label, grade, detect in (("k", K, True), ("default", "phone", True), ("no k", "phone", False)):
            with pytest.MonkeyPatch.context() as mp:
                mp.setitem(GPSDRFilter.__init__.__kwdefaults__, "scale_on_detection", detect)
                out[label] = real_drive_outages(run, filters=KINDS8, use_gps_sigma=True, grade=grade)
    return out


@pytest.mark.parametrize("kind", KINDS8)
def test_a_gyro_that_turns_3_percent_too_far_meets_the_1_hz_target_with_the_scale_state(one_hz_3_percent, kind):
    """Measured (EKF-8, median / max at the outage ends): 1.72 / 10.64 m with the state from the start,
    1.78 / 12.89 m with the phone grade's default (the monitor adds it at step 158), 7.03 / 40.95 m
    without it; the target is 6 / 30."""
    no_k = one_hz_3_percent["no k"][kind]
    for label in ("k", "default"):
        k = one_hz_3_percent[label][kind]
        assert np.median(k) <= 6.0 and k.max() <= 30.0, (label, kind, np.median(k), k.max())
        assert np.median(no_k) > 2 * np.median(k), (label, kind, np.median(no_k), np.median(k))
    assert no_k.max() > 30.0, (kind, np.median(no_k), no_k.max())
    assert one_hz_3_percent["default"]["integrity"][kind]["gyro_scale_added"] is not None


def test_the_command_takes_the_gyro_scale_sd(tmp_path, command_passes):
    from filterwnn.cli import main

    for argv, want in ((["--gyro-scale-sd", "0.01"], 0.01), ([], None)):
        grade = command_passes("real_drive_outages", argv)["grade"]
        assert (grade == "phone") if want is None else (grade["gyro_scale_sd"] == want and grade["rate_bias"])
    argv = ["study", "dr", "--drive", "sample", "--out", str(tmp_path), "--grade", "survey", "--gyro-scale-sd", "0.01"]
    assert main(argv) == 2  # refused, with its one-line error


def test_the_command_takes_the_gyros_own_bias(tmp_path, command_passes):
    """--gyro-bias: the gyro's rate bias (deg/s, one sigma) in place of the phone grade's 0.05; refused with
    a grade that has no rate-bias state."""
    from filterwnn.cli import main

    grade = command_passes("real_drive_outages", ["--gyro-bias", "0.31"])["grade"]
    assert grade["gyro_bias_deg_s"] == 0.31 and grade["rate_bias"] and grade["gps_sigma_m"] == 5.0
    argv = ["study", "dr", "--drive", "sample", "--out", str(tmp_path), "--grade", "survey", "--gyro-bias", "0.3"]
    assert main(argv) == 2


def test_the_command_takes_the_gyros_bias_instability(tmp_path, command_passes):
    """--gyro-bias-instability: how fast the gyro's rate bias moves (deg/h) in place of the phone grade's 10 (the
    consistency monitor's remedy for a bias that moved); refused with a grade that has no rate-bias state."""
    from filterwnn.cli import main

    grade = command_passes("real_drive_outages", ["--gyro-bias-instability", "100"])["grade"]
    assert grade["gyro_bias_instability_deg_h"] == 100.0 and grade["rate_bias"] and grade["gyro_bias_deg_s"] == 0.05
    argv = ["study", "dr", "--drive", "sample", "--out", str(tmp_path), "--grade", "survey",
            "--gyro-bias-instability", "100"]
    assert main(argv) == 2
    with pytest.raises(SystemExit) as stopped:  # argparse's error: a rate above 0
        main(["study", "dr", "--drive", "sample", "--out", str(tmp_path), "--gyro-bias-instability", "0"])
    assert stopped.value.code == 2


def _one_hz_filter(tmp_path, error, grade="phone"):
    path = held_out.write_csv(tmp_path / f"one_hz_{error}.csv", held_out.columns("one_hz", 0, gyro_scale=error))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        run = read_drive_csv(path)
    m = GPSDRModel.from_grade(grade, run.scenario.dt)
    return run, GPSDRFilter(m, "ekf", x0=np.r_[run.x0, m.x0[6:]])


def test_a_filter_without_the_state_warns_when_the_fixes_show_a_scale_error(tmp_path):
    """The 1 Hz analog with a gyro 3 % off, the phone grade (no scale state): the monitor warns once, with
    the step, the estimate so far (+3.7 +- 0.6 % at step 158; 2.85 % at the end) and the remedy; with no error it stays quiet (|z| 0.6 at the end); the
    survey grade's model (no rate bias) has no monitor, and the scale state's model needs none."""
    run, f = _one_hz_filter(tmp_path, 0.03)
    f.scale_on_detection = False
    with pytest.warns(RuntimeWarning, match=r"by step \d+ the fixes show the gyro turning \+\d(\.\d)? % \(\+- 0\.\d+ %\) "
                                            r"more than the car .* use a grade with gyro_scale_sd=0.01 \(--gyro-scale-sd 0.01\)"):
        f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    assert abs(f.gyro_scale_estimate - 0.03) < 0.005 and f.gyro_scale_z > 6.1 and f.gyro_scale_added is None
    run, f = _one_hz_filter(tmp_path, 0.0)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    assert not [w for w in seen if "scale factor error" in str(w.message)]
    assert abs(f.gyro_scale_z) < 3.0 and abs(f.gyro_scale_estimate) < 0.005
    assert GPSDRFilter(GPSDRModel.from_grade("survey")).gyro_scale_z is None
    assert "gyro_scale" not in GPSDRFilter(GPSDRModel.from_grade("survey"))._hyp
    assert "gyro_scale" not in GPSDRFilter(GPSDRModel.from_grade(K))._hyp


@pytest.mark.parametrize("kind", ["ekf", "ukf", "sukf"])
def test_the_monitor_adds_the_scale_state_from_its_estimate(tmp_path, kind):
    """By default the filter adds the state when the monitor fires: x -> [x + s k, k], P augmented by the
    monitor's sensitivity ``s`` and the estimate's variance, the calibration prior extended; batch_filter
    keeps returning the states of the model it started with, and the state then follows the error."""
    run, f = _one_hz_filter(tmp_path, 0.03)
    with pytest.warns(RuntimeWarning, match=r"the filter adds a scale state from here, started at that estimate"):
        est = f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    assert est.shape == (len(run.z_dr), 9) and np.all(np.isfinite(est))
    assert f.gyro_scale_added is not None and f.model.dim_x == 10 and f.x.shape == (10,) and "gyro_scale" not in f._hyp
    assert abs(f.x[GYRO_SCALE] - 0.03) < 0.006, f.x[GYRO_SCALE]
    np.linalg.cholesky(f.P)
    assert f._cal_P.shape == (4, 4) and f._cal_mean.shape == (4,)
    m = GPSDRModel.from_grade("phone").with_gyro_scale(0.01)
    assert m.dim_x == 10 and m.P0[9, 9] == pytest.approx(1e-4) and m.x0.shape == (10,)
    with pytest.raises(ValueError, match="with_gyro_scale needs a model with a rate-bias state and no scale state"):
        m.with_gyro_scale(0.01)
