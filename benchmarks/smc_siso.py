"""The SMC trainer (``WNNRegressor(trainer="smc")``) on the SISO benchmark (issue 13).

Protocol, fixed before any test number:

1. ``--validate``: every candidate setting is fitted on 80 of the 100 training rows of
   seeds 0-2 (the 20 validation rows drawn with ``default_rng(1000 + seed)``) and scored by
   the median validation MSE. The setting with the lowest median wins.
2. ``--test``: the chosen setting is fitted on all 100 training rows of seeds 0-4 once; the
   script reports the test MSE, the 90 % predictive-interval coverage of the test targets
   (``|y - mean| <= 1.645 std``, std from the particles' spread plus R), the mean and minimum
   ESS over the ladder's rungs, the number of rungs, the MALA acceptance, distinct
   particles and distinct initial ancestors at the end, and the time per fit; and the
   default ``WNNRegressor()`` (EKF) on the same seeds.

Candidates are written ``key=value,key=value`` over the ``("smc", "scaled")`` settings
(``kernel``, ``n_moves``, ``n_leapfrog``, ``preconditioner``, ``output_scale``, ``ess_fraction``)
plus ``N`` (particles) and ``R`` (``measurement_noise``, default 0.1); the spec ``ekf``
validates the default ``WNNRegressor()`` for reference. Outputs of the runs behind the
numbers in the README: ``benchmarks/smc_siso_results.txt``.
Run with one BLAS thread, e.g.::

    OPENBLAS_NUM_THREADS=1 python benchmarks/smc_siso.py --validate "N=50" "N=50,preconditioner=cov"
    OPENBLAS_NUM_THREADS=1 python benchmarks/smc_siso.py --test "N=50,preconditioner=cov"
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from filterwnn import WNNRegressor, make_siso_benchmark
from filterwnn.wnn import trainers


def _parse(spec):
    out = {}
    for item in filter(None, spec.split(",")):
        k, v = item.split("=")
        if v.replace(".", "", 1).replace("e-", "", 1).isdigit():
            v = float(v) if any(c in v for c in ".e") else int(v)
        out[k] = v
    return out


def fit_smc(spec, X, y, seed):
    cfg = _parse(spec)
    n = int(cfg.pop("N", 50))
    r = float(cfg.pop("R", 0.1))
    key = ("smc", "scaled")
    auto = trainers.AUTO_SETTINGS[key]  # the smc entry's own dict: changed in place, restored after
    saved = dict(auto)
    auto.update(cfg)
    try:
        t0, c0 = time.perf_counter(), time.process_time()
        reg = WNNRegressor(trainer="smc", n_particles=n, n_epochs=1, measurement_noise=r, random_state=seed)
        reg.fit(X, y)
        reg.cpu_seconds_ = time.process_time() - c0  # CPU time: robust to other jobs on the machine
        return reg, time.perf_counter() - t0
    finally:
        auto.clear()
        auto.update(saved)


def validate(specs, seeds):
    for spec in specs:
        scores = []
        for seed in seeds:
            X, y, _, _ = make_siso_benchmark(rng=seed)
            val = np.zeros(len(X), bool)
            val[np.random.default_rng(1000 + seed).choice(len(X), 20, replace=False)] = True
            if spec == "ekf":  # the default regressor, for reference
                t0 = time.perf_counter()
                reg, extra = WNNRegressor(random_state=seed).fit(X[~val], y[~val]), ""
                dt = time.perf_counter() - t0
            else:
                reg, dt = fit_smc(spec, X[~val], y[~val], seed)
                d = reg.diagnostics_
                extra = (f" ESS {d['mean_ess'][0]:.1f}, acceptance {d['acceptance'][0]:.2f}, "
                         f"ancestors {d['distinct_ancestors'][0]}, rungs {d['n_rungs'][0]}")
            mean, std = reg.predict(X[val], return_std=True)
            scores.append(float(np.mean((mean - y[val]) ** 2)))
            cover = float(np.mean(np.abs(y[val] - mean) <= 1.645 * std))
            print(f"  {spec} seed {seed}: validation MSE {scores[-1]:.4f}, coverage90 {cover:.2f} "
                  f"({dt:.1f} s){extra}", flush=True)
        print(f"VALIDATE {spec}: median {np.median(scores):.4f}  {np.round(scores, 4).tolist()}", flush=True)


def test(spec, seeds):
    rows = []
    for seed in seeds:
        X, y, Xt, yt = make_siso_benchmark(rng=seed)
        reg, dt = fit_smc(spec, X, y, seed)
        mean, std = reg.predict(Xt, return_std=True)
        res = reg._final.result
        ekf = WNNRegressor(random_state=seed).fit(X, y)
        row = dict(
            seed=seed,
            mse=float(np.mean((mean - yt) ** 2)),
            cov90=float(np.mean(np.abs(yt - mean) <= 1.645 * std)),
            mean_ess=float(np.mean(res.ess)),
            min_ess=float(np.min(res.ess)),
            rungs=len(res.betas),
            acceptance=float(np.mean(res.acceptance)),
            distinct=res.distinct_particles[-1],
            ancestors=res.distinct_ancestors[-1],
            seconds=dt,
            cpu_seconds=reg.cpu_seconds_,
            ekf_mse=float(np.mean((ekf.predict(Xt) - yt) ** 2)),
        )
        rows.append(row)
        cells = (f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in row.items())
        print("  " + "  ".join(cells), flush=True)
    med = {k: float(np.median([r[k] for r in rows])) for k in rows[0] if k != "seed"}
    print(f"TEST {spec} seeds {list(seeds)} medians: " + "  ".join(f"{k}={v:.4g}" for k, v in med.items()), flush=True)
    print(f"  mean ESS over seeds {np.mean([r['mean_ess'] for r in rows]):.1f}; "
          f"coverage pooled {np.mean([r['cov90'] for r in rows]):.3f}", flush=True)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("specs", nargs="+")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--validate", action="store_true")
    g.add_argument("--test", action="store_true")
    p.add_argument("--seeds", default=None, help="comma-separated (default 0,1,2 validate; 0-4 test)")
    a = p.parse_args(argv)
    if a.seeds:
        seeds = [int(s) for s in a.seeds.split(",")]
    else:
        seeds = [0, 1, 2] if a.validate else [0, 1, 2, 3, 4]
    if a.validate:
        validate(a.specs, seeds)
    else:
        for spec in a.specs:
            test(spec, seeds)


if __name__ == "__main__":
    main()
