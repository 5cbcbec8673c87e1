"""The first paper's WNN study: Table 1 and Figs. 3-5 (Niu, Wu and Li).

``filterwnn study wnn`` trains a 5-20-1 Morlet wavelet network on the SISO benchmark of
the paper's eq. (12) (:func:`filterwnn.make_siso_benchmark`) with the rows of ``ROWS`` (one per
trainer of :data:`filterwnn.wnn.trainers.TRAINERS`, plus the move rows of ``MOVE_ROWS``),
each named for the algorithm it runs: the paper's seven trainers plus the SUKF (``bp, ekf,
ukf, sukf, spf, epf, upf, supf``; the particle filters with textbook weights), the UPF with a
MALA move after each resampling (``upf+mala``), the Gaussian-sum filters of N EKFs, UKFs and
SUKFs at tempering 0.01 (``gsf-ekf, gsf-ukf, gsf-sukf``: the paper's Kalman-proposal
trainers at their working settings, formerly "bank"), N independent EKFs averaged without
weights (``ekf-ensemble``) and the SMC sampler (``smc``), over independent runs, and writes
(the protocol: ``docs/study-outputs/wnn/PROTOCOL.md``)

``table1.md``
    the Markdown table: one row per trainer at its *working* settings (scaled start; Q, P0 or
    the learning rate, and the number of epochs
    chosen on a validation split, see *Settings* below), a second table at the *paper's* settings (U[0, 1] start, Q = 1,
    R = 0.1, P0 = 1, textbook particle weights), reference rows for scikit-learn's
    ``MLPRegressor`` and ``GaussianProcessRegressor`` on the same data, and the paper's
    Table 1 values beside ours;
``table1.csv``
    the same rows with the columns of :data:`TABLE_COLUMNS`: ``trainer`` (the row key),
    ``algorithm``, ``settings`` (weighting, tempering, move), test MSE median and quartiles,
    ``fit_time_median``, ``mean_ess``, ``distinct_particles`` and ``distinct_ancestors`` (means
    over runs at the end: distinct particles, and distinct initial particles they descend from;
    empty for non-particle rows) and ``coverage90`` (median over runs of the share of test
    targets inside mean +- 1.645 std of ``predict(return_std=True)``; the GP's std included);
``runs.csv``
    one line per (table, trainer, run): test/train MSE, fit time, ESS, distinct particles;
``tuning.md``, ``tuning.csv``
    every candidate setting tried on the validation split, its best epoch and validation
    MSE, and which one was chosen;
``fig3_particles_mse.png``, ``fig4_particles_time.png``, ``fig5_supf_convergence.png``
    test MSE and training time against the number of particles for the four particle
    filters, and the SUPF convergence curve (training and test MSE per epoch).

**Settings.** Before the runs, each trainer tries the candidates of :data:`TUNING_GRID`
on ``tune_runs`` separate *tuning* runs (their own seeds, independent of the table's runs):
it trains on the first 80 % of the tuning run's training rows and scores the last 20 %
after every epoch. Each candidate's median validation curve is smoothed by a running median
of 5 epochs; the candidate and epoch with the lowest smoothed value are then
used for every run of the table (trained on all 100 training rows). Rows with a move and the
SMC sampler run one pass with fixed settings; the EKF ensemble copies ``gsf-ekf``'s choice. The test rows are
never looked at to choose anything. The particle filters and Gaussian sums search Q (x 0.01
to x 100) around the value chosen for the filter their proposal or components use (EPF: EKF,
UPF: UKF, SUPF: SUKF) and keep its P0, so their candidates are set after the single filters' search. ``tune_runs=0`` skips the search
and uses :data:`filterwnn.wnn.trainers.AUTO_SETTINGS` for the full ``n_epochs``.

**Runs.** Run ``i`` uses ``SeedSequence(seed).spawn(n_runs)[i]``; it re-draws its data
from its own seed (so the test set's variance differs between runs: 1.66 for one seed,
about 2.35 typical), and every trainer in run ``i`` sees the same data and the same scaled
start. The runs go through joblib (``--jobs``, ``--backend``) with one BLAS thread per
worker (threadpoolctl); every number except the timings is identical for any ``--jobs``
and backend. To hand the runs to a Dask cluster::

    filterwnn study wnn --backend dask --scheduler tcp://host:8786 --jobs -1

(``--backend dask`` without ``--scheduler`` starts a local ``dask.distributed``
cluster). Timings measured in parallel include contention between workers.

**Size.** The paper's protocol (50 runs, 200 epochs, 50 particles, Figs. 3-4 at 50..250
particles) costs many hours on 2 cores, mostly the particle filters' 160x160 covariance
per particle (``benchmarks/bench_particle.py`` times one step). The default here is a *reduced*
protocol that finishes in a few minutes on 2 cores, and says so in its output;
``--runs``, ``--epochs``, ``--pf-epochs``, ``--particles`` and ``--sweep-particles`` scale it.

>>> res = run_study(n_runs=2, n_epochs=2, pf_epochs=1, n_particles=3, trainers=["ekf", "spf"],
...                 paper_table=False, references=(), sweep_particles=(), seed=1, tune_runs=1)
>>> [row["trainer"] for row in res.table]
['ekf', 'spf']
>>> res.table[1]["algorithm"], sorted(res.table[0])[:3]
('SPF (bootstrap)', ['algorithm', 'coverage90', 'distinct_ancestors'])
"""

from __future__ import annotations

import csv
import os
import time
import warnings
from typing import NamedTuple

import numpy as np

from .._validation import check_choice, check_positive_int, check_seed
from ..datasets import make_siso_benchmark
from ..monte_carlo.particle_filter import DegeneracyWarning
from ..wnn.regressor import WNNRegressor
from ..wnn.trainers import AUTO_SETTINGS, PAPER_SETTINGS, TRAINERS
from . import options
from . import runner

__all__ = [
    "ALL_TRAINERS",
    "PARTICLE_TRAINERS",
    "PAPER_TABLE1",
    "REFERENCES",
    "TABLE_COLUMNS",
    "TUNING_GRID",
    "PROPOSAL_PARENT",
    "StudyResult",
    "run_seeds",
    "tune_seeds",
    "candidates",
    "tune_run",
    "select_settings",
    "fit_run",
    "fit_reference",
    "run_tasks",
    "summarize",
    "run_study",
    "write_outputs",
    "markdown_table",
    "tuning_table",
    "is_reduced",
    "add_arguments",
    "run",
]

class StudyRow(NamedTuple):
    """One row of the study: the trainer it runs, its fixed ``WNNRegressor`` keywords, its fixed
    epochs (None: searched, or the study's epochs) and its label (``{N}``: the number of particles)."""

    trainer: str
    fixed: dict
    epochs: object
    label: str


#: Study-only rows: a registered trainer with a move. key -> (row, cost per epoch and particle,
#: in :data:`ALL_TRAINERS`). They follow the last particle filter in ``ROWS``.
MOVE_ROWS = {
    "spf+mala": (StudyRow("spf", {"move": "mala"}, 1, "SPF + MALA move"), 3, False),
    "epf+mala": (StudyRow("epf", {"move": "mala"}, 1, "EPF + MALA move"), 4, False),
    "upf+mala": (StudyRow("upf", {"move": "mala"}, 1, "UPF + MALA move"), 8, True),
    "supf+mala": (StudyRow("supf", {"move": "mala"}, 1, "SUPF + MALA move"), 6, False),
    "upf+hmc": (StudyRow("upf", {"move": "hmc"}, 1, "UPF + HMC move"), 12, False),
}


def _rows():
    """key -> :class:`StudyRow`: each registered trainer's row (from its
    :class:`~filterwnn.wnn.trainers.TrainerSpec`), and the move rows after the last particle filter;
    read when called, so that a trainer registered later has its row."""
    particle = [name for name, spec in TRAINERS.items() if spec.accepts_move]
    rows = {}
    for name, spec in TRAINERS.items():
        rows[name] = StudyRow(name, dict(spec.study), spec.study_epochs, spec.label or name)
        if particle and name == particle[-1]:
            rows.update({key: row for key, (row, _, _) in MOVE_ROWS.items()})
    return rows


def _uses_particles(key):
    """Whether row ``key``'s trainer carries ``n_particles`` particles or components."""
    return TRAINERS[_rows()[key].trainer].uses_particles


def _specs_with(attr):
    """``name -> spec.<attr>`` for the registered trainers whose ``attr`` is set (not None or empty)."""
    return {name: getattr(spec, attr) for name, spec in TRAINERS.items() if getattr(spec, attr) not in (None, (), {})}


def _sweep_rows():
    """Rows of the particle sweep: the registered particle filters."""
    return [name for name, spec in TRAINERS.items() if spec.accepts_move]


def _cost():
    """Rough seconds per epoch and particle of every row, for scheduling the longest tasks first."""
    return {k: TRAINERS[k].cost if k in TRAINERS else MOVE_ROWS[k][1] for k in _rows()}


def _in_paper_table(key):
    """Whether row ``key`` also runs at the paper's literal settings."""
    return key in TRAINERS and TRAINERS[key].paper_settings is not None


#: The study's rows at import (:class:`StudyRow` tuples): every registered trainer's row, and
#: ``MOVE_ROWS``. See ``docs/study-outputs/wnn/PROTOCOL.md``.
ROWS = _rows()
#: The rows run by default: every trainer, and the move rows so marked in ``MOVE_ROWS``.
ALL_TRAINERS = tuple(k for k in ROWS if k in TRAINERS or MOVE_ROWS[k][2])
#: Rows whose trainer carries ``n_particles`` particles or components.
PARTICLE_TRAINERS = tuple(k for k in ROWS if _uses_particles(k))
#: Rows of the particle sweep (Figs. 3-4): the papers' particle filters (the particle family).
SWEEP_TRAINERS = tuple(_sweep_rows())
#: Rows that copy another row's chosen settings and epochs instead of searching (the entries' ``copy_settings``).
COPY_SETTINGS = _specs_with("copy_settings")

REFERENCES = ("MLPRegressor", "GaussianProcessRegressor")
TABLE_COLUMNS = (
    "trainer", "algorithm", "settings", "test_mse_median", "test_mse_q1", "test_mse_q3", "fit_time_median",
    "mean_ess", "distinct_particles", "distinct_ancestors", "coverage90",
)


def row_label(key, n_particles):
    """The algorithm's name for row ``key`` (e.g. ``"Gaussian-sum filter of 20 EKFs (tempering 0.01)"``)."""
    rows = _rows()
    return rows[key].label.format(N=n_particles) if key in rows else key

#: Candidates tried on the validation split, per trainer (``WNNRegressor`` keywords; the entries'
#: ``grid``). EPF/UPF/SUPF and the Gaussian sums are not listed: they search ``Q x Q_FACTORS``
#: around the Q chosen for their proposal's filter (:data:`PROPOSAL_PARENT`) and keep its P0
#: (see :func:`candidates`).
TUNING_GRID = {name: [dict(c) for c in grid] for name, grid in _specs_with("grid").items()}

#: The single filter whose step each particle filter's proposal (or Gaussian sum's component) runs
#: (the entries' ``parent``).
PROPOSAL_PARENT = _specs_with("parent")

#: Factors applied to the parent's chosen Q (:func:`candidates`).
Q_FACTORS = (0.01, 0.1, 1.0, 10.0, 100.0)

#: Window of the running median that smooths the validation curve before its minimum is taken.
SMOOTHING_WINDOW = 5

#: Half-width of the central 90 % interval of a normal, in standard deviations.
Z90 = 1.6448536269514722

#: Fraction of a tuning run's training rows (the last ones) held out for validation.
VALIDATION_FRACTION = 0.2

#: The paper's Table 1: trainer -> (test MSE, training time in s) (the entries' ``paper``). It has no SUKF row.
PAPER_TABLE1 = _specs_with("paper")


class StudyResult(NamedTuple):
    """Everything :func:`run_study` measured (plain lists and dicts, no figures).

    runs : list of dict
        One per (table, trainer, run): ``table`` ("working"/"paper"/"reference"),
        ``trainer``, ``run``, ``test_mse``, ``train_mse``, ``fit_time``, ``mean_ess``,
        ``distinct``, ``var_test``, ``curve_train``, ``curve_test``, ``settings``.
    table : list of dict
        Summary rows (:data:`TABLE_COLUMNS` plus ``table``, ``n_runs``, ``paper_mse``,
        ``paper_time``).
    sweep : list of dict
        Particle sweep rows: ``trainer``, ``n_particles``, ``test_mse_median``,
        ``fit_time_median``, ``n_runs``.
    config : dict
        The protocol's size and seed.
    tuning : list of dict
        One row per (trainer, candidate) tried on the validation split (see
        :func:`select_settings`); empty when ``tune_runs=0``.
    """

    runs: list
    table: list
    sweep: list
    config: dict
    tuning: list = []


# ---------------------------------------------------------------------------- seeds
def run_seeds(seed, n_runs):
    """``SeedSequence(seed).spawn(n_runs)`` as picklable ``(entropy, spawn_key)`` pairs."""
    seed = check_seed(seed)
    return [(ss.entropy, tuple(ss.spawn_key)) for ss in np.random.SeedSequence(seed).spawn(n_runs)]


def _child(run_seed, k):
    """The ``k``-th child of a run's seed (0: data, 1: training), built without ``spawn``
    so that the same run gives the same streams however the tasks are scheduled."""
    return runner.child(run_seed, k)


def tune_seeds(seed, n_runs):
    """Seeds of the tuning runs: ``SeedSequence(seed, spawn_key=(10**6 + j,))``.

    Their spawn keys lie far beyond any table run's (``(i,)``, ``i < 10**6``), so the
    tuning data are independent of every run that is scored.
    """
    seed = check_seed(seed)
    return [(seed, (10**6 + j,)) for j in range(n_runs)]


def candidates(trainer, chosen=None):
    """The settings tried for ``trainer`` on the validation split.

    Parameters
    ----------
    trainer : str
    chosen : dict, optional
        ``trainer -> settings dict`` already chosen; EPF/UPF/SUPF centre their Q on their
        parent's choice there (else on the parent's :data:`~filterwnn.wnn.trainers.AUTO_SETTINGS`).

    Returns
    -------
    list of dict
        ``WNNRegressor`` keyword sets.

    >>> [c["process_noise"] for c in candidates("upf", {"ukf": {"process_noise": 1e-5, "initial_covariance": 0.01}})]
    [1e-07, 1e-06, 1e-05, 0.0001, 0.001]
    >>> candidates("upf+mala")
    [{}]
    """
    rows = _rows()
    check_choice(trainer, "trainer", rows)
    spec = TRAINERS.get(trainer)
    if rows[trainer].epochs is not None or spec is None or spec.copy_settings:  # fixed settings: nothing to search
        return [{}]
    if spec.grid:
        return [dict(c) for c in spec.grid]
    parent = spec.parent
    if parent is None:  # neither a grid nor a parent: nothing to search
        return [{}]
    base = (chosen or {}).get(parent)
    if base is None:
        auto = AUTO_SETTINGS[(parent, "scaled")]
        base = {"process_noise": auto["Q"], "initial_covariance": auto["P0"]}
    q = base["process_noise"]
    return [{"process_noise": float(f"{q * f:.3g}"), "initial_covariance": base["initial_covariance"]}
            for f in Q_FACTORS]


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


def _running_median(curve, window):
    """Centred running median of ``curve`` (the window shrinks at the ends).

    >>> _running_median(np.array([5.0, 1.0, 5.0, 5.0, 5.0]), 5).tolist()
    [5.0, 5.0, 5.0, 5.0, 5.0]
    """
    half = window // 2
    return np.array([np.median(curve[max(0, i - half):i + half + 1]) for i in range(len(curve))])


def select_settings(results):
    """Pick, for one trainer, the candidate and epoch of lowest smoothed median validation MSE.

    The median over tuning runs of each candidate's validation curve is smoothed by a
    running median of ``SMOOTHING_WINDOW`` epochs (centred, shrunk at the ends); its
    minimum is the candidate's best epoch (ties: the lower raw median, then the earlier epoch).
    Ties between candidates go to the one listed first.

    A candidate that failed numerically (NumericalError) in any tuning run is passed over
    unless every candidate did.

    Parameters
    ----------
    results : list of dict
        :func:`tune_run` results of one trainer (every candidate, every tuning run).

    Returns
    -------
    chosen : dict
        ``params`` (the keywords), ``epochs`` (1-based), ``val_mse``.
    rows : list of dict
        One per candidate: ``trainer``, ``params``, ``best_epoch``, ``val_mse`` (the smoothed median
        over tuning runs at its best epoch), ``val_mse_last`` (the raw median at the last epoch),
        ``n_runs``, ``n_failed``, ``chosen``.

    >>> rs = [{"trainer": "ekf", "candidate": c, "params": {"process_noise": q}, "curve_val": cv,
    ...        "status": "ok"} for c, q, cv in ((0, 1e-3, [3.0, 2.0, 2.5]), (1, 1e-2, [4.0, 1.0, 9.0]))]
    >>> chosen, rows = select_settings(rs)
    >>> chosen
    {'params': {'process_noise': 0.001}, 'epochs': 2, 'val_mse': 2.5}
    """
    by = {}
    for r in results:
        by.setdefault(r["candidate"], []).append(r)
    rows = []
    for c in sorted(by):
        rs = by[c]
        n = min(len(r["curve_val"]) for r in rs)
        med = np.median(np.array([r["curve_val"][:n] for r in rs], dtype=float), axis=0)
        raw = np.where(np.isfinite(med), med, np.inf)
        med = _running_median(raw, SMOOTHING_WINDOW)
        # the smoothed minimum; ties (e.g. a curve shorter than the window) go to the lower raw
        # validation MSE, then the earlier epoch
        e = min(range(n), key=lambda i: (med[i], raw[i], i))
        rows.append({
            "trainer": rs[0]["trainer"], "candidate": c, "params": dict(rs[0]["params"]), "best_epoch": e + 1,
            "val_mse": float(med[e]), "val_mse_last": float(raw[-1]), "n_runs": len(rs),
            "n_failed": sum(r["status"] != "ok" for r in rs), "chosen": False,
        })
    # a setting that failed numerically in any tuning run is chosen only if all did
    best = min(rows, key=lambda r: (r["n_failed"] > 0, r["val_mse"], r["candidate"]))
    best["chosen"] = True
    return {"params": best["params"], "epochs": best["best_epoch"], "val_mse": best["val_mse"]}, rows


# ---------------------------------------------------------------------------- one run
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
        txt = f"init={s['init']}, Q={s['Q']:g}, P0={s['P0']:g}, R={s['R']:g}"
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
        p.update(spec.paper_settings or {})
        return p
    return {"init": "scaled"}


def fit_run(trainer, run_seed, n_epochs, n_particles=50, table="working", track_test=True, run=0, params=None):
    """Train one WNN in one run and score it on that run's test set.

    Parameters
    ----------
    trainer : str
        A key of ``ROWS``: a trainer of :data:`filterwnn.wnn.trainers.TRAINERS`, or a row of ``MOVE_ROWS``.
    run_seed : (entropy, spawn_key)
        From :func:`run_seeds`.
    n_epochs, n_particles : int
    table : {"working", "paper"}
        Working settings (scaled start, ``"auto"``) or the paper's literal ones.
    track_test : bool
        Record the test MSE after every epoch (``curve_test``).
    params : dict, optional
        Extra :class:`~filterwnn.WNNRegressor` parameters.

    Returns
    -------
    dict
        See :class:`StudyResult` ``runs``.
    """
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1), warnings.catch_warnings():
        warnings.simplefilter("ignore", DegeneracyWarning)  # reported as ESS and distinct particles
        X, y, X_test, y_test = make_siso_benchmark(rng=_child(run_seed, 0))
        kind, fixed, _, _ = _rows()[trainer]
        kw = _params(table, trainer)
        if table != "paper":
            kw.update(fixed)
        kw.update(params or {})
        reg = WNNRegressor(trainer=kind, n_epochs=n_epochs, n_particles=n_particles, random_state=_child(run_seed, 1), **kw)
        curve_test = []
        status = "ok"
        try:
            if track_test:
                _train_tracked(reg, X, y, X_test, y_test, n_epochs, curve_test)
            else:
                reg.fit(X, y)
            mean, std = reg.predict(X_test, return_std=True)
            test_mse = float(np.mean((mean - y_test) ** 2))
            coverage = float(np.mean(np.abs(y_test - mean) <= Z90 * std))
            train_mse = reg.loss_curve_[-1]
        except np.linalg.LinAlgError as exc:  # NumericalError included: a failed run is a result
            status = f"failed: {exc}"
            test_mse = train_mse = coverage = float("nan")
            if not hasattr(reg, "fit_time_"):
                reg.fit_time_ = float("nan")
        diag = getattr(reg, "diagnostics_", {}) or {}
        ess = diag.get("mean_ess")
        distinct = diag.get("distinct")
        ancestors = diag.get("distinct_ancestors")
        return {
            "table": table,
            "trainer": trainer,
            "run": run,
            "test_mse": test_mse,
            "train_mse": float(train_mse),
            "fit_time": float(reg.fit_time_),
            "mean_ess": float(np.mean(ess)) if ess else float("nan"),
            "distinct": int(distinct[-1]) if distinct else -1,
            "ancestors": int(ancestors[-1]) if ancestors else -1,
            "coverage90": coverage,
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
            mean, std = model.predict(X_test, return_std=True)
            coverage = float(np.mean(np.abs(y_test - mean) <= Z90 * std))
        else:
            coverage = float("nan")
        return {
            "table": "reference",
            "trainer": name,
            "run": run,
            "test_mse": float(np.mean((model.predict(X_test) - y_test) ** 2)),
            "train_mse": float(np.mean((model.predict(X) - y) ** 2)),
            "fit_time": fit_time,
            "mean_ess": float("nan"),
            "distinct": 0,
            "coverage90": coverage,
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
    return fit_run(*args, **kwargs)


def run_tasks(tasks, n_jobs=1, backend=None, progress=False, cache_dir=None, cached_only=False):
    """Run study tasks through joblib; results in task order whatever ``n_jobs``.

    Parameters
    ----------
    tasks : list of (kind, args, kwargs)
        ``kind`` "fit" (:func:`fit_run`), "tune" (:func:`tune_run`) or "reference"
        (:func:`fit_reference`).
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


# ---------------------------------------------------------------------------- summary
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
        paper = TRAINERS[trainer].paper if trainer in TRAINERS else None
        paper = paper or (float("nan"), float("nan"))
        # an unweighted average (combine="mean") has no weights whose ESS would mean anything
        weighted = trainer not in TRAINERS or TRAINERS[trainer].combine != "mean"
        ess = [r["mean_ess"] for r in rs if np.isfinite(r["mean_ess"]) and weighted]
        distinct = [r["distinct"] for r in rs if r["distinct"] > 0]
        ancestors = [r["ancestors"] for r in rs if r.get("ancestors", -1) > 0]  # absent from older caches
        cover = [r.get("coverage90", float("nan")) for r in rs]
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
            "coverage90": _q(cover, 0.5),
            "n_runs": len(rs),
            "epochs": max(r.get("epochs", 0) for r in rs),
            "n_failed": sum(r["status"] != "ok" for r in rs),
            "var_test_median": _q([r["var_test"] for r in rs], 0.5),
            "paper_mse": paper[0] if table != "reference" else float("nan"),
            "paper_time": paper[1] if table != "reference" else float("nan"),
        })
    return rows


# ---------------------------------------------------------------------------- study
class _Plan(NamedTuple):
    """The study's size, checked: what every task list reads."""

    n_runs: int
    n_epochs: int
    pf_epochs: int
    n_particles: int
    paper_runs: int
    paper_pf_epochs: int
    sweep_runs: int
    tune_runs: int
    seeds: list

    def epochs(self, key):
        """Epochs of row ``key`` without a search: its fixed epochs, else the study's."""
        fixed = _rows()[key].epochs
        if fixed is not None:
            return fixed
        return self.pf_epochs if _uses_particles(key) else self.n_epochs


def _plan(n_runs, n_epochs, pf_epochs, n_particles, trainers, seed, paper_runs, paper_pf_epochs, sweep_runs,
          tune_runs):
    """Check :func:`run_study`'s sizes and trainers; the run seeds."""
    n_runs = check_positive_int(n_runs, "n_runs")
    n_epochs = check_positive_int(n_epochs, "n_epochs")
    pf_epochs = n_epochs if pf_epochs is None else check_positive_int(pf_epochs, "pf_epochs")
    n_particles = check_positive_int(n_particles, "n_particles")
    rows = _rows()
    for t in trainers:
        check_choice(t, "trainer", rows)
    paper_runs = n_runs if paper_runs is None else check_positive_int(paper_runs, "paper_runs", minimum=0)
    sweep_runs = n_runs if sweep_runs is None else check_positive_int(sweep_runs, "sweep_runs")
    tune_runs = check_positive_int(tune_runs, "tune_runs", minimum=0)
    seeds = run_seeds(seed, max(n_runs, paper_runs, sweep_runs))
    paper_pf_epochs = pf_epochs if paper_pf_epochs is None else check_positive_int(paper_pf_epochs, "paper_pf_epochs")
    return _Plan(n_runs, n_epochs, pf_epochs, n_particles, paper_runs, paper_pf_epochs, sweep_runs, tune_runs, seeds)


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


def _working(t, chosen, plan):
    """(epochs, extra task keywords) of row ``t``'s table and sweep runs."""
    copy = _specs_with("copy_settings")
    if t in copy and copy[t] in chosen:
        t = copy[t]
    if t in chosen:
        return chosen[t]["epochs"], {"params": dict(chosen[t]["params"])}
    return plan.epochs(t), {}


def _study_tasks(trainers, plan, chosen, references, paper_table, sweep_particles):
    """The tasks of the working table, the references, the paper table and the sweep, and the
    index of the first sweep task (the tuples key the cache: they must not change)."""
    tasks = []
    for t in trainers:
        ep, extra = _working(t, chosen, plan)
        for i in range(plan.n_runs):
            tasks.append(("fit", (t, plan.seeds[i], ep, plan.n_particles), {"table": "working", "run": i, **extra}))
    for name in references:
        for i in range(plan.n_runs):
            tasks.append(("reference", (name, plan.seeds[i]), {"run": i}))
    if paper_table:
        for t in [t for t in trainers if _in_paper_table(t)]:
            for i in range(plan.paper_runs):
                ep = plan.paper_pf_epochs if _uses_particles(t) else plan.n_epochs
                tasks.append(("fit", (t, plan.seeds[i], ep, plan.n_particles),
                              {"table": "paper", "run": i, "track_test": False}))
    n_main = len(tasks)
    for n in sweep_particles:
        if n == plan.n_particles:
            continue  # reuse the main table's runs
        for t in [t for t in trainers if t in _sweep_rows()]:
            ep, extra = _working(t, chosen, plan)
            for i in range(plan.sweep_runs):
                tasks.append(("fit", (t, plan.seeds[i], ep, int(n)),
                              {"table": "sweep", "run": i, "track_test": False, **extra}))
    return tasks, n_main


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
        Row keys (:data:`ALL_TRAINERS` by default; any registered trainer has a row).
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
    if plan.tune_runs and not complete:  # cached_only with an unfinished search
        copy = _specs_with("copy_settings")
        trainers = [t for t in trainers if t in chosen or candidates(t) == [{}] and t not in copy]
    tasks, n_main = _study_tasks(trainers, plan, chosen, references, paper_table, sweep_particles)
    out = _run_scheduled(tasks, run_kw)
    main = [r for r in out[:n_main] if r is not None]
    swept = [r for r in out[n_main:] if r is not None]
    config = dict(
        n_runs=plan.n_runs, n_epochs=plan.n_epochs, pf_epochs=plan.pf_epochs, n_particles=plan.n_particles,
        seed=seed, trainers=list(trainers), paper_runs=plan.paper_runs if paper_table else 0,
        paper_pf_epochs=plan.paper_pf_epochs, sweep_particles=list(sweep_particles), sweep_runs=plan.sweep_runs,
        n_jobs=n_jobs, backend=backend or "loky", n_tasks=len(out), n_done=sum(r is not None for r in out),
        tune_runs=plan.tune_runs, validation_fraction=VALIDATION_FRACTION, tuning_complete=complete,
    )
    return StudyResult(runs=main + swept, table=summarize(main), sweep=_sweep_table(main, swept, trainers,
                       sweep_particles, plan), config=config, tuning=tuning)


def _task_cost(task, cost):
    kind, args, kwargs = task
    if kind == "reference":
        return 2.0
    t, _, ep, n = args
    per = cost[t] * (n if _uses_particles(t) else 1)
    return per * ep


# ---------------------------------------------------------------------------- output
def is_reduced(config):
    """True when the protocol is smaller than the paper's (50 runs, 200 epochs, 50 particles)."""
    return (
        config["n_runs"] < 50 or config["n_epochs"] < 200 or config["pf_epochs"] < 200 or config["n_particles"] < 50
    )


def _fmt(v, digits=3):
    return runner.fmt(v, digits)


def _run_variances(runs):
    """var(y_test) once per run (run ``i`` has the same data in every table; the sweep's runs too)."""
    return list({r["run"]: r["var_test"] for r in runs if r["table"] != "tuning"}.values())


def markdown_table(result):
    """The study's tables as Markdown text (working settings, paper settings, references)."""
    c = result.config
    lines = [
        "# WNN study (Niu, Wu and Li, Table 1)",
        "",
        f"Protocol: {c['n_runs']} runs (SeedSequence({c['seed']}).spawn), {c['n_epochs']} epochs "
        f"(particle filters {c['pf_epochs']}), {c['n_particles']} particles, 5-20-1 Morlet WNN, "
        "SISO plant of eq. (12), 100 train / 100 test rows. Each run re-draws its data from its own "
        "seed, so the test-set variance differs between runs (median var(y_test) over the "
        f"{len(_run_variances(result.runs))} runs {_fmt(_q(_run_variances(result.runs), 0.5))}; predicting the "
        "mean scores that).",
    ]
    if c.get("n_done", 0) < c.get("n_tasks", 0):
        lines += ["", f"**Incomplete: {c['n_done']} of {c['n_tasks']} fits finished** (the rows say how many "
                  "runs each has)."]
    if is_reduced(c):
        lines += ["", "**This is a reduced protocol** (the paper: 50 runs, 200 epochs, 50 particles); "
                  "scale it with --runs, --epochs, --pf-epochs, --particles."]
    lines += ["", f"Timings: median seconds per fit with {c['n_jobs']} joblib worker(s) ({c['backend']}), "
              "one BLAS thread each; parallel workers contend for memory bandwidth."]
    head = ("| algorithm | settings | epochs | test MSE median | q1 | q3 | fit time (s) | mean ESS | distinct particles "
            "| distinct ancestors | 90 % coverage | runs | paper MSE | paper time (s) |")
    sep = "|---" * 14 + "|"
    if c.get("tune_runs"):
        working_title = (f"Working settings (scaled start; Q, P0 or learning rate and the epochs chosen on a "
                         f"validation split of {c['tune_runs']} separate tuning run(s), never on test data)")
    else:
        working_title = "Working settings (scaled start, AUTO_SETTINGS, no search)"
    if c.get("tune_runs") and not c.get("tuning_complete", True):
        lines += ["", "**Settings search incomplete**: trainers whose search has not finished have no row."]
    for table, title in (
        ("working", working_title),
        ("paper", "Paper's settings (U[0,1] start, Q = 1, P0 = 1, R = 0.1, textbook weights, resampling every step)"),
        ("reference", "References on the same runs"),
    ):
        rows = [r for r in result.table if r["table"] == table]
        if not rows:
            continue
        lines += ["", f"## {title}", "", head, sep]
        for r in rows:
            failed = f" ({r['n_failed']} failed)" if r["n_failed"] else ""
            lines.append(
                f"| {r['algorithm']} | {r['settings'].split(': ', 1)[-1]} | {r['epochs'] or '-'} | "
                f"{_fmt(r['test_mse_median'])}{failed} | "
                f"{_fmt(r['test_mse_q1'])} | {_fmt(r['test_mse_q3'])} | {_fmt(r['fit_time_median'])} | "
                f"{_fmt(r['mean_ess'])} | {_fmt(r['distinct_particles'])} | {_fmt(r['distinct_ancestors'])} | "
                f"{_fmt(r['coverage90'])} | {r['n_runs']} | "
                f"{_fmt(r['paper_mse'], 4)} | {_fmt(r['paper_time'])} |"
            )
    if result.sweep:
        lines += ["", "## Particle sweep (Figs. 3-4)", "", "| trainer | particles | test MSE median | fit time (s) | runs |",
                  "|---|---|---|---|---|"]
        for s in result.sweep:
            lines.append(f"| {s['trainer']} | {s['n_particles']} | {_fmt(s['test_mse_median'])} | "
                         f"{_fmt(s['fit_time_median'])} | {s['n_runs']} |")
    return "\n".join(lines) + "\n"


def _params_text(params):
    names = {"process_noise": "Q", "initial_covariance": "P0", "learning_rate": "lr"}
    return ", ".join(f"{names.get(k, k)}={v:g}" for k, v in params.items())


def tuning_table(result):
    """The settings search as Markdown: every candidate, its best epoch and validation MSE."""
    c = result.config
    lines = [
        "# Settings search on a validation split",
        "",
        f"Each candidate trained on the first {1 - c.get('validation_fraction', VALIDATION_FRACTION):.0%} of the "
        f"training rows of {c.get('tune_runs', 0)} tuning run(s) (seeds independent of the table's runs) and was "
        "scored on the remaining rows after every epoch; the row marked chosen (lowest median validation MSE "
        "smoothed by a running median of 5 epochs, "
        "at its best epoch) is what the table's runs use. Test rows are never used.",
        "",
        "| trainer | candidate | best epoch | validation MSE (smoothed median) | at the last epoch (median) | runs | failed | chosen |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in result.tuning:
        lines.append(f"| {r['trainer']} | {_params_text(r['params'])} | {r['best_epoch']} | {_fmt(r['val_mse'])} | "
                     f"{_fmt(r['val_mse_last'])} | {r['n_runs']} | {r['n_failed']} | {'**yes**' if r['chosen'] else ''} |")
    return "\n".join(lines) + "\n"


def write_outputs(result, out, figures=True):
    """Write ``table1.md``, ``table1.csv``, ``runs.csv`` and the figures into ``out``.

    Returns
    -------
    list of str
        The paths written.
    """
    os.makedirs(out, exist_ok=True)
    paths = []
    p = os.path.join(out, "table1.md")
    with open(p, "w") as f:
        f.write(markdown_table(result))
    paths.append(p)
    p = os.path.join(out, "table1.csv")
    with open(p, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(TABLE_COLUMNS), extrasaction="ignore")
        w.writeheader()
        for r in result.table:
            w.writerow({k: r[k] for k in TABLE_COLUMNS})
    paths.append(p)
    p = os.path.join(out, "runs.csv")
    fields = ["table", "trainer", "run", "n_particles", "epochs", "test_mse", "train_mse", "fit_time", "mean_ess", "distinct",
              "ancestors", "coverage90", "var_test", "status", "settings"]
    with open(p, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in result.runs:
            w.writerow(r)
    paths.append(p)
    if result.tuning:
        p = os.path.join(out, "tuning.md")
        with open(p, "w") as f:
            f.write(tuning_table(result))
        paths.append(p)
        p = os.path.join(out, "tuning.csv")
        fields = ["trainer", "candidate", "settings", "best_epoch", "val_mse", "val_mse_last", "n_runs", "n_failed",
                  "chosen"]
        with open(p, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
            w.writeheader()
            for r in result.tuning:
                w.writerow(dict(r, settings=_params_text(r["params"])))
        paths.append(p)
    if figures:
        import matplotlib

        matplotlib.use("Agg")
        from . import plotting

        if result.sweep:
            for metric, name in (("test_mse_median", "fig3_particles_mse.png"),
                                 ("fit_time_median", "fig4_particles_time.png")):
                fig = plotting.wnn_particle_sweep(result.sweep, metric=metric)
                p = os.path.join(out, name)
                fig.savefig(p, dpi=120, bbox_inches="tight")
                paths.append(p)
        curves = [r for r in result.runs if r["table"] == "working" and r["curve_train"]]
        if curves:
            for trainer, name in (("supf", "fig5_supf_convergence.png"), (None, "convergence_all.png")):
                sel = [r for r in curves if trainer is None or r["trainer"] == trainer]
                if not sel:
                    continue
                fig = plotting.wnn_convergence(sel)
                p = os.path.join(out, name)
                fig.savefig(p, dpi=120, bbox_inches="tight")
                paths.append(p)
    return paths


# ---------------------------------------------------------------------------- CLI
def add_arguments(parser):
    """Options of ``filterwnn study wnn``."""
    parser.add_argument("--runs", type=options.positive_int, default=3,
                        help="independent runs per trainer (paper: 50)")
    parser.add_argument("--epochs", type=options.positive_int, default=30,
                        help="epochs of BP/EKF/UKF/SUKF (paper: 200)")
    parser.add_argument("--pf-epochs", type=options.positive_int, default=3,
                        help="epochs of the particle filters (paper: 200)")
    parser.add_argument("--particles", type=options.positive_int, default=10, help="particles in the table (paper: 50)")
    parser.add_argument("--sweep-particles", type=options.int_list(minimum=1), default="5,10,20",
                        help="comma-separated particle counts for Figs. 3-4 (paper: 50,100,150,200,250; '' skips)")
    parser.add_argument("--sweep-runs", type=options.positive_int, default=2, help="runs per sweep point")
    parser.add_argument("--paper-runs", type=options.nonnegative_int, default=None,
                        help="runs at the paper's settings (default --runs)")
    parser.add_argument("--paper-pf-epochs", type=options.positive_int, default=None,
                        help="particle-filter epochs at the paper's settings (default --pf-epochs)")
    parser.add_argument("--no-paper-table", action="store_true", help="skip the paper-settings table")
    parser.add_argument("--tune-runs", type=options.nonnegative_int, default=2,
                        help="tuning runs of the settings search on a validation split (default 2; 0: use the "
                             "regressor's AUTO_SETTINGS and all epochs)")
    parser.add_argument("--trainers", type=options.name_list(ALL_TRAINERS), default=",".join(ALL_TRAINERS),
                        help=f"comma-separated subset of {', '.join(ALL_TRAINERS)}")
    parser.add_argument("--seed", type=options.seed, default=2026,
                        help="root seed, an integer >= 0 (run i uses SeedSequence(seed).spawn(runs)[i])")
    parser.add_argument("--jobs", type=options.joblib_jobs, default=-1,
                        help="joblib workers (-1: all cores); the numbers do not depend on it")
    parser.add_argument("--backend", type=options.joblib_backend, default=None,
                        help="joblib backend name (loky, threading, dask, ...); default joblib's (loky)")
    parser.add_argument("--scheduler", default=None,
                        help="with --backend dask: a dask.distributed scheduler address (default: a local cluster)")
    parser.add_argument("--out", default="wnn-study", help="output folder")
    parser.add_argument("--cache", default=None,
                        help="checkpoint folder (default OUT/cache): each finished fit is saved there as JSON "
                             "and reused, so an interrupted study resumes with the same numbers; an entry is "
                             "used only if the same package source (a hash of every filterwnn .py file) wrote "
                             "it for the same settings, so after any code change it is recomputed (named on "
                             "stderr); 'none' disables it")
    parser.add_argument("--cached-only", action="store_true",
                        help="only summarize the fits already in the cache (run nothing)")
    parser.add_argument("--no-figures", action="store_true", help="write the tables only (no PNG figures)")
    options.add_progress_flag(parser)


def run(args):
    """Run the study from parsed arguments; prints the table and the files written."""
    import sys

    trainers, sweep = list(args.trainers), list(args.sweep_particles)
    progress = (not args.no_progress) and sys.stderr.isatty()
    cache = os.path.join(args.out, "cache") if args.cache is None else (None if args.cache == "none" else args.cache)
    t0 = time.perf_counter()
    with runner.dask_client(args.backend, args.scheduler, args.jobs):
        res = run_study(
            n_runs=args.runs, n_epochs=args.epochs, pf_epochs=args.pf_epochs, n_particles=args.particles,
            trainers=trainers, seed=args.seed, paper_table=not args.no_paper_table, paper_runs=args.paper_runs,
            paper_pf_epochs=args.paper_pf_epochs, cache_dir=cache, cached_only=args.cached_only,
            sweep_particles=sweep, sweep_runs=args.sweep_runs, n_jobs=args.jobs, backend=args.backend,
            progress=progress, tune_runs=args.tune_runs,
        )
    text = markdown_table(res)
    paths = write_outputs(res, args.out, figures=not args.no_figures)
    print(text)
    print(f"wall time {time.perf_counter() - t0:.0f} s; wrote " + ", ".join(paths))
    if is_reduced(res.config):
        print("(reduced protocol: see --help to scale it to the paper's 50 runs x 200 epochs x 50 particles)")
    return 0
