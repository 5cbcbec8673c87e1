r"""Predictive distributions of the WNN trainers: what ``predict`` means, with its own intervals and density.

Every trainer's prediction at a row is a distribution for the row's target. Two kinds are
used:

:class:`GaussianPredictive`
    ``N(mean, var)``: every trainer whose ``predict(X)`` returns a mean and a variance (the
    Kalman filters, the particle filters, the Gaussian sums, the SMC rows with a Gaussian
    likelihood). Its central interval is ``mean +- z std`` and its log-density the normal's,
    computed with the same formulas the WNN study used before this class existed (so those
    rows' coverage and NLPD are unchanged).
:class:`StudentTMixture`
    an equally weighted mixture over particles of Student-t's,
    :math:`\frac1N \sum_i t_{\nu_i}(y; m_i(x), \sigma_i^2)`: the posterior predictive of the
    SMC sampler with a Student-t likelihood (``"smc-student-10x10"``). Its central interval is
    made of the mixture's own quantiles (found by bisection on the mixture's CDF, bracketed by
    the components' quantiles), its log-density is the mixture's (a log-sum-exp).

Both have ``mean``, ``var``, ``interval(level)`` and ``logpdf(y)``.

A Gaussian predictive whose width is wrong by a factor can be recalibrated on held-out rows
(never the rows it is scored on): :func:`conformal_factor` fits one factor ``c`` from the
standardized residuals ``(y - mean) / std`` of validation rows (split-conformal, Vovk et al.
2005; Lei et al. 2018), and :func:`recalibrate` returns ``N(mean, (c std)^2)``.

>>> import numpy as np
>>> g = GaussianPredictive(np.zeros(2), np.ones(2))
>>> lo, hi = g.interval(0.95)
>>> np.round(hi, 3)
array([1.96, 1.96])
>>> t = StudentTMixture(np.zeros((1, 2)), np.ones(1), np.array([3.0]))
>>> np.round(t.interval(0.95)[1], 3)        # scipy.stats.t(3).ppf(0.975)
array([3.182, 3.182])
"""

from __future__ import annotations

import numpy as np
from scipy.special import gammaln, logsumexp, ndtri, stdtr, stdtrit

__all__ = ["GaussianPredictive", "StudentTMixture", "check_level", "conformal_factor", "recalibrate"]


def check_level(level):
    """``level`` as a float in (0, 1); ``ValueError`` naming it otherwise."""
    value = float(level)
    if not 0.0 < value < 1.0:
        raise ValueError(f"level must be in (0, 1) (the central interval's probability), got {level!r}")
    return value


class GaussianPredictive:
    """``N(mean, var)`` per row.

    Parameters
    ----------
    mean : array-like of shape (n,)
    var : array-like of shape (n,), optional
        Predictive variances (negative values, from rounding, are taken as 0).
    std : array-like of shape (n,), optional
        Predictive standard deviations, instead of ``var`` (kept as given, so that scores from
        a ``(mean, std)`` pair are computed from that very ``std``).
    """

    def __init__(self, mean, var=None, std=None):
        if (var is None) == (std is None):
            raise ValueError("give exactly one of var and std, got "
                             f"var={'None' if var is None else 'an array'}, std={'None' if std is None else 'an array'}")
        self.mean = np.asarray(mean, dtype=float)
        if std is None:
            self.std = np.sqrt(np.maximum(np.asarray(var, dtype=float), 0.0))
        else:
            self.std = np.asarray(std, dtype=float)

    @property
    def var(self):
        """Predictive variances, shape ``(n,)``."""
        return self.std**2

    def interval(self, level):
        """Central ``level`` interval ``mean -+ z std`` with ``z = Phi^{-1}((1 + level) / 2)``: ``(lower, upper)``."""
        z = float(ndtri(0.5 + 0.5 * check_level(level)))
        return self.mean - z * self.std, self.mean + z * self.std

    def logpdf(self, y):
        """Log-density of the targets ``y`` (shape ``(n,)``): ``-log(2 pi var) / 2 - (y - mean)^2 / (2 var)``."""
        std = self.std
        z = np.abs(np.asarray(y, dtype=float) - self.mean) / std
        return -(0.5 * np.log(2.0 * np.pi * std**2) + 0.5 * z**2)

    def covers(self, y, level):
        """Whether each target lies in the central ``level`` interval: ``|y - mean| / std <= z``."""
        z = float(ndtri(0.5 + 0.5 * check_level(level)))
        return np.abs(np.asarray(y, dtype=float) - self.mean) / self.std <= z


def t_logpdf(y, loc, scale2, df):
    """Student-t log-density ``log t_df(y; loc, scale2)`` (broadcast); ``scale2`` is the squared scale."""
    a = (y - loc) ** 2 / (df * scale2)
    return (gammaln(0.5 * (df + 1.0)) - gammaln(0.5 * df) - 0.5 * np.log(np.pi * df * scale2)
            - 0.5 * (df + 1.0) * np.log1p(a))


class StudentTMixture:
    r"""Equally weighted mixture over particles of Student-t's, per row.

    Parameters
    ----------
    loc : array-like of shape (n_particles, n)
        Each particle's location (its network output) at each row.
    scale2 : array-like of shape (n_particles,)
        Each particle's squared scale :math:`\sigma_i^2`.
    df : array-like of shape (n_particles,)
        Each particle's degrees of freedom :math:`\nu_i > 0`.

    Attributes
    ----------
    mean : ndarray of shape (n,)
        The mixture's mean, the particles' mean location (a t's mean exists for
        :math:`\nu > 1`; the locations' mean is what is returned whatever ``df``).
    var : ndarray of shape (n,)
        The mixture's variance: the locations' spread plus the mean of
        :math:`\sigma_i^2 \nu_i / (\nu_i - 2)`; ``inf`` at every row when any particle has
        :math:`\nu_i \le 2` (a t's variance exists only for :math:`\nu > 2`). The intervals
        and the density do not use it.
    """

    def __init__(self, loc, scale2, df):
        self.loc = np.atleast_2d(np.asarray(loc, dtype=float))
        self.scale2 = np.asarray(scale2, dtype=float).reshape(-1)
        self.df = np.asarray(df, dtype=float).reshape(-1)
        n = self.loc.shape[0]
        if self.scale2.shape != (n,) or self.df.shape != (n,):
            raise ValueError(f"scale2 and df must have shape ({n},), one per particle (loc's rows), "
                             f"got {self.scale2.shape} and {self.df.shape}")
        if np.any(self.scale2 <= 0) or np.any(self.df <= 0):
            raise ValueError("scale2 and df must be positive, got minima "
                             f"{self.scale2.min():g} and {self.df.min():g}")
        self.mean = self.loc.mean(axis=0)
        with np.errstate(divide="ignore"):
            t_var = np.where(self.df > 2.0, self.scale2 * self.df / (self.df - 2.0), np.inf)
        self.var = self.loc.var(axis=0) + float(np.mean(t_var))

    @property
    def std(self):
        """``sqrt(var)`` (``inf`` when a particle has ``df <= 2``)."""
        return np.sqrt(self.var)

    def cdf(self, x):
        """The mixture's CDF at ``x`` (shape ``(n,)``, one point per row)."""
        t = (np.asarray(x, dtype=float)[None, :] - self.loc) / np.sqrt(self.scale2)[:, None]
        return stdtr(self.df[:, None], t).mean(axis=0)

    def ppf(self, p, n_iter=100):
        """The mixture's ``p``-quantile at every row (bisection on :meth:`cdf`).

        The quantile lies between the smallest and the largest of the components' ``p``-quantiles
        (the mixture's CDF is their average), which bracket the bisection.
        """
        p = check_level(p)
        q = self.loc + np.sqrt(self.scale2)[:, None] * stdtrit(self.df, p)[:, None]
        lo, hi = q.min(axis=0), q.max(axis=0)
        for _ in range(n_iter):
            mid = 0.5 * (lo + hi)
            below = self.cdf(mid) < p
            lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
            if np.all(hi - lo <= 1e-12 * np.maximum(1.0, np.abs(mid))):
                break
        return 0.5 * (lo + hi)

    def interval(self, level):
        """Central ``level`` interval from the mixture's quantiles: ``(ppf((1 - level)/2), ppf((1 + level)/2))``."""
        level = check_level(level)
        return self.ppf(0.5 - 0.5 * level), self.ppf(0.5 + 0.5 * level)

    def logpdf(self, y):
        """The mixture's log-density at the targets ``y`` (shape ``(n,)``)."""
        y = np.asarray(y, dtype=float)[None, :]
        lp = t_logpdf(y, self.loc, self.scale2[:, None], self.df[:, None])
        return logsumexp(lp, axis=0) - np.log(self.loc.shape[0])

    def covers(self, y, level):
        """Whether each target lies in the mixture's central ``level`` interval."""
        lo, hi = self.interval(level)
        y = np.asarray(y, dtype=float)
        return (lo <= y) & (y <= hi)


def conformal_factor(residuals, level=0.9):
    r"""One width factor for a Gaussian predictive, fitted on held-out standardized residuals.

    Split-conformal with the normalised score :math:`s_i = |y_i - m_i| / \sigma_i` (Lei et al.
    2018, Sec. 5.2): with :math:`s_{(1)} \le \dots \le s_{(n)}` the sorted scores of ``n``
    validation rows and :math:`k = \lceil (n + 1)\,\mathrm{level} \rceil`, the interval
    :math:`m \pm s_{(k)} \sigma` covers a new exchangeable row with probability between
    ``level`` and ``level + 1/(n + 1)``. The factor is :math:`c = s_{(k)} / z` with
    :math:`z = \Phi^{-1}((1 + \mathrm{level})/2)`, so that the Gaussian ``N(m, (c sigma)^2)``
    has that interval as its own central ``level`` interval. On residuals of a calibrated
    Gaussian :math:`c \to 1`; ``c < 1`` narrows a predictive that is too wide.

    Parameters
    ----------
    residuals : array-like of shape (n,)
        Standardized residuals ``(y - mean) / std`` of validation rows (their signs are dropped).
    level : float in (0, 1), default 0.9
        The central interval's probability the factor is fitted for.

    Returns
    -------
    float
        The factor ``c`` (``inf`` when ``n`` is too small for ``level``: ``k > n``).

    Raises
    ------
    ValueError
        When ``residuals`` is empty or not finite.

    Examples
    --------
    >>> r = np.array([0.1, -0.4, 0.9, -0.2, 0.3, 0.05, -0.6, 0.8, 0.15])   # too wide a predictive
    >>> round(conformal_factor(r, level=0.9), 4)                          # s_(9) / 1.645
    0.5471
    >>> conformal_factor(r, level=0.95)                                   # k = 10 > n = 9
    inf
    """
    level = check_level(level)
    s = np.sort(np.abs(np.asarray(residuals, dtype=float).reshape(-1)))
    if s.size == 0 or not np.all(np.isfinite(s)):
        raise ValueError(f"residuals must be a non-empty array of finite numbers, got size {s.size} "
                         f"with {int(np.sum(~np.isfinite(s)))} non-finite")
    k = int(np.ceil((s.size + 1) * level - 1e-9))
    if k > s.size:
        return float("inf")
    return float(s[k - 1] / ndtri(0.5 + 0.5 * level))


def recalibrate(dist, factor):
    """The Gaussian predictive ``dist`` with its standard deviations multiplied by ``factor``.

    Parameters
    ----------
    dist : GaussianPredictive
    factor : float
        Positive and finite (from :func:`conformal_factor` on rows that are not scored).

    Returns
    -------
    GaussianPredictive
        ``N(dist.mean, (factor * dist.std)^2)``: the same mean, intervals ``factor`` times as
        wide, its own density.

    Examples
    --------
    >>> g = recalibrate(GaussianPredictive(np.zeros(1), np.ones(1)), 0.5)
    >>> np.round(g.interval(0.9)[1], 4)
    array([0.8224])
    """
    if not isinstance(dist, GaussianPredictive):
        raise ValueError(f"dist must be a GaussianPredictive (a width factor rescales a Gaussian), got "
                         f"{type(dist).__name__}")
    factor = float(factor)
    if not (np.isfinite(factor) and factor > 0):
        raise ValueError(f"factor must be positive and finite, got {factor!r}")
    return GaussianPredictive(dist.mean, std=factor * dist.std)
