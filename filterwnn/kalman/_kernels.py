"""The compiled kernels of :mod:`filterwnn.kalman._compiled` (imports numba: load it through
``_compiled.kernels()``).

Defined at module level, not in a closure, so that numba's on-disk cache (``cache=True``)
finds them again in a new process; imported through ``_compiled.kernels()``, which places that
cache in ``_compiled.cache_dir()``.
"""

import math

import numba
import numpy as np

from ._compiled import BLOCK as BS

HALF_LOG_2PI = 0.5 * math.log(2.0 * math.pi)

_jit = numba.njit(cache=True, nogil=True, error_model="numpy")
_inline = numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")


@_inline
def factor_block(A, L, b0, mb):
    """Lower Cholesky factors of a block stored member axis last: ``A (n, n, >= mb)`` (the
    lower triangle read) -> ``L[:, :, b0:b0 + mb]`` (zero above the diagonal). Returns -1,
    or the block's first member whose pivot was not positive and finite."""
    n = A.shape[0]
    r = np.empty(mb)
    for j in range(n):
        for i in range(j, n):  # r = A_ij - sum_p L_ip L_jp; the pivot first (i == j), then the column
            for k in range(mb):
                r[k] = A[i, j, k]
            for p in range(j):
                for k in range(mb):
                    r[k] -= L[i, p, b0 + k] * L[j, p, b0 + k]
            if i == j:
                for k in range(mb):
                    v = r[k]
                    if not (v > 0.0 and v < np.inf):
                        return k
                    L[j, j, b0 + k] = math.sqrt(v)
            else:
                for k in range(mb):
                    L[i, j, b0 + k] = r[k] / L[j, j, b0 + k]
        for i in range(j):
            for k in range(mb):
                L[i, j, b0 + k] = 0.0
    return -1

@_inline
def gather_block(F, b0, mb, i, D):
    """Component ``i`` of the block's points, ``F[b0:b0 + mb, :, i]`` -> ``D[i] (S, >= mb)``."""
    S = F.shape[1]
    for k in range(mb):
        for s in range(S):
            D[i, s, k] = F[b0 + k, s, i]


@_inline
def centre_block(F, b0, mb, i, W, D, mu, mean):
    """Component ``i`` of the block's points ``F[b0:b0 + mb, :, i]`` -> ``D[i] (S, >= mb)``
    less its weighted mean (``W``; summed in the scratch ``mu``), which goes to
    ``mean[b0:b0 + mb, i]``."""
    S = F.shape[1]
    gather_block(F, b0, mb, i, D)
    for k in range(mb):
        mu[k] = 0.0
    for s in range(S):
        w = W[s]
        for k in range(mb):
            mu[k] += w * D[i, s, k]
    for k in range(mb):
        mean[b0 + k, i] = mu[k]
    for s in range(S):
        for k in range(mb):
            D[i, s, k] -= mu[k]


@_inline
def deviations_block(F, b0, mb, W, D, mu, mean, centred):
    """Every component of the block's points -> ``D (d, S, >= mb)``: their deviations from
    the weighted mean (``W``; written to ``mean``), or, ``centred``, the deviations ``F``
    already holds (the user's mean and residual functions gave them)."""
    for i in range(F.shape[2]):
        if centred:
            gather_block(F, b0, mb, i, D)
        else:
            centre_block(F, b0, mb, i, W, D, mu, mean)


@_inline
def covariance_block(D, W, noise, b0, mb, acc, out, low):
    """``sum_s W_s D_s D_s^T + noise`` of every member of the block, exactly symmetric: the
    lower triangle computed (also kept in ``low (d, d, >= mb)``), the upper its mirror, written
    to ``out[b0:b0 + mb]``; ``noise (1 or N, d, d)``, its symmetric part added."""
    d, S = D.shape[0], D.shape[1]
    per = noise.shape[0] > 1
    for i in range(d):
        for j in range(i + 1):
            for k in range(mb):
                acc[k] = 0.0
            for s in range(S):
                w = W[s]
                for k in range(mb):
                    acc[k] += w * D[i, s, k] * D[j, s, k]
            for k in range(mb):
                q = b0 + k if per else 0
                v = acc[k] + 0.5 * (noise[q, i, j] + noise[q, j, i])
                low[i, j, k] = v
                out[b0 + k, i, j] = v
                out[b0 + k, j, i] = v


@_jit
def sigma_kernel(x, P, Z, L, sig):
    """Factors and sigma points of every member.

    ``x (N, n)``, ``P (N, n, n)`` (only the lower triangle read), unit points ``Z (S, n)``
    -> ``L (n, n, N)`` (lower factors, member axis last; zero above the diagonal) and
    ``sig (n, N, S)`` (``sig[:, b, s] = x_b + L_b Z[s]``). Returns -1, or the first member
    whose pivot was not positive and finite (``P_b`` not positive definite, or NaN).
    """
    N, n = x.shape
    S = Z.shape[0]
    A = np.empty((n, n, BS))
    X = np.empty((n, BS))
    T = np.empty((S, BS))
    for b0 in range(0, N, BS):
        m = min(BS, N - b0)
        for k in range(m):  # the block's lower triangles and means, member by member
            for i in range(n):
                X[i, k] = x[b0 + k, i]
                for j in range(i + 1):
                    A[i, j, k] = P[b0 + k, i, j]
        bad = factor_block(A, L, b0, m)
        if bad >= 0:
            return b0 + bad
        for i in range(n):
            for s in range(S):
                for k in range(m):
                    T[s, k] = X[i, k]
                for j in range(i + 1):
                    c = Z[s, j]
                    if c != 0.0:  # a zero term adds nothing: Merwe's points have one per row
                        for k in range(m):
                            T[s, k] += L[i, j, b0 + k] * c
            for k in range(m):
                for s in range(S):
                    sig[i, b0 + k, s] = T[s, k]
    return -1

@_jit
def predict_kernel(F, Wm, Wc, Q, xp, Pp, centred):
    """Weighted moments of the propagated points ``F (N, S, n)`` -> ``xp (N, n)`` and
    ``Pp (N, n, n) = sum_s Wc_s (F_s - xp)(F_s - xp)^T + Q`` (``Q (1 or N, n, n)``),
    exactly symmetric (the lower triangle computed, the upper its mirror). With ``centred``,
    ``F`` holds the deviations ``F_s - xp`` already (the user's mean and residual functions),
    and ``xp`` is not written."""
    N, S, n = F.shape
    D = np.empty((n, S, BS))
    low = np.empty((n, n, BS))
    acc = np.empty(BS)
    for b0 in range(0, N, BS):
        m = min(BS, N - b0)
        deviations_block(F, b0, m, Wm, D, acc, xp, centred)
        covariance_block(D, Wc, Q, b0, m, acc, Pp, low)

@_jit
def update_kernel(H, L, Z, xp, Pp, z, R, Wm, Wc, x, P, zp, Sz, Pxy, loglik, centred):
    """The unscented update of every member from its measured points ``H (N, S, m)``.

    ``L (n, n, N)``: the factors of ``Pp`` the points were drawn with (``sigma_kernel``);
    ``z (1 or N, m)``; ``R (1 or N, m, m)``. Writes ``x (N, n)``, ``P (N, n, n)``
    (``Pp - G^T G``, ``G = L_S^{-1} P_xy^T``, exactly symmetric), ``zp (N, m)``,
    ``Sz (N, m, m)`` (with ``R``), ``Pxy (N, n, m)`` and ``loglik (N,)``. Returns -1, or
    the first member whose ``S`` is not positive definite. With ``centred`` (the user's mean
    and residual functions), ``H`` holds the deviations ``H_s - zp``, ``zp`` is read, not
    written, and ``z`` holds the innovations ``(N, m)``.
    """
    N, S, m = H.shape
    n = xp.shape[1]
    D = np.empty((m, S, BS))
    E = np.empty((m, S, BS))
    T = np.empty((n, m, BS))
    C = np.empty((n, m, BS))
    Sl = np.empty((m, m, BS))
    Ls = np.empty((m, m, BS))
    G = np.empty((m, n, BS))
    e = np.empty((m, BS))
    r = np.empty(BS)
    ld = np.empty(BS)
    per_z = z.shape[0] > 1
    for b0 in range(0, N, BS):
        mb = min(BS, N - b0)
        # the predicted measurement, the deviations D, S = sum_s Wc_s D_s D_s^T + R and its factor
        deviations_block(H, b0, mb, Wm, D, r, zp, centred)
        covariance_block(D, Wc, R, b0, mb, r, Sz, Sl)
        bad = factor_block(Sl, Ls, 0, mb)
        if bad >= 0:
            return b0 + bad
        for k in range(mb):
            ld[k] = 0.0
        for j in range(m):
            for k in range(mb):
                ld[k] += math.log(Ls[j, j, k])
        # P_xy = L T with T = Z^T E, E = Wc D (the points' deviations are L Z^T)
        for l in range(m):
            for s in range(S):
                w = Wc[s]
                for k in range(mb):
                    E[l, s, k] = w * D[l, s, k]
        for j in range(n):
            for l in range(m):
                for k in range(mb):
                    T[j, l, k] = 0.0
                for s in range(S):
                    c = Z[s, j]
                    if c != 0.0:  # as in sigma_kernel
                        for k in range(mb):
                            T[j, l, k] += c * E[l, s, k]
        for i in range(n):
            for l in range(m):
                for k in range(mb):
                    r[k] = 0.0
                for j in range(i + 1):
                    for k in range(mb):
                        r[k] += L[i, j, b0 + k] * T[j, l, k]
                for k in range(mb):
                    C[i, l, k] = r[k]
                    Pxy[b0 + k, i, l] = r[k]
        # G = L_S^{-1} P_xy^T and e = L_S^{-1} (z - zp), row by row
        for l in range(m):
            for k in range(mb):
                r[k] = z[b0 + k, l] if centred else z[b0 + k if per_z else 0, l] - zp[b0 + k, l]
            for p in range(l):
                for k in range(mb):
                    r[k] -= Ls[l, p, k] * e[p, k]
            for k in range(mb):
                e[l, k] = r[k] / Ls[l, l, k]
            for i in range(n):
                for k in range(mb):
                    r[k] = C[i, l, k]
                for p in range(l):
                    for k in range(mb):
                        r[k] -= Ls[l, p, k] * G[p, i, k]
                for k in range(mb):
                    G[l, i, k] = r[k] / Ls[l, l, k]
        for k in range(mb):
            r[k] = 0.0
        for l in range(m):
            for k in range(mb):
                r[k] += e[l, k] * e[l, k]
        for k in range(mb):
            loglik[b0 + k] = -0.5 * r[k] - ld[k] - m * HALF_LOG_2PI
        # the posterior: x^- + G^T e and P^- - G^T G (the lower triangle, mirrored)
        for i in range(n):
            for k in range(mb):
                r[k] = xp[b0 + k, i]
            for l in range(m):
                for k in range(mb):
                    r[k] += G[l, i, k] * e[l, k]
            for k in range(mb):
                x[b0 + k, i] = r[k]
            for j in range(i + 1):
                for k in range(mb):
                    r[k] = 0.0
                for l in range(m):
                    for k in range(mb):
                        r[k] += G[l, i, k] * G[l, j, k]
                for k in range(mb):
                    v = Pp[b0 + k, i, j] - r[k]
                    P[b0 + k, i, j] = v
                    P[b0 + k, j, i] = v
    return -1
