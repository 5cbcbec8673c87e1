"""Fixes' accuracy in another unit than metres, a u-blox log's scaled integers, and warnings a user can find in
their own log (stop 60).

A u-blox receiver's ``hAcc`` is in millimetres, other loggers write centimetres, and a ROS ``NavSatFix`` gives a
variance: in ``gps_sigma`` each makes every fix claim a hundred to a thousand times its error, and the filters all
but ignore the fixes. On the 1 Hz analog (seed 0) in millimetres the EKF-8 ended its outages 81.62 / 143.69 m off
(1.63 / 6.28 m in metres) with no word; the city analog's sigmas given as variances, 18.56 / 45.00 (16.43 / 26.30).
The reader now refuses such a column, naming the units, and the filter warns when its fixes' innovations are far
inside their sigma (``docs/gps_dr.md``, "Each fix's accuracy as receivers report it"). A u-blox receiver's UBX
messages also give latitude and longitude in 1e-7 degrees, the speed in mm/s and the heading of motion in 1e-5
degrees: each was refused with no cause named ("check the units of speed/odometer and time") or with the wrong one
("name the column heading_deg" to a heading_deg column); each is named now. The study's warnings name each step's
time on the drive's own clock.
"""

import os
import subprocess
import sys
import warnings

import numpy as np
import pytest

from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.scenarios import DRRun, en_to_latlon
from filterwnn.navigation.gpsdr import NIS_FAR_BELOW, GPSDRFilter
from filterwnn.navigation.dead_reckoning import GPSDRModel

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _held_out_drives as held_out  # noqa: E402


def _drive(tmp_path, name, sigma, seconds=None, t0=0.0):
    """Analog ``name`` (seed 0) with its fixes' sigmas mapped by ``sigma``, its first ``seconds``, written."""
    cols = held_out.columns(name, 0)
    if seconds is not None:
        cols = {k: v[cols["time"] < seconds] for k, v in cols.items()}
    cols["gps_sigma"] = sigma(cols["gps_sigma"])
    cols["time"] = cols["time"] + t0
    return held_out.write_csv(tmp_path / f"{name}.csv", cols)


@pytest.mark.parametrize("name, sigma, unit", [
    ("one_hz", lambda s: 1000.0 * s, "millimetres"),
    ("one_hz", lambda s: 100.0 * s, "centimetres"),
    ("city", lambda s: s * s, "variance")])
def test_an_accuracy_column_not_in_metres_is_refused_with_the_units(tmp_path, name, sigma, unit):
    """The 1 Hz analog's 3-5 m fixes in millimetres and centimetres, the city analog's 5-30 m ones as variances:
    refused, the line naming the median sigma, how many times the fixes' scatter it is, and each unit's remedy."""
    with pytest.raises(ValueError, match="gps_sigma is a standard deviation per axis in metres") as info:
        read_drive_csv(_drive(tmp_path, name, sigma))
    said = str(info.value)
    assert unit in said and "times what they scatter" in said and "--no-plausibility" in said, said


def test_honest_accuracies_and_harmless_variances_are_read():
    """Every analog (seeds 0-2) with its sigmas in metres, and the 1 Hz analog's as variances (9-25 m^2, 2-7 times
    its fixes' scatter: a little pessimistic, which made its outages no worse), are read without that refusal."""
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as tmp:
        for name in held_out.HELD_OUT:
            for seed in (0, 1, 2):
                cols = held_out.columns(name, seed)
                read_drive_csv(held_out.write_csv(Path(tmp) / "d.csv", cols))
        read_drive_csv(_drive(Path(tmp), "one_hz", lambda s: s * s))


def _filter_warnings(run):
    """The phone grade's EKF-8 over the drive, with each fix's own sigma, and its warnings."""
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    return f, [str(w.message) for w in record]


def test_the_filter_warns_once_when_its_fixes_sigma_is_far_past_their_errors(tmp_path):
    """Read past the check (``checks=False``), the 1 Hz analog's first 300 s in millimetres: the consistency monitor
    finds a window's mean NIS under NIS_FAR_BELOW at the 30th fix and warns once, naming the units; in metres, and
    as (harmless) variances, it does not."""
    def far_below(said):
        return [s for s in said if f"under {NIS_FAR_BELOW:g} (2 expected)" in s]

    f, said = _filter_warnings(read_drive_csv(_drive(tmp_path, "one_hz", lambda s: 1000.0 * s, 300.0),
                                              checks=False))
    low = far_below(said)
    assert len(low) == 1 and "millimetres" in low[0] and "median 4" in low[0], said
    assert f.nis_low_step is not None and f.nis_low_step < 40, f.nis_low_step
    for sigma in (lambda s: s, lambda s: s * s):
        f, said = _filter_warnings(read_drive_csv(_drive(tmp_path, "one_hz", sigma, 300.0)))
        assert not far_below(said) and f.nis_low_step is None, said


def test_the_commands_warnings_name_each_step_on_the_drives_own_clock(tmp_path):
    """A log whose clock starts at 45000 s (a time of day): the command's warnings follow each step they name with
    its time there, at which the user finds it in the log."""
    path = _drive(tmp_path, "one_hz", lambda s: 1000.0 * s, 300.0, t0=45000.0)
    out = subprocess.run([sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--grade", "phone",
                          "--no-plausibility", "--filters", "EKF-8", "--no-figures", "--out", str(tmp_path / "out")],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    lines = [s for s in out.stderr.splitlines() if "mean NIS" in s and "under" in s]
    assert len(lines) == 1 and "at step 29 (t = 45030 s)" in lines[0], out.stderr


def _write(path, cols):
    names = list(cols)
    with open(path, "w") as fh:
        fh.write(",".join(names) + "\n")
        for k in range(len(cols["time"])):
            fh.write(",".join("" if np.isnan(cols[c][k]) else f"{cols[c][k]:.10g}" for c in names) + "\n")
    return str(path)


@pytest.mark.parametrize("column, factor, words", [
    ("speed", 1000.0, "speed looks like mm/s (divide by 1000"),
    ("speed", 100.0, "speed looks like cm/s (divide by 100"),
    ("heading_deg", 1e5, "it reads as 1e-5 degrees (u-blox's headMot and headVeh): divide by 1e5"),
    ("heading_deg", 100.0, "it reads as centidegrees: divide by 100")])
def test_a_ublox_logs_scaled_speed_and_heading_are_named(tmp_path, column, factor, words):
    """The 1 Hz analog's first 600 s with its speed in mm/s or cm/s (gSpeed), or its heading in 1e-5 degrees or
    centidegrees (headMot) in ``heading_deg``: refused, naming the unit and its factor."""
    cols = {k: v[:600] for k, v in held_out.columns("one_hz", 0).items()}
    cols = {"time": cols["time"], "heading_deg": np.degrees(cols["heading"]), "speed": cols["speed"],
            "gps_east": cols["gps_east"], "gps_north": cols["gps_north"], "gps_sigma": cols["gps_sigma"]}
    cols[column] = cols[column] * factor
    with pytest.raises(ValueError) as info:
        read_drive_csv(_write(tmp_path / "d.csv", cols))
    assert words in str(info.value), str(info.value)


def test_a_ublox_logs_latitude_and_longitude_in_1e_7_degrees_are_named():
    """UBX's lat and lon are integers of 1e-7 degrees: refused, naming them and the division (were refused as past
    degrees, no cause named); NMEA's ddmm.mmmm is still named as such."""
    cols = {k: v[:600] for k, v in held_out.columns("one_hz", 0).items()}
    fix = np.isfinite(cols["gps_east"])
    lat, lon = en_to_latlon(cols["gps_east"][fix], cols["gps_north"][fix], 48.137, 11.575)
    args = dict(speed=cols["speed"], gps_t=cols["time"][fix])
    with pytest.raises(ValueError, match=r"read as degrees times 1e7 .*: divide by 1e7"):
        DRRun.from_arrays(cols["time"], cols["heading"], lat=np.round(lat * 1e7), lon=np.round(lon * 1e7), **args)
    with pytest.raises(ValueError, match="NMEA's degrees and minutes"):
        DRRun.from_arrays(cols["time"], cols["heading"], lat=np.floor(lat) * 100 + 60 * (lat % 1),
                          lon=np.floor(lon) * 100 + 60 * (lon % 1), **args)


def _ublox_cols(seconds=600.0):
    """The phone analog's first ``seconds`` (10 Hz samples, 1 Hz fixes) as a u-blox ADR user converts it: its
    heading's rate as ``yaw_rate_deg`` (deg/s, clockwise), its cumulative distance as ``odometer``, the fixes in metres
    with their sigmas."""
    cols = held_out.columns("phone", 0)
    c = {k: v[cols["time"] < seconds] for k, v in cols.items()}
    t = c["time"]
    rate = np.r_[0.0, np.degrees(np.diff(np.unwrap(c["heading"]))) / np.diff(t)]
    odo = np.r_[0.0, np.cumsum(0.5 * (c["speed"][1:] + c["speed"][:-1]) * np.diff(t))]
    return {"time": t, "yaw_rate_deg": rate, "odometer": odo, "gps_east": c["gps_east"],
            "gps_north": c["gps_north"], "gps_sigma": c["gps_sigma"]}


@pytest.mark.parametrize("fault, words", [
    ("raw gyro", "it reads as u-blox ESF-MEAS's raw gyro field, in 2^-12 deg/s: divide by 4096"),
    ("unsigned gyro", "a signed 24-bit field (u-blox ESF-MEAS's gyro, 2^-12 deg/s) read unsigned"),
    ("ticks", "the speed or the odometer is in another unit: the dead-reckoned track is"),
    ("tick wrap", "a counter that wrapped (add its range back to every reading after it"),
    ("distance a sample", "the speed column holds each sample's distance (m), not m/s"),
    ("sttag wrap", "is a 32-bit millisecond counter (u-blox ESF's sTtag, a logger's tick) that wrapped"),
    ("itow wrap", "is the GPS week's seconds (iTOW, the time of week, at the week's end) that wrapped; add 604800"),
    ("hacc mm", "gps_sigma is a standard deviation per axis in metres; a column in millimetres")])
def test_a_ublox_adr_logs_conversion_mistakes_are_named(tmp_path, fault, words):
    """A u-blox ADR module's ESF-MEAS gyro (a signed 24-bit field of 2^-12 deg/s) and wheel ticks (23-bit counters),
    its sensor clock (sTtag, ms, wrapping at 2^32) and NAV-PVT's iTOW (wrapping at the GPS week) and hAcc (mm), each
    left unconverted as a user did (a new user's log, ``docs/study-outputs/dr/ublox-log/``): refused naming the
    field and the remedy. Before stop 60 they were named as degrees per second to a column already so named, as the
    heading's zero, as a gap that --fill-gaps closes, as a cumulative odometer that fell, and (with a yaw rate) as a
    drive with no moving stretch between fixes."""
    cols = _ublox_cols()
    if fault == "raw gyro":
        cols["yaw_rate_deg"] = np.round(cols["yaw_rate_deg"] * 4096.0)
    elif fault == "unsigned gyro":
        cols["yaw_rate_deg"] = np.where(cols["yaw_rate_deg"] < 0, cols["yaw_rate_deg"] + 4096.0, cols["yaw_rate_deg"])
    elif fault == "ticks":
        cols["odometer"] = np.round(cols["odometer"] * 50.0)  # 50 ticks a metre
    elif fault == "tick wrap":
        ticks = np.round(cols["odometer"] * 50.0 + 2**23 - 20000) % 2**23
        cols["odometer"] = ticks / 50.0
    elif fault == "distance a sample":
        step = np.diff(cols.pop("odometer"), prepend=0.0)
        cols = {"time": cols["time"], "yaw_rate_deg": cols["yaw_rate_deg"], "speed": step,
                **{k: cols[k] for k in ("gps_east", "gps_north", "gps_sigma")}}
    elif fault == "sttag wrap":
        cols["time"] = (cols["time"] + 2**32 / 1e3 - 300.0) % (2**32 / 1e3)
        order = np.argsort(cols["time"])  # (the rows sorted by the wrapped clock)
        cols = {k: v[order] for k, v in cols.items()}
    elif fault == "itow wrap":
        cols["time"] = (cols["time"] + 604800.0 - 300.0) % 604800.0
    elif fault == "hacc mm":
        cols["gps_sigma"] = np.round(cols["gps_sigma"] * 1000.0 * np.sqrt(2.0))
    with pytest.raises(ValueError) as info:
        read_drive_csv(_write(tmp_path / "d.csv", cols))
    assert words in str(info.value), str(info.value)
    if fault == "hacc mm":  # past the checks, the yaw rate's start is found from the fixes' stretches of 3 m
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            run = read_drive_csv(_write(tmp_path / "d.csv", cols), checks=False)
        assert np.median(run.gps_sigma) > 1000.0


def test_fixes_stamped_in_milliseconds_beside_samples_in_seconds_are_named():
    """NAV-PVT's iTOW is in milliseconds: fixes so stamped beside DR samples in seconds were refused as on two
    clocks; the refusal now names the milliseconds (a clock that is another, as NMEA's time of day beside a logger's
    time from its start, is still named so)."""
    cols = _ublox_cols()
    fix = np.isfinite(cols["gps_east"])
    t = cols["time"] + 400000.0
    args = dict(speed=np.gradient(cols["odometer"], cols["time"]), east=cols["gps_east"][fix],
                north=cols["gps_north"][fix])
    with pytest.raises(ValueError, match=r"the fixes' times look like milliseconds \(divided by 1000 they lie"):
        DRRun.from_arrays(t, np.zeros(len(t)), gps_t=t[fix] * 1000.0, **args)
    with pytest.raises(ValueError, match="on two clocks"):
        DRRun.from_arrays(t, np.zeros(len(t)), gps_t=t[fix] - 3600.0, **args)


def test_a_clock_two_seconds_off_is_warned_of_with_the_setting(tmp_path):
    """The phone analog (seed 1) with its fixes stamped 2 s late (a sensor clock put on GPS time 2 s off, as the
    u-blox log's): warned of with ``gps_latency=2`` (from stop 60 past 1 s; the filters take such an offset only once
    their monitor finds it, and on the u-blox log 2 s off ended the outages 4.90 / 48.84 m off, 3.36 / 15.35 m with
    the setting); 1 s late, as on time, no warning."""
    for late, want in ((2.0, True), (1.0, False), (0.0, False)):
        path = held_out.write_csv(tmp_path / "d.csv", held_out.columns("phone", 1, gps_latency=late))
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            read_drive_csv(path)
        said = [str(w.message) for w in record if "a clock offset between the fixes" in str(w.message)]
        assert bool(said) == want and (not want or "gps_latency=2 " in said[0]), (late, said)


def test_an_hacc_column_is_named_back_as_gps_sigma_with_its_millimetres(tmp_path):
    """A column named as u-blox names the accuracy, ``hAcc``, is not read; the warning names ``gps_sigma`` for it, and
    its millimetres."""
    cols = _ublox_cols(120.0)
    cols["hAcc"] = cols.pop("gps_sigma") * 1000.0
    with pytest.warns(RuntimeWarning, match=r"'hacc' may be 'gps_sigma' .*\(u-blox's hAcc is in millimetres: divide "
                                            r"by 1000\): rename it so"):
        read_drive_csv(_write(tmp_path / "d.csv", cols))
