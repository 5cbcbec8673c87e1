"""Time per step of unscented filters on a WNN-sized problem (issue 3).

The state is the 160 weights of a 5-20-1 Morlet wavelet network, the measurement its
output at one input, the transition a random walk. A filterpy user writes filterpy's
``UnscentedKalmanFilter`` with ``MerweScaledSigmaPoints`` (321 points) and an identity
``fx``; we compare, in one run and on the same data:

1. filterpy's UKF + Merwe points (the baseline, ratio 1),
2. filterpy's UKF + ``SphericalSimplexSigmaPoints`` (162 points),
3. our ``UnscentedKalmanFilter(vectorized=True, fx=None)`` (random walk),
4. ours, vectorized with a general ``fx`` (the identity written as a function),
5. the floor: one Cholesky of the 160x160 covariance and the rank-1 covariance update.

Then, in the same run (issue 22), what a filterpy user sees:

6. loop mode against filterpy on the book's examples as ``tests/kalman/test_filterpy_book.py``
   writes them (first UKF, radar, robot with landmarks; filterpy's Merwe points), the two
   filters interleaved, median time per predict+update and our/filterpy ratio (target <= 1);
7. ``import filterwnn`` against ``import filterpy.kalman``, each in a fresh interpreter,
   interleaved, medians and their ratio (target <= 1.2).

Run: ``python benchmarks/bench_ukf.py`` (``--quick`` for a short run). One BLAS thread.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from filterpy.kalman import MerweScaledSigmaPoints  # noqa: E402
from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

from filterwnn import SphericalSimplexSigmaPoints, UnscentedKalmanFilter, wnn  # noqa: E402
from filterwnn.datasets import make_siso_benchmark  # noqa: E402

N_IN, N_HID = 5, 20
DIM = wnn.n_params(N_IN, N_HID)


def hx_one(theta, x):
    return np.atleast_1d(wnn.forward(theta, x[None, :]))


def hx_all(thetas, x):
    return wnn.forward(thetas, x[None, :])  # (n_sigmas, 1)


def setup(ukf, theta0):
    ukf.x = theta0.copy()
    ukf.P = np.eye(DIM) * 0.01
    ukf.Q = np.eye(DIM) * 1e-5
    ukf.R = np.eye(1) * 0.1
    return ukf


def run(ukf, X, y, n_steps):
    t0 = time.perf_counter()
    for k in range(n_steps):
        ukf.predict()
        ukf.update(y[k % len(y)], x=X[k % len(y)])
    return (time.perf_counter() - t0) / n_steps


def floor(P, n_steps):
    t0 = time.perf_counter()
    K = np.ones(DIM) * 1e-3
    for _ in range(n_steps):
        np.linalg.cholesky(P)
        P2 = P - 0.1 * np.outer(K, K)
    del P2
    return (time.perf_counter() - t0) / n_steps


def book_cases():
    """(name, make(cls), run(filter)) for the book's examples, from the tests' own code."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "kalman"))
    import test_filterpy_book as book  # noqa: E402

    _, cz = book.cv_data()
    _, rz = book.radar_data()
    _, us, bz = book.robot_data()
    return [
        ("first UKF (4 states)", lambda c: book.cv_filter(c, MerweScaledSigmaPoints(4, 0.1, 2.0, -1.0)),
         lambda f: book.run(f, cz)),
        ("radar (3 states)", lambda c: book.radar_filter(c, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0)),
         lambda f: book.run(f, rz)),
        ("robot, landmarks (3 states)", lambda c: book.robot_filter(c, MerweScaledSigmaPoints(3, 0.1, 2.0, 0.0)),
         lambda f: book.run_robot(f, us, bz)),
    ], len(cz), len(rz), len(bz)


def loop_mode(repeats):
    """Median ms per step, filterpy's and ours in loop mode, interleaved."""
    cases, *steps = book_cases()
    rows = []
    for (name, make, go), n_steps in zip(cases, steps):
        t = {FilterpyUKF: [], UnscentedKalmanFilter: []}
        for _ in range(repeats):
            for cls in t:
                f = make(cls)
                t0 = time.perf_counter()
                go(f)
                t[cls].append((time.perf_counter() - t0) / n_steps)
        rows.append((name, float(np.median(t[FilterpyUKF])), float(np.median(t[UnscentedKalmanFilter]))))
    return rows


def import_times(repeats):
    """Median seconds of ``import filterwnn`` and ``import filterpy.kalman`` in fresh interpreters."""
    t = {"import filterwnn": [], "import filterpy.kalman": [],
         "from filterwnn import UnscentedKalmanFilter": [], "from filterpy.kalman import UnscentedKalmanFilter": []}
    for _ in range(repeats):
        for stmt in t:
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-c", stmt], check=True)
            t[stmt].append(time.perf_counter() - t0)
    return {k: float(np.median(v)) for k, v in t.items()}


def report_filterpy_user(repeats):
    print(f"\nloop mode (vectorized=False) against filterpy, the book's examples, Merwe points; "
          f"median of {repeats} interleaved runs")
    print(f"{'example':32s} {'filterpy ms':>12s} {'filterwnn ms':>13s} {'ratio':>7s}")
    ratios = []
    for name, a, b in loop_mode(repeats):
        ratios.append(b / a)
        print(f"{name:32s} {1e3 * a:12.3f} {1e3 * b:13.3f} {b / a:7.2f}")
    print(f"loop-mode ratio filterwnn/filterpy: max {max(ratios):.2f}, median {np.median(ratios):.2f} (target <= 1)")
    imp = list(import_times(repeats).items())
    print(f"import in a fresh interpreter (python -c), median of {repeats} interleaved:")
    for (ours, a), (theirs, b) in (imp[0:2], imp[2:4]):
        print(f"  {ours!r} {a:.3f} s, {theirs!r} {b:.3f} s, ratio {a / b:.2f} (target <= 1.2)")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--steps", type=int, default=20, help="filter steps per repeat")
    ap.add_argument("--repeats", type=int, default=5, help="repeats (medians are reported)")
    ap.add_argument("--quick", action="store_true", help="3 repeats of 10 steps")
    args = ap.parse_args(argv)
    if args.quick:
        args.steps, args.repeats = 10, 3
    X, y, _, _ = make_siso_benchmark(rng=0)
    theta0 = wnn.init_scaled(X, N_HID, rng=1)
    ident = lambda x, dt: x  # noqa: E731  filterpy needs an fx
    variants = {
        "filterpy UKF, Merwe (321 pts)": lambda: setup(
            FilterpyUKF(DIM, 1, 1.0, hx_one, ident, MerweScaledSigmaPoints(DIM, 1.0, 2.0, 0.0)), theta0),
        "filterpy UKF, spherical simplex (162 pts)": lambda: setup(
            FilterpyUKF(DIM, 1, 1.0, hx_one, ident, SphericalSimplexSigmaPoints(DIM)), theta0),
        "filterwnn UKF, vectorized, fx=None (321 pts)": lambda: setup(
            UnscentedKalmanFilter(DIM, 1, 1.0, hx_all, None, MerweScaledSigmaPoints(DIM, 1.0, 2.0, 0.0),
                                  vectorized=True), theta0),
        "filterwnn UKF, vectorized, general fx (321 pts)": lambda: setup(
            UnscentedKalmanFilter(DIM, 1, 1.0, hx_all, ident, MerweScaledSigmaPoints(DIM, 1.0, 2.0, 0.0),
                                  vectorized=True), theta0),
        "filterwnn UKF, vectorized, fx=None, simplex (162 pts)": lambda: setup(
            UnscentedKalmanFilter(DIM, 1, 1.0, hx_all, None, SphericalSimplexSigmaPoints(DIM),
                                  vectorized=True), theta0),
    }
    times = {name: [] for name in variants}
    times["floor: 1 Cholesky + rank-1 P update"] = []
    finals = {}
    with threadpool_limits(1):
        for _ in range(args.repeats):  # interleave variants: load drifts hit all alike
            for name, make in variants.items():
                f = make()
                times[name].append(run(f, X, y, args.steps))
                finals[name] = f.x.copy()
            times["floor: 1 Cholesky + rank-1 P update"].append(floor(np.eye(DIM) * 0.01, args.steps))
    med = {k: float(np.median(v)) for k, v in times.items()}
    base = med["filterpy UKF, Merwe (321 pts)"]
    print(f"bench_ukf: 5-20-1 Morlet WNN, state dim {DIM}, dim_z 1; {args.repeats} repeats x "
          f"{args.steps} steps; median ms per predict+update; 1 BLAS thread")
    print(f"python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}")
    print(f"{'variant':55s} {'ms/step':>9s} {'vs filterpy Merwe':>18s}")
    for k, v in med.items():
        print(f"{k:55s} {1e3 * v:9.3f} {base / v:17.1f}x")
    ref = finals["filterpy UKF, Merwe (321 pts)"]
    for k in ("filterwnn UKF, vectorized, fx=None (321 pts)", "filterwnn UKF, vectorized, general fx (321 pts)"):
        print(f"max |x - x_filterpy| after the run, {k}: {np.abs(finals[k] - ref).max():.1e}")
    print("ratios: simplex/Merwe in filterpy = "
          f"{med['filterpy UKF, spherical simplex (162 pts)'] / base:.2f} (target <= 0.55); "
          f"speed-up fx=None = {base / med['filterwnn UKF, vectorized, fx=None (321 pts)']:.1f}x (target >= 15); "
          f"general fx = {base / med['filterwnn UKF, vectorized, general fx (321 pts)']:.1f}x (target >= 5)")
    fl = med["floor: 1 Cholesky + rank-1 P update"]
    print("vectorized step / floor (one Cholesky + rank-1 update): "
          f"fx=None, Merwe {med['filterwnn UKF, vectorized, fx=None (321 pts)'] / fl:.1f}x, "
          f"fx=None, simplex {med['filterwnn UKF, vectorized, fx=None, simplex (162 pts)'] / fl:.1f}x (target <= 3)")
    report_filterpy_user(max(args.repeats, 5))


if __name__ == "__main__":
    main()
