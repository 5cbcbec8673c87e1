r"""The GPS/DR filter: EKF, UKF or SUKF on :class:`~filterwnn.navigation.dead_reckoning.GPSDRModel`.

A car stands at lights, pulls away, crawls in traffic and drives through tunnels. The
DR measurement ``[heading, odometer distance]`` says nothing useful about the velocity
when the car stands (the heading of a standing car is undefined, and the odometer's
Jacobian vanishes at zero estimated speed, so a filter that starts from rest never picks
up speed), so :class:`GPSDRFilter` decides from each odometer reading which form of the
DR measurement to use:

* odometer speed ``s / dt < standstill_speed``: a zero-velocity update
  ``[v_e, v_n] = 0`` (the car stands; a CAN speed creeps at 0.001-0.03 mph standing,
  so the test is a threshold, not an exact zero);
* ``s / dt < low_speed``: the measured velocity vector ``s/dt [sin theta, cos theta]``,
  linear in the velocity (no singularity at zero speed);
* faster: the paper's ``[heading, distance]`` measurement, unless its heading (less the heading bias) is
  more than ``heading_linear_limit`` (:data:`HEADING_LINEAR_LIMIT`, 30 degrees) from the filter's: that
  update is linearised about the filter's heading and overshoots far from it, so such a sample enters as the
  velocity vector too (a glitch, a start heading far off; counted in ``n_heading_far``, the first warned).

An unsigned speed (a CAN bus's, OBD's) cannot say that the car reverses, and the heading is the car's nose, so
dead reckoning takes a car backing out of a parking space forward: the fixes and the prediction part at twice the
distance reversed. While the car moves the filter tests the fixes against the dead reckoning's displacement, taken
the way it goes and the other way (``reversing_test``, Wald's sequential test at :data:`REVERSING_ALPHA`, each path
also with an unknown constant offset of its fixes, so that a street's multipath that lasts does not read as
reversing); when the other way wins, the position goes to the test's start less the displacement, the velocity
turns, and the samples until the next stop (or the next such decision: a 1 Hz log may change direction with no
standing sample) enter with their heading turned by half a turn (counted in ``n_reversing`` and
``n_forward_again``, the first of each warned). With no fixes (an outage) nothing can tell; a signed speed tells
the drive reader instead.

A speed sensor that reads 0 below a cutoff (a wheel-speed sensor's, a CAN speed's) makes a car creeping in a queue
a standing one, and the zero-velocity update holds it where it stopped. While the speed reads 0 the filter tests
the fixes against the position where the car stopped and against a crawl along its heading at an unknown speed
(``crawl_test``, a generalized likelihood ratio at :data:`CRAWL_ALPHA`, each with an unknown constant offset of
the fixes, and guarded against fixes that jump while the car stands); when the crawl wins, the position moves
along the heading to where the fixes put it and the test starts again from there (counted in ``n_crawl``, the
first warned).

Both thresholds are public attributes, on by default; set ``low_speed=0``,
``standstill_speed=0`` and ``heading_linear_limit=None`` to switch the logic off. A GPS
fix's own accuracy (e.g. the receiver's reported horizontal accuracy) is used as its noise when given
(``update(..., gps_sigma=...)``); otherwise the model's ``sigma_gps``.

What the filter does when GPS lies (each part a public setting, on by default):

* **Integrity gate.** Each fix's innovation ``y = z - [e, n]^-`` is tested against its
  predicted covariance ``S = P^-_{pos} + R_{gps}`` before it is used: the normalised
  innovation squared ``NIS = y^T S^{-1} y`` is chi-square with 2 degrees of freedom for a
  consistent filter. A fix with ``NIS <= gate`` (default :data:`GATE`, the 99.9 % point,
  13.8) is used as it is; up to ``reject_gate`` (default :data:`REJECT_GATE`, the
  1 - 1e-9 point, 41.4) it is down-weighted, its sigma scaled by ``sqrt(NIS / gate)``
  (Huber's weight: it counts as a fix at the gate); above, it is rejected and the step
  updates from dead reckoning alone. Both are counted (``n_downweighted``,
  ``n_rejected``, the steps in ``rejected_steps``);
  ``fix_status`` says what became of the last fix (Bar-Shalom, Li and
  Kirubarajan 2001, sections 5.4 and 11.2; Huber 1964).
* **Re-acquisition.** After :data:`REACQUIRE_AFTER` rejections in a row the filter, not the
  fixes, is taken to be lost (a start far off, a wrong heading, a long drift): the position
  variances are raised to the innovation's square (their cross-covariances dropped) and the
  fix is accepted, counted in ``n_reacquired``; the first re-acquisition warns, with the step
  (fixes that jumped together, into another datum or a street's multipath, also re-acquire).
* **Stale fixes.** A fix that repeats the last different one to the bit after the car drove
  farther than the fix's sigma is a receiver re-sending its last solution: not used or tested
  (``n_stale``, ``fix_status == "stale"``, one warning). A run of them taken for fixes would fail
  the gate, then re-acquire the filter onto a position left behind (a 10 s run at 23 m/s: an
  outage that started there ended 200 m off).
* **Calibration only where it is observable.** The odometer scale, heading bias and gyro
  rate bias learn from a fix only when it was accepted as it is, the car is moving
  (``motion == "moving"``, at least ``low_speed``: the gyro heading is the track's, the
  scale multiplies a real speed; pulling away or creeping they differ by tens of
  degrees, and standing they say nothing). Otherwise they are Schmidt
  "consider" states (zero gain, their uncertainty still counted). A calibration state that
  leaves :data:`CALIBRATION_SIGMAS` prior standard deviations of its prior mean (the grade's
  specification) is held at that bound, with a warning naming the step.
* **A gyro's scale factor error.** With a model that has the state (``GPSDRModel(gyro_scale=True)``,
  a grade with ``gyro_scale_sd`` above 0), every measured turn ``d`` adds ``k d`` to the heading bias,
  ``k`` the gyro's scale factor error (a MEMS gyro's sensitivity is good to a few per cent: 3 % turns a
  90 degree corner into 92.7): a linear map of the state and its covariance at each sample. The fixes
  teach ``k`` as they teach the other calibration states, and an outage's turns are then corrected.
  A model with a rate-bias state and without this one monitors it instead: a generalized likelihood
  ratio test of a scale error on the accepted fixes' innovations (``gyro_scale_estimate``,
  ``gyro_scale_z``) warns once, with the step and the estimate, when the fixes show one
  (:data:`SCALE_ERROR_Z`, :data:`SCALE_ERROR_MIN`), and the filter then adds the state from that
  estimate (``scale_on_detection``, on by default; ``gyro_scale_added`` the step).
* **Fixes stamped late.** A fix stamped at a DR sample's time may be the position of some time before:
  a receiver's latency, or the offset between the clocks that stamped the fixes (a phone) and the DR
  samples (a car's logger). It places every fix behind the car by its speed times the latency, and the
  filter follows them there (on the 1 Hz analog a second of it took the outage ends from 1.63 / 6.28 to
  8.68 / 32.45 m). A known latency is a setting of the drive reader (``gps_latency``). An unknown one
  is tested for with the scale error, in one generalized likelihood ratio test (``latency_estimate``,
  ``latency_z``; :data:`LATENCY_Z`, :data:`LATENCY_MIN`): the two are estimated jointly, with the
  calibration states' errors as nuisance parameters, so that neither is read as the other, nor a
  calibration a bad start left off as either. When it fires the filter adds a latency state, the fix
  modelled as ``p - v tau`` (``latency_on_detection``, on by default; ``latency_added`` the step).
  A log known to have two clocks can have the state from the start (a grade's ``gps_latency_sd``),
  so that the outages before the monitor would fire are corrected too; without a latency it costs.
* **A speed stamped late.** A speed sample may be the car's speed some time before its stamp (a CAN
  bus's latency, or the car logger's clock against the phone's that stamped the heading and the fixes):
  the distance then lags every change of speed. The monitor tests for it too, jointly with the errors
  above but kept apart from them (both latencies move the car along its track, and tested jointly they
  hide each other early), and warns with the step and the estimate, naming the reader's
  ``odometer_latency``, the remedy (``odometer_latency_estimate``, ``odometer_latency_z``).
* **Zero angular rate at standstills.** A car does not turn while it stands, so the gyro
  heading's drift over a stop is the gyro's rate bias. When a stop of at least
  :data:`ZERO_RATE_MIN_SAMPLES` samples ends, the filter fits the slope of the measured heading
  over it (least squares) and updates the rate-bias state with it, the slope's variance taken
  from the grade's heading noise (white) and angle random walk, or the fit's own standard error
  when the headings scatter more than the grade says, or the walk the stop's own headings show
  when it is past four times the grade's (:func:`stop_heading_walk`: a gyro noisier than its grade,
  whose stops the fit's standard error, taking a walk for white, made look several times more
  precise than they were): the zero angular rate update of inertial
  navigation (Groves, *Principles of GNSS, Inertial, and Multisensor Integrated Navigation
  Systems*, 2nd ed., 2013, on zero updates). The slope is tested against the state first (its NIS, chi-square
  with 1 degree of freedom, against the 99.9 % point :data:`ZERO_RATE_GATE`; a car that crept
  round a corner below ``standstill_speed``, or a heading that jumped, is rejected and counted).
  A rejected stop whose heading turned faster than any gyro's bias (:data:`MAX_STOP_RATE_DEG_S`, beyond
  its slope's noise) is a car that moved while its speed read 0 (creeping below a wheel-speed sensor's
  cutoff, turning in a car park) or a heading that jumped: it is counted (``n_zero_rate_turned``), warned at the first, and kept
  out of the re-acquisition below (three turning crawls in a row agree with each other, and were once
  taken for a gyro bias of 4 deg/s: a drive's outages ended 1 km off).
  With ``hold_heading_at_stops``, a stop the gate rejects that did not turn (its drift under
  :data:`MAX_STOP_RATE_DEG_S`) and that the crawl test did not find creeping gives its drift beyond the rate-bias
  state to the heading bias, since the car did not turn while it stood, and teaches the rate bias nothing
  (``n_zero_rate_drift_taken``, the first warned): for a gyro whose bias differs while the engine idles. Off by
  default: where the state is wrong and the stop right, the heading so mended hides the state's error from the
  fixes (stop 74, the parameter's numbers).
  A heading that does not change at all over a stop is held by its source (a fused or
  GPS-course heading), not measured by a gyro, and is not used (``n_zero_rate_held``).
  A heading that steps during a stop (a fused orientation re-aligning to a compass or to GPS) is
  no drift: fitted as one, a step reads as a rate bias of 1.5 times the step over the stop.
  :func:`stop_heading_step` tests the stop's headings for one step, past both their own scatter
  and the grade's heading noise; when there is one, the slope is fitted on either side of it, the
  heading bias takes the step (its variance the step's), the stop is counted
  (``n_zero_rate_stepped``), and the first is warned with its step and size.
  When :data:`ZERO_RATE_REACQUIRE_AFTER` stops (:data:`ZERO_RATE_REACQUIRE_OUTSIDE` where they
  measure a bias outside the grade's bound; up to :data:`ZERO_RATE_WINDOW` kept, cleared only by a
  followed stop that contradicts them) are ones the state could not follow
  (rejected by the gate, or used but held at the calibration bound), their slopes agree
  with each other (their spread about their weighted mean passes chi-square with ``N - 1``
  degrees of freedom at 99.9 %) and together they fail the state's gate (their weighted mean,
  with its variance, against the state: short stops held at the bound measure little), the
  state, not the stops, is taken to be wrong (the gyro's
  bias changed, or it is outside the grade): its variance is raised by the squared difference
  (its cross-covariances dropped), it updates with the stops' weighted mean, and the filter
  warns with the step (``n_zero_rate_reacquired``), as the fixes re-acquire the position. The
  gyro has then measured itself outside what the grade's prior says, so the calibration bounds
  of the rate bias and of the heading bias it drives restart from there (their spread kept): a
  gyro outside its grade is followed, with a warning, instead of held at the bound for ever.
  The warning of a rate bias outside the grade (and of the rate-bias state held at its bound)
  names the remedy, the gyro's own specification (``gyro_bias_deg_s`` in a grade of one's own,
  ``filterwnn study dr --gyro-bias``) with the value measured: until the stops have told it, the
  outages end far off (docs/study-outputs/dr/zero-rate/RUN.md).
  A stop the gate rejects while the fixes taught the state (:attr:`GPSDRFilter.rate_bias_fix_share`, the share of
  its information the fixes gave, at least :data:`FIX_TAUGHT_SHARE`), measuring a drift inside the
  grade's bias, is told once (``fix_taught_step``): fixes whose errors are correlated teach the rate
  bias a drift of their own before their correlation is measured, and a fused heading (an
  orientation's yaw) or a calibrated gyro drifts less than the grade lets them teach; the warning
  names the residual bias to give (the stop's drift and two of its sigmas, rounded up). It only tells:
  the gate's verdict and the state are as without it.
  Counted in ``n_zero_rate`` and ``n_zero_rate_rejected``; only a model with a rate-bias state
  (``GPSDRModel(rate_bias=True)``, the phone grade) has it, and ``zero_rate_update=False``
  switches it off. It needs no GPS: the rate bias is learnt at every stop, from the sensor that
  has it, instead of from GPS fixes whose correlated errors look like a heading drift.
* **Fast correlated fixes** (thinning off by default; ``min_fix_interval=MIN_FIX_INTERVAL``
  switches it on). At 5 or 10 Hz a receiver's fixes can share a street's multipath, and a filter
  that takes each for independent follows their errors into the outage. With
  ``min_fix_interval`` set, a fix that comes sooner than that after the last fix used is not
  used (``n_thinned``, ``fix_status == "thinned"``, one warning); fixes at that rate or slower,
  with their jitter, are all used. Off by default because fixes whose errors are independent
  at 5 Hz lose by it (twice the error at the outage ends). The filter warns, once, with the
  step, when fixes come faster than one a second and their measured correlation
  (``gps_correlation``, over a full window) says they carry less than one independent fix a
  second, and names the remedy.
* **Correlated fixes.** A receiver's errors are correlated from fix to fix (multipath that
  lasts a street, a phone's own smoothing), and a filter that takes them for independent
  learns them as calibration: the rate bias and the heading bias follow a drifting error,
  and the outage integrates it. The whitened innovations ``u = L^{-1} y`` (``S = L L^T``)
  of a consistent filter are white; the filter estimates their integrated autocorrelation
  time over the fixes of the last :data:`WHITENESS_WINDOW` seconds (60 fixes at 1 Hz, 300 at 5 Hz;
  fixes it did not accept, and gaps, break the pairs),
  ``gps_correlation = 1 + 2 sum_m rho_m``, summing the lag-``m`` autocorrelations while each
  is significant (above two standard errors, ``2 / sqrt(2 n_m)``; Geyer 1992's initial
  sequence; Mehra 1970's whiteness test of the innovations): the number of fixes that carry
  the information of one independent fix. The heading bias and the gyro rate bias then take
  ``1 / gps_correlation`` of their Kalman gain from a fix (the covariance updated for that
  gain, as the Schmidt update is); position, velocity and the odometer scale take the full
  gain. (A miscalibrated filter's innovations are correlated too: with the scale
  de-weighted as well, a drive whose filter starts with a wrong heading kept a 3 % scale
  error for minutes.) White innovations leave it at 1: no change. The same holds for the two
  de-weighted states: while the consistency monitor below finds the heading bias or the rate
  bias off (``calibration_error_z``), they take the correlation of the innovations less what the
  monitor's errors explain instead, when smaller, so that the correlation their own error makes
  does not keep it (``n_calibration_error``).
  ``correlated_fixes="inflate"`` instead tests each fix as one fix (its NIS against the gate,
  with its reported covariance ``R``: its marginal distribution) and uses it as
  ``1 / gps_correlation`` of one, in every state (its update takes ``gps_correlation * R``:
  the variance inflation that counts correlated measurements by their effective number).
  On the city analogs it lowers the medians at the outage ends but not every maximum, and
  correlated innovations can come from the model as well as from the fixes: on a recorded
  survey-grade drive it trusted good fixes less. Off by default
  (``docs/study-outputs/dr/inflation/RUN.md``).
* **The fixes' covariance scale** (off by default; ``scale_window=SCALE_WINDOW`` switches it
  on). A receiver that reports a sigma half its true one gives innovations
  ``y_i ~ N(0, P_i + lam R_i)`` with ``lam = 4``. Over the last :data:`SCALE_WINDOW` fixes used
  (accepted or down-weighted, each clipped at the gate; rejected ones never enter) the filter
  takes the maximum-likelihood ``lam`` (:func:`gps_scale_mle`) and scales the next fix's
  reported covariance by it, ``gps_scale``, when it is above 1 and the window's
  likelihood-ratio statistic against ``lam = 1``, over ``gps_correlation``, exceeds
  :data:`SCALE_TEST` (the one-sided 0.1 % point); otherwise 1. Honest fixes keep their
  sigma bit for bit; fixes whose innovations are smaller than reported (a filter that follows
  their correlated errors, as in an urban canyon) too. From innovations alone a wrong ``Q`` and a
  wrong ``R`` look alike (Mehra 1972): on a recorded drive the model's own errors were taken for
  the fixes', and the scale ran away (see ``scale_window``), hence off by default. A scale past
  :data:`SCALE_WARN` (9: a sigma 3x optimistic) warns once, with the step.
* **A fix that reports far better than those before it** (``gps_sigma_floor``, on by default): its reported
  sigma is taken no smaller than :data:`SIGMA_FLOOR` (a quarter) of the lower of the medians of the last
  :data:`FLOOR_FIXES` and :data:`FLOOR_WINDOW` reported sigmas, so that a receiver's placeholder accuracy, which
  the gate cannot tell, does not move the calibration (``n_floored``, one warning); once the consistency
  monitor names such fixes (``floor_on_detection``), every fix's sigma is floored at the median of the last
  :data:`FLOOR_WINDOW` reported, so that runs of them do not pass either.
* **A heading that steps while the car moves** (``heading_jump_z``; a phone's fused orientation
  re-aligning to its compass, a logger's heading to GPS). The consistency monitor's nuisance
  parameters are the calibration's errors when it began listening, so a step later is none of them,
  and the correlation the step's drift gives the innovations cuts the heading bias's gain: the fixes
  teach it for minutes. The filter tests a step in the heading bias at each of the last
  :data:`HEADING_JUMP_WINDOW` s of onsets (one every :data:`HEADING_JUMP_SPACING` s; Willsky and
  Jones's generalized likelihood ratio, jointly with the monitor's hypotheses, the fixes counted at
  the correlation of their residuals so far); past :data:`HEADING_JUMP_Z` the heading bias's variance
  is widened by the step and the fixes teach it again (``n_heading_jumps``, one warning).
* **A heading or an odometer noisier than its grade** (``dr_noise_window``, on by default): a heading from a
  compass or a phone's orientation, or a speed in coarse steps, is noisier than the grade's white noise, and a
  filter that trusts it follows the noise (the plainest drive, 1 degree of heading noise under the survey grade's
  0.2 with its 3 m fixes, ended its three outages 2.36 / 2.90 / 1.51 m off, medians of ten seeds, against 0.52 /
  2.11 / 1.17 m for a grade that fits; estimated, 1.42 / 2.81 / 1.26 m; nothing else tells). Over each window of
  :data:`DR_NOISE_WINDOW` moving samples the heading's and the odometer's normalised innovations squared are
  compared with chi-square(1): past :data:`DR_NOISE_RAISE` times its median, that noise is raised to what they
  show (a covariance matching, never below the grade's), with a warning naming the step and the value to give
  (``heading_noise_raised``, ``odometer_noise_raised``; :attr:`GPSDRFilter.heading_noise`,
  :attr:`GPSDRFilter.odometer_noise`). On the analogs and onavdata's drives nothing is raised: the filter is the one
  without it, bit for bit (``docs/gps_dr.md``, "A heading noisier than its grade").
* **Numerical safety.** After every update ``P`` is symmetrised and checked by Cholesky; one
  that is not positive definite is repaired (symmetrised, eigenvalues floored at 1e-12 of the
  largest), counted in ``n_repairs``, with a warning naming the step.
* **Consistency monitor.** The mean NIS over the last :data:`NIS_WINDOW` fixes it used is compared
  with the 99.9 % point of its chi-square distribution; above it, a warning names the step
  and the remedy (the fixes' reported accuracy is optimistic, or the grade too good; with a rate-bias
  state, or a gyro bias that moved faster than the grade's bias instability allows; with a 6-state model, first
  the odometer scale and heading bias it lacks, which a speed or heading off by a little makes inconsistent:
  ``GPSDRModel(augmented=True)``). Where the fixes carried
  their own sigma, between :data:`HDOP_LOWEST` m and :data:`HDOP_GRADE` of the grade's, and their innovations
  are at least :data:`HDOP_FACTOR` times it, it names an HDOP read as metres (a ``gps_sigma`` column holding
  NMEA's dilution of precision) and the ``gps_hdop`` column that reads it. Below :data:`NIS_FAR_BELOW` it
  warns once (``nis_low_step``) that the fixes' sigma, or the grade's, is far larger than their errors (a
  ``gps_sigma`` in millimetres, centimetres or a variance): the filter then all but ignores them.

>>> import numpy as np
>>> from filterwnn.navigation.dead_reckoning import GPSDRModel
>>> from filterwnn.navigation.scenarios import Scenario, simulate_scenario
>>> sc = Scenario(name="from rest", duration=40.0, speed=0.0, heading=60.0,
...               speed_changes=((5.0, 15.0, 12.0),), gps_rate=1.0, outages=((30.0, 40.0),))
>>> run = simulate_scenario(sc, rng=0)
>>> f = GPSDRFilter(GPSDRModel(augmented=True), kind="ekf", x0=np.r_[run.x0, 1.0, 0.0])
>>> est = f.batch_filter(run.z_dr, run.gps_list())
>>> est.shape
(400, 8)
>>> bool(np.hypot(*(est[-1, [0, 3]] - run.x_true[-1, [0, 3]])) < 5.0)
True
"""

from __future__ import annotations

import warnings
from collections import deque
from statistics import NormalDist

import numpy as np
from filterpy.kalman import ExtendedKalmanFilter

from .._linalg import insert_state, repair_pd
from .._warnings import folded_warnings
from ..metrics import integrated_autocorrelation
from .._validation import as_state, check_choice, check_covariance, check_finite, check_positive, check_positive_int, check_scale
from ._plausibility import MAX_DRIFT_DEG_S, SIGMA_UNITS_REMEDY
from .dead_reckoning import (HEADING_ROUNDING, GPSDRModel, _rate_walk_instability, dr_residual, gps_H, gps_hx,
                             wrap_angle)
from ..kalman.presets import make_points
from ..models import from_model
from ..kalman.unscented import UnscentedKalmanFilter

__all__ = ["GPSDRFilter", "STANDSTILL_SPEED", "LOW_SPEED", "KINDS", "GATE", "REJECT_GATE", "REACQUIRE_AFTER",
           "NIS_WINDOW", "CALIBRATION_SIGMAS", "ZERO_RATE_GATE", "ZERO_RATE_MIN_SAMPLES",
           "ZERO_RATE_REACQUIRE_AFTER", "ZERO_RATE_REACQUIRE_OUTSIDE", "ZERO_RATE_WINDOW", "FIX_TAUGHT_SHARE",
           "WALK_PAST_GRADE",
           "WALK_MIN_SAMPLES", "WALK_BIAS", "STOP_REOPEN", "STOP_REOPEN_M", "REOPEN_PIECES", "TILT_SCALE",
           "MAX_STOP_RATE_DEG_S", "WHITENESS_WINDOW", "FIX_GAPS", "MIN_FIX_INTERVAL",
           "CORRELATED_FIXES", "SCALE_WINDOW", "SCALE_TEST", "SCALE_WARN", "HDOP_FACTOR", "HDOP_LOWEST", "HDOP_GRADE",
           "NIS_FAR_BELOW", "FEW_FIXES_MEDIAN", "FEW_FIXES", "SCALE_ERROR_Z", "SCALE_ERROR_MIN", "SCALE_END_Z",
           "DETECTED_SCALE_SD",
           "LATENCY_Z", "LATENCY_MIN", "LATENCY_END_Z", "DETECTED_LATENCY_SD", "ODOMETER_LATENCY_Z", "ODOMETER_LATENCY_MIN",
           "HEADING_BIAS", "RATE", "GYRO_SCALE", "gps_scale_mle", "gps_scale_loglik", "stop_heading_slope",
           "stop_heading_step", "stop_heading_walk", "STOP_STEP_ALPHA", "STOP_STEP_MIN_SIDE", "STOP_STEP_WITHIN",
           "STOP_STEP_TURN_Z", "CALIBRATION_ERROR_Z",
           "HEADING_JUMP_Z", "HEADING_JUMP_SPACING", "HEADING_JUMP_WINDOW", "HEADING_LINEAR_LIMIT",
           "REVERSING_ALPHA", "REVERSING_FIXES", "REVERSING_OFFSET_ALPHA", "CRAWL_ALPHA", "CRAWL_JUMP_ALPHA",
           "CRAWL_MIN_FIXES", "FAR_BETTER", "SIGMA_FLOOR", "FLOOR_FIXES", "FLOOR_WINDOW",
           "DR_NOISE_WINDOW", "DR_NOISE_RAISE", "DR_NOISE_MIN_WINDOW"]

#: Default standstill threshold (m/s) on the odometer speed: 0.05 m/s = 0.11 mph, four
#: times the creep of a standing car's CAN speed (0.001-0.03 mph).
STANDSTILL_SPEED = 0.05
#: The calibration states' rows: the heading bias, the gyro rate bias and the gyro scale factor error
#: (after the odometer scale, row 6; each where the model has it).
HEADING_BIAS, RATE, GYRO_SCALE = 7, 8, 9
#: The scale-error monitor's gate (a filter without the gyro scale state): the generalized likelihood
#: ratio's z-score of a scale factor error from the accepted fixes' innovations (divided by the square
#: root of ``gps_correlation``), past which it warns; 6.1 is chi-square(1)'s 1 - 1e-9 point's root
#: (the monitor looks at every fix, so its false alarms must be rarer than one fix's).
SCALE_ERROR_Z = 6.1
#: ... and the estimated error must be at least this (a fraction): smaller ones cost less than the state.
SCALE_ERROR_MIN = 0.005
#: The gate of the scale factor error on the monitor's z-score when the drive ends (:meth:`GPSDRFilter.end_of_drive`),
#: as :data:`LATENCY_END_Z`: past it, 2 of the 242 drives at hand without a scale error the monitor had not told ended
#: (3.29: 4), and 5 of the 7 with one, 1-2 %, that it had not told; the rerun with the scale state from the start
#: lowered the median at the outage ends on those five (``docs/study-outputs/dr/log-faults/scale_at_end_remedy.txt``).
SCALE_END_Z = 4.0
#: The specification of a scale factor error the monitor found (``scale_on_detection``): a MEMS gyro's
#: sensitivity tolerance of +-3 % read as three sigmas; the calibration bound of the added state.
DETECTED_SCALE_SD = 0.01
#: A scale error found below minus this (a fraction) is named as a gyro axis tilted off the vertical: past a MEMS
#: gyro's +-3 % sensitivity tolerance with a margin, and of the sign a tilt gives (cos(tilt) - 1; 0.05 is 18 degrees).
TILT_SCALE = 0.05
#: The latency monitor's gate: the generalized likelihood ratio's z-score of the fixes' latency against
#: the DR samples (their clocks' offset, or a receiver's latency), as :data:`SCALE_ERROR_Z`.
LATENCY_Z = 6.1
#: ... and the estimated latency must be at least this (s): at 20 m/s, 0.1 s places a fix 2 m behind.
LATENCY_MIN = 0.1
#: The gate of the fixes' latency on the monitor's z-score when the drive ends (:meth:`GPSDRFilter.end_of_drive`): one
#: test, not one at every fix, takes a lower gate than :data:`LATENCY_Z`. The z-score's tails are heavier than a
#: normal's (correlated fixes, a calibration settling), so not chi-square(1)'s 99.9 % point (3.29, past which 9 of
#: the 230 drives at hand without a latency the monitor had not told ended, with an estimate of 0.1 s or more) but
#: 4.0 (1 of them, at 0.11 s; of the 17 drives with fixes 0.2-1 s late whose latency the monitor had not told by
#: the end, 7; ``docs/study-outputs/dr/log-faults/end_of_drive_*.txt``). A phone + OBD-II log whose app stamps each
#: fix when it arrives (0.15-0.40 s late) ended at 4.4 (stop 62).
LATENCY_END_Z = 4.0
#: The specification of a latency the monitor found (``latency_on_detection``), s: the clocks of a
#: phone and of a car's logger, each set from the network or GPS, agree to about a second; the
#: calibration bound of the added state is three of it. The first-order model ``p - v tau`` holds
#: while ``tau`` is short against the car's turns (a few seconds).
DETECTED_LATENCY_SD = 1.0
#: The gate of the speed's latency against the heading and the fixes (a CAN bus's, or the offset between
#: the car logger's clock and the phone's): its z-score, as :data:`LATENCY_Z`. It only warns: the remedy is
#: the drive reader's ``odometer_latency``.
ODOMETER_LATENCY_Z = 6.1
#: ... and the estimated speed's latency must be at least this (s), as :data:`LATENCY_MIN`.
ODOMETER_LATENCY_MIN = 0.1
#: The monitor's errors, each with its gate on the z-score and its least estimate.
_TESTED = {"gyro_scale": (SCALE_ERROR_Z, SCALE_ERROR_MIN), "latency": (LATENCY_Z, LATENCY_MIN),
           "odometer_latency": (ODOMETER_LATENCY_Z, ODOMETER_LATENCY_MIN)}
#: The errors tested once more when a drive ends (:meth:`GPSDRFilter.end_of_drive`), each with its gate there (their
#: least estimates are :data:`_TESTED`'s).
_TESTED_AT_END = {"latency": LATENCY_END_Z, "gyro_scale": SCALE_END_Z}
#: Default low-speed threshold (m/s): below it the DR sample enters as a velocity vector.
LOW_SPEED = 5.0
#: Filter kinds: filterpy's EKF, the unscented filter with Merwe points, with spherical-simplex points.
KINDS = ("ekf", "ukf", "sukf")
#: Default integrity gate on a fix's NIS: the 99.9 % point of chi-square with 2 degrees of
#: freedom, ``-2 ln(0.001) = 13.82`` (a consistent filter rejects one good fix in 1000).
GATE = float(-2.0 * np.log(1e-3))
#: Default rejection gate: fixes above :data:`GATE` and up to it are down-weighted, above it rejected.
REJECT_GATE = float(-2.0 * np.log(1e-9))
#: Rejected fixes in a row after which the filter re-acquires (takes itself to be lost).
REACQUIRE_AFTER = 5
#: Fixes over which the consistency monitor averages the NIS.
NIS_WINDOW = 30
#: A calibration state is held within this many prior (specification) sigmas of its prior mean.
CALIBRATION_SIGMAS = 3.0
#: The fixes' measured correlation (``gps_correlation``) from which the inconsistency warning says that its window's
#: bound is a white window's, and gives the mean NIS over the drive beside it (:meth:`GPSDRFilter._correlated_words`).
CORRELATED_WORDS = 3.0
#: The zero angular rate update's gate on the NIS of a stop's heading slope: the 99.9 % point of
#: chi-square with 1 degree of freedom (the fixes' gate's level).
ZERO_RATE_GATE = NormalDist().inv_cdf(1.0 - 0.5e-3) ** 2  # = chi2.ppf(0.999, 1) = 10.83
#: Standstill samples a stop needs before its heading slope updates the rate bias (the slope's own
#: variance, from the grade, weighs a short stop down further).
ZERO_RATE_MIN_SAMPLES = 3
#: The level of the test for a step in a stop's headings (:func:`stop_heading_step`), per stop, corrected for
#: the places tried: a stop whose headings step is fitted with an offset on each side of the step.
STOP_STEP_ALPHA = 1e-3
#: Samples a step in a stop's headings must leave on each side of it to be tested (so ``2 * 3 + 2 = 8`` samples
#: at least).
STOP_STEP_MIN_SIDE = 3
#: A step in a stop's headings is a jump: the headings' means over this many seconds on either side of it (less the
#: stop's drift) must not differ by less than half the step (:data:`STOP_STEP_TURN_Z`). A car that turns while its
#: speed reads 0 (creeping below a speed sensor's cutoff, a car park) turns a few degrees a second, and a long turn
#: fits a step too: a 103 degree crawl round a corner taken for a heading step turned the heading bias by that and
#: an outage ended 745 m off.
STOP_STEP_WITHIN = 1.0
#: ... by more than this many standard deviations of that difference (the grade's heading noise over the samples
#: averaged), so that a small step at 1 Hz, one sample either side, is not lost to the noise: 3.29, the 99.9 %
#: two-sided point, as the stop's turned check.
STOP_STEP_TURN_Z = 3.29
#: The fastest heading drift (deg/s) a stop's slope is taken to measure: a gyro's rate bias (a MEMS gyro's
#: turn-on bias reaches about 0.7 deg/s; the drive reader's plausibility check allows this 1 deg/s). A stop
#: whose heading turned faster, by more than its slope's noise allows (the gate's 3.29 sigma), is a car
#: that moved while its speed read 0, not a gyro: it says nothing about the rate bias.
MAX_STOP_RATE_DEG_S = MAX_DRIFT_DEG_S
#: Stops in a row that the rate-bias state could not follow (rejected by the gate, or held at the
#: calibration bound) after which, when their slopes agree with each other, the state re-acquires from
#: them: the GPS fixes' :data:`REACQUIRE_AFTER`, for a sensor sampled at each stop, not each second (a
#: gyro whose bias jumps would otherwise be rejected at every stop).
ZERO_RATE_REACQUIRE_AFTER = 3
#: ... and after this many when the stops' weighted mean lies outside the grade's calibration bound (three prior
#: sigmas): a gyro outside its grade, which the grade's prior holds far off until then (stop 59: two new users'
#: gyros outside the phone grade, 0.2 and 0.4 deg/s, were followed only from a drive's third stop, their first
#: outages ending 170-222 m off). Inside the bound the third is still waited for: a fused heading that re-aligns
#: by a little at each stop makes each stop's slope a little off, and two such agree more often than three.
ZERO_RATE_REACQUIRE_OUTSIDE = 2
#: The most stops the state could not follow that the re-acquisition keeps (a deque): from
#: :data:`ZERO_RATE_REACQUIRE_AFTER` on, they re-acquire once they agree and together fail the state's gate, so that
#: short stops held at the bound, each measuring little, add up (the phone analog with a 0.3 deg/s gyro, 72 stops
#: of a few seconds: stop 59); the oldest leave first, and where they disagree. A stop the state followed clears
#: them only where it contradicts them (its slope fails the gate against their weighted mean): a crawl's second
#: at 0 m/s, whose slope says nothing, no longer does.
ZERO_RATE_WINDOW = 6
#: The share of the gyro rate bias's information (the inverse of its variance) that the GPS fixes gave
#: (:attr:`GPSDRFilter.rate_bias_fix_share`) from which a stop that the state's gate rejects, measuring a drift
#: inside the grade's, is told as contradicting a rate bias the fixes taught: 0.9, the grade's prior and the
#: stops together giving under a tenth of what the state knows.
FIX_TAUGHT_SHARE = 0.9
#: A stop's headings walk more than the grade says (a gyro noisier than its grade, :func:`stop_heading_walk`) when
#: their variogram shows a walk past this many times the grade's angle random walk density (an angle random walk
#: twice the grade's): an estimate from lags of a quarter of the stop has a few degrees of freedom, and passes
#: 4 times its true value about once in 300 stops.
WALK_PAST_GRADE = 4.0
#: The fewest samples a stop needs for its headings' walk to be measured (:func:`stop_heading_walk`): with fewer,
#: an eighth of the stop is too short a lag to tell a walk from white noise, and a step from either.
WALK_MIN_SAMPLES = 30
#: The share of a walk's variogram that an eighth of the stop keeps once the drift fitted to the same headings is
#: taken out (:func:`stop_heading_walk` divides by it): 0.58-0.67 on simulated walks of 100-2000 samples.
WALK_BIAS = 0.6
#: The ``stop_reopen`` (s) to use for a standstill whose speed does not read 0 (``GPSDRFilter(stop_reopen=
#: STOP_REOPEN)``; off by default): a stop that ends and starts again within it, the car having moved at most
#: :data:`STOP_REOPEN_M` between, is one stop to the zero angular rate update.
STOP_REOPEN = 2.0
#: The most the car may move (m) between two stops that ``stop_reopen`` makes one.
STOP_REOPEN_M = 0.5
#: The pieces a standstill is cut into (each ended by a speed over ``standstill_speed`` within :data:`STOP_REOPEN`
#: of the last, the car having moved at most :data:`STOP_REOPEN_M`) at which, when the rate-bias state cannot follow
#: them, the filter takes each standstill whole from then on (``reopen_on_detection``): 3, the fewest that are a
#: pattern rather than one wobble of the speed.
REOPEN_PIECES = 3
#: Seconds of fixes over which the whiteness of the GPS innovations is estimated (lags up to a quarter
#: of it): 60 fixes at 1 Hz, 300 at 5 Hz. In seconds, not fixes, because the errors it looks for last
#: a time (a street's multipath, a phone's own smoothing), whatever the receiver's rate: a window of
#: 60 fixes at 5 Hz would span 12 s, under a 15 s correlation, and miss most of it.
WHITENESS_WINDOW = 60.0
#: The last gaps between fixes from which the filter takes the fixes' interval: their shortest sizes the
#: whiteness window (:attr:`GPSDRFilter.whiteness_fixes`) and their median paces ``min_fix_interval``'s
#: thinning. Recent, so that one early or doubled fix, or a receiver that changes its rate, is followed
#: within that many fixes (over the whole drive, one doubled fix at 1 Hz made every later gap look like a
#: break, and the correlation read 1 from there on).
FIX_GAPS = 10
#: The ``min_fix_interval`` to use for fast fixes whose errors are correlated (``GPSDRFilter(
#: min_fix_interval=MIN_FIX_INTERVAL)``; off by default): the filter then uses one fix a second and thins
#: the others (``n_thinned``). A street's multipath lasts seconds, and a filter that takes 5 Hz fixes for
#: independent follows their errors: on the city analog with 5 Hz fixes the worst 8-state kind met the
#: targets on 8 of 10 seeds with one fix a second against 5 of 10 with every fix, and on held-out seeds 6
#: against 5; with white 5 m errors at 5 Hz thinning doubled the errors at the outage ends
#: (``docs/study-outputs/dr/fix-rate/RUN.md``). One second is the rate every drive the filter was built
#: and checked on delivers its fixes at.
MIN_FIX_INTERVAL = 1.0
#: The ways :class:`GPSDRFilter` can count correlated fixes (its ``correlated_fixes``).
CORRELATED_FIXES = ("calibration", "inflate")
#: The consistency monitor's z-score of the heading bias's or the gyro rate bias's error (one of its nuisance
#: parameters, with the sandwich variance that counts correlated fixes at their worth) past which that state
#: is taken to be off, and its gain is cut by the fixes' own correlation instead of the innovations' (their
#: correlation is then partly the calibration's own error): the 99.9 % point of a normal, two-sided. Unlike the
#: monitor's gates (:data:`SCALE_ERROR_Z`), which add a state once, it holds only while the error does.
CALIBRATION_ERROR_Z = NormalDist().inv_cdf(1.0 - 0.5e-3)  # = 3.29
#: The heading-jump detector's gate (:class:`GPSDRFilter`'s ``heading_jump_z``): the measured heading's offset
#: stepping while the car moves (a phone's fused orientation re-aligning to its compass, a logger's heading to
#: GPS) after the consistency monitor began listening, whose nuisance parameters are the calibration's errors
#: then and miss a step later. Willsky and Jones's (1976) generalized likelihood ratio over a window of onset
#: times: a step in the heading bias from each of the last :data:`HEADING_JUMP_WINDOW` s, one every
#: :data:`HEADING_JUMP_SPACING` s, each tested jointly with the monitor's errors (a gyro scale error or a
#: latency is not read as a step), its z-score counting the fixes at the mean correlation of their residuals so
#: far (the consistency monitor's measure; after a step the innovations are correlated by
#: the step's own drift, and counting them at that would hide it). As :data:`SCALE_ERROR_Z`: the monitor looks
#: at every fix, and here at a dozen onsets each.
HEADING_JUMP_Z = 6.1
#: Seconds between the onsets the heading-jump detector tries, and the seconds back it tries them.
HEADING_JUMP_SPACING, HEADING_JUMP_WINDOW = 5.0, 60.0
#: The largest difference (rad, 30 degrees) between a moving car's measured heading (less the heading bias)
#: and the filter's own, ``atan2(v_e, v_n)``, that the ``[heading, distance]`` update takes as it is. It is
#: linearised about the filter's heading: far from it the update moves the velocity along the tangent, past
#: the measured heading and longer than the odometer's speed, and the acceleration state takes the
#: difference, so the next step is farther off (one 90 degree heading glitch at 3 m/s as a 1 Hz car pulled
#: away took an 8-state EKF's velocity to 51 m/s against an odometer of 15; an outage then ended 815 m off).
#: Past it the sample enters as the measured velocity vector, linear in the velocity. On clean drives
#: (the analogs, the sample, onavdata's) the difference stays under 13 degrees.
HEADING_LINEAR_LIMIT = float(np.radians(30.0))
#: The reversing test's error probability: a moving car on an unsigned speed is taken to move against the
#: direction taken (reversing after a stop, or forward again) when the log-likelihood ratio of its fixes, the other
#: way against this, divided by the fixes' correlation, passes ``log(1 / REVERSING_ALPHA)`` (Wald's sequential
#: test; below minus that the direction holds and the test starts again). As the fixes' reject gate, 1e-9.
REVERSING_ALPHA = 1e-9
#: ... and the last this many fixes (one a second) must each be past the gate from the direction taken and inside it
#: from the other, with at least one fix before them since the test started: one fix that jumped (a street's
#: multipath) is not a car that turned round, and the offset path needs a fix before a jump to tell it.
REVERSING_FIXES = 2
#: ... and the offset path (the same two paths, each with an unknown constant offset of its fixes: a street's
#: multipath that lasts) must favour the other way too, its likelihood ratio past ``log(1 / REVERSING_OFFSET_ALPHA)``:
#: a guard, not a test of its own (a constant offset takes the start's error and the fixes' bias both, so that it
#: learns the direction only from how the fixes move, and a 12 m reversal with 4 m fixes gives it about 7).
REVERSING_OFFSET_ALPHA = 0.01
#: The crawl test's error probability: a car whose speed reads 0 is taken to creep along its heading (under a speed
#: sensor's cutoff) when the generalized likelihood ratio of its fixes, a constant offset and a crawl at the speed
#: that fits them best against the offset alone, divided by the fixes' correlation when the car stopped, passes
#: ``log(1 / CRAWL_ALPHA)``. As the reversing test's, 1e-9.
CRAWL_ALPHA = 1e-9
#: ... and the crawl must fit the fixes better than an offset that jumps once (at whichever fix fits best: a
#: street's multipath that comes or goes while the car stands), its likelihood ratio past
#: ``log(1 / CRAWL_JUMP_ALPHA)``: a guard, as :data:`REVERSING_OFFSET_ALPHA` (without it fixes 20 m ahead for
#: 10 s of a stop read as a crawl, and the filter went 18 m off, 5 m without the test).
CRAWL_JUMP_ALPHA = 0.01
#: ... after at least this many fixes (one a second) since the test started.
CRAWL_MIN_FIXES = 3
#: Fixes over which the scale of the fixes' reported covariance is estimated when the estimate is
#: switched on (``GPSDRFilter(scale_window=SCALE_WINDOW)``; off by default): the consistency monitor's
#: window. With honest fixes the estimate's relative standard error is about ``1 / sqrt(SCALE_WINDOW)``
#: = 0.18 (a mean of 30 chi-square(2) / 2 draws), small enough to tell a 2x optimistic sigma (scale 4)
#: from an honest one (1) by more than ten of them, and one fix, clipped at the gate, moves it by at
#: most ``(GATE - 2) / (2 SCALE_WINDOW)`` = 0.2, for ``SCALE_WINDOW`` fixes only.
SCALE_WINDOW = NIS_WINDOW
#: The scale departs from 1 only when the window's likelihood-ratio statistic for it against 1,
#: divided by ``GPSDRFilter.gps_correlation`` (correlated fixes carry that much less evidence),
#: exceeds this: the one-sided 0.1 % point of chi-square with 1 degree of freedom (the consistency
#: monitor's level), so honest fixes keep their reported sigma in 999 windows of 1000.
SCALE_TEST = NormalDist().inv_cdf(1.0 - 1e-3) ** 2  # = chi2.ppf(1 - 2e-3, 1) = 9.55
#: A covariance scale above this (the fixes' reported sigma more than 3x optimistic) warns, once, with
#: the step: a receiver that reports its accuracy is rarely that far off, and a scale that climbs past
#: it is more likely the model's own errors taken for the fixes' (a wrong ``Q`` looks like a wrong
#: ``R`` from the innovations, Mehra 1972). On onavdata's 2021-04-27C drive the 6-state EKF's scale
#: ran to 467 that way.
SCALE_WARN = 9.0
#: The consistency monitor's warning names an HDOP read as a sigma (m) when every fix of its window carried its
#: own sigma, their median is at least :data:`HDOP_LOWEST` m and at most :data:`HDOP_GRADE` times the grade's GPS
#: sigma (an HDOP is 0.5 or more, about 1: a phone's 5 m fix then claims 1 m; an RTK fix's centimetres are no
#: HDOP), and their innovations are at least this many
#: times it (``sqrt(mean NIS / 2)``). The analogs' honest and optimistic sigmas stay below it; fixes 1 s late
#: in a 6-state EKF do not (2.3), but they claim the grade's accuracy.
HDOP_FACTOR = 2.0
#: A window's mean NIS under which the consistency monitor warns, once, that the fixes' sigma (their own, or the
#: grade's) is far larger than their errors: 2/100, a sigma 10 times their error. The filter then all but ignores
#: them: the 1 Hz analog's fixes given in millimetres (windows of 2e-6) ended its outages 81.62 / 143.69 m off
#: (1.63 / 6.28 in metres), the city analog's given as variances (its first window 0.009) 18.56 / 45.00 (16.43 /
#: 26.30). A phone's 95 % radius given as a sigma (2.45 times: about 0.33) and the variances of the 1 Hz analog's
#: 3-5 m fixes (windows down to 0.072, and no worse outages) are not warned of.
NIS_FAR_BELOW = 0.02
#: The medians of chi-square with one and two degrees of freedom (``2 ln 2``).
_CHI2_1_MEDIAN = 0.454936423119572
_CHI2_2_MEDIAN = 2.0 * np.log(2.0)
#: Where the consistency monitor's window is past its bound but its median NIS is at most this (1.5 times a
#: consistent filter's, chi-square(2)'s median 1.39; the median of 30 consistent fixes passes it in about one window
#: in twenty) and its :data:`FEW_FIXES` largest carry at least half of its sum, the warning says that a few
#: fixes carry the excess (a fault at their steps: fixes that jumped, a reversal or a slide not yet found), not an
#: accuracy optimistic throughout, which would raise the median too. A user's drive reversing out of a parking
#: space warned at step 309 with a mean NIS of 3.65 and a median of 1.31, 71 % of it in the five fixes before the
#: reversal was found (stop 69).
FEW_FIXES_MEDIAN = 1.5 * _CHI2_2_MEDIAN
#: See :data:`FEW_FIXES_MEDIAN`.
FEW_FIXES = 5
#: See :data:`HDOP_FACTOR`: the least median sigma (m) taken for an HDOP...
HDOP_LOWEST = 0.4
#: ... and the most, over the grade's GPS sigma.
HDOP_GRADE = 0.5
#: The consistency monitor's warning names fixes that report an accuracy far better than they have (a
#: receiver's placeholder sigma, a jump in its reported accuracy) when every fix of its window carried its own
#: sigma, some under this fraction of the window's median, and with those at the median, and again with the
#: grade's sigma for every fix, the window's mean NIS would be inside its bound (stop 54: the 1 Hz analog with
#: 5 % of its fixes reporting 0.3 m; its own 3-5 m are never under 0.6 of their median, the phone analog's 5-8 m
#: never under 0.75, and a gyro outside its grade, or every fix reporting half its error, is told without it).
FAR_BETTER = 0.5
#: ``GPSDRFilter(gps_sigma_floor=...)``'s default: a fix's reported sigma is taken no smaller than this fraction of
#: the lower of two medians of the fixes' reported sigmas, this one's among them: of the last :data:`FLOOR_FIXES`
#: (3: of the two before it, when it is the smallest) and of the last :data:`FLOOR_WINDOW`. A receiver's accuracy
#: estimate (its HDOP times its range error) moves with a satellite or two between fixes: over the drives we have,
#: the reports drop to 0.29 of that on onavdata's phones (the stoplight drive; the hill drive's 1.7 -> 0.65 m for
#: good, 0.39), 0.26 on the analogs (the city's, drawn per fix; seeds 0-49) and 0.29 on the random drives (seeds
#: 0-129 of both protocols), and none is floored; the value was chosen below them, not on a score. Fixes that
#: claim ten times their accuracy (0.3 m for 3-5 m) moved the calibration states and took the 1 Hz analog's EKF-8
#: to 46.53 m at an outage's end (7.15 m floored so); claiming 1 m, 7.40 m (6.28 m honest):
#: ``docs/study-outputs/dr/sensor-faults/RUN.md``, stop 55.
SIGMA_FLOOR = 0.25
#: See :data:`SIGMA_FLOOR`: the short median, so that a fix reporting far better than both fixes before it is
#: floored, and a receiver whose accuracy improves for good (a better solution, leaving a city's canyon) is
#: believed from its second such fix...
FLOOR_FIXES = 3
#: ... and the long one, so that placeholders (a sigma of 9999 m where the receiver has no fix; two in a row would
#: make the short median theirs) do not raise the floor of the honest fixes after them.
FLOOR_WINDOW = 30
#: Moving samples (those whose DR measurement enters as ``[heading, distance]``) over which :class:`GPSDRFilter`
#: measures how the heading's and the odometer's innovations compare with their predicted variances, and so
#: estimates the DR noise online (``dr_noise_window``; 0: the grade's noise as given). 10 s at 10 Hz.
DR_NOISE_WINDOW = 100
#: A window's median normalised innovation squared of the heading (or the odometer), over chi-square(1)'s median,
#: past which the filter takes the sensor to be noisier than its grade says: 2, a white noise 1.4 times the grade's
#: sigma. For a consistent filter that median is 1 within about 0.25 over 100 samples (independent ones; 4
#: standard deviations to 2). On the simulated analogs (turns, stops, biases) and onavdata's drives it stays under
#: 0.4; on the shipped sample, whose heading has 1 degree of white noise, the survey grade's 0.2 degrees read 15
#: (``docs/gps_dr.md``, "A heading noisier than its grade").
DR_NOISE_RAISE = 2.0
#: The fewest moving samples a ``dr_noise_window`` other than 0 may have (a median of fewer says little).
DR_NOISE_MIN_WINDOW = 10
#: Per DR sensor (heading, odometer): its name, the model's noise attribute, the unit a grade gives it in and the
#: conversion to it from the filter's (rad, m), the grade's key and the command's option, and what makes such a
#: sensor noisier than its grade. The filter's warning and the drive table's line (``studies.dr``) read it.
_DR_SENSORS = (
    ("heading", "sigma_heading", "deg", np.degrees, "heading_noise_deg", "--heading-noise",
     "A heading from a compass or from a phone's orientation is noisier than a gyro's; a gyro whose bias moves "
     "faster than its grade allows reads so too"),
    ("odometer", "sigma_odometer", "m a sample", float, "odometer_noise_m", "--odometer-noise",
     "A speed in coarse steps (OBD's 1 km/h) or a slow log's sample is noisier than a wheel count"),
)


def _median(values):
    """``numpy.median`` of a few floats, to the bit, in a fraction of its time (it runs at every fix)."""
    s = sorted(values)
    h = len(s) // 2
    return s[h] if len(s) % 2 else 0.5 * (s[h - 1] + s[h])


#: A speed (m/s) past what a car drives, over which a DR sample's distance is told as a speed given in its place
#: (:meth:`GPSDRFilter._check_input`).
MAX_DR_SPEED = 100.0


def _no_fix(z_gps):
    """Whether ``z_gps`` says there is no fix: ``None``, or two NaN (a row of an array of fixes)."""
    if z_gps is None:
        return True
    try:
        z = np.asarray(z_gps, dtype=float)
    except (TypeError, ValueError):
        return False  # refused, with its name, where the fix is read
    return z.shape == (2,) and bool(np.all(np.isnan(z)))


def _half_turn(z_dr):
    """A DR sample ``[heading, distance]`` with its heading turned by half a turn (a reversing car's direction of
    travel)."""
    return np.array([float(wrap_angle(z_dr[0] + np.pi)), float(z_dr[1])])


def _shear(M, b, k, d):
    """``T M T^T`` for ``T = I + d e_b e_k^T`` (row ``k`` added ``d`` times to row ``b``), symmetrised: the
    covariance map of a measured turn ``d`` for a scale factor error in row ``k`` of a heading bias in
    row ``b``."""
    M = M.copy()
    M[b, :] += d * M[k, :]
    M[:, b] += d * M[:, k]
    return 0.5 * (M + M.T)


def _two_digits_up(value):
    """``value`` (> 0) rounded up to two significant digits (0.0206 -> 0.021): a setting a warning names."""
    e = np.floor(np.log10(value)) - 1 if value > 0 else 0
    return float(np.ceil(value / 10**e) * 10**e)


def _gyro_bias_remedy(rate, least=""):
    """The remedy a warning names for a gyro rate bias of ``rate`` (rad/s) outside the grade: the gyro's
    own specification, ``gyro_bias_deg_s`` of that size (rounded up to two digits), from the start."""
    v = _two_digits_up(float(np.degrees(rate)))
    return (f"For a gyro whose turn-on bias is {least + ' ' if least else ''}{v:.2g} deg/s, more than the grade's, "
            f"give the gyro's own specification and the filter starts from it: a grade of your own with "
            f"gyro_bias_deg_s={v:.2g} (filterwnn study dr --gyro-bias {v:.2g}); else the outages before the stops "
            "have told the bias end far off")


def _instability_remedy(model):
    """The remedy a warning names for a gyro whose rate bias moved faster than ``model``'s random walk lets the
    state follow (a phone warming up): its bias instability, in the grade (the model's value given back)."""
    return ("give the gyro's bias instability, gyro_bias_instability_deg_h in the grade (--gyro-bias-instability "
            f"DEG_H; the model's {_rate_walk_instability(model.q_rate):.3g})")


def _walk_variance(t, w, q_arw):
    """The variance an angle random walk of density ``q_arw`` (rad^2/s) adds to an estimate ``w . h`` from
    headings ``h`` at times ``t``: ``q_arw sum_k (t_k - t_{k-1}) (sum_{i >= k} w_i)^2``, the walk's increment
    between samples ``k - 1`` and ``k`` reaching every heading from ``k`` on."""
    tail = np.cumsum(w[::-1])[::-1][1:]  # sum_{i >= k} w_i, k = 1 .. n-1
    return q_arw * float(np.diff(t) @ tail**2)


def stop_heading_slope(t, heading, sigma_heading, q_arw, step_at=None):
    """The gyro heading's drift rate over a stop and its variance: ``(slope (rad/s), variance)``.

    A car does not turn while it stands, so this is the gyro's rate bias (the zero angular rate
    update of :class:`GPSDRFilter`). The slope is the least-squares line through the headings
    ``heading (n,)`` (rad, unwrapped here) at times ``t (n,)`` (s), ``n >= 2``. Its variance is what
    the sensor's specification gives: white heading noise of standard deviation ``sigma_heading``
    (rad) on each sample, ``sigma_heading^2 sum a_i^2`` with ``a_i = (t_i - tbar) / sum (t_j -
    tbar)^2`` the slope's weights, plus an angle random walk of density ``q_arw`` (rad^2/s) whose
    increments between samples enter as ``q_arw sum_k (t_k - t_{k-1}) (sum_{i >= k} a_i)^2``; or,
    with ``n > 2`` samples, the fit's own standard error ``sum a_i^2 RSS / (n - 2)`` when that is
    larger (headings that scatter more than the specification says).

    ``step_at`` (an index, see :func:`stop_heading_step`): the heading stepped before that sample (a fused
    heading re-aligned); the line then has an offset of its own on each side, and the slope comes from the
    headings' change within each side (the weights ``a_i`` the times less their side's mean, over their sum of
    squares; the fit's standard error then has ``n - 3`` degrees of freedom).

    >>> import numpy as np
    >>> t = np.arange(0.0, 10.0, 0.1)
    >>> slope, var = stop_heading_slope(t, 0.3 + 1e-3 * t, 1e-3, 0.0)
    >>> round(slope, 9), bool(np.sqrt(var) < 1e-4)
    (0.001, True)
    >>> h = 0.3 + 1e-3 * t + 0.01 * (t >= 4.0)  # a 0.57 deg step at 4 s
    >>> round(stop_heading_slope(t, h, 1e-3, 0.0, step_at=40)[0], 9)
    0.001
    """
    t = np.asarray(t, dtype=float)
    h = np.asarray(heading, dtype=float)
    if t.ndim != 1 or t.shape != h.shape or len(t) < 2:
        raise ValueError(f"t and heading must be 1-D of the same length >= 2, got {t.shape} and {h.shape}")
    h = np.unwrap(h)
    n = len(t)
    if step_at is None:
        t = t - t.mean()
        fitted = 2
    else:
        k = int(step_at)
        if not 2 <= k <= n - 2:
            raise ValueError(f"step_at must leave at least 2 samples on each side of the step, got {step_at} of {n}")
        t = np.concatenate([t[:k] - t[:k].mean(), t[k:] - t[k:].mean()])
        fitted = 3
    tt = float(t @ t)
    if not tt > 0:
        raise ValueError("t must not be constant")
    a = t / tt
    slope = float(a @ h)
    # (with a step, the times are centred on each side, so their difference across the step is no interval;
    # the weights after the step sum to 0, so it counts for nothing)
    var = sigma_heading**2 * float(a @ a) + _walk_variance(t, a, q_arw)
    if n > fitted:
        if step_at is None:
            res = h - h.mean() - slope * t
        else:
            res = np.concatenate([h[:k] - h[:k].mean(), h[k:] - h[k:].mean()]) - slope * t
        var = max(var, float(res @ res) / (n - fitted) * float(a @ a))
    return slope, var


def _best_step(t, h, min_side):
    """The step that reduces the residual sum of squares of the line through the headings ``h`` (rad, unwrapped)
    at times ``t`` the most, leaving ``min_side`` samples on each side: ``(k, size, u, w, r, tc, tt, n_k)``, with
    ``u`` the step's regressor less its projection on ``(1, t)``, ``w = u / (u . u)`` the weights of its estimate
    ``w . h``, ``r`` the line's residuals, ``tc`` the centred times, ``tt = tc . tc`` and ``n_k`` the steps tried;
    None when there is none. ValueError for constant times."""
    n = len(t)
    tc = t - t.mean()
    tt = float(tc @ tc)
    if not tt > 0:
        raise ValueError("t must not be constant")
    r = h - h.mean() - (tc @ h) / tt * tc  # the line's residuals
    # u_k = [i >= k] less its projection on (1, t): r . u_k = sum_{i >= k} r_i (r is orthogonal to both),
    # u_k . u_k = m - m^2 / n - (sum_{i >= k} tc_i)^2 / tt with m = n - k samples after the step
    ks = np.arange(min_side, n - min_side + 1)
    if not len(ks):
        return None
    rsum = np.cumsum(r[::-1])[::-1][ks]
    tsum = np.cumsum(tc[::-1])[::-1][ks]
    m = (n - ks).astype(float)
    uu = m - m * m / n - tsum * tsum / tt
    ok = uu > 1e-12 * n
    drss = np.where(ok, rsum * rsum / np.where(ok, uu, 1.0), 0.0)
    j = int(np.argmax(drss))
    if not drss[j] > 0:
        return None
    k, size = int(ks[j]), float(rsum[j] / uu[j])
    # the step's estimate is w . h: u_k, less its projection on (1, t), over its sum of squares
    u = (np.arange(n) >= k) - m[j] / n - tsum[j] / tt * tc
    return k, size, u, u / uu[j], r, tc, tt, len(ks)


def stop_heading_walk(t, heading, q_arw, min_side=STOP_STEP_MIN_SIDE):
    """The angle random walk density (rad^2/s) a stop's headings show, when past :data:`WALK_PAST_GRADE` times
    the grade's ``q_arw``; else ``q_arw``.

    A heading integrated from a gyro noisier than its grade walks more than the grade says: a walk is no line,
    and with the grade's walk the stop's slope (:func:`stop_heading_slope`) reads as measured several times
    more precisely than it is (its own standard error takes the residuals for white), stops that agree read as
    disagreeing, and the walk reads as a heading step (:func:`stop_heading_step`). The walk is read from the
    variogram of the headings ``heading (n,)`` (rad) at times ``t (n,)`` (s), ``v(L)``, the variance of their
    change over ``L`` samples (about its mean, the drift), which grows as ``q L dt`` for a walk of density ``q``
    and stays flat for white noise: ``q`` is ``v(L) - v(2)`` over ``(L - 2) dt`` for ``L`` an eighth of the
    stop (short correlations, such as a log's averaging or a trapezoidal integral leaves, cancel), divided by
    :data:`WALK_BIAS` (the drift fitted to the same walk takes a share of it), and is taken only when
    ``v(L)`` is past twice ``v(2)`` (the walk, not white noise, makes the change over ``L``). The changes
    across the best single step (:func:`stop_heading_step`'s) are left out, so that a fused heading's real step
    is not read as a walk. Stops of fewer than :data:`WALK_MIN_SAMPLES` samples give ``q_arw``.

    >>> import numpy as np
    >>> t = np.arange(0.0, 25.0, 0.05)
    >>> q = np.deg2rad(0.1) ** 2  # a walk of 0.1 deg / sqrt(s), 20 times the phone grade's 0.3 deg / sqrt(h)
    >>> h = np.sqrt(q * 0.05) * np.cumsum(np.random.default_rng(0).standard_normal(len(t)))
    >>> grade = np.deg2rad(0.3 / 60) ** 2
    >>> bool(0.5 < stop_heading_walk(t, h, grade) / q < 2), bool(stop_heading_walk(t, 0.0 * h, grade) == grade)
    (True, True)
    """
    t = np.asarray(t, dtype=float)
    h = np.unwrap(np.asarray(heading, dtype=float))
    n = len(t)
    if t.ndim != 1 or t.shape != h.shape:
        raise ValueError(f"t and heading must be 1-D of the same length, got {t.shape} and {h.shape}")
    if n < max(WALK_MIN_SAMPLES, 2 * min_side + 2):
        return q_arw
    best = _best_step(t, h, min_side)
    k = None if best is None else best[0]

    def variogram(lag):
        d = h[lag:] - h[:-lag]
        if k is not None:  # none across the step
            i = np.arange(n - lag)
            d = d[(i + lag < k) | (i >= k)]
        d = d - d.mean()  # less the drift
        return float(d @ d) / len(d)

    short, long = 2, max(4, n // 8)
    v_short, v_long = variogram(short), variogram(long)
    if not v_long > 2.0 * v_short:
        return q_arw
    q = (v_long - v_short) / ((long - short) * float(np.mean(np.diff(t)))) / WALK_BIAS
    return q if q > WALK_PAST_GRADE * q_arw else q_arw


def stop_heading_step(t, heading, sigma_heading=None, q_arw=0.0, alpha=STOP_STEP_ALPHA, min_side=STOP_STEP_MIN_SIDE):
    """The most likely step in a stop's headings, and whether it is one: ``(index or None, size, sd, p)``.

    A gyro's heading drifts steadily while the car stands; a fused heading (a phone's orientation, a
    logger that re-aligns to a compass or to GPS) may also jump. A jump fitted as a drift reads as a rate
    bias of 1.5 times the jump over the stop's length (a 0.5 degree jump in a 15 s stop: 0.05 deg/s), which
    the rate-bias state then integrates through the next outage. The step: the one before sample ``k``
    that reduces the residual sum of squares of the line through the headings ``heading (n,)`` (rad) at
    times ``t (n,)`` (s) the most, ``k`` leaving ``min_side`` samples on each side. Its size over its
    standard deviation is tested twice, each with a Bonferroni correction over the ``k`` tried:

    * against the headings' own scatter about the line with the step (Student's t, ``n - 3`` degrees of
      freedom), widened by their lag-1 correlation ``rho`` as an AR(1)'s long-run variance,
      ``(1 + rho) / (1 - rho)``: headings smoother than white (a low-passed fused heading) wander like steps;
    * with the grade's white heading noise ``sigma_heading`` (rad), against the scatter the specification
      allows: a heading noisier than its grade makes no step.

    Both add the grade's angle random walk ``q_arw`` (rad^2/s), ``q_arw sum_k dt_k (sum_{i >= k} w_i)^2``
    for the step estimate's weights ``w``: a random walk is no line, and would otherwise step everywhere.
    A step when the larger p-value, ``p``, is below ``alpha``, unless the headings' means over
    :data:`STOP_STEP_WITHIN` s before and after it, less the line's slope, differ by less than half the step and by
    :data:`STOP_STEP_TURN_Z` of their difference's standard deviation less than the step (``sigma_heading``'s, else
    the residuals' scatter, with the walk): a step is a jump, and a car turning while its speed reads 0 turns a
    few degrees a second, which fits a step too. Returns the index of the first sample after the step (None when
    there is none, or fewer than ``2 min_side + 2`` samples), the step's size (rad), its standard deviation (rad:
    the larger of the two; 0 without a step), and ``p`` (below ``alpha`` with None: a turn, not a jump).

    >>> import numpy as np
    >>> t = np.arange(0.0, 15.0, 0.1)
    >>> noise = np.deg2rad(0.3) * np.random.default_rng(0).standard_normal(len(t))
    >>> k, size, sd, p = stop_heading_step(t, 1.0 + noise + np.deg2rad(1.0) * (t >= 6.0))
    >>> int(k), round(float(np.degrees(size)), 1), round(float(np.degrees(sd)), 2), bool(p < 1e-6)
    (60, 1.0, 0.1, True)
    >>> stop_heading_step(t, 1.0 + noise)[0] is None
    True
    >>> walk = np.deg2rad(0.3 / 60) * np.sqrt(0.1) * np.cumsum(np.random.default_rng(1).standard_normal(len(t)))
    >>> stop_heading_step(t, 1.0 + walk, q_arw=np.deg2rad(0.3 / 60) ** 2)[0] is None  # its own walk: no step
    True
    """
    from scipy.stats import t as t_dist

    t = np.asarray(t, dtype=float)
    h = np.unwrap(np.asarray(heading, dtype=float))
    n = len(t)
    if t.ndim != 1 or t.shape != h.shape:
        raise ValueError(f"t and heading must be 1-D of the same length, got {t.shape} and {h.shape}")
    if n < 2 * min_side + 2:
        return None, 0.0, 0.0, 1.0
    best = _best_step(t, h, min_side)
    if best is None:
        return None, 0.0, 0.0, 1.0
    k, size, u, w, r, tc, tt, n_k = best
    walk = _walk_variance(t, w, q_arw)
    # the residuals' own variance, with their lag-1 correlation rho as an AR(1)'s long-run factor
    e = r - size * u
    ee = float(e @ e)
    rho = min(max(float(e[1:] @ e[:-1]) / ee, 0.0), 0.99) if ee > 0 else 0.0
    var = ee / (n - 3) * float(w @ w) * (1.0 + rho) / (1.0 - rho) + walk
    p = min(1.0, 2.0 * float(t_dist.sf(abs(size) / np.sqrt(var), n - 3)) * n_k) if var > 0 else 0.0
    if sigma_heading is not None:
        spec = sigma_heading**2 * float(w @ w) + walk
        if spec > 0:
            p = max(p, min(1.0, 2.0 * NormalDist().cdf(-abs(size) / np.sqrt(spec)) * n_k))
        var = max(var, spec)
    if p >= alpha:
        return None, 0.0, 0.0, p
    d = h - float(tc @ (h - size * (np.arange(n) >= k))) / tt * tc  # less the drift about the step
    before = d[:k][t[:k] >= t[k] - STOP_STEP_WITHIN - 1e-9]
    after = d[k:][t[k:] <= t[k - 1] + STOP_STEP_WITHIN + 1e-9]
    near = float(after.mean() - before.mean()) * np.sign(size)  # the step's share near it
    # the noise of that difference: the grade's white noise (or the residuals' scatter) and the walk over the span
    white = ee / (n - 3) if sigma_heading is None else sigma_heading**2
    span = t[k] - t[k - 1] + 2.0 * STOP_STEP_WITHIN
    sd_near = np.sqrt(white * (1.0 / len(before) + 1.0 / len(after)) + q_arw * span)
    if near < abs(size) / 2.0 and abs(size) - near > STOP_STEP_TURN_Z * sd_near:
        return None, 0.0, 0.0, p
    return k, size, float(np.sqrt(var)), p


def gps_scale_mle(y, P, R, scale=1.0, iterations=20, rtol=1e-6):
    """Maximum-likelihood scale ``lam`` of the fixes' covariance from their innovations.

    Each innovation is taken as ``y_i ~ N(0, P_i + lam R_i)`` (``P_i`` the predicted position
    covariance, ``R_i`` the fix's reported covariance); the log-likelihood's stationary point
    ``sum_i tr(S_i^{-1} R_i) = sum_i y_i^T S_i^{-1} R_i S_i^{-1} y_i`` (``S_i = P_i + lam R_i``) is
    found by the multiplicative fixed point ``lam <- lam * sum(y^T S^-1 R S^-1 y) / sum(tr(S^-1 R))``
    (an EM step for a variance component; Mehra 1972's covariance matching is its one-step form).
    With ``P_i = 0`` it is the mean NIS of the fixes against ``R_i`` over their dimension.

    Parameters
    ----------
    y : array-like of shape (n, d)
        Innovations.
    P, R : array-like of shape (n, d, d)
        Their predicted-state and reported-fix covariances.
    scale : float
        Start of the iteration (the last estimate).
    iterations : int
        At most this many fixed-point steps.
    rtol : float
        Stop when a step changes ``lam`` by less than this fraction.

    Returns
    -------
    float
        ``lam`` (> 0; small when the innovations are smaller than ``P`` alone predicts).

    >>> import numpy as np
    >>> y = np.array([[2.0, 0.0], [0.0, -2.0]])
    >>> R = np.broadcast_to(np.eye(2), (2, 2, 2))
    >>> round(gps_scale_mle(y, np.zeros((2, 2, 2)), R), 6)  # mean of y^T R^-1 y / d: (4 + 4) / 2 / 2
    2.0
    """
    y, P, R = (np.asarray(a, dtype=float) for a in (y, P, R))
    lam = float(scale)
    for _ in range(iterations):
        S = P + lam * R
        Sy = np.linalg.solve(S, y[..., None])[..., 0]
        num = float(np.einsum("ni,nij,nj->", Sy, R, Sy))
        den = float(np.trace(np.linalg.solve(S, R), axis1=1, axis2=2).sum())
        new = max(lam * num / den, 1e-6)
        done = abs(new - lam) <= rtol * lam
        lam = new
        if done:
            break
    return lam


def gps_scale_loglik(y, P, R, scale):
    """Log-likelihood of the scale ``lam`` of the fixes' covariance: ``-1/2 sum_i (ln det S_i +
    y_i^T S_i^{-1} y_i)``, ``S_i = P_i + lam R_i``, up to a constant (shapes as :func:`gps_scale_mle`)."""
    S = np.asarray(P, dtype=float) + float(scale) * np.asarray(R, dtype=float)
    y = np.asarray(y, dtype=float)
    quad = np.einsum("ni,ni->", y, np.linalg.solve(S, y[..., None])[..., 0])
    return float(-0.5 * (np.linalg.slogdet(S)[1].sum() + quad))


class GPSDRFilter:
    """A GPS/DR filter that handles starts, stops, outages and per-fix GPS accuracy.

    filterpy-style: ``predict()``, ``update(z_dr, z_gps=None, gps_sigma=None)``,
    ``batch_filter``, and the state ``x``/``P`` (those of the filter it wraps, ``kf``).

    A filterpy user's loop is ``predict()`` then ``update()`` at each DR sample, and :meth:`end_of_drive` when
    the drive ends (``batch_filter`` does all three and returns the posterior means, their covariances through a
    filterpy ``Saver`` passed as ``saver``; there is no smoother). ``z_dr`` is ``[heading (rad), distance since the last sample (m)]``: a speed is times ``dt``. ``R``
    and ``Q`` are read, not set: the filter builds ``R`` at each update from each fix's ``gps_sigma`` (or the
    model's ``sigma_gps``) and the model's DR noise, and ``Q`` comes from the model, so a different noise is a
    different :class:`~filterwnn.navigation.dead_reckoning.GPSDRModel` (or grade); setting ``kf.R`` on the
    wrapped filter is overwritten at the next update. The wrapped filterpy filter ``kf`` has ``x_prior``,
    ``x_post``, ``y``, ``S``, ``K`` and ``log_likelihood`` of its last update, a DR sample's alone (2 rows) or with
    its fix (4 rows), so a sum of ``log_likelihood`` mixes the two. ``copy.copy`` is a deep copy;
    ``copy.deepcopy`` and ``pickle`` work.

    Parameters
    ----------
    model : GPSDRModel
        The model: 6 states, 8 with ``augmented=True`` (an odometer scale and a heading bias), 9 with a gyro
        rate-bias state (:meth:`~filterwnn.navigation.dead_reckoning.GPSDRModel.from_grade`'s ``"phone"``), and a
        gyro scale or a fixes' latency state where the grade or the monitor adds one. The 6-state model has no
        heading bias: a heading whose zero is a few degrees off, which the 8-state models learn from the fixes,
        stays in its dead reckoning.
    kind : {"ekf", "ukf", "sukf"}
        filterpy's ``ExtendedKalmanFilter`` with the analytic Jacobian, or the unscented
        filter with Merwe points (``alpha=0.5, beta=2, kappa=0``) or spherical-simplex
        points with the same settings (on the same sphere, with the same centre weights;
        the presets ``"gpsdr-ukf"`` and ``"gpsdr-sukf"``, :mod:`filterwnn.kalman.presets`);
        every kind wraps the heading residual and averages headings
        circularly.
    x0, P0 : array-like, optional
        Prior, default ``model.x0``, ``model.P0``.
    standstill_speed : float
        Odometer speed (m/s) below which the update is a zero-velocity update
        (default :data:`STANDSTILL_SPEED`; 0 switches it off).
    low_speed : float
        Odometer speed (m/s) below which the DR sample enters as a velocity vector
        (default :data:`LOW_SPEED`; 0 switches it off).
    hold_without_gps : bool
        Without a GPS fix, the DR update changes only the velocity and the acceleration:
        the position and the calibration states (odometer scale, heading bias, rate bias)
        are Schmidt-Kalman "consider" states (zero gain; their uncertainty still counts).
        None of them is observable from ``[heading, distance]``, and an EKF that lets the
        DR update move them finds false information along the unobservable directions
        (speed against scale, track against heading bias): on the shipped sample drive, 30 s
        outages that start before the calibration has converged ended 58-85 m off with the
        full update against 7-19 m held (the raw dead reckoning: 7-9 m). On by default;
        ``False`` gives the full EKF/UKF update.
    gps_window : int
        When > 0: fixes that carry no accuracy of their own get a GPS noise estimated
        from the last ``gps_window`` GPS innovations (covariance matching,
        ``sigma^2 = mean(y_e^2 + y_n^2)/2 - mean(HPH^T)``, floored at 0.1 m, used once 10
        fixes are in), instead of the model's ``sigma_gps``; the estimate is
        :attr:`gps_sigma_est`. 0 (default): the model's ``sigma_gps``. Measured: it
        recovers a simulated 1 m or 8 m GPS noise within 4 % (model: 3 m), but on the
        onavdata drives (survey grade, no per-fix accuracy) it made the 8-state EKF worse
        (median/max at 30 s outage ends 1.62/17.36 m -> 2.97/19.73 m and 2.43/7.36 m ->
        2.48/42.78 m): the innovations carry the model's own errors too. Prefer the
        receiver's per-fix accuracy.
    points : sigma points, optional
        Override the unscented kinds' points (filterpy protocol). For the model's dimension: when the
        filter adds a state (``scale_on_detection``, ``latency_on_detection``) it takes its kind's preset
        points for the new dimension, with a warning; a model with the state from the start keeps them.
    gate : float
        A fix whose NIS exceeds it is down-weighted (default :data:`GATE`; ``numpy.inf``
        switches the test off).
    reject_gate : float, optional
        A fix whose NIS exceeds it is rejected (default :data:`REJECT_GATE`, or ``gate`` when
        that is larger; ``gate``: no down-weighting).
    reacquire_after : int
        Rejected fixes in a row after which the next one re-acquires (default
        :data:`REACQUIRE_AFTER`).
    nis_window : int
        Fixes averaged by the consistency monitor (default :data:`NIS_WINDOW`).
    whiteness_window : float
        Seconds of fixes over which the innovations' autocorrelation is estimated (default
        :data:`WHITENESS_WINDOW`, 60 s: 60 fixes at 1 Hz, 300 at 5 Hz, :attr:`whiteness_fixes`;
        0 takes every fix for independent). It once counted fixes; at 1 Hz the two are the
        same.
    correlated_fixes : {"calibration", "inflate"}
        How ``gps_correlation`` counts the fixes. ``"calibration"`` (default): the heading bias
        and the gyro rate bias take ``1 / gps_correlation`` of their gain, and the other states take
        each fix as independent (while the consistency monitor finds either of the two off, past
        ``calibration_error_z``, they take the fixes' own correlation instead: see below). ``"inflate"``: each fix is tested with its reported covariance and
        used with ``gps_correlation`` times it, so that correlated fixes count as the independent
        fixes they are worth, in every state. For fixes whose errors last (urban-canyon multipath);
        measured in ``docs/study-outputs/dr/inflation/RUN.md``: on the city analogs it lowers the
        medians at the outage ends (by 4.9 m over ten held-out seeds) but not every maximum, and a
        survey-grade recorded drive's worst outage end grows from 15.21 to 17.47 m (its innovations
        are correlated by the model's own errors, not the fixes').
    calibration_error_z : float or None
        The z-score past which the consistency monitor's estimate of the heading bias's or the gyro rate
        bias's error (since it began listening; its sandwich standard deviation counts correlated fixes at
        their worth) takes that state to be off (default :data:`CALIBRATION_ERROR_Z`, 3.29). A calibration
        that is off makes the innovations correlated by itself (the car drifts sideways fix after fix), and
        cutting its gain by that correlation keeps it off: a phone analog whose heading re-aligned by half a
        degree at each stop ended its outages 38.19 / 74.12 m off, its heading bias 7 degrees from the
        truth with a standard deviation of 1 (``docs/study-outputs/dr/log-faults/RUN.md``, stop 45). While
        the monitor finds it, the two take ``1 / c`` of their gain with ``c`` the correlation of the
        innovations less what the monitor's errors explain (when smaller), counted in
        ``n_calibration_error`` and warned at the first. None: never.
    heading_jump_z : float or None
        The heading-jump detector's gate (default :data:`HEADING_JUMP_Z`, 6.1). A measured heading whose offset
        steps while the car moves (a phone's fused orientation re-aligning to its compass; a step during a stop
        is :func:`stop_heading_step`'s) after the monitor began listening is none of its nuisance parameters,
        and the fixes teach the heading bias slowly (the correlation the step's drift makes cuts its gain): a
        phone analog whose heading stepped 5 degrees at 360 s ended its outages for the next 8 minutes 12-41 m
        off against 1-10 m without the step, and the monitor read the step as a 2.7 % gyro scale error
        (``docs/study-outputs/dr/log-faults/RUN.md``, stop 46). The detector is Willsky and Jones's generalized
        likelihood ratio over a window of onsets (:data:`HEADING_JUMP_WINDOW`, one every
        :data:`HEADING_JUMP_SPACING` s): each a step in the heading bias from then, tested jointly with the
        monitor's hypotheses, the fixes counted at the correlation of their residuals so far (the step's own
        would hide it). Past the gate, with a step of at least the grade's white heading noise and at most the
        heading bias's bound, the heading bias's variance is widened by the step (its cross-covariances
        dropped, its calibration bound widened too) and the fixes teach it again, the state not moved (a false
        step costs less so: ``docs/study-outputs/dr/log-faults/RUN.md``, stop 46); the monitor's hypotheses keep what the fixes told of them
        beyond the step. Counted in ``n_heading_jumps`` (``heading_jumps``), the
        first warned. An outage (a gap in the fixes) starts the onsets again. None: not looked for.
    heading_linear_limit : float or None
        While the car moves, a DR sample whose heading (less the heading bias) is more than this (rad; default
        :data:`HEADING_LINEAR_LIMIT`, 30 degrees) from the filter's own enters as the measured velocity
        vector (``GPSDRModel.measurement_for(velocity=True)``, linear in the velocity) instead of as
        ``[heading, distance]``, whose update is linearised about the filter's heading and overshoots far
        from it. Counted in ``n_heading_far``, the first warned (a heading glitch the drive reader did not
        catch, a heading in another convention, or a filter that lost its velocity). None: never.
    reversing_test : bool
        While the car moves, test the fixes for it moving against the direction taken on an unsigned speed
        (reversing after a stop, which starts forward; forward again): Wald's sequential probability ratio test of
        the fixes against the test's start (the stop, or its last decision) plus, and minus, the dead reckoning's
        displacement since (the start's position covariance, the fix's, and the displacement times the odometer
        scale's and heading bias's uncertainty; each fix counted at the fixes' correlation, at most one a second,
        :data:`MIN_FIX_INTERVAL`, and its normalised innovations clipped at the gate), error probability
        :data:`REVERSING_ALPHA`; and the same two paths each with a constant unknown offset of its fixes (a
        generalized likelihood ratio, the offset least squares), so that fixes displaced for a while (a street's
        multipath) do not read as reversing. The first past
        ``log(1 / REVERSING_ALPHA)``, the second past ``log(1 / REVERSING_OFFSET_ALPHA)`` (a guard), and the last
        :data:`REVERSING_FIXES` fixes each past the gate from the direction taken and inside it from the other,
        after at least one fix since the test started: the car moves the other way from there, until it next
        stands or the test decides again. The position goes to the start less the displacement, velocity and
        acceleration turn, and the samples' headings are turned by half a turn while reversing (as the drive
        reader turns a negative speed's). Either below minus the first bound: the direction holds and the test
        starts again. Counted in ``n_reversing`` and ``n_forward_again`` (``reversing_steps``), the first of each
        warned. Default True; a signed speed never reads as reversing here (the reader turned its heading).
    crawl_test : bool
        While the speed reads 0 (a standstill sample), test the fixes for the car creeping along its heading (a speed
        sensor that reads 0 below a cutoff: a queue): a generalized likelihood ratio of the fixes, one a second at
        most, less the test's start (the filter's position when the car stopped, or at its last decision) as an
        unknown constant offset plus ``v`` times the path the heading (less the heading bias) draws at unit speed
        since, ``v >= 0``, against the offset alone (weighted least squares, each fix's residual from the fit so
        far clipped at the gate, by the fix's covariance and the fit's own), divided by the fixes' correlation when the car stopped, past
        ``log(1 / CRAWL_ALPHA)`` after :data:`CRAWL_MIN_FIXES` fixes; and the crawl must fit better than an offset
        that jumps once, past ``log(1 / CRAWL_JUMP_ALPHA)`` (a guard: multipath that comes while the car stands).
        Then the position moves by the fitted crawl and its covariance along it widens by the move and its
        variance (the fixes place the car), the zero-velocity update holds it there, and the test starts again.
        Counted in ``n_crawl`` (``crawl_steps``, ``crawl_moved``), the first warned. Default True. A creeping car
        that reverses, or crawls in an outage, is not found.
    gps_sigma_floor : float
        A fix's reported sigma (``gps_sigma``) is taken no smaller than this fraction of the lower of the medians
        of the last :data:`FLOOR_FIXES` and the last :data:`FLOOR_WINDOW` fixes' reported sigmas (this one's among
        them; default :data:`SIGMA_FLOOR`, a quarter; 0: as reported). A receiver's accuracy follows its
        satellites' geometry, which moves little between fixes: a fix that reports far better than both fixes
        before it (a placeholder accuracy, a jump in the receiver's estimate) is not trusted beyond a quarter of
        them, while an accuracy that improves for good is believed from its second fix. The gate cannot catch such a fix: its innovation is measured against the filter's
        covariance as well as the fix's, and the fix, used with its tiny covariance, moves the calibration states
        (with 5 % of the 1 Hz analog's fixes claiming 0.3 m the EKF-8's outages ended 2.68 / 46.53 m off; floored,
        2.85 / 7.15 m: ``docs/study-outputs/dr/sensor-faults/RUN.md``, stop 55). Counted in ``n_floored``
        (``floored_steps``), the first warned. Fixes without a reported sigma (the grade's) are not floored.
    floor_on_detection : bool
        When the consistency monitor finds that fixes reporting far better than the others carry its excess (its
        warning names them; see :data:`FAR_BETTER`), take every fix's sigma from then on no smaller than the median
        of the last :data:`FLOOR_WINDOW` reported (``floor_raised``, the step; those fixes counted in
        ``n_floored``): runs of such fixes pass the floor above, and two in a row, one second apart, are as harmful as
        one (our reading: they set a velocity that the heading bias takes; stop 55: the 1 Hz analog with 5 % of its fixes
        claiming 0.3 m in pairs ended an outage 55.66 m off with no floor). Default True; False only warns. Where
        the monitor does not name such fixes, nothing changes.
    dr_noise_window : int
        Moving samples (those whose DR measurement enters as ``[heading, distance]``) over which the heading's and
        the odometer's white noise are estimated from their innovations (default :data:`DR_NOISE_WINDOW`, 100; 0:
        the grade's as given; otherwise at least 10). Where a window's median normalised innovation squared is
        past :data:`DR_NOISE_RAISE` times chi-square(1)'s, the noise's variance is multiplied by it, and each window
        after moves it so, never below the grade's (``dr_noise_scale``); the first raise of each warns with the step
        and the value to give the grade (``heading_noise_deg``, ``odometer_noise_m``). The zero-velocity update's
        noise is not the sensors' and is not scaled. As with any covariance matching, an error the model does not
        have (a gyro bias moving faster than its grade) reads as noise too; the warning names that as well.
    min_fix_interval : float
        Seconds after a fix used before the next is used; fixes that come faster are thinned
        (``n_thinned``, with one warning), and fixes at that rate or slower, with their jitter, are
        all used. Default 0: every fix used. ``MIN_FIX_INTERVAL`` (1 s) is the value for fast
        fixes whose errors are correlated (an urban canyon's at 5 Hz), which a filter that takes each
        for independent follows; the filter warns when it measures such fixes. Not the default
        because fast fixes with independent errors lose by it (measured in
        ``docs/study-outputs/dr/fix-rate/RUN.md``).
    stop_reopen : float
        Seconds within which a stop that ended and starts again, the car having moved at most
        :data:`STOP_REOPEN_M` (0.5 m) between, is the same stop to the zero angular rate update (the rate
        bias's update waits until the car has moved on). Default 0: a stop ends at the first sample whose
        speed reads over ``standstill_speed``. :data:`STOP_REOPEN` (2 s) is the value for a standstill whose
        speed does not read 0 (a GNSS speed; a speed with noise on a creeping car): its stop is otherwise cut
        into stops of a sample or two whose slopes say nothing of the gyro, and the rate bias is not learnt
        (a random drive with such stops ended its outages 26.18 / 77.59 m off, 6.82 / 25.44 m with 2 s; the
        city analogs whose stops creep, seeds 2 and 3, 21.63 / 71.60 -> 18.89 / 56.07 and 15.92 / 39.73 ->
        13.79 / 30.73 m). Not the default: on a plain drive from rest with no gyro bias to find, the whole
        stop's slope only adds its noise (outage ends 3.35 -> 4.61 m median over 20 seeds), and every drive's
        numbers move with it (the update comes up to 2 s later): ``docs/study-outputs/dr/analog-seeds/RUN.md``,
        stop 44. Switched on where it is needed (``reopen_on_detection``).
    reopen_on_detection : bool
        With ``stop_reopen`` 0: when a stop that the rate-bias state could not follow (rejected by the gate, or
        held at its calibration bound) is the :data:`REOPEN_PIECES`-th piece or later of one standstill (each
        piece within :data:`STOP_REOPEN` s and :data:`STOP_REOPEN_M` m of the last), warn with the step and take
        each standstill whole from then on (``stop_reopen`` = :data:`STOP_REOPEN`; ``stops_cut_step`` the
        step). A speed that does not read 0 while the car stands (a GNSS speed given as the speed) cuts each stop
        into pieces too short to measure the gyro's bias, and a bias outside the grade was then held at its bound
        (stop 61: a u-blox log's GNSS speed, EKF-8 outage ends 7.32 / 173.35 -> 4.97 / 21.85 m). Default True;
        False only warns. Of 271 drives at hand (the analogs' seeds 0-9, 220 random drives, the tests' drive from
        rest over 20 seeds, the sample) it fired on one, a drive from rest whose stop reads noise (0.52 -> 0.71 m).
    scale_on_detection : bool
        With a rate-bias state and no scale state: when the scale-error monitor finds a gyro scale
        factor error (see ``gyro_scale_z``), add the state from its estimate (``gyro_scale_added``;
        the model becomes :meth:`~filterwnn.navigation.dead_reckoning.GPSDRModel.with_gyro_scale`'s,
        ``batch_filter`` still returns the first states; an unscented kind takes its kind's preset
        points for the 10 states, with a warning when it was given its own). Default True; False only warns. On drives without such an error the
        monitor did not fire, so the filter is the 9-state one bit for bit.
    latency_on_detection : bool
        With a calibrated model (8 states or more) without a latency state: when the monitor finds the fixes
        late against the DR samples (see ``latency_z``), add the latency state from its estimate
        (``latency_added``; the model becomes :meth:`~filterwnn.navigation.dead_reckoning.GPSDRModel.with_latency`'s,
        the fix ``p - v tau``; ``batch_filter`` still returns the first states). Default True; False only
        warns, naming ``gps_latency`` (the reader's setting for a latency one knows).
    scale_window : int
        Fixes over which the scale of their reported covariance is estimated (``gps_scale``;
        :data:`SCALE_WINDOW` = 30 is the window to use). Default 0: off, every fix's covariance
        as reported. Off by default because it hurt a recorded drive: on onavdata's 2021-04-27C
        drive (survey grade, the receiver's accuracy) the innovations also carry the model's own
        errors (from innovations alone a wrong ``Q`` and a wrong ``R`` look alike: covariance
        matching finds ``R`` only when ``Q`` is right, Mehra 1972), a scale taken for the fixes'
        made the filter trust them less, its innovations grew and the scale with them (a mean of
        5.35 over the fixes for the 8-state EKF, 467 for the 6-state one), and the 30 s outages
        ended at a median of 1.96 m (8-state EKF; 1.65 m off) and 10.82 m (6-state; 1.59 m off).
        On the simulated drives it stayed at 1 and changed almost nothing (``docs/gps_dr.md``,
        "The covariance scale on the analogs and the recorded drives": one 1 Hz analog's SUKF-8 median 2.73 -> 2.84 m).

    zero_rate_update : bool
        At the end of every stop, update the gyro rate bias with the slope of the measured
        heading over the stop (a car does not turn while it stands; see the module docstring).
        On by default; it acts only on a model with a rate-bias state (``rate_bias=True``, the
        phone grade) and with ``standstill_speed > 0``.
    zero_rate_reacquire_after : int
        Stops in a row that the state could not follow (rejected, or held at the calibration bound)
        after which, when their slopes agree, the rate-bias state re-acquires from them (default
        :data:`ZERO_RATE_REACQUIRE_AFTER`; 0: never).
    hold_heading_at_stops : bool
        A stop the zero angular rate gate rejects, not turned and not found creeping, gives its drift beyond the
        rate-bias state to the heading bias (the car does not turn while it stands) and teaches the rate bias
        nothing (``n_zero_rate_drift_taken``, the first warned). For a gyro whose bias differs while the car stands
        (a phone shaken in its holder by the idling engine): a seventh user's drive with 0.15 deg/s more at idle
        through a 4-minute level crossing, EKF-8 6.52 / 93.42 -> 3.25 / 36.10 m (its twin without the vibration
        3.03 / 16.91). Default False: where the stop is right and the state wrong (a rate bias taught by a stop
        whose heading stepped), the heading so mended hides the state's error from the fixes, which correct the rate
        bias through it (random drive 205 of protocol 3: 13.93 / 135.95 -> 64.17 / 168.49 m; stop 74). Nothing
        detects which of the two a rejected stop is.

    Attributes
    ----------
    kf : filter
        The wrapped filterpy-style filter.
    dr_noise_scale : ndarray of shape (2,)
        Factors ``(heading, odometer)`` on the grade's DR noise variances (1: the grade's; see ``dr_noise_window``).
    heading_noise_raised, odometer_noise_raised : int or None
        The steps at which the heading's and the odometer's noise were first found above the grade's (None: not).
    motion : str
        What the last update took the car to do: ``"still"``, ``"slow"`` or ``"moving"``.
    step : int
        Updates so far (the step the warnings name is ``step - 1``, counted from 0).
    fix_status : str
        What became of the last update's fix: ``"none"``, ``"accepted"``,
        ``"down-weighted"``, ``"rejected"``, ``"reacquired"``, ``"thinned"`` (not used: it came
        sooner than ``min_fix_interval`` after the last fix used) or ``"stale"`` (not used: the last
        fix again, to the bit, after the car drove farther than the fix's sigma).
    nis : float or None
        The last fix's normalised innovation squared (before the gate).
    n_fixes, n_downweighted, n_rejected, n_reacquired, n_repairs : int
        Fixes tested, down-weighted, rejected, accepted to re-acquire; covariance repairs.
    n_thinned : int
        Fixes not used (nor tested) because they came sooner than ``min_fix_interval`` after the
        last one used.
    n_stale : int
        Fixes not used (nor tested) because they repeat the last different fix to the bit after the car
        drove farther than their sigma since it: a receiver that re-sends its last solution while it
        has none (one warning, with the step). Taken for fixes, a run of them first fails the gate and
        then re-acquires the filter onto a position left behind.
    n_calibration_error : int
        Fixes whose heading-bias and rate-bias gain took the fixes' own correlation because the consistency
        monitor found one of the two off (``calibration_error_z``; the first warned).
    n_heading_far : int
        DR samples taken as a velocity vector because their heading was farther than ``heading_linear_limit``
        from the filter's (the first warned, with the step).
    n_reversing, n_forward_again, reversing_steps : int, int, list of int
        The times the fixes showed the car reversing, and driving forward again without a stop between
        (``reversing_test``), and the steps of both (the first of each warned).
    n_crawl, crawl_steps, crawl_moved : int, list of int, float
        The times the fixes showed the car creeping while its speed read 0 (``crawl_test``), their steps (the first
        warned), and the distance (m) the position moved at them in all.
    n_heading_jumps, heading_jumps : int, list of tuple
        The steps of the heading the heading-jump detector found while the car moved (``heading_jump_z``), and
        per step ``(step found, onset step, its estimate (rad), z-score)``.
    rejected_steps : list of int
        The steps whose fix was rejected.
    nis_accepted : list of float
        The NIS of every accepted fix (:attr:`nis_mean` is their mean; 2 when consistent).
    nis_warnings : list of int
        The steps at which the consistency monitor warned.
    nis_low_step : int or None
        The step at which the consistency monitor found the fixes' sigma far larger than their errors (a window's
        mean NIS under :data:`NIS_FAR_BELOW`; warned once), None if never.
    n_zero_rate, n_zero_rate_rejected, n_zero_rate_held, n_zero_rate_reacquired, n_zero_rate_turned, n_zero_rate_stepped, n_zero_rate_drift_taken : int
        Stops whose heading slope updated the rate bias; stops whose slope the gate rejected; stops
        over which the heading did not change at all (held by its source, e.g. a fused or GPS-course
        heading, so it says nothing about the gyro: not used); re-acquisitions of the rate-bias state
        from stops it could not follow that agreed with each other; of the rejected stops, those whose
        heading turned faster than :data:`MAX_STOP_RATE_DEG_S` (the car moved while its speed read 0:
        kept out of the re-acquisition too, with a warning at the first); stops whose headings stepped
        (:func:`stop_heading_step`: the heading bias took the step, and the slope was fitted on either side);
        of the rejected stops not turned and not found creeping, those whose drift beyond the rate-bias state the
        heading bias took (the car does not turn while it stands).
    zero_rate_steps : list of tuple
        Per stop tested: ``(step, slope (rad/s), its standard deviation (rad/s), accepted)``.
    fix_taught_step : int or None
        The step of the first stop whose drift the rate-bias state's gate rejected while the state was taught
        by the fixes (:attr:`rate_bias_fix_share` at least :data:`FIX_TAUGHT_SHARE`) and the stop's drift lay
        inside the grade's bias (warned, with the residual bias to give), None if none.
    stops_cut_step : int or None
        The step at which a standstill cut into pieces left the rate-bias state unable to follow one
        (``reopen_on_detection``; warned once), None if never.
    gps_correlation : float
        The integrated autocorrelation time of the accepted fixes' whitened innovations, in
        fixes (1: white); the heading bias and rate bias take ``1 / gps_correlation`` of their gain (with
        ``correlated_fixes="inflate"``: each fix used counts as ``1 / gps_correlation`` of one, in every
        state). :attr:`gps_correlation_mean` is its mean over the drive's fixes.
    gps_scale : float
        The factor (>= 1) on the next fix's reported covariance: the maximum-likelihood scale of the
        last ``scale_window`` fixes' covariance (:func:`gps_scale_mle`), held at 1 when below it;
        1 until the window is full, while the window does not tell it from 1 (its likelihood-ratio
        statistic over ``gps_correlation`` under :data:`SCALE_TEST`), and always 1 with
        ``scale_window=0``.
    gps_scales : list of float
        The factor each tested fix got (:attr:`gps_scale_mean` is their mean); empty with
        ``scale_window=0``.
    gyro_scale_added : int or None
        The step at which the monitor's scale error made the filter add the scale state (None: not).
    gyro_scale_estimate, gyro_scale_z : float or None
        With a rate-bias state and no scale state: the gyro scale factor error the accepted fixes
        show so far (a fraction; the generalized likelihood ratio's estimate) and its z-score (see
        ``latency_z``); None before the first accepted fix while moving, and without the monitor. Past
        :data:`SCALE_ERROR_Z` and :data:`SCALE_ERROR_MIN` it warns once.
    latency_added : int or None
        The step at which the monitor's latency made the filter add the latency state (None: not).
    latency_estimate, latency_z : float or None
        With a calibrated model without a latency state: the fixes' latency against the DR samples the
        accepted fixes show so far (s; positive: each fix is the position that long before its stamp) and its
        z-score; None before the monitor has scored a fix, and without the monitor. Past :data:`LATENCY_Z` and
        :data:`LATENCY_MIN` it warns once. Both monitors' estimates are joint (one generalized likelihood
        ratio test), their z-scores the estimate over its standard deviation, each fix's information
        counted at the correlation its innovations showed when it came, less what the estimated errors
        explain; scoring starts at the first accepted fix while moving, with the calibration states' errors
        then as nuisance parameters (their prior the filter's own covariance; without a rate-bias state,
        a heading drift too).
    latency_at_end, gyro_scale_at_end : float or None
        The fixes' latency (s) and the gyro's scale factor error (a fraction) that :meth:`end_of_drive` told when
        the drive ended: the z-score past :data:`LATENCY_END_Z` / :data:`SCALE_END_Z` (one test) but not
        :data:`LATENCY_Z` / :data:`SCALE_ERROR_Z` (the test at every fix); None else.
    odometer_latency_estimate, odometer_latency_z : float or None
        With a calibrated model: the speed's latency against the heading and the fixes that the accepted fixes
        show so far (s; positive: each speed sample is the one that long before its stamp, a CAN bus's latency
        or the car logger's clock behind the phone's) and its z-score, estimated jointly with the errors above
        (which are estimated as without it). Past :data:`ODOMETER_LATENCY_Z` and :data:`ODOMETER_LATENCY_MIN`
        it warns once, naming the drive reader's ``odometer_latency``; no state is added.
    """

    #: Held as slots, out of the instance's ``__dict__`` (read and set as any attribute): the histories that grow
    #: with the drive (public lists, and ``held_states``, whose shape follows the states), and every private buffer
    #: and monitor. filterpy's ``Saver`` copies ``__dict__`` at each ``save()`` and stacks each entry in
    #: ``to_array()``: entries that grow cannot be stacked (it raised on the first, ``_nis``), and copying them at
    #: every step made its memory grow with the square of the drive's length. What it records is then the state
    #: (``x``, ``P``, the filter ``kf``), the counts and the monitors' estimates, a row per step.
    __slots__ = (
        "crawl_steps", "floored_steps", "gps_scales", "heading_jumps", "held_states", "nis_accepted", "nis_warnings",
        "rejected_steps", "reversing_steps", "zero_rate_steps",
        "_I", "_Ioo", "_Ixo", "_J", "_Joo", "_Jxo", "_adopt", "_cal", "_cal_F", "_cal_P", "_cal_Q", "_cal_mean",
        "_cal_warned", "_corr_n", "_corr_sum", "_crawl", "_driven", "_fast_warned", "_fix_gap", "_fix_interval",
        "_gps_hph", "_gps_y", "_hyp", "_in_a_row", "_inconsistent", "_innovation", "_innovations", "_jB", "_jc",
        "_jd", "_jo", "_js", "_jt", "_ju", "_last_fix_step", "_last_heading", "_last_new_fix", "_last_stop",
        "_listening", "_nis", "_nis_bound", "_nis_steps", "_odometer", "_offer_gaps", "_offered", "_own_points",
        "_own_sigma",
        "_piece_end", "_pieces", "_rate_clamped_since", "_rc_n", "_rc_sum", "_reported", "_residual_c", "_residuals",
        "_restate", "_scale_fixes", "_scale_raw", "_scale_warned", "_seen_gaps", "_sens", "_since_measured", "_so",
        "_stop", "_stretch", "_theta", "_turn_sum", "_u", "_uo", "_used", "_var", "_warned_errors", "_white",
        "_zr_rejected", "_dr_nis", "_dr_scaled",
        "__dict__", "__weakref__")

    def __init__(self, model, kind="ekf", *, x0=None, P0=None, standstill_speed=STANDSTILL_SPEED,
                 low_speed=LOW_SPEED, hold_without_gps=True, gps_window=0, points=None, gate=GATE,
                 reject_gate=None, reacquire_after=REACQUIRE_AFTER, nis_window=NIS_WINDOW,
                 whiteness_window=WHITENESS_WINDOW, scale_window=0, zero_rate_update=True,
                 zero_rate_reacquire_after=ZERO_RATE_REACQUIRE_AFTER, correlated_fixes="calibration",
                 min_fix_interval=0.0, scale_on_detection=True, latency_on_detection=True, stop_reopen=0.0,
                 calibration_error_z=CALIBRATION_ERROR_Z, heading_jump_z=HEADING_JUMP_Z,
                 heading_linear_limit=HEADING_LINEAR_LIMIT, reversing_test=True, crawl_test=True,
                 gps_sigma_floor=SIGMA_FLOOR, floor_on_detection=True, reopen_on_detection=True,
                 dr_noise_window=DR_NOISE_WINDOW, hold_heading_at_stops=False):
        if not isinstance(model, GPSDRModel):
            raise TypeError(f"model must be a GPSDRModel, got {type(model).__name__}")
        self.model = model
        self.kind = check_choice(kind, "kind", KINDS)
        self.standstill_speed = check_positive(standstill_speed, "standstill_speed", strict=False)
        self.low_speed = check_positive(low_speed, "low_speed", strict=False)
        self.hold_without_gps = bool(hold_without_gps)
        self.gps_window = int(gps_window)
        if self.gps_window < 0:
            raise ValueError(f"gps_window must be >= 0, got {gps_window}")
        self._gps_y = deque(maxlen=max(self.gps_window, 1))
        self._gps_hph = deque(maxlen=max(self.gps_window, 1))
        #: the innovation-based GPS sigma (m) when ``gps_window > 0`` and enough fixes came in, else None
        self.gps_sigma_est = None
        #: state rows held without GPS: position and the calibration states
        self.held_states = np.array([0, 3] + list(range(6, model.dim_x)))
        self.kf = self._inner_filter(model, x0, P0, points)
        self._own_points = points is not None and self.kind != "ekf"
        self.scale_on_detection = bool(scale_on_detection)
        self.latency_on_detection = bool(latency_on_detection)
        self.motion = None
        self._init_integrity(gate, reject_gate, reacquire_after, nis_window, self.kf.x)
        self.correlated_fixes = check_choice(correlated_fixes, "correlated_fixes", CORRELATED_FIXES)
        self.calibration_error_z = (None if calibration_error_z is None
                                    else check_positive(calibration_error_z, "calibration_error_z"))
        self.n_calibration_error = 0
        self.heading_jump_z = None if heading_jump_z is None else check_positive(heading_jump_z, "heading_jump_z")
        self.n_heading_jumps = 0
        self.heading_jumps = []  # (step found, onset step, size (rad), z)
        self.heading_linear_limit = (None if heading_linear_limit is None
                                     else check_positive(heading_linear_limit, "heading_linear_limit"))
        self.n_heading_far = 0
        self.n_from_rest = 0  # moving samples taken as a velocity vector where the filter stood (_from_rest)
        self.reversing_test = bool(reversing_test)
        # the fixes' decisions that the car reverses, that it drives forward again, and the steps of both
        self.n_reversing, self.n_forward_again, self.reversing_steps = 0, 0, []
        # the stretch since the car last stood (_direction): whether it is taken as reversing, and the test's
        # state since its start (_restart_direction); None while the car stands
        self._stretch = None
        self.crawl_test = bool(crawl_test)
        self.n_crawl, self.crawl_steps, self.crawl_moved = 0, [], 0.0
        # the standstill since the car last moved (_crawl_sample): the crawl test's state; None while it moves
        self._crawl = None
        self.min_fix_interval = float(min_fix_interval)
        if not (np.isfinite(self.min_fix_interval) and self.min_fix_interval >= 0):
            raise ValueError(f"min_fix_interval must be >= 0 s (0: every fix used), got {min_fix_interval}")
        self.n_thinned, self._fast_warned = 0, False
        self.stop_reopen = float(stop_reopen)
        if not (np.isfinite(self.stop_reopen) and self.stop_reopen >= 0):
            raise ValueError(f"stop_reopen must be >= 0 s (0: every stop ends where its speed first reads over the "
                             f"standstill speed), got {stop_reopen}")
        self._last_heading = None  # the last DR sample's heading (the gyro scale factor's turn)
        # the monitor's hypotheses, each an error the model does not estimate (_monitor_errors): a gyro
        # scale factor error (a MEMS gyro's model: a rate-bias state, no scale state; not for a model without
        # the rate bias, the survey grade's tactical gyro, where a drift it does not model can read as a scale
        # error on a drive that turns mostly one way) and the fixes' latency (a calibrated model without it)
        self._hyp = (["gyro_scale"] if model.rate_bias and not model.gyro_scale else []) + (
            ["latency"] if model.augmented and not model.latency else [])
        m = len(self._hyp)
        # per hypothesis the state's sensitivity to the error, and the accepted fixes' score and information
        self._sens = np.zeros((model.dim_x, m)) if model.augmented else None  # (every hypothesis needs one)
        # the speed's latency (a calibrated model), tested jointly with those but kept apart (_monitor_speed):
        # its sensitivity, score, its information and score variance's cross terms with them, and its own
        self._so = np.zeros(model.dim_x) if model.augmented else None
        self._uo, self._Ixo, self._Jxo, self._Ioo, self._Joo = 0.0, np.zeros(m), np.zeros(m), 0.0, 0.0
        # the score's variance: each fix's information times the fixes' correlation when it came
        self._u, self._I, self._J = np.zeros(m), np.zeros((m, m)), np.zeros((m, m))
        self._theta = self._var = None  # the joint estimates and their variances (the sandwich's)
        self._warned_errors = set()
        self._listening = False  # scoring started (:meth:`_listen`)
        self._restate = False  # a state was added: the others' estimates to be made again
        self._residuals = deque()  # the scored fixes' whitened innovations and sensitivities (None: a break)
        self._residual_c, self._since_measured = None, 0  # their last correlation, and fixes scored since
        self._rc_sum, self._rc_n = 0.0, 0  # its measurements so far (the heading-jump detector's onsets)
        self._turn_sum = 0.0  # the measured turns so far (rad), for the added state's calibration bound
        self._adopt = None  # the hypothesis to add a state for, when the monitor found its error
        self._drop_jumps()  # the heading-jump detector's onsets (_test_jumps)
        #: the step at which the monitor's scale error made the filter add the scale state (None: not)
        self.gyro_scale_added = None
        self.gyro_scale_z = None  #: the monitor's z-score (see :data:`SCALE_ERROR_Z`), None before a fix
        self.gyro_scale_estimate = None  #: the scale factor error the fixes show (fraction), None before
        #: the step at which the monitor's latency made the filter add the latency state (None: not)
        self.latency_added = None
        self.latency_z = None  #: the latency monitor's z-score (see :data:`LATENCY_Z`), None before a fix
        self.latency_at_end = None  #: the fixes' latency told when the drive ended (:meth:`end_of_drive`), or None
        self.gyro_scale_at_end = None  #: the gyro's scale error told when the drive ended, or None
        self.latency_estimate = None  #: the fixes' latency the fixes show (s), None before
        self.odometer_latency_z = None  #: the speed-latency monitor's z-score, None before a fix
        self.odometer_latency_estimate = None  #: the speed's latency the fixes show (s), None before
        self.n_stale, self._last_new_fix, self._driven = 0, None, 0.0  # the last fix that differed; m since
        # the last fix offered and used (steps), the last steps between fixes offered, and their median (s)
        self._offered, self._used, self._offer_gaps, self._fix_interval = None, None, deque(maxlen=FIX_GAPS), 0.0
        self.whiteness_window = float(whiteness_window)
        if not (np.isfinite(self.whiteness_window) and self.whiteness_window >= 0):
            raise ValueError(f"whiteness_window must be >= 0 s (0: fixes taken for independent), got {whiteness_window}")
        self.gps_correlation = 1.0
        self._corr_sum, self._corr_n = 0.0, 0  # for gps_correlation_mean
        # whitened innovations, None at a break; bounded to whiteness_window once the fixes' interval is known
        self._white = deque()
        # the fixes' interval (steps): the shortest of the last ten gaps between the fixes it sees
        self._fix_gap, self._last_fix_step, self._seen_gaps = None, None, deque(maxlen=FIX_GAPS)
        self.scale_window = int(scale_window)
        if self.scale_window < 0:
            raise ValueError(f"scale_window must be >= 0 (0: the fixes' covariance as reported), got {scale_window}")
        self.gps_scale, self._scale_raw, self.gps_scales, self._scale_warned = 1.0, 1.0, [], False
        self._scale_fixes = deque(maxlen=max(self.scale_window, 1))  # (y clipped at the gate, P_pos, R)
        self.gps_sigma_floor = float(gps_sigma_floor)
        if not 0.0 <= self.gps_sigma_floor <= 1.0:
            raise ValueError(f"gps_sigma_floor must be in [0, 1] (a fraction of the recent fixes' median reported "
                             f"sigma; 0: every fix's sigma as reported), got {gps_sigma_floor}")
        self._reported = deque(maxlen=FLOOR_WINDOW)  # the last reported sigmas
        self.n_floored, self.floored_steps = 0, []
        self.floor_on_detection = bool(floor_on_detection)
        self.floor_raised = None  # the step from which every fix's sigma is floored at the median (the monitor's)
        self.zero_rate_update = bool(zero_rate_update) and model.rate_bias
        self._stop = []  # (time, heading) of the standstill samples of the stop going on
        self._last_stop = None  # the samples of a stop that ended at _piece_end and may go on (stop_reopen)
        self.reopen_on_detection = bool(reopen_on_detection)
        self.hold_heading_at_stops = bool(hold_heading_at_stops)
        self.stops_cut_step = None  # the step at which _stops_cut found standstills cut into pieces
        self.fix_taught_step = None  # the step of the stop that contradicted a rate bias the fixes taught
        # the rate bias's information (1 / its variance) by where it came from: the grade's prior and the stops,
        # and the fixes (rate_bias_fix_share; _rate_info_before, _rate_info_after)
        self._rate_info = np.array([1.0 / self.kf.P[RATE, RATE], 0.0]) if model.rate_bias else None
        self._piece_end = None  # (the step, the distance driven) where the last piece of a standstill ended
        self._pieces = 0  # the pieces of the standstill going on (REOPEN_PIECES)
        self._odometer = 0.0  # m driven since the start (the stop_reopen test's; _driven restarts at each fix)
        self.zero_rate_reacquire_after = int(zero_rate_reacquire_after)
        if self.zero_rate_reacquire_after < 0:
            raise ValueError(f"zero_rate_reacquire_after must be >= 0 (0: never), got {zero_rate_reacquire_after}")
        self.n_zero_rate = self.n_zero_rate_rejected = self.n_zero_rate_held = self.n_zero_rate_reacquired = 0
        self.n_zero_rate_turned = self.n_zero_rate_stepped = self.n_zero_rate_drift_taken = self._stop_crawls = 0
        self.zero_rate_steps = []
        # (slope, var) of the kept stops that the state could not follow (_zero_rate_reacquire)
        self._zr_rejected = deque(maxlen=max(self.zero_rate_reacquire_after, ZERO_RATE_WINDOW))
        self._rate_clamped_since = None  # the step from which the bound holds the rate bias (_track_rate_hold)
        self.dr_noise_window = check_positive_int(dr_noise_window, "dr_noise_window", minimum=0)
        if 0 < self.dr_noise_window < DR_NOISE_MIN_WINDOW:
            raise ValueError(f"dr_noise_window must be 0 (the grade's DR noise as given) or at least "
                             f"{DR_NOISE_MIN_WINDOW} moving samples (a median of fewer says little), got "
                             f"{dr_noise_window}")
        #: factors ``(heading, odometer)`` on the grade's DR noise variances, estimated online (1: the grade's)
        self.dr_noise_scale = np.ones(2)
        #: the steps at which the heading's and the odometer's noise were first raised past the grade's (None: not)
        self.heading_noise_raised = self.odometer_noise_raised = None
        self._dr_nis = []  # the window's (heading, odometer) normalised innovations squared
        self._dr_scaled = False  # any factor above 1
        self._predicted = True  # predict() since the last update() (a caller's loop that forgets it is told once)
        self._told_input = set()  # the input mistakes told once (_check_input)

    def _init_integrity(self, gate, reject_gate, reacquire_after, nis_window, x0):
        """The gate, the counters, the consistency monitor and the calibration bounds."""
        gate = float(gate)
        if not gate > 0:
            raise ValueError(f"gate must be > 0 (numpy.inf: no gate), got {gate}")
        reject_gate = max(REJECT_GATE, gate) if reject_gate is None else float(reject_gate)
        if not reject_gate >= gate:
            raise ValueError(f"reject_gate must be >= gate ({gate:.4g}), got {reject_gate}")
        self.gate, self.reject_gate = gate, max(reject_gate, gate)
        self.reacquire_after = check_positive_int(reacquire_after, "reacquire_after")
        self.nis_window = check_positive_int(nis_window, "nis_window")
        from scipy.stats import chi2

        # the window's mean NIS is chi-square(2 W) / W for a consistent filter
        self._nis_bound = float(chi2.ppf(0.999, 2 * self.nis_window)) / self.nis_window
        self._nis = deque(maxlen=self.nis_window)
        self._own_sigma = deque(maxlen=self.nis_window)
        self._innovations = deque(maxlen=self.nis_window)
        self._nis_steps = deque(maxlen=self.nis_window)
        self.step, self.fix_status, self.nis = 0, "none", None
        self.n_fixes = self.n_rejected = self.n_downweighted = self.n_reacquired = self.n_repairs = 0
        self.rejected_steps, self.nis_accepted, self.nis_warnings = [], [], []
        self._in_a_row, self._inconsistent, self.nis_low_step = 0, False, None
        cal = np.arange(6, self.model.dim_x)
        self._cal = cal
        self._cal_mean = np.asarray(x0, dtype=float)[cal].copy()
        # what the specification allows: the prior (model.P0, model.Q) propagated without measurements
        self._cal_F = self.model.F[np.ix_(cal, cal)]
        self._cal_Q = self.model.Q[np.ix_(cal, cal)]
        self._cal_P = self.model.P0[np.ix_(cal, cal)].copy()
        self._cal_warned = set()

    @property
    def gps_scale_mean(self):
        """Mean factor on the tested fixes' reported covariance (1: as reported; None before the first,
        and with ``scale_window=0``, where it is not estimated)."""
        return float(np.mean(self.gps_scales)) if self.gps_scales else None

    @property
    def gps_correlation_mean(self):
        """Mean of ``gps_correlation`` over the fixes so far, each taken after its own update (1:
        white fixes; the longer their errors last, the larger; None before the first fix, and with
        ``whiteness_window=0``, where it is not estimated)."""
        return self._corr_sum / self._corr_n if self._corr_n else None

    @property
    def nis_mean(self):
        """Mean NIS of the accepted fixes (2 for a consistent filter; None before the first)."""
        return float(np.mean(self.nis_accepted)) if self.nis_accepted else None

    def _inner_filter(self, model, x0, P0, points=None):
        """filterpy's EKF, or our UKF with ``points`` (default this kind's preset), on ``model``."""
        if self.kind == "ekf":
            return from_model(ExtendedKalmanFilter, model, x0=x0, P0=P0)
        if points is None:
            points = make_points("gpsdr-ukf" if self.kind == "ukf" else "gpsdr-sukf", model.dim_x)
        # fx, hx and the heading's mean and residual on all sigma points at once (the model's functions
        # are written on the last axis; dim_z, 4 with GPS and 2 without, is taken from each update's R)
        return from_model(UnscentedKalmanFilter, model, points=points, x0=x0, P0=P0, vectorized=True)

    def _set_x(self, value):
        self.kf.x = as_state(value, "x", self.model.dim_x).copy()

    def _set_P(self, value):
        self.kf.P = check_covariance(value, "P", self.model.dim_x).copy()

    # the inner filter's estimate; setting one checks its shape (and P's definiteness)
    x = property(lambda self: self.kf.x, _set_x, doc="State estimate ``(dim_x,)``.")
    P = property(lambda self: self.kf.P, _set_P, doc="State covariance ``(dim_x, dim_x)``.")

    def classify(self, z_dr):
        """``"still"``, ``"slow"`` or ``"moving"`` from the odometer distance ``z_dr[1]``."""
        v = float(z_dr[1]) / self.model.dt
        if v < self.standstill_speed:
            return "still"
        if v < self.low_speed:
            return "slow"
        return "moving"

    def predict(self):
        """Propagate ``x`` and ``P`` one DR sample interval."""
        self._predicted = True
        self.kf.predict()
        if self._sens is not None:
            self._sens = self.model.F @ self._sens
            if "drift" in self._hyp:  # a heading drift the model lacks grows the heading bias's error
                self._sens[HEADING_BIAS, self._hyp.index("drift")] += self.model.dt
        if self._so is not None:
            self._so = self.model.F @ self._so
        if self._js.shape[1]:
            self._js = self.model.F @ self._js
        if self._jumps_on:
            self._spawn_jump()
        if self._cal.size:
            self._cal_mean = self._cal_F @ self._cal_mean
            self._cal_P = self._cal_F @ self._cal_P @ self._cal_F.T + self._cal_Q
        return self

    def update(self, z_dr, z_gps=None, gps_sigma=None, gps_offset=None):
        """Update with one DR sample and an optional GPS fix.

        Parameters
        ----------
        z_dr : array-like of shape (2,)
            ``[heading (rad, from north, clockwise), distance since the last sample (m)]``.
        z_gps : array-like of shape (2,) or None
            ``[e, n]`` (m), or ``None`` (or ``[nan, nan]``, an array's row) when there is no fix; a fix with
            one coordinate NaN is refused.
        gps_sigma : float, optional
            This fix's standard deviation per axis (m); default the model's ``sigma_gps``.
        gps_offset : float, optional
            The fix's time less this sample's (s; :meth:`DRRun.gps_offset_list
            <filterwnn.navigation.scenarios.DRRun.gps_offset_list>`): the fix is the position that long after
            the sample, and is moved back to the sample's time along the filter's velocity, ``z - v d``
            (a fix logged between the samples of a 1 Hz log is up to 0.5 s, 10 m at 20 m/s, off). Default 0.
        """
        z_dr = check_scale(as_state(z_dr, "z_dr", 2), "z_dr")  # a distance of 1e308 would give x = inf
        if z_gps is not None:
            try:
                column = np.asarray(z_gps, dtype=float)
            except (TypeError, ValueError):
                column = None
            if column is not None and column.ndim == 2 and column.size == 2:  # filterpy's column vector (2, 1)
                z_gps = column.reshape(2)
        if _no_fix(z_gps):
            z_gps = gps_sigma = None
        self._check_input(z_dr)
        if gps_sigma is not None:
            gps_sigma = self._floor_sigma(gps_sigma)
        if self.model.gyro_scale:
            self._turn(float(z_dr[0]))
        elif "gyro_scale" in self._hyp:
            self._monitor_turn(float(z_dr[0]))
        self.motion = self.classify(z_dr)
        if self.zero_rate_update:
            self._zero_rate(z_dr[0])
        if self.reversing_test:
            z_dr = self._direction(z_dr)
        if self.crawl_test:
            self._crawl_sample(z_dr)
        self._driven += float(z_dr[1])
        self._odometer += float(z_dr[1])
        stale = z_gps is not None and self._stale(z_gps, gps_sigma)
        thinned = z_gps is not None and not stale and self._thin()
        if stale or thinned:
            z_gps = gps_sigma = None
        if z_gps is not None and gps_offset:
            d = check_finite(gps_offset, "gps_offset", "seconds", " (the fix's time less the sample's)")
            z_gps = np.asarray(z_gps, dtype=float) - d * self.kf.x[[1, 4]]
        adapt = self.gps_window > 0 and z_gps is not None and gps_sigma is None
        if adapt:
            # the fix's innovation and its predicted-state part, before the update
            hph = np.trace(self.kf.P[np.ix_([0, 3], [0, 3])]) / 2.0
            y = np.asarray(z_gps, dtype=float) - self.kf.x[[0, 3]]
            if self.gps_sigma_est is not None:
                gps_sigma = self.gps_sigma_est
        self.fix_status = "stale" if stale else "thinned" if thinned else "none"
        if z_gps is not None and self._stretch is not None:
            z_dr = self._test_reversing(z_dr, z_gps, gps_sigma)
        if z_gps is not None and self._crawl is not None:
            self._test_crawl(z_gps, gps_sigma)
        if z_gps is not None:  # a noise still being learnt from the innovations cannot judge them yet
            c = self.gps_correlation  # the fixes so far: each carries 1 / c of an independent fix
            z_gps, gps_sigma = self._check_fix(z_gps, gps_sigma, test=not (adapt and self.gps_sigma_est is None),
                                               scaled=not adapt)
            outage = self._fix_gaps()
            if outage:
                # the fixes after it carry the dead reckoning's error over it (which the filter's covariance
                # accounts for), and an onset before or in it would read that as a step
                self._drop_jumps()
            self._whiteness(outage)
            if z_gps is not None and c > 1.0 and self.correlated_fixes == "inflate":  # tested as one, counted 1 / c
                gps_sigma = self._fix_sigma(gps_sigma) * np.sqrt(c)
        z, R, kw = self.model.measurement_for(z_dr, z_gps, zupt=self.motion == "still",
                                              low_speed=self.motion == "slow", gps_sigma=gps_sigma,
                                              velocity=self.motion == "moving" and (self._from_rest(z_dr)
                                                                                   or self._heading_far(z_dr)),
                                              dr_noise_scale=self.dr_noise_scale if self._dr_scaled else None)
        weights = self._gain_weights(kw["gps"])
        taught = self._rate_info_before() if kw["gps"] else None
        x_prior = self.kf.x.copy() if weights is not None or self._sens is not None else None
        if weights is not None:
            x_pre, P_pre = x_prior, self.kf.P.copy()
        self._update(z, R, kw)
        if self.dr_noise_window and self.motion == "moving" and not kw["velocity"]:
            self._dr_noise()
        if weights is not None:
            self._schmidt(x_pre, P_pre, weights)
        if self._sens is not None:
            self._monitor_errors(x_prior, kw, weights)
        if self._bound_calibration() | self._repair() and hasattr(self.kf, "x_post"):
            self.kf.x_post, self.kf.P_post = self.kf.x.copy(), self.kf.P.copy()
        if taught is not None:
            self._rate_info_after(taught, fix=True)
        if adapt:
            self._gps_y.append(float(np.mean(y * y)))
            self._gps_hph.append(hph)
            if len(self._gps_y) >= 10:
                self.gps_sigma_est = float(np.sqrt(max(np.mean(self._gps_y) - np.mean(self._gps_hph), 0.01)))
        if self._adopt is not None:
            self._add_state()
        self.step += 1
        return self

    def _check_input(self, z_dr):
        """Tell, once each, what a caller's own loop gets wrong that the filter would otherwise take for the
        sensors' faults (a trial by a filterpy user, stop 71: a heading in degrees read as reversals and a creeping
        car, a speed given as the distance read as 143 m/s, an update without its predict read as noisy sensors)."""
        said = []

        def tell(key, happened, words):
            if happened and key not in self._told_input:
                self._told_input.add(key)
                said.append(words())

        tell("predict", not self._predicted, lambda: (
            f"update() at step {self.step} without predict() since the last update(): each DR sample is predict() "
            "then update(), as in filterpy (batch_filter does both); without it the state does not move between "
            "samples"))
        self._predicted = False
        tell("degrees", abs(float(z_dr[0])) > 2 * np.pi + HEADING_ROUNDING, lambda: (
            f"the heading z_dr[0] = {float(z_dr[0]):g} at step {self.step} is past 2 pi: the heading is in radians "
            "(np.deg2rad of one in degrees; an unwrapped heading in radians is fine)"))
        speed = float(z_dr[1]) / self.model.dt
        tell("speed", speed > MAX_DR_SPEED, lambda: (
            f"the distance since the last sample z_dr[1] = {float(z_dr[1]):g} m at step {self.step} is {speed:.4g} "
            f"m/s over the sample interval ({self.model.dt:g} s), past what a car drives: z_dr[1] is a distance (m), "
            f"the speed times the interval; a speed given there reads {1.0 / self.model.dt:g} times too fast"))
        for words in said:
            warnings.warn(f"GPSDRFilter: {words}", RuntimeWarning, stacklevel=3)

    @property
    def R(self):
        """The last update's measurement noise (the wrapped filter's): the filter builds it at each update from the
        model's DR noise and each fix's ``gps_sigma`` (or the model's ``sigma_gps``), so setting it is refused."""
        return self.kf.R

    @R.setter
    def R(self, value):
        raise AttributeError("GPSDRFilter builds R at each update: the fixes' noise from each fix's gps_sigma (update, "
                             "batch_filter) or the model's sigma_gps, the DR sample's from the model's sigma_heading "
                             "and sigma_odometer (GPSDRModel, or GPSDRModel.from_grade); set those instead")

    @property
    def Q(self):
        """The process noise (the wrapped filter's), from the model's ``q`` (the vehicle's jerk) and its sensors'
        drifts; setting it is refused (set the model's)."""
        return self.kf.Q

    @Q.setter
    def Q(self, value):
        raise AttributeError("GPSDRFilter's Q comes from its model (GPSDRModel: q, the vehicle's white jerk, and the "
                             "sensors' drifts; GPSDRModel.from_grade maps a grade's specification to them): build the "
                             "filter with the model you want")

    def __copy__(self):
        """A deep copy: the filter's counters, windows and the filter it wraps are all mutable, and a shallow copy
        stepped on would leave the original with the copy's state and its own counters."""
        import copy

        return copy.deepcopy(self)

    @property
    def heading_noise(self):
        """The heading's white noise the filter uses (rad): the grade's ``sigma_heading``, or its online estimate."""
        return float(self.model.sigma_heading * np.sqrt(self.dr_noise_scale[0]))

    @property
    def odometer_noise(self):
        """The odometer's noise per sample the filter uses (m): the grade's ``sigma_odometer``, or its online
        estimate."""
        return float(self.model.sigma_odometer * np.sqrt(self.dr_noise_scale[1]))

    def _dr_noise(self):
        """Estimate the DR noise from the last update's innovation (a moving sample, ``[heading, distance]``).

        Each window of :attr:`dr_noise_window` such samples gives, per sensor, the median of ``y^2 / S`` over
        chi-square(1)'s median (1 for a consistent filter; robust to the turns' and the spikes' few large
        ones). Past :data:`DR_NOISE_RAISE` the sensor's variance factor is multiplied by it (the first time, a
        warning with the step and the value); from then on each window multiplies it so, never below 1: a
        covariance matching (Mehra 1972; Mohamed and Schwarz 1999) of the innovations' spread, whose fixed point
        is a filter whose DR innovations are as predicted. Scaling the whole ``S`` by the noise's factor leaves
        the state's part of it unscaled, so that each step is short of the fixed point (the first estimate is a
        lower bound: 0.78 deg on the shipped sample, whose heading has 1 deg) and the estimate does not overshoot
        it (taking the whole excess at once swung between 0.5 and 2.6 deg there). The grade's noise stays the
        floor: a sensor is taken to be no better than its specification."""
        y, S = np.asarray(self.kf.y, dtype=float), np.asarray(self.kf.S, dtype=float)
        self._dr_nis.append((y[0] ** 2 / S[0, 0], y[1] ** 2 / S[1, 1]))
        if len(self._dr_nis) < self.dr_noise_window:
            return
        ratio = np.median(np.array(self._dr_nis), axis=0) / _CHI2_1_MEDIAN
        self._dr_nis = []
        for i in (0, 1):
            if not np.isfinite(ratio[i]) or not (self.dr_noise_scale[i] > 1.0 or ratio[i] > DR_NOISE_RAISE):
                continue
            self.dr_noise_scale[i] = max(1.0, self.dr_noise_scale[i] * ratio[i])
            sensor, attr, unit, to, key, flag, why = _DR_SENSORS[i]
            if getattr(self, f"{sensor}_noise_raised") is None:
                setattr(self, f"{sensor}_noise_raised", self.step)
                value, grade = (f"{to(v):.2g}" for v in (getattr(self, f"{sensor}_noise"), getattr(self.model, attr)))
                warnings.warn(
                    f"GPSDRFilter: the {sensor} is noisier than the grade says at step {self.step}: its innovations "
                    f"over the last {self.dr_noise_window} moving samples give a white noise of at least about "
                    f"{value} {unit} against the grade's {grade} {unit} ({attr}); the filter takes its estimate from "
                    f"here on and refines it every {self.dr_noise_window} (where it ends is the value to give: the "
                    f"drive table's line, or the filter's {sensor}_noise{' in rad' if unit == 'deg' else ''}). {why}. "
                    f"To have it from the start: the grade's {key} ({flag}); dr_noise_window=0 keeps the grade's",
                    RuntimeWarning, stacklevel=3)
        self._dr_scaled = bool((self.dr_noise_scale > 1.0).any())

    def _from_rest(self, z_dr):
        """Whether the filter stands (its speed under ``standstill_speed``) where the sample moves past
        ``low_speed``: a speed that jumps from 0 in one sample (a log that starts moving, a coarse speed). The
        ``[heading, distance]`` update's Jacobian in the velocity vanishes at rest, so the filter would never start
        to move (a user's drive from a parked start, its speed 0 then 7.8 m/s: the EKF-8 stood for the whole first
        outage, 239 m off; stop 69); such a sample enters as the measured velocity vector, which is linear in it
        (counted; the first warns)."""
        if float(np.hypot(self.kf.x[1], self.kf.x[4])) >= self.standstill_speed:
            return False
        self.n_from_rest += 1
        if self.n_from_rest == 1:
            warnings.warn(
                f"GPSDRFilter at step {self.step}: the odometer reads {float(z_dr[1]) / self.model.dt:.1f} m/s where "
                f"the filter stands: a speed that jumps from 0 past low_speed ({self.low_speed:g} m/s) in one sample "
                "(a log that starts moving, or a coarse speed), where the [heading, distance] update cannot start the "
                "filter's velocity (its Jacobian vanishes at rest); the sample enters as the measured velocity "
                "vector (n_from_rest)", RuntimeWarning, stacklevel=3)
        return True

    def _heading_far(self, z_dr):
        """Whether the measured heading, less the heading bias, is farther than ``heading_linear_limit`` from
        the filter's: the heading row of the ``[heading, distance]`` update's own residual at the prior (counted;
        the first warns with the step, the difference and the speed)."""
        if self.heading_linear_limit is None:
            return False
        d = float(dr_residual(np.asarray(z_dr, dtype=float), self.model.hx(self.kf.x, gps=False))[0])
        if abs(d) <= self.heading_linear_limit:
            return False
        self.n_heading_far += 1
        if self.n_heading_far == 1:
            warnings.warn(
                f"GPSDRFilter at step {self.step}: the measured heading is {np.degrees(d):+.0f} degrees from the "
                f"filter's at {float(z_dr[1]) / self.model.dt:.1f} m/s by the odometer, too far for the "
                f"[heading, distance] update (linearised about the filter's heading, it overshoots); the sample "
                f"enters as the measured velocity vector, as do later ones so far off (n_heading_far). A heading "
                f"glitch the drive reader did not catch, a heading in another convention or frame, or a filter that "
                f"lost its velocity: check the drive there", RuntimeWarning, stacklevel=3)
        return True

    def _direction(self, z_dr):
        """The stretch the reversing test looks at (``reversing_test``): a standstill sample ends one, and the
        next sample (or the first of all) starts one, forward. A sample in a stretch taken as reversing has its
        heading turned by half a turn: the direction of travel, as the drive reader turns it for a negative
        speed. Each sample adds its displacement to the test's (:meth:`_restart_direction`): the distance (less
        the odometer's scale) along the heading so used (less the heading bias)."""
        if self.motion == "still":
            self._stretch = None
            return z_dr
        if self._stretch is None:
            self._stretch = {"reversing": False}
            self._restart_direction()
        st, x = self._stretch, self.kf.x
        if st["reversing"]:
            z_dr = _half_turn(z_dr)
        h, d = float(z_dr[0]), float(z_dr[1])
        if self.model.augmented:
            h, d = h - float(x[HEADING_BIAS]), d / float(x[6])
        st["D"] += d * np.array([np.sin(h), np.cos(h)])
        return z_dr

    def _restart_direction(self):
        """Start the reversing test again from the filter's position and its covariance now (a stretch's start,
        a direction taken): no displacement, no evidence."""
        pos = [0, 3]
        self._stretch.update(since=self.step, p=self.kf.x[pos].copy(), P=self.kf.P[np.ix_(pos, pos)].copy(),
                             D=np.zeros(2), llr=0.0, glr=0.0, n=0, streak=0, last=self.step, A=np.zeros((2, 2)),
                             b=np.zeros((2, 2)), c=np.zeros(2))

    def _test_reversing(self, z_dr, z_gps, gps_sigma):
        """Wald's sequential test of the direction the car moves in (:data:`REVERSING_ALPHA`): on an unsigned
        speed a car moves along its displacement or against it. Each fix adds the log-likelihood ratio of the
        test's start less and plus the displacement since (the start's position covariance, the fix's, and the
        displacement times the odometer scale's and the heading bias's uncertainty), over the fixes'
        correlation, one fix a second at most (:data:`MIN_FIX_INTERVAL`: faster fixes carry less than one
        independent fix a second), each fix's normalised innovations clipped at the gate (a fix that jumped
        counts as one at the gate, as the update's Huber weight has it); beside it, the same two paths each with
        an unknown constant offset of its fixes (their weighted least-squares residuals: a street's multipath that
        lasts, the start's own error).
        Either below minus the bound: the direction taken holds, and the test starts again from here. The
        sequential test above it, the offset path's above ``log(1 / REVERSING_OFFSET_ALPHA)`` (a guard), the last
        :data:`REVERSING_FIXES` fixes each past the gate from the direction taken and inside it from the other,
        and a fix before them: the car moves the other way from here: the position is the start less the
        displacement, the velocity and acceleration turn (their covariance with them), this and later samples'
        headings turn by half a turn (reversing, or forward again), and the test starts again (counted, the first
        of each warned)."""
        st, x, pos = self._stretch, self.kf.x, [0, 3]
        if self._too_soon(st):
            return z_dr
        D = st["D"]
        rel = float(self.kf.P[6, 6] + self.kf.P[HEADING_BIAS, HEADING_BIAS]) if self.model.augmented else 0.0
        R = self._fix_sigma(gps_sigma) ** 2 * self.gps_scale * np.eye(2)
        S = st["P"] + R + float(D @ D) * rel * np.eye(2)
        e0 = np.asarray(z_gps, dtype=float) - st["p"] - D
        e1 = e0 + 2.0 * D
        n0, n1 = float(e0 @ np.linalg.solve(S, e0)), float(e1 @ np.linalg.solve(S, e1))
        c = max(self.gps_correlation, 1.0)
        # each fix's share clipped at the gate's: one fix that jumped (past the gate from both) moves it little
        st["llr"] += 0.5 * (min(n0, self.gate) - min(n1, self.gate)) / c
        st["n"] += 1
        W = np.linalg.inv(S - st["P"])
        st["A"] += W
        for i, e in enumerate((e0, e1)):
            st["b"][i] += W @ e
            st["c"][i] += float(e @ W @ e)
        rss = st["c"] - np.einsum("ij,jk,ik->i", st["b"], np.linalg.inv(st["A"]), st["b"])
        st["glr"] = 0.5 * float(rss[0] - rss[1]) / c
        st["streak"] = st["streak"] + 1 if n0 > self.gate >= n1 else 0
        bound = float(np.log(1.0 / REVERSING_ALPHA))
        if st["llr"] < -bound or st["glr"] < -bound:
            self._restart_direction()
            return z_dr
        if not (st["llr"] > bound and st["glr"] > np.log(1.0 / REVERSING_OFFSET_ALPHA)
                and st["streak"] >= REVERSING_FIXES and st["n"] > REVERSING_FIXES):
            return z_dr
        st["reversing"] = back = not st["reversing"]
        self.reversing_steps.append(self.step)
        if back:
            self.n_reversing += 1
        else:
            self.n_forward_again += 1
        T = np.ones(self.model.dim_x)
        T[[1, 2, 4, 5]] = -1.0
        x = x * T
        x[pos] = st["p"] - D
        P = self.kf.P * np.outer(T, T)
        P[pos, :] = P[:, pos] = 0.0
        P[np.ix_(pos, pos)] = S - R
        self.kf.x, self.kf.P = x, P
        if self._sens is not None:
            self._sens *= T[:, None]
        if self._so is not None:
            self._so *= T
        if self._js.shape[1]:
            self._js *= T[:, None]
        self._redraw_sigmas()
        if (self.n_reversing if back else self.n_forward_again) == 1:
            what, against = ("reversing", "driving forward") if back else ("driving forward again", "reversing")
            warnings.warn(
                f"GPSDRFilter: the fixes show the car {what} at step {self.step}, since step {st['since']} ({st['n']} "
                f"fixes, a log-likelihood ratio of {st['llr']:.3g} against {against}, {np.hypot(*D):.3g} m): its "
                f"speed is unsigned. Until the car next stands or the fixes show it turn again, its samples are "
                f"taken as {'reversing, their heading turned by half a turn' if back else 'forward'} (n_reversing, "
                f"n_forward_again, reversing_steps). A signed speed (negative when reversing) tells the drive reader "
                f"so, also where no fixes come", RuntimeWarning, stacklevel=3)
        self._restart_direction()
        return _half_turn(z_dr)

    def _too_soon(self, test):
        """Whether this fix comes sooner than :data:`MIN_FIX_INTERVAL` after the last one the reversing or crawl test
        ``test`` (its state: ``n`` fixes taken, the ``last`` one's step) took, else take it: faster fixes carry less
        than one independent fix a second."""
        if test["n"] and (self.step - test["last"]) * self.model.dt < MIN_FIX_INTERVAL - 1e-9:
            return True
        test["last"] = self.step
        return False

    def _crawl_sample(self, z_dr):
        """The standstill the crawl test looks at (``crawl_test``): a moving sample ends one, and the next standstill
        sample starts one, with the fixes' correlation then (a crawl makes the innovations that measure it
        correlated). Each standstill sample adds to the path the heading (less the heading bias) draws at unit
        speed since the test's start: where a car creeping at ``v`` would be is the start plus ``v`` times it."""
        if self.motion != "still":
            self._crawl = None
            return
        if self._crawl is None:
            self._crawl = {"c": max(self.gps_correlation, 1.0)}
            self._restart_crawl()
        h = float(z_dr[0]) - (float(self.kf.x[HEADING_BIAS]) if self.model.augmented else 0.0)
        self._crawl["U"] += self.model.dt * np.array([np.sin(h), np.cos(h)])

    def _restart_crawl(self):
        """Start the crawl test again from the filter's position now: no path, no evidence."""
        self._crawl.update(since=self.step, p=self.kf.x[[0, 3]].copy(), U=np.zeros(2), n=0, last=self.step,
                           A=np.zeros((3, 3)), g=np.zeros(3), fit=np.zeros(3), glr=0.0, fixes=[])

    @staticmethod
    def _crawl_jump_fit(fixes):
        """The most of the fixes' weighted sum of squares ``[(e, W), ...]`` that a constant offset jumping once
        (between any two fixes) explains, ``max_j (g_1 A_1^-1 g_1 + g_2 A_2^-1 g_2)`` over the fixes before and from
        ``j``: what fixes that jumped while the car stood give (a street's multipath)."""
        A = np.cumsum([W for _, W in fixes], axis=0)
        g = np.cumsum([W @ e for e, W in fixes], axis=0)
        a1, g1, a2, g2 = A[:-1], g[:-1], A[-1] - A[:-1], g[-1] - g[:-1]
        explained = [(gi * np.linalg.solve(ai, gi[:, :, None])[:, :, 0]).sum(axis=1) for ai, gi in ((a1, g1), (a2, g2))]
        return float(np.max(explained[0] + explained[1]))

    def _test_crawl(self, z_gps, gps_sigma):
        """The generalized likelihood ratio of a crawl along the heading against standing (:data:`CRAWL_ALPHA`):
        each fix ``z`` (one a second at most, :data:`MIN_FIX_INTERVAL`) less the test's start ``p`` is ``o + v U``
        (an unknown constant offset ``o``: the start's own error, a street's multipath that lasts; the unit-speed
        path ``U`` since the start; the crawl's speed ``v >= 0``) plus noise of the fix's covariance ``R``. ``o``
        and ``v`` are fitted by weighted least squares, each fix's residual from the fit so far clipped at the gate
        (a fix that jumped counts as one at the gate; the residual's covariance is ``R`` plus the fit's, which
        two fixes, or one with a far larger sigma, leave wide along ``U``), and the likelihood ratio against
        ``v = 0`` is divided by the fixes' correlation when the car stopped. Past ``log(1 / CRAWL_ALPHA)`` after :data:`CRAWL_MIN_FIXES`
        fixes, and past ``log(1 / CRAWL_JUMP_ALPHA)`` against an offset that jumps once (:meth:`_crawl_jump_fit`):
        the car crept, the position moves by ``v U`` and its covariance along ``U`` widens by the move and its
        uncertainty, ``(v^2 + var v) U U^T`` (so that this fix and the next place it), the zero-velocity update
        holds it there, and the test starts again (counted, the first warned)."""
        cr, pos = self._crawl, [0, 3]
        if self._too_soon(cr):
            return
        R = self._fix_sigma(gps_sigma) ** 2 * self.gps_scale * np.eye(2)
        W = np.linalg.inv(R)
        G = np.column_stack([np.eye(2), cr["U"]])  # [offset east, offset north, crawl speed]
        e = np.asarray(z_gps, dtype=float) - cr["p"]
        fit = G @ cr["fit"]
        S = R
        if cr["n"] >= 2:  # the fit's own uncertainty: an offset and a speed from two fixes may be far off
            S = R + cr["c"] * G @ np.linalg.pinv(cr["A"]) @ G.T
        q = float((e - fit) @ np.linalg.solve(S, e - fit))
        if q > self.gate:
            e = fit + (e - fit) * np.sqrt(self.gate / q)
        cr["A"] += G.T @ W @ G
        cr["g"] += G.T @ W @ e
        cr["fixes"].append((e, W))
        cr["n"] += 1
        A, g, c = cr["A"], cr["g"], cr["c"]
        if cr["n"] < 2:
            cr["fit"] = np.r_[e, 0.0]
            return
        sol = np.linalg.lstsq(A, g, rcond=None)[0]
        o = np.linalg.solve(A[:2, :2], g[:2])  # the offset alone
        cr["fit"] = sol if sol[2] > 0 else np.r_[o, 0.0]
        cr["glr"] = 0.5 * float(g @ sol - g[:2] @ o) / c if sol[2] > 0 else 0.0
        if not (cr["glr"] > np.log(1.0 / CRAWL_ALPHA) and cr["n"] >= CRAWL_MIN_FIXES):
            return
        if 0.5 * (float(g @ sol) - self._crawl_jump_fit(cr["fixes"])) / c <= np.log(1.0 / CRAWL_JUMP_ALPHA):
            return  # a jump of the offset fits about as well
        v = float(sol[2])
        var = c * float(np.linalg.inv(A)[2, 2])
        moved = v * cr["U"]
        self.n_crawl += 1
        self.crawl_steps.append(self.step)
        self.crawl_moved += float(np.hypot(*moved))
        x, P = self.kf.x.copy(), self.kf.P.copy()
        x[pos] += moved
        P[np.ix_(pos, pos)] += (v * v + var) * np.outer(cr["U"], cr["U"])
        self.kf.x, self.kf.P = x, P
        self._redraw_sigmas()
        if self.n_crawl == 1:
            warnings.warn(
                f"GPSDRFilter: the fixes show the car creeping at step {self.step} while its speed reads 0, since step "
                f"{cr['since']} ({cr['n']} fixes, a log-likelihood ratio of {cr['glr']:.3g} against standing, "
                f"{np.hypot(*moved):.3g} m along its heading at {v:.2g} m/s): a speed sensor that reads 0 below a "
                f"cutoff (a queue). The position moves to the fixes' crawl and the test starts again (n_crawl, "
                f"crawl_steps, crawl_moved). A speed that reads down to 0, such as the wheel-tick distance given as "
                f"the drive's odometer column, tells it also where no fixes come", RuntimeWarning, stacklevel=3)
        self._restart_crawl()

    def _turn(self, heading):
        """The gyro's scale factor error ``k``: a measured turn ``d`` (this heading less the last) adds
        ``k d`` to the heading bias, ``b += k d``, a linear map of the state and its covariance (and
        of the calibration's prior, which bounds it)."""
        d = self._measured_turn(heading)
        if not d:
            return
        kf = self.kf
        x = kf.x.copy()
        x[HEADING_BIAS] += d * x[GYRO_SCALE]
        kf.x, kf.P = x, _shear(kf.P, HEADING_BIAS, GYRO_SCALE, d)
        if self._sens is not None:  # the map acts on the estimate's error too
            self._sens[HEADING_BIAS] += d * self._sens[GYRO_SCALE]
        if self._so is not None:
            self._so[HEADING_BIAS] += d * self._so[GYRO_SCALE]
        if self._js.shape[1]:
            self._js[HEADING_BIAS] += d * self._js[GYRO_SCALE]
        b, k = HEADING_BIAS - 6, GYRO_SCALE - 6  # the calibration prior's rows
        self._cal_mean[b] += d * self._cal_mean[k]
        self._cal_P = _shear(self._cal_P, b, k, d)
        self._redraw_sigmas()

    def _measured_turn(self, heading):
        """This DR sample's heading less the last one's, wrapped (0 at the first)."""
        last, self._last_heading = self._last_heading, heading
        return 0.0 if last is None else float(wrap_angle(heading - last))

    def _monitor_turn(self, heading):
        """The scale-error monitor's turn: a scale error ``k`` would add ``k d`` to the heading bias."""
        d = self._measured_turn(heading)
        self._sens[HEADING_BIAS, self._hyp.index("gyro_scale")] += d
        self._turn_sum += d

    def _monitor_errors(self, x_prior, kw, weights):
        """The generalized likelihood ratio test (Willsky and Jones 1976) of the errors the model does not
        estimate (``_hyp``: a gyro scale factor error, the fixes' latency), jointly.

        Per hypothesis ``j``, ``s_j``, the state's sensitivity to the error, follows the filter (``F s``, each
        measured turn into the heading bias for a scale error, ``s - K a`` at each update, ``a = H s + g``,
        ``g`` the measurement's own sensitivity: ``-v`` in a fix's rows for a latency, 0 else). Each accepted
        fix while moving adds ``A^T S^-1 y`` and ``A^T S^-1 A`` (``A`` the fix's rows of the ``a``) to the
        score and the information, and the information times the fixes' correlation when it came (of their
        innovations less what the estimated errors explain, :meth:`_residual_correlation`) to the score's
        variance. The information's inverse times the score estimates the errors jointly (a latency is not
        read as a scale error), and each estimate over its standard deviation (the sandwich, the
        information's inverse about the score's variance) is its z-score: past :data:`SCALE_ERROR_Z` /
        :data:`LATENCY_Z`, with an error of at least :data:`SCALE_ERROR_MIN` / :data:`LATENCY_MIN`, it warns
        once, with the step and the remedy, and the filter adds the state (``scale_on_detection``,
        ``latency_on_detection``)."""
        scored = kw["gps"] and self.fix_status == "accepted" and self.motion == "moving"
        if scored and not self._listening:
            self._listen()
        H = np.asarray(self.model.HJacobian(x_prior, **kw), dtype=float)
        K = np.asarray(self.kf.K, dtype=float)
        if weights is not None:
            K = K * weights[:, None]
        A = H @ self._sens
        if kw["gps"] and "latency" in self._hyp:  # a fix tau late is the position v tau behind
            A[2:, self._hyp.index("latency")] -= x_prior[[1, 4]]
        if scored:
            S = np.asarray(self.kf.S, dtype=float)[2:, 2:]
            y = np.asarray(self.kf.y, dtype=float)[2:]
            G = A[2:]
            W = np.linalg.solve(S, G)
            self._u += W.T @ y
            info = G.T @ W
            self._I += info
            L = np.linalg.cholesky(S)
            self._residuals.append((np.linalg.solve(L, y), np.linalg.solve(L, G)))
            c = self._residual_correlation()
            self._J += c * info  # the score's variance: correlated fixes count less
        elif kw["gps"] and self._listening:
            self._residuals.append(None)
        speed = None  # the speed's latency's fix rows, at a scored fix
        if self._so is not None:
            speed = self._monitor_speed(H, K, x_prior, kw, (y, S, G, c) if scored else None)
        self._sens = self._sens - K @ A
        if self._js.shape[1]:
            self._score_jumps(H, K, (y, S, G, c) if scored else None, speed)
        if scored and self._js.shape[1] and self._adopt is None:
            self._test_jumps()
        if scored or self._restate:  # the estimates change with the score, the information, or a state added
            self._restate = False
            self._estimate_errors()

    def _monitor_speed(self, H, K, x_prior, kw, fix):
        """The speed's latency as one more hypothesis of :meth:`_monitor_errors`, its column kept apart so that
        the others are estimated as without it: its sensitivity (the DR measurement's own, :meth:`_speed_lag`,
        while the car moves), and at a scored ``fix = (y, S, G, c)`` its score, its information, and their
        cross terms with the others' (``G`` their rows), the score's variance at the same correlation ``c``.
        Returns its rows of the fix (for the heading-jump onsets' cross terms, :meth:`_score_jumps`), None
        at a fix not scored."""
        a = H @ self._so
        if self.motion != "still":
            a[:2] += self._speed_lag(x_prior, kw["velocity"])
        if fix is not None:
            y, S, G, c = fix
            w = np.linalg.solve(S, a[2:])
            cross, own = G.T @ w, float(a[2:] @ w)
            self._uo += float(w @ y)
            self._Ixo, self._Ioo = self._Ixo + cross, self._Ioo + own
            self._Jxo, self._Joo = self._Jxo + c * cross, self._Joo + c * own
        self._so = self._so - K @ a
        return None if fix is None else a[2:]

    def _speed_lag(self, x, velocity):
        """The DR measurement's sensitivity to the speed's latency ``t``: a speed sample that long late reads
        ``|v| - t a`` (``a`` the acceleration along the velocity), so the odometer's distance is ``zeta dt a``
        short per second of it, and the low-speed form's velocity vector ``zeta a`` along the velocity."""
        v = np.array([x[1], x[4]])
        speed = max(float(np.hypot(*v)), self.model.min_speed)
        along = float(v @ x[[2, 5]]) / speed
        if velocity:
            return -x[6] * along * v / speed
        return np.array([0.0, -x[6] * self.model.dt * along])

    def _listen(self):
        """Start scoring: add the calibration states' errors as nuisance hypotheses, their sensitivity the
        unit vector and their prior information the inverse of their covariance now (the filter's own
        account of how far off they may be). A calibration that a bad start left off (an unknown start
        heading teaches the heading and rate bias wrong things) then explains its own innovations instead
        of reading as a latency or a scale error. A model without a rate-bias state (the survey grade's)
        gets one more: a heading drift from here (its sensitivity ``dt`` more in the heading bias at each
        predict), with no prior, since a gyro that drifts where its grade says it does not would otherwise
        read as a latency (on 1 Hz analogs with a 0.05 deg/s gyro it fired at -0.5 s)."""
        self._listening = True
        cal = list(self._cal)
        n, m = len(cal), len(self._hyp)
        drift = not self.model.rate_bias  # a model without a rate bias: a drift it lacks, from here, unbounded
        E = np.zeros((self.model.dim_x, n + drift))
        E[cal, np.arange(n)] = 1.0
        self._sens = np.hstack([self._sens, E])
        I = np.zeros((m + n + drift, m + n + drift))
        I[:m, :m] = self._I
        I[m:m + n, m:m + n] = np.linalg.inv(self.kf.P[np.ix_(cal, cal)])
        J = I.copy()
        J[:m, :m] = self._J
        self._I, self._J, self._u = I, J, np.r_[self._u, np.zeros(n + drift)]
        self._Ixo, self._Jxo = np.r_[self._Ixo, np.zeros(n + drift)], np.r_[self._Jxo, np.zeros(n + drift)]
        self._hyp = self._hyp + [f"calibration {i}" for i in cal] + ["drift"] * drift
        self._drop_jumps()

    @property
    def _jumps_on(self):
        return self.heading_jump_z is not None and self._sens is not None and self._listening

    def _drop_jumps(self):
        """Forget the heading-jump detector's onsets (:meth:`_test_jumps`): their sensitivities ``(dim_x, n)``,
        onset steps, scores, information (their own, and its cross terms with the monitor's hypotheses) and the
        fixes' correlation each counts its fixes at."""
        m = len(self._hyp)
        n = self.model.dim_x
        self._js, self._jt = np.zeros((n, 0)), []
        self._ju, self._jd, self._jc, self._jB = np.zeros(0), np.zeros(0), np.zeros(0), np.zeros((m, 0))
        self._jo = np.zeros(0)  # their cross terms with the speed's latency (:meth:`_monitor_speed`)

    def _spawn_jump(self):
        """Start an onset every :data:`HEADING_JUMP_SPACING` s (a step in the heading bias from here: its
        sensitivity the unit vector), and forget those older than :data:`HEADING_JUMP_WINDOW` s."""
        dt = self.model.dt
        if self._jt and (self.step - self._jt[-1]) * dt < HEADING_JUMP_SPACING - 0.5 * dt:
            return
        e = np.zeros((self.model.dim_x, 1))
        e[HEADING_BIAS] = 1.0
        keep = max(int(round(HEADING_JUMP_WINDOW / HEADING_JUMP_SPACING)), 1) - 1
        drop = max(len(self._jt) - keep, 0)
        m = len(self._hyp)
        self._js = np.hstack([self._js[:, drop:], e])
        self._jt = self._jt[drop:] + [self.step]
        self._ju, self._jd = np.r_[self._ju[drop:], 0.0], np.r_[self._jd[drop:], 0.0]
        # the fixes' correlation before the onset, its score variance's (the mean of the monitor's measures so
        # far: one window's is noisy, and the last before a step is the step's own): after a step the
        # innovations are correlated by the step itself, and counting its fixes at that would hide it
        c = self._rc_sum / self._rc_n if self._rc_n else max(self.gps_correlation, 1.0)
        self._jc = np.r_[self._jc[drop:], c]
        self._jB = np.hstack([self._jB[:, drop:], np.zeros((m, 1))])
        self._jo = np.r_[self._jo[drop:], 0.0]

    def _score_jumps(self, H, K, fix, speed=None):
        """The onsets' share of :meth:`_monitor_errors`: at a scored ``fix = (y, S, G, c)`` their scores,
        information and its cross terms with the monitor's hypotheses (``G`` their rows) and with the speed's
        latency (``speed`` its rows); then their sensitivities ``s - K H s``."""
        A = H @ self._js
        if fix is not None:
            y, S, G, _ = fix  # (the fixes' correlation: each onset counts its fixes at its own, _jc)
            W = np.linalg.solve(S, A[2:])
            own, cross = (A[2:] * W).sum(axis=0), G.T @ W
            self._ju = self._ju + W.T @ y
            self._jd, self._jB = self._jd + own, self._jB + cross
            if speed is not None:
                self._jo = self._jo + W.T @ speed
        self._js = self._js - K @ A

    def _test_jumps(self):
        """Willsky and Jones's generalized likelihood ratio test of a step in the heading bias at each onset
        kept, jointly with the monitor's hypotheses (their information ``I`` and score ``u``; per onset its own
        information ``d``, score ``u_j`` and cross terms ``b``): the estimate ``(u_j - b^T I^-1 u) / s`` with
        ``s = d - b^T I^-1 b`` (the information left for the step beyond the hypotheses), and its variance
        ``c_j / s``, each fix counted at ``1 / c_j`` of one (``c_j`` the mean correlation of the fixes'
        residuals before the onset: the sandwich variance of a correlation that stays as it was). Past
        :attr:`heading_jump_z`, with an estimate of at least the grade's white heading noise and at most the
        heading bias's calibration bound (:data:`CALIBRATION_SIGMAS` of its specification; a larger estimate
        is past what the linear test can tell), the filter takes the likeliest onset's step
        (:meth:`_take_jump`)."""
        Iinv = self._information_inverse(self._I)
        if Iinv is None:
            return
        IB = Iinv @ self._jB
        s = self._jd - (self._jB * IB).sum(axis=0)
        ok = s > 1e-9 * np.maximum(self._jd, 1e-300)
        if not ok.any():
            return
        s = np.where(ok, s, 1.0)
        theta = (self._ju - IB.T @ self._u) / s
        var = np.maximum(self._jc, 1.0) / s
        z = np.where(ok, theta / np.sqrt(var), 0.0)
        j = int(np.argmax(np.abs(z)))
        most = CALIBRATION_SIGMAS * np.sqrt(self.model.P0[HEADING_BIAS, HEADING_BIAS])
        if abs(z[j]) > self.heading_jump_z and self.heading_noise <= abs(theta[j]) <= most:
            self._take_jump(j, float(theta[j]), float(var[j]), float(z[j]))

    def _take_jump(self, j, theta, var, z):
        """Take the step ``theta`` found at onset ``j``: the heading bias's variance ``+= theta^2`` (its
        cross-covariances dropped, :meth:`_widen`), its calibration bound as wide, so that the fixes teach it
        again; the state is not moved. The monitor's hypotheses keep what the fixes told of them beyond the
        step (conditioned on it, as :meth:`_add_state` does), the speed's latency among them (through the onsets'
        cross terms with it); the onsets start again. Counted in
        ``n_heading_jumps``, the first warned.

        Not the generalized likelihood ratio's jump compensation (``x += s theta``, ``P += s s^T var``): the
        detector also fires, rarely, on a heading bias the filter holds a degree or two off without a step,
        where the estimate is poor (phone analog seed 16: -5.7 degrees where the state was 1.7 off, -3.2 for
        the unscented kinds), and a false step taken into the state costs more than one taken into its
        variance: seed 16's outage ends (10.40 / 28.03 m without the detector, EKF-8) went 13.47 / 36.04
        compensated, 9.58 / 28.03 compensated and widened (but UKF-8 10.37 / 27.77 -> 14.98 / 36.59), 10.12 /
        28.03 with ``P += s s^T theta^2`` (UKF-8 11.28), and 10.28 / 28.03 widened (UKF-8 10.01 / 27.77). Widened,
        a step found late can be overshot (phone seed 2, 5 degrees found after 81 s: 12.05 / 73.27 -> 10.64 /
        93.58 m, compensated 6.47 / 73.27); ``docs/study-outputs/dr/log-faults/RUN.md``, stop 46."""
        onset = self._jt[j]
        self._widen((HEADING_BIAS,), (theta,))  # the heading bias as unsure as the step is large
        if self._cal.size:  # and its calibration bound as wide
            self._cal_P[HEADING_BIAS - 6, HEADING_BIAS - 6] += theta ** 2
        # the hypotheses conditioned on the step (the system's Schur complement; its score variance is c_j times
        # its information, as the onset's test has it)
        b, d = self._jB[:, j], self._jd[j]
        f = b / d
        self._u = self._u - f * self._ju[j]
        self._I = self._I - np.outer(b, b) / d
        self._J = self._J - (np.outer(f, b) + np.outer(b, f) - np.outer(f, f) * d) * self._jc[j]
        self._I, self._J = 0.5 * (self._I + self._I.T), 0.5 * (self._J + self._J.T)
        if self._so is not None:  # the speed's latency likewise (its cross term with the onset o)
            o, cj = self._jo[j], self._jc[j]
            self._condition_speed(self._ju[j], o, d, cj * o, cj * d, b, cj * b)
        self._residuals.clear()
        self._residual_c = None
        self._restate = True
        self._drop_jumps()
        self._repair()
        self._redraw_sigmas()
        self.n_heading_jumps += 1
        self.heading_jumps.append((self.step, onset, theta, z))
        if self.n_heading_jumps > 1:
            return
        warnings.warn(
            f"GPSDRFilter: by step {self.step} the fixes show the heading stepped by {np.degrees(theta):+.3g} deg "
            f"(+- {np.degrees(np.sqrt(var)):.2g}; z-score {z:+.3g}) about step {onset}, while the car moved: a "
            "heading that re-aligns (a phone's fused orientation, a compass or GPS-course correction), or a "
            "heading bias the filter held that far off. The heading bias's variance is widened by it, and the "
            "fixes teach it again (later ones are counted in n_heading_jumps; heading_jump_z=None, --heading-jump-z "
            "off, does not look for them). If the heading column comes from a fused orientation, a gyro-only heading "
            f"(the gyro's yaw rate, integrated) is what the model takes{self._speed_late_note()}", RuntimeWarning,
            stacklevel=5)

    def _speed_or_fixes_note(self, name, theta):
        """The fixes' or the speed's latency warning's last words when the filter has warned of the other with the
        opposite sign: a speed stamped late reads to the fixes as fixes stamped early (the dead-reckoned distance
        lags every change of speed, as fixes placed ahead of their time would), so the speed's is the remedy to take
        first. On the 1 Hz and phone analogs' generators with the speed 0.7 s late the fixes' latency state was
        added, at -0.36 to -0.64 s, on 6 of 12; the command's EKF-8 on two of them went from 6.80 / 15.37 and 10.34 /
        37.26 m at the outage ends to 1.52 / 6.45 and 6.80 / 17.74 with the speed's remedy, 7.44 / 11.71 and 9.62 /
        29.80 with the fixes', 1.53 / 6.56 and 9.59 / 29.97 with both (``log-faults/speed_late_fixes_early.txt``,
        stop 64)."""
        est = self._told_opposite("odometer_latency" if name == "latency" else "latency", theta)
        if est is None:
            return ""
        if name == "odometer_latency":
            return (f". The filter has found the fixes {est:+.2g} s late: a speed stamped late reads as fixes stamped "
                    "early, so take this remedy first, and give the fixes a latency only if they still show one")
        return (f". The filter has warned that the fixes show the speed {est:+.2g} s late: a speed stamped late reads "
                f"as fixes stamped early, so read the drive with each speed at its own time first (odometer_latency="
                f"{est:.2g}, --odometer-latency {est:.2g}), and give the fixes a latency only if they still show one")

    def _heading_late_note(self, name, theta):
        """The fixes' or the speed's latency warning's last words when the other of the two shows the same sign (the
        other warned already, or its z-score past :data:`CALIBRATION_ERROR_Z`): both early against the heading can
        be the heading late against both (a heading averaged over each sample's interval is half an interval late;
        on the 1 Hz analogs with the heading 0.5 s late the fixes read -0.25 to -0.39 s and the speed -0.44 to
        -0.57 s: ``log-faults/heading_latency.py``), which the drive reader's ``heading_latency`` gives back. A speed
        alone late or early made the fixes' test read the opposite sign (``log-faults/heading_latency_named.py``)."""
        other = "latency" if name == "odometer_latency" else "odometer_latency"
        est = self._paired(other, theta)
        if est is None:
            return ""
        speed = theta if name == "odometer_latency" else est
        fixes = "the fixes show themselves" if other == "latency" else "the speed shows itself"
        return (f"; {fixes} {est:+.2g} s late too, and both {'early' if theta < 0 else 'late'} can be the heading "
                f"{-speed:+.2g} s late against them (a heading averaged over each sample's interval is half an "
                f"interval late, 0.5 s at 1 Hz): if so, read the drive with the heading at its own time "
                f"(heading_latency={-speed:.2g}, --heading-latency {-speed:.2g}) instead")

    def _told_opposite(self, other, theta):
        """The estimate of ``other`` (``"latency"`` or ``"odometer_latency"``) where the filter has warned of it and
        it has the opposite sign of ``theta`` (:meth:`_paired`), else None: a speed late beside fixes early."""
        return self._paired(other, -theta) if other in self._warned_errors else None

    def _paired(self, other, theta):
        """The monitor's estimate of ``other`` (``"latency"``, the fixes', or ``"odometer_latency"``, the speed's)
        where it has the sign of ``theta`` and was warned of or has a z-score past :data:`CALIBRATION_ERROR_Z`;
        else None."""
        est, z = ((self.latency_estimate, self.latency_z) if other == "latency"
                  else (self.odometer_latency_estimate, self.odometer_latency_z))
        if est is None or np.sign(est) != np.sign(theta) or not (
                other in self._warned_errors or (z is not None and abs(z) >= CALIBRATION_ERROR_Z)):
            return None
        return est

    def _speed_late_note(self):
        """The heading-step warning's last words when the filter has warned of the speed's latency: a speed
        stamped late moves the car along its track at every start and stop, and the onsets, tested without it,
        can take it for a step (1 Hz analogs with the speed 0.5-1 s late: ``log-faults/speed_jumps.py``)."""
        if "odometer_latency" not in self._warned_errors:
            return ""
        tau = self.odometer_latency_estimate
        fixes = self._paired("latency", tau)
        heading = "" if fixes is None else (
            f" (or, the fixes showing themselves {fixes:+.2g} s late too, the heading {-tau:+.2g} s late against "
            f"both: heading_latency={-tau:.2g}, --heading-latency {-tau:.2g})")
        return (f". The filter has warned that the fixes show the speed late (now {tau:+.2g} s): a speed stamped "
                "late can read as such a step; read the drive with each speed at its own time "
                f"(odometer_latency={tau:.2g}, --odometer-latency {tau:.2g}){heading} first")

    def _residual_correlation(self):
        """The correlation of the scored fixes' innovations less what the estimated errors explain (the
        innovations' own, :attr:`gps_correlation`, also carries the errors' signature: a scale error or a
        latency the model lacks makes them correlated); ``gps_correlation`` until the window is full.
        Measured again once a second of fixes (every fix at 1 Hz, every fifth at 5 Hz)."""
        n = self.whiteness_fixes
        if self._residuals.maxlen != n:
            self._residuals = deque(self._residuals, maxlen=n)
        if self._theta is None or n is None or len(self._residuals) < n:
            return max(self.gps_correlation, 1.0)
        per_second = max(int(round(1.0 / (self._fix_gap * self.model.dt))), 1)
        self._since_measured += 1
        if self._residual_c is not None and self._since_measured < per_second:
            return self._residual_c
        self._since_measured = 0
        self._residual_c = self._measure_residual_correlation()
        self._rc_sum, self._rc_n = self._rc_sum + self._residual_c, self._rc_n + 1
        return self._residual_c

    def _measure_residual_correlation(self):
        """:func:`~filterwnn.metrics.integrated_autocorrelation` of the window's residuals ``L^-1 (y - A theta)``."""
        scored = [e for e in self._residuals if e is not None]
        if not scored:
            return max(self.gps_correlation, 1.0)
        left = iter(np.array([e[0] for e in scored]) - np.array([e[1] for e in scored]) @ self._theta)
        return integrated_autocorrelation([None if e is None else next(left) for e in self._residuals])

    def _estimate_errors(self):
        """The joint estimates of the monitor's errors, their z-scores, and the warning past the gates.

        The gyro scale and the fixes' latency are estimated as without the speed's latency; the speed's
        latency jointly with them all (the system with its row and column). Both latencies move the car along
        its track, so tested jointly each hides the other early in a drive (with the speed's latency among
        them, a fix a second late on the phone analog was told after 10 minutes instead of 2.6); tested this
        way the fixes' latency is told as before, and a fixes' latency or a scale error is not read as the
        speed's."""
        if not self._listening:  # (listening, the system holds the calibration's nuisance parameters at least)
            return
        found = []
        solved = self._solve(self._I, self._J, self._u)
        if solved is not None:
            self._theta, self._var = solved
            found = [(name, theta, var) for name, theta, var in zip(self._hyp, *solved) if name in _TESTED]
        if self._so is not None and self._Ioo > 0.0:
            I = np.block([[self._I, self._Ixo[:, None]], [self._Ixo[None, :], np.array([[self._Ioo]])]])
            J = np.block([[self._J, self._Jxo[:, None]], [self._Jxo[None, :], np.array([[self._Joo]])]])
            every = self._solve(I, J, np.r_[self._u, self._uo])
            if every is not None:
                found.append(("odometer_latency", every[0][-1], every[1][-1]))
        found = [(name, theta, np.sqrt(var), theta / np.sqrt(var)) for name, theta, var in found]
        for name, theta, _, z in found:
            setattr(self, f"{name}_estimate", float(theta))
            setattr(self, f"{name}_z", float(z))
        for name, theta, sd, z in found:
            gate, least = _TESTED[name]
            if abs(z) > gate and abs(theta) >= least and name not in self._warned_errors:
                self._warned_errors.add(name)
                self._warn_error(name, theta, sd, z)
                if self._adopt is None and {"gyro_scale": self.scale_on_detection,
                                            "latency": self.latency_on_detection}.get(name, False):
                    self._adopt = name

    @staticmethod
    def _solve(I, J, u):
        """The estimates of the monitor's errors and their sandwich variances: the information ``I``'s
        inverse times the score ``u``, and the information's inverse around the score's variance ``J``
        (never below the information's inverse: each fix counts at a correlation of 1 or more, and rounding
        could take it under, to zero or below, when the first fixes leave the information nearly singular).
        None while an error has no information yet."""
        Iinv = GPSDRFilter._information_inverse(I)
        if Iinv is None:
            return None
        return Iinv @ u, np.maximum(np.diag(Iinv @ J @ Iinv), np.diag(Iinv))

    @staticmethod
    def _information_inverse(I):
        """The inverse of the monitor's information ``I`` (through its Cholesky factor), or None while it is not
        positive definite (an error with no information yet)."""
        if not (np.diag(I) > 0.0).all():
            return None
        try:
            inv = np.linalg.inv(np.linalg.cholesky(I))
        except np.linalg.LinAlgError:
            return None
        return inv.T @ inv

    @staticmethod
    def _tilt_words(theta):
        """The words of a scale error ``theta`` below -:data:`TILT_SCALE` (past a MEMS gyro's tolerance, and less: a
        tilted axis), else ``""``."""
        if theta >= -TILT_SCALE:
            return ""
        return (f". That is past a MEMS gyro's +-3 %, and what an axis tilted "
                f"{np.degrees(np.arccos(max(1.0 + theta, 0.0))):.0f} degrees from the vertical reads (it turns with "
                "cos(tilt) of the car's turns): a phone in a reclined mount, its axis nearest the vertical given as the "
                "yaw rate. Rotate the gyro's rates onto the vertical (the accelerometer's gravity, averaged while the "
                "car stands, gives it) and give that rate")

    def _warn_error(self, name, theta, sd, z):
        if name == "gyro_scale":
            if self.scale_on_detection:
                then = ("the filter adds a scale state from here, started at that estimate "
                        "(scale_on_detection=False only warns; a grade with gyro_scale_sd=0.01, --gyro-scale-sd 0.01, "
                        "estimates it from the start)")
            else:
                then = "use a grade with gyro_scale_sd=0.01 (--gyro-scale-sd 0.01) to estimate it"
            what = (f"the gyro turning {100 * theta:+.2g} % (+- {100 * sd:.2g} %) more than the car (a scale factor "
                    f"error; z-score {z:+.3g}), which this model does not estimate: each turn in an outage then leaves "
                    "that share of it in the heading")
            what += self._tilt_words(theta)
        elif name == "odometer_latency":
            then = (f"read the drive with each speed placed at its own time (odometer_latency={theta:.2g}, "
                    f"--odometer-latency {theta:.2g})")
            if self.n_heading_jumps:  # a late speed reads as heading steps (log-faults/speed_jumps.py)
                steps = ", ".join(str(found) for found, *_ in self.heading_jumps)
                then += (f"; the {self.n_heading_jumps} heading step(s) found before it (at step(s) {steps}) may be "
                         "its doing")
            what = (f"the speed {theta:+.2g} s (+- {sd:.2g} s) late against the heading and themselves (a CAN bus's "
                    f"latency, or the offset between the clocks that stamped them; z-score {z:+.3g}): each speed is "
                    "then that of that long before, and the distance lags every change of speed")
        else:
            if self.latency_on_detection:
                then = ("the filter adds a latency state from here, started at that estimate "
                        "(latency_on_detection=False only warns; a grade with gps_latency_sd=0.5, --gps-latency-sd "
                        "0.5, estimates it from the start)")
            else:
                then = "place the fixes at their own time (gps_latency=, --gps-latency, when it is known)"
            what = (f"themselves {theta:+.2g} s (+- {sd:.2g} s) late against the DR samples (a receiver's latency, or "
                    f"the offset between the clocks that stamped them; z-score {z:+.3g}): each fix is then the "
                    "position that long before its time, behind the car by its speed times it")
        if name != "gyro_scale":  # the fixes' or the speed's latency: both of one sign can be the heading's
            then += self._heading_late_note(name, theta) + self._speed_or_fixes_note(name, theta)
        # warn (1) <- _estimate_errors <- _monitor_errors <- update <- the caller (5)
        # each error's own kind before the step, so that a run's folded warnings keep them apart
        topic = {"gyro_scale": "the gyro's scale", "latency": "the fixes' latency",
                 "odometer_latency": "the speed's latency"}[name]
        warnings.warn(f"GPSDRFilter, {topic}: by step {self.step} the fixes show {what}; {then}", RuntimeWarning,
                      stacklevel=5)

    def _add_state(self):
        """Add the error the monitor found as a state (:meth:`GPSDRModel.with_gyro_scale` at row 9, or
        :meth:`GPSDRModel.with_latency` last), from its joint estimate ``k`` and that estimate's variance ``v``
        (the generalized likelihood ratio's jump compensation): ``x -> [x + s k, k]``,
        ``P -> [[P + s s^T v, s v], [s^T v, v]]`` (``s`` the monitor's sensitivity). The calibration prior
        gets the state with :data:`DETECTED_SCALE_SD` (and the heading bias the spread such a state would
        have given it over the turns so far) or :data:`DETECTED_LATENCY_SD`. A hypothesis still tested
        keeps what the fixes told of it beyond the added error (its score and information conditioned on
        the added one's)."""
        name, self._adopt = self._adopt, None
        j = self._hyp.index(name)
        k, v, s = float(self._theta[j]), float(self._var[j]), self._sens[:, j]
        n = self.model.dim_x + 1
        if name == "gyro_scale":
            index, model, sd = GYRO_SCALE, self.model.with_gyro_scale(DETECTED_SCALE_SD), DETECTED_SCALE_SD
        else:
            index, model, sd = n - 1, self.model.with_latency(DETECTED_LATENCY_SD), DETECTED_LATENCY_SD
        x, P = insert_state(self.kf.x + s * k, self.kf.P + np.outer(s, s) * v, index, k, v, s * v)
        if self._own_points:
            setting = "gyro_scale_sd" if name == "gyro_scale" else "gps_latency_sd"
            warnings.warn(f"GPSDRFilter: at step {self.step} the filter adds the {model.state_names[index]} state "
                          f"and takes the {self.kind.upper()}'s preset sigma points for its {n} states in place of the "
                          f"points it was given (for {n - 1}); to keep your own, give it a model with that state from "
                          f"the start (a grade with {setting}) and points for its dimension", RuntimeWarning,
                          stacklevel=3)
            self._own_points = False
        self.model, self.kf = model, self._inner_filter(model, x, 0.5 * (P + P.T))
        self.held_states = np.array([0, 3] + list(range(6, n)))
        c = index - 6  # the calibration prior's row
        # the bound stays the specification's, about 0, even for an estimate past it: centred on the estimate (stop
        # 61), a phone's tilted gyro axis was followed (an OBD-II user's log, EKF-8 54.16 / 459.06 -> 42.10 / 146.52
        # m), but drives whose rows had lost turns ran away with the "scale" that reads as (53.01 / 144.25 -> 123.25 /
        # 1020.05 m): docs/study-outputs/dr/obd-log/RUN.md
        self._cal_mean, C = insert_state(self._cal_mean, self._cal_P, c, 0.0, sd ** 2)
        if name == "gyro_scale":
            b = HEADING_BIAS - 6
            C[b, b] += self._turn_sum ** 2 * sd ** 2
            C[b, c] = C[c, b] = self._turn_sum * sd ** 2
        self._cal = np.arange(6, n)
        self._cal_F = model.F[np.ix_(self._cal, self._cal)]
        self._cal_Q = model.Q[np.ix_(self._cal, self._cal)]
        self._cal_P = C
        setattr(self, f"{name}_added", self.step)
        self._restate = True
        # the others: what the fixes told of them beyond this error (the information's Schur complement; the
        # calibration's nuisance parameters are always among them)
        rest = [i for i in range(len(self._hyp)) if i != j]
        L = np.eye(len(self._hyp))[rest]
        L[:, j] = -self._I[rest, j] / self._I[j, j]
        if self._so is not None:  # the speed's latency, conditioned the same way
            self._condition_speed(self._u[j], self._Ixo[j], self._I[j, j], self._Jxo[j], self._J[j, j],
                                  self._I[rest, j], self._J[rest, j], rest)
            self._so = np.insert(self._so, index, 0.0)
        self._u, self._I, self._J = L @ self._u, L @ self._I @ L.T, L @ self._J @ L.T
        self._residuals.clear()
        self._residual_c = None
        self._sens = np.insert(self._sens[:, rest], index, 0.0, axis=0)
        self._hyp = [self._hyp[i] for i in rest]
        self._drop_jumps()  # their cross terms were with the hypotheses as they were

    def _condition_speed(self, u, o, d, o_var, d_var, b, b_var, rest=None):
        """Condition the speed's latency's score, information and score variance (and their cross terms with the
        hypotheses ``rest``, default all) on a parameter taken as known: a heading step taken (:meth:`_take_jump`)
        or an error added as a state (:meth:`_add_state`). The parameter's score ``u``, its information ``d`` and
        its cross information with the speed's latency ``o`` and with the hypotheses ``b``; ``*_var`` the same of
        the score's variance. The Schur complement, as for the hypotheses themselves."""
        keep = slice(None) if rest is None else rest
        fo, f = o / d, b / d
        self._uo -= fo * u
        self._Ixo = self._Ixo[keep] - b * fo
        self._Jxo = self._Jxo[keep] - fo * b_var - f * o_var + f * fo * d_var
        self._Ioo -= o * fo
        self._Joo += fo * (fo * d_var - 2.0 * o_var)

    def _stale(self, z_gps, gps_sigma):
        """Whether this fix repeats the last different fix to the bit although the car drove farther
        than the fix's sigma since it (a receiver re-sending its last solution). Warns at the first."""
        z = np.array(as_state(z_gps, "z_gps", 2))
        if self._last_new_fix is None or not np.array_equal(z, self._last_new_fix):
            self._last_new_fix, self._driven = z, 0.0
            return False
        if self._driven <= self._fix_sigma(gps_sigma):  # a standing car's receiver may repeat its fix
            return False
        if not self.n_stale:
            warnings.warn(
                f"GPSDRFilter: the fix at step {self.step} repeats the last one to the bit after the car drove "
                f"{self._driven:.3g} m: a receiver re-sending its last solution while it has none (or coordinates "
                "written with too few decimals, which the drive reader tells); such fixes "
                "are not used (n_stale counts them). Taken for fixes, a run of them would fail the gate and then "
                "re-acquire the filter onto a position left behind", RuntimeWarning, stacklevel=3)
        self.n_stale += 1
        return True

    def _thin(self):
        """Whether this step's fix comes too soon after the last fix used to be used itself: sooner than
        ``min_fix_interval`` less half the fixes' interval (the median of the last :data:`FIX_GAPS`), so
        that fixes at ``min_fix_interval`` or slower, with their jitter, are all used, and faster ones one
        in ``min_fix_interval / interval``. Warns at the first, with the step."""
        if self._offered is not None:
            self._offer_gaps.append(self.step - self._offered)
        self._offered = self.step
        dt = self.model.dt
        interval = self._fix_interval = float(np.median(self._offer_gaps)) * dt if self._offer_gaps else 0.0
        if (not self.min_fix_interval or self._used is None
                or (self.step - self._used) * dt >= self.min_fix_interval - 0.5 * interval):
            self._used = self.step
            return False
        if not self.n_thinned:
            warnings.warn(
                f"GPSDRFilter thins its fixes from step {self.step}: they come every {interval:g} s, "
                f"and it uses one every {self.min_fix_interval:g} s (min_fix_interval): faster fixes' errors are "
                "correlated, and a filter that takes each for independent follows them; pass min_fix_interval=0 "
                "to use every fix (for fixes whose errors are independent at that rate)", RuntimeWarning, stacklevel=3)
        self.n_thinned += 1
        return True

    def _zero_rate(self, heading):
        """Collect a stop's headings; when it ends, update the rate bias with their slope."""
        if self.motion == "still":
            if self._last_stop is not None:  # back to a standstill within stop_reopen: the same stop
                self._stop, self._last_stop = self._last_stop, None
            elif not self._stop:
                self._count_piece()
                self._stop_crawls = self.n_crawl
            self._stop.append((self.step * self.model.dt, float(heading)))
            return
        if self._stop:
            self._piece_end = (self.step, self._odometer)
        if self._stop and self.stop_reopen > 0:  # the stop may go on: its update waits
            self._last_stop, self._stop = self._stop, []
            return
        if self._last_stop is not None:
            if self._near_last_piece(self.stop_reopen):
                return
            stop, self._last_stop = self._last_stop, None
        else:
            stop, self._stop = self._stop, []
        if len(stop) < ZERO_RATE_MIN_SAMPLES:
            return
        t, h = (np.array(a) for a in zip(*stop))
        if np.all(h == h[0]):  # held by its source (a fused or GPS-course heading), not measured by a gyro
            self.n_zero_rate_held += 1
            return
        sigma = self.heading_noise  # the grade's, or its estimate where the heading showed more (dr_noise_window)
        q = stop_heading_walk(t, h, self.model.q_bias)  # the grade's walk, or the stop's own when past it
        k, size, sd, p = stop_heading_step(t, h, sigma, q)
        if k is not None:
            self._stepped(t, k, size, sd, p)
        slope, var = stop_heading_slope(t, h, sigma, q, step_at=k)
        if self._stop_turned(t, h, sigma, k, slope, var, q):
            return  # the car moved: no evidence about the gyro, for a re-acquisition either
        r = RATE  # the gyro rate bias
        S = self.kf.P[r, r] + var
        y = slope - self.kf.x[r]
        ok = y * y / S <= ZERO_RATE_GATE
        self.zero_rate_steps.append((self.step, slope, float(np.sqrt(var)), bool(ok)))
        if ok:
            self.n_zero_rate += 1
            if not self._rate_update(slope, var):
                if self._zr_rejected:  # followed: the stops kept so far go, where this one contradicts them
                    *_, mean, mean_var = self._kept_stops()
                    if (slope - mean) ** 2 > ZERO_RATE_GATE * (var + mean_var):
                        self._zr_rejected.clear()
                return
            # used, but the calibration bound held the state: it could not follow this stop either
        else:
            self.n_zero_rate_rejected += 1
            self._warn_fix_taught(slope, var)
            if self.hold_heading_at_stops:
                self._take_stop_drift(t, slope, var)
        self._stops_cut(slope, var)
        if not self.zero_rate_reacquire_after:
            return
        self._zr_rejected.append((slope, var))
        if len(self._zr_rejected) >= self._stops_needed(outside=True):
            self._zero_rate_reacquire()

    def _count_piece(self):
        """A standstill begins: the next piece of the last (:data:`REOPEN_PIECES`) when that ended within
        :data:`STOP_REOPEN` and :data:`STOP_REOPEN_M`, else its first."""
        self._pieces = self._pieces + 1 if self._near_last_piece(STOP_REOPEN) else 1

    def _near_last_piece(self, seconds):
        """Whether the last piece of a standstill ended at most ``seconds`` ago, the car having moved at most
        :data:`STOP_REOPEN_M` since (``stop_reopen``'s test, and :meth:`_count_piece`'s)."""
        end = self._piece_end
        return (end is not None and (self.step - end[0]) * self.model.dt <= seconds
                and self._odometer - end[1] <= STOP_REOPEN_M)

    def _stops_cut(self, slope, var):
        """A stop the rate-bias state could not follow (rejected, or held at its calibration bound) that is the
        :data:`REOPEN_PIECES`-th piece or later of one standstill: its speed does not read 0 while the car stands,
        and the pieces are too short to measure the gyro's bias (a u-blox log's GNSS speed given as the speed:
        47 pieces used, the state held at its bound until step 5630, outages ending 7.32 / 173.35 m off). From
        here each standstill is taken whole (``stop_reopen`` = :data:`STOP_REOPEN`, with ``reopen_on_detection``;
        ``stops_cut_step`` the step), warned once."""
        if self.stop_reopen > 0 or self._pieces < REOPEN_PIECES or self.stops_cut_step is not None:
            return
        self.stops_cut_step = self.step
        deg = 180.0 / np.pi
        r = RATE
        state, sd = float(self.kf.x[r]) * deg, float(np.sqrt(self.kf.P[r, r])) * deg
        if self.reopen_on_detection:
            self.stop_reopen = STOP_REOPEN
            done = (f"From here each standstill is taken whole: a stop that starts again within {STOP_REOPEN:g} s, "
                    f"the car having moved at most {STOP_REOPEN_M:g} m, is the same stop (stop_reopen="
                    f"{STOP_REOPEN:g}; reopen_on_detection=False only warns)")
        else:
            done = (f"Pass stop_reopen={STOP_REOPEN:g} (command line: --stop-reopen {STOP_REOPEN:g}), which takes "
                    "each standstill whole")
        warnings.warn(
            f"GPSDRFilter: the stop that ended at step {self.step} is piece {self._pieces} of one standstill (its "
            f"speed read over standstill_speed, {self.standstill_speed:g} m/s, between them, each within "
            f"{STOP_REOPEN:g} s of the last and the car moving at most {STOP_REOPEN_M:g} m): a speed that does not "
            "read 0 while the car stands (a GNSS speed, or a wheel speed with noise) cuts each stop into pieces "
            "too short to measure the gyro's rate bias, and the rate-bias state could not follow this one "
            f"({slope * deg:+.3g} +- {np.sqrt(var) * deg:.2g} deg/s; the state {state:+.3g} +- {sd:.2g}). {done}. "
            "Where the log has a wheel speed or an odometer, give that as the speed", RuntimeWarning, stacklevel=4)

    def _stop_turned(self, t, h, sigma, k, slope, var, q):
        """Whether the stop's heading turned faster than any gyro's bias (:data:`MAX_STOP_RATE_DEG_S`, past the gate's
        margin of its slope's standard error with the grade's walk): counted as rejected and turned (:meth:`_turned`),
        before the gate. A turn within a stop is no walk, but read as one (:func:`stop_heading_walk`) it widened the
        slope's variance until the gate took the turn for the gyro's (stop 59; the sensor-faults probe's city car
        turning while it crept at a speed that read 0: 1 stop used, 4 rejected (3 turned), then 5 used)."""
        if q != self.model.q_bias:  # the margin with the grade's walk: a noisy gyro's walks 1 deg/s over no stop
            var = stop_heading_slope(t, h, sigma, self.model.q_bias, step_at=k)[1]
        if abs(slope) - np.deg2rad(MAX_STOP_RATE_DEG_S) <= np.sqrt(ZERO_RATE_GATE * var):
            return False
        self.zero_rate_steps.append((self.step, slope, float(np.sqrt(var)), False))
        self.n_zero_rate_rejected += 1
        self._turned(t, h, slope)
        return True

    def _kept_stops(self):
        """The kept stops' slopes, variances and weights, and their weighted mean and its variance."""
        s, v = (np.array(a) for a in zip(*self._zr_rejected))
        w = 1.0 / v
        return s, v, w, float(w @ s / w.sum()), float(1.0 / w.sum())

    def _stops_needed(self, outside):
        """The stops the state could not follow that re-acquire it: :attr:`zero_rate_reacquire_after`, or at most
        :data:`ZERO_RATE_REACQUIRE_OUTSIDE` where they measure a bias ``outside`` the grade's bound."""
        n = self.zero_rate_reacquire_after
        return min(n, ZERO_RATE_REACQUIRE_OUTSIDE) if outside else n

    def _heading_bias_takes(self, size, sd):
        """The heading bias moved by ``size`` (rad) and its variance widened by ``sd ** 2``, the centre of its
        calibration bound with it: a change of the measured heading's offset from the car's that a stop showed."""
        kf, b = self.kf, HEADING_BIAS
        x = kf.x.copy()
        x[b] += size
        kf.x = x
        P = kf.P.copy()
        P[b, b] += sd * sd
        kf.P = P
        if self._cal.size:
            self._cal_mean[b - 6] += size
        self._repair()
        self._redraw_sigmas()

    def _take_stop_drift(self, t, slope, var):
        """A stop the gate rejected, not turned (under :data:`MAX_STOP_RATE_DEG_S`) and not found creeping by the
        crawl test: the car did not turn while it stood, so the heading's drift over it beyond the rate-bias state's
        is the gyro's (a bias that differs while the engine idles, or a state taught wrong), and the heading bias
        takes it, its variance the slope's over the stop's length; the rate bias learns nothing from it. Counted
        (``n_zero_rate_drift_taken``), the first warned."""
        if self.n_crawl > self._stop_crawls:  # (the crawls found when the stop began)
            return
        T = float(t[-1] - t[0])
        state = float(self.kf.x[RATE])
        size = (slope - state) * T
        self._heading_bias_takes(size, np.sqrt(var) * T)
        self.n_zero_rate_drift_taken += 1
        if self.n_zero_rate_drift_taken > 1:
            return
        deg = 180.0 / np.pi
        warnings.warn(
            f"GPSDRFilter: over the {T:.3g} s stop that ended at step {self.step} the heading drifted "
            f"{slope * deg:+.3g} +- {np.sqrt(var) * deg:.2g} deg/s, which the rate-bias state ({state * deg:+.3g} deg/s) "
            f"rejects: the car does not turn while it stands, so the heading bias takes the {size * deg:+.3g} deg the "
            "heading drifted beyond the state, and the rate bias learns nothing from the stop. A gyro whose bias "
            "differs while the car stands (the engine's vibration at idle) does this, as do a rate bias the fixes "
            "taught wrong and a gyro outside its grade until the stops re-acquire the state (later stops are counted "
            "in n_zero_rate_drift_taken)", RuntimeWarning, stacklevel=4)

    def _stepped(self, t, k, size, sd, p):
        """A stop whose headings stepped (:func:`stop_heading_step`): the measured heading's offset from the
        car's changed by the step, so the heading bias takes it (its variance the step's), with the centre of
        its calibration bound; counted, and warned at the first."""
        self._heading_bias_takes(size, sd)
        self.n_zero_rate_stepped += 1
        if self.n_zero_rate_stepped > 1:
            return
        dt = self.model.dt
        warnings.warn(
            f"GPSDRFilter: over the {t[-1] - t[0]:.3g} s stop that ended at step {self.step} the heading stepped by "
            f"{np.degrees(size):+.3g} deg at step {int(round(t[k] / dt))} (p = {p:.2g}) while the car stood: a heading "
            "that re-aligns (a phone's fused orientation, a compass or GPS-course correction), not a gyro's drift. "
            "The stop's drift is fitted on either side of the step (a step fitted as a drift reads as a rate bias "
            "of 1.5 times the step over the stop), and the heading bias takes the step. "
            "If the heading column comes from a fused orientation, a gyro-only heading (the gyro's yaw rate, "
            "integrated) is what the model takes (later steps are counted in n_zero_rate_stepped)",
            RuntimeWarning, stacklevel=4)

    def _turned(self, t, h, slope):
        """Count a stop whose heading turned faster than any gyro's bias (the car moved while its speed
        read 0, or the heading jumped), and warn at the first."""
        self.n_zero_rate_turned += 1
        if self.n_zero_rate_turned > 1:
            return
        turn = np.degrees(np.unwrap(h)[-1] - h[0])
        warnings.warn(
            f"GPSDRFilter: over the {t[-1] - t[0]:.3g} s stop that ended at step {self.step} the heading turned "
            f"{turn:+.3g} deg (a fitted drift of {np.degrees(slope):+.3g} deg/s), faster than any gyro's bias "
            f"({MAX_STOP_RATE_DEG_S:g} deg/s), while the speed read 0: the car moved (creeping below the speed "
            "sensor's low-speed cutoff, or turning in a car park), or the heading's source jumped. Such stops do "
            "not teach the rate bias "
            "(n_zero_rate_turned), but the zero-velocity update held the position while the car moved, and the "
            "fixes pull it back only afterwards: where a speed sensor reads 0 below some speed, expect larger "
            "errors after slow traffic (later ones are counted)", RuntimeWarning, stacklevel=4)

    def _zero_rate_reacquire(self):
        """After :attr:`zero_rate_reacquire_after` kept stops that the state could not follow (rejected by the
        gate, or used but held at the calibration bound; :data:`ZERO_RATE_REACQUIRE_OUTSIDE` where they measure a
        bias outside the grade's bound): when their slopes agree (their weighted spread passes chi-square(N - 1)
        at 99.9 %, the oldest leaving until it does) and their weighted mean, with its variance, fails the state's
        gate (:data:`ZERO_RATE_GATE`: together they tell the state wrong), re-acquire the rate bias from it."""
        from scipy.stats import chi2

        while True:
            s, v, w, mean, var = self._kept_stops()
            if len(s) < 2 or float(w @ (s - mean) ** 2) <= chi2.ppf(0.999, len(s) - 1):
                break
            self._zr_rejected.popleft()  # they disagree (creeping, a jumping heading): the oldest leaves
        outside = abs(mean) > CALIBRATION_SIGMAS * np.sqrt(self.model.P0[RATE, RATE])  # past the grade's bound
        if len(s) < self._stops_needed(outside):
            return  # keep waiting
        r = RATE
        kf = self.kf
        state, sd = float(kf.x[r]), float(np.sqrt(kf.P[r, r]))
        if (mean - state) ** 2 <= ZERO_RATE_GATE * (var + sd * sd):
            # together they do not tell the state wrong: stops too short to measure the bias, used but held at
            # the bound (two 1 s stops agreeing loosely on 1.8 +- 1.9 deg/s once re-acquired a UKF to divergence);
            # they are kept, and the next such stops add to them (up to ZERO_RATE_WINDOW)
            return
        self._zr_rejected.clear()
        # while the bound held the rate bias, the heading bias integrated a rate bias about (mean - state)
        # off: it lags by up to that times the time held, and is widened by it as the rate bias is by its
        # own difference (else GPS catches the heading up through the rate bias, which overshoots: a
        # 0.3 deg/s gyro run with the phone grade re-acquired at 0.35 and then ran to the new bound, 0.5)
        held = 0 if self._rate_clamped_since is None else self.step - self._rate_clamped_since
        lag = (mean - state) * held * self.model.dt
        # the gyro itself measured its bias: the grade's prior no longer describes it, so the calibration
        # bounds of the rate bias and of the heading bias it drives restart from here (their spread kept,
        # the heading bias's widened by the lag)
        self._cal_mean[RATE - 6] = mean
        self._cal_mean[HEADING_BIAS - 6] = kf.x[HEADING_BIAS]
        self._cal_P[HEADING_BIAS - 6, HEADING_BIAS - 6] += lag ** 2
        self._widen((HEADING_BIAS, r), (lag, mean - state))
        self._rate_clamped_since = None
        self.n_zero_rate_reacquired += 1
        if self.n_zero_rate_reacquired == 1:
            deg = 180.0 / np.pi
            remedy = ". " + (_gyro_bias_remedy(abs(mean)) if outside else "For a gyro whose bias moves faster than "
                                                                          "the grade allows, "
                                                                          + _instability_remedy(self.model))
            warnings.warn(
                f"GPSDRFilter: the last {len(s)} stops measured the gyro rate bias at {mean * deg:+.3g} "
                f"+- {np.sqrt(var) * deg:.2g} deg/s, which the state ({state * deg:+.3g} +- {sd * deg:.2g} deg/s) "
                "could not follow (each rejected, or held at its calibration bound); the rate-bias state "
                f"re-acquires from them at step {self.step}, and the "
                "calibration bounds of the rate bias and the heading bias restart from there. The gyro's bias has "
                "changed, or it is outside the sensor grade's specification: check the grade (later "
                "re-acquisitions are counted in n_zero_rate_reacquired)" + remedy, RuntimeWarning, stacklevel=4)
        self._rate_update(mean, var)

    def _rate_update(self, slope, var):
        """The Kalman update of the rate-bias state (the last) with a measured rate ``slope`` of variance
        ``var``; True when the calibration bound then held the rate bias (the state could not follow it)."""
        r = RATE
        before = self._rate_info_before()
        kf = self.kf
        x, P = kf.x, kf.P
        S = P[r, r] + var
        Pr = P[:, r]
        if self._sens is not None:  # the stop's slope depends on no monitored error: the state's share goes
            self._sens = self._sens - np.outer(Pr, self._sens[r] / S)
        if self._so is not None:
            self._so = self._so - Pr * (self._so[r] / S)
        if self._js.shape[1]:
            self._js = self._js - np.outer(Pr, self._js[r] / S)
        kf.x = x_new = x + Pr * ((slope - x[r]) / S)
        P = P - np.outer(Pr, Pr) / S
        kf.P = 0.5 * (P + P.T)
        held = self._bound_calibration() and kf.x[r] != x_new[r]
        self._repair()
        self._redraw_sigmas()
        self._rate_info_after(before, fix=False)
        return held

    def _rate_info_before(self):
        """The rate bias's information ``1 / P[RATE, RATE]`` before an update, its parts first scaled to it
        (predictions, bounds, repairs and re-acquisitions change what it knows in proportion to where it came
        from); None for a model without the state."""
        if self._rate_info is None:
            return None
        info = 1.0 / self.kf.P[RATE, RATE]
        self._rate_info *= info / self._rate_info.sum()
        return info

    def _rate_info_after(self, before, fix):
        """Book the information an update gave the rate bias (its gain since ``before``): to the fixes' part
        for a GPS update (``fix``), else (a stop's) to the prior's and the stops'."""
        gained = 1.0 / self.kf.P[RATE, RATE] - before
        if gained > 0.0:
            self._rate_info[1 if fix else 0] += gained

    @property
    def rate_bias_fix_share(self):
        """The share of the gyro rate-bias state's information (the inverse of its variance) that the GPS
        fixes gave, against the grade's prior and the stops (the zero angular rate updates); each
        prediction, bound or repair scales both parts alike, so it leaves the share as it is (read without
        rescaling them). None for a model without the state. A state the fixes taught (near 1) learnt from
        them whatever drift their errors share over a minute, where they are correlated (``gps_correlation``)."""
        if self._rate_info is None:
            return None
        return float(self._rate_info[1] / self._rate_info.sum())

    def _warn_fix_taught(self, slope, var):
        """Warn, once, when the state's gate rejected a stop (``slope`` with variance ``var``, rad/s) while the
        fixes taught the rate bias (:attr:`rate_bias_fix_share` at least :data:`FIX_TAUGHT_SHARE`) and the stop's
        drift lies inside the grade's bias (two of its sigmas): the residual bias to give (``fix_taught_step``).
        Stop 73's fused heading (an AHRS yaw whose bias wanders 0.5 degrees over 300 s, phone grade): the fixes,
        correlated over 20 s, taught -0.024 +- 0.008 deg/s in the first two minutes, the first stop measured
        +0.016 +- 0.002 and was rejected, and the outages ended 5.40 / 21.89 m off against dead reckoning's 3.06 /
        7.44; silent until then."""
        if self.fix_taught_step is not None:
            return
        share = self.rate_bias_fix_share
        grade = float(np.sqrt(self.model.P0[RATE, RATE]))
        bound = abs(slope) + 2.0 * np.sqrt(var)
        if share < FIX_TAUGHT_SHARE or bound >= grade:
            return
        self.fix_taught_step = self.step
        deg = 180.0 / np.pi
        v = _two_digits_up(bound * deg)
        state, sd = float(self.kf.x[RATE]) * deg, float(np.sqrt(self.kf.P[RATE, RATE])) * deg
        warnings.warn(
            f"GPSDRFilter: the stop that ended at step {self.step} measured the heading's drift at "
            f"{slope * deg:+.2g} +- {np.sqrt(var) * deg:.2g} deg/s, and the gyro rate-bias state ({state:+.2g} "
            f"+- {sd:.2g} deg/s), {share:.0%} of whose information the GPS fixes gave (their innovations' "
            f"correlation {self.gps_correlation:.3g}), rejected it: fixes whose errors are correlated teach the "
            "rate bias a drift of their own, and the outages integrate it. A fused heading (an orientation's yaw, "
            "whose fusion has taken out its gyro's bias) or a calibrated gyro drifts less than the grade's "
            f"{grade * deg:.2g} deg/s lets the fixes teach, and this stop's drift is inside {v:.2g}: where the "
            f"heading is such, give its residual bias, a grade of your own with gyro_bias_deg_s={v:.2g} "
            f"(filterwnn study dr --gyro-bias {v:.2g}); else the stops re-acquire the state once "
            f"{self.zero_rate_reacquire_after} of them agree (n_zero_rate_reacquired)",
            RuntimeWarning, stacklevel=4)

    def _floor_sigma(self, gps_sigma):
        """A fix's reported sigma, taken no smaller than ``gps_sigma_floor`` times the lower of the medians of the
        last :data:`FLOOR_FIXES` and :data:`FLOOR_WINDOW` fixes' reported sigmas (this one's among them; see
        ``gps_sigma_floor``), and, once the consistency monitor found fixes reporting far better than they are
        (``floor_on_detection``, ``floor_raised``), than the median of the last :data:`FLOOR_WINDOW`. Counted in
        ``n_floored`` (the steps in ``floored_steps``), the first with a warning."""
        reported = check_positive(float(gps_sigma), "gps_sigma")
        self._reported.append(reported)
        if self.floor_raised is not None:
            typical = floor = _median(self._reported)
        elif not self.gps_sigma_floor:
            return gps_sigma
        else:
            last = list(self._reported)
            typical = min(_median(last[-FLOOR_FIXES:]), _median(last))
            floor = self.gps_sigma_floor * typical
        if reported >= floor:
            return gps_sigma
        self.n_floored += 1
        self.floored_steps.append(self.step)
        if self.n_floored == 1 and self.floor_raised is None:
            n = len(self._reported)
            warnings.warn(
                f"GPSDRFilter takes the fix at step {self.step} as {floor:.3g} m, not the {reported:.3g} m it "
                f"reports: under {self.gps_sigma_floor:g} of the fixes' reported sigma before it ({typical:.3g} m, "
                + (f"the lower of the medians of the last {FLOOR_FIXES} and the last {n} reported"
                   if n > FLOOR_FIXES else f"the median of the {n} reported so far")
                + ", this one's among them), and a receiver's accuracy moves little between fixes (a placeholder "
                "accuracy, or a jump in the receiver's estimate). Later fixes so are counted in n_floored; "
                "gps_sigma_floor=0 (--gps-sigma-floor 0) takes every fix's sigma as reported, as an RTK receiver's "
                "should be whose fixes go from a float solution back to a fixed one (centimetres from decimetres)",
                RuntimeWarning, stacklevel=3)
        return floor

    def _fix_sigma(self, gps_sigma):
        return self.model.sigma_gps if gps_sigma is None else float(gps_sigma)

    def _check_fix(self, z_gps, gps_sigma, test=True, scaled=True):
        """The integrity test of one fix: ``(fix or None, its sigma)``.

        The fix's reported sigma is first scaled by ``sqrt(gps_scale)`` (``scaled=False``: as
        reported, and the fix does not enter the scale's window). ``NIS <= gate``: accepted.
        ``gate < NIS <= reject_gate``: down-weighted, its sigma scaled by ``sqrt(NIS / gate)``
        (Huber's weight on the squared residual: the fix then counts as one at the gate).
        ``NIS > reject_gate``: rejected (``None``), unless :attr:`reacquire_after` rejections came
        in a row, when it re-acquires (:meth:`_reacquire`). ``test=False`` accepts it untested
        (its NIS still counts). Fixes accepted or down-weighted then update ``gps_scale``.
        """
        z_gps = check_scale(as_state(z_gps, "z_gps", 2), "z_gps")
        pos = [0, 3]
        lat = self.model.latency_index
        reported = check_positive(self._fix_sigma(gps_sigma), "gps_sigma")
        own = np.nan if gps_sigma is None else reported  # the fix's own accuracy, for the monitor's words
        lam = self.gps_scale if scaled else 1.0
        if lam != 1.0:  # an unscaled fix keeps its sigma as given (bit for bit as without the estimate)
            gps_sigma = reported * np.sqrt(lam)
        sigma = self._fix_sigma(gps_sigma)
        if lat is None:
            y = z_gps - self.kf.x[pos]
            P_pos = self.kf.P[np.ix_(pos, pos)]
        else:  # the fix predicted at its latency: p - v tau
            y = z_gps - gps_hx(self.kf.x, lat)
            G = gps_H(self.kf.x, self.model.dim_x, lat)
            P_pos = G @ self.kf.P @ G.T
        S = P_pos + sigma**2 * np.eye(2)
        self._innovation = y, S
        self.nis = nis = float(y @ np.linalg.solve(S, y))
        self.n_fixes += 1
        if scaled and self.scale_window:
            self.gps_scales.append(lam)
        if nis <= self.reject_gate or not test:  # the fixes it uses: the gate answers for the others
            self._monitor(min(nis, self.reject_gate), own, (y, P_pos, lam))
        if nis <= self.gate or not test:
            self._in_a_row = 0
            self.fix_status = "accepted"
            self.nis_accepted.append(nis)
            if scaled:
                self._update_scale(y, P_pos, reported, nis)
            return z_gps, gps_sigma
        if nis <= self.reject_gate:
            self._in_a_row = 0
            self.fix_status = "down-weighted"
            self.n_downweighted += 1
            if scaled:
                self._update_scale(y, P_pos, reported, nis)
            return z_gps, sigma * np.sqrt(nis / self.gate)
        if self._in_a_row >= self.reacquire_after:
            self._reacquire(y)
            self._in_a_row = 0
            self.fix_status = "reacquired"
            self.n_reacquired += 1
            if self.n_reacquired == 1:
                warnings.warn(
                    f"GPSDRFilter re-acquires at step {self.step}: {self.reacquire_after} fixes in a row failed "
                    f"its gate, and this one is {np.hypot(*y):.3g} m from its prediction (NIS {nis:.3g}); it takes "
                    "itself to be lost and follows the fixes. If the fixes jumped instead (another datum, a "
                    "street's multipath), the position follows them: check the drive there (later "
                    "re-acquisitions are counted in n_reacquired)", RuntimeWarning, stacklevel=3)
            return z_gps, gps_sigma
        self._in_a_row += 1
        self.fix_status = "rejected"
        self.n_rejected += 1
        self.rejected_steps.append(self.step)
        return None, gps_sigma

    def _update_scale(self, y, P_pos, reported, nis):
        """Add a used fix to the scale's window and re-estimate ``gps_scale``.

        The innovation enters clipped at the gate (``y sqrt(gate / NIS)`` above it: a fix counts
        at most as one at the gate, as the Huber down-weighting has it; a rejected fix does not
        enter), so a jump moves the estimate by at most ``(gate - 2) / (2 scale_window)`` and
        leaves the window ``scale_window`` fixes later. Until the window is full the scale stays
        as it is; then it is the window's maximum-likelihood scale (:func:`gps_scale_mle`, started
        from the last one) when that is above 1 and the window tells it from 1: the
        likelihood-ratio statistic ``2 (l(lam) - l(1))`` (:func:`gps_scale_loglik`), divided by
        ``gps_correlation`` (the fixes' worth in independent fixes), exceeds
        :data:`SCALE_TEST`. Otherwise 1: honest fixes keep their reported sigma (a max(1, lam)
        alone would inflate them by its noise, 6-12 % on average over 30 fixes), and so do fixes
        whose innovations are smaller than reported (a filter that follows their correlated errors).
        """
        if not self.scale_window:
            return
        if nis > self.gate:
            y = y * np.sqrt(self.gate / nis)
        self._scale_fixes.append((y, P_pos.copy(), reported**2 * np.eye(2)))
        if len(self._scale_fixes) < self.scale_window:
            return
        ys, Ps, Rs = (np.array(a) for a in zip(*self._scale_fixes))
        self._scale_raw = lam = gps_scale_mle(ys, Ps, Rs, scale=self._scale_raw)
        if lam <= 1.0:
            self.gps_scale = 1.0
            return
        lr = 2.0 * (gps_scale_loglik(ys, Ps, Rs, lam) - gps_scale_loglik(ys, Ps, Rs, 1.0))
        self.gps_scale = lam if lr / self.gps_correlation > SCALE_TEST else 1.0
        if self.gps_scale > SCALE_WARN and not self._scale_warned:
            self._scale_warned = True
            warnings.warn(
                f"GPSDRFilter: the fixes' covariance scale reached {self.gps_scale:.3g} at step {self.step} "
                f"(their reported sigma {np.sqrt(self.gps_scale):.2g}x optimistic, past the plausible "
                f"{np.sqrt(SCALE_WARN):g}x): the innovations may carry the model's own errors (a wrong Q looks "
                "like a wrong R); check the sensor grade, or take the fixes' covariance as reported "
                "(scale_window=0)", RuntimeWarning, stacklevel=4)

    def _reacquire(self, y):
        """Take the filter to be lost: position variances ``+= y^2``, their cross-covariances dropped."""
        self._widen((0, 3), y)
        self._redraw_sigmas()

    def _widen(self, rows, y):
        """Take the states ``rows`` to be lost: their variances ``+= y^2`` (``y``: one difference per
        row), their cross-covariances dropped (the fixes' and the stops' re-acquisition)."""
        P = self.kf.P.copy()
        for r, yr in zip(rows, y):
            v = P[r, r] + yr ** 2
            P[r, :] = P[:, r] = 0.0
            P[r, r] = v
        self.kf.P = P

    def _redraw_sigmas(self):
        """The unscented kinds' update takes its sigma points from the prior: after ``x`` or ``P``
        changed outside a step, draw them from the new ones (the EKF keeps none)."""
        if self.kind != "ekf":
            self.kf.compute_process_sigmas(self.model.dt, fx=lambda s, dt: s)

    def _monitor(self, nis, own=np.nan, innovation=None):
        """Warn when the mean NIS over the last :attr:`nis_window` fixes leaves its 99.9 % bound.

        ``own``: the fix's reported sigma (m), NaN for a fix that gets the grade's. When every fix of the window
        carried its own and their innovations are at least :data:`HDOP_FACTOR` times it, the warning names a
        ``gps_sigma`` column that holds an HDOP (no unit; measured in ``docs/study-outputs/dr/log-faults/RUN.md``,
        stop 50). ``innovation``: the fix's ``(y, P_pos, scale)``; where the window's fixes that report an
        accuracy far better than its others carry the excess, the warning says so (:meth:`_floored_words`;
        ``docs/study-outputs/dr/sensor-faults/RUN.md``, stop 54)."""
        self._nis.append(nis)
        self._nis_steps.append(self.step)
        self._own_sigma.append(own)
        self._innovations.append(innovation)
        if len(self._nis) < self.nis_window:
            return
        mean = float(np.mean(self._nis))
        high = mean > self._nis_bound
        if high and not self._inconsistent:
            self.nis_warnings.append(self.step)
            # a gyro whose bias moved faster than the grade's random walk lets the rate bias follow: the
            # innovations grow as the heading drifts (docs/study-outputs/dr/log-faults/RUN.md, stop 47)
            gyro = ("; or the gyro's bias moved faster than the grade allows (its temperature): "
                    + _instability_remedy(self.model)) if self.model.rate_bias else ""
            few = self._few_fixes_words()  # (its own kind of warning: folded apart from the others)
            # a model without calibration states takes an odometer's scale or a heading's bias for the fixes' fault
            # (stop 72: with a 5 % scale, mean NIS 5.7 over the drive where the 8-state model read 1.8)
            six = ("" if self.model.augmented else
                   f"this model has no odometer scale or heading bias ({self.model.dim_x} states): a speed a few per "
                   "cent off, or a heading a degree or two off, keeps the innovations growing between fixes; "
                   "GPSDRModel(augmented=True) or a grade (GPSDRModel.from_grade: the study's EKF-8, UKF-8, SUKF-8) "
                   "estimates them. Else ")
            warnings.warn(
                f"GPSDRFilter is inconsistent{' in a few fixes' if few else ''} at step {self.step}: the mean NIS of "
                f"the last {self.nis_window} fixes is {mean:.1f}, above its 99.9 % bound "
                f"{self._nis_bound:.2f} (2 expected); "
                f"{few}{six}the fixes' reported accuracy is optimistic or the sensor grade too good: "
                "pass the receiver's accuracy as gps_sigma, use a lower grade, or estimate the fixes' covariance scale "
                f"(scale_window={SCALE_WINDOW}) if they are optimistic all through the drive: a single stretch at "
                "fault (a car carried, fixes dragged, a heading that deviates) the scale takes for their accuracy, and "
                f"distrusts good fixes after it{gyro}{self._hdop_words(mean) or self._raise_floor()}"
                f"{self._correlated_words()}", RuntimeWarning, stacklevel=4)
        self._inconsistent = high
        if mean < NIS_FAR_BELOW and self.nis_low_step is None:
            self.nis_low_step = self.step
            warnings.warn(self._far_below_words(mean), RuntimeWarning, stacklevel=4)

    def _few_fixes_words(self):
        """The inconsistency warning's words where a few fixes of the window carry its excess ("" otherwise; see
        :data:`FEW_FIXES_MEDIAN`)."""
        w = np.asarray(self._nis, dtype=float)
        top = np.argsort(w)[::-1][:FEW_FIXES]
        share, median = float(w[top].sum() / w.sum()), float(np.median(w))
        if share < 0.5 or median > FEW_FIXES_MEDIAN:
            return ""
        steps = ", ".join(str(k) for k in sorted(np.asarray(self._nis_steps)[top]))
        return (f"most of it is in {len(top)} of the {len(w)} fixes ({100 * share:.0f} % of the sum; the fixes at "
                f"steps {steps}), and the window's median NIS is {median:.2f}, a consistent filter's "
                f"{_CHI2_2_MEDIAN:.2f}: a fault at those steps (fixes that jumped, a reversal or a slide not yet "
                "found) rather than an accuracy optimistic throughout, which would raise the median too: check the "
                "drive there; else ")

    def _far_below_words(self, mean):
        """The warning of a window whose mean NIS is under :data:`NIS_FAR_BELOW`: the fixes' own sigma (every fix of
        the window carried one) or the grade's is far larger than their errors."""
        own = np.asarray(self._own_sigma)
        said = (f"GPSDRFilter: at step {self.step} the mean NIS of the last {self.nis_window} fixes is {mean:.2g}, "
                f"under {NIS_FAR_BELOW:g} (2 expected): ")
        if np.isnan(own).any():
            return said + (f"the grade's GPS sigma ({self.model.sigma_gps:.3g} m) is far larger than the fixes' "
                           "errors, and the filter all but ignores them: pass the receiver's accuracy as gps_sigma, "
                           "or use a better grade")
        return said + (f"the fixes' own sigma (median {float(np.median(own)):.4g} m) is far larger than their errors, "
                       f"and the filter all but ignores them: {SIGMA_UNITS_REMEDY}; and an accuracy in metres given as "
                       "gps_hdop is multiplied by hdop_sigma: give it as gps_sigma. A receiver that reports its accuracy "
                       "a few times too large costs little where its fixes are many: each weighs less than it is worth "
                       "(the eighth user trial's, 5 times: EKF-8 2.95 / 13.12 m at the outage ends, the true sigma "
                       "3.59 / 13.48; stop 75); divide the column by the factor where the receiver's is known, or drop it (every "
                       "fix then gets the grade's sigma)")

    def _correlated_words(self):
        """The inconsistency warning's words where the fixes' errors are correlated (``gps_correlation`` at least
        :data:`CORRELATED_WORDS`): the window's bound is a white window's, and its mean strays past it more often,
        so the warning gives the mean NIS of every accepted fix so far beside it (a phone log with honest fixes
        correlated over 20 s warned at windows of 3.3-3.4 with a mean of 1.19 over the drive: stop 58). It says
        which is the cause of neither: 40 s of fixes 20-40 m off reporting a few metres warned so with a mean of
        0.86 so far (a second new user's log, stop 58)."""
        c = self.gps_correlation
        if c < CORRELATED_WORDS or not self.nis_accepted:
            return ""
        return (f". Its fixes' errors are correlated (gps_correlation {c:.0f}): the window holds about "
                f"{max(self.nis_window / c, 1.0):.0f} independent fixes, and its bound is that of {self.nis_window} "
                f"white ones, which correlated fixes pass more often by chance alone; the mean NIS of the "
                f"{len(self.nis_accepted)} fixes accepted so far is {np.mean(self.nis_accepted):.2f} (2 expected)")

    def _raise_floor(self):
        """The inconsistency warning's words on fixes that report far better than they are
        (:meth:`_floored_words`), and with ``floor_on_detection``, every fix's sigma floored at the median of the
        last :data:`FLOOR_WINDOW` reported from here (``floor_raised``, the step)."""
        words = self._floored_words()
        if not words or not self.floor_on_detection:
            return words
        self.floor_raised = self.step
        return (words + f". From here the filter takes every fix's sigma no smaller than the median of the last "
                f"{FLOOR_WINDOW} reported (floor_on_detection=False: it only warns)")

    def _floored_words(self):
        """The inconsistency warning's words where every fix of the window carried its own sigma and the window's
        mean NIS would be inside its bound both had its fixes that report a sigma under :data:`FAR_BETTER` times
        the window's median reported the median and had every fix the grade's sigma: the excess comes from fixes
        that report an accuracy far better than they have (a receiver's, on some fixes), and the grade's sigma
        would do. ``""`` otherwise: where the fixes are all a little optimistic, or worse than the grade (a
        city's), or the model is wrong (a gyro outside its grade), the other remedies stand."""
        own = np.asarray(self._own_sigma)
        if np.isnan(own).any():
            return ""
        floor = float(np.median(own))
        far = own < FAR_BETTER * floor
        if not far.any():
            return ""

        def mean_nis(sigma):
            return np.mean([min(float(y @ np.linalg.solve(P + s * s * lam * np.eye(2), y)), self.reject_gate)
                            for s, (y, P, lam) in zip(sigma, self._innovations)])

        floored, graded = mean_nis(np.where(far, floor, own)), mean_nis(np.full(len(own), self.model.sigma_gps))
        if max(floored, graded) > self._nis_bound:
            return ""
        return (f". Its fixes that report an accuracy far better than the others carry the excess (down to "
                f"{own.min():.2g} m, the window's median {floor:.2g} m): with those at the median the window's mean "
                f"NIS would be {floored:.2g}, with the grade's {self.model.sigma_gps:.2g} m for every fix "
                f"{graded:.2g}, inside the bound. If the receiver's reported accuracy is what is optimistic, drop the "
                "gps_sigma column (every fix then gets the grade's sigma)")

    def _hdop_words(self, mean):
        """The inconsistency warning's words for fixes whose own sigma is far below their innovations' (an HDOP
        read as metres), or ``""``."""
        own = np.asarray(self._own_sigma)
        factor = np.sqrt(mean / 2.0)  # the innovations' size in the fixes' reported sigma (NIS clipped: at least)
        if np.isnan(own).any() or factor < HDOP_FACTOR:
            return ""
        median, grade = float(np.median(own)), self.model.sigma_gps
        if not HDOP_LOWEST <= median <= HDOP_GRADE * grade:
            return ""
        return (f". The window's innovations are at least {factor:.2g}x its fixes' own sigma (median "
                f"{median:.2g} m, the grade's {grade:.2g} m): a gps_sigma column that holds an HDOP (a dilution of "
                "precision, without a "
                "unit; NMEA GGA's) reads so. Give it as gps_hdop (read_drive_csv's hdop_sigma, --hdop-sigma, the "
                "sigma at HDOP 1), or drop the column (every fix then gets the grade's sigma)")

    @property
    def whiteness_fixes(self):
        """The fixes the whiteness window holds: ``whiteness_window`` seconds at the fixes' interval, the
        shortest of the last :data:`FIX_GAPS` between them (60 at 1 Hz, 300 at 5 Hz; at least 1), None before
        the second fix and with ``whiteness_window=0``. One early or doubled fix is forgotten after that many,
        and a receiver that changes its rate is followed as soon."""
        if self._fix_gap is None or not self.whiteness_window:
            return None
        return max(int(round(self.whiteness_window / (self._fix_gap * self.model.dt))), 1)

    def _fix_gaps(self):
        """Note the gap since the last fix that reached the filter (not stale, not thinned) and keep the
        shortest of the last :data:`FIX_GAPS` (:attr:`whiteness_fixes`); whether it was an outage, a gap over
        twice that shortest one. Every setting: the heading-jump detector's onsets are dropped at one."""
        last, self._last_fix_step = self._last_fix_step, self.step
        if last is None:
            return False
        gap = self.step - last
        self._seen_gaps.append(gap)
        self._fix_gap = min(self._seen_gaps)
        return gap > 2 * self._fix_gap

    def _whiteness(self, outage=False):
        """Add the last fix's whitened innovation ``L^{-1} y`` to the window (a break instead
        when it was not accepted as it is, or came after an ``outage``, :meth:`_fix_gaps`) and
        re-estimate :attr:`gps_correlation` (:func:`~filterwnn.metrics.integrated_autocorrelation`)."""
        if not self.whiteness_window:
            return
        if self._white.maxlen != self.whiteness_fixes:  # the last ones kept
            self._white = deque(self._white, maxlen=self.whiteness_fixes)
        if outage:
            self._white.append(None)
        if self.fix_status == "accepted":
            y, S = self._innovation
            self._white.append(np.linalg.solve(np.linalg.cholesky(S), y))
        else:
            self._white.append(None)
        self.gps_correlation = integrated_autocorrelation(self._white)
        self._corr_sum += self.gps_correlation
        self._corr_n += 1
        self._warn_fast_correlated()

    def _warn_fast_correlated(self):
        """Warn, once, when fixes come faster than one a second, every one is used, and their measured
        correlation says they carry less than one independent fix a second (``gps_correlation`` above
        the fixes per second), measured over a full window (a filter still converging has correlated
        innovations of its own for its first seconds)."""
        if (self._fast_warned or self.min_fix_interval or not self._offer_gaps or self._white.maxlen is None
                or len(self._white) < self._white.maxlen):
            return
        # the mean interval between the fixes offered, outages (gaps over twice the median) left out: 1 Hz fixes
        # that reach a 10 Hz log on its first row after them come 0.7-1.3 s apart, and ten such gaps' median
        # is often 0.9 s (stop 58: a phone log, warned on); their mean is the fixes' rate
        gaps = np.asarray(self._offer_gaps, dtype=float)
        interval = float(np.mean(gaps[gaps <= 2.0 * np.median(gaps)])) * self.model.dt
        # faster than one a second: by half a DR sample at least (not by the rounding of the times' floats)
        if interval > 1.0 - 0.5 * self.model.dt or self.gps_correlation * interval <= 1.0:
            return
        self._fast_warned = True
        warnings.warn(
            f"GPSDRFilter's fixes come every {interval:.3g} s and are correlated at step {self.step}: each carries "
            f"1/{self.gps_correlation:.0f} of an independent fix (gps_correlation), less than one independent fix "
            "a second, and a filter that uses every one follows their errors; pass "
            f"min_fix_interval={MIN_FIX_INTERVAL:g} (--min-fix-interval {MIN_FIX_INTERVAL:g}) to use one a second",
            RuntimeWarning, stacklevel=4)

    def _gain_weights(self, gps):
        """Per state, the share of its Kalman gain this update keeps ``(dim_x,)``, or None for all of it.

        The held rows (:meth:`_held_rows`) keep none. With ``correlated_fixes="inflate"`` the others
        keep all of it (correlated fixes are counted by their covariance, in :meth:`update`); with
        ``"calibration"`` the heading bias and the gyro rate bias keep ``1 / gps_correlation``
        (correlated fixes carry less of the heading's drift than their number says), and the odometer
        scale its full gain: a miscalibrated scale makes the innovations correlated too, and
        de-weighting it would keep it miscalibrated.
        """
        held = self._held_rows(gps)
        c = self.gps_correlation if gps and self.correlated_fixes == "calibration" else 1.0
        if c > 1.0 and self._calibration_off():
            c = max(min(c, self._residual_c), 1.0)
        if not held.size and c <= 1.0:
            return None
        w = np.ones(self.model.dim_x)
        if c > 1.0:
            w[self._cal[1:]] = 1.0 / c
        w[held] = 0.0
        return w

    def _calibration_off(self):
        """Whether the consistency monitor finds the heading bias or the gyro rate bias off, past
        ``calibration_error_z`` (its estimate of that state's error since it began listening, over the
        estimate's sandwich standard deviation), with a fixes' own correlation to take (``_residual_c``):
        counted in ``n_calibration_error``, the first warned."""
        if self.calibration_error_z is None or self._residual_c is None or self._theta is None:
            return False
        worst = None
        for r in (HEADING_BIAS, RATE) if self.model.rate_bias else (HEADING_BIAS,):  # (row 8: another state)
            name = f"calibration {r}"
            if name in self._hyp:
                i = self._hyp.index(name)
                z = abs(self._theta[i]) / np.sqrt(self._var[i]) if self._var[i] > 0 else 0.0
                if z > self.calibration_error_z and (worst is None or z > worst[2]):
                    worst = (r, float(self._theta[i]), float(z))
        if worst is None:
            return False
        self.n_calibration_error += 1
        if self.n_calibration_error == 1:
            r, theta, z = worst
            what = (f"the heading bias off by {np.degrees(theta):+.3g} deg" if r == HEADING_BIAS else
                    f"the gyro rate bias off by {np.degrees(theta):+.3g} deg/s")
            warnings.warn(
                f"GPSDRFilter: at step {self.step} the consistency monitor finds {what} (z = {z:.3g}, past "
                f"{self.calibration_error_z:.3g}), more than the correlated fixes explain. The innovations' "
                f"correlation (gps_correlation {self.gps_correlation:.3g}) is then partly that error's own, and "
                "cutting the calibration's gain by it would keep the error: while the monitor finds it, the heading "
                f"bias and the rate bias take the fixes' own correlation ({self._residual_c:.3g}: the innovations "
                "less what the monitor's errors explain) instead (n_calibration_error counts the fixes). A heading "
                "that re-aligns (a fused orientation) or a gyro whose bias changed does this"
                + ("; for a gyro whose bias moves faster than the grade allows, " + _instability_remedy(self.model)
                   if self.model.rate_bias else ""), RuntimeWarning, stacklevel=4)
        return True

    def _held_rows(self, gps):
        """The rows this update must not move: position and calibration without a fix; the
        calibration when it is not observable (see the module docstring)."""
        if not gps:
            return self.held_states if self.hold_without_gps else np.zeros(0, dtype=int)
        if not self._cal.size:
            return self._cal
        observable = self.motion == "moving" and self.fix_status == "accepted"
        return np.zeros(0, dtype=int) if observable else self._cal

    def _bound_calibration(self):
        """Hold each calibration state within :data:`CALIBRATION_SIGMAS` of its prior (its specification).

        The prior is the model's ``P0`` propagated by its ``F`` and ``Q`` without measurements
        (a random walk's spread grows with time; a heading bias driven by a rate bias grows
        with the rate bias's specification times the time), about the start's mean propagated by
        ``F`` (a heading bias drifts with the rate bias's mean). A re-acquisition of the rate bias
        from the stops (:meth:`_zero_rate_reacquire`) restarts the mean of the rate bias and of the
        heading bias from there: the gyro has measured itself outside its specification. The heading
        bias is an angle: compared with its prior mean the shorter way round, and kept in ``[-pi, pi)``.
        True when it changed the state.
        """
        if not self._cal.size:
            return False
        x = self.kf.x
        d = x[self._cal] - self._cal_mean
        b = HEADING_BIAS - 6  # the heading bias is an angle: its distance from its prior mean the shorter way
        d[b] = wrap_angle(d[b])
        bound = CALIBRATION_SIGMAS * np.sqrt(np.diag(self._cal_P))
        out = np.abs(d) > bound
        if self.model.rate_bias:
            i = RATE - 6
            self._track_rate_hold(out[i], bound[i] - abs(d[i]))
        wrap = abs(x[HEADING_BIAS]) > np.pi
        if not (out.any() or wrap):
            return False
        x = x.copy()
        x[self._cal] = self._cal_mean + np.clip(d, -bound, bound)
        x[HEADING_BIAS] = wrap_angle(x[HEADING_BIAS])  # kept in [-pi, pi)
        self.kf.x = x
        if not out.any():
            return True
        names = self.model.state_names[6:]
        for i in np.flatnonzero(out):
            if i not in self._cal_warned:
                self._cal_warned.add(i)
                remedy = ""
                if self.model.rate_bias and i == RATE - 6:  # the gyro's own specification, at least where held
                    remedy = ". " + _gyro_bias_remedy(abs(x[RATE]), "at least")
                elif i == 0:  # the odometer scale: a speed off by more than the grade allows is the reader's to fix
                    remedy = (f". A speed or odometer that reads {'more' if d[i] > 0 else 'less'} than the car drove "
                              "by more than the grade allows (a speedometer's signal reads high by up to 10 %) is "
                              "divided out by the drive reader's speed_scale= (--speed-scale), whose check against "
                              "the fixes names the value")
                warnings.warn(
                    f"GPSDRFilter: the {names[i]} state ran past {CALIBRATION_SIGMAS:g} sigma of its "
                    f"specification at step {self.step} ({d[i]:+.3g} from its prior mean, bound "
                    f"{bound[i]:.3g}); held at the bound. Check the sensor grade (or the sensor)" + remedy,
                    RuntimeWarning, stacklevel=4)
        return True

    def _track_rate_hold(self, clamped, margin):
        """Note the step from which the bound holds the rate bias (:meth:`_zero_rate_reacquire` widens the
        heading bias by what it integrated since): held from the first clamp, and free again once the state
        is more than one of its standard deviations inside the bound."""
        if clamped:
            if self._rate_clamped_since is None:
                self._rate_clamped_since = self.step
        elif margin > np.sqrt(self.kf.P[RATE, RATE]):
            self._rate_clamped_since = None

    def _repair(self):
        """Keep ``P`` symmetric positive definite (documented repair, counted and warned)."""
        P = self.kf.P
        if not np.array_equal(P, P.T):  # the EKF's Joseph form leaves last-bit asymmetry
            self.kf.P = P = 0.5 * (P + P.T)
        P, n_bad = repair_pd(P[None])
        if not n_bad:
            return False
        self.kf.P = P[0]
        self.n_repairs += 1
        if self.n_repairs == 1:
            warnings.warn(f"GPSDRFilter: P lost positive definiteness at step {self.step}; repaired (symmetrised, "
                          "eigenvalues floored at 1e-12 of the largest; later repairs are counted in n_repairs)",
                          RuntimeWarning, stacklevel=4)
        return True

    def _schmidt(self, x_pre, P_pre, weights):
        """Redo the last update with the gain's rows scaled by ``weights (dim_x,)`` (0: zero
        gain, a Schmidt-Kalman "consider" state; 1: the full gain).

        With gain ``K`` (its rows scaled: ``K'``), innovation ``y`` and its covariance ``S``,
        the cross-covariance is ``C = K S`` and, for any gain,
        ``P = P^- - K' C^T - C K'^T + K' S K'^T``.
        """
        kf = self.kf
        K = np.asarray(kf.K, dtype=float)
        S = np.asarray(kf.S, dtype=float)
        C = K @ S
        Kc = K * weights[:, None]
        kf.x = x_pre + Kc @ np.asarray(kf.y, dtype=float)
        P = P_pre - Kc @ C.T - C @ Kc.T + Kc @ S @ Kc.T
        kf.P = 0.5 * (P + P.T)
        if hasattr(kf, "x_post"):
            kf.x_post, kf.P_post = kf.x.copy(), kf.P.copy()

    def _update(self, z, R, kw):
        m = self.model
        if self.kind == "ekf":
            args = (kw["gps"], kw["velocity"])
            self.kf.update(z, m.HJacobian, m.hx, R=R, args=args, hx_args=args,
                           residual=np.subtract if kw["velocity"] else dr_residual)
        elif kw["velocity"]:
            # the velocity form's first entry is v_e (m/s), not a heading: a linear mean and a plain
            # residual (the heading's circular mean and wrap folded the sigma points' v_e into
            # [-pi, pi): with widely spread points, as the SUKF's former preset had, it lost the speed)
            kf = self.kf
            z_mean, residual = kf.z_mean, kf.residual_z
            kf.z_mean, kf.residual_z = None, np.subtract
            try:
                kf.update(z, R=R, gps=kw["gps"], velocity=True)
            finally:
                kf.z_mean, kf.residual_z = z_mean, residual
        else:
            self.kf.update(z, R=R, gps=kw["gps"])

    def batch_filter(self, z_dr, z_gps=None, gps_sigma=None, gps_offset=None, saver=None):
        """Run over a drive: ``predict`` then ``update`` at every DR sample.

        Parameters
        ----------
        z_dr : array-like of shape (n_steps, 2)
        z_gps : sequence of length n_steps, optional
            Per step the fix ``(2,)`` or ``None`` (:meth:`filterwnn.navigation.scenarios.DRRun.gps_list`), or an
            array ``(n_steps, 2)`` whose rows without a fix are NaN.
        gps_sigma : float or sequence of length n_steps, optional
            Per step the fix's sigma (m) or ``None`` (any value where there is no fix); one number for every fix.
        gps_offset : sequence of length n_steps, optional
            Per step the fix's time less the sample's (s) or ``None`` (:meth:`update`;
            :meth:`~filterwnn.navigation.scenarios.DRRun.gps_offset_list`).
        saver : filterpy.common.Saver, optional
            As filterpy's ``batch_filter`` takes it: ``saver.save()`` after every step, so that ``P`` (or anything
            else the filter holds) is recorded with the means (``Saver(f)`` on this filter; ``saver.to_array()``
            afterwards).

        Returns
        -------
        ndarray of shape (n_steps, dim_x)
            The posterior means (their covariances: ``saver``).

        Warns
        -----
        RuntimeWarning
            What the steps warn (an inconsistent window of fixes, a calibration state at its bound, a
            re-acquisition, a covariance repair), once per kind when the run ends: the first with its
            step, then how many more like it came and at which steps. ``predict``/``update`` warn at
            each step as it happens.
        """
        z_dr = np.asarray(z_dr, dtype=float)
        if z_dr.ndim != 2 or z_dr.shape[1] != 2:
            raise ValueError(f"z_dr must have shape (n_steps, 2), got {z_dr.shape}")
        n = len(z_dr)
        gps = [None] * n if z_gps is None else list(z_gps)
        sig = [None] * n if gps_sigma is None else [gps_sigma] * n if np.ndim(gps_sigma) == 0 else list(gps_sigma)
        off = [None] * n if gps_offset is None else list(gps_offset)
        for name, seq in (("z_gps", gps), ("gps_sigma", sig), ("gps_offset", off)):
            if len(seq) != n:
                raise ValueError(f"{name} must have one entry per DR sample ({n}), got {len(seq)}")
        width = self.model.dim_x
        out = np.empty((n, width))
        with folded_warnings():  # a long drive can warn many times for one cause: once per kind
            for k in range(n):
                self.predict()
                self.update(z_dr[k], gps[k], sig[k], off[k])
                out[k] = self.kf.x[:width]  # the states of the model it started with (a scale state added is not)
                if saver is not None:
                    saver.save()
            self.end_of_drive()
        return out

    def end_of_drive(self):
        """The tests made once, when a drive ends (:meth:`batch_filter` calls it after its last step; a caller of
        :meth:`predict` and :meth:`update` calls it when its drive ends). The fixes' latency and the gyro's scale
        factor error, which the monitor tests at every fix against :data:`LATENCY_Z` and :data:`SCALE_ERROR_Z`, are
        tested once more, against :data:`LATENCY_END_Z` and :data:`SCALE_END_Z`: past it, with an estimate of at
        least :data:`LATENCY_MIN` / :data:`SCALE_ERROR_MIN`, where the monitor has neither told the error nor the
        model estimates it, the filter warns with the estimate and the setting to rerun with (the reader's
        ``gps_latency``, which places each fix at its own time; a grade's ``gyro_scale_sd``, the scale state from
        the start) and keeps the estimate (``latency_at_end``, ``gyro_scale_at_end``; None else). It only warns: the
        run is over. Called again, it says no more. Fixes that read early where the filter has warned that the
        speed reads late are not told: a late speed reads so, and its remedy comes first (a random drive with the
        speed 0.43 s late, protocol 3's seed 260: told -0.10 s at the end, whose rerun gave 6.13 / 22.51 m at the
        outage ends against 4.84 / 16.51, and with the speed's remedy too 3.06 / 15.97 against its alone 2.73 /
        15.97: ``log-faults/speed_late_fixes_early_before.txt``; stop 64).

        Returns
        -------
        dict
            ``{"latency": latency_at_end, "gyro_scale": gyro_scale_at_end}``.
        """
        for name, gate in _TESTED_AT_END.items():
            z, est = getattr(self, f"{name}_z"), getattr(self, f"{name}_estimate")
            if (getattr(self, f"{name}_at_end") is not None or z is None or est is None or name in self._warned_errors
                    or getattr(self.model, name) or abs(z) <= gate or abs(est) < _TESTED[name][1]):
                continue
            if name == "latency" and self._told_opposite("odometer_latency", est) is not None:
                continue  # fixes early as the speed told late makes them: its remedy first (_speed_or_fixes_note)
            setattr(self, f"{name}_at_end", float(est))
            self._warn_at_end(name, float(est), float(z))
        return {name: getattr(self, f"{name}_at_end") for name in _TESTED_AT_END}

    def _warn_at_end(self, name, est, z):
        """The warning of :meth:`end_of_drive` for the error ``name`` (its estimate and z-score)."""
        test = (f"the monitor's estimate, z-score {z:+.3g}: past {_TESTED_AT_END[name]:g} for this one test at the "
                f"drive's end, under the {_TESTED[name][0]:g} its test at every fix needs")
        if name == "latency":
            said = (f"the fixes' latency: over the whole drive (to step {self.step}) the fixes read {est:+.2f} s late "
                    f"against the DR samples ({test}). An app that stamps each fix when it arrives (0.15-0.45 s after "
                    "it) reads so, as do a receiver's latency and two clocks: rerun with each fix at its own time "
                    f"(read_drive_csv's gps_latency={est:.2f}; command line --gps-latency {est:.2f}; a drive read with a "
                    "gps_latency already: add this to it); on 230 drives without a latency this end test fired on 1")
        else:
            said = (f"the gyro's scale: over the whole drive (to step {self.step}) the fixes show the gyro turning "
                    f"{100 * est:+.2g} % more than the car ({test}){self._tilt_words(est)}: rerun with the scale state "
                    "from the start (a grade with gyro_scale_sd=0.01; command line --gyro-scale-sd 0.01); on 242 "
                    "drives without a scale error this end test fired on 2")
        warnings.warn(f"GPSDRFilter, {said}", RuntimeWarning, stacklevel=3)
