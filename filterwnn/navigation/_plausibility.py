r"""Plausibility checks of a recorded drive: unit mistakes the data itself can reveal.

A drive file can be well-formed and still wrong: time in milliseconds, a heading in
degrees that happens to stay under :math:`2\pi`, speed in km/h, latitude and longitude
swapped. Every such file gives confident, wrong numbers. Where the drive has GPS fixes
that move, the fixes tell: between two fixes :math:`p_i, p_j` about :math:`L` apart
(a *chord*; :math:`L = \max(20\,\mathrm{m}, 8\sigma)` so the fixes' noise is small
against it; chosen by the odometer's path between them, so that neither the fixes' noise
nor a fix jumped by multipath chooses it), the dead-reckoned displacement

.. math:: d_{ij} = \sum_{s} \ell_s\,(\sin\psi_s, \cos\psi_s)

(odometer steps :math:`\ell_s`, headings :math:`\psi_s` from north, clockwise) must
point along :math:`p_j - p_i` and the odometer's path length :math:`\sum_s \ell_s` must be
about :math:`|p_j - p_i|` (at least it, a little more on a bend). :func:`check_drive`
takes the median over the chords of the angle between the two and of the length ratio;
a median angle over 30 degrees (unless a gyro's drift explains it: a heading right at the
start whose error grows steadily, by at most 1 deg/s, with the chords within 30 degrees of
that line) or a ratio outside [0.6, 1.8] is an error that names the
likely cause when one of the usual mistakes (degrees, counter-clockwise from east, km/h,
mph, kilometres, milliseconds, swapped lat/lon) would fit the fixes, and says how to
override (``checks=False``; ``--no-plausibility`` on the command line). A sample interval
over 2 s is refused by itself ("time looks like milliseconds"): dead-reckoning sensors
sample at 1-100 Hz, and fixes a median over :math:`\max(100\,\mathrm{m}, 30\sigma)` from
a given truth ("the fixes and the truth must share one frame"). Drives whose fixes never
move by :math:`L` are not judged on course and length.

A drive that passes can still have its heading's zero off by a constant (a phone mounted askew; a
magnetic heading, by the declination): the line through the chords' angles over time starts there.
Past :data:`HEADING_OFFSET_WARN_DEG` and the 0.1 % point of its t-statistic, from at least
:data:`WARN_MIN_CHORDS` chords (:func:`heading_offset`), the
check warns with the value and the reader's remedy (``heading_offset=``, ``--heading-offset``); a
refusal that such an offset explains names the same remedy. Likewise a median length ratio off 1 by
more than :data:`SPEED_SCALE_WARN` and the same point of its t-statistic (:func:`speed_scale`): a speed
that reads high (a speedometer's signal) is warned with the ratio and ``speed_scale=`` /
``--speed-scale``, which divides it out.

A drive whose fixes are stamped by another clock than its DR samples (GPS time leads UTC by 18 s) has every
chord compared with the wrong stretch of dead reckoning: :func:`clock_offset` moves the stretches by each
offset within :data:`CLOCK_OFFSET_SCAN_S` and finds the one the turns, starts and stops fit best (a sign test
over the chords, at the 0.1 % level over all the offsets tried). Past :data:`CLOCK_OFFSET_WARN_S` the check
warns with it and the reader's remedy (``gps_latency=``, ``--gps-latency``), in place of the offset and scale
warnings, which misplaced chords cannot judge; a refusal names it first.

Fixes whose reported accuracy (``gps_sigma``) has a median past :data:`SIGMA_UNIT_MIN` and
:data:`SIGMA_PAST_SCATTER` times the fixes' own scatter about the dead-reckoned track are refused as a
column not in metres (millimetres, centimetres, a variance): the filters would all but ignore them. A ``gps_hdop``
column whose median is past :data:`HDOP_AS_METRES_MIN` and whose sigma (times ``hdop_sigma``) is past
:data:`HDOP_PAST_SCATTER` times that scatter is warned of as an accuracy in metres (:func:`hdop_as_metres`).

Fixes that are not GNSS's but a receiver's own dead reckoning (an ADR module in a tunnel) move along the
dead-reckoned track as the odometer does, each step's length fitting the odometer's to millimetres where GNSS fixes
misfit it by decimetres: :func:`receiver_dead_reckoning` names runs of :data:`RECEIVER_DR_STEPS` such steps or more.

Fixes dragged away from the dead-reckoned track (a spoofer walking them off at a fraction of a metre a second, their
reported accuracy unchanged; a receiver's fault), which the filters follow: :func:`fix_drag` tests, in windows of
:data:`DRAG_WINDOW_S`, a world-fixed velocity of the fixes' offset beyond what the dead reckoning errs by (an offset, a
speed scale and latency, a heading offset, drift, gyro scale and latency, steps of the fixes), and the check warns of
a stretch where :data:`DRAG_MIN_WINDOWS` windows pass :data:`DRAG_LEVEL`, with the reader's remedy (``drop_fixes=``,
``--drop-fixes``).
"""

from __future__ import annotations

import warnings

import numpy as np

__all__ = ["check_drive", "heading_offset", "speed_scale", "clock_offset", "MAX_DT", "MAX_ANGLE_DEG",
           "MAX_DRIFT_DEG_S", "RATIO_RANGE", "HEADING_OFFSET_WARN_DEG", "SPEED_SCALE_WARN", "WARN_MIN_CHORDS",
           "CLOCK_OFFSET_WARN_S", "CLOCK_OFFSET_SCAN_S", "GPS_DERIVED_HELD", "GPS_DERIVED_AT_FIX",
           "GPS_DERIVED_AT_FIX_LINEAR", "GPS_DERIVED_SLOPE_TOL", "GPS_DERIVED_MIN_CHANGES", "TILTED_TURNS",
           "GPS_DERIVED_MIN_RATIO", "GPS_DERIVED_SPEED", "GPS_DERIVED_ROUNDING", "SIGMA_UNIT_MIN",
           "SIGMA_PAST_SCATTER", "HDOP_AS_METRES_MIN", "HDOP_PAST_SCATTER", "hdop_as_metres",
           "RECEIVER_DR_STEPS", "RECEIVER_DR_FRAC", "RECEIVER_DR_MOVING_M", "RECEIVER_DR_SIGMA_FALLS",
           "RECEIVER_DR_GROWS", "receiver_dead_reckoning", "heading_deviation", "HEADING_DEVIATION_WARN_DEG",
           "HEADING_DEVIATION_LEVEL", "DEVIATION_STRAIGHT_DEG", "DEVIATION_KNOT_S", "DEVIATION_CHORDS_PER_PARAMETER",
           "deviation_of", "carried", "CARRIED_MIN_S", "CARRIED_SPEED", "CARRIED_MIN_M", "fix_drag", "drag_windows",
           "DRAG_WINDOW_S", "DRAG_EVERY_S", "DRAG_LEVEL", "DRAG_MIN_SPEED", "DRAG_MIN_TURN_DEG", "DRAG_MIN_WINDOWS",
           "DRAG_STEPS", "DRAG_MARGIN_S", "DRAG_MIN_FIXES", "alternating_sources", "ALTERNATING_MIN_M",
           "ALTERNATING_Z", "ALTERNATING_MIN_PAIRS"]

#: The longest DR sample interval (s) accepted without ``checks=False``.
MAX_DT = 2.0
#: The largest median angle (degrees) between the dead-reckoned and the GPS chords.
MAX_ANGLE_DEG = 30.0
#: The fastest heading drift (deg/s) taken for a gyro's rate bias rather than a wrong heading:
#: a MEMS gyro's turn-on bias reaches about 0.7 deg/s.
MAX_DRIFT_DEG_S = 1.0
#: The accepted range of the median odometer path length over the GPS chord length.
RATIO_RANGE = (0.6, 1.8)
#: A heading offset at the start (deg) past which the drive reader warns: twice the phone grade's heading-bias
#: sigma (5 deg), the larger of the two grades'. The filters learn a heading bias from the fixes, but not
#: before the first ones, and one past their grade's bound slowly; the warning names the reader's remedy.
HEADING_OFFSET_WARN_DEG = 10.0
#: A speed (or odometer) scale off by more than this fraction makes the drive reader warn: twice the phone grade's
#: odometer-scale sigma (3 %), the larger of the two grades'. A speedometer's signal may read high by up to
#: 10 % (and 4 km/h) by regulation; a wheel-speed signal with the wrong tyre circumference by a few per cent.
SPEED_SCALE_WARN = 0.06
#: The fewest chords from which either of those is warned: their spread, which gives the estimates' standard
#: errors, is its own estimate only from that many (a city drive's first 90 s, 3 or 4 chords of 20 m fixes,
#: otherwise read speed scales of 0.86-1.17 at "+- 1 %").
WARN_MIN_CHORDS = 10
_MIN_CHORDS = 3
#: The peak (deg) of a heading error that turns with the direction of travel (a compass's deviation:
#: :func:`heading_deviation`), over the courses the drive drove, past which the drive reader warns: the phone grade's
#: heading-bias sigma (5 deg). The filters estimate one heading bias (and a gyro's drift of it); an error that changes
#: with every turn is neither, and each outage starts with the bias of the road before it.
HEADING_DEVIATION_WARN_DEG = 5.0
#: The level of the deviation's test (an F-test of its four coefficients beyond an offset, a drift and a scale):
#: 1e-4, under the 0.1 % of the reader's other tests, since the chords' errors are heavy-tailed (fixes jumped by
#: multipath) and correlated (a street's multipath): of 530 simulated drives without a deviation, 363 judged, one
#: read p = 0.0009 and 0.0011 (random drive 231 of protocols 3 and 2, 4 % of its fixes jumped, correlated over
#: 28 s), the next 0.067 (``docs/study-outputs/dr/user-trial/compass_null.txt``); the user trial's compass drives
#: read 5e-12 to 6e-15 (``compass.txt``).
HEADING_DEVIATION_LEVEL = 1e-4
#: A chord whose heading turns more than this (deg) between its fixes is left out of the deviation's fit: in a
#: turn the chord's angle depends on where on the arc its fixes fell (a roundabout's chords read 5-10 degrees).
DEVIATION_STRAIGHT_DEG = 15.0
#: The spacing (s) of the knots of the piecewise-linear drift the deviation is fitted beside: a gyro's heading drifts
#: with its rate bias, which moves over minutes (its bias instability); a deviation changes with every turn.
DEVIATION_KNOT_S = 120.0
#: The fewest chords a parameter of the deviation's fit needs (knots, scale and the four coefficients): fewer, and
#: the coefficients trade against the drift (a drive of two or three long straights): not judged.
DEVIATION_CHORDS_PER_PARAMETER = 5
#: A clock offset between the fixes and the DR samples (s) past which the drive reader warns. Until stop 60 it was 3 s,
#: the bound of the fixes' latency state that a GPS/DR filter adds when its monitor finds a latency (three of its 1 s
#: specification, :data:`filterwnn.navigation.gpsdr.DETECTED_LATENCY_SD`), taken for what the filters take; but they
#: take it only once the monitor has found it, and a u-blox log's sensor clock 2 s off GPS time ended its outages
#: 4.90 / 48.84 m off (EKF-8), 3.36 / 15.35 m with the offset the check finds (1.5 s) given, 3.56 / 15.06 m on time.
#: No drive with its fixes on time (the analogs' seeds 0-9, 220 random drives) shows a significant offset at all.
CLOCK_OFFSET_WARN_S = 1.0
#: The clock offsets tried (s, either way): GPS time leads UTC by 18 s (since 2017), and a logger that stamps
#: its fixes by one clock and its DR samples by the other carries that offset.
CLOCK_OFFSET_SCAN_S = 30.0
_CLOCK_STEP_S = 0.5
#: The level of the clock offset's test (the gate's, 0.1 %), over all the offsets tried (Bonferroni).
_CLOCK_LEVEL = 1e-3
#: A median ``gps_sigma`` (m) past which the fixes' own scatter is measured against it: no receiver's fixes report
#: that, per axis, over a whole drive; a column in millimetres (a u-blox ``hAcc``) or centimetres does.
SIGMA_UNIT_MIN = 50.0
#: The factor by which a median ``gps_sigma`` past :data:`SIGMA_UNIT_MIN` may exceed the fixes' scatter (the
#: median misfit of their stretches' lengths to the dead-reckoned track's, at least 1 m) before the column is
#: refused as not in metres. A sigma in millimetres is 500-1000 times it (the 1 Hz analog: 4.0 m of fixes reporting
#: 4000: the filters, all but ignoring them, ended its outages 81.62 / 143.69 m off, 1.63 / 6.28 with metres),
#: a variance of honest 3-10 m fixes 2-7 times.
SIGMA_PAST_SCATTER = 20.0
#: A median ``gps_hdop`` from which its fixes' sigma (times ``hdop_sigma``) is measured against their scatter
#: (:func:`hdop_as_metres`): an HDOP is about 1 under open sky, and only a city's canyons keep it past 3 over a
#: drive (the city analog's HDOPs are 2-8, their medians 3.15-4.4), where the fixes scatter as much; a phone's
#: accuracy in metres is 3-10.
HDOP_AS_METRES_MIN = 3.0
#: The factor by which the sigma of such a ``gps_hdop`` may exceed the fixes' scatter before the column is named
#: as an accuracy in metres. On the 250 drives at hand (``docs/study-outputs/dr/log-faults/hdop_as_metres.txt``)
#: each written with its HDOP gives at most 2.61 (the city analog's, of median HDOPs 3.15-4.4, among them; only
#: those past :data:`HDOP_AS_METRES_MIN` are tested), each with its 68 % radius in ``gps_hdop`` read at the phone
#: grade's 5 m at least 5.27 (an OBD-II user's Android log 15): 4 lies between, nearer the honest side, since a miss
#: costs (12.32 / 37.00 m against 6.80 / 17.53 on that log) and a false alarm is a warning.
HDOP_PAST_SCATTER = 4.0
#: What the reader's warning of a ``gps_hdop`` that looks like an accuracy in metres (:func:`hdop_as_metres`), and its
#: refusal of such a drive for another cause, say to do.
HDOP_METRES_REMEDY = ("an HDOP is about 1 under open sky; a column that holds an accuracy in metres (a phone's, Android's "
                      "Location accuracy, a 68 % radius) reads so: give it as gps_sigma, divided by 1.51 (a 68 % "
                      "radius; a 95 % one by 2.45); if it is an HDOP, pass the receiver's sigma at HDOP 1 as hdop_sigma "
                      "(--hdop-sigma)")
#: Fixes that move along the dead-reckoned track as its odometer does (:func:`receiver_dead_reckoning`): a run of at
#: least this many moving steps between fixes in a row, each step's length within :data:`RECEIVER_DR_FRAC` of the
#: drive's median misfit of what the step before's gives (its length over the odometer's, times this step's
#: odometer). A receiver's own dead reckoning in a tunnel (a u-blox ADR module's ``fixType`` 1) follows the same
#: wheels to millimetres a step (a u-blox user's log, stop 60: 0.0064 m, where its GNSS fixes misfit 0.54 m); on 273
#: drives at hand the longest such run of GNSS fixes is 5 steps (``docs/study-outputs/dr/log-faults/receiver_dr_0.txt``
#: and ``_1.txt``).
RECEIVER_DR_STEPS = 10
RECEIVER_DR_FRAC = 0.1
#: The odometer's path between two fixes (m) from which a step counts as moving: a fix repeated to the bit (a log or
#: a receiver holding its last one) is not a step either (the filters leave such fixes, ``n_stale``).
RECEIVER_DR_MOVING_M = 0.5
#: A run whose fixes' reported sigma falls at this many of them or more is not named: a GNSS receiver's accuracy
#: changes both ways (falling at about half its fixes), one's own dead reckoning's grows at every fix, or is held.
RECEIVER_DR_SIGMA_FALLS = 3
#: A run whose reported sigma rises at this share of its fixes at least is named as a receiver's own dead reckoning
#: (whose accuracy grows at every fix without GNSS: :data:`RECEIVER_DR_REMEDY`); one without a sigma, or whose sigma
#: is held, may also be GNSS fixes far cleaner than the drive's others (an RTK fix, open sky), and is named as either
#: (:data:`RECEIVER_DR_UNSURE`): 120 s of fixes with 0.03-0.1 m of noise among the analogs' are so named
#: (``docs/study-outputs/dr/log-faults/clean_stretch.txt``).
RECEIVER_DR_GROWS = 0.8
#: The least time (s) the speed reads 0 while the fixes move at :data:`CARRIED_SPEED` or more before the reader says
#: the car was carried (:func:`carried`): a standstill's fixes wander (multipath) and jump, but do not travel. A ferry
#: or a car train carries a car for minutes.
CARRIED_MIN_S = 60.0
#: The median speed (m/s) of the fixes, fix to fix, over such a stretch past which it is no crawl that a speed's
#: cutoff hides: such cutoffs read 0 under 0.3-1 m/s (a queue), and a car carried by a ferry or a car train moves at
#: several metres a second (a second new user's ferry crossing, stop 70: 5 m/s for 334 s, which the filters'
#: crawl test told as a crawl at 1 m/s in a queue, and followed with 16 re-acquisitions).
CARRIED_SPEED = 2.0
#: The least distance (m) the fixes move over such a stretch: past a standing car's multipath, whose street bias can
#: change while it stands (the city analog's seed 109 moved its fixes 103 m over a 42 s stop: p95 55 m each way).
CARRIED_MIN_M = 200.0
#: What the reader's warning of fixes that follow the odometer says where their sigma grows.
RECEIVER_DR_REMEDY = ("a receiver's own dead reckoning (a u-blox ADR/UDR module's fixType 1, gnssFixOK 0; NMEA GGA "
                      "quality 6, RMC mode E), not GNSS. The filters take them for fixes and follow them, and the "
                      "receiver's error at their end becomes theirs. Drop those rows (keep fixType 3 and 4 with "
                      "gnssFixOK 1; GGA quality 1, 2, 4 or 5): the filters dead-reckon across the gap themselves")
#: What it says where their sigma does not grow (:data:`RECEIVER_DR_GROWS`), or the drive gives none.
RECEIVER_DR_UNSURE = ("either a receiver's own dead reckoning (a u-blox ADR/UDR module's fixType 1, gnssFixOK 0; NMEA "
                      "GGA quality 6, RMC mode E), which the filters take for fixes and follow, or GNSS fixes far "
                      "cleaner than the drive's others (an RTK fix, open sky). Check the log's fix type at those "
                      "times: drop the dead-reckoned rows (the filters dead-reckon across the gap themselves); clean "
                      "GNSS fixes need nothing")
#: What the reader's refusal and the filter's warning of a ``gps_sigma`` not in metres say to do.
SIGMA_UNITS_REMEDY = ("gps_sigma is a standard deviation per axis in metres; a column in millimetres (a u-blox "
                      "hAcc) is divided by 1000, one in centimetres by 100, and a variance (m^2) is given as its "
                      "square root")
_OVERRIDE = "; if the drive really is so, pass checks=False (command line: --no-plausibility)"
#: A heading or speed held between the fixes and changing only at them (a receiver's course or Doppler speed
#: logged on every DR row) is warned of where, while the car moves (:data:`GPS_DERIVED_SPEED` m/s), it is held
#: over at least :data:`GPS_DERIVED_HELD` of the intervals and at least :data:`GPS_DERIVED_AT_FIX` of its
#: changes come at a fix's sample or the one beside it, over :data:`GPS_DERIVED_MIN_CHANGES` changes or more,
#: with at least :data:`GPS_DERIVED_MIN_RATIO` samples per fix (by chance, at most 3 in that many changes
#: come beside a fix: the analogs' gyro headings and speeds, written to 4 decimals, are held over 0-1 % of their
#: moving intervals and change beside a fix at that chance, 20 % at 10 Hz).
GPS_DERIVED_HELD = 0.5
GPS_DERIVED_AT_FIX = 0.9
GPS_DERIVED_MIN_CHANGES = 30
GPS_DERIVED_MIN_RATIO = 5
GPS_DERIVED_SPEED = 2.0
#: With fixes every 2 to :data:`GPS_DERIVED_MIN_RATIO` samples (a 5 Hz receiver on a 10 Hz log: stop 59), a change
#: beside a fix is no sign, so the changes are counted at the fix's own sample (1 in 2-4 by chance), and the values
#: held over at least :data:`GPS_DERIVED_HELD` of the samples between fixes; with a fix on nearly every sample
#: (fewer than this many samples per fix) there is nothing to tell.
GPS_DERIVED_FAST_RATIO = 1.5
#: A column interpolated between the fixes (a receiver's 1 Hz speed on a 10 Hz log: a u-blox user's gSpeed, stop
#: 61) is found as one held, on its slope (its change from sample to sample): held over :data:`GPS_DERIVED_HELD` of
#: the moving intervals, with at least this share of its changes at a fix (lower than :data:`GPS_DERIVED_AT_FIX`:
#: a receiver that goes on giving its speed in a tunnel, with no fix, puts knots there; the u-blox log's 90 %, the
#: analogs' and that log's wheel speeds 27-29 %, chance), and a change only past :data:`GPS_DERIVED_SLOPE_TOL`
#: (relative; a CSV's 10 digits and the reader's arithmetic leave slopes that differ by 1e-9).
GPS_DERIVED_AT_FIX_LINEAR = 0.8
GPS_DERIVED_SLOPE_TOL = 1e-6
#: ... and, in a column written to a few decimals, only past this many of its steps (:func:`_resolution`): each
#: value rounded by up to half a step moves the slope between neighbours by up to two (stop 64: the OBD-II user's
#: GNSS speed, written ``%.3f``, and the u-blox test's written so, changed slope at every sample by its rounding).
GPS_DERIVED_ROUNDING = 2.0
#: Length-ratio mistakes: (factor the ratio shows, the likely cause).
_SCALES = ((3.6, "speed looks like km/h (divide by 3.6 for m/s, or pass speed_scale=3.6: --speed-scale 3.6)"),
           (1 / 0.3048, "speed looks like ft/s (multiply by 0.3048 for m/s, or pass speed_scale=3.281: "
                        "--speed-scale 3.281)"),
           (1 / 0.44704, "speed looks like mph (multiply by 0.44704 for m/s, or pass speed_scale=2.237: "
                         "--speed-scale 2.237)"),
           (1 / 0.514444, "speed looks like knots (multiply by 0.514444 for m/s, or pass speed_scale=1.944: "
                          "--speed-scale 1.944)"),
           (1 / 1000.0, "the odometer looks like kilometres (multiply by 1000 for m)"),
           (100.0, "speed looks like cm/s (divide by 100 for m/s), or the odometer like centimetres"),
           (1000.0, "speed looks like mm/s (divide by 1000 for m/s; u-blox's gSpeed), or the odometer like "
                    "millimetres, or time like milliseconds (divide by 1000 for s)"))
#: The factor within which :func:`_ratio_cause` names a mistake of :data:`_SCALES` near 1, and
#: :func:`_per_sample_cause` a length ratio at the sample interval.
_UNIT_TOLERANCE = 1.25
#: The factor within which :func:`_ratio_cause` names a mistake of :data:`_SCALES` a decade or more from 1
#: (:func:`_decade_off`; those nearer 1 are named within :data:`_UNIT_TOLERANCE`). Between fixes a second apart
#: the fixes' noise lengthens the chord, so a speed in mm/s shows 784 (the phone-log drive of
#: ``tests/navigation/test_phone_log.py``), in cm/s 82.
_DECADE_TOLERANCE = 2.0
#: A second mistake of :data:`_SCALES` is named beside the nearest (:func:`_ratio_cause`) where it fits the length
#: ratio within this factor of how well the nearest does: a car's speed may itself read several per cent off (a
#: speedometer's signal up to 10 % high), and km/h (3.6) and ft/s (3.28) lie 9.7 % apart, mph (2.24) and knots
#: (1.94) 15 %. On the 250 drives at hand (stop 65, ``docs/study-outputs/dr/log-faults/speed_units.txt``), their
#: speeds in each unit, the ratio (:func:`_unit_ratio`) read 0.88-1.11 of the unit's factor, 95 % of them
#: 0.93-1.03, the random drives' own odometer faults included.
_UNIT_EITHER = 1.05
#: :data:`_DECADE_TOLERANCE` where the ratio was measured again over at least :data:`WARN_MIN_CHORDS` stretches that
#: long on the road (:func:`_unit_ratio`), no longer read low by the fixes' noise: a wheel-tick count of 50 a metre
#: is not named centimetres (a speed in cm/s measured so read 0.68-1.03 of 100 on 95 % of the drives at hand).
_DECADE_TOLERANCE_AGAIN = 1.5


#: Time units a DR sample interval over :data:`MAX_DT` seconds may be written in: (the factor from seconds, the
#: unit). A ROS log's stamps are nanoseconds since the epoch (an int64), a CAN logger's often microseconds.
_TIME_UNITS = ((1e9, "nanoseconds"), (1e6, "microseconds"), (1e3, "milliseconds"))


def interval_refusal(dt):
    """The words refusing a DR sample interval of ``dt`` s past :data:`MAX_DT`, naming the unit the time looks
    written in: the one that makes the interval 1-100 Hz's (the largest whose interval is at least 0.005 s)."""
    cause = "resample the drive"
    if dt >= 10:
        factor, unit = next(((f, u) for f, u in _TIME_UNITS if dt / f >= 0.005), _TIME_UNITS[-1])
        cause = (f"time looks like {unit} (divide by {factor:.0e} for s".replace("e+0", "e") + f": a {dt / factor:.3g} "
                 "s interval)")
    return (f"plausibility: the DR sample interval is {dt:.3g} s, longer than {MAX_DT:g} s (dead-reckoning sensors "
            f"sample at 1-100 Hz): {cause}{_OVERRIDE}")


def _chords(n, apart):
    """Index pairs ``(i, j)`` of ``n`` fixes with ``apart(i, j)`` (far enough apart), each starting where the
    last ended."""
    pairs, i = [], 0
    for j in range(1, n):
        if apart(i, j):
            pairs.append((i, j))
            i = j
    return pairs


def _chord_pairs(steps, z_gps, sigma, step):
    """The chords of a drive whose fixes have the typical ``sigma`` (m; None: 3): ``L = max(20 m, 8 sigma)``
    of odometer path between their fixes, so the fixes' noise is small against them (see the module
    docstring); chords at least ``L`` apart by the fixes' own distance where the odometer gives fewer than
    three (an odometer in kilometres).

    Not chosen by the fixes' distance first: a chord that ends at the first fix past ``L`` is chosen by the
    fixes' errors, longer than the car drove (5 Hz fixes read a speed 6-9 % low), and a fix jumped 20-80 m by
    multipath ends one at once (at 3-10 m/s, 6.6 % of such fixes made the median ratio 0.5, and the drive
    was refused)."""
    pairs = _odometer_chords(steps, sigma, step)
    if len(pairs) >= _MIN_CHORDS:
        return pairs
    min_len = _chord_length(sigma)
    return _chords(len(steps), lambda i, j: np.hypot(*(z_gps[j] - z_gps[i])) >= min_len)


def _chord_length(sigma):
    """``L = max(20 m, 8 sigma)`` (``sigma`` None: 3 m), the least length of a chord (:func:`_chord_pairs`)."""
    return max(20.0, 8.0 * (3.0 if sigma is None else float(sigma)))


def _odometer_chords(steps, sigma, step, longer=1.0):
    """The chords of at least ``longer`` times :func:`_chord_length` of odometer path between their fixes."""
    min_len = _chord_length(sigma) * longer
    path = np.r_[0.0, np.cumsum(step)][np.asarray(steps, dtype=int) + 1]  # the fix at step k is sample k + 1
    return _chords(len(steps), lambda i, j: path[j] - path[i] >= min_len)


def _unwrap(ang, k=5):
    """The angles ``ang`` (rad) unwrapped, each taken within pi of the median of the ``k`` before it: numpy's
    unwrap takes each within pi of the one before, so one chord pointing anywhere (a fix jumped by
    multipath) shifts all that follow by a turn."""
    out = np.array(ang, dtype=float)
    for i in range(1, len(out)):
        ref = np.median(out[max(0, i - k):i])
        out[i] = ref + (out[i] - ref + np.pi) % (2 * np.pi) - np.pi
    return out


def _medians(ang, ratio):
    """Median absolute angle (degrees) between the DR and GPS chords, and median path/chord length ratio."""
    return float(np.degrees(np.median(np.abs(ang)))), float(np.median(ratio))


def _scores(heading, step, steps, z_gps, pairs):
    """:func:`_medians` of the chords with this heading and these fixes."""
    return _medians(*_chord_angles(heading, step, steps, z_gps, pairs)[:2])


def _track(heading, step):
    """The dead-reckoned track ``(2, n_samples)``: east and north of each sample from the first, the odometer's
    steps along the headings."""
    return np.stack([np.r_[0.0, np.cumsum(step * np.sin(heading[1:]))], np.r_[0.0, np.cumsum(step * np.cos(heading[1:]))]])


def _chord_samples(steps, pairs):
    """The samples at each chord's two fixes ``(first, last)`` (the fix at step ``k`` is sample ``k + 1``)."""
    return np.array([steps[i] + 1 for i, _ in pairs]), np.array([steps[j] + 1 for _, j in pairs])


def _chord_vectors(heading, step, steps, z_gps, pairs):
    """Per chord, the dead-reckoned displacement and the fixes' ``(n_chords, 2)`` (east, north, m)."""
    cum_e, cum_n = _track(heading, step)
    a, b = _chord_samples(steps, pairs)
    return (np.stack([cum_e[b] - cum_e[a], cum_n[b] - cum_n[a]], axis=1),
            np.stack([z_gps[j] - z_gps[i] for i, j in pairs]))


def _chord_angles(heading, step, steps, z_gps, pairs):
    """Per chord, the signed angle (rad, in ``[-pi, pi)``) from the GPS chord to the DR one, and
    the path/chord length ratio, and the ratio of the dead-reckoned displacement's length to the chord's (a
    speed scale, which a bend does not lengthen as it does the path)."""
    cum_l = np.r_[0.0, np.cumsum(step)]
    a, b = _chord_samples(steps, pairs)
    dr, gps = _chord_vectors(heading, step, steps, z_gps, pairs)
    ang = np.arctan2(dr[:, 0], dr[:, 1]) - np.arctan2(gps[:, 0], gps[:, 1])
    chord = np.hypot(gps[:, 0], gps[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):  # a fix re-sent (stale) while the car moved: inf
        ratio, length = (cum_l[b] - cum_l[a]) / chord, np.hypot(dr[:, 0], dr[:, 1]) / chord
    return (ang + np.pi) % (2 * np.pi) - np.pi, ratio, length


#: A change of the fixes' course over :data:`TURN_CHORDS` chords (deg) that :func:`_turn_ratio` counts as a turn (a
#: chord is at least 8 sigma of the fixes long, so their noise turns it by about 10 degrees).
TURN_DEG = 45.0
#: The chords over which :func:`_turn_ratio` takes each change of direction.
TURN_CHORDS = 4
#: The turns :func:`_turn_ratio` needs for a slope.
MIN_TURNS = 5


def _median3(x):
    """Each value of ``x`` replaced by the median of it and its two neighbours (the ends kept)."""
    if len(x) < 3:
        return x
    return np.r_[x[0], np.median(np.stack([x[:-2], x[1:-1], x[2:]]), axis=0), x[-1]]


def _turn_ratio(heading, step, steps, z_gps, pairs):
    """How much the dead-reckoned course turns where the fixes' course turns: ``(slope, turns)``, the least-squares
    slope through 0 of the dead-reckoned chords' change of direction over :data:`TURN_CHORDS` chords against the
    fixes' chords', over the ``turns`` changes of the fixes' of :data:`TURN_DEG` to 180 less it (1 for a heading
    that follows the car, 0 for one that does not turn); ``(nan, turns)`` with fewer than :data:`MIN_TURNS`."""
    dr, gps = [np.arctan2(v[:, 0], v[:, 1]) for v in _chord_vectors(heading, step, steps, z_gps, pairs)]
    # each direction unwrapped (:func:`_unwrap`) and the median of it and its neighbours (a chord to or from a fix
    # jumped by multipath points anywhere, and is left out so), then its change over TURN_CHORDS chords (a turn
    # spreads over several), in windows that do not overlap
    dd, dg = [np.diff(_median3(_unwrap(x))[::TURN_CHORDS]) for x in (dr, gps)]
    # turns of 45-135 degrees, the dead-reckoned one taken within half a turn of the fixes' (each unwrapped on its
    # own, one U-turn read -170 and the other +176 degrees; a turn of half a turn either way is left out)
    big = (np.abs(dg) >= np.deg2rad(TURN_DEG)) & (np.abs(dg) <= np.pi - np.deg2rad(TURN_DEG))
    dd = dg + (dd - dg + np.pi) % (2 * np.pi) - np.pi
    turns = int(big.sum())
    if turns < MIN_TURNS:
        return float("nan"), turns
    return float(dd[big] @ dg[big] / (dg[big] @ dg[big])), turns


#: A dead-reckoned course that turns less than this share of the fixes' turns (:func:`_turn_ratio`) does not follow
#: the car: a gyro's wrong axis (a phone upright on a dashboard, its z axis given, read and scored 122.84 / 809.64
#: m at the outage ends: 0.09 of the turns; stop 58). The headings of the analogs (seeds 0-9), of the random
#: drives of protocols 2 and 3 (seeds 200-279, multipath, drifting gyros, every fault) and of two new users' logs
#: turn 0.68-1.15 of them, where they have five turns (182 drives).
STILL_TURNS = 0.3


#: A yaw rate's integral that does not follow the car's turns (:data:`STILL_TURNS`) but, multiplied by ``180 / pi``,
#: turns as the fixes do within this factor (:func:`_turn_ratio`), is a rate in rad/s given as deg/s
#: (``yaw_rate_deg``): a ROS log's ``angular_velocity.z`` (stop 59; the right conversions turned 0.68-1.15 of them).
YAW_UNIT_TOLERANCE = 1.5


#: A dead-reckoned course that turns at least :data:`STILL_TURNS` but less than this share of the fixes' turns is
#: warned of as a gyro axis tilted off the vertical, which turns with cos(tilt) of the car (stop 61: an OBD-II user's
#: phone reclined 30 degrees in its mount, its screen's axis given, 0.45 of the turns; the careful conversion and
#: the axis nearest the vertical 0.87, and the right conversions of stop 58's 182 drives 0.68-1.15: the ratio reads
#: low by the fixes' noise, so only a tilt past about 45 degrees shows here; a smaller one the filters' scale
#: monitor tells, ``TILT_SCALE``).
TILTED_TURNS = 0.6


def _warn_tilted(heading, step, steps, z_gps, pairs):
    """Warn of a course that turns :data:`STILL_TURNS` to :data:`TILTED_TURNS` of the fixes' turns."""
    slope, turns = _turn_ratio(heading, step, steps, z_gps, pairs)
    if not STILL_TURNS <= slope < TILTED_TURNS:
        return
    warnings.warn(f"plausibility: over {turns} turns of the fixes' course ({TURN_DEG:g} degrees or more over "
                  f"{TURN_CHORDS} moving stretches between fixes), the dead-reckoned course turned {slope:.2g} times "
                  "as much: a gyro axis tilted far off the vertical reads so (it turns with cos(tilt) of the car's "
                  "turns: a phone in a reclined mount, the axis out of its screen given), and the filters read it as a "
                  "gyro scale error far past any sensor's, a rate bias, or the car reversing. Rotate the gyro's rates "
                  "onto the vertical (the accelerometer's gravity, averaged while the car stands, gives it) and give "
                  "that rate", RuntimeWarning, stacklevel=5)


def _not_turning(heading, step, steps, z_gps, pairs):
    """``(slope, turns)`` of :func:`_turn_ratio` for a heading that follows the car's turns neither way (under
    :data:`STILL_TURNS`), else None: one that turns the wrong way is named so elsewhere (a right-angle turn the wrong
    way reads as any ratio, and so does it magnified)."""
    slope, turns = _turn_ratio(heading, step, steps, z_gps, pairs)
    if not slope < STILL_TURNS or not _turn_ratio(-heading, step, steps, z_gps, pairs)[0] < STILL_TURNS:
        return None  # (nan: too few turns)
    return slope, turns


def _yaw_unit_cause(heading, step, steps, z_gps, pairs):
    """The words for a yaw rate in rad/s read as deg/s (its integral turns ``pi / 180`` of the fixes' turns, within a
    factor :data:`YAW_UNIT_TOLERANCE`), or ``""``."""
    found = _not_turning(heading, step, steps, z_gps, pairs)
    if found is None:
        return ""
    slope, turns = found
    scaled = _turn_ratio(np.unwrap(heading) * (180.0 / np.pi), step, steps, z_gps, pairs)[0]
    if not abs(np.log(scaled)) < np.log(YAW_UNIT_TOLERANCE):
        return ""
    return (f"over {turns} turns of the fixes' course ({TURN_DEG:g} degrees or more over {TURN_CHORDS} moving "
            f"stretches between fixes), the yaw rate's integral turned {slope:.2g} times as much, and {scaled:.2g} "
            "times as much read as radians a second: the "
            "yaw rate looks like radians a second given as degrees a second (a ROS Imu's angular_velocity.z is in "
            "rad/s): give it as yaw_rate, clockwise positive (its negative, for a rate counter-clockwise as ROS and "
            "ENU frames write it)")


def _still_cause(heading, step, steps, z_gps, pairs):
    """The words for a heading that does not follow the car's turns (:data:`STILL_TURNS`), or ``""``."""
    found = _not_turning(heading, step, steps, z_gps, pairs)
    if found is None:
        return ""
    slope, turns = found
    return (f"over {turns} turns of the fixes' course ({TURN_DEG:g} degrees or more over {TURN_CHORDS} moving "
            f"stretches between fixes), the dead-reckoned course turned {slope:.2g} times as much: the heading does "
            "not follow the car's turns. A gyro's wrong axis reads so (a phone upright on a dashboard mount turns with "
            "the car about its y axis, one lying flat about its z: give the rate about the axis nearest the "
            "vertical), or a column that holds another angle (a pitch or a roll)")


def _fix_scatter(heading, step, steps, z_gps):
    """The fixes' scatter about the dead-reckoned track (m) and the stretches measured, or None with fewer than
    :data:`_MIN_CHORDS`: the median misfit of each stretch's fix-to-fix length to the dead-reckoned
    displacement's (scaled by their median ratio), which a heading's zero or sign does not change; the stretches
    are those of fixes of 3 m."""
    pairs = _chord_pairs(steps, z_gps, None, step)
    if len(pairs) < _MIN_CHORDS:
        return None
    dr, gps = _chord_vectors(heading, step, steps, z_gps, pairs)
    d, g = np.hypot(*dr.T), np.hypot(*gps.T)
    ok = d > 0
    if ok.sum() < _MIN_CHORDS:
        return None
    scale = float(np.median(g[ok] / d[ok]))
    return float(np.median(np.abs(g[ok] - scale * d[ok]))), len(pairs)


def _sigma_unit(heading, step, steps, z_gps, sigma):
    """The refusal's words where the fixes' median reported ``sigma`` (m) is past :data:`SIGMA_UNIT_MIN` and
    :data:`SIGMA_PAST_SCATTER` times their scatter (:func:`_fix_scatter`), else None."""
    if sigma is None or not sigma > SIGMA_UNIT_MIN:
        return None
    past = _past_scatter(heading, step, steps, z_gps, sigma, SIGMA_PAST_SCATTER)
    return past and f"the fixes' median gps_sigma is {sigma:.4g} m, {past}: {SIGMA_UNITS_REMEDY}"


def _past_scatter(heading, step, steps, z_gps, sigma, factor):
    """Where a claimed ``sigma`` (m) is past ``factor`` times the fixes' scatter (:func:`_fix_scatter`, at least
    1 m), the words that say by how much and over what ("N times what they scatter about ..."); else None."""
    found = _fix_scatter(heading, step, steps, z_gps)
    if found is None:
        return None
    scatter, n = found
    if sigma <= factor * max(scatter, 1.0):
        return None
    return (f"{sigma / max(scatter, 1.0):.0f} times what they scatter about the dead-reckoned track (over {n} moving "
            f"stretches between fixes, their lengths agree with it to {scatter:.2g} m, median)")


def hdop_as_metres(run, hdop_sigma):
    """The warning's words where a drive's ``gps_hdop`` column looks like an accuracy in metres, else None.

    ``run``: the :class:`~filterwnn.navigation.scenarios.DRRun` read with each fix's sigma its HDOP times
    ``hdop_sigma`` (m). An HDOP is about 1 under open sky and 2-8 in a city's canyons, whose fixes scatter as
    much; a phone's accuracy (a 68 % radius, 3-10 m) written there makes each fix claim ``hdop_sigma`` times
    that, several times what the fixes scatter about the dead-reckoned track (:func:`_fix_scatter`): where the
    median HDOP is at least :data:`HDOP_AS_METRES_MIN` and the sigma it gives is past :data:`HDOP_PAST_SCATTER`
    times that scatter, the column is named (a new user's phone + OBD-II log, stop 62: EKF-8 12.32 / 37.00 m at
    the outage ends against 6.80 / 17.53 with the accuracy as gps_sigma)."""
    if run.gps_sigma is None or not len(run.gps_sigma):
        return None
    sigma = float(np.median(run.gps_sigma))
    hdop = sigma / hdop_sigma
    if hdop < HDOP_AS_METRES_MIN:
        return None
    heading = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]]  # (the first sample's heading is not kept: its second's)
    past = _past_scatter(heading, run.z_dr[:, 1], run.gps_steps, run.z_gps, sigma, HDOP_PAST_SCATTER)
    return past and (f"plausibility: the fixes' gps_hdop has a median of {hdop:.3g}, which times hdop_sigma "
                     f"({hdop_sigma:g} m at HDOP 1) makes each fix claim a sigma of {sigma:.3g} m, {past}: the "
                     f"filters then weigh them far too little; {HDOP_METRES_REMEDY}")


def _run_bounds(flags):
    """``(starts, ends)``: each run of True values of ``flags`` (boolean) is ``[start, end)``, in order."""
    edges = np.diff(np.r_[0, flags.astype(np.int8), 0])
    return np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)


def _runs(flags, least):
    """``(first, last)`` index of each run of at least ``least`` True values of ``flags``, in order."""
    return [(int(a), int(b) - 1) for a, b in zip(*_run_bounds(flags)) if b - a >= least]


def _follow_misfits(step, steps, z_gps):
    """Per step between fixes (fixes ``i``, ``i + 1``), the misfit of its length (m) to the odometer's path times
    the step before's ratio (inf where either step is not moving, :data:`RECEIVER_DR_MOVING_M`), and the median
    of those finite; None where fewer than ``3 *`` :data:`RECEIVER_DR_STEPS` are."""
    steps = np.asarray(steps, dtype=int)
    if len(steps) < 3 * RECEIVER_DR_STEPS:
        return None
    d = np.diff(np.r_[0.0, np.cumsum(step)][steps + 1])
    g = np.hypot(*np.diff(np.asarray(z_gps, dtype=float), axis=0).T)
    moving = (d >= RECEIVER_DR_MOVING_M) & (g > 0.0)
    both = moving[1:] & moving[:-1]
    misfit = np.full(len(d), np.inf)
    misfit[1:][both] = np.abs(g[1:][both] - d[1:][both] * g[:-1][both] / d[:-1][both])
    finite = np.isfinite(misfit)
    if finite.sum() < 3 * RECEIVER_DR_STEPS:
        return None
    return misfit, float(np.median(misfit[finite]))


def receiver_dead_reckoning(t, step, steps, z_gps, sigma=None):
    """The warning's words where runs of fixes move along the dead-reckoned track as its odometer does, else None.

    ``t``: the DR samples' times (s; the fix at step ``k`` is sample ``k + 1``); ``step``: the odometer's distance
    between samples (m); ``steps``, ``z_gps``: the fixes' steps and east/north (m); ``sigma``: their reported sigmas
    (m), or None. GNSS fixes scatter about the track: between fixes a second apart, the length of each step
    between them misfits the odometer's path times the step before's ratio by tens of centimetres (their errors'
    change; :func:`_follow_misfits`). A receiver that goes on giving positions without GNSS (its own dead
    reckoning, from the same wheels) misfits it by millimetres. Where at least :data:`RECEIVER_DR_STEPS` moving
    steps in a row misfit by under :data:`RECEIVER_DR_FRAC` of the drive's median, those fixes are named, with the
    time of each such run (runs that share a fix, one) and the longest's sigma's course: a receiver's accuracy
    grows at every fix without GNSS (:data:`RECEIVER_DR_GROWS`), and a run whose sigma does not grow may be GNSS
    fixes far cleaner than the others, which the words say; a run whose sigma falls at
    :data:`RECEIVER_DR_SIGMA_FALLS` of its fixes or more is GNSS's. Only the lengths are compared: the heading's
    zero, its drift and the speed's scale do not enter."""
    found = _follow_misfits(step, steps, z_gps)
    if found is None or not found[1] > 0.0:
        return None
    misfit, spread = found
    fixes = []
    for a, b in _runs(misfit <= RECEIVER_DR_FRAC * spread, RECEIVER_DR_STEPS):  # misfit[a..b]: fixes a - 1 .. b + 1
        if fixes and a - 1 <= fixes[-1][1]:
            fixes[-1] = (fixes[-1][0], b + 1)
        else:
            fixes.append((a - 1, b + 1))
    if sigma is not None and len(sigma) == len(steps):  # (GNSS's accuracy changes both ways, a receiver's own grows)
        sigma = np.asarray(sigma, dtype=float)
        fixes = [(i, j) for i, j in fixes if np.sum(np.diff(sigma[i:j + 1]) < 0.0) < RECEIVER_DR_SIGMA_FALLS]
    else:
        sigma = None
    if not fixes:
        return None
    inside = float(np.median(np.concatenate([misfit[i + 1:j] for i, j in fixes])))
    steps = np.asarray(steps, dtype=int)
    when = [f"t = {t[steps[i] + 1]:g}-{t[steps[j] + 1]:g} s" for i, j in fixes]
    if len(when) > 5:
        when = when[:5] + [f"and {len(when) - 5} more"]
    i, j = max(fixes, key=lambda f: f[1] - f[0])
    if sigma is None:
        course, grows = "; the drive gives no gps_sigma", False
    else:
        change = np.diff(sigma[i + 1:j])  # (a run's first and last fix may be GNSS fixes on its line)
        grows = bool(np.mean(change > 0.0) >= RECEIVER_DR_GROWS)
        course = (f"; the gps_sigma of the longest {'grows' if grows else 'does not grow'} ({int(np.sum(change > 0))} "
                  f"of its {len(change)} changes up: {sigma[i + 1]:.3g} -> {sigma[j - 1]:.3g} m)")
    return (f"plausibility: {sum(j - i + 1 for i, j in fixes)} fixes in {len(fixes)} run(s) of "
            f"{RECEIVER_DR_STEPS} moving steps or more ({', '.join(when)}) move along the dead-reckoned track as "
            f"the odometer does: each step's length misfits the odometer's path (times the step before's ratio) by "
            f"{inside:.2g} m, median, where the drive's fixes misfit it by {spread:.2g} m{course}"
            + (f", as a receiver's accuracy does without GNSS: {RECEIVER_DR_REMEDY}" if grows else
               f": {RECEIVER_DR_UNSURE}"))


def _inliers(residuals):
    """The chords within three robust sigmas (1.4826 times the median absolute residual, rad) of a fit, and at least
    within a degree of it: a chord from a fix jumped by multipath points anywhere."""
    r = np.abs(residuals)
    return r <= max(3.0 * 1.4826 * np.median(r), np.deg2rad(1.0))


def _offset_fit(ang, steps, pairs, dt):
    """The line through the chords' signed angles ``ang`` (:func:`_chord_angles`') over time: ``(offset
    (deg) at the first chord, its standard error (deg), rate (deg/s), median absolute residual (deg), chords
    fitted)``. Least squares, then again without the chords past three robust sigmas (1.4826 times the median
    absolute residual) of the first line: a chord from a fix jumped by multipath points anywhere, and a few
    of them had doubled the offset's standard error on a city drive of 25 chords."""
    ang = _unwrap(ang)
    off0 = np.round(np.median(ang[:5]) / (2 * np.pi)) * 2 * np.pi  # the unwrapped line starts within +-pi
    t = dt * np.array([0.5 * (steps[i] + steps[j]) for i, j in pairs])
    t, a = t - t[0], ang - off0
    (rate, offset), cov = np.polyfit(t, a, 1, cov=True)
    r = np.abs(a - offset - rate * t)
    resid = np.median(r)
    keep = _inliers(r)  # a chord from a jumped fix leaves the fit
    n = len(keep)
    if 4 <= keep.sum() < n:
        (rate, offset), cov = np.polyfit(t[keep], a[keep], 1, cov=True)
        n = int(keep.sum())
    return (float(np.degrees(offset)), float(np.degrees(np.sqrt(cov[1, 1]))), float(np.degrees(rate)),
            float(np.degrees(resid)), n)


def _drifting_gyro(fit):
    """Whether a gyro's drift explains the chords' angles (``fit``: :func:`_offset_fit`'s): a heading right
    at the start whose error grows at a steady rate (an integrated rate bias, up to
    :data:`MAX_DRIFT_DEG_S`), about which the chords scatter by at most :data:`MAX_ANGLE_DEG` (median)."""
    offset, _, rate, resid = fit[:4]
    return abs(offset) <= MAX_ANGLE_DEG and abs(rate) <= MAX_DRIFT_DEG_S and resid <= MAX_ANGLE_DEG


def _past(n, dof):
    """The two-sided 0.1 % point (the gate's level) of Student's t with ``dof`` degrees of freedom, for an
    estimate from ``n`` chords whose standard error is estimated from their spread; inf under
    :data:`WARN_MIN_CHORDS`."""
    from scipy.stats import t

    return float(t.ppf(1.0 - 0.5e-3, dof)) if n >= WARN_MIN_CHORDS else np.inf


def _offset_told(fit):
    """The heading's offset a warning or refusal names, or None: a line of the chords' angles over time
    (``fit``: :func:`_offset_fit`'s; a gyro's drift at most :data:`MAX_DRIFT_DEG_S`, the chords within
    :data:`MAX_ANGLE_DEG` of it) through ``n`` chords (those it fitted, at least :data:`WARN_MIN_CHORDS`)
    that starts past :data:`HEADING_OFFSET_WARN_DEG` and past the 0.1 % point of its t-statistic (``n - 2``
    degrees of freedom)."""
    offset, se, rate, resid, n = fit
    if (abs(rate) <= MAX_DRIFT_DEG_S and resid <= MAX_ANGLE_DEG
            and abs(offset) > max(HEADING_OFFSET_WARN_DEG, _past(n, n - 2) * se)):
        return offset
    return None


def _offset_remedy(offset, se, rate, filters=False):
    """What a warning (``filters``: with what the filters do about it) or a refusal says of the offset."""
    wrapped = (offset + 180.0) % 360.0 - 180.0
    why = ("The GPS/DR filters learn a heading bias from the fixes, but not before the first ones, and one past "
           "their grade slowly (the phone grade's: 5 deg, one sigma). " if filters else "")
    return (f"the dead-reckoned course starts {wrapped:+.0f} +- {se:.1g} degrees off the fixes' (a line through "
            f"the stretches' angles over time, drifting {rate:+.2g} deg/s from there): a heading whose zero is off "
            "(a phone mounted askew; a magnetic heading, by the declination) reads that much more than the car's "
            f"course. {why}If the offset is the heading's, pass heading_offset={wrapped:.0f} (command line: "
            f"--heading-offset {wrapped:.0f}), which subtracts it")


def _scale_fit(ratio):
    """The chords' median length ratio and its standard error (both of the log; the median's
    ``1.2533 * 1.4826 MAD / sqrt(n)``): ``(ratio, se)``. A chord with no dead-reckoned displacement (the car
    stood while a fix jumped, where the chords come from the fixes' distance) has the log ``-inf``: the lowest
    ratio, which the median and its absolute deviation take as such."""
    with np.errstate(divide="ignore"):
        lr = np.log(ratio)
    med = float(np.median(lr))
    return float(np.exp(med)), float(1.2533 * 1.4826 * np.median(np.abs(lr - med)) / np.sqrt(len(lr)))


def speed_scale(dt, heading, step, steps, z_gps, sigma=None):
    """How much longer the dead-reckoned displacement is than the GPS fixes' over the same stretch: ``(ratio,
    standard error of its log)``, or None with fewer than three chords. The median over the chords (see the
    module docstring) of the straight-line lengths, which a bend shortens alike (the odometer's path, longer
    on a bend, read a city drive's speed 10 % high); the fixes' own noise lengthens a chord by a per cent or
    two. The arguments are :func:`check_drive`'s."""
    pairs = _chord_pairs(steps, z_gps, sigma, step)
    if len(pairs) < _MIN_CHORDS:
        return None
    return _scale_fit(_chord_angles(heading, step, steps, z_gps, pairs)[2])


def _warn_scale(ratio, n):
    """Warn of a speed scale past :data:`SPEED_SCALE_WARN` and the 0.1 % point of its t-statistic (``n - 1``
    degrees of freedom; at least :data:`WARN_MIN_CHORDS` chords), with the remedy; one past 1.5 that a unit of
    :data:`_SCALES` fits (:func:`_ratio_cause`: knots, whose 1.94 a speed reading 8 % low brings inside the
    reader's range, stop 65) names the unit first."""
    r, se = _scale_fit(ratio)
    if abs(np.log(r)) <= max(np.log1p(SPEED_SCALE_WARN), _past(n, n - 1) * se):
        return
    found = (f"plausibility: over {n} moving stretches between GPS fixes, the dead-reckoned distance is {r:.3g} "
             f"times the fixes' (median, +- {100 * se:.1g} %)")
    remedy = (f"if the scale is the sensor's, pass speed_scale={r:.3g} (command line: --speed-scale {r:.3g}), which "
              "divides it out")
    unit = _ratio_cause(r) if abs(np.log(r)) > np.log(1.5) else None
    if unit:
        words = f"{found}, more than a speed's scale is off: {unit}; else, {remedy}"
    else:
        words = (f"{found}: a speed (or odometer) that reads {100 * (r - 1):+.0f} % (a speedometer's signal reads "
                 "high by up to 10 %, a wheel-speed signal with the wrong tyre circumference a few per cent). The "
                 "GPS/DR filters learn an odometer scale from the fixes, but not before the first ones, and not past "
                 f"their grade (the phone grade's: 3 %, one sigma, held within three); {remedy}")
    warnings.warn(words, RuntimeWarning, stacklevel=5)


def heading_offset(dt, heading, step, steps, z_gps, sigma=None, pairs=None):
    """How far the heading's zero looks off the GPS fixes' course at the start of a drive: ``(offset,
    standard error, rate, residual)`` (deg, deg, deg/s, deg), or None with fewer than three chords.

    The signed angle from each GPS chord to the dead-reckoned one (see the module docstring), as a
    straight line over time: its value at the first chord is the heading's offset (positive: the
    heading reads clockwise of the course), its slope a gyro's drift, the median absolute residual
    the chords' scatter about it. The arguments are :func:`check_drive`'s (``pairs``: the chords, when the
    caller has them).
    """
    if pairs is None:
        pairs = _chord_pairs(steps, z_gps, sigma, step)
    if len(pairs) < _MIN_CHORDS:
        return None
    return _offset_fit(_chord_angles(heading, step, steps, z_gps, pairs)[0], steps, pairs, dt)[:4]


#: The knots of a yaw rate's start fit (s) where its drift is not steady (:func:`yaw_start`): a gyro warming up.
YAW_START_KNOT_S = 120.0
#: The level of :func:`yaw_start`'s F-test past which the drift's knots are taken over a steady drift.
YAW_START_LEVEL = 1e-3
#: The moving stretches between fixes that must lie between two runs of a saturated yaw rate, at least, for
#: :func:`yaw_start` to fit the turn each lost apart (fewer: the runs are one step).
SATURATED_CHORDS = 3


#: The chords a piece of :func:`yaw_start`'s piecewise line holds, at least (a piece over a long gap of fixes, a car
#: park's 361 s, would swing its rate freely: a trial's clean drive read a change of 0.27 deg/s there).
YAW_START_PIECE_CHORDS = 10


def _chord_knots(t):
    """The knots (s) of :func:`yaw_start`'s piecewise line over the chords' times ``t`` (from 0): a piece at least
    :data:`YAW_START_KNOT_S` long and holding :data:`YAW_START_PIECE_CHORDS` chords, the last piece merged into the
    one before it when it holds fewer."""
    knots, since = [0.0], 0
    for v in t[1:]:
        since += 1
        if v - knots[-1] >= YAW_START_KNOT_S and since >= YAW_START_PIECE_CHORDS:
            knots.append(float(v))
            since = 0
    end = max(float(t[-1]), knots[-1] + 1.0)
    if len(knots) > 1 and since < YAW_START_PIECE_CHORDS:
        knots[-1] = end
    else:
        knots.append(end)
    return np.array(knots)


def yaw_start(dt, heading, step, steps, z_gps, pairs, saturated=()):
    """Where a yaw rate's integral starts, and the turns a saturated gyro lost: the chords' signed angles
    (:func:`_chord_angles`, the dead-reckoned course less the fixes') over time, a line (a gyro's steady rate bias),
    or, where that misfits at :data:`YAW_START_LEVEL` (an F-test, its statistic and degrees of freedom divided by
    the residuals' integrated autocorrelation time; with :data:`DEVIATION_CHORDS_PER_PARAMETER` chords per
    parameter at least: a city analog's 22 swung the pieces' rates by +-0.4 deg/s), a piecewise line with pieces of
    :data:`YAW_START_KNOT_S` or more, each holding :data:`YAW_START_PIECE_CHORDS` chords (:func:`_chord_knots`; a
    bias that changes: a gyro warming up, whose straight line had started a trial's drive 36 degrees off with a
    standard error of 1); beside a step at each group of ``saturated`` runs (sample index ranges ``(first, last)``
    where the rate read its range's rail: each leaves the turn past the rail out of the heading), the runs with
    fewer than :data:`SATURATED_CHORDS` chords between them one group, the chords that span a group left out.
    Both beside a gyro's scale factor error (the turn since the start) where no run is saturated. Least squares, then again without the chords
    past three robust sigmas (:func:`_inliers`). A steady drift with no turn to mend is :func:`_offset_fit`'s line, as
    :func:`heading_offset` gives it (the reader's start before stop 71).

    Returns
    -------
    dict or None
        ``offset`` (deg, at the first chord), ``se`` (deg), ``rate`` (deg/s, the first piece's), ``last_rate``
        (the last piece's), ``rates`` (each piece's), ``pieces`` (their lengths, s), ``piecewise`` (bool), ``resid`` (deg, the median absolute residual), ``n`` (chords
        fitted), ``steps``: per group ``(first, last, turn, se)`` (samples; deg: the turn the heading lost there,
        positive clockwise), ``groups`` the runs each took; None with fewer than :data:`_MIN_CHORDS` chords.
    """
    from scipy.stats import f as f_dist

    from ..metrics import integrated_autocorrelation

    if len(pairs) < _MIN_CHORDS:
        return None
    ang = _unwrap(_chord_angles(heading, step, steps, z_gps, pairs)[0])
    a, b = _chord_samples(steps, pairs)
    groups = []  # [first, last, runs]: runs without SATURATED_CHORDS chords between them are one
    for first, last in sorted(saturated):
        between = int(np.sum((a >= groups[-1][1]) & (b <= first))) if groups else SATURATED_CHORDS
        if groups and between < SATURATED_CHORDS:
            groups[-1][1], groups[-1][2] = last, groups[-1][2] + 1
        else:
            groups.append([first, last, 1])
    span = np.zeros(len(a), dtype=bool)
    for first, last, _ in groups:
        span |= (a < last + 1) & (b > first)  # (the run's last sample turned into the next)
    ok = ~span
    if ok.sum() < _MIN_CHORDS:
        return None
    t = dt * 0.5 * (a + b)[ok]
    t = t - t[0]
    y = ang[ok] - np.round(np.median(ang[ok][:5]) / (2 * np.pi)) * 2 * np.pi  # (the line starts within +-pi)
    jumps = np.stack([(a[ok] >= last + 1).astype(float) for _, last, _ in groups], axis=1) if groups else \
        np.zeros((len(t), 0))
    # a group with no chord after it (the drive's end, an outage) or none before has nothing to fit
    told = (jumps.sum(axis=0) > 0) & (jumps.sum(axis=0) < len(t))  # (and one with none before it: the start's)
    jumps = jumps[:, told]
    # a gyro's scale factor error beside either (the heading's error grows with the turn since the start: a car
    # park's helix up and down, read as a drift that changed, had asked a trial's clean drive for 800 deg/h)
    # (not beside the saturated runs' steps, which take the turns' errors there: with every turn saturated, the scale
    # is their sum)
    turned = np.unwrap(np.asarray(heading, dtype=float))
    scale = (0.5 * (turned[a] + turned[b]) - turned[0])[ok][:, None] if not jumps.shape[1] else np.zeros((len(t), 0))
    line = np.hstack([np.stack([np.ones_like(t), t], axis=1), scale, jumps])
    at = _chord_knots(t)
    knots = np.hstack([np.stack([np.interp(t, at, row) for row in np.eye(len(at))], axis=1), scale, jumps])

    def fit(X, keep):
        coef = np.linalg.lstsq(X[keep], y[keep], rcond=None)[0]
        return coef, y - X @ coef

    every = np.ones(len(y), dtype=bool)
    keep = _inliers(fit(knots, every)[1]) if len(y) > knots.shape[1] else every
    if keep.sum() <= line.shape[1]:
        keep = every
    piecewise = False
    n = int(keep.sum())
    coef, r = fit(line, keep)
    if knots.shape[1] > line.shape[1] and n >= DEVIATION_CHORDS_PER_PARAMETER * knots.shape[1]:  # (fewer: it overfits)
        coef_k, r_k = fit(knots, keep)
        rss_k, rss_l, p = float(r_k[keep] @ r_k[keep]), float(r[keep] @ r[keep]), knots.shape[1]
        if rss_k > 0.0:
            tau = integrated_autocorrelation([np.array([v]) for v in r_k[keep] / np.sqrt(rss_k / (n - p))])
            stat = (rss_l - rss_k) / (p - line.shape[1]) / (rss_k / (n - p)) / tau
            if f_dist.sf(stat, p - line.shape[1], max((n - p) / tau, 1.0)) < YAW_START_LEVEL:
                piecewise, coef, r = True, coef_k, r_k
    unfitted = sum(g[2] for g, on in zip(groups, told) if not on)
    if not piecewise and not jumps.shape[1]:  # a steady drift and no turn to mend: the heading line's fit, as before
        offset, se, rate, resid, n = _offset_fit(ang, steps, pairs, dt)
        return {"offset": offset, "se": se, "rate": rate, "last_rate": rate, "rates": np.array([rate]),
                "pieces": np.array([max(float(t[-1]), 1.0)]), "piecewise": False, "resid": resid, "n": n, "steps": [],
                "unfitted": unfitted}
    X = (knots if piecewise else line)[keep]
    dof = max(n - X.shape[1], 1)
    cov = np.linalg.pinv(X.T @ X) * float(r[keep] @ r[keep]) / dof
    m = jumps.shape[1]
    base = X.shape[1] - m - scale.shape[1]  # the line's or the pieces' columns (then the scale's, then the steps')
    if piecewise:
        rates = np.diff(coef[:base]) / np.diff(at)
    else:
        rates = coef[1:2]
    fitted = [g for g, on in zip(groups, told) if on]
    first_step = base + scale.shape[1]
    turns = [(int(first), int(last), float(np.degrees(-c)),
              float(np.degrees(np.sqrt(cov[first_step + i, first_step + i]))), runs)
             for i, ((first, last, runs), c) in enumerate(zip(fitted, coef[first_step:]))]
    return {"offset": float(np.degrees(coef[0])), "se": float(np.degrees(np.sqrt(cov[0, 0]))),
            "rate": float(np.degrees(rates[0])), "last_rate": float(np.degrees(rates[-1])),
            "rates": np.degrees(rates), "pieces": np.diff(at) if piecewise else np.array([max(float(t[-1]), 1.0)]),
            "piecewise": piecewise,
            "resid": float(np.degrees(np.median(np.abs(r[keep])))), "n": n, "steps": turns, "unfitted": unfitted}


def deviation_of(heading, coefficients):
    """A compass's deviation (rad) at each ``heading`` (rad, from north, clockwise), from the ``coefficients``
    ``(B, C, D, E)`` (deg) of its card (Smith's and Airy's): ``B sin h + C cos h + D sin 2h + E cos 2h``, what the
    heading reads more than the course (its constant, ``A``, is a heading offset)."""
    h = np.asarray(heading, dtype=float)
    b, c, d, e = np.deg2rad(np.asarray(coefficients, dtype=float))
    return b * np.sin(h) + c * np.cos(h) + d * np.sin(2 * h) + e * np.cos(2 * h)


def _hats(t, spacing):
    """Piecewise-linear basis functions ``(len(t), k + 1)`` over ``t`` (from 0) with ``k`` equal pieces of at most
    ``spacing``."""
    span = float(t[-1]) if len(t) and t[-1] > 0 else 1.0
    k = max(int(np.ceil(span / spacing)), 1)
    knots = np.linspace(0.0, span, k + 1)
    return np.stack([np.interp(t, knots, row) for row in np.eye(k + 1)], axis=1)


def heading_deviation(dt, heading, step, steps, z_gps, sigma=None, pairs=None):
    """A heading error that turns with the direction of travel: a compass's (magnetometer's) deviation, which the
    car's own steel and electrics give it (hard and soft iron). The chords' signed angles (:func:`_chord_angles`,
    the dead-reckoned course less the fixes') against the deviation card's harmonics of the dead-reckoned course
    ``h`` (the heading as read; its noise is not the fixes'), ``B sin h + C cos h + D sin 2h + E cos 2h``, fitted
    beside what a gyro's heading does: an offset and a drift (piecewise linear in time, knots every
    :data:`DEVIATION_KNOT_S`) and a scale factor error (the heading's turn since the start). Chords that turn more
    than :data:`DEVIATION_STRAIGHT_DEG` or whose dead-reckoned length is not within 0.67-1.5 of the fixes' (a fix
    jumped or held, a tunnel's end) are left out; least squares, then again without the chords past three robust
    sigmas. The four coefficients are tested together (an F-test of the residual sums of squares with and without
    them, its statistic and degrees of freedom divided by the residuals' integrated autocorrelation time). The card
    returned is fitted to the same chords beside an offset alone, as a compass swing measures it (a compass's
    heading does not drift, and beside a drift the coefficients trade against it), unless the drift is significant
    at the same level (a gyro's or a fused heading): then beside the drift.

    Returns
    -------
    tuple or None
        ``(coefficients, low, high, p, n)``: ``(B, C, D, E)`` (deg), the least and the largest deviation over the
        chords' own courses (deg; the card's harmonics alone, without a constant), the test's p-value and the chords
        fitted; None with fewer chords than :data:`DEVIATION_CHORDS_PER_PARAMETER` per parameter (or
        :data:`WARN_MIN_CHORDS`). The arguments are :func:`check_drive`'s.
    """
    from scipy.stats import f as f_dist

    from ..metrics import integrated_autocorrelation

    if pairs is None:
        pairs = _chord_pairs(steps, z_gps, sigma, step)
    if len(pairs) < _MIN_CHORDS:
        return None
    ang = _unwrap(_chord_angles(heading, step, steps, z_gps, pairs)[0])
    dr, gps = _chord_vectors(heading, step, steps, z_gps, pairs)
    a, b = _chord_samples(steps, pairs)
    turned = np.unwrap(heading)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.hypot(dr[:, 0], dr[:, 1]) / np.hypot(gps[:, 0], gps[:, 1])
    keep = (np.abs(turned[b] - turned[a]) <= np.deg2rad(DEVIATION_STRAIGHT_DEG)) & (ratio > 1 / 1.5) & (ratio < 1.5)
    if keep.sum() < WARN_MIN_CHORDS:
        return None
    course = np.arctan2(dr[:, 0], dr[:, 1])[keep]
    total = np.r_[0.0, np.cumsum(turned)]
    scale = ((total[b + 1] - total[a]) / (b + 1 - a) - turned[0])[keep]  # the mean turn since the start
    t = dt * 0.5 * (a + b)[keep]
    y = ang[keep] - np.round(np.median(ang[keep][:5]) / (2 * np.pi)) * 2 * np.pi  # (the line starts within +-pi)
    harm = np.stack([np.sin(course), np.cos(course), np.sin(2 * course), np.cos(2 * course)], axis=1)
    gyro = np.hstack([_hats(t - t[0], DEVIATION_KNOT_S), scale[:, None]])
    full = np.hstack([gyro, harm])
    if len(y) < DEVIATION_CHORDS_PER_PARAMETER * full.shape[1]:
        return None

    def residuals(X, v):
        coef = np.linalg.lstsq(X, v, rcond=None)[0]
        return coef, v - X @ coef

    near = _inliers(residuals(full, y)[1])  # a chord from a jumped fix leaves
    coef1, r1 = residuals(full[near], y[near])
    n, p, q = int(near.sum()), full.shape[1], harm.shape[1]
    rss1 = float(r1 @ r1)
    if rss1 <= 0.0 or n <= p:
        return None
    tau = integrated_autocorrelation([np.array([v]) for v in r1 / np.sqrt(rss1 / (n - p))])

    def f_test(reduced, k):
        """The p-value of the ``k`` parameters the full fit has beyond the ``reduced`` one's residuals."""
        stat = (float(reduced @ reduced) - rss1) / k / (rss1 / (n - p)) / tau
        return float(f_dist.sf(stat, k, max((n - p) / tau, 1.0)))

    pval = f_test(residuals(gyro[near], y[near])[1], q)
    # the card itself beside an offset alone where the heading does not drift (a compass's): beside the drift's knots
    # the coefficients trade against it (the trial's compass drives 101-103, user-trial/compass.py: fitted beside
    # the drift, as this stop's first version did, the first harmonic's B read 2.0-5.6 degrees and its C 2.3-4.7,
    # against 5.8 and 4.0 drawn; beside an offset 5.8-6.3 and 3.2-4.4); where the drift is significant (a gyro's
    # heading, or a fused one: at the deviation's level), beside the drift
    coef, r2 = residuals(np.hstack([np.ones((n, 1)), harm[near]]), y[near])
    if f_test(r2, gyro.shape[1] - 1) < HEADING_DEVIATION_LEVEL:  # (the drift's parameters beyond the offset)
        coef = coef1
    dev = np.rad2deg(harm[near] @ coef[-q:])
    return tuple(float(c) for c in np.rad2deg(coef[-q:])), float(dev.min()), float(dev.max()), pval, n


def _deviation_told(fit):
    """Whether :func:`heading_deviation`'s ``fit`` is warned of: past :data:`HEADING_DEVIATION_LEVEL` and with a
    peak past :data:`HEADING_DEVIATION_WARN_DEG`."""
    return (fit is not None and fit[3] < HEADING_DEVIATION_LEVEL
            and max(-fit[1], fit[2]) > HEADING_DEVIATION_WARN_DEG)


def _warn_deviation(dt, heading, step, steps, z_gps, sigma, pairs):
    """Warn of a compass's deviation (:func:`heading_deviation`), with its card and the reader's remedy."""
    fit = heading_deviation(dt, heading, step, steps, z_gps, sigma, pairs)
    if not _deviation_told(fit):
        return
    card, low, high, pval, n = fit
    given = ",".join(f"{c:.1f}" for c in card)
    warnings.warn(f"plausibility: over {n} straight moving stretches between GPS fixes, the heading's error turns with "
                  f"the direction of travel, from {low:+.0f} to {high:+.0f} degrees over the courses driven (a "
                  f"compass's deviation card, B sin h + C cos h + D sin 2h + E cos 2h: B, C, D, E = {given} deg; "
                  f"p = {pval:.1g} beside a gyro's offset, drift and scale): a magnetic heading (a phone's or a car's "
                  "compass) deviates so near the car's steel. The GPS/DR filters estimate one heading bias and a "
                  "gyro's drift of it, neither of which this is: each outage starts with the bias of the road before "
                  "it, and the rate-bias state takes the deviation's changes for a drift. Give the heading a gyro "
                  "integrates (a yaw_rate column) if the log has one; else pass heading_deviation=("
                  f"{given}) (command line: --heading-deviation {given}), which subtracts it (a deviation card, as a "
                  "compass swing gives: measured here from this drive's own fixes, it holds for later drives with the "
                  "same mount)", RuntimeWarning, stacklevel=5)


def _chord_misfits(heading, step, steps, z_gps, pairs, dt, taus):
    """Per offset in ``taus`` (s) and chord ``(len(taus), len(pairs))``: how far the dead-reckoned displacement
    over the fixes' times less the offset is from the chord, once the chords' common rotation and scale are
    taken out: ``|log(g / d) - median|`` for the chord ``g`` and the displacement ``d`` as complex numbers
    (east + i north; the angle unwrapped, as :func:`_offset_fit` does); NaN where the moved stretch leaves the
    drive or has no displacement (all NaN with fewer than three chords left)."""
    cum = _track(heading, step)
    grid = np.arange(cum.shape[1], dtype=float)
    first, last = _chord_samples(steps, pairs)
    g = np.array([complex(*(z_gps[j] - z_gps[i])) for i, j in pairs])
    out = np.full((len(taus), len(pairs)), np.nan)
    for row, tau in zip(out, taus):
        a, b = first - tau / dt, last - tau / dt
        d = np.interp(b, grid, cum[0]) - np.interp(a, grid, cum[0]) + 1j * (np.interp(b, grid, cum[1])
                                                                             - np.interp(a, grid, cum[1]))
        with np.errstate(divide="ignore", invalid="ignore"):
            lr = np.log(g / d)
        ok = (a >= 0) & (b <= grid[-1]) & np.isfinite(lr)
        if ok.sum() >= _MIN_CHORDS:
            ang = _unwrap(lr.imag[ok])
            row[ok] = np.abs(lr.real[ok] - np.median(lr.real[ok]) + 1j * (ang - np.median(ang)))
    return out


def clock_offset(dt, heading, step, steps, z_gps, sigma=None, pairs=None):
    """The clock offset between the fixes and the DR samples that the drive shows: ``(tau, p, wins, n)`` or
    None with fewer than :data:`WARN_MIN_CHORDS` chords. ``tau`` (s; positive: each fix is the car's position
    that long before its stamp) is the offset, of those tried every 0.5 s within :data:`CLOCK_OFFSET_SCAN_S`,
    at which the chords' median misfit (:func:`_chord_misfits`: the dead-reckoned track against the fixes',
    rotation and scale aside) is least; ``p`` a sign test that the misfit at ``tau`` is below the one at 0 on
    more chords than chance gives (``wins`` of ``n``), times the number of offsets tried (each was a chance to
    find one). A heading's offset or a speed's scale is common to every chord and is not an offset; only the
    timing of the turns, starts and stops tells one. The other arguments are :func:`check_drive`'s."""
    if pairs is None:
        pairs = _chord_pairs(steps, z_gps, sigma, step)
    if len(pairs) < WARN_MIN_CHORDS:
        return None
    half = round(CLOCK_OFFSET_SCAN_S / _CLOCK_STEP_S)
    taus = _CLOCK_STEP_S * np.arange(-half, half + 1)
    m = _chord_misfits(heading, step, steps, z_gps, pairs, dt, taus)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # an offset that leaves too few chords: all NaN
        med = np.nanmedian(m, axis=1)
    med[~np.isfinite(med)] = np.inf
    k, k0 = int(np.argmin(med)), half
    both = np.isfinite(m[k]) & np.isfinite(m[k0])
    n, wins = int(both.sum()), int(np.sum(m[k0][both] > m[k][both]))
    if k == k0 or n < WARN_MIN_CHORDS:
        return 0.0, 1.0, 0, n
    from scipy.stats import binom

    p = float(binom.sf(wins - 1, n, 0.5)) * len(taus)
    return float(taus[k]), min(p, 1.0), wins, n


def _clock_told(dt, heading, step, steps, z_gps, pairs):
    """The clock offset a warning or refusal names (:func:`clock_offset`'s), or None: past
    :data:`CLOCK_OFFSET_WARN_S` and the test's level."""
    found = clock_offset(dt, heading, step, steps, z_gps, pairs=pairs)
    if found is None:
        return None
    tau, p = found[:2]
    return found if abs(tau) > CLOCK_OFFSET_WARN_S and p <= _CLOCK_LEVEL else None


def _clock_remedy(tau, p, wins, n):
    """What a warning or a refusal says of a clock offset (:func:`clock_offset`'s)."""
    return (f"the fixes match the dead-reckoned track best placed {abs(tau):g} s {'earlier' if tau > 0 else 'later'} "
            f"than their time stamps (each fix the car's position {abs(tau):g} s {'before' if tau > 0 else 'after'} "
            f"its stamp; the misfit there below the one as stamped on {wins} of {n} moving stretches between fixes): "
            "a clock offset between the fixes and the DR samples (GPS time leads UTC by 18 s; two loggers' clocks), "
            "which the GPS/DR filters' latency state takes only once its monitor has found it. If the offset is the "
            f"fixes', pass gps_latency={tau:g} (command line: --gps-latency {tau:g}), which places each fix at its "
            "time; the heading's offset and the speed's scale are judged once the fixes are at their time. Fixes "
            "that a receiver or phone smooths (a low-pass filter: they lag on every road and cut every corner) read "
            "as late too, and no latency mends them (the sixth user trial's, lagging 2.5 s: 7.83 / 25.16 m at the "
            "outage ends, 7.80 / 15.20 with the latency this names, raw dead reckoning 3.83 / 8.98; stop 72): for "
            "those, the receiver's raw fixes")


#: A dead-reckoned track shorter than this share of the fixes' distance (its median stretch) has a speed that reads
#: 0 where the car moves: its refusal says so rather than naming a heading's cause (an OBD logger's local time read
#: as UTC, whose speed was 0 over the whole drive, was refused as a yaw rate turning the wrong way: stop 58).
STILL_RATIO = 0.05


def _fits(angle, ratio):
    return angle <= MAX_ANGLE_DEG and RATIO_RANGE[0] <= ratio <= RATIO_RANGE[1]


def _badness(angle, ratio):
    """How far a hypothesis is from fitting: 1 at either limit of :func:`_fits`."""
    return max(angle / MAX_ANGLE_DEG, abs(np.log(ratio)) / np.log(RATIO_RANGE[1]))


#: How many more of the chords (a share) a hypothesis about the heading must fit than another to be named before
#: it: a heading mirrored about one street's direction fits that street's chords, and on a drive that spends most
#: of its time along one street axis (right-angle turns) their median as well: 81 % of a test drive's stretches
#: (``tests/navigation/test_phone_log.py``), 51 % of a phone log's, where the heading turned the other way fits
#: 100 %. The analogs' and the shipped sample's headings (seeds 0-4) fit 88-100 % of their stretches, and no
#: mirrored zero fits them at all (stop 58).
SHARE_MARGIN = 0.1


def _share(ang):
    """The share of the chords whose angle (:func:`_chord_angles`') is within :data:`MAX_ANGLE_DEG`."""
    return float(np.mean(np.abs(ang) <= np.deg2rad(MAX_ANGLE_DEG)))


def _track_cause(heading, step, steps, z_gps, pairs, swapped, offset=None, dt=None):
    """The usual heading or frame mistake that fits the fixes best, or None.

    Heading counter-clockwise from east and swapped lat/lon both mirror the track about
    the north-east line; only the swap also stretches it (by the cosine of the latitude),
    so the better fit of the two names the cause. ``offset`` (deg, :func:`_offset_fit`'s, or None): the heading's
    zero off by that much (its words are :func:`_offset_remedy`'s, which the caller gives: returned as ``"offset"``);
    a heading that turns the wrong way from some zero (:func:`_mirrored`) is tried as well.

    A hypothesis fits where the median chord does (:func:`_badness` at most 1). On a drive of right-angle turns,
    a wrong one can: a heading counter-clockwise from east, given clockwise with its zero 142 degrees off (a
    phone's yaw negated), fits the chords of one street axis, and the drive spent most of its time on it. So the
    named mistakes are chosen among the fitting hypotheses only while none fits :data:`SHARE_MARGIN` more of the
    chords (:func:`_share`); else the offset, or the heading turned the other way, that does.
    """
    named = [(np.deg2rad(heading), z_gps, "heading looks like degrees (values under 2 pi, but the GPS course "
                                          "matches them read as degrees: use the heading_deg column or np.deg2rad)"),
             (np.pi / 2 - heading, z_gps, "heading looks counter-clockwise from east (the GPS course matches "
                                          "pi/2 - heading; the convention is clockwise from north)")]
    if swapped is not None:
        named.append((heading, swapped, "lat and lon look swapped (the drive matches its fixes with latitude "
                                        "and longitude exchanged)"))
    others = []
    if offset is not None:
        others.append((heading - np.deg2rad(offset), z_gps, "offset"))
    c = _mirrored(heading, step, steps, z_gps, pairs)
    if c is not None:
        others.append((c - heading, z_gps, _mirrored_cause(c)))

    def fitting(tries):
        out = []
        for h, z, cause in tries:
            ang, ratio = _chord_angles(h, step, steps, z, pairs)[:2]
            bad = _badness(*_medians(ang, ratio))
            if bad <= 1.0:
                out.append((bad, _share(ang), cause))
        return out

    headings = {cause: h for h, z, cause in named if z is z_gps}
    named, others = fitting(named), fitting(others)
    best_other = max((share for _, share, _ in others), default=-1.0)
    named = [t for t in named if t[1] > best_other - SHARE_MARGIN]
    if named:
        cause = min(named, key=lambda t: t[0])[2]
        split = _from_where(_chord_angles(heading, step, steps, z_gps, pairs)[0], headings[cause], step, steps, z_gps,
                            pairs, dt) if cause in headings and dt is not None else None
        return cause + ("; but " + _split_words(*split) if split else "")
    return max(others, key=lambda t: t[1])[2] if others else None


def _warn_stretch_convention(ang, heading, step, steps, z_gps, pairs, dt, yaw_rate):
    """Warn where the heading fits the fixes as written on one stretch only and, on the rest, as a named mistake
    (degrees, counter-clockwise from east) would (:func:`_from_where`): a drive the refusal's remedy converted whole
    (stop 72's sixth trial, its heading counter-clockwise from 250 s on, converted whole: 13.42 / 523.46 m)."""
    if yaw_rate:
        return
    for named, what in ((np.deg2rad(heading), "degrees"), (np.pi / 2 - heading, "counter-clockwise from east")):
        split = _from_where(ang, named, step, steps, z_gps, pairs, dt)
        if split:
            warnings.warn(f"plausibility: the heading reads as {what} on a stretch of the drive, and the filters take "
                          f"all of it as written: {_split_words(*split)}", RuntimeWarning, stacklevel=5)
            return


#: The share of the chords the better split of a drive (as written before a time, as a named mistake after it, or the
#: other way round) must fit, and by how much more than the mistake named for the whole drive, before a refusal says
#: that the mistake holds only from (or until) then (:func:`_from_where`).
SPLIT_SHARE = 0.85
SPLIT_MARGIN = 0.15


def _from_where(ang, named, step, steps, z_gps, pairs, dt):
    """Words for a refusal whose heading mistake (``named``, the heading so corrected) holds on one stretch of the
    drive only, as written on the rest (a logger restarted with another convention: stop 72's sixth trial, whose
    heading turned counter-clockwise from east at 250 s, was refused as if all of it were, and converted whole it
    ended its outages 13.42 / 523.46 m off): the split of the chords into a first stretch and the rest, one as written
    and the other corrected, that fits most of them, where it fits :data:`SPLIT_SHARE` of them and
    :data:`SPLIT_MARGIN` more than the correction, and than the heading as written, throughout. ``ang``: the chords'
    angles as written (:func:`_chord_angles`'); ``named``: the heading corrected. Returns ``(t, later, share)``, the
    time (s from the first row) and whether the mistake holds after it, or None."""
    n = len(pairs)
    if n < 4 * _MIN_CHORDS:
        return None
    limit = np.deg2rad(MAX_ANGLE_DEG)
    as_is = np.abs(ang) <= limit
    fixed = np.abs(_chord_angles(named, step, steps, z_gps, pairs)[0]) <= limit
    best = None
    for first, rest, later in ((as_is, fixed, True), (fixed, as_is, False)):
        score = (np.r_[0, np.cumsum(first)] + np.r_[np.cumsum(rest[::-1])[::-1], 0]) / n
        k = int(np.argmax(score[1:n])) + 1
        if best is None or score[k] > best[0]:
            best = (float(score[k]), k, later)
    share, k, later = best
    if share < SPLIT_SHARE or share < max(float(np.mean(fixed)), float(np.mean(as_is))) + SPLIT_MARGIN:
        return None
    return float(dt * (int(steps[pairs[k][0]]) + 1)), later, share


def _split_words(at, later, share):
    """The words of :func:`_from_where`'s split: the mistake holds from (``later``) or until ``at`` (s)."""
    return (f"only {'from' if later else 'until'} about t = {at:.0f} s (s from the first row); "
            f"{'before' if later else 'after'} it the heading fits the fixes as written ({share:.0%} of the chords "
            "fit so split): a log whose convention changed there (a logger restarted with another setting), whose "
            f"rows {'from' if later else 'until'} then alone need converting")


def _mirrored(heading, step, steps, z_gps, pairs):
    """The zero ``c`` (rad) for which ``c - heading`` fits the fixes (a heading that turns the wrong way: a yaw angle
    counter-clockwise, as ROS and ENU frames write it, from wherever its integration started), the chords' circular
    mean with the heading negated; None when even that does not fit."""
    ang = _chord_angles(-heading, step, steps, z_gps, pairs)[0]
    c = -float(np.arctan2(np.mean(np.sin(ang)), np.mean(np.cos(ang))))
    return None if _badness(*_scores(c - heading, step, steps, z_gps, pairs)) > 1.0 else c


def _mirrored_drifting(heading, step, steps, z_gps, pairs, dt):
    """Whether the heading turned the other way fits the fixes as a drifting gyro's does (:func:`_drifting_gyro`'s
    line through the chords' angles, from any zero): a yaw rate counted counter-clockwise, with a rate bias (a raw
    phone gyro's 0.3 deg/s, whose refusal named a clock offset of 10.5 s until stop 58)."""
    offset, _, rate, resid = _offset_fit(_chord_angles(-heading, step, steps, z_gps, pairs)[0], steps, pairs, dt)[:4]
    return abs(rate) <= MAX_DRIFT_DEG_S and resid <= MAX_ANGLE_DEG


def _mirrored_cause(c):
    """The words for a heading that turns the wrong way from the zero ``c`` (rad, :func:`_mirrored`'s), with the
    remedy."""
    deg = float(np.degrees(c)) % 360.0
    return (f"the heading turns the wrong way (the GPS course matches {deg:.0f} deg - heading: a yaw angle "
            f"counter-clockwise, as ROS and ENU frames write it, from a zero {deg:.0f} deg clockwise of north; the "
            f"convention is clockwise from north): give heading_deg = {deg:.0f} - yaw_deg, or heading = "
            f"{c % (2 * np.pi):.3f} - heading in radians")


#: The least share of the stretches a heading turned the other way must fit for a heading whose median fits to be
#: refused as turning the wrong way (:func:`_refuse_mirrored`): one that does fits them all (100 % on a phone log and
#: a test drive), while a mirrored zero fits 60 % of a drifting gyro's (the 1 Hz analog's first 400 s with a 0.5
#: deg/s bias, whose own fit 29 %; stop 58).
MIRRORED_SHARE = 0.8


def _refuse_mirrored(heading, step, steps, z_gps, pairs, ang, yaw_rate, n, angle, ratio):
    """Refuse a heading whose median chord fits but which turns the wrong way: turned the other way (from the zero
    that fits best, :func:`_mirrored`) it fits :data:`SHARE_MARGIN` more of the chords (:func:`_share`; ``ang``:
    the heading's own chord angles), and at least :data:`MIRRORED_SHARE` of them. A heading mirrored about the
    street the car drove most on fits that street's chords, and their median on a drive of right-angle turns."""
    c = _mirrored(heading, step, steps, z_gps, pairs)
    if c is None:
        return
    own, other = _share(ang), _share(_chord_angles(c - heading, step, steps, z_gps, pairs)[0])
    if other < max(own + SHARE_MARGIN, MIRRORED_SHARE):
        return
    cause = _YAW_SIGN if yaw_rate else _mirrored_cause(c)
    raise ValueError(f"plausibility: over {n} moving stretches between GPS fixes, the dead-reckoned track's median "
                     f"is {angle:.0f} degrees off the fixes' course and {ratio:.3g} times their distance, but it "
                     f"fits {own:.0%} of the stretches within {MAX_ANGLE_DEG:g} degrees, and {other:.0%} turned the "
                     f"other way: {cause}{_OVERRIDE}")


#: A yaw rate's refusal when it turns the wrong way (:func:`check_drive` with ``yaw_rate=True``).
_YAW_SIGN = ("the yaw rate turns the wrong way (the fixes' course matches the heading it integrates to turned the "
             "other way): give it clockwise positive, a right turn positive (its negative: ROS and ENU frames count "
             "counter-clockwise)")


def _decade_off(ratio):
    """Whether a length ratio is a decade or more off 1 (a unit's factor of 10 or more)."""
    return not 0.1 < ratio < 10.0


def _per_sample_cause(ratio, dt):
    """The refusal's cause for a track whose length ratio is the sample interval ``dt`` (within 1.25; at most 0.5 s):
    a speed column holding each sample's distance (a tick count's difference scaled to metres), else None."""
    if not (ratio > 0 and dt <= 0.5 and abs(np.log(ratio / dt)) < np.log(_UNIT_TOLERANCE)):
        return None
    return (f"the dead-reckoned track is the sample interval ({dt:g} s) times the fixes' distance: the speed column "
            "holds each sample's distance (m), not m/s; divide it by the interval, or give its cumulative sum as "
            "the odometer column")


def _ratio_cause(ratio, decade_tolerance=_DECADE_TOLERANCE, where=""):
    """The unit mistake of :data:`_SCALES` nearest the track's length ratio (within a factor 1.25, or
    ``decade_tolerance`` for those a decade or more from 1), or None. km/h (3.6) and ft/s (3.28), mph (2.24)
    and knots (1.94) lie within that of each other: the nearer names it, and the other is named after it, as the
    other possibility, where it fits within :data:`_UNIT_EITHER` of as well, with the ratio (measured ``where``)."""
    if not ratio > 0:
        return None
    fits = sorted((abs(np.log(ratio / factor)), factor, cause) for factor, cause in _SCALES)
    off, factor, cause = fits[0]
    tolerance = decade_tolerance if _decade_off(factor) else _UNIT_TOLERANCE
    if not off < np.log(tolerance):
        return None
    other = fits[1]
    if other[0] < np.log(tolerance) and other[0] <= off + np.log(_UNIT_EITHER):
        cause += (f", or else {other[2].replace('speed looks like ', '')}: the track is {ratio:.3g} times the fixes' "
                  f"distance{where}, near both (a speed that reads a few per cent off; the logger's documentation "
                  "says which)")
    return cause


def _unit_ratio(step, steps, z_gps, sigma, ratio, heading):
    """``(ratio, tolerance)``: the track's median length ratio to the fixes' (:func:`_medians`), ``ratio``,
    measured again over chords that long in the fixes' distance, as the ratio of the dead-reckoned displacement's
    length to theirs (the path, longer on a bend, read a city's ft/s as km/h over such chords), and the factor
    within which :func:`_ratio_cause` names a unit a decade or more from 1 by it. A speed in another unit makes the
    chords of :func:`_chord_pairs` (chosen by the odometer's path) that many times shorter, and the fixes' noise
    then lengthens them (a speed in km/h read 2.6-3.7 times; stop 65). ``ratio`` and
    :data:`_DECADE_TOLERANCE` where it is under 1 (chords already long) or where fewer than
    :data:`WARN_MIN_CHORDS` chords are that long; else :data:`_DECADE_TOLERANCE_AGAIN`."""
    if not ratio > 1.0:
        return ratio, _DECADE_TOLERANCE
    pairs = _odometer_chords(steps, sigma, step, longer=ratio)
    if len(pairs) < WARN_MIN_CHORDS:
        return ratio, _DECADE_TOLERANCE
    return float(np.median(_chord_angles(heading, step, steps, z_gps, pairs)[2])), _DECADE_TOLERANCE_AGAIN


#: The refusal's cause for fixes whose latitude and longitude look like radians (:func:`check_drive`'s ``radians``).
_RADIANS = ("the fixes' lat and lon look like radians (every one within pi/2 and pi; read as degrees they lie tens of "
            "times closer together than the car drove): give them in degrees (np.degrees)")


def carried(dt, step, steps, z_gps):
    """The stretches where the speed reads 0 for :data:`CARRIED_MIN_S` or more while the fixes move
    :data:`CARRIED_MIN_M` or more at :data:`CARRIED_SPEED` or more: from the median of the stretch's first quarter of
    fixes to the median of its last (medians: a standing car's fixes scatter and jump, and fix to fix their noise
    alone reads metres a second). A car carried (a ferry, a car train, a tow truck), or a speed whose signal was
    lost while the car drove. ``[(first sample, last sample, metres moved (at least: from the first quarter's median to
    the last's), m/s), ...]``; the arguments are :func:`check_drive`'s."""
    at = np.asarray(steps, dtype=int) + 1  # each fix's sample
    found = []
    for a, b in zip(*_run_bounds(np.asarray(step, dtype=float) == 0.0)):  # steps a..b-1: samples a..b stand
        if (b - a) * dt < CARRIED_MIN_S:
            continue
        inside = (at >= a) & (at <= b)
        if inside.sum() < 3:
            continue
        z, k = z_gps[inside], at[inside]
        quarter = max(len(k) // 4, 1)  # the run's first and last quarter of fixes, each by its median
        moved = float(np.hypot(*(np.median(z[-quarter:], axis=0) - np.median(z[:quarter], axis=0))))
        took = dt * float(np.median(k[-quarter:]) - np.median(k[:quarter]))
        if took > 0 and moved >= CARRIED_MIN_M and moved / took >= CARRIED_SPEED:
            found.append((int(a), int(b), moved, moved / took))
    return found


def _warn_carried(dt, step, steps, z_gps):
    """Warn of the stretches :func:`carried` finds, the first named and the others counted."""
    found = carried(dt, step, steps, z_gps)
    if not found:
        return
    a, b, path, speed = found[0]
    more = f" (and {len(found) - 1} more such stretch(es))" if len(found) > 1 else ""
    warnings.warn(f"plausibility: from t = {a * dt:.0f} s to {b * dt:.0f} s ({(b - a) * dt:.0f} s) the speed reads 0 "
                  f"while the fixes move {path:.0f} m or more, at {speed:.2g} m/s{more}: no speed reads 0 at that "
                  "speed (a cutoff hides a crawl under 0.3-1 m/s): the car was carried (a ferry, a car train, a tow "
                  "truck), or the speed's signal was lost while it drove. The GPS/DR filters take the car to stand, "
                  "and the fixes for a crawl or a jump (they re-acquire); estimating the fixes' covariance scale "
                  "(scale_window) then takes the stretch for their accuracy and distrusts them after it. Split the "
                  "drive there (the rows before and after as two drives: the command takes several --drive), or give "
                  "the speed the car had there", RuntimeWarning, stacklevel=4)


def _check_truth(steps, z_gps, truth, sigma, clock=None, radians=False):
    """Refuse fixes that lie far from the truth at their samples (another frame, lat/lon swapped, in radians; a
    clock offset, when ``clock`` has found one)."""
    if truth is None or not len(steps):
        return
    d = float(np.median(np.hypot(*(z_gps - truth[steps + 1]).T)))
    if d > max(100.0, 30.0 * sigma):
        cause = (_RADIANS if radians else
                 "the fixes and the truth must share one frame and origin (lat and lon swapped in one of them?)"
                 if clock is None else _clock_remedy(*clock) + "; else the fixes and the truth must share one "
                 "frame and origin")
        raise ValueError(f"plausibility: the GPS fixes lie a median {d:.4g} m from the truth at their samples: "
                         f"{cause}{_OVERRIDE}")


def _held_at_fixes(values, moving, near, least_held=GPS_DERIVED_HELD, tol=1e-9, least_at=GPS_DERIVED_AT_FIX,
                   least=0.0):
    """``(changes, share at a fix, share held)`` of ``values`` over the intervals ``moving``, or None when they do
    not look held between the fixes (held over ``least_held`` of them at least, ``least_at`` of the changes at a
    fix); ``near``: the intervals beside a fix's sample; ``tol``: the relative change that is one, and ``least``
    the absolute change at or under which none is (a column's rounding)."""
    changed = np.abs(np.diff(values)) > np.maximum(tol * (1.0 + np.abs(values[1:])), least)
    n = int(np.sum(changed & moving))
    if moving.sum() < 2 * GPS_DERIVED_MIN_CHANGES or n < GPS_DERIVED_MIN_CHANGES:
        return None
    held, at = 1.0 - n / moving.sum(), float(np.sum(changed & moving & near)) / n
    return (n, at, held) if held >= least_held and at >= least_at else None


def _interpolated_at_fixes(values, moving, near, least_held):
    """:func:`_held_at_fixes` of ``values``' slope: a column interpolated between the fixes (its knots at them).
    A column written to a few decimals (a CSV's ``%.3f``) rounds each value by up to half its step
    (:func:`_resolution`), which moves a straight line's slope by up to two steps from sample to sample: no
    change of slope is counted within that."""
    both = moving[1:] & moving[:-1]
    return _held_at_fixes(np.diff(values), both, near[:len(both)], least_held, tol=GPS_DERIVED_SLOPE_TOL,
                          least_at=GPS_DERIVED_AT_FIX_LINEAR, least=GPS_DERIVED_ROUNDING * _resolution(values))


def _resolution(values):
    """The step a column was written to (the least change between neighbouring values, past a double's last bits):
    0.001 for a speed written ``%.3f``; about 0 for one written in full."""
    finite = values[np.isfinite(values)]
    d = np.abs(np.diff(finite))
    d = d[d > 1e-12 * (1.0 + np.max(np.abs(finite), initial=0.0))]
    return float(d.min()) if len(d) else 0.0


#: What a column held between the fixes is, and what to give instead.
_GPS_DERIVED = {"heading": ("a GPS course (a receiver's bearing), not a gyro's heading", "the gyro's heading, or its "
                            "yaw rate (yaw_rate)"),
                "speed": ("a GPS speed (a receiver's Doppler speed), not the car's", "the car's speed (its CAN bus, "
                          "OBD or wheel ticks)")}


def _gps_derived(dt, heading, step, steps, speed=None):
    """Warn of a heading or a speed that changes only at the fixes (:data:`GPS_DERIVED_HELD`): the receiver's, not
    a dead-reckoning sensor's. Over a real outage it stays where the last fix left it, while outages cut into such a
    drive still carry the withheld fixes' course or speed, and score better than dead reckoning could. ``speed``
    (each sample's, as the drive gave it) is read where given, not ``step``: a step is a speed times its stamped
    interval, and stamps in seconds since 1970 (1.8e9, to a double's 2.4e-7 s) change every step's last digits."""
    n = len(heading)
    if len(steps) < 2 or n < 3:
        return
    ratio = float(np.median(np.diff(steps)))
    if ratio < GPS_DERIVED_FAST_RATIO:  # a fix on (nearly) every sample: nothing to tell the samples from the fixes
        return
    fix = np.zeros(n + 1, dtype=bool)
    fix[np.clip(np.asarray(steps) + 1, 0, n - 1)] = True  # the fix at step k is sample k + 1
    moving = np.asarray(step, dtype=float) >= GPS_DERIVED_SPEED * dt
    speed = np.asarray(step, dtype=float) if speed is None else np.asarray(speed, dtype=float)[1:]  # (step k's)
    for name, values, intervals, at in (("heading", np.asarray(heading, dtype=float), moving, 1),
                                        ("speed", speed, moving[1:] & moving[:-1], 2)):
        if ratio >= GPS_DERIVED_MIN_RATIO:  # a change into sample i + 1: a fix at sample i, i + 1 or i + 2
            near, held = fix[:n - 1] | fix[1:n] | fix[2:n + 1], GPS_DERIVED_HELD
            bent = near[at - 1:]  # a change of slope centred on a fix's sample or one beside it (a fix logged
            # between two samples bends the line at both)
        else:  # fixes every 2-4 samples (5 Hz on a 10 Hz log): changes at the fix's own sample (a step's distance,
            # step k, is sample k + 1's speed), held over the rest
            near, held = fix[at:n - 1 + at], GPS_DERIVED_HELD * (1.0 - 1.0 / ratio)
            bent = near
        found = _held_at_fixes(values, intervals, near[:len(intervals)], held)
        how = ("changes only where there is a GPS fix", "changes at a fix's sample or beside it, held over",
               "stays where the last fix left it")
        if found is None:
            found = _interpolated_at_fixes(values, intervals, bent, held)
            how = ("changes its slope only where there is a GPS fix, and runs straight between",
                   "slope's changes at a fix's sample or beside it, straight over", "runs straight from the last "
                   "fix's value to the next's (or stays at the last)")
        if found is None:
            continue
        k, at, held = found
        what, remedy = _GPS_DERIVED[name]
        warnings.warn(f"plausibility: while the car moves the {name} {how[0]} ({at:.0%} of its {k} {how[1]} "
                      f"{held:.0%} of the intervals): {what}. Dead reckoning then has no {name} of its own: over a "
                      f"real outage it {how[2]}, and outages cut into this drive (filterwnn study dr) are scored "
                      f"with the withheld fixes' {name}, better than dead reckoning could do. Give {remedy}",
                      RuntimeWarning, stacklevel=5)


def check_drive(dt, heading, step, steps, z_gps, sigma=None, swapped=None, truth=None, yaw_rate=False,
                radians=False, speed=None):
    """Refuse a drive whose units or frame contradict its own GPS fixes (see the module docstring).

    Parameters
    ----------
    dt : float
        DR sample interval (s).
    heading : ndarray of shape (n_samples,)
        Heading (rad, from north, clockwise).
    step : ndarray of shape (n_samples - 1,)
        Odometer distance (m) from sample ``s`` to ``s + 1``.
    steps : ndarray of int, shape (n_fixes,)
        Each fix's step (the fix at step ``k`` is sample ``k + 1``), increasing.
    z_gps : ndarray of shape (n_fixes, 2)
        The fixes, east/north (m).
    sigma : float, optional
        The fixes' typical standard deviation per axis (m; default 3).
    swapped : ndarray of shape (n_fixes, 2), optional
        The fixes with latitude and longitude exchanged (east/north, m), when they came
        as latitude/longitude: tried as a cause.
    truth : ndarray of shape (n_samples, 2), optional
        Reference east/north (m): the fixes must lie near it (median within
        ``max(100 m, 30 sigma)``).
    yaw_rate : bool
        The heading is a yaw rate's integral (:meth:`DRRun.from_arrays`'s ``yaw_rate``): a track that fits
        the fixes turned the other way is named as the yaw rate's sign.
    radians : bool
        The fixes came as latitude/longitude all within ``pi/2`` and ``pi``: fixes far from the truth, or a
        track many times their length, are named as lat/lon in radians.
    speed : ndarray of shape (n_samples,), optional
        The speed (m/s) as the drive gave it, where it gave one: a speed held or interpolated between the fixes (a
        receiver's) is looked for in it rather than in ``step``.

    Raises
    ------
    ValueError
        ``dt`` over :data:`MAX_DT`, a ``sigma`` not in metres (:data:`SIGMA_PAST_SCATTER`), or a median
        chord angle over :data:`MAX_ANGLE_DEG` or length ratio outside :data:`RATIO_RANGE`, with the likely cause.
    """
    if dt > MAX_DT:
        raise ValueError(interval_refusal(dt))
    if len(steps):
        _warn_two_sources(dt, heading, step, steps, z_gps)
    _gps_derived(dt, heading, step, steps, speed)
    unit = _sigma_unit(heading, step, steps, z_gps, sigma)
    if unit:
        raise ValueError(f"plausibility: {unit}{_OVERRIDE}")
    pairs = _chord_pairs(steps, z_gps, sigma, step)
    clock = _clock_told(dt, heading, step, steps, z_gps, pairs)
    _check_truth(steps, z_gps, truth, 3.0 if sigma is None else float(sigma), clock, radians)
    _warn_carried(dt, step, steps, z_gps)
    if len(pairs) < _MIN_CHORDS:
        return
    ang, ratios, lengths = _chord_angles(heading, step, steps, z_gps, pairs)  # once, for every test below
    angle, ratio = _medians(ang, ratios)
    fit = _offset_fit(ang, steps, pairs, dt)
    told = _offset_told(fit)
    if _fits(angle, ratio) or (_fits(0.0, ratio) and _drifting_gyro(fit)):
        if _fits(angle, ratio):  # (a drifting gyro's own stretches fit less, and a mirrored zero some of them)
            _refuse_mirrored(heading, step, steps, z_gps, pairs, ang, yaw_rate, len(pairs), angle, ratio)
        if clock is not None:  # the chords as stamped are misplaced: neither offset nor scale can be judged
            warnings.warn(f"plausibility: {_clock_remedy(*clock)}", RuntimeWarning, stacklevel=4)
            return
        still = ((yaw_rate and _yaw_unit_cause(heading, step, steps, z_gps, pairs))
                 or _still_cause(heading, step, steps, z_gps, pairs))  # (nor turns: fixes 18 s late turn 18 s late)
        if still:
            raise ValueError(f"plausibility: {still}{_OVERRIDE}")
        _warn_tilted(heading, step, steps, z_gps, pairs)
        _warn_stretch_convention(ang, heading, step, steps, z_gps, pairs, dt, yaw_rate)
        if not yaw_rate:  # (a yaw rate's integral turns with the car's turns, not with its direction)
            _warn_deviation(dt, heading, step, steps, z_gps, sigma, pairs)
        if told is not None:
            warnings.warn(f"plausibility: over {len(pairs)} moving stretches between GPS fixes, "
                          f"{_offset_remedy(*fit[:3], filters=True)}", RuntimeWarning, stacklevel=4)
        _warn_scale(lengths, len(pairs))
        _warn_drag(dt, heading, step, steps, z_gps)
        return
    found = (f"median over {len(pairs)} moving stretches between GPS fixes: the dead-reckoned track is "
             f"{angle:.0f} degrees off the fixes' course and {ratio:.3g} times their distance")
    unit_ratio, decade = _unit_ratio(step, steps, z_gps, sigma, ratio, heading)  # (units: on chords that long)
    length_unit = _ratio_cause(unit_ratio, decade, " over stretches as long on the road")
    per_sample = _per_sample_cause(ratio, dt)
    if ratio < STILL_RATIO:  # (no angle means anything then)
        cause = (f"the speed moves the dead-reckoned track {ratio:.2g} times the fixes' distance: it reads 0, or "
                 "nearly, where the fixes move (a speed from a logger of its own whose times do not overlap the "
                 "drive's: a local time read as UTC, a clock offset of hours; or a speed in the wrong unit)")
    elif yaw_rate and (unit := _yaw_unit_cause(heading, step, steps, z_gps, pairs)):
        cause = unit  # (a course that hardly turns fits a mirrored zero as well as any)
    elif yaw_rate and angle > MAX_ANGLE_DEG and (_mirrored(heading, step, steps, z_gps, pairs) is not None
                                              or _mirrored_drifting(heading, step, steps, z_gps, pairs, dt)):
        cause = _YAW_SIGN  # (a track turned the wrong way also misplaces the chords, which a clock offset is sought in)
    elif clock is not None and not (_decade_off(ratio) or per_sample or length_unit):
        # (a clock offset misplaces the chords but leaves their lengths: a track a unit's factor long is the unit's,
        # whatever offset fits its misplaced chords best; a speed in mm/s was told a clock offset, stop 65)
        cause = _clock_remedy(*clock) + "; else check the units, the heading's zero and sign, and the fixes' frame"
    elif per_sample:
        cause = per_sample
    elif _decade_off(ratio) and not (radians and ratio > 10.0):  # (chords a fix or two long, or many: the
        # angle says nothing then; lat and lon in radians, read as degrees, lie that much closer together)
        cause = length_unit or (
            f"the speed or the odometer is in another unit: the dead-reckoned track is {ratio:.3g} times the fixes' "
            "distance (a wheel-tick count needs the distance a tick, and a counter that wrapped its range added back)")
    elif (RATIO_RANGE[0] <= ratio <= RATIO_RANGE[1]  # (a track of another length turns elsewhere)
          and (still := _still_cause(heading, step, steps, z_gps, pairs))):
        cause = still
    elif angle <= MAX_ANGLE_DEG:
        cause = ((_RADIANS if radians and ratio > 10.0 else None) or length_unit
                 or "check the units of speed/odometer and time")
    elif length_unit and _drifting_gyro(fit):  # a drifting gyro's angle, and a length in another unit
        cause = (length_unit + f"; the angle is a gyro's drift ({fit[2]:+.2g} deg/s from a heading right at "
                 "the start)")
    else:
        cause = _track_cause(heading, step, steps, z_gps, pairs, swapped,
                             told if told is not None and _fits(0.0, ratio) else None, dt)
        check = "check the heading's zero (north) and sign (clockwise), and the fixes' frame"
        cause = (_offset_remedy(*fit[:3]) + "; else " + check) if cause == "offset" else (cause or check)
    raise ValueError(f"plausibility: {found} (expected at most {MAX_ANGLE_DEG:g} degrees and "
                     f"{RATIO_RANGE[0]}-{RATIO_RANGE[1]}): {cause}{_OVERRIDE}")
#: The window (s) over which the fixes less the dead-reckoned track are fitted for a drag (:func:`fix_drag`): long
#: enough for the car to turn while a drag of a few decimetres a second walks the fixes tens of metres, short enough
#: for a gyro's heading error to stay a quadratic in time.
DRAG_WINDOW_S = 180.0
#: The spacing (s) of the windows' starts.
DRAG_EVERY_S = 30.0
#: The level of a window's test of a drag (an F-test of the drag's two velocity components beyond the nuisance
#: model, its statistic and degrees of freedom divided by the residuals' integrated autocorrelation time). Far under
#: the reader's other levels: the fixes' errors are not the test's (a street's multipath drifts for minutes, and a
#: city analog's fixes moved 0.27 m/s over one). Of 530 simulated drives without a drag, the least p of a window that
#: could count (:data:`DRAG_MIN_SPEED`, :data:`DRAG_MIN_TURN_DEG`) is 1.7e-9 (the phone analog's seed 101, whose
#: next window reads 4e-4), the least of two such windows together (:data:`DRAG_MIN_WINDOWS`) 3.7e-7 (the city
#: analog's seed 70); the user trials' drives without a drag 1.3e-8 and 4.8e-7 (a ferry, which ``carried`` names);
#: the third trial's spoofer (0.33 m/s for 240 s) 4.2e-37 and 1.9e-30
#: (``docs/study-outputs/dr/user-trial/drag_null.txt``).
DRAG_LEVEL = 1e-9
#: The least drag speed (m/s) a window must fit to count: a street's multipath moves the fixes' offset by metres
#: over minutes; the spoofer's windows fit 0.17-0.37 m/s.
DRAG_MIN_SPEED = 0.15
#: The least the car turns (deg) within a window that counts: on a straight road a drag along it is a speed
#: scale's, and across it a heading offset's.
DRAG_MIN_TURN_DEG = 60.0
#: The fewest windows that must count, each at most two spacings after the one before (a window between them may
#: miss: the one over a walk's end, whose fixes snap back), before a stretch is named: a drag lasts, a multipath's
#: wander seldom twice over (the null drives' single windows reach 1.7e-9, their pairs 3.7e-7).
DRAG_MIN_WINDOWS = 2
#: The 2-D steps of the fixes (a multipath offset that changes, a wheel's spin on snow that puts the dead-reckoned
#: track ahead by metres in seconds) fitted as nuisance in each window, chosen greedily on a 10 s grid. The third
#: trial's snow drive (wheel spin ten times) reads, at its least, p = 4.4e-8 with none, 2.9e-15 (0.57 m/s) with one,
#: 1.3e-6 with two and 8.5e-7 with three; the spoofer 1.4e-37, 2.4e-38, 4.2e-37 and 9.6e-33.
DRAG_STEPS = 2
#: The margin (s) by which the span the warning says to drop is wider, each side, than the walk fitted
#: (:func:`_drag_ramp`, on a 10 s grid): the spoof drive's walk of 240-480 s was fitted as 260-480 s; its fixes' offset
#: is small near its start, and the heading's drift and the steps fitted beside it take some of it.
DRAG_MARGIN_S = 20.0
#: The fewest fixes a window needs.
DRAG_MIN_FIXES = 20
_DRAG_ITERATIONS = 3
_DRAG_GRID_S = 10.0


def _drag_columns(dt, h, step, at, idx, corr):
    """The nuisance columns ``(2 n, 9)`` of the window of fixes ``idx`` (their samples ``at[idx]``) and the
    dead-reckoned track's displacement at each ``(2 n,)``, its steps' headings ``h`` (unwrapped) turned by ``corr``
    (rad, one per step of the window), and the functions of each step a heading error is fitted as (offset, drift,
    quadratic drift, gyro scale, latency)."""
    si = at[idx]
    a, b = int(si[0]), int(si[-1])
    hs = h[a + 1:b + 1] + corr
    length = step[a:b]
    ue, un = np.sin(hs), np.cos(hs)
    ee, nn = length * ue, length * un
    pos = si - a

    def cum(v):
        return np.r_[0.0, np.cumsum(v)][pos]

    tt = dt * np.arange(1, b - a + 1)
    turned = h[a + 1:b + 1] - h[a]
    rate = (h[a + 1:b + 1] - h[a:b]) / dt
    funcs = (np.ones_like(tt), tt, tt ** 2 / 60.0, turned, rate)
    dstep = np.diff(step[a - 1:b]) if a >= 1 else np.r_[0.0, np.diff(step[:b])]  # (the speed's change: its latency)
    n = len(idx)
    cols = [np.r_[np.ones(n), np.zeros(n)], np.r_[np.zeros(n), np.ones(n)], np.r_[cum(ee), cum(nn)],
            np.r_[cum(dstep * ue), cum(dstep * un)]]
    cols += [np.r_[cum(f * nn), -cum(f * ee)] for f in funcs]
    return np.stack(cols, axis=1), np.r_[cum(ee), cum(nn)], funcs


def _drag_fit(X, y, keep):
    kk = np.r_[keep, keep]
    coef = np.linalg.lstsq(X[kk], y[kk], rcond=None)[0]
    return coef, y - X @ coef


def _drag_prepared(dt, h, step, at, z, idx, W):
    """The window's nuisance columns, the fixes less the dead-reckoned track and the fixes kept ``(base, y, keep)``:
    the track's steps turned by the heading error fitted (beside ``W``), :data:`_DRAG_ITERATIONS` times (a gyro's
    drift of 0.3 deg/s turns it 54 degrees over a window, past what one linearisation holds), each fit then cut to
    the fixes within three robust sigmas (at least 1 m) of it (a fix jumped by multipath)."""
    n = len(idx)
    corr = np.zeros(int(at[idx[-1]] - at[idx[0]]))
    keep = np.ones(n, dtype=bool)
    for i in range(_DRAG_ITERATIONS + 3):
        base, track, funcs = _drag_columns(dt, h, step, at, idx, corr)
        y = np.r_[z[idx, 0], z[idx, 1]] - track
        if i < 2:  # first the track turned as a whole, by the angle of the similarity that fits it (a gyro's drift
            # since the drive's start can have turned it by more than a right angle, past any linearisation)
            coef = _drag_fit(base[:, [0, 1, 2, 4]], y, keep)[0]
            corr = corr + np.arctan2(coef[3], 1.0 + coef[2])
            continue
        coef, res = _drag_fit(np.hstack([base, W]), y, keep)
        r = np.hypot(res[:n], res[n:])
        keep = r <= max(3.0 * 1.4826 * float(np.median(r[keep])), 1.0)
        corr = corr + np.arctan2(coef[4], 1.0 + coef[2]) + sum(c * f for c, f in zip(coef[5:9], funcs[1:]))
    return base, y, keep


def _drag_steps(B, yk, tk, span, count=None):
    """The columns of the ``count`` (default :data:`DRAG_STEPS`) 2-D steps of the fixes, at times ``tk`` (s from the
    window's first fix), that take the most from the residual sum of squares beside the nuisance columns ``B``, chosen
    one after the other on a :data:`_DRAG_GRID_S` grid within ``span`` (s)."""
    chosen = []
    for _ in range(DRAG_STEPS if count is None else count):
        best = None
        for ts in np.arange(_DRAG_GRID_S, span - _DRAG_GRID_S + 1e-9, _DRAG_GRID_S):
            if ts in chosen:
                continue
            X = np.hstack([B, _drag_step_columns(tk, chosen + [ts])])
            res = yk - X @ np.linalg.lstsq(X, yk, rcond=None)[0]
            if best is None or float(res @ res) < best[0]:
                best = (float(res @ res), ts)
        if best is None:
            break
        chosen.append(best[1])
    return _drag_step_columns(tk, chosen)


def _drag_window(dt, h, step, at, z, idx, window):
    """One window's test of a drag (:func:`drag_windows`): ``(p, w_east, w_north, turn (deg))``, or None where
    fewer than :data:`DRAG_MIN_FIXES` fixes are kept."""
    from scipy.stats import f as f_dist

    from ..metrics import integrated_autocorrelation

    n = len(idx)
    tau = dt * (at[idx] - at[idx[0]])
    W = np.zeros((2 * n, 2))
    W[:n, 0] = W[n:, 1] = tau
    base, y, keep = _drag_prepared(dt, h, step, at, z, idx, W)
    m = int(keep.sum())
    if m < DRAG_MIN_FIXES:
        return None
    kk = np.r_[keep, keep]
    B, Wk, yk = base[kk], W[kk], y[kk]
    S = _drag_steps(B, yk, tau[keep], window)
    Xr, Xf = np.hstack([B, S]), np.hstack([B, S, Wk])
    rr = yk - Xr @ np.linalg.lstsq(Xr, yk, rcond=None)[0]
    cf = np.linalg.lstsq(Xf, yk, rcond=None)[0]
    rf = yk - Xf @ cf
    rss_f = float(rf @ rf)
    dof = 2 * m - Xf.shape[1]
    if dof <= 0 or rss_f <= 0.0:
        return None
    c = max(integrated_autocorrelation(list(np.stack([rf[:m], rf[m:]], axis=1))), 1.0)
    stat = (float(rr @ rr) - rss_f) / 2.0 / (rss_f / dof) / c
    p = float(f_dist.sf(stat, 2, max(dof / c, 1.0)))
    seen = h[at[idx]]
    return p, float(cf[-2]), float(cf[-1]), float(np.rad2deg(seen.max() - seen.min()))


def _drag_step_columns(tk, times):
    m = len(tk)
    S = np.zeros((2 * m, 2 * len(times)))
    for i, ts in enumerate(times):
        st = (tk >= ts).astype(float)
        S[:m, 2 * i] = st
        S[m:, 2 * i + 1] = st
    return S


def drag_windows(dt, heading, step, steps, z_gps, window=DRAG_WINDOW_S, every=DRAG_EVERY_S):
    """Every window's test: ``[(start s, end s, p, w_east, w_north, turn deg), ...]`` (times from the first
    sample)."""
    h = np.unwrap(np.asarray(heading, dtype=float))
    step = np.asarray(step, dtype=float)
    at = np.asarray(steps, dtype=int) + 1
    z = np.asarray(z_gps, dtype=float)
    out = []
    if len(at) < DRAG_MIN_FIXES:
        return out
    tf = at * dt
    t0 = float(tf[0])
    while t0 + window <= tf[-1] + 1e-9:
        idx = np.flatnonzero((tf >= t0) & (tf < t0 + window))
        if len(idx) >= DRAG_MIN_FIXES and at[idx[-1]] > at[idx[0]]:
            got = _drag_window(dt, h, step, at, z, idx, window)
            if got is not None:
                out.append((t0, t0 + window) + got)
        t0 += every
    return out


def _drag_ramp(dt, h, step, at, z, idx):
    """The drag's own stretch within the fixes ``idx`` (the windows that counted, together): the fix offset
    ``w clip(t - T1, 0, T2 - T1)`` (a walk from ``T1`` to ``T2``, held after) beside the nuisance model and a 2-D step
    at ``T2`` (fixes that snap back when the walk ends), ``T1 < T2`` on a :data:`_DRAG_GRID_S` grid, the pair that
    fits best: ``(T1, T2, w_east, w_north)``, times in s from the first sample."""
    n = len(idx)
    tau = dt * (at[idx] - at[idx[0]])
    grid = np.arange(0.0, float(tau[-1]) + 1e-9, _DRAG_GRID_S)

    def walk(t, t1, t2):
        R = np.zeros((2 * len(t), 4))  # the walk, and a step where it ends
        R[:len(t), 0] = R[len(t):, 1] = np.clip(t - t1, 0.0, t2 - t1)
        R[:len(t), 2] = R[len(t):, 3] = (t >= t2)
        return R

    best = (None, 0.0, float(tau[-1]) + 1.0)  # first a walk over all the fixes; then from the best walk's fit
    for _ in range(2):
        base, y, keep = _drag_prepared(dt, h, step, at, z, idx, walk(tau, best[1], best[2]))
        kk = np.r_[keep, keep]
        B, yk, tk = base[kk], y[kk], tau[keep]
        best = None
        for i, t1 in enumerate(grid):
            for t2 in grid[i + 2:]:
                X = np.hstack([B, walk(tk, t1, t2)])
                coef = np.linalg.lstsq(X, yk, rcond=None)[0]
                res = yk - X @ coef
                if best is None or float(res @ res) < best[0]:
                    best = (float(res @ res), t1, t2, float(coef[-4]), float(coef[-3]))
    start = dt * float(at[idx[0]])
    return start + best[1], start + best[2], best[3], best[4]


def fix_drag(dt, heading, step, steps, z_gps, sigma=None):
    """The stretches where the fixes are dragged away from the dead-reckoned track: a world-fixed velocity of the
    fixes' offset (a spoofer walking them off, a receiver's fault) that nothing the dead reckoning errs by explains.

    In windows of :data:`DRAG_WINDOW_S` every :data:`DRAG_EVERY_S` (:func:`drag_windows`), the fixes less the
    dead-reckoned track are fitted with the track's own errors: a position offset, a speed scale, a speed latency, a
    heading error that is an offset, a drift linear and quadratic in time, a gyro scale (proportional to the angle
    turned) and a latency (proportional to the turn rate), the track's steps turned by the heading error fitted
    (iterated: a gyro's drift turns it tens of degrees over a window), and :data:`DRAG_STEPS` 2-D steps of the fixes
    (a multipath offset that changes; a wheel's spin that puts the track ahead), chosen greedily; fixes past three
    robust sigmas (at least 1 m) are left out. A drag, the fixes' offset growing linearly in time, is tested beyond
    them: an F-test of its two components, its statistic and degrees of freedom divided by the residuals' integrated
    autocorrelation time. A window counts where p < :data:`DRAG_LEVEL`, the drag is :data:`DRAG_MIN_SPEED` or faster
    and the car turned :data:`DRAG_MIN_TURN_DEG` or more (on a straight road a drag is a speed scale's or a heading
    offset's); :data:`DRAG_MIN_WINDOWS` such windows, each at most two spacings after the one before, make a stretch,
    whose start, end and velocity are then fitted over them and a third of a window each side (:func:`_drag_ramp`: a
    walk from one time to another, on a 10 s grid). The warning's span to drop is that walk widened by
    :data:`DRAG_MARGIN_S` each side.

    Returns
    -------
    list of tuple
        ``[(start, end, w_east, w_north, speed, p), ...]``: the walk's start and end (s from the first sample, as the
        study's ``--outage-starts`` counts), its velocity (m/s east and north) and speed, and the least p of its
        windows. The arguments are :func:`check_drive`'s (``sigma`` unused: the fit measures the fixes' scatter).
    """
    h = np.unwrap(np.asarray(heading, dtype=float))
    at = np.asarray(steps, dtype=int) + 1
    tf = at * dt
    found = []
    for run in _drag_runs(drag_windows(dt, heading, step, steps, z_gps)):
        # the walk fitted over the windows and a third of a window each side (a walk's ends fall inside its first
        # and last windows, or past them: fixes that snap back are in the next window)
        idx = np.flatnonzero((tf >= run[0][0] - DRAG_WINDOW_S / 3) & (tf < run[-1][1] + DRAG_WINDOW_S / 3))
        t1, t2, we, wn = _drag_ramp(dt, h, np.asarray(step, dtype=float), at, np.asarray(z_gps, dtype=float), idx)
        found.append((t1, t2, we, wn, float(np.hypot(we, wn)), min(w[2] for w in run)))
    return found


def _drag_counts(w):
    """Whether a window of :func:`drag_windows` counts toward a stretch (:func:`fix_drag`)."""
    return w[2] < DRAG_LEVEL and float(np.hypot(w[3], w[4])) >= DRAG_MIN_SPEED and w[5] >= DRAG_MIN_TURN_DEG


def _drag_runs(wins):
    """The windows that count (:func:`_drag_counts`), in groups whose starts are at most two spacings apart (one
    window between them may miss the level: a drag's end snaps back within it), of :data:`DRAG_MIN_WINDOWS` or more."""
    runs, run = [], []
    for w in wins:
        if not _drag_counts(w):
            continue
        if run and w[0] - run[-1][0] > 2 * DRAG_EVERY_S + 1e-6:
            runs.append(run)
            run = []
        run.append(w)
    runs.append(run)
    return [r for r in runs if len(r) >= DRAG_MIN_WINDOWS]


def _drag_span(t1, t2):
    """The span of fixes the warning of a walk fitted from ``t1`` to ``t2`` (s) says to drop: widened by
    :data:`DRAG_MARGIN_S` each side, to whole tens of seconds, from 0."""
    return max(np.floor((t1 - DRAG_MARGIN_S) / 10.0) * 10.0, 0.0), np.ceil((t2 + DRAG_MARGIN_S) / 10.0) * 10.0


def _warn_drag(dt, heading, step, steps, z_gps):
    """Warn of the stretches :func:`fix_drag` finds, the first named (with the window's turn) and the others counted."""
    found = fix_drag(dt, heading, step, steps, z_gps)
    if not found:
        return
    t1, t2, we, wn, speed, p = found[0]
    walked = speed * (t2 - t1)
    spans = [_drag_span(f[0], f[1]) for f in found]
    t1, t2 = spans[0]
    bearing = float(np.rad2deg(np.arctan2(we, wn))) % 360.0
    h = np.unwrap(np.asarray(heading, dtype=float))
    at = np.asarray(steps, dtype=int) + 1
    inside = h[at[(at * dt >= t1) & (at * dt <= t2)]]
    turn = float(np.rad2deg(inside.max() - inside.min())) if len(inside) else 0.0
    given = ",".join(f"{a:.0f},{b:.0f}" for a, b in spans)
    more = f" (and {len(found) - 1} more such stretch(es))" if len(found) > 1 else ""
    warnings.warn(f"plausibility: from t = {t1:.0f} s to {t2:.0f} s the GPS fixes walk away from the dead-reckoned "
                  f"track at {speed:.2f} m/s toward bearing {bearing:.0f} degrees (east {we:+.2f}, north {wn:+.2f} "
                  f"m/s; {walked:.0f} m by its end){more}: the car turned {turn:.0f} degrees while the "
                  "fixes' offset grew one way, which no heading offset, drift or gyro scale, speed scale or step of "
                  f"the fixes fitted beside it explains (p = {p:.1g}). A spoofer walking the fixes off (their reported "
                  "accuracy unchanged), or a receiver's fault. The GPS/DR filters follow the fixes there (their "
                  "heading and odometer states take the drag for the dead reckoning's errors), and an outage after it "
                  "starts where the fixes led them. Drop those fixes: drop_fixes=["
                  + ", ".join(f"({a:.0f}, {b:.0f})" for a, b in spans) + f"] (command line: --drop-fixes {given}), "
                  "and check the receiver (a spoofer's fixes agree with one another, not with the car's own sensors)",
                  RuntimeWarning, stacklevel=4)


#: The least offset (m) between two sources of fixes taking turns in one column (:func:`alternating_sources`) that the
#: reader warns of: the sixth user trial's two receivers 5.5 m apart took the 8-state EKF's outage ends from 1.59 to
#: 3.33 m (median) against their twin's; of its other drives and the earlier trials', none reads over 0.61 m (a
#: twin whose two receivers agree but for their own wandering errors).
ALTERNATING_MIN_M = 2.0
#: ... and the z-score its estimate must pass (the alternating mean of the fixes' offset changes over its standard
#: error: slow errors, a multipath that lasts, a heading off, cancel from one pair to the next).
ALTERNATING_Z = 10.0
#: The fewest pairs of fixes in consecutive slots.
ALTERNATING_MIN_PAIRS = 50


def alternating_sources(dt, heading, step, steps, z_gps):
    """Fixes from two sources taking turns in one column (two receivers, or two antennas, merged by a logger): the
    fixes' offset from the dead-reckoned track changes by the sources' offset ``D`` from each fix to the next, one
    way then the other. The fixes are given slots at their median interval; between fixes in consecutive slots the
    change of their offset from the track, signed by the later slot's parity, averages ``D`` (the odd slots' source
    less the even's), and anything that changes slowly (the receivers' own errors, a heading off, a speed scale)
    cancels. Returns ``(D (2,), odd (n_fixes,) bool, z, pairs)`` where ``|D|`` is at least :data:`ALTERNATING_MIN_M`
    and ``z`` at least :data:`ALTERNATING_Z` over :data:`ALTERNATING_MIN_PAIRS` or more pairs, else None."""
    at = np.asarray(steps, dtype=int) + 1
    z = np.asarray(z_gps, dtype=float)
    if len(at) < ALTERNATING_MIN_PAIRS + 1:
        return None
    off = z - _track(np.asarray(heading, dtype=float), np.asarray(step, dtype=float))[:, at].T
    gap = float(np.median(np.diff(at)))
    slot = np.round((at - at[0]) / gap).astype(int)
    odd = slot % 2 == 1
    next_slot = np.diff(slot) == 1
    if next_slot.sum() < ALTERNATING_MIN_PAIRS:
        return None
    sign = np.where(odd[1:], 1.0, -1.0)[next_slot]
    a = sign[:, None] * np.diff(off, axis=0)[next_slot]
    D = a.mean(axis=0)
    se = a.std(axis=0, ddof=1) / np.sqrt(len(a))
    zs = float(np.hypot(*(D / np.maximum(se, 1e-12))))
    if float(np.hypot(*D)) < ALTERNATING_MIN_M or zs < ALTERNATING_Z:
        return None
    return D, odd, zs, int(len(a))


def _warn_two_sources(dt, heading, step, steps, z_gps):
    """Warn of the fixes of a second source taking turns with the first in one column (:func:`alternating_sources`).
    Not mended: which of the two is right the fixes cannot say, and moved onto either, or to their midpoint, the sixth
    trial's drive ended its outages farther off than as written (EKF-8 6.21 and 3.86 m, median, against 3.33; the
    twin of one source 1.59; stop 72)."""
    found = alternating_sources(dt, heading, step, steps, z_gps)
    if found is None:
        return
    D, odd, zs, pairs = found
    first = dt * float(int(steps[np.argmax(odd)]) + 1)
    warnings.warn(f"the GPS fixes take turns between two sources {np.hypot(*D):.2f} m apart (every other fix, from "
                  f"t = {first:.10g} s on, {D[0]:+.2f} m east and {D[1]:+.2f} m north of the ones between; z = {zs:.0f} "
                  f"over {pairs} pairs): two receivers, or two antennas, merged into one column. The filters follow "
                  "neither, but a position between them, off by up to half that from either, and the outages start "
                  "there; which one is right the fixes cannot say. Give one source's fixes alone (its receiver's, "
                  "or those of the antenna the truth, or the car's reference point, is at)", RuntimeWarning,
                  stacklevel=4)
