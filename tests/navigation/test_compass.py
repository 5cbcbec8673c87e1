"""A heading whose error turns with the direction of travel (a compass's deviation): the drive reader's check
(:func:`filterwnn.navigation._plausibility.heading_deviation`), its warning with the deviation card, and the
reader's remedy (``heading_deviation=``, ``--heading-deviation``) that subtracts it. Before stop 70 such a drive
(the second user trial's compass drive) ended its outages worse than raw dead reckoning and nothing said why."""

import re
import warnings

import numpy as np
import pytest

from filterwnn.navigation import _plausibility as P
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.scenarios import DRRun, en_to_latlon

LAT0, LON0 = 59.91, 10.75
COLUMNS = ["time", "heading", "speed", "gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"]
CARD = (6.0, 3.0, -1.0, 4.0)  # B, C, D, E (deg): a car compass's deviation, peaks of 7-10 degrees


def _drive(seed=0, card=(0.0, 0.0, 0.0, 0.0), scale=0.0, drift=0.0, duration=600.0, dt=0.1, v=10.0, sigma=3.0):
    """Straights of 15-50 s joined by turns of 30-150 degrees either way (over 5 s), a 10 Hz heading (0.5 degree
    noise) and speed, 1 Hz fixes of ``sigma`` per axis. The heading reads the course plus ``card``'s deviation at
    it, a gyro's scale factor error ``scale`` of its turns and a drift of ``drift`` deg/s."""
    rng = np.random.default_rng(seed)
    n = int(round(duration / dt)) + 1
    t = dt * np.arange(n)
    rate = np.zeros(n)
    k = 0
    while k < n:
        k += int(rng.uniform(15.0, 50.0) / dt)
        m = int(5.0 / dt)
        rate[k:k + m] = rng.choice([-1, 1]) * np.deg2rad(rng.uniform(30.0, 150.0)) / (m * dt)
        k += m
    turned = np.cumsum(rate) * dt
    h = rng.uniform(0.0, 2 * np.pi) + turned
    e = np.r_[0.0, np.cumsum(v * dt * np.sin(h[1:]))]
    nn = np.r_[0.0, np.cumsum(v * dt * np.cos(h[1:]))]
    tlat, tlon = en_to_latlon(e, nn, LAT0, LON0)
    glat, glon = en_to_latlon(e + sigma * rng.standard_normal(n), nn + sigma * rng.standard_normal(n), LAT0, LON0)
    fix = np.arange(n) % int(round(1.0 / dt)) == 0
    read = (h + P.deviation_of(h, card) + scale * turned + np.deg2rad(drift) * t
            + np.deg2rad(0.5) * rng.standard_normal(n))
    return {"time": t, "heading": np.mod(read, 2 * np.pi), "speed": np.full(n, v),
            "gps_lat": np.where(fix, glat, np.nan), "gps_lon": np.where(fix, glon, np.nan),
            "gps_sigma": np.where(fix, sigma, np.nan), "true_lat": tlat, "true_lon": tlon}


def _write(path, cols):
    lines = [",".join(COLUMNS)]
    for k in range(len(cols["time"])):
        lines.append(",".join("" if np.isnan(cols[c][k]) else repr(float(cols[c][k])) for c in COLUMNS))
    path.write_text("\n".join(lines) + "\n")
    return path


def _read(path, **kw):
    """The drive and the reader's warnings' texts."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = read_drive_csv(path, **kw)
    return run, [str(w.message) for w in caught]


def _fit(run):
    heading = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]]
    return P.heading_deviation(float(run.t[1] - run.t[0]), heading, run.z_dr[:, 1], run.gps_steps, run.z_gps, 3.0)


def test_a_compass_deviation_is_warned_with_its_card_and_the_card_reads_it_back(tmp_path):
    """A heading that deviates by the card (6, 3, -1, 4) degrees is warned of, with a card within a degree of it and
    the reader's remedy; read with the card the warning names, the drive has no deviation left to warn of (its peak
    under 2 degrees). The same drive without the deviation is read without a word."""
    run, said = _read(_write(tmp_path / "compass.csv", _drive(0, CARD)))
    told = [s for s in said if "turns with the direction of travel" in s]
    assert len(told) == 1, said
    m = re.search(r"--heading-deviation (\S+)\)", told[0])
    card = [float(c) for c in m.group(1).split(",")]
    np.testing.assert_allclose(card, CARD, atol=1.0)
    assert f"pass heading_deviation=({m.group(1)})" in told[0] and "a yaw_rate column" in told[0]
    fit = _fit(run)
    assert fit[3] < P.HEADING_DEVIATION_LEVEL and max(-fit[1], fit[2]) > P.HEADING_DEVIATION_WARN_DEG
    corrected, said = _read(tmp_path / "compass.csv", heading_deviation=card)
    assert not [s for s in said if "direction of travel" in s], said
    fit = _fit(corrected)
    assert max(-fit[1], fit[2]) < 2.0, fit
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        clean = read_drive_csv(_write(tmp_path / "clean.csv", _drive(0)))
    assert _fit(clean)[3] > 0.01


@pytest.mark.parametrize("scale, drift", [(0.03, 0.0), (-0.03, 0.05), (0.0, 0.1)])
def test_a_gyro_heading_is_not_read_as_a_deviation(tmp_path, scale, drift):
    """A gyro's heading errors, a scale factor error of 3 % (whose error follows the turns since the start, as a
    deviation follows the direction on a drive that does not loop) and a drift of up to 0.1 deg/s, are no
    deviation: the check fits them beside it and says nothing."""
    run, said = _read(_write(tmp_path / "gyro.csv", _drive(1, scale=scale, drift=drift)))
    assert not [s for s in said if "direction of travel" in s], said
    assert _fit(run)[3] > P.HEADING_DEVIATION_LEVEL


def test_the_card_is_subtracted_at_the_heading_read():
    """``heading_deviation`` subtracts the card's deviation at each heading as read, after ``heading_offset``."""
    t = np.arange(0.0, 60.0, 0.1)
    h = np.mod(0.3 + 0.1 * t, 2 * np.pi)
    plain = DRRun.from_arrays(t, h, speed=np.full(len(t), 5.0), checks=False)
    run = DRRun.from_arrays(t, h, speed=np.full(len(t), 5.0), checks=False, heading_offset=2.0,
                            heading_deviation=CARD)
    h0 = plain.z_dr[:, 0] - np.deg2rad(2.0)
    expected = h0 - P.deviation_of(h0, CARD)
    np.testing.assert_allclose(np.angle(np.exp(1j * (run.z_dr[:, 0] - expected))), 0.0, atol=1e-12)
    # north: C + E; east: B - E
    np.testing.assert_allclose(np.rad2deg(P.deviation_of(np.deg2rad([0.0, 90.0]), CARD)), [3.0 + 4.0, 6.0 - 4.0],
                               atol=1e-12)


def test_a_card_that_is_not_one_is_refused():
    t = np.arange(0.0, 10.0, 0.1)
    v = np.full(len(t), 5.0)
    with pytest.raises(ValueError, match=r"heading_deviation must be a compass's deviation card, four finite numbers"):
        DRRun.from_arrays(t, np.zeros(len(t)), speed=v, heading_deviation=(1.0, 2.0, 3.0))
    with pytest.raises(ValueError, match=r"heading_deviation must be .* got \(1.0, nan, 0.0, 0.0\)"):
        DRRun.from_arrays(t, np.zeros(len(t)), speed=v, heading_deviation=(1.0, float("nan"), 0.0, 0.0))
    with pytest.raises(ValueError, match=r"heading_deviation has no meaning with a yaw rate"):
        DRRun.from_arrays(t, yaw_rate=np.zeros(len(t)), speed=v, heading_deviation=CARD)


def test_the_command_takes_the_card(command_passes, capsys):
    seen = command_passes("read_drive_csv", ["--heading-deviation", "6,3,-1,4.5"])
    assert seen["heading_deviation"] == [6.0, 3.0, -1.0, 4.5]
    assert command_passes("read_drive_csv", [])["heading_deviation"] is None
    command_passes("read_drive_csv", ["--heading-deviation", "6,3,-1"])
    assert "expected four comma-separated numbers B,C,D,E (degrees), got '6,3,-1'" in capsys.readouterr().err


def test_a_straight_road_is_not_judged_a_deviation():
    """A drive that holds one course (a highway) gives the card nothing to tell from an offset: no warning, and the
    fit, where it is made at all, is not past the level."""
    t = np.arange(0.0, 600.0, 0.1)
    rng = np.random.default_rng(3)
    north = 20.0 * t
    fix = np.arange(len(t)) % 10 == 0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run = DRRun.from_arrays(t, np.full(len(t), 0.02), speed=np.full(len(t), 20.0), gps_t=t[fix],
                                east=3.0 * rng.standard_normal(int(fix.sum())),
                                north=north[fix] + 3.0 * rng.standard_normal(int(fix.sum())),
                                gps_sigma=np.full(int(fix.sum()), 3.0))
    fit = _fit(run)
    assert fit is None or fit[3] > P.HEADING_DEVIATION_LEVEL
