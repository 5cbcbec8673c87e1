"""A car carried with its speed at 0 (a ferry, a car train, a tow truck): the drive reader names it
(:func:`filterwnn.navigation._plausibility.carried`) with the stretch and the remedy, splitting the drive. Before stop
70 a third new user's ferry crossing (334 s at 5 m/s) was told by the filters as a crawl at 1 m/s in a queue."""

import warnings

import numpy as np
import pytest

from filterwnn.navigation import _plausibility as P
from filterwnn.navigation.scenarios import DRRun


def _drive(stand_speed=5.0, jump=0.0, seed=0, dt=0.1):
    """100 s at 10 m/s north, 150 s with the speed reading 0 while the car moves east at ``stand_speed`` (a ferry;
    0: a stop), with the fixes ``jump`` m off for 10 s of it (multipath), then 100 s at 10 m/s north again. 10 Hz
    heading and speed, 1 Hz fixes of 3 m."""
    rng = np.random.default_rng(seed)
    t = dt * np.arange(int(350.0 / dt) + 1)
    on = (t >= 100.0) & (t < 250.0)
    v_true = np.where(on, stand_speed, 10.0)
    heading = np.where(on, np.pi / 2, 0.0)
    ve, vn = v_true * np.sin(heading), v_true * np.cos(heading)
    east = np.r_[0.0, np.cumsum(ve[1:] * dt)]
    north = np.r_[0.0, np.cumsum(vn[1:] * dt)]
    fix = np.arange(len(t)) % 10 == 0
    ge = east + 3.0 * rng.standard_normal(len(t))
    gn = north + 3.0 * rng.standard_normal(len(t))
    ge = np.where((t >= 150.0) & (t < 160.0), ge + jump, ge)
    speed = np.where(on, 0.0, 10.0)
    return dict(t=t, heading=heading, speed=speed, gps_t=t[fix], east=ge[fix], north=gn[fix],
                gps_sigma=np.full(int(fix.sum()), 3.0), truth=np.stack([east, north], axis=1))


def _read(cols):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = DRRun.from_arrays(cols.pop("t"), cols.pop("heading"), **cols)
    return run, [str(w.message) for w in caught]


def test_a_car_carried_with_its_speed_at_0_is_named_with_the_stretch_and_the_remedy():
    run, said = _read(_drive())
    told = [s for s in said if "the car was carried" in s]
    assert len(told) == 1, said
    assert "from t = 100 s to 250 s (150 s) the speed reads 0 while the fixes move" in told[0], told[0]
    assert "Split the drive there" in told[0] and "several --drive" in told[0]
    (a, b, moved, speed), = P.carried(0.1, run.z_dr[:, 1], run.gps_steps, run.z_gps)
    assert moved == pytest.approx(0.75 * 750.0, rel=0.1)  # the quarters' medians and speed == pytest.approx(5.0, rel=0.1)


@pytest.mark.parametrize("stand_speed, jump", [(0.0, 0.0), (0.0, 80.0), (0.8, 0.0)])
def test_a_stop_a_jump_or_a_crawl_under_a_cutoff_is_not_carried(stand_speed, jump):
    """A stop, one whose fixes jump 80 m for 10 s (multipath), and a crawl at 0.8 m/s under a speed's cutoff (120 m
    in 150 s): not carried."""
    _, said = _read(_drive(stand_speed, jump))
    assert not [s for s in said if "carried" in s], said
