"""The DR study's Monte-Carlo runs and their scores: :func:`run_study`, :func:`run_one`, :func:`summarize`.

Run ``i`` of every scenario draws from ``SeedSequence(seed).spawn(n_runs)[i]``: the drive
from its child 0, the initial error from child 1, each filter from ``(2, stream)``, so the
numbers do not depend on the worker count, the backend or the cache.
"""

from __future__ import annotations

import time
from functools import partial
from typing import NamedTuple

import numpy as np

from ..._validation import check_positive_int, check_seed
from ...navigation.scenarios import SCENARIOS, simulate_scenario
from .. import runner
from ._filters import (
    DR_FILTERS,
    FILTER_TABLE,
    FILTERS,
    GPSDR_FILTERS,
    ORACLE,
    scenario_kind,
    run_filter,
    train_general_nn,
)

DEFAULT_SCENARIOS = ("straight", "turns", "heading180", "outliers", "gpsdr")
DIV_FACTOR = 3.0
DIV_FLOOR = 1.0


def run_one(scenario, filters, seed_seq, nn_cache=None):
    """One Monte-Carlo run of one scenario: every filter on the same simulated drive.

    Parameters
    ----------
    scenario : Scenario
    filters : sequence of str
        Names of :data:`FILTER_TABLE` rows of the scenario's kind.
    seed_seq : numpy.random.SeedSequence
        This run's seed: the drive uses its child ``0``, the initial error ``1``, each
        filter ``(2, stream)`` (:attr:`DRFilter.stream`).
    nn_cache : dict, optional
        ``{"NN-gen": fitted NeuralFilter}``.

    Returns
    -------
    dict
        ``"x_true" (n_steps, 6)``, ``"t" (n_steps,)``, ``"est" {filter: (n_steps, 6)}``,
        ``"seconds" {filter: float}``.
    """
    kind = scenario_kind(scenario)
    entries = []
    for name in filters:
        if (kind, name) not in FILTERS:
            valid = DR_FILTERS if kind == "dr" else GPSDR_FILTERS
            raise ValueError(f"unknown filter {name!r}; valid: {', '.join(valid)}")
        entries.append(FILTERS[(kind, name)])
    run = simulate_scenario(scenario, rng=np.random.default_rng(runner.child(seed_seq, 0)))
    x0 = run.x0 + np.array([0.0, 0.5, 0.0, 0.0, 0.5, 0.0]) * np.random.default_rng(
        runner.child(seed_seq, 1)).standard_normal(6)
    est, secs = {}, {}
    for entry in entries:
        rng = np.random.default_rng(runner.child(seed_seq, 2, entry.stream))
        t0 = time.perf_counter()
        est[entry.name] = run_filter(entry, run, x0, rng, nn_cache)
        secs[entry.name] = time.perf_counter() - t0
    return {"x_true": run.x_true, "t": run.t, "est": est, "seconds": secs}


class StudyResult(NamedTuple):
    """What :func:`run_study` returns.

    Attributes
    ----------
    table : list of dict
        One row per (scenario, filter) with the scores (see :func:`summarize`).
    errors : dict
        ``{scenario: {"t": (n_steps,), "filters": {name: (n_runs, n_steps, 2)}}}``:
        east/north position errors (estimate minus truth) of every run.
    scenarios : dict
        ``{name: Scenario}`` as run.
    settings : dict
        ``seed``, ``n_runs``, ``jobs``, ``filters``.
    """

    table: list
    errors: dict
    scenarios: dict
    settings: dict


def summarize(scenario, t, errs, vel_errs, secs, n_steps):
    """Score one scenario: rows of dict, one per filter (see the module docstring)."""
    kind = scenario_kind(scenario)
    oracle = ORACLE[kind] if ORACLE[kind] in errs else None
    horiz = {f: np.hypot(e[..., 0], e[..., 1]) for f, e in errs.items()}
    env = None
    if oracle is not None:
        env = np.maximum(np.sqrt(np.mean(horiz[oracle] ** 2, axis=0)), DIV_FLOOR)
    after = t >= scenario.t_switch
    in_out = np.zeros(len(t), dtype=bool)
    ends = []
    for a, b in scenario.outages:
        in_out |= (t >= a) & (t < b)
        ends.append(int(np.searchsorted(t, b - 1e-9)) - 1)
    rows = []
    for f, e in errs.items():
        h = horiz[f]
        row = {"scenario": scenario.name, "filter": f, "runs": e.shape[0]}
        if kind == "dr":
            row["rmse_e_before"] = float(np.sqrt(np.mean(e[:, ~after, 0] ** 2)))
            row["rmse_n_before"] = float(np.sqrt(np.mean(e[:, ~after, 1] ** 2)))
            row["rmse_e_after"] = float(np.sqrt(np.mean(e[:, after, 0] ** 2))) if after.any() else np.nan
            row["rmse_n_after"] = float(np.sqrt(np.mean(e[:, after, 1] ** 2))) if after.any() else np.nan
            row["vel_rmse_after"] = (
                float(np.sqrt(np.mean(np.sum(vel_errs[f][:, after] ** 2, axis=-1)))) if after.any() else np.nan
            )
        else:
            gps_on = (~in_out) & (t > 5.0)
            row["rmse_gps"] = float(np.sqrt(np.mean(h[:, gps_on] ** 2)))
            row["rmse_outage"] = float(np.sqrt(np.mean(h[:, in_out] ** 2))) if in_out.any() else np.nan
            row["outage_end_median"] = "/".join(f"{np.median(h[:, k]):.2f}" for k in ends)
            row["vel_rmse_after"] = float(np.sqrt(np.mean(np.sum(vel_errs[f] ** 2, axis=-1))))
        row["final_median"] = float(np.median(h[:, -1]))
        row["final_p95"] = float(np.percentile(h[:, -1], 95))
        row["div"] = int(np.sum(np.any(h > DIV_FACTOR * env, axis=1))) if env is not None else -1
        row["us_per_step"] = float(np.median(secs[f]) / n_steps * 1e6)
        rows.append(row)
    return rows


def run_study(scenarios=DEFAULT_SCENARIOS, n_runs=10, filters=None, seed=0, jobs=1,
              n_steps=None, factor=None, progress=False, backend=None, cache_dir=None):
    """Run the Monte-Carlo study and score it.

    Parameters
    ----------
    scenarios : sequence of str
        Keys of :data:`~filterwnn.navigation.scenarios.SCENARIOS`.
    n_runs : int
        Monte-Carlo runs per scenario.
    filters : sequence of str, optional
        Subset of :data:`DR_FILTERS` / :data:`GPSDR_FILTERS` (each scenario runs the ones
        that apply; default all but :data:`OPT_IN`).
    seed : int
        Root seed; run ``i`` uses ``SeedSequence(seed).spawn(n_runs)[i]`` in every scenario.
    jobs : int
        joblib workers (``-1``: all cores); the numbers do not depend on it.
    n_steps : int, optional
        Truncate the drives (tests); the noise switch stays at its time.
    factor : float, optional
        Override the noise factor of the DR-only scenarios.
    progress : bool
        Show a tqdm bar.
    backend : str, optional
        joblib backend ("loky", "threading", "dask" inside
        :func:`filterwnn.studies.runner.dask_client`); default joblib's.
    cache_dir : str, optional
        Checkpoint folder: each finished (scenario, run) is stored there
        (``<hash of the task>.npz``, :func:`filterwnn.studies.runner.run_tasks`) and read
        back instead of run next time, timings included, while the package's source is
        unchanged (other code's entries are recomputed).

    Returns
    -------
    StudyResult
    """
    n_runs = check_positive_int(n_runs, "n_runs")
    if isinstance(jobs, bool) or not isinstance(jobs, (int, np.integer)) or jobs == 0:
        raise ValueError(f"jobs must be >= 1, or negative (-1: all cores), got {jobs!r}")
    seed = check_seed(seed)
    if n_steps is not None:
        n_steps = check_positive_int(n_steps, "n_steps")
    scs, flist = _plan(scenarios, filters, factor, n_steps)
    tasks = [{"study": "dr", "scenario": name, "run": i, "seed": seed, "filters": flist[name],
              "n_steps": n_steps, "factor": None if factor is None else float(factor)}
             for name in scs for i in range(n_runs)]
    context = {}
    cached = runner.load_cached(tasks, cache_dir, runner.NPZ)
    if any("NN-gen" in t["filters"] and r is None for t, r in zip(tasks, cached)):
        context["NN-gen"] = train_general_nn(seed)
    results = runner.run_tasks(tasks, partial(_run_task, context=context), n_jobs=int(jobs), backend=backend,
                               progress=progress, cache_dir=cache_dir, desc="dr study", unit="run",
                               serializer=runner.NPZ)
    table, errors = [], {}
    for name, sc in scs.items():
        res = [r for t, r in zip(tasks, results) if t["scenario"] == name]
        rows, errors[name] = _score(sc, flist[name], res)
        table += rows
    return StudyResult(table, errors, scs, {"seed": seed, "n_runs": n_runs, "jobs": jobs, "filters": flist})


def _scenario(name, factor=None, n_steps=None):
    """Scenario ``name`` with the DR noise factor and the length overridden when given."""
    sc = SCENARIOS[name]()
    if factor is not None and sc.gps_rate == 0:
        sc = sc.with_(factor=float(factor))
    if n_steps is not None:
        sc = sc.with_(duration=n_steps * sc.dt)
    return sc


def _plan(scenarios, filters, factor, n_steps):
    """Check the names; ``({name: Scenario}, {name: [filters it runs]})``."""
    scenarios = list(scenarios)
    if not scenarios:
        raise ValueError(f"scenarios must name at least one of {', '.join(SCENARIOS)}, got []")
    for s in scenarios:
        if s not in SCENARIOS:
            raise ValueError(f"unknown scenario {s!r}; valid: {', '.join(SCENARIOS)}")
    want = set(filters) if filters is not None else None
    if want is not None:
        bad = want - {f.name for f in FILTER_TABLE}
        if bad:
            raise ValueError(f"unknown filters {sorted(bad)}; valid: {sorted({f.name for f in FILTER_TABLE})}")
    scs, flist = {}, {}
    for name in scenarios:
        scs[name] = sc = _scenario(name, factor, n_steps)
        kind = scenario_kind(sc)
        flist[name] = [f.name for f in FILTER_TABLE if f.scenario == kind
                       and (f.name in want if want is not None else not f.opt_in)]
    return scs, flist


def _run_task(task, context):
    """One task of :func:`run_study`: run ``task["run"]`` of its scenario, one BLAS thread."""
    from threadpoolctl import threadpool_limits

    sc = _scenario(task["scenario"], task["factor"], task["n_steps"])
    seed_seq = runner.child(np.random.SeedSequence(task["seed"]), task["run"])  # = spawn(n_runs)[run]
    with threadpool_limits(1):
        return run_one(sc, task["filters"], seed_seq, context)


def _score(sc, names, res):
    """Rows of :func:`summarize` and ``{"t", "filters": {name: (n_runs, n_steps, 2)}}`` of one scenario."""
    t = res[0]["t"]
    errs = {f: np.stack([r["est"][f][:, [0, 3]] - r["x_true"][:, [0, 3]] for r in res]) for f in names}
    verr = {f: np.stack([r["est"][f][:, [1, 4]] - r["x_true"][:, [1, 4]] for r in res]) for f in names}
    secs = {f: np.array([r["seconds"][f] for r in res]) for f in names}
    return summarize(sc, t, errs, verr, secs, len(t)), {"t": t, "filters": errs}
