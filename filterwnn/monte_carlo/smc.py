r"""Posterior samples of static parameters: a MALA move and an SMC sampler.

A static parameter ``theta`` (a wavelet network's weights with ``Q = 0``) has the posterior

.. math::

    \pi(\theta) \propto p(\theta) \prod_{k=1}^{n} p(y_k \mid \theta, x_k).

A particle filter run on such a model degenerates: resampling copies particles and nothing
moves them apart again (the textbook UPF on a 160-weight network ends with one distinct
particle). The two standard cures, both provided here, move particles with an MCMC kernel
that leaves the current target invariant.

**MALA move** (:class:`MALAMove`; Roberts and Tweedie 1996). One step proposes

.. math::

    \theta' = \theta + \tfrac{h^2}{2} M \nabla \log \pi_\beta(\theta) + h M^{1/2} \xi,
    \qquad \xi \sim N(0, I),

and accepts with the Metropolis-Hastings probability
:math:`\min(1, \pi_\beta(\theta') q(\theta \mid \theta') / (\pi_\beta(\theta) q(\theta' \mid \theta)))`,
for the tempered target :math:`\pi_\beta \propto p(\theta)\, L(\theta)^\beta`. The
preconditioner ``M`` comes from the population itself: its diagonal variance
(``preconditioner="diag"``, floored at ``var_floor`` times the prior variance so that a
collapsed population does not freeze), or its covariance shrunk toward that diagonal
(``"cov"``). The step ``h`` adapts toward the acceptance 0.574 of optimally scaled MALA.
Called as ``move(particles, rng)`` it is the particle filter's resample-move hook (Gilks
and Berzuini 2001): the target is the prior times the likelihood of the rows seen so far
(:class:`RowsTarget`, which grows with :meth:`RowsTarget.append`).

**SMC sampler** (:func:`smc_sampler`; Del Moral, Doucet and Jasra 2006). Particles drawn
from the prior are carried to the posterior through the tempered targets
:math:`\pi_{\beta_t}`, :math:`0 = \beta_0 < \beta_1 < \dots < \beta_T = 1`. Each rung
reweights by :math:`L(\theta)^{\beta_{t} - \beta_{t-1}}`, where the next exponent is found by
bisection so that the ESS of the new weights is ``ess_fraction * n_particles`` (an adaptive
ladder; Jasra et al. 2011), resamples, and moves every particle with MALA steps on
:math:`\pi_{\beta_t}`. The last rung is untempered (``beta = 1``), so the particles are an
equally weighted sample of the posterior. The product of the rungs' mean incremental
weights estimates the evidence :math:`p(y_{1:n})`.

The target is anything that supplies the prior (``x0``, ``P0``), the log-likelihood of its
rows and the gradients: :class:`RowsTarget` wraps a model with
``log_prior_and_grad(thetas)`` and ``log_likelihood_and_grad(thetas, X, y)``, such as
:class:`filterwnn.wnn.weight_model.WNNWeightModel`.

Example: a conjugate Gaussian mean, whose posterior is known in closed form.

>>> import numpy as np
>>> class GaussianMean:                      # y_k ~ N(theta, 1), theta ~ N(0, 1)
...     dim_x, x0, P0 = 1, np.zeros(1), np.eye(1)
...     def log_prior_and_grad(self, thetas):
...         return -0.5 * thetas[:, 0] ** 2, -thetas
...     def log_likelihood_and_grad(self, thetas, X, y):
...         r = y[None, :] - thetas
...         return -0.5 * np.sum(r**2, axis=1), np.sum(r, axis=1, keepdims=True)
...     def log_likelihood(self, thetas, X, y):
...         return self.log_likelihood_and_grad(thetas, X, y)[0]
>>> y = np.full(9, 2.0)                      # posterior N(1.8, 0.1)
>>> res = smc_sampler(RowsTarget(GaussianMean(), np.zeros((9, 1)), y), n_particles=400, rng=0)
>>> res.betas[-1]
1.0
>>> round(float(res.particles.mean()), 1), round(float(res.particles.var()), 2)
(1.8, 0.1)
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .._validation import NumericalError, check_choice, check_positive, check_positive_int, check_rng
from ..metrics import kish_ess
from .resampling import effective_sample_size, normalize_log_weights, resample

__all__ = ["RowsTarget", "AddedRowsTarget", "MALAMove", "HMCMove", "SMCResult", "smc_sampler", "make_weight_model_move"]

#: The acceptance rate of optimally scaled MALA in high dimension (Roberts and Rosenthal 1998).
MALA_OPTIMAL_ACCEPTANCE = 0.574


class RowsTarget:
    """Prior times the likelihood of a (growing) set of rows: the posterior given them.

    Parameters
    ----------
    model : object
        Supplies ``dim_x``, the prior's mean ``x0`` and covariance ``P0`` (the prior is ``N(x0, P0)``
        unless the model has ``sample_prior(n, rng)``), ``log_prior_and_grad(thetas)``,
        ``log_likelihood(thetas, X, y)`` and ``log_likelihood_and_grad(thetas, X, y)`` batched
        over particles ``(n_particles, dim_x)`` (e.g. :class:`~filterwnn.wnn.weight_model.WNNWeightModel`).
    X : array-like of shape (n_rows, n_inputs), optional
        Rows seen so far (none by default: the target is the prior).
    y : array-like of shape (n_rows,), optional

    Attributes
    ----------
    dim : int
    prior_variance : ndarray of shape (dim,)
        ``diag(P0)``, the scale of the MALA preconditioner's floor.
    """

    def __init__(self, model, X=None, y=None):
        self.model = model
        self.dim = int(model.dim_x)
        self.prior_variance = np.diag(np.asarray(model.P0, dtype=float)).copy()
        self.X, self.y = None, None
        if X is not None:
            self.set_rows(X, y)

    @property
    def n_rows(self):
        """Number of rows in the likelihood."""
        return 0 if self.y is None else len(self.y)

    def set_rows(self, X, y):
        """Replace the rows: ``X (n_rows, n_inputs)``, ``y (n_rows,)``."""
        X = np.asarray(X, dtype=float)
        y = np.asarray(y, dtype=float).reshape(-1)
        if X.ndim != 2 or X.shape[0] != y.shape[0]:
            raise ValueError(
                f"X must have shape (n_rows, n_inputs) with one row per entry of y ({y.shape[0]}), "
                f"got shape {X.shape}"
            )
        self.X, self.y = X, y

    def append(self, x, y):
        """Add one row (``x`` of shape ``(n_inputs,)``, scalar ``y``) to the likelihood."""
        x = np.asarray(x, dtype=float).reshape(1, -1)
        y = np.asarray(y, dtype=float).reshape(1)
        if self.X is None:
            self.X, self.y = x, y
        else:
            self.X, self.y = np.vstack([self.X, x]), np.concatenate([self.y, y])

    def sample_prior(self, n, rng=None):
        """``n`` draws from the prior, ``(n, dim)``: the model's own ``sample_prior(n, rng)`` when it
        has one (a prior that is not Gaussian), else ``N(x0, P0)``."""
        n = check_positive_int(n, "n")
        rng = check_rng(rng)
        if hasattr(self.model, "sample_prior"):
            return np.asarray(self.model.sample_prior(n, rng), dtype=float)
        L = np.linalg.cholesky(np.asarray(self.model.P0, dtype=float))
        return np.asarray(self.model.x0, dtype=float) + rng.standard_normal((n, self.dim)) @ L.T

    def log_prior_and_grad(self, thetas):
        """Prior log-density ``(n_particles,)`` and gradient ``(n_particles, dim)``."""
        return self.model.log_prior_and_grad(thetas)

    def log_likelihood_and_grad(self, thetas):
        """Log-likelihood of the rows ``(n_particles,)`` and its gradient ``(n_particles, dim)``."""
        if self.n_rows == 0:
            return np.zeros(len(thetas)), np.zeros_like(thetas)
        return self.model.log_likelihood_and_grad(thetas, self.X, self.y)

    def log_likelihood(self, thetas):
        """Log-likelihood of the rows, ``(n_particles,)``."""
        if self.n_rows == 0:
            return np.zeros(len(thetas))
        return self.model.log_likelihood(thetas, self.X, self.y)


class AddedRowsTarget:
    """The posterior given a :class:`RowsTarget`'s rows, as the prior; new rows as the likelihood.

    Tempering this target from 0 to 1 (:func:`smc_sampler` started from a sample of
    ``base``'s posterior) carries the particles from ``p(theta | old rows)`` to
    ``p(theta | old and new rows)``: iterated batch importance sampling (Chopin 2002) with a
    tempered ladder per batch.

    Parameters
    ----------
    base : RowsTarget
    X : array-like of shape (n_new, n_inputs)
    y : array-like of shape (n_new,)
    """

    def __init__(self, base, X, y):
        self.base = base
        self.new = RowsTarget(base.model, X, y)
        self.dim = base.dim
        self.prior_variance = base.prior_variance

    def log_prior_and_grad(self, thetas):
        lp, gp = self.base.log_prior_and_grad(thetas)
        ll, gl = self.base.log_likelihood_and_grad(thetas)
        return lp + ll, gp + gl

    def log_likelihood_and_grad(self, thetas):
        return self.new.log_likelihood_and_grad(thetas)

    def log_likelihood(self, thetas):
        return self.new.log_likelihood(thetas)


class _State:
    """Particles with their cached prior and likelihood values and gradients."""

    def __init__(self, target, particles):
        self.x = np.array(particles, dtype=float)
        self.lp, self.gp = target.log_prior_and_grad(self.x)
        self.ll, self.gl = target.log_likelihood_and_grad(self.x)

    def take(self, idx):
        for name in ("x", "lp", "gp", "ll", "gl"):
            setattr(self, name, getattr(self, name)[idx])


class MALAMove:
    """Metropolis-adjusted Langevin steps on ``prior x likelihood**beta``, preconditioned by the population.

    Parameters
    ----------
    target : RowsTarget
        The posterior the move leaves invariant (at ``beta = 1``).
    n_steps : int, default 10
        MALA steps per call.
    step_size : float, optional
        Initial ``h`` (relative to the preconditioner); default ``1.65 * dim**(-1/3)``, the
        optimal scaling for a well-preconditioned Gaussian target.
    adapt : bool, default True
        After each step, ``h *= exp(acceptance - target_acceptance)`` (population mean
        acceptance), carried over to the next call.
    target_acceptance : float, default 0.574
    preconditioner : {"diag", "cov"}, default "diag"
        ``"diag"``: the population's variance per coordinate; ``"cov"``: the population
        covariance shrunk toward its diagonal, ``(1 - shrinkage) C + shrinkage diag(C)``,
        refused (``ValueError``) for a population of no more particles than dimensions.
        Either is estimated once per call from the population it moves, so the kernel depends
        on the particle it moves: the moves leave the target invariant only as the population
        grows (the usual adaptive SMC practice; Del Moral, Doucet and Jasra 2006). With
        ``"cov"`` at ``N <= d`` the dependence is large (a Bayesian regression's variance
        ended at 0.71 of the target's), hence the refusal.
    shrinkage : float, default 0.1
        Only for ``"cov"``.
    var_floor : float, default 1e-4
        The preconditioner's variances are at least ``var_floor * prior_variance``.
    beta : float, default 1.0
        Exponent of the likelihood (the SMC sampler sets it per rung).

    Attributes
    ----------
    acceptance_ : list of float
        Mean acceptance of every step run so far.
    step_size : float
        The current ``h``.
    """

    def __init__(
        self,
        target,
        n_steps=10,
        step_size=None,
        adapt=True,
        target_acceptance=MALA_OPTIMAL_ACCEPTANCE,
        preconditioner="diag",
        shrinkage=0.1,
        var_floor=1e-4,
        beta=1.0,
    ):
        self.target = target
        self.n_steps = check_positive_int(n_steps, "n_steps")
        self.step_size = (
            1.65 * target.dim ** (-1.0 / 3.0) if step_size is None else check_positive(step_size, "step_size")
        )
        self.adapt = bool(adapt)
        self.target_acceptance = check_positive(target_acceptance, "target_acceptance")
        self.preconditioner = check_choice(preconditioner, "preconditioner", ("diag", "cov"))
        self.shrinkage = float(shrinkage)
        if not 0.0 < self.shrinkage <= 1.0:
            raise ValueError(f"shrinkage must be in (0, 1], got {shrinkage}")
        self.var_floor = check_positive(var_floor, "var_floor")
        self.beta = check_positive(beta, "beta", strict=False)
        self.acceptance_ = []

    def __call__(self, particles, rng=None):
        """Move ``particles`` of shape ``(n_particles, dim)``; returns the moved array (a copy).

        The particle filter's ``move`` hook: call it right after resampling.
        """
        particles = np.asarray(particles, dtype=float)
        if particles.ndim != 2 or particles.shape[1] != self.target.dim:
            raise ValueError(
                f"particles must have shape (n_particles, {self.target.dim}), got shape {particles.shape}"
            )
        state = _State(self.target, particles)
        self.run(state, check_rng(rng))
        return state.x

    def _factor(self, x):
        """The preconditioner ``M`` as ``(sqrt of diag, None)`` or ``(None, lower Cholesky)``."""
        floor = self.var_floor * self.target.prior_variance
        if len(x) < 2:
            return np.sqrt(floor), None
        var = np.maximum(x.var(axis=0, ddof=1), floor)
        if self.preconditioner == "diag":
            return np.sqrt(var), None
        if len(x) <= self.target.dim:
            raise ValueError(
                f"preconditioner='cov' needs more particles than dimensions, got {len(x)} particles in "
                f"{self.target.dim} dimensions: a covariance estimated from the population it moves, with "
                "N <= d, does not leave the target invariant (on a Bayesian regression the moved variance "
                "ended at 0.71 of the target's); use preconditioner='diag', or more particles than dimensions"
            )
        # (1 - s) C + s diag(C), with the floored variances on the diagonal: positive definite
        M = (1.0 - self.shrinkage) * np.cov(x, rowvar=False)
        M[np.diag_indices_from(M)] = var
        return None, np.linalg.cholesky(0.5 * (M + M.T))

    def run(self, state, rng):
        """Run ``n_steps`` steps on a cached population (used by :func:`smc_sampler`).

        Returns
        -------
        float
            Mean acceptance over the steps.
        """
        sd, L = self._factor(state.x)
        target, beta = self.target, self.beta
        accepted = []
        for _ in range(self.n_steps):
            h = self.step_size
            g = state.gp + beta * state.gl
            xi = rng.standard_normal(state.x.shape)
            if L is None:
                drift = 0.5 * h * h * (sd * sd) * g
                prop = state.x + drift + h * sd * xi
            else:
                drift = 0.5 * h * h * (g @ L) @ L.T
                prop = state.x + drift + h * xi @ L.T
            lp, gp = target.log_prior_and_grad(prop)
            ll, gl = target.log_likelihood_and_grad(prop)
            g_new = gp + beta * gl
            # forward and reverse proposal log-densities (the shared constant cancels)
            if L is None:
                back = (state.x - prop - 0.5 * h * h * (sd * sd) * g_new) / (h * sd)
            else:
                back = np.linalg.solve(L, (state.x - prop - 0.5 * h * h * (g_new @ L) @ L.T).T).T / h
            log_q_fwd = -0.5 * np.sum(xi * xi, axis=1)
            log_q_back = -0.5 * np.sum(back * back, axis=1)
            log_alpha = (lp + beta * ll) - (state.lp + beta * state.ll) + log_q_back - log_q_fwd
            accepted.append(self._accept(state, log_alpha, rng, prop, lp, ll, gp, gl))
        return float(np.mean(accepted))

    def _accept(self, state, log_alpha, rng, x, lp, ll, gp, gl):
        """Metropolis-Hastings: take the proposed rows ``x`` (and their log-prior, log-likelihood
        and gradients) where ``log u < log_alpha``; record the acceptance rate and adapt the step."""
        log_alpha = np.where(np.isfinite(log_alpha), log_alpha, -np.inf)
        accept = np.log(rng.uniform(size=len(x))) < log_alpha
        state.x = np.where(accept[:, None], x, state.x)
        state.lp = np.where(accept, lp, state.lp)
        state.ll = np.where(accept, ll, state.ll)
        state.gp = np.where(accept[:, None], gp, state.gp)
        state.gl = np.where(accept[:, None], gl, state.gl)
        rate = float(np.mean(accept))
        self.acceptance_.append(rate)
        if self.adapt:
            self.step_size = float(self.step_size * np.exp(rate - self.target_acceptance))
        return rate


class HMCMove(MALAMove):
    """Hamiltonian Monte Carlo steps on ``prior x likelihood**beta`` (Neal 2011), mass from the population.

    Each step draws a momentum ``p ~ N(0, M^{-1})`` with ``M`` the preconditioner of
    :class:`MALAMove` (the population's floored diagonal variance, or its shrunk
    covariance), runs ``n_leapfrog`` leapfrog steps of size ``h`` (jittered by
    ``U[0.8, 1.2]`` against periodic orbits) and accepts with probability
    ``min(1, exp(H_old - H_new))``. One step costs ``n_leapfrog`` gradient evaluations and
    can travel ``n_leapfrog`` times farther than a MALA step. The step adapts toward
    acceptance 0.65 (Beskos et al. 2013).

    Parameters
    ----------
    target : RowsTarget
    n_steps : int, default 3
        HMC steps per call.
    n_leapfrog : int, default 10
    step_size : float, optional
        Initial leapfrog step relative to the preconditioner; default ``dim**(-1/4)``.
    **kwargs
        ``adapt``, ``target_acceptance`` (default 0.65), ``preconditioner``, ``shrinkage``,
        ``var_floor``, ``beta`` as in :class:`MALAMove`.
    """

    def __init__(self, target, n_steps=3, n_leapfrog=10, step_size=None, target_acceptance=0.65, **kwargs):
        super().__init__(target, n_steps=n_steps, target_acceptance=target_acceptance, **kwargs)
        self.n_leapfrog = check_positive_int(n_leapfrog, "n_leapfrog")
        self.step_size = target.dim ** (-0.25) if step_size is None else check_positive(step_size, "step_size")

    def run(self, state, rng):
        """Run ``n_steps`` HMC steps on a cached population; returns the mean acceptance."""
        sd, L = self._factor(state.x)
        target, beta = self.target, self.beta

        def scale(g):  # M g
            return (sd * sd) * g if L is None else (g @ L) @ L.T

        accepted = []
        for _ in range(self.n_steps):
            h = self.step_size * rng.uniform(0.8, 1.2)
            xi = rng.standard_normal(state.x.shape)
            # momentum in whitened form: velocity v = M p, kinetic energy |xi|^2 / 2
            v = sd * xi if L is None else xi @ L.T
            x = state.x
            lp, gp, ll, gl = state.lp, state.gp, state.ll, state.gl
            g = gp + beta * gl
            v = v + 0.5 * h * scale(g)
            with np.errstate(over="ignore", invalid="ignore"):
                for i in range(self.n_leapfrog):
                    x = x + h * v
                    lp, gp = target.log_prior_and_grad(x)
                    ll, gl = target.log_likelihood_and_grad(x)
                    g = gp + beta * gl
                    v = v + (h if i < self.n_leapfrog - 1 else 0.5 * h) * scale(g)
                xi_new = v / sd if L is None else np.linalg.solve(L, v.T).T
                log_alpha = (lp + beta * ll) - (state.lp + beta * state.ll) - 0.5 * (
                    np.sum(xi_new * xi_new, axis=1) - np.sum(xi * xi, axis=1)
                )
            accepted.append(self._accept(state, log_alpha, rng, x, lp, ll, gp, gl))
        return float(np.mean(accepted))


class SMCResult(NamedTuple):
    """What :func:`smc_sampler` returns; per-rung lists have one entry per rung of the ladder.

    Attributes
    ----------
    particles : ndarray of shape (n_particles, dim)
        Equally weighted posterior sample.
    log_likelihood : ndarray of shape (n_particles,)
        Each particle's untempered log-likelihood.
    betas : list of float
        The ladder ``beta_1 < ... < beta_T = 1`` (``beta_0 = 0`` not listed).
    ess : list of float
        ESS of the incremental weights at each rung, before resampling.
    acceptance : list of float
        Mean MALA acceptance of each rung's moves.
    step_sizes : list of float
        MALA ``h`` at the end of each rung.
    distinct_particles : list of int
        Distinct rows after each rung's moves.
    distinct_ancestors : list of int
        Distinct initial (prior) particles that the population descends from, after each rung.
    ancestors : ndarray of int, shape (n_particles,)
        Index of each final particle's initial ancestor.
    log_evidence : float
        Estimate of ``log p(y_1..n)`` (prior to posterior normalising constant).
    """

    particles: np.ndarray
    log_likelihood: np.ndarray
    betas: list
    ess: list
    acceptance: list
    step_sizes: list
    distinct_particles: list
    distinct_ancestors: list
    ancestors: np.ndarray
    log_evidence: float


def _next_beta(ll, beta, n_target):
    """Largest ``b in (beta, 1]`` whose incremental weights ``exp((b - beta) ll)`` keep ESS >= n_target."""

    def ess(delta):
        w, _ = normalize_log_weights(delta * ll)
        return kish_ess(w)

    if ess(1.0 - beta) >= n_target:
        return 1.0
    lo, hi = 0.0, 1.0 - beta
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if ess(mid) >= n_target:
            lo = mid
        else:
            hi = mid
    # lo keeps ESS >= n_target; never a zero step (progress is guaranteed)
    return beta + max(lo, 1e-12 * (1.0 - beta), np.finfo(float).eps)


def smc_sampler(target, n_particles=50, rng=None, *, move=None, n_moves=30, ess_fraction=0.5, resampling="systematic",
                max_rungs=500, particles=None):
    """Sample the posterior with a tempered SMC sampler (Del Moral, Doucet and Jasra 2006).

    Parameters
    ----------
    target : RowsTarget
        Prior, rows and gradients (see the module docstring).
    n_particles : int, default 50
    rng : None, int, SeedSequence or Generator
    move : MALAMove, optional
        The kernel used at every rung (its ``beta`` is set per rung and its step size
        adapts across rungs); default ``MALAMove(target, n_steps=n_moves)``.
    n_moves : int, default 30
        MALA steps per rung when ``move`` is not given.
    ess_fraction : float in (0, 1), default 0.5
        Each next exponent keeps the ESS of the incremental weights at
        ``ess_fraction * n_particles``.
    resampling : str, default "systematic"
        Scheme of :func:`filterwnn.monte_carlo.resampling.resample`.
    max_rungs : int, default 500
        Stop with ``RuntimeError`` if the ladder is longer (a likelihood too sharp for the
        particles: use more particles or a wider ``ess_fraction``).
    particles : array-like of shape (n_particles, dim), optional
        Draws from the prior to start from (default: :meth:`RowsTarget.sample_prior`).

    Returns
    -------
    SMCResult

    Raises
    ------
    NumericalError
        When every particle's likelihood is zero or not finite (``step`` is the rung).
    RuntimeError
        When the ladder exceeds ``max_rungs``.
    """
    rng, n_particles, ess_fraction, max_rungs = _sampler_settings(rng, n_particles, ess_fraction, max_rungs)
    if move is None:
        move = MALAMove(target, n_steps=n_moves)
    state = _State(target, _initial_particles(target, particles, n_particles, rng))
    ancestors = np.arange(n_particles)
    beta, log_z = 0.0, 0.0
    out = {k: [] for k in ("betas", "ess", "acceptance", "step_sizes", "distinct_particles", "distinct_ancestors")}
    while beta < 1.0:
        beta, log_inc, idx = _reweight_resample(state, beta, ess_fraction, max_rungs, resampling, rng, out)
        log_z += log_inc
        ancestors = ancestors[idx]
        move.beta = beta
        out["betas"].append(beta)
        out["acceptance"].append(move.run(state, rng))
        out["step_sizes"].append(move.step_size)
        out["distinct_particles"].append(int(np.unique(state.x, axis=0).shape[0]))
        out["distinct_ancestors"].append(int(np.unique(ancestors).size))
    return SMCResult(particles=state.x, log_likelihood=state.ll, ancestors=ancestors, log_evidence=float(log_z), **out)


def _sampler_settings(rng, n_particles, ess_fraction, max_rungs):
    """The sampler's checked generator, particle count, ESS fraction and rung limit."""
    rng = check_rng(rng)
    n_particles = check_positive_int(n_particles, "n_particles", minimum=2)
    ess_fraction = float(ess_fraction)
    if not 0.0 < ess_fraction < 1.0:
        raise ValueError(f"ess_fraction must be in (0, 1), got {ess_fraction}")
    return rng, n_particles, ess_fraction, check_positive_int(max_rungs, "max_rungs")


def _initial_particles(target, particles, n_particles, rng):
    """``particles`` as an array of shape ``(n_particles, target.dim)``; draws from the prior when None."""
    if particles is None:
        particles = target.sample_prior(n_particles, rng)
    particles = np.asarray(particles, dtype=float)
    if particles.shape != (n_particles, target.dim):
        raise ValueError(f"particles must have shape ({n_particles}, {target.dim}), got shape {particles.shape}")
    return particles


def _reweight_resample(state, beta, ess_fraction, max_rungs, resampling, rng, out):
    """One rung's reweighting and resampling: the next exponent, the rung's log-evidence
    increment and the resampled indices (``state`` is resampled in place, the ESS appended
    to ``out["ess"]``). RuntimeError when the ladder already has ``max_rungs`` rungs."""
    if len(out["betas"]) >= max_rungs:
        raise RuntimeError(
            f"the SMC ladder reached max_rungs={max_rungs} at beta={beta:.3g}; use more particles, "
            "more moves per rung or a larger max_rungs"
        )
    n_particles = len(state.x)
    ll = np.where(np.isfinite(state.ll), state.ll, -np.inf)
    new = _next_beta(ll, beta, ess_fraction * n_particles)
    w, log_sum = normalize_log_weights((new - beta) * ll)
    if not np.isfinite(log_sum):
        rung = len(out["betas"]) + 1
        raise NumericalError(
            f"every particle has a zero or non-finite likelihood at rung {rung} (beta={beta:.3g}); "
            "check the rows for non-finite or huge values, or widen the noise R",
            matrix="log_likelihood",
            step=rung,
        )
    out["ess"].append(effective_sample_size(w))
    idx = resample(w, resampling, rng)
    state.take(idx)
    return new, log_sum - np.log(n_particles), idx


def make_weight_model_move(model, X=None, y=None, **kwargs):
    """A :class:`MALAMove` on ``p(theta | rows seen so far)`` for a weight model: the particle filter's hook.

    The returned move's ``target`` is a :class:`RowsTarget` with the rows given (none by
    default); add each row as it is seen with ``move.target.append(x_k, y_k)`` before the
    filter's update, and pass ``move`` as ``ParticleFilter(..., move=move)``.

    The prior is the model's ``N(x0, P0)``: it must be the filter's initial distribution
    (e.g. ``x0, var = scaled_prior(X, n_hidden)`` and ``P0 = var``), or the move pulls the
    particles toward ``x0`` (zeros by default). The move's target is the static posterior
    ``p(theta | rows)``; with ``Q > 0`` the filter's target is a random walk's, which this
    move leaves invariant only approximately (exactly when ``Q = 0``).

    Parameters
    ----------
    model : WNNWeightModel
        Its ``x0``, ``P0`` are the prior, ``R`` the noise of every row.
    X : array-like of shape (n_rows, n_inputs), optional
    y : array-like of shape (n_rows,), optional
    **kwargs
        Passed to :class:`MALAMove` (``n_steps``, ``preconditioner``, ...).

    Returns
    -------
    MALAMove

    Examples
    --------
    >>> import numpy as np
    >>> from filterwnn.wnn.weight_model import WNNWeightModel
    >>> move = make_weight_model_move(WNNWeightModel(2, 3, P0=0.1), n_steps=2)
    >>> move.target.append(np.array([0.1, -0.2]), 0.3)
    >>> move(np.random.default_rng(0).normal(size=(8, 15)), rng=0).shape
    (8, 15)
    """
    return MALAMove(RowsTarget(model, X, y), **kwargs)
