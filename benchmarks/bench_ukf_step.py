"""Where one UKF step on the 160 network weights stands against its floors (issue 25).

The problem is ``bench_peers.py``'s row 3: the 160 weights of a 5-20-1 Morlet wavelet
network, a random walk (``fx=None``), ``dim_z = 1``, Merwe points (321), the filter
built once and stepped on. The variants take turns within each repeat (``bench_peers``'s
``_measure``), so a change in a shared machine's load falls on all of them alike:

1. ``UnscentedKalmanFilter(vectorized=True)`` of this checkout;
2. optionally the same class from another file (``--against``, e.g. the module before a
   change: ``git show <rev>:filterwnn/kalman/unscented.py > /tmp/unscented_old.py``),
   loaded beside this checkout's modules, so a before/after pair is one run;
3. the same arithmetic written out in NumPy and LAPACK/BLAS without any check, copy or
   cache, the cheapest calls found for each piece (the step the filter's bookkeeping is
   measured against: ``P + Q``, one ``dpotrf``, ``c U`` and the 321 sigma points from it,
   ``hx`` on them, the transform, ``P_xz`` from ``c U``, the gain by a division, the rank-1
   downdate as the filter makes it, ``P - u u^T`` by NumPy's elementwise ops);
4. ``hx`` alone on the 321 sigma points the filter evaluated last (the user's function:
   the filter cannot make it cheaper; its cost depends on the points, so the points are
   the filter's own, not copies of one point);
5. the floor of issue 25 (``bench_peers.py``'s): one ``np.linalg.cholesky`` of the
   160x160 covariance and the rank-1 update ``P - s K K^T``;
6. the same floor with the calls the filter makes (LAPACK ``dpotrf`` without numpy's
   copies and zeroing of the other triangle, the downdate by NumPy's elementwise ops): the filter's
   ratio to it is printed too, so a cheaper call is not mistaken for less bookkeeping.

Run: ``python benchmarks/bench_ukf_step.py [--repeats 9] [--against FILE] [--clock cpu]``. One
BLAS thread. ``--clock cpu`` times with this process's CPU time (``time.process_time``) instead
of the wall clock: on a shared, oversubscribed machine the time spent descheduled is then not
counted (the cache contention still is).
"""

from __future__ import annotations

import argparse
import contextlib
import importlib.util
import os
import platform
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's filterwnn
sys.path.insert(0, str(Path(__file__).resolve().parent))
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from filterpy.kalman import MerweScaledSigmaPoints  # noqa: E402
from scipy.linalg.lapack import dpotrf  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

import bench_peers  # noqa: E402
from bench_peers import Timed, _measure  # noqa: E402
from filterwnn import UnscentedKalmanFilter, wnn  # noqa: E402
from filterwnn.datasets import make_siso_benchmark  # noqa: E402

N_STEPS = 10  # steps per timed call


def load_against(path):
    """``UnscentedKalmanFilter`` from another version of ``unscented.py``, beside this checkout's modules."""
    spec = importlib.util.spec_from_file_location("filterwnn.kalman._unscented_against", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.UnscentedKalmanFilter


def problem():
    X, y, _, _ = make_siso_benchmark(rng=0)
    theta0 = wnn.init_scaled(X, 20, rng=1)
    n = theta0.size
    return dict(X=X, y=y, theta0=theta0, n=n, pts=MerweScaledSigmaPoints(n, 1.0, 2.0, 0.0),
                P0=np.eye(n) * 0.01, Q=np.eye(n) * 1e-5, R=np.eye(1) * 0.1)


def hx(thetas, x):
    return wnn.forward(thetas, x[None, :])


def filter_steps(cls, pb):
    f = cls(pb["n"], 1, 1.0, hx, None, pb["pts"], vectorized=True)
    f.x, f.P, f.Q, f.R = pb["theta0"].copy(), pb["P0"].copy(), pb["Q"].copy(), pb["R"].copy()

    def go():
        for k in range(N_STEPS):
            f.predict()
            f.update(pb["y"][k], x=pb["X"][k])
    return go, f


def arithmetic_steps(pb):
    """The filter's arithmetic (random walk, Merwe points, dim_z = 1) with no check, copy or cache."""
    n, Wm, Wc = pb["n"], pb["pts"].Wm, pb["pts"].Wc
    c = np.sqrt(pb["pts"].alpha ** 2 * (n + pb["pts"].kappa))
    cU, upper, sig = np.zeros((n, n)), np.triu(np.ones((n, n), dtype=bool)), np.empty((2 * n + 1, n))
    state = {"x": pb["theta0"].copy(), "P": pb["P0"].copy()}

    def go():
        for k in range(N_STEPS):
            x, P = state["x"], state["P"] + pb["Q"]
            L = dpotrf(P, lower=1, clean=0)[0]  # L in the lower triangle, P's entries above
            np.multiply(c, L.T, out=cU, where=upper)
            sig[0] = x
            np.add(x, cU, out=sig[1 : n + 1])
            np.subtract(x, cU, out=sig[n + 1 :])
            h = hx(sig, pb["X"][k]).reshape(-1, 1)
            zp = Wm @ h
            dz = h - zp
            s = ((dz.T * Wc) @ dz + pb["R"])[0, 0]
            wdz = dz * Wc[:, None]
            Pxz = (cU.T @ (wdz[1 : n + 1] - wdz[n + 1 :]))[:, 0]
            state["x"] = x + (Pxz / s) * (pb["y"][k] - zp[0])
            u = Pxz / np.sqrt(s)
            uu = np.multiply.outer(u, u)
            state["P"] = np.subtract(P, uu, out=uu)
    return go, state


def hx_steps(sig, pb):
    for k in range(N_STEPS):
        hx(sig, pb["X"][k])


def floor_steps(P):
    """``bench_peers.py``'s floor: one Cholesky and the rank-1 update a step (results dropped as made)."""
    K = np.full(P.shape[0], 1e-3)
    for _ in range(N_STEPS):
        np.linalg.cholesky(P)
        P - 0.1 * np.outer(K, K)


def lapack_floor_steps(P):
    """The same floor with the filter's calls: ``dpotrf`` (uncleaned) and the downdate ``P - u u^T``
    by NumPy's elementwise ops (exactly symmetric on every machine, unlike BLAS ``dger``)."""
    u = np.full(P.shape[0], 1e-3 * np.sqrt(0.1))
    for _ in range(N_STEPS):
        dpotrf(P, lower=1, clean=0)
        uu = np.multiply.outer(u, u)
        np.subtract(P, uu, out=uu)


class _CPUClock:
    """Stands in for ``time`` in ``bench_peers`` (its ``_measure`` reads ``time.perf_counter``)."""

    perf_counter = staticmethod(time.process_time)


@contextlib.contextmanager
def _clock(kind):
    if kind == "wall":
        yield
        return
    saved, bench_peers.time = bench_peers.time, _CPUClock
    try:
        yield
    finally:
        bench_peers.time = saved


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=9, help="repeats per variant (medians are reported)")
    ap.add_argument("--against", help="another unscented.py to time beside this checkout's")
    ap.add_argument("--clock", choices=("wall", "cpu"), default="wall",
                    help="wall clock (as bench_peers) or this process's CPU time")
    args = ap.parse_args(argv)
    pb = problem()
    ours, f = filter_steps(UnscentedKalmanFilter, pb)
    row = {"filterwnn UKF (this checkout)": Timed(ours, N_STEPS)}
    if args.against:
        other, g = filter_steps(load_against(args.against), pb)
        row["filterwnn UKF (--against)"] = Timed(other, N_STEPS)
    arith, state = arithmetic_steps(pb)
    row.update({"the same arithmetic, no checks": Timed(arith, N_STEPS),
                "hx on the filter's 321 sigma points": Timed(lambda: hx_steps(f.sigmas_f, pb), N_STEPS),
                "floor (1 Cholesky + rank-1)": Timed(lambda: floor_steps(pb["P0"]), N_STEPS),
                "floor, the filter's calls (dpotrf + downdate)": Timed(lambda: lapack_floor_steps(pb["P0"]), N_STEPS)})
    with threadpool_limits(1), _clock(args.clock):
        med = _measure(row, args.repeats)
    floor = med["floor (1 Cholesky + rank-1)"]
    print(f"bench_ukf_step: 160-weight UKF step, median of {args.repeats} repeats x {N_STEPS} steps, "
          f"variants in turn, {args.clock} clock; 1 BLAS thread; python {platform.python_version()}, numpy {np.__version__}")
    if args.against:
        print(f"--against: {args.against}")
    print(f"{'variant':60s} {'us/step':>9s} {'/ floor':>8s}")
    for k, v in med.items():
        print(f"{k:60s} {1e6 * v:9.1f} {v / floor:7.2f}x")
    ours = med["filterwnn UKF (this checkout)"]
    print(f"target (issue 25): the filter within 3x of the floor: {'yes' if ours <= 3 * floor else 'no'} "
          f"({ours / floor:.2f}x; {ours / med['floor, the filter' + chr(39) + 's calls (dpotrf + downdate)']:.2f}x "
          "the floor with the filter's calls)")
    if args.against:
        print(f"this checkout's x after the run vs --against's: max abs difference {np.abs(f.x - g.x).max():.1e} "
              f"(after the same number of steps: {f.step == g.step})")
    print(f"vs the arithmetic without checks: max abs difference in x {np.abs(f.x - state['x']).max():.1e}")


if __name__ == "__main__":
    main()
