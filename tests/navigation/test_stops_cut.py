"""A standstill whose speed does not read 0, found by the filter (stop 61).

A u-blox user with no wheel ticks gave the receiver's GNSS speed (``gSpeed``, 1 Hz, interpolated to the 10 Hz rows)
as the speed. At a standstill it reads a few cm/s of noise, clipped at 0, so each stop came apart into pieces of a
sample or two, each too short to measure the gyro's rate bias; the gyro's 0.18 deg/s, outside the phone grade, stayed
held at its calibration bound until step 5630, and the EKF-8 ended the command's outages 7.32 / 173.35 m off (3.56 /
15.06 m with the wheel ticks), with nothing naming the speed. ``stop_reopen=2`` (``--stop-reopen 2``), which takes
each standstill whole, existed (3.52 / 22.15 m) and nothing pointed to it. The filter now finds such standstills
when the rate-bias state cannot follow a piece, warns with the step, and takes each standstill whole from there
(``reopen_on_detection``; 4.97 / 21.85 m): ``docs/gps_dr.md``, "Stops whose speed does not read 0". The reader
names such a speed too: its slope changes only at the fixes (a column interpolated between them), as it named a speed
or a heading held between them.
"""

import warnings

import numpy as np
import pytest

from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.gpsdr import KINDS, REOPEN_PIECES, STOP_REOPEN, GPSDRFilter
from filterwnn.navigation.scenarios import DRRun
from filterwnn.studies.dr._real import real_drive_outages, real_drive_table

OUTAGE = 30.0  # the drive's last 30 s have no fixes: the error at its end is scored


def _drive(seed=0, bias_deg_s=0.18, gnss_speed=True, dt=0.1, duration=420.0, gnss_heading=False, caught=None,
           gyro_scale=1.0, exported=False):
    """Legs of 12 m/s with a 90 degree turn each, and stops of 25 s with a speed of exactly 0, the gyro heading
    drifting by ``bias_deg_s``; with ``gnss_speed`` the speed is a receiver's 1 Hz GNSS speed (noise of 0.05 m/s,
    clipped at 0) interpolated to the samples, as the u-blox user gave it. Fixes 1 Hz, 2 m, none in the last 30 s.
    ``exported``: as a logger's CSV gives it, the time in seconds since 1970 and the speed (m/s) and heading (deg)
    written to 3 and 2 decimals."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, duration, dt)
    knots, tk = [(0.0, 0.0), (8.0, 0.0), (12.0, 12.0)], 12.0
    while tk < duration:
        knots += [(tk + 36, 12.0), (tk + 40, 0.0), (tk + 65, 0.0), (tk + 69, 12.0)]
        tk += 69
    v = np.interp(t, *zip(*knots))
    rate = np.zeros_like(t)
    for j, t0 in enumerate(np.arange(30.0, duration, 69.0)):
        rate[(t >= t0) & (t < t0 + 6)] = np.radians(15.0) * (1 if j % 2 else -1)
    heading = np.radians(40.0) + np.cumsum(rate) * dt
    east, north = np.cumsum(v * np.sin(heading)) * dt, np.cumsum(v * np.cos(heading)) * dt
    gyro = (heading[0] + gyro_scale * (heading - heading[0]) + np.radians(bias_deg_s) * t
            + rng.normal(0.0, np.radians(0.05), len(t)))
    every = np.arange(0, len(t), int(round(1.0 / dt)))
    speed = v
    if gnss_heading:  # the receiver's course, interpolated to the samples
        gyro = np.interp(t, t[every], heading[every] + rng.normal(0.0, np.radians(0.5), len(every)))
    if gnss_speed:
        speed = np.interp(t, t[every], np.maximum(v[every] + rng.normal(0.0, 0.05, len(every)), 0.0))
    fixes = every[t[every] < duration - OUTAGE]
    stamps = t
    if exported:
        stamps = np.round(t + 1.7964e9, 3)
        speed, gyro = np.round(speed, 3), np.radians(np.round(np.degrees(gyro), 2))
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("always")  # the reader's words, kept in caught when asked
        run = DRRun.from_arrays(stamps, gyro, speed=speed, gps_t=stamps[fixes],
                                 east=east[fixes] + rng.normal(0.0, 2.0, len(fixes)),
                                 north=north[fixes] + rng.normal(0.0, 2.0, len(fixes)),
                                 gps_sigma=np.full(len(fixes), 2.0), truth=np.c_[east, north])
    if caught is not None:
        caught.extend(str(w.message) for w in said)
    return run


@pytest.fixture(scope="module")
def gnss_run():
    return _drive()


def _run(run, kind="ekf", **kw):
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    f = GPSDRFilter(model, kind, x0=np.r_[run.x0, model.x0[6:]], **kw)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        est = f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
    err = float(np.hypot(*(est[-1, [0, 3]] - run.x_true[-1, [0, 3]])))
    return f, err, [str(w.message) for w in caught if "piece" in str(w.message)]


@pytest.mark.parametrize("kind", KINDS)
def test_a_gnss_speed_at_a_standstill_is_found_and_each_standstill_taken_whole(gnss_run, kind):
    f, err, said = _run(gnss_run, kind)
    off, err_off, said_off = _run(gnss_run, kind, reopen_on_detection=False)
    assert f.stops_cut_step is not None and f.stop_reopen == STOP_REOPEN
    assert len(said) == 1 and f"ended at step {f.stops_cut_step} is piece" in said[0]
    assert "a GNSS speed" in said[0] and "taken whole" in said[0]
    # the rate bias is learnt from the whole standstills; held at its bound (0.15 deg/s) without
    assert np.degrees(f.x[8]) == pytest.approx(0.18, abs=0.01)
    assert np.degrees(off.x[8]) < 0.155
    assert err < 0.75 * err_off and err < 2.0, (err, err_off)


def test_only_warns_with_reopen_on_detection_off(gnss_run):
    f, err, said = _run(gnss_run, reopen_on_detection=False)
    assert f.stops_cut_step is not None and f.stop_reopen == 0.0
    assert len(said) == 1 and "--stop-reopen 2" in said[0]


def test_piece_count_at_the_warning_is_at_least_the_threshold(gnss_run):
    f, _, said = _run(gnss_run)
    piece = int(said[0].split("is piece ")[1].split()[0])
    assert piece >= REOPEN_PIECES


@pytest.mark.parametrize("case", [dict(gnss_speed=False), dict(bias_deg_s=0.0), dict(bias_deg_s=0.05)],
                         ids=["speed reads 0 at stops", "no gyro bias", "bias inside the grade"])
def test_never_fires_where_the_stops_are_stops_or_the_state_follows(case):
    f, _, said = _run(_drive(**case))
    assert f.stops_cut_step is None and f.stop_reopen == 0.0 and not said


def test_stop_reopen_given_is_kept_and_never_warned(gnss_run):
    f, err, said = _run(gnss_run, stop_reopen=1.5)
    assert f.stop_reopen == 1.5 and f.stops_cut_step is None and not said


def test_the_drive_table_says_from_which_step_standstills_were_taken_whole(gnss_run):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = real_drive_outages(gnss_run, filters=("EKF-8",), grade="phone", starts=[100.0, 300.0])
        off = real_drive_outages(gnss_run, filters=("EKF-8",), grade="phone", starts=[100.0, 300.0],
                                 reopen_on_detection=False)
    step = res["integrity"]["EKF-8"]["stops_cut"]
    assert step is not None and off["integrity"]["EKF-8"]["stops_cut"] == step
    assert f"(whole from step {step})" in real_drive_table(res)


def test_stop_reopen_measures_the_distance_across_fixes():
    """``stop_reopen`` joins two stops only where the car moved at most 0.5 m between them: measured since the
    drive's start, not since the last fix (whose distance restarted at each new fix, so with 10 Hz fixes a car that
    drove 2.7 m between two stops, 0.3 m between fixes, passed as having stood)."""
    model = GPSDRModel.from_grade("phone", 0.1)
    f = GPSDRFilter(model, "ekf", x0=np.r_[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, model.x0[6:]], stop_reopen=2.0)
    rng = np.random.default_rng(0)
    north = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for ds in [0.0] * 40 + [0.3] * 9 + [0.0] * 40 + [1.0] * 30:  # a stop, 2.7 m in 0.9 s, a stop, away
            north += ds
            f.predict()
            f.update(np.array([rng.normal(0.0, 1e-3), ds]), np.array([0.0, north]) + rng.normal(0.0, 0.5, 2), 0.5)
    assert len(f.zero_rate_steps) == 2  # two stops, not one


@pytest.mark.parametrize("exported", [False, True], ids=["as computed", "as a logger exports it"])
@pytest.mark.parametrize("case,column", [(dict(), "speed"), (dict(gnss_speed=False, gnss_heading=True), "heading")],
                         ids=["GNSS speed", "GNSS course"])
def test_the_reader_names_a_column_interpolated_between_the_fixes(case, column, exported):
    """Also as a logger's CSV export gives it (stop 64): the OBD-II user's GNSS speed, stamped in seconds since 1970
    and written to 3 decimals, had been read without a word. Each step is a speed times its stamped interval, whose
    last digits the stamps' size changes at every sample, and a straight line written to 3 decimals changes its slope
    at every sample by its rounding: the speed is now read as given, and no change within the rounding counted."""
    caught = []
    _drive(caught=caught, exported=exported, **case)
    said = [m for m in caught if "runs straight between" in m]
    assert len(said) == 1 and f"the {column} changes its slope only where there is a GPS fix" in said[0]
    assert ("a GPS speed" if column == "speed" else "a GPS course") in said[0]


@pytest.mark.parametrize("exported", [False, True], ids=["as computed", "as a logger exports it"])
def test_the_reader_says_nothing_of_a_wheel_speed_and_a_gyro(exported):
    caught = []
    _drive(gnss_speed=False, caught=caught, exported=exported)
    assert not [m for m in caught if "GPS fix" in m]


def test_a_column_interpolated_between_fixes_logged_between_the_samples_is_named():
    """Fixes on rows of their own, between the DR samples (the careful conversion of a phone log), with the GNSS speed
    interpolated to the samples from the fixes' own times: its line bends at both samples beside each fix's time,
    one of which the test had looked past (71 % of its changes at a fix, under the 80 % it needs)."""
    rng = np.random.default_rng(3)
    dt = 0.1
    t = np.arange(0.0, 400.0, dt)
    v = 10.0 + 4.0 * np.sin(t / 17.0) + 2.0 * np.sin(t / 5.3)
    heading = np.radians(30.0) + 0.2 * np.sin(t / 40.0)
    east, north = np.cumsum(v * np.sin(heading)) * dt, np.cumsum(v * np.cos(heading)) * dt
    tf = np.arange(0.5, 399.0, 1.0) + rng.uniform(-0.045, 0.045, 399)  # each fix at its own time
    speed = np.round(np.interp(t, tf, np.interp(tf, t, v) + rng.normal(0.0, 0.05, len(tf))), 3)
    for given, told in ((speed, True), (np.round(v + rng.normal(0.0, 0.05, len(t)), 3), False)):
        with warnings.catch_warnings(record=True) as said:
            warnings.simplefilter("always")
            DRRun.from_arrays(t + 1.7964e9, heading + rng.normal(0.0, 1e-3, len(t)), speed=given,
                              gps_t=tf + 1.7964e9, east=np.interp(tf, t, east) + rng.normal(0.0, 2.0, len(tf)),
                              north=np.interp(tf, t, north) + rng.normal(0.0, 2.0, len(tf)),
                              gps_sigma=np.full(len(tf), 2.0))
        named = [str(w.message) for w in said if "the speed changes its slope only where there is a GPS fix" in
                 str(w.message)]
        assert bool(named) == told


def test_a_tilted_gyro_axis_is_named_by_the_scale_monitor():
    """A phone reclined in its mount, its axis nearest the vertical given: the gyro turns cos(30 deg) = 0.87 of the car
    (an OBD-II user's log, stop 61: EKF-8 54.16 / 459.06 m at the outage ends, warned of a -6.7 % scale error with no
    cause). The scale monitor's warning now names the tilt and the remedy; on the same drive without a tilt it says
    nothing of one."""
    for scale, told in ((np.cos(np.radians(30.0)), True), (1.0, False)):
        run = _drive(gnss_speed=False, bias_deg_s=0.0, gyro_scale=scale)
        model = GPSDRModel.from_grade("phone", run.scenario.dt)
        f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
        said = [str(w.message) for w in caught if "an axis tilted" in str(w.message)]
        assert (f.gyro_scale_added is not None) == told and bool(said) == told
        if told:
            assert "the gyro's scale" in said[0] and "Rotate the gyro's rates onto the vertical" in said[0]


@pytest.mark.parametrize("scale,warned", [(0.45, True), (0.87, False), (1.0, False)])
def test_the_reader_names_an_axis_tilted_far_off_the_vertical(scale, warned):
    """A gyro axis whose course turns 0.3-0.6 of the fixes' turns (a phone reclined 60 degrees, the axis out of its
    screen given: the OBD-II user's 0.45, EKF-8 222.83 / 1782.85 m) is warned of; at 30 degrees the ratio, read low by
    the fixes' noise, is a right conversion's, and the filters' scale monitor tells it."""
    caught = []
    _drive(gnss_speed=False, bias_deg_s=0.0, gyro_scale=scale, caught=caught)
    assert bool([m for m in caught if "tilted far off the vertical" in m]) == warned
