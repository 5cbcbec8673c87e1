"""Where the batched step switches to the column path (``filterwnn._linalg.columns_layout``).

A stack of N small covariances ``(n, n)`` is factored either by LAPACK
(``numpy.linalg.cholesky``: one call per matrix inside NumPy) or by
:func:`~filterwnn._linalg.cholesky_columns` (the member axis last, a few length-N vector
operations per column). The unscented step follows the factor: on the column path its
sigma points are one BLAS product per state component. This script times both paths,
in turn within each repeat (paired), on

* ``cholesky``: ``filterwnn._linalg.cholesky`` alone, transposes included;
* ``ukf step``: one predict and update of :class:`~filterwnn.kalman.bank.UnscentedKalmanFilterBank`
  (Merwe points, ``fx(x) = x + dt sin(reversed x)``, ``hx`` the first ``min(n, 3)``
  components);

and prints the median over repeats of (column path time) / (LAPACK path time) for each
``(n, N)``: below 1 the column path is faster. The path is forced by setting
``COLUMNS_MIN_STACK`` (1 or a huge number) and ``COLUMNS_MAX_N`` for the run.

    python benchmarks/bench_columns.py [--repeats 15]
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's filterwnn

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from filterpy.kalman import MerweScaledSigmaPoints  # noqa: E402

from filterwnn import _linalg  # noqa: E402
from filterwnn.kalman.bank import UnscentedKalmanFilterBank  # noqa: E402

NS = (2, 3, 4, 6, 8, 12, 16)
STACKS = (16, 64, 128, 256, 512, 1000, 4000)


def _path(columns, n):
    """Force the column path (``columns=True``) or LAPACK for stacks of ``(n, n)``."""
    _linalg.COLUMNS_MIN_STACK = 1 if columns else 2**62
    _linalg.COLUMNS_MAX_N = max(n, 1)


def _pd(N, n, g):
    A = g.standard_normal((N, n, n + 2))
    return np.matmul(A, np.swapaxes(A, 1, 2)) / (n + 2) + 0.1 * np.eye(n)


def _bank(N, n, g):
    m = min(n, 3)
    bank = UnscentedKalmanFilterBank(N, n, m, 0.1, lambda X: X[:, :m], lambda X, dt: X + dt * np.sin(X[:, ::-1]),
                                     MerweScaledSigmaPoints(n, 1.0, 2.0, 0.0))
    bank.x, bank.P, bank.Q, bank.R = g.standard_normal((N, n)), _pd(N, n, g), 1e-3 * np.eye(n), 0.1 * np.eye(m)
    z = g.standard_normal(m)
    return lambda: (bank.predict(), bank.update(z))


def _ratio(make, n, N, repeats):
    """Median over repeats of column-path time / LAPACK-path time (each timed once per repeat)."""
    g = np.random.default_rng(0)
    work = make(N, n, g)
    ratios = []
    for _ in range(repeats + 1):
        t = {}
        for columns in (True, False):
            _path(columns, n)
            t0 = time.perf_counter()
            work()
            t[columns] = time.perf_counter() - t0
        ratios.append(t[True] / t[False])
    return float(np.median(ratios[1:]))


def _cholesky(N, n, g):
    P = _pd(N, n, g)
    return lambda: _linalg.cholesky(P, "P")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=15)
    args = ap.parse_args(argv)
    saved = _linalg.COLUMNS_MIN_STACK, _linalg.COLUMNS_MAX_N
    print(f"bench_columns: median of {args.repeats} paired repeats of (column path) / (LAPACK path); 1 BLAS thread; "
          f"python {platform.python_version()}, numpy {np.__version__}; in force: COLUMNS_MAX_N = {saved[1]}, "
          f"COLUMNS_MIN_STACK = {saved[0]}")
    try:
        for name, make in (("cholesky", _cholesky), ("ukf step", _bank)):
            print(f"\n{name}: rows n, columns N")
            print("| n \\ N | " + " | ".join(f"{N:,}" for N in STACKS) + " |")
            print("|---" * (len(STACKS) + 1) + "|")
            for n in NS:
                row = [_ratio(make, n, N, args.repeats) for N in STACKS]
                print(f"| {n} | " + " | ".join(f"{r:.2f}" for r in row) + " |", flush=True)
    finally:
        _linalg.COLUMNS_MIN_STACK, _linalg.COLUMNS_MAX_N = saved


if __name__ == "__main__":
    main()
