"""What the SMC rows' predictive intervals hold, measured on the WNN study's own fits (issue 24).

Refits a row of ``filterwnn study wnn`` run by run, with the study's seeds and settings
(:func:`filterwnn.studies.wnn.runs._regressor`, the same estimator ``fit_run`` builds; the test
MSE printed must equal the study's ``runs.csv``), and splits the predictive variance on the test
inputs into its parts: the cloud's spread of outputs and the noise term (the learned
``mean exp(s_i)`` for ``smc-noise*``, R for ``smc``). Beside them, the residuals it is meant to
cover: the training rows' and the test rows' squared error of the mean prediction (median and
mean: a Gaussian's squared errors have mean / median 2.2), the particles' own training error
averaged over the particles (what each particle's ``s_i`` sees), and the 90 % coverage of each
part alone. The SISO plant has no measurement noise (``datasets.siso_plant``): every residual is the
network's error. Diagnostics only: nothing here chooses a setting.

    PYTHONPATH=. OPENBLAS_NUM_THREADS=1 python benchmarks/wnn_smc_intervals.py smc-noise-10x10 60 10
"""

import sys

import numpy as np

from filterwnn.datasets import make_siso_benchmark
from filterwnn.studies.wnn.plan import run_seeds
from filterwnn.studies.wnn.runs import _child, _regressor
from filterwnn.wnn import network

Z90 = 1.6448536269514722


def one(row, seed, n_particles):
    """One run's parts of the predictive variance and its residuals."""
    X, y, X_test, y_test = make_siso_benchmark(rng=_child(seed, 0))
    reg = _regressor(row, "working", seed, 1, n_particles, None).fit(X, y)
    tr = reg._final
    noisy = hasattr(tr, "noise")
    W = tr.particles[:, :-1] if noisy else tr.particles
    noise = float(np.mean(tr.noise)) if noisy else float(tr.model.R[0, 0])
    out = {}
    for part, (Xs, ys) in (("train", (X, y)), ("test", (X_test, y_test))):
        Y = network.forward(W, Xs, tr.model.wavelet)
        r2 = (Y.mean(axis=0) - ys) ** 2
        cloud = Y.var(axis=0)
        out[f"{part}_mse"], out[f"{part}_r2_median"] = float(r2.mean()), float(np.median(r2))
        out[f"{part}_cloud"] = float(np.median(cloud))
        out[f"{part}_mse_particles"] = float(np.mean((Y - ys) ** 2))  # each particle's own error, averaged
        out[f"{part}_cov90"] = float(np.mean(r2 <= Z90**2 * (cloud + noise)))
        out[f"{part}_cov90_cloud"] = float(np.mean(r2 <= Z90**2 * cloud))
        out[f"{part}_cov90_noise"] = float(np.mean(r2 <= Z90**2 * noise))
    out["noise"] = noise
    out["noise_spread"] = float(np.std(np.log(tr.noise))) if noisy else 0.0
    return out


def main(row, n_particles, n_runs):
    cols = ("test_mse", "noise", "noise_spread", "test_cloud", "train_cloud", "train_mse", "train_mse_particles",
            "train_r2_median",
            "test_r2_median", "test_cov90", "test_cov90_cloud", "test_cov90_noise", "train_cov90")
    print(f"# {row}, N = {n_particles}, runs 0-{n_runs - 1} of seed 2026 (the study's fits); medians over "
          "inputs within a run; noise = mean exp(s_i) (smc: R); noise_spread = sd of s_i over particles")
    print("| run | " + " | ".join(cols) + " |")
    print("|---" * (len(cols) + 1) + "|")
    rs = []
    for i, seed in enumerate(run_seeds(2026, n_runs)):
        rs.append(one(row, seed, n_particles))
        print(f"| {i} | " + " | ".join(f"{rs[-1][c]:.4g}" for c in cols) + " |", flush=True)
    print("| median | " + " | ".join(f"{np.median([r[c] for r in rs]):.4g}" for c in cols) + " |")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
