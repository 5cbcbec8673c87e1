"""Time per step (predict + update) of the adaptive EKF against filterpy's EKF (issue 14).

The paper's 6-state DR model on the straight road with the noise x20 at 150 s (2000
steps): filterpy's ``ExtendedKalmanFilter`` (ratio 1), ``AdaptiveExtendedKalmanFilter``
with its defaults, and with ``inflate=False`` (no window sensitivities to carry).
Interleaved repeats, the minimum of each; one BLAS thread.

Run: ``python benchmarks/bench_aekf.py`` (``--repeats N``).
"""

from __future__ import annotations

import argparse
import os
import platform
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from filterpy.kalman import ExtendedKalmanFilter  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

from filterwnn import AdaptiveExtendedKalmanFilter  # noqa: E402
from filterwnn.navigation.dead_reckoning import DRModel, dr_residual  # noqa: E402
from filterwnn.navigation.scenarios import SCENARIOS, simulate_scenario  # noqa: E402

FILTERS = {
    "EKF (filterpy)": lambda: ExtendedKalmanFilter(6, 2),
    "AdaptiveEKF": lambda: AdaptiveExtendedKalmanFilter(6, 2),
    "AdaptiveEKF inflate=False": lambda: AdaptiveExtendedKalmanFilter(6, 2, inflate=False),
}


def time_filter(make, model, run):
    kf = make()
    kf.F, kf.Q, kf.R = model.F.copy(), model.Q.copy(), model.R.copy()
    kf.x, kf.P = run.x0.copy(), model.P0.copy()
    t0 = time.perf_counter()
    for z in run.z_dr:
        kf.predict()
        kf.update(z, model.HJacobian, model.hx, residual=dr_residual)
    return (time.perf_counter() - t0) / len(run.z_dr)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5)
    args = p.parse_args(argv)
    model = DRModel()
    run = simulate_scenario(SCENARIOS["straight"](), rng=0)
    best = {name: np.inf for name in FILTERS}
    with threadpool_limits(1):
        for _ in range(args.repeats):
            for name, make in FILTERS.items():
                best[name] = min(best[name], time_filter(make, model, run))
    base = best["EKF (filterpy)"]
    print(f"{platform.processor() or platform.machine()}, numpy {np.__version__}, "
          f"{len(run.z_dr)} steps, min of {args.repeats}")
    print("| filter | us/step | ratio |\n|---|---|---|")
    for name, t in best.items():
        print(f"| {name} | {t * 1e6:.0f} | {t / base:.2f} |")


if __name__ == "__main__":
    main()
