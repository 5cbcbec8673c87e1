"""A receiver's own dead reckoning given as fixes (stop 63).

A u-blox ADR module goes on giving positions in a tunnel from its own dead reckoning (NAV-PVT ``fixType`` 1,
``gnssFixOK`` 0; NMEA GGA quality 6). Kept as fixes (stop 60's u-blox user, ``docs/study-outputs/dr/ublox-log/``) they
were read without a word, and the filters followed them: the EKF-8 ended the real tunnel 14.23 m off instead of
11.75 m. Such positions follow the same wheels: each step between them has the odometer's length to millimetres,
where GNSS fixes misfit it by decimetres or metres. The reader now names them (``receiver_dead_reckoning``).
"""

import os
import sys
import warnings

import numpy as np
import pytest

from filterwnn.navigation import _plausibility as pl
from filterwnn.navigation.drives import read_drive_csv

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _held_out_drives as held_out  # noqa: E402

#: The stretch the receiver dead-reckons (s of the phone analog, seed 0: the car moves at over 4 m/s throughout).
START, END = 420.0, 465.0


def _read(path, **kw):
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        run = read_drive_csv(path, **kw)
    return run, [str(w.message) for w in record if "as the odometer does" in str(w.message)]


def _with_receiver_dr(cols, drift_deg_s=0.05, scale=1.004, sigma="grows", wheels="ours"):
    """``cols`` with its fixes from :data:`START` to :data:`END` replaced by a receiver's dead reckoning from the fix
    before, ``scale`` long and turning ``drift_deg_s`` off the track: along the drive's own speed and heading
    (``wheels="ours"``: the module's wheel ticks, which the log's odometer also reads), or along the true track
    (``"own"``: wheels of its own, without the speed column's noise); its accuracy growing at every fix
    (``sigma="grows"``) or held."""
    cols = {k: v.copy() for k, v in cols.items()}
    t, fix = cols["time"], np.isfinite(cols["gps_east"])
    inside = fix & (t >= START) & (t <= END)
    k0 = np.flatnonzero(fix & (t < START))[-1]
    after = t > t[k0]
    turn = np.radians(drift_deg_s) * (t - t[k0])
    if wheels == "ours":
        ds = cols["speed"] * np.diff(t, prepend=t[0])
        de, dn = ds * np.sin(cols["heading"] + turn), ds * np.cos(cols["heading"] + turn)
    else:
        te, tn = (np.diff(cols[c], prepend=cols[c][0]) for c in ("true_east", "true_north"))
        de, dn = np.cos(turn) * te + np.sin(turn) * tn, np.cos(turn) * tn - np.sin(turn) * te
    east = cols["gps_east"][k0] + scale * np.cumsum(np.where(after, de, 0.0))
    north = cols["gps_north"][k0] + scale * np.cumsum(np.where(after, dn, 0.0))
    cols["gps_east"][inside], cols["gps_north"][inside] = east[inside], north[inside]
    s0 = cols["gps_sigma"][k0]
    cols["gps_sigma"][inside] = s0 + 0.05 * (t[inside] - t[k0]) ** 1.3 if sigma == "grows" else s0
    return cols, int(inside.sum())


@pytest.mark.parametrize("name", ["phone", "one_hz"])
@pytest.mark.parametrize("wheels", ["ours", "own"])
def test_a_receivers_dead_reckoning_given_as_fixes_is_named(tmp_path, name, wheels):
    """45 s of a receiver's own dead reckoning among an analog's fixes (the car moves throughout): one warning, naming
    the stretch by its times, the misfits, the accuracy that grows at every fix, and the rows to drop (fixType 1,
    GGA quality 6); whether the receiver reads the log's own wheels or wheels of its own."""
    cols, n = _with_receiver_dr(held_out.columns(name, 0), wheels=wheels)
    _, said = _read(held_out.write_csv(tmp_path / "d.csv", cols))
    assert len(said) == 1, said
    words = said[0]
    found = [float(x) for x in words.split("(t = ", 1)[1].split(" s", 1)[0].split("-")]
    # (the fix the receiver started from, and by chance a GNSS fix before it, also lie on the run's line)
    assert START - 2.5 <= found[0] <= START + 1.0 and END - 1.0 <= found[1] <= END, words
    count = int(words.split("plausibility: ", 1)[1].split(" fixes", 1)[0])
    assert "1 run(s)" in words and n - 1 <= count <= n + 3, (n, words)
    assert "of the longest grows (" in words and "fixType 1" in words and "GGA quality 6" in words, words
    assert "Drop those rows" in words and "either" not in words


def test_a_held_accuracy_names_either_cause(tmp_path):
    """The same stretch with the receiver's last accuracy held (an HDOP held in a tunnel): named as either a receiver's
    dead reckoning or GNSS fixes far cleaner than the others, with the check (the log's fix type at those times)."""
    cols, _ = _with_receiver_dr(held_out.columns("one_hz", 0), sigma="held")
    _, said = _read(held_out.write_csv(tmp_path / "d.csv", cols))
    assert len(said) == 1 and "does not grow (0 of its" in said[0], said
    assert "either a receiver's own dead reckoning" in said[0] and "Check the log's fix type" in said[0], said


@pytest.mark.parametrize("accuracy", [None, "gps_sigma"])
def test_a_clean_gnss_stretch_is_not_called_dead_reckoning(tmp_path, accuracy):
    """Two minutes of GNSS fixes far cleaner than the 1 Hz analog's others (3 cm of noise, an RTK fix's) follow the
    odometer as closely: without a sigma, or with one held at 1 m, the warning names either cause and says clean
    fixes need nothing; it does not say to drop them."""
    rng = np.random.default_rng(1)
    cols = {k: v.copy() for k, v in held_out.columns("one_hz", 0).items()}
    t, fix = cols["time"], np.isfinite(cols["gps_east"])
    clean = fix & (t >= 300.0) & (t <= 420.0)
    for c, at in (("gps_east", "true_east"), ("gps_north", "true_north")):
        cols[c][clean] = cols[at][clean] + 1.0 + rng.normal(0.0, 0.03, clean.sum())
    cols["gps_sigma"][clean] = 1.0
    _, said = _read(held_out.write_csv(tmp_path / "d.csv", cols, accuracy=accuracy))
    assert len(said) == 1, said
    assert "or GNSS fixes far cleaner" in said[0] and "clean GNSS fixes need nothing" in said[0], said
    assert "Drop those rows" not in said[0]


def test_a_standstill_inside_splits_the_runs(tmp_path):
    """The city analog (seed 0) stands still inside the stretch: the fixes either side are named as two runs."""
    cols, _ = _with_receiver_dr(held_out.columns("city", 0), wheels="own")
    _, said = _read(held_out.write_csv(tmp_path / "d.csv", cols))
    assert len(said) == 1 and "2 run(s)" in said[0], said


@pytest.mark.parametrize("name", ["phone", "city", "one_hz"])
def test_gnss_fixes_are_not_named(tmp_path, name):
    """The analogs as they come (seeds 0 and 1): none named (the drives at hand: ``log-faults/receiver_dr_*.txt``)."""
    for seed in (0, 1):
        _, said = _read(held_out.write_csv(tmp_path / "d.csv", held_out.columns(name, seed)))
        assert not said, (name, seed, said)


def test_fixes_held_to_the_bit_are_not_taken_for_it(tmp_path):
    """A receiver (or a log) that holds its last fix while the car drives on repeats it to the bit: not a step along
    the track (the filters leave such fixes themselves, ``n_stale``)."""
    cols = {k: v.copy() for k, v in held_out.columns("one_hz", 0).items()}
    t, fix = cols["time"], np.isfinite(cols["gps_east"])
    inside = fix & (t >= START) & (t <= END)
    k0 = np.flatnonzero(fix & (t < START))[-1]
    for c in ("gps_east", "gps_north", "gps_sigma"):
        cols[c][inside] = cols[c][k0]
    _, said = _read(held_out.write_csv(tmp_path / "d.csv", cols))
    assert not said, said


def test_checks_false_skips_it(tmp_path):
    """``checks=False`` (``--no-plausibility``) reads the same drive without the warning."""
    cols, _ = _with_receiver_dr(held_out.columns("phone", 0))
    _, said = _read(held_out.write_csv(tmp_path / "d.csv", cols), checks=False)
    assert not said


def test_the_runs_are_measured_by_lengths_alone():
    """The misfits do not see the heading's zero or the speed's scale: a run along a track turned 90 degrees and
    3 % long is the same run; one short of :data:`RECEIVER_DR_STEPS` is not named, nor one whose sigma falls at
    :data:`RECEIVER_DR_SIGMA_FALLS` of its fixes (GNSS's accuracy)."""
    rng = np.random.default_rng(0)
    n = 120
    step = np.full(10 * n, 1.5)  # 15 m/s at 10 Hz, a fix a second
    steps = 10 * np.arange(n) + 9
    path = np.r_[0.0, np.cumsum(step)][steps + 1]
    z = np.stack([np.zeros(n), path], axis=1) + rng.normal(0.0, 1.0, (n, 2))
    t = 0.1 * np.arange(10 * n + 1)
    a, b = 40, 40 + pl.RECEIVER_DR_STEPS + 1  # fixes a..b: RECEIVER_DR_STEPS + 1 steps, the misfits of all but one
    z[a:b + 1] = z[a] + 1.03 * np.stack([path[a:b + 1] - path[a], np.zeros(b - a + 1)], axis=1)
    words = pl.receiver_dead_reckoning(t, step, steps, z)
    assert words is not None and "1 run(s)" in words, words
    grows = np.r_[np.full(a, 2.0), 2.0 + 0.1 * np.arange(b - a + 1), np.full(n - b - 1, 2.0)]
    assert "of the longest grows (" in pl.receiver_dead_reckoning(t, step, steps, z, grows)
    changes = 2.0 + rng.uniform(-0.3, 0.3, n)  # (GNSS's accuracy changes both ways: the run is taken for GNSS)
    assert np.sum(np.diff(changes[a:b + 1]) < 0) >= pl.RECEIVER_DR_SIGMA_FALLS
    assert pl.receiver_dead_reckoning(t, step, steps, z, changes) is None
    z2 = z.copy()
    z2[b] = z2[b] + [0.0, 5.0]  # the run's last step spoilt: RECEIVER_DR_STEPS - 1 steps left in it
    assert pl.receiver_dead_reckoning(t, step, steps, z2) is None
