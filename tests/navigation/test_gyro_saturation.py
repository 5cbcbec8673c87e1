"""A yaw rate that does not hold what a straight line through the fixes' course assumes (stop 71, the fourth user
trial): a gyro whose range saturates in the tightest turns (each loses its turn past the rail, and the reader's line
started such a drive 31 degrees off, the filters then 40 m past their clean twin) is told, and the turns it lost are
fitted to the fixes' course before and after each and mended; a gyro warming up (its rate bias settling from 0.5 to
0.05 deg/s) is started where the fixes' course is, by a piecewise line (a straight one had started it 36 degrees off
with a standard error of 1), and its warning names the instability its drift shows rather than a prior that keeps
the first minutes' rate."""

import re
import warnings

import numpy as np
import pytest

from filterwnn.navigation import scenarios as S
from filterwnn.navigation.scenarios import DRRun, en_to_latlon

LAT0, LON0 = 47.37, 8.54


def _drive(seed=0, rail=None, bias=lambda t: 0.05 + 0.0 * t, duration=720.0, dt=0.1, v=8.0, sigma=2.5,
           fastest=35.0, rounding=None):
    """Straights of 15-45 s joined by turns of 60-150 degrees either way over 3-6 s (up to ``fastest`` deg/s), a
    10 Hz yaw rate (deg/s: the car's, plus ``bias(t)``, plus 0.1 deg/s of noise; clipped at ``rail``, rounded to
    ``rounding``) and speed, 1 Hz fixes of ``sigma`` per axis; returns the reader's arguments and the true heading."""
    rng = np.random.default_rng(seed)
    n = int(round(duration / dt)) + 1
    t = dt * np.arange(n)
    rate = np.zeros(n)
    k = int(20.0 / dt)
    while k < n:
        turn = rng.choice([-1, 1]) * rng.uniform(60.0, 150.0)
        m = int(max(abs(turn) / fastest, 3.0) / dt)
        rate[k:k + m] = turn / (m * dt)
        k += m + int(rng.uniform(15.0, 45.0) / dt)
    h = np.deg2rad(rng.uniform(0.0, 360.0)) + np.deg2rad(np.cumsum(rate) * dt)
    e = np.r_[0.0, np.cumsum(v * dt * np.sin(h[1:]))]
    nn = np.r_[0.0, np.cumsum(v * dt * np.cos(h[1:]))]
    fix = np.arange(n) % int(round(1.0 / dt)) == 0
    lat, lon = en_to_latlon(e[fix] + sigma * rng.standard_normal(fix.sum()),
                            nn[fix] + sigma * rng.standard_normal(fix.sum()), LAT0, LON0)
    read = rate + bias(t) + 0.1 * rng.standard_normal(n)
    if rail is not None:
        read = np.clip(read, -rail, rail)
    if rounding is not None:
        read = np.round(read / rounding) * rounding
    kw = dict(yaw_rate=np.deg2rad(read), speed=np.full(n, v), gps_t=t[fix], lat=lat, lon=lon,
              gps_sigma=np.full(fix.sum(), sigma))
    return t, kw, h


def _read(t, kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = DRRun.from_arrays(t, **kw)
    return run, [str(w.message) for w in caught]


def _off(run, h):
    """The reader's heading less the true one (deg, wrapped), per DR step."""
    return np.degrees((run.z_dr[:, 0] - h[1:] + np.pi) % (2 * np.pi) - np.pi)


def test_a_saturated_gyro_is_told_and_the_turns_it_lost_are_mended():
    t, clean_kw, h = _drive()
    _, kw, _ = _drive(rail=20.0)
    clean, said_clean = _read(t, clean_kw)
    run, said = _read(t, kw)
    assert not [w for w in said_clean if "largest value" in w]
    told = [w for w in said if "largest value" in w]
    assert len(told) == 1, said
    assert re.search(r"the yaw rate reads its largest value, \+20 and -20 deg/s, on \d+ samples in \d+ run\(s\), the "
                     r"first at [\d.]+ s: a gyro's range saturated", told[0]), told[0]
    assert "the heading is mended by them" in told[0]
    lost = [float(v) for v in re.findall(r"([+-]\d+) \+- [\d.]+", told[0].split("fixes' course before and after")[1])]
    assert len(lost) >= 5 and max(abs(v) for v in lost) > 20.0, told[0]
    # mended: within a few degrees of the clean gyro's heading away from the runs (inside them the mend is spread)
    off, off_clean = _off(run, h), _off(clean, h)
    assert np.percentile(np.abs(off), 90) < 4.0 + np.percentile(np.abs(off_clean), 90), np.percentile(np.abs(off), 90)
    # without the mend (the raw integral, started alike) the turns' losses add up: the test can fail
    raw, _ = S._integrate_yaw(t, kw["yaw_rate"], speed=kw["speed"])
    drift = np.degrees(np.abs(np.unwrap(raw) - np.unwrap(h)))
    assert drift.max() - drift.min() > 60.0


def test_a_rate_rounded_to_a_coarse_step_or_a_gyro_within_its_range_is_not_told_saturated():
    t, kw, _ = _drive(rounding=1.0)
    _, said = _read(t, kw)
    assert not [w for w in said if "largest value" in w]
    assert S._saturated(t, np.deg2rad(np.r_[np.zeros(50), np.full(20, 2.0)]))[0] == []  # (a constant under 5 deg/s)


def test_a_gyro_warming_up_is_started_at_the_fixes_course_and_its_instability_named():
    warm = lambda t: 0.05 + 0.45 * np.exp(-t / 150.0)  # noqa: E731 (deg/s)
    t, kw, h = _drive(bias=warm, duration=600.0)
    run, said = _read(t, kw)
    start = [w for w in said if "integrated from" in w]
    assert len(start) == 1
    assert "a piecewise line through their angles, pieces of 120 s or more" in start[0], start[0]
    walk = re.search(r"--gyro-bias-instability (\d+)", start[0])
    assert walk and 100 <= float(walk.group(1)) <= 3000, start[0]
    assert "--gyro-bias 0" not in start[0]  # (a larger prior keeps the first minutes' rate: not offered)
    first = int(2.0 / 0.1)  # the fit's first stretch (the drift from there on is the rate-bias state's to learn)
    assert abs(_off(run, h)[first]) < 3.0, _off(run, h)[first]
    # a steady rate bias keeps the straight line and its words
    t, kw, h = _drive(bias=lambda t: 0.05 + 0.0 * t, duration=600.0)
    run, said = _read(t, kw)
    start = [w for w in said if "integrated from" in w]
    assert re.search(r"a line through their angles, drifting \+0.0[45]\d* deg/s", start[0]), start[0]
    assert abs(_off(run, h)[first]) < 3.0


@pytest.mark.parametrize("gap", [2.0, 60.0])
def test_saturated_runs_close_together_are_one_step(gap):
    """Runs with fewer than three stretches between fixes between them are fitted as one step (two steps with no
    stretch between them could not be told apart)."""
    from filterwnn.navigation._plausibility import yaw_start

    t, kw, h = _drive(rail=20.0)
    run, _ = _read(t, {**kw, "yaw_rate": np.deg2rad(np.clip(np.degrees(kw["yaw_rate"]), -100, 100))})
    steps, z = run.gps_steps, run.z_gps
    step = run.z_dr[:, 1]
    heading = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]]
    from filterwnn.navigation._plausibility import _chord_pairs

    pairs = _chord_pairs(steps, z, 2.5, step)
    a = int(300 / 0.1)
    fit = yaw_start(0.1, heading, step, steps, z, pairs, [(a, a + 5), (a + int(gap / 0.1), a + int(gap / 0.1) + 5)])
    assert len(fit["steps"]) == (1 if gap < 10 else 2)
    assert all(abs(turn) < 6.0 for _, _, turn, _, _ in fit["steps"])  # (nothing was lost: the steps read ~0)


def test_saturated_runs_without_fixes_on_both_sides_are_named_and_not_mended():
    """Runs before the first fix (or after the last, or in a gap of fixes) have no course on one side to fit the turn
    they lost: the warning counts them as not mended."""
    t, kw, _ = _drive(rail=20.0)
    late = kw["gps_t"] >= 150.0
    kw = {**kw, "gps_t": kw["gps_t"][late], "lat": kw["lat"][late], "lon": kw["lon"][late],
          "gps_sigma": kw["gps_sigma"][late]}
    runs, _ = S._saturated(t, kw["yaw_rate"])
    assert any(b < 150.0 for _, b in runs)  # (a run before the first fix)
    _, said = _read(t, kw)
    told = [w for w in said if "largest value" in w]
    assert len(told) == 1 and re.search(r"\d+ run\(s\) without fixes on both sides are not mended", told[0]), told
