"""The ``filterwnn`` console script.

``filterwnn study wnn``  reproduces the first paper's WNN study (Table 1, Figs. 3-5).
``filterwnn study dr``   reproduces the second paper's dead-reckoning study (Figs. 4-5).
``filterwnn demo``       a ten-second tour: sigma points, a filter-trained network, GPS/DR.

Each study module registers its own options (``filterwnn study wnn --help``).
"""

from __future__ import annotations

import argparse
import importlib
import sys

from . import __version__
from .studies import STUDIES
from .studies import options

__all__ = ["command", "main"]

_DESCRIPTION = """\
Reduced sigma points, particle filters, filter-trained wavelet networks and GPS/DR navigation.

commands:
  filterwnn demo            a ten-second tour: sigma points, a filter-trained network, GPS/DR
  filterwnn study wnn       the first paper's WNN study (Table 1, Figs. 3-5)
  filterwnn study dr        the second paper's dead-reckoning study (Figs. 4-5)

Each command has its own options: filterwnn study wnn --help."""


def _demo(args):
    import time

    import numpy as np
    from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF

    from .datasets import make_siso_benchmark
    from .models import LinearGaussianModel, from_model
    from .wnn.regressor import WNNRegressor
    from .navigation.dead_reckoning import GPSDRModel
    from .navigation.gpsdr import GPSDRFilter
    from .navigation.drives import read_drive_csv, sample_drive_path
    from .navigation.scenarios import with_outage
    from .kalman.presets import make_points
    from .kalman.sigma_points import MinimalSkewSigmaPoints

    t0 = time.perf_counter()
    model = LinearGaussianModel.random(dim_x=4, dim_z=2, rng=args.seed)
    xs, zs = model.simulate(50, rng=args.seed + 1)
    kf = model.kalman_filter()
    ref, _, _, _ = kf.batch_filter(zs)
    print(f"filterwnn {__version__}: a tour in three parts\n")
    print("1. Reduced sigma points in filterpy's own UnscentedKalmanFilter, on a random 4-state")
    print("   linear model (50 steps; every set must give the Kalman filter's answer):")
    for points in (
        make_points("merwe-kappa", 4),
        MinimalSkewSigmaPoints(4),
        make_points("simplex", 4),
    ):
        ukf = from_model(FilterpyUKF, model, points=points)
        means, _ = ukf.batch_filter(zs)
        err = np.max(np.abs(means - np.asarray(ref).reshape(means.shape)))
        # the agreement is at rounding level, whose last digits differ between machines: print the bound
        gap = "< 1e-12" if err < 1e-12 else f"{err:.1e}"
        print(f"   {type(points).__name__:28s} {points.num_sigmas():3d} points   max |x - x_KF| {gap}")

    X, y, X_test, y_test = make_siso_benchmark(rng=args.seed)
    print("\n2. A 5-20-1 wavelet network trained by an extended Kalman filter (WNNRegressor), on the")
    print("   first paper's SISO plant (100 training rows, 10 epochs):")
    reg = WNNRegressor(n_epochs=10, random_state=args.seed).fit(X, y)
    mean, std = reg.predict(X_test, return_std=True)
    inside = np.mean(np.abs(mean - y_test) <= 1.645 * std)
    print(f"   test MSE {np.mean((mean - y_test) ** 2):.3f} (predicting the mean: {np.var(y_test):.2f}); "
          f"{100 * inside:.0f} % of test targets inside the 90 % interval")

    run = with_outage(read_drive_csv(sample_drive_path()), start=100.0, length=30.0)
    print("\n3. GPS/DR on the shipped sample drive (the phone grade's settings; the filter estimates the\n"
          "   odometer scale, the gyro biases and the sensors' noise where it is above the grade's, and\n"
          "   warns of that; no GPS from 100 s to 130 s):")
    gps_model = GPSDRModel.from_grade("phone", run.scenario.dt)
    kf = GPSDRFilter(gps_model, "ekf", x0=np.r_[run.x0, gps_model.x0[6:]])
    est = kf.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
    k0, k1 = np.searchsorted(run.t, 100.0), np.searchsorted(run.t, 130.0) - 1
    z = run.z_dr[k0:k1 + 1]  # raw dead reckoning from the true position at the outage start
    raw = run.x_true[k0 - 1, [0, 3]] + z[:, 1] @ np.stack([np.sin(z[:, 0]), np.cos(z[:, 0])], axis=1)
    truth = run.x_true[k1, [0, 3]]
    print(f"   error at the end of the outage: raw dead reckoning {np.hypot(*(raw - truth)):.1f} m, "
          f"GPS/DR EKF {np.hypot(*(est[k1, [0, 3]] - truth)):.1f} m")
    print(f"\n({time.perf_counter() - t0:.1f} s. Next: the notebooks in notebooks/, "
          "`filterwnn study wnn --help`, `filterwnn study dr --help`.)")
    return 0


def _build_parser():
    """The ``filterwnn`` parser with every command and every study's options."""
    fmt = options.HelpFormatter
    parser = argparse.ArgumentParser(prog="filterwnn", description=_DESCRIPTION, formatter_class=fmt)
    parser.add_argument("--version", action="version", version=f"filterwnn {__version__}")
    parser.add_argument("--debug", action="store_true",
                        help="show the traceback of an error (anywhere on the line; by default an error is "
                             "one line on stderr: exit 2 for a refused input, 130 for Ctrl-C)")
    sub = parser.add_subparsers(dest="command", required=True, metavar="{demo,study}")
    demo = sub.add_parser("demo", help="a ten-second tour: sigma points, a filter-trained network, GPS/DR", formatter_class=fmt,
                          description="filterpy's UnscentedKalmanFilter with Merwe's, the minimal-skew and the\n"
                                      "spherical-simplex points on a random 4-state linear model.")
    demo.add_argument("--seed", type=options.seed, default=0, help="seed of the model and the simulated run (>= 0)")
    demo.set_defaults(func=_demo)
    study = sub.add_parser("study", help="reproduce one of the papers' studies", formatter_class=fmt)
    studies = study.add_subparsers(dest="study", required=True)
    for name, modname in STUDIES.items():
        mod = importlib.import_module(modname)
        summary = (mod.__doc__ or name).strip().split("\n")[0]
        sp = studies.add_parser(name, help=summary, description=summary, formatter_class=fmt)
        mod.add_arguments(sp)
        sp.set_defaults(func=mod.run)
    return parser


#: Exit status of a run ended by Ctrl-C (SIGINT), and by SIGTERM: 128 + the signal number.
EXIT_INTERRUPT, EXIT_TERMINATED = 130, 143
#: Exit status of a refused input (a bad option, file or drive) and of an internal error.
EXIT_BAD_INPUT, EXIT_INTERNAL = 2, 1
#: The exceptions that mean "the input is wrong": reported in one line, exit 2.
BAD_INPUT = (ValueError, OSError, ImportError)


class _Terminated(BaseException):
    """Raised in the main thread by SIGTERM, so the run unwinds (workers end) like Ctrl-C."""


def _one_line(exc):
    """The exception's message as one line (its own line breaks folded)."""
    text = " ".join(str(exc).split())
    return text or type(exc).__name__


def _warning_line(message, category, filename, lineno, file=None, line=None):
    """``warnings.showwarning`` for the command: one line per warning on stderr, no source line."""
    print(f"filterwnn: warning: {' '.join(str(message).split())}", file=file or sys.stderr)


def _on_sigterm(signum, frame):
    raise _Terminated()


def _say_now(line):
    print(line, file=sys.stderr)


def _loky_tracker():
    """loky's resource tracker where this process started one (a study's worker pool), else ``None``."""
    module = sys.modules.get("joblib.externals.loky.backend.resource_tracker")
    tracker = getattr(module, "_resource_tracker", None)
    return tracker if getattr(tracker, "_fd", None) is not None else None


def _say_at_exit(line, wait=5.0):
    """Say an interrupted command's ``line`` as the process exits, after the worker pool.

    Workers stopped mid-task can leave a queue's lock or a memory-mapped folder to loky's
    resource tracker, a process of its own that removes them once the command has exited
    and says so in a warning: printed after the command's line, that warning read as the
    cause of the exit, on some runs and not others. Here the line waits for the last of
    multiprocessing's exit finalizers (the pool's queues and locks are released at
    priority 0 and above), then the tracker is ended, waiting at most ``wait`` seconds, so
    its warning, if any, comes first. Without a tracker (no pool was started), or with a
    joblib whose tracker cannot be ended within a bound, the line is said now."""
    import inspect

    tracker = _loky_tracker()
    stop = getattr(tracker, "_stop", None)
    try:
        bounded = stop is not None and "wait_timeout" in inspect.signature(stop).parameters
    except (TypeError, ValueError):
        bounded = False
    if not bounded:
        _say_now(line)
        return
    from multiprocessing import util

    util.Finalize(None, _end_tracker_then_say, args=(stop, line, wait), exitpriority=-100)


def _end_tracker_then_say(stop, line, wait):
    """The exit finalizer of :func:`_say_at_exit` (a second Ctrl-C cannot cut its bounded wait)."""
    import signal

    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        stop(wait_timeout=wait)
    except Exception:  # noqa: BLE001 -- a private call of joblib's: the line is said without it
        pass
    try:
        print(line, file=sys.stderr, flush=True)
    except (OSError, ValueError):  # stderr closed by the caller
        pass


def _interrupted_line(args):
    """The line of a command interrupted by Ctrl-C, with the study's note of where its finished tasks are kept
    (``args.interrupted_note(args)``, set by the study's parser; None: nothing is kept, e.g. ``study dr
    --drive``, whose drives are not cached)."""
    note = getattr(args, "interrupted_note", None)
    note = note(args) if note is not None else None
    return "filterwnn: interrupted (Ctrl-C)" + (f"; {note}" if note else "")


def _run(args, debug, say=_say_now):
    """``args.func(args)``; a refused input, an interrupt or an error becomes one stderr line
    and an exit status (2, 130/143, 1), unless ``debug``. ``say`` says an interrupt's line."""
    try:
        return args.func(args) or 0
    except KeyboardInterrupt:
        if debug:
            raise
        say(_interrupted_line(args))
        return EXIT_INTERRUPT
    except _Terminated:
        if debug:
            raise
        say("filterwnn: terminated (SIGTERM)")
        return EXIT_TERMINATED
    except BAD_INPUT as exc:
        if debug:
            raise
        print(f"filterwnn: error: {_one_line(exc)} (--debug shows the traceback)", file=sys.stderr)
        return EXIT_BAD_INPUT
    except Exception as exc:  # noqa: BLE001 -- the command's last line of defence: one line, exit 1
        if debug:
            raise
        print(f"filterwnn: internal error: {type(exc).__name__}: {_one_line(exc)} (a bug: rerun with "
              "--debug for the traceback and report it)", file=sys.stderr)
        return EXIT_INTERNAL


def main(argv=None):
    """The ``filterwnn`` command, called from Python (the console script is :func:`command`).

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default ``sys.argv[1:]``). A bad value exits with status 2 and one
        argparse error line, before any work starts. ``--debug`` (anywhere) shows the
        traceback of an error instead of its one line.

    Returns
    -------
    int
        The exit status: 0 on success, 2 for a refused input (the line names the file,
        column, row and rule), 130 after Ctrl-C, 143 after SIGTERM, 1 for an internal
        error. Warnings (a cache entry not used) print one line each on stderr.
    """
    return _main(argv, _say_now)


def _main(argv, say):
    """:func:`main`, with ``say`` saying an interrupted run's line."""
    import signal
    import threading
    import warnings

    argv = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in argv
    argv = [a for a in argv if a != "--debug"]
    args = _build_parser().parse_args(argv)
    old_term = None
    if threading.current_thread() is threading.main_thread():
        old_term = signal.signal(signal.SIGTERM, _on_sigterm)
    show = warnings.showwarning
    if not debug:
        warnings.showwarning = _warning_line
    try:
        return _run(args, debug, say)
    finally:
        warnings.showwarning = show
        if old_term is not None:
            signal.signal(signal.SIGTERM, old_term)


def command():
    """Entry point of the ``filterwnn`` console script and of ``python -m filterwnn.cli``:
    :func:`main` on ``sys.argv[1:]``, then exit with its status.

    As the process ends, an interrupted run (Ctrl-C, SIGTERM) says its line after the worker
    pool's own cleanup, so the line is the last thing printed (:func:`main` says it at once).
    """
    sys.exit(_main(None, _say_at_exit))


if __name__ == "__main__":  # pragma: no cover
    command()
