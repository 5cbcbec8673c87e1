"""What the Student-t SMC row's predictive intervals hold, on the WNN study's own fits (protocol 5, issue 24).

Refits ``smc-student-10x10`` run by run with the study's seeds and settings
(:func:`filterwnn.studies.wnn.runs._regressor`, the estimator ``fit_run`` builds: the test MSE
printed must equal protocol 5's ``runs.csv``) and splits its 90 % interval on the test inputs:

- ``cov90``: the mixture of t's (what the study scores);
- ``cov90_cloud``: the particles' locations alone (the central 90 % of the particles' outputs);
- ``cov90_noise``: the learned t alone, centred on the mean prediction (the mixture with every
  location set to the mean);
- ``width_ratio``: the mixture's median 90 % half-width over the 90 % quantile of the test
  absolute errors of the mean prediction (1 for an interval of the right width at 90 %; above 1:
  too wide);
- the learned noise: the particles' median ``sigma^2`` and ``nu``, and the share of particles
  with ``nu < 5`` (under the prior Gamma(2, rate 0.1): 9.0 %; heavy tails need small ``nu``).

Diagnostics only, written after protocol 5's numbers were seen (said in its ``RUN.md``):
nothing here chooses a setting.

    PYTHONPATH=. OPENBLAS_NUM_THREADS=1 python benchmarks/wnn_student_intervals.py 60 10
"""

import sys

import numpy as np

from filterwnn.datasets import make_siso_benchmark
from filterwnn.studies.wnn.plan import run_seeds
from filterwnn.studies.wnn.runs import _child, _regressor
from filterwnn.wnn.predictive import StudentTMixture

ROW = "smc-student-10x10"


def _covers(dist, y, level=0.9):
    return float(np.mean(dist.covers(y, level)))


def one(seed, n_particles):
    """One run's 90 % coverages (mixture, cloud alone, noise alone), width ratio and learned noise."""
    X, y, X_test, y_test = make_siso_benchmark(rng=_child(seed, 0))
    reg = _regressor(ROW, "working", seed, 1, n_particles, None).fit(X, y)
    tr = reg._final
    dist = reg.predictive(X_test)
    err = np.abs(dist.mean - y_test)
    lo, hi = dist.interval(0.9)
    cloud_lo, cloud_hi = np.quantile(dist.loc, [0.05, 0.95], axis=0)
    noise_only = StudentTMixture(np.broadcast_to(dist.mean, dist.loc.shape), tr.noise, tr.df)
    return {
        "test_mse": float(np.mean(err**2)),
        "cov90": _covers(dist, y_test),
        "cov90_cloud": float(np.mean((cloud_lo <= y_test) & (y_test <= cloud_hi))),
        "cov90_noise": _covers(noise_only, y_test),
        "width_ratio": float(np.median(0.5 * (hi - lo)) / np.quantile(err, 0.9)),
        "scale2": float(np.median(tr.noise)),
        "nu": float(np.median(tr.df)),
        "nu_below_5": float(np.mean(tr.df < 5.0)),
        "err2_mean_over_median": float(np.mean(err**2) / np.median(err**2)),
    }


def main(n_particles, n_runs):
    cols = ("test_mse", "cov90", "cov90_cloud", "cov90_noise", "width_ratio", "scale2", "nu", "nu_below_5",
            "err2_mean_over_median")
    print(f"# {ROW}, N = {n_particles}, runs 0-{n_runs - 1} of seed 2026 (the study's fits)")
    print("| run | " + " | ".join(cols) + " |")
    print("|---" * (len(cols) + 1) + "|")
    rs = []
    for i, seed in enumerate(run_seeds(2026, n_runs)):
        rs.append(one(seed, n_particles))
        print(f"| {i} | " + " | ".join(f"{rs[-1][c]:.4g}" for c in cols) + " |", flush=True)
    print("| median | " + " | ".join(f"{np.median([r[c] for r in rs]):.4g}" for c in cols) + " |")


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]))
