r"""Importance proposals for particle filters, batched over particles: a small protocol.

A particle filter moves particle ``i`` from :math:`x'_i = x_{k-1}^{(i)}` to
:math:`x_i \sim q(\cdot \mid x'_i, y_k)` and adds to its log-weight

.. math::
    \log \alpha_i = \log p(y_k \mid x_i) + \log p(x_i \mid x'_i) - \log q(x_i \mid x'_i, y_k) .

**The proposal owns its weight.** A proposal is any object with

``carries_covariance`` : bool
    whether each particle carries a covariance (Kalman proposals) or is a point;
``predict(model, particles, covariances, fx_args, rng, step) -> Prediction``
    the time update (called by the filter's ``predict``): the moved particles, or each
    particle's predicted mean (and covariance), and what ``propose`` needs later;
``propose(model, prediction, z, hx_args, rng, step) -> Proposed``
    the measurement step (called by the filter's ``update``): the new particles, their
    covariances (or None) and the log-weight increment :math:`\log \alpha_i`
    (``z=None``: no measurement, a draw from the transition and a zero increment).

The filter adds the increment, normalises, forms the moments and resamples; it never asks
what kind of proposal it holds (as in Chopin's ``particles``, where a guided model gives
both the draw and its ``logG``, and Stone Soup's ``KalmanProposal``). The proposals see
the model only through a :class:`ProposalModel` (``fx``/``hx`` on rows, residuals, the
noise ``Q``/``R`` factored once, the transition and measurement densities), never the
filter.

:class:`PriorProposal`
    :math:`q = p(x_k \mid x'_i)`, the transition prior (the bootstrap filter, SPF);
    then :math:`\log \alpha_i = \log p(y_k \mid x_i)`. Particles carry no covariance.
:class:`ExtendedKalmanProposal`
    every particle carries a mean and a covariance :math:`(x'_i, P_i)` and runs one
    extended Kalman step with ``FJacobian``/``HJacobian``; :math:`q = N(\hat x_i, \hat P_i)`
    (the EPF).
:class:`UnscentedKalmanProposal`
    the same with an unscented Kalman step on any filterpy-protocol sigma points
    (the UPF of van der Merwe, Doucet, de Freitas and Wan 2000 with Merwe points; the
    paper's SUPF with :class:`~filterwnn.SphericalSimplexSigmaPoints`).

**A singular Q** (rank :math:`r < n`, e.g. filterpy's ``Q_discrete_white_noise``): the
transition :math:`x = f(x') + G v`, :math:`Q = G G^T`, :math:`v \sim N(0, I_r)`, has a
density only on an affine subspace. The Kalman proposals then sample *in the noise
space*: :math:`v` from the Kalman posterior :math:`N(\hat x_i, \hat P_i)` conditioned on
that subspace, and weight by :math:`p(y \mid x)\, N(v; 0, I_r) / q(v)` (both densities in
the same coordinates). :meth:`ProposalModel.log_transition` evaluates the density on
Q's support and raises :class:`~filterwnn.NumericalError` naming the step for a particle
off it.

**Batched over particles.** A Kalman proposal is a user of the batched Kalman step of
:mod:`filterwnn.kalman.batched` (:class:`~filterwnn.kalman.batched.ExtendedStep`,
:class:`~filterwnn.kalman.batched.UnscentedStep`, held as ``kalman_step``): it works on
the stacks ``x (N, n)`` and ``P (N, n, n)`` at once, one stacked Cholesky factors every
particle's covariance and with ``vectorized=True`` the model is called *once* on all
``N * n_sigmas`` points. With ``dim_z == 1`` the covariance update is the rank-1 downdate
:math:`\hat P = P^- - P_{xy} P_{xy}^T / S`.

**Sampling without a second Cholesky** (``dim_z == 1``). With :math:`P^- = L L^T` and
:math:`u = L^{-1} P_{xy} / \sqrt{S}`, :math:`\hat P = L (I - u u^T) L^T`, and
:math:`(I - u u^T)^{1/2} = I - c\, u u^T` with :math:`c = (1 - \sqrt{1 - |u|^2})/|u|^2`, so

.. math::
    x = \hat x + L (\varepsilon - c\, u\, (u^T \varepsilon)), \qquad
    \log q(x) = -\tfrac12 |\varepsilon|^2 - \sum_j \log L_{jj} - \tfrac12 \log(1 - |u|^2)
               - \tfrac n2 \log 2\pi ,

instead of a second stacked Cholesky. :math:`L^{-1} P_{xy} = Z^T (W_c \circ \Delta Y)`
for the unscented step and :math:`L^T H^T` for the extended one. ``|u|^2 < 1`` holds
exactly when :math:`\hat P` is positive definite. With ``dim_z > 1`` the proposal
factors :math:`\hat P` itself. ``fx=None`` is a random walk (:math:`x^- = x, P^- = P + Q`).

>>> import numpy as np
>>> from filterwnn.kalman import make_points
>>> model = ProposalModel(2, 1, dt=1.0, fx=None, hx=lambda X: X[:, :1] ** 2,
...                       Q=0.01 * np.eye(2), R=np.array([[0.1]]), vectorized=True)
>>> prop = UnscentedKalmanProposal(make_points("merwe", 2))
>>> x, P = np.ones((3, 2)), np.tile(np.eye(2), (3, 1, 1))    # 3 particles
>>> rng = np.random.default_rng(0)
>>> pred = prop.predict(model, x, P, {}, rng, step=1)
>>> out = prop.propose(model, pred, np.array([1.2]), {}, rng, step=1)
>>> out.particles.shape, out.covariances.shape, out.log_weight.shape
((3, 2), (3, 2, 2), (3,))

References
----------
R. van der Merwe, A. Doucet, N. de Freitas and E. Wan, "The unscented particle filter",
Technical Report CUED/F-INFENG/TR 380, Cambridge University, 2000 (and NIPS 13, 2001).
A. Doucet, S. Godsill and C. Andrieu, "On sequential Monte Carlo sampling methods for
Bayesian filtering", Statistics and Computing 10, 2000.
"""

from __future__ import annotations

import warnings
from typing import Any, NamedTuple, Optional

import numpy as np

from .._linalg import LOG_2PI, cholesky, repair_pd
from .._validation import NumericalError
from ..kalman.batched import (ExtendedStep, KalmanModel, KalmanPrediction, KalmanUpdate, UnscentedStep,
                              apply_rows, noise_matrix, repairing, solve_lower)

__all__ = [
    "ProposalModel",
    "Prediction",
    "Proposed",
    "PriorProposal",
    "ExtendedKalmanProposal",
    "UnscentedKalmanProposal",
]

# ``KalmanPrediction`` and ``KalmanUpdate`` (the batched step's results) live in
# :mod:`filterwnn.kalman.batched`; they stay importable from here.


def _scalars(f, first, X, vectorized, name, kwargs):
    """A log-density ``f(first, x_row, ...)`` per row of ``X`` -> ``(m,)``."""
    m = X.shape[0]
    if vectorized:
        out = np.asarray(f(first, X, **kwargs), dtype=float).reshape(-1)
        if out.size != m:
            raise ValueError(f"{name} with vectorized=True must return shape ({m},), got {out.shape}")
        return out
    return np.array([float(f(first, X[i], **kwargs)) for i in range(m)])


class ProposalModel(KalmanModel):
    """What a proposal may use of the state-space model: a small object, not the filter.

    The batched Kalman step's :class:`~filterwnn.kalman.batched.KalmanModel` (the callables,
    the noise factored once, the model on rows) plus the densities a proposal weights with.

    Parameters
    ----------
    dim_x, dim_z, dt, fx, hx, Q, R, vectorized, FJacobian, HJacobian, x_mean_fn, z_mean_fn, residual_x, residual_z
        As in :class:`~filterwnn.kalman.batched.KalmanModel` (the callables as in
        :class:`~filterwnn.ParticleFilter`).
    process_sampler, transition_logpdf, measurement_logpdf : callable, optional
        Non-Gaussian transition and likelihood (see :class:`~filterwnn.ParticleFilter`).
    recover : bool
        Kalman proposals repair a non-PD particle covariance (with a warning) instead of
        raising.

    Attributes are plain and may be reassigned.
    """

    def __init__(self, dim_x, dim_z, dt=1.0, fx=None, hx=None, Q=None, R=None, *, vectorized=False,
                 FJacobian=None, HJacobian=None, x_mean_fn=None, z_mean_fn=None, residual_x=None,
                 residual_z=None, process_sampler=None, transition_logpdf=None, measurement_logpdf=None,
                 recover=False):
        super().__init__(dim_x, dim_z, dt, fx, hx, Q, R, vectorized=vectorized, FJacobian=FJacobian,
                         HJacobian=HJacobian, x_mean_fn=x_mean_fn, z_mean_fn=z_mean_fn, residual_x=residual_x,
                         residual_z=residual_z, recover=recover)
        self.process_sampler = process_sampler
        self.transition_logpdf = transition_logpdf
        self.measurement_logpdf = measurement_logpdf

    # --- densities ----------------------------------------------------------------------
    def sample_transition(self, x_prev, fx_args, rng):
        """Draw ``x_i ~ p(x_k | x_prev_i)`` for every row -> ``(N, dim_x)``.

        ``process_sampler(x_prev, rng, **fx_args)`` when given, else ``fx(x_prev) + w``
        with ``w ~ N(0, Q)`` (``Q`` may be singular).
        """
        if self.process_sampler is not None:
            return apply_rows(self.process_sampler, x_prev, self.dim_x, self.vectorized, "process_sampler",
                         (rng,), fx_args)
        mean = self.transition_mean(x_prev, fx_args)
        A = self.noise("Q", check=False).sqrt
        e = rng.standard_normal(mean.shape)
        if self.dim_x == 1:
            e *= A[0, 0]
        else:
            e = e @ A.T
        e += mean  # mean + e, bit for bit (addition commutes), in e's storage: no temporary
        return e

    def log_transition(self, x, x_prev, fx_args, fx_prev=None, step=None):
        """``log p(x_i | x_prev_i)`` for every row -> ``(N,)``.

        ``transition_logpdf(x, x_prev, **fx_args)`` when given, else
        ``log N(residual_x(x, fx(x_prev)); 0, Q)``, on Q's support when Q is singular
        (a row off the support raises :class:`~filterwnn.NumericalError` naming ``step``).
        ``fx_prev`` may pass ``fx(x_prev)`` when already computed.
        """
        f = self.transition_logpdf
        if f is not None:
            if self.vectorized:
                return np.asarray(f(x, x_prev, **fx_args), dtype=float).reshape(-1)
            return np.array([float(f(x[i], x_prev[i], **fx_args)) for i in range(x.shape[0])])
        mean = self.transition_mean(x_prev, fx_args) if fx_prev is None else fx_prev
        return self.noise("Q").logpdf(self.residual_x_rows(x, mean), step=step)

    def log_likelihood(self, z, X, hx_args):
        """``log p(z | x_i)`` for every row -> ``(N,)``.

        ``measurement_logpdf(z, x, **hx_args)`` when given, else
        ``log N(residual_z(z, hx(x_i)); 0, R)``.
        """
        if self.measurement_logpdf is not None:
            return _scalars(self.measurement_logpdf, z, X, self.vectorized, "measurement_logpdf", hx_args)
        y = self.residual_z_rows(z[None, :], self.measure(X, hx_args))
        return self.noise("R", check=False).logpdf(y)


class Prediction(NamedTuple):
    """What a proposal's ``predict`` hands to the filter (and back to its ``propose``).

    Attributes
    ----------
    particles : ndarray of shape (n_particles, dim_x)
        The moved particles, or every particle's predicted mean (Kalman proposals).
    covariances : ndarray of shape (n_particles, dim_x, dim_x) or None
        Per-particle predicted covariances.
    spread : ndarray of shape (dim_x, dim_x) or None
        Added to the weighted spread of ``particles`` to give the predicted covariance
        (``Q`` when the particles themselves move only in ``propose``).
    context : object
        Anything the proposal's ``propose`` needs (the previous particles, ``fx_args``).
    """

    particles: np.ndarray
    covariances: Optional[np.ndarray] = None
    spread: Optional[np.ndarray] = None
    context: Any = None


class Proposed(NamedTuple):
    """What a proposal's ``propose`` returns.

    Attributes
    ----------
    particles : ndarray of shape (n_particles, dim_x)
    covariances : ndarray of shape (n_particles, dim_x, dim_x) or None
    log_weight : ndarray of shape (n_particles,)
        The increment ``log p(z|x) + log p(x|x') - log q(x|x', z)`` (zeros for ``z=None``).
    log_likelihood : ndarray of shape (n_particles,) or None
        ``log p(z|x_i)`` alone, for error messages (None when not computed).
    """

    particles: np.ndarray
    covariances: Optional[np.ndarray]
    log_weight: np.ndarray
    log_likelihood: Optional[np.ndarray] = None


class PriorProposal:
    """The transition prior ``q = p(x_k | x_{k-1})``: the bootstrap (SPF) proposal.

    Particles carry no covariance; the log-weight increment is the log-likelihood
    ``log p(y_k | x_k)``. Sampling uses ``process_sampler`` when the model has one, else
    ``fx(x) + N(0, Q)`` (``Q`` may be singular).
    """

    carries_covariance = False

    def predict(self, model, particles, covariances, fx_args, rng, step=None):
        """Move every particle by the transition -> :class:`Prediction`."""
        return Prediction(model.sample_transition(particles, fx_args, rng))

    def propose(self, model, prediction, z, hx_args, rng, step=None):
        """Weight the moved particles by the likelihood -> :class:`Proposed`."""
        X = prediction.particles
        if z is None:
            return Proposed(X, None, np.zeros(X.shape[0]))
        log_lik = model.log_likelihood(z, X, hx_args)
        return Proposed(X, None, log_lik, log_lik)

    def __repr__(self):
        return "PriorProposal()"


class _KalmanContext(NamedTuple):
    x_prev: np.ndarray
    fx_args: dict


class _KalmanProposal:
    r"""A Kalman step per particle as proposal, ``q = N(x_hat_i, P_hat_i)``.

    ``carry_covariance=True`` (van der Merwe et al.'s UPF) starts each particle's Kalman
    step from the particle's own covariance ``P_i``, which it carries from step to step.
    ``carry_covariance=False`` starts it from the particle as a point, ``P^- = Q`` and
    ``x^- = f(x'_i)``: the local linearisation of the optimal proposal
    :math:`p(x_k \mid x'_i, y_k)` (Doucet, Godsill and Andrieu 2000, sec. II-D; exact for
    linear-Gaussian models; it needs a positive definite ``Q``). Its weights stay
    balanced where the carried covariance is much wider than ``Q``.
    """

    def __init__(self, carry_covariance=True):
        if not isinstance(carry_covariance, (bool, np.bool_)):
            raise TypeError(f"carry_covariance must be a bool, got {type(carry_covariance).__name__}")
        self.carry_covariance = bool(carry_covariance)

    @property
    def carries_covariance(self):
        """Whether particles carry covariances (``carry_covariance``)."""
        return self.carry_covariance

    # --- the protocol -------------------------------------------------------------------
    def predict(self, model, particles, covariances, fx_args, rng, step=None):
        """Every particle's Kalman prediction -> :class:`Prediction` (spread ``Q``)."""
        P = covariances if self.carry_covariance else None
        pred, _ = repairing(model, lambda C: self.kalman_predict(model, particles, C, fx_args, step),
                            P, step, "posterior", stacklevel=6)  # past rolls_back_on_error
        Q = noise_matrix(model.Q, "Q", model.dim_x)
        return Prediction(pred.x, pred.P, Q, _KalmanContext(particles, fx_args))

    def propose(self, model, prediction, z, hx_args, rng, step=None):
        """Kalman update, one draw from ``N(x_hat_i, P_hat_i)`` and its weight -> :class:`Proposed`."""
        ctx = prediction.context
        if z is None:  # no measurement: the optimal proposal is the transition, zero increment
            X = model.sample_transition(ctx.x_prev, ctx.fx_args, rng)
            return Proposed(X, prediction.covariances if self.carry_covariance else None, np.zeros(X.shape[0]))
        upd, P_prior = repairing(
            model,
            lambda C: self.kalman_update(model, KalmanPrediction(prediction.particles, C), z, hx_args, step),
            prediction.covariances, step, "predicted", stacklevel=6,  # past rolls_back_on_error
        )
        singular = model.transition_logpdf is None and not model.noise("Q").full_rank
        fx_prev = model.transition_mean(ctx.x_prev, ctx.fx_args) if singular or model.transition_logpdf is None else None
        if singular:
            if not self.carry_covariance:
                raise ValueError("carry_covariance=False needs a positive definite Q (P^- = Q); Q is singular")
            X, log_ratio = self._sample_noise_space(model, upd, fx_prev, rng, step)
            log_lik = model.log_likelihood(z, X, hx_args)
            return Proposed(X, upd.P, log_lik + log_ratio, log_lik)
        try:
            X, log_q = self.sample(upd, rng, step=step, P_prior=P_prior)
        except NumericalError as exc:
            if not model.recover or exc.matrix not in ("P", "P_prior"):
                raise
            repaired, n_bad = repair_pd(upd.P)
            warnings.warn(
                f"step {step}: {n_bad} particle proposal covariance(s) not positive definite "
                f"({exc}); eigenvalues clipped (recover=True)",
                RuntimeWarning,
                stacklevel=5,  # past rolls_back_on_error
            )
            upd = upd._replace(P=repaired, L_prior=None, LinvPxy=None)
            X, log_q = self.sample(upd, rng, step=step)
        log_lik = model.log_likelihood(z, X, hx_args)
        log_tr = model.log_transition(X, ctx.x_prev, ctx.fx_args, fx_prev=fx_prev, step=step)
        covs = upd.P if self.carry_covariance else None
        return Proposed(X, covs, log_lik + log_tr - log_q, log_lik)

    @staticmethod
    def _sample_noise_space(model, upd, fx_prev, rng, step):
        r"""Singular ``Q = G G^T``: ``x = f(x') + G v`` with ``v`` from ``N(x_hat, P_hat)``
        conditioned on that subspace; returns ``x`` and ``log N(v; 0, I) - log q(v)``."""
        G = model.noise("Q").G
        N, n = upd.x.shape
        r = G.shape[1]
        Lp = cholesky(upd.P, "P", step)
        B = solve_lower(Lp, np.broadcast_to(G, (N, n, r)))
        c = solve_lower(Lp, (upd.x - fx_prev)[:, :, None])
        A = np.matmul(np.swapaxes(B, -1, -2), B)  # precision of v under q
        b = np.matmul(np.swapaxes(B, -1, -2), c)[:, :, 0]
        LA = cholesky(A, "noise-space proposal precision", step)
        v_hat = np.linalg.solve(A, b[:, :, None])[:, :, 0]
        eps = rng.standard_normal((N, r))
        v = v_hat + np.linalg.solve(np.swapaxes(LA, -1, -2), eps[:, :, None])[:, :, 0]
        log_q = -0.5 * np.sum(eps * eps, axis=1) + np.sum(np.log(np.diagonal(LA, axis1=1, axis2=2)), axis=1)
        log_p = -0.5 * np.sum(v * v, axis=1)
        return fx_prev + v @ G.T, log_p - log_q

    # --- the Kalman steps ---------------------------------------------------------------
    def kalman_predict(self, model, x, P, fx_args, step=None):
        """Every particle's predicted ``(x (N, n), P (N, n, n))`` -> ``KalmanPrediction``:
        the batched step's, or from the particle as a point (``P`` None: ``x^- = f(x)``,
        ``P^- = Q``, a broadcast view)."""
        self.kalman_step.check(model.dim_x)
        if P is None:
            Q = noise_matrix(model.Q, "Q", model.dim_x)
            return KalmanPrediction(model.transition_mean(x, fx_args), np.broadcast_to(Q, (x.shape[0],) + Q.shape))
        return self.kalman_step.predict(model, x, P, fx_args, step)

    def kalman_update(self, model, prediction, z, hx_args, step=None):
        """The batched step's update with ``z (dim_z,)`` -> ``KalmanUpdate``."""
        return self.kalman_step.update(model, prediction, z, hx_args, step)

    def check(self, dim_x):
        """Raise ``ValueError`` when the proposal's step does not fit a ``dim_x`` state."""
        self.kalman_step.check(dim_x)

    @staticmethod
    def _with_factor(upd, P_prior, step):
        """``upd`` with ``L_prior`` and ``LinvPxy`` filled in (at most one Cholesky, no solve
        for the extended and unscented steps)."""
        if upd.L_prior is None:
            if P_prior is None:
                raise ValueError("P_prior is needed to factor the predicted covariance")
            upd = upd._replace(L_prior=cholesky(P_prior, "P_prior", step))
        if upd.LinvPxy is None:
            if upd.H is not None:
                LinvPxy = np.matmul(np.swapaxes(upd.L_prior, -1, -2), np.swapaxes(upd.H, -1, -2))
            else:
                LinvPxy = solve_lower(upd.L_prior, upd.Pxy)
            upd = upd._replace(LinvPxy=LinvPxy)
        return upd

    @staticmethod
    def _rank1(upd, step):
        """``u = L^{-1} Pxy / sqrt(S)`` and ``|u|^2`` (``dim_z == 1``)."""
        u = upd.LinvPxy[:, :, 0] / np.sqrt(upd.S[:, 0:1, 0])
        r2 = np.sum(u * u, axis=1)
        if not np.all(r2 < 1.0):
            bad = int(np.argmax(~(r2 < 1.0)))
            raise NumericalError(
                f"posterior covariance of particle {bad} is not positive definite at step {step} "
                f"(|u|^2 = {r2[bad]:.6g} >= 1)",
                matrix="P",
                step=step,
            )
        return upd.L_prior, u, r2

    def sample(self, upd, rng, step=None, P_prior=None):
        """Draw one sample per particle from ``N(x_hat_i, P_hat_i)`` and its log-density.

        Parameters
        ----------
        upd : KalmanUpdate
        rng : numpy.random.Generator
        step : int, optional
            For error messages.
        P_prior : ndarray of shape (n_particles, dim_x, dim_x), optional
            Predicted covariances, factored here when ``upd.L_prior`` is None and
            ``dim_z == 1`` (the rank-1 path).

        Returns
        -------
        x : ndarray of shape (n_particles, dim_x)
        log_q : ndarray of shape (n_particles,)
        """
        N, n = upd.x.shape
        eps = rng.standard_normal((N, n))
        if upd.S.shape[-1] == 1 and (upd.L_prior is not None or P_prior is not None):
            upd = self._with_factor(upd, P_prior, step)
            L, u, r2 = self._rank1(upd, step)
            with np.errstate(invalid="ignore", divide="ignore"):
                c = np.where(r2 > 1e-300, (1.0 - np.sqrt(1.0 - r2)) / np.where(r2 > 0, r2, 1.0), 0.5)
            v = eps - (c * np.sum(u * eps, axis=1))[:, None] * u
            x = upd.x + np.matmul(L, v[:, :, None])[:, :, 0]
            logdet = 2.0 * np.sum(np.log(np.diagonal(L, axis1=1, axis2=2)), axis=1) + np.log1p(-r2)
        else:
            Lp = cholesky(upd.P, "P", step)
            x = upd.x + np.matmul(Lp, eps[:, :, None])[:, :, 0]
            logdet = 2.0 * np.sum(np.log(np.diagonal(Lp, axis1=1, axis2=2)), axis=1)
        log_q = -0.5 * (np.sum(eps * eps, axis=1) + logdet + n * LOG_2PI)
        return x, log_q

    def logpdf(self, upd, x, step=None, P_prior=None):
        """``log N(x_i; x_hat_i, P_hat_i)`` for one point per particle -> ``(n_particles,)``.

        Uses the rank-1 form (one triangular solve) when ``dim_z == 1`` and the
        predicted factor is known, else a Cholesky of ``P_hat``.
        """
        N, n = upd.x.shape
        d = np.asarray(x, dtype=float) - upd.x
        if upd.S.shape[-1] == 1 and (upd.L_prior is not None or P_prior is not None):
            upd = self._with_factor(upd, P_prior, step)
            L, u, r2 = self._rank1(upd, step)
            e = solve_lower(L, d[:, :, None])[:, :, 0]
            ue = np.sum(u * e, axis=1)
            maha = np.sum(e * e, axis=1) + ue * ue / (1.0 - r2)
            logdet = 2.0 * np.sum(np.log(np.diagonal(L, axis1=1, axis2=2)), axis=1) + np.log1p(-r2)
        else:
            Lp = cholesky(upd.P, "P", step)
            e = solve_lower(Lp, d[:, :, None])[:, :, 0]
            maha = np.sum(e * e, axis=1)
            logdet = 2.0 * np.sum(np.log(np.diagonal(Lp, axis1=1, axis2=2)), axis=1)
        return -0.5 * (maha + logdet + n * LOG_2PI)

    def __repr__(self):
        extra = "" if self.carry_covariance else "carry_covariance=False"
        return f"{type(self).__name__}({extra})"


class ExtendedKalmanProposal(_KalmanProposal):
    """One extended Kalman step per particle (the EPF proposal).

    The step is :class:`~filterwnn.kalman.batched.ExtendedStep`: predict
    :math:`x^-_i = f(x_i)`, :math:`P^-_i = F_i P_i F_i^T + Q` with
    ``F_i = FJacobian(x_i, dt, **fx_args)`` (random walk when ``fx`` is None); update with
    ``H_i = HJacobian(x^-_i, **hx_args)``, :math:`P_{xy} = P^- H^T`,
    :math:`S = H P^- H^T + R`. With ``vectorized=True`` the Jacobians are called once on
    all particles (``(N, dim_x)`` in, ``(N, rows, dim_x)`` or one shared matrix out).
    """

    def __init__(self, carry_covariance=True):
        super().__init__(carry_covariance)
        self.kalman_step = ExtendedStep()


class UnscentedKalmanProposal(_KalmanProposal):
    """One unscented Kalman step per particle (the UPF proposal; SUPF with reduced points).

    Parameters
    ----------
    points : sigma-point object
        The set of the step (:class:`~filterwnn.kalman.batched.UnscentedStep`: any
        filterpy-protocol set, the structured ones built in O(n^2) per particle).
    carry_covariance : bool, default True

    Notes
    -----
    The step is :class:`~filterwnn.kalman.batched.UnscentedStep`: as filterpy 2.0 does,
    the update draws fresh sigma points from the predicted ``(x^-_i, P^-_i)``; the factor
    of ``P^-_i`` is kept for the rank-1 sampling. With ``fx=None`` the predict is
    ``P^- = P + Q`` and a step costs one stacked Cholesky.
    """

    def __init__(self, points, carry_covariance=True):
        super().__init__(carry_covariance)
        self.kalman_step = UnscentedStep(points)

    @property
    def points(self):
        """The sigma-point set of the step."""
        return self.kalman_step.points

    def __repr__(self):
        extra = "" if self.carry_covariance else ", carry_covariance=False"
        return f"UnscentedKalmanProposal(points={type(self.points).__name__}(n={self.points.n}){extra})"
