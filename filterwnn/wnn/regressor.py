r"""Wavelet networks trained by filters: :class:`WNNRegressor`, a scikit-learn estimator.

Training a WNN with a filter is running the filter on the weight-state model of
:mod:`filterwnn.wnn.weight_model` (``theta_k = theta_{k-1} + u_k``, ``y_k = WNN(theta_k, x_k) + v_k``),
one training sample per step, epoch after epoch (Niu, Wu and Li, Sec. 4). The trainers
(``"bp"``, ``"ekf"``, ``"ukf"``, ``"sukf"``, the particle filters ``"spf"``, ``"epf"``, ``"upf"``,
``"supf"``, the Gaussian sums, ``"ekf-ensemble"`` and ``"smc"``), their ``"auto"`` settings and how
to add one are in :mod:`filterwnn.wnn.trainers` (one table, :data:`filterwnn.wnn.trainers.TRAINERS`); this
module holds the estimator, :class:`WNNRegressor`, which reads that table.

>>> from filterwnn.datasets import make_siso_benchmark
>>> X, y, X_test, y_test = make_siso_benchmark(rng=0)
>>> reg = WNNRegressor(n_epochs=5, random_state=0).fit(X, y)
>>> reg.theta_.shape, len(reg.loss_curve_)
((160,), 5)
>>> mean, std = reg.predict(X_test[:3], return_std=True)
>>> mean.shape, bool(np.all(std > 0))
((3,), True)

Online training: a filter trains one row per step, so rows that arrive over time are
fed to ``partial_fit`` as they come; the filter's state and covariance carry over
between calls (:meth:`WNNRegressor.partial_fit`):

>>> online = WNNRegressor(random_state=0)
>>> for start in range(0, len(X), 25):
...     online = online.partial_fit(X[start:start + 25], y[start:start + 25])
>>> online.n_iter_, online.t_
(4, 100)
>>> WNNRegressor(trainer="adam").fit(X, y)
Traceback (most recent call last):
...
ValueError: unknown trainer 'adam'; valid: 'bp', 'ekf', 'ekf-ensemble', 'epf', 'gsf-ekf', 'gsf-sukf', 'gsf-ukf', 'smc', 'smc-noise', 'smc-noise-10x10', 'smc-student-10x10', 'spf', 'sukf', 'supf', 'ukf', 'upf'
"""

from __future__ import annotations

import copy
import sys
import time

import numpy as np
from sklearn.base import BaseEstimator, RegressorMixin
from sklearn.utils.validation import check_is_fitted, validate_data
from threadpoolctl import ThreadpoolController

from . import network as wnn
from .._validation import check_choice, check_positive, check_positive_int, check_rng
from .trainers import (  # re-exported: their home is filterwnn.wnn.trainers
    AUTO_SETTINGS,
    MOVE_SETTINGS,
    MOVES,
    PAPER_SETTINGS,
    TRAINERS,
    get_trainer,
    make_trainer,
)
from .weight_model import WNNWeightModel

__all__ = ["WNNRegressor"]



# ---------------------------------------------------------------------------- estimator
def _check_verbose(verbose):
    """``verbose`` as an int >= 0 (``True``/``False`` count as 1/0, as in scikit-learn)."""
    if isinstance(verbose, bool):
        return int(verbose)
    return check_positive_int(verbose, "verbose", minimum=0)


def _progress(verbose, total, desc):
    """A tqdm bar over ``total`` epochs when ``verbose >= 1``, else None."""
    if verbose < 1:
        return None
    from tqdm.auto import tqdm

    return tqdm(total=total, desc=desc, leave=False)


_BLAS = []  # the ThreadpoolController, built on first use (scanning the libraries costs 1 ms)


def _one_blas_thread():
    """Limit every loaded BLAS to one thread; ``.restore_original_limits()`` undoes it."""
    if not _BLAS:
        _BLAS.append(ThreadpoolController())
    return _BLAS[0].limit(limits=1, user_api="blas")


def _write_line(line, bar):
    """One per-epoch line on stdout (through the bar, so that it is not overwritten)."""
    if bar is None:
        print(line, file=sys.stdout)
    else:
        bar.write(line, file=sys.stdout)


class WNNRegressor(RegressorMixin, BaseEstimator):
    """A 1-output wavelet network trained by a filter (scikit-learn estimator).

    Parameters
    ----------
    n_hidden : int, default 20
        Wavelet nodes.
    wavelet : {"morlet", "mexican_hat"}
    trainer : str, default "ekf"
        A name in :data:`filterwnn.wnn.trainers.TRAINERS` (``"ekf"``, ``"bp"``, ``"ukf"``, ``"sukf"``,
        ``"spf"``, ``"epf"``, ``"upf"``, ``"supf"``, ``"gsf-ekf"``, ``"gsf-ukf"``, ``"gsf-sukf"``,
        ``"ekf-ensemble"``, ``"smc"``, and any registered with
        :func:`~filterwnn.wnn.trainers.register_trainer`). The EKF from the scaled start is the
        default. ``WNNRegressor()`` as it stands (EKF, Q = 1e-3, P0 = 0.1, 50 epochs) measured
        test MSE 0.040, 0.073 and 0.166 on the WNN study's runs 0-2 (seed 2026), about 0.5 s per
        fit. (The study's search chooses its own EKF settings, e.g. Q = 1e-2, P0 = 1 and 21
        epochs in ``docs/study-outputs/wnn-medium/``: another configuration.)
    n_epochs : int, default 50
        Passes over the training samples (all of them, in order, one filter step each).
    init : {"scaled", "paper"}, default "scaled"
        ``"scaled"`` places the wavelets on the data (:func:`filterwnn.wnn.network.init_scaled`);
        ``"paper"`` draws every parameter from U[0, 1] as the paper does.
    process_noise : "auto" or float
        Q (times the identity) of the random-walk weights; ``"auto"`` from
        :data:`filterwnn.wnn.trainers.AUTO_SETTINGS` for the trainer and start.
    initial_covariance : "auto" or float
        P0 (times the identity).
    measurement_noise : float, default 0.1
        R, the paper's value.
    n_particles : int, default 50
        Particles of the particle-filter trainers and ``smc``; components of the Gaussian sums
        and members of ``ekf-ensemble``.
    move : {None, "mala", "hmc"}, default None
        MCMC move after each resampling of the bootstrap filter (``trainer="spf"``): IBIS
        (iterated batch importance sampling, Chopin 2002) on the static posterior, with Q = 0
        (``process_noise`` must be ``"auto"`` or 0) and the prior matched to the start
        (``initial_covariance`` scales it, ``"auto"``: 1). 5 MALA steps, or 2 HMC steps of 10
        leapfrog steps (:data:`filterwnn.wnn.trainers.MOVE_SETTINGS`). Refused for ``epf``,
        ``upf``, ``supf`` (at Q = 0 their Kalman proposals never move a particle: they ran
        the same IBIS, bit for bit) and for the non-particle trainers. The predictive variance is
        the cloud's spread plus R.
    early_stopping : bool, default False
        Hold out ``validation_fraction`` of the training rows (chosen with
        ``random_state``, the rest kept in order), stop after ``n_iter_no_change`` epochs
        without a lower validation MSE and keep the best epoch's weights.
    validation_fraction : float, default 0.1
    random_state : None, int, SeedSequence, BitGenerator or Generator, default None
        Seeds the initial weights, the validation split and the particle draws
        (normalised with :func:`numpy.random.default_rng` when ``fit`` starts; the
        legacy ``RandomState`` is refused). An int gives the same ``theta_`` on every
        fit; a ``Generator`` is drawn from, so each fit differs. scikit-learn's name
        for the seed (``check_estimator`` and ``set_random_state`` set it); the rest of
        the package calls it ``rng``.
    tempering : "auto" or float
        Exponent of the particle or component likelihood; ``"auto"`` is 1 (untempered).
    ess_threshold : "auto" or float
        Resample when ESS < ``ess_threshold * n_particles``; ``"auto"`` is 0.5 for the
        particle filters and 0 (never) for the Gaussian sums and the EKF ensemble.
    learning_rate : "auto" or float
        Step of the ``bp`` trainer (``"auto"``: 0.05).
    ekf_backend : {"rank1", "filterpy"}
        ``"filterpy"`` runs :class:`filterpy.kalman.ExtendedKalmanFilter` (same numbers,
        about 10x slower).
    n_iter_no_change : int, default 10
        Patience of early stopping.
    warm_start : bool, default False
        Continue from the previous fit's filter state for another ``n_epochs`` (a long
        fit can be checkpointed by pickling the estimator between fits, and resumed).
    verbose : int, default 0
        0: silent (the studies show their own bars). 1: a tqdm bar over the epochs of
        ``fit`` (on stderr). 2 or more: also one line per iteration (epoch of ``fit``,
        call of ``partial_fit``) on stdout with the training MSE (and the validation
        MSE with ``early_stopping``).

    Attributes
    ----------
    theta_ : ndarray of shape (n_params,)
        Learned weights (particle filters: the particle of largest weight; predictions
        average all particles).
    loss_curve_ : list of float
        Training MSE after each iteration (an epoch of ``fit`` or a ``partial_fit``
        call), on the rows that iteration trained on.
    validation_scores_ : list of float or None
        Validation MSE per epoch when ``early_stopping``.
    best_epoch_ : int
        Iteration whose weights were kept (the last one without early stopping).
    n_features_in_ : int
    n_iter_ : int
        Iterations run since the start was drawn: epochs of ``fit`` (summed over
        warm starts) plus one per ``partial_fit`` call, as in ``MLPRegressor``.
    t_ : int
        Filter steps run (training rows seen, counted once per pass), as in
        ``MLPRegressor``.
    fit_time_ : float
        Wall-clock seconds of the training epochs of the last ``fit`` (or accumulated over
        ``partial_fit`` calls).
    settings_ : dict
        The resolved Q, P0, R, tempering, ... actually used.
    diagnostics_ : dict
        Per-iteration ``mean_ess`` and ``distinct`` particle counts (particle trainers).
    """

    def __init__(
        self,
        n_hidden=20,
        wavelet="morlet",
        trainer="ekf",
        n_epochs=50,
        init="scaled",
        process_noise="auto",
        initial_covariance="auto",
        measurement_noise=0.1,
        n_particles=50,
        move=None,
        early_stopping=False,
        validation_fraction=0.1,
        random_state=None,
        tempering="auto",
        ess_threshold="auto",
        learning_rate="auto",
        ekf_backend="rank1",
        n_iter_no_change=10,
        warm_start=False,
        verbose=0,
    ):
        self.n_hidden = n_hidden
        self.wavelet = wavelet
        self.trainer = trainer
        self.n_epochs = n_epochs
        self.init = init
        self.process_noise = process_noise
        self.initial_covariance = initial_covariance
        self.measurement_noise = measurement_noise
        self.n_particles = n_particles
        self.move = move
        self.early_stopping = early_stopping
        self.validation_fraction = validation_fraction
        self.random_state = random_state
        self.tempering = tempering
        self.ess_threshold = ess_threshold
        self.learning_rate = learning_rate
        self.ekf_backend = ekf_backend
        self.n_iter_no_change = n_iter_no_change
        self.warm_start = warm_start
        self.verbose = verbose

    # ------------------------------------------------------------------ helpers
    def _resolve(self):
        spec = get_trainer(self.trainer)
        check_choice(self.init, "init", ("scaled", "paper"))
        check_choice(self.wavelet, "wavelet", wnn.WAVELETS)
        if self.move not in MOVES:
            raise ValueError(f"unknown move {self.move!r}; valid: None, 'hmc', 'mala'")
        check_choice(self.ekf_backend, "ekf_backend", ("rank1", "filterpy"))
        check_positive_int(self.n_hidden, "n_hidden")
        check_positive_int(self.n_epochs, "n_epochs")
        check_positive_int(self.n_particles, "n_particles")
        check_positive_int(self.n_iter_no_change, "n_iter_no_change")
        auto = AUTO_SETTINGS[(self.trainer, self.init)]
        s = {"R": check_positive(self.measurement_noise, "measurement_noise")}
        if not spec.noise_settings:
            lr = auto["learning_rate"] if self.learning_rate == "auto" else self.learning_rate
            s["learning_rate"] = check_positive(lr, "learning_rate")
            s["Q"], s["P0"] = 0.0, 1.0
        else:
            q = auto["Q"] if self.process_noise == "auto" else self.process_noise
            p0 = auto["P0"] if self.initial_covariance == "auto" else self.initial_covariance
            s["Q"] = check_positive(q, "process_noise", strict=False)
            s["P0"] = check_positive(p0, "initial_covariance")
        if self.move is not None and not spec.accepts_move:
            movable = tuple(name for name, other in TRAINERS.items() if other.accepts_move)
            raise ValueError(
                f"move is for the particle-filter trainers {movable}, got move={self.move!r} with "
                f"trainer={self.trainer!r}; use move=None"
            )
        if spec.starts_per_particle:
            self._resolve_particles(spec, s)
        for option in spec.options:
            s[option] = getattr(self, option)
        if spec.family == "smc":
            s.update({k: v for k, v in auto.items() if k not in ("Q", "P0")})
            s["n_particles"] = int(self.n_particles)
            s["prior"] = self.init
        return s

    def _resolve_particles(self, spec, s):
        """The settings of a particle or Gaussian-sum trainer (weights, resampling, move), into ``s``."""
        gsf = not spec.accepts_move
        temp = 1.0 if self.tempering == "auto" else self.tempering
        ess = (0.0 if gsf else 0.5) if self.ess_threshold == "auto" else self.ess_threshold
        s["tempering"] = check_positive(temp, "tempering")
        s["ess_threshold"] = check_positive(ess, "ess_threshold", strict=False)
        s["n_particles"] = int(self.n_particles)
        s["weighting"] = spec.weighting
        s["move"] = None if gsf else self.move
        if gsf or self.move is None:
            return
        s["Q"] = MOVE_SETTINGS["Q"] if self.process_noise == "auto" else s["Q"]
        if s["Q"] != 0:
            raise ValueError(
                f"process_noise must be 0 (or 'auto') with move={self.move!r}: the move targets the static "
                f"posterior p(theta | rows), got {self.process_noise!r}"
            )
        if spec.points is not None or spec.jacobian:
            raise ValueError(
                f"move={self.move!r} with trainer={self.trainer!r}: at Q = 0 its Kalman proposal never moves a "
                "particle (what runs is IBIS, the bootstrap step's reweighting with the move, at the cost of "
                f"unused Kalman updates); use trainer='spf' with move={self.move!r}"
            )
        s["P0"] = MOVE_SETTINGS["P0"] if self.initial_covariance == "auto" else s["P0"]
        s["output_scale"] = MOVE_SETTINGS["output_scale"]
        s.update(MOVE_SETTINGS[self.move])
        s["prior"] = self.init

    def _start(self, X, n_inputs, rng):
        n_starts = self.n_particles if TRAINERS[self.trainer].starts_per_particle else 1
        draws = []
        for _ in range(n_starts):
            if self.init == "scaled":
                draws.append(wnn.init_scaled(X, self.n_hidden, rng=rng))
            else:
                draws.append(wnn.init_paper(n_inputs, self.n_hidden, rng=rng))
        return draws[0] if n_starts == 1 else np.stack(draws)

    def _split(self, X, y, rng):
        if not self.early_stopping:
            return X, y, None, None
        frac = float(self.validation_fraction)
        if not 0 < frac < 1:
            raise ValueError(f"validation_fraction must be in (0, 1), got {self.validation_fraction}")
        n = len(X)
        n_val = max(1, int(round(frac * n)))
        if n - n_val < 2:
            raise ValueError(f"early_stopping needs at least 2 training rows after the split, got {n - n_val}")
        val = np.zeros(n, dtype=bool)
        val[rng.choice(n, n_val, replace=False)] = True
        return X[~val], y[~val], X[val], y[val]

    def _initialize(self, X, y, early_stopping):
        self._settings = self._resolve()
        self._rng = check_rng(self.random_state, "random_state")
        if early_stopping:
            self._data = self._split(X, y, self._rng)
            self._source = (X, y)
        else:
            self._data, self._source = (X, y, None, None), None
        Xt = self._data[0]
        model = WNNWeightModel(
            X.shape[1], self.n_hidden, self.wavelet, Q=self._settings["Q"], R=self._settings["R"],
            P0=self._settings["P0"],
        )
        theta0 = self._start(Xt, X.shape[1], self._rng)
        self._trainer = make_trainer(self.trainer, model, theta0, self._settings, self._rng)
        self.loss_curve_ = []
        self.validation_scores_ = [] if early_stopping else None
        self.n_iter_ = 0
        self.t_ = 0
        self.fit_time_ = 0.0
        self._reset_best()
        self.settings_ = dict(self._settings, init=self.init, trainer=self.trainer)

    def _reset_best(self):
        self._best = None
        self._best_score = np.inf
        self._no_change = 0

    def _continue_on(self, X, y):
        """A warm-started ``fit`` trains on the rows it is given (the first fit's split
        is kept when they are the same rows, so that a resumed fit equals an
        uninterrupted one)."""
        if not self.early_stopping:
            self._data, self._source = (X, y, None, None), None
            return
        src = self._source
        if src is not None and np.array_equal(src[0], X) and np.array_equal(src[1], y):
            return
        self._data, self._source = self._split(X, y, self._rng), (X, y)
        if self.validation_scores_ is None:
            self.validation_scores_ = []
        self._reset_best()  # scores on other validation rows do not compare

    def _run_epochs(self, n_epochs, data, show_bar=True):
        Xt, yt, Xv, yv = data
        tr = self._trainer
        verbose = _check_verbose(self.verbose)
        bar = _progress(verbose, n_epochs, f"WNN/{self.trainer}") if show_bar else None
        t0 = time.perf_counter()
        # one BLAS thread: the rank-1 and small dense products of a filter step run 3x
        # faster on one thread than on several, and the numbers do not depend on the
        # machine's thread count (the studies limit their workers the same way)
        limits = _one_blas_thread()
        try:
            for _ in range(n_epochs):
                tr.epoch(Xt, yt)
                self.n_iter_ += 1
                self.t_ += len(Xt)
                tr.check_finite(self.n_iter_, tr.theta)
                self.loss_curve_.append(float(np.mean((tr.predict_mean(Xt) - yt) ** 2)))
                if bar is not None:
                    bar.update(1)
                    bar.set_postfix(mse=f"{self.loss_curve_[-1]:.3g}")
                if Xv is not None:
                    score = float(np.mean((tr.predict_mean(Xv) - yv) ** 2))
                    self.validation_scores_.append(score)
                if verbose >= 2:
                    line = f"iteration {self.n_iter_}: training MSE {self.loss_curve_[-1]:.6g}"
                    if Xv is not None:
                        line += f", validation MSE {score:.6g}"
                    _write_line(line, bar)
                if Xv is not None:
                    if score < self._best_score:
                        self._best_score, self._no_change = score, 0
                        self._best = (self.n_iter_, copy.deepcopy(tr))
                    else:
                        self._no_change += 1
                        if self._no_change >= self.n_iter_no_change:
                            break
        finally:
            limits.restore_original_limits()
            if bar is not None:
                bar.close()
        self.fit_time_ += time.perf_counter() - t0
        if self._best is not None:
            self.best_epoch_, self._final = self._best[0], self._best[1]
        else:
            self.best_epoch_, self._final = self.n_iter_, tr
        self.theta_ = np.array(self._final.theta, dtype=float)
        self.diagnostics_ = {k: list(v) for k, v in self._final.diagnostics.items()}

    # ------------------------------------------------------------------ API
    def anneal(self, X, y, n_epochs=5):
        """After training, ``n_epochs`` more epochs with Q falling linearly to 0 (the last at Q = 0).

        For the Kalman trainers (``ekf``, ``ukf``, ``sukf``). Their random-walk ``Q > 0`` adds
        to ``P`` at every step, so after training ``P`` is not a posterior covariance (the WNN
        study measured its weight part at 9-91 against R = 0.1 for the EKF). With Q annealed to
        0 the last passes are the filter of static weights, whose ``P`` is the linearised
        posterior covariance given the rows of those passes, starting from the trained state:
        a documented way to get ``predict(return_std=True)`` intervals from a posterior
        covariance (an approximation: the rows are counted again by each pass). What it
        measures is in ``benchmarks/anneal_kalman.py``.

        Parameters
        ----------
        X : array-like of shape (n_samples, n_features)
        y : array-like of shape (n_samples,)
        n_epochs : int, default 5
            Epochs at ``Q (n - k) / n`` for ``k = 1 .. n``.

        Returns
        -------
        self
        """
        check_is_fitted(self, "theta_")
        tr = self._final
        if not hasattr(tr, "scale_process_noise"):
            raise ValueError(
                f"anneal is for the Kalman trainers ('ekf', 'ukf', 'sukf'), got trainer={self.trainer!r}; "
                "the SMC sampler's spread is already a posterior's ('smc', 'smc-noise')"
            )
        n = check_positive_int(n_epochs, "n_epochs")
        X, y = validate_data(self, X, y, reset=False, y_numeric=True)
        self._trainer, self._best = tr, None  # continue from the kept (best) state
        for k in range(1, n + 1):
            tr.scale_process_noise((n - k) / n)
            self._run_epochs(1, (X, y, None, None), show_bar=False)
        return self

    def fit(self, X, y):
        """Train for ``n_epochs`` epochs (or continue, with ``warm_start``).

        Each epoch is one filter step per row, in order. With ``warm_start`` and a
        previous fit (or ``partial_fit``), the filter's state and covariance are kept
        and ``n_epochs`` more epochs run on the rows given here.

        Parameters
        ----------
        X : array-like of shape (n_samples, n_features)
            Training rows, one filter step each per epoch, in order.
        y : array-like of shape (n_samples,)

        Returns
        -------
        self
        """
        first = not (self.warm_start and hasattr(self, "_trainer"))
        X, y = validate_data(self, X, y, reset=first, y_numeric=True)
        if first:
            self._initialize(X, y, self.early_stopping)
        else:
            self._continue_on(X, y)
            self.fit_time_ = 0.0
        self._run_epochs(self.n_epochs, self._data)
        return self

    def partial_fit(self, X, y):
        """Online training: one filter pass over these rows, keeping the filter's state.

        A filter trainer is online by nature: each row is one predict/update step of
        the filter whose state is the weight vector. ``partial_fit`` runs one step per
        given row, in order, and keeps the state and covariance (the particles and
        their weights, for the particle trainers) for the next call, so rows fed in
        chunks give the same weights and covariance as one call over all of them, bit
        for bit, for every trainer (the particle trainers make the same draws in the
        same order; ``"bp"``'s reported std is the RMSE on the last call's rows). The
        first call draws the start: ``init="scaled"`` places it on the first call's
        rows, ``init="paper"`` does not look at the rows.

        As in scikit-learn's ``MLPRegressor``, each call is one iteration:
        ``n_iter_`` grows by one, ``t_`` by the number of rows, ``loss_curve_`` gains the
        training MSE on these rows after the pass and ``fit_time_`` accumulates.
        ``early_stopping`` and ``n_epochs`` are not used. After ``fit``, ``partial_fit``
        continues from the weights the estimator predicts with (the best epoch's, with
        early stopping). Pickling the estimator between calls checkpoints the filter.

        Parameters
        ----------
        X : array-like of shape (n_samples, n_features)
            The rows of this pass, one filter step each, in order.
        y : array-like of shape (n_samples,)

        Returns
        -------
        self

        Examples
        --------
        Rows arriving in four chunks train the same network as one pass over all of
        them:

        >>> from filterwnn.datasets import make_siso_benchmark
        >>> X, y, X_test, y_test = make_siso_benchmark(rng=0)
        >>> online = WNNRegressor(init="paper", random_state=0)
        >>> for rows in np.array_split(np.arange(len(X)), 4):
        ...     online = online.partial_fit(X[rows], y[rows])
        >>> batch = WNNRegressor(init="paper", random_state=0).partial_fit(X, y)
        >>> bool(np.array_equal(online.theta_, batch.theta_))
        True
        >>> online.n_iter_, online.t_, len(online.loss_curve_)
        (4, 100, 4)
        """
        first = not hasattr(self, "_trainer")
        X, y = validate_data(self, X, y, reset=first, y_numeric=True)
        if first:
            self._initialize(X, y, early_stopping=False)
        else:
            self._trainer = self._final  # continue from the weights used to predict
            self._reset_best()
        self._run_epochs(1, (X, y, None, None), show_bar=False)
        return self

    def predict(self, X, return_std=False):
        """Network output, optionally with the predictive standard deviation.

        What the variance holds, per trainer (each trainer's ``predict`` says the same):

        ``bp``
            the training rows' mean squared residual (no weight uncertainty at all);
        ``ekf``, ``ukf``, ``sukf``
            ``J P J^T + R``: the filter's weight covariance ``P`` through the output's
            Jacobian ``J`` at each row, plus the noise R. With a random-walk ``Q > 0``, ``P``
            is not a posterior covariance: every step adds ``Q``, so the weight part grows
            with the number of rows and epochs (the WNN study measured it at 9-91 against
            R = 0.1 for the EKF). :meth:`anneal` brings ``Q`` to 0 over extra epochs so that
            ``P`` is the static-weight filter's, linearised;
        ``spf``, ``epf``, ``upf``, ``supf`` (and ``move=``: IBIS)
            the particles' weighted spread of outputs, plus for the Kalman proposals the
            weighted ``J P_i J^T`` of each particle's carried covariance ``P_i`` (which
            accumulates Q as the EKF's does), plus R; with a move (Q = 0, no carried
            covariance) the cloud's spread plus R;
        ``gsf-*``, ``ekf-ensemble``
            the components' weighted (or, for the ensemble, equal-weight) spread of outputs,
            plus their weighted ``J P_i J^T``, plus R;
        ``smc``
            the posterior sample's spread of outputs, plus R (fixed by ``measurement_noise``);
        ``smc-noise``, ``smc-noise-10x10``
            the spread of outputs plus each particle's own learned noise ``exp(s_i)``,
            averaged over the particles: the posterior predictive with R learned;
        ``smc-student-10x10``
            the variance of its predictive, a mixture of Student-t's (:meth:`predictive`): the
            spread of outputs plus the mean of ``sigma_i^2 nu_i / (nu_i - 2)``; ``inf`` when any
            particle has ``nu_i <= 2`` (a t's variance exists only for ``nu > 2``). Its
            intervals are not ``mean +- z std``: use :meth:`predict_interval`.

        The returned std is the square root of that variance. For every trainer but
        ``smc-student-10x10`` the predictive is the Gaussian with it; :meth:`predictive`,
        :meth:`predict_interval` and :meth:`predict_log_density` give each trainer's own
        predictive, which the WNN study scores (coverage at 50 / 90 / 95 % and the negative log
        predictive density).

        Parameters
        ----------
        X : array-like of shape (n_samples, n_features)
        return_std : bool

        Returns
        -------
        y_mean : ndarray of shape (n_samples,)
        y_std : ndarray of shape (n_samples,), only with ``return_std``
        """
        check_is_fitted(self, "theta_")
        X = validate_data(self, X, reset=False)
        mean, var = self._final.predict(X)
        if return_std:
            return mean, np.sqrt(np.maximum(var, 0.0))
        return mean

    def predictive(self, X):
        """The predictive distribution at the rows ``X`` (:mod:`filterwnn.wnn.predictive`).

        A :class:`~filterwnn.wnn.predictive.GaussianPredictive` ``N(mean, var)`` with
        :meth:`predict`'s mean and variance for every trainer but ``smc-student-10x10``, whose
        predictive is the particles' mixture of Student-t's
        (:class:`~filterwnn.wnn.predictive.StudentTMixture`). Each has ``mean``, ``var``,
        ``interval(level)`` and ``logpdf(y)``.

        Parameters
        ----------
        X : array-like of shape (n_samples, n_features)

        Returns
        -------
        GaussianPredictive or StudentTMixture
        """
        check_is_fitted(self, "theta_")
        X = validate_data(self, X, reset=False)
        return self._final.predictive(X)

    def predict_interval(self, X, level=0.9):
        """The predictive's own central ``level`` interval at each row.

        Gaussian predictives: ``mean -+ z std``, ``z = Phi^{-1}((1 + level) / 2)``; the Student-t
        mixture: the mixture's ``(1 - level) / 2`` and ``(1 + level) / 2`` quantiles.

        Parameters
        ----------
        X : array-like of shape (n_samples, n_features)
        level : float in (0, 1), default 0.9

        Returns
        -------
        lower, upper : ndarray of shape (n_samples,)

        Examples
        --------
        >>> from filterwnn.datasets import make_siso_benchmark
        >>> X, y, X_test, y_test = make_siso_benchmark(rng=0)
        >>> reg = WNNRegressor(n_epochs=2, random_state=0).fit(X, y)
        >>> lo, hi = reg.predict_interval(X_test[:3], level=0.9)
        >>> mean, std = reg.predict(X_test[:3], return_std=True)
        >>> bool(np.allclose(hi - mean, 1.6448536269514722 * std))
        True
        """
        return self.predictive(X).interval(level)

    def predict_log_density(self, X, y):
        """The predictive's log-density at the targets ``y``, one value per row.

        Parameters
        ----------
        X : array-like of shape (n_samples, n_features)
        y : array-like of shape (n_samples,)

        Returns
        -------
        ndarray of shape (n_samples,)
            ``log p(y_i | x_i, training rows)``; minus its mean is the NLPD.
        """
        y = np.asarray(y, dtype=float).reshape(-1)
        dist = self.predictive(X)
        if y.shape != dist.mean.shape:
            raise ValueError(f"y must have one target per row of X ({dist.mean.shape[0]}), got shape {y.shape}")
        return dist.logpdf(y)
