"""Where one bank step goes at B = 1,000 (issue 25): stages, fixed cost, calls, page faults.

``bench_peers.py``'s bank (6-state UKF, Merwe points, ``dim_z = 3``, the column path of
``filterwnn._linalg.columns_layout``). Prints, CPU clock (``time.process_time`` per block of
steps; ``perf_counter`` inside a step), medians:

1. the step's stages: a copy of ``UnscentedStep.predict`` / ``_update`` / ``finish_update``
   (column path) with a timer after each stage, checked bit for bit against the bank's own
   ``predict``/``update`` from the same state first (so the copy is the code timed);
2. the fixed cost a step pays whatever B (the same column path at B = 16, its gate lowered)
   and, at B = 256, 1,000 and 4,000, the step, its cost per member and the fixed part's share;
3. Python-level and C-level calls a step (``sys.setprofile``; NumPy ufuncs are not counted)
   and minor page faults a step when the bank steps alone.

    python benchmarks/bank_work/step_profile.py [--reps 300]
"""

from __future__ import annotations

import argparse
import resource
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))  # this checkout's filterwnn
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402
from bench_peers import _bank, _six  # noqa: E402

from filterwnn._linalg import LOG_2PI, cholesky, solve_lower_columns  # noqa: E402
from filterwnn.kalman import batched as bt  # noqa: E402


def staged_step(bank, z, mark):
    """One predict + update of ``bank`` by main's column-path arithmetic, ``mark(name)`` after
    each stage; returns ``(x, P, log_likelihood)`` without touching the bank."""
    st, model = bank._step, bank._model
    x, P, Q, R = bank._x, bank._P, bank._Q, bank._R
    N, n = x.shape
    m, Wm, Wc = model.dim_z, st.points.Wm, st.points.Wc
    for stage in ("p", "u"):
        Lx = np.zeros((n, n + 1, N))
        L = cholesky(P, "P", 1, out=Lx[:, :n])
        mark(f"{stage}.cholesky")
        Lx[:, n] = x.T
        sig = np.matmul(Lx.transpose(0, 2, 1), st._Zx).transpose(1, 2, 0)
        S_ = sig.shape[1]
        mark(f"{stage}.sigma points")
        f, d, args = (model.fx, n, (model.dt,)) if stage == "p" else (model.hx, m, ())
        Y = bt.apply_rows(f, sig.reshape(N * S_, n), d, True, "fx" if stage == "p" else "hx", args, {},
                          model.rows_checked).reshape(N, S_, d)
        del sig
        mark(f"{stage}.{'fx' if stage == 'p' else 'hx'}")
        mean = bt._weighted_mean(None, Y, Wm)
        mark(f"{stage}.mean")
        dY = bt._residual(None, Y, mean[:, None, :], True)
        del Y
        mark(f"{stage}.residual")
        WdY = bt._times_weights(dY, Wc)
        C = np.matmul(np.swapaxes(WdY if stage == "p" else dY, -1, -2), dY if stage == "p" else WdY)
        mark(f"{stage}.{'P_pred' if stage == 'p' else 'S'} product")
        if stage == "p":
            C += Q
            P = C + np.swapaxes(C, -1, -2)
            P *= 0.5
            x = mean
            mark("p.symmetrise")
            bank._check_finite(x, P, "predict", 1, "")
            mark("p.finite check")
    LinvPxy = bt.unit_transpose_apply(st.points, st._Z, WdY)
    Pxy, rhs = bt._cross_columns(L, LinvPxy)
    mark("u.P_xy")
    S = C + R
    y = bt._residual(None, bt._as_z(z, N, m), mean, True)
    Ls = cholesky(S, "S", 1)
    mark("u.cholesky of S")
    rhs[:, n] = y.T
    E = solve_lower_columns(Ls.transpose(1, 2, 0), rhs)
    G, e = E[:, :n], E[:, n]
    mark("u.solve")
    xn = x + np.einsum("kib,kb->ib", G, e).T
    GtG = G[0, :, None] * G[0]
    for k in range(1, m):
        GtG += G[k, :, None] * G[k]
    Pn = P - GtG.transpose(2, 0, 1)
    mark("u.x, P")
    log_det = np.sum(np.log(np.diagonal(Ls, axis1=1, axis2=2)), axis=1)
    ll = -0.5 * np.sum(e * e, axis=0) - log_det - 0.5 * m * LOG_2PI
    bank._check_finite(xn, Pn, "update", 1, "")
    mark("u.log-likelihood, finite check")
    return xn, Pn, ll


def stages(B, reps):
    """Median us a step of each stage (and the sum), after a bit-for-bit check of the copy."""
    prob, x, z = _six(B)
    bank = _bank(prob, x)
    for _ in range(5):
        bank.predict()
        bank.update(z)
    got = staged_step(bank, z, lambda name: None)
    bank.predict()
    bank.update(z)
    same = all(np.array_equal(a, b) for a, b in zip(got, (bank._x, bank._P, bank.log_likelihood)))
    times = {}
    for _ in range(reps):
        last = [time.perf_counter()]

        def mark(name):
            t = time.perf_counter()
            times.setdefault(name, []).append(t - last[0])
            last[0] = t

        staged_step(bank, z, mark)
    return same, {k: float(np.median(v)) * 1e6 for k, v in times.items()}


def step_time(B, reps):
    """Median CPU us of one bank step (blocks of steps, ``time.process_time``)."""
    prob, x, z = _six(B)
    bank = _bank(prob, x)
    k = max(1, 4000 // B)
    ts = []
    for r in range(reps + 3):
        t0 = time.process_time()
        for _ in range(k):
            bank.predict()
            bank.update(z)
        if r >= 3:
            ts.append((time.process_time() - t0) / k)
    return float(np.median(ts)) * 1e6


def fixed_cost(reps):
    """Median CPU us of a step at B = 16 on the column path (its gate lowered for the call)."""
    from filterwnn import _linalg

    gate = _linalg.COLUMNS_MIN_STACK
    _linalg.COLUMNS_MIN_STACK = 1
    try:
        return step_time(16, reps)
    finally:
        _linalg.COLUMNS_MIN_STACK = gate


def calls_and_faults(B, steps=200):
    """Python/C calls a step (``sys.setprofile``) and minor page faults a step (alone)."""
    prob, x, z = _six(B)
    bank = _bank(prob, x)
    for _ in range(20):
        bank.predict()
        bank.update(z)
    n = [0]

    def count(frame, event, arg):
        n[0] += event in ("call", "c_call")

    sys.setprofile(count)
    bank.predict()
    bank.update(z)
    sys.setprofile(None)
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    for _ in range(steps):
        bank.predict()
        bank.update(z)
    return n[0] - 1, (resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0) / steps


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=300)
    a = ap.parse_args(argv)
    same, st = stages(1000, a.reps)
    print(f"stages of one step at B = 1,000 (median us; the copy equals the bank's step bit for bit: {same})")
    total = sum(st.values())
    for k, v in st.items():
        print(f"  {k:34s} {v:8.1f}  {100 * v / total:5.1f} %")
    print(f"  {'sum':34s} {total:8.1f}")
    fixed = fixed_cost(max(200, a.reps))
    print(f"the same path at B = 16 (columns_layout's gate lowered): {fixed:.0f} us a step, the cost a step pays "
          f"whatever B (Python and NumPy's per-call set-up, the model's calls)")
    for B in (256, 1000, 4000):
        t = step_time(B, max(20, a.reps // 10))
        print(f"B = {B:,}: {t:.0f} us a step, {t / B:.2f} us a member; less the B = 16 cost "
              f"{(t - fixed) / B:.2f} us a member ({100 * fixed / t:.0f} % of the step is the fixed cost)")
    calls, faults = calls_and_faults(1000)
    print(f"B = 1,000: {calls} Python/C calls a step (ufuncs not counted), {faults:.1f} minor page faults a step alone")


if __name__ == "__main__":
    main()
