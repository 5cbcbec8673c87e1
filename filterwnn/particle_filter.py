r"""Particle filters with filterpy's look: SPF, EPF, UPF and SUPF, batched over particles.

One :class:`ParticleFilter` runs the generic loop of van der Merwe, Doucet, de Freitas
and Wan (2000) (paper 1, section 3, steps 1-5); the importance proposal
(:mod:`filterwnn.proposals`) and the resampling scheme (:mod:`filterwnn.resampling`) are
arguments. For each step ``k`` and particle ``i``:

1. *Proposal*: a Kalman proposal runs one (extended or unscented) Kalman step from the
   particle's mean and covariance :math:`(x_{k-1}^{(i)}, P_{k-1}^{(i)})` with the
   measurement :math:`y_k`, giving :math:`N(\hat x_k^{(i)}, \hat P_k^{(i)})`; the prior
   proposal uses :math:`p(x_k \mid x_{k-1}^{(i)})`.
2. *Weights* (log scale), by ``weighting``:

   ``"textbook"``
       sample :math:`x_k^{(i)} \sim q` and multiply the weight by
       :math:`\alpha_i = p(y_k \mid x_k^{(i)})\, p(x_k^{(i)} \mid x_{k-1}^{(i)}) / q(x_k^{(i)})`
       (for the prior proposal :math:`\alpha_i = p(y_k \mid x_k^{(i)})`); the particle
       keeps :math:`\hat P_k^{(i)}` as its covariance.
   ``"bank"``
       no sampling: the particle *is* its Kalman filter, :math:`x_k^{(i)} = \hat x_k^{(i)}`,
       and :math:`\alpha_i = N(y_k; \hat y_k^{(i)}, S_k^{(i)})`, the innovation
       likelihood, which approximates the optimal proposal's weight
       :math:`p(y_k \mid x_{k-1}^{(i)})`. In 160 dimensions the textbook weight collapses
       (effective sample size 1 at every step in the project's prototypes); the bank
       does not.

   ``tempering`` :math:`\tau` raises the incremental weight to a power,
   :math:`w_i \propto w_i\, \alpha_i^\tau` (``tempering=0.01`` with ``ess_threshold=0``
   is the tempered, non-resampling bank that the WNN trainer uses).
3. *Estimate*: the weighted mean and covariance (the paper's eqs. 8-9),
   :math:`x = \sum_i w_i x^{(i)}`, :math:`P = \sum_i w_i (x^{(i)} - x)(x^{(i)} - x)^T`;
   in the bank, where every particle is a Gaussian, :math:`P` is the *mixture*
   covariance (:math:`+ \sum_i w_i \hat P^{(i)}`). (For sampled particles the spread of
   the samples already represents :math:`\hat P^{(i)}`; adding it again would double it.)
4. *Resample* when the effective sample size :math:`1/\sum_i w_i^2` is below
   ``ess_threshold * n_particles`` (``1.0``, the default, means every step as in the
   paper; ``0`` never), copying means and covariances.

The marginal log-likelihood :math:`\log p(y_k \mid y_{1:k-1}) \approx \log \sum_i w_{k-1,i}
\alpha_i` (untempered) is kept per step (``log_likelihood``) and summed
(``log_marginal_likelihood``).

Presets (all with the same constructor, so one script loops over them):
:class:`BootstrapParticleFilter` (SPF), :class:`ExtendedKalmanParticleFilter` (EPF),
:class:`UnscentedParticleFilter` (UPF, Merwe points) and
:class:`SimplexUnscentedParticleFilter` (the first paper's SUPF, spherical-simplex points).

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
>>> len(pf.ess_history), bool(np.isfinite(pf.log_marginal_likelihood))
(10, True)

References
----------
R. van der Merwe, A. Doucet, N. de Freitas and E. Wan, "The unscented particle filter",
Technical Report CUED/F-INFENG/TR 380, Cambridge University, 2000.
"""

from __future__ import annotations

import warnings

import numpy as np
from filterpy.kalman import MerweScaledSigmaPoints

from ._validation import (
    NumericalError,
    as_measurement,
    as_state,
    check_choice,
    check_covariance,
    check_positive,
    check_positive_int,
    check_rng,
    check_symmetric,
)
from .proposals import (
    ExtendedKalmanProposal,
    KalmanPrediction,
    PriorProposal,
    UnscentedKalmanProposal,
    _noise,
    _residual,
    measurement_logpdf,
    sample_transition,
    transition_logpdf,
)
from .resampling import get_scheme
from .sigma_points import SphericalSimplexSigmaPoints

__all__ = [
    "ParticleFilter",
    "BootstrapParticleFilter",
    "ExtendedKalmanParticleFilter",
    "UnscentedParticleFilter",
    "SimplexUnscentedParticleFilter",
]

WEIGHTINGS = ("textbook", "bank")
PROPOSALS = ("prior", "extended", "unscented", "simplex")


def _logsumexp(a):
    """``log(sum(exp(a)))`` of a 1-D array (``-inf`` if every entry is ``-inf``)."""
    m = np.max(a)
    if not np.isfinite(m):
        return float(m)
    return float(m + np.log(np.sum(np.exp(a - m))))


def _repair_pd(C):
    """Copy of the stack ``C (N, n, n)`` with every non-PD matrix's eigenvalues clipped.

    Returns the repaired stack and the number of matrices changed.
    """
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


def _check_callable(f, name, allow_none=True):
    if f is None and allow_none:
        return None
    if not callable(f):
        raise TypeError(f"{name} must be callable{' or None' if allow_none else ''}, got {type(f).__name__}")
    return f


class ParticleFilter:
    """A particle filter with a pluggable proposal and resampling, filterpy-style.

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
    proposal : {"prior", "extended", "unscented", "simplex"} or proposal object
        The importance proposal: a name, or a :class:`~filterwnn.PriorProposal`,
        :class:`~filterwnn.ExtendedKalmanProposal` or
        :class:`~filterwnn.UnscentedKalmanProposal` object. ``"unscented"`` uses
        ``points`` (default Merwe, alpha=1, beta=2, kappa=0); ``"simplex"`` uses
        ``points`` (default :class:`~filterwnn.SphericalSimplexSigmaPoints`).
    points : sigma-point object, optional
        For the unscented proposals.
    FJacobian, HJacobian : callable, optional
        ``FJacobian(x, dt, **fx_args)`` and ``HJacobian(x, **hx_args)`` for the extended
        proposal (with ``vectorized=True`` called on ``(n_particles, dim_x)`` and
        returning one matrix per row, or one shared matrix).
    x_mean_fn, z_mean_fn, residual_x, residual_z : callable, optional
        As in filterpy's ``UnscentedKalmanFilter`` (angles): ``x_mean_fn(points, weights)``,
        ``residual_x(a, b)``. With ``vectorized=True`` residuals are called on whole
        arrays. ``x_mean_fn`` also forms the weighted particle mean.
    weighting : {"textbook", "bank"}, default "textbook"
        See the module docstring. ``"bank"`` needs a Kalman proposal.
    resampling : {"systematic", "stratified", "residual", "multinomial"}
        Resampling scheme (:mod:`filterwnn.resampling`).
    ess_threshold : float in [0, 1], default 1.0
        Resample when ``ESS < ess_threshold * n_particles``; 1 means every step, 0 never.
    tempering : float > 0, default 1.0
        Exponent on the incremental weight.
    vectorized : bool, default False
        Call ``fx``, ``hx`` (and the optional callables below) once on all points.
    rng : None, int, SeedSequence, BitGenerator or Generator
        All randomness (initial draw, proposals, resampling); the same seed gives
        bit-identical output.
    transition_logpdf : callable, optional
        ``transition_logpdf(x, x_prev, **fx_args)``: log-density of the transition, for
        non-Gaussian process noise (default ``log N(x; fx(x_prev), Q)``).
    process_sampler : callable, optional
        ``process_sampler(x_prev, rng, **fx_args)``: a draw from the transition (default
        ``fx(x_prev) + N(0, Q)``). ``fx`` and ``Q`` must then be its mean and covariance,
        which the Kalman proposals use.
    measurement_logpdf : callable, optional
        ``measurement_logpdf(z, x, **hx_args)``: log-likelihood (default
        ``log N(z; hx(x), R)``). The bank weight stays the Kalman innovation likelihood.
    recover : bool, default False
        Opt-in recovery instead of :class:`~filterwnn.NumericalError` (each use warns
        with a ``RuntimeWarning`` naming the step): a particle covariance that is not
        positive definite is repaired by clipping its eigenvalues to ``1e-12`` times the
        largest (then the step is retried); a measurement under which every weight
        underflows (or is NaN) is skipped as an outlier, as if ``z`` were None.

    Attributes
    ----------
    x : ndarray of shape (dim_x,)
        State estimate; set it (and ``P``) before the first ``predict``: the particles
        are drawn from ``N(x, P)`` then, unless :meth:`initialize` set them.
    P : ndarray of shape (dim_x, dim_x)
    Q : ndarray of shape (dim_x, dim_x)
        Process noise covariance (identity by default, as in filterpy).
    R : ndarray of shape (dim_z, dim_z)
        Measurement noise covariance.
    x_prior, P_prior, x_post, P_post : ndarray
        Moments after the last ``predict`` / ``update``.
    particles : ndarray of shape (n_particles, dim_x) or None
    covariances : ndarray of shape (n_particles, dim_x, dim_x) or None
        Per-particle covariances (Kalman proposals only).
    log_weights : ndarray of shape (n_particles,)
        Normalised log-weights; ``weights`` is their exponential.
    log_likelihood : float
        ``log p(z_k | z_{1:k-1})`` estimated at the last update (``nan`` before one).
    log_marginal_likelihood : float
        Its sum over all updates, ``log p(z_{1:k})``.
    ess, n_distinct : float, int
        Effective sample size (before resampling) and number of distinct particles
        (after resampling) at the last step; ``ess_history`` and
        ``n_distinct_history`` keep one entry per ``update`` (``z=None`` included).
    resampled_history : list of bool
    step : int
        Time step: the count of ``predict`` calls (named in error messages).
    """

    _default_proposal = "prior"

    def __init__(
        self,
        dim_x,
        dim_z,
        dt,
        hx,
        fx,
        n_particles,
        proposal="prior",
        *,
        points=None,
        FJacobian=None,
        HJacobian=None,
        x_mean_fn=None,
        z_mean_fn=None,
        residual_x=None,
        residual_z=None,
        weighting="textbook",
        resampling="systematic",
        ess_threshold=1.0,
        tempering=1.0,
        vectorized=False,
        rng=None,
        transition_logpdf=None,
        process_sampler=None,
        measurement_logpdf=None,
        recover=False,
    ):
        self.dim_x = check_positive_int(dim_x, "dim_x")
        self.dim_z = check_positive_int(dim_z, "dim_z")
        self.dt = check_positive(dt, "dt")
        self.hx = _check_callable(hx, "hx", allow_none=False)
        self.fx = _check_callable(fx, "fx")
        self.n_particles = check_positive_int(n_particles, "n_particles")
        self.FJacobian = _check_callable(FJacobian, "FJacobian")
        self.HJacobian = _check_callable(HJacobian, "HJacobian")
        self.x_mean_fn = _check_callable(x_mean_fn, "x_mean_fn")
        self.z_mean_fn = _check_callable(z_mean_fn, "z_mean_fn")
        self.residual_x = _check_callable(residual_x, "residual_x")
        self.residual_z = _check_callable(residual_z, "residual_z")
        self.transition_logpdf = _check_callable(transition_logpdf, "transition_logpdf")
        self.process_sampler = _check_callable(process_sampler, "process_sampler")
        self.measurement_logpdf = _check_callable(measurement_logpdf, "measurement_logpdf")
        if not isinstance(recover, (bool, np.bool_)):
            raise TypeError(f"recover must be a bool, got {type(recover).__name__}")
        self.recover = bool(recover)
        self.weighting = check_choice(weighting, "weighting", WEIGHTINGS)
        get_scheme(resampling)  # validates the name
        self.resampling = resampling
        if isinstance(ess_threshold, bool) or not np.isscalar(ess_threshold) or not 0 <= ess_threshold <= 1:
            raise ValueError(f"ess_threshold must be a number in [0, 1], got {ess_threshold!r}")
        self.ess_threshold = float(ess_threshold)
        self.tempering = check_positive(tempering, "tempering")
        if not isinstance(vectorized, (bool, np.bool_)):
            raise TypeError(f"vectorized must be a bool, got {type(vectorized).__name__}")
        self.vectorized = bool(vectorized)
        self.rng = check_rng(rng)
        self.proposal = self._make_proposal(proposal, points)
        if self.weighting == "bank" and not self.proposal.uses_covariance:
            raise ValueError(
                "weighting='bank' needs a Kalman proposal (extended or unscented) whose particles "
                f"carry covariances, got {self.proposal!r}"
            )
        if isinstance(self.proposal, ExtendedKalmanProposal):
            if self.HJacobian is None:
                raise ValueError("the extended Kalman proposal needs HJacobian, got None")
            if self.fx is not None and self.FJacobian is None and self.proposal.uses_covariance:
                raise ValueError("the extended Kalman proposal needs FJacobian when fx is given, got None")

        # filterpy's defaults
        self.x = np.zeros(self.dim_x)
        self.P = np.eye(self.dim_x)
        self.Q = np.eye(self.dim_x)
        self.R = np.eye(self.dim_z)
        self.x_prior, self.P_prior = self.x.copy(), self.P.copy()
        self.x_post, self.P_post = self.x.copy(), self.P.copy()

        self.particles = None
        self.covariances = None
        self.log_weights = np.full(self.n_particles, -np.log(self.n_particles))
        self._pending = None
        self.step = 0
        self.log_likelihood = np.nan
        self.log_marginal_likelihood = 0.0
        self.ess = float(self.n_particles)
        self.n_distinct = self.n_particles
        self.ess_history = []
        self.n_distinct_history = []
        self.resampled_history = []

    # ------------------------------------------------------------------ set-up
    def _make_proposal(self, proposal, points):
        if isinstance(proposal, str):
            check_choice(proposal, "proposal", PROPOSALS)
            if proposal == "prior":
                return PriorProposal()
            if proposal == "extended":
                return ExtendedKalmanProposal()
            if points is None:
                if proposal == "unscented":
                    points = MerweScaledSigmaPoints(self.dim_x, alpha=1.0, beta=2.0, kappa=0.0)
                else:
                    points = SphericalSimplexSigmaPoints(self.dim_x)
            return UnscentedKalmanProposal(points)
        if not hasattr(proposal, "uses_covariance"):
            raise TypeError(
                "proposal must be a name or a proposal object (PriorProposal, "
                f"ExtendedKalmanProposal, UnscentedKalmanProposal), got {type(proposal).__name__}"
            )
        if isinstance(proposal, UnscentedKalmanProposal) and proposal.points.n != self.dim_x:
            raise ValueError(f"points.n must equal dim_x={self.dim_x}, got {proposal.points.n}")
        return proposal

    @property
    def weights(self):
        """Normalised weights, ``exp(log_weights)``, shape ``(n_particles,)``."""
        return np.exp(self.log_weights)

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
            Per-particle covariances for the Kalman proposals (default ``P`` for every
            particle). Ignored by the prior proposal.

        Notes
        -----
        The default start (means drawn from ``N(x, P)``, each particle with covariance
        ``P``, as van der Merwe et al. start the UPF) is right for textbook weights, where
        the covariances only shape the proposal. In the bank every particle is a Gaussian,
        so that start is a mixture with covariance ``2 P``; for a Gaussian-sum start that
        is exactly ``N(x, P)``, draw the means from ``N(x, P - C)`` and pass
        ``covariances=C`` (e.g. ``C = P / 2``).
        """
        X = np.asarray(particles, dtype=float)
        if X.shape != (self.n_particles, self.dim_x):
            raise ValueError(
                f"particles must have shape ({self.n_particles}, {self.dim_x}), got shape {X.shape}"
            )
        if not np.all(np.isfinite(X)):
            raise ValueError("particles must be finite, got non-finite entries")
        C = None
        if self.proposal.uses_covariance:
            if covariances is None:
                C = np.broadcast_to(check_covariance(self.P, "P", self.dim_x), (self.n_particles, self.dim_x, self.dim_x))
            else:
                C = np.asarray(covariances, dtype=float)
                if C.ndim == 2:
                    C = check_covariance(C, "covariances", self.dim_x)
                    C = np.broadcast_to(C, (self.n_particles, self.dim_x, self.dim_x))
                elif C.shape != (self.n_particles, self.dim_x, self.dim_x):
                    raise ValueError(
                        f"covariances must have shape ({self.dim_x}, {self.dim_x}) or "
                        f"({self.n_particles}, {self.dim_x}, {self.dim_x}), got shape {C.shape}"
                    )
                if not np.all(np.isfinite(C)):
                    raise ValueError("covariances must be finite, got non-finite entries")
            C = np.array(C)
        self.particles = X.copy()
        self.covariances = C
        self.log_weights = np.full(self.n_particles, -np.log(self.n_particles))
        self._pending = None
        w = self.weights
        self.x, self.P = self._moments(self.particles, w, self.covariances if self.weighting == "bank" else None)
        self.x_post, self.P_post = self.x.copy(), self.P.copy()

    def _draw_initial(self):
        x = as_state(self.x, "x", self.dim_x)
        P = check_covariance(self.P, "P", self.dim_x)
        L = np.linalg.cholesky(P)
        self.initialize(x + self.rng.standard_normal((self.n_particles, self.dim_x)) @ L.T, P)

    # ------------------------------------------------------------------ helpers
    def _repairing(self, fn, C, step, what):
        """``fn(C)``; with ``recover=True`` a covariance failure repairs ``C`` once and retries.

        Returns ``(result, C_used)``.
        """
        try:
            return fn(C), C
        except NumericalError as exc:
            if not self.recover or exc.matrix not in ("P", "P_prior") or C is None:
                raise
            C2, n_bad = _repair_pd(C)
            warnings.warn(
                f"step {step}: {n_bad} particle {what} covariance(s) not positive definite ({exc}); "
                "eigenvalues clipped (recover=True)",
                RuntimeWarning,
                stacklevel=3,
            )
            return fn(C2), C2

    def _check_Q(self):
        """``Q`` as a finite symmetric ``(dim_x, dim_x)`` array (PSD is checked where it is factored)."""
        return check_symmetric(_noise(self.Q, "Q", self.dim_x), "Q")

    def _moments(self, X, w, C=None):
        if self.x_mean_fn is None:
            x = w @ X
        else:
            x = as_state(self.x_mean_fn(X, w), "x_mean_fn(particles, weights)", self.dim_x)
        d = _residual(self.residual_x, X, x[None, :], self.vectorized)
        P = (d.T * w) @ d
        if C is not None:
            P = P + np.tensordot(w, C, axes=1)
        return x, 0.5 * (P + P.T)

    @staticmethod
    def _distinct(X):
        """Number of distinct rows (exact equality: copies made by resampling)."""
        X = np.ascontiguousarray(X)
        rows = X.view(np.dtype((np.void, X.dtype.itemsize * X.shape[1]))).ravel()
        return int(np.unique(rows).size)

    def _record(self, ess, n_distinct, resampled):
        self.ess, self.n_distinct = float(ess), int(n_distinct)
        self.ess_history.append(self.ess)
        self.n_distinct_history.append(self.n_distinct)
        self.resampled_history.append(bool(resampled))

    def _skip_measurement(self, step, why):
        """``recover=True``: treat the measurement as an outlier, warn, keep the prior."""
        warnings.warn(
            f"step {step}: the measurement gives {why}; skipped as an outlier (recover=True)",
            RuntimeWarning,
            stacklevel=3,
        )
        self._no_measurement_step()

    def _no_measurement_step(self):
        """End a step without a measurement: the prior is the posterior, nothing resampled."""
        self._finish_without_measurement()
        self.x_post, self.P_post = self.x.copy(), self.P.copy()
        self._record(self.ess, self._distinct(self.particles), False)

    def _finish_without_measurement(self):
        """Complete a pending prediction with no measurement (``z=None``)."""
        pend = self._pending
        self._pending = None
        if pend is None or pend["kind"] == "prior":
            return
        pred = pend["prediction"]
        if self.weighting == "bank":
            self.particles = pred.x
        else:
            # no measurement: the optimal proposal is the transition, weights unchanged
            self.particles = sample_transition(self, pend["x_prev"], pend["fx_args"], self.rng)
        self.covariances = pred.P if self.proposal.uses_covariance else None

    # ------------------------------------------------------------------ filterpy API
    def predict(self, **fx_args):
        """Propagate the particles one step; ``fx_args`` go to ``fx`` and ``FJacobian``.

        At the first call the particles are drawn from ``N(x, P)`` unless
        :meth:`initialize` set them. Afterwards ``x_prior``/``P_prior`` (and ``x``/``P``)
        are the predicted weighted moments: of the moved particles (prior proposal), of the
        particles' predicted means plus ``Q`` (Kalman proposals, textbook weights; the
        particles themselves move in ``update``), or of the mixture of the particles'
        predicted Gaussians (bank).
        """
        Q = self._check_Q()
        if self.particles is None:
            self._draw_initial()
        if self._pending is not None:
            self._finish_without_measurement()
        step = self.step + 1
        w = self.weights
        if getattr(self.proposal, "is_kalman", self.proposal.uses_covariance):
            pred, covs_used = self._repairing(
                lambda C: self.proposal.predict(self, self.particles, C, fx_args, step=step),
                self.covariances,
                step,
                "posterior",
            )
            if not (np.all(np.isfinite(pred.x)) and np.all(np.isfinite(pred.P))):
                bad = int(np.argmin(np.isfinite(pred.x).all(axis=1) & np.isfinite(pred.P).all(axis=(1, 2))))
                raise NumericalError(
                    f"non-finite Kalman prediction at step {step} (particle {bad}: check fx, FJacobian and Q)",
                    matrix="P_prior",
                    step=step,
                )
            self.covariances = covs_used
            self._pending = {"kind": "kalman", "x_prev": self.particles, "prediction": pred, "fx_args": fx_args}
            if self.weighting == "bank":
                x, P = self._moments(pred.x, w, pred.P)  # the mixture of the predicted Gaussians
            else:
                # sampled particles move by the transition: spread of the predicted means + Q
                x, P = self._moments(pred.x, w)
                P = P + Q
        else:
            new = self.proposal.sample(self, self.particles, fx_args, self.rng)
            if not np.all(np.isfinite(new)):
                raise NumericalError(f"non-finite particles after predict at step {step}", matrix="particles", step=step)
            self.particles = new
            self._pending = {"kind": "prior"}
            x, P = self._moments(new, w)
        self.step = step
        self.x, self.P = x, P
        self.x_prior, self.P_prior = x.copy(), P.copy()

    def update(self, z, **hx_args):
        """Weight (and resample) the particles with measurement ``z``.

        ``z=None`` skips the update (the step is recorded with unchanged weights); a ``z``
        with NaN or inf raises ``ValueError`` and leaves the filter unchanged; ``hx_args``
        go to ``hx``, ``HJacobian`` and ``measurement_logpdf``.

        Raises
        ------
        filterwnn.NumericalError
            When every weight underflows (the message names the step and the largest
            log-likelihood), a weight is NaN, or a particle covariance is not positive
            definite. The filter's state is left as it was before the call.
        """
        if z is None:
            if self.particles is None:
                self._draw_initial()
            self._no_measurement_step()
            return
        z = as_measurement(z, self.dim_z)
        check_covariance(self.R, "R", self.dim_z)
        self._check_Q()
        if self.particles is None:
            self._draw_initial()
        step = self.step
        pend = self._pending
        lw_prev = self.log_weights
        covs = None
        log_lik_max = None
        if pend is not None and pend["kind"] == "kalman":
            pred = pend["prediction"]
            try:
                upd, P_prior = self._repairing(
                    lambda C: self.proposal.update(self, KalmanPrediction(pred.x, C), z, hx_args, step=step),
                    pred.P,
                    step,
                    "predicted",
                )
            except NumericalError as exc:
                if not (self.recover and exc.matrix == "S"):
                    raise
                self._skip_measurement(step, f"no usable Kalman update ({exc})")
                return
            covs = upd.P if self.proposal.uses_covariance else None
            if self.weighting == "bank":
                X = upd.x
                log_alpha = upd.log_likelihood
            else:
                try:
                    X, log_q = self.proposal.sample(upd, self.rng, step=step, P_prior=P_prior)
                except NumericalError as exc:
                    if not self.recover or exc.matrix not in ("P", "P_prior"):
                        raise
                    repaired, n_bad = _repair_pd(upd.P)
                    covs = repaired if self.proposal.uses_covariance else None
                    warnings.warn(
                        f"step {step}: {n_bad} particle proposal covariance(s) not positive definite "
                        f"({exc}); eigenvalues clipped (recover=True)",
                        RuntimeWarning,
                        stacklevel=2,
                    )
                    upd = upd._replace(P=repaired, L_prior=None, LinvPxy=None)
                    X, log_q = self.proposal.sample(upd, self.rng, step=step)
                log_lik = measurement_logpdf(self, z, X, hx_args)
                log_tr = transition_logpdf(self, X, pend["x_prev"], pend["fx_args"])
                log_alpha = log_lik + log_tr - log_q
                log_lik_max = np.max(log_lik)
        elif self.proposal.uses_covariance and self.weighting == "bank":
            # update without predict: a Kalman update of every particle in place
            upd = self.proposal.update(
                self, KalmanPrediction(self.particles, self.covariances), z, hx_args, step=step
            )
            X, covs, log_alpha = upd.x, upd.P, upd.log_likelihood
        else:
            # bootstrap particles (or an update without predict): reweight in place
            X = self.particles
            covs = self.covariances
            log_alpha = measurement_logpdf(self, z, X, hx_args)

        bad_weights = np.any(np.isnan(log_alpha)) or np.any(log_alpha == np.inf)
        if self.recover and (bad_weights or not np.any(log_alpha > -np.inf)):
            self._skip_measurement(step, "no finite particle weight (all underflow or NaN)")
            return
        if bad_weights:
            bad = int(np.argmax(np.isnan(log_alpha) | (log_alpha == np.inf)))
            raise NumericalError(
                f"non-finite particle weight at step {step} (particle {bad}: log-weight {log_alpha[bad]})",
                matrix="weights",
                step=step,
            )
        log_inc = lw_prev + log_alpha
        log_lik_step = float(_logsumexp(log_inc))
        new_lw = lw_prev + self.tempering * log_alpha
        lse = _logsumexp(new_lw)
        if not np.isfinite(lse):
            if log_lik_max is None or not np.isfinite(log_lik_max):
                log_lik_max = np.max(log_alpha) if log_lik_max is None else log_lik_max
                detail = f"the measurement is impossible under every particle (largest log-likelihood {log_lik_max:.6g})"
            else:
                detail = (
                    f"largest log-likelihood {log_lik_max:.6g}, but the transition density is 0 "
                    f"at every sample (largest log-weight increment {np.max(log_alpha):.6g})"
                )
            raise NumericalError(
                f"all particle weights underflowed at step {step}: {detail}",
                matrix="weights",
                step=step,
            )
        new_lw = new_lw - lse
        w = np.exp(new_lw)
        ess = 1.0 / np.dot(w, w)
        bank = self.weighting == "bank"
        x, P = self._moments(X, w, covs if bank else None)

        resampled = self.ess_threshold >= 1.0 or ess < self.ess_threshold * self.n_particles
        if resampled:
            idx = get_scheme(self.resampling)(w, self.rng, self.n_particles)
            X = X[idx]
            if covs is not None:
                covs = covs[idx]
            new_lw = np.full(self.n_particles, -np.log(self.n_particles))
        # commit
        self.particles = np.ascontiguousarray(X)
        self.covariances = covs
        self.log_weights = new_lw
        self._pending = None
        self.log_likelihood = log_lik_step
        self.log_marginal_likelihood += log_lik_step
        self.x, self.P = x, P
        self.x_post, self.P_post = x.copy(), P.copy()
        self._record(ess, self._distinct(self.particles), resampled)

    def batch_filter(self, zs, fx_args=None, hx_args=None):
        """Run ``predict``/``update`` over a sequence of measurements.

        Parameters
        ----------
        zs : sequence of length n_steps of array-like of shape (dim_z,) or None
            ``None`` entries skip the update.
        fx_args, hx_args : dict, optional
            Keywords for every ``predict``/``update`` call.

        Returns
        -------
        means : ndarray of shape (n_steps, dim_x)
        covariances : ndarray of shape (n_steps, dim_x, dim_x)
        """
        fx_args = {} if fx_args is None else dict(fx_args)
        hx_args = {} if hx_args is None else dict(hx_args)
        n = len(zs)
        means = np.empty((n, self.dim_x))
        covs = np.empty((n, self.dim_x, self.dim_x))
        for k, z in enumerate(zs):
            self.predict(**fx_args)
            self.update(z, **hx_args)
            means[k], covs[k] = self.x, self.P
        return means, covs

    def __repr__(self):
        return (
            f"{type(self).__name__}(dim_x={self.dim_x}, dim_z={self.dim_z}, n_particles={self.n_particles}, "
            f"proposal={self.proposal!r}, weighting={self.weighting!r}, resampling={self.resampling!r}, "
            f"ess_threshold={self.ess_threshold}, tempering={self.tempering}, step={self.step})"
        )


class _Preset(ParticleFilter):
    """A named particle filter: the issue's constructor, proposal fixed by the class."""

    _proposal_name = "prior"

    def __init__(
        self,
        dim_x,
        dim_z,
        dt,
        hx,
        fx,
        n_particles,
        *,
        points=None,
        FJacobian=None,
        HJacobian=None,
        x_mean_fn=None,
        z_mean_fn=None,
        residual_x=None,
        residual_z=None,
        weighting="textbook",
        resampling="systematic",
        ess_threshold=1.0,
        vectorized=False,
        rng=None,
        tempering=1.0,
        transition_logpdf=None,
        process_sampler=None,
        measurement_logpdf=None,
        recover=False,
    ):
        super().__init__(
            dim_x,
            dim_z,
            dt,
            hx,
            fx,
            n_particles,
            proposal=self._proposal_name,
            points=points,
            FJacobian=FJacobian,
            HJacobian=HJacobian,
            x_mean_fn=x_mean_fn,
            z_mean_fn=z_mean_fn,
            residual_x=residual_x,
            residual_z=residual_z,
            weighting=weighting,
            resampling=resampling,
            ess_threshold=ess_threshold,
            tempering=tempering,
            vectorized=vectorized,
            rng=rng,
            transition_logpdf=transition_logpdf,
            process_sampler=process_sampler,
            measurement_logpdf=measurement_logpdf,
            recover=recover,
        )


_PRESET_DOC = """{what}

    The constructor is shared by the four presets: ``(dim_x, dim_z, dt, hx, fx,
    n_particles, *, points=None, FJacobian=None, HJacobian=None, x_mean_fn=None,
    z_mean_fn=None, residual_x=None, residual_z=None, weighting="textbook",
    resampling="systematic", ess_threshold=1.0, vectorized=False, rng=None)`` plus the
    keyword-only ``tempering``, ``transition_logpdf``, ``process_sampler`` and
    ``measurement_logpdf``; see :class:`ParticleFilter` for their meaning. {extra}
    """


class BootstrapParticleFilter(_Preset):
    __doc__ = _PRESET_DOC.format(
        what="The bootstrap particle filter (SPF): the transition prior as proposal.",
        extra="``points`` and the Jacobians are ignored; ``weighting`` must be ``'textbook'``.",
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
        extra="``points`` defaults to ``MerweScaledSigmaPoints(dim_x, alpha=1, beta=2, kappa=0)``.",
    )
    _proposal_name = "unscented"


class SimplexUnscentedParticleFilter(_Preset):
    __doc__ = _PRESET_DOC.format(
        what="The first paper's SUPF: the UPF with reduced (n + 2) sigma points.",
        extra=(
            "``points`` defaults to ``SphericalSimplexSigmaPoints(dim_x)`` (what the paper's "
            "equations give, and what works at n = 160); ``MinimalSkewSigmaPoints`` suits small states. "
            "For small states with strongly nonlinear measurements pass ``beta=2`` as the UPF's Merwe "
            "default has (on van der Merwe et al.'s gamma-noise benchmark, n = 1 and a quadratic "
            "measurement, the default ``beta=0`` gives a too narrow proposal and loses to the bootstrap "
            "filter; ``SphericalSimplexSigmaPoints(1, beta=2)`` beats it, see the tests)."
        ),
    )
    _proposal_name = "simplex"
