r"""Drives for the GPS/DR filters: simulated scenarios, one's own recorded drive, GPS outages.

A drive is a :class:`DRRun`: DR samples (gyro heading and odometer distance per sample)
on a regular grid, the GPS fixes that fall on that grid, and, where known, the truth.
Three ways to get one:

* :func:`simulate_scenario` of a :class:`Scenario` (the named ones are in
  :data:`SCENARIOS`): the truth and the sensors, with seeded noise;
* :meth:`DRRun.from_arrays` or :func:`~filterwnn.navigation.drives.read_drive_csv`: one's own drive (time, heading,
  odometer distance or speed, GPS fixes as east/north metres or latitude/longitude,
  optionally each fix's accuracy and the truth), validated;
* :func:`~filterwnn.navigation.drives.load_car_drive`: the onavdata HGuide n380 car drives
  (optional ``data`` extra).

Conventions (the ones :class:`DRRun` documents): ``run.t`` are the sample times after
the first one, measured from it (``t[0]`` is one sample interval), ``run.x0`` is the
state at the first sample (``t = 0``), ``run.z_dr[k]`` is ``[heading (rad, from north,
clockwise), distance driven since the previous sample (m)]``, and GPS fix ``j`` belongs to
step ``run.gps_steps[j]``. A missing fix is absent, never NaN.

Outages are cut in with :func:`with_outage` (one) or placed by :func:`outage_starts`
(given start times, or spread evenly over the parts of the drive where the car moves and has its fixes: none
starts in the drive's own gaps of fixes, :func:`fix_gaps`).

>>> run = simulate_scenario(SCENARIOS["straight"](), rng=0)
>>> run.x_true.shape, run.z_dr.shape
((2000, 6), (2000, 2))
>>> import numpy as np
>>> t = np.arange(0.0, 10.05, 0.1)
>>> own = DRRun.from_arrays(t, np.full(t.size, 0.5), speed=np.full(t.size, 10.0),
...                         gps_t=t[::10], east=10 * np.sin(0.5) * t[::10],
...                         north=10 * np.cos(0.5) * t[::10], gps_sigma=3.0)
>>> own.z_dr.shape, own.gps_steps[:3], float(own.scenario.dt)
((100, 2), array([ 9, 19, 29]), 0.1)
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, replace
from typing import NamedTuple, Optional

import numpy as np

from .._validation import check_finite, check_positive, check_rng
from ._plausibility import _run_bounds, _track
from .dead_reckoning import HEADING_ROUNDING, SENSOR_GRADES, dr_fx, wrap_angle

__all__ = [
    "Scenario",
    "DRRun",
    "SCENARIOS",
    "true_trajectory",
    "simulate_scenario",
    "latlon_to_en",
    "en_to_latlon",
    "with_outage",
    "outage_starts",
    "fix_gaps",
    "OUTAGE_GAP_SLACK",
    "HEADING_ROUNDING",
    "STOPPED",
]


# --------------------------------------------------------------------------- simulation


@dataclass(frozen=True)
class Scenario:
    """A simulated drive and its sensors (all times in s, angles in degrees).

    The truth has no process noise: its acceleration follows the speed and turn
    profile (piecewise constant over each sample), integrated by the kinematic
    transition, so the truth is exactly what the model with ``T^2/2`` describes.

    Attributes
    ----------
    name : str
    duration, dt : float
        Length of the run and DR sample interval.
    speed, heading : float
        Initial speed (m/s) and heading (deg from north, clockwise).
    turns : tuple of (t_start, t_end, angle_deg)
        Constant-rate turns (positive clockwise).
    speed_changes : tuple of (t_start, t_end, delta_speed)
        Constant-rate speed changes (m/s).
    sigma_heading, sigma_odometer : float
        Nominal DR noise (deg, m per sample).
    t_switch, factor : float
        From ``t_switch`` on, both DR noise levels are multiplied by ``factor``.
    outlier_prob, outlier_deg : float
        After ``t_switch``, each heading has this chance of a +-``outlier_deg`` error.
    odometer_scale, heading_bias : float
        True odometer scale ``zeta`` and heading bias (deg).
    gps_rate, sigma_gps : float
        GPS fix rate (Hz; 0 for none) and noise per axis (m).
    outages : tuple of (t_start, t_end)
        Intervals without GPS.
    heading_drift : float
        Gyro rate bias (deg/s): the heading bias grows as ``heading_bias + heading_drift * t``
        (a MEMS gyro's residual bias, integrated).
    title, figure : str
        The scenario in words and the stem of its figure's file name (the DR study's
        figures); empty: built from ``name``.
    """

    name: str = "straight"
    duration: float = 200.0
    dt: float = 0.1
    speed: float = 10.0 * np.sqrt(2.0)
    heading: float = 45.0
    turns: tuple = ()
    speed_changes: tuple = ()
    sigma_heading: float = 1.0
    sigma_odometer: float = 0.02
    t_switch: float = 150.0
    factor: float = 1.0
    outlier_prob: float = 0.0
    outlier_deg: float = 30.0
    odometer_scale: float = 1.0
    heading_bias: float = 0.0
    gps_rate: float = 0.0
    sigma_gps: float = 3.0
    outages: tuple = field(default=())
    heading_drift: float = 0.0
    title: str = ""
    figure: str = ""

    def __post_init__(self):
        for name in ("duration", "dt", "factor"):
            check_positive(getattr(self, name), name)
        for name in ("speed", "sigma_heading", "sigma_odometer", "outlier_deg", "gps_rate",
                     "sigma_gps", "odometer_scale"):
            check_positive(getattr(self, name), name, strict=False)
        if not self.t_switch >= 0:  # inf means never
            raise ValueError(f"t_switch must be >= 0 (inf: never), got {self.t_switch}")
        if not 0 <= self.outlier_prob <= 1:
            raise ValueError(f"outlier_prob must satisfy 0 <= outlier_prob <= 1, got {self.outlier_prob}")

    @property
    def n_steps(self):
        return int(round(self.duration / self.dt))

    @property
    def x0(self):
        """True initial state ``(6,)``."""
        h = np.deg2rad(self.heading)
        return np.array([0.0, self.speed * np.sin(h), 0.0, 0.0, self.speed * np.cos(h), 0.0])

    def with_(self, **changes):
        """A copy with some fields changed."""
        return replace(self, **changes)


_TURNING = dict(
    turns=((20.0, 30.0, 90.0), (60.0, 75.0, -135.0), (100.0, 110.0, 60.0), (160.0, 175.0, -90.0)),
    speed_changes=((40.0, 50.0, -6.0), (85.0, 95.0, 8.0), (130.0, 140.0, -4.0)),
)

#: Named scenario factories; each accepts keyword overrides of :class:`Scenario` fields.
SCENARIOS = {
    # the paper: straight road, 10*sqrt(2) m/s at 45 deg, noise x20 at 150 s
    "straight": lambda **kw: Scenario(**{"name": "straight", "title": "straight road", "figure": "dr_straight_road",
                                         "factor": 20.0, **kw}),
    # turns and speed changes, noise x5 at 150 s
    "turns": lambda **kw: Scenario(**{"name": "turns", "title": "turning route", "figure": "dr_turning_route",
                                      "factor": 5.0, **_TURNING, **kw}),
    # heading near 180 deg: west-south-west... through south (180) and back, noise x5
    "heading180": lambda **kw: Scenario(
        **{
            "name": "heading180",
            "title": "drive through heading 180 deg",
            "figure": "dr_through_heading_180_deg",
            "heading": 170.0,
            "turns": ((20.0, 40.0, 20.0), (90.0, 110.0, -25.0), (160.0, 180.0, 30.0)),
            "factor": 5.0,
            **kw,
        }
    ),
    # noise x5 plus 10 % heading outliers of +-30 deg after 150 s
    "outliers": lambda **kw: Scenario(
        **{"name": "outliers", "title": "heading outliers", "figure": "dr_heading_outliers", "factor": 5.0,
           "outlier_prob": 0.1, **kw}
    ),
    # GPS/DR: turning route, 1 Hz GPS (3 m) with outages, 2 % odometer scale, 2 deg bias
    "gpsdr": lambda **kw: Scenario(
        **{
            "name": "gpsdr",
            "title": "GPS/DR",
            "figure": "gps_dr",
            "factor": 1.0,
            "odometer_scale": 1.02,
            "heading_bias": 2.0,
            "gps_rate": 1.0,
            "outages": ((50.0, 80.0), (120.0, 170.0)),
            **_TURNING,
            **kw,
        }
    ),
}


class DRRun(NamedTuple):
    """One simulated drive.

    Attributes
    ----------
    t : ndarray of shape (n_steps,)
        Sample times ``dt, 2 dt, ...`` (s).
    x0 : ndarray of shape (6,)
        True state at ``t = 0``.
    x_true : ndarray of shape (n_steps, 6)
        True states at ``t``.
    z_dr : ndarray of shape (n_steps, 2)
        ``[heading (rad, wrapped), odometer distance (m)]``.
    gps_steps : ndarray of shape (n_fixes,)
        Indices into ``t`` of the steps with a GPS fix.
    z_gps : ndarray of shape (n_fixes, 2)
        The fixes ``[e, n]`` (m).
    R_true : ndarray of shape (n_steps, 2)
        True DR noise variances ``[heading, odometer]`` at each step (for oracle filters).
    scenario : Scenario
    gps_sigma : ndarray of shape (n_fixes,) or None
        Each fix's reported standard deviation per axis (m), when the drive has them.
    gps_offset : ndarray of shape (n_fixes,) or None
        Each fix's time less its sample's (s): a fix is placed on the sample nearest its time, and is the
        position that long after it (a fix logged between the samples of a slow DR log, or moved by a
        ``gps_latency`` finer than the samples' interval). None when every fix is at its sample's time.
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter` takes it (``gps_offset``; :meth:`gps_offset_list`).
    reversed_by_speed : bool
        The drive's speed is signed and told the car reversing (a sample below ``-REVERSING_SPEED``): the
        reversal is in the dead reckoning already, and ``filterwnn study dr`` runs the filters without the
        fixes' test for it (``GPSDRFilter(reversing_test=False)``), which could then only be wrong.
    t_start : float
        The time of the drive's first sample on its own clock (s; :meth:`from_arrays`' first ``t``): step ``k``
        is at ``t_start + t[k]`` there (``filterwnn study dr --drive`` names its warnings' steps so). 0 for a
        simulated drive.
    """

    t: np.ndarray
    x0: np.ndarray
    x_true: np.ndarray
    z_dr: np.ndarray
    gps_steps: np.ndarray
    z_gps: np.ndarray
    R_true: np.ndarray
    scenario: Scenario
    gps_sigma: Optional[np.ndarray] = None
    gps_offset: Optional[np.ndarray] = None
    reversed_by_speed: bool = False
    t_start: float = 0.0

    def gps_list(self):
        """Per-step list: the fix ``(2,)`` or ``None`` (missing GPS is ``None``, never NaN)."""
        out = [None] * len(self.t)
        for k, z in zip(self.gps_steps, self.z_gps):
            out[int(k)] = z
        return out

    def gps_sigma_list(self):
        """Per-step list: the fix's sigma (m) or ``None`` (no fix, or no per-fix accuracy)."""
        out = [None] * len(self.t)
        if self.gps_sigma is not None:
            for k, sd in zip(self.gps_steps, self.gps_sigma):
                out[int(k)] = float(sd)
        return out

    def gps_offset_list(self):
        """Per-step list: the fix's time less its sample's (s), or ``None`` (no fix, or every fix at its
        sample's time). :class:`~filterwnn.navigation.gpsdr.GPSDRFilter` takes it as ``gps_offset``."""
        out = [None] * len(self.t)
        if self.gps_offset is not None:
            for k, d in zip(self.gps_steps, self.gps_offset):
                out[int(k)] = float(d)
        return out

    @property
    def has_truth(self):
        """Whether ``x_true`` holds a reference trajectory (simulated, or given to :meth:`from_arrays`)."""
        return self.x_true is not None

    @classmethod
    def from_arrays(cls, t, heading=None, *, distance=None, speed=None, gps_t=None, east=None, north=None,
                    lat=None, lon=None, gps_sigma=None, truth=None, origin=None, name="drive",
                    max_jitter=0.2, checks=True, fill_gaps=0.0, gps_latency=0.0, intervals="auto",
                    odometer_latency=0.0, heading_offset=0.0, speed_scale=1.0, yaw_rate=None, heading_latency=0.0,
                    heading_deviation=None, drop_fixes=None, restamp_fixes=False):
        """One's own drive from arrays: validated, on the DR sample grid, in local metres.

        Parameters
        ----------
        t : array-like of shape (n_samples,)
            DR sample times (s), strictly increasing and evenly spaced: each interval within
            ``max_jitter`` of the median interval, which becomes ``dt``, or stamps that jitter about a
            regular grid (each within ``GRID_TOLERANCE`` of an interval of it, and a late one followed by
            a short interval: their lag-1 autocorrelation below ``GRID_CORRELATION``).
        heading : array-like of shape (n_samples,)
            Gyro (or fused) heading in **radians**, from north, clockwise positive (values beyond
            ``+-2 pi`` are taken for degrees and refused). Give this or ``yaw_rate``.
        yaw_rate : array-like of shape (n_samples,), optional
            The gyro's yaw rate (rad/s, clockwise positive: a right turn), in place of ``heading``: integrated
            by the trapezoid rule from the first sample, and started at the heading the fixes' course gives
            (the line through the moving stretches' angles that ``heading_offset``'s check fits, at least
            ``YAW_START_CHORDS`` of them, or a piecewise line where the drift is not steady: a gyro warming up),
            with a warning that names it and its standard error. A rate that reads its range's rail (a gyro past
            its range in tight turns: ``SATURATED_MIN_SAMPLES``, ``SATURATED_PILE``) is warned of, and the turns it
            lost, fitted to the fixes' course on either side, are added back. Values over
            ``MAX_YAW_RATE`` are refused as degrees per second; a run of up to ``MAX_SPIKE_RUN`` samples past
            what a car turns at the odometer's speed (``YAW_SPIKE_MIN``) is interpolated first, with a warning.
        distance : array-like of shape (n_samples,), optional
            Cumulative odometer reading (m), non-decreasing. Give this or ``speed``. Each increment is the
            mean speed over its interval, the speed at the interval's middle; each sample's speed is the two
            beside it interpolated to its time (the first and last sample's, their one interval's), since the
            models measure the speed at the samples.
        speed : array-like of shape (n_samples,), optional
            Odometer (wheel / CAN) speed (m/s); step ``k`` covers ``|speed[k]|`` times its interval
            (``intervals``). A signed speed below ``-REVERSING_SPEED`` is the car reversing: there the
            heading is turned by 180 degrees to be the direction of travel, with a warning. Warned
            too: a speed that reads 0 below a cutoff (``MAX_STOP_ACCEL``, ``SPEED_CUTOFF_WARN``).
            Interpolated from the samples beside them, with a warning: a 0 between samples of a car that
            cannot have stopped (``MAX_DROPOUT_ACCEL``), and a run of up to ``MAX_SPIKE_RUN`` samples that the
            speed, or the heading, jumps into and back out of faster than a car can (``SPEED_SPIKE_MIN``,
            ``MIN_TURN_RADIUS``, ``MAX_LATERAL_ACCEL``, ``HEADING_SPIKE_MIN``, ``SPIKE_NOISE``).
        gps_t : array-like of shape (n_fixes,), optional
            GPS fix times (s, same clock as ``t``), each to the nearest sample (fixes over half an
            interval outside the samples are dropped).
        east, north : array-like of shape (n_fixes,), optional
            Fix positions (m) in a local frame. Or:
        lat, lon : array-like of shape (n_fixes,), optional
            Fix latitude/longitude (degrees, WGS84), converted by :func:`latlon_to_en` about
            ``origin`` (default the first fix). Fixes at exactly lat = lon = 0, a receiver's null
            fix written before it has a position, are dropped with a warning.
        gps_sigma : float or array-like of shape (n_fixes,), optional
            Each fix's standard deviation per axis (m), e.g. the receiver's reported horizontal
            accuracy; kept in ``run.gps_sigma`` for the filters.
        truth : array-like of shape (n_samples, 2), optional
            Reference east/north (m, the fixes' frame; with ``lat``/``lon`` fixes, east/north about
            the same ``origin``). Without it the study scores against the withheld GPS fixes.
        origin : (lat0, lon0), optional
            Origin of the local frame (degrees) for ``lat``/``lon``.
        name : str
            Name of the drive (tables and figures).
        max_jitter : float
            Allowed relative deviation of a sample interval from the median interval (stamps that
            jitter about a regular grid may deviate more).
        checks : bool
            Plausibility checks against the GPS fixes (``filterwnn.navigation._plausibility``): refuse
            a sample interval over 2 s ("time looks like milliseconds") and a dead-reckoned track whose
            course or length contradicts the moving fixes ("heading looks like degrees", "speed looks
            like km/h", "lat and lon look swapped"); warn of runs of fixes that move along the dead-reckoned
            track as the odometer does (a receiver's own dead reckoning given as fixes:
            ``_plausibility.receiver_dead_reckoning``). ``False`` skips them, for a drive that really is so.
        fill_gaps : float
            Dropped DR samples: an interval that is a whole number (2 or more) of sample intervals,
            and at most ``fill_gaps`` seconds long, is filled with interpolated samples (heading
            along the shorter arc, speed or odometer and truth linearly; the fixes keep their own
            times), with a warning that counts them and names the longest gap. Default 0: such a
            drive is refused as unevenly sampled. Interpolated dead reckoning is a guess: keep it
            to a few sample intervals.
        gps_latency : float
            Seconds by which each fix's position is older than its time stamp (the receiver's
            latency, from its data sheet; or the offset between the clocks that stamped the fixes and
            the DR samples): the fix is placed at ``gps_t - gps_latency``; negative, a fix stamped
            before its position. Default 0. Unmodelled, 0.3 s at 23 m/s puts every fix 7 m behind the
            car along its track. An unknown latency of a second or two is what the GPS/DR filter's
            latency monitor estimates (``GPSDRFilter(latency_on_detection=True)``, the default); one
            past 1 s (GPS time against UTC is 18 s) the plausibility checks find from the turns, starts
            and stops, with a warning that names its value (the filters take it only once their monitor has).
        odometer_latency : float
            Seconds by which each ``speed`` (or ``distance``) sample is older than its time stamp (a CAN
            bus's or a logger's latency, from the vehicle's data sheet): the odometer is read at
            ``t + odometer_latency`` (linearly interpolated, the last sample held; the first one before it,
            for a negative latency: a speed stamped late by a clock behind the heading's). Default 0.
            Unmodelled, the dead-reckoned distance lags the heading and the fixes: 0.5 s took a phone-grade
            EKF-8's worst outage end from 28.16 to 33.01 m (docs/study-outputs/dr/sensor-faults). An unknown
            one is what the GPS/DR filter's monitor estimates and warns of, with this setting's value.
        heading_latency : float
            The same for the heading (or the yaw rate's integral): read at ``t + heading_latency``, along the
            shorter arc. A heading averaged over each sample's interval (a log thinned to 1 Hz by averaging) is
            half an interval late: 0.5 s at 1 Hz took the 1 Hz analogs' EKF-8 from 1.63-1.76 to 6.34-6.83 m
            median (docs/study-outputs/dr/log-faults/heading_latency.py); the filter's monitor then tells the
            fixes and the speed early against it, and names this setting. Default 0.
        heading_offset : float
            Degrees by which the heading reads clockwise of the car's course (its zero off: a phone mounted
            askew; a magnetic heading reads ``-D`` for a declination ``D`` east): subtracted from every heading.
            Default 0. The plausibility check estimates it against the fixes and warns past
            ``HEADING_OFFSET_WARN_DEG`` (10 degrees) with this setting's value; the filters learn a heading
            bias from the fixes, but an outage before the first ones ends off by the whole offset.
        heading_deviation : sequence of 4 floats, optional
            A compass's deviation card ``(B, C, D, E)`` in degrees: the heading (after ``heading_offset``) reads
            ``B sin h + C cos h + D sin 2h + E cos 2h`` more than the car's course at the heading ``h`` it reads
            (a magnetic heading near the car's steel), which is subtracted
            (``filterwnn.navigation._plausibility.deviation_of``). Default None: none. The plausibility check
            estimates the card against the fixes (``filterwnn.navigation._plausibility.heading_deviation``)
            and warns, with this setting's value, of a deviation past ``HEADING_DEVIATION_WARN_DEG`` (5 degrees):
            no filter state models it. Not with ``yaw_rate``.
        drop_fixes : sequence of (start, end), optional
            Spans of time ``[(start, end), ...]`` (s from the first sample, ``t[0]``, as the study's
            ``--outage-starts`` counts; by the fixes' stamped times, before ``gps_latency``) whose GPS fixes are
            dropped, with every per-fix array (``gps_t``, ``east``/``north`` or ``lat``/``lon``, ``gps_sigma``), before
            anything else reads them, with a warning that counts them: fixes the plausibility check found dragged
            away from the dead-reckoned track (a spoofer's walk: ``filterwnn.navigation._plausibility.fix_drag``),
            which the filters would follow. Default None: none. A span that is not two finite numbers with
            ``0 <= start < end``, or spans that hold no fix, are refused.
        restamp_fixes : bool
            Fixes stamped when the logger received them rather than at the receiver's epoch (a phone app's
            location callback, a serial port read) are each late by a time that varies; the reader finds them
            from the stamps alone (``filterwnn.navigation.scenarios._arrival_stamps``) and warns. With True,
            each such fix is placed on the receiver's regular grid of epochs, fitted to the stamps, at the
            earliest arrivals (their 1st percentile), before ``gps_latency``: what is left is a constant latency.
            Default False: a warning that names this. A drive whose stamps show no such grid is read as it is, with
            a warning. A receiver whose rate truly varies must not be re-stamped.
        speed_scale : float
            The factor by which ``speed`` (or ``distance``) reads more than the car drove (a speedometer's
            signal reads high by up to 10 %; a wheel-speed signal with the wrong tyre circumference a few per
            cent): divided out. Default 1. The plausibility check estimates it against the fixes and warns
            past ``SPEED_SCALE_WARN`` (6 %) with this setting's value; the filters learn an odometer scale
            from the fixes, within their grade, but an outage before the first ones drives on the whole error.
        intervals : {"auto", "stamps", "grid"}
            The interval each ``speed`` sample covers. ``"stamps"``: its stamped one, ``t[k] - t[k-1]``.
            ``"grid"``: the stamps' regular grid's (the slope of their least-squares line over the sample
            index), for regular samples whose stamps jitter (a logger's): a stamp written 5 ms late at
            23 m/s would add 0.12 m to one step and take it from the next, more than a wheel odometer's
            0.01-0.02 m of noise, and the filters take each step for a measurement. ``"auto"`` (default):
            the stamped intervals, unless their spread adds more than ``STAMP_JITTER_M`` a step at the median
            moving speed; then the grid when every stamp stays within ``GRID_TOLERANCE`` (a quarter) of an
            interval of it and the intervals' lag-1 autocorrelation is below ``GRID_CORRELATION`` (a late
            stamp makes the next interval short), with a warning, and otherwise the stamped intervals with a warning that
            they add noise. Ignored with ``distance``.

        Returns
        -------
        DRRun
            ``t`` from ``dt`` (the first sample is ``t = 0`` and gives ``x0``: position the truth's or,
            without truth, the first fix's taken back to the first sample along the dead-reckoned track, velocity
            from the first speed and heading), ``x_true`` ``None`` without
            truth, ``R_true`` the nominal DR variances (1 degree, 2 cm), ``scenario`` the drive's.

        Raises
        ------
        ValueError
            Naming the argument, the rule and the value: lengths that differ, non-finite values, time
            not strictly increasing or unevenly sampled, headings in degrees, a decreasing odometer,
            both or neither of ``distance``/``speed``, both or neither of
            ``east``/``north`` and ``lat``/``lon``, a failed plausibility check (with its likely cause).
        """
        if (heading is None) == (yaw_rate is None):
            raise ValueError("give exactly one of heading (rad) and yaw_rate (rad/s), got "
                             + ("both" if heading is not None else "neither"))
        if drop_fixes is not None:  # (before anything reads the fixes)
            gps_t, east, north, lat, lon, gps_sigma = _drop_fixes(drop_fixes, t, gps_t, east, north, lat, lon,
                                                                   gps_sigma)
        if gps_t is not None:  # (the stamps as logged, before the latency is taken off)
            gps_t = _arrival_restamped(t, gps_t, restamp_fixes)
        if checks:  # a time in another unit, before any warning read in it (spikes, jitter, reversing)
            from ._plausibility import MAX_DT, interval_refusal

            t_s = _finite_1d(t, "t")
            median = float(f"{np.median(np.diff(t_s)):.9g}") if len(t_s) > 1 else 0.0
            if median > MAX_DT:
                raise ValueError(interval_refusal(median))
        integrated = yaw_rate is not None
        saturated = ([], [])
        if integrated:
            if heading_deviation is not None:
                raise ValueError("heading_deviation has no meaning with a yaw rate: a gyro's heading does not deviate "
                                 "with the direction of travel as a compass's does")
            if heading_offset:
                raise ValueError("heading_offset has no meaning with a yaw rate: the heading it integrates to starts "
                                 "where the fixes' course says")
            heading, saturated = _integrate_yaw(_finite_1d(t, "t"), yaw_rate, distance, speed)
        if fill_gaps:
            t, heading, distance, speed, truth = _fill_gaps(t, heading, distance, speed, truth,
                                                            check_positive(fill_gaps, "fill_gaps"), max_jitter)
        lag = check_finite(odometer_latency, "odometer_latency", "seconds", " (negative: the speed is early)")
        if lag:  # the odometer's value at t is the one logged at t + lag
            t_read = _finite_1d(t, "t") + lag
            if speed is not None:
                speed = np.interp(t_read, t, _finite_1d(speed, "speed", len(t_read)))
            if distance is not None:
                distance = np.interp(t_read, t, _finite_1d(distance, "distance", len(t_read)))
        h_lag = check_finite(heading_latency, "heading_latency", "seconds", " (negative: the heading is early)")
        if h_lag and heading is not None:  # the heading at t is the one logged at t + lag
            t_h = _finite_1d(t, "t")
            heading = _heading_at(t_h + h_lag, t_h, heading)
        latency = check_finite(gps_latency, "gps_latency", "seconds", " (negative: the fixes are stamped early)")
        if gps_t is not None and latency:
            gps_t = np.asarray(gps_t, dtype=float) - latency
        off = check_finite(heading_offset, "heading_offset", "degrees")
        card = _deviation_card(heading_deviation)
        scale = check_positive(speed_scale, "speed_scale")
        if scale != 1.0:
            speed = None if speed is None else _finite_1d(speed, "speed") / scale
            distance = None if distance is None else _finite_1d(distance, "distance") / scale
        return cls(*_drive_fields(t, heading, distance, speed, gps_t, east, north, lat, lon, gps_sigma,
                                  truth, origin, name, max_jitter, checks, intervals, np.deg2rad(off), integrated,
                                  card, saturated),
                   t_start=float(np.asarray(t, dtype=float).ravel()[0]))


#: Fixes stamped on arrival (:func:`_arrival_stamps`): at least this many fixes, slower than the DR samples (a median
#: interval of two samples or more: a fix per sample hides its stamps' jitter in the samples'), ...
ARRIVAL_MIN_FIXES = 30
#: ... at least this share of their intervals off the receiver's rate (an integer number of its median interval) by
#: more than half a sample interval, ...
ARRIVAL_OFF_SHARE = 0.25
#: ... and a long interval followed by a short one more often than chance gives: the intervals' lag-one correlation
#: at most minus this many of its standard errors under independence (``1 / sqrt(n)``). A stamp late by a time that
#: varies lengthens one interval and shortens the next (a white lateness gives -0.5); a receiver whose own rate
#: varies gives intervals about independent (stop 75: the seventh user trial's drive stamped on arrival, late
#: 0.2-1.5 s, read -0.31 over 681 intervals, -8.1 of them; none of 74 other drive files was told:
#: ``docs/study-outputs/dr/user-trial/restamp_null.txt``).
ARRIVAL_LAG1_Z = 4.0


def _arrival_stamps(t, gps_t):
    """Whether the fixes' stamps are a receiver's regular epochs, each late by a time that varies (stamped when the
    logger received them): a dict or None. None unless the fixes are at least :data:`ARRIVAL_MIN_FIXES`, come at
    least two DR samples apart (median), have :data:`ARRIVAL_OFF_SHARE` of their intervals off an integer number of
    the median interval by more than half a sample interval, and a lag-one correlation of those misfits
    (:func:`_lag1`) of at most ``-ARRIVAL_LAG1_Z / sqrt(n)``. Then ``period`` (s) is the receiver's grid fitted to the
    stamps (:func:`_grid_line`, each interval counted as the nearest whole number of median intervals, at least one),
    ``late`` each stamp's lateness on that grid less the 1st percentile's (s, at least 0 but for the few below it),
    ``grid`` the stamps placed on that grid at the earliest arrivals (s), ``median`` the median interval (s), and
    ``off``, ``n``, ``lag1`` the test's counts and correlation. ``t``: the DR samples' times."""
    try:
        t = np.asarray(t, dtype=float).ravel()
        gps_t = np.asarray(gps_t, dtype=float).ravel()
    except (TypeError, ValueError):
        return None
    if len(gps_t) < ARRIVAL_MIN_FIXES or len(t) < 3 or not (np.isfinite(t).all() and np.isfinite(gps_t).all()):
        return None
    dt, iv = float(np.median(np.diff(t))), np.diff(gps_t)
    if not dt > 0 or np.any(iv <= 0):
        return None  # (the reader's own refusals name what is wrong)
    period = float(np.median(iv))
    if period < 2.0 * dt:
        return None
    k = np.maximum(1.0, np.rint(iv / period))
    misfit = iv - k * period
    off = int(np.sum(np.abs(misfit) > 0.5 * dt * (1.0 + 1e-9)))
    n = len(iv)
    if off < ARRIVAL_OFF_SHARE * n or np.std(misfit) == 0.0:
        return None
    lag1 = _lag1(misfit)
    if not lag1 * np.sqrt(n) <= -ARRIVAL_LAG1_Z:
        return None
    step, late = _grid_line(gps_t, np.r_[0.0, np.cumsum(k)])
    early = float(np.percentile(late, 1.0))
    return {"period": step, "grid": gps_t - late + early, "late": late - early, "off": off, "n": n, "lag1": lag1,
            "median": period}


def _arrival_restamped(t, gps_t, restamp):
    """``gps_t`` as :meth:`DRRun.from_arrays` reads it: with a warning where :func:`_arrival_stamps` finds fixes
    stamped on arrival, and with ``restamp`` those fixes on the receiver's grid (``restamp_fixes``)."""
    found = _arrival_stamps(t, gps_t)
    if found is None:
        if restamp:
            warnings.warn("restamp_fixes: the fixes' stamps show no receiver's regular grid late by a time that "
                          "varies (too few fixes, fixes as fast as the samples, or intervals on the "
                          "receiver's rate); read as stamped", RuntimeWarning, stacklevel=4)
        return gps_t
    lo, hi = np.percentile(found["late"], [5.0, 95.0])
    said = (f"{found['off']} of {found['n']} intervals between GPS fixes ({found['off'] / found['n']:.0%}) are off "
            f"their {found['median']:.4g} s rate by more than half a sample interval, a long one followed by a short "
            f"one (lag-one correlation {found['lag1']:+.2f}): fixes stamped when the logger received them, not at "
            f"the receiver's epoch, each late by a time that varies (on a regular {found['period']:.6g} s grid fitted "
            f"to the stamps, {lo:.2g}-{hi:.2g} s later than the earliest, 5-95 %)")
    if restamp:
        warnings.warn(f"{said}: re-stamped on that grid at the earliest arrivals (restamp_fixes); what is left is a "
                      "constant latency (the filters' latency state, or gps_latency where it is known)",
                      RuntimeWarning, stacklevel=4)
        on_grid = found["grid"]
        t0 = float(np.asarray(t, dtype=float).ravel()[0])  # (a first epoch just before the log's first sample)
        return np.where((on_grid < t0) & (np.asarray(gps_t, dtype=float) >= t0), t0, on_grid)
    warnings.warn(f"{said}. A latency that varies is no constant the filters' latency state can take (the seventh "
                  "user trial's drive, late 0.2-1.5 s: EKF-8 9.67 / 25.93 m at the outage ends, phone grade; its "
                  "twin stamped by the receiver 4.51 / 14.35). Stamp the fixes with the receiver's own time (GPS "
                  "time: NMEA RMC or ZDA, Android's Location.getTime()) where the log has it; else pass "
                  "restamp_fixes=True (command line: --restamp-fixes), which places each fix on that grid at the "
                  "earliest arrivals (that drive 3.86 / 14.91 m). A receiver whose own rate varies must not be "
                  "re-stamped", RuntimeWarning, stacklevel=4)
    return gps_t


def _fix_spans(spans):
    """``drop_fixes`` checked: a list of ``(start, end)`` floats, ``0 <= start < end``, each finite."""
    try:
        pairs = [tuple(float(v) for v in span) for span in spans]
    except (TypeError, ValueError):
        pairs = None
    if not pairs or any(len(p) != 2 for p in pairs):
        raise ValueError(f"drop_fixes must be spans [(start, end), ...] in seconds from the drive's first sample, got "
                         f"{spans!r}")
    for start, end in pairs:
        if not (np.isfinite(start) and np.isfinite(end) and 0.0 <= start < end):
            raise ValueError(f"drop_fixes: each span must be finite with 0 <= start < end (s from the drive's first "
                             f"sample), got ({start:g}, {end:g})")
    return pairs


def _drop_fixes(spans, t, gps_t, east, north, lat, lon, gps_sigma):
    """The per-fix arrays ``(gps_t, east, north, lat, lon, gps_sigma)`` without the fixes whose time lies in one of
    ``drop_fixes``' ``spans`` (s from ``t[0]``), with a warning that counts them; refused where no fix lies in them."""
    pairs = _fix_spans(spans)
    if gps_t is None:
        raise ValueError("drop_fixes needs GPS fixes (gps_t) to drop; the drive has none")
    t0 = float(_finite_1d(t, "t")[0])
    gps_t = _finite_1d(gps_t, "gps_t")
    m = len(gps_t)
    since = gps_t - t0
    drop = np.zeros(m, dtype=bool)
    for start, end in pairs:
        drop |= (since >= start) & (since <= end)
    said = ", ".join(f"{a:g}-{b:g} s" for a, b in pairs)
    if not drop.any():
        raise ValueError(f"drop_fixes: no GPS fix lies in the span(s) {said} (s from the drive's first sample; its "
                         f"fixes lie at {since.min():g}-{since.max():g} s)")
    if drop.all():
        raise ValueError(f"drop_fixes: the span(s) {said} hold every one of the drive's {m} GPS fixes")
    keep = ~drop

    def kept(a, name):
        return None if a is None else _finite_1d(a, name, m)[keep]

    sig = gps_sigma
    if sig is not None and np.ndim(sig):
        sig = _finite_1d(sig, "gps_sigma", m)[keep]
    warnings.warn(f"dropped {int(drop.sum())} of {m} GPS fix(es) in drop_fixes' span(s) {said} (s from the drive's "
                  "first sample)", RuntimeWarning, stacklevel=3)
    return (gps_t[keep], kept(east, "east"), kept(north, "north"), kept(lat, "lat"), kept(lon, "lon"), sig)


def _deviation_card(card):
    """``heading_deviation`` checked: None, or four finite numbers (deg) as an array."""
    if card is None:
        return None
    values = np.asarray(card, dtype=float).ravel()
    if values.size != 4 or not np.isfinite(values).all():
        raise ValueError(f"heading_deviation must be a compass's deviation card, four finite numbers (B, C, D, E) in "
                         f"degrees, got {card!r}")
    return values


def _fill_gaps(t, heading, distance, speed, truth, longest, max_jitter):
    """``(t, heading, distance, speed, truth)`` with each dropped-sample gap of at most ``longest``
    seconds filled by interpolated samples (see :meth:`DRRun.from_arrays`'s ``fill_gaps``)."""
    t = _finite_1d(t, "t")
    if len(t) < 3 or np.any(np.diff(t) <= 0):
        return t, heading, distance, speed, truth  # _sample_grid says what is wrong
    dts = np.diff(t)
    ratio = dts / float(np.median(dts))
    k = np.rint(ratio)
    gap = (k >= 2) & (np.abs(ratio - k) <= max_jitter * k) & (dts <= longest * (1.0 + 1e-9))  # 2.1 s: 2.1000000000000014
    if not gap.any():
        return t, heading, distance, speed, truth
    parts = [t[:1]] + [np.linspace(t[i], t[i + 1], int(k[i]) + 1)[1:] if gap[i] else t[i + 1:i + 2]
                       for i in range(len(t) - 1)]
    new_t = np.concatenate(parts)
    h = _heading_at(new_t, t, heading)  # degrees are refused here, with their values

    def interp(a, name):
        return None if a is None else np.interp(new_t, t, _finite_1d(a, name, len(t)))

    tr = None if truth is None else np.stack([np.interp(new_t, t, c) for c in np.asarray(truth, dtype=float).T], 1)
    i = int(np.flatnonzero(gap)[np.argmax(dts[gap])])
    long = ""
    if dts[i] > LONG_GAP_S:
        stepped = _clock_step_cause(dts[i], float(np.median(dts)), i + 1, f"t = {t[i + 1]:g} s", filled=True)
        long = ("; it is " + stepped if stepped else
                f"; dead reckoning interpolated over {dts[i]:g} s is a guess (the turns and stops in it are lost, and "
                "the filters have no fix in it): a log that paused is better split there and given as two drives "
                "(the command takes several --drive)")
    warnings.warn(f"filled {int(gap.sum())} gap(s) of dropped DR samples with {len(new_t) - len(t)} interpolated "
                  f"sample(s); the longest {dts[i]:g} s after t = {t[i]:g} s" + long, RuntimeWarning, stacklevel=3)
    return new_t, h, interp(distance, "distance"), interp(speed, "speed"), tr


def _heading_at(new_t, t, heading):
    """``heading`` (rad, at the times ``t``) at the times ``new_t``, linearly interpolated along the shorter arc
    (held beyond the first and last), wrapped; degrees are refused here, with their values."""
    return wrap_angle(np.interp(new_t, t, np.unwrap(_heading_radians(heading, len(t)))))


def _drive_fields(t, heading, distance, speed, gps_t, east, north, lat, lon, gps_sigma, truth, origin, name,
                  max_jitter, checks, intervals="auto", heading_offset=0.0, integrated=False, deviation=None,
                  saturated=((), ())):
    """The :class:`DRRun` fields of one's own drive (the work of :meth:`DRRun.from_arrays`, whose
    arguments these are): checked arrays, the GPS fixes on the sample grid, ``x0`` and the scenario.
    ``integrated``: the heading is a yaw rate's integral from 0, started here at the fixes' course; ``deviation``: a
    compass's deviation card (deg), subtracted after the offset; ``saturated``: the runs (s) and rails (deg/s) where
    the yaw rate read its range's rail (:func:`_saturated`)."""
    t = _finite_1d(t, "t")
    n = len(t)
    dts, dt, stamps = _sample_grid(t, max_jitter)
    heading = _heading_radians(heading, n)
    if heading_offset:
        heading = wrap_angle(heading - heading_offset)
    if deviation is not None:
        from ._plausibility import deviation_of

        heading = wrap_angle(heading - deviation_of(heading, deviation))
    signed = None
    if speed is not None:
        raw = _finite_1d(speed, "speed", n)
        if checks:
            _speed_sentinel(t, raw)
        signed = _speed_spikes(t, _speed_dropouts(t, raw, gps_t))
        speed = np.abs(signed)
        grid = _speed_interval(t, dts, dt, speed, intervals, stamps)
        if grid is not None:  # the stamps' grid: each speed covers its interval, and the filters run on it
            dts, dt = np.full_like(dts, grid), float(f"{grid:.6g}")
    step, v0 = _odometer_steps(distance, speed, dts, n)
    if not integrated:  # (a yaw rate's integral has no sample of its own to leave and come back to)
        heading = _heading_spikes(t, heading, step / dts)
    if speed is not None:
        _warn_speed_cutoff(speed, dt)
        heading, v0 = _reversing(t, heading, signed, dts), float(signed[0])
    steps = np.zeros(0, dtype=int)
    z_gps = np.zeros((0, 2))
    sig = swapped = offset = None
    if gps_t is not None:
        steps, z_gps, sig, swapped, offset = _gps_fixes(gps_t, east, north, lat, lon, gps_sigma, origin, t, dt)
    started = None
    if integrated:
        runs = [(int(np.searchsorted(t, first - 0.5 * dt)), int(np.searchsorted(t, last + 0.5 * dt)) - 1)
                for first, last in saturated[0]]
        good = _start_fixes(sig)  # (a receiver's cold start: fixes far off, saying so, give no course)
        heading, started = _yaw_start(dt, heading, step, steps[good], z_gps[good], None if sig is None or not len(sig)
                                      else float(np.median(sig)), checks, runs, saturated[1])
    z_dr = np.stack([wrap_angle(heading[1:]), step], axis=1)
    x_true = None
    if truth is not None:
        x_true, p0 = _truth_states(truth, t)
    elif len(z_gps):  # the first fix, taken back to the first sample along the dead-reckoned track (stop 72: taken
        # as it is, a drive starting at 20 m/s with its first fix 1 s in started 24.5 m off)
        p0 = z_gps[0] - _track(heading, step)[:, int(steps[0]) + 1]
    else:
        p0 = np.zeros(2)
    if checks:
        from ._plausibility import check_drive, receiver_dead_reckoning

        check_drive(dt, heading, step, steps, z_gps, None if sig is None or not len(sig) else float(np.median(sig)),
                    swapped, None if truth is None else np.asarray(truth, dtype=float), yaw_rate=integrated,
                    radians=lat is not None and bool(np.all(np.abs(np.asarray(lat, dtype=float)) <= np.pi / 2)
                                                     and np.all(np.abs(np.asarray(lon, dtype=float)) <= np.pi)),
                    speed=speed)
        followed = receiver_dead_reckoning(t, step, steps, z_gps, sig)
        if followed:
            warnings.warn(followed, RuntimeWarning, stacklevel=3)
    for words in started or ():  # (after the checks: a drive they refuse is not started, and its words would mislead)
        warnings.warn(words, RuntimeWarning, stacklevel=3)
    x0 = np.array([p0[0], v0 * np.sin(heading[0]), 0.0, p0[1], v0 * np.cos(heading[0]), 0.0])
    sc = _own_drive_scenario(name, n, dt, v0, heading[0], steps, sig)
    R_true = np.tile([np.deg2rad(1.0) ** 2, 0.02**2], (n - 1, 1))
    backed = signed is not None and bool(np.any(signed[1:] < -REVERSING_SPEED))
    return (dt * np.arange(1, n), x0, x_true, z_dr, steps, z_gps, R_true, sc, sig, offset, backed)


#: A yaw rate (rad/s) past which the column is taken for degrees per second (a car turns at most about 1 rad/s).
MAX_YAW_RATE = 3.0
#: The moving stretches between fixes a yaw rate's start heading needs (the heading-offset check's least).
YAW_START_CHORDS = 5
#: A yaw rate whose heading drifts from the fixes' course faster than this many times the phone grade's
#: ``gyro_bias_deg_s`` (its one sigma) has its drift named as the grade's setting in the reader's warning (a raw
#: phone gyro's 0.3 deg/s, where the grade's state had learnt 0.16 deg/s after 600 s and 5 stops: stop 58).
YAW_BIAS_SIGMAS = 3.0


#: The samples a yaw rate must read its largest value on (exactly: the rail of a gyro's range), at least, to be
#: told saturated (:func:`_saturated`) ...
SATURATED_MIN_SAMPLES = 5
#: ... and how many times the samples within 10 % under it: a rail piles the samples up, a rate that turns about
#: as fast only passes (a yaw rate rounded to a coarse step has as many at its top step as at the one below).
SATURATED_PILE = 2.0
#: The least rail (deg/s) told: a car's turn (a constant written at rest is no rail).
SATURATED_MIN_DEG_S = 5.0


def _saturated(t, rate):
    """The runs ``(first time, last time)`` (s) where a yaw rate (rad/s) reads the rail of its range, each sign
    apart (:data:`SATURATED_MIN_SAMPLES`, :data:`SATURATED_PILE`, :data:`SATURATED_MIN_DEG_S`), and the rails
    (deg/s, signed); a gyro past its range reads its largest value while the car turns faster, and the turn past it
    is lost from the heading."""
    flags, rails = np.zeros(len(rate), dtype=bool), []
    for sign in (1.0, -1.0):
        r = sign * rate
        top = float(np.max(r)) if len(r) else 0.0
        if top < np.deg2rad(SATURATED_MIN_DEG_S):
            continue
        at = r == top
        under = (r >= 0.9 * top) & ~at
        if at.sum() >= SATURATED_MIN_SAMPLES and at.sum() >= SATURATED_PILE * under.sum():
            flags |= at
            rails.append(sign * float(np.degrees(top)))
    edges = np.flatnonzero(np.diff(np.r_[0, flags.astype(int), 0]))
    return [(float(t[i]), float(t[j - 1])) for i, j in zip(edges[::2], edges[1::2])], rails


def _integrate_yaw(t, yaw_rate, distance=None, speed=None):
    """The heading (rad, wrapped) a yaw rate (rad/s, clockwise positive) integrates to from 0, by the trapezoid
    rule over the samples' own intervals, its spikes first interpolated (:func:`_rate_spikes`, at the speed the
    odometer gives); refused when it looks like degrees per second. Returns the heading, and the runs and rails
    :func:`_saturated` finds."""
    rate = _finite_1d(yaw_rate, "yaw_rate", len(t))
    big = float(np.max(np.abs(rate)))
    if big > MAX_YAW_RATE:
        raise ValueError(f"yaw_rate must be in rad/s; max |yaw_rate| = {big:g} is past {MAX_YAW_RATE:g} rad/s, faster "
                         "than a car turns, and looks like degrees per second: pass np.deg2rad(yaw_rate)")
    saturated = _saturated(t, rate)
    v = None
    if speed is not None:
        v = np.abs(np.asarray(speed, dtype=float))
    elif distance is not None and len(t) >= 2:
        v = np.abs(np.gradient(np.asarray(distance, dtype=float), t))
    if v is not None and len(v) == len(t) and np.all(np.isfinite(v)):
        rate = _rate_spikes(t, rate, v)
    return wrap_angle(np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))])), saturated


#: A fix whose reported sigma is more than this many times the fixes' median is left out of the moving stretches that
#: start a yaw rate's heading (:func:`_yaw_start`): a receiver's cold start, its first fixes hundreds of metres off
#: and saying so (the eighth user trial's drive: 55 s of fixes up to 322 m off, reported up to 260 m; their course
#: started the heading about 7 degrees off and read as a gyro warming up; stop 75). The filters weigh each fix by its
#: own sigma; the start's line through the stretches' angles weighs them alike.
START_SIGMA_FACTOR = 5.0
#: ... and the drive's first fixes, until one reports at most this many times the median: a cold start's tail, still
#: metres to tens of metres off as it converges.
START_SETTLED_FACTOR = 2.0


def _start_fixes(sig):
    """Which fixes start a yaw rate's heading: all, but those reporting more than :data:`START_SIGMA_FACTOR` times
    the median sigma and the first ones until one reports at most :data:`START_SETTLED_FACTOR` times it (a slice of
    all when there is no sigma)."""
    if sig is None or not len(sig):
        return slice(None)
    sig = np.asarray(sig, dtype=float)
    med = float(np.median(sig))
    good = sig <= START_SIGMA_FACTOR * med
    good[:int(np.argmax(sig <= START_SETTLED_FACTOR * med))] = False
    return good


def _yaw_start(dt, heading, step, steps, z_gps, sigma, checks=True, saturated=(), rails=()):
    """The integrated heading started at the fixes' course: less the offset the moving stretches between fixes
    give at the first of them (:func:`~filterwnn.navigation._plausibility.yaw_start`: a line through their angles, or
    a piecewise one where the drift is not steady), the turns lost where the rate read its range's rail (``saturated``:
    sample index runs; ``rails``: deg/s) added back, spread over the runs' samples; and the words of the warnings
    (a list) that name them (given once the drive has passed its checks); ValueError with fewer than ``YAW_START_CHORDS``
    stretches, or (with ``checks``) a ``sigma`` not in metres, whose stretches are too long to count
    (:func:`~filterwnn.navigation._plausibility._sigma_unit`)."""
    from ._plausibility import _OVERRIDE, YAW_START_KNOT_S, _chord_pairs, _sigma_unit, yaw_start

    pairs = _chord_pairs(steps, z_gps, sigma, step) if len(steps) else []
    n = len(pairs)
    fit = yaw_start(dt, heading, step, steps, z_gps, pairs, saturated) if n >= YAW_START_CHORDS else None
    unit = fit is None and _sigma_unit(heading, step, steps, z_gps, sigma)  # (a sigma in mm: stretches of km)
    if unit and checks:
        raise ValueError(f"plausibility: {unit}{_OVERRIDE}")
    if unit:  # past the checks: the stretches of fixes of 3 m (the filter warns of the sigma)
        pairs = _chord_pairs(steps, z_gps, None, step)
        n = len(pairs)
        fit = yaw_start(dt, heading, step, steps, z_gps, pairs, saturated) if n >= YAW_START_CHORDS else None
    if fit is None:
        raise ValueError(f"a yaw rate gives the heading but for its start, which the fixes' course gives: the drive has "
                         f"{n} moving stretch(es) between fixes, fewer than {YAW_START_CHORDS}; give the heading "
                         "instead")
    offset, se, rate = fit["offset"], fit["se"], fit["rate"]
    start = (-offset + 180.0) % 360.0 - 180.0
    none = "the survey grade and the 6-state EKF have no rate-bias state"
    if fit["piecewise"]:
        # each change between two pieces, over the time between their middles, as the grade's random walk reads it
        # (q_rate = (instability / 3600)^2 / 100 s: a change c over T s is instability 3600 c / sqrt(T / 100))
        changes = np.abs(np.diff(fit["rates"]))
        apart = 0.5 * (fit["pieces"][1:] + fit["pieces"][:-1])
        k = int(np.argmax(changes / np.sqrt(apart)))
        change, over = float(changes[k]), float(apart[k])
        walk = float(f"{3600.0 * change / np.sqrt(over / 100.0):.2g}")
        how = (f"a piecewise line through their angles, pieces of {YAW_START_KNOT_S:g} s or more, since a straight one "
               f"misfits: its drift goes from {rate:+.2g} deg/s at the start to {fit['last_rate']:+.2g} at the end, a "
               f"gyro's rate bias that changes (a gyro warming up, or one whose bias wanders); {none}, and the phone "
               "grade's 8-state filters estimate a rate bias that moves as fast as the grade's instability lets it "
               f"({SENSOR_GRADES['phone']['gyro_bias_instability_deg_h']:g} deg/h), while a larger prior (--gyro-bias) "
               "only learns the first minutes' rate and keeps it: give the instability the drift shows, "
               f"gyro_bias_instability_deg_h={walk:g} in the phone grade (--grade phone --gyro-bias-instability "
               f"{walk:g}: its largest change between two pieces, {change:.2g} deg/s in {over:.0f} s, as the "
               "grade's random walk of the rate bias reads it; measured on all of this drive's fixes, those the "
               "study's outages hide among them, so a drive of the same gyro, or its data sheet, is the blind value)")
    else:
        spec = SENSOR_GRADES["phone"]["gyro_bias_deg_s"]
        bias = (f"; at {abs(rate):.2g} deg/s it is past {YAW_BIAS_SIGMAS:g} times the phone grade's {spec:g} deg/s (one "
                "sigma), which its rate-bias state learns only after several stops or minutes of fixes: give it from "
                f"the start, gyro_bias_deg_s in the phone grade (--grade phone --gyro-bias {abs(rate):.2g}; the survey "
                "grade has no state to take it)"
                if abs(rate) > YAW_BIAS_SIGMAS * spec else "")
        how = (f"a line through their angles, drifting {rate:+.2g} deg/s from there: a gyro's rate bias, which the "
               f"phone grade's 8-state filters estimate; {none}{bias}")
    words = (f"the heading is the yaw rate integrated from {start % 360.0:.1f} +- {se:.1g} deg at the start, the "
             f"fixes' course over {n} moving stretches ({how})")
    mend, said = np.zeros(len(heading)), [words]
    if saturated:
        mend, lost = _saturation_mend(len(heading), saturated, fit)
        said.append(_saturation_words(dt, saturated, rails, fit, lost))
    return wrap_angle(heading - np.deg2rad(offset) + mend), said


def _saturation_mend(n, saturated, fit):
    """The heading's mend ``(n,)`` (rad) for the turns :func:`~filterwnn.navigation._plausibility.yaw_start` fitted
    at the saturated runs, each spread evenly over its group's saturated samples, and the turns (deg) in order."""
    inc = np.zeros(n)
    lost = []
    for first, last, turn, _, _ in fit["steps"]:
        at = np.concatenate([np.arange(a, b + 1) for a, b in saturated if a >= first and b <= last])
        at = at[(at >= 0) & (at < n)]
        if len(at):
            inc[at] += np.deg2rad(turn) / len(at)
            lost.append(turn)
    return np.cumsum(inc), lost


def _saturation_words(dt, saturated, rails, fit, lost):
    """The warning's words for a yaw rate that read its range's rail (:func:`_saturated`)."""
    count = sum(b - a + 1 for a, b in saturated)
    rail = " and ".join(f"{r:+.4g}" for r in rails)
    each = ", ".join(f"{turn:+.0f} +- {se:.1g}" for _, _, turn, se, _ in fit["steps"])
    left = fit["unfitted"]
    return (f"the yaw rate reads its largest value, {rail} deg/s, on {count} samples in {len(saturated)} run(s), the "
            f"first at {saturated[0][0] * dt:.1f} s: a gyro's range saturated in the tightest turns, and each such "
            "turn's part past it is lost from the heading (the filters would take the heading's steps for a gyro "
            "scale error, or a tilted axis, or a drifting bias). "
            + (f"The turns lost, fitted to the fixes' course before and after each group of runs: {each} deg "
               f"(clockwise positive; {sum(lost):+.0f} in all); the heading is mended by them, spread over the "
               "saturated samples. " if fit["steps"] else "")
            + (f"{left} run(s) without fixes on both sides are not mended. " if left else "")
            + "A wider range (the gyro's full-scale setting, 250 deg/s or more) avoids it")


def _heading_radians(heading, n):
    """``heading`` as ``n`` finite floats; ValueError when it looks like degrees (beyond ``+-2 pi``,
    give or take the rounding of a written value, :data:`HEADING_ROUNDING`)."""
    heading = _finite_1d(heading, "heading", n)
    big = float(np.max(np.abs(heading)))
    if big > 2 * np.pi + HEADING_ROUNDING:
        raise ValueError(f"heading must be in radians (|heading| <= 2 pi); max |heading| = {big:g} looks like "
                         "degrees: pass np.deg2rad(heading)")
    return heading


def _own_drive_scenario(name, n, dt, v0, heading0, steps, sig):
    """The :class:`Scenario` describing a drive given as arrays (:meth:`DRRun.from_arrays`):
    its duration, first speed and heading, GPS rate (from the median gap between fixes) and
    GPS sigma (the median of ``sig``, else 3 m)."""
    rate = 0.0
    if len(steps) > 1:
        rate = 1.0 / (float(np.median(np.diff(steps))) * dt)
    return Scenario(name=str(name), duration=float(f"{(n - 1) * dt:.9g}"), dt=dt, speed=float(abs(v0)),
                    heading=float(np.degrees(heading0)), t_switch=np.inf, factor=1.0, gps_rate=rate,
                    sigma_gps=float(np.median(sig)) if sig is not None and len(sig) else 3.0)


def _ceil_to(gap, dt):
    """``gap`` rounded up to the sample interval's precision (one more digit than ``dt``'s)."""
    digits = max(int(np.ceil(-np.log10(dt))) + 1, 0)
    return float(np.ceil(gap * 10**digits - 1e-9) / 10**digits)


def _rounded_stamps(t, dts):
    """The refusal's words for times written with too few digits, or None: repeated times on most rows, the rest
    stepping by one unit of the digits they kept (an epoch in seconds written with ``%.10g``: stop 58)."""
    rises = dts[dts > 0]
    if np.mean(dts == 0) < 0.5 or not len(rises):
        return None
    unit = float(np.min(rises))
    digits = int(np.floor(np.log10(max(abs(float(t[-1])), 1e-300)))) - int(np.round(np.log10(unit))) + 1
    return (f": {int(np.sum(dts == 0))} of the {len(dts)} intervals are 0 and the rest at least {unit:g} s, as times "
            f"written with {digits} significant digits are (an epoch in seconds needs 13 for its milliseconds): "
            "write the time column with more digits")


#: The spread (standard deviation over the median) of the sample intervals, gaps left out, past which a drive refused
#: for a gap is told that its rows come at irregular intervals, where the intervals are also independent of each
#: other (lag-1 autocorrelation at least :data:`GRID_CORRELATION`; stamps jittering about a grid have -0.5): a
#: polled sensor's replies or a row per message (a phone + OBD-II log's poll rows, 0.25-0.50 s: 0.19).
POLLED_SPREAD = 0.1


def _polled(dts, dt):
    """The sample intervals ``dts`` (median ``dt``), those of 2 ``dt`` or more left out, where they spread past
    :data:`POLLED_SPREAD` and independently of each other (:data:`GRID_CORRELATION`), else None."""
    d = dts[np.round(dts / dt) < 2]
    if len(d) < 3 or np.std(d) <= POLLED_SPREAD * dt:
        return None
    return d if _lag1(d) >= GRID_CORRELATION else None


def _sample_grid(t, max_jitter):
    """The intervals of the sample times ``t``, their median ``dt``, and :func:`_stamp_grid`'s answer when
    an interval strays past ``max_jitter`` (else None); ValueError unless there are 3 or more, strictly
    increasing, and evenly spaced within ``max_jitter`` or jittering about a regular grid."""
    n = len(t)
    if n < 3:
        raise ValueError(f"t must have at least 3 samples, got {n}")
    dts = np.diff(t)
    if np.any(dts <= 0):
        k = int(np.argmax(dts <= 0)) + 1
        raise ValueError(f"t must be strictly increasing; t[{k}] = {float(t[k])!r} <= t[{k - 1}] = {float(t[k - 1])!r}"
                         + ((_rounded_stamps(t, dts) or ": a sample logged twice? drop the repeated rows")
                            if dts[k - 1] == 0 else _wrap_cause(dts[k - 1], t) or _step_words(dts[k - 1], _dt_of(dts), k)
                            or _back_cause(dts[k - 1])))
    dt = float(f"{np.median(dts):.9g}")  # 0.1, not 0.09999999999999787
    # times far from 0 (Unix epoch seconds, 1.7e9) are stored to 2.4e-7 s: round dt to what they resolve
    # (0.1, not 0.0999999046, which made 1 Hz fixes look faster than one a second)
    dt = float(np.round(dt, int(np.floor(-np.log10(8.0 * np.spacing(float(np.max(np.abs(t)))))))))
    jit = np.abs(dts / dt - 1.0)
    stamps = _stamp_grid(t, dts) if np.any(jit > max_jitter) else None
    if stamps is not None and not stamps[1]:  # regular samples whose stamps jitter pass
        gap = _dropped(dts, dt)
        if not np.any(gap):  # stamps that jitter independently, no sample dropped: read, each over its interval
            return dts, dt, stamps
        k = int(np.argmax(np.where(gap, jit, -1.0))) + 1  # the longest
        said = (f"t must be evenly sampled (each interval within {max_jitter:.0%} of the median {dt:g} s); "
                f"t[{k}] - t[{k - 1}] = {dts[k - 1]:g} s")
        wrapped = _wrap_cause(dts[k - 1], t)
        if wrapped:
            raise ValueError(said + wrapped)
        stepped = _step_words(dts[k - 1], dt, k)
        long_gap = ("; dead reckoning interpolated over so long is a guess: for a log that paused, split the file "
                    f"before t[{k}] and run each part as a drive of its own (the command takes several --drive)"
                    if dts[k - 1] > LONG_GAP_S else "")
        polled = _polled(dts, dt)
        if polled is not None:  # rows at a sensor's polls or messages: no grid to fill (stop 62)
            q25, q75 = np.percentile(polled, [25, 75])
            raise ValueError(said + f"; and the rows come at irregular intervals (half of them between {q25:.3g} and "
                             f"{q75:.3g} s, each independent of the last), as rows at a polled sensor's replies or at "
                             "each sensor's messages do: resample the drive onto a regular grid (a row every 0.1 s, "
                             "say), each sensor's column from its own rows (the speed interpolated, across its pauses "
                             "too; the gyro's rate averaged over each interval); fill_gaps (--fill-gaps) fills the gaps "
                             "of a regular grid, which these rows are not on" + long_gap)
        if stepped:
            raise ValueError(said + stepped)
        raise ValueError(said + ": resample the drive first"
                         + (" (dropped samples: fill_gaps=SECONDS, or --fill-gaps, interpolates gaps up to that "
                            f"long; this one needs {_ceil_to(dts[k - 1], dt):g})"
                            if 2 <= round(dts[k - 1] / dt) and dts[k - 1] <= FILL_OFFER_S else "")
                         + long_gap
                         + ("; where only one sensor paused and the others logged on (an OBD-II adapter's hang beside "
                            "a phone's gyro), keep their rows and interpolate that sensor's column alone across the "
                            "gap: rows filled whole lose the turns the gyro logged in it" if round(dts[k - 1] / dt) >= 2
                            else ""))
    return dts, dt, stamps


#: The ranges (s) of the clocks that wrap in drive logs, and the words that name them.
_CLOCK_WRAPS = ((2.0**32 / 1e3, "a 32-bit millisecond counter (u-blox ESF's sTtag, a logger's tick)"),
                (2.0**32 / 1e6, "a 32-bit microsecond counter"),
                (604800.0, "the GPS week's seconds (iTOW, the time of week, at the week's end)"),
                (86400.0, "a time of day (past midnight)"))


def _wrap_cause(interval, t):
    """The refusal's words for a step of the sample times by about a wrapping clock's range (:data:`_CLOCK_WRAPS`,
    either way, give or take the drive's own span), else ``""``."""
    interval = float(interval)
    size = abs(interval)
    span = max(float(np.max(t) - np.min(t)) - size, 0.0)
    for period, what in _CLOCK_WRAPS:
        if abs(size - period) <= span + 1.0 and size > 0.5 * period:
            remedy = (f"add {period:.10g} s to every time after it" if interval < 0 else
                      f"the rows run across the wrap out of order (sorted by the wrapped time?): unwrap the clock, adding "
                      f"{period:.10g} s to the times after it wrapped, before sorting")
            return f": a step of {interval:+.7g} s, about {period:.10g} s, is {what} that wrapped; {remedy}"
    return ""


#: The steps (s) a clock makes while a log runs on, and the words that name them: an hour set forward or back (summer
#: time, a time zone; stop 74: a seventh user's log stepped +3600 s mid-drive), GPS time's lead on UTC (18 s since 2017).
_CLOCK_STEPS = ((3600.0, "an hour: a clock set forward or back (summer time, a time zone) while the log ran"),
                (18.0, "GPS time's lead on UTC (18 s since 2017): stamps that switched between the two"))


def _dt_of(dts):
    """The sample interval of the intervals ``dts``: their median over the positive ones (a step back is one of them)."""
    pos = dts[dts > 0]
    return float(np.median(pos)) if pos.size else 0.0


def _clock_step_cause(interval, dt, k, at=None, filled=False):
    """The words for an interval between samples ``k - 1`` and ``k`` (``at``: the words for that sample, ``t[k]`` by
    default) that is a clock's step (:data:`_CLOCK_STEPS`, either way) and one sample interval ``dt`` (within half of
    one), else ``""``; ``filled``: said of a gap that ``fill_gaps`` filled, not of one refused."""
    at = f"t[{k}]" if at is None else at
    step = float(interval) - float(dt)
    for size, what in _CLOCK_STEPS:
        if dt > 0 and abs(abs(step) - size) <= 0.5 * dt:
            fix = (f"subtract {size:g} s from every time from {at} on" if step > 0 else
                   f"add {size:g} s to every time from {at} on")
            if step < 0:
                return (f"{-step:g} s back, less one sample interval, {what}. Where the speed and the fixes run on "
                        f"across it (the car a sample's travel further), the log went on: {fix}")
            return (f"{step:g} s and one sample interval, {what}. Where the speed and the fixes run on across it "
                    f"(the car a sample's travel further, not {step:g} s of it), the log did not pause: {fix}; a log "
                    "that did pause is split there (each part a drive of its own: the command takes several --drive). "
                    + ("Filled, the filters follow" if filled else "Filled (--fill-gaps), the filters would follow")
                    + f" {step:g} s of interpolated dead reckoning without a fix")
    return ""


def _step_words(interval, dt, k):
    """A refusal's ``": ..."`` for a clock's step (:func:`_clock_step_cause`), else ``""``."""
    words = _clock_step_cause(interval, dt, k)
    return ": " + words if words else ""


def _back_cause(interval):
    """The refusal's words for sample times that go back by ``interval`` (< 0) other than a clock's wrap (stop 69:
    a user's logger restarted, its clock from 0 again, or wrote a block twice)."""
    return (f": the time goes back {-float(interval):.7g} s there, a logger that restarted (its clock from 0 again) or "
            "wrote a block twice: split the file there and give each part (the command takes several --drive), "
            "dropping a repeated block")


def _dropped(dts, dt):
    """Which intervals look like dropped samples: at least 1.5 sample intervals, and not made up by a short one
    beside them (their sum with either neighbour at least 2.75 intervals). A stamp written late makes its interval
    long and the next one short (a ROS bag's receipt times, a 100 Hz IMU's stamps jittering by a millisecond: stop
    59); a dropped sample leaves one interval of two with regular ones beside it."""
    long = dts >= 1.5 * dt
    before = np.r_[np.inf, dts[:-1] + dts[1:]]
    after = np.r_[dts[:-1] + dts[1:], np.inf]
    return long & (before >= 2.75 * dt) & (after >= 2.75 * dt)


#: A gap in the DR samples (s) past which the refusal of an unevenly sampled drive also says to split it: as
#: long as the longest sample interval the plausibility checks accept (dead-reckoning sensors sample at 1-100 Hz).
LONG_GAP_S = 2.0


#: The longest gap (s) for which the refusal of an unevenly sampled drive offers ``fill_gaps``: a minute, twice the
#: study's outages. Past it only the split is named (stop 74: a gap of an hour filled as offered took the filters
#: 49.6 km off, the DR interpolated over it with no fix).
FILL_OFFER_S = 60.0


#: A fall of a cumulative odometer (m) past which its refusal names a counter that wrapped or was reset.
ODOMETER_WRAP_M = 100.0


def _odometer_steps(distance, speed, dts, n):
    """The distance of each step and the first speed, from a cumulative odometer or speeds."""
    if (distance is None) == (speed is None):
        raise ValueError("give exactly one of distance (cumulative odometer, m) and speed (m/s), got "
                         + ("both" if distance is not None else "neither"))
    if distance is not None:
        distance = _finite_1d(distance, "distance", n)
        dd = np.diff(distance)
        if np.any(dd < 0):
            k = int(np.argmax(dd < 0)) + 1
            drop = float(distance[k - 1] - distance[k])
            raise ValueError(f"distance must be non-decreasing (a cumulative odometer); distance[{k}] = "
                             f"{float(distance[k])!r} < distance[{k - 1}] = {float(distance[k - 1])!r}"
                             + (f": a drop of {drop:.6g} m, a counter that wrapped (add its range back to every "
                                "reading after it, before scaling to metres: 2^23 ticks for u-blox ESF's wheel ticks) "
                                "or an odometer reset" if drop > ODOMETER_WRAP_M else ""))
        speed = _odometer_speed(dd, dts)
        return speed[1:] * dts, speed[0]
    speed = _finite_1d(speed, "speed", n)
    return speed[1:] * dts, speed[0]


def _odometer_speed(dd, dts):
    """The speed at each sample of a cumulative odometer whose increments over the intervals ``dts`` are ``dd``.

    An increment over ``[t_k, t_k+1]`` is the mean speed over that interval, the speed at its middle; the
    models measure the speed at each sample (step ``k`` is ``speed[k + 1]`` times its interval, as a speed
    column's), so each sample's speed is the two interval means beside it interpolated to its time (the
    first and last sample take their one interval's). Taken as the speed at the interval's end, as a speed
    column's sample would be, each speed would be half an interval late: 0.5 s at 1 Hz, which the
    consistency monitor tells as a speed stamped late (docs/study-outputs/dr/log-faults/RUN.md, stop 49)."""
    ts = np.concatenate([[0.0], np.cumsum(dts)])  # the samples' times from the first
    return np.interp(ts, 0.5 * (ts[:-1] + ts[1:]), dd / dts)


#: A signed speed below minus this (m/s) is a car reversing: its samples' heading is turned half a turn to
#: be the direction of travel. Between it and 0 a speed is a standstill's dither (``GPSDRFilter``'s
#: ``standstill_speed``), whose heading is kept, so that a stop's headings stay the gyro's.
REVERSING_SPEED = 0.05


#: The value a phone's logger writes for a speed it does not know (iOS's ``CLLocation.speed``, which loggers such as
#: SensorLog write as they get it, at a standstill and between fixes).
SPEED_SENTINEL = -1.0
#: The least samples at :data:`SPEED_SENTINEL`, and their least share of the negative speeds, that make it the
#: logger's mark rather than a car reversing at exactly that speed.
SENTINEL_MIN_SAMPLES, SENTINEL_SHARE = 10, 0.9


def _speed_sentinel(t, speed):
    """Refuse a speed whose negative values are nearly all exactly :data:`SPEED_SENTINEL` (a logger's mark for an
    unknown speed): read as a signed speed, it is a car reversing at 1 m/s wherever the speed was unknown (stop
    58: a phone log's GPS speed, -1 while the car stood, read as 255 m of reversing; EKF-8 20.40 / 56.67 m at the
    outage ends, 5.78 / 12.54 m with those samples 0)."""
    neg = speed < 0.0
    at = speed == SPEED_SENTINEL
    if at.sum() < SENTINEL_MIN_SAMPLES or at.sum() < SENTINEL_SHARE * neg.sum():
        return
    k = int(np.argmax(at))
    raise ValueError(f"the speed is exactly {SPEED_SENTINEL:g} on {int(at.sum())} of its {int(neg.sum())} negative "
                     f"samples (the first speed[{k}], {float(t[k] - t[0]):g} s after the first sample): a logger's "
                     "mark for a speed it does not know (iOS writes -1 for an invalid speed, at a standstill and "
                     "between fixes), not a car reversing at 1 m/s: give those samples' speed as 0 where the car "
                     "stood (np.where(speed < 0, 0, speed)), or the speed interpolated between the samples beside "
                     "them; if the car really reversed at exactly 1 m/s, pass checks=False (command line: "
                     "--no-plausibility)")


def _reversing(t, heading, speed, dts):
    """The heading as the direction of travel: turned by pi where the signed ``speed`` is below
    -:data:`REVERSING_SPEED` (the car reversing, its nose the other way), with a warning that counts them."""
    back = speed[1:] < -REVERSING_SPEED  # step k covers sample k + 1
    if not back.any():
        return heading
    heading = heading.copy()
    heading[1:][back] = wrap_angle(heading[1:][back] + np.pi)
    k = int(np.argmax(back)) + 1
    warnings.warn(f"the speed is negative on {int(back.sum())} sample(s), the first at t = {float(t[k]):g} s: the car "
                  f"reversed, {float(np.sum(-speed[1:][back] * dts[back])):.3g} m in all; there the heading is turned "
                  "by 180 deg to be the direction of travel (if the speed's sign means something else, give its "
                  "magnitude)", RuntimeWarning, stacklevel=4)
    return heading


#: Timestamp jitter (m of odometer distance per step: the median moving speed times the spread of the
#: sample intervals) above which :meth:`DRRun.from_arrays` gives each speed the stamps' grid interval when
#: they jitter about one, and otherwise warns. ``speed`` samples become distances through their
#: intervals, so a logger that stamps regular samples late adds that much noise to every step; the sensor
#: grades' odometers are 0.01-0.02 m (stamps off by up to 5 ms, 0.067 m a step at 23 m/s, took a
#: phone-grade EKF-8's worst outage end from 34.57 to 75.48 m, and 34.57 with the grid's interval:
#: docs/study-outputs/dr/log-faults).
STAMP_JITTER_M = 0.02


#: The lag-1 autocorrelation of the sample intervals below which their spread is taken for time stamps
#: that jitter about a regular grid: a stamp written late makes its interval long and the next one short
#: (-0.5 for stamps jittered independently), while intervals that really vary do so independently (0).
GRID_CORRELATION = -0.25
#: What ``intervals`` of :meth:`DRRun.from_arrays` takes.
INTERVALS = ("auto", "stamps", "grid")


#: How far (in sample intervals) every stamp may lie from the stamps' regular grid for them to be taken
#: as jittering about it: a quarter, so that one dropped sample (the stamps after it a whole interval
#: late) is not.
GRID_TOLERANCE = 0.25


def _lag1(x):
    """The lag-1 autocorrelation of ``x`` about its mean (0 for a constant ``x``): a stamp written late makes its
    interval long and the next one short (-0.5 for stamps jittered independently)."""
    d = np.asarray(x, dtype=float) - np.mean(x)
    dd = float(d @ d)
    return float(d[1:] @ d[:-1] / dd) if dd > 0 else 0.0


def _grid_line(t, k):
    """The least-squares line through ``(k, t)``: ``(slope, misfit)``, each ``t``'s misfit from the line (fitted
    about ``t[0]`` and the means, so that epoch times keep their digits)."""
    k = np.asarray(k, dtype=float)
    k = k - np.mean(k)
    tc = t - t[0]
    tc = tc - np.mean(tc)
    slope = float(k @ tc / (k @ k))
    return slope, tc - slope * k


def _stamp_grid(t, dts):
    """The stamps' regular grid: ``(interval, on_grid, rho)``. ``interval`` is the slope of the
    least-squares line through ``(k, t[k])`` (:func:`_grid_line`); ``on_grid`` whether the stamps jitter about it:
    every stamp within :data:`GRID_TOLERANCE` of an interval of the line, and the intervals' lag-1 autocorrelation
    ``rho`` (:func:`_lag1`) below :data:`GRID_CORRELATION`."""
    interval, misfit = _grid_line(t, np.arange(len(t)))
    rho = _lag1(dts)
    on_grid = float(np.max(np.abs(misfit))) <= GRID_TOLERANCE * interval and rho < GRID_CORRELATION
    return interval, on_grid, rho


def _speed_interval(t, dts, dt, speed, intervals, stamps=None):
    """The stamps' grid interval (:func:`_stamp_grid`) when each speed sample is to cover it, else None
    (each covers its stamped interval). ``intervals="auto"`` takes the grid, with a warning, when the
    stamps jitter about one and enough to add more than :data:`STAMP_JITTER_M` of noise to a step at the
    median moving speed; a jitter that large with intervals that vary independently is warned as noise.
    ``stamps``: :func:`_stamp_grid`'s answer when :func:`_sample_grid` already has it."""
    if intervals not in INTERVALS:
        raise ValueError(f"intervals must be one of {', '.join(map(repr, INTERVALS))}, got {intervals!r}")
    noise = _stamp_noise(dts, dt, speed)
    if intervals == "stamps" or (intervals == "auto" and noise <= STAMP_JITTER_M):
        if intervals == "stamps":
            _warn_stamp_jitter(dts, dt, noise, None)
        return None
    grid, on_grid, rho = _stamp_grid(t, dts) if stamps is None else stamps
    if intervals == "grid":
        return grid
    if not on_grid:
        _warn_stamp_jitter(dts, dt, noise, rho)
        return None
    warnings.warn(f"the sample times jitter by {1e3 * float(np.std(dts - dt)):.2g} ms (sd of the intervals) about "
                  f"a regular {grid:.4g} s grid (their lag-1 correlation {rho:.2f}: a stamp written late makes the "
                  "next interval short, as a logger's do): each speed is taken over the grid's interval, not its "
                  f"stamped one, which would add {noise:.2g} m of noise to each step at the "
                  "median speed; pass intervals='stamps' (--intervals stamps) if the samples really came at their "
                  "stamped times", RuntimeWarning, stacklevel=4)
    return grid


def _stamp_noise(dts, dt, speed):
    """The noise (m) the intervals' spread adds to a step at the median speed while moving (over 1 m/s)."""
    moving = speed[speed > 1.0]
    return float(np.median(moving)) * float(np.std(dts - dt)) if len(moving) else 0.0


def _warn_stamp_jitter(dts, dt, noise, rho):
    """Warn when the intervals' spread times the median speed while moving (``noise``,
    :func:`_stamp_noise`) is more than :data:`STAMP_JITTER_M` of odometer distance a step (``rho``:
    their lag-1 autocorrelation, when measured)."""
    if noise > STAMP_JITTER_M:
        why = "" if rho is None else (f" (their lag-1 correlation {rho:.2f}, not below {GRID_CORRELATION:g}: they "
                                      "vary independently, not about a regular grid)" if rho >= GRID_CORRELATION else
                                      f" (their lag-1 correlation {rho:.2f} is that of stamps jittering about a grid, "
                                      f"but some lie more than {GRID_TOLERANCE:g} of an interval off any regular one: "
                                      "stamps late by varying amounts, as a message's time of receipt is (a ROS "
                                      "bag's; its header stamp is the sample's own time), or a rate that drifts)")
        warnings.warn(f"the sample times jitter by {1e3 * float(np.std(dts - dt)):.2g} ms (sd of the intervals about "
                      f"{dt:g} s){why}: speed times interval then adds {noise:.2g} m of noise to each step at the "
                      "median speed, more than a wheel odometer's 0.01-0.02 m. If the samples are regular and only "
                      "their time stamps jitter (a logger's), pass intervals='grid' (--intervals grid), or give the "
                      "times on their grid (t[0] + k dt)", RuntimeWarning, stacklevel=5)


#: The fastest a car's speed changes when it pulls away from a stop or comes to one in ordinary driving
#: (m/s^2): the first speed sample after a standstill, and the last before one, is at most this times
#: the sample interval.
MAX_STOP_ACCEL = 3.0
#: The smallest low-speed cutoff (m/s) :meth:`DRRun.from_arrays` warns of: a speed sensor that reads 0
#: below it. A car creeping slower covers little (a 1 km/h quantisation reads 0 below 0.14 m/s).
SPEED_CUTOFF_WARN = 0.5
_MIN_SPEED_EDGES = 4


#: A run of speed samples reading 0 between two that do not is a dropout, not a stop, when the car would have
#: had to brake to a stop and pull away again within it at more than this on average (m/s^2, 1 g: no car
#: does either so fast).
MAX_DROPOUT_ACCEL = 10.0
#: The slowest speed (m/s) the samples beside a dropout may read: under it a reading of 0 is the sensor's own
#: at a crawl (a wheel-speed sensor's low-speed cutoff, up to about 1.5 m/s; a noisy speed clipped at 0), and
#: stays as read.
MIN_DROPOUT_SPEED = 2.0


def _inner_runs(mask):
    """The runs ``[i, j)`` of ``mask`` (boolean) with a sample on either side: ``(starts, ends)``."""
    starts, ends = _run_bounds(mask)
    inner = (starts >= 1) & (ends <= len(mask) - 1)
    return starts[inner], ends[inner]


def _unfixed(t, starts, ends, gps_t):
    """Per zero run ``[starts, ends)`` of the samples ``t``: whether it spans a gap of the GPS fixes, the receiver's
    speed lost with them. No fix is stamped between the sample before it and the sample after it (a fix at either
    is the receiver's last or first), a fix at least is missing there (the span at least 1.5 of the fixes' median
    interval), and the run covers at least half of the time between the fixes around it (a CAN frame lost inside a
    tunnel is a sample's dropout, not the receiver's)."""
    out = np.zeros(len(starts), dtype=bool)
    try:
        g = np.sort(np.asarray(gps_t, dtype=float).ravel())
    except (TypeError, ValueError):
        return out
    g = g[np.isfinite(g)]
    if len(g) < 3 or not len(starts):
        return out
    rate = float(np.median(np.diff(g)))
    a, b = t[starts - 1], t[ends]
    before, after = np.searchsorted(g, a, side="right"), np.searchsorted(g, b, side="left")
    ok = (before >= 1) & (after < len(g)) & (before == after) & (b - a >= 1.5 * rate)  # (a fix at either: not in)
    gap = g[np.minimum(after, len(g) - 1)] - g[np.maximum(before - 1, 0)]
    return ok & (b - a >= 0.5 * gap)


def _speed_dropouts(t, speed, gps_t=None):
    """``speed`` with its dropouts interpolated from the samples beside them, with a warning.

    A dropout is a run of samples reading 0 (a CAN frame lost and logged as 0, a wheel-speed signal's glitch)
    between two samples of speeds ``a`` and ``b``, ``D`` seconds apart, with ``(a + b) / D`` over
    :data:`MAX_DROPOUT_ACCEL`, both at least :data:`MIN_DROPOUT_SPEED`: a stop so short is no car's. Taken for
    a stop, each held the filters still for its samples while the car moved on (20 such samples over the phone
    analog's 15 minutes took EKF-8 from 6.68 / 28.16 to 63.51 / 397.75 m). A real stop, however abrupt, lasts
    longer than that.

    A run that lies in a gap of the fixes (``gps_t``: none stamped from the sample before it to the one after it)
    is a dropout already past :data:`MAX_STOP_ACCEL` each way, an ordinary stop's: a speed from the GPS receiver
    itself (its Doppler speed), logged as 0 when the receiver loses its fixes under a bridge, lost with them (the
    eighth user trial's drive, 7 bridges at 19-26 m/s for 3.4-7.9 s: four of them, longer than the rule above
    allows, taken for stops, held the filters still while the car drove on, and the reader named the fixes after
    them a spoofer's walk; stop 75). Warned of apart, naming that."""
    low = speed == 0.0
    if not low.any():
        return speed
    starts, ends = _inner_runs(low)
    a, b = np.abs(speed[starts - 1]), np.abs(speed[ends])
    fast = (a + b) / (t[ends] - t[starts - 1])
    moving = np.minimum(a, b) >= MIN_DROPOUT_SPEED
    unfixed = moving & (fast > MAX_STOP_ACCEL) & _unfixed(t, starts, ends, gps_t)
    drop = (fast > MAX_DROPOUT_ACCEL) & moving & ~unfixed

    def said(runs, where=""):  # (the runs' count and the first's speeds beside it)
        k = int(np.flatnonzero(runs)[0])
        i, j = starts[k], ends[k]
        return (f"the speed reads 0 for {int((ends - starts)[runs].sum())} sample(s) in {int(runs.sum())} run(s)"
                f"{where} between samples that do not (the first at t = {t[i]:g} s, between {a[k]:.3g} and "
                f"{b[k]:.3g} m/s {t[j] - t[i - 1]:.2g} s apart)")

    if unfixed.any():
        warnings.warn(said(unfixed, " where the GPS receiver has no fix either,") + ": a car "
                      f"braking to a stop and pulling away at an ordinary {MAX_STOP_ACCEL:g} m/s^2 would take longer, "
                      "so the speed is the receiver's own (its Doppler speed, lost with its fixes under a bridge or in "
                      "a tunnel), and taken for stops these would hold the filters still while the car drives on; they "
                      "are interpolated from the samples beside them. Give the car's own speed (a CAN or wheel speed, "
                      "an odometer) if the log has one: a speed from the receiver is lost wherever its fixes are, "
                      "which is where dead reckoning has to carry the car", RuntimeWarning, stacklevel=4)
    if not (drop | unfixed).any():
        return speed
    out = speed.copy()
    for i, j in zip(starts[drop | unfixed], ends[drop | unfixed]):
        out[i:j] = np.interp(t[i:j], [t[i - 1], t[j]], [speed[i - 1], speed[j]])
    if not drop.any():
        return out
    warnings.warn(said(drop) + ": no car stops and pulls away again so fast (over "
                  f"{MAX_DROPOUT_ACCEL:g} m/s^2 each way), so these are dropouts (a CAN frame lost and logged as 0, a "
                  "wheel-speed signal's glitch), which taken for stops would hold the filters still while the car "
                  "moves on; they are interpolated from the samples beside them", RuntimeWarning, stacklevel=4)
    return out


#: A car's largest lateral acceleration (m/s^2, 1 g: its tyres grip no more): at speed ``v`` it turns at most
#: this over ``v`` rad/s...
MAX_LATERAL_ACCEL = 10.0
#: ... and at most ``v`` over its tightest turning radius (m; a car's turning circle is 9-12 m kerb to kerb):
#: at most 1.4 rad/s, at 7 m/s.
MIN_TURN_RADIUS = 5.0
#: A heading that leaves and comes back by less than this (rad, 10 degrees) is never taken for a spike: a
#: standing car's heading noise, a magnetometer's jitter.
HEADING_SPIKE_MIN = np.deg2rad(10.0)


#: The longest run of samples taken for one spike (a CAN bus that repeats a bad frame, a glitch over a few samples).
MAX_SPIKE_RUN = 3
#: A speed that jumps away and back by less than this (m/s, 18 km/h) is never taken for a spike: a speed sensor's
#: noise and quantization at 20-100 Hz (a wheel tick's worth over 0.05 s) reach 1 g between samples (a random
#: drive at 20 Hz, 0.3 m/s noise, had 0.5 m/s jumps taken for spikes), and so small a glitch moves the track
#: little at such rates.
SPEED_SPIKE_MIN = 5.0
#: ... nor by less than this many times the drive's own jumps between samples (their median absolute jump over
#: 0.6745, while the car moves): a speed or heading whose noise is large (a wheel-tick speed at 20 Hz jumps by
#: 1.7 m/s on median in ``random_drives.py``'s protocol 1) has its own spikes by the thousand.
SPIKE_NOISE = 8.0


def _turn_bound(speed):
    """The fastest a car turns (rad/s) at ``speed`` (m/s): :data:`MAX_LATERAL_ACCEL` over the speed, or the speed
    over :data:`MIN_TURN_RADIUS`, whichever is less, and at most :data:`MAX_YAW_RATE`."""
    v = np.maximum(speed, 1e-9)
    return np.minimum(np.minimum(MAX_YAW_RATE, MAX_LATERAL_ACCEL / v), v / MIN_TURN_RADIUS)


def _spike_runs(jump, limit):
    """The runs ``[i, j)`` of samples that a jump ``jump[i - 1]`` (from sample ``i - 1`` to ``i``) past its
    ``limit`` leads into and one of the other sign past its limit ``jump[j - 1]`` leads out of, within
    :data:`MAX_SPIKE_RUN` samples: out and back, faster than the limits allow each way (back: the first such jump
    that lands within half the jump out of the level before the run, else the one that lands nearest it)."""
    big = np.abs(jump) > limit
    runs, i = [], 0
    idx = np.flatnonzero(big)
    while i < len(idx):
        a = idx[i]
        ahead = idx[(idx > a) & (idx <= a + MAX_SPIKE_RUN)]
        back = [b for b in ahead if np.sign(jump[b]) == -np.sign(jump[a])]
        if back:
            # the first jump back that lands within half the jump out of the level before the run, else the one
            # that lands nearest it (a spike, then a dropout interpolated from it, jumps back down twice: to the
            # interpolated sample, half-way, and on to the drive)
            off = {b: abs(np.sum(jump[a:b + 1])) for b in back}
            b = next((b for b in back if off[b] <= 0.5 * abs(jump[a])), min(back, key=off.get))
            runs.append((a + 1, b + 1))
            i = int(np.searchsorted(idx, b)) + 1
        else:
            i += 1
    return runs


def _noise(jump, moving):
    """The drive's own jump between samples, robustly: the median absolute ``jump`` over the intervals
    ``moving``, over 0.6745 (a standard deviation for Gaussian jumps); 0 with none."""
    j = np.abs(jump[moving])
    return float(np.median(j)) / 0.6745 if len(j) else 0.0


def _fill_runs(t, values, runs, along=None):
    """``values`` with each run ``[i, j)`` interpolated between samples ``i - 1`` and ``j`` (``along``: the
    difference to use between them, the shorter arc for a heading)."""
    out = np.array(values, dtype=float)
    for i, j in runs:
        d = values[j] - values[i - 1] if along is None else along(values[j] - values[i - 1])
        out[i:j] = values[i - 1] + d * (t[i:j] - t[i - 1]) / (t[j] - t[i - 1])
    return out


def _speed_spikes(t, speed):
    """``speed`` with its spikes interpolated from the samples beside them, with a warning.

    A spike is a run of up to :data:`MAX_SPIKE_RUN` samples that the speed jumps into and back out of, each jump
    faster than :data:`MAX_DROPOUT_ACCEL` (1 g) allows and by over :data:`SPEED_SPIKE_MIN` and :data:`SPIKE_NOISE`
    times the speed's own jumps: a CAN frame's glitch (255 km/h), a wheel that slipped. A run that reads 0 is
    :func:`_speed_dropouts`' to judge (a dropout, or a sensor's cutoff at a crawl, which stays). Integrated, each
    moved the track by its excess times its length: 20 such samples of 70.8 m/s over the phone analog's 15 minutes
    took its EKF-8 from 6.68 / 28.16 to 58.54 / 306.49 m, and at 1 Hz from 1.63 / 6.28 to 43.26 / 1175.94 m
    (``docs/study-outputs/dr/log-faults/spikes.py``)."""
    if len(speed) < 3:
        return speed
    jump = np.diff(speed)
    floor = max(SPEED_SPIKE_MIN, SPIKE_NOISE * _noise(jump, (speed[1:] != 0.0) & (speed[:-1] != 0.0)))
    limit = np.maximum(MAX_DROPOUT_ACCEL * np.diff(t), floor)
    runs = _spike_runs(jump, limit)
    runs = [(i, j) for i, j in runs if np.any(speed[i:j] != 0.0)]  # a 0 is a dropout's or a cutoff's (above)
    if not runs:
        return speed
    out = _fill_runs(t, speed, runs)
    for _ in range(MAX_SPIKE_RUN - 1):
        # a glitch of two kinds side by side (a spike, then a dropout interpolated from it: 15, 70.8, 0, 15.8 m/s
        # reads 15, 70.8, 43.3, 15.8, whose first run is the 70.8 alone) leaves a spike where a run was filled:
        # judged again there only, it is filled from the samples beside the whole glitch
        near = lambda a, b: any(a <= j and b >= i for i, j in runs)  # noqa: E731 (touches a filled run)
        more = [(a, b) for a, b in _spike_runs(np.diff(out), limit) if near(a, b) and np.any(out[a:b] != 0.0)]
        if not more:
            break
        out = _fill_runs(t, out, more)
        runs = sorted(runs + more)
    merged = []
    for a, b in runs:  # the runs as one per glitch, for the warning
        if merged and a <= merged[-1][1]:
            merged[-1] = (merged[-1][0], max(merged[-1][1], b))
        else:
            merged.append((a, b))
    runs = merged
    i, j = runs[0]
    warnings.warn(f"{sum(b - a for a, b in runs)} speed sample(s) in {len(runs)} run(s) jump away from the samples "
                  f"beside them and back faster than a car can (over {MAX_DROPOUT_ACCEL:g} m/s^2 and {floor:.3g} m/s "
                  f"each way; the first "
                  f"at t = {t[i]:g} s, {speed[i]:.4g} m/s between {speed[i - 1]:.4g} and {speed[j]:.4g}): spikes (a "
                  "CAN frame's glitch, a wheel that slipped), which the filters would integrate into the track; each "
                  "is interpolated from the samples beside it", RuntimeWarning, stacklevel=4)
    return out


def _heading_spikes(t, heading, speed):
    """``heading`` with its spikes interpolated along the shorter arc, with a warning.

    A spike is a run of up to :data:`MAX_SPIKE_RUN` samples that the heading turns into and back out of, each turn
    faster than a car turns at its speed (``speed``, m/s over each interval; :func:`_turn_bound`) and by over
    :data:`HEADING_SPIKE_MIN` and :data:`SPIKE_NOISE` times the heading's own jumps while the car moves (an
    orientation glitch of a phone, a heading logged from another frame for a sample). Integrated, each moved the track sideways: 20 such samples of 90 degrees took the 1 Hz
    analog's EKF-8 from 1.63 / 6.28 to 6.89 / 1005.23 m (``docs/study-outputs/dr/log-faults/spikes.py``)."""
    if len(heading) < 3:
        return heading
    jump = wrap_angle(np.diff(heading))
    floor = max(HEADING_SPIKE_MIN, SPIKE_NOISE * _noise(jump, speed > 0.0))
    runs = _spike_runs(jump, np.maximum(_turn_bound(speed) * np.diff(t), floor))
    if not runs:
        return heading
    i, j = runs[0]
    warnings.warn(f"{sum(b - a for a, b in runs)} heading sample(s) in {len(runs)} run(s) turn away from the samples "
                  f"beside them and back faster than a car turns (over {MAX_LATERAL_ACCEL:g} m/s^2 sideways at its "
                  f"speed, or a {MIN_TURN_RADIUS:g} m turning radius, and by over "
                  f"{np.rad2deg(floor):.3g} degrees; the first at t = {t[i]:g} s, "
                  f"{np.rad2deg(jump[i - 1]):+.3g} degrees from the sample before): spikes (an orientation glitch), "
                  "which the filters would integrate into the track; each is interpolated from the samples beside "
                  "it", RuntimeWarning, stacklevel=4)
    return _fill_runs(t, heading, runs, wrap_angle)


#: A yaw rate that leaves what a car can turn at its speed by less than this (rad/s) is never taken for a spike.
YAW_SPIKE_MIN = 0.1


def _rate_spikes(t, rate, speed):
    """``rate`` (a yaw rate, rad/s) with its spikes interpolated from the samples beside them, with a warning.

    A spike is a run of up to :data:`MAX_SPIKE_RUN` samples past what a car turns at its speed (``speed``, m/s at
    each sample; :func:`_turn_bound`) by over
    :data:`YAW_SPIKE_MIN` and :data:`SPIKE_NOISE` times the rate's own jumps while the car moves, with the samples
    beside it within it: a gyro's glitch. Integrated, each turned every later heading by its excess times its
    interval (1.5 rad/s for a sample of a 1 Hz log: 86 degrees; ``docs/study-outputs/dr/log-faults/
    yaw_rate_spikes.py``)."""
    if len(rate) < 3:
        return rate
    moving = (speed[1:] > 0.0) & (speed[:-1] > 0.0)
    past = np.abs(rate) > _turn_bound(speed) + max(YAW_SPIKE_MIN, SPIKE_NOISE * _noise(np.diff(rate), moving))
    runs = [(i, j) for i, j in zip(*_inner_runs(past)) if j - i <= MAX_SPIKE_RUN]
    if not runs:
        return rate
    i, j = runs[0]
    warnings.warn(f"{sum(b - a for a, b in runs)} yaw rate sample(s) in {len(runs)} run(s) turn faster than a car can "
                  f"at its speed while the samples beside them do not (over {MAX_LATERAL_ACCEL:g} m/s^2 sideways, or a "
                  f"{MIN_TURN_RADIUS:g} m turning radius; the first at t = {t[i]:g} s, {rate[i]:+.3g} rad/s at "
                  f"{speed[i]:.3g} m/s): spikes (a gyro's glitch), which integrated would turn every later heading; "
                  "each is interpolated from the samples beside it", RuntimeWarning, stacklevel=5)
    return _fill_runs(t, rate, runs)


def _ddmm_cause(lat, lon):
    """The words a refusal of lat/lon past degrees adds where every value reads as NMEA's degrees and minutes
    (``ddmm.mmmm``, ``dddmm.mmmm``: GGA's and RMC's 4807.038 is 48 degrees 7.038 minutes), else ``""``."""
    a, o = np.abs(lat), np.abs(lon)
    if not (np.all(a < 9000) and np.all(o < 18000) and np.all(a % 100 < 60) and np.all(o % 100 < 60)):
        return ""
    return ("; they read as NMEA's degrees and minutes (ddmm.mmmm, as GGA and RMC write them: 4807.038 is 48 degrees "
            "7.038 minutes): give degrees, floor(x / 100) + (x % 100) / 60, negative for S and W")


def _e7_cause(lat, lon):
    """The words a refusal of lat/lon past degrees adds where every value reads as degrees times 1e7 (the integers
    of u-blox's UBX and of many binary protocols: 481370000 is 48.137 degrees), else ``""``."""
    a, o = np.abs(lat), np.abs(lon)
    if not (np.all(a <= 90e7) and np.all(o <= 360e7) and np.max(np.r_[a, o]) > 1e5):
        return ""
    return ("; they read as degrees times 1e7 (the integers of u-blox's UBX and many binary protocols: 481370000 is "
            "48.137 degrees): divide by 1e7")


def _warn_speed_cutoff(speed, dt):
    """Warn when the speed reads 0 below some cutoff: at each of at least four start-ups and stops it steps
    between 0 and at least ``s`` within one sample, more than a car's speed changes in one
    (:data:`MAX_STOP_ACCEL` times ``dt``), and ``s`` is at least :data:`SPEED_CUTOFF_WARN`. At 1 Hz a car
    can change speed by 3 m/s in a sample, so only a cutoff above that is seen there."""
    still = speed == 0
    edges = speed[np.r_[np.flatnonzero(still[:-1] & ~still[1:]) + 1, np.flatnonzero(~still[:-1] & still[1:])]]
    if len(edges) < _MIN_SPEED_EDGES:
        return
    s = float(edges.min())
    if s < max(SPEED_CUTOFF_WARN, MAX_STOP_ACCEL * dt):
        return
    warnings.warn(f"at each of the {len(edges)} start-ups and stops the speed steps between 0 and at least {s:.2g} "
                  f"m/s within one {dt:g} s sample, more than a car's speed changes in one ({MAX_STOP_ACCEL:g} "
                  f"m/s^2): the speed sensor reads 0 below about {s:.2g} m/s (a wheel-speed sensor's cutoff). A car "
                  "creeping slower, in a queue, is taken to stand, and the zero-velocity update holds its position "
                  "while it moves (the filters find a long crawl from the fixes, and warn of a turn while creeping). "
                  "If the log has the wheel-tick distance, give it as the odometer column instead", RuntimeWarning,
                  stacklevel=4)


def _null_fixes(lat, lon):
    """Which fixes are a receiver's null fix: exactly lat = lon = 0, written before it has a position
    (:meth:`DRRun.from_arrays` drops them; the default origin is the first fix that is not one)."""
    return (np.asarray(lat) == 0.0) & (np.asarray(lon) == 0.0)


def _gps_fixes(gps_t, east, north, lat, lon, gps_sigma, origin, t, dt):
    """The GPS fixes on the DR grid: their steps, east/north (m), sigmas (or None), for lat/lon fixes
    east/north read with lat and lon exchanged (or None), and each fix's time less its sample's (s; None
    when every fix is at its sample's time)."""
    n = len(t)
    gps_t = _finite_1d(gps_t, "gps_t")
    m = len(gps_t)
    swapped = None
    en_given = east is not None or north is not None
    ll_given = lat is not None or lon is not None
    if en_given == ll_given:
        raise ValueError("give the GPS fixes as exactly one of east/north (m) and lat/lon (deg), got "
                         + ("both" if en_given else "neither"))
    if en_given:
        e, nn = _finite_1d(east, "east", m), _finite_1d(north, "north", m)
    else:
        la, lo = _finite_1d(lat, "lat", m), _finite_1d(lon, "lon", m)
        if np.any(np.abs(la) > 90) or np.any(np.abs(lo) > 360):
            raise ValueError(f"lat/lon must be degrees (|lat| <= 90, |lon| <= 360), got max |lat| = "
                             f"{np.max(np.abs(la)):g}, max |lon| = {np.max(np.abs(lo)):g}"
                             + (_ddmm_cause(la, lo) or _e7_cause(la, lo)))
        null = _null_fixes(la, lo)
        if null.any():  # a receiver's "no position" written as a position; as the origin it bent every fix
            if null.all():
                raise ValueError(f"every GPS fix is at lat = lon = 0 (a receiver's null fix: no position); "
                                 f"the drive has no fix to use ({m} given)")
            warnings.warn(f"dropped {int(null.sum())} GPS fix(es) at lat = lon = 0 (a receiver's null fix, written "
                          f"before it has a position), the first at t = {float(gps_t[null][0]):g} s", RuntimeWarning,
                          stacklevel=4)
            ok = ~null
            gps_t, la, lo, m = gps_t[ok], la[ok], lo[ok], int(ok.sum())
            if gps_sigma is not None and np.ndim(gps_sigma):
                gps_sigma = np.asarray(gps_sigma, dtype=float)[ok]
        lat0, lon0 = (la[0], lo[0]) if origin is None else (float(origin[0]), float(origin[1]))
        e, nn = latlon_to_en(la, lo, lat0, lon0)
        if np.all(np.abs(lo) <= 90):  # the fixes read with lat and lon exchanged, for the plausibility check
            swapped = np.stack(latlon_to_en(lo, la, lon0, lat0), axis=1)
    if gps_sigma is not None:
        gs = np.asarray(gps_sigma, dtype=float)
        gs = np.full(m, float(gs)) if gs.ndim == 0 else _finite_1d(gs, "gps_sigma", m)
        if not np.all(np.isfinite(gs)) or np.any(gs <= 0):
            k = int(np.argmax(~np.isfinite(gs) | (gs <= 0)))
            raise ValueError(f"gps_sigma must be finite and > 0 (m); gps_sigma[{k}] = {float(gs[k])!r}")
    held = _held_fixes(gps_t, e, nn, dt)
    if held is not None:
        gps_t, e, nn = gps_t[held], e[held], nn[held]
        gs = gs[held] if gps_sigma is not None else None
        swapped = None if swapped is None else swapped[held]
    # each fix on the sample nearest its time (ties to the earlier), as a step (sample i is step i - 1); not
    # by the nominal dt: with intervals within max_jitter whose mean is not their median (a logger that
    # is late one sample in ten by 15 ms), t0 + k dt drifts from the k-th sample, by 15 s after 1000 s
    i = np.clip(np.searchsorted(t, gps_t), 1, n - 1)
    i = np.where(gps_t - t[i - 1] <= t[i] - gps_t, i - 1, i)
    k_fix = i - 1
    keep = (k_fix >= 0) & (gps_t <= t[-1] + 0.5 * dt)
    _fixes_outside(gps_t, (gps_t >= t[0] - 0.5 * dt) & (gps_t <= t[-1] + 0.5 * dt), t)
    k_fix, idx = np.unique(k_fix[keep], return_index=True)
    shared = np.ones(int(keep.sum()), dtype=bool)
    shared[idx] = False  # the fixes a sample's first fix left out
    if shared.any():
        warnings.warn(f"{int(shared.sum())} GPS fix(es) share their nearest DR sample with an earlier fix "
                      f"(the first at t = {float(gps_t[keep][shared][0]):.10g} s): each sample takes one fix, the "
                      "first; fixes faster than the samples, or stamps that jitter by more than half a sample "
                      "interval, do so", RuntimeWarning, stacklevel=5)
    sel = np.flatnonzero(keep)[idx]
    offset = np.round(gps_t[sel] - t[k_fix + 1], 9)  # to the nanosecond: a fix on its sample is 0 exactly
    return (k_fix, np.stack([e[sel], nn[sel]], axis=1), (gs[sel] if gps_sigma is not None else None),
            None if swapped is None else swapped[sel], offset if np.any(offset) else None)



def _fixes_outside(gps_t, keep, t):
    """Refuse fixes whose times mostly lie outside the DR samples' (two clocks: a receiver's UTC time of day
    against a logger's time from its start, stop 59), naming both spans; warn of the few that do (the log's ends).
    ``keep``: the fixes within half a sample interval of the samples' span."""
    out = int(len(keep) - keep.sum())
    if not out:
        return
    spans = (f"the fixes' times run {float(gps_t.min()):.10g}-{float(gps_t.max()):.10g} s, the DR samples' "
             f"{float(t[0]):.10g}-{float(t[-1]):.10g} s")
    if out > 0.5 * len(keep):
        from ._plausibility import _TIME_UNITS

        for factor, unit in _TIME_UNITS:  # the fixes' times in another unit than the samples'
            scaled = gps_t / factor
            inside = (scaled >= t[0] - 1.0) & (scaled <= t[-1] + 1.0)
            if inside.mean() > 0.5 and np.ptp(scaled) >= 0.5 * (t[-1] - t[0]):  # (and as long as the drive)
                raise ValueError(f"{out} of the {len(keep)} GPS fixes lie outside the DR samples' time span ({spans}): "
                                 f"the fixes' times look like {unit} (divided by {factor:g} they lie in the samples' "
                                 f"span; u-blox's iTOW is in milliseconds): give them in seconds")
        raise ValueError(f"{out} of the {len(keep)} GPS fixes lie outside the DR samples' time span ({spans}): the "
                         "fixes and the samples are on two clocks (a receiver's UTC time of day, or seconds of the GPS "
                         "week, against a logger's time from its start?): put both on one clock (the logger's start "
                         "in UTC added to its times, or the fixes' date added to theirs)")
    warnings.warn(f"{out} GPS fix(es) lie outside the DR samples' time span ({spans}) and are not used",
                  RuntimeWarning, stacklevel=6)


#: The share of the fixes that repeat the one on the row before, to the bit, past which a drive's GPS columns are
#: read as a log that carries its last fix forward to every DR sample (see :func:`_held_fixes`).
HELD_FIX_SHARE = 0.5


def _held_fixes(gps_t, east, north, dt):
    """Which fixes to keep when the fixes are a log's last fix carried forward (sample and hold): more than
    :data:`HELD_FIX_SHARE` of them on the DR sample after the one before (within 1.5 sample intervals) with
    the same position to the bit. Then only each run's first is a fix, with a warning; else None (every fix
    kept: a receiver that holds its fix while the car stands, or re-sends it while it has none, repeats a few,
    which the GPS/DR filter takes or leaves itself, ``n_stale``)."""
    if len(gps_t) < 3:
        return None
    same = np.r_[False, (np.diff(gps_t) <= 1.5 * dt) & (np.diff(east) == 0.0) & (np.diff(north) == 0.0)]
    if same.mean() <= HELD_FIX_SHARE:
        return None
    keep = ~same
    runs = np.diff(np.r_[np.flatnonzero(keep), len(same)])
    gaps = np.diff(gps_t[keep])
    warnings.warn(f"the GPS columns repeat each fix on the rows after it ({int(same.sum())} of {len(same)} fix rows "
                  f"repeat the one before to the bit, in runs of a median {np.median(runs):g} rows): a log that "
                  "carries its last fix forward to every DR sample. Only each run's first row is taken for a fix "
                  f"({int(keep.sum())} fixes, a median {np.median(gaps) if len(gaps) else 0:g} s apart); repeated, "
                  "each would count as a new fix", RuntimeWarning, stacklevel=5)
    return keep


def _truth_states(truth, t):
    """The 6-state truth (steps ``1..n-1``) from reference east/north, and the first position."""
    n = len(t)
    tr = np.asarray(truth, dtype=float)
    if tr.shape != (n, 2):
        raise ValueError(f"truth must have shape (n_samples, 2) = ({n}, 2) [east, north in m], got {tr.shape}")
    if not np.all(np.isfinite(tr)):
        raise ValueError(f"truth must be finite; row {int(np.argmax(~np.isfinite(tr).all(axis=1)))} is not")
    ve, vn = np.gradient(tr[:, 0], t), np.gradient(tr[:, 1], t)
    full = np.stack([tr[:, 0], ve, np.gradient(ve, t), tr[:, 1], vn, np.gradient(vn, t)], axis=1)
    return full[1:], tr[0]


def _finite_1d(a, name, n=None):
    a = np.asarray(a, dtype=float)
    if a.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {a.shape}")
    if n is not None and len(a) != n:
        raise ValueError(f"{name} must have the same length as t ({n}), got {len(a)}")
    bad = ~np.isfinite(a)
    if bad.any():
        k = int(np.argmax(bad))
        raise ValueError(f"{name} must be finite; {name}[{k}] = {float(a[k])!r}")
    return a


_WGS84_A, _WGS84_E2 = 6378137.0, 6.69437999014e-3


def earth_radii(lat0_rad):
    sl = np.sin(lat0_rad)
    rn = _WGS84_A / np.sqrt(1 - _WGS84_E2 * sl * sl)
    rm = _WGS84_A * (1 - _WGS84_E2) / (1 - _WGS84_E2 * sl * sl) ** 1.5
    return rn, rm


def latlon_to_en(lat, lon, lat0, lon0, h0=0.0):
    """Latitude/longitude (degrees, WGS84) to local east/north metres about ``(lat0, lon0)``.

    The local tangent-plane approximation with the WGS84 radii of curvature at the origin
    (prime vertical ``R_N``, meridian ``R_M``): ``e = dlon (R_N + h0) cos(lat0)``,
    ``n = dlat (R_M + h0)``. Good to centimetres over a few kilometres.

    >>> e, n = latlon_to_en([45.0, 45.001], [7.0, 7.001], 45.0, 7.0)
    >>> [round(float(v), 2) for v in (e[1], n[1])]
    [78.85, 111.13]
    """
    la0, lo0 = np.deg2rad(lat0), np.deg2rad(lon0)
    rn, rm = earth_radii(la0)
    dlon = wrap_angle(np.deg2rad(np.asarray(lon, dtype=float)) - lo0)
    e = dlon * (rn + h0) * np.cos(la0)
    n = (np.deg2rad(np.asarray(lat, dtype=float)) - la0) * (rm + h0)
    return e, n


def en_to_latlon(east, north, lat0, lon0, h0=0.0):
    """The inverse of :func:`latlon_to_en`: ``(lat, lon)`` in degrees."""
    la0 = np.deg2rad(lat0)
    rn, rm = earth_radii(la0)
    lat = lat0 + np.rad2deg(np.asarray(north, dtype=float) / (rm + h0))
    lon = lon0 + np.rad2deg(np.asarray(east, dtype=float) / ((rn + h0) * np.cos(la0)))
    return lat, lon


def _profile_rate(windows, t):
    rate = 0.0
    for t0, t1, amount in windows:
        if t0 <= t < t1:
            rate += amount / (t1 - t0)
    return rate


#: Speed (m/s) under which the simulated truth is at rest: a speed change that brakes the car to
#: exactly its speed leaves it at rounding level (1e-15 m/s), whose direction is noise.
STOPPED = 1e-9


def true_trajectory(scenario):
    """Noise-free truth of a scenario: ``(t (n,), x0 (6,), x_true (n, 6))``."""
    sc = scenario
    n = sc.n_steps
    dt = sc.dt
    x = sc.x0.copy()
    xs = np.empty((n, 6))

    h0 = np.deg2rad(sc.heading)
    last = [np.sin(h0), np.cos(h0)]  # a standing car pulls away along its last heading

    def accel(x, t):
        ve, vn = x[1], x[4]
        v = np.hypot(ve, vn)
        dv = _profile_rate(sc.speed_changes, t)
        om = np.deg2rad(_profile_rate(sc.turns, t))
        if v > 0:
            last[:] = ve / v, vn / v
        ue, un = last
        return dv * ue + om * vn, dv * un - om * ve

    x[2], x[5] = accel(x, 0.0)
    for k in range(n):
        x = dr_fx(x, dt)
        if 0.0 < np.hypot(x[1], x[4]) < STOPPED:  # braked to rest up to rounding: standing
            x[1] = x[4] = 0.0
        t = (k + 1) * dt
        x[2], x[5] = accel(x, t)
        xs[k] = x
    return dt * np.arange(1, n + 1), sc.x0.copy(), xs


def _true_heading(xs, heading0_deg):
    """``atan2(v_e, v_n)``, held at its last value while the car stands (a gyro keeps its heading)."""
    hd = np.arctan2(xs[:, 1], xs[:, 4])
    moving = np.hypot(xs[:, 1], xs[:, 4]) > 0
    if moving.all():
        return hd
    idx = np.where(moving, np.arange(len(hd)), -1)
    idx = np.maximum.accumulate(idx)
    return np.where(idx >= 0, hd[np.maximum(idx, 0)], np.deg2rad(heading0_deg))


def simulate_scenario(scenario, rng=None):
    """Simulate the truth and the sensors of a :class:`Scenario`.

    Random numbers are drawn in a fixed order (heading noise, odometer noise, outlier
    draws, GPS noise), always for every step, so two scenarios differing only in noise
    levels share their random numbers.

    Returns
    -------
    DRRun
    """
    if not isinstance(scenario, Scenario):
        raise TypeError(f"scenario must be a Scenario, got {type(scenario).__name__}")
    rng = check_rng(rng)
    sc = scenario
    t, x0, xs = true_trajectory(sc)
    n = len(t)
    f = np.where(t >= sc.t_switch, sc.factor, 1.0)
    sh = np.deg2rad(sc.sigma_heading) * f
    so = sc.sigma_odometer * f
    e_h = rng.standard_normal(n)
    e_s = rng.standard_normal(n)
    u_out = rng.random(n)
    sign_out = np.where(rng.random(n) < 0.5, -1.0, 1.0)
    e_g = rng.standard_normal((n, 2))
    heading = _true_heading(xs, sc.heading) + np.deg2rad(sc.heading_bias + sc.heading_drift * t) + sh * e_h
    outlier = (t >= sc.t_switch) & (u_out < sc.outlier_prob)
    heading = heading + outlier * sign_out * np.deg2rad(sc.outlier_deg)
    speed = np.hypot(xs[:, 1], xs[:, 4])
    # an odometer never reads negative, and reads exactly 0 at standstill
    dist = np.where(speed > 0, np.maximum(sc.dt * sc.odometer_scale * speed + so * e_s, 0.0), 0.0)
    z_dr = np.stack([wrap_angle(heading), dist], axis=1)
    if sc.gps_rate > 0:
        every = max(int(round(1.0 / (sc.gps_rate * sc.dt))), 1)
        steps = np.arange(every - 1, n, every)
        ok = np.ones(len(steps), dtype=bool)
        for a, b in sc.outages:
            ok &= ~((t[steps] >= a) & (t[steps] < b))
        steps = steps[ok]
        z_gps = xs[steps][:, [0, 3]] + sc.sigma_gps * e_g[steps]
    else:
        steps = np.zeros(0, dtype=int)
        z_gps = np.zeros((0, 2))
    R_true = np.stack([sh**2, so**2], axis=1)
    return DRRun(t, x0, xs, z_dr, steps, z_gps, R_true, sc)


def with_outage(run, start, length):
    """A copy of ``run`` without GPS fixes in ``[start, start + length)`` (times of ``run.t``: seconds from the
    drive's first sample, not the log's own clock, which started at ``run.t_start``). A ``length`` that is not
    positive is refused; an outage that drops no fix is warned of, naming the times the fixes span."""
    start, length = check_finite(start, "start", "seconds"), check_positive(length, "length")
    tf = run.t[run.gps_steps]
    keep = ~((tf >= start) & (tf < start + length))
    if keep.all():
        span = f"{tf[0]:g} to {tf[-1]:g} s" if len(tf) else "none: the drive has no fix"
        clock = (f"; the log's own clock started at {run.t_start:g} s (run.t_start): subtract it from a time on "
                 "that clock" if getattr(run, "t_start", 0.0) else "")
        warnings.warn(f"with_outage drops no fix: [{start:g}, {start + length:g}) s holds none of the drive's fixes, "
                      f"whose times (run.t, seconds from the drive's first sample) run {span}{clock}", RuntimeWarning,
                      stacklevel=2)
    sc = run.scenario.with_(outages=((float(start), float(start + length)),))
    sig = None if run.gps_sigma is None else run.gps_sigma[keep]
    offset = None if run.gps_offset is None else run.gps_offset[keep]
    return run._replace(gps_steps=run.gps_steps[keep], z_gps=run.z_gps[keep], scenario=sc, gps_sigma=sig,
                        gps_offset=offset)


#: An outage of ``length`` s placed in a drive starts at most ``OUTAGE_GAP_SLACK * length`` after the drive's last
#: fix before it (or twice the fixes' median interval, where that is longer): later, it would start in the drive's
#: own gap of fixes (a tunnel, a receiver off), and the filters would go longer than ``length`` without a fix where
#: dead reckoning from the true start (``DR-mech``) goes ``length`` (:func:`fix_gaps`, :func:`outage_starts`).
OUTAGE_GAP_SLACK = 0.1


def fix_gaps(run, length=30.0):
    """The drive's own gaps of fixes, where an outage of ``length`` s is not placed.

    A gap runs from a fix (or the drive's start, ``t = 0``, whose state ``run.x0`` the filters are given) to the
    next fix (or the drive's end); it is the drive's own where it is longer than the allowance,
    ``max(OUTAGE_GAP_SLACK * length, 2 * the fixes' median interval)``. An outage starting in one more than the
    allowance after its beginning is longer, for the filters, than ``length`` (they have had no fix since the gap
    began), while dead reckoning from the true start goes ``length``: its score would not be an outage of
    ``length`` s. A drive with fewer than two fixes has none (there is nothing to place against).

    Returns
    -------
    gaps : ndarray of shape (n_gaps, 2)
        Each gap's beginning and end (s, on ``run.t``); an outage may start in ``[begin, begin + allowance]``.
    allowance : float
        The allowance (s).

    >>> t = np.arange(0.0, 600.05, 0.1)
    >>> gps_t = np.concatenate([np.arange(1.0, 200.0), np.arange(300.0, 601.0)])   # a 100 s tunnel
    >>> run = DRRun.from_arrays(t, np.zeros(t.size), speed=np.full(t.size, 10.0), gps_t=gps_t,
    ...                         east=np.zeros(gps_t.size), north=10 * gps_t)
    >>> gaps, allowance = fix_gaps(run)
    >>> gaps.round(1).tolist(), allowance
    ([[199.0, 300.0]], 3.0)
    """
    length = check_positive(length, "length")
    tf = np.asarray(run.t, dtype=float)[np.asarray(run.gps_steps, dtype=int)]
    if len(tf) < 2:
        return np.zeros((0, 2)), float(OUTAGE_GAP_SLACK * length)
    allowance = float(max(OUTAGE_GAP_SLACK * length, 2.0 * np.median(np.diff(tf))))
    points = np.concatenate([[0.0], tf, [float(run.t[-1])]])
    long = np.flatnonzero(np.diff(points) > allowance)
    return np.stack([points[long], points[long + 1]], axis=1), allowance


def _in_gaps(starts, gaps, allowance):
    """Per start, the index of the drive's own gap of fixes it starts in (-1: none)."""
    starts = np.atleast_1d(np.asarray(starts, dtype=float))
    if not len(gaps):
        return np.full(len(starts), -1)
    inside = (starts[:, None] > gaps[:, 0] + allowance) & (starts[:, None] < gaps[:, 1])
    return np.where(inside.any(axis=1), inside.argmax(axis=1), -1)


def outage_starts(run, length=30.0, starts=None, n=20, min_speed=0.0):
    """Start times (s, on ``run.t``) of GPS outages of ``length`` s.

    Parameters
    ----------
    run : DRRun
    length : float
        Outage length (s).
    starts : array-like, optional
        The start times, as given: checked to lie in ``[0, t_end - length]``.
    n : int
        Without ``starts``: ``n`` outages spread evenly over the drive, among the
        windows that qualify under ``min_speed`` and start where the drive has its fixes (not in its own gaps
        of fixes, :func:`fix_gaps`: there an outage would be longer than ``length``).
    min_speed : float
        Without ``starts``: only windows whose mean odometer speed is at least this
        (m/s) qualify (0: every window; e.g. 2 m/s keeps outages where the car drives
        rather than waits at lights). Fewer than ``n`` come back if fewer qualify
        without overlapping the same start.

    Returns
    -------
    ndarray of shape (n_outages,)
    """
    length = check_positive(length, "length")
    t_end = float(run.t[-1])
    if t_end - length < run.t[0]:
        raise ValueError(f"length must be shorter than the drive ({t_end:g} s), got {length:g}")
    if starts is not None:
        starts = np.atleast_1d(np.asarray(starts, dtype=float))
        bad = ~np.isfinite(starts) | (starts < 0) | (starts > t_end - length)
        if bad.any():
            raise ValueError(f"starts must lie in [0, {t_end - length:g}] (the drive is {t_end:g} s, outages "
                             f"{length:g} s), got {float(starts[bad][0])!r}")
        return starts
    n = int(n)
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    min_speed = check_positive(min_speed, "min_speed", strict=False)
    dt = run.scenario.dt
    grid = np.arange(0.0, t_end - length, dt)
    cum = np.concatenate([[0.0], np.cumsum(run.z_dr[:, 1])])
    k0 = np.searchsorted(run.t, grid)
    k1 = np.searchsorted(run.t, grid + length)
    mean_speed = (cum[k1] - cum[k0]) / length
    gaps, allowance = fix_gaps(run, length)
    fixed = _in_gaps(grid, gaps, allowance) < 0
    ok = grid[(mean_speed >= min_speed) & fixed]
    if len(ok) == 0:
        fast = grid[mean_speed >= min_speed]
        if len(fast) == 0:
            raise ValueError(f"no {length:g} s window has a mean odometer speed >= min_speed = {min_speed:g} m/s")
        raise ValueError(f"no {length:g} s window with a mean odometer speed >= min_speed = {min_speed:g} m/s starts "
                         f"within {allowance:g} s of a GPS fix: the drive's own gaps of fixes cover them")
    pick = np.unique(np.round(np.linspace(0, len(ok) - 1, n)).astype(int))
    return ok[pick]


