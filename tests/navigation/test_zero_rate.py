"""The zero angular rate update: a stop's heading drift updates the gyro rate bias (issue 23).

A car does not turn while it stands, so the gyro heading's slope over a stop is the gyro's rate
bias; :class:`GPSDRFilter` fits it when the stop ends (:func:`stop_heading_slope`) and updates the
rate-bias state, gated, with the variance the sensor grade gives (or the fit's own standard error
when the headings scatter more).
"""

import re
import warnings

import numpy as np
import pytest

from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.gpsdr import (HEADING_BIAS, KINDS, MAX_STOP_RATE_DEG_S, RATE, STOP_STEP_ALPHA,
                                       STOP_STEP_MIN_SIDE, WALK_MIN_SAMPLES, ZERO_RATE_GATE, ZERO_RATE_MIN_SAMPLES,
                                       GPSDRFilter, stop_heading_slope, stop_heading_step, stop_heading_walk)

DT = 0.1
DEG = np.pi / 180.0
#: DR samples of 5 s driving at 10 m/s (heading 0.5 rad), between stops
MOVING = np.stack([np.full(50, 0.5), np.full(50, 1.0)], axis=1)


def _headings(rng, n, rate, white, arw):
    """``n`` gyro headings (rad) every ``DT`` s from 0: a drift of ``rate`` (rad/s), white noise of
    standard deviation ``white`` (rad) and an angle random walk of density ``arw`` (rad^2/s)."""
    t = DT * np.arange(n)
    return (rate * t + white * rng.standard_normal(n)
            + np.sqrt(arw * DT) * np.concatenate([[0.0], np.cumsum(rng.standard_normal(n - 1))]))


def _stop(rng, model, rate_deg_s, seconds, heading=0.5, turn_deg_s=0.0):
    """DR samples of a car standing ``seconds`` (the gyro heading drifting at the rate bias, plus
    ``turn_deg_s`` of real turning, with the grade's noise), then one moving sample that ends the
    stop: ``(n + 1, 2)``."""
    n = int(round(seconds / DT))
    h = heading + _headings(rng, n, (rate_deg_s + turn_deg_s) * DEG, model.sigma_heading, model.q_bias)
    z = np.stack([np.mod(h + np.pi, 2 * np.pi) - np.pi, np.zeros(n)], axis=1)
    return np.vstack([z, [[heading, 1.0 * DT]]])  # pulls away at 1 m/s


def _run(model, z, kind="ekf", **kw):
    f = GPSDRFilter(model, kind, x0=np.r_[np.zeros(6), model.x0[6:]], **kw)
    for zk in z:
        f.predict()
        f.update(zk)
    return f


@pytest.fixture(scope="module")
def phone():
    return GPSDRModel.from_grade("phone", DT)


def test_the_slope_and_its_variance_match_their_definitions():
    """The closed-form variance against the exact covariance of white noise plus a random walk."""
    t = np.sort(np.random.default_rng(0).uniform(0.0, 20.0, 40))
    sigma, q = 0.01, 2e-5
    slope, var = stop_heading_slope(t, 0.2 - 0.003 * t, sigma, q)
    assert slope == pytest.approx(-0.003, abs=1e-12)
    tc = t - t.mean()
    a = tc / (tc @ tc)
    cov = sigma**2 * np.eye(len(t)) + q * np.minimum.outer(t - t[0], t - t[0])
    assert var == pytest.approx(a @ cov @ a, rel=1e-12)


def test_the_variance_is_honest_over_many_stops(phone):
    """Stops drawn with the grade's own noise: the standardised slope errors have unit variance."""
    rng = np.random.default_rng(1)
    zs = []
    for _ in range(400):
        n = rng.integers(20, 300)
        h = _headings(rng, n, 0.001, phone.sigma_heading, phone.q_bias)
        s, v = stop_heading_slope(DT * np.arange(n), h, phone.sigma_heading, phone.q_bias)
        zs.append((s - 0.001) / np.sqrt(v))
    assert 0.85 < np.var(zs) < 1.15


def test_noisier_headings_than_the_grade_take_the_fits_standard_error():
    t = DT * np.arange(100)
    h = 0.01 * np.random.default_rng(2).standard_normal(100)  # 0.57 degrees, against 0.001 rad said
    slope, var = stop_heading_slope(t, h, 1e-3, 0.0)
    tc = t - t.mean()
    res = h - h.mean() - slope * tc
    assert var == pytest.approx(res @ res / 98 / (tc @ tc), rel=1e-12)
    assert var > 1e-6 / (tc @ tc)


def test_a_stop_across_plus_minus_pi_is_unwrapped():
    t = DT * np.arange(50)
    h = np.pi - 0.01 + 0.001 * t  # crosses +pi at 10 s
    slope, _ = stop_heading_slope(t, np.mod(h + np.pi, 2 * np.pi) - np.pi, 1e-3, 0.0)
    assert slope == pytest.approx(0.001, abs=1e-12)


def test_stop_heading_slope_rejects_bad_input():
    with pytest.raises(ValueError, match="same length >= 2"):
        stop_heading_slope([0.0], [0.0], 1e-3, 0.0)
    with pytest.raises(ValueError, match="constant"):
        stop_heading_slope([1.0, 1.0, 1.0], [0.0, 0.1, 0.2], 1e-3, 0.0)


@pytest.mark.parametrize("kind", KINDS)
def test_a_stop_teaches_the_rate_bias(phone, kind):
    """A 20 s stop with a 0.04 deg/s rate bias: the state goes from 0 (prior sd 0.05 deg/s) to the truth
    within three of its new standard deviations, which is several times smaller than the prior's."""
    z = _stop(np.random.default_rng(3), phone, 0.04, 20.0)
    f = _run(phone, z, kind)
    assert f.n_zero_rate == 1 and f.n_zero_rate_rejected == 0
    step, slope, sd, ok = f.zero_rate_steps[0]
    assert step == len(z) - 1 and ok
    sd_r = np.sqrt(f.P[8, 8])
    assert sd_r < 0.3 * 0.05 * DEG
    assert abs(f.x[8] - 0.04 * DEG) < 3 * sd_r
    off = _run(phone, z, kind, zero_rate_update=False)
    assert off.n_zero_rate == 0 and not off.zero_rate_steps
    assert abs(off.x[8]) < 1e-12 and np.sqrt(off.P[8, 8]) > 0.9 * 0.05 * DEG


def test_the_kinds_make_the_same_update(phone):
    z = _stop(np.random.default_rng(4), phone, -0.03, 15.0)
    fs = [_run(phone, z, kind) for kind in KINDS]
    for f in fs[1:]:
        assert f.x[8] == pytest.approx(fs[0].x[8], rel=1e-9, abs=1e-15)
        assert f.P[8, 8] == pytest.approx(fs[0].P[8, 8], rel=1e-9)


def test_a_car_turning_below_the_standstill_speed_is_rejected(phone):
    """Creeping round a corner at 2 deg/s while the odometer reads below ``standstill_speed``: the
    slope is no rate bias; the gate rejects it, counts it, and the state keeps its prior."""
    z = _stop(np.random.default_rng(5), phone, 0.0, 10.0, turn_deg_s=2.0)
    f = _run(phone, z)
    assert f.n_zero_rate == 0 and f.n_zero_rate_rejected == 1
    _, slope, sd, ok = f.zero_rate_steps[0]
    assert not ok and (slope / DEG) == pytest.approx(2.0, abs=0.2)
    assert ((slope - 0.0) ** 2 / (sd**2 + f.P[8, 8])) > ZERO_RATE_GATE
    assert abs(f.x[8]) < 1e-12


def test_too_short_a_stop_is_not_used(phone):
    z = _stop(np.random.default_rng(6), phone, 0.04, DT * (ZERO_RATE_MIN_SAMPLES - 1))
    f = _run(phone, z)
    assert not f.zero_rate_steps and f.n_zero_rate == 0


def test_only_a_model_with_a_rate_bias_state_has_it():
    survey = GPSDRModel.from_grade("survey", DT)
    assert survey.dim_x == 8
    z = _stop(np.random.default_rng(7), survey, 0.04, 20.0)
    f = _run(survey, z)
    assert f.zero_rate_update is False and not f.zero_rate_steps
    assert GPSDRFilter(GPSDRModel.from_grade("phone", DT)).zero_rate_update is True


def test_every_stop_of_a_drive_is_used(phone):
    """Three stops with moving stretches between them (no GPS): three updates, the state near the
    truth, and the moving samples collect nothing."""
    rng = np.random.default_rng(8)
    z = np.vstack([_stop(rng, phone, 0.02, 8.0), MOVING, _stop(rng, phone, 0.02, 12.0), MOVING,
                   _stop(rng, phone, 0.02, 5.0)])
    f = _run(phone, z)
    assert f.n_zero_rate == 3 and f.n_zero_rate_rejected == 0
    assert abs(f.x[8] - 0.02 * DEG) < 3 * np.sqrt(f.P[8, 8])
    assert not f._stop


def test_a_heading_held_by_its_source_is_not_used(phone):
    """A heading that stays exactly the same over a stop (a fused or GPS-course heading holds its last
    value) measures nothing about the gyro: the stop is counted as held, and the state keeps its prior."""
    z = _stop(np.random.default_rng(9), phone, 0.04, 10.0)
    z[:-1, 0] = 0.5
    f = _run(phone, z)
    assert f.n_zero_rate_held == 1 and f.n_zero_rate == 0 and not f.zero_rate_steps
    assert abs(f.x[8]) < 1e-12


def _bias_jump(rng, model, after, before=0.0, n_before=3, n_after=3, seconds=20.0):
    """Stops with moving stretches between them (no GPS): ``n_before`` at a rate bias of ``before`` deg/s,
    then ``n_after`` at ``after`` (the gyro's bias jumped, as a temperature change or a re-calibration does)."""
    rates = [before] * n_before + [after] * n_after
    return np.vstack([np.vstack([_stop(rng, model, r, seconds), MOVING]) for r in rates])


@pytest.mark.parametrize("kind", KINDS)
def test_a_bias_that_jumped_is_reacquired_from_the_stops(phone, kind):
    """Three stops teach a rate bias of 0; it then jumps to 0.1 deg/s (inside the grade's 3-sigma bound
    of 0.15). Every later stop disagrees with the now-confident state and is rejected; the third in a
    row agrees with the other two (inside the bound two are not enough), so the state re-acquires from
    them, with a warning naming the step, and ends within three of its standard deviations of 0.1 deg/s.
    Without re-acquisition it would reject every stop for ever and keep 0."""
    z = _bias_jump(np.random.default_rng(10), phone, 0.1)
    with pytest.warns(RuntimeWarning, match=r"the last 3 stops measured the gyro rate bias at \+0\.09.* re-acquires "
                                            r"from them at step \d+"):
        f = _run(phone, z, kind)
    assert f.n_zero_rate == 3 and f.n_zero_rate_rejected == 3 and f.n_zero_rate_reacquired == 1
    assert [ok for *_, ok in f.zero_rate_steps] == [True] * 3 + [False] * 3
    assert abs(f.x[8] - 0.1 * DEG) < 3 * np.sqrt(f.P[8, 8]) and np.sqrt(f.P[8, 8]) < 0.01 * DEG
    assert np.all(np.linalg.eigvalsh(f.P) > 0)
    never = _run(phone, z, kind, zero_rate_reacquire_after=0)
    assert never.n_zero_rate_rejected == 3 and never.n_zero_rate_reacquired == 0
    assert abs(never.x[8]) < 0.02 * DEG


def test_rejected_stops_that_disagree_do_not_reacquire(phone):
    """Three stops in a row creeping round corners (+2, -2, +2 deg/s below the standstill speed): each is
    rejected, but they do not agree with each other, so the state keeps what the first stops taught."""
    rng = np.random.default_rng(11)
    z = np.vstack([_bias_jump(rng, phone, 0.0, n_after=0)]
                  + [np.vstack([_stop(rng, phone, 0.0, 20.0, turn_deg_s=turn), MOVING]) for turn in (2.0, -2.0, 2.0)])
    f = _run(phone, z)
    assert f.n_zero_rate == 3 and f.n_zero_rate_rejected == 3 and f.n_zero_rate_reacquired == 0
    assert abs(f.x[8]) < 0.02 * DEG


@pytest.mark.parametrize("kind", KINDS)
def test_turning_crawls_that_agree_are_no_gyro_bias(phone, kind):
    """Three 20 s crawls in a row, each turning 80 deg (4 deg/s) while the speed reads 0 (a queue below a
    wheel-speed sensor's cutoff, a car park): each is rejected, and their slopes agree with each other,
    but no gyro's bias is 4 deg/s, so they are counted as turned, warned once, and do not re-acquire the
    rate bias (before they did: the state took 4 deg/s, the heading bias ran away, and a probe drive's
    outages ended 1 km off). The stops before them still teach the state."""
    rng = np.random.default_rng(14)
    z = np.vstack([_bias_jump(rng, phone, 0.0, n_after=0)]
                  + [np.vstack([_stop(rng, phone, 0.0, 20.0, turn_deg_s=4.0), MOVING]) for _ in range(3)])
    with pytest.warns(RuntimeWarning, match=r"the heading turned \+(79|80)\.\d deg \(a fitted drift of \+(3\.9|4\.0)\d* deg/s\), faster than any "
                                            r"gyro's bias \(1 deg/s\), while the speed read 0: the car moved"):
        f = _run(phone, z, kind)
    assert f.n_zero_rate == 3 and f.n_zero_rate_rejected == 3 and f.n_zero_rate_turned == 3
    assert f.n_zero_rate_reacquired == 0
    assert abs(f.x[8]) < 0.02 * DEG
    assert MAX_STOP_RATE_DEG_S == 1.0


@pytest.mark.parametrize("kind", KINDS)
def test_a_crawl_that_turns_for_part_of_a_stop_is_turned_not_a_walk(phone, kind):
    """Three 20 s stops in a row whose car stands for 10 s, then creeps round a corner at 4 deg/s while the speed
    reads 0 (the sensor-faults probe's city car): a turn for part of a stop is no line, and read as a walk
    (``stop_heading_walk``) it widened the slope's variance until the gate took the turn for the gyro's and used
    it (stop 59; the probe's 1 stop used, 4 rejected (3 turned) became 5 used). Counted as turned now, before the
    gate: warned, rejected, and kept out of the rate bias."""
    rng = np.random.default_rng(16)
    stops = []
    for _ in range(3):
        z = _stop(rng, phone, 0.0, 20.0)
        ramp = np.clip(DT * np.arange(len(z) - 1) - 10.0, 0.0, None) * 4.0 * DEG
        z[:-1, 0] = np.mod(z[:-1, 0] + ramp + np.pi, 2 * np.pi) - np.pi
        stops.append(np.vstack([z, MOVING]))
    z = np.vstack([_bias_jump(rng, phone, 0.0, n_after=0)] + stops)
    with pytest.warns(RuntimeWarning, match="faster than any gyro's bias"):
        f = _run(phone, z, kind)
    assert f.n_zero_rate == 3 and f.n_zero_rate_turned == 3 and f.n_zero_rate_reacquired == 0
    assert abs(f.x[8]) < 0.02 * DEG


def test_a_mems_gyro_bias_is_still_followed(phone):
    """0.7 deg/s, a MEMS gyro's turn-on bias and far outside the phone grade: under the turning limit, so
    the stops re-acquire the state, as for any gyro outside its grade."""
    z = _bias_jump(np.random.default_rng(15), phone, 0.7, n_before=0, n_after=4)
    with pytest.warns(RuntimeWarning, match="re-acquires from them"):
        f = _run(phone, z)
    assert f.n_zero_rate_turned == 0 and f.n_zero_rate_reacquired == 1
    assert abs(f.x[8] - 0.7 * DEG) < 3 * np.sqrt(f.P[8, 8])


def test_zero_rate_reacquire_after_is_checked(phone):
    with pytest.raises(ValueError, match="zero_rate_reacquire_after must be >= 0"):
        GPSDRFilter(phone, zero_rate_reacquire_after=-1)


def test_a_gyro_outside_its_grade_is_followed_with_a_warning(phone):
    """A rate bias of 0.3 deg/s against the phone grade's 0.05 (its bound: three prior sigmas, 0.15 and
    growing slowly). The stops are rejected; the second in a row, outside the bound, re-acquires (until stop 59
    the third), and the calibration bounds
    restart from the stops' value, so the state follows the gyro (within three of its sigmas of 0.3)
    instead of being held at the bound. Without re-acquisition it stays under the grade's bound."""
    z = _bias_jump(np.random.default_rng(12), phone, 0.3, n_before=0, n_after=4)
    with pytest.warns(RuntimeWarning, match="calibration bounds of the rate bias and the heading bias restart"):
        f = _run(phone, z)
    assert f.n_zero_rate_rejected == 2 and f.n_zero_rate_reacquired == 1 and f.n_zero_rate == 2
    assert abs(f.x[8] - 0.3 * DEG) < 3 * np.sqrt(f.P[8, 8])
    never = _run(phone, z, zero_rate_reacquire_after=0)
    assert never.n_zero_rate_rejected == 4 and never.x[8] < 0.16 * DEG


def test_the_warning_names_the_gyros_own_specification_as_the_remedy(phone):
    """A gyro outside its grade (0.3 deg/s against the phone grade's 0.05): the re-acquisition's warning
    gives the value to state, gyro_bias_deg_s=0.31 (--gyro-bias 0.31), and a grade with it follows the same
    stops from the first, with no re-acquisition. A bias that jumped inside the grade (0.1 deg/s, its
    bound 0.15) has no such value: the warning names the gyro's bias instability instead (a bias that moves)."""
    z = _bias_jump(np.random.default_rng(12), phone, 0.3, n_before=0, n_after=4)
    with pytest.warns(RuntimeWarning, match=r"re-acquires from them .* turn-on bias is 0\.3\d? deg/s, more than "
                                            r"the grade's, .*gyro_bias_deg_s=0\.3\d? \(filterwnn study dr --gyro-bias 0\.3\d?\)"):
        _run(phone, z)
    own = GPSDRModel.from_grade({"gyro_bias_deg_s": 0.31}, DT)
    f = _run(own, z)
    assert f.n_zero_rate == 4 and f.n_zero_rate_rejected == 0 and f.n_zero_rate_reacquired == 0
    assert abs(f.x[8] - 0.3 * DEG) < 3 * np.sqrt(f.P[8, 8])
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        _run(phone, _bias_jump(np.random.default_rng(10), phone, 0.1))
    said = [str(w.message) for w in seen if "re-acquires from them" in str(w.message)]
    assert len(said) == 1 and "gyro_bias_deg_s" not in said[0]
    assert "bias moves faster than the grade allows, give the gyro's bias instability, gyro_bias_instability_deg_h" \
        in said[0] and "the model's 10)" in said[0]


def test_each_calibration_bound_names_its_own_remedy(phone):
    """Held at its bound, the rate bias names the gyro's own specification (at least the value held), the
    odometer scale the drive reader's speed_scale (a speed that reads high), the heading bias neither."""
    f = GPSDRFilter(phone, x0=np.r_[np.zeros(6), phone.x0[6:]])
    f.predict()
    for row, value, want, not_ in ((8, 0.3 * DEG, r"gyro rate bias state ran past .* at least 0\.16 deg/s.*--gyro-bias 0\.16",
                                    "speed_scale"),
                                   (6, 1.2, r"odometer scale state ran past .* reads more than the car drove .*"
                                            r"speed_scale= \(--speed-scale\)", "gyro-bias"),
                                   (7, 30.0 * DEG, r"heading bias state ran past", "speed_scale")):
        f.kf.x = np.r_[f.kf.x[:row], value, f.kf.x[row + 1:]]
        with pytest.warns(RuntimeWarning, match=want) as seen:
            f._bound_calibration()
        assert all(not_ not in str(w.message) and "gyro-bias" not in str(w.message) * (row != 8) for w in seen)


def test_stops_held_at_the_bound_count_as_not_followed(phone):
    """Short stops (3 s) at 0.3 deg/s each pass the gate (their slopes are uncertain), so the state climbs
    until the calibration bound holds it near 0.15 deg/s. Stops the bound holds are ones the state could
    not follow, as rejected ones are: those that agree and measure a bias outside the bound re-acquire, and the
    state follows the gyro."""
    z = _bias_jump(np.random.default_rng(13), phone, 0.3, n_before=0, n_after=20, seconds=3.0)
    with pytest.warns(RuntimeWarning, match="held at its calibration bound"):
        f = _run(phone, z)
    assert f.n_zero_rate_reacquired >= 1
    assert abs(f.x[8] - 0.3 * DEG) < 3 * np.sqrt(f.P[8, 8])
    never = _run(phone, z, zero_rate_reacquire_after=0)
    assert never.n_zero_rate_reacquired == 0 and never.x[8] < 0.16 * DEG
    assert never.n_zero_rate_rejected < 3  # they passed the gate: the gate alone would never re-acquire


def test_a_reacquisition_widens_the_heading_bias_by_what_it_integrated_while_held(phone):
    """While the bound holds the rate bias, the heading bias integrates the difference: at the
    re-acquisition its variance grows by (the rate bias's change times the time held)^2, its
    cross-covariances are dropped, and its calibration bound widens by as much. A re-acquisition
    whose state was never held (a jump inside the bound) leaves the heading bias as it was."""
    seen = []

    class Spy(GPSDRFilter):
        def _zero_rate_reacquire(self):
            before = (self._rate_clamped_since, self.step, self.x.copy(), self.P.copy(), self._cal_P.copy())
            n = self.n_zero_rate_reacquired
            super()._zero_rate_reacquire()
            if self.n_zero_rate_reacquired > n:
                seen.append(before + (self.P.copy(), self._cal_P.copy()))

    def run(z):
        f = Spy(phone, x0=np.r_[np.zeros(6), phone.x0[6:]])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            for zk in z:
                f.predict()
                f.update(zk)
        return f

    run(_bias_jump(np.random.default_rng(13), phone, 0.3, n_before=0, n_after=20, seconds=3.0))
    since, step, _, P, cal_P, P_new, cal_P_new = seen[0]
    assert since is not None and step - since > 50
    lag_min = (0.3 - 0.16) * DEG * (step - since) * DT  # the state is held at most at 0.16 deg/s
    assert P_new[7, 7] - P[7, 7] > lag_min ** 2
    assert np.all(P_new[7, np.r_[0:7, 8]] == 0.0)
    assert cal_P_new[1, 1] - cal_P[1, 1] == pytest.approx(P_new[7, 7] - P[7, 7], rel=1e-9)

    seen.clear()
    run(_bias_jump(np.random.default_rng(10), phone, 0.1))
    since, step, _, P, cal_P, P_new, cal_P_new = seen[0]
    assert since is None and P_new[7, 7] == P[7, 7] and cal_P_new[1, 1] == cal_P[1, 1]


def test_the_rate_bias_is_held_from_its_first_clamp_until_it_is_well_inside_its_bound(phone):
    """The time the heading bias is widened by counts from the step the bound first held the rate bias,
    and is forgotten once the state is back more than one of its standard deviations inside the bound
    (an early clamp does not widen a re-acquisition many minutes later)."""
    f = GPSDRFilter(phone, x0=np.r_[np.zeros(6), phone.x0[6:]])
    bound = 3.0 * 0.05 * DEG
    for _ in range(5):
        f.predict()
    with pytest.warns(RuntimeWarning, match="gyro rate bias state ran past"):
        f.kf.x = np.r_[f.kf.x[:8], 0.3 * DEG]
        f._bound_calibration()
    since = f._rate_clamped_since
    assert since == f.step and f.kf.x[8] == pytest.approx(bound, rel=1e-3)
    f.predict()
    f.update(np.array([0.0, 0.0]))  # a step later
    f.kf.x = np.r_[f.kf.x[:8], bound - 0.5 * np.sqrt(f.P[8, 8])]  # inside, but within one sigma: still held
    f._bound_calibration()
    assert f._rate_clamped_since == since < f.step
    f.kf.x = np.r_[f.kf.x[:8], 0.0]
    f._bound_calibration()
    assert f._rate_clamped_since is None


def test_a_standstill_whose_speed_flickers_is_one_stop_with_stop_reopen(phone):
    """A 30 s standstill whose speed reads over the standstill speed every third sample (a GNSS speed's
    noise, 0.1 m/s; 0.3 m in all): without stop_reopen, ten pieces too short to use or with slopes of no
    weight, and the rate bias stays near its prior; with 2 s, one stop, used once, and the state at the
    truth with a standard deviation a fifth of the prior's. A real stop (MOVING after it) is not merged."""
    rng = np.random.default_rng(11)
    z = _stop(rng, phone, 0.08, 30.0)[:-1]
    z[2::3, 1] = 0.1 * DT  # 0.1 m/s: over the standstill speed
    z = np.vstack([z, MOVING])
    cut = _run(phone, z)
    whole = _run(phone, z, stop_reopen=2.0)
    assert cut.n_zero_rate + cut.n_zero_rate_rejected == 0  # two samples a piece: none long enough
    assert abs(cut.x[8]) < 0.01 * DEG
    assert whole.n_zero_rate == 1 and whole.n_zero_rate_rejected == 0
    sd = np.sqrt(whole.P[8, 8])
    assert sd < 0.2 * 0.05 * DEG and abs(whole.x[8] - 0.08 * DEG) < 3 * sd
    two = _run(phone, np.vstack([z, _stop(rng, phone, 0.08, 10.0), MOVING]), stop_reopen=2.0)
    assert two.n_zero_rate == 2  # the drive between (5 s, 50 m) keeps them apart


def test_stop_reopen_is_checked_and_off_by_default(phone):
    assert GPSDRFilter(phone).stop_reopen == 0.0
    with pytest.raises(ValueError, match="stop_reopen must be >= 0 s"):
        GPSDRFilter(phone, stop_reopen=-1.0)
    with pytest.raises(ValueError, match="stop_reopen must be >= 0 s"):
        GPSDRFilter(phone, stop_reopen=float("nan"))


def test_the_command_passes_stop_reopen_to_the_filters(command_passes):
    assert command_passes("real_drive_outages", ["--stop-reopen", "2"])["stop_reopen"] == 2.0
    assert command_passes("real_drive_outages", [])["stop_reopen"] == 0.0


def test_the_command_passes_calibration_error_z_to_the_filters(command_passes):
    assert command_passes("real_drive_outages", [])["calibration_error_z"] == pytest.approx(3.2905, abs=1e-4)
    assert command_passes("real_drive_outages", ["--calibration-error-z", "5"])["calibration_error_z"] == 5.0
    assert command_passes("real_drive_outages", ["--calibration-error-z", "off"])["calibration_error_z"] is None
    assert command_passes("real_drive_outages", ["--calibration-error-z", "0"]) == {}  # refused: > 0 or off


def test_the_command_passes_heading_jump_z_to_the_filters(command_passes):
    assert command_passes("real_drive_outages", [])["heading_jump_z"] == 6.1
    assert command_passes("real_drive_outages", ["--heading-jump-z", "8"])["heading_jump_z"] == 8.0
    assert command_passes("real_drive_outages", ["--heading-jump-z", "off"])["heading_jump_z"] is None
    assert command_passes("real_drive_outages", ["--heading-jump-z", "-1"]) == {}  # refused: > 0 or off


def test_stop_heading_step_finds_a_step_past_the_grades_noise(phone):
    """A 1.5 deg step 8 s into a 20 s stop, with the grade's noise: found before its sample, its size within
    three of its standard deviations, and a slope fitted on either side of it near the drift; the line alone
    reads the step as a drift many of its standard deviations off."""
    rng = np.random.default_rng(20)
    t = DT * np.arange(200)
    h = 0.5 + _headings(rng, 200, 0.02 * DEG, phone.sigma_heading, phone.q_bias) + 1.5 * DEG * (t >= 8.0)
    k, size, sd, p = stop_heading_step(t, h, phone.sigma_heading, phone.q_bias)
    assert k == 80 and p < 1e-6
    assert abs(size - 1.5 * DEG) < 3 * sd
    slope, var = stop_heading_slope(t, h, phone.sigma_heading, phone.q_bias, step_at=k)
    assert abs(slope - 0.02 * DEG) < 3 * np.sqrt(var)
    line, line_var = stop_heading_slope(t, h, phone.sigma_heading, phone.q_bias)
    assert abs(line - 0.02 * DEG) > 5 * np.sqrt(line_var)


def test_a_turn_while_the_speed_reads_zero_is_no_step(phone):
    """A car creeping round a corner while its speed reads 0 (a queue under a speed sensor's cutoff) turns its
    heading by 103 degrees over 12 s of a 57 s "stop" (a 5 m radius at 0.8 m/s): a step fits that better than a
    line (p = 3e-6, below the test's 1e-3), but the headings' means over a second either side of it differ by
    about 17 degrees, not half the step: no step (the stop is a turn, rejected as such); the same 103 degrees in
    one sample is one, and so is a 2 degree re-alignment spread over half a second."""
    rng = np.random.default_rng(23)
    t = DT * np.arange(570)
    noise = _headings(rng, 570, 0.02 * DEG, phone.sigma_heading, phone.q_bias)
    turn = 103.0 * DEG * np.clip((t - 20.0) / 12.0, 0.0, 1.0)
    k, size, sd, p = stop_heading_step(t, 0.5 + noise + turn, phone.sigma_heading, phone.q_bias)
    assert k is None and size == 0.0 and p < STOP_STEP_ALPHA, (k, p)
    k, size, sd, p = stop_heading_step(t, 0.5 + noise + 103.0 * DEG * (t >= 29.0), phone.sigma_heading, phone.q_bias)
    assert k == 290 and abs(size - 103.0 * DEG) < 3 * sd
    smooth = 2.0 * DEG * np.clip((t - 29.0) / 0.5, 0.0, 1.0)
    k, size, sd, p = stop_heading_step(t, 0.5 + noise + smooth, phone.sigma_heading, phone.q_bias)
    assert k is not None and 289 <= k <= 296 and abs(size - 2.0 * DEG) < 0.5 * DEG, (k, np.degrees(size))


def test_headings_as_the_grade_describes_them_make_no_step(phone):
    """Over 300 stops of 3-60 s with the grade's white noise and angle random walk, and 100 with the random
    walk alone (a gyro heading without white noise, which is no line), no step is found."""
    rng = np.random.default_rng(21)
    found = 0
    for i in range(400):
        n = int(rng.integers(30, 600))
        white = phone.sigma_heading if i < 300 else 0.0
        h = 0.5 + _headings(rng, n, 0.03 * DEG, white, phone.q_bias)
        found += stop_heading_step(DT * np.arange(n), h, phone.sigma_heading, phone.q_bias)[0] is not None
    assert found == 0


def test_a_low_passed_heading_is_not_taken_for_steps(phone):
    """A fused heading smoother than white (AR(1) noise with a lag-1 correlation of 0.5, 0.3 deg): its own
    scatter, widened by the correlation, keeps the test at its level (at most 1 in 100 stops of 15 s)."""
    rng = np.random.default_rng(22)
    found = 0
    for _ in range(100):
        e = rng.standard_normal(150)
        for i in range(1, 150):
            e[i] = 0.5 * e[i - 1] + np.sqrt(0.75) * e[i]
        h = 0.5 + 0.3 * DEG * e
        found += stop_heading_step(DT * np.arange(150), h, phone.sigma_heading, phone.q_bias)[0] is not None
    assert found <= 1


def test_stop_heading_step_needs_enough_samples_on_each_side():
    t = DT * np.arange(2 * STOP_STEP_MIN_SIDE + 1)
    assert stop_heading_step(t, 0.1 * (t > 0.3)) == (None, 0.0, 0.0, 1.0)
    with pytest.raises(ValueError, match="same length"):
        stop_heading_step(t, t[:-1])
    with pytest.raises(ValueError, match="step_at"):
        stop_heading_slope(t, t, 1e-3, 0.0, step_at=1)


@pytest.mark.parametrize("kind", KINDS)
def test_a_heading_that_steps_during_a_stop_moves_the_heading_bias_not_the_rate_bias(phone, kind):
    """A fused heading re-aligning by 2 deg halfway through a 20 s stop: the stop's drift is fitted on either
    side (the rate bias near the truth, not the 0.15 deg/s a line reads), the heading bias takes the step
    (against the same stop without it), the step is counted and warned once with its step and size."""
    z = _stop(np.random.default_rng(23), phone, 0.02, 20.0)
    stepped = z.copy()
    stepped[100:-1, 0] = np.mod(stepped[100:-1, 0] + 2.0 * DEG + np.pi, 2 * np.pi) - np.pi
    with pytest.warns(RuntimeWarning, match=r"stepped by \+2\.\d+ deg at step 100") as record:
        f = _run(phone, stepped, kind)
    assert sum("stepped" in str(w.message) for w in record) == 1
    clean = _run(phone, z, kind)
    assert f.n_zero_rate_stepped == 1 and clean.n_zero_rate_stepped == 0
    assert f.n_zero_rate == 1 and f.zero_rate_steps[0][3]
    assert abs(f.x[RATE] - 0.02 * DEG) < 3 * np.sqrt(f.P[RATE, RATE])
    shift = f.x[HEADING_BIAS] - clean.x[HEADING_BIAS]
    assert abs(shift - 2.0 * DEG) < 0.2 * DEG
    assert f.P[HEADING_BIAS, HEADING_BIAS] > clean.P[HEADING_BIAS, HEADING_BIAS]


def _noisy_gyro_stops(rng, model, rate_deg_s, walk, n=4, seconds=25.0):
    """``n`` stops, with moving stretches between, of a heading integrated from a gyro of rate bias ``rate_deg_s``
    whose angle random walk is ``walk`` times the grade's (density; no white part: a yaw rate's integral)."""
    def stop():
        k = int(round(seconds / DT))
        h = 0.5 + _headings(rng, k, rate_deg_s * DEG, 0.0, walk * model.q_bias)
        return np.vstack([np.stack([h, np.zeros(k)], axis=1), [[0.5, 1.0 * DT]], MOVING])
    return np.vstack([stop() for _ in range(n)])


def test_a_walk_is_measured_only_past_the_grades():
    """stop_heading_walk reads a walk 400 times the grade's density (20 times its angle random walk) within a
    factor of two, and gives the grade's for white headings, for a walk of the grade's own, and for a white
    heading that steps (the changes across the step left out)."""
    rng = np.random.default_rng(30)
    t = DT * np.arange(250)
    grade = (0.3 * DEG / 60.0) ** 2
    ratios = [stop_heading_walk(t, _headings(rng, 250, 0.4 * DEG, 0.0, 400 * grade), grade) / (400 * grade)
              for _ in range(20)]
    assert 0.5 < np.median(ratios) < 2.0 and min(ratios) > 0.2
    for h in (_headings(rng, 250, 0.0, 0.5 * DEG, 0.0), _headings(rng, 250, 0.01 * DEG, 0.0, grade),
              _headings(rng, 250, 0.0, 0.1 * DEG, 0.0) + 2.0 * DEG * (t >= 10.0)):
        assert stop_heading_walk(t, h, grade) == grade
    assert stop_heading_walk(t[:WALK_MIN_SAMPLES - 1], _headings(rng, WALK_MIN_SAMPLES - 1, 0.0, 0.0, 400 * grade),
                             grade) == grade


@pytest.mark.parametrize("kind", KINDS)
def test_a_gyro_noisier_than_its_grade_is_followed_from_the_second_stop(phone, kind):
    """A gyro outside the phone grade (0.4 deg/s) whose angle random walk is 20 times the grade's (a simulated
    ROS drive's, stop 59): each stop's slope scatters by about 0.02 deg/s, while the grade's walk and white
    noise said 0.002-0.007, so the stops, which agree, were taken to disagree, the state was not re-acquired
    until three happened to agree (two thirds into that drive: EKF-8 251 / 634 m at the outage ends), and the
    walk read as a heading step. With the walk measured from the stops, the second re-acquires, no step is
    found, and the state ends within three of its sigmas of 0.4 deg/s."""
    z = _noisy_gyro_stops(np.random.default_rng(31), phone, -0.4, 400.0)
    with pytest.warns(RuntimeWarning, match="re-acquires from them"):
        f = _run(phone, z, kind)
    assert f.n_zero_rate_reacquired == 1 and f.n_zero_rate_stepped == 0
    assert [ok for *_, ok in f.zero_rate_steps] == [False] * 2 + [True] * 2
    assert abs(f.x[8] + 0.4 * DEG) < 3 * np.sqrt(f.P[8, 8])


def test_stops_that_measure_little_do_not_reacquire_however_they_agree(phone):
    """Two stops the state could not follow, agreeing loosely on 1.8 +- 1.9 deg/s (1 s stops, used but held at the
    calibration bound), tell the state (0.15 deg/s) nothing: together they pass its gate, and the state stays (with
    two stops in a row such a pair re-acquired the phone analog's UKF-8, which diverged to 280 km; stop 59). Two
    that measure the bias (0.40 and 0.41 +- 0.01 deg/s) re-acquire."""
    for stops, reacquired in (([1.6, 2.0], 2.7), ([0.40, 0.41], 0.01)):
        f = GPSDRFilter(phone, x0=np.r_[np.zeros(6), phone.x0[6:]])
        x, P = f.kf.x.copy(), f.kf.P.copy()
        x[8], P[8, 8] = 0.15 * DEG, (0.01 * DEG) ** 2
        f.kf.x, f.kf.P = x, P
        f._zr_rejected.extend((s * DEG, (reacquired * DEG) ** 2) for s in stops)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            f._zero_rate_reacquire()
        assert f.n_zero_rate_reacquired == (reacquired < 1.0)


def _full_run(path, grade="phone"):
    """A drive CSV run whole through the EKF-8 of ``grade`` as ``filterwnn study dr --drive`` starts it
    (1 m of position sigma), warnings recorded: ``(filter, warnings)``."""
    from filterwnn.navigation.drives import read_drive_csv

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(path, progress=False)
    model = GPSDRModel.from_grade(grade, dt=run.scenario.dt)
    P0 = model.P0.copy()
    P0[0, 0] = P0[3, 3] = 1.0
    f = GPSDRFilter(model, x0=np.r_[run.x0, model.x0[6:]], P0=P0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for z, fix, sigma in zip(run.z_dr, run.gps_list(), run.gps_sigma_list()):
            f.predict()
            f.update(z, fix, sigma)
    return f, [str(w.message) for w in caught]


@pytest.mark.filterwarnings("ignore:GPSDRFilter at step 0. the odometer reads")
def test_the_rate_bias_books_where_its_information_came_from(phone):
    """``rate_bias_fix_share``: 0 from the grade's prior and the stops alone, near 1 once fixes on a long drive
    taught the state, None for a model without a rate-bias state."""
    rng = np.random.default_rng(3)
    f = _run(phone, np.vstack([MOVING, _stop(rng, phone, 0.02, 20.0)]))
    assert f.n_zero_rate == 1 and f.rate_bias_fix_share == 0.0
    g = GPSDRFilter(phone, x0=np.r_[np.zeros(6), phone.x0[6:]])
    x = np.zeros(2)
    for k in range(1200):  # 2 minutes at 10 m/s heading 0.5 rad with a fix a second, the gyro without bias
        g.predict()
        x = x + 1.0 * np.array([np.sin(0.5 + 0.3 * np.sin(k / 100)), np.cos(0.5 + 0.3 * np.sin(k / 100))])
        fix = x + rng.normal(0.0, 2.0, 2) if k % 10 == 0 else None
        g.update([0.5 + 0.3 * np.sin(k / 100), 1.0], fix, 2.0 if fix is not None else None)
    assert g.rate_bias_fix_share > 0.9
    survey = GPSDRFilter(GPSDRModel.from_grade("survey", DT), x0=np.zeros(8))
    assert survey.rate_bias_fix_share is None


def test_a_stop_that_contradicts_a_rate_bias_the_fixes_taught_is_told(tmp_path):
    """A fused heading (an AHRS yaw whose bias wanders 0.5 degrees over 300 s) with fixes correlated over 20 s, phone
    grade: the fixes teach the rate bias -0.024 deg/s in two minutes, the first stop measures +0.016 and the gate
    rejects it (stop 73; the sixth trial's ``enu_restart_clean``, whose outages end 5.40 / 21.89 m off against dead
    reckoning's 3.06 / 7.44, silent until then). Told once, with the residual bias to give; a drive whose gyro the
    stops measure (the phone analog) is not told."""
    import os
    import subprocess
    import sys

    here = os.path.dirname(os.path.abspath(__file__))
    gen = os.path.join(here, "..", "..", "docs", "study-outputs", "dr", "user-trial", "gen_drives_6.py")
    subprocess.run([sys.executable, gen, str(tmp_path)], check=True, capture_output=True)
    f, said = _full_run(tmp_path / "enu_restart_clean.csv")
    told = [w for w in said if "of whose information the GPS fixes gave" in w]
    assert len(told) == 1 and f.fix_taught_step is not None
    assert re.search(r"the stop that ended at step \d+ measured the heading's drift at \+0\.016 \+- 0\.002\d? deg/s, "
                     r"and the gyro rate-bias state \(-0\.0\d+ \+- 0\.00\d+ deg/s\), 9\d% of whose information the "
                     r"GPS fixes gave .* --gyro-bias 0\.021\)", told[0])
    sys.path.insert(0, os.path.join(here, ".."))
    try:
        import _held_out_drives as held_out
    finally:
        sys.path.pop(0)
    path = held_out.write_csv(tmp_path / "phone_0.csv", held_out.columns("phone", 0))
    g, said = _full_run(path)
    assert g.fix_taught_step is None and g.n_zero_rate > 0
    assert not [w for w in said if "of whose information the GPS fixes gave" in w]


@pytest.mark.parametrize("hold", [True, False])
def test_with_hold_heading_at_stops_a_rejected_stops_drift_goes_to_the_heading_bias(phone, command_passes, hold):
    """``hold_heading_at_stops``: the car does not turn while it stands, so a stop whose drift the gate rejects
    (0.3 deg/s, past the phone grade's 0.05 against a state still at its prior; a gyro whose bias differs at idle,
    the engine's vibration, stop 74's seventh user) leaves the rate bias as it was, and the heading bias takes the
    drift beyond the state over the stop, once warned. Off (the default), the heading keeps the drift. A stop the gate
    takes moves the heading bias only as the rate bias drives it. The command's flag reaches the filters."""
    assert command_passes("real_drive_outages", ["--hold-heading-at-stops"])["hold_heading_at_stops"] is True
    assert command_passes("real_drive_outages", [])["hold_heading_at_stops"] is False
    rng = np.random.default_rng(7)
    z = np.vstack([MOVING, _stop(rng, phone, 0.3, 60.0)])
    f = GPSDRFilter(phone, "ekf", x0=np.r_[np.zeros(6), phone.x0[6:]], hold_heading_at_stops=hold)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        for zk in z[:-1]:
            f.predict()
            f.update(zk)
        rate, bias = f.kf.x[RATE], f.kf.x[HEADING_BIAS]
        f.predict()
        f.update(z[-1])
    step, slope, sd, ok = f.zero_rate_steps[-1]
    assert not ok and f.n_zero_rate_rejected == 1
    assert f.kf.x[RATE] == pytest.approx(rate, abs=1e-4 * DEG)  # the rate bias learns nothing from it
    if not hold:
        assert f.n_zero_rate_drift_taken == 0 and not [w for w in seen if "drifted" in str(w.message)]
        assert abs(f.kf.x[HEADING_BIAS] - bias) < 0.01 * DEG
        return
    assert f.n_zero_rate_drift_taken == 1
    T = 60.0 - DT
    assert f.kf.x[HEADING_BIAS] - bias == pytest.approx((slope - rate) * T, abs=0.02 * DEG + abs(rate) * DT)
    assert abs(np.degrees(f.kf.x[HEADING_BIAS] - bias) - 0.3 * T) < 1.0
    said = [str(w.message) for w in seen if "drifted" in str(w.message)]
    assert len(said) == 1 and re.search(r"the heading bias takes the \+1\d.?\d* deg the heading drifted beyond", said[0]), said
    # the same stop inside the grade (0.02 deg/s) is taken by the gate: nothing for the heading bias to take
    f = _run(phone, np.vstack([MOVING, _stop(np.random.default_rng(7), phone, 0.02, 60.0)]), hold_heading_at_stops=True)
    assert f.zero_rate_steps[-1][3] and f.n_zero_rate_drift_taken == 0
