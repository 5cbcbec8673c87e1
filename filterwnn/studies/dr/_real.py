"""The DR study on recorded drives: GPS outages cut into a drive, each filter scored at their ends.

:func:`real_drive_outages` places ``length``-second outages over a drive (onavdata's car
drives, the shipped sample, or one's own CSV), runs each filter of :data:`REAL_FILTERS`
once with GPS, snapshots it at each outage start and runs each outage alone;
:func:`real_drive_table` is its Markdown table.
"""

from __future__ import annotations

import contextlib
import copy
import sys
import warnings

import numpy as np

from ..._warnings import folded_warnings, give_again, kept_warnings, recorded_call
from ...navigation.dead_reckoning import GPSDRModel
from ...navigation.drives import CAR_DRIVE
from ...navigation.gpsdr import (_DR_SENSORS, CALIBRATION_ERROR_Z, DR_NOISE_WINDOW, GYRO_SCALE, HEADING_JUMP_Z,
                                  SIGMA_FLOOR, GPSDRFilter)
from ...navigation.scenarios import _in_gaps, fix_gaps, outage_starts
from ._filters import FILTER_KIND

#: GPS/DR model settings for the real drive (a car's manoeuvres need a larger jerk PSD,
#: the receiver's fixes are about 1 m, and the gyro's heading drifts: a random-walk bias).
REAL_MODEL = dict(q=2.0, sigma_heading=np.deg2rad(1.0), sigma_odometer=0.02, sigma_gps=1.0,
                  q_scale=1e-6, q_bias=1e-6)


#: The filters run on a real drive (raw dead reckoning, the 6-state EKF and the 8-state filters).
REAL_FILTERS = ("DR-mech", "EKF", "EKF-8", "UKF-8", "SUKF-8")


def check_reference(run):
    """Refuse a drive with neither a truth nor a fix: nothing to score its outages against."""
    if run.x_true is None and not len(run.gps_steps):
        raise ValueError("the drive has no truth and no GPS fix at all to score against (a drive CSV gives its fixes "
                         "as gps_east/gps_north or gps_lat/gps_lon, and its truth as true_east/true_north or "
                         "true_lat/true_lon: filterwnn.navigation.drives.DRIVE_CSV_COLUMNS)")


#: :func:`real_drive_outages`'s filters by default.
_DEFAULT_FILTERS = ("DR-mech", "EKF", "EKF-8")


def real_drive_outages(run, n_placements=20, length=30.0, filters=_DEFAULT_FILTERS,
                       model_kwargs=None, slow_speed=None, starts=None, min_speed=0.0,
                       use_gps_sigma=False, grade=None, gps_window=0, scale_window=0,
                       correlated_fixes="calibration", min_fix_interval=0.0, stop_reopen=0.0,
                       calibration_error_z=CALIBRATION_ERROR_Z, heading_jump_z=HEADING_JUMP_Z, reversing_test=True,
                       crawl_test=True, gps_sigma_floor=SIGMA_FLOOR, floor_on_detection=True,
                       reopen_on_detection=True, dr_noise_window=DR_NOISE_WINDOW, hold_heading_at_stops=False,
                       progress=False, n_jobs=1):
    """Cut GPS outages of ``length`` s into a drive and score each filter at each outage end.

    Placements: ``starts`` as given (one in the drive's own gap of fixes is warned of), or ``n_placements`` spread
    evenly over the windows that start where the drive has its fixes
    (:func:`~filterwnn.navigation.scenarios.fix_gaps`) and whose mean
    odometer speed is at least ``min_speed`` (:func:`~filterwnn.navigation.scenarios.outage_starts`; with the
    default 0 the first one starts before the car moves). ``EKF``/``EKF-8``/``UKF-8``/``SUKF-8`` are
    :class:`~filterwnn.navigation.gpsdr.GPSDRFilter` s (6 or 8 states; the filter decides standstill and low
    speed itself); ``DR-mech`` integrates ``s [sin theta, cos theta]`` from the reference position at the
    outage start (dead reckoning without a filter).

    The reference is the truth when the drive has one (``run.x_true``); otherwise the GPS fix
    withheld last in the outage, so the score then includes that fix's own error (for a fix logged between
    the samples, the fixes' track at its sample's time: the errors of the two fixes beside it, interpolated).

    Parameters
    ----------
    run : DRRun
    n_placements, length, starts, min_speed : where the outages go (see above)
    filters : sequence of str
        Subset of :data:`REAL_FILTERS`.
    model_kwargs : dict, optional
        :class:`~filterwnn.navigation.dead_reckoning.GPSDRModel` settings over :data:`REAL_MODEL`, or
        over the grade's settings.
    grade : str or dict, optional
        Settings from a sensor grade or specification
        (:meth:`~filterwnn.navigation.dead_reckoning.GPSDRModel.from_grade`; ``"phone"`` adds the gyro
        rate-bias state to the 8-state filters) instead of :data:`REAL_MODEL`, which was
        tuned on the onavdata drive.
    slow_speed : float, optional
        The filters' low-speed threshold (m/s; default :data:`filterwnn.navigation.gpsdr.LOW_SPEED`).
    use_gps_sigma : bool
        Use each fix's reported accuracy (``run.gps_sigma``) as its noise.
    gps_window, scale_window : int
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: the noise of fixes without an accuracy, and the
        scale of the fixes' reported covariance, estimated over this many fixes (0, the defaults: neither).
    correlated_fixes : {"calibration", "inflate"}
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: how the fixes' correlation counts them.
    stop_reopen : float
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: seconds within which a stop that starts again is
        the same stop to the zero angular rate update (0, the default: none).
    calibration_error_z : float or None
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: the consistency monitor's z-score past which the
        heading bias or the rate bias is taken to be off and their gain takes the fixes' own correlation
        (default :data:`~filterwnn.navigation.gpsdr.CALIBRATION_ERROR_Z`; None: never).
    heading_jump_z : float or None
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: the heading-jump detector's gate (a heading that
        steps while the car moves; default :data:`~filterwnn.navigation.gpsdr.HEADING_JUMP_Z`; None: not looked for).
    reversing_test : bool
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: test the fixes for the car reversing on an unsigned
        speed (default True; off for a drive whose signed speed told its reversals, ``run.reversed_by_speed``).
    crawl_test : bool
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: test the fixes for the car creeping while its speed
        reads 0 (default True).
    min_fix_interval : float
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: seconds after a fix used before the next
        is used (0, the default: every fix).
    gps_sigma_floor : float
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: with ``use_gps_sigma``, a fix's reported sigma is
        taken no smaller than this fraction of the lower of the medians of the last 3 and the last 30 reported
        (default :data:`~filterwnn.navigation.gpsdr.SIGMA_FLOOR`; 0: as reported).
    floor_on_detection : bool
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: once the consistency monitor names fixes that report far
        better than they are, floor every fix's sigma at the median of the last 30 reported (default True).
    reopen_on_detection : bool
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: once a standstill cut into pieces by a speed that does
        not read 0 leaves the rate-bias state unable to follow a piece, take each standstill whole from then on
        (``stop_reopen`` 2 s; default True).
    hold_heading_at_stops : bool
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: a stop the zero angular rate gate rejects gives its drift
        beyond the rate-bias state to the heading bias, for a gyro whose bias differs while the car stands (default
        False).
    dr_noise_window : int
        :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s: moving samples over which the heading's and the
        odometer's white noise are estimated online from their innovations, raised past the grade's where they
        are larger (default :data:`~filterwnn.navigation.gpsdr.DR_NOISE_WINDOW`; 0: the grade's as given).
    progress : bool or None
        A tqdm bar on stderr over each filter's steps (the pass over the drive, then each outage run again
        without its fixes), named by the drive and the filter and cleared when the filter is done (before its
        warnings). None: on a terminal, and only once a filter has run for 2 s (``PROGRESS_DELAY``; an hour
        of 100 Hz log takes each filter minutes). Default False. With the filters in worker processes
        (``n_jobs``), a bar over the filters done instead (on a terminal, for None).
    n_jobs : int
        Processes (joblib's loky; -1: one per core) that run the GPS/DR filters side by side, each filter
        in one, where there are two or more and the drive's steps times their number reach
        40,000 (``PARALLEL_STEPS``; a shorter drive runs here: starting the workers would take longer). The
        numbers and the warnings (the same lines, in the filters' order, once all have run) do not depend
        on it. Default 1.

    Returns
    -------
    dict
        ``starts (n,)``, ``length``, ``moved (n,)`` (distance driven during each outage, m), ``end_steps
        (n,)`` (the scored step of each outage), ``reference`` ("truth" or "withheld GPS"), ``name``,
        ``track (n_steps, 2)`` (truth, else the fixes interpolated), ``fix_gaps (n_gaps, 2)`` (the drive's own
        gaps of fixes, :func:`~filterwnn.navigation.scenarios.fix_gaps`), ``in_fix_gap (n,)`` (the gap each given
        start lies in, -1: none), ``end_xy {filter: (n, 2)}``,
        ``start_err {filter: (n,)}`` (the horizontal error when each outage starts, against the same
        reference as the ends; 0 for ``DR-mech``, which starts there), ``integrity {filter: dict}`` (over
        the whole drive with GPS: ``n_fixes`` (tested), ``n_thinned`` (not used: ``min_fix_interval``),
        ``n_stale`` (not used: the last fix re-sent),
        ``n_rejected``, ``n_downweighted``, ``n_reacquired``,
        ``nis_mean``, the NIS of the accepted fixes (2 when consistent), ``gps_scale_mean`` and ``gps_scale``,
        the mean and last factor on the fixes' covariance (mean None: not estimated),
        ``gps_correlation_mean``, the mean of the fixes' measured correlation (1: white; None: not
        estimated), ``rejected_xy (m, 2)``,
        the rejected fixes, ``n_zero_rate``, ``n_zero_rate_rejected`` and ``n_zero_rate_held``, the stops
        whose heading drift updated the gyro rate bias, was rejected, or did not move at all (a heading
        held by its source), ``n_zero_rate_reacquired``, the rate-bias state's re-acquisitions from
        stops it could not follow that agreed, ``n_zero_rate_turned``, the rejected stops whose heading
        turned faster than any gyro's bias, "(N turned)" in the table, and ``n_zero_rate_stepped``, the stops
        whose heading stepped (a fused heading re-aligning), "(N stepped)", and ``n_zero_rate_drift_taken``, the
        rejected stops whose drift beyond the state the heading bias took, "(N drift taken)"; None without a
        rate-bias state;
        ``n_calibration_error``, the fixes at which the consistency monitor found the heading bias or the rate
        bias off and their gain took the fixes' own correlation, "(off at N fixes)" after the correlation;
        ``n_heading_jumps``, the steps of the heading the heading-jump detector found while the car moved,
        "(N jumped)" after the fixes' counts, and ``heading_jumps``, per step (step found, onset step,
        estimate (rad), z-score); ``n_heading_far``, the DR samples whose heading was so far from the filter's
        that they entered as a velocity vector (``heading_linear_limit``), "(N headings far)"; ``n_from_rest``, the
        moving DR samples that entered so where the filter stood (a speed that jumped from 0), "(N from rest)";
        ``n_reversing``,
        the times the fixes showed the car reversing on an unsigned speed (``reversing_test``), "(N reversing)",
        and ``n_forward_again``, driving forward again with no stop between, "(N forward again)"; ``n_crawl``, the
        times the fixes showed the car creeping while its speed read 0 (``crawl_test``), "(N crawling)", and
        ``crawl_moved``, how far (m) the position moved at them in all; ``n_floored``, the fixes whose reported
        sigma was under the floor (``gps_sigma_floor``), "(N floored)", and ``floor_raised``, the step from which the
        floor was the median (``floor_on_detection``; None: never), "(floor raised at step N)"; ``stops_cut``, the
        step at which the filter found a standstill cut into pieces that the rate-bias state could not follow, from
        which it took each standstill whole (``reopen_on_detection``; None: never), "(whole from step N)" after the
        stops' counts;
        ``gyro_scale_estimate`` and ``gyro_scale_z``, the scale-error monitor's estimate and z-score (None
        without it), ``gyro_scale_added``, the step at which it made the filter add the scale state (None:
        not), and ``gyro_scale``, that state's last value (None without one); ``latency_estimate``,
        ``latency_z``, ``latency_added`` and ``latency``, the same for the fixes' latency (s), and ``latency_at_end``
        and ``gyro_scale_at_end``, the latency and the scale error told when the drive ended
        (:meth:`~filterwnn.navigation.gpsdr.GPSDRFilter.end_of_drive`; None: not);
        ``odometer_latency_estimate`` and ``odometer_latency_z``, the speed's latency (s);
        ``heading_noise_raised`` and ``odometer_noise_raised``, the steps at which the filter found the heading or
        the odometer noisier than its grade (``dr_noise_window``; None: never), and ``heading_noise_deg`` and
        ``odometer_noise_m``, its estimate at the drive's end (None: the grade's throughout), and
        ``heading_noise_back`` and ``odometer_noise_back``, whether a raised estimate was back at the grade's by the
        end), and
        ``warnings``, the text of each warning the filters gave (one line per kind and filter, its repeats folded:
        what the terminal shows), and ``read_warnings``, empty here (``filterwnn study dr --drive`` puts the drive
        reader's there), both written under the table (:func:`real_drive_table`); and per filter
        ``(n,)`` end-of-outage errors (m; a non-finite estimate raises).
    """
    bad = [f for f in filters if f not in REAL_FILTERS]
    if bad:
        raise ValueError(f"unknown real-drive filters {bad}; valid: {', '.join(REAL_FILTERS)}")
    _check_jobs(n_jobs)
    placed = []  # (kept for the saved table, as the filters' are)
    with kept_warnings(placed):
        out, windows = _outage_plan(run, length, starts, n_placements, min_speed)
    out["warnings"] += placed
    settings = dict(grade=grade, model_kwargs=model_kwargs, gps_window=gps_window, slow_speed=slow_speed,
                    filter_kw=dict(scale_window=scale_window, correlated_fixes=correlated_fixes,
                                   min_fix_interval=min_fix_interval, stop_reopen=stop_reopen,
                                   calibration_error_z=calibration_error_z, heading_jump_z=heading_jump_z,
                                   reversing_test=reversing_test and not run.reversed_by_speed,
                                   crawl_test=crawl_test,
                                   gps_sigma_floor=gps_sigma_floor, floor_on_detection=floor_on_detection,
                                   reopen_on_detection=reopen_on_detection, dr_noise_window=dr_noise_window,
                                   hold_heading_at_stops=hold_heading_at_stops))
    done = _score_side_by_side(out, filters, run, windows, use_gps_sigma, settings, progress, n_jobs)
    for name in filters:
        with kept_warnings(out["warnings"]):  # (folded: the filter's name, the step and its time)
            if name in done:
                _merge_scored(out, name, *done[name])
            else:
                _score_filter(out, name, run, windows, use_gps_sigma, settings, progress)
    return out


def score_drives(drives, n_jobs=1, progress=False, score=None):
    """:func:`real_drive_outages` on several drives, their results in the drives' order (a generator).

    ``drives``: ``(run, keywords)`` pairs, each drive's keywords of :func:`real_drive_outages`. With ``n_jobs``
    (joblib's loky; -1: one process per core), two or more drives whose steps times GPS/DR filters reach
    ``PARALLEL_STEPS`` in all run side by side, a drive to a worker (its filters one after the other there);
    each drive's warnings are given here, as one process gives them (the same lines, in the same order), before
    its result is yielded, and what a drive raised is raised then. Otherwise each drive runs as
    :func:`real_drive_outages` runs it with ``n_jobs`` and ``progress`` (a long one's filters side by side). A bar
    counts the drives done (``progress``; None: on a terminal). ``score``: the function that scores a drive
    (default :func:`real_drive_outages`; a module's function where the drives run side by side).
    """
    _check_jobs(n_jobs)
    score = real_drive_outages if score is None else score
    drives = list(drives)
    steps = sum(len(run.t) * sum(f != "DR-mech" for f in kw.get("filters", _DEFAULT_FILTERS)) for run, kw in drives)
    if n_jobs == 1 or len(drives) < 2 or steps < PARALLEL_STEPS:
        for run, kw in drives:
            yield score(run, progress=progress, n_jobs=n_jobs, **kw)
        return
    from ..runner import run_tasks

    tasks = [(score, run, kw) for run, kw in drives]
    for res, told, failed in run_tasks(tasks, _drive_scored, n_jobs=n_jobs, progress=_bar_wanted(progress),
                                       desc="drives", unit="drive"):
        with warnings.catch_warnings():  # (the filters kept; as a drive run here, the lines shown start afresh:
            give_again(told, failed, stacklevel=3)  # a second drive's line like the first's is shown again)
        yield res


def _check_jobs(n_jobs):
    """ValueError unless ``n_jobs`` is a joblib worker count (an integer >= 1, or negative)."""
    if isinstance(n_jobs, bool) or not isinstance(n_jobs, (int, np.integer)) or n_jobs == 0:
        raise ValueError(f"n_jobs must be an integer >= 1, or negative (-1: one process per core), got {n_jobs!r}")


def _drive_scored(task):
    """One drive scored in a worker (:func:`score_drives`): its result, its warnings ``[(category, text)]`` and
    what it raised (None)."""
    score, run, kw = task
    return recorded_call(score, run, **kw)


#: The drive's DR steps times the GPS/DR filters run on it from which ``real_drive_outages(n_jobs=...)`` runs
#: them in worker processes: about 20 s of filtering here (a worker's start, its imports and the drive sent to
#: it take 1-2 s); the shipped sample's 2400 steps with four filters stay in this process.
PARALLEL_STEPS = 40_000
#: What :func:`_score_filter` writes into the result per filter (and ``out[name]``).
_SCORED = ("end_xy", "start_err", "integrity")


def _score_side_by_side(out, filters, run, windows, use_gps_sigma, settings, progress, n_jobs):
    """``{filter: (its scores, its warnings)}`` of the GPS/DR filters run in ``n_jobs`` worker processes, one
    filter each (:func:`_scored`); empty where they run here (see :func:`real_drive_outages`)."""
    names = [n for n in filters if n != "DR-mech"]
    if n_jobs == 1 or len(names) < 2 or len(run.t) * len(names) < PARALLEL_STEPS:
        return {}
    from ..runner import run_tasks

    tasks = [(name, run, windows, use_gps_sigma, settings, out["starts"], out["track"]) for name in names]
    scored = run_tasks(tasks, _scored, n_jobs=n_jobs, progress=_bar_wanted(progress),
                       desc=f"{run.scenario.name}: filters", unit="filter")
    return dict(zip(names, scored))


def _scored(task):
    """One GPS/DR filter scored on a drive (in a worker): its entries of :func:`real_drive_outages`'s result
    and its warnings, ``[(category, text)]`` as :func:`_score_filter` gave them (folded and named)."""
    name, run, windows, use_gps_sigma, settings, starts, track = task
    part = {"starts": starts, "track": track, **{key: {} for key in _SCORED}}

    def scores():
        _score_filter(part, name, run, windows, use_gps_sigma, settings)
        return {key: part[key][name] for key in _SCORED} | {name: part[name]}

    return recorded_call(scores)


def _merge_scored(out, name, part, told, failed=None):
    """Write filter ``name``'s scores from a worker into ``out`` and give its warnings again, here; then raise
    what the filter raised, if it did (as the filter run here would, after its warnings)."""
    give_again(told, failed, stacklevel=5)
    for key in _SCORED:
        out[key][name] = part[key]
    out[name] = part[name]


def _outage_plan(run, length, starts, n_placements, min_speed, warn=True):
    """The outages' placements and windows: the result dict without scores (see
    :func:`real_drive_outages`) and ``(k0s, k1s, refs)``, each outage's first and scored step
    and its reference east/north. Spread evenly, none starts in the drive's own gaps of fixes
    (:func:`~filterwnn.navigation.scenarios.fix_gaps`); given ones that do are kept, and said (``warn``)."""
    gaps, allowance = fix_gaps(run, length)
    if starts is None and min_speed == 0.0:
        even = np.linspace(0.0, float(run.t[-1]) - length - 1.0, n_placements)
        starts = even if (_in_gaps(even, gaps, allowance) < 0).all() else None  # else spread over the fixed part
    starts = outage_starts(run, length, starts=starts, n=n_placements, min_speed=min_speed)
    in_gap = _in_gaps(starts, gaps, allowance)  # (spread ones never are: only given ones can be)
    if warn:
        for a, g in zip(starts, in_gap):
            if g >= 0:
                b, e = gaps[g]
                warnings.warn(f"the outage at {a:.1f} s starts {a - b:.1f} s after the drive's last GPS fix, in its "
                              f"own gap of fixes ({b:.1f}-{e:.1f} s): the filters go {a - b + length:.0f} s without a "
                              f"fix to its end, dead reckoning from the true start (DR-mech) {length:g} s, so its "
                              f"score is not that of a {length:g} s outage. Start it where the drive has fixes, or "
                              f"give no starts (--outage-starts): they are then spread where it has them",
                              RuntimeWarning,
                              stacklevel=3)
    k0s, k1s, refs, moved, track = _outage_windows(run, starts, length)
    out = {"starts": starts, "length": length, "moved": moved, "end_steps": np.array(k1s),
           "reference": "truth" if run.x_true is not None else "withheld GPS", "name": run.scenario.name,
           "track": track, "t": run.t, "end_xy": {}, "start_err": {}, "integrity": {}, "read_warnings": [],
           "warnings": [], "fix_gaps": gaps, "in_fix_gap": in_gap}
    return out, (k0s, k1s, refs)


def _score_filter(out, name, run, windows, use_gps_sigma, settings, progress=False):
    """Run filter ``name`` over the drive and write its outage-end positions, errors against the
    references, start errors and (for a GPS/DR filter) integrity counts into ``out``."""
    k0s, k1s, refs = windows
    track = out["track"] if run.x_true is None else None
    if name == "DR-mech":
        ends = _dr_mech_ends(run, k0s, k1s, track)
        out["start_err"][name] = np.zeros(len(k0s))
    else:
        kw = dict(REAL_MODEL, **(settings["model_kwargs"] or {}))
        f = _real_drive_filter(name, run, settings["grade"], settings["model_kwargs"], kw,
                               settings["gps_window"], settings["slow_speed"], **settings["filter_kw"])
        sig = run.gps_sigma_list() if use_gps_sigma else [None] * len(run.t)
        with folded_warnings(name, times=run.t_start + run.t):  # each names its filter and time; repeats folded
            with _steps_bar(progress, run, name, k0s, k1s) as bar:  # (cleared before the warnings come)
                ends, begins = _outage_ends(f, name, run, k0s, k1s, out["starts"], run.gps_list(), sig, bar)
        out["start_err"][name] = np.hypot(*(begins - _start_refs(run, k0s, track)).T)
        out["integrity"][name] = _integrity(f, run)
    out["end_xy"][name] = ends
    out[name] = np.hypot(*(ends - refs).T)


def _outage_windows(run, starts, length):
    """The first and scored step of each outage, its reference east/north (the truth, else the
    last fix withheld), the distance driven in it, and the track ``(n_steps, 2)``."""
    check_reference(run)
    truth = run.x_true is not None
    cum = np.concatenate([[0.0], np.cumsum(run.z_dr[:, 1])])
    k0s, k1s, refs, moved = [], [], [], []
    gps_t = run.t[run.gps_steps]
    for a in starts:
        k0 = int(np.searchsorted(run.t, a))
        k1 = int(np.searchsorted(run.t, a + length)) - 1
        if truth:
            ref = run.x_true[k1, [0, 3]]
        else:
            inside = np.flatnonzero((gps_t >= a) & (gps_t < a + length))
            if len(inside) == 0:
                raise ValueError(f"the drive has no truth and no GPS fix in the outage at {a:.1f} s to score against")
            j = inside[-1]
            k1 = int(run.gps_steps[j])
            ref = _fix_at_sample(run, j)
        k0s.append(k0)
        k1s.append(k1)
        refs.append(ref)
        moved.append(float(cum[k1 + 1] - cum[k0]) if not truth else float(np.sum(np.hypot(
            *np.diff(run.x_true[k0:k1 + 1][:, [0, 3]], axis=0).T))))
    if truth:
        track = run.x_true[:, [0, 3]]
    else:
        track = np.stack([np.interp(run.t, _fix_times(run), run.z_gps[:, i]) for i in (0, 1)], axis=1)
    return k0s, k1s, np.array(refs), np.array(moved), track


def _fix_times(run):
    """Each fix's own time: its sample's, plus its offset from it (``run.gps_offset``: a fix logged between the
    samples of a slow log)."""
    t = run.t[run.gps_steps]
    return t if run.gps_offset is None else t + run.gps_offset


def _fix_at_sample(run, j):
    """The fixes' track at the time of fix ``j``'s sample: the fix itself, or for a fix logged off its sample's
    time, the track of the fixes at their own times interpolated to it (the fix and its neighbour on the other
    side of the sample), so that a reference is not that fix's offset times the speed ahead of the position it
    scores (the filters move such a fix likewise, ``GPSDRFilter.update(gps_offset=)``)."""
    if run.gps_offset is None or run.gps_offset[j] == 0.0:
        return np.asarray(run.z_gps[j], dtype=float)
    at = run.t[run.gps_steps[j]]
    ft = _fix_times(run)
    return np.array([np.interp(at, ft, run.z_gps[:, i]) for i in (0, 1)])


def _real_drive_filter(name, run, grade, model_kwargs, kw, gps_window, slow_speed, **filter_kw):
    """The :class:`~filterwnn.navigation.gpsdr.GPSDRFilter` ``name`` for a real drive, set from ``grade``
    (or the settings ``kw``), started at the drive's first state with 1 m position sigma; ``filter_kw``
    go to the filter (``scale_window``, ``correlated_fixes``, ``min_fix_interval``)."""
    aug = name.endswith("-8")
    dt = run.scenario.dt
    if grade is not None:
        model = GPSDRModel.from_grade(grade, dt, augmented=aug, **({} if aug else {"rate_bias": False}),
                                      **(model_kwargs or {}))
    else:
        model = GPSDRModel(dt=dt, augmented=aug, **kw)
    x0 = np.concatenate([run.x0, model.x0[6:]])
    P0 = model.P0.copy()
    P0[0, 0] = P0[3, 3] = 1.0
    low = {} if slow_speed is None else {"low_speed": slow_speed}
    return GPSDRFilter(model, FILTER_KIND[name], x0=x0, P0=P0, gps_window=gps_window, **low, **filter_kw)


_REAL_META = ("starts", "moved", "length", "end_steps", "reference", "name", "track", "t", "end_xy", "start_err",
              "integrity", "read_warnings", "warnings", "fix_gaps", "in_fix_gap")


def _start_refs(run, k0s, track=None):
    """The reference east/north just before each outage's first step ``k0`` (the truth, else ``track``)."""
    ref = run.x_true[:, [0, 3]] if track is None else track
    return np.array([ref[k0 - 1] if k0 > 0 else run.x0[[0, 3]] for k0 in k0s])


def _dr_mech_ends(run, k0s, k1s, track=None):
    """Mechanised dead reckoning over each outage ``k0..k1``: ``s [sin theta, cos theta]``
    summed from the reference position before it (the truth, else ``track``)."""
    ends = _start_refs(run, k0s, track)
    for j, (k0, k1) in enumerate(zip(k0s, k1s)):
        z = run.z_dr[k0:k1 + 1]
        ends[j] += np.sum(z[:, 1:2] * np.stack([np.sin(z[:, 0]), np.cos(z[:, 0])], axis=1), axis=0)
    return ends


def _integrity(f, run):
    """What the filter ``f`` did with the drive's fixes (see :func:`real_drive_outages`)."""
    rej = np.isin(run.gps_steps, f.rejected_steps)
    return {"n_fixes": f.n_fixes, "n_thinned": f.n_thinned, "n_stale": f.n_stale, "n_rejected": f.n_rejected,
            "n_downweighted": f.n_downweighted,
            "n_reacquired": f.n_reacquired,
            "nis_mean": f.nis_mean, "gps_scale_mean": f.gps_scale_mean,
            "gps_correlation_mean": f.gps_correlation_mean,
            "gps_scale": f.gps_scale, "rejected_xy": run.z_gps[rej],
            "n_zero_rate": f.n_zero_rate if f.zero_rate_update else None,
            "n_zero_rate_rejected": f.n_zero_rate_rejected if f.zero_rate_update else None,
            "n_zero_rate_held": f.n_zero_rate_held if f.zero_rate_update else None,
            "n_zero_rate_reacquired": f.n_zero_rate_reacquired if f.zero_rate_update else None,
            "n_zero_rate_turned": f.n_zero_rate_turned if f.zero_rate_update else None,
            "n_zero_rate_stepped": f.n_zero_rate_stepped if f.zero_rate_update else None,
            "n_zero_rate_drift_taken": f.n_zero_rate_drift_taken if f.zero_rate_update else None,
            "stops_cut": f.stops_cut_step if f.zero_rate_update else None,
            "n_calibration_error": f.n_calibration_error, "n_heading_jumps": f.n_heading_jumps,
            "n_heading_far": f.n_heading_far, "n_from_rest": f.n_from_rest, "n_reversing": f.n_reversing,
            "n_forward_again": f.n_forward_again, "n_crawl": f.n_crawl, "crawl_moved": f.crawl_moved,
            "n_floored": f.n_floored, "floor_raised": f.floor_raised,
            "heading_jumps": list(f.heading_jumps),
            "gyro_scale_estimate": f.gyro_scale_estimate, "gyro_scale_z": f.gyro_scale_z,
            "gyro_scale_added": f.gyro_scale_added,
            "gyro_scale": float(f.x[GYRO_SCALE]) if f.model.gyro_scale else None,
            "latency_estimate": f.latency_estimate, "latency_z": f.latency_z, "latency_added": f.latency_added,
            "latency_at_end": f.latency_at_end, "gyro_scale_at_end": f.gyro_scale_at_end,
            "latency": float(f.x[f.model.latency_index]) if f.model.latency else None,
            "odometer_latency_estimate": f.odometer_latency_estimate, "odometer_latency_z": f.odometer_latency_z,
            **_dr_noise_entries(f)}


def _dr_noise_entries(f):
    """Per DR sensor, the step at which ``f`` found it noisier than its grade (``heading_noise_raised``; None: not)
    and its noise at the end in the grade's unit, under the grade's key (``heading_noise_deg``; None: the grade's
    throughout)."""
    out = {}
    for i, (sensor, _, _, to, key, _, _) in enumerate(_DR_SENSORS):
        raised = out[f"{sensor}_noise_raised"] = getattr(f, f"{sensor}_noise_raised")
        out[key] = None if raised is None else float(to(getattr(f, f"{sensor}_noise")))
        out[f"{sensor}_noise_back"] = raised is not None and bool(f.dr_noise_scale[i] == 1.0)
    return out


#: Seconds a filter runs over a drive before its progress bar shows (``progress=None``: on a terminal).
PROGRESS_DELAY = 2.0
#: Steps between the bar's updates.
_BAR_EVERY = 512


def _bar_wanted(progress):
    """Whether a bar shows: ``progress``, or for None whether stderr is a terminal."""
    return sys.stderr.isatty() if progress is None else bool(progress)


class _NoBar:
    """A bar that shows nothing (``progress`` off)."""

    def update(self, n):
        pass


@contextlib.contextmanager
def _steps_bar(progress, run, name, k0s, k1s):
    """A tqdm bar over filter ``name``'s steps on ``run`` (the pass with the fixes, then each outage again), or
    one that shows nothing; ``progress`` None: on a terminal, after :data:`PROGRESS_DELAY` s."""
    if not _bar_wanted(progress):
        yield _NoBar()
        return
    from tqdm.auto import tqdm

    total = len(run.t) + sum(k1 - k0 + 1 for k0, k1 in zip(k0s, k1s))
    with tqdm(total=total, desc=f"{run.scenario.name}: {name}", unit="step", unit_scale=True, leave=False,
              delay=PROGRESS_DELAY if progress is None else 0.0, mininterval=0.5) as bar:
        yield bar


def _outage_ends(f, name, run, k0s, k1s, starts, gps, sig, bar=None):
    """The east/north of filter ``f`` at the start (before step ``k0``) and the end of each
    outage: one pass with GPS over the whole drive, a snapshot at each outage start, then
    each outage alone (DR only); ``bar`` (a tqdm bar) is told the steps run, every :data:`_BAR_EVERY`."""
    bar = _NoBar() if bar is None else bar
    ends, begins = np.empty((len(k0s), 2)), np.empty((len(k0s), 2))
    snaps = {}
    offsets = run.gps_offset_list()
    starting = set(k0s)
    for k in range(len(run.t)):
        if k in starting:
            snaps[k] = copy.deepcopy(f)
        f.predict()
        f.update(run.z_dr[k], gps[k], sig[k], offsets[k])
        if k % _BAR_EVERY == _BAR_EVERY - 1:
            bar.update(_BAR_EVERY)
    bar.update(len(run.t) % _BAR_EVERY)
    f.end_of_drive()  # the tests made once, when the drive ends
    for j, (k0, k1) in enumerate(zip(k0s, k1s)):
        g = copy.deepcopy(snaps[k0])
        begins[j] = g.x[[0, 3]]
        for k in range(k0, k1 + 1):
            g.predict()
            g.update(run.z_dr[k], None)
        bar.update(k1 - k0 + 1)
        if not np.all(np.isfinite(g.x)):
            raise FloatingPointError(f"{name}: non-finite state at step {k1} (outage at {starts[j]:.1f} s)")
        ends[j] = g.x[[0, 3]]
    return ends, begins


def real_drive_table(res, min_moved=100.0, told=True):
    """Markdown: median/p90/max end-of-outage error over all placements and moving ones, the
    error at the outage starts and its growth over them (medians), what each filter did with
    the drive's fixes (rejected / down-weighted / re-acquired of those it saw), its mean NIS
    of the accepted ones, the mean factor on the fixes' reported covariance ("-": not estimated), the
    mean of their measured correlation (``gps_correlation``: fixes worth one independent fix) and
    the stops whose heading drift updated the gyro rate bias, was rejected or was held by its source
    ("-": no rate-bias state). Below it, a line per filter that estimated the gyro's scale factor error or
    the fixes' latency: the state's last value, and the step at which the monitor added it (or "from the
    start"). Then, with ``told``, the warnings given while the drive was read (``res["read_warnings"]``) and
    while the filters ran (``res["warnings"]``), a line each, so that the saved table keeps what the numbers were
    warned of (the command prints its tables without them: the terminal has shown them as they came)."""
    mv = res["moved"] >= min_moved
    names = [k for k in res if k not in _REAL_META]
    lines = [f"### real drive {res.get('name', CAR_DRIVE)}: {len(res['starts'])} GPS outages of {res['length']:g} s "
             f"({int(mv.sum())} with >= {min_moved:g} m driven{_gaps_clause(res)}), error at the outage ends against "
             f"the {res.get('reference', 'truth')} (m)", "",
             "| filter | median all | p90 all | max all | median moving | max moving | median at start | "
             "median growth | fixes rejected / down-weighted / re-acquired | mean NIS (2: consistent) | "
             "mean GPS covariance scale (1: as reported) | mean fix correlation (1: white) | "
             "stops for the gyro rate bias: used / rejected / re-acquired / heading held |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for n in names:
        e = res[n]
        em = e[mv] if mv.any() else np.array([np.nan])
        s = res.get("start_err", {}).get(n, np.full(len(e), np.nan))
        lines.append(f"| {n} | {np.median(e):.2f} | {np.percentile(e, 90):.2f} | {e.max():.2f} | "
                     f"{np.median(em):.2f} | {em.max():.2f} | {np.median(s):.2f} | {np.median(e - s):.2f} | "
                     + _integrity_cells(res.get("integrity", {}).get(n)) + " |")
    states = [f"- {n}: {said}" for n in names if (said := _states_added(res.get("integrity", {}).get(n)))]
    given = []
    for key, when in (("read_warnings", "while the drive was read"),
                      ("warnings", "while the filters ran (each filter's repeats folded into one line)")):
        if told and res.get(key):
            given += ["", f"Warnings given {when}:", ""] + [f"- {w}" for w in res[key]]
    return "\n".join(lines + ([""] + states if states else []) + given) + "\n"


def _gaps_clause(res):
    """The header's words on the drive's own gaps of fixes ("" where it has none)."""
    gaps = res.get("fix_gaps")
    if gaps is None or not len(gaps):
        return ""
    more = f" and {len(gaps) - 4} more" if len(gaps) > 4 else ""
    spans = ", ".join(f"{b:.0f}-{e:.0f} s" for b, e in gaps[:4]) + more
    inside = int((res["in_fix_gap"] >= 0).sum())
    return f"; {inside or 'none'} starting in the drive's own gaps of fixes, {spans}"


def _states_added(ig):
    """What the filter ended with in the states a drive can add (the gyro's scale factor error and the
    fixes' latency) and in the DR noise it estimated ("" without them)."""
    if ig is None:
        return ""
    told = []
    for key, what, unit in (("gyro_scale", "the gyro's scale factor error", "%"), ("latency", "the fixes' latency", "s")):
        if ig.get(key) is None:
            continue
        value = f"{100 * ig[key]:+.2f} %" if unit == "%" else f"{ig[key]:+.2f} s"
        added = ig.get(f"{key}_added")
        told.append(f"{what} {value} at the end ({'from the start' if added is None else f'added at step {added}'})")
    if ig.get("latency_at_end") is not None:  # told once when the drive ended (GPSDRFilter.end_of_drive)
        told.append(f"the fixes {ig['latency_at_end']:+.2f} s late over the whole drive (told at its end; rerun with "
                    f"--gps-latency {ig['latency_at_end']:.2f})")
    for sensor, _, unit, _, key, flag, _ in _DR_SENSORS:
        if ig.get(key) is None:
            continue
        if ig.get(f"{sensor}_noise_back"):  # later windows took it down to the grade's again: nothing to give
            told.append(f"the {sensor} read noisier than the grade from step {ig[f'{sensor}_noise_raised']}, and was "
                        f"back at the grade's {ig[key]:.2g} {unit} by the end (nothing to rerun with)")
        else:
            told.append(f"the {sensor}'s white noise {ig[key]:.2g} {unit} at the end (estimated from step "
                        f"{ig[f'{sensor}_noise_raised']}; rerun with {flag} {ig[key]:.2g} to have it from the start)")
    if ig.get("gyro_scale_at_end") is not None:
        told.append(f"the gyro turning {100 * ig['gyro_scale_at_end']:+.2f} % more than the car over the whole drive "
                    "(told at its end; rerun with --gyro-scale-sd 0.01)")
    return "; ".join(told)


def _integrity_cells(ig):
    if ig is None:
        return "- | - | - | - | -"
    nis = "-" if ig["nis_mean"] is None else f"{ig['nis_mean']:.2f}"
    corr = "-" if ig.get("gps_correlation_mean") is None else f"{ig['gps_correlation_mean']:.2f}"
    if ig.get("n_calibration_error"):
        corr += f" (off at {ig['n_calibration_error']} fixes)"
    scale = "-" if ig.get("gps_scale_mean") is None else f"{ig['gps_scale_mean']:.2f}"
    turned = f" ({ig['n_zero_rate_turned']} turned)" if ig.get("n_zero_rate_turned") else ""
    if ig.get("n_zero_rate_drift_taken"):  # the heading bias took their drift (the car does not turn standing)
        turned += f" ({ig['n_zero_rate_drift_taken']} drift taken)"
    stepped = f" ({ig['n_zero_rate_stepped']} stepped)" if ig.get("n_zero_rate_stepped") else ""
    cut = f" (whole from step {ig['stops_cut']})" if ig.get("stops_cut") is not None else ""
    stops = ("-" if ig.get("n_zero_rate") is None
             else f"{ig['n_zero_rate']} / {ig['n_zero_rate_rejected']}{turned} / {ig['n_zero_rate_reacquired']} / "
                  f"{ig['n_zero_rate_held']}{stepped}{cut}")
    unused = "".join(f" ({ig[f'n_{k}']} more {k})" for k in ("thinned", "stale") if ig.get(f"n_{k}"))
    if ig.get("n_heading_jumps"):
        unused += f" ({ig['n_heading_jumps']} jumped)"
    if ig.get("n_heading_far"):
        unused += f" ({ig['n_heading_far']} headings far)"
    if ig.get("n_from_rest"):
        unused += f" ({ig['n_from_rest']} from rest)"
    if ig.get("n_reversing"):
        unused += f" ({ig['n_reversing']} reversing)"
    if ig.get("n_forward_again"):
        unused += f" ({ig['n_forward_again']} forward again)"
    if ig.get("n_crawl"):
        unused += f" ({ig['n_crawl']} crawling)"
    if ig.get("n_floored"):
        unused += f" ({ig['n_floored']} floored)"
    if ig.get("floor_raised") is not None:
        unused += f" (floor raised at step {ig['floor_raised']})"
    return (f"{ig['n_rejected']} / {ig['n_downweighted']} / {ig['n_reacquired']} of {ig['n_fixes']}{unused} | {nis} | "
            f"{scale} | {corr} | {stops}")
