"""Scores for filter output: errors, consistency (NEES/NIS) and effective sample size.

NEES (normalised estimation error squared) of an estimate ``x_hat`` with covariance ``P``
of the true state ``x`` is ``e^T P^{-1} e`` with ``e = x - x_hat``. For a consistent filter
it is chi-square distributed with ``dim_x`` degrees of freedom, so its average over ``M``
independent runs lies, with probability ``1 - alpha``, in :func:`chi2_bounds`.
NIS is the same statistic for the innovation ``y`` with covariance ``S``
(Bar-Shalom, Li and Kirubarajan 2001, sec. 5.4).

>>> import numpy as np
>>> float(nees(np.array([1.0, 0.0]), np.zeros(2), np.eye(2)))
1.0
>>> lo, hi = chi2_bounds(dof=2, n_runs=50)
>>> bool(lo < 2 < hi)
True
"""

from __future__ import annotations

import numpy as np
from scipy import linalg, stats

__all__ = ["mse", "rmse", "nees", "nis", "chi2_bounds", "effective_sample_size"]


def mse(y_true, y_pred):
    """Mean squared error over all entries."""
    d = np.asarray(y_true, dtype=float) - np.asarray(y_pred, dtype=float)
    return float(np.mean(d * d))


def rmse(y_true, y_pred, axis=None):
    """Root mean squared error (over ``axis``; all entries by default)."""
    d = np.asarray(y_true, dtype=float) - np.asarray(y_pred, dtype=float)
    return np.sqrt(np.mean(d * d, axis=axis))


def _quad(e, P):
    """``e^T P^{-1} e`` stacked over leading axes, by Cholesky solves (no inverse)."""
    e = np.asarray(e, dtype=float)
    P = np.asarray(P, dtype=float)
    L = np.linalg.cholesky(P)
    if e.ndim == 1:
        u = linalg.solve_triangular(L, e, lower=True)
        return float(u @ u)
    u = np.linalg.solve(L, e[..., None])[..., 0]  # batched triangular system
    return np.sum(u * u, axis=-1)


def nees(x_true, x_hat, P):
    """Normalised estimation error squared.

    Parameters
    ----------
    x_true, x_hat : ndarray of shape (..., dim_x)
    P : ndarray of shape (..., dim_x, dim_x)

    Returns
    -------
    float or ndarray of shape (...)
    """
    return _quad(np.asarray(x_true, float) - np.asarray(x_hat, float), P)


def nis(y, S):
    """Normalised innovation squared ``y^T S^{-1} y`` (shapes as in :func:`nees`)."""
    return _quad(y, S)


def chi2_bounds(dof, n_runs=1, alpha=0.05):
    """Two-sided ``1 - alpha`` interval of the average of ``n_runs`` chi-square(dof) draws."""
    lo = stats.chi2.ppf(alpha / 2, dof * n_runs) / n_runs
    hi = stats.chi2.ppf(1 - alpha / 2, dof * n_runs) / n_runs
    return float(lo), float(hi)


def effective_sample_size(weights):
    """``1 / sum(w_i^2)`` of normalised weights (``n`` for equal weights, 1 for one-hot)."""
    w = np.asarray(weights, dtype=float)
    return float(1.0 / np.sum(w * w))
