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

import numpy as np
from scipy.linalg import solve_triangular

from ._validation import NumericalError

__all__ = ["LOG_2PI", "cholesky", "first_not_pd", "repair_pd", "gaussian_logpdf_chol", "NoiseFactor"]

LOG_2PI = float(np.log(2.0 * np.pi))


def first_not_pd(P):
    """Index of the first matrix of the stack ``P (N, n, n)`` that is not PD (None if all are)."""
    if P.ndim < 3:
        return None
    for i in range(P.shape[0]):
        try:
            Li = np.linalg.cholesky(P[i])
        except np.linalg.LinAlgError:
            return i
        if not np.all(np.isfinite(Li)):
            return i
    return None


def cholesky(P, name, step=None):
    """Stacked lower Cholesky factors of ``P (..., n, n)``, or :class:`NumericalError`.

    The error names the matrix, the step and the first failing particle. A broadcast
    stack (one matrix repeated, stride 0) is factored once.
    """
    if P.ndim == 3 and P.shape[0] > 1 and P.strides[0] == 0:
        return np.broadcast_to(cholesky(P[:1], name, step), P.shape)
    try:
        L = np.linalg.cholesky(P)
    except np.linalg.LinAlgError:
        L = None
    if L is None or not np.all(np.isfinite(L)):
        bad = first_not_pd(P)
        where = f" at step {step}" if step is not None else ""
        raise NumericalError(
            f"{name} is not positive definite{where}" + (f" (particle {bad})" if bad is not None else ""),
            matrix=name,
            step=step,
        )
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


def gaussian_logpdf_chol(d, L):
    """``log N(d_i; 0, L L^T)`` for the rows of ``d (m, k)`` and one lower factor ``L (k, k)``."""
    k = d.shape[1]
    if k == 1:
        e2 = (d[:, 0] / L[0, 0]) ** 2
    else:
        e = solve_triangular(L, d.T, lower=True, check_finite=False)
        e2 = np.sum(e * e, axis=0)
    return -0.5 * e2 - np.sum(np.log(np.diag(L))) - 0.5 * k * LOG_2PI


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
        try:
            self.L = np.linalg.cholesky(M)
            if not np.all(np.isfinite(self.L)):
                raise np.linalg.LinAlgError
        except np.linalg.LinAlgError:
            self.L = None
        if self.L is not None:
            self.rank, self.full_rank, self.sqrt, self.G = n, True, self.L, self.L
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
            return gaussian_logpdf_chol(d, self.L)
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
