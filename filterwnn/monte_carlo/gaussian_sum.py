r"""The Gaussian-sum filter: a weighted bank of Kalman filters (EKF, UKF or SUKF steps).

The posterior is a mixture :math:`\sum_i w_i N(m_i, P_i)`. The components are a filter
bank (:mod:`filterwnn.kalman.bank`) on this filter's model: each runs its own Kalman step
(extended, unscented with Merwe points, or unscented with the reduced spherical-simplex
points) in one batched call, and its weight is multiplied by its predictive likelihood,
the innovation density (Alspach and Sorenson 1972):

.. math::
    w_i \propto w_i\, N(z_k; \hat z_i, S_i)^{\tau} .

With ``tempering`` :math:`\tau = 1` (the default) and a linear-Gaussian model this is the
exact Bayesian posterior of a Gaussian-mixture prior. :math:`\tau \ne 1` is a
*heuristic*: it flattens (:math:`\tau < 1`) or sharpens the weights and no longer gives
the Bayesian posterior. When the effective sample size of the weights falls below
``ess_threshold * n_components`` the components are resampled (means and covariances
copied, weights equalised), the resampling step of Kotecha and Djuric's Gaussian-sum
particle filter (2003); ``ess_threshold=0`` (the default) never resamples.

This is **not a particle filter**: nothing is sampled, and the components are Gaussians,
not points. The particle filters (:class:`~filterwnn.ParticleFilter` and its presets) are
a different algorithm.

``x`` and ``P`` are the mixture's moments (``combine="mixture"``):
:math:`x = \sum_i w_i m_i`, :math:`P = \sum_i w_i (P_i + (m_i - x)(m_i - x)^T)`; with
``combine="mean"`` they are the *unweighted* ensemble average of the components (equal
weights in the same formulas), which ignores the likelihood weights: an ensemble of
Kalman filters, not the Bayesian mixture.

>>> import numpy as np
>>> from filterwnn.models import LinearGaussianModel
>>> m = LinearGaussianModel.random(dim_x=2, dim_z=1, rng=0)
>>> xs, zs = m.simulate(5, rng=1)
>>> gsf = GaussianSumFilter(2, 1, 1.0, m.hx, m.fx, component="ukf", vectorized=True)
>>> gsf.Q, gsf.R = m.Q, m.R
>>> gsf.initialize([[1.0, 0.0], [-1.0, 0.0]], np.eye(2))
>>> means, covs = gsf.batch_filter(zs)
>>> means.shape, gsf.means.shape, gsf.covariances.shape, round(float(gsf.weights.sum()), 12)
((5, 2), (2, 2), (2, 2, 2), 1.0)

References
----------
D. L. Alspach and H. W. Sorenson, "Nonlinear Bayesian estimation using Gaussian sum
approximations", IEEE Trans. Automatic Control 17(4), 1972.
J. H. Kotecha and P. M. Djuric, "Gaussian sum particle filtering", IEEE Trans. Signal
Processing 51(10), 2003.
"""

from __future__ import annotations

import numpy as np

from .._validation import (NumericalError, as_measurement, as_state, check_choice, check_covariance,
                          check_positive, check_positive_int, check_rng)
from .._state import rolls_back_on_error
from ._weighted import ModelAttribute, WeightedMixtureFilter, logsumexp
from .resampling import count_distinct, get_scheme
from ..kalman.bank import ExtendedKalmanFilterBank, UnscentedKalmanFilterBank
from ..kalman.batched import ExtendedStep, KalmanModel, UnscentedStep, check_callable
from ..kalman.presets import make_points
from ..metrics import kish_ess

__all__ = ["GaussianSumFilter"]

COMPONENTS = ("ekf", "ukf", "sukf")
COMBINES = ("mixture", "mean")


class GaussianSumFilter(WeightedMixtureFilter):
    """A Gaussian-sum filter (a weighted bank of Kalman filters), filterpy-style.

    Parameters
    ----------
    dim_x, dim_z : int
    dt : float
        Passed to ``fx(x, dt, **fx_args)``.
    hx, fx : callable
        As in :class:`~filterwnn.ParticleFilter` (``fx=None`` is a random walk).
    component : {"ekf", "ukf", "sukf"}, default "ukf"
        The Kalman step of every component: extended (needs ``HJacobian``, and
        ``FJacobian`` unless ``fx`` is None), unscented with ``points`` (default the
        ``"merwe"`` preset of :mod:`filterwnn.kalman.presets`: alpha=1, beta=2, kappa=0) or
        unscented with ``points`` (default the ``"supf"`` preset: spherical simplex, beta=2).
    points : sigma-point object, optional
        For ``"ukf"``/``"sukf"``; ``points.n`` must equal ``dim_x``.
    FJacobian, HJacobian, x_mean_fn, z_mean_fn, residual_x, residual_z : callable, optional
        As in :class:`~filterwnn.ParticleFilter`.
    tempering : float > 0, default 1.0
        Exponent on the innovation likelihood; 1 is the Bayesian filter, anything else
        a heuristic (see the module docstring).
    resampling : {"systematic", "stratified", "residual", "multinomial"} or callable
        Scheme for the optional component resampling.
    ess_threshold : float in [0, 1], default 0.0
        Resample the components when ``ESS < ess_threshold * n_components`` (1: every
        step, 0: never).
    combine : {"mixture", "mean"}, default "mixture"
        What ``x``/``P`` report: the weighted mixture's moments, or the unweighted
        ensemble average.
    vectorized : bool, default False
    rng : None, int, SeedSequence, BitGenerator or Generator
        Only the component resampling draws random numbers.
    recover : bool, default False
        Repair a component covariance that is not positive definite (with a warning).

    Attributes
    ----------
    means : ndarray of shape (n_components, dim_x)
    covariances : ndarray of shape (n_components, dim_x, dim_x)
    weights : ndarray of shape (n_components,)
        ``exp(log_weights)``.
    x, P : ndarray
        Moments (see ``combine``); ``x_prior``, ``P_prior``, ``x_post``, ``P_post`` after
        the last ``predict``/``update``.
    log_likelihood, log_marginal_likelihood : float
        ``log p(z_k | z_{1:k-1})`` (untempered) and its sum.
    ess, n_distinct : float, int
        ESS of the weights at the last update, and the number of distinct components the
        last resampling kept (``n_components`` when it did not resample); ``ess_history``,
        ``n_distinct_history``, ``resampled_history`` per update.
    step : int
        The time step: ``predict`` advances it by one.
    """

    #: stepped in place by predict/update: restored with the filter when a step fails
    _rollback_parts = ("_bank",)

    _members_attr = "means"
    _members_word = "components"
    _restart_hint = "call initialize(means, covariances) to restart the mixture"
    x = WeightedMixtureFilter.x  # (in this class's namespace, so that its page documents them)
    P = WeightedMixtureFilter.P
    # the model: one KalmanModel, read and written through
    hx = ModelAttribute(lambda f, name: check_callable(f, name, False), "Measurement function (on the model).")
    fx = ModelAttribute(check_callable, "Transition mean, or None for a random walk (on the model).")
    Q = ModelAttribute(doc="Process noise covariance (on the model; checked when it changes).")
    R = ModelAttribute(doc="Measurement noise covariance (on the model; checked when it changes).")

    def __init__(self, dim_x, dim_z, dt, hx, fx, *, component="ukf", points=None, FJacobian=None,
                 HJacobian=None, x_mean_fn=None, z_mean_fn=None, residual_x=None, residual_z=None,
                 tempering=1.0, resampling="systematic", ess_threshold=0.0, combine="mixture",
                 vectorized=False, rng=None, recover=False):
        self.dim_x = check_positive_int(dim_x, "dim_x")
        self.dim_z = check_positive_int(dim_z, "dim_z")
        self.dt = check_positive(dt, "dt")
        for name, f in (("hx", hx), ("fx", fx), ("FJacobian", FJacobian), ("HJacobian", HJacobian),
                        ("x_mean_fn", x_mean_fn), ("z_mean_fn", z_mean_fn), ("residual_x", residual_x),
                        ("residual_z", residual_z)):
            check_callable(f, name, allow_none=name != "hx")
        self.component = check_choice(component, "component", COMPONENTS)
        self.combine = check_choice(combine, "combine", COMBINES)
        self.tempering = check_positive(tempering, "tempering")
        if isinstance(ess_threshold, bool) or not np.isscalar(ess_threshold) or not 0 <= ess_threshold <= 1:
            raise ValueError(f"ess_threshold must be a number in [0, 1], got {ess_threshold!r}")
        self.ess_threshold = float(ess_threshold)
        self._resample = get_scheme(resampling)
        self.resampling = resampling
        self.rng = check_rng(rng)
        if component == "ekf":
            if HJacobian is None:
                raise ValueError("component='ekf' needs HJacobian, got None")
            if fx is not None and FJacobian is None:
                raise ValueError("component='ekf' needs FJacobian when fx is given, got None")
            self._step, self._bank_cls = ExtendedStep(), ExtendedKalmanFilterBank
        else:
            if points is None:
                points = make_points("merwe" if component == "ukf" else "supf", self.dim_x)
            if getattr(points, "n", None) != self.dim_x:
                raise ValueError(f"points.n must equal dim_x={self.dim_x}, got {getattr(points, 'n', None)}")
            self._step, self._bank_cls = UnscentedStep(points), UnscentedKalmanFilterBank
        self.points = points
        self._model = KalmanModel(
            self.dim_x, self.dim_z, self.dt, fx, hx, vectorized=bool(vectorized), FJacobian=FJacobian,
            HJacobian=HJacobian, x_mean_fn=x_mean_fn, z_mean_fn=z_mean_fn, residual_x=residual_x,
            residual_z=residual_z, recover=bool(recover),
        )
        self._bank = None  # the components: a filter bank on this filter's model
        self._filterpy_defaults()
        self.log_weights = None
        self._predicted = False
        self.step = 0
        self.log_likelihood = np.nan
        self.log_marginal_likelihood = 0.0
        self.ess = np.nan
        self.n_distinct = 0
        self.ess_history, self.n_distinct_history, self.resampled_history = [], [], []

    @property
    def weights(self):
        """Normalised component weights, shape ``(n_components,)``."""
        return None if self.log_weights is None else np.exp(self.log_weights)

    @property
    def means(self):
        """Component means, shape ``(n_components, dim_x)`` (the bank's ``x``)."""
        return None if self._bank is None else self._bank.x

    @property
    def covariances(self):
        """Component covariances, shape ``(n_components, dim_x, dim_x)`` (the bank's ``P``)."""
        return None if self._bank is None else self._bank.P

    @property
    def n_components(self):
        return 0 if self.means is None else self.means.shape[0]

    def initialize(self, means, covariances, weights=None):
        """Set the mixture: component means, covariances and (default equal) weights.

        Parameters
        ----------
        means : array-like of shape (n_components, dim_x)
        covariances : array-like of shape (dim_x, dim_x) or (n_components, dim_x, dim_x)
            One covariance shared by every component, or one each.
        weights : array-like of shape (n_components,), optional
            Non-negative with a positive sum (normalised here).
        """
        M = np.atleast_2d(np.asarray(means, dtype=float))
        if M.ndim != 2 or M.shape[1] != self.dim_x or not np.all(np.isfinite(M)):
            raise ValueError(f"means must be finite of shape (n_components, {self.dim_x}), got shape {M.shape}")
        n = M.shape[0]
        C = np.asarray(covariances, dtype=float)
        if C.ndim == 2:
            C = np.broadcast_to(check_covariance(C, "covariances", self.dim_x), (n, self.dim_x, self.dim_x))
        elif C.shape != (n, self.dim_x, self.dim_x) or not np.all(np.isfinite(C)):
            raise ValueError(f"covariances must be finite of shape ({self.dim_x}, {self.dim_x}) or "
                             f"({n}, {self.dim_x}, {self.dim_x}), got shape {C.shape}")
        if weights is None:
            lw = np.full(n, -np.log(n))
        else:
            w = np.asarray(weights, dtype=float)
            if w.shape != (n,) or not np.all(np.isfinite(w)) or np.any(w < 0) or not w.sum() > 0:
                raise ValueError(f"weights must be {n} finite non-negative numbers with a positive sum, got {w}")
            with np.errstate(divide="ignore"):
                lw = np.log(w / w.sum())
        self._bank = self._bank_cls.of_components(self._model, self._step, M.copy(), np.array(C))
        self.log_weights = lw
        self._predicted = False
        self._x, self._P = self._moments(self.means, self.covariances)
        self.x_post, self.P_post = self._x.copy(), self._P.copy()

    def _sync(self):
        m = self._model
        m.noise("Q")
        m.noise("R")
        if self.means is None:  # one component N(x, P)
            self.initialize(as_state(self._x, "x", self.dim_x)[None, :], check_covariance(self._P, "P", self.dim_x))
        return m

    def _moments(self, M, C):
        w = self.weights if self.combine == "mixture" else np.full(M.shape[0], 1.0 / M.shape[0])
        model = self._model
        x = model.mean_x(M, w)
        d = model.residual_x_rows(M, x[None, :])
        P = (d.T * w) @ d + np.tensordot(w, C, axes=1)
        return x, 0.5 * (P + P.T)

    @rolls_back_on_error
    def predict(self, **fx_args):
        """Advance the step and every component by its Kalman prediction."""
        self._sync()
        step = self.step + 1
        bank = self._bank
        bank.step = self.step
        bank.predict(**fx_args)  # every component's step; errors name the component and the step
        self._predicted = True
        self.step = step
        self._x, self._P = self._moments(self.means, self.covariances)
        self.x_prior, self.P_prior = self._x.copy(), self._P.copy()

    @rolls_back_on_error
    def update(self, z, **hx_args):
        """Kalman-update every component with ``z`` and reweight by its innovation likelihood.

        ``z=None`` skips the measurement (weights unchanged).
        """
        self._sync()
        step = self.step
        if z is None:
            self.x_post, self.P_post = self._x.copy(), self._P.copy()
            self._record(self.ess, self.n_components, False)
            return
        z = as_measurement(z, self.dim_z)
        bank = self._bank
        prior = bank.x, bank.P
        bank.step = step
        bank.update(z, **hx_args)  # a failure restores the bank with the filter (_rollback_parts)
        M, C, log_alpha = bank.x, bank.P, bank.log_likelihood
        bank.set_state(*prior)  # the components change only once their weights are good
        if not np.all(np.isfinite(log_alpha)):
            raise NumericalError(f"non-finite component likelihood at step {step}", matrix="weights", step=step)
        lw_prev = self.log_weights
        log_lik = logsumexp(lw_prev + log_alpha)
        new_lw = lw_prev + self.tempering * log_alpha
        lse = logsumexp(new_lw)
        if not np.isfinite(lse):
            raise NumericalError(f"all component weights underflowed at step {step}", matrix="weights", step=step)
        new_lw = new_lw - lse
        w = np.exp(new_lw)
        ess = kish_ess(w)
        self.log_weights = new_lw
        x, P = self._moments(M, C)
        n = M.shape[0]
        n_distinct = n
        resampled = self.ess_threshold >= 1.0 or ess < self.ess_threshold * n
        if resampled:
            idx = self._resample(w, self.rng, n)
            M, C = M[idx], C[idx]
            new_lw = np.full(n, -np.log(n))
            n_distinct = count_distinct(idx, n, self._resample)
        bank.set_state(np.ascontiguousarray(M), C)
        self.log_weights = new_lw
        self._predicted = False
        self.log_likelihood = log_lik
        self.log_marginal_likelihood += log_lik
        self._x, self._P = x, P
        self.x_post, self.P_post = x.copy(), P.copy()
        self._record(ess, n_distinct, resampled)

    def __repr__(self):
        return (f"GaussianSumFilter(dim_x={self.dim_x}, dim_z={self.dim_z}, component={self.component!r}, "
                f"n_components={self.n_components}, tempering={self.tempering}, "
                f"ess_threshold={self.ess_threshold}, combine={self.combine!r}, step={self.step})")
