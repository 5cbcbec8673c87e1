"""How often DegeneracyWarning fires on healthy runs (issue 22): the book's chapter-12 robot
particle filter and the plain 4-state range-bearing tracker, 30 seeds each.

For each run: does it end on the robot (the last 6 errors below 0.5; the tracker: position
RMSE below 3), did the warning fire, and would the rule before issue 22 (ESS < 2 for 3
consecutive updates, from ``ess_history``) have fired. The problems are the tests' own
(``tests/monte_carlo/test_filterpy_book_pf.py``, ``tests/monte_carlo/test_particle_filter.py``).

Run: ``python benchmarks/degeneracy_book_pf.py`` (about a minute, one BLAS thread).
"""

from __future__ import annotations

import os
import sys
import warnings

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.join(HERE, "..", "tests"), os.path.join(HERE, "..", "tests", "monte_carlo")]

import test_filterpy_book_pf as book  # noqa: E402
from test_particle_filter import _cv_range_bearing, cv_hx  # noqa: E402

from filterwnn import BootstrapParticleFilter, DegeneracyWarning  # noqa: E402
from filterwnn.angles import angle_residual  # noqa: E402


def old_rule(ess_history):
    run = 0
    for e in ess_history:
        run = run + 1 if e < 2 else 0
        if run >= 3:
            return True
    return False


def book_row(seed):
    rng = np.random.default_rng(seed)
    n = 5000
    pf = BootstrapParticleFilter(3, 4, 1.0, book.hx, book.fx, n, vectorized=True, rng=seed,
                                 process_sampler=book.sampler, ess_threshold=0.5)
    pf.Q, pf.R = np.diag([0.05**2, 0.05**2, 0.2**2]), np.eye(4) * book.SENSOR_STD**2
    pf.initialize(np.column_stack([rng.uniform(0, 20, n), rng.uniform(0, 20, n), rng.uniform(0, 2 * np.pi, n)]))
    pos, errors = np.zeros(2), []
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        for _ in range(18):
            pos = pos + 1.0
            pf.predict(u=book.STEP)
            pf.update(np.linalg.norm(book.LANDMARKS - pos, axis=1) + rng.normal(0, book.SENSOR_STD, 4))
            errors.append(np.linalg.norm(pf.x[:2] - pos))
    warned = any(issubclass(w.category, DegeneracyWarning) for w in rec)
    return max(errors[-6:]) < 0.5, warned, old_rule(pf.ess_history)


def tracker_row(seed):
    F, xs, zs = _cv_range_bearing(seed=seed)
    pf = BootstrapParticleFilter(4, 2, 1.0, cv_hx, lambda X, dt: X @ F.T, 300, residual_z=angle_residual(1),
                                 vectorized=True, rng=seed)
    pf.x, pf.P = xs[0] + np.array([0.5, 0.1, -0.5, 0.1]), np.diag([1.0, 0.1, 1.0, 0.1])
    pf.Q, pf.R = 0.01 * np.eye(4), np.diag([0.25, 1e-4])
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        means, _ = pf.batch_filter(zs)
    rmse = np.sqrt(np.mean((means[:, [0, 2]] - xs[:, [0, 2]]) ** 2))
    return rmse < 3.0, any(issubclass(w.category, DegeneracyWarning) for w in rec), old_rule(pf.ess_history)


def main():
    print("DegeneracyWarning on 30 seeds each: runs that end fine, and how many of them warn")
    print(f"{'problem':44s} {'fine':>5s} {'warned':>7s} {'fine+warned':>12s} {'old rule warned':>16s} {'old, fine':>10s}")
    for name, row in (("book ch. 12 robot PF (Bootstrap, 5000)", book_row),
                      ("4-state range-bearing tracker (Bootstrap, 300)", tracker_row)):
        rows = np.array([row(s) for s in range(30)])
        fine, new, old = rows.T
        print(f"{name:44s} {fine.sum():5d} {new.sum():7d} {(fine & new).sum():12d} {old.sum():16d} "
              f"{(fine & old).sum():10d}")


if __name__ == "__main__":
    main()
