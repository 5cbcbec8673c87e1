"""Bootstrap filter, side by side with Chopin's ``particles``: per-step time.

The univariate growth model (Kitagawa 1987; Gordon, Salmond and Smith 1993)::

    x_k = x/2 + 25 x / (1 + x^2) + 8 cos(1.2 k) + v,   v ~ N(0, 10)
    y_k = x_k^2 / 20 + w,                              w ~ N(0, 1)

100 steps, resampling every step (systematic in both), N = 1000 and 10,000 particles.
Each row is the median over ``--repeats`` runs of the whole filter divided by the number
of steps; the ratio is ours / ``particles`` (<= 1.0 is the goal of issue 12).

    python benchmarks/bench_particles_peer.py [--repeats 7] [--sizes 1000 10000]
"""

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's filterwnn, not an installed one

import particles
from particles import state_space_models as ssm
from particles import distributions as dists

from filterwnn import BootstrapParticleFilter

T = 100


class Growth(ssm.StateSpaceModel):
    default_params = {"sigma_v": np.sqrt(10.0), "sigma_w": 1.0}

    def PX0(self):
        return dists.Normal(loc=0.0, scale=np.sqrt(5.0))

    def PX(self, t, xp):
        return dists.Normal(loc=xp / 2 + 25 * xp / (1 + xp**2) + 8 * np.cos(1.2 * t), scale=self.sigma_v)

    def PY(self, t, xp, x):
        return dists.Normal(loc=x**2 / 20, scale=self.sigma_w)


def fx(X, dt, k):
    return X / 2 + 25 * X / (1 + X**2) + 8 * np.cos(1.2 * k)


def hx(X):
    return X**2 / 20


def simulate(seed=0):
    rng = np.random.default_rng(seed)
    x = rng.normal(0, np.sqrt(5.0))
    ys = []
    for k in range(T):
        x = x / 2 + 25 * x / (1 + x**2) + 8 * np.cos(1.2 * k) + rng.normal(0, np.sqrt(10.0))
        ys.append(x**2 / 20 + rng.normal())
    return np.array(ys)


def run_ours(ys, N, seed):
    pf = BootstrapParticleFilter(1, 1, 1.0, hx, fx, N, vectorized=True, rng=seed, resampling="systematic")
    pf.x, pf.P, pf.Q, pf.R = np.zeros(1), np.array([[5.0]]), np.array([[10.0]]), np.array([[1.0]])
    t0 = time.perf_counter()
    z = np.empty(1)
    for k in range(T):
        pf.predict(k=k)
        z[0] = ys[k]
        pf.update(z)
    return time.perf_counter() - t0


def run_peer(ys, N, seed):
    np.random.seed(seed)  # particles draws from numpy's global stream
    fk = ssm.Bootstrap(ssm=Growth(), data=list(ys))
    alg = particles.SMC(fk=fk, N=N, resampling="systematic", ESSrmin=1.0, store_history=False, collect=None)
    t0 = time.perf_counter()
    alg.run()
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--sizes", type=int, nargs="+", default=[1000, 10000])
    args = ap.parse_args()
    ys = simulate()
    print(f"bootstrap filter, growth model, {T} steps, resampling every step; median of {args.repeats}")
    print(f"{'N':>7} {'filterwnn us/step':>18} {'particles us/step':>18} {'ratio':>7}")
    for N in args.sizes:
        run_ours(ys, N, 0), run_peer(ys, N, 0)  # warm-up
        ours, peer = [], []
        for r in range(args.repeats):  # interleaved, so load changes hit both alike
            ours.append(run_ours(ys, N, r))
            peer.append(run_peer(ys, N, r))
        a, b = 1e6 * np.median(ours) / T, 1e6 * np.median(peer) / T
        print(f"{N:>7} {a:18.1f} {b:18.1f} {a / b:7.2f}")


if __name__ == "__main__":
    main()
