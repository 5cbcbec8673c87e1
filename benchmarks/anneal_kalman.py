"""What ``WNNRegressor.anneal`` does to the Kalman trainers' intervals (issue 24).

The medium WNN run's first five seeds (``SeedSequence(2026).spawn(10)[:5]``, the study's data
and training streams), each Kalman trainer at the settings and epochs the medium run's search
chose on validation rows (``docs/study-outputs/wnn-medium/tuning.md``), scored on the test rows
before and after ``anneal(X, y, n_epochs)``: test MSE, coverage of the central 50 / 90 / 95 %
intervals and the mean negative log predictive density (medians over the seeds). Nothing here
is chosen from these numbers.

    PYTHONPATH=. OPENBLAS_NUM_THREADS=1 python benchmarks/anneal_kalman.py [--trainers ekf,ukf] [--anneal 5]
"""

import argparse

import numpy as np

from filterwnn import WNNRegressor
from filterwnn.datasets import make_siso_benchmark
from filterwnn.studies.wnn import predictive_scores, run_seeds
from filterwnn.studies import runner

#: The medium run's choices (tuning.md there): Q, P0, epochs.
CHOSEN = {"ekf": (1e-2, 1.0, 21), "ukf": (1e-6, 0.01, 83), "sukf": (1e-6, 0.01, 100)}


def one(trainer, seed, n_anneal):
    X, y, Xt, yt = make_siso_benchmark(rng=runner.child(seed, 0))
    q, p0, epochs = CHOSEN[trainer]
    reg = WNNRegressor(trainer=trainer, process_noise=q, initial_covariance=p0, n_epochs=epochs,
                       random_state=runner.child(seed, 1)).fit(X, y)
    rows = []
    for stage in ("trained", "annealed"):
        if stage == "annealed":
            reg.anneal(X, y, n_epochs=n_anneal)
        mean, std = reg.predict(Xt, return_std=True)
        rows.append(dict(stage=stage, mse=float(np.mean((mean - yt) ** 2)), **predictive_scores(mean, std, yt)))
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--trainers", default="ekf,ukf")
    ap.add_argument("--anneal", type=int, default=5)
    ap.add_argument("--runs", type=int, default=5)
    a = ap.parse_args()
    seeds = run_seeds(2026, 10)[: a.runs]
    print(f"| trainer | stage | test MSE | coverage 50 / 90 / 95 % | NLPD |  (medians over {a.runs} runs; "
          f"anneal {a.anneal} epochs)")
    print("|---|---|---|---|---|")
    for t in a.trainers.split(","):
        res = [one(t, s, a.anneal) for s in seeds]
        for i, stage in enumerate(("trained", "annealed")):
            med = {k: float(np.median([r[i][k] for r in res])) for k in res[0][i] if k != "stage"}
            print(f"| {t} | {stage} | {med['mse']:.4f} | {med['coverage50']:.2f} / {med['coverage90']:.2f} / "
                  f"{med['coverage95']:.2f} | {med['nlpd']:.3f} |", flush=True)


if __name__ == "__main__":
    main()
