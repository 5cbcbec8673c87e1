"""The three held-out drives of issue 23, rebuilt in simulation and checked as the checkers will.

``tests/_held_out_drives.py`` simulates each drive from the issue's description (a car with a
phone; a city centre with urban-canyon fixes; 21 minutes at 1 Hz with a MEMS-like gyro), writes
it as a drive CSV with its truth, and here it is read back and scored as ``filterwnn study dr
--drive FILE --grade phone`` scores it: 20 outages of 30 s spread over the drive, every 8-state
kind set from the phone grade, nothing tuned. The issue's thresholds (median / max at the outage
ends): phone drive 10 / 30 m, city drive 20 / 50 m, 1 Hz drive 6 / 30 m; the command must exit 0
on each with both grades. The 1 Hz drive and a short CLI run are in the default run; the rest
is ``slow`` (``pytest -m slow``).
"""

import os
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from filterwnn.navigation.drives import read_drive_csv
from filterwnn.studies.dr import real_drive_outages

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _held_out_drives as held_out  # noqa: E402

KINDS8 = ("EKF-8", "UKF-8", "SUKF-8")
#: The issue's thresholds: (median, max) at the outage ends, m.
TARGETS = {"phone": (10.0, 30.0), "city": (20.0, 50.0), "one_hz": (6.0, 30.0)}
#: A missed target, with its number (seed 0): the check stays, and passes the day it is met.
MISSED = {}  # the city drive's UKF-8 max (50.4 m, seed 0) was met by the zero angular rate update


def _csv(tmp_path_factory, name, rows=None):
    cols = held_out.columns(name)
    if rows is not None:
        cols = {k: v[:rows] for k, v in cols.items()}
    return held_out.write_csv(tmp_path_factory.mktemp(name) / f"{name}.csv", cols)


def test_the_analogs_match_their_descriptions():
    city = held_out.columns("city")
    fix = np.isfinite(city["gps_east"])
    err = np.hypot(city["gps_east"][fix] - city["true_east"][fix], city["gps_north"][fix] - city["true_north"][fix])
    assert 18.0 < np.median(err) < 25.0 and 45.0 < np.percentile(err, 95) < 65.0
    assert 0.38 < np.mean(err < city["gps_sigma"][fix]) < 0.50  # optimistic: 44 % inside 1 sigma
    assert city["time"][1] == pytest.approx(0.2)
    phone = held_out.columns("phone")
    fix = np.isfinite(phone["gps_east"])
    s = phone["gps_sigma"][fix]
    assert s.min() >= 5.0 and s.max() <= 8.0
    per_axis = np.concatenate([(phone[a][fix] - phone[b][fix]) / s
                               for a, b in (("gps_east", "true_east"), ("gps_north", "true_north"))])
    assert 0.85 < np.std(per_axis) < 1.15  # the true error matches the reported accuracy
    one = held_out.columns("one_hz")
    assert one["time"][1] == 1.0 and one["time"][-1] == 1260.0
    assert 0.30 < np.mean(one["speed"] == 0.0) < 0.42


@pytest.fixture(scope="module", params=[pytest.param("phone", marks=pytest.mark.slow),
                                        pytest.param("city", marks=pytest.mark.slow), "one_hz"])
def scored(request, tmp_path_factory):
    run = read_drive_csv(_csv(tmp_path_factory, request.param))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the filters' own alarms (NIS, bounds)
        res = real_drive_outages(run, filters=("DR-mech",) + KINDS8, use_gps_sigma=True, grade="phone")
    return request.param, res


@pytest.mark.parametrize("kind", KINDS8)
def test_every_8_state_kind_meets_the_issue_threshold(scored, kind):
    name, res = scored
    med, worst = TARGETS[name]
    e = res[kind]
    assert np.all(np.isfinite(res["end_xy"][kind]))
    if (name, kind) in MISSED and not (np.median(e) <= med and e.max() <= worst):
        pytest.xfail(MISSED[name, kind])  # still missed: said with its number; met, it passes
    assert np.median(e) <= med, (name, kind, np.median(e))
    assert e.max() <= worst, (name, kind, e.max())


def _cli(path, grade, tmp_path):
    cmd = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--grade", grade, "--no-figures",
           "--out", str(tmp_path / grade)]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=900)


#: The README's table of the three analogs (seed 0): the start of each drive's row.
README_ROWS = {"phone": "| a car with a phone:", "city": "| a city centre:", "one_hz": "| 21 minutes at 1 Hz"}


def test_the_readme_table_is_what_the_filters_give(scored):
    """Every number the README's analog table quotes is what the code gives today: a change
    that moves them fails here until the README says so (the 1 Hz row in the default run, the
    phone and city rows with ``-m slow``)."""
    name, res = scored
    readme = (Path(__file__).parents[2] / "README.md").read_text()
    row = next(line for line in readme.splitlines() if line.startswith(README_ROWS[name]))
    quoted = [cell.strip() for cell in row.strip("|").split("|")[1:5]]
    given = [f"{np.median(res[k]):.2f} / {res[k].max():.2f}" for k in ("DR-mech",) + KINDS8]
    assert quoted == given, (name, quoted, given)


@pytest.mark.parametrize("grade", ["phone", "survey"])
def test_the_command_exits_0_on_a_short_1hz_analog(tmp_path_factory, tmp_path, grade):
    done = _cli(_csv(tmp_path_factory, "one_hz", rows=300), grade, tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "| SUKF-8 |" in done.stdout and "Traceback" not in done.stderr


@pytest.mark.slow
@pytest.mark.parametrize("name", list(TARGETS))
@pytest.mark.parametrize("grade", ["phone", "survey"])
def test_the_command_exits_0_on_every_analog_with_both_grades(tmp_path_factory, tmp_path, name, grade):
    done = _cli(_csv(tmp_path_factory, name), grade, tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "| SUKF-8 |" in done.stdout and "Traceback" not in done.stderr


def test_a_gyro_outside_its_grade_is_re_acquired_on_the_1hz_analog(tmp_path_factory, monkeypatch):
    """The 1 Hz analog with a gyro of 0.3 deg/s, six times what it is run with (the phone grade, bound
    0.15): the stops re-acquire the rate bias, and the heading bias, which integrated the bound's 0.15
    deg/s too little while the bound held the rate bias, is widened by that, so GPS sets it again
    within a minute of driving. Seed 0: 296.6 m median at the outage ends without the re-acquisition,
    23.3 m with it but without the heading bias's widening, 2.6 m now (dead reckoning alone 150.1 m)."""
    from filterwnn.navigation import gpsdr

    cols = held_out.columns("one_hz", rate_bias=0.3)
    run = read_drive_csv(held_out.write_csv(tmp_path_factory.mktemp("gyro") / "gyro.csv", cols))

    def score():
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            res = real_drive_outages(run, filters=("DR-mech", "EKF-8"), use_gps_sigma=True, grade="phone")
        return res, [str(w.message) for w in seen]

    with_, said = score()
    assert any("re-acquires from them at step" in m for m in said)
    assert with_["integrity"]["EKF-8"]["n_zero_rate_reacquired"] >= 1
    monkeypatch.setitem(gpsdr.GPSDRFilter.__init__.__kwdefaults__, "zero_rate_reacquire_after", 0)
    without, _ = score()
    assert without["integrity"]["EKF-8"]["n_zero_rate_reacquired"] == 0
    assert np.median(with_["EKF-8"]) < 6.0 < 100.0 < np.median(without["EKF-8"])


def _study_ekf8(path, out, *options):
    """``filterwnn study dr --drive path --grade phone --filters EKF-8 *options``, in a subprocess as a
    user runs it: its EKF-8 table row, and all it printed."""
    cmd = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--grade", "phone",
           "--no-figures", "--no-progress", "--filters", "EKF-8", *options, "--out", str(out)]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-2000:]
    row = next(line for line in done.stdout.splitlines() if line.startswith("| EKF-8 |"))
    return row, done.stdout + done.stderr


def test_inflating_correlated_fixes_is_an_option_of_the_command(tmp_path_factory, tmp_path):
    """``--correlated-fixes inflate`` reaches the filters: on the city analog (seed 0) the EKF-8 counts the
    street-long multipath as the independent fixes it is worth and ends its outages nearer (median 16.43 ->
    11.04 m), and the default is the calibration's share."""
    path = _csv(tmp_path_factory, "city")
    medians = {}
    for mode in ("calibration", "inflate"):
        row, _ = _study_ekf8(path, tmp_path / mode, "--correlated-fixes", mode)
        medians[mode] = float(row.split("|")[2].split("/")[0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the filters' own alarms (NIS, bounds)
        default = real_drive_outages(read_drive_csv(path), filters=("EKF-8",), use_gps_sigma=True, grade="phone")
    assert medians["calibration"] == pytest.approx(np.median(default["EKF-8"]), abs=0.01)
    assert medians["inflate"] < medians["calibration"] - 3.0, medians


def test_fast_correlated_fixes_warn_and_the_command_thins_them(tmp_path_factory, tmp_path):
    """The city analog with its fixes at 5 Hz (the same multipath in seconds): the command warns that the
    fixes are correlated and names ``min_fix_interval=1``; ``--min-fix-interval 1`` uses one fix a second,
    the table counts the others as thinned, and it is what the API gives with that setting."""
    path = held_out.write_csv(tmp_path_factory.mktemp("city5") / "city5.csv", held_out.columns("city", 0, gps_rate=5.0))
    rows, said = {}, {}
    for interval in ("0", "1"):
        rows[interval], said[interval] = _study_ekf8(path, tmp_path / interval, "--min-fix-interval", interval)
    assert "are correlated at step" in said["0"] and "pass min_fix_interval=1" in said["0"]
    assert "are correlated at step" not in said["1"] and "thins its fixes" in said["1"]
    assert "more thinned" in rows["1"] and "more thinned" not in rows["0"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        thinned = real_drive_outages(read_drive_csv(path), filters=("EKF-8",), use_gps_sigma=True, grade="phone",
                                     min_fix_interval=1.0)
    assert float(rows["1"].split("|")[2]) == pytest.approx(np.median(thinned["EKF-8"]), abs=0.01)
    assert thinned["integrity"]["EKF-8"]["n_thinned"] > 3 * thinned["integrity"]["EKF-8"]["n_fixes"]


def _re_aligned_at_stops(cols, deg, seed):
    """The drive's heading stepped by ``deg`` (up or down, drawn from ``seed``) halfway through every stop of 5 s
    or more: a fused heading re-aligning while the car stands."""
    c = {k: np.asarray(v, dtype=float).copy() for k, v in cols.items()}
    standing = np.r_[0, (c["speed"] == 0).astype(int), 0]
    starts, ends = np.flatnonzero(np.diff(standing) == 1), np.flatnonzero(np.diff(standing) == -1)
    rng = np.random.default_rng(seed)
    for a, b in zip(starts, ends):
        if (b - a) * (c["time"][1] - c["time"][0]) >= 5.0:
            m = (a + b) // 2
            c["heading"][m:] = np.mod(c["heading"][m:] + np.deg2rad(deg) * rng.choice([-1, 1]), 2 * np.pi)
    return c


def _stepped_while_moving(cols, deg, at, deg_s=0.0):
    """The drive's heading stepped by ``deg`` (a fused heading re-aligning while the car drives), and drifting at
    ``deg_s`` (a gyro whose rate bias moved with its temperature), from the first sample at or after ``at`` s at
    which the car moves at 3 m/s or more."""
    c = {k: np.asarray(v, dtype=float).copy() for k, v in cols.items()}
    t = c["time"]
    k = int(np.flatnonzero((t >= at) & (c["speed"] >= 3.0))[0])
    c["heading"][k:] = np.mod(c["heading"][k:] + np.deg2rad(deg + deg_s * (t[k:] - t[k])), 2 * np.pi)
    return c


def test_a_heading_that_steps_while_the_car_moves_is_found_and_learnt_again(tmp_path, monkeypatch):
    """The phone analog (seed 1) with its heading stepped by 5 deg at 360 s, the car at speed: the monitor's
    nuisance parameters are the calibration's errors when it began listening, so the step is none of them,
    and the fixes taught the heading bias for 8 minutes (EKF-8 12.26 / 40.83 m at the outage ends, against
    3.97 / 10.38 without the step), the monitor reading it as a 2.7 % gyro scale error. The heading-jump
    detector finds it 48 s later, warns once and widens the heading bias by it: the outage that starts 4 s
    after that still ends 29.80 m off, every later one at most 10.33 m (up to 40.59 without the detector,
    0.98-9.71 without the step; 4.39 / 40.83 m over all, the 40.83 the outage the step falls in); on the drive
    without the step it never fires."""
    import filterwnn.navigation.gpsdr as gpsdr

    clean = held_out.columns("phone", 1)
    path = held_out.write_csv(tmp_path / "step.csv", _stepped_while_moving(clean, 5.0, 360.0))

    def ends(p):
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            res = real_drive_outages(read_drive_csv(p), filters=("EKF-8",), use_gps_sigma=True, grade="phone")
        said = [str(w.message) for w in record]
        return res, [m for m in said if "heading stepped by" in m], [m for m in said if "gyro's scale" in m]

    now, jumped, scale = ends(path)
    assert len(jumped) == 1 and "while the car moved" in jumped[0] and not scale
    assert now["integrity"]["EKF-8"]["n_heading_jumps"] == 1
    (found, onset, size, _), = now["integrity"]["EKF-8"]["heading_jumps"]
    assert 3600 - 100 <= onset < found and np.degrees(size) > 3.0
    assert not ends(held_out.write_csv(tmp_path / "clean.csv", clean))[1]
    init = gpsdr.GPSDRFilter.__init__
    monkeypatch.setattr(gpsdr.GPSDRFilter, "__init__",
                        lambda self, *a, **k: init(self, *a, **dict(k, heading_jump_z=None)))
    before, jumped, scale = ends(path)
    assert not jumped and scale  # without the detector the step reads as a gyro scale error
    after = now["starts"] > 420.0  # the outages that start after the detector found it (408 s), but the first
    assert np.median(now["EKF-8"]) < 0.5 * np.median(before["EKF-8"])
    assert now["EKF-8"][after].max() < 11.0 < 30.0 < before["EKF-8"][after].max()


def test_a_gyro_bias_that_moves_is_warned_with_the_grade_that_follows_it(tmp_path):
    """The phone analog (seed 0) whose gyro's rate bias moves by 0.05 deg/s at 40 % of the drive (a phone gyro
    warming up), 180 deg/h against the phone grade's bias instability of 10: the rate-bias state's random walk
    follows it slowly, and the outages end 23.96 / 53.04 m off (EKF-8; 6.68 / 28.16 without the drift). The
    consistency monitor warns, and its remedy names the gyro's bias instability; a grade that gives it as 100
    deg/h (``--gyro-bias-instability 100``) ends them 7.79 / 28.07 m off, unwarned."""
    drifting = _stepped_while_moving(held_out.columns("phone", 0), 0.0, 360.0, deg_s=0.05)
    run = read_drive_csv(held_out.write_csv(tmp_path / "drift.csv", drifting))

    def ends(grade):
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade=grade)
        return res["EKF-8"], [str(w.message) for w in record if "is inconsistent" in str(w.message)]

    before, said = ends("phone")
    assert len(said) == 1 and "gyro_bias_instability_deg_h" in said[0] and "--gyro-bias-instability" in said[0]
    assert "the model's 10)" in said[0]
    after, said = ends({"gyro_bias_instability_deg_h": 100.0})
    assert not said
    assert np.median(after) < 10.0 < 20.0 < np.median(before) and after.max() < 30.0 < 50.0 < before.max()


def test_a_step_found_after_the_speed_was_found_late_names_the_speed_first(tmp_path):
    """The 1 Hz analog (seed 0) with its speed 0.5 s late: the monitor warns of the speed's latency (steps
    232-235), and later the SUKF-8's heading-jump detector takes part of what the late speed does at each start
    and stop for a step (-1.76 deg at step 1219; there is none). That warning then names the speed's remedy
    first (``log-faults/speed_jumps.py``: 15 such steps on the analogs with a late speed, all at 1 Hz). Where the
    steps come first (seed 2, the speed 1 s late: five), the speed's warning names them."""
    cols = held_out.columns("one_hz", 0, odometer_latency=0.5)
    run = read_drive_csv(held_out.write_csv(tmp_path / "late.csv", cols))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        res = real_drive_outages(run, filters=("SUKF-8",), use_gps_sigma=True, grade="phone")
    said = [str(w.message) for w in record]
    late = [m for m in said if "the speed's latency" in m]
    stepped = [m for m in said if "the heading stepped by" in m]
    assert late and len(stepped) == 1 and res["integrity"]["SUKF-8"]["n_heading_jumps"] == 1
    assert "The filter has warned that the fixes show the speed late (now +0." in stepped[0]
    assert "--odometer-latency 0." in stepped[0]
    # the other order: seed 2 with the speed 1 s late, the EKF-8 takes five steps, then finds the speed late
    cols = held_out.columns("one_hz", 2, odometer_latency=1.0)
    run = read_drive_csv(held_out.write_csv(tmp_path / "later.csv", cols))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone")
    late = [str(w.message) for w in record if "the speed's latency" in str(w.message)]
    found = [k for k, *_ in res["integrity"]["EKF-8"]["heading_jumps"]]
    assert len(late) == 1 and len(found) == 5
    assert (f"; the 5 heading step(s) found before it (at step(s) {', '.join(map(str, found))}) may be its doing"
            in late[0])
    # the fixes' latency was told first, at the opposite sign: a late speed reads so (stop 64), said last
    assert late[0].endswith("so take this remedy first, and give the fixes a latency only if they still show one")


def test_the_1hz_analog_logged_with_an_odometer_reads_as_with_its_speed(tmp_path):
    """The 1 Hz analog (seed 0) with a cumulative odometer column in place of its speed. Each increment is the
    mean speed over its second; read as the speed at the second's end (the reader until stop 49), each speed was
    0.5 s late: the monitor warned of a speed stamped late (+0.52 s at step 232), a wrong cause for a clean
    log, and the EKF-8 ended its outages 3.63 / 11.06 m off against 1.63 / 6.28 m with the speed column
    (``log-faults/odometer_column.py``: every 1 Hz seed 2-4 times the median). Now no warning of it, and the
    speed column's numbers (1.52 / 5.92 m)."""
    cols = held_out.columns("one_hz", 0)
    run = read_drive_csv(held_out.write_csv(tmp_path / "odo.csv", cols, odometer=True))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone")
    assert not [w for w in record if "the speed's latency" in str(w.message)]
    e = res["EKF-8"]
    assert np.median(e) < 1.63 + 0.3 and e.max() < 6.28 + 0.5, (np.median(e), e.max())


def test_fixes_stamped_by_another_clock_are_named_with_the_offset(tmp_path):
    """The phone analog (seed 0) with every fix stamped 18 s late (GPS time against UTC): with its truth the reader
    refuses it, and the refusal names the clock offset it finds (17.5 s) and the reader's remedy, not another
    frame; without the truth it warns of it, not of a heading offset. Read at the offset, neither. The same drive
    with its fixes 5 s early is warned of with a negative offset (``log-faults/clock_offset.py``)."""
    cols = held_out.columns("phone", 0, gps_latency=18.0)
    path = held_out.write_csv(tmp_path / "late.csv", cols)
    with pytest.raises(ValueError, match=r"median 22\d.\d m from the truth.*best placed 17.5 s earlier.*"
                                         r"--gps-latency 17.5\)"):
        read_drive_csv(path)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        read_drive_csv(path, gps_latency=17.5)
    assert not [w for w in record if "plausibility" in str(w.message)]
    untrue = dict(cols, true_east=np.full(len(cols["time"]), np.nan), true_north=np.full(len(cols["time"]), np.nan))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        read_drive_csv(held_out.write_csv(tmp_path / "untrue.csv", untrue))
    said = [str(w.message) for w in record if "plausibility" in str(w.message)]
    assert len(said) == 1 and "a clock offset between the fixes and the DR samples" in said[0]
    assert "gps_latency=17.5" in said[0] and "heading_offset" not in said[0]
    early = held_out.write_csv(tmp_path / "early.csv", held_out.columns("phone", 1, gps_latency=-5.0))
    with pytest.warns(RuntimeWarning, match=r"best placed 4.5 s later than their time stamps.*--gps-latency -4.5\)"):
        read_drive_csv(early)


def _ekf8_ends(path):
    """EKF-8's outage ends as the command scores them, and the warnings that say the monitor found a calibration off."""
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        ends = real_drive_outages(read_drive_csv(path), filters=("EKF-8",), use_gps_sigma=True, grade="phone")["EKF-8"]
    return ends, [w for w in record if "consistency monitor finds" in str(w.message)]


def test_a_calibration_the_monitor_finds_off_is_not_kept_off_by_the_correlation_it_makes(tmp_path, monkeypatch):
    """The phone analog (seed 0, exact stops) with a heading that re-aligns by 0.5 deg halfway through each
    stop of 5 s or more: too little for the stop's step test (the grade's own heading noise), so the heading
    bias goes wrong, the car drifts sideways fix after fix, and the innovations' correlation that makes cut
    the heading bias's gain and kept it wrong (38.19 / 74.12 m at the outage ends, EKF-8). The consistency
    monitor finds the calibration off, warns once, and the gain takes the fixes' own correlation: the
    median falls by half (16.95 / 49.53 m); on the drive without the steps it never fires."""
    import filterwnn.navigation.gpsdr as gpsdr

    clean = held_out.columns("phone", 0, exact_stops=True)
    path = held_out.write_csv(tmp_path / "steps.csv", _re_aligned_at_stops(clean, 0.5, 0))
    now, said = _ekf8_ends(path)
    assert len(said) == 1 and "a gyro whose bias changed does this; for a gyro whose bias moves faster than the " \
        "grade allows, give the gyro's bias instability" in str(said[0].message)  # the remedy for the other cause
    assert not _ekf8_ends(held_out.write_csv(tmp_path / "clean.csv", clean))[1]
    init = gpsdr.GPSDRFilter.__init__
    monkeypatch.setattr(gpsdr.GPSDRFilter, "__init__",
                        lambda self, *a, **k: init(self, *a, **dict(k, calibration_error_z=None)))
    before, said = _ekf8_ends(path)
    assert not said
    assert np.median(now) < 0.5 * np.median(before) and now.max() < before.max()


def test_an_hdop_read_as_a_sigma_is_named_and_read_as_gps_hdop_gives_the_sigma_numbers(tmp_path):
    """The 1 Hz analog (seed 0) with its fixes' accuracy given as an NMEA HDOP (the sigma over 5 m, rounded to 0.1
    as GGA writes it). In ``gps_sigma``, read as metres, each fix claims 3-8 times its accuracy: the EKF-8 ended its
    outages 4.81 / 43.55 m off (1.63 / 6.28 m with the sigma; ``log-faults/accuracy_columns.py``), and its warning
    of inconsistency now names an HDOP and the column for it. As ``gps_hdop`` with ``hdop_sigma=5`` (the phone
    grade's, what the command passes) it gives the sigma's numbers, with no warning."""
    cols = held_out.columns("one_hz", 0)
    cols["gps_sigma"] = np.maximum(0.5, np.round(cols["gps_sigma"] / 5.0, 1))
    for accuracy in ("gps_sigma", "gps_hdop"):
        run = read_drive_csv(held_out.write_csv(tmp_path / f"{accuracy}.csv", cols, accuracy=accuracy), hdop_sigma=5.0)
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone")
        said = [str(w.message) for w in record if "is inconsistent" in str(w.message)]
        e = res["EKF-8"]
        if accuracy == "gps_sigma":
            assert len(said) == 1 and "a gps_sigma column that holds an HDOP" in said[0], said
            assert "Give it as gps_hdop" in said[0] and e.max() > 20.0, e.max()
        else:
            assert not said and np.median(e) < 1.63 + 0.3 and e.max() < 6.28 + 0.5, (said, np.median(e), e.max())


@pytest.mark.parametrize("fault", ["far_too_good", "all_optimistic", "gyro_outside_grade"])
def test_fixes_that_report_far_better_than_they_are_are_named(tmp_path, fault):
    """A receiver that reports 0.3 m on 5 % of its fixes (the 1 Hz analog's first 400 s, its fixes 3-5 m): without
    the floor the EKF-8 ended its outages 2.68 / 46.53 m off on the whole drive (1.63 / 6.28 m with honest sigmas,
    1.47 / 6.28 m with the grade's for every fix; ``sensor-faults/placeholder_fixes.txt``), floored 2.85 / 7.15 m:
    the floored fixes (0.8-1 m) are still optimistic, and its warning of inconsistency names
    those fixes and the remedy (drop the column) where the window's mean NIS, with them at the median sigma and
    again with the grade's for every fix, would be inside the bound; fixes all reporting half their error, or a gyro
    outside its grade, are warned without it."""
    from filterwnn import GPSDRFilter
    from filterwnn.navigation.dead_reckoning import GPSDRModel

    cols = {k: v[:400] for k, v in held_out.columns("one_hz", 0, rate_bias=0.5 if fault.startswith("gyro") else 0.05).items()}
    fix = np.flatnonzero(np.isfinite(cols["gps_east"]))
    if fault == "far_too_good":
        cols["gps_sigma"][np.random.default_rng(5).choice(fix, size=len(fix) // 20, replace=False)] = 0.3
    elif fault == "all_optimistic":
        cols["gps_sigma"][fix] *= 0.5
    run = read_drive_csv(held_out.write_csv(tmp_path / "d.csv", cols))
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    kf = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        kf.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    said = [str(w.message) for w in record if "is inconsistent" in str(w.message)]
    assert said, fault
    named = ["far better than the others carry the excess" in m and "drop the gps_sigma column" in m for m in said]
    assert any(named) == (fault == "far_too_good"), said


@pytest.mark.parametrize("run_of", [1, 2])
def test_fixes_that_claim_ten_times_their_accuracy_are_floored(tmp_path, run_of):
    """The 1 Hz analog with 5 % of its fixes reporting 0.3 m (their errors 3-5 m), alone or in pairs: the gate cannot
    tell them (each is measured against the filter's covariance too), and used with their tiny covariance they moved
    the calibration states: the EKF-8 ended an outage 46.53 m off (pairs: 55.66 m). The floor at a quarter of the
    fixes' reported sigma before them (``gps_sigma_floor``) mends the lone ones (2.85 / 7.15 m) but not the pairs,
    whose second fix it believes (71.69 m); the floor raised to the median once the monitor names such fixes
    (``floor_on_detection``; both the defaults) mends both (``sensor-faults/placeholder_fixes.txt``)."""
    cols = held_out.columns("one_hz", 0)
    fix = np.flatnonzero(np.isfinite(cols["gps_east"]))
    rng = np.random.default_rng(5)
    starts = rng.choice(len(fix) - run_of, size=len(fix) // 20 // run_of, replace=False)
    cols["gps_sigma"][fix[(starts[:, None] + np.arange(run_of)).ravel()]] = 0.3
    run = read_drive_csv(held_out.write_csv(tmp_path / "d.csv", cols))
    ends = {}
    for floor, raise_it in ((0.25, True), (0.25, False), (0.0, False)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=("EKF-8",), grade="phone", use_gps_sigma=True, gps_sigma_floor=floor,
                                     floor_on_detection=raise_it)
        ig = res["integrity"]["EKF-8"]
        ends[floor, raise_it] = (np.median(res["EKF-8"]), res["EKF-8"].max(), ig["n_floored"], ig["floor_raised"])
    median, worst = TARGETS["one_hz"]
    met = {k: v[0] <= median and v[1] <= worst for k, v in ends.items()}
    assert met[0.25, True] and ends[0.25, True][3] is not None, ends
    assert met[0.25, False] == (run_of == 1) and ends[0.25, False][2] > 0, ends
    assert not met[0.0, False] and ends[0.0, False][2] == 0, ends  # the failure they mend


@pytest.mark.parametrize("grade, flag, expect", [("phone", [], 5.0), ("survey", [], 1.5),
                                                  ("phone", ["--hdop-sigma", "2"], 2.0)])
def test_the_command_reads_an_hdop_with_the_grades_sigma_at_hdop_1(tmp_path, monkeypatch, grade, flag, expect):
    """``filterwnn study dr --drive`` reads a ``gps_hdop`` column with the grade's GPS sigma as the sigma at HDOP 1,
    or ``--hdop-sigma``."""
    from filterwnn.cli import main
    from filterwnn.studies.dr import _cli

    cols = {k: v[:300] for k, v in held_out.columns("one_hz", 0).items()}
    cols["gps_sigma"] = np.round(cols["gps_sigma"] / 5.0, 1)
    path = held_out.write_csv(tmp_path / "d.csv", cols, accuracy="gps_hdop")
    seen = []

    class Read(BaseException):
        """Read and passed on: enough."""

    def scored(run, **kw):
        seen.append(run.gps_sigma / cols["gps_sigma"][np.isfinite(cols["gps_sigma"])][-len(run.gps_sigma):])
        raise Read

    monkeypatch.setattr(_cli, "real_drive_outages", scored)
    with pytest.raises(Read):
        main(["study", "dr", "--drive", path, "--grade", grade, "--no-figures", "--out", str(tmp_path)] + flag)
    np.testing.assert_allclose(seen[0], expect)


def _every_fault(cols, rng):
    """The 1 Hz analog's columns with stop 56's faults at once (``random-drives/RUN.md``, protocol 3), in place: the
    heading stepping by 1 degree halfway through each stop of 5 s or more, a speed cutoff of 0.8 m/s, 6 samples over
    12 m/s read as 0, 5 speed samples of 70.8 m/s and 5 headings turned by 120 degrees, and 2.5 % of the fixes in
    pairs reporting 0.3 m (the fixes' 0.5 s latency and the gyro's 2 % scale error are the generator's)."""
    v, h = cols["speed"], cols["heading"]
    edges = np.diff(np.r_[0, (v == 0).astype(int), 0])
    for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)):
        if b - a >= 5:
            h[(a + b) // 2:] += np.deg2rad(1.0) * rng.choice([-1, 1])
    v[v < 0.8] = 0.0
    v[rng.choice(np.flatnonzero(v >= 12.0), 6, replace=False)] = 0.0
    moving = np.flatnonzero(v > 1.0)
    v[rng.choice(moving, 5, replace=False)] = 70.8
    h[rng.choice(moving, 5, replace=False)] += np.deg2rad(120.0)
    cols["heading"] = np.mod(h, 2 * np.pi)
    fix = np.flatnonzero(np.isfinite(cols["gps_east"]))
    starts = rng.choice(len(fix) - 2, size=len(fix) // 40, replace=False)
    cols["gps_sigma"][fix[(starts[:, None] + np.arange(2)).ravel()]] = 0.3
    return cols


def test_the_1hz_analog_with_every_fault_at_once_meets_its_target(tmp_path):
    """Each fault the reader and the filter learnt to handle, tried alone on the analog it was built on, says little of
    a log that has them all. The 1 Hz analog with seven at once (:func:`_every_fault`): one of its speed spikes fell
    beside a dropout (70.8, 0 m/s), which the reader left at 43 m/s; the filters then took the car to be driving
    backwards at step 31 and read its gyro 5.6 % off (2 % drawn), and ended 5.53 / 33.66 m (EKF-8), past the drive's
    30 m. Read as one glitch (stop 56) every kind meets the 1 Hz drive's target, and each fault is told."""
    rng = np.random.default_rng(56)
    cols = _every_fault(held_out.columns("one_hz", 0, gps_latency=0.5, gyro_scale=0.02), rng)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = read_drive_csv(held_out.write_csv(tmp_path / "d.csv", cols))
        res = real_drive_outages(run, filters=("DR-mech",) + KINDS8, grade="phone", use_gps_sigma=True)
    said = " ".join(str(w.message) for w in caught)
    for words in ("speed reads 0 for 6 sample(s)", "6 speed sample(s) in 5 run(s) jump away", "5 heading sample(s)",
                  "the fixes show themselves +0.6", "the gyro turning +2", "while the car stood", "takes the fix at"):
        assert words in said, words
    assert "measured heading is" not in said  # the car never read as driving the other way
    median, worst = TARGETS["one_hz"]
    for kind in KINDS8:
        assert np.median(res[kind]) <= median and res[kind].max() <= worst, (kind, np.median(res[kind]), res[kind].max())
        assert np.median(res[kind]) < np.median(res["DR-mech"]) and res[kind].max() < res["DR-mech"].max()
