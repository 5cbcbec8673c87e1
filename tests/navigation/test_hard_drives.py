"""A bench of hard simulated drives (issue 23): every 8-state kind beats dead reckoning alone.

Each drive is seeded and its truth known; the filters are set from a sensor grade (the
phone's, or the specification of the gyro the drive simulates), never tuned on the drive.
Each drive gets four 30 s GPS outages; a filter is scored as the DR study scores it
(:func:`filterwnn.studies.dr.real_drive_outages`): one pass with GPS, then each outage from
the filter's state at its start, the horizontal error at its end. Dead reckoning alone
(``DR-mech``) starts each outage at the true position. Every 8-state kind (``EKF-8``,
``UKF-8``, ``SUKF-8``) must stay finite and end the outages closer than dead reckoning,
in median and at the worst outage.

* urban canyon: 5 Hz odometry with a small rate bias, 1 Hz fixes of which 25 % carry a
  multipath jump of 20-80 m, every fix reporting 4 m (optimistic for the jumps);
* 1 Hz dead reckoning with long standstills (two of about 100 s), a MEMS gyro of 0.05
  deg/s, a 1.5 % odometer scale error;
* a MEMS gyro with a 0.7 deg/s turn-on bias (the filter told the gyro's specification);
* an unknown start heading (the filter starts 150 degrees off);
* a drive that starts in a 60 s outage.
"""

import warnings
from dataclasses import replace

import numpy as np
import pytest
from scipy.stats import chi2

from filterwnn.navigation.scenarios import Scenario, simulate_scenario, true_trajectory
from filterwnn.studies.dr import real_drive_outages

KINDS8 = ("EKF-8", "UKF-8", "SUKF-8")
TURNS = ((40.0, 50.0, 90.0), (110.0, 125.0, -120.0), (190.0, 200.0, 60.0))


def _reported(run, sigma):
    return run._replace(gps_sigma=np.full(len(run.z_gps), float(sigma)))


def urban_canyon(rng):
    sc = Scenario(name="urban canyon", duration=240.0, dt=0.2, speed=8.0, heading=30.0, turns=TURNS,
                  gps_rate=1.0, sigma_gps=4.0, odometer_scale=1.02, heading_drift=0.02, sigma_heading=0.5)
    run = simulate_scenario(sc, rng=rng)
    n = len(run.z_gps)
    jump = rng.random(n) < 0.25
    angle, size = rng.uniform(0.0, 2.0 * np.pi, n), rng.uniform(20.0, 80.0, n)
    z = run.z_gps + (jump * size)[:, None] * np.stack([np.sin(angle), np.cos(angle)], axis=1)
    return _reported(run._replace(z_gps=z), 4.0), "phone", 20.0


def _to_rest(sc):
    """``sc`` with each speed change marked ``-inf`` set to brake the car to rest from the speed the
    truth has when it begins (at 1 Hz the turns' discretisation adds speed: a nominal -12 m/s after
    a turn left the car crawling at 1.6 m/s, and the drive had no standstill)."""
    changes = list(sc.speed_changes)
    for i, (t0, t1, amount) in enumerate(changes):
        if amount == -np.inf:
            _, _, x = true_trajectory(replace(sc, speed_changes=tuple(changes[:i])))
            k = int(round(t0 / sc.dt)) - 1
            changes[i] = (t0, t1, -float(np.hypot(x[k, 1], x[k, 4])))
    return replace(sc, speed_changes=tuple(changes))


def standstills_1hz(rng):
    sc = _to_rest(Scenario(name="1 Hz DR, long standstills", duration=600.0, dt=1.0, speed=12.0, heading=100.0,
                           turns=TURNS, speed_changes=((60.0, 66.0, -np.inf), (170.0, 176.0, 12.0),
                                                       (300.0, 306.0, -np.inf), (400.0, 410.0, 14.0)),
                           gps_rate=1.0, sigma_gps=4.0, odometer_scale=1.015, heading_drift=0.05,
                           sigma_odometer=0.1, sigma_heading=0.5))
    run = simulate_scenario(sc, rng=rng)
    assert np.mean(np.hypot(run.x_true[:, 1], run.x_true[:, 4]) == 0.0) > 0.3  # 200 s of 600 standing
    return _reported(run, 4.0), "phone", 20.0


def mems_gyro(rng):
    sc = Scenario(name="MEMS gyro 0.7 deg/s", duration=300.0, dt=0.1, speed=12.0, heading=200.0, turns=TURNS,
                  gps_rate=1.0, sigma_gps=3.0, odometer_scale=0.98, heading_drift=0.7, sigma_heading=0.5)
    return _reported(simulate_scenario(sc, rng=rng), 3.0), {"gyro_bias_deg_s": 0.7}, 20.0


def unknown_heading(rng):
    sc = Scenario(name="unknown start heading", duration=240.0, dt=0.1, speed=10.0, heading=45.0, turns=TURNS,
                  gps_rate=1.0, sigma_gps=3.0, odometer_scale=1.02, heading_drift=0.03, sigma_heading=0.5)
    run = simulate_scenario(sc, rng=rng)
    x0 = run.x0.copy()
    wrong = np.deg2rad(45.0 + 150.0)
    x0[1], x0[4] = 10.0 * np.sin(wrong), 10.0 * np.cos(wrong)
    return _reported(run._replace(x0=x0), 3.0), "phone", 20.0


def starts_in_outage(rng):
    sc = Scenario(name="starts in an outage", duration=240.0, dt=0.1, speed=10.0, heading=300.0, turns=TURNS,
                  gps_rate=1.0, sigma_gps=3.0, odometer_scale=1.02, heading_drift=0.03, sigma_heading=0.5,
                  outages=((0.0, 60.0),))
    return _reported(simulate_scenario(sc, rng=rng), 3.0), "phone", 70.0


DRIVES = (urban_canyon, standstills_1hz, mems_gyro, unknown_heading, starts_in_outage)


@pytest.fixture(scope="module", params=DRIVES, ids=lambda d: d.__name__)
def scored(request):
    rng = np.random.default_rng(np.random.SeedSequence([23, DRIVES.index(request.param)]))
    run, grade, first = request.param(rng)
    starts = np.linspace(first, run.t[-1] - 32.0, 4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the filters' own alarms: tested below
        res = real_drive_outages(run, length=30.0, starts=starts, filters=("DR-mech",) + KINDS8,
                                 use_gps_sigma=True, grade=grade)
    return request.param.__name__, res


@pytest.mark.parametrize("kind", KINDS8)
def test_every_8_state_kind_beats_dead_reckoning(scored, kind):
    name, res = scored
    e, dr = res[kind], res["DR-mech"]
    assert np.all(np.isfinite(res["end_xy"][kind]))
    assert np.median(e) < np.median(dr), (name, kind, np.median(e), np.median(dr))
    assert e.max() < dr.max(), (name, kind, e.max(), dr.max())


def test_the_gate_rejects_the_multipath_jumps(scored):
    name, res = scored
    if name != "urban_canyon":
        pytest.skip("the urban-canyon drive only")
    for kind in KINDS8:
        ig = res["integrity"][kind]
        # about a quarter of the fixes jump by 20-80 m against a 4 m sigma
        assert 0.15 * ig["n_fixes"] < ig["n_rejected"] < 0.35 * ig["n_fixes"], (kind, ig["n_rejected"])
        assert len(ig["rejected_xy"]) == ig["n_rejected"]


@pytest.mark.parametrize("kind", KINDS8)
def test_every_8_state_kind_stays_consistent_over_the_drive(scored, kind):
    # the mean NIS of the fixes it accepted as they are, against the 99.9 % point of
    # chi-square(2 m) / m for m consistent fixes (2 expected). The SUKF with its earlier points
    # (3.35 sigma out in 9 states) failed it on the 1 Hz standstill drive: 2.47 against 2.27,
    # with 41 fixes down-weighted where the EKF and UKF down-weighted none
    name, res = scored
    ig = res["integrity"][kind]
    m = ig["n_fixes"] - ig["n_rejected"] - ig["n_downweighted"] - ig["n_reacquired"]
    bound = chi2.ppf(0.999, 2 * m) / m
    assert ig["nis_mean"] <= bound, (name, kind, ig["nis_mean"], bound, ig["n_downweighted"])
