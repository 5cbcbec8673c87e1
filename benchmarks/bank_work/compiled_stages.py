"""Where the compiled bank's step goes: each kernel, the model's calls and the whole step.

bench_peers.py's 6-state UKF bank (Merwe points, dim_z = 3), B members, one BLAS thread,
median wall time over ``--reps`` calls, per member. The kernels are timed on their own
(``filterwnn.kalman._compiled.kernels()``: the factors and sigma points, the predicted
moments, the update), beside the user's ``fx`` and ``hx`` on the same rows and the whole
step of the bank with ``compiled=True`` and ``compiled=False``.

    OPENBLAS_NUM_THREADS=1 python benchmarks/bank_work/compiled_stages.py [--reps 300]
"""

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402
from filterpy.kalman import MerweScaledSigmaPoints  # noqa: E402

from bench_particle import DT6, six_fx, six_hx, six_problem  # noqa: E402
from filterwnn.kalman import UnscentedKalmanFilterBank, _compiled  # noqa: E402


def per_member(f, B, reps):
    ts = []
    for _ in range(reps):
        t0 = time.perf_counter()
        f()
        ts.append(time.perf_counter() - t0)
    return float(np.median(ts)) / B * 1e6


def stages(B, reps):
    g = np.random.default_rng(0)
    prob = six_problem(g, 1)
    x = prob["x0"] + g.standard_normal((B, 6)) * np.sqrt(np.diag(prob["P0"]))
    z = prob["zs"][0] + g.standard_normal((B, 3)) * np.sqrt(np.diag(prob["R"]))
    banks = {}
    for c in (True, False):
        b = UnscentedKalmanFilterBank(B, 6, 3, DT6, six_hx, six_fx, MerweScaledSigmaPoints(6, 1.0, 2.0, 0.0),
                                      compiled=c)
        b.x, b.P, b.Q, b.R = x, prob["P0"], prob["Q"], prob["R"]
        b.predict()
        b.update(z)
        banks[c] = b
    sk, pk, uk = _compiled.kernels()
    Wm, Wc, Z = banks[True]._step._weights
    n, S, m = 6, Z.shape[0], 3
    P, xx = np.ascontiguousarray(banks[True].P), banks[True].x.copy()
    L, sig = np.empty((n, n, B)), np.empty((n, B, S))
    sk(xx, P, Z, L, sig)
    rows = sig.transpose(1, 2, 0).reshape(B * S, n)
    F = np.ascontiguousarray(six_fx(rows, DT6)).reshape(B, S, n)
    H = np.ascontiguousarray(six_hx(rows)).reshape(B, S, m)
    xp, Pp = np.empty((B, n)), np.empty((B, n, n))
    pk(F, Wm, Wc, prob["Q"][None], xp, Pp, False)
    out = [np.empty(s) for s in ((B, n), (B, n, n), (B, m), (B, m, m), (B, n, m), (B,))]
    res = {
        "factors and sigma points (x2 a step)": per_member(lambda: sk(xx, P, Z, L, sig), B, reps),
        "predicted moments": per_member(lambda: pk(F, Wm, Wc, prob["Q"][None], xp, Pp, False), B, reps),
        "update": per_member(lambda: uk(H, L, Z, xp, P, z, prob["R"][None], Wm, Wc, *out, False), B, reps),
        "the user's fx": per_member(lambda: six_fx(rows, DT6), B, reps),
        "the user's hx": per_member(lambda: six_hx(rows), B, reps),
    }
    for c, name in ((True, "bank step, compiled"), (False, "bank step, NumPy")):
        res[name] = per_member(lambda b=banks[c]: (b.predict(), b.update(z)), B, reps)
    return res


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--reps", type=int, default=300)
    args = ap.parse_args(argv)
    for B in (1000, 10000):
        res = stages(B, args.reps if B == 1000 else max(args.reps // 10, 10))
        kern = 2 * res["factors and sigma points (x2 a step)"] + res["predicted moments"] + res["update"]
        print(f"B = {B:,}: us per member (median)")
        for k, v in res.items():
            print(f"  {k:40s} {v:6.3f}")
        print(f"  {'the kernels, one step':40s} {kern:6.3f}")
        print(f"  {'compiled / NumPy step':40s} {res['bank step, compiled'] / res['bank step, NumPy']:6.3f}")


if __name__ == "__main__":
    main()
