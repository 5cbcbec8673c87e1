r"""The linear algebra the filters share: Cholesky or fail with the step, PD repair,
Gaussian log-densities, and noise covariances factored once (singular ones included).

A Gaussian log-density is evaluated through a lower Cholesky factor :math:`L`
(:math:`M = L L^T`), never an inverse:

.. math::
    \log N(d; 0, M) = -\tfrac12 |L^{-1} d|^2 - \sum_j \log L_{jj} - \tfrac k2 \log 2\pi .

A *singular* noise covariance (rank :math:`r < n`, e.g. filterpy's
``Q_discrete_white_noise``) has a density only on its support, the range of :math:`M`.
:class:`NoiseFactor` writes :math:`M = G G^T` with :math:`G = V_r \Lambda_r^{1/2}`
(``(n, r)``, from the eigenvalues above ``1e-12`` times the largest); a residual on the
support has the coordinates :math:`v = G^+ d` and the density
:math:`\log N(v; 0, I_r) - \sum \log \Lambda_r^{1/2}` (with respect to the Lebesgue
measure on the support), and a residual off the support is an error naming the step.

>>> import numpy as np
>>> f = NoiseFactor(np.diag([4.0, 0.0]), "Q")
>>> f.rank, f.full_rank
(1, False)
>>> round(float(f.logpdf(np.array([[2.0, 0.0]]))[0]), 6)     # log N(2; 0, 4)
-2.112086
>>> f.logpdf(np.array([[0.0, 1.0]]), step=3)
Traceback (most recent call last):
...
filterwnn._validation.NumericalError: a particle lies off the support of the singular Q at step 3 (particle 0: residual 1 outside its range)
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import solve_triangular
from scipy.linalg.lapack import dpotrf

from ._validation import NumericalError, cholesky_lower

__all__ = [
    "LOG_2PI",
    "STAIRCASE_LOOP_ABOVE_N",
    "COLUMNS_MAX_N",
    "COLUMNS_MIN_STACK",
    "cholesky",
    "cholesky_columns",
    "cholesky_lower",
    "cholesky_lower_raw",
    "columns_layout",
    "first_not_pd",
    "not_pd_error",
    "smallest_eigenvalue",
    "solve_lower_columns",
    "repair_pd",
    "insert_state",
    "gaussian_logpdf_chol",
    "NoiseFactor",
    "staircase_apply",
    "staircase_sigma_points",
    "staircase_transpose_apply",
    "symmetric_sigma_points",
]

#: Stacked staircase products (minimal skew, spherical simplex points) switch from one
#: vectorised NumPy expression (less Python overhead) to an O(n^2) row recursion above
#: this state size (the one gate for :func:`staircase_sigma_points` and
#: :func:`staircase_transpose_apply`).
STAIRCASE_LOOP_ABOVE_N = 16

LOG_2PI = float(np.log(2.0 * np.pi))

#: Stacks of small matrices are factored "by columns" (:func:`cholesky_columns`: the member
#: axis last, each entry one vector operation over the whole stack) when the matrices are
#: at most ``COLUMNS_MAX_N`` wide and the stack holds at least ``COLUMNS_MIN_STACK`` of them;
#: else by LAPACK (``numpy.linalg.cholesky``, one call per matrix inside NumPy). Chosen by
#: timing both paths in turn (``benchmarks/bench_columns.py``, 1 BLAS thread, two runs in
#: ``bench_columns_results.txt``): a bank's unscented step took 0.82-0.99x the LAPACK path's
#: time at N = 256 for n <= 8 (0.89-0.99x at N = 128 in the second run, 0.94-1.08x in the
#: first); at n = 12 it gains only from N = 512-1,000, at n = 16 little or nothing. The
#: factor alone pays from N = 256-512 (1.14-1.37x LAPACK's time at N = 256 in run 2), so the
#: gate is set for the step, its main user. The column code costs about 5 NumPy calls per
#: column: it wins once the stack pays for them and n keeps them few.
COLUMNS_MAX_N = 8
COLUMNS_MIN_STACK = 256


def columns_layout(N, n):
    """True when a stack of ``N`` matrices ``(n, n)`` is factored by columns (see
    :data:`COLUMNS_MAX_N`, :data:`COLUMNS_MIN_STACK`)."""
    return n <= COLUMNS_MAX_N and N >= COLUMNS_MIN_STACK


def cholesky_columns(A):
    r"""Lower Cholesky factors of a stack stored member axis last, ``A (n, n, N)`` -> ``(L, ok)``.

    Column :math:`j` for every member at once (Crout order):
    :math:`r_i = A_{ij} - \sum_{k<j} L_{ik} L_{jk}` for :math:`i \ge j`,
    :math:`L_{jj} = \sqrt{r_j}`, :math:`L_{ij} = r_i / L_{jj}`: a few vector operations of
    length ``N`` per column. Only the lower triangle of ``A`` is read, as LAPACK's.

    Returns
    -------
    L : ndarray of shape (n, n, N)
        Zero above the diagonal.
    ok : ndarray of bool, shape (N,)
        False for a member whose pivot was not positive and finite (not PD, or NaN or
        infinite entries, the rule of ``numpy.linalg.cholesky`` with the finiteness check
        of :func:`cholesky_lower`); its column of ``L`` is then meaningless.

    >>> A = np.stack([np.array([[4.0, 2.0], [2.0, 5.0]]), np.diag([1.0, -1.0])], axis=-1)
    >>> L, ok = cholesky_columns(A)
    >>> L[:, :, 0].tolist(), ok.tolist()
    ([[2.0, 0.0], [1.0, 2.0]], [True, False])
    """
    L, d = _columns_factor(A)
    return L, ((d > 0) & (d < np.inf)).all(axis=0)


def _columns_factor(A, out=None):
    """:func:`cholesky_columns`' factor ``L (n, n, N)`` and a view of its diagonals ``(n, N)``
    (every pivot positive and finite: the whole stack is PD). ``out``, when given, is a
    zeroed ``(n, n, N)`` array (or view) that receives ``L``."""
    n = A.shape[0]
    L = np.zeros(A.shape) if out is None else out
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for j in range(n):
            if j:  # the products summed over k in order, as (L[j:, :j] * L[j, :j]).sum(axis=1), without the temporary
                r = np.einsum("ikb,kb->ib", L[j:, :j], L[j, :j])
                np.subtract(A[j:, j], r, out=r)
            else:
                r = A[:, 0]
            np.sqrt(r[0], out=L[j, j])
            if j < n - 1:
                np.divide(r[1:], L[j, j], out=L[j + 1 :, j])
    return L, L.diagonal(0, 0, 1).T  # the diagonals, (n, N), a view


def solve_lower_columns(L, B):
    """``L^{-1} B`` for lower factors stored member axis last, ``L (n, n, N)``, ``B (n, m, N)``.

    Forward substitution, one row of every member's system per step; ``L`` is taken to
    be a valid factor (from :func:`cholesky_columns` with every member ``ok``).
    """
    n = L.shape[0]
    X = np.empty(B.shape)
    for j in range(n):
        r = B[j] - (L[j, :j, None] * X[:j]).sum(axis=0) if j else B[0]
        np.divide(r, L[j, j], out=X[j])
    return X


def first_not_pd(P):
    """Index of the first matrix of the stack ``P (N, n, n)`` that is not PD (None if all are)."""
    if P.ndim < 3:
        return None
    for i in range(P.shape[0]):
        if cholesky_lower(P[i]) is None:
            return i
    return None


def smallest_eigenvalue(M):
    """Smallest eigenvalue of the symmetric part of the square matrix ``M``.

    None if it fails or if ``M`` holds a NaN or an infinity (no eigenvalue means anything then).
    """
    if not np.isfinite(M).all():
        return None
    try:
        return float(np.linalg.eigvalsh(0.5 * (M + np.swapaxes(M, -1, -2))).min())
    except (np.linalg.LinAlgError, ValueError):
        return None


def not_pd_error(name, P, step=None, remedy=None):
    """The :class:`NumericalError` for a matrix ``P`` (or stack) that is not positive definite.

    The message names the matrix, the step, the first failing particle of a stack, the
    smallest eigenvalue of a single matrix (or, where it holds a NaN or an infinity, the
    first such entry instead), and the remedy when one is given.

    >>> print(not_pd_error("P", np.array([[1.0, 0.0], [0.0, np.nan]]), step=4))
    P is not positive definite at step 4; P[1, 1] is nan
    """
    msg = f"{name} is not positive definite"
    if step is not None:
        msg += f" at step {step}"
    bad = first_not_pd(P)
    if bad is not None:
        msg += f" (particle {bad})"
    if P.ndim == 2:
        ev = smallest_eigenvalue(P)
        if ev is not None:
            msg += f"; smallest eigenvalue {ev:.3g}"
        elif not np.isfinite(P).all():
            i, j = np.argwhere(~np.isfinite(P))[0]
            msg += f"; {name}[{i}, {j}] is {P[i, j]}"
    if remedy:
        msg += f"; {remedy}"
    return NumericalError(msg, matrix=name, step=step)


def cholesky(P, name, step=None, remedy=None, out=None):
    """Stacked lower Cholesky factors of ``P (..., n, n)``, or :class:`NumericalError`.

    The error (:func:`not_pd_error`) names the matrix, the step, the first failing
    particle and the ``remedy``. A broadcast stack (one matrix repeated, stride 0) is
    factored once. A stack of small matrices (:func:`columns_layout`) is factored by
    :func:`cholesky_columns`; the factors are then returned as a view
    ``L.transpose(2, 0, 1)`` of its member-axis-last array, whose ``transpose(1, 2, 0)`` is
    that array again (no copy for a caller that works by columns). ``out`` (a zeroed
    ``(n, n, N)`` array or view, for a stack ``P (N, n, n)`` on that path) receives that
    array, so that a caller which stores the factors beside other columns copies nothing.

    >>> cholesky(np.diag([4.0, 9.0]), "P")
    array([[2., 0.],
           [0., 3.]])
    >>> cholesky(np.diag([1.0, -1.0]), "P", step=2, remedy="make P positive definite")
    Traceback (most recent call last):
    ...
    filterwnn._validation.NumericalError: P is not positive definite at step 2; smallest eigenvalue -1; make P positive definite
    """
    if P.ndim == 3 and P.shape[0] > 1 and P.strides[0] == 0:
        L = np.broadcast_to(cholesky(P[:1], name, step, remedy), P.shape)
        if out is None:
            return L
        out[...] = L.transpose(1, 2, 0)
        return out.transpose(2, 0, 1)
    if P.ndim == 3 and columns_layout(P.shape[0], P.shape[1]):
        Lc, d = _columns_factor(P.transpose(1, 2, 0), out)  # read in place: each entry once
        if not (d.min() > 0 and d.max() < np.inf):  # two reductions for the stack (NaN fails both)
            raise not_pd_error(name, P, step, remedy)
        return Lc.transpose(2, 0, 1)
    L = cholesky_lower(P)
    if L is None:
        raise not_pd_error(name, P, step, remedy)
    return L


def cholesky_lower_raw(P, name, step=None, remedy=None):
    """LAPACK's lower Cholesky factor of one ``(n, n)`` ``P``, uncleaned, or :class:`NumericalError`.

    One ``dpotrf`` call: numpy's ``cholesky`` and scipy's ``clean=True`` then zero the
    strict upper triangle, a strided pass that at n = 160 costs about as much as the
    factorisation. Here it is left as it was: the result (F-ordered) holds ``L`` in its
    lower triangle and ``P``'s entries above it, so read its lower triangle only (its
    ``.T`` is the upper factor in C order, to be read above the diagonal).

    LAPACK stops at a non-positive pivot but lets a NaN through. Every entry of row ``i``
    enters the pivot as a square (``L_ii^2 = P_ii - sum_k L_ik^2``), so a NaN or an
    infinity anywhere in ``L`` stops the factorisation or makes a pivot NaN: checking the
    diagonal checks the factor, in O(n), here by its trace (each pivot is positive and at most
    ``sqrt`` of the largest float, so the sum is finite exactly when every pivot is). The
    error is :func:`cholesky`'s.

    >>> L = cholesky_lower_raw(np.array([[4.0, 2.0], [2.0, 5.0]]), "P")
    >>> np.tril(L)
    array([[2., 0.],
           [1., 2.]])
    """
    L, info = dpotrf(P, lower=1, clean=0)
    if info != 0 or not math.isfinite(L.trace()):
        raise not_pd_error(name, np.asarray(P, dtype=float), step, remedy)
    return L


def repair_pd(C):
    """Copy of the stack ``C (N, n, n)`` with every non-PD matrix's eigenvalues clipped to
    ``1e-12`` times the largest. Returns the repaired stack and the number changed."""
    C = np.array(C, dtype=float)
    n_bad = 0
    for i in range(C.shape[0]):
        try:
            np.linalg.cholesky(C[i])
            if np.all(np.isfinite(C[i])):
                continue
        except np.linalg.LinAlgError:
            pass
        M = 0.5 * (C[i] + C[i].T)
        M[~np.isfinite(M)] = 0.0
        ev, V = np.linalg.eigh(M)
        floor = 1e-12 * max(np.max(np.abs(ev)), np.finfo(float).tiny)
        C[i] = (V * np.maximum(ev, floor)) @ V.T
        C[i] = 0.5 * (C[i] + C[i].T)
        n_bad += 1
    return C, n_bad


def insert_state(x, P, index, value, var, cross=None):
    """A Gaussian ``(x, P)`` with one more state at row ``index``: mean ``value``, variance ``var``, and
    covariance ``cross`` ``(n,)`` with the others (default 0). Returns the new ``(x, P)``.

    >>> x, P = insert_state(np.zeros(2), np.eye(2), 1, 5.0, 4.0, cross=np.array([0.5, 0.0]))
    >>> x.tolist(), P[1].tolist()
    ([0.0, 5.0, 0.0], [0.5, 4.0, 0.0])
    """
    n = len(x) + 1
    keep = np.delete(np.arange(n), index)
    out = np.zeros((n, n))
    out[np.ix_(keep, keep)] = P
    if cross is not None:
        out[keep, index] = out[index, keep] = cross
    out[index, index] = var
    return np.insert(x, index, value), out


def gaussian_logpdf_chol(d, L, half_logdet=None):
    """``log N(d_i; 0, L L^T)`` for the rows of ``d (m, k)`` and one lower factor ``L (k, k)``.

    ``half_logdet``, when given, is ``np.sum(np.log(np.diag(L)))`` computed once (a factor
    kept across steps, :class:`NoiseFactor`): the same number, not recomputed per call.
    """
    k = d.shape[1]
    if k == 1:
        e2 = d[:, 0] / L[0, 0]
        np.square(e2, out=e2)
    else:
        e = solve_triangular(L, d.T, lower=True, check_finite=False)
        e2 = np.sum(e * e, axis=0)
    if half_logdet is None:
        half_logdet = np.sum(np.log(np.diag(L)))
    # -0.5 * e2 - half_logdet - 0.5 * k * LOG_2PI, the same operations in place on e2 (a fresh array)
    e2 *= -0.5
    e2 -= half_logdet
    e2 -= 0.5 * k * LOG_2PI
    return e2


class NoiseFactor:
    """A noise covariance factored once: Cholesky when PD, else its support.

    Parameters
    ----------
    M : ndarray of shape (n, n)
        Symmetric positive semi-definite.
    name : str
        For error messages (``"Q"``, ``"R"``).

    Attributes
    ----------
    matrix : ndarray of shape (n, n)
    rank : int
    full_rank : bool
    L : ndarray of shape (n, n) or None
        Lower Cholesky factor when full rank.
    sqrt : ndarray of shape (n, n)
        A square root, ``sqrt @ sqrt.T = M`` (the Cholesky factor, or eigenvectors
        scaled by the square roots of the clipped eigenvalues).
    G : ndarray of shape (n, rank)
        The non-zero columns of the eigen square root (the noise-space map).
    """

    def __init__(self, M, name):
        M = np.array(M, dtype=float)
        self.matrix, self.name = M, name
        n = M.shape[0]
        self.L = cholesky_lower(M)
        if self.L is not None:
            self.rank, self.full_rank, self.sqrt, self.G = n, True, self.L, self.L
            self._half_logdet = np.sum(np.log(np.diag(self.L)))
            return
        ev, V = np.linalg.eigh(0.5 * (M + M.T))
        top = max(float(ev.max()), 0.0)
        if ev.min() < -1e-10 * max(top, 1e-300):
            raise ValueError(
                f"{name} must be positive semi-definite, smallest eigenvalue {ev.min():.3g} "
                f"(build it as G @ G.T, e.g. filterpy's Q_discrete_white_noise)"
            )
        keep = ev > 1e-12 * top if top > 0 else np.zeros(n, dtype=bool)
        self.full_rank = False
        self.rank = int(keep.sum())
        self.sqrt = V * np.sqrt(np.clip(ev, 0.0, None))
        self.G = V[:, keep] * np.sqrt(ev[keep])
        self._V = V[:, keep]
        self._sd = np.sqrt(ev[keep])
        self._scale = np.sqrt(top) if top > 0 else 1.0

    def logpdf(self, d, step=None):
        """``log N(d_i; 0, M)`` for the rows of ``d (m, n)``, on ``M``'s support when singular.

        Raises :class:`NumericalError` naming the step when a row lies off the support.
        """
        if self.full_rank:
            return gaussian_logpdf_chol(d, self.L, getattr(self, "_half_logdet", None))  # (older pickles)
        c = d @ self._V  # (m, r) coordinates on the support
        off = d - c @ self._V.T
        off_norm = np.sqrt(np.sum(off * off, axis=1))
        tol = 1e-6 * (self._scale + np.sqrt(np.sum(d * d, axis=1)))
        if np.any(off_norm > tol):
            bad = int(np.argmax(off_norm > tol))
            where = f" at step {step}" if step is not None else ""
            raise NumericalError(
                f"a particle lies off the support of the singular {self.name}{where} "
                f"(particle {bad}: residual {off_norm[bad]:.3g} outside its range)",
                matrix=self.name,
                step=step,
            )
        e = c / self._sd
        return -0.5 * np.sum(e * e, axis=1) - np.sum(np.log(self._sd)) - 0.5 * self.rank * LOG_2PI


# ---------------------------------------------------------------------------
# Structured sigma-point products: Z @ U and Z^T B in O(n^2), never a dense product
# ---------------------------------------------------------------------------


def staircase_apply(a, b, U):
    """``Z @ U`` for a staircase set, in O(n^2), stacked over leading axes of ``U``.

    The staircase unit points ``Z`` (``(n + 2, n)``: row 0 zero, ``Z[1:j+1, j-1] = a[j-1]``,
    ``Z[j+1, j-1] = b[j-1]``) are never formed: row ``i >= 1`` of ``Z @ U`` is
    ``b[i-2] U[i-2] + sum_{j >= i} a[j-1] U[j-1]``.
    """
    n = a.size
    V = a[:, None] * U  # (..., n, n): a_j * row j of U
    # suffix sums S[k] = sum_{m >= k} V[m], k = 0..n-1
    S = np.flip(np.cumsum(np.flip(V, axis=-2), axis=-2), axis=-2)
    D = np.zeros(U.shape[:-2] + (n + 2, n))
    D[..., 1 : n + 1, :] = S
    D[..., 2:, :] += b[:, None] * U
    return D


def staircase_sigma_points(a, b, x, U):
    """``x_i + Z @ U_i`` for a staircase set, ``x (N, n)``, ``U (N, n, n)`` -> ``(N, n + 2, n)``.

    Up to :data:`STAIRCASE_LOOP_ABOVE_N` dimensions the stacked reverse ``cumsum`` of
    :func:`staircase_apply`; above, the suffix sums accumulated row by row in an
    ``(N, n)`` buffer (about half the time of the stacked ``cumsum`` there).
    """
    N, n = x.shape
    if n <= STAIRCASE_LOOP_ABOVE_N:
        sig = staircase_apply(a, b, U)
        sig += x[:, None, :]
        return sig
    U = np.ascontiguousarray(U)  # rows of U are read one by one below
    sig = np.empty((N, n + 2, n))
    sig[:, 0] = x
    acc = np.zeros((N, n))
    tmp = np.empty((N, n))
    for i in range(n, 0, -1):
        # row i: sum_{m >= i-1} a_m U_m  (+ b_{i-2} U_{i-2} for i >= 2)
        np.multiply(U[:, i - 1], a[i - 1], out=tmp)
        acc += tmp
        np.add(x, acc, out=sig[:, i])
        if i >= 2:
            np.multiply(U[:, i - 2], b[i - 2], out=tmp)
            sig[:, i] += tmp
    np.multiply(U[:, n - 1], b[n - 1], out=tmp)
    np.add(x, tmp, out=sig[:, n + 1])
    return sig


def staircase_transpose_apply(a, b, Z, B):
    """``Z^T B`` for staircase unit points ``Z (n + 2, n)`` and ``B (N, n + 2, m)`` -> ``(N, n, m)``.

    Above :data:`STAIRCASE_LOOP_ABOVE_N` dimensions a prefix sum in O(n m) per particle,
    ``(Z^T B)_j = a_j sum_{i=1..j+1} B_i + b_j B_{j+2}``; up to it the dense product
    (within about 20 % of the prefix sum there, with less Python overhead).
    """
    n = a.size
    if n <= STAIRCASE_LOOP_ABOVE_N:
        return np.matmul(Z.T, B)
    C = np.cumsum(B[:, 1 : n + 1, :], axis=1)
    return a[:, None] * C + b[:, None] * B[:, 2 : n + 2, :]


def symmetric_sigma_points(c, x, U):
    """``x_i + [0, c U_i, -c U_i]`` for ``x (N, n)``, ``U (N, n, n)`` -> ``(N, 2n + 1, n)``.

    Three passes over the output (filterpy's Merwe and Julier sets, ``Z = [0, c I, -c I]``).
    """
    N, n = x.shape
    sig = np.empty((N, 2 * n + 1, n))
    sig[:, 0] = x
    plus = sig[:, 1 : n + 1]
    np.multiply(U, c, out=plus)
    np.subtract(x[:, None, :], plus, out=sig[:, n + 1 :])
    plus += x[:, None, :]
    return sig
