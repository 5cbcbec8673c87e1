"""``filterwnn study dr``: its options (:func:`add_arguments`) and its entry point (:func:`run`)."""

from __future__ import annotations

import argparse
import os

from ..._warnings import kept_warnings
from ...navigation.dead_reckoning import SENSOR_GRADES, _grade
from ...navigation.drives import CAR_DRIVES, load_car_drive, read_drive_csv
from ...navigation.gpsdr import (CALIBRATION_ERROR_Z, CORRELATED_FIXES, DR_NOISE_MIN_WINDOW, DR_NOISE_WINDOW,
                                  HEADING_JUMP_Z, SIGMA_FLOOR)
from ...navigation.scenarios import INTERVALS, SCENARIOS
from .. import options, runner
from ._filters import FILTER_TABLE, OPT_IN
from ._real import REAL_FILTERS, _outage_plan, check_reference, real_drive_outages, real_drive_table, score_drives
from ._run import DEFAULT_SCENARIOS, run_study
from ._tables import markdown_table, write_outputs

def add_arguments(parser):
    """Options of ``filterwnn study dr``."""
    parser.add_argument("--runs", type=options.positive_int, default=10, help="Monte-Carlo runs per scenario")
    parser.add_argument("--seed", type=options.seed, default=0,
                        help="root seed, an integer >= 0 (run i uses SeedSequence(seed).spawn(runs)[i])")
    parser.add_argument("--jobs", type=options.joblib_jobs, default=2,
                        help="joblib workers, -1 for all cores (the numbers do not depend on it); on drives "
                             "(--drive, --real), the filters of a long one side by side")
    parser.add_argument("--backend", type=options.joblib_backend, default=None,
                        help="joblib backend (loky, threading, dask, ...); default joblib's (loky)")
    parser.add_argument("--scheduler", default=None,
                        help="with --backend dask: the address of a dask.distributed scheduler "
                             "(default: a local cluster of --jobs workers)")
    parser.add_argument("--cache", default=None, metavar="DIR",
                        help="checkpoint folder (default none): each finished (scenario, run) is stored "
                             "there as <hash of its settings>.npz (no pickle: nothing in it can run code) and "
                             "read back instead of run, timings included, so an interrupted study resumes "
                             "with the same numbers; an entry written by other code (any change to the "
                             "package's source), another task, or damaged is named on stderr and recomputed")
    parser.add_argument("--scenarios", type=options.name_list(SCENARIOS), default=",".join(DEFAULT_SCENARIOS),
                        help=f"comma-separated subset of {', '.join(SCENARIOS)}")
    names = tuple(dict.fromkeys([f.name for f in FILTER_TABLE] + list(REAL_FILTERS)))
    simulated = tuple(dict.fromkeys(f.name for f in FILTER_TABLE))
    parser.add_argument("--filters", type=options.name_list(names), default=None,
                        help=f"comma-separated filters: on the simulated scenarios a subset of {', '.join(simulated)} "
                             f"(default all that apply to each scenario, but {', '.join(OPT_IN)}); with --drive a "
                             f"subset of {', '.join(REAL_FILTERS)} (default all)")
    parser.add_argument("--factor", type=options.positive_float, default=None,
                        help="override the DR noise factor at 150 s of the DR-only scenarios (default each "
                             "scenario's own)")
    parser.add_argument("--out", type=options.output_folder, default="results/dr", help="output folder")
    parser.add_argument("--no-figures", action="store_true", help="write the tables only (no PNG figures)")
    options.add_progress_flag(parser, "--quiet")
    parser.set_defaults(interrupted_note=interrupted_note)
    parser.add_argument("--real", action="store_true",
                        help=f"also run the GPS/DR filters on onavdata's car drives {', '.join(CAR_DRIVES)} "
                             "(needs the data extra), set from --grade (default survey)")
    parser.add_argument("--drive", action="append", default=None, metavar="CSV",
                        help="run the GPS/DR filters on one's own drive, a CSV with the columns of "
                             "filterwnn.navigation.drives.DRIVE_CSV_COLUMNS ('sample' for the shipped sample drive); "
                             "repeatable; with --drive only the drives run, not the simulated scenarios")
    parser.add_argument("--no-plausibility", action="store_true",
                        help="with --drive: skip the checks of the drive against its own GPS fixes (sample "
                             "interval over 2 s, a heading or speed that contradicts the fixes' course or "
                             "distance, lat/lon swapped), for a drive that really is so")
    parser.add_argument("--fill-gaps", type=options.nonnegative_float, default=0.0, metavar="SECONDS",
                        help="with --drive: fill gaps of dropped DR samples up to this long (s) by interpolation, "
                             "with a warning that counts them (default 0: a drive with dropped samples is refused)")
    parser.add_argument("--gps-latency", type=options.finite_float, default=0.0, metavar="SECONDS",
                        help="with --drive: the receiver's latency (s, from its data sheet), or the offset between "
                             "the fixes' clock and the DR samples': each fix's position is that much older than its "
                             "time stamp, negative younger (default 0; an unknown one the filters estimate when the "
                             "fixes show it, and one past 3 s the drive reader warns of, with its value)")
    parser.add_argument("--odometer-latency", type=options.finite_float, default=0.0, metavar="SECONDS",
                        help="with --drive: the speed's (or odometer's) latency (s, from the vehicle's data sheet, "
                             "e.g. a CAN bus's): each sample is that much older than its time stamp (default 0; negative: the "
                             "speed is early; an unknown one the filters warn of when the fixes show it, with its value)")
    parser.add_argument("--heading-latency", type=options.finite_float, default=0.0, metavar="SECONDS",
                        help="with --drive: the heading's (or yaw rate's) latency (s): each sample is that much older "
                             "than its time stamp (default 0; a heading averaged over each sample's interval is half "
                             "an interval late, 0.5 s at 1 Hz; negative: early; the filters warn when the fixes and the "
                             "speed both show themselves early against it, with its value)")
    parser.add_argument("--heading-offset", type=options.finite_float, default=0.0, metavar="DEG",
                        help="with --drive: degrees by which the heading reads clockwise of the car's course (its "
                             "zero off: a phone mounted askew; a magnetic heading, by the declination), subtracted "
                             "from every heading (default 0; the drive reader warns past 10 degrees, with the value)")
    parser.add_argument("--heading-deviation", type=options.deviation_card, default=None, metavar="B,C,D,E",
                        help="with --drive: a compass's deviation card (degrees): the heading reads B sin h + C cos h "
                             "+ D sin 2h + E cos 2h more than the car's course at the heading h it reads (a magnetic "
                             "heading near the car's steel), subtracted after --heading-offset (default none; the "
                             "drive reader warns of a deviation past 5 degrees, with the card)")
    parser.add_argument("--drop-fixes", type=options.spans, default=None, metavar="START,END,...",
                        help="with --drive: drop the GPS fixes in these spans (s from the drive's first row, as "
                             "--outage-starts counts; several spans as START,END,START,END): fixes dragged away from "
                             "the dead-reckoned track (a spoofer's walk), which the drive reader warns of with the "
                             "span, and which the filters would follow (default none)")
    parser.add_argument("--restamp-fixes", action="store_true",
                        help="with --drive: fixes stamped when the logger received them, each late by a time that "
                             "varies (the drive reader warns of them, with how much), placed on the receiver's regular "
                             "grid of epochs fitted to their stamps, at the earliest arrivals; what is left is a "
                             "constant latency (default: as stamped; not for a receiver whose own rate varies)")
    parser.add_argument("--hdop-sigma", type=options.positive_float, default=None, metavar="M",
                        help="with --drive: for a drive whose fixes carry a gps_hdop column (a dilution of "
                             "precision, without a unit), the sigma per axis (m) of a fix at HDOP 1, the receiver's "
                             "UERE / sqrt(2); each fix's sigma is its HDOP times it (default the grade's GPS sigma, "
                             "5 m for phone)")
    parser.add_argument("--speed-scale", type=options.positive_float, default=1.0, metavar="FACTOR",
                        help="with --drive: the factor by which the speed (or odometer) reads more than the car "
                             "drove (a speedometer's signal reads high by up to 10 %%), divided out (default 1; the "
                             "drive reader warns past 6 %%, with the value)")
    parser.add_argument("--intervals", choices=INTERVALS, default="auto",
                        help="with --drive: the interval each speed sample covers: its stamped one ('stamps'), the "
                             "stamps' regular grid's ('grid': regular samples whose time stamps jitter, a logger's), "
                             "or 'auto' (default): the grid when the stamps jitter about one, with a warning")
    parser.add_argument("--outage-length", type=options.positive_float, default=30.0, help="GPS outage length on drives (s)")
    parser.add_argument("--outages", type=options.positive_int, default=20,
                        help="number of outages spread over each drive, where it has its GPS fixes (none starts "
                             "in the drive's own gaps of fixes, a tunnel's: there it would be longer for the filters)")
    parser.add_argument("--outage-starts", type=options.float_list, default=None,
                        help="comma-separated outage start times (s) on --drive drives, instead of spreading them; "
                             "seconds from the drive's first row, not the log's own time stamps (a start in the "
                             "drive's own gap of fixes is warned of)")
    parser.add_argument("--min-speed", type=options.nonnegative_float, default=0.0,
                        help="spread outages only over windows with at least this mean speed (m/s)")
    parser.add_argument("--gps-scale-window", type=options.nonnegative_int, default=0, metavar="N",
                        help="estimate the scale of the fixes' reported covariance from the last N fixes' "
                             "innovations (GPSDRFilter's scale_window; 30 is the window to use; default 0: off)")
    parser.add_argument("--correlated-fixes", choices=CORRELATED_FIXES, default="calibration",
                        help="how the fixes' measured correlation counts them (GPSDRFilter's correlated_fixes): "
                             "calibration (default) slows the heading and rate-bias calibration; inflate counts each "
                             "fix as the independent fixes it is worth, in every state (for urban-canyon multipath)")
    parser.add_argument("--min-fix-interval", type=options.nonnegative_float, default=0.0, metavar="SECONDS",
                        help="use one fix every this many seconds and thin the others (GPSDRFilter's "
                             "min_fix_interval; 1 for fast fixes whose errors are correlated, which the filters "
                             "warn of; default 0: every fix)")
    parser.add_argument("--stop-reopen", type=options.nonnegative_float, default=0.0, metavar="SECONDS",
                        help="a stop that starts again within this many seconds, the car having moved at most "
                             "0.5 m, is the same stop to the gyro rate bias's update (GPSDRFilter's stop_reopen; "
                             "2 for a speed that does not read 0 at a standstill, a GNSS speed; default 0: off, until "
                             "the filters find a standstill cut into pieces that the rate-bias state cannot follow)")
    parser.add_argument("--no-reopen-on-detection", action="store_true",
                        help="when a standstill is cut into pieces by a speed that does not read 0 and the gyro rate "
                             "bias cannot follow them, only warn (GPSDRFilter's reopen_on_detection=False); by default "
                             "each standstill is then taken whole, as --stop-reopen 2 does")
    parser.add_argument("--hold-heading-at-stops", action="store_true",
                        help="a stop whose heading drift the gyro rate bias's gate rejects gives the drift beyond the "
                             "state to the heading bias and teaches the rate bias nothing (GPSDRFilter's "
                             "hold_heading_at_stops): for a gyro whose bias differs while the car stands, a phone "
                             "shaken in its holder by the idling engine; off by default, since a stop right against a "
                             "state taught wrong then hides the state's error from the fixes")
    parser.add_argument("--calibration-error-z", type=_z_or_off, default=CALIBRATION_ERROR_Z, metavar="Z",
                        help="the consistency monitor's z-score past which the heading bias or the gyro rate bias "
                             "is taken to be off, and their gain is cut by the fixes' own correlation instead of "
                             "the innovations' (GPSDRFilter's calibration_error_z; default %(default).3g; off: never)")
    parser.add_argument("--heading-jump-z", type=_z_or_off, default=HEADING_JUMP_Z, metavar="Z",
                        help="the heading-jump detector's z-score past which the heading is taken to have stepped "
                             "while the car moved (a fused orientation re-aligning), and the heading bias's variance "
                             "is widened by the step (GPSDRFilter's heading_jump_z; default "
                             "%(default).3g; off: not looked for)")
    parser.add_argument("--no-reversing-test", action="store_true",
                        help="do not test the fixes for the car reversing on an unsigned speed "
                             "(GPSDRFilter's reversing_test=False; a signed speed needs no test)")
    parser.add_argument("--no-crawl-test", action="store_true",
                        help="do not test the fixes for the car creeping while its speed reads 0 "
                             "(GPSDRFilter's crawl_test=False; a speed that reads down to 0 needs no test)")
    parser.add_argument("--gps-sigma-floor", type=options.fraction, default=SIGMA_FLOOR, metavar="FRACTION",
                        help="take a fix's reported sigma (a drive's gps_sigma column) no smaller than this fraction "
                             "of the fixes' before it, the lower of the medians of the last 3 and the last 30 reported "
                             "(GPSDRFilter's gps_sigma_floor: a fix that reports far better than both fixes before it, "
                             "a receiver's placeholder accuracy, is not trusted beyond that; default %(default)g; 0: as "
                             "reported)")
    parser.add_argument("--no-floor-on-detection", action="store_true",
                        help="when the consistency monitor names fixes that report an accuracy far better than they "
                             "have, only warn (GPSDRFilter's floor_on_detection=False); by default every fix's sigma "
                             "is then floored at the median of the last 30 reported")
    parser.add_argument("--grade", choices=sorted(SENSOR_GRADES), default=None,
                        help="sensor grade for the GPS/DR settings (survey, phone; see "
                             "filterwnn.navigation.dead_reckoning.SENSOR_GRADES); default phone for --drive, survey for --real")
    parser.add_argument("--gyro-scale-sd", type=options.nonnegative_float, default=0.0, metavar="FRACTION",
                        help="with --drive: estimate the gyro's scale factor error as a state, its prior sd this "
                             "fraction (a MEMS gyro's sensitivity tolerance of +-3 %% over three sigmas: 0.01); needs "
                             "the phone grade's rate-bias state (default 0: not estimated)")
    parser.add_argument("--gyro-bias", type=options.positive_float, default=None, metavar="DEG_S",
                        help="with --drive: the gyro's rate bias (deg/s, one sigma; its data sheet's turn-on bias) "
                             "in place of the grade's (phone: 0.05), the rate-bias state's prior and, three of it, "
                             "its bound; for a gyro outside the grade, which the filters warn of with the value to "
                             "give; needs the phone grade's rate-bias state (default: the grade's)")
    parser.add_argument("--gyro-bias-instability", type=options.positive_float, default=None, metavar="DEG_H",
                        help="with --drive: how fast the gyro's rate bias moves (deg/h, its data sheet's bias "
                             "instability) in place of the grade's (phone: 10), the rate-bias state's random walk; "
                             "for a gyro whose bias moves with its temperature, which the consistency monitor "
                             "warns of; needs the phone grade's rate-bias state (default: the grade's)")
    parser.add_argument("--gps-latency-sd", type=options.nonnegative_float, default=0.0, metavar="SECONDS",
                        help="with --drive: estimate the fixes' latency against the DR samples as a state from the "
                             "start, its prior sd this many seconds (fixes and speed stamped by two clocks, or a "
                             "receiver's unknown latency; default 0: the filters add the state when the fixes show a "
                             "latency, with a warning)")
    parser.add_argument("--heading-noise", type=options.positive_float, default=None, metavar="DEG",
                        help="with --drive: the heading's white noise (deg, one sigma) in place of the grade's (phone: "
                             "0.5, survey: 0.2); for a heading noisier than its grade (a compass's, a phone's "
                             "orientation), which the filters estimate online and warn of with the value to give "
                             "(default: the grade's)")
    parser.add_argument("--odometer-noise", type=options.positive_float, default=None, metavar="M",
                        help="with --drive: the odometer's noise per DR sample (m, one sigma) in place of the "
                             "grade's (phone: 0.01, survey: 0.02); estimated online and warned of likewise "
                             "(default: the grade's)")
    parser.add_argument("--dr-noise-window", type=_dr_window, default=DR_NOISE_WINDOW, metavar="N",
                        help="moving samples over which the GPS/DR filters estimate the heading's and the "
                             "odometer's noise from their innovations, raised past the grade's where larger "
                             "(GPSDRFilter's dr_noise_window; default %(default)s; 0: the grade's as given)")
    options.remember_defaults(parser)  # to tell the options given (_check_applies)


#: The options that apply to ``--drive`` drives only (their help says "with --drive"), and those that apply to
#: drives, one's own or ``--real``'s (the outages' placement, the GPS/DR filters' settings): given where they
#: do not apply, the command refuses them rather than ignore them.
DRIVE_ONLY = ("--no-plausibility", "--fill-gaps", "--gps-latency", "--odometer-latency", "--heading-latency",
              "--heading-offset", "--heading-deviation", "--drop-fixes", "--restamp-fixes",
              "--speed-scale", "--hdop-sigma", "--intervals", "--outage-starts", "--gyro-scale-sd", "--gyro-bias",
              "--gyro-bias-instability", "--gps-latency-sd", "--heading-noise", "--odometer-noise")
ON_DRIVES = ("--outage-length", "--outages", "--min-speed", "--gps-scale-window", "--correlated-fixes",
             "--min-fix-interval", "--stop-reopen", "--calibration-error-z", "--heading-jump-z", "--no-reversing-test",
             "--no-crawl-test", "--gps-sigma-floor", "--no-floor-on-detection", "--no-reopen-on-detection",
             "--hold-heading-at-stops", "--grade", "--dr-noise-window")
#: ... and those of the simulated scenarios' Monte Carlo, which ``--drive`` does not run. Not ``--jobs``: a
#: worker count changes no number, and scripts pass ``--jobs 1`` whatever they run (``log_faults.py`` does).
SIMULATED_ONLY = ("--runs", "--seed", "--backend", "--scheduler", "--cache", "--scenarios", "--factor")


def _dest(flag):
    return flag.lstrip("-").replace("-", "_")


def _check_applies(args):
    """Refuse options given where they do not apply (they would be ignored): :data:`DRIVE_ONLY` without
    ``--drive``, :data:`ON_DRIVES` without ``--drive`` or ``--real``, :data:`SIMULATED_ONLY` and ``--real``
    with ``--drive`` (which runs the given drives only)."""
    drives, real = getattr(args, "drive", None), getattr(args, "real", False)
    if drives and real:
        raise ValueError("--real with --drive: --drive runs the given drives only; run --real as a command of its own")
    for flags, where in ((DRIVE_ONLY, None if drives else "--drive drives"),
                         (ON_DRIVES, None if drives or real else "drives (--drive or --real)"),
                         (SIMULATED_ONLY, "the simulated scenarios (not run with --drive)" if drives else None)):
        bad = [f for f in flags if options.given(args, _dest(f))] if where else []
        if bad:
            raise ValueError(f"{', '.join(bad)} appl{'ies' if len(bad) == 1 else 'y'} to {where} only, and would "
                             "be ignored here")


def _z_or_off(text):
    """``off`` (None), or a z-score: a finite number > 0."""
    if text.strip().lower() == "off":
        return None
    try:
        return options.positive_float(text)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"must be a finite number > 0 or off, got {text!r}") from None


def _dr_window(text):
    """0, or a window of at least ``DR_NOISE_MIN_WINDOW`` moving samples."""
    value = options.nonnegative_int(text)
    if 0 < value < DR_NOISE_MIN_WINDOW:
        raise argparse.ArgumentTypeError(f"must be 0 (the grade's noise) or at least {DR_NOISE_MIN_WINDOW}, "
                                         f"got {text!r}")
    return value


def interrupted_note(args):
    """What ``filterwnn`` adds to the line of a study interrupted by Ctrl-C: where its finished runs are kept, or
    the option that would keep them; None with ``--drive`` (the drives are not cached)."""
    if getattr(args, "drive", None):
        return None
    if getattr(args, "cache", None):
        return f"the finished runs are kept in {args.cache}: the same command resumes"
    return "--cache DIR keeps the finished runs for the next one"


def _drive_running(args):
    """``real_drive_outages``'s ``progress`` and ``n_jobs``: None (a bar on a terminal, once a filter has run a
    while), or False with ``--no-progress``; ``--jobs`` (a long drive's filters side by side)."""
    return dict(progress=False if getattr(args, "no_progress", False) else None, n_jobs=getattr(args, "jobs", 1))


def _filter_options(args):
    """The GPS/DR filters' options of the command line (``real_drive_outages``'s), the same for ``--real``
    and ``--drive``."""
    return dict(scale_window=getattr(args, "gps_scale_window", 0),
                correlated_fixes=getattr(args, "correlated_fixes", "calibration"),
                min_fix_interval=getattr(args, "min_fix_interval", 0.0),
                stop_reopen=getattr(args, "stop_reopen", 0.0),
                calibration_error_z=getattr(args, "calibration_error_z", CALIBRATION_ERROR_Z),
                heading_jump_z=getattr(args, "heading_jump_z", HEADING_JUMP_Z),
                reversing_test=not getattr(args, "no_reversing_test", False),
                crawl_test=not getattr(args, "no_crawl_test", False),
                gps_sigma_floor=getattr(args, "gps_sigma_floor", SIGMA_FLOOR),
                floor_on_detection=not getattr(args, "no_floor_on_detection", False),
                reopen_on_detection=not getattr(args, "no_reopen_on_detection", False),
                hold_heading_at_stops=getattr(args, "hold_heading_at_stops", False),
                dr_noise_window=getattr(args, "dr_noise_window", DR_NOISE_WINDOW))


def run(args):
    """Entry point of ``filterwnn study dr``."""
    _check_applies(args)
    drives = getattr(args, "drive", None)
    if drives:
        return _run_drives(args, drives, args.filters)
    with runner.dask_client(getattr(args, "backend", None), getattr(args, "scheduler", None), args.jobs):
        res = run_study(scenarios=args.scenarios, n_runs=args.runs, filters=args.filters, seed=args.seed,
                        jobs=args.jobs, factor=args.factor, progress=not args.no_progress,
                        backend=getattr(args, "backend", None), cache_dir=getattr(args, "cache", None))
    paths = write_outputs(res, args.out, figures=not args.no_figures)
    print(markdown_table(res))
    if getattr(args, "real", False):
        grade = args.grade or "survey"
        results, texts = [], []
        for name in CAR_DRIVES:
            try:
                drive = load_car_drive(name)
            except ImportError as exc:
                print(f"skipping the real drives: {exc}")
                break
            rd = real_drive_outages(drive, n_placements=args.outages, length=args.outage_length,
                                    min_speed=args.min_speed, grade=grade, use_gps_sigma=True,
                                    **_drive_running(args), **_filter_options(args))
            results.append(rd)
            texts.append(real_drive_table(rd))
            print(real_drive_table(rd, told=False))
        if results:
            p = os.path.join(args.out, "dr_real_drive.md")
            with open(p, "w") as fh:
                fh.write(f"Settings: sensor grade {grade!r} (filterwnn.navigation.dead_reckoning.SENSOR_GRADES), each fix's "
                         f"reported accuracy as its noise; nothing tuned on these drives.\n\n" + "\n".join(texts))
            paths.append(p)
            paths += write_outputs(None, args.out, figures=not args.no_figures, real_drives=results)
    print("wrote:", ", ".join(paths))
    return 0


def _drive_grade(args):
    """``--grade`` for ``--drive`` (default phone), with ``--gyro-scale-sd``, ``--gyro-bias``,
    ``--gyro-bias-instability``, ``--gps-latency-sd``, ``--heading-noise`` and ``--odometer-noise`` when given."""
    grade = getattr(args, "grade", None) or "phone"
    k = getattr(args, "gyro_scale_sd", 0.0)
    bias = getattr(args, "gyro_bias", None)
    moves = getattr(args, "gyro_bias_instability", None)
    for flag, v in (("--gyro-scale-sd", k), ("--gyro-bias", bias), ("--gyro-bias-instability", moves)):
        if v and not SENSOR_GRADES[grade]["rate_bias"]:
            raise ValueError(f"{flag} needs a grade with a gyro rate-bias state (phone), got --grade {grade}")
    extra = {key: v for key, v in (("gyro_scale_sd", k), ("gyro_bias_deg_s", bias),
                                   ("gyro_bias_instability_deg_h", moves),
                                   ("gps_latency_sd", getattr(args, "gps_latency_sd", 0.0)),
                                   ("heading_noise_deg", getattr(args, "heading_noise", None)),
                                   ("odometer_noise_m", getattr(args, "odometer_noise", None))) if v}
    return dict(SENSOR_GRADES[grade], **extra) if extra else grade


def _run_drives(args, drives, filters):
    """``--drive``: the GPS/DR filters on one's own drives, with each fix's accuracy when given."""
    from ...navigation.drives import sample_drive_path

    starts = args.outage_starts or None
    fl = tuple(filters) if filters else REAL_FILTERS
    grade = _drive_grade(args)
    runs = []
    for path in drives:  # every drive read and its outages placed before any runs: a bad one stops nothing done
        told = []  # the reader's warnings, shown as ever and kept for the drive's saved table
        with kept_warnings(told):
            run = read_drive_csv(sample_drive_path() if path == "sample" else path,
                                 checks=not getattr(args, "no_plausibility", False),
                                 fill_gaps=getattr(args, "fill_gaps", 0.0),
                                 gps_latency=getattr(args, "gps_latency", 0.0),
                                 intervals=getattr(args, "intervals", "auto"),
                                 odometer_latency=getattr(args, "odometer_latency", 0.0),
                                 heading_latency=getattr(args, "heading_latency", 0.0),
                                 heading_offset=getattr(args, "heading_offset", 0.0),
                                 heading_deviation=getattr(args, "heading_deviation", None),
                                 drop_fixes=getattr(args, "drop_fixes", None),
                                 restamp_fixes=getattr(args, "restamp_fixes", False),
                                 speed_scale=getattr(args, "speed_scale", 1.0),
                                 hdop_sigma=getattr(args, "hdop_sigma", None) or _grade(grade)["gps_sigma_m"],
                                 progress=None if not getattr(args, "no_progress", False) else False)
        try:  # (not under the outage options' message: nothing to place them against)
            check_reference(run)
        except ValueError as exc:
            raise ValueError(f"{path}: {exc}") from None
        try:
            _outage_plan(run, args.outage_length, starts, args.outages, args.min_speed, warn=False)
        except ValueError as exc:  # name the drive (and the options behind the outages)
            raise ValueError(f"{path}: {exc} (outages from --outage-length, --outages, --outage-starts, "
                             "--min-speed)") from None
        runs.append((path, run, told))
    results = []
    scored = score_drives([(run, dict(n_placements=args.outages, length=args.outage_length, filters=fl,
                                      starts=starts, min_speed=args.min_speed,
                                      use_gps_sigma=run.gps_sigma is not None, grade=grade, **_filter_options(args)))
                           for _, run, _ in runs], score=real_drive_outages, **_drive_running(args))
    for path, run, told in runs:
        try:
            res = next(scored)
        except ValueError as exc:  # name the drive
            raise ValueError(f"{path}: {exc}") from None
        res["read_warnings"] = told
        results.append(res)
        print(real_drive_table(res, told=False))  # (the warnings: shown as they came, and in the saved table)
    paths = write_outputs(None, args.out, figures=not args.no_figures, real_drives=results)
    print("wrote:", ", ".join(paths))
    return 0
