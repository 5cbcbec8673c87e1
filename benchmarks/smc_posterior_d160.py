"""The SMC sampler against a known posterior at the WNN study's size (issue 24 e).

A Bayesian linear regression with d = 160 weights (the 5-20-1 WNN's count) and 100 rows (the
study's training rows, fewer than d as there): ``y = X w + e``, ``e ~ N(0, 0.1)``, prior
``w ~ N(0, I)``, ``X`` standard normal; the posterior ``N(mu, S)`` is closed form. For a few N
at a fixed budget of particle-gradient evaluations per rung (the study's ``smc`` row: N = 20,
6 HMC steps of 10 leapfrogs = 1200; MALA: N x steps = 1200), the sampler's final cloud is
compared with the posterior: ``var ratio`` (median over coordinates of the cloud's variance over
the posterior's; 1 is right, below 1 too narrow), ``mean z`` (median over coordinates of
``|cloud mean - mu| / sd``, which a sample of N i.i.d. draws puts near ``0.67 / sqrt(N)``), the
distinct ancestors and the rungs. Seeds 0-2, medians.

    PYTHONPATH=. OPENBLAS_NUM_THREADS=1 python benchmarks/smc_posterior_d160.py

``--choose BUDGET`` (issue 24, protocol 4) compares, at one fixed budget of particle-gradient
evaluations per rung set before the run, HMC at N = 20, 40, 60 (10 leapfrogs), HMC at N = 20
with 5 and 20 leapfrogs, and MALA at N = 20, on seeds 0-4 (medians), and writes the choice
rule's pick: the largest var ratio, mean z as the tie-break (within 0.02 of the best ratio):

    PYTHONPATH=. OPENBLAS_NUM_THREADS=1 python benchmarks/smc_posterior_d160.py --choose 6000
"""

import sys

import time

import numpy as np

from filterwnn.monte_carlo.smc import HMCMove, MALAMove, RowsTarget, smc_sampler

D, N_ROWS, NOISE, BUDGET = 160, 100, 0.1, 1200


class BayesianRegression:
    """``y ~ N(X w, NOISE)``, ``w ~ N(0, I)``: the target's interface, batched over particles."""

    def __init__(self, d):
        self.dim_x, self.x0, self.P0 = d, np.zeros(d), np.eye(d)

    def log_prior_and_grad(self, W):
        return -0.5 * np.sum(W * W, axis=1), -W

    def log_likelihood_and_grad(self, W, X, y):
        r = y[None, :] - W @ X.T
        return -0.5 * np.sum(r * r, axis=1) / NOISE, (r @ X) / NOISE

    def log_likelihood(self, W, X, y):
        return self.log_likelihood_and_grad(W, X, y)[0]


def posterior(X, y):
    S = np.linalg.inv(np.eye(X.shape[1]) + X.T @ X / NOISE)
    return S @ X.T @ y / NOISE, S


def one(seed, n, kernel, budget=BUDGET, n_leapfrog=10):
    rng = np.random.default_rng(seed)
    X = rng.standard_normal((N_ROWS, D))
    y = X @ rng.standard_normal(D) + np.sqrt(NOISE) * rng.standard_normal(N_ROWS)
    mu, S = posterior(X, y)
    target = RowsTarget(BayesianRegression(D), X, y)
    if kernel == "hmc":
        move = HMCMove(target, n_steps=max(1, budget // (n_leapfrog * n)), n_leapfrog=n_leapfrog)
    else:
        move = MALAMove(target, n_steps=max(1, budget // n))
    t0 = time.process_time()
    res = smc_sampler(target, n_particles=n, rng=seed + 100, move=move)
    sd = np.sqrt(np.diag(S))
    return dict(var_ratio=float(np.median(res.particles.var(axis=0, ddof=1) / np.diag(S))),
                mean_z=float(np.median(np.abs(res.particles.mean(axis=0) - mu) / sd)),
                ancestors=res.distinct_ancestors[-1], rungs=len(res.betas), cpu=time.process_time() - t0)


def main():
    print(f"| kernel | N | steps per rung | var ratio | mean z (iid: {0.67:.2f}/sqrt(N)) | distinct ancestors "
          "| rungs | CPU s |  (d = 160, 100 rows, medians over seeds 0-2)")
    print("|---|---|---|---|---|---|---|---|")
    for kernel in ("hmc", "mala"):
        for n in (20, 40, 60, 120):
            rs = [one(s, n, kernel) for s in range(3)]
            m = {k: float(np.median([r[k] for r in rs])) for k in rs[0]}
            steps = max(1, BUDGET // (10 * n)) if kernel == "hmc" else max(1, BUDGET // n)
            print(f"| {kernel} | {n} | {steps} | {m['var_ratio']:.3f} | {m['mean_z']:.3f} (iid {0.67 / np.sqrt(n):.3f}) "
                  f"| {m['ancestors']:.0f} | {m['rungs']:.0f} | {m['cpu']:.1f} |", flush=True)

    print("\nHMC at N = 20, larger budgets (particle-gradient evaluations per rung):\n")
    print("| budget | HMC steps per rung | var ratio | mean z | rungs | CPU s |")
    print("|---|---|---|---|---|---|")
    for budget in (BUDGET, 5 * BUDGET, 20 * BUDGET):
        rs = [one(s, 20, "hmc", budget) for s in range(3)]
        m = {k: float(np.median([r[k] for r in rs])) for k in rs[0]}
        print(f"| {budget} | {budget // 200} | {m['var_ratio']:.3f} | {m['mean_z']:.3f} | {m['rungs']:.0f} "
              f"| {m['cpu']:.1f} |", flush=True)


def choose(budget, seeds=range(5)):
    """At ``budget`` particle-gradient evaluations per rung: each candidate's medians, and the pick."""
    candidates = [("hmc", 20, 10), ("hmc", 40, 10), ("hmc", 60, 10), ("hmc", 20, 5), ("hmc", 20, 20), ("mala", 20, 1)]
    print(f"# budget {budget} particle-gradient evaluations per rung; d = 160, 100 rows; medians over seeds "
          f"{seeds.start}-{seeds.stop - 1}")
    print("| kernel | N | leapfrogs | steps per rung | var ratio | mean z (iid) | distinct ancestors | rungs | CPU s |")
    print("|---|---|---|---|---|---|---|---|---|")
    rows = []
    for kernel, n, lf in candidates:
        rs = [one(s, n, kernel, budget, lf) for s in seeds]
        m = {k: float(np.median([r[k] for r in rs])) for k in rs[0]}
        steps = max(1, budget // (lf * n))
        rows.append((kernel, n, lf, steps, m))
        print(f"| {kernel} | {n} | {lf if kernel == 'hmc' else '-'} | {steps} | {m['var_ratio']:.3f} "
              f"| {m['mean_z']:.3f} ({0.67 / np.sqrt(n):.3f}) | {m['ancestors']:.0f} | {m['rungs']:.0f} "
              f"| {m['cpu']:.1f} |", flush=True)
    best = max(r[4]["var_ratio"] for r in rows)
    pick = min((r for r in rows if r[4]["var_ratio"] >= best - 0.02), key=lambda r: r[4]["mean_z"])
    print(f"\npick (largest var ratio; within 0.02 of it, smallest mean z): {pick[0]} N = {pick[1]}, "
          f"{pick[3]} steps x {pick[2]} leapfrogs per rung (var ratio {pick[4]['var_ratio']:.3f}, "
          f"mean z {pick[4]['mean_z']:.3f})")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--choose":
        choose(int(sys.argv[2]))
    else:
        main()
