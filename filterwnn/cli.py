"""The ``filterwnn`` console script.

``filterwnn study wnn``  reproduces the first paper's WNN study (Table 1, Figs. 3-5).
``filterwnn study dr``   reproduces the second paper's dead-reckoning study (Figs. 4-5).
``filterwnn demo``       a ten-second tour: reduced sigma points in filterpy's UKF.

Each study module registers its own options (``filterwnn study wnn --help``).
"""

from __future__ import annotations

import argparse
import importlib
import sys

from . import __version__
from .studies import STUDIES
from .studies import _args

__all__ = ["main"]

_DESCRIPTION = """\
Reduced sigma points, particle filters, filter-trained wavelet networks and GPS/DR navigation.

commands:
  filterwnn demo            a ten-second tour: reduced sigma points in filterpy's UKF
  filterwnn study wnn       the first paper's WNN study (Table 1, Figs. 3-5)
  filterwnn study dr        the second paper's dead-reckoning study (Figs. 4-5)

Each command has its own options: filterwnn study wnn --help."""


def _demo(args):
    import numpy as np
    from filterpy.kalman import MerweScaledSigmaPoints
    from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF

    from .models import LinearGaussianModel
    from .sigma_points import MinimalSkewSigmaPoints, SphericalSimplexSigmaPoints

    model = LinearGaussianModel.random(dim_x=4, dim_z=2, rng=args.seed)
    xs, zs = model.simulate(50, rng=args.seed + 1)
    kf = model.kalman_filter()
    ref, _, _, _ = kf.batch_filter(zs)
    print(f"filterwnn {__version__}: filterpy's UnscentedKalmanFilter with three point sets")
    print("on a random 4-state linear model, 50 steps (max |x - x_KF| over the run):")
    for points in (
        MerweScaledSigmaPoints(4, alpha=0.5, beta=2.0, kappa=-1.0),
        MinimalSkewSigmaPoints(4),
        SphericalSimplexSigmaPoints(4),
    ):
        ukf = FilterpyUKF(4, 2, 1.0, model.hx, model.fx, points)
        ukf.x, ukf.P, ukf.Q, ukf.R = model.x0.copy(), model.P0.copy(), model.Q, model.R
        means, _ = ukf.batch_filter(zs)
        err = np.max(np.abs(means - np.asarray(ref).reshape(means.shape)))
        print(f"  {type(points).__name__:28s} {points.num_sigmas():3d} points   {err:.1e}")
    return 0


def _build_parser():
    """The ``filterwnn`` parser with every command and every study's options."""
    fmt = _args.HelpFormatter
    parser = argparse.ArgumentParser(prog="filterwnn", description=_DESCRIPTION, formatter_class=fmt)
    parser.add_argument("--version", action="version", version=f"filterwnn {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="{demo,study}")
    demo = sub.add_parser("demo", help="a ten-second tour of the reduced sigma points", formatter_class=fmt,
                          description="filterpy's UnscentedKalmanFilter with Merwe's, the minimal-skew and the\n"
                                      "spherical-simplex points on a random 4-state linear model.")
    demo.add_argument("--seed", type=_args.seed, default=0, help="seed of the model and the simulated run (>= 0)")
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


def main(argv=None):
    """Entry point of the ``filterwnn`` command.

    Parameters
    ----------
    argv : list of str, optional
        The arguments (default ``sys.argv[1:]``). A bad value exits with status 2 and one
        argparse error line, before any work starts.

    Returns
    -------
    int
        The exit status of the command (0 on success).
    """
    args = _build_parser().parse_args(argv)
    return args.func(args) or 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
