"""A phone + OBD-II user's log, the findings of stop 61's new user left open (stop 62).

Android's accuracy (a 68 % radius in metres) written in the ``gps_hdop`` column was read without a word: each fix
claimed five times its accuracy (the phone grade's 5 m at HDOP 1) and the EKF-8 ended its outages 12.32 / 37.00 m off
(6.80 / 17.53 with the accuracy as ``gps_sigma``), while the 6-state EKF's only warning named millimetres. The
reader now names the column. Rows at an OBD-II adapter's polls (irregular, 0.25-0.50 s) refused for its hangs were
told to fill the gaps (``--fill-gaps``), which ended 53.01 / 144.25 m off: the refusal now says to resample onto a
regular grid (``docs/study-outputs/dr/obd-log/``).
"""

import warnings

import numpy as np
import pytest

from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.scenarios import DRRun
from filterwnn.navigation.gpsdr import GPSDRFilter
from filterwnn.navigation.dead_reckoning import GPSDRModel

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _held_out_drives as held_out  # noqa: E402


def _read(path, **kw):
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        run = read_drive_csv(path, **kw)
    return run, [str(w.message) for w in record]


def _hdop_words(said):
    return [w for w in said if "gps_hdop has a median" in w]


@pytest.mark.parametrize("name", ["phone", "one_hz"])
def test_an_accuracy_in_metres_given_as_gps_hdop_is_named(tmp_path, name):
    """A phone's 68 % radius (1.51 sigma) in ``gps_hdop``, read at the phone grade's 5 m at HDOP 1: warned, naming
    the accuracy in metres and its remedy (``gps_sigma``, divided by 1.51)."""
    cols = held_out.columns(name, 0)
    cols["gps_sigma"] = np.round(1.51 * cols["gps_sigma"], 1)
    _, said = _read(held_out.write_csv(tmp_path / "d.csv", cols, accuracy="gps_hdop"), hdop_sigma=5.0)
    words = _hdop_words(said)
    assert len(words) == 1, said
    assert "accuracy in metres" in words[0] and "gps_sigma, divided by 1.51" in words[0], words[0]
    assert "--hdop-sigma" in words[0]


def test_honest_hdops_are_read_without_that_warning(tmp_path):
    """Each analog's (seeds 0-2) HDOP, its sigma over 5 m rounded to 0.1 as GGA writes it (at least 0.5): the city
    analog's are 2-8, with fixes that scatter as much, and no analog's is named."""
    for name in held_out.HELD_OUT:
        for seed in (0, 1, 2):
            cols = held_out.columns(name, seed)
            cols["gps_sigma"] = np.where(np.isnan(cols["gps_sigma"]), np.nan,
                                         np.maximum(0.5, np.round(cols["gps_sigma"] / 5.0, 1)))
            _, said = _read(held_out.write_csv(tmp_path / "d.csv", cols, accuracy="gps_hdop"), hdop_sigma=5.0)
            assert not _hdop_words(said), (name, seed, said)


def test_the_check_is_the_readers_and_checks_false_skips_it(tmp_path):
    """``checks=False`` (``--no-plausibility``) reads the same column without the warning."""
    cols = held_out.columns("phone", 0)
    cols["gps_sigma"] = np.round(1.51 * cols["gps_sigma"], 1)
    _, said = _read(held_out.write_csv(tmp_path / "d.csv", cols, accuracy="gps_hdop"), hdop_sigma=5.0,
                    checks=False)
    assert not _hdop_words(said)


def test_the_filters_far_below_warning_names_an_accuracy_given_as_gps_hdop(tmp_path):
    """The warning of fixes whose own sigma is far past their errors (the 6-state EKF's, on the OBD-II user's log)
    names an accuracy in metres given as gps_hdop beside the units."""
    cols = held_out.columns("one_hz", 0)
    cols["gps_sigma"] = 1000.0 * cols["gps_sigma"]
    run, _ = _read(held_out.write_csv(tmp_path / "d.csv", cols), checks=False)
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
    said = [str(w.message) for w in record if "far larger than their errors" in str(w.message)]
    assert said and "given as gps_hdop" in said[0], said
    assert "reports its accuracy a few times too large costs little" in said[0]  # (stop 75: a pessimistic receiver)


def _polled(rng, seconds, lo, hi, gap_at, gap):
    """Sample times at independent intervals ``lo``-``hi`` s over ``seconds``, with one pause of ``gap`` s."""
    t = np.cumsum(rng.uniform(lo, hi, int(seconds / lo)))
    t = t[t < seconds]
    k = np.searchsorted(t, gap_at)
    return np.r_[t[:k], t[k:] + gap]


def test_rows_at_a_polled_sensors_replies_are_told_to_resample_not_to_fill_gaps():
    """Rows at an OBD-II adapter's polls (independent intervals of 0.25-0.50 s) with a 3 s hang: refused naming the
    irregular intervals and a regular grid, without the fill_gaps remedy (which fills a grid's gaps)."""
    t = _polled(np.random.default_rng(0), 120.0, 0.25, 0.5, 60.0, 3.0)
    with pytest.raises(ValueError, match="the rows come at irregular intervals") as info:
        DRRun.from_arrays(t, np.zeros(len(t)), speed=np.full(len(t), 10.0), checks=False)
    said = str(info.value)
    assert "resample the drive onto a regular grid" in said and "this one needs" not in said, said


@pytest.mark.parametrize("sd", [0.0, 0.0015])
def test_a_grid_with_a_gap_is_still_told_to_fill_it(sd):
    """A 10 Hz grid (its stamps exact, or jittering 1.5 ms as a phone's) with a 3.4 s gap: the fill_gaps remedy as
    before, and no word of irregular rows."""
    rng = np.random.default_rng(1)
    t = np.arange(0.0, 120.0, 0.1)
    t = np.r_[t[:600], t[634:]] + rng.normal(0.0, sd, len(t) - 34)
    with pytest.raises(ValueError, match="this one needs") as info:
        DRRun.from_arrays(t, np.zeros(len(t)), speed=np.full(len(t), 10.0), checks=False)
    assert "irregular intervals" not in str(info.value)


def test_a_refusal_of_such_a_drive_names_the_column_too(tmp_path):
    """The city analog (seed 5) with its 68 % radius in ``gps_hdop``: each fix claims 136 m, the checks' stretches
    between fixes grow eight times that, and only 3 are left, which read as a speed in mph; the refusal now adds the
    column's median and the remedy."""
    cols = held_out.columns("city", 5)
    cols["gps_sigma"] = np.round(1.51 * cols["gps_sigma"], 1)
    with pytest.raises(ValueError, match="plausibility") as info:
        read_drive_csv(held_out.write_csv(tmp_path / "d.csv", cols, accuracy="gps_hdop"), hdop_sigma=5.0)
    assert "gps_hdop has a median of 27.2" in str(info.value) and "divided by 1.51" in str(info.value)
