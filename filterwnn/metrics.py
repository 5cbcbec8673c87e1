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

from ._linalg import cholesky_lower, smallest_eigenvalue
from ._validation import check_positive, check_positive_int, check_symmetric, check_weights

__all__ = ["mse", "rmse", "nees", "nis", "chi2_bounds", "effective_sample_size", "kish_ess",
           "integrated_autocorrelation"]


def _difference(y_true, y_pred):
    """``y_true - y_pred`` (broadcasting), with an error naming both if shapes clash."""
    a = np.asarray(y_true, dtype=float)
    b = np.asarray(y_pred, dtype=float)
    try:
        return a - b
    except ValueError as exc:
        raise ValueError(
            f"y_true and y_pred must have the same (or broadcastable) shapes, got {a.shape} and {b.shape}"
        ) from exc


def mse(y_true, y_pred):
    """Mean squared error over all entries."""
    d = _difference(y_true, y_pred)
    return float(np.mean(d * d))


def rmse(y_true, y_pred, axis=None):
    """Root mean squared error (over ``axis``; all entries by default)."""
    d = _difference(y_true, y_pred)
    return np.sqrt(np.mean(d * d, axis=axis))


def _quad(e, P, e_name="x_true - x_hat", P_name="P"):
    """``e^T P^{-1} e`` stacked over leading axes, by Cholesky solves (no inverse).

    Raises ``ValueError`` naming the argument for mismatched shapes, non-finite
    entries, a non-symmetric or a non-positive-definite ``P``.
    """
    e = np.asarray(e, dtype=float)
    P = np.asarray(P, dtype=float)
    if e.ndim < 1 or P.ndim < 2 or P.shape[-2:] != (e.shape[-1], e.shape[-1]):
        raise ValueError(
            f"{P_name} must have shape (..., {e.shape[-1] if e.ndim else 1}, "
            f"{e.shape[-1] if e.ndim else 1}) to match {e_name} of shape {e.shape}, got {P.shape}"
        )
    if not np.all(np.isfinite(e)):
        raise ValueError(f"{e_name} must be finite, got non-finite entries")
    if not np.all(np.isfinite(P)):
        raise ValueError(f"{P_name} must be finite, got non-finite entries")
    check_symmetric(P, P_name)
    L = cholesky_lower(P)
    if L is None:
        raise ValueError(
            f"{P_name} must be positive definite (Cholesky failed); smallest eigenvalue "
            f"{smallest_eigenvalue(P):.3g}"
        )
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
    for name, v in (("x_true", x_true), ("x_hat", x_hat)):
        if not np.all(np.isfinite(np.asarray(v, dtype=float))):
            raise ValueError(f"{name} must be finite, got non-finite entries")
    try:
        e = np.asarray(x_true, float) - np.asarray(x_hat, float)
    except ValueError as exc:
        raise ValueError(
            f"x_true and x_hat must have the same shape, got {np.shape(x_true)} and {np.shape(x_hat)}"
        ) from exc
    return _quad(e, P)


def nis(y, S):
    """Normalised innovation squared ``y^T S^{-1} y`` (shapes as in :func:`nees`)."""
    return _quad(y, S, "y", "S")


def chi2_bounds(dof, n_runs=1, alpha=0.05):
    """Two-sided ``1 - alpha`` interval of the average of ``n_runs`` chi-square(dof) draws."""
    dof = check_positive_int(dof, "dof")
    n_runs = check_positive_int(n_runs, "n_runs")
    alpha = check_positive(alpha, "alpha")
    if not alpha < 1:
        raise ValueError(f"alpha must satisfy 0 < alpha < 1, got {alpha}")
    lo = stats.chi2.ppf(alpha / 2, dof * n_runs) / n_runs
    hi = stats.chi2.ppf(1 - alpha / 2, dof * n_runs) / n_runs
    return float(lo), float(hi)


def effective_sample_size(weights):
    """Kish's effective sample size ``1 / sum(w_i^2)`` of (normalised) weights.

    Parameters
    ----------
    weights : array-like of shape (n_particles,)
        Non-negative weights with a positive sum (normalised here).

    Returns
    -------
    float
        ``n_particles`` for equal weights, 1 for a one-hot weight.
    """
    return float(kish_ess(check_weights(weights)))


def kish_ess(w):
    """Kish's ``1 / sum(w_i^2)`` of weights that already sum to 1, unchecked: the filters' inner loop.

    Parameters
    ----------
    w : ndarray of shape (n_particles,)
        Normalised weights (e.g. ``exp`` of normalised log-weights); use
        :func:`effective_sample_size` for weights from elsewhere.

    Returns
    -------
    numpy.float64

    >>> float(kish_ess(np.full(4, 0.25)))
    4.0
    """
    return 1.0 / np.dot(w, w)


def integrated_autocorrelation(u, min_pairs=10, n_se=2.0):
    r"""Integrated autocorrelation time ``1 + 2 sum_m rho_m`` of a sequence of vectors, with breaks.

    ``rho_m = sum u_k . u_{k-m} / sum (|u_k|^2 + |u_{k-m}|^2) / 2`` over the pairs ``m`` apart
    that straddle no break (a ``None``), for lags ``m = 1, 2, ...`` below a quarter of the
    length, summed while each is significant: above ``n_se`` standard errors of a white
    sequence's, ``1 / sqrt(d n_m)`` for ``n_m`` pairs of ``d``-vectors, and from at least
    ``min_pairs`` pairs (Geyer 1992's initial sequence, with a whiteness test as the stop).
    For whitened innovations of a consistent filter (zero mean, unit covariance) it is 1; for
    correlated ones it is the number of samples that carry the information of one
    independent sample (an AR(1) sequence of lag-one correlation ``phi`` gives
    ``(1 + phi) / (1 - phi)``).

    Parameters
    ----------
    u : sequence of ndarray of shape (d,) or None
        The samples in time order; ``None`` marks a break (no pair spans it).
    min_pairs : int
        Fewest pairs a lag needs to count.
    n_se : float
        Standard errors a lag's autocorrelation must exceed to count.

    Returns
    -------
    float
        At least 1.

    >>> rng = np.random.default_rng(0)
    >>> white = list(rng.standard_normal((60, 2)))
    >>> integrated_autocorrelation(white)
    1.0
    >>> ar = [np.zeros(2)]
    >>> for e in rng.standard_normal((400, 2)):
    ...     ar.append(0.9 * ar[-1] + np.sqrt(1 - 0.81) * e)
    >>> 5.0 < integrated_autocorrelation(ar[1:]) < 25.0
    True
    """
    u = list(u)
    n = len(u)
    ok = np.array([v is not None for v in u], dtype=bool)
    rows = [v for v in u if v is not None]
    d = len(rows[0]) if rows else 0
    n_lags = n // 4  # lags m = 1 .. n_lags - 1
    if not ok.any() or n_lags < 2:
        return 1.0
    U = np.zeros((n + n_lags, d))  # zero rows after the end: every lag's partner exists
    U[:n][ok] = rows
    # a pair spans no break when no break lies between its ends: sample k pairs at lags up to
    # ahead[k], the samples after it before the next break (-1 for a break), and back[k] before it
    k = np.arange(n)
    ahead = np.where(ok, np.minimum.accumulate(np.where(ok, n, k)[::-1])[::-1] - k - 1, -1)
    back = np.where(ok, k - np.maximum.accumulate(np.where(ok, -1, k)) - 1, -1)

    def from_lag(reach, w):
        """``[sum of w[k] over the k with reach[k] >= m for m in 1 .. n_lags - 1]``."""
        per = np.bincount(np.clip(reach, 0, n_lags - 1), weights=w, minlength=n_lags)
        return np.cumsum(per[::-1])[::-1][1:]

    sq = np.square(U[:n]).sum(axis=1)
    n_pairs = from_lag(ahead, None)
    with np.errstate(invalid="ignore", divide="ignore"):
        inv_den = 2.0 / (from_lag(ahead, sq) + from_lag(back, sq))  # 1 / (sum (|u_k|^2 + |u_k-m|^2) / 2)
        bound = n_se / np.sqrt(d * n_pairs)
    c = 1.0
    for lo, hi in ((1, 2), (2, n_lags)):  # lag 1 alone first: a white sequence stops there
        # [k, i, m - lo] = U[k + m, i] for the lags m of the block
        later = np.lib.stride_tricks.as_strided(U[lo:], (n, d, hi - lo), U.strides + U.strides[:1])
        pair = np.arange(lo, hi) <= ahead[:, None]
        num = sum(U[:n, i] @ np.where(pair, later[:, i], 0.0) for i in range(d))
        with np.errstate(invalid="ignore"):
            r = num * inv_den[lo - 1:hi - 1]
        counts = (n_pairs[lo - 1:hi - 1] >= min_pairs) & (r >= bound[lo - 1:hi - 1])
        last = int(np.argmin(counts)) if not counts.all() else len(counts)
        c += 2.0 * float(r[:last].sum())  # Geyer's initial sequence: the lags before the first that fails
        if last < len(counts):
            break
    return c
