"""Reduced sigma points against Merwe's in filterpy's own UKF at small n (issue 15).

A filterpy user who swaps ``points=`` on a small tracker should not pay for it. For each
state size ``n`` this times, on the same data and interleaved (load drifts hit all sets
alike):

* ``sigma_points(x, P)`` alone, for filterpy's ``MerweScaledSigmaPoints(n, 1, 2, 0)``
  (``2n + 1`` points), :class:`~filterwnn.SphericalSimplexSigmaPoints` and
  :class:`~filterwnn.MinimalSkewSigmaPoints` (``n + 2``);
* one step (``predict`` + ``update``) of filterpy's own
  ``filterpy.kalman.UnscentedKalmanFilter`` with each set, on a nonlinear model:
  ``fx(x) = x + 0.1 dt sin(x)`` and a range-bearing ``hx`` on the first two states.

It prints the medians and the ratio ours / Merwe's per ``n`` (below 1: ours is faster).

Run: ``python benchmarks/bench_sigma_points.py`` (``--quick`` for a short run; from a
checkout that is not the installed copy, ``PYTHONPATH=. python benchmarks/...``: the
header prints which ``filterwnn`` was timed). One BLAS thread.
"""

from __future__ import annotations

import argparse
import os
import platform
import time
import warnings

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from filterpy.kalman import MerweScaledSigmaPoints  # noqa: E402
from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

import filterwnn  # noqa: E402
from filterwnn import MinimalSkewSigmaPoints, SphericalSimplexSigmaPoints  # noqa: E402

SETS = {
    "merwe": lambda n: MerweScaledSigmaPoints(n, 1.0, 2.0, 0.0),
    "spherical": lambda n: SphericalSimplexSigmaPoints(n),
    "minskew": lambda n: MinimalSkewSigmaPoints(n),
}


def fx(x, dt):
    return x + 0.1 * dt * np.sin(x)


def hx(x):
    return np.array([np.hypot(x[0], x[1]), np.arctan2(x[1], x[0])])


def make_ukf(points, n):
    ukf = FilterpyUKF(n, 2, 1.0, hx, fx, points)
    ukf.x = np.linspace(1.0, 2.0, n)
    ukf.P = np.eye(n) * 0.1
    ukf.Q = np.eye(n) * 1e-3
    ukf.R = np.diag([0.1, 0.01])
    return ukf


def time_points(points, x, P, number):
    t0 = time.perf_counter()
    for _ in range(number):
        points.sigma_points(x, P)
    return (time.perf_counter() - t0) / number


def time_steps(ukf, zs):
    t0 = time.perf_counter()
    for z in zs:
        ukf.predict()
        ukf.update(z)
    return (time.perf_counter() - t0) / len(zs)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dims", type=int, nargs="+", default=list(range(2, 21)), help="state sizes n")
    ap.add_argument("--repeats", type=int, default=15, help="repeats (medians are reported)")
    ap.add_argument("--number", type=int, default=200, help="sigma_points calls per repeat")
    ap.add_argument("--steps", type=int, default=50, help="UKF steps per repeat")
    ap.add_argument("--quick", action="store_true", help="n = 2, 4, 8, 20; 7 repeats")
    args = ap.parse_args(argv)
    if args.quick:
        args.dims, args.repeats, args.number, args.steps = [2, 4, 8, 20], 7, 100, 30
    print(f"bench_sigma_points: filterpy UKF, fx = x + 0.1 dt sin(x), range-bearing hx; "
          f"median of {args.repeats} repeats ({args.number} sigma_points calls, {args.steps} "
          f"steps each); 1 BLAS thread")
    print(f"python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}; "
          f"filterwnn from {os.path.dirname(filterwnn.__file__)}")
    print(f"{'n':>3s} | {'sigma_points us: Merwe':>22s} {'spher':>6s} {'minsk':>6s} "
          f"{'ratio s/M':>9s} {'m/M':>5s} | {'UKF step us: Merwe':>18s} {'spher':>6s} "
          f"{'minsk':>6s} {'ratio s/M':>9s} {'m/M':>5s}")
    rng = np.random.default_rng(0)
    worst = worst_min = 0.0
    with threadpool_limits(1), warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        for n in args.dims:
            A = rng.standard_normal((n, n))
            P = A @ A.T / n + np.eye(n)
            x = rng.standard_normal(n)
            zs = np.column_stack([np.full(args.steps, 2.0), np.full(args.steps, 0.8)])
            zs += 0.01 * rng.standard_normal(zs.shape)
            pts = {k: make(n) for k, make in SETS.items()}
            t_pts = {k: [] for k in SETS}
            t_ukf = {k: [] for k in SETS}
            for _ in range(args.repeats):
                for k, p in pts.items():
                    t_pts[k].append(time_points(p, x, P, args.number))
                    t_ukf[k].append(time_steps(make_ukf(p, n), zs))
            mp = {k: 1e6 * float(np.median(v)) for k, v in t_pts.items()}
            mu = {k: 1e6 * float(np.median(v)) for k, v in t_ukf.items()}
            rs, rm = mu["spherical"] / mu["merwe"], mu["minskew"] / mu["merwe"]
            worst = max(worst, rs, rm)
            lo = {k: min(v) for k, v in t_ukf.items()}  # the least disturbed repeat
            worst_min = max(worst_min, lo["spherical"] / lo["merwe"], lo["minskew"] / lo["merwe"])
            print(f"{n:3d} | {mp['merwe']:22.1f} {mp['spherical']:6.1f} {mp['minskew']:6.1f} "
                  f"{mp['spherical'] / mp['merwe']:9.2f} {mp['minskew'] / mp['merwe']:5.2f} | "
                  f"{mu['merwe']:18.1f} {mu['spherical']:6.1f} {mu['minskew']:6.1f} "
                  f"{rs:9.2f} {rm:5.2f}")
    print(f"largest UKF-step ratio ours / Merwe over n = {args.dims[0]}..{args.dims[-1]}: "
          f"{worst:.2f} of medians, {worst_min:.2f} of minima (target <= 1; on a shared "
          "machine the minima are the steadier estimate)")


if __name__ == "__main__":
    main()
