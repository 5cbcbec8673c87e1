r"""WNN trainers: one table, :data:`TRAINERS`, of the filters that train a wavelet network.

Training a WNN with a filter is running the filter on the weight-state model of
:mod:`filterwnn.wnn.weight_model` (``theta_k = theta_{k-1} + u_k``, ``y_k = WNN(theta_k, x_k) + v_k``),
one training sample per step, epoch after epoch (Niu, Wu and Li, Sec. 4). A trainer is one
:class:`TrainerSpec` entry: its class, its family (what the estimator resolves for it), the
filter class, points and Jacobian it builds and its ``"auto"`` settings per start: how to
train, nothing more (the WNN study's rows, grids, costs, labels and the paper's Table 1 live in
the study, :data:`filterwnn.studies.wnn.rows.STUDY`). :class:`filterwnn.WNNRegressor` reads only
this table; :func:`register_trainer` adds one. The trainers, by name:

``"bp"``
    back-propagation: per-sample gradient descent on the squared error (the baseline).
``"ekf"``
    extended Kalman filter. By default a rank-1 EKF written for ``dim_z = 1``
    (``backend="rank1"``): the same equations as filterpy's
    :class:`~filterpy.kalman.ExtendedKalmanFilter` (which the tests check it against
    step by step), about 10x faster because it skips filterpy's dense ``(I - K H)``
    Joseph products; ``ekf_backend="filterpy"`` runs filterpy's class itself.
``"ukf"``, ``"sukf"``
    :class:`filterwnn.kalman.unscented.UnscentedKalmanFilter` (vectorized, ``fx=None``) with
    Merwe's ``2n + 1`` points (``alpha=1, beta=2, kappa=0``) or the ``n + 2`` spherical
    simplex points (Julier 2003; the paper's SUKF).
``"spf"``, ``"epf"``, ``"upf"``, ``"supf"``
    the papers' particle filters (:mod:`filterwnn.monte_carlo.particle_filter`): bootstrap, and the EKF-,
    UKF- and simplex-UKF-proposal filters, with the textbook weights
    ``p(y|x) p(x|x') / q(x)`` and resampling at ESS < N/2. Without a move they degenerate to
    one particle in 160 dimensions (see the findings). ``move="mala"`` or ``"hmc"`` adds an MCMC
    move after every resampling (resample-move, Gilks and Berzuini 2001;
    :func:`filterwnn.monte_carlo.smc.make_weight_model_move`): the move leaves the static posterior
    ``p(theta | rows seen)`` invariant, each row joins its target before the row's update, its
    prior is the filter's initial distribution (the Gaussian matched to the start, as for
    ``"smc"``), and Q is 0. A second pass over the rows counts them again (the filter's weights
    and the move's target alike), so ``n_epochs=1`` is the posterior. Predictions average the
    particles' outputs with their weights.
``"gsf-ekf"``, ``"gsf-ukf"``, ``"gsf-sukf"``
    Gaussian-sum filters (:class:`filterwnn.GaussianSumFilter`) of ``n_particles`` EKF, UKF or
    SUKF components, each weighted by its innovation likelihood ``N(y_k; y_hat_i, S_i)`` raised
    to ``tempering`` (default 1, the Bayesian mixture; the WNN study's working rows use 0.01, a
    heuristic; these were the former ``weighting="bank"`` of epf/upf/supf). Not particle filters:
    the components are Gaussians, drawn once at the start.
``"ekf-ensemble"``
    ``n_particles`` independent EKFs from ``n_particles`` starts, their predictions averaged
    without weights (``GaussianSumFilter(combine="mean")``): the baseline that tells the Gaussian
    sum's weights from plain averaging.
``"smc"``
    a tempered SMC sampler over all training rows (:func:`filterwnn.monte_carlo.smc.smc_sampler`; Del
    Moral, Doucet and Jasra 2006): ``n_particles`` draws from a Gaussian prior matched to
    the start (:func:`filterwnn.wnn.weight_model.scaled_prior`, output weights of sd 1.0; for
    ``init="paper"`` the moments of U[0, 1]) are carried to the posterior ``p(theta | rows)``
    (``Q = 0``) on an adaptive ladder of likelihood exponents that keeps the ESS at N/2, with
    resampling and MCMC moves at every rung (by default 6 HMC steps of 10 leapfrogs each,
    :class:`filterwnn.monte_carlo.smc.HMCMove`; ``kernel="mala"`` in the settings for MALA), untempered at
    the end. The first epoch runs the sampler; each later epoch runs the same moves again on
    the posterior (still a posterior sample), so ``n_epochs=1`` is the plain sampler;
    ``partial_fit`` with new rows tempers their likelihood in from the current particles
    (iterated batch importance sampling; chunks are not bit-for-bit one pass here). R is
    part of the posterior: ``measurement_noise=0.03`` measured better than the default 0.1
    on validation rows (``benchmarks/smc_siso.py``; disclosed there: R was searched after
    its test coverage was seen). Predictions are the particles' mean output, with variance
    the particles' spread plus R.
``"smc-noise"``
    the same sampler with the noise learned: ``s = log R`` is one more coordinate of the
    state, with the prior ``N(log 0.1, 2^2)``, and the particles sample the joint posterior of
    the weights and R (``measurement_noise`` is not used). Predictive variance: the spread of
    the particles' outputs plus their mean ``exp(s_i)``.
``"smc-noise-10x10"``
    ``"smc-noise"`` with 10 HMC steps of 10 leapfrogs per rung (not 6): the moves that
    ``benchmarks/smc_posterior_d160.py --choose 6000`` picked with N = 60 at a fixed budget of
    6000 particle-gradient evaluations per rung (the cloud holds 0.80 of a known d = 160
    posterior's variance there; 0.39 at ``"smc"``'s N = 20 x 6 steps). Use it with
    ``n_particles=60``.
``"smc-student-10x10"``
    ``"smc-noise-10x10"``'s sampler (10 HMC steps of 10 leapfrogs per rung; use it with
    ``n_particles=60``) with a Student-t likelihood ``y_k ~ t_nu(WNN(theta, x_k), sigma^2)``:
    ``s = log sigma^2`` (prior ``N(log 0.1, 2^2)``, as ``"smc-noise"``'s ``log R``) and
    ``u = log nu`` (prior ``nu ~ Gamma(2, rate 0.1)``, Juarez and Steel 2010) join the weights
    in the state. For a plant whose residuals are the network's heavy-tailed error, not
    Gaussian noise. Its predictive is the particles' mixture of t's
    (:class:`filterwnn.wnn.predictive.StudentTMixture`): intervals from the mixture's quantiles,
    density from the mixture.

``"auto"`` noise settings (``process_noise`` Q, ``initial_covariance`` P0) are per trainer and
start (:data:`AUTO_SETTINGS`, from each entry's ``auto``): for the scaled start, what the WNN study chose on a validation
split (``filterwnn study wnn``, ``docs/study-outputs/wnn/tuning.md``). The paper's ``Q = 1``
does not work literally (UKF/SUKF end worse than the mean predictor).

>>> sorted(TRAINERS)[:4]
['bp', 'ekf', 'ekf-ensemble', 'epf']
>>> spec = TRAINERS["upf"]
>>> spec.family, spec.filter.__name__, spec.points.__name__
('particle', 'UnscentedParticleFilter', 'merwe_points')
>>> AUTO_SETTINGS[("upf", "scaled")]
{'Q': 1e-05, 'P0': 0.01}

A new trainer is one :func:`register_trainer` call (see ``tests/wnn/test_trainers.py``);
:class:`~filterwnn.WNNRegressor` and the WNN study then accept its name.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from filterpy.kalman import ExtendedKalmanFilter
from scipy.linalg.blas import dsymv, dsyr
from scipy.special import gammaln, polygamma, psi

from ..monte_carlo import smc
from . import network as wnn
from .._validation import NumericalError, check_choice, check_rng
from ..monte_carlo.gaussian_sum import GaussianSumFilter
from ..monte_carlo.particle_filter import (
    BootstrapParticleFilter,
    ExtendedKalmanParticleFilter,
    SimplexUnscentedParticleFilter,
    UnscentedParticleFilter,
)
from ..kalman.presets import make_points
from ..models import from_model
from ..kalman.unscented import UnscentedKalmanFilter
from .predictive import GaussianPredictive, StudentTMixture
from .weight_model import WNNWeightModel, scaled_prior

__all__ = [
    "TrainerSpec",
    "BaseTrainer",
    "TRAINERS",
    "AUTO_SETTINGS",
    "PAPER_SETTINGS",
    "MOVES",
    "MOVE_SETTINGS",
    "FAMILIES",
    "register_trainer",
    "unregister_trainer",
    "get_trainer",
    "make_trainer",
    "merwe_points",
    "simplex_points",
]

#: The trainer families, each a set of settings the estimator resolves: ``"gradient"`` (a
#: learning rate, no Q or P0), ``"single"`` (Q and P0, one start), ``"particle"`` (Q and P0, one
#: start per particle, textbook weights, an optional MCMC move), ``"gaussian-sum"`` (one start per
#: component, likelihood-weighted or averaged components) and ``"smc"`` (a static posterior:
#: the entry's ``auto`` settings configure the sampler).
FAMILIES = ("gradient", "single", "particle", "gaussian-sum", "smc")

#: The paper's literal settings (Sec. 5): Q = 1, R = 0.1, U[0, 1] start; P0 is not stated (1 here).
PAPER_SETTINGS = {"init": "paper", "process_noise": 1.0, "initial_covariance": 1.0, "measurement_noise": 0.1}

#: The MCMC moves a ``"particle"`` trainer accepts (``WNNRegressor(move=...)``).
MOVES = (None, "mala", "hmc")
#: A particle trainer with a move (resample-move): Q = 0 (the static posterior), P0 multiplies the
#: prior matched to the start (output weights of sd ``output_scale``), ``n_moves`` MALA steps (or HMC
#: steps of ``n_leapfrog`` leapfrog steps) after each resampling. Not searched by the study.
MOVE_SETTINGS = {"Q": 0.0, "P0": 1.0, "output_scale": 1.0, "mala": {"n_moves": 5}, "hmc": {"n_moves": 2, "n_leapfrog": 10}}


def merwe_points(n, alpha=1.0):
    """The ``"merwe"`` preset (:mod:`filterwnn.kalman.presets`): van der Merwe's ``2n + 1`` points,
    ``beta=2, kappa=0``, with the trainer's ``alpha`` (the ``ukf``, ``upf`` and ``gsf-ukf`` trainers)."""
    return make_points("merwe", n, alpha=alpha)


def simplex_points(n, alpha=1.0):
    """The ``"simplex"`` preset (:mod:`filterwnn.kalman.presets`): the unscaled ``n + 2`` spherical
    simplex of Julier (2003), ``beta=0, w0=0``, with the trainer's ``alpha`` (the ``sukf``,
    ``supf`` and ``gsf-sukf`` trainers).

    A named choice, not the SUPF preset's ``beta=2``: the WNN study's searched settings and
    numbers were measured with this set, so the ``supf`` trainer keeps it (``beta=2`` would be
    another trainer, with its own row).
    """
    return make_points("simplex", n, alpha=alpha)


@dataclass(frozen=True, eq=False)
class TrainerSpec:
    """One trainer: how to train (what the estimator reads); the WNN study's rows, grids, costs,
    labels and the paper's numbers live in the study (:data:`filterwnn.studies.wnn.rows.STUDY`).

    Frozen; compared and hashed by identity (an entry is one registration).

    Parameters
    ----------
    name : str
        The ``trainer`` name of :class:`~filterwnn.WNNRegressor`.
    trainer : type
        The class, built as ``trainer(model, theta0, settings, rng, spec)`` (see
        :class:`BaseTrainer`).
    family : str
        One of :data:`FAMILIES`: which settings the estimator resolves and how many starts it draws.
    auto : dict
        ``{"scaled": {...}, "paper": {...}}``: the ``"auto"`` settings per start (``Q`` and ``P0``;
        ``learning_rate`` for the gradient family; the sampler's settings for ``smc``).
    filter : type, optional
        The filter class the trainer builds (a :mod:`filterwnn.monte_carlo.particle_filter` preset,
        :class:`~filterwnn.GaussianSumFilter`, :class:`~filterwnn.UnscentedKalmanFilter`, ...).
    points : callable, optional
        Sigma-point factory ``points(n, alpha=1.0)`` (:func:`merwe_points`, :func:`simplex_points`).
    jacobian : bool
        Pass the model's ``HJacobian`` to the filter.
    component : str, optional
        The Gaussian-sum filter's component (``"ekf"``, ``"ukf"``, ``"sukf"``).
    combine : {"mixture", "mean"}
        Gaussian sums: weight the components, or average them without weights.
    options : tuple of str
        Estimator parameters passed through into the settings (``("ekf_backend",)``).
    doc : str
        One line on what the trainer runs.
    """

    name: str
    trainer: type
    family: str
    auto: dict
    filter: type = None
    points: object = None
    jacobian: bool = False
    component: str = None
    combine: str = "mixture"
    options: tuple = ()
    doc: str = ""

    @property
    def noise_settings(self):
        """Whether the trainer takes Q and P0 (``process_noise``, ``initial_covariance``)."""
        return self.family != "gradient"

    @property
    def starts_per_particle(self):
        """Whether the estimator draws one start per particle or component."""
        return self.family in ("particle", "gaussian-sum")

    @property
    def uses_particles(self):
        """Whether ``n_particles`` means something for this trainer."""
        return self.family in ("particle", "gaussian-sum", "smc")

    @property
    def accepts_move(self):
        """Whether ``move="mala"``/``"hmc"`` applies (the particle family)."""
        return self.family == "particle"

    @property
    def weighting(self):
        """The weighting a particle or Gaussian-sum trainer reports in its settings, else None."""
        if self.family == "gaussian-sum":
            return "unweighted average" if self.combine == "mean" else "gaussian-sum"
        return "textbook" if self.family == "particle" else None


def _filter_extras(spec, model):
    """The points and Jacobian the spec's filter takes."""
    extras = {}
    if spec.points is not None:
        extras["points"] = spec.points(model.dim_x)
    if spec.jacobian:
        extras["HJacobian"] = model.HJacobian
    return extras


def _weight_prior(X, model, settings):
    """The static posterior's prior: the Gaussian matched to the start (the paper's start: U[0, 1]'s
    moments), its variances times ``settings["P0"]``. Returns the weight model with ``Q = 0`` that
    carries it, and those variances."""
    if settings.get("prior", "scaled") == "scaled":
        x0, var = scaled_prior(X, model.n_hidden, output_scale=settings["output_scale"])
    else:  # the paper's start: every weight U[0, 1], mean 0.5 and variance 1/12
        x0, var = np.full(model.dim_x, 0.5), np.full(model.dim_x, 1.0 / 12.0)
    var = var * settings["P0"]
    prior = WNNWeightModel(model.n_inputs, model.n_hidden, model.wavelet, Q=0.0, R=model.R, x0=x0, P0=var)
    return prior, var


# ---------------------------------------------------------------------------- trainers
class BaseTrainer:
    """One trainer: holds the filter state, runs epochs, predicts with a variance.

    A trainer class is built as ``cls(model, theta0, settings, rng, spec)``: the weight-state
    model (:class:`~filterwnn.wnn.weight_model.WNNWeightModel`), the start (shape ``(n_params,)``, or
    ``(n_particles, n_params)`` for the particle and Gaussian-sum families), the settings the
    estimator resolved (Q, P0, R, ...), a ``Generator`` and its :class:`TrainerSpec` (what the
    class reads to build its filter). Subclasses implement ``epoch(X, y)``, ``theta`` and
    ``predict(X) -> (mean, var)``. ``diagnostics`` collects per-epoch numbers (e.g. mean ESS)
    as lists.
    """

    def __init__(self, model, theta0, settings, rng, spec=None):
        self.model = model
        self.settings = settings
        self.rng = rng
        self.spec = spec
        self.name = spec.name if spec is not None else type(self).__name__
        self.diagnostics = {}

    def _record(self, key, value):
        self.diagnostics.setdefault(key, []).append(value)

    def predict_mean(self, X):
        """The predictive mean alone (the loss curve needs no variance)."""
        return self.predict(X)[0]

    def predictive(self, X):
        """The predictive distribution at the rows ``X``: by default the Gaussian
        :class:`~filterwnn.wnn.predictive.GaussianPredictive` with ``predict(X)``'s mean and variance
        (a trainer whose predictive is not Gaussian overrides this)."""
        return GaussianPredictive(*self.predict(X))

    def check_finite(self, epoch, *arrays):
        """Raise :class:`~filterwnn.NumericalError` if any of ``arrays`` is not finite after ``epoch``."""
        for a in arrays:
            if not np.all(np.isfinite(a)):
                raise NumericalError(
                    f"the {self.name} trainer produced non-finite weights in epoch {epoch}; "
                    "lower process_noise/initial_covariance (or the learning rate) or use init='scaled'",
                    matrix="theta",
                    step=epoch,
                )


class _BPTrainer(BaseTrainer):
    """Per-sample gradient descent on ``(y - f)^2 / 2`` (samples in order)."""

    def __init__(self, model, theta0, settings, rng, spec=None):
        super().__init__(model, theta0, settings, rng, spec)
        self.x = np.array(theta0, dtype=float)
        self.lr = float(settings["learning_rate"])
        self.resid_var = float(model.R[0, 0])

    @property
    def theta(self):
        return self.x

    def epoch(self, X, y):
        wav = self.model.wavelet
        x = self.x
        for xk, yk in zip(X, y):
            xk = xk[None]
            err = yk - wnn.forward(x, xk, wav)[0]
            x = x + self.lr * err * wnn.jacobian(x, xk, wav)[0]
        self.x = x
        self.resid_var = max(float(np.mean((y - wnn.forward(x, X, wav)) ** 2)), 1e-12)

    def predict(self, X):
        """The output; variance: the training rows' mean squared residual (no weight uncertainty)."""
        return wnn.forward(self.x, X, self.model.wavelet), np.full(len(X), self.resid_var)


class _EKFTrainer(BaseTrainer):
    """EKF on the weight model; ``backend="rank1"`` (default) or ``"filterpy"``.

    The rank-1 backend keeps ``P`` as its lower triangle (a Fortran array whose upper
    triangle is never read): ``P h`` by BLAS ``dsymv`` and the update
    ``P - (P h)(P h)^T / s`` by ``dsyr`` read and write half the matrix, so ``P`` is
    symmetric by construction and no pass has to symmetrise it. A pass over rows is
    then the same arithmetic however the rows are split into calls (``partial_fit``).
    """

    def __init__(self, model, theta0, settings, rng, spec=None):
        super().__init__(model, theta0, settings, rng, spec)
        self.backend = settings.get("ekf_backend", "rank1")
        self.x = np.array(theta0, dtype=float)
        self.P_lower = np.asfortranarray(model.P0, dtype=float).copy(order="F")
        Q = model.Q
        self.q_diag = np.diag(Q).copy() if np.allclose(Q, np.diag(np.diag(Q))) else None
        if self.backend == "filterpy":
            self.kf = from_model(ExtendedKalmanFilter, model, x0=self.x)

    @property
    def theta(self):
        return self.kf.x if self.backend == "filterpy" else self.x

    @property
    def cov(self):
        if self.backend == "filterpy":
            return self.kf.P
        L = np.tril(self.P_lower)
        return L + np.tril(L, -1).T

    def epoch(self, X, y):
        m = self.model
        if self.backend == "filterpy":
            kf = self.kf
            for xk, yk in zip(X, y):
                kf.predict()
                kf.update(np.array([yk]), _Bound(m.HJacobian, xk), _Bound(m.hx, xk))
            return
        x, P = self.x, self.P_lower
        Q, r, qd = getattr(self, "_Q", m.Q), float(m.R[0, 0]), self.q_diag
        idx = np.diag_indices_from(P)
        wav = m.wavelet
        # theta = [W, v, a, b] and dy/dv = psi(t): the output psi(t) v is read off the
        # Jacobian row, by the same product wnn.forward computes (one network pass a step)
        n_hidden = m.n_hidden
        v_part = slice(n_hidden * X.shape[1], n_hidden * (X.shape[1] + 1))
        for xk, yk in zip(X, y):
            if qd is not None:
                P[idx] += qd
            else:
                P += Q  # only the lower triangle is read
            h = wnn.jacobian(x, xk[None], wav)[0]
            f = np.matmul(h[None, v_part], x[v_part, None])[0, 0]
            Ph = dsymv(1.0, P, h, lower=1)
            s = h @ Ph + r
            x = x + (Ph / s) * (yk - f)
            P = dsyr(-1.0 / s, Ph, a=P, lower=1, overwrite_a=1)
        self.x, self.P_lower = x, P

    def scale_process_noise(self, factor):
        """Run the next epochs with ``factor * Q`` (``WNNRegressor.anneal``: down to 0)."""
        Q = self.model.Q * float(factor)
        self._Q = Q
        if self.q_diag is not None:
            self.q_diag = np.diag(Q).copy()
        if self.backend == "filterpy":
            self.kf.Q = Q.copy()

    def predict_mean(self, X):
        return wnn.forward(self.theta, X, self.model.wavelet)

    def predict(self, X):
        """The output at the mean weights; variance ``J P J^T + R`` (the weight covariance through
        the output's Jacobian, plus the noise): with Q > 0, ``P`` holds the random walk's
        accumulated Q, not a posterior covariance (``WNNRegressor.anneal`` brings Q to 0)."""
        J = wnn.jacobian(self.theta, X, self.model.wavelet)
        var = np.sum((J @ self.cov) * J, axis=1)
        return wnn.forward(self.theta, X, self.model.wavelet), var + float(self.model.R[0, 0])


class _Bound:
    """``f(theta)`` = ``fn(theta, x=x)``: picklable partial for filterpy's EKF update."""

    def __init__(self, fn, x):
        self.fn, self.x = fn, x

    def __call__(self, theta):
        return self.fn(theta, x=self.x)


class _UKFTrainer(BaseTrainer):
    """The spec's UKF class (vectorized, ``fx=None``: the random walk) with the spec's points
    (Merwe's or the spherical simplex; ``settings["alpha"]``, default 1)."""

    def __init__(self, model, theta0, settings, rng, spec=None):
        super().__init__(model, theta0, settings, rng, spec)
        n = model.dim_x
        points = spec.points(n, alpha=settings.get("alpha", 1.0))
        self.kf = from_model(spec.filter, model, x0=theta0, fx=None, points=points, vectorized=True)

    @property
    def theta(self):
        return self.kf.x

    def epoch(self, X, y):
        kf = self.kf
        for xk, yk in zip(X, y):
            kf.predict()
            kf.update(np.array([yk]), x=xk)
        kf.P = 0.5 * (kf.P + kf.P.T)

    def scale_process_noise(self, factor):
        """Run the next epochs with ``factor * Q`` (``WNNRegressor.anneal``: down to 0)."""
        Q_scaled = float(factor) * self.model.Q  # a scaled copy, not the model's wiring
        self.kf.Q = Q_scaled

    def predict_mean(self, X):
        return wnn.forward(self.kf.x, X, self.model.wavelet)

    def predict(self, X):
        """The output at the mean weights; variance ``J P J^T + R`` as the EKF trainer's."""
        J = wnn.jacobian(self.kf.x, X, self.model.wavelet)
        var = np.sum((J @ self.kf.P) * J, axis=1)
        return wnn.forward(self.kf.x, X, self.model.wavelet), var + float(self.model.R[0, 0])


class _ParticleTrainer(BaseTrainer):
    """A particle filter of :mod:`filterwnn.monte_carlo.particle_filter` (the spec's preset class, its points
    and Jacobian) on the weight model, with textbook weights.

    ``settings["move"]`` (``None``, ``"mala"`` or ``"hmc"``) adds an MCMC move after every
    resampling (resample-move, Gilks and Berzuini 2001): the move's target is the prior times the
    likelihood of every row the filter has been updated with (rows counted once per pass, as the
    filter's weights count them), and each row is added to it before its update. The prior is the
    filter's initial distribution: with a move the particles are drawn from the Gaussian prior
    matched to the start (:func:`filterwnn.wnn.weight_model.scaled_prior`, or U[0, 1]'s moments for the
    paper's start), scaled by ``P0``, and ``Q`` is 0 (the static posterior the move leaves invariant).
    """

    def __init__(self, model, theta0, settings, rng, spec=None):
        super().__init__(model, theta0, settings, rng, spec)
        self._move_kind = settings.get("move")
        cls = spec.filter
        kwargs = dict(
            n_particles=settings["n_particles"],
            resampling="systematic",
            ess_threshold=settings["ess_threshold"],
            vectorized=True,
            rng=rng,
            tempering=settings["tempering"],
        )
        kwargs.update(_filter_extras(spec, model))
        self._kwargs, self._cls = kwargs, cls
        self.move = None
        if self._move_kind is not None:  # the prior needs the training inputs: built in the first epoch
            self.pf = None
            return
        theta0 = np.atleast_2d(np.asarray(theta0, dtype=float))
        # fx=None: the random walk, predicted without sigma points (P += Q)
        self.pf = from_model(cls, model, x0=theta0[0], fx=None, **kwargs)
        if theta0.shape[0] > 1:  # one start per particle (the paper's step 1: draws from the initial distribution)
            self.pf.initialize(theta0, model.P0)

    def _start_with_move(self, X):
        m, s = self.model, self.settings
        prior, var = _weight_prior(X, m, s)
        target = smc.RowsTarget(prior)
        if self._move_kind == "hmc":
            self.move = smc.HMCMove(target, n_steps=s["n_moves"], n_leapfrog=s["n_leapfrog"])
        else:
            self.move = smc.MALAMove(target, n_steps=s["n_moves"])
        self.pf = from_model(self._cls, m, P0=prior.P0, Q=prior.Q, fx=None, move=self.move, **self._kwargs)
        draws = self.rng.standard_normal((s["n_particles"], m.dim_x))
        self.pf.initialize(prior.x0 + draws * np.sqrt(var), prior.P0)

    @property
    def particles(self):
        return np.asarray(self.pf.particles)

    @property
    def weights(self):
        return np.asarray(self.pf.weights)

    @property
    def theta(self):
        return self.particles[int(np.argmax(self.weights))]

    def epoch(self, X, y):
        if self._move_kind is not None and self.pf is None:
            self._start_with_move(X)
        pf = self.pf
        ess, distinct = [], []
        for xk, yk in zip(X, y):
            if self.move is not None:  # the move's target: every row up to this one
                self.move.target.append(xk, yk)
            pf.predict()
            pf.update(np.array([yk]), x=xk)
            ess.append(pf.ess)
            distinct.append(pf.n_distinct)
        self._record("mean_ess", float(np.mean(ess)))
        self._record("distinct", int(distinct[-1]))
        self._record("distinct_ancestors", pf.n_ancestors)
        if self.move is not None and self.move.acceptance_:
            self._record("acceptance", float(np.mean(self.move.acceptance_)))
        self.check_finite(len(self.diagnostics["mean_ess"]), self.particles)

    def predict(self, X):
        """The weighted mean output; variance: the particles' (or components') weighted spread of
        outputs, plus their weighted ``J P_i J^T`` where they carry covariances (the Kalman
        proposals and the Gaussian sums: Q accumulates there as in the EKF), plus R."""
        w = self.weights
        wav = self.model.wavelet
        Y = wnn.forward(self.particles, X, wav)  # (N, n)
        mean = w @ Y
        spread = w @ (Y - mean) ** 2
        Pp = getattr(self.pf, "covariances", None)
        within = 0.0
        if Pp is not None and np.ndim(Pp) == 3:
            J = wnn.jacobian(self.particles, X, wav)  # (N, n, d)
            within = w @ np.sum(np.matmul(J, Pp) * J, axis=2)
        return mean, spread + within + float(self.model.R[0, 0])



class _GaussianSumTrainer(_ParticleTrainer):
    """A Gaussian-sum filter of ``n_particles`` Kalman filters (:class:`filterwnn.GaussianSumFilter`).

    Each component (the spec's ``component``) is an EKF, UKF (Merwe points) or SUKF (simplex
    points) on the weight-state model, weighted by its innovation likelihood raised to
    ``tempering`` (1: the Bayesian mixture; the WNN study's working rows use 0.01, a heuristic),
    or averaged without weights (the spec's ``combine="mean"``, the EKF ensemble). Not a
    particle filter: nothing is sampled after the start, whose component means are
    ``n_particles`` draws of the initial distribution.
    """

    def __init__(self, model, theta0, settings, rng, spec=None):
        BaseTrainer.__init__(self, model, theta0, settings, rng, spec)
        self.move = None
        self.combine = spec.combine
        kwargs = dict(resampling="systematic", ess_threshold=settings["ess_threshold"], vectorized=True,
                      rng=rng, tempering=settings["tempering"], combine=self.combine)
        kwargs.update(_filter_extras(spec, model))
        theta0 = np.atleast_2d(np.asarray(theta0, dtype=float))
        self.pf = from_model(spec.filter, model, fx=None, component=spec.component, **kwargs)
        if theta0.shape[0] == 1:  # one start: component means drawn from N(theta0, P0)
            L = np.linalg.cholesky(model.P0)
            theta0 = theta0[0] + self.pf.rng.standard_normal((settings["n_particles"], model.dim_x)) @ L.T
        self.pf.initialize(theta0, model.P0)

    @property
    def particles(self):
        return np.asarray(self.pf.means)

    @property
    def weights(self):
        w = np.asarray(self.pf.weights)
        return w if self.combine == "mixture" else np.full(len(w), 1.0 / len(w))

    def epoch(self, X, y):
        pf = self.pf
        ess = []
        for xk, yk in zip(X, y):
            pf.predict()
            pf.update(np.array([yk]), x=xk)
            ess.append(pf.ess)
        self._record("mean_ess", float(np.mean(ess)))
        self.check_finite(len(self.diagnostics["mean_ess"]), self.particles)



class _SMCTrainer(BaseTrainer):
    """Tempered SMC sampler over all training rows, then MCMC rejuvenation at the posterior (:mod:`filterwnn.monte_carlo.smc`)."""

    def __init__(self, model, theta0, settings, rng, spec=None):
        super().__init__(model, theta0, settings, rng, spec)
        self.result = None
        self.move = None
        self.particles = None

    @property
    def theta(self):
        """The particle of largest posterior density (predictions average all of them)."""
        t = self.move.target
        lp = t.log_prior_and_grad(self.particles)[0] + t.log_likelihood(self.particles)
        return self.particles[int(np.argmax(lp))]

    def _kernel(self, target):
        s = self.settings
        if s.get("kernel", "mala") == "hmc":
            return smc.HMCMove(
                target, n_steps=s["n_moves"], n_leapfrog=s["n_leapfrog"], preconditioner=s["preconditioner"]
            )
        return smc.MALAMove(target, n_steps=s["n_moves"], preconditioner=s["preconditioner"])

    def _sample(self, target, move, particles):
        n = len(self.diagnostics.get("acceptance", [])) + 1
        try:
            return smc.smc_sampler(
                target, self.settings["n_particles"], self.rng, move=move,
                ess_fraction=self.settings["ess_fraction"], particles=particles,
            )
        except (NumericalError, RuntimeError) as err:
            raise NumericalError(f"the smc trainer failed in epoch {n}: {err}", matrix="theta", step=n) from err

    def _keep(self, res):
        """Keep a sampler run's particles and record its diagnostics."""
        self.result, self.particles = res, res.particles
        self._record("mean_ess", float(np.mean(res.ess)))
        self._record("n_rungs", len(res.betas))
        self._record("acceptance", float(np.mean(res.acceptance)))
        self._record("distinct", res.distinct_particles[-1])
        self._record("distinct_ancestors", res.distinct_ancestors[-1])

    def _prior_model(self, X):
        """The model whose prior and likelihood the sampler's target reads (the weight model, Q = 0)."""
        return _weight_prior(X, self.model, self.settings)[0]

    def epoch(self, X, y):
        if self.result is None:
            target = smc.RowsTarget(self._prior_model(X), X, y)
            self.move = self._kernel(target)
            res = self._sample(target, self.move, None)
            self._keep(res)
        elif not (X.shape == self.move.target.X.shape and np.array_equal(X, self.move.target.X)
                  and np.array_equal(y, self.move.target.y)):
            # new rows (partial_fit): temper their likelihood in, from the current posterior
            base = self.move.target
            added = smc.AddedRowsTarget(base, X, y)
            res = self._sample(added, self._kernel(added), self.particles)
            base.set_rows(np.vstack([base.X, X]), np.concatenate([base.y, y]))
            self._keep(res)
        else:  # the same rows again (fit's later epochs): rejuvenation on the untempered posterior
            n_before = len(self.move.acceptance_)
            self.particles = self.move(self.particles, self.rng)
            self._record("acceptance", float(np.mean(self.move.acceptance_[n_before:])))
            self._record("distinct", int(np.unique(self.particles, axis=0).shape[0]))
            self._record("distinct_ancestors", self.diagnostics["distinct_ancestors"][-1])
        self.check_finite(len(self.diagnostics["acceptance"]), self.particles)

    def predict(self, X):
        """Mean and variance of the posterior predictive with R fixed: the particles' mean output,
        and the particles' spread of outputs plus R (``measurement_noise``)."""
        Y = wnn.forward(self.particles, X, self.model.wavelet)  # (N, n)
        return Y.mean(axis=0), Y.var(axis=0) + float(self.model.R[0, 0])


class _LearnedNoise:
    """The weights and ``s = log R`` as one static parameter: the prior ``N(x0, P0) x N(s0, sd^2)``,
    the likelihood ``prod_k N(y_k; WNN(theta, x_k), exp(s))``, batched over particles, with gradients
    (what :class:`filterwnn.monte_carlo.smc.RowsTarget` reads). ``prior`` is the weight model (Q = 0)
    whose ``x0``, ``P0`` are the weights' prior."""

    def __init__(self, prior, s_mean, s_sd):
        self.prior, self.wavelet = prior, prior.wavelet
        self.s_mean, self.s_sd = float(s_mean), float(s_sd)
        self.dim_x = prior.dim_x + 1
        self.x0 = np.append(prior.x0, self.s_mean)
        self.P0 = np.zeros((self.dim_x, self.dim_x))
        self.P0[:-1, :-1], self.P0[-1, -1] = prior.P0, self.s_sd**2

    def log_prior_and_grad(self, thetas):
        # a leapfrog step that overflowed (s far below its prior makes exp(-s) huge) leaves
        # non-finite rows: their density is 0 (log -inf, rejected), their gradient 0
        bad = ~np.all(np.isfinite(thetas), axis=1)
        safe = np.where(bad[:, None], self.x0, thetas)
        lp, gp = self.prior.log_prior_and_grad(safe[:, :-1])
        u = (safe[:, -1] - self.s_mean) / self.s_sd
        lps = -0.5 * u * u - np.log(self.s_sd * np.sqrt(2.0 * np.pi))
        grad = np.column_stack([gp, -u / self.s_sd])
        grad[bad] = 0.0
        return np.where(bad, -np.inf, lp + lps), grad

    def _residuals(self, thetas, X, y):
        return np.asarray(y, dtype=float) - wnn.forward(thetas[:, :-1], X, self.wavelet)  # (N, n)

    def log_likelihood(self, thetas, X, y):
        resid, s = self._residuals(thetas, X, y), thetas[:, -1]
        return -0.5 * np.sum(resid * resid, axis=1) * np.exp(-s) - 0.5 * len(y) * (np.log(2.0 * np.pi) + s)

    def log_likelihood_and_grad(self, thetas, X, y):
        resid, s = self._residuals(thetas, X, y), thetas[:, -1]
        J = wnn.jacobian(thetas[:, :-1], X, self.wavelet)  # (N, n, d)
        inv_r, ss = np.exp(-s), np.sum(resid * resid, axis=1)
        ll = -0.5 * ss * inv_r - 0.5 * len(y) * (np.log(2.0 * np.pi) + s)
        g_w = np.matmul(resid[:, None, :], J)[:, 0, :] * inv_r[:, None]
        return ll, np.column_stack([g_w, 0.5 * ss * inv_r - 0.5 * len(y)])


class _SMCNoiseTrainer(_SMCTrainer):
    """The SMC sampler with the noise learned: ``s = log R`` joins the weights in the state, with
    the prior ``N(log noise_prior_mean, noise_prior_sd^2)`` (settings; ``N(log 0.1, 2^2)`` by default,
    the paper's R as its median), and the sampler carries both to their joint posterior. R
    (``measurement_noise``) is not used."""

    #: How many coordinates the state appends to the weights (``s``; a subclass may append more after it).
    _LEARNED = 1

    def _prior_model(self, X):
        return self._with_noise(super()._prior_model(X))

    def _with_noise(self, weights_model):
        """The static parameter: the weights' model with the learned noise appended."""
        s = self.settings
        return _LearnedNoise(weights_model, np.log(s["noise_prior_mean"]), s["noise_prior_sd"])

    @property
    def theta(self):
        """The weights of the particle of largest posterior density (the learned coordinates left out)."""
        return super().theta[:-self._LEARNED]

    @property
    def noise(self):
        """The particles' learned noise variances (or squared scales) ``exp(s_i)``, shape ``(n_particles,)``."""
        return np.exp(self.particles[:, -self._LEARNED])

    def _outputs(self, X):
        """The particles' network outputs on ``X``, shape ``(N, n)``."""
        return wnn.forward(self.particles[:, :-self._LEARNED], X, self.model.wavelet)

    def predict(self, X):
        """Mean and variance of the posterior predictive with R learned: the particles' mean output,
        and the particles' spread of outputs plus their mean noise ``exp(s_i)``."""
        Y = self._outputs(X)
        return Y.mean(axis=0), Y.var(axis=0) + float(np.mean(self.noise))



class _StudentNoise:
    r"""The weights, ``s = log sigma^2`` and ``u = log nu`` as one static parameter, for a Student-t
    likelihood ``y_k ~ t_nu(WNN(theta, x_k), sigma^2)`` (what :class:`filterwnn.monte_carlo.smc.RowsTarget`
    reads, batched over particles, with gradients).

    Prior: the weight model's ``N(x0, P0)`` (Q = 0), ``s ~ N(s_mean, s_sd^2)`` and
    ``nu ~ Gamma(df_shape, rate=df_rate)`` (Juarez and Steel 2010's weakly informative prior for
    ``(2, 0.1)``: mean 20, 1.8 % of its mass below ``nu = 2``), carried to ``u`` with the Jacobian
    ``nu``: ``log p(u) = df_shape u - df_rate e^u + const``. :meth:`sample_prior` draws that prior
    exactly (the Gamma by ``rng.gamma``); ``x0``/``P0`` hold its means and variances (``u``'s:
    ``E log nu = psi(df_shape) - log df_rate``, ``Var log nu = psi'(df_shape)``), which the
    moves read only for their preconditioner's floor.

    Per row, with ``r = y - f``, ``a = r^2 / sigma^2`` and ``w = (nu + 1) / (nu + a)``:
    ``d/df = w r / sigma^2``, ``d/ds = (w a - 1) / 2`` and
    ``d/du = nu [psi((nu+1)/2)/2 - psi(nu/2)/2 - 1/(2 nu) - log(1 + a/nu)/2 + w a / (2 nu)]``.
    """

    def __init__(self, prior, s_mean, s_sd, df_shape, df_rate):
        self.prior, self.wavelet = prior, prior.wavelet
        self.s_mean, self.s_sd = float(s_mean), float(s_sd)
        self.df_shape, self.df_rate = float(df_shape), float(df_rate)
        self._weights_and_s = _LearnedNoise(prior, s_mean, s_sd)
        self.dim_x = prior.dim_x + 2
        u_mean = float(psi(self.df_shape) - np.log(self.df_rate))
        self.x0 = np.concatenate([prior.x0, [self.s_mean, u_mean]])
        self.P0 = np.zeros((self.dim_x, self.dim_x))
        self.P0[:-2, :-2] = prior.P0
        self.P0[-2, -2], self.P0[-1, -1] = self.s_sd**2, float(polygamma(1, self.df_shape))

    def sample_prior(self, n, rng):
        """``n`` draws of the prior, shape ``(n, dim_x)``: Gaussian weights and ``s``, ``log`` of a Gamma ``nu``."""
        L = np.linalg.cholesky(np.asarray(self.P0[:-1, :-1], dtype=float))
        ws = self.x0[:-1] + rng.standard_normal((n, self.dim_x - 1)) @ L.T
        return np.column_stack([ws, np.log(rng.gamma(self.df_shape, 1.0 / self.df_rate, size=n))])

    def log_prior_and_grad(self, thetas):
        bad = ~np.all(np.isfinite(thetas), axis=1)
        safe = np.where(bad[:, None], self.x0, thetas)
        # the weights and s: the Gaussian-noise row's prior (rows made finite above)
        lp, gp = self._weights_and_s.log_prior_and_grad(safe[:, :-1])
        k, b, u = self.df_shape, self.df_rate, safe[:, -1]
        with np.errstate(over="ignore"):
            e_u = np.exp(u)
        lpu = k * np.log(b) - gammaln(k) + k * u - b * e_u
        grad = np.column_stack([gp, k - b * e_u])
        lp = lp + lpu
        bad |= ~np.isfinite(lp) | ~np.all(np.isfinite(grad), axis=1)
        grad[bad] = 0.0
        return np.where(bad, -np.inf, lp), grad

    def _parts(self, thetas, X, y):
        resid = np.asarray(y, dtype=float) - wnn.forward(thetas[:, :-2], X, self.wavelet)  # (N, n)
        s, nu = thetas[:, -2], np.exp(thetas[:, -1])
        a = resid * resid * np.exp(-s)[:, None]
        log1p = np.log1p(a / nu[:, None])
        return resid, s, nu, a, log1p

    def _ll(self, s, nu, log1p, n):
        const = gammaln(0.5 * (nu + 1.0)) - gammaln(0.5 * nu) - 0.5 * np.log(np.pi * nu) - 0.5 * s
        return n * const - 0.5 * (nu + 1.0) * np.sum(log1p, axis=1)

    def log_likelihood(self, thetas, X, y):
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            _, s, nu, _, log1p = self._parts(thetas, X, y)
            ll = self._ll(s, nu, log1p, len(y))
        return np.where(np.isfinite(ll), ll, -np.inf)

    def log_likelihood_and_grad(self, thetas, X, y):
        n = len(y)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            resid, s, nu, a, log1p = self._parts(thetas, X, y)
            ll = self._ll(s, nu, log1p, n)
            w = (nu[:, None] + 1.0) / (nu[:, None] + a)
            J = wnn.jacobian(thetas[:, :-2], X, self.wavelet)  # (N, n, d)
            g_w = np.matmul((w * resid)[:, None, :], J)[:, 0, :] * np.exp(-s)[:, None]
            g_s = 0.5 * np.sum(w * a, axis=1) - 0.5 * n
            d_nu = (n * (0.5 * psi(0.5 * (nu + 1.0)) - 0.5 * psi(0.5 * nu) - 0.5 / nu)
                    - 0.5 * np.sum(log1p, axis=1) + np.sum(w * a, axis=1) / (2.0 * nu))
            grad = np.column_stack([g_w, g_s, nu * d_nu])
        bad = ~np.isfinite(ll) | ~np.all(np.isfinite(grad), axis=1)
        grad[bad] = 0.0
        return np.where(bad, -np.inf, ll), grad


class _SMCStudentTrainer(_SMCNoiseTrainer):
    r"""The SMC sampler with a Student-t likelihood, its scale and degrees of freedom learned:
    ``y_k ~ t_nu(WNN(theta, x_k), sigma^2)``, with ``s = log sigma^2`` and ``u = log nu`` in the state
    (:class:`_StudentNoise`; priors ``s ~ N(log noise_prior_mean, noise_prior_sd^2)`` and
    ``nu ~ Gamma(df_prior_shape, rate=df_prior_rate)``). R (``measurement_noise``) is not used.
    Its predictive is the particles' mixture of t's (:class:`~filterwnn.wnn.predictive.StudentTMixture`)."""

    _LEARNED = 2  # s, then u

    def _with_noise(self, weights_model):
        s = self.settings
        return _StudentNoise(weights_model, np.log(s["noise_prior_mean"]), s["noise_prior_sd"],
                             s["df_prior_shape"], s["df_prior_rate"])

    @property
    def df(self):
        """The particles' learned degrees of freedom ``nu_i = exp(u_i)``, shape ``(n_particles,)``."""
        return np.exp(self.particles[:, -1])

    def epoch(self, X, y):
        super().epoch(X, y)
        self._record("noise_scale2", float(np.median(self.noise)))
        self._record("noise_df", float(np.median(self.df)))

    def predictive(self, X):
        """The posterior predictive: the particles' equally weighted mixture of ``t_{nu_i}(WNN(theta_i, x), sigma_i^2)``."""
        return StudentTMixture(self._outputs(X), self.noise, self.df)

    def predict(self, X):
        """The mixture's mean (the particles' mean output) and variance: the outputs' spread plus the
        mean of ``sigma_i^2 nu_i / (nu_i - 2)``; ``inf`` when any particle has ``nu_i <= 2`` (a t's
        variance exists only for ``nu > 2``). Intervals and density: :meth:`predictive`."""
        p = self.predictive(X)
        return p.mean, p.var



# ---------------------------------------------------------------------------- the table
#: The trainer table: name -> :class:`TrainerSpec`, in registration order (the study's row order).
#: Add to it with :func:`register_trainer`.
TRAINERS = {}

#: ``(trainer, init) -> dict`` used for ``"auto"``: each entry's ``auto`` (the same dicts).
#: Scaled start: the settings the WNN study's validation search chose (5 tuning runs,
#: ``docs/study-outputs/wnn/tuning.md``), except the EKF's: the search's Q = 1e-4 wins only
#: when stopped after 5 epochs, Q = 1e-3 is the best candidate over 50 to 200 epochs (the
#: regressor's default runs 50). Paper start: the prototypes' values (the study does not search it).
AUTO_SETTINGS = {}

_REQUIRED = {"gradient": ("learning_rate",), "single": ("Q", "P0"), "particle": ("Q", "P0"),
             "gaussian-sum": ("Q", "P0"), "smc": ("Q", "P0")}


def _check_spec(spec):
    """The rules a :class:`TrainerSpec` must meet before it joins the table."""
    if not isinstance(spec, TrainerSpec):
        raise TypeError(f"spec must be a TrainerSpec, got {type(spec).__name__}")
    if not isinstance(spec.name, str) or not spec.name or "+" in spec.name:
        raise ValueError(f"name must be a non-empty string without '+', got {spec.name!r}")
    check_choice(spec.family, "family", FAMILIES)
    if not callable(spec.trainer):
        raise TypeError(f"trainer must be a class, got {spec.trainer!r}")
    for init in ("scaled", "paper"):
        auto = spec.auto.get(init) if isinstance(spec.auto, dict) else None
        missing = [k for k in _REQUIRED[spec.family] if auto is None or k not in auto]
        if missing:
            raise ValueError(f"auto[{init!r}] of trainer {spec.name!r} must set {missing}, got {auto!r}")
    if spec.family in ("particle", "gaussian-sum") and spec.filter is None:
        raise ValueError(f"a {spec.family} trainer needs its filter class, got filter=None for {spec.name!r}")


def register_trainer(spec, replace=False):
    """Add ``spec`` to :data:`TRAINERS` (and its ``auto`` to :data:`AUTO_SETTINGS`).

    Parameters
    ----------
    spec : TrainerSpec
    replace : bool
        Replace an entry of the same name (else a duplicate is refused).

    Returns
    -------
    TrainerSpec
        ``spec``.

    Raises
    ------
    ValueError
        For a duplicate name (without ``replace``), an unknown family, ``auto`` settings that
        lack the family's keys.

    Examples
    --------
    A UKF that is another entry (here a copy of ``"ukf"`` under a new name): the estimator and
    the WNN study accept its name once it is registered.

    >>> from dataclasses import replace
    >>> spec = register_trainer(replace(TRAINERS["ukf"], name="ukf-copy"))
    >>> AUTO_SETTINGS[("ukf-copy", "scaled")]
    {'Q': 1e-06, 'P0': 0.01}
    >>> register_trainer(spec)
    Traceback (most recent call last):
    ...
    ValueError: trainer 'ukf-copy' is already registered; pass replace=True to replace it
    >>> unregister_trainer("ukf-copy") is spec
    True
    """
    _check_spec(spec)
    if spec.name in TRAINERS and not replace:
        raise ValueError(f"trainer {spec.name!r} is already registered; pass replace=True to replace it")
    TRAINERS[spec.name] = spec
    for init in ("scaled", "paper"):
        AUTO_SETTINGS[(spec.name, init)] = spec.auto[init]
    return spec


def unregister_trainer(name):
    """Remove trainer ``name`` from :data:`TRAINERS` and :data:`AUTO_SETTINGS`; returns its spec."""
    check_choice(name, "trainer", TRAINERS)
    for init in ("scaled", "paper"):
        AUTO_SETTINGS.pop((name, init), None)
    return TRAINERS.pop(name)


def get_trainer(name):
    """The :class:`TrainerSpec` of ``name``; ``ValueError`` listing the valid names otherwise."""
    check_choice(name, "trainer", TRAINERS)
    return TRAINERS[name]


def make_trainer(name, model, theta0, settings, rng=None):
    """Build the trainer ``name`` (a key of :data:`TRAINERS`) on ``model``.

    Raises ``ValueError`` listing the valid names for an unknown one.
    """
    spec = get_trainer(name)
    return spec.trainer(model, theta0, settings, check_rng(rng), spec)


# ---------------------------------------------------------------------------- the built-in trainers
def _qp(scaled, paper):
    """``auto`` of a Q/P0 trainer from ``(Q, P0)`` pairs for the scaled and paper starts."""
    return {"scaled": {"Q": scaled[0], "P0": scaled[1]}, "paper": {"Q": paper[0], "P0": paper[1]}}


# smc: a static posterior (Q = 0); P0 multiplies the prior matched to the start (kernel "mala": n_moves
# MALA steps per rung; "hmc": n_moves HMC steps of n_leapfrog leapfrog steps). Scaled: chosen on
# validation rows (benchmarks/smc_siso.py --validate, seeds 0-2, 80/20 split of the training rows): HMC
# 6 x 10 median validation MSE 0.070, HMC 3 x 10 0.072, MALA 30 steps 0.137 (at the default R = 0.1).
# measurement_noise=0.03 gave 0.027 (R = 0.01: 0.040); R is the estimator's argument.
_SMC = {"Q": 0.0, "P0": 1.0, "output_scale": 1.0, "n_moves": 6, "ess_fraction": 0.5, "kernel": "hmc",
        "n_leapfrog": 10, "preconditioner": "diag"}
# smc-noise: the same sampler with s = log R in the state, prior N(log 0.1, 2^2) (the issue's
# specification: the paper's R as the median, two e-folds of spread either way); nothing searched
_SMC_NOISE = dict(_SMC, noise_prior_mean=0.1, noise_prior_sd=2.0)
# smc-noise-10x10: 10 HMC steps per rung, picked with N = 60 on the d = 160 known posterior at 6000
# particle-gradient evaluations per rung (benchmarks/smc_posterior_d160_choose6000_results.txt)
_SMC_NOISE_10X10 = dict(_SMC_NOISE, n_moves=10)
# smc-student-10x10: smc-noise-10x10's sampler (N = 60, 10 x 10 HMC, the same prior on s = log sigma^2)
# with a Student-t likelihood, nu learned with the prior Gamma(2, rate 0.1) of Juarez and Steel (2010),
# fixed in protocol 5 (docs/study-outputs/wnn-protocol5) before its run; nothing searched
_SMC_STUDENT_10X10 = dict(_SMC_NOISE_10X10, df_prior_shape=2.0, df_prior_rate=0.1)

for _spec in (
    TrainerSpec("bp", _BPTrainer, "gradient", {"scaled": {"learning_rate": 0.1}, "paper": {"learning_rate": 0.05}},
                doc="back-propagation (the baseline)"),
    TrainerSpec("ekf", _EKFTrainer, "single", _qp((1e-3, 0.1), (1e-2, 0.01)), filter=ExtendedKalmanFilter,
                options=("ekf_backend",), doc="extended Kalman filter (rank-1)"),
    TrainerSpec("ukf", _UKFTrainer, "single", _qp((1e-6, 0.01), (1e-4, 0.1)), filter=UnscentedKalmanFilter,
                points=merwe_points, doc="UKF, Merwe's 2n + 1 points"),
    TrainerSpec("sukf", _UKFTrainer, "single", _qp((1e-6, 0.01), (1e-4, 0.1)), filter=UnscentedKalmanFilter,
                points=simplex_points, doc="UKF, n + 2 spherical simplex points"),
    TrainerSpec("spf", _ParticleTrainer, "particle", _qp((1e-5, 0.01), (1e-4, 0.1)), filter=BootstrapParticleFilter,
                doc="bootstrap particle filter"),
    TrainerSpec("epf", _ParticleTrainer, "particle", _qp((1e-3, 0.1), (1e-2, 0.01)),
                filter=ExtendedKalmanParticleFilter, jacobian=True, doc="particle filter, EKF proposal"),
    TrainerSpec("upf", _ParticleTrainer, "particle", _qp((1e-5, 0.01), (1e-4, 0.1)), filter=UnscentedParticleFilter,
                points=merwe_points, doc="particle filter, UKF proposal"),
    TrainerSpec("supf", _ParticleTrainer, "particle", _qp((1e-5, 0.01), (1e-4, 0.1)),
                filter=SimplexUnscentedParticleFilter, points=simplex_points,
                doc="particle filter, simplex-UKF proposal (the 'simplex' point preset: beta 0, not the SUPF's 2)"),
    # Gaussian sums: the settings the WNN study chose for the former "bank" weighting of epf/upf/supf
    # (which were these filters); ekf-ensemble: the EKF's.
    TrainerSpec("gsf-ekf", _GaussianSumTrainer, "gaussian-sum", _qp((1e-3, 0.1), (1e-2, 0.01)),
                filter=GaussianSumFilter, jacobian=True, component="ekf", doc="Gaussian sum of EKFs"),
    TrainerSpec("gsf-ukf", _GaussianSumTrainer, "gaussian-sum", _qp((1e-5, 0.01), (1e-4, 0.1)),
                filter=GaussianSumFilter, points=merwe_points, component="ukf", doc="Gaussian sum of UKFs"),
    TrainerSpec("gsf-sukf", _GaussianSumTrainer, "gaussian-sum", _qp((1e-5, 0.01), (1e-4, 0.1)),
                filter=GaussianSumFilter, points=simplex_points, component="sukf", doc="Gaussian sum of SUKFs"),
    TrainerSpec("ekf-ensemble", _GaussianSumTrainer, "gaussian-sum", _qp((1e-3, 0.1), (1e-2, 0.01)),
                filter=GaussianSumFilter, jacobian=True, component="ekf", combine="mean",
                doc="independent EKFs, averaged without weights"),
    TrainerSpec("smc", _SMCTrainer, "smc", {"scaled": dict(_SMC), "paper": dict(_SMC)},
                doc="tempered SMC sampler with HMC moves"),
    TrainerSpec("smc-noise", _SMCNoiseTrainer, "smc", {"scaled": dict(_SMC_NOISE), "paper": dict(_SMC_NOISE)},
                doc="tempered SMC sampler with HMC moves, the noise R learned with the weights"),
    TrainerSpec("smc-noise-10x10", _SMCNoiseTrainer, "smc",
                {"scaled": dict(_SMC_NOISE_10X10), "paper": dict(_SMC_NOISE_10X10)},
                doc="smc-noise with 10 HMC steps of 10 leapfrogs per rung (chosen with N = 60 at d = 160)"),
    TrainerSpec("smc-student-10x10", _SMCStudentTrainer, "smc",
                {"scaled": dict(_SMC_STUDENT_10X10), "paper": dict(_SMC_STUDENT_10X10)},
                doc="smc-noise-10x10's sampler with a Student-t likelihood, its scale and nu learned"),
):
    register_trainer(_spec)
del _spec
