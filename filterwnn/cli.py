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

__all__ = ["main"]


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


def main(argv=None):
    """Entry point of the ``filterwnn`` command."""
    parser = argparse.ArgumentParser(prog="filterwnn", description=__doc__.split("\n\n")[0])
    parser.add_argument("--version", action="version", version=f"filterwnn {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    demo = sub.add_parser("demo", help="a ten-second tour of the reduced sigma points")
    demo.add_argument("--seed", type=int, default=0)
    demo.set_defaults(func=_demo)
    study = sub.add_parser("study", help="reproduce one of the papers' studies")
    studies = study.add_subparsers(dest="study", required=True)
    for name, modname in STUDIES.items():
        try:
            mod = importlib.import_module(modname)
        except ModuleNotFoundError as exc:  # that study is not part of this build
            if exc.name != modname:
                raise
            continue
        sp = studies.add_parser(name, help=(mod.__doc__ or name).strip().split("\n")[0])
        mod.add_arguments(sp)
        sp.set_defaults(func=mod.run)
    args = parser.parse_args(argv)
    return args.func(args) or 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
