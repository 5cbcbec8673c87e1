"""The WNN study's runs: one tuning fit, one table fit, one reference, the summary rows and
:func:`~filterwnn.studies.wnn.run_study`, which runs the search, then the table, the references and the sweep."""

from __future__ import annotations

import time
import warnings

import numpy as np

from ..._validation import check_choice
from ...datasets import make_siso_benchmark
from ...monte_carlo.particle_filter import DegeneracyWarning
from ...wnn.predictive import GaussianPredictive, conformal_factor, recalibrate
from ...wnn.regressor import WNNRegressor
from ...wnn.trainers import PAPER_SETTINGS, TRAINERS
from .. import runner
from .plan import (StudyResult, _child, _plan, _study_tasks, _task_cost, candidates, select_settings,
                   tune_seeds)
from .rows import (ALL_TRAINERS, REFERENCES, SCORE_COLUMNS, VALIDATION_FRACTION, _cost, _rows,
                   _specs_with, _sweep_rows, _uses_particles, row_label, study_entry)

__all__ = [
    "predictive_scores",
    "distribution_scores",
    "tune_run",
    "calibration_run",
    "fit_run",
    "fit_reference",
    "run_tasks",
    "summarize",
    "run_study",
]


def tune_run(trainer, tune_seed, n_epochs, n_particles=50, params=None, candidate=0, run=0):
    """Train on the first 80 % of a tuning run's training rows; validation MSE per epoch.

    The run's test rows are drawn (so the data match :func:`fit_run`'s for the same seed)
    and discarded unseen. A fit that fails numerically scores ``inf`` from the failing epoch on.

    Returns
    -------
    dict
        ``table`` ("tuning"), ``trainer``, ``candidate``, ``params``, ``run``, ``curve_val``
        (validation MSE after each epoch), ``fit_time``, ``status``.
    """
    from threadpoolctl import threadpool_limits

    params = dict(params or {})
    with threadpool_limits(limits=1), warnings.catch_warnings():
        warnings.simplefilter("ignore", DegeneracyWarning)  # reported as ESS and distinct particles
        X, y, _, _ = make_siso_benchmark(rng=_child(tune_seed, 0))  # test rows unused
        n_val = int(round(VALIDATION_FRACTION * len(X)))
        Xt, yt, Xv, yv = X[:-n_val], y[:-n_val], X[-n_val:], y[-n_val:]
        kind, fixed, _, _ = _rows()[trainer]
        reg = WNNRegressor(trainer=kind, n_epochs=n_epochs, n_particles=n_particles, init="scaled",
                           random_state=_child(tune_seed, 1), **dict(fixed, **params))
        curve, status = [], "ok"
        try:
            _train_tracked(reg, Xt, yt, Xv, yv, n_epochs, curve)
        except np.linalg.LinAlgError as exc:
            status = f"failed: {exc}"
        curve = [v if np.isfinite(v) else float("inf") for v in curve]
        curve += [float("inf")] * (n_epochs - len(curve))
    return {
        "table": "tuning", "trainer": trainer, "candidate": int(candidate), "params": params, "run": run,
        "curve_val": curve, "fit_time": float(getattr(reg, "fit_time_", float("nan"))), "status": status,
        "n_particles": n_particles if _uses_particles(trainer) else 0,
    }


def calibration_run(trainer, tune_seed, n_particles=50, run=0):
    """Standardized residuals of row ``trainer``'s fit on a tuning run's validation split.

    The row's estimator (its trainer, fixed settings and epochs; seeded with the tuning run's
    training stream) is trained on the first 80 % of the tuning run's training rows, and its
    predictive is read on the last 20 % (the plant's later steps, as the test rows are). The
    tuning run's test rows are drawn and discarded unseen.

    Returns
    -------
    dict
        ``table`` ("calibration"), ``trainer``, ``run``, ``residuals`` (``(y - mean) / std`` on
        the validation rows), ``val_mse``, ``fit_time``, ``status``.
    """
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1), warnings.catch_warnings():
        warnings.simplefilter("ignore", DegeneracyWarning)
        X, y, _, _ = make_siso_benchmark(rng=_child(tune_seed, 0))  # test rows unused
        n_val = int(round(VALIDATION_FRACTION * len(X)))
        reg = _regressor(trainer, "working", tune_seed, _rows()[trainer].epochs or 1, n_particles, None)
        reg.fit(X[:-n_val], y[:-n_val])
        dist = reg.predictive(X[-n_val:])
        residuals = (y[-n_val:] - dist.mean) / dist.std
    return {"table": "calibration", "trainer": trainer, "run": run, "residuals": [float(r) for r in residuals],
            "val_mse": float(np.mean((dist.mean - y[-n_val:]) ** 2)), "fit_time": float(reg.fit_time_),
            "status": "ok"}


def _train_tracked(reg, X, y, X_eval, y_eval, n_epochs, curve):
    """``n_epochs`` epochs of ``partial_fit``, appending the MSE on ``(X_eval, y_eval)`` after
    each to ``curve`` (kept up to the failing epoch if a NumericalError interrupts)."""
    for _ in range(n_epochs):
        reg.partial_fit(X, y)
        curve.append(float(np.mean((reg.predict(X_eval) - y_eval) ** 2)))


def _settings_text(table, trainer, reg):
    s = reg.settings_
    if "learning_rate" in s:
        txt = f"init={s['init']}, lr={s['learning_rate']:g}"
    else:
        noise = (f"R learned (log R ~ N(log {s['noise_prior_mean']:g}, {s['noise_prior_sd']:g}^2))"
                 if "noise_prior_mean" in s else f"R={s['R']:g}")
        if "df_prior_shape" in s:
            noise = (f"Student-t likelihood, scale and nu learned (log scale^2 ~ N(log {s['noise_prior_mean']:g}, "
                     f"{s['noise_prior_sd']:g}^2), nu ~ Gamma({s['df_prior_shape']:g}, rate {s['df_prior_rate']:g}))")
        txt = f"init={s['init']}, Q={s['Q']:g}, P0={s['P0']:g}, {noise}"
    if s.get("weighting") == "unweighted average":
        txt += f", N={s['n_particles']}, weighting=none (unweighted average)"
    elif "weighting" in s:
        txt += (
            f", N={s['n_particles']}, weighting={s['weighting']}, tempering={s['tempering']:g}, "
            f"ess_threshold={s['ess_threshold']:g}, move={s.get('move') or 'none'}"
        )
        if s.get("move"):
            txt += f" ({s['n_moves']} steps)"
    if getattr(TRAINERS.get(s.get("trainer")), "family", None) == "smc":
        txt += f", N={s['n_particles']}, weighting=tempered SMC, move={s['kernel']} ({s['n_moves']} steps)"
    return f"{table}: {txt}"


def _params(table, trainer):
    if table == "paper":  # the entry's paper_settings over PAPER_SETTINGS (Q and P0 only where used)
        spec = TRAINERS[_rows()[trainer].trainer]
        p = dict(PAPER_SETTINGS)
        if not spec.noise_settings:
            p.pop("process_noise")
            p.pop("initial_covariance")
        p.update(study_entry(trainer).paper_settings or {})
        return p
    return {"init": "scaled"}


def _particle_fields(reg):
    """A fit's particle diagnostics: mean ESS, distinct particles and ancestors at the end (NaN or
    -1 where the trainer has none)."""
    diag = getattr(reg, "diagnostics_", {}) or {}
    ess, distinct, ancestors = diag.get("mean_ess"), diag.get("distinct"), diag.get("distinct_ancestors")
    return {
        "mean_ess": float(np.mean(ess)) if ess else float("nan"),
        "distinct": int(distinct[-1]) if distinct else -1,
        "ancestors": int(ancestors[-1]) if ancestors else -1,
    }


def _regressor(trainer, table, run_seed, n_epochs, n_particles, params):
    """The row's estimator in one run: the table's settings, the row's fixed keywords (not in the
    paper table), then ``params``; seeded with the run's training stream."""
    kind, fixed, _, _ = _rows()[trainer]
    kw = _params(table, trainer)
    if table != "paper":
        kw.update(fixed)
    kw.update(params or {})
    return WNNRegressor(trainer=kind, n_epochs=n_epochs, n_particles=n_particles, random_state=_child(run_seed, 1),
                        **kw)


def _noise_fields(reg):
    """A fit's learned noise, for the rows that learn a Student-t's (``noise_scale2``: the
    particles' median squared scale; ``noise_df``: their median degrees of freedom); none for
    the other rows, so that their records are as before."""
    diag = getattr(reg, "diagnostics_", {}) or {}
    if "noise_df" not in diag:
        return {}
    return {"noise_scale2": float(diag["noise_scale2"][-1]), "noise_df": float(diag["noise_df"][-1])}


def predictive_scores(mean, std, y):
    """How well a Gaussian predictive ``N(mean, std**2)`` describes the targets ``y``.

    Returns
    -------
    dict
        ``coverage50``, ``coverage90``, ``coverage95``: the share of targets inside the central
        50 / 90 / 95 % interval ``mean +- z std`` (calibrated: 0.50 / 0.90 / 0.95; a width measure
        alone says nothing of calibration, so all three are reported), and ``nlpd``: the mean
        negative log predictive density ``log(2 pi std**2) / 2 + (y - mean)**2 / (2 std**2)``
        (lower is better; a proper scoring rule that punishes intervals too wide and too narrow,
        Gneiting and Raftery 2007). All NaN when ``mean`` is None (no predictive distribution).

    >>> s = predictive_scores(np.zeros(4), np.ones(4), np.array([0.1, -0.5, 1.0, 3.0]))
    >>> s["coverage50"], s["coverage95"], round(s["nlpd"], 3)
    (0.5, 0.75, 2.201)
    """
    if mean is None:
        return distribution_scores(None, y)
    return distribution_scores(GaussianPredictive(mean, std=std), y)


def distribution_scores(dist, y):
    """How well a predictive distribution describes the targets ``y``, from its own intervals and density.

    Parameters
    ----------
    dist : GaussianPredictive or StudentTMixture or None
        A predictive of :mod:`filterwnn.wnn.predictive` (what
        :meth:`~filterwnn.wnn.regressor.WNNRegressor.predictive` returns); None: no predictive distribution.
    y : array-like of shape (n,)

    Returns
    -------
    dict
        ``coverage50``, ``coverage90``, ``coverage95``: the share of targets inside the
        predictive's own central 50 / 90 / 95 % interval (for a Gaussian ``mean +- z std``,
        for the Student-t mixture its quantiles); ``nlpd``: minus the mean of its log-density at
        the targets. All NaN for ``dist=None``. For a Gaussian these are the numbers of
        :func:`predictive_scores`, to the last digit.

    >>> from filterwnn.wnn.predictive import StudentTMixture
    >>> t = StudentTMixture(np.zeros((1, 4)), np.ones(1), np.array([1.0]))   # a Cauchy
    >>> distribution_scores(t, np.array([0.1, -0.5, 1.0, 3.0]))["coverage50"]
    0.75
    """
    if dist is None:
        return {k: float("nan") for k in SCORE_COLUMNS}
    y = np.asarray(y, dtype=float)
    out = {f"coverage{c}": float(np.mean(dist.covers(y, c / 100.0))) for c in (50, 90, 95)}
    out["nlpd"] = float(np.mean(-dist.logpdf(y)))
    return out


def fit_run(trainer, run_seed, n_epochs, n_particles=50, table="working", track_test=True, run=0, params=None,
            recal_factor=None):
    """Train one WNN in one run and score it on that run's test set.

    Parameters
    ----------
    trainer : str
        A key of ``ROWS``: a trainer of :data:`filterwnn.wnn.trainers.TRAINERS`, or a study-only row of ``STUDY``.
    run_seed : (entropy, spawn_key)
        From :func:`run_seeds`.
    n_epochs, n_particles : int
    table : {"working", "paper"}
        Working settings (scaled start, ``"auto"``) or the paper's literal ones.
    track_test : bool
        Record the test MSE after every epoch (``curve_test``).
    params : dict, optional
        Extra :class:`~filterwnn.WNNRegressor` parameters.
    recal_factor : float, optional
        Score the predictive recalibrated by this width factor
        (:func:`~filterwnn.wnn.predictive.recalibrate`; fitted on other data by the caller); the
        unrecalibrated scores are kept as ``coverage50_base`` ... ``nlpd_base``.

    Returns
    -------
    dict
        See :class:`StudyResult` ``runs`` (and :func:`predictive_scores`).
    """
    from threadpoolctl import threadpool_limits
    with threadpool_limits(limits=1), warnings.catch_warnings():
        warnings.simplefilter("ignore", DegeneracyWarning)  # reported as ESS and distinct particles
        X, y, X_test, y_test = make_siso_benchmark(rng=_child(run_seed, 0))
        reg = _regressor(trainer, table, run_seed, n_epochs, n_particles, params)
        curve_test, status = [], "ok"
        try:
            if track_test:
                _train_tracked(reg, X, y, X_test, y_test, n_epochs, curve_test)
            else:
                reg.fit(X, y)
            dist = reg.predictive(X_test)
            test_mse = float(np.mean((dist.mean - y_test) ** 2))
            scores = distribution_scores(dist, y_test)
            if recal_factor is not None:
                base = {f"{k}_base": v for k, v in scores.items()}
                scores = dict(distribution_scores(recalibrate(dist, recal_factor), y_test), **base,
                              recal_factor=float(recal_factor))
            train_mse = reg.loss_curve_[-1]
        except np.linalg.LinAlgError as exc:  # NumericalError included: a failed run is a result
            status, test_mse, train_mse = f"failed: {exc}", float("nan"), float("nan")
            scores = predictive_scores(None, None, y_test)
            if not hasattr(reg, "fit_time_"):
                reg.fit_time_ = float("nan")
        return {
            "table": table,
            "trainer": trainer,
            "run": run,
            "test_mse": test_mse,
            "train_mse": float(train_mse),
            "fit_time": float(reg.fit_time_),
            **_particle_fields(reg),
            **_noise_fields(reg),
            **scores,
            "var_test": float(np.var(y_test)),
            "curve_train": list(getattr(reg, "loss_curve_", [])),
            "curve_test": curve_test,
            "settings": _settings_text(table, trainer, reg) if hasattr(reg, "settings_") else table,
            "n_particles": n_particles if _uses_particles(trainer) else 0,
            "epochs": int(getattr(reg, "n_iter_", 0)),
            "status": status,
        }


def fit_reference(name, run_seed, run=0):
    """Fit a scikit-learn reference (``MLPRegressor`` or ``GaussianProcessRegressor``) on run data.

    ``MLPRegressor``: 20 tanh units, L-BFGS, ``alpha=1e-2``, 2000 iterations.
    ``GaussianProcessRegressor``: constant x ARD RBF + white noise, 2 optimiser restarts.
    """
    from threadpoolctl import threadpool_limits
    from sklearn.gaussian_process import GaussianProcessRegressor
    from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.neural_network import MLPRegressor

    check_choice(name, "reference", REFERENCES)
    with threadpool_limits(limits=1):
        X, y, X_test, y_test = make_siso_benchmark(rng=_child(run_seed, 0))
        seed = int(_child(run_seed, 1).generate_state(1)[0])
        if name == "MLPRegressor":
            model = MLPRegressor(
                hidden_layer_sizes=(20,), activation="tanh", solver="lbfgs", alpha=1e-2, max_iter=2000,
                random_state=seed,
            )
            settings = "reference: MLPRegressor 5-20-1 tanh, lbfgs, alpha=1e-2"
        else:
            kernel = ConstantKernel(1.0) * RBF(length_scale=np.ones(X.shape[1])) + WhiteKernel(1e-3)
            model = GaussianProcessRegressor(kernel=kernel, normalize_y=True, n_restarts_optimizer=2, random_state=seed)
            settings = "reference: GaussianProcessRegressor, ARD RBF + white noise"
        t0 = time.perf_counter()
        with warnings.catch_warnings():  # length scales of the distractor inputs hit their bound: intended
            warnings.simplefilter("ignore", ConvergenceWarning)
            model.fit(X, y)
        fit_time = time.perf_counter() - t0
        if name == "GaussianProcessRegressor":  # predictive std, the fitted white noise included
            scores = predictive_scores(*model.predict(X_test, return_std=True), y_test)
        else:
            scores = predictive_scores(None, None, y_test)
        return {
            "table": "reference",
            "trainer": name,
            "run": run,
            "test_mse": float(np.mean((model.predict(X_test) - y_test) ** 2)),
            "train_mse": float(np.mean((model.predict(X) - y) ** 2)),
            "fit_time": fit_time,
            "mean_ess": float("nan"),
            "distinct": 0,
            **scores,
            "var_test": float(np.var(y_test)),
            "curve_train": [],
            "curve_test": [],
            "settings": settings,
            "n_particles": 0,
            "epochs": 0,
            "status": "ok",
        }


def _task(task):
    kind, args, kwargs = task
    if kind == "reference":
        return fit_reference(*args, **kwargs)
    if kind == "tune":
        return tune_run(*args, **kwargs)
    if kind == "calibration":
        return calibration_run(*args, **kwargs)
    return fit_run(*args, **kwargs)


def run_tasks(tasks, n_jobs=1, backend=None, progress=False, cache_dir=None, cached_only=False):
    """Run study tasks through joblib; results in task order whatever ``n_jobs``.

    Parameters
    ----------
    tasks : list of (kind, args, kwargs)
        ``kind`` "fit" (:func:`fit_run`), "tune" (:func:`tune_run`), "calibration"
        (:func:`calibration_run`) or "reference" (:func:`fit_reference`).
    n_jobs : int
        joblib workers (``-1``: all cores).
    backend : str, optional
        joblib backend name ("loky", "threading", "dask", ...); ``None`` is joblib's
        default (loky). "dask" needs a ``dask.distributed.Client`` (see :func:`run`).
    progress : bool
        A tqdm bar over tasks.
    cache_dir : str, optional
        Checkpoint folder: each finished task is saved there as JSON (named by a hash of
        the task), and tasks already there are loaded instead of run, so an interrupted
        study resumes where it stopped, with the same numbers.
    cached_only : bool
        Only load cached results; tasks not in the cache give ``None``.

    Returns
    -------
    list
        One result dict per task (``None`` for a task skipped by ``cached_only``).
    """
    return runner.run_tasks(tasks, _task, n_jobs=n_jobs, backend=backend, progress=progress, cache_dir=cache_dir,
                            cached_only=cached_only, desc="WNN study", unit="fit", serializer=runner.JSON)


_q = runner.quantile


def summarize(runs):
    """Table rows (one per table and trainer, in first-seen order) from per-run results."""
    keys = []
    for r in runs:
        k = (r["table"], r["trainer"], r.get("n_particles", 0))
        if k not in keys:
            keys.append(k)
    rows = []
    for table, trainer, _ in keys:
        rs = [r for r in runs if r["table"] == table and r["trainer"] == trainer]
        mse = [r["test_mse"] for r in rs]
        paper = study_entry(trainer).paper if trainer in _rows() else None
        paper = paper or (float("nan"), float("nan"))
        # an unweighted average (combine="mean") has no weights whose ESS would mean anything
        weighted = trainer not in TRAINERS or TRAINERS[trainer].combine != "mean"
        ess = [r["mean_ess"] for r in rs if np.isfinite(r["mean_ess"]) and weighted]
        distinct = [r["distinct"] for r in rs if r["distinct"] > 0]
        ancestors = [r["ancestors"] for r in rs if r.get("ancestors", -1) > 0]  # absent from older caches
        rows.append({
            "table": table,
            "trainer": trainer,
            "algorithm": row_label(trainer, rs[0].get("n_particles", 0)),
            "settings": rs[0]["settings"],
            "test_mse_median": _q(mse, 0.5),
            "test_mse_q1": _q(mse, 0.25),
            "test_mse_q3": _q(mse, 0.75),
            "fit_time_median": _q([r["fit_time"] for r in rs], 0.5),
            "mean_ess": float(np.mean(ess)) if ess else float("nan"),
            "distinct_median": float(np.median(distinct)) if distinct else float("nan"),
            "distinct_particles": float(np.mean(distinct)) if distinct else float("nan"),
            "distinct_ancestors": float(np.mean(ancestors)) if ancestors else float("nan"),
            **{k: _q([r.get(k, float("nan")) for r in rs], 0.5) for k in SCORE_COLUMNS},
            "n_runs": len(rs),
            "epochs": max(r.get("epochs", 0) for r in rs),
            "n_failed": sum(r["status"] != "ok" for r in rs),
            "var_test_median": _q([r["var_test"] for r in rs], 0.5),
            "paper_mse": paper[0] if table != "reference" else float("nan"),
            "paper_time": paper[1] if table != "reference" else float("nan"),
        })
    return rows


def _search(trainers, plan, seed, run_kw):
    """The settings search on the validation split (module docstring): the single filters and BP
    first, then the trainers that centre on their parent's choice.

    Returns
    -------
    chosen : dict
        ``trainer -> select_settings(...)[0]``.
    tuning : list of dict
        The candidates' rows.
    complete : bool
        False when some trainer's search is not finished (``cached_only``).
    """
    chosen, tuning, complete = {}, [], True
    if not plan.tune_runs:
        return chosen, tuning, complete
    tseeds = tune_seeds(seed, plan.tune_runs)
    parent_of, cost = _specs_with("parent"), _cost()
    searched = [t for t in trainers if candidates(t) != [{}]]
    for phase in ([t for t in searched if t not in parent_of], [t for t in searched if t in parent_of]):
        ttasks = []
        parents = {k: v["params"] for k, v in chosen.items()}
        for t in phase:
            for c, params in enumerate(candidates(t, parents)):
                for j in range(plan.tune_runs):
                    ttasks.append(("tune", (t, tseeds[j], plan.epochs(t), plan.n_particles),
                                   {"params": params, "candidate": c, "run": j}))
        ttasks.sort(key=lambda task: -_task_cost(task, cost))
        results = run_tasks(ttasks, **run_kw)
        for t in phase:
            rs = [r for r in results if r is not None and r["trainer"] == t]
            if len(rs) < sum(task[1][0] == t for task in ttasks):
                complete = False
                continue
            choice, rows = select_settings(rs)
            chosen[t] = choice
            tuning += rows
    return chosen, tuning, complete


def _calibrate(trainers, plan, seed, run_kw):
    """The recalibrated rows' width factors, each fitted on the tuning runs' validation split.

    For every row with a ``recalibrate`` level, the row's trainer is fitted on each tuning run
    (:func:`calibration_run`), the standardized validation residuals of all tuning runs are pooled
    and :func:`~filterwnn.wnn.predictive.conformal_factor` gives the factor at that level.

    Returns
    -------
    dict
        ``row -> {"factor", "level", "n_residuals", "val_mse_median"}`` (only the rows whose
        calibration runs all finished).
    """
    rows = {t: study_entry(t).recalibrate for t in trainers if study_entry(t).recalibrate is not None}
    if rows and not plan.tune_runs:
        raise ValueError(f"tune_runs must be >= 1 for the recalibrated rows {sorted(rows)} (their factor is "
                         f"fitted on the tuning runs' validation split), got {plan.tune_runs}")
    tseeds = tune_seeds(seed, plan.tune_runs)
    tasks = [("calibration", (t, tseeds[j], plan.n_particles), {"run": j}) for t in rows for j in range(plan.tune_runs)]
    results = run_tasks(tasks, **run_kw) if tasks else []
    out = {}
    for t, level in rows.items():
        rs = [r for r in results if r is not None and r["trainer"] == t]
        if len(rs) == plan.tune_runs:
            res = np.concatenate([r["residuals"] for r in rs])
            out[t] = {"factor": conformal_factor(res, level), "level": level, "n_residuals": int(res.size),
                      "val_mse_median": _q([r["val_mse"] for r in rs], 0.5)}
    return out


def _run_scheduled(tasks, run_kw):
    """Run ``tasks``: the working table run by run (so an interrupted study has whole runs), then
    references, paper table and sweep, longest first inside each; results in task order."""
    group = {"working": 0, "paper": 2, "sweep": 3}
    cost = _cost()

    def priority(k):
        kind, args, kwargs = tasks[k]
        g = 1 if kind == "reference" else group[kwargs["table"]]
        return (g, kwargs["run"] if g == 0 else 0, -_task_cost(tasks[k], cost))

    order = sorted(range(len(tasks)), key=priority)
    results = run_tasks([tasks[k] for k in order], **run_kw)
    out = [None] * len(tasks)
    for k, r in zip(order, results):
        out[k] = r
    return out


def _sweep_table(main, swept, trainers, sweep_particles, plan):
    """The particle sweep's rows (Figs. 3-4), the main table's runs counted at its particle number."""
    sweep = []
    pool = [r for r in main if r["table"] == "working" and r["trainer"] in _sweep_rows()] + swept
    for t in [t for t in trainers if t in _sweep_rows()]:
        for n in sorted(set(list(sweep_particles) + [plan.n_particles])):
            rs = [r for r in pool if r["trainer"] == t and r["n_particles"] == n][:plan.sweep_runs]
            if not rs:
                continue
            sweep.append({
                "trainer": t, "n_particles": int(n), "n_runs": len(rs),
                "test_mse_median": _q([r["test_mse"] for r in rs], 0.5),
                "fit_time_median": _q([r["fit_time"] for r in rs], 0.5),
            })
    return sweep


def run_study(n_runs=3, n_epochs=30, pf_epochs=None, n_particles=10, trainers=ALL_TRAINERS, seed=2026,
              paper_table=True, paper_runs=None, paper_pf_epochs=None, references=REFERENCES,
              sweep_particles=(5, 10, 20), sweep_runs=None, n_jobs=1, backend=None, progress=False,
              cache_dir=None, cached_only=False, tune_runs=2):
    """Run the study (settings search, Table 1 rows, the particle sweep, the curves).

    Parameters
    ----------
    n_runs : int
        Independent runs per trainer (the paper: 50).
    n_epochs : int
        Epochs of the single-filter trainers and BP (the paper: up to 200).
    pf_epochs : int, optional
        Epochs of the particle-filter trainers (default ``n_epochs``).
    n_particles : int
        Particles of the main table (the paper: 50).
    trainers : sequence of str
        Row keys (:data:`~filterwnn.studies.wnn.rows.ALL_TRAINERS` by default; any registered trainer has a row).
    seed : int
        Root of ``SeedSequence(seed).spawn(n_runs)``.
    paper_table : bool
        Also run every trainer at the paper's literal settings.
    paper_runs : int, optional
        Runs of the paper-settings table (default ``n_runs``).
    paper_pf_epochs : int, optional
        Epochs of the particle filters in the paper-settings table (default ``pf_epochs``).
    references : sequence of str
        scikit-learn references to fit on the same runs.
    sweep_particles : sequence of int
        Particle counts of Figs. 3-4 (the paper: 50..250); empty to skip.
    sweep_runs : int, optional
        Runs per sweep point (default ``n_runs``).
    n_jobs, backend, progress, cache_dir, cached_only
        See :func:`run_tasks` (``cache_dir`` makes the study resumable).
    tune_runs : int
        Tuning runs of the settings search on the validation split (module docstring);
        0 uses :data:`~filterwnn.wnn.trainers.AUTO_SETTINGS` and all ``n_epochs``.

    Returns
    -------
    StudyResult
    """
    plan = _plan(n_runs, n_epochs, pf_epochs, n_particles, trainers, seed, paper_runs, paper_pf_epochs, sweep_runs,
                 tune_runs)
    run_kw = dict(n_jobs=n_jobs, backend=backend, progress=progress, cache_dir=cache_dir, cached_only=cached_only)
    chosen, tuning, complete = _search(trainers, plan, seed, run_kw)
    if plan.tune_runs and not complete:  # cached_only with an unfinished search: the rows that need none
        copy = _specs_with("copy_settings")
        trainers = [t for t in trainers if t in chosen or candidates(t) == [{}] and t not in copy]
    calibration = _calibrate(trainers, plan, seed, run_kw)
    trainers = [t for t in trainers if study_entry(t).recalibrate is None or t in calibration]
    tasks, n_main = _study_tasks(trainers, plan, chosen, references, paper_table, sweep_particles)
    for kind, args, kwargs in tasks:
        if kind == "fit" and args[0] in calibration:
            kwargs["recal_factor"] = calibration[args[0]]["factor"]
    out = _run_scheduled(tasks, run_kw)
    main, swept = [r for r in out[:n_main] if r is not None], [r for r in out[n_main:] if r is not None]
    config = dict(
        n_runs=plan.n_runs, n_epochs=plan.n_epochs, pf_epochs=plan.pf_epochs, n_particles=plan.n_particles,
        seed=seed, trainers=list(trainers), paper_runs=plan.paper_runs if paper_table else 0,
        paper_pf_epochs=plan.paper_pf_epochs, sweep_particles=list(sweep_particles), sweep_runs=plan.sweep_runs,
        n_jobs=n_jobs, backend=backend or "loky", n_tasks=len(out), n_done=sum(r is not None for r in out),
        tune_runs=plan.tune_runs, validation_fraction=VALIDATION_FRACTION, tuning_complete=complete,
        calibration=calibration)
    return StudyResult(runs=main + swept, table=summarize(main), sweep=_sweep_table(main, swept, trainers,
                       sweep_particles, plan), config=config, tuning=tuning)
