"""Outages placed where the drive has its fixes, not in its own gaps of fixes (issue 23, stop 69).

A user's 1 Hz highway log with a 185 s tunnel had 5 of its 20 evenly spread outages start inside the tunnel: the
filters had gone up to 176 s without a fix when the outage began, while dead reckoning from the true start
(``DR-mech``) went its 30 s, and nothing said so (EKF-8 4.53 / 24.75 m against DR-mech's 4.68 / 8.28 m). An outage
of 30 s is now placed only where the drive has a fix within ``max(OUTAGE_GAP_SLACK * length, 2 * the fixes' median
interval)`` before its start (or at the drive's start); a start given by hand in a gap is kept and warned of, and the
table's header names the drive's own gaps.
"""

import warnings

import numpy as np
import pytest

from filterwnn.navigation.scenarios import OUTAGE_GAP_SLACK, DRRun, fix_gaps, outage_starts
from filterwnn.studies.dr import real_drive_outages, real_drive_table


def _drive(tunnel=(200.0, 300.0), first_fix=1.0, end=600.0, fix_every=1.0, standing=0.0):
    """A straight drive at 10 m/s (after ``standing`` s at rest), 10 Hz DR, fixes every ``fix_every`` s from
    ``first_fix`` but in ``tunnel``."""
    t = np.arange(0.0, end + 0.05, 0.1)
    north = 10 * np.maximum(t - standing, 0.0)
    gps_t = np.arange(first_fix, end + 0.5, fix_every)
    if tunnel is not None:
        gps_t = gps_t[(gps_t < tunnel[0]) | (gps_t >= tunnel[1])]
    rng = np.random.default_rng(0)
    return DRRun.from_arrays(t, np.zeros(t.size), speed=np.where(t < standing, 0.0, 10.0), gps_t=gps_t,
                             east=rng.normal(0.0, 2.0, gps_t.size),
                             north=np.interp(gps_t, t, north) + rng.normal(0.0, 2.0, gps_t.size),
                             gps_sigma=2.0, truth=np.stack([np.zeros(t.size), north], axis=1))


def test_the_drives_own_gaps_are_found_with_their_allowance():
    gaps, allowance = fix_gaps(_drive())
    assert allowance == OUTAGE_GAP_SLACK * 30.0 == 3.0
    np.testing.assert_allclose(gaps, [[199.0, 300.0]], atol=0.11)
    # twice the fixes' interval where that is more; the drive's start counts as a known state, its end closes a gap
    gaps, allowance = fix_gaps(_drive(tunnel=None, first_fix=60.0, fix_every=5.0))
    assert allowance == 10.0
    np.testing.assert_allclose(gaps, [[0.0, 60.0]], atol=0.11)
    assert fix_gaps(_drive(tunnel=None))[0].shape == (0, 2)


def test_spread_outages_start_where_the_drive_has_fixes():
    run = _drive()
    gaps, allowance = fix_gaps(run)
    even = np.linspace(0.0, float(run.t[-1]) - 31.0, 20)
    assert ((even > gaps[0, 0] + allowance) & (even < gaps[0, 1])).sum() == 4  # the plain spread lands 4 in the tunnel
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # nothing to warn of: none was given
        res = real_drive_outages(run, filters=("DR-mech",))
    starts = res["starts"]
    assert len(starts) == 20 and starts[0] == 0.0
    assert not ((starts > gaps[0, 0] + allowance) & (starts < gaps[0, 1])).any()
    assert (res["in_fix_gap"] == -1).all()
    assert "none starting in the drive's own gaps of fixes, 199-300 s" in real_drive_table(res)
    for min_speed in (0.0, 5.0):  # the API's spread, with a speed to meet or without
        s = outage_starts(run, 30.0, n=20, min_speed=min_speed)
        assert not ((s > gaps[0, 0] + allowance) & (s < gaps[0, 1])).any()


def test_a_drive_without_gaps_keeps_its_even_placements():
    run = _drive(tunnel=None)
    res = real_drive_outages(run, filters=("DR-mech",))
    np.testing.assert_array_equal(res["starts"], np.linspace(0.0, float(run.t[-1]) - 31.0, 20))
    assert "gaps of fixes" not in real_drive_table(res)


def test_a_start_given_in_a_gap_is_kept_and_warned_of():
    run = _drive()
    with pytest.warns(RuntimeWarning, match=r"the outage at 250.0 s starts 51.0 s after the drive's last GPS fix, in "
                                            r"its own gap of fixes \(199.0-300.0 s\): the filters go 81 s without a "
                                            r"fix to its end, dead reckoning from the true start \(DR-mech\) 30 s"):
        res = real_drive_outages(run, starts=[100.0, 250.0], filters=("DR-mech",))
    np.testing.assert_array_equal(res["starts"], [100.0, 250.0])
    np.testing.assert_array_equal(res["in_fix_gap"], [-1, 0])
    assert any("the outage at 250.0 s" in w for w in res["warnings"])  # kept for the saved table
    assert "1 starting in the drive's own gaps of fixes, 199-300 s" in real_drive_table(res)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # within the allowance of the last fix: an outage of 30 s
        real_drive_outages(run, starts=[201.5], filters=("DR-mech",))


def test_no_window_left_is_said():
    run = _drive(tunnel=(50.0, 600.0), standing=100.0)  # fixes for the first 50 s only, moving from 100 s
    with pytest.raises(ValueError, match="starts within 3 s of a GPS fix: the drive's own gaps of fixes cover them"):
        outage_starts(run, 30.0, n=5, min_speed=5.0)


def test_the_command_names_the_gap(tmp_path, capsys):
    from filterwnn.cli import main

    run = _drive()
    path = tmp_path / "tunnel.csv"
    fixes = dict(zip(run.gps_steps, run.z_gps))
    with open(path, "w") as fh:
        fh.write("time,heading,speed,gps_east,gps_north,gps_sigma,true_east,true_north\n")
        for k, t in enumerate(run.t):
            e, n = fixes.get(k, (np.nan, np.nan))
            cell = "" if np.isnan(e) else f"{e:.3f}"
            fh.write(f"{t:.1f},0.0,10.0,{cell},{'' if np.isnan(n) else f'{n:.3f}'},{'' if np.isnan(e) else 2.0},"
                     f"{run.x_true[k, 0]:.3f},{run.x_true[k, 3]:.3f}\n")
    with warnings.catch_warnings():
        warnings.simplefilter("always")  # (the command shows each on stderr, a line each)
        rc = main(["study", "dr", "--drive", str(path), "--filters", "DR-mech", "--out", str(tmp_path / "out"),
                   "--no-figures", "--no-progress", "--outage-starts", "100,250"])
    assert rc in (0, None)
    out = capsys.readouterr()
    assert "1 starting in the drive's own gaps of fixes" in out.out
    assert out.err.count("the outage at 250.0 s starts") == 1  # once, not again from the command's own check
    saved = (tmp_path / "out" / "real_drive_tunnel_outage_errors.md").read_text()
    assert "the outage at 250.0 s starts 51.1 s after the drive's last GPS fix" in saved  # (the CSV's times: 0.1 s on)
