"""Drive files that are well-formed but wrong, or written by other tools: plausibility checks
against the GPS fixes, delimiters, a byte-order mark, NaN cells, short files, a large file."""

import os
import re
import subprocess
import sys
import warnings

import numpy as np
import pytest

from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.scenarios import DRRun, en_to_latlon, with_outage

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _held_out_drives as held_out  # noqa: E402

LAT0, LON0 = 48.137, 11.575
COLUMNS = ["time", "heading", "speed", "gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"]


def _drive(n=1201, dt=0.1, v=10.0, bearing=0.6, turn=0.02, sigma=3.0, seed=0):
    """A gently turning drive: 10 Hz heading and speed, 1 Hz fixes (noise ``sigma``), the truth."""
    rng = np.random.default_rng(seed)
    t = dt * np.arange(n)
    h = np.mod(bearing + turn * t, 2 * np.pi)  # a heading in [0, 2 pi), as a gyro reports it
    e = np.r_[0.0, np.cumsum(v * dt * np.sin(h[1:]))]
    nn = np.r_[0.0, np.cumsum(v * dt * np.cos(h[1:]))]
    tlat, tlon = en_to_latlon(e, nn, LAT0, LON0)
    glat, glon = en_to_latlon(e + sigma * rng.standard_normal(n), nn + sigma * rng.standard_normal(n), LAT0, LON0)
    fix = np.arange(n) % 10 == 0
    return {"time": t, "heading": h, "speed": np.full(n, v), "gps_lat": np.where(fix, glat, np.nan),
            "gps_lon": np.where(fix, glon, np.nan), "gps_sigma": np.where(fix, sigma, np.nan),
            "true_lat": tlat, "true_lon": tlon}


def _write(path, cols, sep=",", bom=False, columns=COLUMNS, header=None):
    lines = [sep.join(header or columns)]
    for k in range(len(cols["time"])):
        lines.append(sep.join("" if np.isnan(cols[c][k]) else repr(float(cols[c][k])) for c in columns))
    path.write_text(("\ufeff" if bom else "") + "\n".join(lines) + "\n", encoding="utf-8")
    return str(path)


def test_a_plain_drive_passes_and_the_sample_drive_too(tmp_path):
    run = read_drive_csv(_write(tmp_path / "d.csv", _drive()))
    assert run.scenario.dt == 0.1 and len(run.gps_steps) == 120
    from filterwnn.navigation.drives import sample_drive_path

    read_drive_csv(sample_drive_path())  # checks on


def test_a_drifting_gyro_passes_and_a_wrong_heading_zero_does_not(tmp_path):
    """21 minutes of a 0.05 deg/s rate bias integrated (63 degrees at the end, a median chord
    angle over 30) is a gyro's drift the filters estimate; a constant 60 degree offset is not."""
    cols = _drive(n=1261, dt=1.0, turn=0.02)
    drift = {**cols, "heading": np.mod(cols["heading"] + np.deg2rad(0.05) * cols["time"], 2 * np.pi)}
    read_drive_csv(_write(tmp_path / "drift.csv", drift))
    wrong = {**cols, "heading": np.mod(cols["heading"] + np.deg2rad(60.0), 2 * np.pi)}
    with pytest.raises(ValueError, match="degrees off the fixes' course"):
        read_drive_csv(_write(tmp_path / "zero.csv", wrong))


def _read_quietly(path, **kw):
    """``read_drive_csv(path, **kw)``, any warning an error."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return read_drive_csv(path, **kw)


def test_a_heading_zero_off_is_warned_with_its_value_and_the_remedy_reads_it_back(tmp_path):
    """A heading whose zero is off by a constant (a phone mounted askew, a magnetic heading): up to 10
    degrees nothing is said; 15 degrees is warned with the offset the fixes show (+15, +- 1) and the
    reader's remedy, heading_offset=15, which gives back the clean drive's headings; past 30 degrees the
    refusal names the same remedy, and the remedy reads it. A gyro's drift is no offset: 0.05 deg/s over
    21 minutes is not warned."""
    cols = _drive(n=1261, dt=1.0, turn=0.02)
    clean = read_drive_csv(_write(tmp_path / "clean.csv", cols))

    def off(deg):
        return {**cols, "heading": np.mod(cols["heading"] + np.deg2rad(deg), 2 * np.pi)}

    _read_quietly(_write(tmp_path / "5.csv", off(5.0)))
    drift = {**cols, "heading": np.mod(cols["heading"] + np.deg2rad(0.05) * cols["time"], 2 * np.pi)}
    _read_quietly(_write(tmp_path / "drift.csv", drift))
    path = _write(tmp_path / "15.csv", off(15.0))
    with pytest.warns(RuntimeWarning, match=r"the dead-reckoned course starts \+15 \+- [0-9.]+ degrees off the fixes'.*"
                                            r"pass heading_offset=15 \(command line: --heading-offset 15\)"):
        read_drive_csv(path)
    told = _read_quietly(path, heading_offset=15.0)
    np.testing.assert_allclose(np.angle(np.exp(1j * (told.z_dr[:, 0] - clean.z_dr[:, 0]))), 0.0, atol=1e-9)
    path = _write(tmp_path / "-90.csv", off(-90.0))
    with pytest.raises(ValueError, match=r"degrees off the fixes' course .* starts -90 .* heading_offset=-90 .*"
                                         r"else check the heading's zero"):
        read_drive_csv(path)
    read_drive_csv(path, heading_offset=-90.0)
    with pytest.raises(ValueError, match="heading_offset must be a finite number of degrees"):
        read_drive_csv(path, heading_offset=float("nan"))


def test_a_speed_that_reads_high_is_warned_with_its_scale_and_the_remedy_divides_it_out(tmp_path):
    """A speed 12 % high (a speedometer's signal may read up to 10 % high; past the phone grade's 3 % sigma
    held within three): warned with the ratio the fixes show and speed_scale=, which gives back the clean
    drive's steps; 4 % (within the grade) is not warned."""
    cols = _drive(n=1261, dt=1.0, turn=0.02)
    clean = read_drive_csv(_write(tmp_path / "clean.csv", cols))
    _read_quietly(_write(tmp_path / "4.csv", {**cols, "speed": cols["speed"] * 1.04}))
    path = _write(tmp_path / "12.csv", {**cols, "speed": cols["speed"] * 1.12})
    with pytest.warns(RuntimeWarning, match=r"the dead-reckoned distance is 1\.1[12] times the fixes' .* reads \+1[12] % .*"
                                            r"pass speed_scale=1\.1[12] \(command line: --speed-scale 1\.1[12]\)"):
        read_drive_csv(path)
    told = _read_quietly(path, speed_scale=1.12)
    np.testing.assert_allclose(told.z_dr, clean.z_dr, rtol=1e-12, atol=1e-12)
    short = {k: v[:101] for k, v in _drive().items()}  # 100 m, 4 chords: their spread says nothing of their error
    _read_quietly(_write(tmp_path / "short.csv", {**short, "speed": short["speed"] * 1.12,
                                                 "heading": np.mod(short["heading"] + np.deg2rad(15.0), 2 * np.pi)}))
    with pytest.raises(ValueError, match="speed_scale must be finite and > 0"):
        read_drive_csv(path, speed_scale=0.0)


def test_a_drive_whose_only_fix_is_its_start_reads_without_a_numpy_warning():
    """The first fix gives the start and is not a fix to filter: with no other, the check had taken the median
    of no sigmas (numpy's "Mean of empty slice")."""
    t = np.arange(0.0, 5.0, 0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run = DRRun.from_arrays(t, np.full(len(t), 0.5), speed=np.full(len(t), 5.0), gps_t=[0.0], east=[0.0],
                                north=[0.0], gps_sigma=[3.0])
    assert len(run.gps_steps) == 0


def _arrays(minutes=20.0, dt=0.1, v=12.0, fix_every=10, sigma=4.0, drift=0.0, jumps=0.0, seed=0):
    """A gently turning drive as DRRun.from_arrays' keywords: heading drifting ``drift`` deg/s, fixes every
    ``fix_every`` samples with white noise ``sigma`` and a fraction ``jumps`` of them 40-80 m off."""
    rng = np.random.default_rng(seed)
    t = dt * np.arange(int(round(60.0 * minutes / dt)) + 1)
    h = 0.6 + 0.5 * np.sin(t / 40.0)
    e = np.r_[0.0, np.cumsum(v * dt * np.sin(h[1:]))]
    nn = np.r_[0.0, np.cumsum(v * dt * np.cos(h[1:]))]
    k = np.arange(fix_every, len(t), fix_every)
    err = sigma * rng.standard_normal((len(k), 2))
    jumped = rng.random(len(k)) < jumps
    ang = rng.uniform(0.0, 2 * np.pi, len(k))
    err += (jumped * rng.uniform(40.0, 80.0, len(k)))[:, None] * np.stack([np.sin(ang), np.cos(ang)], axis=1)
    return dict(t=t, heading=np.mod(h + np.deg2rad(drift) * t, 2 * np.pi), speed=np.full(len(t), v),
                gps_t=t[k], east=e[k] + err[:, 0], north=nn[k] + err[:, 1], gps_sigma=np.full(len(k), sigma))


def _quiet(**kw):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return DRRun.from_arrays(**kw)


def test_a_drive_without_truth_starts_where_its_first_fix_puts_its_first_sample():
    """Without truth the start is the first fix taken back along the dead-reckoned track to the first sample (stop
    72): taken as it is, a drive at 20 m/s whose first fix comes 1 s in started 20 m off, with the truth 0."""
    kw = {**_arrays(minutes=3.0, v=20.0, sigma=0.0), "gps_sigma": 3.0}  # (fixes without error: the start is exact)
    run = _quiet(**kw)
    truth = _quiet(**kw, truth=np.stack([np.r_[0.0, np.cumsum(20.0 * 0.1 * np.sin(kw["heading"][1:]))],
                                         np.r_[0.0, np.cumsum(20.0 * 0.1 * np.cos(kw["heading"][1:]))]], axis=1))
    assert run.x_true is None and run.gps_steps[0] == truth.gps_steps[0] == 9  # (the first fix at t = 1 s)
    assert np.hypot(*(run.x0[[0, 3]] - truth.x0[[0, 3]])) < 1e-6
    assert np.hypot(*(run.z_gps[0] - truth.x0[[0, 3]])) == pytest.approx(20.0, abs=0.01)


def test_fixes_from_two_sources_taking_turns_are_named():
    """Two receivers merged into one column, every other fix 5 m off the ones between: named with the offset, and
    left as written (stop 72: moved onto either source, or their midpoint, the sixth trial's drive ended farther
    off); one source at the same rate is not."""
    kw = _arrays(minutes=6.0, fix_every=5, sigma=1.5)
    _quiet(**kw)
    moved = dict(kw, east=kw["east"].copy(), north=kw["north"].copy())
    moved["east"][1::2] += 4.0
    moved["north"][1::2] -= 3.0
    with pytest.warns(RuntimeWarning, match=r"the GPS fixes take turns between two sources (\d.\d\d) m apart \(every "
                                            r"other fix, .*: two receivers, or two antennas, merged into one column") as w:
        run = DRRun.from_arrays(**moved)
    said = [re.search(r"sources (\d.\d\d) m apart", str(x.message)) for x in w]
    assert abs(float(next(m for m in said if m).group(1)) - 5.0) < 0.5
    np.testing.assert_array_equal(run.z_gps[:, 0], moved["east"])  # (as written)


def test_a_heading_convention_that_changes_mid_drive_is_placed(tmp_path):
    """A logger restarted with another convention: the sixth user trial's drive (``gen_drives_6.py``), its heading
    counter-clockwise from east after 250 s. The refusal says from when (stop 72: it named the whole column, and
    converted whole the drive ended its outages 13.42 / 523.46 m off); the drive converted whole is warned of, with
    the time until which the conversion holds."""
    here = os.path.dirname(os.path.abspath(__file__))
    gen = os.path.join(here, "..", "..", "docs", "study-outputs", "dr", "user-trial", "gen_drives_6.py")
    subprocess.run([sys.executable, gen, str(tmp_path)], check=True, capture_output=True)
    with pytest.raises(ValueError, match=r"heading looks counter-clockwise from east .*; but only from about t = "
                                         r"24\d s \(s from the first row\); before it the heading fits the fixes as "
                                         r"written \(\d+% of the chords fit so split\): a log whose convention "
                                         r"changed there"):
        read_drive_csv(tmp_path / "enu_restart.csv", progress=False)
    with open(tmp_path / "enu_restart.csv") as fh:
        header, *rows = fh.read().splitlines()
    cols = header.split(",")
    t, h = cols.index("time"), cols.index("heading_deg")
    whole = []
    for row in rows:  # the refusal's remedy applied to every row
        cells = row.split(",")
        cells[h] = f"{(90.0 - float(cells[h])) % 360.0:.3f}"
        whole.append(",".join(cells))
    (tmp_path / "whole.csv").write_text("\n".join([header] + whole) + "\n")
    with pytest.warns(RuntimeWarning, match=r"the heading reads as counter-clockwise from east on a stretch of the "
                                            r"drive, and the filters take all of it as written: only until about t = "
                                            r"24\d s"):
        read_drive_csv(tmp_path / "whole.csv", progress=False)
    assert float(rows[0].split(",")[t]) == 0.0


def test_a_drifting_gyro_with_multipath_jumps_is_read():
    """20 minutes of a 0.09 deg/s rate bias (108 degrees at the end; the phone grade's gyro, within 2 sigma)
    with 5 % of the fixes jumped 40-80 m: numpy's unwrap of the chords' angles took a jumped chord's for a
    turn and shifted every later one by 360 degrees, and the drive was refused ("68 degrees off the fixes'
    course"); 12 of 60 random drives were. The line's drift is the gyro's."""
    kw = _arrays(drift=0.09, jumps=0.05)
    _quiet(**kw)
    from filterwnn.navigation._plausibility import heading_offset

    run = DRRun.from_arrays(**kw, checks=False)
    heading = np.r_[kw["heading"][0], run.z_dr[:, 0]]
    offset, se, rate, resid = heading_offset(0.1, heading, run.z_dr[:, 1], run.gps_steps, run.z_gps, 4.0)
    assert abs(offset) < 3 * se + 1.0 and abs(rate - 0.09) < 0.005 and resid < 10.0


def test_a_speed_dropping_to_0_for_a_sample_is_interpolated_and_a_stop_is_not():
    """A CAN frame lost and logged as 0 (one sample, or three) between 10 m/s samples: no car stops and pulls
    away so fast, so it is a dropout, interpolated with a warning; taken for a stop it held the filters still
    while the car moved (20 of them took the phone analog's EKF-8 from 6.68 / 28.16 to 63.51 / 397.75 m). A
    real stop (braking at 3 m/s^2, 5 s at 0) stays, and so does a 0 between samples of a crawl (1.5 m/s)."""
    kw = _arrays(minutes=2.0, v=10.0)
    clean = _quiet(**kw)
    speed = kw["speed"].copy()
    speed[[300, 601, 602, 603]] = 0.0
    with pytest.warns(RuntimeWarning, match=r"the speed reads 0 for 4 sample\(s\) in 2 run\(s\) .* first at t = 30 s, "
                                            r"between 10 and 10 m/s 0.2 s apart.* interpolated"):
        run = DRRun.from_arrays(**{**kw, "speed": speed})
    np.testing.assert_allclose(run.z_dr, clean.z_dr, atol=1e-12)
    crawl = {**kw, "speed": np.where(speed == 0.0, 0.0, 1.5)}  # at a crawl a 0 is the sensor's own (a cutoff)
    with pytest.warns(RuntimeWarning, match="a wheel-speed sensor's cutoff") as seen:
        read = DRRun.from_arrays(**crawl, checks=False)  # its fixes drove at 10 m/s
    assert not any("dropouts" in str(w.message) for w in seen)
    assert np.array_equal(read.z_dr[:, 1] == 0.0, crawl["speed"][1:] == 0.0)
    t = kw["t"]
    stop = np.clip(np.minimum(np.abs(t - 60.0) - 2.5, 1e9) * 3.0, 0.0, 10.0)  # 10 m/s, braking to 5 s at 0 at 60 s
    _quiet(**{**kw, "speed": stop})


def test_one_wild_chord_angle_does_not_turn_the_rest():
    """numpy's unwrap takes each angle within pi of the one before: one chord pointing anywhere (a jumped fix)
    shifted all later angles by a turn. Unwrapped against the median of the five before, it stays one."""
    from filterwnn.navigation._plausibility import _unwrap

    line = np.deg2rad(0.5 * np.arange(40.0) + 170.0)  # a drift through +-180 degrees
    ang = (line + np.pi) % (2 * np.pi) - np.pi
    ang[20] = ang[20] + np.deg2rad(179.8)  # the wild one: numpy takes the step into it (+180.3 deg) for -179.7, and every later angle a turn lower
    out = _unwrap(ang)
    keep = np.arange(40) != 20
    np.testing.assert_allclose(out[keep], line[keep], atol=1e-12)
    assert not np.allclose(np.unwrap(ang)[keep], line[keep])


@pytest.mark.parametrize("case", ["5 Hz fixes", "multipath at walking pace"])
def test_chords_chosen_by_the_odometer_read_the_speed_scale_right(case):
    """A chord that ended at the first fix past its length was chosen by the fixes' errors: 5 Hz fixes
    read the speed 8 % low (a warning naming a scale the sensor does not have), and fixes jumped by
    multipath at 3 m/s ended chords at once (a median ratio of 0.5: the drive refused). Chosen by the
    odometer's path, the scale is read within 3 % (multipath still pulls it 2 %), and nothing is warned."""
    kw = (_arrays(fix_every=2, sigma=4.0, v=20.0) if case == "5 Hz fixes"
          else _arrays(v=3.0, fix_every=10, sigma=5.0, jumps=0.066))
    _quiet(**kw)
    from filterwnn.navigation._plausibility import speed_scale

    run = DRRun.from_arrays(**kw, checks=False)
    heading = np.r_[kw["heading"][0], run.z_dr[:, 0]]
    ratio, _ = speed_scale(0.1, heading, run.z_dr[:, 1], run.gps_steps, run.z_gps, float(kw["gps_sigma"][0]))
    assert abs(ratio - 1.0) < 0.03, ratio


def test_a_fix_jumping_while_the_car_stands_reads_without_a_numpy_warning():
    """A chord between a standing car's fixes, one jumped 60 m (multipath), has no odometer path: its ratio
    is 0, taken as the lowest by the speed scale's median; numpy's "divide by zero encountered in log"
    had reached the user."""
    t = np.arange(0.0, 300.0, 0.1)
    speed = np.where((t > 100.0) & (t < 140.0), 0.0, 10.0)
    north = np.r_[0.0, np.cumsum(speed[:-1] * 0.1)]
    gps = np.arange(10, len(t), 10)
    ge, gn = np.zeros(len(gps)), north[gps].copy()
    ge[np.searchsorted(t[gps], 120.0)] = 60.0  # the jump, while the car stands
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run = DRRun.from_arrays(t, np.zeros(len(t)), speed=speed, gps_t=t[gps], east=ge, north=gn,
                                gps_sigma=np.full(len(gps), 2.0))
    assert len(run.gps_steps) == len(gps)


def test_the_command_takes_the_heading_offset_and_the_speed_scale(command_passes):
    seen = command_passes("read_drive_csv", ["--heading-offset", "-12.5", "--speed-scale", "1.08"])
    assert seen["heading_offset"] == -12.5 and seen["speed_scale"] == 1.08
    seen = command_passes("read_drive_csv", [])
    assert seen["heading_offset"] == 0.0 and seen["speed_scale"] == 1.0


def _swap(cols, *pairs):
    out = dict(cols)
    for a, b in pairs:
        out[a], out[b] = cols[b], cols[a]
    return out


MISTAKES = {
    "time in milliseconds": (lambda c: {**c, "time": c["time"] * 1000}, "time looks like milliseconds"),
    "time in microseconds": (lambda c: {**c, "time": c["time"] * 1e6}, r"time looks like microseconds \(divide by 1e6"),
    # a ROS log's int64 stamps, refused before any warning read in them (spikes, jitter: stop 59)
    "time in nanoseconds from the epoch": (lambda c: {**c, "time": 1.718e18 + c["time"] * 1e9},
                                           r"time looks like nanoseconds \(divide by 1e9 for s: a 0.1 s interval\)"),
    "heading in degrees under 2 pi": (lambda c: {**c, "heading": np.full_like(c["heading"], 3.0)},
                                      "heading looks like degrees"),
    "heading counter-clockwise from east": (lambda c: {**c, "heading": np.pi / 2 - c["heading"]},
                                            "counter-clockwise from east"),
    "heading counter-clockwise from another zero": (
        lambda c: {**c, "heading": np.mod(np.deg2rad(200.0) - c["heading"], 2 * np.pi)},
        r"the heading turns the wrong way \(the GPS course matches 200 deg - heading: .* give heading_deg = 200 - "
        r"yaw_deg, or heading = 3.49\d - heading in radians"),
    "speed in km/h": (lambda c: {**c, "speed": c["speed"] * 3.6}, "speed looks like km/h"),
    "speed in ft/s": (lambda c: {**c, "speed": c["speed"] / 0.3048}, r"speed looks like ft/s \(multiply by 0.3048"),
    "speed in mph": (lambda c: {**c, "speed": c["speed"] / 0.44704}, "speed looks like mph"),
    "speed in knots": (lambda c: {**c, "speed": c["speed"] / 0.514444}, r"speed looks like knots \(multiply by 0.514444"),
    "lat and lon in radians": (lambda c: {**c, **{k: np.deg2rad(c[k]) for k in ("gps_lat", "gps_lon", "true_lat",
                                                                              "true_lon")}},
                               "the fixes' lat and lon look like radians"),
    "lat and lon in radians in the fixes only": (lambda c: {**c, "gps_lat": np.deg2rad(c["gps_lat"]),
                                                            "gps_lon": np.deg2rad(c["gps_lon"])},
                                                 "the GPS fixes lie a median .* from the truth at their samples: the "
                                                 "fixes' lat and lon look like radians"),
    "lat and lon swapped": (lambda c: _swap(c, ("gps_lat", "gps_lon"), ("true_lat", "true_lon")),
                            "lat and lon look swapped"),
    "lat and lon swapped in the fixes only": (lambda c: _swap(c, ("gps_lat", "gps_lon")),
                                              "lat and lon swapped"),
}


@pytest.mark.parametrize("mistake", sorted(MISTAKES))
def test_a_unit_mistake_is_refused_with_its_likely_cause_and_can_be_overridden(tmp_path, mistake):
    change, cause = MISTAKES[mistake]
    # a drive on a 3 degree bearing stays under 2 pi in degrees; counter-clockwise from east
    # mirrors the heading about 45 degrees: a drive far from that bearing tells
    kw = {"heading in degrees under 2 pi": dict(bearing=np.deg2rad(3.0), turn=0.0),
          "heading counter-clockwise from east": dict(bearing=2.0)}.get(mistake, {})
    cols = _drive(**kw)
    path = _write(tmp_path / "d.csv", change(cols))
    with pytest.raises(ValueError, match=cause) as info:
        read_drive_csv(path)
    assert str(info.value).startswith(path) and "checks=False" in str(info.value)
    read_drive_csv(path, checks=False)  # the override reads it


def test_unix_epoch_times_read_as_times_from_zero(tmp_path):
    cols = _drive()
    want = read_drive_csv(_write(tmp_path / "zero.csv", cols))
    cols["time"] = cols["time"] + 1.7e9  # stored to 2.4e-7 s: the median interval is 0.0999999046 s
    got = read_drive_csv(_write(tmp_path / "epoch.csv", cols))
    assert got.scenario.dt == want.scenario.dt == 0.1 and got.scenario.gps_rate == 1.0
    np.testing.assert_array_equal(got.gps_steps, want.gps_steps)
    np.testing.assert_allclose(got.z_dr, want.z_dr, rtol=1e-5)  # each step's distance from its own interval


def test_null_fixes_at_lat_lon_zero_are_dropped_with_a_warning(tmp_path):
    cols = _drive()
    want = read_drive_csv(_write(tmp_path / "clean.csv", cols))
    fix = np.flatnonzero(~np.isnan(cols["gps_lat"]))
    cols["gps_lat"][fix[:3]] = cols["gps_lon"][fix[:3]] = 0.0  # logged before the receiver had a position
    # (the first, at t = 0, is the start's and never used: two fixes fewer)
    with pytest.warns(RuntimeWarning, match=r"dropped 3 GPS fix\(es\) at lat = lon = 0 \(a receiver's null fix"):
        got = read_drive_csv(_write(tmp_path / "null.csv", cols))
    # the origin is the first real fix: as the first fix, (0, 0) bent every fix and the truth (EKF-8 9.8 -> 126 m)
    shift = want.z_gps[2] - got.z_gps[0]
    np.testing.assert_array_equal(got.gps_steps, want.gps_steps[2:])
    np.testing.assert_allclose(got.z_gps + shift, want.z_gps[2:], atol=0.05)
    np.testing.assert_allclose(got.x_true[:, [0, 3]] + shift, want.x_true[:, [0, 3]], atol=0.05)
    cols["gps_lat"][fix] = cols["gps_lon"][fix] = 0.0
    with pytest.raises(ValueError, match="every GPS fix is at lat = lon = 0"):
        read_drive_csv(_write(tmp_path / "none.csv", cols))


def test_a_loggers_faults_are_named_with_their_remedy(tmp_path):
    """What a probe with a user's kind of log met: each refusal names the line, the cause and what to do."""
    def refused(cols, match, **kw):
        with pytest.raises(ValueError, match=match):
            read_drive_csv(_write(tmp_path / "d.csv", cols), **kw)

    c = _drive()
    c["gps_sigma"][np.flatnonzero(~np.isnan(c["gps_sigma"]))[:100]] = 0.0  # the fix's index was all it said
    refused(c, r"'gps_sigma' must be > 0 \(m\) where there is a fix; data row 1 \(line 2\) has 0 \(0 is how")
    c = _drive()
    c["heading"] = np.degrees(c["heading"])
    refused(c, "looks like degrees: name the column heading_deg, or write it in radians")
    c = _drive()
    c["time"][11] = c["time"][10]
    refused(c, r"t\[11\] \(line 13\) = 1.0 <= t\[10\] \(line 12\) = 1.0: a sample logged twice\? drop the repeated")
    keep = np.ones(1201, dtype=bool)
    keep[500:520] = False  # 2 s of rows dropped: a 2.1 s interval
    c = {k: v[keep] for k, v in _drive().items()}
    refused(c, r"= 2.1 s: .* this one needs 2.1\)", fill_gaps=2.0)
    # an OBD-II adapter that hung beside a gyro that logged on (stop 61: filled whole, the turns in the gap went)
    refused(c, r"this one needs 2.1\);.* where only one sensor paused .* interpolate that sensor's column alone",
            fill_gaps=2.0)
    with pytest.warns(RuntimeWarning, match="filled 1 gap"):
        read_drive_csv(_write(tmp_path / "d.csv", c), fill_gaps=2.1)  # as the message says (2.1000000000000014)
    keep[500:800] = False  # a logger that paused for 30 s: interpolating it is a guess, so split it
    refused({k: v[keep] for k, v in _drive().items()}, r"= 30.1 s: .* this one needs 30.1\); dead reckoning "
            r"interpolated over so long is a guess: for a log that paused, split the file before t\[500\] \(line 502\)")


def test_a_clock_that_stepped_an_hour_is_named_and_not_offered_to_fill(tmp_path):
    """A seventh user's log (stop 74) stepped +3600 s mid-drive, summer time set while it ran: the refusal offered
    ``--fill-gaps 3600.1``, and filled as offered the filters ended outages 49.6 km off. Such a step (an hour, or GPS
    time's 18 s on UTC, and one sample interval) is named with its remedy; a long gap that is no clock's is told to
    be split, not filled; a gap of an hour filled all the same is warned of."""
    def refused(cols, match):
        with pytest.raises(ValueError, match=match) as info:
            read_drive_csv(_write(tmp_path / "d.csv", cols))
        return str(info.value)

    c = _drive()
    c["time"][500:] += 3600.0
    said = refused(c, r"= 3600.1 s: 3600 s and one sample interval, an hour: a clock set forward or back .* subtract "
                      r"3600 s from every time from t\[500\] \(line 502\) on; a log that did pause is split there")
    assert "this one needs" not in said
    with pytest.warns(RuntimeWarning, match=r"the longest 3600.1 s after t = 49.9 s; it is 3600 s and one sample "
                                            r"interval, an hour.*from t = 3650 s on.*Filled, the filters follow"):
        read_drive_csv(_write(tmp_path / "d.csv", c), fill_gaps=3600.1)
    c = _drive()
    c["time"][500:] += 18.0
    refused(c, r"18 s and one sample interval, GPS time's lead on UTC .* subtract 18 s from every time from t\[500\]")
    c = _drive()
    c["time"][500:] -= 3600.0
    refused(c, r"t must be strictly increasing.*: 3600 s back, less one sample interval, an hour.* add 3600 s to every "
               r"time from t\[500\] \(line 502\) on")
    c = _drive()
    c["time"][500:] += 100.0  # a pause of 100 s, no clock's step: split, not filled
    said = refused(c, r"= 100.1 s: resample the drive first; dead reckoning interpolated over so long is a guess")
    assert "this one needs" not in said and "an hour" not in said


def test_a_gps_sigma_column_the_receiver_never_filled_is_taken_as_absent(tmp_path):
    """A logger's ``gps_sigma`` column empty on every fix (a receiver that reports no accuracy) is no column: every
    fix gets the grade's sigma, with a warning; one empty on some fixes only is refused with the remedy."""
    c = _drive()
    c["gps_sigma"][:] = np.nan
    with pytest.warns(RuntimeWarning, match="'gps_sigma' is empty on every fix: taken as absent"):
        run = read_drive_csv(_write(tmp_path / "d.csv", c))
    assert run.gps_sigma is None and len(run.gps_steps) == 120
    c = _drive()
    fixes = np.flatnonzero(~np.isnan(c["gps_sigma"]))
    c["gps_sigma"][fixes[5]] = np.nan  # one empty among the others: their neighbours' (stop 72; refused before)
    with pytest.warns(RuntimeWarning, match=r"'gps_sigma' is empty or 0 on 1 fixes \(the first at t = 5 s\): the "
                                            r"receiver gave none. Those 1 fixes take the accuracy of the fixes beside"):
        run = read_drive_csv(_write(tmp_path / "d.csv", c))
    assert np.all(np.isfinite(run.gps_sigma))
    c["gps_sigma"][fixes[:100]] = np.nan  # most empty: refused with the remedy, as before
    with pytest.raises(ValueError, match=r"'gps_sigma' is empty on data row 1, which has a fix \(give every fix "
                                         r"its accuracy, or drop the column"):
        read_drive_csv(_write(tmp_path / "d.csv", c))


def test_a_placeholder_accuracy_takes_its_neighbours(tmp_path):
    """A logger's 99.9 where the receiver's record had no accuracy (runs of it, far above every other value) is no
    measurement: those fixes take their neighbours' accuracy, with a warning (stop 72: the sixth trial's drive, 37 %
    of its fixes at 99.9, ended its outages 4.90 / 30.46 m off, 3.73 / 19.33 so read, the twin 3.64 / 19.42). A
    receiver whose accuracy is one value throughout, or a large value on a few fixes, is read as written."""
    c = _drive()
    fixes = np.flatnonzero(~np.isnan(c["gps_sigma"]))
    c["gps_sigma"][fixes] = np.linspace(2.0, 3.0, len(fixes))
    c["gps_sigma"][fixes[40:60]] = 99.9
    with pytest.warns(RuntimeWarning, match=r"'gps_sigma' reads 99.9 on 20 fixes \(1 stretch\(es\), the first from "
                                            r"t = 40 s to 59 s\), 39 times the median .* a placeholder"):
        run = read_drive_csv(_write(tmp_path / "d.csv", c))
    assert np.all(run.gps_sigma < 3.1)
    c["gps_sigma"][fixes[40:60]] = np.tile([99.9, 80.0], 10)  # alternating: no run, read as written
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run = read_drive_csv(_write(tmp_path / "d.csv", c))
    assert run.gps_sigma.max() == pytest.approx(99.9)


def test_an_hdop_column_is_read_as_a_sigma_through_the_sigma_at_hdop_1(tmp_path):
    """``gps_hdop`` (NMEA GGA's dilution of precision, without a unit) gives each fix the sigma ``HDOP *
    hdop_sigma``; without ``hdop_sigma`` it is refused with what to pass, beside ``gps_sigma`` as two accuracies,
    and a column named ``hdop`` is named back as ``gps_hdop``. A 0 is refused as for ``gps_sigma``."""
    c = _drive()
    c["gps_hdop"] = c.pop("gps_sigma") / 3.0 * np.linspace(0.8, 1.6, 1201)  # 1 at 3 m, the geometry changing
    cols = [k if k != "gps_sigma" else "gps_hdop" for k in COLUMNS]
    path = _write(tmp_path / "d.csv", c, columns=cols)
    run = read_drive_csv(path, hdop_sigma=3.0)
    hdop = c["gps_hdop"][np.isfinite(c["gps_lat"])][1:]  # (the first fix is the start's, before step 0)
    np.testing.assert_allclose(run.gps_sigma, 3.0 * hdop)
    with pytest.raises(ValueError, match=r"column 'gps_hdop' is a dilution of precision, without a unit: pass "
                                         r"hdop_sigma, the sigma per axis \(m\) of a fix at HDOP 1"):
        read_drive_csv(path)
    with pytest.raises(ValueError, match="hdop_sigma must be finite and > 0"):
        read_drive_csv(path, hdop_sigma=0.0)
    c["gps_sigma"] = c["gps_hdop"] * 3.0
    with pytest.raises(ValueError, match=r"give each fix's accuracy as 'gps_sigma' \(m\) or as 'gps_hdop' \(no "
                                         r"unit\), not both"):
        read_drive_csv(_write(tmp_path / "both.csv", c, columns=cols + ["gps_sigma"]), hdop_sigma=3.0)
    with pytest.warns(RuntimeWarning, match="the header's 'hdop' may be 'gps_hdop' "):
        plain = read_drive_csv(_write(tmp_path / "named.csv", c, columns=cols, header=COLUMNS[:5] + ["hdop"]
                                      + COLUMNS[6:]))
    assert plain.gps_sigma is None  # not read: every fix gets the grade's sigma
    c["gps_hdop"][np.flatnonzero(np.isfinite(c["gps_lat"]))[4:100]] = 0.0
    with pytest.raises(ValueError, match=r"'gps_hdop' must be > 0 \(no unit\) where there is a fix; data row 41"):
        read_drive_csv(_write(tmp_path / "d.csv", c, columns=cols), hdop_sigma=3.0)


def test_a_heading_or_speed_that_changes_only_at_the_fixes_is_named_a_receivers(tmp_path):
    """A phone log's GPS bearing or Doppler speed written on every DR row holds between the fixes and changes at
    them: no dead-reckoning sensor, and outages cut into the drive carry the withheld fixes' course. Warned, naming
    the column and what to give; a gyro's heading and a car's speed, as the plain drive has them, are not."""
    c = _drive()
    fix = np.isfinite(c["gps_lat"])
    held = np.maximum.accumulate(np.where(fix, np.arange(1201), 0))  # each row: the last fix's row
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        read_drive_csv(_write(tmp_path / "d.csv", c))
    for column, epoch in (("heading", 0.0), ("speed", 0.0), ("speed", 1.7964e9)):
        g = dict(c, time=np.round(c["time"] + epoch, 3))  # (stamps since 1970: each step's last digits change, stop 64)
        g[column] = c[column][held] * (1.0 if column == "heading" else 1.0 + 0.1 * np.sin(held / 50.0))
        with pytest.warns(RuntimeWarning, match=rf"while the car moves the {column} changes only where there is a GPS "
                                                rf"fix \(100% of its \d+ changes .*: a GPS "):
            read_drive_csv(_write(tmp_path / "d.csv", g))


def test_speed_and_heading_spikes_are_interpolated_with_a_warning(tmp_path):
    """A CAN glitch (255 km/h for a sample, or two) and a heading turned by 90 degrees for a sample leave the
    samples beside them and come back faster than a car can: each is interpolated from its neighbours, with a
    warning that counts them, and the drive reads as without them (``log-faults/spikes.py``: 20 such speed samples
    had taken the phone analog's EKF-8 from 6.68 / 28.16 to 58.54 / 306.49 m)."""
    c = _drive()
    clean = read_drive_csv(_write(tmp_path / "d.csv", c))
    g = dict(c, speed=c["speed"].copy())
    g["speed"][[100, 400, 401, 900]] = 70.8
    with pytest.warns(RuntimeWarning, match=r"4 speed sample\(s\) in 3 run\(s\) jump away from the samples beside "
                                            r"them and back faster than a car can .* the first at t = 10 s, 70.8 m/s"):
        run = read_drive_csv(_write(tmp_path / "d.csv", g))
    np.testing.assert_allclose(run.z_dr, clean.z_dr, atol=1e-9)
    g = dict(c, heading=c["heading"].copy())
    g["heading"][[100, 700]] = np.mod(g["heading"][[100, 700]] + np.pi / 2, 2 * np.pi)
    with pytest.warns(RuntimeWarning, match=r"2 heading sample\(s\) in 2 run\(s\) turn away .* the first at t = 10 s, "
                                            r"\+90.1 degrees from the sample before"):
        run = read_drive_csv(_write(tmp_path / "d.csv", g))
    np.testing.assert_allclose(run.z_dr, clean.z_dr, atol=1e-9)


def test_a_spike_beside_a_dropout_is_interpolated_as_one_glitch(tmp_path):
    """A CAN glitch of 255 km/h and a lost frame logged as 0 side by side (stop 56's protocol 3 drew them on the 1
    Hz analog): the dropout was interpolated from the spike (70.8, 0 -> 70.8, 43) and the spike's run ended at the
    first sample back down, so 43 m/s stayed in the drive. Both orders now read as the drive without them, and so
    does a spike between two dropouts (at 1 Hz it had left a ramp of 24-43 m/s)."""
    c = _drive()
    clean = read_drive_csv(_write(tmp_path / "d.csv", c))
    for rows in ([100, 101], [101, 100]):  # the spike first, then the dropout; and the other way round
        g = dict(c, speed=c["speed"].copy())
        g["speed"][rows] = [70.8, 0.0]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            run = read_drive_csv(_write(tmp_path / "d.csv", g))
        said = " ".join(str(w.message) for w in caught)
        assert "the speed reads 0 for 1 sample(s)" in said and "2 speed sample(s) in 1 run(s) jump away" in said, said
        np.testing.assert_allclose(run.z_dr, clean.z_dr, atol=1e-9)
    c = _drive(dt=1.0, v=15.0)  # at 1 Hz a car's 1 g is 9.8 m/s a sample
    clean = read_drive_csv(_write(tmp_path / "d.csv", c))
    g = dict(c, speed=c["speed"].copy())
    g["speed"][[100, 101, 102]] = [0.0, 70.8, 0.0]  # a spike between two dropouts: its jump back is the second down
    g["speed"][[300, 302]] = 70.8  # two spikes with a good sample between them: two runs, the sample kept
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = read_drive_csv(_write(tmp_path / "d.csv", g))
    said = " ".join(str(w.message) for w in caught)
    assert "5 speed sample(s) in 3 run(s) jump away" in said, said
    np.testing.assert_allclose(run.z_dr, clean.z_dr, atol=1e-9)


def test_a_receivers_speed_lost_with_its_fixes_under_a_bridge_is_interpolated_and_named(tmp_path):
    """An eighth user's speed was the GPS receiver's Doppler speed, logged as 0 under 7 bridges where the receiver had
    no fix either (stop 75): four runs of 5.4-7.9 s at 19-23 m/s passed no dropout rule (under 10 m/s^2 each way),
    were taken for stops, and the fixes after them were named a spoofer's walk (EKF-8 8.81 / 185.24 m against the
    twin's 5.31 / 27.04). A zero run that spans a gap of the fixes, between samples of a moving car, past an
    ordinary stop's 3 m/s^2 each way, is the receiver's speed lost with its fixes: interpolated, and named so. Not so
    for the same run where the fixes go on (a stop as far as the fixes can tell: the spoofer's check judges it), for
    a real stop in a gap of the fixes (the speed comes down to 0 and up again), or CAN frames lost for 2 s in a
    tunnel (a run far shorter than the gap: the dropout rule's, as before)."""
    c = _drive(v=20.0, turn=0.0)
    clean = read_drive_csv(_write(tmp_path / "clean.csv", c))
    g = {k: v.copy() for k, v in c.items()}
    g["speed"][400:470] = 0.0  # 7 s of 0 at 20 m/s ...
    for k in ("gps_lat", "gps_lon", "gps_sigma"):
        g[k][400:470] = np.nan  # ... where the receiver has no fix (its last at 39 s, its next at 47 s)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = read_drive_csv(_write(tmp_path / "d.csv", g))
    said = [str(w.message) for w in caught if "where the GPS receiver has no fix either" in str(w.message)]
    assert len(said) == 1 and "70 sample(s) in 1 run(s)" in said[0] and "Doppler" in said[0], said
    assert not any("walk away" in str(w.message) for w in caught)
    np.testing.assert_allclose(run.z_dr, clean.z_dr, atol=1e-9)
    fixes_on = {k: v.copy() for k, v in g.items()}
    for k in ("gps_lat", "gps_lon", "gps_sigma"):
        fixes_on[k] = c[k].copy()
    stop = {k: v.copy() for k, v in g.items()}  # a real stop in the gap: 20 -> 0 at 2 m/s^2, 3 s still, 0 -> 20
    ramp = np.clip(20.0 - 2.0 * 0.1 * np.arange(1, 101), 0.0, None)
    stop["speed"][300:400], stop["speed"][400:430], stop["speed"][430:530] = ramp, 0.0, ramp[::-1]
    for k in ("gps_lat", "gps_lon", "gps_sigma"):
        stop[k][300:530] = np.nan
    frame = {k: v.copy() for k, v in c.items()}  # CAN frames lost for 2 s inside a 20 s gap of the fixes
    frame["speed"][450:470] = 0.0
    for k in ("gps_lat", "gps_lon", "gps_sigma"):
        frame[k][300:500] = np.nan
    for name, cols in (("fixes on", fixes_on), ("a real stop", stop), ("a lost frame", frame)):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                read_drive_csv(_write(tmp_path / "d.csv", cols))
            except ValueError:
                pass  # (a stop the plausibility checks refuse is still not the receiver's speed)
        assert not any("where the GPS receiver has no fix" in str(w.message) for w in caught), name
        if name == "a lost frame":
            assert any("so these are dropouts" in str(w.message) for w in caught)


def test_the_analogs_have_no_spikes_to_find(tmp_path):
    """What a car does is no spike: the analogs' stops, pull-aways and turns (seed 0 of each, as written) read
    without the warning."""
    for name in ("phone", "city", "one_hz"):
        cols = held_out.columns(name, 0)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            read_drive_csv(held_out.write_csv(tmp_path / f"{name}.csv", cols))
        assert not [w for w in caught if "spikes (" in str(w.message)], name


def test_column_names_are_read_whatever_their_case_and_an_empty_truth_is_no_truth(tmp_path):
    """A header as a spreadsheet writes it (``Time``, ``GPS_Lat``) reads as the lower-case names; truth columns
    empty on every row (a template the logger never filled) are taken as absent, with a warning, and the drive is
    scored against its fixes."""
    c = _drive()
    plain = read_drive_csv(_write(tmp_path / "d.csv", c))
    head, rest = (tmp_path / "d.csv").read_text().split("\n", 1)
    (tmp_path / "caps.csv").write_text(head.title().replace("Gps_", "GPS_") + "\n" + rest)
    caps = read_drive_csv(str(tmp_path / "caps.csv"))
    np.testing.assert_array_equal(caps.z_gps, plain.z_gps)
    np.testing.assert_array_equal(caps.x_true, plain.x_true)
    c["true_lat"][:] = c["true_lon"][:] = np.nan
    with pytest.warns(RuntimeWarning, match="'true_lat' and 'true_lon' are empty on every row: taken as absent"):
        run = read_drive_csv(_write(tmp_path / "d.csv", c))
    assert run.x_true is None and len(run.gps_steps) == 120
    c["true_lat"][3] = 48.0  # one value: a truth with holes, refused as before
    with pytest.raises(ValueError, match="true_lat"):
        read_drive_csv(_write(tmp_path / "d.csv", c))


def test_a_trailing_delimiter_on_every_line_is_read(tmp_path):
    """A spreadsheet's export that ends every line with delimiters (unnamed, empty columns) reads as without them
    (two of them were refused as duplicated column names)."""
    plain = read_drive_csv(_write(tmp_path / "d.csv", _drive()))
    text = (tmp_path / "d.csv").read_text().splitlines()
    (tmp_path / "t.csv").write_text("\n".join(line + ",," for line in text) + "\n")
    trailing = read_drive_csv(str(tmp_path / "t.csv"))
    np.testing.assert_array_equal(trailing.z_dr, plain.z_dr)
    np.testing.assert_array_equal(trailing.z_gps, plain.z_gps)


def test_stamps_that_jitter_about_a_regular_grid_give_each_speed_the_grids_interval(tmp_path):
    """A logger stamps regular samples up to 5 ms late: taken over its stamped interval each speed would
    add 0.067 m of noise to a step (each late stamp lengthens one interval and shortens the next); read
    with the default, the distances are the clean drive's, with a warning that says so."""
    rng = np.random.default_rng(0)
    c = _drive(v=23.0)
    clean = read_drive_csv(_write(tmp_path / "c.csv", c), checks=False)
    c["time"] = c["time"] + rng.uniform(-0.005, 0.005, len(c["time"]))
    path = _write(tmp_path / "d.csv", c)
    with pytest.warns(RuntimeWarning, match=r"sample times jitter by 4.\d ms \(sd of the intervals\) about a regular "
                                            r"0.1 s grid \(their lag-1 correlation -0.\d\d: .* add 0.0\d+ m of noise .* "
                                            r"intervals='stamps'"):
        run = read_drive_csv(path, checks=False)
    np.testing.assert_allclose(run.z_dr, clean.z_dr, rtol=2e-5, atol=0)
    assert np.ptp(run.z_dr[:, 1]) < 1e-12  # one interval for every step
    with pytest.warns(RuntimeWarning, match=r"sample times jitter by 4.\d ms \(sd of the intervals about 0.099\d+ s\): "
                                            r"speed times interval then adds 0.0\d+ m .* intervals='grid'"):
        stamped = read_drive_csv(path, checks=False, intervals="stamps")
    assert np.std(stamped.z_dr[:, 1]) > 0.05  # the stamped intervals' noise
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # asked for: not warned
        np.testing.assert_array_equal(read_drive_csv(path, checks=False, intervals="grid").z_dr, run.z_dr)
    with pytest.raises(ValueError, match="intervals must be one of 'auto', 'stamps', 'grid', got 'median'"):
        read_drive_csv(path, checks=False, intervals="median")
    c["time"] = 0.1 * np.arange(1201) + rng.uniform(-0.0005, 0.0005, 1201)  # at 10 m/s: 0.004 m, under a wheel's
    c["speed"][:] = 10.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run = read_drive_csv(_write(tmp_path / "d.csv", c), checks=False)
    assert np.std(run.z_dr[:, 1]) > 0  # a jitter under a wheel's noise keeps the stamped intervals


def test_stamps_that_jitter_past_max_jitter_about_a_grid_are_read_and_dropped_samples_are_not():
    """Stamps with a 6 ms sd about a 0.1 s grid make intervals up to 27 % off their median (past
    max_jitter's 20 %): the samples are regular, and the drive is read. A dropped sample among such
    stamps leaves those after it an interval late, and is refused with the fill_gaps it needs."""
    rng = np.random.default_rng(0)
    n = 3001
    t = 0.1 * np.arange(n) + rng.normal(0.0, 0.006, n)
    assert np.max(np.abs(np.diff(t) / 0.1 - 1.0)) > 0.25
    with pytest.warns(RuntimeWarning, match="about a regular 0.1 s grid"):
        run = DRRun.from_arrays(t, np.zeros(n), speed=np.full(n, 23.0), checks=False)
    assert run.scenario.dt == pytest.approx(0.1, abs=1e-3)
    np.testing.assert_allclose(run.z_dr[:, 1], 2.3, rtol=1e-3)
    for m in (5, 1500, 2995):
        t = np.delete(0.1 * np.arange(n), m) + rng.uniform(-0.01, 0.01, n - 1)
        with pytest.raises(ValueError, match=r"resample the drive first \(dropped samples: fill_gaps"):
            DRRun.from_arrays(t, np.zeros(n - 1), speed=np.full(n - 1, 23.0), checks=False)
    # intervals that vary by 25 % independently, no sample dropped (refused until stop 59): read, each speed over
    # its own interval, with the jitter's noise warned of
    t = np.r_[0.0, np.cumsum(0.1 * (1.0 + rng.uniform(-0.25, 0.25, n - 1)))]
    with pytest.warns(RuntimeWarning, match="they vary independently, not about a regular grid"):
        run = DRRun.from_arrays(t, np.zeros(n), speed=np.full(n, 23.0), checks=False)
    np.testing.assert_allclose(run.z_dr[:, 1], 23.0 * np.diff(t))


def test_stamps_late_by_varying_amounts_are_read_with_each_speed_over_its_own_interval():
    """A ROS bag's times of receipt: 20 Hz samples each received 2-40 ms after its time (a queue's delays), so
    that one interval is 0.021 s and the next 0.079: no regular grid holds them within a quarter interval, and
    until stop 59 the drive was refused ("resample the drive first"). No sample is dropped: it is read, each
    speed over its stamped interval, and the warning names a message's time of receipt; a dropped sample among
    such stamps is still refused."""
    rng = np.random.default_rng(5)
    n = 2001
    t = 0.05 * np.arange(n) + 0.002 + rng.exponential(0.008, n).clip(0.0, 0.038)
    with pytest.warns(RuntimeWarning, match="some lie more than 0.25 of an interval off any regular one: stamps late "
                                            "by varying amounts, as a message's time of receipt is"):
        run = DRRun.from_arrays(t, np.zeros(n), speed=np.full(n, 10.0), checks=False)
    assert run.scenario.dt == pytest.approx(0.05, abs=1e-3)
    np.testing.assert_allclose(run.z_dr[:, 1], 10.0 * np.diff(t))
    with pytest.raises(ValueError, match=r"evenly sampled.*dropped samples: fill_gaps"):
        DRRun.from_arrays(np.delete(t, 700), np.zeros(n - 1), speed=np.full(n - 1, 10.0), checks=False)


def test_a_receivers_latency_places_each_fix_where_the_car_was(tmp_path):
    c = _drive(sigma=1e-9)
    late = {k: np.roll(v, 3) if k.startswith("gps_") else v for k, v in c.items()}  # stamped 0.3 s late
    # 10 m/s for 0.3 s: 3 m behind the car; a negative latency (a fix stamped early) places it later still
    for latency, off in ((0.0, 3.0), (0.3, 0.0), (-0.3, 6.0)):
        run = read_drive_csv(_write(tmp_path / "late.csv", late), gps_latency=latency)
        err = np.hypot(*(run.z_gps - run.x_true[run.gps_steps][:, [0, 3]]).T)
        np.testing.assert_allclose(np.median(err), off, atol=0.01)
    with pytest.raises(ValueError, match="gps_latency must be a finite number of seconds"):
        read_drive_csv(_write(tmp_path / "late.csv", late), gps_latency=np.nan)


def test_a_log_that_carries_its_last_fix_forward_is_read_as_its_fixes(tmp_path):
    """A logger that writes the last fix on every DR row (sample and hold) makes each 1 Hz fix ten rows: each
    would count as a new fix. Read as the fixes they are (each run's first row), with a warning; the drive
    is then the one logged with its fixes alone. A receiver that holds its fix for a few rows (a standing car)
    is read as it is, unwarned."""
    c = _drive()
    plain = read_drive_csv(_write(tmp_path / "plain.csv", c))
    held = dict(c)
    rows = np.flatnonzero(~np.isnan(c["gps_lat"]))
    last = rows[np.searchsorted(rows, np.arange(len(c["time"])), side="right") - 1]
    for k in ("gps_lat", "gps_lon", "gps_sigma"):
        held[k] = c[k][last]
    with pytest.warns(RuntimeWarning, match=r"repeat each fix on the rows after it \(1080 of 1201 fix rows.*runs of "
                                            r"a median 10 rows.*121 fixes, a median 1 s apart"):
        run = read_drive_csv(_write(tmp_path / "held.csv", held))
    np.testing.assert_array_equal(run.gps_steps, plain.gps_steps)
    np.testing.assert_array_equal(run.z_gps, plain.z_gps)
    few = dict(c)  # the first 30 fixes held for two more rows each: a quarter of the fix rows repeat
    for k in ("gps_lat", "gps_lon", "gps_sigma"):
        few[k] = c[k].copy()
        for r in rows[:30]:
            few[k][r + 1:r + 3] = c[k][r]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run = read_drive_csv(_write(tmp_path / "few.csv", few))
    assert len(run.gps_steps) == 180


def test_a_log_with_a_row_per_sensor_message_is_read_with_each_fix_at_its_time(tmp_path):
    """A log that writes each sensor's message on a row of its own (a fix 30 ms after the DR sample it follows,
    the heading and speed cells empty there; the DR rows without a fix): the DR samples are the rows with a
    heading and a speed, and each fix keeps its own time, placed on the nearest sample as the arrays' reader
    places it, with its offset from it (stop 49). The same drive as one row per DR sample, to the fixes' and the
    samples' last digit. A row that is
    neither (a heading but no speed) is refused, naming its line and what it lacks."""
    c = _drive()
    plain = read_drive_csv(_write(tmp_path / "plain.csv", c))
    fix = ~np.isnan(c["gps_lat"])
    split = {k: [] for k in c}
    for k in range(len(c["time"])):
        for key in c:  # the DR row, its fix cells empty
            split[key].append(np.nan if key.startswith("gps_") else c[key][k])
        if fix[k]:  # the fix's own row, 30 ms later, with only its own cells
            for key in c:
                split[key].append(c["time"][k] + 0.03 if key == "time" else c[key][k] if key.startswith("gps_")
                                  else np.nan)
    split = {k: np.array(v) for k, v in split.items()}
    run = read_drive_csv(_write(tmp_path / "split.csv", split))
    np.testing.assert_array_equal(run.gps_steps, plain.gps_steps)
    np.testing.assert_array_equal(run.z_gps, plain.z_gps)
    np.testing.assert_array_equal(run.z_dr, plain.z_dr)
    np.testing.assert_array_equal(run.x_true, plain.x_true)
    assert plain.gps_offset is None  # each fix 30 ms after its sample, which the GPS/DR filter moves it back by
    np.testing.assert_allclose(run.gps_offset, 0.03, rtol=0, atol=1e-9)
    lone = {k: v.copy() for k, v in split.items()}
    lone["speed"][11] = np.nan  # a DR row with a heading and no speed
    with pytest.raises(ValueError, match=r"data row 12 \(line 13\) has a 'heading' but no 'speed': in a log with a "
                                         r"row per sensor message \(rows with a fix alone, as data row 2\), every "
                                         r"other row is a DR sample with both"):
        read_drive_csv(_write(tmp_path / "lone.csv", lone))


def test_iso_8601_time_stamps_are_read_as_seconds(tmp_path):
    """A logger's time column as ISO 8601 date-times (UTC with Z, an offset, or none, taken as UTC; a comma or a
    point before the fraction) is read as seconds: the drive is the one with its times in seconds. Anything else
    that is not a number is refused as before."""
    import datetime

    c = _drive()
    plain = read_drive_csv(_write(tmp_path / "plain.csv", c))
    base = datetime.datetime(2021, 4, 27, 10, 0, 0)
    for zone, shift in (("Z", 0), ("+02:00", 2), ("", 0)):
        stamps = [(base + datetime.timedelta(hours=shift, seconds=float(t))).isoformat(timespec="milliseconds")
                  for t in c["time"]]
        sep = ";" if zone == "+02:00" else ","  # a decimal comma in a file split by semicolons
        if sep == ";":
            stamps = [st.replace(".", ",") for st in stamps]
        lines = [sep.join(COLUMNS)] + [sep.join([st + zone] + ["" if np.isnan(c[k][i]) else repr(float(c[k][i]))
                                                             for k in COLUMNS[1:]]) for i, st in enumerate(stamps)]
        (tmp_path / "iso.csv").write_text("\n".join(lines) + "\n")
        run = read_drive_csv(str(tmp_path / "iso.csv"))
        assert run.scenario.dt == plain.scenario.dt
        np.testing.assert_array_equal(run.gps_steps, plain.gps_steps)
        np.testing.assert_allclose(run.z_dr, plain.z_dr, rtol=1e-5)  # seconds since 1970 resolve 2.4e-7 s
    (tmp_path / "bad.csv").write_text(",".join(COLUMNS) + "\n" + "\n".join("10:00:0%d,0,10,,,,48.1,11.5" % k
                                                                        for k in range(3)) + "\n")
    with pytest.raises(ValueError, match=r"column 'time' must hold numbers; data row 1 \(line 2\) has '10:00:00'"):
        read_drive_csv(str(tmp_path / "bad.csv"))


def test_columns_named_as_loggers_name_them_are_named_back(tmp_path):
    """Unknown columns are not read. One whose name is a logger's for a known column (``east`` for ``gps_east``,
    ``accuracy`` for ``gps_sigma``, ``speed_kmh`` containing ``speed``) is named in the warning, or in the
    refusal of a missing required column, with what the reader would take it for; a drive whose columns all
    have the reader's names is read without a word."""
    c = _drive()
    named = ["time", "heading", "speed", "latitude", "lon", "accuracy", "ref_lat", "ref_lon"]
    with pytest.warns(RuntimeWarning, match=r"columns the reader does not know are not read; the header's 'latitude' "
                                            r"may be 'gps_lat' \(deg: .*'lon' may be 'gps_lon' .*'accuracy' may be "
                                            r"'gps_sigma' \(m: .*: rename them so"):
        run = read_drive_csv(_write(tmp_path / "named.csv", c, columns=COLUMNS, header=named))
    assert not len(run.gps_steps)
    with pytest.raises(ValueError, match=r"needs exactly one of the columns \['speed', 'odometer'\], found \[\] in .*; "
                                         r"the header's 'speed_kmh' may be 'speed' \(m/s: .*: rename it so"):
        read_drive_csv(_write(tmp_path / "kmh.csv", c, columns=COLUMNS,
                              header=["time", "heading", "speed_kmh"] + COLUMNS[3:]))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        read_drive_csv(_write(tmp_path / "plain.csv", c))  # the reader's own names: no word


def _reversing_drive(sigma=3.0):
    """East at 10 m/s, a stop, 8 s of reversing at up to 2 m/s (14 m), a stop, east again: 10 Hz
    signed speed, the gyro heading (the car's nose, east throughout), 1 Hz fixes and the truth."""
    t = 0.1 * np.arange(1201)
    v = np.interp(t, [0, 30, 35, 40, 41, 47, 48, 53, 60, 120], [10, 10, 0, 0, -2, -2, 0, 0, 10, 10])
    e = np.r_[0.0, np.cumsum(v[1:] * 0.1)]
    rng = np.random.default_rng(5)
    fix = np.arange(len(t)) % 10 == 0
    return t, v, e, fix, rng.normal(0.0, sigma, (len(t), 2))


def test_a_signed_speed_reverses_the_car_along_its_heading():
    """A signed speed below -0.05 m/s is the car reversing: the heading there is turned half a turn, with a
    warning, and the dead reckoning ends where the car did; given the unsigned speed (the remedy the reader
    once asked for) it ends twice the reversed distance off. Each 8-state kind with the phone grade, its
    fixes gone from 25 to 70 s (the reversing inside), ends that outage as close as on the same drive with
    the car standing instead of reversing, where the unsigned speed ends over 20 m off."""
    from filterwnn import GPSDRFilter
    from filterwnn.navigation.dead_reckoning import GPSDRModel
    from filterwnn.navigation.scenarios import with_outage

    t, v, e, fix, noise = _reversing_drive()
    gps = dict(gps_t=t[fix], east=e[fix] + noise[fix, 0], north=noise[fix, 1], gps_sigma=3.0,
               truth=np.stack([e, np.zeros_like(e)], axis=1))
    heading = np.full(len(t), np.pi / 2)
    with pytest.warns(RuntimeWarning, match=r"the speed is negative on 79 sample\(s\), the first at t = 40.1 s: "
                                            r"the car reversed, 14 m in all; there the heading is turned by 180"):
        run = DRRun.from_arrays(t, heading, speed=v, **gps)
    back = v[1:] < -0.05
    np.testing.assert_allclose(run.z_dr[back, 0], -np.pi / 2)
    np.testing.assert_allclose(run.z_dr[~back, 0], np.pi / 2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        unsigned = DRRun.from_arrays(t, heading, speed=np.abs(v), **gps)

    def dr_end(r):
        return r.x0[0] + np.sum(r.z_dr[:, 1] * np.sin(r.z_dr[:, 0]))

    assert abs(dr_end(run) - e[-1]) < 0.2 and abs(dr_end(unsigned) - e[-1]) > 26.0
    assert run.reversed_by_speed and not unsigned.reversed_by_speed
    stands = np.maximum(v, 0.0)  # the control: the car stands instead of reversing
    es = np.r_[0.0, np.cumsum(stands[1:] * 0.1)]
    control = DRRun.from_arrays(t, heading, speed=stands, **{**gps, "east": es[fix] + noise[fix, 0],
                                                              "truth": np.stack([es, np.zeros_like(es)], axis=1)})
    for kind in ("ekf", "ukf", "sukf"):
        ends = []
        for r in (run, control, unsigned):
            r = with_outage(r, start=25.0, length=45.0)
            model = GPSDRModel.from_grade("phone", r.scenario.dt)
            kf = GPSDRFilter(model, kind, x0=np.r_[r.x0, model.x0[6:]])
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                est = kf.batch_filter(r.z_dr, r.gps_list(), r.gps_sigma_list())
            k = np.searchsorted(r.t, 70.0) - 1
            ends.append(float(np.hypot(est[k, 0] - r.x_true[k, 0], est[k, 3] - r.x_true[k, 3])))
        assert ends[0] < ends[1] + 0.5 and ends[2] > 20.0, (kind, ends)  # 3.53, 3.74, 31.66 m with the EKF


def _unsigned_reversing_run(offset=None, speed=None):
    """The reversing drive with its speed unsigned (a CAN speed), its fixes optionally displaced by ``offset``
    (east, m, per sample), or the car driving ``speed`` instead (a car that never reverses)."""
    t, v, e, fix, noise = _reversing_drive()
    v = v if speed is None else speed
    truth = np.r_[0.0, np.cumsum(v[1:] * 0.1)]
    off = np.zeros_like(t) if offset is None else offset
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return DRRun.from_arrays(t, np.full(len(t), np.pi / 2), speed=np.abs(v), gps_t=t[fix],
                                 east=truth[fix] + noise[fix, 0] + off[fix], north=noise[fix, 1], gps_sigma=3.0,
                                 truth=np.stack([truth, np.zeros_like(truth)], axis=1))


def _errors(run, kind, **kw):
    from filterwnn import GPSDRFilter
    from filterwnn.navigation.dead_reckoning import GPSDRModel

    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    kf = GPSDRFilter(model, kind, x0=np.r_[run.x0, model.x0[6:]], **kw)
    est = kf.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    return kf, np.hypot(est[:, 0] - run.x_true[:, 0], est[:, 3] - run.x_true[:, 3])


def test_the_study_tests_the_fixes_for_reversing_only_where_the_speed_could_not_tell(monkeypatch):
    """A signed speed that told the car reversing has its reversals in the dead reckoning: the fixes' test for one
    could then only be wrong (a new user's drive with a signed speed was warned of reversing by it, stop 59), so
    the study runs the filters without it there, and with it on an unsigned speed."""
    import filterwnn.studies.dr._real as real

    t, v, e, fix, noise = _reversing_drive()
    gps = dict(gps_t=t[fix], east=e[fix] + noise[fix, 0], north=noise[fix, 1], gps_sigma=3.0,
               truth=np.stack([e, np.zeros_like(e)], axis=1))
    seen = []
    monkeypatch.setattr(real, "_score_filter", lambda out, name, run, windows, use, settings, *progress: seen.append(
        settings["filter_kw"]["reversing_test"]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for speed in (v, np.abs(v)):
            run = DRRun.from_arrays(t, np.full(len(t), np.pi / 2), speed=speed, **gps)
            real.real_drive_outages(run, filters=("EKF-8",), length=10.0, starts=[20.0])
    assert seen == [False, True]


def test_the_fixes_tell_a_car_reversing_on_an_unsigned_speed():
    """A CAN speed is unsigned: dead reckoning takes the 14 m the car reverses (40-48 s) forward, and the
    fixes, there all the time, part from it at twice the distance. The filter's reversing test finds it from
    the fixes after the stop (Wald's test at 1e-9, at the sixth fix), warns once with the step, turns
    the stretch's headings and velocity, and every kind stays within 4 m of the truth from 48 s on; without
    the test the fixes are first down-weighted, then rejected, and the filter ends the reversing over 20 m off
    (26.4 m with the EKF) until it re-acquires."""
    run = _unsigned_reversing_run()
    after = run.t >= 48.0
    for kind in ("ekf", "ukf", "sukf"):
        with pytest.warns(RuntimeWarning, match=r"GPSDRFilter: the fixes show the car reversing at step 4\d\d, since "
                                                r"step 4\d\d \(\d fixes, a log-likelihood ratio of [\d.]+ against "
                                                r"driving forward, [\d.]+ m\): its speed is unsigned"):
            kf, err = _errors(run, kind)
        assert kf.n_reversing == 1 and 430 <= kf.reversing_steps[0] < 480, (kind, kf.reversing_steps)
        assert err[after].max() < 4.0, (kind, err[after].max())  # 2.93 m with the EKF
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            off, err_off = _errors(run, kind, reversing_test=False)
        assert off.n_reversing == 0 and err_off[after].max() > 20.0, (kind, err_off[after].max())


def test_a_one_hz_log_that_reverses_with_no_standing_sample_turns_twice():
    """At 1 Hz a car that stops for an instant, reverses 16 m and drives on may show no standing sample (here
    0.5 m/s at the slowest): the test, running while the car moves, finds it reversing and then driving forward
    again, each warned once with its step; the EKF-8 is at most 26.3 m off (34.0 m without), the error the
    fixes' clipped shares of the test take to tell the turns (it drives on at 10 m/s while they do)."""
    fine = 0.01 * np.arange(12001)
    v_fine = np.interp(fine, [0, 30, 35.5, 37.5, 45.5, 47.5, 55, 120], [10, 10, 0, -2, -2, 0, 10, 10])
    e_fine = np.r_[0.0, np.cumsum((v_fine[1:] + v_fine[:-1]) / 2 * 0.01)]
    t = np.arange(121.0)
    v, e = np.interp(t, fine, v_fine), np.interp(t, fine, e_fine)
    assert np.abs(v).min() == 0.5
    noise = np.random.default_rng(5).normal(0.0, 3.0, (len(t), 2))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        run = DRRun.from_arrays(t, np.full(len(t), np.pi / 2), speed=np.abs(v), gps_t=t, east=e + noise[:, 0],
                                north=noise[:, 1], gps_sigma=3.0, truth=np.stack([e, np.zeros_like(e)], axis=1))
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        kf, err = _errors(run, "ekf")
    said = [str(w.message) for w in seen]
    assert any("show the car reversing at step 4" in m for m in said), said
    assert any("show the car driving forward again at step 5" in m for m in said), said
    assert (kf.n_reversing, kf.n_forward_again) == (1, 1) and err.max() < 30.0, (kf.reversing_steps, err.max())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        _, err_off = _errors(run, "ekf", reversing_test=False)
    assert err_off.max() > 30.0


def test_a_drive_that_parks_reversing_into_each_space_on_an_unsigned_speed(tmp_path):
    """Eight parking manoeuvres, each reversing 12 m while turning 45 degrees, with 4 m fixes every second
    (``_held_out_drives.parking_drive``, seed 52), read from its CSV: the EKF-8 takes six of the eight for
    reversing, none for forward again, and its error over the drive (fixes all the time) has a median of 1.12 m
    against 2.79 m without the test."""
    path = held_out.write_csv(tmp_path / "parking.csv", held_out.parking_drive(np.random.default_rng(52)))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        run = read_drive_csv(path)
        kf, err = _errors(run, "ekf")
        _, err_off = _errors(run, "ekf", reversing_test=False)
    assert kf.n_reversing >= 5 and kf.n_forward_again == 0, kf.reversing_steps
    assert np.median(err) < 0.6 * np.median(err_off), (np.median(err), np.median(err_off))


@pytest.mark.parametrize("jump, length", [(20.0, 10.0), (60.0, 20.0)])
def test_fixes_displaced_backward_as_the_car_pulls_away_are_not_reversing(jump, length):
    """A car that only drives forward, pulling away slowly (to 2 m/s in 8 s) while its fixes sit ``jump`` m
    behind for ``length`` s (a street's multipath): their displacement grows against the dead reckoning's as
    a reversing car's would at first. The test's second path, with a constant unknown offset of the fixes,
    keeps it from reading as reversing (without it, the first version of the test turned every kind round
    and left it 44-83 m off); no kind takes it for reversing."""
    t = 0.1 * np.arange(1201)
    speed = np.interp(t, [0, 30, 35, 40, 48, 120], [10, 10, 0, 0, 2, 2])
    run = _unsigned_reversing_run(offset=np.where((t >= 40.0) & (t < 40.0 + length), -jump, 0.0), speed=speed)
    for kind in ("ekf", "ukf", "sukf"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            kf, _ = _errors(run, kind)
        assert kf.n_reversing == 0, kind


def test_the_drive_table_counts_the_stretches_taken_as_reversing(command_passes):
    """``filterwnn study dr --drive`` reports the stretches taken as reversing after the fixes' counts, and
    ``--no-reversing-test`` switches the test off."""
    from filterwnn.studies.dr import real_drive_outages, real_drive_table

    run = _unsigned_reversing_run()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = real_drive_outages(run, filters=("EKF-8",), starts=[80.0], use_gps_sigma=True, grade="phone")
    assert res["integrity"]["EKF-8"]["n_reversing"] == 1
    assert " (1 reversing) |" in real_drive_table(res)
    assert command_passes("real_drive_outages", ["--no-reversing-test"])["reversing_test"] is False
    assert command_passes("real_drive_outages", [])["reversing_test"] is True


def _crawl_run(crawl=True, sigma=3.0, jump=None, tau=None, stop=50.0, seed=5):
    """East at 10 m/s, a stop at 35 s, a crawl at 0.5 m/s from 40 to 80 s (19.5 m) whose speed reads 0 (a
    wheel-speed sensor's 0.8 m/s cutoff), a stop, east again at 85 s: 10 Hz, 1 Hz fixes of ``sigma`` m with that
    sigma, and the truth. ``crawl=False``: the car stands for ``stop`` s instead; ``jump=(m, t0, t1)``: the fixes
    that many metres ahead (east) from t0 to t1 s; ``tau``: the fixes' errors a first-order Gauss-Markov process
    of that correlation time (s), as a phone's."""
    t = 0.1 * np.arange(int((stop + 80.0) * 10) + 1)
    if crawl:
        v = np.interp(t, [0, 30, 35, 40, 41, 79, 80, 85, 90, 130], [10, 10, 0, 0, 0.5, 0.5, 0, 0, 10, 10])
    else:
        v = np.interp(t, [0, 30, 35, 35 + stop, 40 + stop, t[-1]], [10, 10, 0, 0, 10, 10])
    e = np.r_[0.0, np.cumsum(v[1:] * 0.1)]
    rng = np.random.default_rng(seed)
    fix = np.arange(len(t)) % 10 == 0
    noise = rng.normal(0.0, sigma, (fix.sum(), 2))
    if tau is not None:
        a = np.exp(-1.0 / tau)
        for i in range(1, len(noise)):
            noise[i] = a * noise[i - 1] + np.sqrt(1.0 - a * a) * noise[i]
    off = np.zeros(len(t)) if jump is None else np.where((t >= jump[1]) & (t < jump[2]), jump[0], 0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return DRRun.from_arrays(t, np.full(len(t), np.pi / 2), speed=np.where(v < 0.8, 0.0, v), gps_t=t[fix],
                                 east=e[fix] + noise[:, 0] + off[fix], north=noise[:, 1], gps_sigma=sigma,
                                 truth=np.stack([e, np.zeros_like(e)], axis=1))


def test_the_fixes_tell_a_car_creeping_while_its_speed_reads_zero():
    """A speed that reads 0 below a cutoff makes a car creeping 19.5 m through a queue a standing one, and the
    zero-velocity update holds it where it stopped: every kind is over 12 m off from when the car drives on (90 s)
    to the end. The crawl test finds it from the fixes (at 68.9 s, 18.5 m along the heading), warns once with the
    step, moves the position to the fixes' crawl, and every kind is under 6 m off from 90 s on (3.92-3.96 m)."""
    run = _crawl_run()
    after = run.t >= 90.0
    for kind in ("ekf", "ukf", "sukf"):
        with pytest.warns(RuntimeWarning, match=r"GPSDRFilter: the fixes show the car creeping at step [67]\d\d while "
                                                r"its speed reads 0, since step 3\d\d \(\d\d fixes, a log-likelihood "
                                                r"ratio of [\d.]+ against standing, [\d.]+ m along its heading"):
            kf, err = _errors(run, kind)
        assert kf.n_crawl >= 1 and 600 <= kf.crawl_steps[0] < 760 and kf.crawl_moved > 10.0, (kind, kf.crawl_steps)
        assert err[after].max() < 6.0, (kind, err[after].max())
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            off, err_off = _errors(run, kind, crawl_test=False)
        assert off.n_crawl == 0 and err_off[after].max() > 10.0, (kind, err_off[after].max())


@pytest.mark.parametrize("seed", [0, 4])
def test_a_standing_car_whose_fixes_wander_together_is_not_taken_for_creeping(seed):
    """Two minutes at a standstill with fixes whose 5 m errors wander together (correlated over 20 s, as a
    phone's): a crawl fits them better than standing now and then, but not by the test's 1e-9 with their offset
    free (its statistic at most 7.6 of 20.7 on 40 seeds, seed 4's, ``sensor-faults/crawl_test.txt``); and fixes
    20 m ahead for 10 s or 40 s of a 50 s stop (multipath) fit a jump better than a crawl. No decision, the filter
    as without the test."""
    runs = [_crawl_run(crawl=False, sigma=5.0, tau=20.0, stop=120.0, seed=seed),
            _crawl_run(crawl=False, jump=(20.0, 40.0 + 5.0 * seed, 50.0 + 5.0 * seed), seed=seed)]
    if seed == 0:
        runs.append(_crawl_run(crawl=False, jump=(20.0, 40.0, 80.0), seed=seed))
    for run in runs:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            kf, err = _errors(run, "ekf")
            _, err_off = _errors(run, "ekf", crawl_test=False)
        assert kf.n_crawl == 0, kf.crawl_steps
        np.testing.assert_array_equal(err, err_off)


@pytest.mark.parametrize("at", [36.0, 37.0])
def test_a_far_fix_with_a_far_larger_sigma_early_in_a_stop_is_no_crawl(at):
    """A receiver that writes a placeholder fix (500 m ahead, sigma 9999 m) as the car stands: the crawl test's fit
    after two fixes, one of them that one, was an offset and a speed that met it exactly (47 m/s), the next fixes
    were clipped towards that fit, and the test moved a standing car 146 m (found on the 1 Hz analog with 5 % of
    its fixes so; here 1,736 m with the placeholder the stop's second fix). The clip now counts the fit's own
    uncertainty: no decision, and the filter as without the test."""
    run = _crawl_run(crawl=False, stop=50.0, seed=3)
    k = int(np.flatnonzero(np.isclose(run.t[run.gps_steps], at))[0])
    z, sig = run.z_gps.copy(), np.full(len(run.gps_steps), 3.0)
    z[k] += [500.0, -100.0]
    sig[k] = 9999.0
    run = run._replace(z_gps=z, gps_sigma=sig)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        kf, err = _errors(run, "ekf")
        _, err_off = _errors(run, "ekf", crawl_test=False)
    assert kf.n_crawl == 0, (kf.crawl_steps, kf.crawl_moved)
    np.testing.assert_array_equal(err, err_off)


def test_the_drive_table_counts_the_crawls_found(command_passes):
    """``filterwnn study dr --drive`` reports the crawls found after the fixes' counts, and ``--no-crawl-test``
    switches the test off."""
    from filterwnn.studies.dr import real_drive_outages, real_drive_table

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = real_drive_outages(_crawl_run(), filters=("EKF-8",), starts=[95.0], use_gps_sigma=True, grade="phone")
    assert res["integrity"]["EKF-8"]["n_crawl"] >= 1 and res["integrity"]["EKF-8"]["crawl_moved"] > 10.0
    assert f" ({res['integrity']['EKF-8']['n_crawl']} crawling) |" in real_drive_table(res)
    assert command_passes("real_drive_outages", ["--no-crawl-test"])["crawl_test"] is False
    assert command_passes("real_drive_outages", [])["crawl_test"] is True


def test_an_odometers_latency_reads_each_speed_where_it_was_measured(tmp_path):
    """A CAN speed 0.5 s late (5 samples at 10 Hz) through stops and starts: with ``odometer_latency=0.5``
    the steps are the honest speed's but for the last 0.5 s (the last sample held); a cumulative odometer
    late by as much reads the same way (within its increments' read to each sample's time, 8e-5 m for this
    speed's curvature); a speed 0.5 s early reads back with -0.5 (the first sample held)."""
    c = _drive()
    c["speed"] = 5.0 + 5.0 * np.sin(0.3 * c["time"])  # 0 to 10 m/s
    honest = read_drive_csv(_write(tmp_path / "h.csv", c), checks=False)
    late = {**c, "speed": np.r_[np.full(5, c["speed"][0]), c["speed"][:-5]]}
    path = _write(tmp_path / "late.csv", late)
    as_logged = read_drive_csv(path, checks=False)
    run = read_drive_csv(path, checks=False, odometer_latency=0.5)
    np.testing.assert_allclose(run.z_dr[:-5], honest.z_dr[:-5], rtol=0, atol=1e-9)
    assert np.max(np.abs(as_logged.z_dr[:-5, 1] - honest.z_dr[:-5, 1])) > 0.07  # 0.5 s of 1.5 m/s^2: 0.075 m
    t = c["time"] - 0.5  # the odometer 0.5 s late: the integral of the speed up to then
    odo = 5.0 * t - 5.0 / 0.3 * np.cos(0.3 * t)
    cols = ["time", "heading", "odometer", "gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"]
    run = read_drive_csv(_write(tmp_path / "odo.csv", {**late, "odometer": odo}, columns=cols), checks=False,
                         odometer_latency=0.5)
    np.testing.assert_allclose(run.z_dr[5:-6, 1], honest.z_dr[5:-6, 1], rtol=0, atol=1e-4)
    early = {**c, "speed": np.r_[c["speed"][5:], np.full(5, c["speed"][-1])]}
    run = read_drive_csv(_write(tmp_path / "early.csv", early), checks=False, odometer_latency=-0.5)
    np.testing.assert_allclose(run.z_dr[6:, 1], honest.z_dr[6:, 1], rtol=0, atol=1e-9)
    with pytest.raises(ValueError, match=r"odometer_latency must be a finite number of seconds \(negative"):
        read_drive_csv(path, odometer_latency=np.nan)


def test_a_cumulative_odometer_gives_each_sample_the_speed_at_its_own_time(tmp_path):
    """An odometer's increment over an interval is the mean speed over it, the speed at the interval's middle; the
    models measure the speed at each sample, so the reader interpolates the means beside each sample to its time.
    A car at 1 Hz pulling away at 1.5 m/s^2: each step is the speed at its sample times 1 s, as its speed column
    gives it; taken as the speed at the interval's end (the reader until stop 49) each was the speed 0.5 s
    before, 0.75 m short. At a constant speed nothing changes, and a jittered stamp keeps its own interval."""
    c = _drive(n=21, dt=1.0)
    t = c["time"]
    accel = {**c, "speed": 1.5 * t}
    cols = ["time", "heading", "odometer", "gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"]
    from_speed = read_drive_csv(_write(tmp_path / "v.csv", accel), checks=False)
    from_odo = read_drive_csv(_write(tmp_path / "o.csv", {**accel, "odometer": 0.75 * t ** 2}, columns=cols),
                              checks=False)
    np.testing.assert_allclose(from_odo.z_dr[:-1, 1], from_speed.z_dr[:-1, 1], rtol=0, atol=1e-9)
    np.testing.assert_allclose(from_odo.z_dr[:-1, 1], 1.5 * t[1:-1], rtol=0, atol=1e-9)
    assert from_odo.z_dr[-1, 1] == pytest.approx(1.5 * (t[-1] - 0.5))  # the last sample: its one interval's mean
    assert from_odo.x0[1] ** 2 + from_odo.x0[4] ** 2 == pytest.approx(0.75 ** 2)  # the first: its one interval's
    steady = read_drive_csv(_write(tmp_path / "s.csv", {**c, "odometer": 10.0 * t}, columns=cols), checks=False)
    np.testing.assert_allclose(steady.z_dr[:, 1], 10.0, rtol=0, atol=1e-9)
    t = t + np.where(np.arange(len(t)) == 10, 0.05, 0.0)  # one stamp 50 ms late
    jitter = read_drive_csv(_write(tmp_path / "j.csv", {**c, "time": t, "odometer": 10.0 * t}, columns=cols),
                            checks=False, intervals="stamps")
    np.testing.assert_allclose(jitter.z_dr[:, 1], 10.0 * np.diff(t), rtol=0, atol=1e-9)


def test_a_log_with_the_heading_and_the_speed_on_rows_of_their_own_reads_the_sparser_at_its_times(tmp_path):
    """A log with a row per sensor message whose gyro heading (10 Hz) and wheel speed (5 Hz, 4 ms after the
    heading) each come on rows of their own, the fixes on theirs (1 Hz, 30 ms after a heading): refused before
    ("has a 'heading' but no 'speed'"). The DR samples are now the speed's rows, the heading interpolated to their
    times along the shorter arc (here it turns steadily through north: exact), each fix at its own time. The
    other way round (the speed the denser), the heading's rows are the samples. A row with none of them is
    refused, naming its line."""
    c = _drive(n=601, bearing=-0.3, turn=0.02)  # through north at t = 15 s
    t = c["time"]
    rows = {k: [] for k in c}

    def add(time, **cells):
        for key in c:
            rows[key].append(time if key == "time" else cells.get(key, np.nan))

    for k in range(len(t)):
        add(t[k], heading=c["heading"][k])
        if k % 2 == 0:
            add(t[k] + 0.004, speed=10.0)
        if k % 10 == 0:
            add(t[k] + 0.03, **{key: c[key][k] for key in ("gps_lat", "gps_lon", "gps_sigma")})
    log = {k: np.array(v) for k, v in rows.items()}
    cols = ["time", "heading", "speed", "gps_lat", "gps_lon", "gps_sigma"]
    run = read_drive_csv(_write(tmp_path / "apart.csv", log, columns=cols), checks=False)
    assert run.scenario.dt == pytest.approx(0.2) and len(run.z_dr) == 300 and len(run.gps_steps) == 60
    want = np.mod(-0.3 + 0.02 * (t[2::2] + 0.004), 2 * np.pi)
    np.testing.assert_allclose(np.mod(run.z_dr[:-1, 0], 2 * np.pi), want[:-1], rtol=0, atol=1e-9)  # the last: held
    np.testing.assert_allclose(run.z_dr[:, 1], 2.0, rtol=0, atol=1e-9)
    np.testing.assert_allclose(run.gps_offset, 0.026, rtol=0, atol=1e-9)  # 30 ms after a heading, 4 ms after a speed
    extra = {key: t + 0.05 if key == "time" else np.full(len(t), 10.0 if key == "speed" else np.nan) for key in log}
    with_more = {key: np.r_[log[key], extra[key]] for key in log}  # a speed row 50 ms after each heading too: 15 Hz
    order = np.argsort(with_more["time"], kind="stable")
    with_more = {key: v[order] for key, v in with_more.items()}
    run = read_drive_csv(_write(tmp_path / "denser.csv", with_more, columns=cols), checks=False)
    assert run.scenario.dt == pytest.approx(0.1) and len(run.z_dr) == 600
    np.testing.assert_allclose(run.z_dr[:, 1], 1.0, rtol=0, atol=1e-9)
    empty = {k: v.copy() for k, v in log.items()}
    empty["heading"][3] = np.nan  # the fourth row, a heading's, left with nothing
    with pytest.raises(ValueError, match=r"data row 4 \(line 5\) has no 'heading', no 'speed' and no fix: in a log "
                                         r"with a row per sensor message \(the 'heading' and the 'speed' each on rows"):
        read_drive_csv(_write(tmp_path / "empty.csv", empty, columns=cols), checks=False)


def test_lat_lon_as_nmea_degrees_and_minutes_are_refused_naming_them(tmp_path):
    """A log that copies GGA's latitude and longitude as written (ddmm.mmmm: 4808.2 for 48 degrees 8.2 minutes) is
    refused, naming the format and the conversion."""
    c = _drive()
    for k in ("gps_lat", "gps_lon"):
        d = np.floor(c[k])
        c[k] = d * 100.0 + (c[k] - d) * 60.0
    with pytest.raises(ValueError, match=r"lat/lon must be degrees .* they read as NMEA's degrees and minutes "
                                         r"\(ddmm.mmmm, .*\): give degrees, floor\(x / 100\) \+ \(x % 100\) / 60"):
        read_drive_csv(_write(tmp_path / "d.csv", c))


def test_a_yaw_rate_spike_is_interpolated_before_it_is_integrated(tmp_path):
    """A gyro's glitch in a yaw-rate column (1.5 rad/s for a sample, where the car at 10 m/s turns at most 1 rad/s)
    would turn every later heading by its excess: interpolated from its neighbours first, with a warning, and the
    drive reads as without it."""
    c = _drive()
    cols = ["time", "yaw_rate", "speed", "gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"]
    rate = {**c, "yaw_rate": np.full(len(c["time"]), 0.02)}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (the start's warning)
        clean = read_drive_csv(_write(tmp_path / "clean.csv", rate, columns=cols))
    rate["yaw_rate"] = rate["yaw_rate"].copy()
    rate["yaw_rate"][[300, 301, 800]] = 1.5
    with pytest.warns(RuntimeWarning, match=r"3 yaw rate sample\(s\) in 2 run\(s\) turn faster than a car can at its "
                                            r"speed .* the first at t = 30 s, \+1.5 rad/s at 10 m/s"):
        run = read_drive_csv(_write(tmp_path / "spiked.csv", rate, columns=cols))
    np.testing.assert_allclose(run.z_dr, clean.z_dr, atol=1e-9)


def test_a_receivers_cold_start_does_not_start_a_yaw_rates_heading(tmp_path):
    """An eighth user's receiver started cold: 55 s of fixes up to 322 m off, reporting up to 260 m (stop 75). The
    line through the moving stretches' angles that starts a yaw rate's heading weighed those stretches like the
    others: the heading started 7 degrees off and the drift read as a gyro warming up (EKF-8 7.35 / 45.98 m against
    4.44 / 19.84 with those fixes dropped by hand). Fixes reporting more than ``START_SIGMA_FACTOR`` times the median
    sigma no longer start it: the heading reads back within 0.5 degree, as without the cold start."""
    from filterwnn.navigation.scenarios import START_SIGMA_FACTOR

    c = _drive()
    cols = ["time", "yaw_rate_deg", "speed", "gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"]
    rate = {**c, "yaw_rate_deg": np.full(len(c["time"]), np.degrees(0.02))}
    cold = {k: v.copy() for k, v in rate.items()}
    t = c["time"]
    first = (t < 40.0) & np.isfinite(c["gps_lat"])
    off = 300.0 * np.exp(-t[first] / 12.0)  # a cold start's error, shrinking, its direction swinging
    lat0, lon0 = c["gps_lat"][first], c["gps_lon"][first]
    cold["gps_lat"][first] = lat0 + np.degrees(off * np.cos(0.15 * t[first]) / 6.371e6)
    cold["gps_lon"][first] = lon0 + np.degrees(off * np.sin(0.15 * t[first]) / 6.371e6 / np.cos(np.radians(lat0)))
    cold["gps_sigma"][first] = np.maximum(3.0, 0.8 * off)
    assert np.sum(cold["gps_sigma"][first] > START_SIGMA_FACTOR * 3.0) >= 15
    want = read_drive_csv(_write(tmp_path / "heading.csv", c))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(_write(tmp_path / "cold.csv", cold, columns=cols))
    d = np.degrees(np.abs((run.z_dr[:, 0] - want.z_dr[:, 0] + np.pi) % (2 * np.pi) - np.pi))
    assert d.max() < 0.5, d.max()


def test_a_yaw_rate_is_integrated_and_started_at_the_fixes_course(tmp_path):
    """A log with the gyro's yaw rate in place of a heading (``yaw_rate_deg``, clockwise positive): the reader
    integrates it and starts it at the heading the fixes' course gives, with a warning naming it (the drive turns
    steadily from 34.4 deg at 0.02 rad/s: the heading read back within 0.5 deg). A yaw rate counter-clockwise
    positive (ROS, ENU) is refused naming its sign; a yaw rate in deg/s given as rad/s, both a heading and a yaw rate, a heading offset with a yaw rate, and a drive with too few moving
    stretches between fixes to start it are refused, each saying so."""
    c = _drive()
    cols = ["time", "yaw_rate_deg", "speed", "gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"]
    rate = {**c, "yaw_rate_deg": np.full(len(c["time"]), np.degrees(0.02))}
    with pytest.warns(RuntimeWarning, match=r"the heading is the yaw rate integrated from 34.\d \+- \d deg at the "
                                            r"start, the fixes' course over \d+ moving stretches"):
        run = read_drive_csv(_write(tmp_path / "yaw.csv", rate, columns=cols))
    want = read_drive_csv(_write(tmp_path / "heading.csv", c))
    d = np.degrees(np.abs((run.z_dr[:, 0] - want.z_dr[:, 0] + np.pi) % (2 * np.pi) - np.pi))
    assert d.max() < 0.5, d.max()
    np.testing.assert_allclose(run.z_dr[:, 1], want.z_dr[:, 1])
    t, h, v = c["time"], c["heading"], c["speed"]
    with pytest.raises(ValueError, match=r"yaw_rate must be in rad/s; max \|yaw_rate\| = 65.6 is past 3 rad/s"):
        DRRun.from_arrays(t, yaw_rate=np.full(len(t), 65.6), speed=v)  # 65.6 deg/s, a sharp turn
    with pytest.raises(ValueError, match=r"give exactly one of heading \(rad\) and yaw_rate \(rad/s\), got both"):
        DRRun.from_arrays(t, h, yaw_rate=np.zeros(len(t)), speed=v)
    with pytest.raises(ValueError, match=r"heading_offset has no meaning with a yaw rate"):
        DRRun.from_arrays(t, yaw_rate=np.zeros(len(t)), speed=v, heading_offset=5.0)
    with pytest.raises(ValueError, match=r"a yaw rate gives the heading but for its start, which the fixes' course "
                                         r"gives: the drive has 0 moving stretch\(es\) between fixes"):
        DRRun.from_arrays(t, yaw_rate=np.zeros(len(t)), speed=v)
    ccw = {**rate, "yaw_rate_deg": -rate["yaw_rate_deg"]}  # counter-clockwise positive, as ROS and ENU count it
    with warnings.catch_warnings(record=True) as seen, \
            pytest.raises(ValueError, match=r"the yaw rate turns the wrong way .* give it clockwise positive, a right "
                                            r"turn positive"):
        warnings.simplefilter("always")
        read_drive_csv(_write(tmp_path / "ccw.csv", ccw, columns=cols))
    # the start is named once the drive passes its checks (stop 58): a refused one's would mislead
    assert not [w for w in seen if "integrated from" in str(w.message)]
    with pytest.raises(ValueError, match=r"name the column yaw_rate_deg, or write it in rad/s"):
        read_drive_csv(_write(tmp_path / "deg.csv", {**c, "yaw_rate": np.full(len(t), 5.0)},
                              columns=["time", "yaw_rate"] + cols[2:]))


def test_a_truth_on_rows_of_its_own_in_a_log_with_a_row_per_message_is_read_at_the_samples_times(tmp_path):
    """A reference (an INS's solution) logged on rows of its own beside a log with a row per message: each sample
    takes it interpolated to its time; before, its rows were refused as rows with no heading, no speed and no fix.
    The drive with its truth on its own rows 50 ms after each heading reads as with the truth on the heading's rows
    (to 1 mm: the track is nearly straight over 50 ms)."""
    c = _drive(n=301)
    t = c["time"]
    keys = list(c)
    on_rows, apart = {k: [] for k in keys}, {k: [] for k in keys}

    def add(log, time, **cells):
        for key in keys:
            log[key].append(time if key == "time" else cells.get(key, np.nan))

    for k in range(len(t)):
        truth = {key: c[key][k] for key in ("true_lat", "true_lon")}
        add(on_rows, t[k], heading=c["heading"][k], **truth)
        add(apart, t[k], heading=c["heading"][k])
        for log in (on_rows, apart):
            add(log, t[k] + 0.004, speed=10.0)
            if k % 10 == 0:
                add(log, t[k] + 0.03, **{key: c[key][k] for key in ("gps_lat", "gps_lon", "gps_sigma")})
        later = k + 1 if k + 1 < len(t) else k  # the reference 50 ms after the heading: halfway to the next
        add(apart, t[k] + 0.05, true_lat=0.5 * (c["true_lat"][k] + c["true_lat"][later]),
            true_lon=0.5 * (c["true_lon"][k] + c["true_lon"][later]))
    want = read_drive_csv(_write(tmp_path / "on.csv", {k: np.array(v) for k, v in on_rows.items()}), checks=False)
    run = read_drive_csv(_write(tmp_path / "apart.csv", {k: np.array(v) for k, v in apart.items()}), checks=False)
    assert run.has_truth and run.x_true.shape == want.x_true.shape
    np.testing.assert_allclose(run.x_true[:-1, [0, 3]], want.x_true[:-1, [0, 3]], rtol=0, atol=1e-3)


def test_each_fix_lands_on_the_sample_nearest_its_time_when_the_intervals_vary():
    """One sample in ten 15 ms late (within max_jitter): the median interval is 0.1 s and the mean 0.1015 s,
    so t0 + k dt drifted from the samples, and after 1000 s the fixes landed 15 s (148 samples) early."""
    dts = np.where(np.arange(10000) % 10 == 9, 0.115, 0.1)
    t = np.r_[0.0, np.cumsum(dts)]
    gps_t = np.arange(1.0, t[-1], 1.0)
    # 4.5 ms at 10 m/s: 0.045 m a step; the intervals vary independently (lag-1 correlation -0.11), not
    # about a grid, so each speed keeps its stamped interval
    with pytest.warns(RuntimeWarning, match=r"sample times jitter .* lag-1 correlation -0.11, not below -0.25"):
        run = DRRun.from_arrays(t, np.zeros(len(t)), speed=np.full(len(t), 10.0), gps_t=gps_t,
                                east=np.zeros(len(gps_t)), north=10.0 * gps_t, checks=False)
    assert run.scenario.dt == 0.1 and len(run.gps_steps) == len(gps_t)
    # sample gps_steps + 1 is the fix's step's end: within half an interval of the fix's time
    assert np.max(np.abs(t[run.gps_steps + 1] - gps_t)) <= 0.0575 + 1e-9


def test_fixes_between_slow_samples_keep_their_offset_and_the_filter_moves_them_to_the_sample():
    """A fix is placed on the DR sample nearest its time. At 1 Hz, fixes logged 0.4 s past each sample were each
    used 0.4 s off, and a ``gps_latency`` of 0.3 s moved no fix (each landed on its own sample again): the run
    now keeps each fix's time less its sample's (``gps_offset``), and ``GPSDRFilter`` moves the fix back along
    its velocity. A car at 10 m/s with exact fixes 0.4 s after their samples: 4 m behind with the fixes as
    placed, on the truth with their offsets. Fixes on the samples keep none (every output as before)."""
    from filterwnn.navigation.dead_reckoning import GPSDRModel
    from filterwnn.navigation.gpsdr import GPSDRFilter

    def read(dt, offset, **kw):
        t = dt * np.arange(int(100 / dt) + 1)
        gps_t = np.arange(1.0, 99.0, 1.0) + offset
        return DRRun.from_arrays(t, np.zeros(len(t)), speed=np.full(len(t), 10.0), gps_t=gps_t,
                                 east=np.zeros(len(gps_t)), north=10.0 * gps_t, gps_sigma=0.5, checks=False,
                                 truth=np.stack([np.zeros(len(t)), 10.0 * t], axis=1), **kw)

    run = read(1.0, 0.4)
    np.testing.assert_allclose(run.gps_offset, 0.4, rtol=0, atol=1e-12)
    np.testing.assert_allclose(read(1.0, 0.0, gps_latency=0.3).gps_offset, -0.3, rtol=0, atol=1e-12)
    assert read(1.0, 0.0).gps_offset is None and read(0.1, 0.0, gps_latency=0.3).gps_offset is None
    assert with_outage(run, 20.0, 10.0).gps_offset.shape == (len(run.gps_steps) - 10,)
    errors = []
    for offsets in (None, run.gps_offset_list()):
        model = GPSDRModel.from_grade("phone", 1.0)
        kf = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            est = kf.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), offsets)
        errors.append(float(np.median(np.abs(est[10:60, 3] - run.x_true[10:60, 3]))))
    assert errors[0] > 3.0 and errors[1] < 0.3, errors
    with pytest.raises(ValueError, match=r"gps_offset must be a finite number of seconds"):
        kf.update(run.z_dr[0], [0.0, 0.0], None, np.nan)


def test_from_arrays_checks_too():
    c = _drive()
    fix = ~np.isnan(c["gps_lat"])
    with pytest.raises(ValueError, match="speed looks like km/h"):
        DRRun.from_arrays(c["time"], c["heading"], speed=3.6 * c["speed"], gps_t=c["time"][fix],
                          lat=c["gps_lat"][fix], lon=c["gps_lon"][fix])
    DRRun.from_arrays(c["time"], c["heading"], speed=3.6 * c["speed"], gps_t=c["time"][fix],
                      lat=c["gps_lat"][fix], lon=c["gps_lon"][fix], checks=False)


@pytest.mark.parametrize("sep, bom", [(";", False), ("\t", False), (",", True), (";", True)])
def test_semicolon_tab_and_a_byte_order_mark_read_the_same(tmp_path, sep, bom):
    cols = _drive()
    want = read_drive_csv(_write(tmp_path / "plain.csv", cols))
    got = read_drive_csv(_write(tmp_path / "other.csv", cols, sep=sep, bom=bom))
    np.testing.assert_array_equal(got.z_dr, want.z_dr)
    np.testing.assert_array_equal(got.z_gps, want.z_gps)


@pytest.mark.parametrize("text, match", [
    ("time;heading;speed\n0,0;0,5;1\n0,1;0,5;1\n0,2;0,5;1\n", r"line 2\) has '0,0' \(a decimal comma"),
    ("time heading speed\n0 0 1\n", "not split by a comma, semicolon or tab"),
    ("time,heading,speed\n0,0,1\n", "1 data row; a drive needs at least 3"),
    ("time,heading,speed\n", "0 data rows"),
    ("", "the file is empty"),
    ("time,heading,speed,gps_east,gps_north\n0,0,1,,\n0.1,0,1,nan,nan\n0.2,0,1,,\n",
     r"column 'gps_east' must hold finite numbers; data row 2 \(line 3\) has 'nan' \(leave the cell empty"),
    ("time,heading,speed,gps_lat,gps_lon,true_lat,true_lon\n" + "".join(
        f"{0.1 * k:.1f},0,1,,,48.1,11.5\n" for k in range(5)), "true_lat/true_lon are converted .* the file has none"),
    ("time,heading,speed\n0,0,1\n0.1,0,1\n0.1,0,1\n0.3,0,1\n", r"t must be strictly increasing; t\[2\] \(line 4\)"),
])
def test_bad_files_are_refused_naming_the_file_and_the_rule(tmp_path, text, match):
    path = tmp_path / "d.csv"
    path.write_text(text)
    with pytest.raises(ValueError, match=match) as info:
        read_drive_csv(path)
    assert str(info.value).startswith(str(path))


def test_a_utf16_file_is_refused_with_the_reason(tmp_path):
    path = tmp_path / "d.csv"
    path.write_text("time,heading,speed\n0,0,1\n", encoding="utf-16")
    with pytest.raises(ValueError, match="not UTF-8 text.*save it as CSV UTF-8"):
        read_drive_csv(path)


def test_a_large_drive_reads_in_bounded_memory_with_a_progress_bar(tmp_path, capsys):
    import tracemalloc

    import tqdm.auto  # noqa: F401 -- imported before tracing: its import is not the reader's memory

    from filterwnn.navigation import drives

    n = 20001
    path = _write(tmp_path / "big.csv", _drive(n=n, turn=0.001))
    tracemalloc.start()
    try:
        header, cols, lines = drives._read_columns(path, progress=True)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert len(lines) == n and set(cols) == set(COLUMNS)
    arrays = n * (len(COLUMNS) + 1) * 8  # the columns' floats and the line numbers
    # the columns, their final concatenation and one block; the previous reader kept every
    # cell's string, about 10 times the floats
    assert peak < 2 * arrays + drives._CHUNK * (len(COLUMNS) + 1) * 8 + 2**20, (peak, arrays)
    assert "reading big.csv" in capsys.readouterr().err


@pytest.mark.parametrize("mistake", ["time in milliseconds", "lat and lon swapped"])
def test_the_cli_refuses_a_drive_in_one_line_and_can_skip_the_checks(tmp_path, mistake):
    change, cause = MISTAKES[mistake]
    path = _write(tmp_path / "d.csv", change(_drive(n=3001)))
    argv = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--out", str(tmp_path / "o"),
            "--no-figures", "--no-progress", "--outages", "2", "--outage-length", "20"]
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=300)
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2 and len(lines) == 1 and cause in lines[0] and path in lines[0], proc.stderr
    if mistake == "lat and lon swapped":  # a drive that is so: the flag skips the checks
        proc = subprocess.run(argv + ["--no-plausibility", "--filters", "EKF"], capture_output=True, text=True,
                              timeout=300)
        assert proc.returncode == 0, proc.stderr


def _dropped(cols, rows):
    """``cols`` without the DR samples ``rows`` (a logger that dropped them; no fix on them)."""
    keep = np.ones(len(cols["time"]), dtype=bool)
    keep[rows] = False
    return {k: v[keep] for k, v in cols.items()}


def test_dropped_samples_are_refused_with_the_remedy_and_filled_on_request(tmp_path):
    full = _drive(n=601, bearing=2 * np.pi - 0.02 * 28.2)
    # the heading crosses 2 pi -> 0 in the second gap (the drive turns past north at t = 28.2 s)
    cols = _dropped(full, [41, 42, 282, 283, 284, 333])
    path = _write(tmp_path / "d.csv", cols)
    with pytest.raises(ValueError, match=r"evenly sampled.*t\[280\].*= 0\.4 s.*dropped samples: fill_gaps=SECONDS"):
        read_drive_csv(path)
    with pytest.warns(RuntimeWarning, match=r"filled 3 gap\(s\) .* with 6 interpolated sample\(s\); the longest "
                                             r"0\.4 s after t = 28\.1 s"):
        run = read_drive_csv(path, fill_gaps=0.5)
    ref = read_drive_csv(_write(tmp_path / "full.csv", full))
    assert run.z_dr.shape == ref.z_dr.shape and np.array_equal(run.gps_steps, ref.gps_steps)
    np.testing.assert_allclose(run.z_dr[:, 1], ref.z_dr[:, 1], atol=1e-9)  # constant speed: exact
    dh = np.angle(np.exp(1j * (run.z_dr[:, 0] - ref.z_dr[:, 0])))  # along the shorter arc, not round the circle
    assert np.abs(dh).max() < 1e-6
    # the truth's positions linearly between samples: within the track's sagitta over 0.4 s (4 mm)
    np.testing.assert_allclose(run.x_true[:, [0, 3]], ref.x_true[:, [0, 3]], atol=0.01)
    # a gap longer than fill_gaps is still refused
    with pytest.raises(ValueError, match=r"evenly sampled.*= 0\.4 s"), pytest.warns(RuntimeWarning, match="filled 2"):
        read_drive_csv(path, fill_gaps=0.35)
    with pytest.raises(ValueError, match="fill_gaps must be"):
        read_drive_csv(path, fill_gaps=-1.0)


def test_the_cli_fills_dropped_samples_on_request(tmp_path):
    path = _write(tmp_path / "d.csv", _dropped(_drive(n=601), [41, 42]))
    argv = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--out", str(tmp_path / "o"),
            "--no-figures", "--no-progress", "--outages", "2", "--outage-length", "20", "--filters", "EKF"]
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 2 and "--fill-gaps" in proc.stderr, proc.stderr
    proc = subprocess.run(argv + ["--fill-gaps", "0.5"], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0 and "filled 1 gap(s) of dropped DR samples" in proc.stderr, proc.stderr


def test_the_cli_names_the_columns_when_a_drive_has_no_fix_and_no_truth(tmp_path):
    """Fixes in columns the reader does not know (``latitude``, ``lon``): the command warns which they may be,
    then refuses the drive for what it lacks, naming the columns a drive gives its fixes and truth in (it said
    "no GPS fix in the outage at 0.0 s", and named the outage options)."""
    c = _drive(n=601)
    path = _write(tmp_path / "d.csv", c, header=["time", "heading", "speed", "latitude", "lon", "gps_sigma", "a", "b"])
    argv = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--out", str(tmp_path / "o"),
            "--no-figures", "--no-progress", "--filters", "EKF"]
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 2 and "'latitude' may be 'gps_lat'" in proc.stderr, proc.stderr
    assert "the drive has no truth and no GPS fix at all to score against (a drive CSV gives its fixes as " \
           "gps_east/gps_north or gps_lat/gps_lon" in proc.stderr and "--outage-length" not in proc.stderr


def test_the_cli_passes_the_latencies_and_the_intervals_to_the_reader(command_passes):
    for argv, want in ((["--gps-latency", "0.3", "--intervals", "stamps", "--odometer-latency", "0.2",
                         "--heading-latency", "0.5"], (0.3, "stamps", 0.2, 0.5)), ([], (0.0, "auto", 0.0, 0.0))):
        seen = command_passes("read_drive_csv", argv)
        assert (seen["gps_latency"], seen["intervals"], seen["odometer_latency"], seen["heading_latency"]) == want


def test_a_headings_latency_reads_each_heading_where_it_was_measured(tmp_path):
    """A heading 0.5 s late (5 samples at 10 Hz; a heading averaged over each sample's interval is half an
    interval late) through a turn that crosses north: with ``heading_latency=0.5`` the headings are the honest
    ones but for the last 0.5 s (the last sample held), along the shorter arc; -0.5 reads an early one back."""
    c = _drive(turn=0.2, bearing=5.5)  # 5.5 rad, turning 0.2 rad/s: through north after 4 s
    honest = read_drive_csv(_write(tmp_path / "h.csv", c), checks=False)
    late = {**c, "heading": np.r_[np.full(5, c["heading"][0]), c["heading"][:-5]]}
    path = _write(tmp_path / "late.csv", late)
    as_logged = read_drive_csv(path, checks=False)
    run = read_drive_csv(path, checks=False, heading_latency=0.5)
    off = lambda a, b: np.abs(np.angle(np.exp(1j * (a - b))))  # noqa: E731
    assert off(run.z_dr[:-5, 0], honest.z_dr[:-5, 0]).max() < 1e-9
    assert off(as_logged.z_dr[5:, 0], honest.z_dr[5:, 0]).min() > 0.09  # 0.5 s of 0.2 rad/s
    early = {**c, "heading": np.r_[c["heading"][5:], np.full(5, c["heading"][-1])]}
    run = read_drive_csv(_write(tmp_path / "early.csv", early), checks=False, heading_latency=-0.5)
    assert off(run.z_dr[6:, 0], honest.z_dr[6:, 0]).max() < 1e-9
    with pytest.raises(ValueError, match=r"heading_latency must be a finite number of seconds \(negative"):
        read_drive_csv(path, heading_latency=np.inf)


def _stop_and_go(dt, cycles=5, accel=1.5, top=8.0, stand=10.0):
    """Speeds every ``dt`` s of ``cycles`` stops and starts at ``accel`` (m/s^2), each start at a random
    phase of the sample grid: the truth a speed sensor reads."""
    rng = np.random.default_rng(1)
    v = []
    for _ in range(cycles):
        ramp = np.arange(rng.uniform(0.0, dt), top / accel, dt) * accel
        v += [0.0] * int(stand / dt) + list(ramp) + [top] * int(20 / dt) + list(ramp[::-1])
    return np.array(v + [0.0] * int(stand / dt))


@pytest.mark.parametrize("dt", [0.1, 0.2])
def test_a_speed_that_reads_0_below_a_cutoff_warns(dt):
    """A wheel-speed sensor that reads 0 below 0.8 m/s: at every start and stop the speed steps between 0
    and 0.8 m/s or more in one sample, which no car does at 10 or 5 Hz; the reader names the cutoff, what
    it does to a creeping car, and the remedy. The same drive with the honest speed does not warn."""
    v = _stop_and_go(dt)
    t = dt * np.arange(len(v))
    cut = np.where(v < 0.8, 0.0, v)
    with pytest.warns(RuntimeWarning, match=r"at each of the 10 start-ups and stops the speed steps between 0 and at "
                                            r"least 0.8\d* m/s .* reads 0 below about 0.8\d* m/s .* give it as the "
                                            r"odometer column"):
        DRRun.from_arrays(t, np.zeros(len(t)), speed=cut, checks=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        DRRun.from_arrays(t, np.zeros(len(t)), speed=v, checks=False)


def test_a_1_hz_speed_cannot_show_a_cutoff_under_3_m_s():
    """At 1 Hz a car pulling away at 3 m/s^2 reads 3 m/s at its first sample: a cutoff under that is not
    told from a brisk start, so the reader says nothing (no false alarm on the 1 Hz analogs)."""
    v = _stop_and_go(1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        DRRun.from_arrays(np.arange(len(v), dtype=float), np.zeros(len(v)), speed=np.where(v < 0.8, 0.0, v),
                          checks=False)


def test_dr_takes_a_worker_count_with_drive(command_passes):
    """--jobs changes no number, and scripts pass it whatever they run: --drive takes it (and runs its drives in
    turn), where --runs or --scenarios are refused."""
    assert command_passes("real_drive_outages", ["--jobs", "1"])["grade"] == "phone"


def test_cells_left_empty_in_a_few_rows_are_told_not_read_silently_as_a_row_per_message(tmp_path):
    """A logger that missed a value leaves a cell empty: a few rows with a heading but no speed, a few with a speed but
    no heading (the fourth user trial's drive d4, stop 71), among rows with both. The reader reads such a file as a
    log with a row per sensor message (the speed interpolated at the heading's rows, the rows without a heading not
    samples): it now says so, naming the first such row, where before the empty speeds were filled silently."""
    c = _drive()
    c["speed"], c["heading"] = c["speed"].copy(), c["heading"].copy()
    c["speed"][[101, 402, 703]] = np.nan
    c["heading"][[205, 606]] = np.nan
    with pytest.warns(RuntimeWarning, match=r"3 row\(s\) have a 'heading' but no 'speed' and 2 a 'speed' but no "
                                            r"'heading', among 1196 with both \(the first at data row 102, line 103\): "
                                            r"read as a log with a row per sensor message"):
        run = read_drive_csv(_write(tmp_path / "d.csv", c), fill_gaps=0.2)
    np.testing.assert_allclose(run.z_dr[:, 1], 1.0, atol=1e-9)  # (the speeds interpolated, the gaps filled)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a log with a row per sensor message is not warned of
        log = {k: np.r_[v, v] for k, v in _drive().items()}
        order = np.argsort(np.r_[log["time"][:1201], log["time"][1201:] + 0.05], kind="stable")
        log["time"] = np.r_[log["time"][:1201], log["time"][1201:] + 0.05][order]
        for k in ("heading", "speed", "gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"):
            log[k] = log[k][order]
        log["speed"][::2], log["heading"][1::2] = np.nan, np.nan
        for k in ("gps_lat", "gps_lon", "gps_sigma"):
            log[k][1::2] = np.nan
        read_drive_csv(_write(tmp_path / "log.csv", log), checks=False)


@pytest.mark.parametrize("decimals, told", [(4, True), (3, True), (5, False), (7, False)])
def test_fixes_written_with_few_decimals_are_told_their_rounding(tmp_path, decimals, told):
    """A seventh user's export wrote the fixes' latitude and longitude with '%.4f' (stop 74): a grid of 11.1 m north
    by 7.4 m east at their latitude, whose repeats the filters then dropped as a receiver's re-sent fixes. Written
    with 4 decimals or fewer, the reader names the steps and the rounding's spread; with 5 or more, nothing."""
    c = _drive()
    for k in ("gps_lat", "gps_lon"):
        c[k] = np.round(c[k], decimals)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        read_drive_csv(_write(tmp_path / "d.csv", c), checks=False)
    said = [str(w.message) for w in seen if "decimals" in str(w.message)]
    assert bool(said) == told, said
    if told:
        north = 10.0**-decimals * np.pi / 180.0 * 6.36e6
        m = re.search(rf"written with {decimals} decimals \(steps of ([\d.]+) m north and ([\d.]+) m east here\): "
                      r"their rounding adds ([\d.]+) m north", said[0])
        assert m and float(m.group(1)) == pytest.approx(north, rel=0.01) and float(m.group(2)) < float(m.group(1))
        assert float(m.group(3)) == pytest.approx(float(m.group(1)) / np.sqrt(12), rel=0.05)
