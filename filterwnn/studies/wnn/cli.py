"""``filterwnn study wnn``: the options and the command."""

from __future__ import annotations

import os
import time

from .. import options
from .. import runner
from .rows import ALL_TRAINERS, ROWS
from .runs import run_study
from .tables import is_reduced, markdown_table, write_outputs

__all__ = [
    "add_arguments",
    "run",
]


def add_arguments(parser):
    """Options of ``filterwnn study wnn``."""
    parser.add_argument("--runs", type=options.positive_int, default=3,
                        help="independent runs per trainer (paper: 50)")
    parser.add_argument("--epochs", type=options.positive_int, default=30,
                        help="epochs of BP/EKF/UKF/SUKF (paper: 200)")
    parser.add_argument("--pf-epochs", type=options.positive_int, default=3,
                        help="epochs of the particle filters (paper: 200)")
    parser.add_argument("--particles", type=options.positive_int, default=10, help="particles in the table (paper: 50)")
    parser.add_argument("--sweep-particles", type=options.int_list(minimum=1), default="5,10,20",
                        help="comma-separated particle counts for Figs. 3-4 (paper: 50,100,150,200,250; '' skips)")
    parser.add_argument("--sweep-runs", type=options.positive_int, default=2, help="runs per sweep point")
    parser.add_argument("--paper-runs", type=options.nonnegative_int, default=None,
                        help="runs at the paper's settings (default --runs)")
    parser.add_argument("--paper-pf-epochs", type=options.positive_int, default=None,
                        help="particle-filter epochs at the paper's settings (default --pf-epochs)")
    parser.add_argument("--no-paper-table", action="store_true", help="skip the paper-settings table")
    parser.add_argument("--tune-runs", type=options.nonnegative_int, default=2,
                        help="tuning runs of the settings search on a validation split (default 2; 0: use the "
                             "regressor's AUTO_SETTINGS and all epochs)")
    opt_in = [k for k in ROWS if k not in ALL_TRAINERS]
    parser.add_argument("--trainers", type=options.name_list(tuple(ROWS)), default=",".join(ALL_TRAINERS),
                        help=f"comma-separated rows of {', '.join(ALL_TRAINERS)} (the default), "
                             f"and the opt-in {', '.join(opt_in)}")
    parser.add_argument("--seed", type=options.seed, default=2026,
                        help="root seed, an integer >= 0 (run i uses SeedSequence(seed).spawn(runs)[i])")
    parser.add_argument("--jobs", type=options.joblib_jobs, default=-1,
                        help="joblib workers (-1: all cores); the numbers do not depend on it")
    parser.add_argument("--backend", type=options.joblib_backend, default=None,
                        help="joblib backend name (loky, threading, dask, ...); default joblib's (loky)")
    parser.add_argument("--scheduler", default=None,
                        help="with --backend dask: a dask.distributed scheduler address (default: a local cluster)")
    parser.add_argument("--out", type=options.output_folder, default="wnn-study", help="output folder")
    parser.add_argument("--cache", default=None,
                        help="checkpoint folder (default OUT/cache): each finished fit is saved there as JSON "
                             "and reused, so an interrupted study resumes with the same numbers; an entry is "
                             "used only if the same package source (a hash of every filterwnn .py file) wrote "
                             "it for the same settings, so after any code change it is recomputed (named on "
                             "stderr); 'none' disables it")
    parser.add_argument("--cached-only", action="store_true",
                        help="only summarize the fits already in the cache (run nothing)")
    parser.add_argument("--no-figures", action="store_true", help="write the tables only (no PNG figures)")
    options.add_progress_flag(parser)
    parser.set_defaults(interrupted_note=interrupted_note)
    options.remember_defaults(parser)  # to tell the options given (_check_applies)


#: ``(option, its dest, when it does not apply, why)``: refused there rather than ignored.
_NOT_APPLYING = (
    ("--paper-runs", "paper_runs", lambda a: a.no_paper_table, "with --no-paper-table"),
    ("--paper-pf-epochs", "paper_pf_epochs", lambda a: a.no_paper_table, "with --no-paper-table"),
    ("--sweep-runs", "sweep_runs", lambda a: not a.sweep_particles, "with --sweep-particles '' (no sweep)"),
    ("--cached-only", "cached_only", lambda a: a.cache == "none", "with --cache none (no cache to read)"),
)


def _check_applies(args):
    """Refuse an option given where it does not apply (it would be ignored), with one line."""
    for flag, dest, idle, why in _NOT_APPLYING:
        if options.given(args, dest) and idle(args):
            raise ValueError(f"{flag} does not apply {why}, and would be ignored")


def cache_folder(args):
    """The study's checkpoint folder: ``--cache``, by default ``OUT/cache``; None for ``--cache none``."""
    return os.path.join(args.out, "cache") if args.cache is None else (None if args.cache == "none" else args.cache)


def interrupted_note(args):
    """What ``filterwnn`` adds to the line of a study interrupted by Ctrl-C: where its finished fits are kept."""
    cache = cache_folder(args)
    return cache and f"the finished fits are kept in {cache}: the same command resumes"


def run(args):
    """Run the study from parsed arguments; prints the table and the files written."""
    import sys

    _check_applies(args)
    trainers, sweep = list(args.trainers), list(args.sweep_particles)
    progress = (not args.no_progress) and sys.stderr.isatty()
    cache = cache_folder(args)
    t0 = time.perf_counter()
    with runner.dask_client(args.backend, args.scheduler, args.jobs):
        res = run_study(
            n_runs=args.runs, n_epochs=args.epochs, pf_epochs=args.pf_epochs, n_particles=args.particles,
            trainers=trainers, seed=args.seed, paper_table=not args.no_paper_table, paper_runs=args.paper_runs,
            paper_pf_epochs=args.paper_pf_epochs, cache_dir=cache, cached_only=args.cached_only,
            sweep_particles=sweep, sweep_runs=args.sweep_runs, n_jobs=args.jobs, backend=args.backend,
            progress=progress, tune_runs=args.tune_runs,
        )
    text = markdown_table(res)
    paths = write_outputs(res, args.out, figures=not args.no_figures)
    print(text)
    print(f"wall time {time.perf_counter() - t0:.0f} s; wrote " + ", ".join(paths))
    if is_reduced(res.config):
        print("(reduced protocol: see --help to scale it to the paper's 50 runs x 200 epochs x 50 particles)")
    return 0
