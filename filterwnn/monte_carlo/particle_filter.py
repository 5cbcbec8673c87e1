r"""Particle filters with filterpy's look: SPF, EPF, UPF and SUPF, batched over particles.

One :class:`ParticleFilter` runs the generic sequential importance resampling loop (van
der Merwe, Doucet, de Freitas and Wan 2000, section 3, steps 1-5); the importance
proposal (:mod:`filterwnn.monte_carlo.proposals`) and the resampling scheme
(:mod:`filterwnn.monte_carlo.resampling`) are arguments. At time step ``k``:

1. ``predict``: the proposal's time update (:math:`x_k^{(i)} \sim p(x_k \mid x_{k-1}^{(i)})`
   for the prior proposal; every particle's Kalman prediction for the Kalman ones).
2. ``update(z)``: the proposal draws the new particles and returns each one's log-weight
   increment :math:`\log \alpha_i = \log p(z_k \mid x_k^{(i)}) + \log p(x_k^{(i)} \mid
   x_{k-1}^{(i)}) - \log q(x_k^{(i)} \mid x_{k-1}^{(i)}, z_k)`; the filter adds it
   (times ``tempering``, 1 by default), normalises on the log scale, forms the weighted
   moments (the paper's eqs. 8-9) :math:`x = \sum_i w_i x^{(i)}`,
   :math:`P = \sum_i w_i (x^{(i)} - x)(x^{(i)} - x)^T`, and resamples when the effective
   sample size :math:`1/\sum_i w_i^2` is below ``ess_threshold * n_particles`` (1, the
   default, resamples every step; 0 never), then applies the optional ``move``
   (resample-move, Gilks and Berzuini 2001).

The marginal log-likelihood :math:`\log p(z_k \mid z_{1:k-1}) \approx \log \sum_i w_{k-1,i}
\alpha_i` is kept per step (``log_likelihood``) and summed (``log_marginal_likelihood``).

When the weights collapse (ESS below 2 for 3 consecutive updates) the filter warns once
with a :class:`DegeneracyWarning` naming the step, the ESS and what to try. With the prior
(bootstrap) proposal and the Gaussian likelihood a collapse counts only while the best
particle cannot explain the measurement (its Mahalanobis distance :math:`d^2` beyond the
0.999 quantile of :math:`\chi^2_{\dim z}`): a sharp likelihood that singles out a
particle close to the measurement is the filter working, not a risk.

The particle filters are *not* the Gaussian-sum filter: a bank of Kalman filters weighted
by their innovation likelihoods, never sampled, is :class:`filterwnn.GaussianSumFilter`,
a different algorithm.

Presets (all with the same constructor, so one script loops over them):
:class:`BootstrapParticleFilter` (SPF), :class:`ExtendedKalmanParticleFilter` (EPF),
:class:`UnscentedParticleFilter` (UPF, Merwe points, alpha=1, beta=2, kappa=0) and
:class:`SimplexUnscentedParticleFilter` (the first paper's SUPF, spherical-simplex points
with beta=2).

>>> import numpy as np
>>> from filterwnn.models import LinearGaussianModel
>>> m = LinearGaussianModel.random(dim_x=2, dim_z=1, rng=0)
>>> xs, zs = m.simulate(10, rng=1)
>>> pf = UnscentedParticleFilter(2, 1, 1.0, m.hx, m.fx, n_particles=100,
...                              vectorized=True, rng=2)
>>> pf.Q, pf.R = m.Q, m.R
>>> means, covs = pf.batch_filter(zs)
>>> means.shape, covs.shape
((10, 2), (10, 2, 2))
>>> len(pf.ess_history), bool(np.isfinite(pf.log_marginal_likelihood)), pf.step
(10, True, 10)

References
----------
R. van der Merwe, A. Doucet, N. de Freitas and E. Wan, "The unscented particle filter",
Technical Report CUED/F-INFENG/TR 380, Cambridge University, 2000.
W. R. Gilks and C. Berzuini, "Following a moving target: Monte Carlo inference for
dynamic Bayesian models", JRSS B 63, 2001.
"""

from __future__ import annotations

import inspect
import math
import warnings

import numpy as np
from scipy.special import chdtri

from .._validation import (
    NumericalError,
    as_measurement,
    as_real,
    as_state,
    check_choice,
    check_covariance,
    check_positive,
    check_positive_int,
    check_rng,
    check_scale,
    check_weights,
)
from .._state import rolls_back_on_error
from ._weighted import ModelAttribute, SettledAttribute, WeightedMixtureFilter, logsumexp
from .proposals import ExtendedKalmanProposal, PriorProposal, ProposalModel, UnscentedKalmanProposal
from .resampling import SCHEMES, count_distinct, get_scheme
from ..kalman.batched import check_callable
from ..kalman.presets import make_points
from ..metrics import kish_ess

__all__ = [
    "DegeneracyWarning",
    "ParticleFilter",
    "BootstrapParticleFilter",
    "ExtendedKalmanParticleFilter",
    "UnscentedParticleFilter",
    "SimplexUnscentedParticleFilter",
]

PROPOSALS = ("prior", "extended", "unscented")

#: ESS below this for ``_DEGENERATE_RUN`` consecutive updates triggers the warning.
_DEGENERATE_ESS = 2.0
_DEGENERATE_RUN = 3
#: A measurement that leaves the ESS under ``_DEGENERATE_ESS`` and lies, from the best particle, past this tail
#: probability of chi-square (bootstrap proposal, Gaussian ``R``: ``d^2`` past 37.3 in one dimension, 6.1 sigma)
#: warns at once, the first time: one gross outlier (a unit slip in ``z``) collapsed the weights onto a particle or
#: two and moved the estimate, which the three-update rule above does not see (stop 69: ``z = 1e6`` in the
#: growth model took the estimate to -23.3 with no word).
_OUTLIER_TAIL = 1e-9


class DegeneracyWarning(RuntimeWarning):
    """The particle weights collapsed: the effective sample size stayed below 2 for 3
    consecutive updates, or fell below 2 at once on a measurement that no particle explains by
    far (the bootstrap proposal with a Gaussian ``R``: a gross outlier, or particles that lost the
    state). Raised once per filter; the message names the step, the ESS and what to try."""


#: The package's schemes (their implementations): they read the weights and write nothing
#: else, so ``update`` may keep the weights it resampled with for the moments formed later.
_READ_ONLY_SCHEMES = frozenset(SCHEMES[name].impl for name in ("multinomial", "stratified", "systematic", "residual"))

_UNIFORM = {}  # n -> the kept np.full(n, -log n) that _uniform_log_weights copies


def _uniform_log_weights(n):
    """``np.full(n, -np.log(n))`` (equal weights), a copy of an array kept per ``n``."""
    kept = _UNIFORM.get(n)
    if kept is None:
        kept = _UNIFORM[n] = np.full(n, -np.log(n))
    return kept.copy()


def _flag(value, name):
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be a bool, got {type(value).__name__}")
    return bool(value)


def _required(f, name):
    return check_callable(f, name, allow_none=False)


#: The constructor's model keywords: they live on the filter's one ``ProposalModel`` (the
#: attributes of the same names read and write through it, :class:`ModelAttribute`).
_MODEL_CALLABLES = ("FJacobian", "HJacobian", "x_mean_fn", "z_mean_fn", "residual_x", "residual_z",
                    "transition_logpdf", "process_sampler", "measurement_logpdf")


class ParticleFilter(WeightedMixtureFilter):
    """A particle filter with a pluggable proposal and resampling, filterpy-style.

    The parameters fall in groups that live where they belong: the **model** (``dt``,
    ``hx``, ``fx``, the Jacobians, mean and residual functions, the densities,
    ``vectorized``, ``recover``) is one :class:`~filterwnn.monte_carlo.proposals.ProposalModel`
    that the attributes of the same names read and write (``pf.Q = ...``, ``pf.hx = ...``);
    the **proposal** carries its own settings (``proposal="unscented", points=pts,
    carry_covariance=False`` is a shorthand for
    ``proposal=UnscentedKalmanProposal(pts, carry_covariance=False)``); the **resampling**
    is ``resampling``, ``ess_threshold`` and ``move``; ``tempering`` weights; ``rng`` draws.

    Parameters
    ----------
    dim_x, dim_z : int
        State and measurement sizes.
    dt : float
        Time step, passed to ``fx`` as ``fx(x, dt, **fx_args)`` (``> 0``).
    hx : callable
        ``hx(x, **hx_args)`` -> ``(dim_z,)``; with ``vectorized=True`` it receives one
        2-D array, one row per point, ``(n_points, dim_x)``, and returns
        ``(n_points, dim_z)``.
    fx : callable or None
        ``fx(x, dt, **fx_args)``, the *mean* of the transition (vectorized alike);
        ``None`` is a random walk, ``x_k = x_{k-1} + w_k``.
    n_particles : int
        Number of particles.
    proposal : {"prior", "extended", "unscented"} or proposal object
        The importance proposal: a name, or any object with the protocol of
        :mod:`filterwnn.monte_carlo.proposals` (``carries_covariance``, ``predict``, ``propose``),
        e.g. :class:`~filterwnn.PriorProposal`, :class:`~filterwnn.ExtendedKalmanProposal`,
        :class:`~filterwnn.UnscentedKalmanProposal` or your own. ``"unscented"`` uses
        ``points`` (default the ``"merwe"`` preset, alpha=1, beta=2, kappa=0); pass
        ``make_points("supf", dim_x)`` (:mod:`filterwnn.kalman.presets`) for the reduced-point SUPF (the
        default of :class:`SimplexUnscentedParticleFilter`).
    points : sigma-point object, optional
        For the unscented proposals; ``points.n`` must equal ``dim_x`` (checked here).
    FJacobian, HJacobian : callable, optional
        ``FJacobian(x, dt, **fx_args)`` and ``HJacobian(x, **hx_args)`` for the extended
        proposal (with ``vectorized=True`` called on ``(n_particles, dim_x)`` and
        returning one matrix per row, or one shared matrix).
    x_mean_fn, z_mean_fn, residual_x, residual_z : callable, optional
        As in filterpy's ``UnscentedKalmanFilter`` (angles): ``x_mean_fn(points, weights)``,
        ``residual_x(a, b)``. With ``vectorized=True`` residuals are called on whole
        arrays. ``x_mean_fn`` also forms the weighted particle mean.
    resampling : {"systematic", "stratified", "residual", "multinomial"}
        Resampling scheme (:mod:`filterwnn.monte_carlo.resampling`).
    ess_threshold : float in [0, 1], default 1.0
        Resample when ``ESS < ess_threshold * n_particles``; 1 means every step, 0 never.
    tempering : float > 0, default 1.0
        Exponent on the log-weight increment. 1 is the particle filter; other values
        are a heuristic (tempered weights), not Bayesian filtering.
    vectorized : bool, default False
        Call ``fx``, ``hx`` (and the optional callables below) once on all points.
    rng : None, int, SeedSequence, BitGenerator or Generator
        All randomness (initial draw, proposals, resampling, ``move``); the same seed
        gives bit-identical output.
    transition_logpdf : callable, optional
        ``transition_logpdf(x, x_prev, **fx_args)``: log-density of the transition, for
        non-Gaussian process noise (default ``log N(x; fx(x_prev), Q)``, on Q's support
        when Q is singular).
    process_sampler : callable, optional
        ``process_sampler(x_prev, rng, **fx_args)``: a draw from the transition (default
        ``fx(x_prev) + N(0, Q)``). ``fx`` and ``Q`` must then be its mean and covariance,
        which the Kalman proposals use.
    measurement_logpdf : callable, optional
        ``measurement_logpdf(z, x, **hx_args)``: log-likelihood (default
        ``log N(z; hx(x), R)``).
    recover : bool, default False
        Opt-in recovery instead of :class:`~filterwnn.NumericalError` (each use warns
        with a ``RuntimeWarning`` naming the step): a particle covariance that is not
        positive definite is repaired by clipping its eigenvalues to ``1e-12`` times the
        largest (then the step is retried); a measurement under which every weight
        underflows (or is NaN) is skipped as an outlier, as if ``z`` were None.
    move : callable, optional
        ``move(particles, rng) -> particles`` (both ``(n_particles, dim_x)``), applied to
        the particles right after each resampling (resample-move, Gilks and Berzuini
        2001), e.g. MCMC steps. It **must leave the current posterior invariant** (e.g. a
        Metropolis-Hastings kernel targeting :math:`p(x_k \\mid z_{1:k})`); the filter
        cannot check that. The particle covariances (Kalman proposals) are kept.
    carry_covariance : bool, default True
        For a Kalman proposal given by name (``"extended"`` or ``"unscented"``):
        each particle carries its own covariance from step to step (van der Merwe et al.
        2000), or, with ``False``, its Kalman step starts from the transition noise ``Q``
        alone (the one-step approximation of the optimal proposal, Doucet, Godsill and
        Andrieu 2000). The carried covariance can grow much wider than ``Q``, so the
        textbook weight ``p(x|x') / q(x)`` collapses (a :class:`DegeneracyWarning` says
        so); ``False`` is the remedy on an ordinary tracker. A proposal object brings its
        own setting, so ``False`` with one is an error.

    Attributes
    ----------
    x : ndarray of shape (dim_x,)
        State estimate. Set it (and ``P``) before the first ``predict``: the particles are
        drawn from ``N(x, P)`` then, unless :meth:`initialize` set them. Setting ``x`` or
        ``P`` once the particles exist raises ``ValueError`` (use :meth:`initialize`).
    P : ndarray of shape (dim_x, dim_x)
    Q : ndarray of shape (dim_x, dim_x)
        Process noise covariance (identity by default, as in filterpy); may be singular
        (e.g. ``Q_discrete_white_noise``). Checked and factored only when it changes.
    R : ndarray of shape (dim_z, dim_z)
        Measurement noise covariance (positive definite).
    x_prior, P_prior, x_post, P_post : ndarray
        Moments after the last ``predict`` / ``update``.
    particles : ndarray of shape (n_particles, dim_x) or None
        The weighted cloud after the last ``update`` (``initialize``).
    covariances : ndarray of shape (n_particles, dim_x, dim_x) or None
        Per-particle covariances (proposals that carry them).
    log_weights : ndarray of shape (n_particles,)
        Normalised log-weights; ``weights`` is their exponential.
    log_likelihood : float
        ``log p(z_k | z_{1:k-1})`` estimated at the last update (``nan`` before one).
    log_marginal_likelihood : float
        Its sum over all updates, ``log p(z_{1:k})``.
    ess : float
        Effective sample size at the last update (before resampling).
    n_distinct : int
        Number of distinct particles the last resampling kept (counted from its indices);
        ``n_particles`` when the step did not resample. ``ess_history``,
        ``n_distinct_history`` and ``resampled_history`` keep one entry per ``update``
        (``z=None`` included).
    ancestors : ndarray of int, shape (n_particles,)
        The index, in the cloud set by the last ``initialize`` (or the first draw), of the
        particle each one descends from through every resampling since; ``n_ancestors`` is the
        number of distinct ones (1: every particle shares one ancestor).
    step : int
        The time step: ``predict`` advances it by one; ``update`` works at (and its
        errors and warnings name) the current step. 0 before the first ``predict``.
    """

    #: Out of ``__dict__``, as the histories are (filterpy's ``Saver`` cannot stack a list that grows).
    __slots__ = ("unexplained_steps",)

    _members_attr = "particles"
    _members_word = "particles"
    _restart_hint = "call initialize(particles) to restart the cloud, or set x and P before the first predict"
    x = WeightedMixtureFilter.x  # (in this class's namespace, so that its page documents them)
    P = WeightedMixtureFilter.P
    # the model: one ProposalModel, read and written through (no per-step copying)
    dt = ModelAttribute(doc="Time step passed to ``fx`` (on the model).")
    hx = ModelAttribute(_required, "Measurement function (on the model).")
    fx = ModelAttribute(check_callable, "Transition mean, or None for a random walk (on the model).")
    Q = ModelAttribute(doc="Process noise covariance (on the model; checked when it changes).")
    R = ModelAttribute(doc="Measurement noise covariance (on the model; checked when it changes).")
    vectorized = ModelAttribute(_flag, "Whether the callables take one row per point (on the model).")
    recover = ModelAttribute(_flag, "Opt-in recovery (on the model; see the constructor).")
    (FJacobian, HJacobian, x_mean_fn, z_mean_fn, residual_x, residual_z, transition_logpdf, process_sampler,
     measurement_logpdf) = (ModelAttribute(check_callable, "None or callable, on the model (see the constructor).")
                            for _ in _MODEL_CALLABLES)

    def __init__(self, dim_x, dim_z, dt, hx, fx, n_particles, proposal="prior", *, points=None,
                 FJacobian=None, HJacobian=None, x_mean_fn=None, z_mean_fn=None, residual_x=None,
                 residual_z=None, resampling="systematic", ess_threshold=1.0, vectorized=False, rng=None,
                 tempering=1.0, transition_logpdf=None, process_sampler=None, measurement_logpdf=None,
                 recover=False, move=None, carry_covariance=True):
        self.dim_x = check_positive_int(dim_x, "dim_x")
        self.dim_z = check_positive_int(dim_z, "dim_z")
        self._model = ProposalModel(self.dim_x, self.dim_z)
        self._pending_prior = self._pending_post = None
        self.dt = check_positive(dt, "dt")
        self.hx, self.fx = hx, fx
        self.n_particles = check_positive_int(n_particles, "n_particles")
        optional = dict(FJacobian=FJacobian, HJacobian=HJacobian, x_mean_fn=x_mean_fn, z_mean_fn=z_mean_fn,
                        residual_x=residual_x, residual_z=residual_z, transition_logpdf=transition_logpdf,
                        process_sampler=process_sampler, measurement_logpdf=measurement_logpdf)
        for name, f in optional.items():  # None or callable, checked by the attribute
            setattr(self, name, f)
        self.move = check_callable(move, "move")
        self.recover, self.vectorized = recover, vectorized
        self._set_resampling(resampling, ess_threshold)
        self.tempering = check_positive(tempering, "tempering")
        self.rng = check_rng(rng)
        self.proposal = self._make_proposal(proposal, points, bool(carry_covariance))
        self._filterpy_defaults()
        self.particles = None
        self.covariances = None
        self.log_weights = _uniform_log_weights(self.n_particles)
        self._prediction = None
        self.step = 0
        self.log_likelihood = np.nan
        self.log_marginal_likelihood = 0.0
        self.ess = float(self.n_particles)
        self.n_distinct = self.n_particles
        self.ancestors = np.arange(self.n_particles)
        self.ess_history = []
        self.n_distinct_history = []
        self.resampled_history = []
        self._low_ess_run = 0
        self._warned_degenerate = False
        self.unexplained_steps = []  # updates whose z no particle explained (see _OUTLIER_TAIL)

    # ------------------------------------------------------------------ set-up
    def _set_resampling(self, resampling, ess_threshold):
        self._resample = get_scheme(resampling)  # validates the name (or callable)
        self.resampling = resampling
        if isinstance(ess_threshold, bool) or not np.isscalar(ess_threshold) or not 0 <= ess_threshold <= 1:
            raise ValueError(f"ess_threshold must be a number in [0, 1], got {ess_threshold!r}")
        self.ess_threshold = float(ess_threshold)

    def _make_proposal(self, proposal, points, carry_covariance=True):
        proposal = self._proposal_object(proposal, points, carry_covariance)
        if isinstance(proposal, ExtendedKalmanProposal):
            if self.HJacobian is None:
                raise ValueError("the extended Kalman proposal needs HJacobian, got None")
            if self.fx is not None and self.FJacobian is None and proposal.carries_covariance:
                raise ValueError("the extended Kalman proposal needs FJacobian when fx is given, got None")
        return proposal

    def _proposal_object(self, proposal, points, carry_covariance):
        if isinstance(proposal, str):
            check_choice(proposal, "proposal", PROPOSALS)
            if proposal == "prior":
                return PriorProposal()
            if proposal == "extended":
                return ExtendedKalmanProposal(carry_covariance=carry_covariance)
            if points is None:
                points = make_points("merwe", self.dim_x)
            n = getattr(points, "n", None)
            if n != self.dim_x:
                raise ValueError(f"points.n must equal dim_x={self.dim_x}, got {n}")
            return UnscentedKalmanProposal(points, carry_covariance=carry_covariance)
        if not carry_covariance:
            raise ValueError("carry_covariance=False applies to a proposal given by name; a proposal object "
                             "brings its own (e.g. UnscentedKalmanProposal(points, carry_covariance=False))")
        missing = [a for a in ("carries_covariance", "predict", "propose") if not hasattr(proposal, a)]
        if missing:
            raise TypeError(
                "proposal must be a name or a proposal object (carries_covariance, predict, propose; "
                f"see filterwnn.monte_carlo.proposals), got {type(proposal).__name__} without {', '.join(missing)}"
            )
        check = getattr(proposal, "check", None)
        if check is not None:
            check(self.dim_x)
        return proposal

    @property
    def weights(self):
        """Normalised weights, ``exp(log_weights)``, shape ``(n_particles,)``.

        Read-only: an edit in place (filterpy's ``weights.fill(1 / N)``) raises instead of
        changing a copy. Assign instead, ``pf.weights = w`` (non-negative, positive sum,
        normalised here; ``log_weights`` follows).
        """
        w = np.exp(self.log_weights)
        w.flags.writeable = False
        return w

    @weights.setter
    def weights(self, w):
        w = check_weights(w)
        if w.shape != (self.n_particles,):
            raise ValueError(f"weights must have shape ({self.n_particles},), got {w.shape}")
        with np.errstate(divide="ignore"):
            self.log_weights = np.log(w)

    x_prior = SettledAttribute("Predicted weighted mean after the last ``predict``, shape ``(dim_x,)`` "
                               "(formed when read).")
    P_prior = SettledAttribute("Predicted covariance after the last ``predict`` (plus ``Q`` for the Kalman "
                               "proposals).")

    x_post = SettledAttribute("Weighted mean after the last ``update``, shape ``(dim_x,)`` (formed when read).",
                              when_missing=True)
    P_post = SettledAttribute("Weighted covariance after the last ``update`` (formed when read).", when_missing=True)

    def _settle(self):
        """Form the moments left pending by ``update`` and ``predict`` (the same arithmetic, later).

        The posterior's first: after an ``update`` that a ``predict`` followed, the estimate
        ``x``/``P`` is the prediction's, and only ``x_post``/``P_post`` take the posterior's.
        """
        post = self._pending_post
        if post is not None:
            self._pending_post = None
            X, w, current = post
            x, P = _plain_moments(X, w)  # update left them pending only for the default mean and residual
            self._x_post, self._P_post = x.copy(), P.copy()
            if current:
                self._x, self._P = x, P
        pending = self._pending_prior
        if pending is None:
            return
        self._pending_prior = None
        X, log_w, spread = pending
        x, P = self._moments(self._model, X, np.exp(log_w))
        if spread is not None:
            P = P + spread
        self._x_prior, self._P_prior = x.copy(), P.copy()
        if self._x is None:  # between predict and update: the estimate is the prediction
            self._x, self._P = x, P

    def __setstate__(self, state):
        for name in ("x_post", "P_post"):  # pickled before they were formed when read
            if name in state:
                state["_" + name] = state.pop(name)
        super().__setstate__(state)

    @property
    def n_ancestors(self):
        """Distinct initial particles the current cloud descends from (see ``ancestors``)."""
        return int(np.unique(self.ancestors).size)

    @property
    def likelihood(self):
        """``exp(log_likelihood)`` of the last update."""
        return float(np.exp(self.log_likelihood))

    def initialize(self, particles, covariances=None):
        """Set the particle cloud (any starting cloud, e.g. uniform) and equal weights.

        Parameters
        ----------
        particles : array-like of shape (n_particles, dim_x)
        covariances : array-like of shape (dim_x, dim_x) or (n_particles, dim_x, dim_x), optional
            Per-particle covariances for proposals that carry them (default ``P`` for
            every particle); ignored by the others.
        """
        X = as_real(particles, "particles")
        if X.shape != (self.n_particles, self.dim_x):
            raise ValueError(
                f"particles must have shape ({self.n_particles}, {self.dim_x}), got shape {X.shape}"
            )
        if not np.all(np.isfinite(X)):
            raise ValueError("particles must be finite, got non-finite entries")
        check_scale(X, "particles")
        C = None
        if self.proposal.carries_covariance:
            C = _stack_covariances(self.P if covariances is None else covariances,
                                   "P" if covariances is None else "covariances", self.n_particles, self.dim_x)
        self.particles = X.copy()
        self.covariances = C
        self.ancestors = np.arange(self.n_particles)
        self.log_weights = _uniform_log_weights(self.n_particles)
        self._prediction = None
        self._set_posterior(self._moments(self._sync_model(), self.particles, self.weights), None)

    def _draw_initial(self):
        x = as_state(self._x, "x", self.dim_x)
        P = check_covariance(self._P, "P", self.dim_x)
        L = np.linalg.cholesky(P)
        self.initialize(x + self.rng.standard_normal((self.n_particles, self.dim_x)) @ L.T, P)

    # ------------------------------------------------------------------ helpers
    def _sync_model(self):
        """The filter's :class:`ProposalModel` (its attributes *are* the model's); ``Q`` and
        ``R`` are checked and factored only when they changed (in place too)."""
        m = self._model
        m.noise("Q")
        m.noise("R")
        return m

    @staticmethod
    def _moments(model, X, w):
        if _plain(model):
            return _plain_moments(X, w)
        x = model.mean_x(X, w)
        d = model.residual_x_rows(X, x[None, :])
        P = (d.T * w) @ d
        if P.shape[0] > 1:  # a 1x1 P is its own symmetric part, bit for bit
            P = 0.5 * (P + P.T)
        return x, P

    def _degeneracy_remedy(self):
        if isinstance(self.proposal, PriorProposal):
            return ("more particles, or a Kalman proposal that looks at the measurement "
                    "(ExtendedKalmanParticleFilter or UnscentedParticleFilter with carry_covariance=False), or "
                    "filterwnn.GaussianSumFilter")
        if getattr(self.proposal, "carries_covariance", False):
            return ("carry_covariance=False (each particle's Kalman step from Q: the one-step optimal "
                    "proposal), more particles, or filterwnn.GaussianSumFilter")
        return "more particles, a wider proposal (a larger Q in the proposal), or filterwnn.GaussianSumFilter"

    def _unexplained(self, log_lik):
        """Best particle's ``d^2`` if no particle explains ``z`` (bootstrap, Gaussian R), else None.

        Where this cannot be judged (other proposals, a custom likelihood) it returns
        ``inf``, so the ESS rule alone decides.
        """
        if log_lik is None or not isinstance(self.proposal, PriorProposal) or self.measurement_logpdf is not None:
            return np.inf
        peak = float(self._model.noise("R", check=False).logpdf(np.zeros((1, self.dim_z)))[0])
        d2 = 2.0 * (peak - float(np.max(log_lik)))
        return d2 if d2 > chdtri(self.dim_z, 1e-3) else None  # the chi^2 0.999 quantile

    def _watch_degeneracy(self, ess, log_lik=None):
        d2 = self._unexplained(log_lik) if ess < _DEGENERATE_ESS else None
        tail = chdtri(self.dim_z, _OUTLIER_TAIL) if d2 is not None and d2 != np.inf else np.inf
        if d2 is not None and d2 > tail:
            self.unexplained_steps.append(self.step)
            if len(self.unexplained_steps) == 1 and not self._warned_degenerate:
                self._warned_degenerate = True  # (one DegeneracyWarning a filter: a collapse that lasts is this one)
                warnings.warn(
                    f"{type(self).__name__}: no particle explains the measurement at step {self.step}: the best one "
                    f"is d^2 = {d2:.3g} from it (chi-square's 1e-9 tail starts at {tail:.3g}), and the weights "
                    f"collapsed onto it (ESS {ess:.3g} of "
                    f"{self.n_particles}), moving the estimate there. A gross outlier (check z's units and R), or "
                    f"particles that have lost the state (try {self._degeneracy_remedy()}); later such steps are "
                    "listed in unexplained_steps", DegeneracyWarning, stacklevel=4)
        self._low_ess_run = self._low_ess_run + 1 if d2 is not None else 0
        if self._low_ess_run >= _DEGENERATE_RUN and not self._warned_degenerate:
            self._warned_degenerate = True
            warnings.warn(
                f"{type(self).__name__}: the particle weights collapsed: the effective sample size "
                f"stayed below {_DEGENERATE_ESS:g} for {_DEGENERATE_RUN} consecutive updates (step "
                f"{self.step}: ESS {ess:.3g} of {self.n_particles} particles"
                f"{'' if d2 == np.inf else f', and the best particle d^2 = {d2:.3g} cannot explain z'}). Try "
                f"{self._degeneracy_remedy()}",
                DegeneracyWarning,
                stacklevel=4,  # the caller of predict/update, past rolls_back_on_error
            )

    def _no_measurement(self, model, step):
        """End a step without a measurement: move, keep the weights, the prior is the posterior."""
        self._settle()
        if self._prediction is not None:
            out = self.proposal.propose(model, self._prediction, None, {}, self.rng, step)
            self.particles, self.covariances = out.particles, out.covariances
            self._prediction = None
        self.x_post, self.P_post = self._x.copy(), self._P.copy()
        self._record(self.ess, self.n_particles, False)

    def _skip_measurement(self, model, step, why):
        """``recover=True``: treat the measurement as an outlier, warn, keep the prior."""
        warnings.warn(
            f"step {step}: the measurement gives {why}; skipped as an outlier (recover=True)",
            RuntimeWarning,
            stacklevel=4,  # the caller of predict/update, past rolls_back_on_error
        )
        self._no_measurement(model, step)

    # ------------------------------------------------------------------ filterpy API
    @rolls_back_on_error
    def predict(self, **fx_args):
        """Advance the time step by one and propagate the particles (the proposal's time
        update); ``fx_args`` go to ``fx`` and ``FJacobian``.

        At the first call the particles are drawn from ``N(x, P)`` unless
        :meth:`initialize` set them. Afterwards ``x_prior``/``P_prior`` (and ``x``/``P``)
        are the predicted weighted moments (for the Kalman proposals: the spread of the
        predicted means plus ``Q``).
        """
        model = self._sync_model()
        if self.particles is None:
            self._draw_initial()
        if self._prediction is not None:  # predict twice: the first one's move, no measurement
            out = self.proposal.propose(model, self._prediction, None, {}, self.rng, self.step)
            self.particles, self.covariances = out.particles, out.covariances
            self._prediction = None
        step = self.step + 1
        pred = self.proposal.predict(model, self.particles, self.covariances, fx_args, self.rng, step)
        if not (np.isfinite(pred.particles).all() and (pred.covariances is None or np.isfinite(pred.covariances).all())):
            bad = ~np.isfinite(pred.particles).all(axis=1)
            if pred.covariances is not None:
                bad |= ~np.isfinite(pred.covariances).all(axis=(1, 2))
            raise NumericalError(
                f"non-finite prediction at step {step} (particle {int(np.argmax(bad))}: check fx, FJacobian and Q)",
                matrix="particles",
                step=step,
            )
        self._prediction = pred
        self.step = step
        # the predicted moments are formed when first read (x, P, x_prior, P_prior): a filter
        # that only updates next never pays for them
        self._pending_prior = (pred.particles, self.log_weights, pred.spread)
        post = self._pending_post
        if post is not None:  # the posterior stays pending for x_post/P_post only
            self._pending_post = (post[0], post[1], False)
        self._x = self._P = None

    @rolls_back_on_error
    def update(self, z, **hx_args):
        """Weight (and resample) the particles with measurement ``z`` at the current step.

        The proposal draws the particles and their log-weight increment; the filter adds
        it, normalises, forms the moments and resamples when the ESS asks for it (then
        applies ``move``). ``z=None`` skips the measurement (the step is recorded with
        unchanged weights); a ``z`` with NaN or inf raises ``ValueError`` and leaves the
        filter unchanged; ``hx_args`` go to ``hx``, ``HJacobian`` and ``measurement_logpdf``.
        Without a preceding ``predict`` the particles are reweighted in place.

        Raises
        ------
        filterwnn.NumericalError
            When every weight underflows (the message names the step and the largest
            log-likelihood), a weight is NaN, or a particle covariance is not positive
            definite. The filter's state is left as it was before the call.
        """
        model = self._sync_model()
        if self.particles is None:
            self._draw_initial()
        step = self.step
        if z is None:
            self._no_measurement(model, step)
            return
        z = as_measurement(z, self.dim_z)
        try:
            if self._prediction is None:  # no predict since the last update: reweight in place
                ll = model.log_likelihood(z, self.particles, hx_args)
                out = (self.particles, self.covariances, ll, ll)
            else:
                out = self.proposal.propose(model, self._prediction, z, hx_args, self.rng, step)
        except NumericalError as exc:
            if not (self.recover and exc.matrix == "S"):
                raise
            self._skip_measurement(model, step, f"no usable Kalman update ({exc})")
            return
        X, covs, log_alpha, log_lik = out
        log_w = self._add_weights(model, step, log_alpha, log_lik)
        if log_w is None:
            return
        w = np.exp(log_w)
        ess = kish_ess(w)
        n_distinct = self.n_particles
        resampled = self.ess_threshold >= 1.0 or ess < self.ess_threshold * self.n_particles
        moments, Xw = self._posterior_moments(model, X, w, resampled), (X, w)
        if resampled:
            idx = self._resample(w, self.rng, self.n_particles)
            X = X.take(idx, axis=0)  # X[idx]'s copy, without fancy indexing's set-up (N = 1,000: 1.8 us, not 2.7)
            covs = None if covs is None else covs.take(idx, axis=0)
            log_w = _uniform_log_weights(self.n_particles)
            n_distinct = count_distinct(idx, self.n_particles, self._resample)
            self.ancestors = self.ancestors.take(idx)
            if self.move is not None:
                X = self._apply_move(X, step)
        self.particles, self.covariances, self.log_weights = X, covs, log_w
        self._prediction = None
        self._set_posterior(moments, Xw)
        self._record(ess, n_distinct, resampled)
        self._watch_degeneracy(ess, log_lik)

    def _posterior_moments(self, model, X, w, resampled):
        """The update's weighted moments ``(x, P)``, or None to form them at the first read of
        ``x``/``P``/``x_post``/``P_post`` from ``X`` and ``w`` as they are now: when nothing a
        user reaches holds those (``X`` resampled away; one of the package's schemes, which
        reads ``w`` and writes nothing) and the moments are pure arithmetic (no ``x_mean_fn``,
        no ``residual_x``)."""
        if resampled and _plain(model) and self._resample in _READ_ONLY_SCHEMES:
            return None
        return self._moments(model, X, w)

    def _set_posterior(self, moments, Xw):
        """``x``/``P`` and ``x_post``/``P_post`` from ``moments``, or pending on ``Xw = (X, w)``
        when ``moments`` is None (formed by ``_settle`` at the first read)."""
        if moments is None:
            self._x = self._P = self._x_post = self._P_post = None
            self._pending_post = (*Xw, True)
            return
        self._pending_post = None
        self._x, self._P = moments
        self._x_post, self._P_post = moments[0].copy(), moments[1].copy()

    def _add_weights(self, model, step, log_alpha, log_lik):
        """New normalised log-weights from the increment (None when skipped as an outlier).

        One pass in the usual case: a finite normaliser means no NaN or ``+inf`` increment
        (either would make it non-finite), so the scans for them run only when it is not.
        """
        lw_prev = self.log_weights
        new_lw = lw_prev + log_alpha if self.tempering == 1.0 else lw_prev + self.tempering * log_alpha
        lse = logsumexp(new_lw)  # a float
        if not math.isfinite(lse):
            if self._weights_failed(model, step, log_alpha, log_lik):
                return None
        log_lik_step = lse if self.tempering == 1.0 else logsumexp(lw_prev + log_alpha)
        self.log_likelihood = float(log_lik_step)
        self.log_marginal_likelihood += float(log_lik_step)
        new_lw -= lse  # a fresh array: normalised in place
        return new_lw

    def _weights_failed(self, model, step, log_alpha, log_lik):
        """The weights cannot be normalised: skip as an outlier (``recover``, True) or raise."""
        bad_weights = np.any(np.isnan(log_alpha)) or np.any(log_alpha == np.inf)
        if self.recover and (bad_weights or not np.any(log_alpha > -np.inf)):
            self._skip_measurement(model, step, "no finite particle weight (all underflow or NaN)")
            return True
        if bad_weights:
            bad = int(np.argmax(np.isnan(log_alpha) | (log_alpha == np.inf)))
            raise NumericalError(
                f"non-finite particle weight at step {step} (particle {bad}: log-weight {log_alpha[bad]})",
                matrix="weights",
                step=step,
            )
        lmax = np.max(log_alpha if log_lik is None else log_lik)
        if log_lik is None or not np.isfinite(lmax):
            detail = f"the measurement is impossible under every particle (largest log-likelihood {lmax:.6g})"
        else:
            detail = (
                f"largest log-likelihood {lmax:.6g}, but the transition density is 0 "
                f"at every sample (largest log-weight increment {np.max(log_alpha):.6g})"
            )
        raise NumericalError(f"all particle weights underflowed at step {step}: {detail}; a gross outlier (check z's "
                             "units and R) or particles that have lost the state: recover=True skips such a "
                             "measurement as an outlier", matrix="weights", step=step)

    def _apply_move(self, X, step):
        Y = np.asarray(self.move(X, self.rng), dtype=float)
        if Y.shape != X.shape or not np.all(np.isfinite(Y)):
            raise NumericalError(
                f"move must return finite particles of shape {X.shape} at step {step}, got shape {Y.shape}",
                matrix="particles",
                step=step,
            )
        return Y

    def __repr__(self):
        return (
            f"{type(self).__name__}(dim_x={self.dim_x}, dim_z={self.dim_z}, n_particles={self.n_particles}, "
            f"proposal={self.proposal!r}, resampling={self.resampling!r}, "
            f"ess_threshold={self.ess_threshold}, tempering={self.tempering}, step={self.step})"
        )


def _plain(model):
    """Whether the model keeps the default mean and residual (no ``x_mean_fn``, no ``residual_x``)."""
    return model.x_mean_fn is None and model.residual_x is None


def _plain_moments(X, w):
    """The weighted moments of :meth:`ParticleFilter._moments` without ``x_mean_fn`` and
    ``residual_x`` (the model's defaults, ``w @ X`` and ``X - x``): pure arithmetic on the
    arrays, which is what lets ``update`` leave them to the first read."""
    x = w @ X
    d = X - x[None, :]
    P = (d.T * w) @ d
    if P.shape[0] > 1:  # a 1x1 P is its own symmetric part, bit for bit
        P = 0.5 * (P + P.T)
    return x, P


def _stack_covariances(C, name, n, dim):
    """``C`` as a writable ``(n, dim, dim)`` stack (one matrix repeated, or one per row)."""
    C = np.asarray(C, dtype=float)
    if C.ndim == 2 or C.ndim == 0:
        C = np.broadcast_to(check_covariance(C, name, dim), (n, dim, dim))
    elif C.shape != (n, dim, dim):
        raise ValueError(f"{name} must have shape ({dim}, {dim}) or ({n}, {dim}, {dim}), got shape {C.shape}")
    if not np.all(np.isfinite(C)):
        raise ValueError(f"{name} must be finite, got non-finite entries")
    return np.array(C)


class _Preset(ParticleFilter):
    """A named particle filter: the issue's constructor, proposal fixed by the class."""

    _proposal_name = "prior"
    #: ``points`` when the caller passes None (the point set of the preset), or None.
    _default_points = None

    def __init__(self, dim_x, dim_z, dt, hx, fx, n_particles, *, points=None, **kwargs):
        if points is None and self._default_points is not None:
            points = self._default_points(check_positive_int(dim_x, "dim_x"))
        super().__init__(dim_x, dim_z, dt, hx, fx, n_particles, proposal=self._proposal_name, points=points,
                         **kwargs)


# the presets' signature is ParticleFilter's without ``proposal`` (fixed by the class)
_Preset.__signature__ = inspect.signature(ParticleFilter).replace(
    parameters=[p for p in inspect.signature(ParticleFilter).parameters.values() if p.name != "proposal"]
)


_PRESET_DOC = """{what}

    The constructor is shared by the four presets: ``(dim_x, dim_z, dt, hx, fx,
    n_particles, *, points=None, FJacobian=None, HJacobian=None, x_mean_fn=None,
    z_mean_fn=None, residual_x=None, residual_z=None, resampling="systematic",
    ess_threshold=1.0, vectorized=False, rng=None)`` plus the keyword-only ``tempering``,
    ``transition_logpdf``, ``process_sampler``, ``measurement_logpdf``, ``recover``,
    ``move`` and ``carry_covariance`` (Kalman proposals only); see :class:`ParticleFilter` for their meaning. {extra}
    """


class BootstrapParticleFilter(_Preset):
    __doc__ = _PRESET_DOC.format(
        what="The bootstrap particle filter (SPF): the transition prior as proposal.",
        extra="``points`` and the Jacobians are ignored.",
    )
    _proposal_name = "prior"


class ExtendedKalmanParticleFilter(_Preset):
    __doc__ = _PRESET_DOC.format(
        what="The extended Kalman particle filter (EPF): a per-particle EKF step as proposal.",
        extra="Needs ``HJacobian``, and ``FJacobian`` unless ``fx`` is None.",
    )
    _proposal_name = "extended"


class UnscentedParticleFilter(_Preset):
    __doc__ = _PRESET_DOC.format(
        what=(
            "The unscented particle filter (UPF) of van der Merwe, Doucet, de Freitas and Wan "
            "(2000): a per-particle UKF step as proposal."
        ),
        extra="``points`` defaults to the ``\"merwe\"`` preset (alpha=1, beta=2, kappa=0).",
    )
    _proposal_name = "unscented"


class SimplexUnscentedParticleFilter(_Preset):
    __doc__ = _PRESET_DOC.format(
        what="The first paper's SUPF: the UPF with reduced (n + 2) sigma points.",
        extra=(
            "``points`` defaults to the ``\"supf\"`` preset (spherical simplex, beta=2: the paper's "
            "equations with the Gaussian-optimal beta = 2 that the UPF's Merwe default also has: on "
            "van der Merwe et al.'s gamma-noise benchmark, n = 1 with a quadratic measurement, "
            "beta = 0 gives a too narrow proposal and loses to the bootstrap filter); "
            "``MinimalSkewSigmaPoints`` suits small states."
        ),
    )
    _proposal_name = "unscented"

    @staticmethod
    def _default_points(dim_x):
        return make_points("supf", dim_x)
