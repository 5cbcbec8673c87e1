"""Stop 72's prototype (not shipped): for each gap of 30 s or more in the fixes, the fixes SETTLE-WIN s after its exit
are fitted with the dead reckoning's errors (the drag test's columns COLS) and the fixes before SETTLE tested against
that fit extrapolated back: the run of fixes from the exit on each past 3 sigmas (with the fit's leverage), and an F-test
of that run over the residuals' integrated autocorrelation. See ``null.py`` and ``summary.txt``."""
import numpy as np
from scipy.stats import f as f_dist
from filterwnn.navigation import _plausibility as P
from filterwnn.navigation._plausibility import _drag_columns, _drag_fit, _DRAG_ITERATIONS
from filterwnn.metrics import integrated_autocorrelation

import os
EXIT_GAP_S, EXIT_SETTLE_S, EXIT_WINDOW_S, EXIT_SIGMAS, EXIT_MIN_RUN, EXIT_MIN_REF = 30.0, float(os.environ.get('SETTLE', 30)), float(os.environ.get('WIN', 150)), 3.0, 3, 20

def prepared(dt, h, step, at, z, idx, within, cols):
    n = len(idx)
    corr = np.zeros(int(at[idx[-1]] - at[idx[0]]))
    keep = within.copy()
    cols = list(cols)
    for i in range(_DRAG_ITERATIONS + 3):
        base, track, funcs = _drag_columns(dt, h, step, at, idx, corr)
        base = base[:, cols]
        y = np.r_[z[idx, 0], z[idx, 1]] - track
        if i < 2:
            coef = _drag_fit(base[:, [cols.index(c) for c in (0, 1, 2, 4)]], y, keep)[0]
            corr = corr + np.arctan2(coef[3], 1.0 + coef[2]); continue
        coef, res = _drag_fit(base, y, keep)
        r = np.hypot(res[:n], res[n:])
        keep = (r <= max(3.0 * 1.4826 * float(np.median(r[keep])), 1.0)) & within
        corr = corr + np.arctan2(coef[cols.index(4)], 1.0 + coef[2]) + sum(coef[cols.index(c)] * funcs[c - 4] for c in cols if c > 4)
    return base, y, keep

COLS = [int(c) for c in os.environ.get('COLS', '0,1,2,4,5').split(',')]
def exits(dt, heading, step, steps, z_gps, detail=False):
    h = np.unwrap(np.asarray(heading, float)); step = np.asarray(step, float)
    at = np.asarray(steps, int) + 1; z = np.asarray(z_gps, float); tf = at * dt
    out = []
    gaps = np.flatnonzero(np.diff(tf) >= EXIT_GAP_S) + 1
    for j in gaps:
        nxt = gaps[gaps > j]
        end = min(tf[j] + EXIT_WINDOW_S, tf[nxt[0]] if len(nxt) else np.inf)
        idx = np.flatnonzero((tf >= tf[j]) & (tf < end))
        within = tf[idx] >= tf[j] + EXIT_SETTLE_S
        if within.sum() < EXIT_MIN_REF or at[idx[-1]] <= at[idx[0]]:
            continue
        base, y, keep = prepared(dt, h, step, at, z, idx, within, COLS)
        n = len(idx); kk = np.r_[keep, keep]; m = int(keep.sum())
        if m < EXIT_MIN_REF: continue
        X = base[kk]; coef = np.linalg.lstsq(X, y[kk], rcond=None)[0]
        res = y - base @ coef
        dof = 2 * m - X.shape[1]
        rk = res[kk]; s2 = float(rk @ rk) / dof
        c = max(integrated_autocorrelation(list(np.stack([res[:n][keep], res[n:][keep]], axis=1))), 1.0)
        sc = np.linalg.norm(X, axis=0); sc[sc == 0] = 1.0
        if np.linalg.cond(X / sc) > 1e6: continue
        G = np.linalg.inv(X.T @ X)
        lev = np.einsum("ij,jk,ik->i", base, G, base)
        lev2 = 0.5 * (lev[:n] + lev[n:])
        d2 = (res[:n] ** 2 + res[n:] ** 2) / (s2 * (1 + lev2))
        early = np.flatnonzero(~within)
        run = 0
        for i in early:
            if d2[i] > EXIT_SIGMAS ** 2: run += 1
            else: break
        T = float(np.sum(d2[early[:max(run,1)]]))
        k = max(run, 1)
        p = float(f_dist.sf(T / (2 * k) / c, max(2 * k / c, 1.0), max(dof / c, 1.0)))
        ue = res[:n][early[:k]]; un = res[n:][early[:k]]
        L = np.hypot(ue, un)
        coh = float(np.hypot(np.sum(ue / L), np.sum(un / L)) / k)
        if detail: print(np.round(np.sqrt(d2[early[:15]]),1), np.round(np.hypot(res[:n],res[n:])[early[:15]],1))
        out.append((tf[j - 1], tf[j], tf[idx[early[k - 1]]], run, float(L.max()), float(np.sqrt(s2)), c, coh, p))
    return out
