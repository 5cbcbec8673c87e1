"""``GPSDRFilter(stop_reopen=2.0)`` on the plainest drive: ``FROM_REST`` of ``tests/navigation/test_gpsdr.py``
(a car from rest, a 90-degree turn, a 10 s stop, a 30 s outage to the end; no gyro rate bias, 1 degree of heading
noise, a standstill speed with the odometer's noise), phone grade, each kind, seeds 0-19.

Run from the repository root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/analog-seeds/stop_reopen_from_rest.py > docs/study-outputs/dr/analog-seeds/stop_reopen_from_rest.txt

Each line: the kind, then the error at the outage's end (the last sample before the fix at 120 s, m) on each seed
with the default and with ``stop_reopen=2``, their medians and maxima, and on how many seeds it is worse or
better by more than 0.1 m.

``--drift D`` (stop 45) gives the gyro a rate bias of ``D`` deg/s (``Scenario.heading_drift``), so that the stop
has a bias to find::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/analog-seeds/stop_reopen_from_rest.py --drift 0.01 --drift -0.02 --drift 0.04 > docs/study-outputs/dr/analog-seeds/stop_reopen_from_rest_drift.txt

(each line then starts with the drift, and gives the means too).
"""
import argparse
import dataclasses
import os
import sys
import warnings

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests", "navigation"))

from test_gpsdr import FROM_REST  # noqa: E402
from filterwnn.navigation.dead_reckoning import GPSDRModel  # noqa: E402
from filterwnn.navigation.gpsdr import KINDS, GPSDRFilter  # noqa: E402
from filterwnn.navigation.scenarios import simulate_scenario  # noqa: E402


def outage_end(run, kind, reopen):
    gps, sig = run.gps_list(), run.gps_sigma_list()
    end = int(np.flatnonzero(run.t < FROM_REST.outages[0][1] - 1e-9)[-1])
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        f = GPSDRFilter(model, kind, x0=np.r_[run.x0, model.x0[6:]], stop_reopen=reopen)
        for k in range(end + 1):
            f.predict()
            f.update(run.z_dr[k], gps[k], sig[k])
    return float(np.hypot(f.x[0] - run.x_true[end, 0], f.x[3] - run.x_true[end, 3]))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--drift", type=float, action="append", help="the gyro's rate bias (deg/s); repeatable")
    args = p.parse_args(argv)
    for drift in args.drift or [None]:
        scenario = FROM_REST if drift is None else dataclasses.replace(FROM_REST, heading_drift=drift)
        runs = [simulate_scenario(scenario, rng=seed) for seed in range(20)]
        for kind in KINDS:
            a = np.array([outage_end(r, kind, 0.0) for r in runs])
            b = np.array([outage_end(r, kind, 2.0) for r in runs])
            head = "" if drift is None else f"drift {drift:+g} deg/s | "
            means = "" if drift is None else f", mean {a.mean():.2f} -> {b.mean():.2f}"
            print(f"{head}{kind} | default {' '.join(f'{v:.2f}' for v in a)} | stop_reopen=2 "
                  f"{' '.join(f'{v:.2f}' for v in b)} | median {np.median(a):.2f} -> {np.median(b):.2f}, max "
                  f"{a.max():.2f} -> {b.max():.2f}{means} | worse on {int((b > a + 0.1).sum())}, better on "
                  f"{int((b < a - 0.1).sum())} of 20", flush=True)


if __name__ == "__main__":
    main()
