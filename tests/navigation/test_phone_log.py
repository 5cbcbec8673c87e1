"""A phone's log, converted as a user would (stop 58): what a new user's drive showed the reader getting wrong.

A drive of right-angle turns that spends most of its time on one street axis, logged at 10 Hz with 1 Hz fixes whose
errors are correlated (the phone analog's, ``tests/_held_out_drives.py``): a fused yaw negated but its zero left
142 degrees off was refused as "counter-clockwise from east", whose remedy made a heading that turns the wrong way,
which the reader then took (its median stretch fitted: that street's stretches); a logger's -1 for an unknown speed
was read as a car reversing; a raw gyro's 0.3 deg/s bias was named without the setting the phone grade needs, and
counted counter-clockwise it was refused as a clock offset; 1 Hz fixes reaching the log on its first row after them
were warned of as coming faster than one a second; epoch times written with 10 digits were refused as samples logged
twice; and the reader's warnings named a line of its own instead of the caller's
(``docs/study-outputs/dr/phone-log/``; ``docs/gps_dr.md``, "A phone's log").
"""

import os
import sys
import warnings

import numpy as np
import pytest

from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.gpsdr import GPSDRFilter
from filterwnn.navigation.scenarios import en_to_latlon

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _held_out_drives as held_out  # noqa: E402

LAT0, LON0 = 48.137, 11.575
AXIS = 30.0  # deg: the street the drive spends most of its time on
#: (seconds, speed at the end (m/s), turn over the segment (deg)): stops at lights, right-angle turns, most of the
#: driving along AXIS and its reverse
PLAN = [(8, 0, 0), (8, 12, 0), (40, 12, 0), (6, 6, 90), (6, 12, 0), (10, 12, 0), (6, 6, 90), (6, 12, 0),
        (40, 12, 0), (6, 0, 0), (30, 0, 0), (8, 12, 0), (45, 12, 0), (6, 6, -90), (6, 12, 0), (10, 12, 0),
        (6, 6, -90), (6, 12, 0), (40, 12, 0), (6, 0, 0), (60, 0, 0), (8, 12, 0), (40, 12, 0), (6, 6, 90),
        (6, 12, 0), (10, 12, 0), (6, 6, 90), (6, 12, 0), (40, 12, 0), (6, 0, 0), (10, 0, 0)]
COLUMNS = ["time", "heading_deg", "speed", "gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"]


def _grid_drive(seed=0, dt=0.1, jitter_rows=0):
    """The drive's columns: its clockwise heading (deg), speed, 1 Hz fixes with the phone analog's correlated
    errors and reported sigmas (each on the row ``0..jitter_rows`` after its time, drawn: a logger's), the truth."""
    rng = np.random.default_rng(seed)
    knots_t, knots_v, rates = [0.0], [0.0], []
    for secs, v_end, turn in PLAN:
        knots_t.append(knots_t[-1] + secs)
        knots_v.append(float(v_end))
        rates.append(turn / secs)
    t = np.arange(0.0, knots_t[-1], dt)
    v = np.interp(t, knots_t, knots_v)
    rate = np.asarray(rates)[np.minimum(np.searchsorted(knots_t, t, side="right") - 1, len(rates) - 1)]
    psi = np.deg2rad(AXIS) + np.cumsum(np.deg2rad(rate) * dt)
    e = np.r_[0.0, np.cumsum(v[:-1] * np.sin(psi[:-1]) * dt)]
    n = np.r_[0.0, np.cumsum(v[:-1] * np.cos(psi[:-1]) * dt)]
    fix_rows = np.flatnonzero(np.isclose(t % 1.0, 0.0) | np.isclose(t % 1.0, 1.0))
    err, reported = held_out.phone_fixes(rng, len(fix_rows))
    at = np.minimum(fix_rows + rng.integers(0, jitter_rows + 1, len(fix_rows)), len(t) - 1)
    glat, glon = en_to_latlon(e[fix_rows] + err[:, 0], n[fix_rows] + err[:, 1], LAT0, LON0)
    tlat, tlon = en_to_latlon(e, n, LAT0, LON0)
    cols = {"time": t, "heading_deg": np.mod(np.rad2deg(psi) + rng.normal(0.0, 0.2, len(t)), 360.0),
            "speed": v, "true_lat": tlat, "true_lon": tlon}
    for name, values in (("gps_lat", glat), ("gps_lon", glon), ("gps_sigma", reported)):
        cols[name] = np.full(len(t), np.nan)
        cols[name][at] = values
    return cols


def _write(path, cols, columns=COLUMNS):
    lines = [",".join(columns)]
    for k in range(len(cols["time"])):
        lines.append(",".join("" if np.isnan(cols[c][k]) else repr(float(cols[c][k])) for c in columns))
    path.write_text("\n".join(lines) + "\n")
    return str(path)


@pytest.fixture(scope="module")
def drive():
    return _grid_drive()


def test_the_drive_as_logged_reads(tmp_path, drive):
    run = read_drive_csv(_write(tmp_path / "d.csv", drive))
    assert len(run.gps_steps) == 496


def test_a_yaw_whose_zero_is_142_degrees_off_is_named_as_an_offset_not_as_counter_clockwise(tmp_path, drive):
    """The heading turns the right way; only its zero is off. Every stretch between fixes fits that offset, and
    about half of them (one street axis) the "counter-clockwise from east" the reader named before."""
    off = {**drive, "heading_deg": np.mod(drive["heading_deg"] - 142.0, 360.0)}
    with pytest.raises(ValueError, match=r"starts \+?-?14[0-4] .* heading_offset=-14[0-4] ") as info:
        read_drive_csv(_write(tmp_path / "off.csv", off))
    assert "counter-clockwise from east" not in str(info.value)
    read_drive_csv(_write(tmp_path / "off.csv", off), heading_offset=-142.0)  # the remedy reads it


def test_a_heading_that_turns_the_wrong_way_is_refused_even_where_its_median_stretch_fits(tmp_path, drive):
    """``60 - heading``: mirrored about the street axis (30 degrees), where the drive's stretches along the axis fit
    within 30 degrees (81 % of them, and so their median); turned the other way, every one fits. A phone's yaw
    negated and then "corrected" as counter-clockwise from east, ``90 - (heading - 142)``, was such a heading."""
    mirrored = {**drive, "heading_deg": np.mod(2 * AXIS - drive["heading_deg"], 360.0)}
    with pytest.raises(ValueError, match=r"but it fits \d+% of the stretches within 30 degrees, and 100% turned the "
                                         r"other way: the heading turns the wrong way .* give heading_deg = 60 - "
                                         r"yaw_deg"):
        read_drive_csv(_write(tmp_path / "mirrored.csv", mirrored))
    read_drive_csv(_write(tmp_path / "mirrored.csv", mirrored), checks=False)  # the override reads it


def test_a_loggers_minus_one_for_an_unknown_speed_is_refused_not_read_as_reversing(tmp_path, drive):
    marked = {**drive, "speed": np.where(drive["speed"] == 0.0, -1.0, drive["speed"])}
    path = _write(tmp_path / "m1.csv", marked)
    with pytest.raises(ValueError, match=r"the speed is exactly -1 on \d+ of its \d+ negative samples \(the first "
                                         r"speed\[0\] \(line 2\), 0 s after the first sample\): a logger's mark"):
        read_drive_csv(path)
    # a car that really reversed, at speeds of its own, is still read as reversing
    back = {**drive, "speed": np.where(drive["speed"] == 0.0, -np.linspace(0.5, 1.5, len(drive["speed"])),
                                       drive["speed"])}
    with pytest.warns(RuntimeWarning, match="the car reversed"):
        read_drive_csv(_write(tmp_path / "back.csv", back), checks=False)


def test_a_raw_gyros_bias_past_the_phone_grade_is_named_with_its_setting(tmp_path, drive):
    """A yaw rate 0.3 deg/s off: the reader names the drift, and, past three times the phone grade's 0.05 deg/s,
    the ``--gyro-bias`` to give, with the phone grade (the survey grade refuses it: it has no rate-bias state)."""
    h = np.unwrap(np.deg2rad(drive["heading_deg"]))
    rate = np.gradient(h, drive["time"]) + np.deg2rad(0.3)
    cols = {**drive, "yaw_rate_deg": np.rad2deg(rate)}
    columns = ["time", "yaw_rate_deg"] + COLUMNS[2:]
    with pytest.warns(RuntimeWarning, match=r"drifting \+0.3 deg/s .* past 3 times the phone grade's 0.05 deg/s .* "
                                            r"\(--grade phone --gyro-bias 0.3; the survey grade has no state to "
                                            r"take it\)") as seen:
        read_drive_csv(_write(tmp_path / "gyro.csv", cols, columns))
    assert all(w.filename == __file__ for w in seen), [w.filename for w in seen]  # the caller's line, not ours


def test_a_raw_gyros_rate_counted_counter_clockwise_is_named_so_not_as_a_clock_offset(tmp_path, drive):
    """The same yaw rate as logged, counter-clockwise: its heading, turned the other way, fits the fixes as a
    drifting gyro's does; until stop 58 the refusal named a clock offset of the fixes instead."""
    h = np.unwrap(np.deg2rad(drive["heading_deg"]))
    rate = -(np.gradient(h, drive["time"]) + np.deg2rad(0.3))
    cols = {**drive, "yaw_rate_deg": np.rad2deg(rate)}
    with pytest.raises(ValueError, match="the yaw rate turns the wrong way") as info:
        read_drive_csv(_write(tmp_path / "ccw.csv", cols, ["time", "yaw_rate_deg"] + COLUMNS[2:]))
    assert "clock offset" not in str(info.value)


def test_a_gyros_wrong_axis_is_refused_as_a_heading_that_does_not_follow_the_turns(tmp_path, drive):
    """A phone upright on a dashboard mount turns with the car about its y axis; its z axis, given as the yaw rate,
    reads a pitch's wobble. Started at the fixes' course and drifting within a gyro's bias, such a heading was read,
    and a second new user's drive so read ended its outages 122.84 / 809.64 m off (stop 58); over the fixes' turns
    it turns 0.09 times as much, where every other drive tried turns 0.68-1.15."""
    rng = np.random.default_rng(3)
    wobble = 0.3 * np.sin(2 * np.pi * drive["time"] / 7.0) + rng.normal(0.0, 0.2, len(drive["time"]))  # deg/s
    cols = {**drive, "yaw_rate_deg": wobble}
    with pytest.raises(ValueError, match=r"over \d+ turns of the fixes' course .* the dead-reckoned course turned "
                                         r"-?0\.\d+ times as much: the heading does not follow the car's turns"):
        read_drive_csv(_write(tmp_path / "z.csv", cols, ["time", "yaw_rate_deg"] + COLUMNS[2:]))
    with pytest.warns(RuntimeWarning, match="integrated from"):  # the override reads it, and names its start
        read_drive_csv(_write(tmp_path / "z.csv", cols, ["time", "yaw_rate_deg"] + COLUMNS[2:]), checks=False)


def test_a_speed_that_reads_0_where_the_fixes_move_is_named_so(tmp_path, drive):
    """An OBD logger's local time read as UTC put its speed hours from the drive: 0 on every sample, refused until
    stop 58 as a yaw rate turning the wrong way (and a bare numpy warning of a log of 0)."""
    cols = {**drive, "speed": np.zeros(len(drive["time"]))}
    with warnings.catch_warnings(record=True) as seen, \
            pytest.raises(ValueError, match=r"the speed moves the dead-reckoned track 0 times the fixes' distance: it "
                                            r"reads 0, or nearly, where the fixes move"):
        warnings.simplefilter("always")
        read_drive_csv(_write(tmp_path / "still.csv", cols))
    assert not [w for w in seen if "divide by zero" in str(w.message)]


def test_epoch_times_written_with_too_few_digits_are_named_so(tmp_path, drive):
    """An epoch in seconds written with 10 significant digits repeats each second's stamp on its ten rows: refused
    naming the digits, not as samples logged twice."""
    cols = {**drive, "time": np.round(1715674893.156 + drive["time"])}
    with pytest.raises(ValueError, match=r"t\[1\] \(line 3\) .* as times written with 10 significant digits are"):
        read_drive_csv(_write(tmp_path / "t.csv", cols))


@pytest.fixture(scope="module")
def late_fixes(tmp_path_factory):
    """The drive with each fix on the row 0-3 samples after its time, through the phone grade's EKF-8: the
    filter and the warnings it gave."""
    run = read_drive_csv(_write(tmp_path_factory.mktemp("late") / "late.csv", _grid_drive(jitter_rows=3)))
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
    return run, f, [str(w.message) for w in seen]


def test_one_hz_fixes_reaching_the_log_late_are_not_warned_of_as_faster_than_one_a_second(late_fixes):
    """Each fix on the row 0-3 samples after its time: ten gaps' median is often 0.9 s, their mean 1 s."""
    run, f, said = late_fixes
    gaps = np.diff(run.gps_steps)
    assert gaps.min() < 9 and gaps.max() > 11  # they do reach it late
    assert f.gps_correlation_mean > 1.5  # correlated, so a fast stream would be warned of
    assert not [m for m in said if "fixes come every" in m]


def test_an_inconsistency_among_correlated_fixes_gives_the_drives_mean_nis_beside_it(late_fixes):
    """The fixes' errors correlated over 20 s (``gps_correlation`` about 6): a window of 30 holds about 5
    independent ones and passes its white bound more often; the warning says so, with the mean NIS so far."""
    run, f, said = late_fixes
    inconsistent = [m for m in said if "is inconsistent" in m]
    assert inconsistent
    for m in inconsistent:
        assert "Its fixes' errors are correlated (gps_correlation" in m and "fixes accepted so far is" in m, m


def test_a_yaw_rate_in_rad_s_given_as_deg_s_is_named_so(tmp_path, drive):
    """A ROS Imu's angular_velocity.z (rad/s, negated to clockwise) written into ``yaw_rate_deg``: its integral turns
    pi / 180 of the car's turns. Until stop 59 it was refused as a yaw rate turning the wrong way."""
    h = np.unwrap(np.deg2rad(drive["heading_deg"]))
    cols = {**drive, "yaw_rate_deg": np.gradient(h, drive["time"]) + np.deg2rad(0.3)}  # rad/s
    with pytest.raises(ValueError, match=r"turned 0\.0\d+ times as much, and (0\.[6-9]\d*|1|1\.[0-3]\d*) times as much "
                                         r"read as radians a second: the yaw rate looks like radians a second given "
                                         r"as degrees a second") as info:
        read_drive_csv(_write(tmp_path / "rad.csv", cols, ["time", "yaw_rate_deg"] + COLUMNS[2:]))
    assert "wrong way" not in str(info.value)
    with pytest.warns(RuntimeWarning, match="integrated from"):  # given as yaw_rate, it reads
        read_drive_csv(_write(tmp_path / "rad.csv", {**cols, "yaw_rate": cols["yaw_rate_deg"]},
                              ["time", "yaw_rate"] + COLUMNS[2:]))
    # as ROS writes it, counter-clockwise, in yaw_rate: turning the wrong way, not a unit (a right-angle turn the
    # wrong way reads as any turn ratio, magnified too: the first form of the unit's test named it so)
    with pytest.raises(ValueError, match="the yaw rate turns the wrong way") as info:
        read_drive_csv(_write(tmp_path / "ccw.csv", {**cols, "yaw_rate": -cols["yaw_rate_deg"]},
                              ["time", "yaw_rate"] + COLUMNS[2:]))
    assert "radians a second" not in str(info.value)


def test_a_speed_in_km_h_with_a_drifting_gyro_is_named_as_km_h(tmp_path, drive):
    """Wheel speeds left in km/h beside a yaw rate 0.3 deg/s off: the track is 3.6 times the fixes' length and its
    angle the gyro's drift. Until stop 59 the refusal named the heading's zero and sign, not the unit."""
    h = np.unwrap(np.deg2rad(drive["heading_deg"]))
    cols = {**drive, "yaw_rate_deg": np.rad2deg(np.gradient(h, drive["time"]) + np.deg2rad(0.3)),
            "speed": 3.6 * drive["speed"]}
    with pytest.raises(ValueError, match=r"speed looks like km/h \(divide by 3.6 for m/s, or pass speed_scale=3.6: "
                                         r"--speed-scale 3.6\); the angle is a gyro's drift"):
        read_drive_csv(_write(tmp_path / "kmh.csv", cols, ["time", "yaw_rate_deg"] + COLUMNS[2:]))


def _fix_rows(drive, shift, repeat=0.0):
    """The drive with its fixes on rows of their own at their time plus ``shift`` (s), and, with ``repeat``, each
    fix again ``repeat`` s later (a 5 Hz receiver's next fix, stamped by a logger on receipt)."""
    fix = ~np.isnan(drive["gps_lat"])
    t = [drive["time"], drive["time"][fix] + shift] + ([drive["time"][fix] + shift + repeat] if repeat else [])
    out = {"time": np.concatenate(t)}
    for c in COLUMNS[1:]:
        dr = np.where(fix, np.nan, drive[c]) if c.startswith("gps_") else drive[c]
        fixes = np.where(fix, drive[c], np.nan)[fix] if c.startswith("gps_") else np.full(fix.sum(), np.nan)
        out[c] = np.concatenate([dr, fixes] + ([fixes] if repeat else []))
    order = np.argsort(out["time"], kind="stable")
    return {c: v[order] for c, v in out.items()}


def test_fixes_on_another_clock_are_refused_naming_both_spans(tmp_path, drive):
    """NMEA's UTC time of day (9 h) beside a logger's time from its start: every fix lies past the samples. Until
    stop 59 the refusal said the drive had no moving stretches between fixes; a few outside are warned of."""
    with pytest.raises(ValueError, match=r"lie outside the DR samples' time span \(the fixes' times run 32\d+.* the "
                                         r"DR samples' 0-\d+.* s\): the fixes and the samples are on two clocks"):
        read_drive_csv(_write(tmp_path / "utc.csv", _fix_rows(drive, 32400.0)))
    cols = _fix_rows(drive, 0.0)
    late = {c: np.r_[v, np.nan if c != "time" else v[-1] + 5.0] for c, v in cols.items()}  # a last fix 5 s on
    for c in ("gps_lat", "gps_lon", "gps_sigma"):
        late[c][-1] = late[c][np.flatnonzero(~np.isnan(late[c]))[-1]]
    with pytest.warns(RuntimeWarning, match=r"1 GPS fix\(es\) lie outside the DR samples' time span"):
        read_drive_csv(_write(tmp_path / "late.csv", late))


def test_fixes_that_share_a_sample_are_warned_of(tmp_path, drive):
    """A fix again 0.03 s after each (a 5 Hz receiver's stamps on a 10 Hz log): one of each pair was dropped with
    nothing said until stop 59."""
    with pytest.warns(RuntimeWarning, match=r"\d+ GPS fix\(es\) share their nearest DR sample with an earlier fix"):
        read_drive_csv(_write(tmp_path / "pairs.csv", _fix_rows(drive, 0.0, repeat=0.03)))


def test_a_tunnels_null_fixes_with_no_accuracy_are_dropped_not_refused(tmp_path, drive):
    """A receiver in a tunnel writes its fixes as lat = lon = 0 with an empty accuracy; until stop 59 the reader
    refused the drive as a fix without its accuracy. They are null fixes, dropped with the warning."""
    cols = {c: v.copy() for c, v in drive.items()}
    rows = np.flatnonzero(~np.isnan(cols["gps_lat"]))[100:130]
    cols["gps_lat"][rows] = cols["gps_lon"][rows] = 0.0
    cols["gps_sigma"][rows] = np.nan
    with pytest.warns(RuntimeWarning, match=r"dropped 30 GPS fix\(es\) at lat = lon = 0"):
        run = read_drive_csv(_write(tmp_path / "tunnel.csv", cols))
    assert len(run.gps_steps) == int(np.sum(~np.isnan(drive["gps_lat"]))) - 30 - 1  # (the first row's has no step)


def test_a_5_hz_receivers_course_or_speed_on_a_10_hz_log_is_warned_of(tmp_path, drive):
    """A 5 Hz receiver's RMC course (or speed) given as the heading (or speed) of a 10 Hz log: it changes at every
    fix and holds between, and outages cut into the drive are scored with the withheld fixes' course. With a fix
    every other sample a change beside a fix is no sign, and until stop 59 nothing was said (a user's EKF-8 then
    ended 25.83 / 639.97 m off while DR-mech read 2.35 / 20.67); the heading and speed as logged are not warned of."""
    cols = {c: v.copy() for c, v in drive.items()}
    rng = np.random.default_rng(7)
    fix = np.arange(len(cols["time"])) % 2 == 0
    for c, truth in (("gps_lat", "true_lat"), ("gps_lon", "true_lon")):
        cols[c] = np.where(fix, cols[truth] + rng.normal(0.0, 1e-5, len(fix)), np.nan)
    cols["gps_sigma"] = np.where(fix, 2.0, np.nan)
    held = np.flatnonzero(fix)[np.cumsum(fix) - 1]  # each row's last fix row
    for column, what in (("heading_deg", "heading"), ("speed", "speed")):
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            read_drive_csv(_write(tmp_path / "ok.csv", cols))
        assert not any("changes only where there is a GPS fix" in str(w.message) for w in seen)
        rmc = {**cols, column: cols[column][held]}
        with pytest.warns(RuntimeWarning, match=f"the {what} changes only where there is a GPS fix"):
            read_drive_csv(_write(tmp_path / "rmc.csv", rmc))
