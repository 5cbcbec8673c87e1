"""The WNN study's plan: seeds, the candidates of the settings search and the choice among them,
the checked sizes and the task lists (nothing here trains a network)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..._validation import check_positive_int, check_seed
from ...wnn.trainers import AUTO_SETTINGS
from .. import runner
from .rows import (Q_FACTORS, SMOOTHING_WINDOW, _in_paper_table, _rows, _specs_with, _sweep_rows, _uses_particles,
                   check_row, study_entry)

__all__ = [
    "StudyResult",
    "run_seeds",
    "tune_seeds",
    "candidates",
    "select_settings",
]


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
    >>> candidates("ibis-mala")
    [{}]
    """
    rows = _rows()
    check_row(trainer)
    entry = study_entry(trainer)
    if rows[trainer].epochs is not None or entry.copy_settings:  # fixed settings: nothing to search
        return [{}]
    if entry.grid:
        return [dict(c) for c in entry.grid]
    parent = entry.parent
    if parent is None:  # neither a grid nor a parent: nothing to search
        return [{}]
    base = (chosen or {}).get(parent)
    if base is None:
        auto = AUTO_SETTINGS[(parent, "scaled")]
        base = {"process_noise": auto["Q"], "initial_covariance": auto["P0"]}
    q = base["process_noise"]
    return [{"process_noise": float(f"{q * f:.3g}"), "initial_covariance": base["initial_covariance"]}
            for f in (entry.q_factors or Q_FACTORS)]


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
    for t in trainers:
        check_row(t)
    paper_runs = n_runs if paper_runs is None else check_positive_int(paper_runs, "paper_runs", minimum=0)
    sweep_runs = n_runs if sweep_runs is None else check_positive_int(sweep_runs, "sweep_runs")
    tune_runs = check_positive_int(tune_runs, "tune_runs", minimum=0)
    seeds = run_seeds(seed, max(n_runs, paper_runs, sweep_runs))
    paper_pf_epochs = pf_epochs if paper_pf_epochs is None else check_positive_int(paper_pf_epochs, "paper_pf_epochs")
    return _Plan(n_runs, n_epochs, pf_epochs, n_particles, paper_runs, paper_pf_epochs, sweep_runs, tune_runs, seeds)


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


def _task_cost(task, cost):
    kind, args, kwargs = task
    if kind == "reference":
        return 2.0
    t, _, ep, n = args
    per = cost[t] * (n if _uses_particles(t) else 1)
    return per * ep
