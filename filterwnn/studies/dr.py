"""The second paper's dead-reckoning study: EKF, adaptive EKF, UKF/SUKF and the neural filter.

``filterwnn study dr`` runs seeded Monte-Carlo runs of every scenario in
:data:`filterwnn.navigation.scenarios.SCENARIOS` (the paper's straight road with the noise
raised x20 at 150 s, a turning route, a run through heading 180 degrees, heading
outliers, and GPS/DR with 1 Hz fixes, outages, a 2 % odometer-scale error and a
2-degree heading bias), with common random numbers: run ``i`` of every filter sees the
same drive, the same sensor noise and the same initial error, drawn from
``SeedSequence(seed).spawn(n_runs)[i]`` whatever the number of worker processes.
Inside a run every filter draws from its own stream, keyed by its fixed
:attr:`DRFilter.stream`, so adding a filter changes no other filter's numbers.

Each filter is one row of :data:`FILTER_TABLE` (:class:`DRFilter`: name, the scenarios
it applies to, how it is built, its stream key, opt-in and oracle flags), and all of
them run through one predict/update loop, :func:`run_filter`. The runs go through
:func:`filterwnn.studies.runner.run_tasks`: joblib workers (``--jobs``), Dask
(``--backend dask --scheduler ADDRESS``), and a per-run cache (``--cache DIR``) that
makes an interrupted study resume with the same numbers.

Filters (DR-only scenarios)

===============  ===========
``EKF``          filterpy ``ExtendedKalmanFilter``, nominal ``R`` throughout (too small after the switch)
``EKF-oracle``   the same, told the true ``R`` at every step (the reference envelope)
``AEKF``         ``R`` matched to the innovations over 3 s, ``P`` inflated when it rises
                 (:class:`~filterwnn.AdaptiveExtendedKalmanFilter`)
``UKF``          unscented, Merwe points (13), circular heading mean
``SUKF``         unscented, spherical-simplex points (8)
``NN``           :class:`~filterwnn.NeuralFilter`, position pass-through (the default form),
                 trained on the paper's 30 points at the scenario's initial velocity
``NN-faithful``  the paper's absolute form, same training
``NN-gen``       pass-through form trained once on 1500 random motions (knows no route)
``UPF``          unscented particle filter (UKF proposal from ``Q``, textbook weights; opt-in)
===============  ===========

Filters (GPS/DR): ``EKF`` (6 states), ``EKF-8`` (odometer scale and heading bias
estimated; the oracle there), ``UKF-8``, ``SUKF-8``, ``DR-only`` (6-state EKF without GPS).

Real drives (``--real``, needs the ``data`` extra): :func:`load_car_drive` reads
onavdata's two car drives (:data:`~filterwnn.navigation.drives.CAR_DRIVES`: gyro yaw integrated
for the heading, the reference speed with a 2 % scale error and noise as the odometer,
1 Hz GNSS fixes with their reported accuracy, the INS solution as truth) and
:func:`real_drive_outages` cuts 30 s GPS outages into each at 20 placements and scores the
error at the end of each. The filters are set from a sensor grade (``--grade``, default
``survey``), never tuned on these drives; the second drive was not looked at while the
grades were written (held out).

One's own drive (``--drive my.csv``, ``--drive sample`` for the shipped one): read by
:func:`~filterwnn.navigation.drives.read_drive_csv`, the filters set from a sensor grade
(``--grade``, default ``phone``; :meth:`~filterwnn.navigation.dead_reckoning.GPSDRModel.from_grade`),
each fix's reported accuracy as its noise (without one, the grade's), outages at ``--outage-starts`` or spread over
the drive (``--outages``, ``--min-speed``); a table and a figure (the track with the
outages, each filter's error at the outage ends) per drive.

The GPS/DR filters are :class:`~filterwnn.navigation.gpsdr.GPSDRFilter` s: they decide standstill
(zero-velocity update) and low speed (velocity-vector form) from the odometer themselves,
and without a fix update only velocity and acceleration.

Scores: east/north RMSE before and after the noise switch (pooled over runs and
steps), the median and 95th percentile of the final horizontal error, the velocity
RMSE after the switch, divergence counts (a run diverges when its horizontal error
exceeds 3x the oracle filter's RMS error at the same time, floored at 1 m, at any time),
and the median time per step. The GPS/DR table scores the error with GPS and in the
outages and at the end of each outage.

>>> res = run_study(scenarios=["straight"], n_runs=2, filters=["EKF", "NN"], n_steps=100, seed=1)
>>> sorted(res.table[0].keys())[:3]
['div', 'filter', 'final_median']
>>> len(res.table)
2
"""

from __future__ import annotations

import copy
import csv
import os
import time
from functools import partial
from typing import Callable, NamedTuple

import numpy as np
from filterpy.kalman import ExtendedKalmanFilter, MerweScaledSigmaPoints

from .._validation import check_seed, check_positive_int
from ..kalman.adaptive import AdaptiveExtendedKalmanFilter
from ..navigation.dead_reckoning import SENSOR_GRADES, DRModel, GPSDRModel, dr_residual, dr_z_mean
from ..navigation.gpsdr import GPSDRFilter
from ..navigation.drives import CAR_DRIVE, CAR_DRIVES, load_car_drive, read_drive_csv
from ..navigation.scenarios import SCENARIOS, outage_starts, simulate_scenario, with_outage
from ..navigation.neural_filter import (
    NeuralFilter,
    make_training_set,
    paper_training_states,
    random_motion_states,
)
from ..kalman.sigma_points import SphericalSimplexSigmaPoints
from ..kalman.unscented import UnscentedKalmanFilter
from . import options
from . import runner

__all__ = [
    "DRFilter",
    "FILTER_TABLE",
    "FILTERS",
    "run_filter",
    "DR_FILTERS",
    "GPSDR_FILTERS",
    "StudyResult",
    "run_study",
    "scenario_figure",
    "run_one",
    "summarize",
    "write_outputs",
    "add_arguments",
    "run",
    "load_car_drive",
    "with_outage",
    "real_drive_outages",
    "real_drive_table",
    "write_real_drive",
    "REAL_FILTERS",
    "REAL_MODEL",
]

UPF_PARTICLES = 50
DEFAULT_SCENARIOS = ("straight", "turns", "heading180", "outliers", "gpsdr")
DIV_FACTOR = 3.0
DIV_FLOOR = 1.0


# ----------------------------------------------------------------------------- filters


class _Steps(NamedTuple):
    """A filter ready to run over one drive: ``predict()``, ``update(k)`` with step ``k``'s
    measurements, and ``state()``, the posterior mean (its first 6 entries are scored)."""

    predict: Callable
    update: Callable
    state: Callable


class DRFilter(NamedTuple):
    """One row of :data:`FILTERS`: a filter of the study and how it is built.

    Attributes
    ----------
    name : str
        The name in the tables and in ``--filters``.
    scenario : str
        ``"dr"`` (the DR-only scenarios) or ``"gpsdr"`` (the scenarios with GPS fixes).
    build : callable
        ``build(run, x0, rng, context) -> _Steps``: the filter set up on ``run`` from the
        initial estimate ``x0 (6,)``, its own random stream ``rng`` and the study's shared
        ``context`` (``{"NN-gen": fitted NeuralFilter}``).
    stream : int
        The fixed key of its random stream in every run,
        ``child(run_seed, 2, stream)``: a new filter takes a new key and changes no other
        filter's numbers.
    opt_in : bool
        Run only when named in ``filters`` (the UPF costs about 100x the EKF).
    oracle : bool
        The reference filter whose RMS error sets the divergence envelope.
    """

    name: str
    scenario: str
    build: Callable
    stream: int
    opt_in: bool = False
    oracle: bool = False


def _ekf_steps(run, x0, rng, context, adaptive=False, true_R=False):
    """filterpy's EKF (or the adaptive one) with the nominal ``R``, or told the true ``R``."""
    model = DRModel(dt=run.scenario.dt)
    kf = AdaptiveExtendedKalmanFilter(6, 2) if adaptive else ExtendedKalmanFilter(6, 2)
    kf.F, kf.Q, kf.R = model.F.copy(), model.Q.copy(), model.R.copy()
    kf.x, kf.P = x0.copy(), model.P0.copy()

    def update(k):
        R = np.diag(run.R_true[k]) if true_R else None
        kf.update(run.z_dr[k], model.HJacobian, model.hx, R=R, residual=dr_residual)

    return _Steps(kf.predict, update, lambda: kf.x)


def _ukf(model, points, x0, P0, gps):
    f = UnscentedKalmanFilter(model.dim_x, 4 if gps else 2, model.dt, hx=model.hx, fx=model.fx, points=points,
                              z_mean_fn=dr_z_mean, residual_z=dr_residual,
                              vectorized=not gps)  # dim_z varies with GPS
    f.x, f.P, f.Q = x0.copy(), P0.copy(), model.Q.copy()
    f.R = model.R.copy()
    return f


def _points(kind, n):
    if kind == "merwe":
        return MerweScaledSigmaPoints(n, alpha=0.5, beta=2.0, kappa=0.0)
    return SphericalSimplexSigmaPoints(n, w0=0.2)


def _ukf_steps(run, x0, rng, context, points="merwe"):
    """The unscented filter with Merwe (13) or spherical-simplex (8) points, circular heading mean."""
    model = DRModel(dt=run.scenario.dt)
    f = _ukf(model, _points(points, 6), x0, model.P0, False)
    return _Steps(f.predict, lambda k: f.update(run.z_dr[k]), lambda: f.x)


def _nn_steps(run, x0, rng, context, form="passthrough", features="velocity"):
    """:class:`~filterwnn.NeuralFilter` trained on the paper's 30 points at the scenario's velocity.

    ``rng`` draws the training set's noise, then the network's initial weights.
    """
    model, sc = DRModel(dt=run.scenario.dt), run.scenario
    states = paper_training_states(30, speed=sc.speed, heading_deg=sc.heading)
    Xp, Z, X = make_training_set(states, model, rng=rng)
    nf = NeuralFilter(model, form=form, features=features, rng=rng).fit(Xp, Z, X)
    return _nn_run_steps(nf, run, x0)


def _nn_gen_steps(run, x0, rng, context):
    """The network :func:`train_general_nn` trained once per study (``context["NN-gen"]``)."""
    return _nn_run_steps(context["NN-gen"], run, x0)


def _nn_run_steps(nf, run, x0):
    nf.reset(x0)
    return _Steps(nf.predict, lambda k: nf.update(run.z_dr[k]), lambda: nf.x)


def train_general_nn(seed=0, n_states=1500, n_epochs=60, dt=0.1):
    """``NN-gen``: the pass-through network trained on random motions (no route knowledge)."""
    model = DRModel(dt=dt)
    rng = np.random.default_rng(np.random.SeedSequence([seed, 6060]))
    Xp, Z, X = make_training_set(random_motion_states(n_states, rng), model, rng=rng)
    return NeuralFilter(model, form="passthrough", features="velocity", n_epochs=n_epochs,
                        batch_size=10, rng=rng).fit(Xp, Z, X)


def _upf_steps(run, x0, rng, context, n_particles=UPF_PARTICLES):
    """The unscented particle filter on a DR-only run (fixed ``dim_z = 2``).

    A particle filter with a UKF proposal and the textbook weight
    ``p(z|x) p(x|x') / q(x)``, each particle's UKF step started from ``Q``
    (``carry_covariance=False``). With van der Merwe et al.'s carried per-particle
    covariances the weights collapse on this model (ESS 1, 15 m at 200 s on run 0 of the
    straight road, where this form keeps a median ESS of 34 of 50 and ends 11.8 m off).
    """
    from ..monte_carlo.particle_filter import UnscentedParticleFilter

    model = DRModel(dt=run.scenario.dt)
    pf = UnscentedParticleFilter(6, 2, model.dt, model.hx, model.fx, n_particles, points=_points("merwe", 6),
                                 residual_z=dr_residual, z_mean_fn=dr_z_mean, vectorized=True, rng=rng,
                                 carry_covariance=False)
    pf.Q, pf.R = model.Q.copy(), model.R.copy()
    pf.x, pf.P = np.asarray(x0, dtype=float).copy(), np.asarray(model.P0, dtype=float).copy()
    return _Steps(pf.predict, lambda k: pf.update(run.z_dr[k]), lambda: pf.x)


_KIND = {"EKF": "ekf", "EKF-8": "ekf", "DR-only": "ekf", "UKF-8": "ukf", "SUKF-8": "sukf"}


def _gpsdr_steps(run, x0, rng, context, kind="ekf", augmented=False, gps=True):
    """A :class:`~filterwnn.navigation.gpsdr.GPSDRFilter` (6 states, or 8 with odometer scale and heading
    bias), with the run's fixes and their accuracies, or without GPS (``gps=False``)."""
    sc = run.scenario
    model = GPSDRModel(dt=sc.dt, augmented=augmented, sigma_gps=sc.sigma_gps)
    f = GPSDRFilter(model, kind, x0=np.concatenate([x0, [1.0, 0.0]]) if augmented else x0)
    n = len(run.t)
    fixes = run.gps_list() if gps else [None] * n
    sigmas = run.gps_sigma_list() if gps else [None] * n
    return _Steps(f.predict, lambda k: f.update(run.z_dr[k], fixes[k], sigmas[k]), lambda: f.kf.x)


#: Every filter of the study, one row each (:class:`DRFilter`). The stream keys are
#: fixed: they are the positions the filters had in the study's first list, so the
#: numbers stayed when the list became this table; a new filter takes the next free key.
FILTER_TABLE = (
    DRFilter("EKF", "dr", _ekf_steps, 0),
    DRFilter("EKF-oracle", "dr", partial(_ekf_steps, true_R=True), 1, oracle=True),
    DRFilter("AEKF", "dr", partial(_ekf_steps, adaptive=True), 2),
    DRFilter("UKF", "dr", partial(_ukf_steps, points="merwe"), 3),
    DRFilter("SUKF", "dr", partial(_ukf_steps, points="simplex"), 4),
    DRFilter("NN", "dr", _nn_steps, 5),
    DRFilter("NN-faithful", "dr", partial(_nn_steps, form="absolute", features="angle"), 6),
    DRFilter("NN-gen", "dr", _nn_gen_steps, 7),
    DRFilter("UPF", "dr", _upf_steps, 8, opt_in=True),
    DRFilter("EKF", "gpsdr", partial(_gpsdr_steps, kind="ekf"), 0),
    DRFilter("EKF-8", "gpsdr", partial(_gpsdr_steps, kind="ekf", augmented=True), 10, oracle=True),
    DRFilter("UKF-8", "gpsdr", partial(_gpsdr_steps, kind="ukf", augmented=True), 11),
    DRFilter("SUKF-8", "gpsdr", partial(_gpsdr_steps, kind="sukf", augmented=True), 12),
    DRFilter("DR-only", "gpsdr", partial(_gpsdr_steps, kind="ekf", gps=False), 13),
)
#: ``{(scenario kind, name): DRFilter}``, the lookup of :data:`FILTER_TABLE`.
FILTERS = {(f.scenario, f.name): f for f in FILTER_TABLE}
DR_FILTERS = tuple(f.name for f in FILTER_TABLE if f.scenario == "dr")
GPSDR_FILTERS = tuple(f.name for f in FILTER_TABLE if f.scenario == "gpsdr")
#: Filters run only when asked for (``--filters``): the UPF costs about 100x the EKF.
OPT_IN = tuple(dict.fromkeys(f.name for f in FILTER_TABLE if f.opt_in))
ORACLE = {f.scenario: f.name for f in FILTER_TABLE if f.oracle}


def _scenario_kind(scenario):
    return "gpsdr" if scenario.gps_rate > 0 else "dr"


def run_filter(entry, run, x0, rng, context=None):
    """Run one filter of :data:`FILTER_TABLE` over a drive: the one predict/update/store loop.

    Parameters
    ----------
    entry : DRFilter
    run : DRRun
    x0 : ndarray of shape (6,)
        The initial estimate.
    rng : numpy.random.Generator
        The filter's own stream.
    context : dict, optional
        ``{"NN-gen": fitted NeuralFilter}`` for ``NN-gen``.

    Returns
    -------
    ndarray of shape (n_steps, 6)
        The posterior mean after each step.
    """
    steps = entry.build(run, x0, rng, context or {})
    out = np.empty((len(run.t), 6))
    for k in range(len(run.t)):
        steps.predict()
        steps.update(k)
        out[k] = steps.state()[:6]
    return out


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
    kind = _scenario_kind(scenario)
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


# ----------------------------------------------------------------------------- scoring


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
    kind = _scenario_kind(scenario)
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
        kind = _scenario_kind(sc)
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


# ----------------------------------------------------------------------------- output

_DR_COLS = [
    ("filter", "filter"), ("rmse_e_before", "RMSE e <150"), ("rmse_n_before", "RMSE n <150"),
    ("rmse_e_after", "RMSE e >=150"), ("rmse_n_after", "RMSE n >=150"),
    ("final_median", "median err@end"), ("final_p95", "p95 err@end"),
    ("vel_rmse_after", "vel RMSE >=150 [m/s]"), ("div", "div"), ("us_per_step", "us/step"),
]
_GPS_COLS = [
    ("filter", "filter"), ("rmse_gps", "horiz RMSE GPS on"), ("rmse_outage", "horiz RMSE in outages"),
    ("outage_end_median", "median err at outage ends"), ("final_median", "median err@end"),
    ("div", "div"), ("us_per_step", "us/step"),
]


def markdown_table(result):
    """The study's tables as Markdown (one per scenario)."""
    lines = []
    for name, sc in result.scenarios.items():
        rows = [r for r in result.table if r["scenario"] == name]
        cols = _GPS_COLS if sc.gps_rate > 0 else _DR_COLS
        head = f"### {name}: "
        if sc.gps_rate > 0:
            head += (f"GPS {sc.gps_rate:g} Hz ({sc.sigma_gps:g} m), outages {list(sc.outages)}, "
                     f"odometer scale {sc.odometer_scale:g}, heading bias {sc.heading_bias:g} deg")
        else:
            head += f"noise x{sc.factor:g} at {sc.t_switch:g} s" + (
                f", {sc.outlier_prob:.0%} heading outliers of {sc.outlier_deg:g} deg" if sc.outlier_prob else "")
        n = rows[0]["runs"] if rows else 0
        oracle = ORACLE[_scenario_kind(sc)]
        lines += [head + f" ({n} runs, positions in m; div: error > {DIV_FACTOR:g}x {oracle} RMS envelope)", ""]
        lines.append("| " + " | ".join(c[1] for c in cols) + " |")
        lines.append("|" + "---|" * len(cols))
        for r in rows:
            lines.append("| " + " | ".join(runner.fmt(r.get(c[0], ""), 2, fixed=True, missing="nan") for c in cols) + " |")
        lines.append("")
    return "\n".join(lines)


def write_outputs(result, out_dir, figures=True, real_drives=()):
    """Write the tables and figures to ``out_dir``; returns the paths.

    ``result`` (a :class:`StudyResult`, or ``None`` for real drives only) gives
    ``dr_table.md``, ``dr_table.csv`` and a figure per scenario, named in words by
    :func:`scenario_figure` (``dr_straight_road.png``, ``gps_dr_with_outages.png``); each of ``real_drives``
    (results of :func:`real_drive_outages`) gives ``real_drive_<name>_outage_errors.md``
    and ``real_drive_<name>_track_and_outage_end_errors.png`` (:func:`write_real_drive`).
    """
    os.makedirs(out_dir, exist_ok=True)
    paths = []
    for res in real_drives:
        paths += write_real_drive(res, out_dir, figures)
    if result is None:
        return paths
    md = os.path.join(out_dir, "dr_table.md")
    with open(md, "w") as fh:
        s = result.settings
        fh.write(f"# Dead-reckoning study (seed {s['seed']}, {s['n_runs']} runs per scenario)\n\n")
        fh.write(markdown_table(result))
    paths.append(md)
    keys = []
    for r in result.table:
        keys += [k for k in r if k not in keys]
    csv_path = os.path.join(out_dir, "dr_table.csv")
    with open(csv_path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        for r in result.table:
            w.writerow(r)
    paths.append(csv_path)
    if figures:
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        from . import plotting

        for name, sc in result.scenarios.items():
            e = result.errors[name]
            title, fname = scenario_figure(name, sc)
            if sc.gps_rate > 0:
                fig = plotting.dr_outage_errors(e["t"], e["filters"], outages=sc.outages, title=title)
            else:
                fig = plotting.dr_position_errors(e["t"], e["filters"], t_switch=sc.t_switch, title=title)
            p = os.path.join(out_dir, fname)
            fig.savefig(p, dpi=110, bbox_inches="tight")
            paths.append(p)
            plt.close(fig)
    return paths


_COUNT_WORDS = ("no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine")


def scenario_figure(name, sc):
    """``(title, file name)`` of a scenario's figure, in words, from its settings.

    >>> from filterwnn.navigation.scenarios import SCENARIOS
    >>> scenario_figure("straight", SCENARIOS["straight"]())
    ('straight road, sensor noise x20 from 150 s', 'dr_straight_road.png')
    >>> scenario_figure("gpsdr", SCENARIOS["gpsdr"]())[1]
    'gps_dr_with_outages.png'
    """
    words, stem = sc.title or str(name), sc.figure or "dr_" + _slug(name)
    if sc.gps_rate > 0:
        k = len(sc.outages)
        if k:
            words += f" with {_COUNT_WORDS[k] if k < len(_COUNT_WORDS) else k} GPS outage{'s' if k > 1 else ''}"
            stem += "_with_outages"
        extra = []
        if sc.odometer_scale != 1:
            extra.append(f"odometer scale {sc.odometer_scale:g}")
        if sc.heading_bias:
            extra.append(f"heading bias {sc.heading_bias:g} deg")
        if extra:
            words += " (" + ", ".join(extra) + ")"
    else:
        if sc.outlier_prob:
            words += (f" ({sc.outlier_prob:.0%} of {sc.outlier_deg:g} deg)" if name == "outliers"
                      else f", {sc.outlier_prob:.0%} heading outliers of {sc.outlier_deg:g} deg")
        if sc.factor != 1:
            words += f", sensor noise x{sc.factor:g} from {sc.t_switch:g} s"
    return words, stem + ".png"


# ----------------------------------------------------------------------------- real drive

#: GPS/DR model settings for the real drive (a car's manoeuvres need a larger jerk PSD,
#: the receiver's fixes are about 1 m, and the gyro's heading drifts: a random-walk bias).
REAL_MODEL = dict(q=2.0, sigma_heading=np.deg2rad(1.0), sigma_odometer=0.02, sigma_gps=1.0,
                  q_scale=1e-6, q_bias=1e-6)


#: The filters run on a real drive (raw dead reckoning, the 6-state EKF and the 8-state filters).
REAL_FILTERS = ("DR-mech", "EKF", "EKF-8", "UKF-8", "SUKF-8")


def real_drive_outages(run, n_placements=20, length=30.0, filters=("DR-mech", "EKF", "EKF-8"),
                       model_kwargs=None, slow_speed=None, starts=None, min_speed=0.0,
                       use_gps_sigma=False, grade=None, gps_window=0):
    """Cut GPS outages of ``length`` s into a drive and score each filter at each outage end.

    Placements: ``starts`` as given, or ``n_placements`` spread evenly over the windows
    whose mean odometer speed is at least ``min_speed`` (:func:`~filterwnn.navigation.scenarios.outage_starts`;
    with the default 0 the first one starts before the car moves). ``EKF``/``EKF-8``/
    ``UKF-8``/``SUKF-8`` are :class:`~filterwnn.navigation.gpsdr.GPSDRFilter` s (6 or 8 states; the filter
    decides standstill and low speed itself); ``DR-mech`` integrates
    ``s [sin theta, cos theta]`` from the reference position at the outage start (dead
    reckoning without a filter).

    The reference is the truth when the drive has one (``run.x_true``); otherwise the
    GPS fix withheld last in the outage, so the score then includes that fix's own error.

    Parameters
    ----------
    run : DRRun
    n_placements, length, starts, min_speed
        Where the outages go (see above).
    filters : sequence of str
        Subset of :data:`REAL_FILTERS`.
    model_kwargs : dict, optional
        :class:`~filterwnn.navigation.dead_reckoning.GPSDRModel` settings over :data:`REAL_MODEL`, or
        over the grade's settings.
    grade : str or dict, optional
        Settings from a sensor grade or specification
        (:meth:`~filterwnn.navigation.dead_reckoning.GPSDRModel.from_grade`; ``"phone"`` adds the gyro
        rate-bias state to the 8-state filters) instead of :data:`REAL_MODEL`, which was
        tuned on the onavdata drive.
    slow_speed : float, optional
        The filters' low-speed threshold (m/s; default :data:`filterwnn.navigation.gpsdr.LOW_SPEED`).
    use_gps_sigma : bool
        Use each fix's reported accuracy (``run.gps_sigma``) as its noise.
    gps_window : int
        Estimate the noise of fixes without an accuracy from the GPS innovations over
        this many fixes (:class:`~filterwnn.navigation.gpsdr.GPSDRFilter`; 0: the model's ``sigma_gps``).

    Returns
    -------
    dict
        ``starts (n,)``, ``length``, ``moved (n,)`` (distance driven during each outage, m),
        ``end_steps (n,)`` (the scored step of each outage), ``reference`` ("truth" or
        "withheld GPS"), ``name``, ``track (n_steps, 2)`` (truth, else the fixes
        interpolated), ``end_xy {filter: (n, 2)}``, and per filter ``(n,)`` end-of-outage
        horizontal errors (m); NaN never appears (a non-finite estimate raises).
    """
    bad = [f for f in filters if f not in REAL_FILTERS]
    if bad:
        raise ValueError(f"unknown real-drive filters {bad}; valid: {', '.join(REAL_FILTERS)}")
    kw = dict(REAL_MODEL, **(model_kwargs or {}))
    t_end = float(run.t[-1])
    if starts is None and min_speed == 0.0:
        starts = np.linspace(0.0, t_end - length - 1.0, n_placements)
    starts = outage_starts(run, length, starts=starts, n=n_placements, min_speed=min_speed)
    k0s, k1s, refs, moved, track = _outage_windows(run, starts, length)
    truth = run.x_true is not None
    out = {"starts": starts, "length": length, "moved": moved, "end_steps": np.array(k1s),
           "reference": "truth" if truth else "withheld GPS", "name": run.scenario.name,
           "track": track, "t": run.t, "end_xy": {}}
    gps = run.gps_list()
    sig = run.gps_sigma_list() if use_gps_sigma else [None] * len(run.t)
    for name in filters:
        if name == "DR-mech":
            ends = _dr_mech_ends(run, k0s, k1s, track if not truth else None)
        else:
            f = _real_drive_filter(name, run, grade, model_kwargs, kw, gps_window, slow_speed)
            ends = _outage_ends(f, name, run, k0s, k1s, starts, gps, sig)
        out["end_xy"][name] = ends
        out[name] = np.hypot(*(ends - refs).T)
    return out


def _outage_windows(run, starts, length):
    """The first and scored step of each outage, its reference east/north (the truth, else the
    last fix withheld), the distance driven in it, and the track ``(n_steps, 2)``."""
    truth = run.x_true is not None
    cum = np.concatenate([[0.0], np.cumsum(run.z_dr[:, 1])])
    k0s, k1s, refs, moved = [], [], [], []
    gps_t = run.t[run.gps_steps]
    for a in starts:
        k0 = int(np.searchsorted(run.t, a))
        k1 = int(np.searchsorted(run.t, a + length)) - 1
        if truth:
            ref = run.x_true[k1, [0, 3]]
        else:
            inside = np.flatnonzero((gps_t >= a) & (gps_t < a + length))
            if len(inside) == 0:
                raise ValueError(f"the drive has no truth and no GPS fix in the outage at {a:.1f} s to score against")
            k1 = int(run.gps_steps[inside[-1]])
            ref = run.z_gps[inside[-1]]
        k0s.append(k0)
        k1s.append(k1)
        refs.append(ref)
        moved.append(float(cum[k1 + 1] - cum[k0]) if not truth else float(np.sum(np.hypot(
            *np.diff(run.x_true[k0:k1 + 1][:, [0, 3]], axis=0).T))))
    if truth:
        track = run.x_true[:, [0, 3]]
    else:
        track = np.stack([np.interp(run.t, gps_t, run.z_gps[:, i]) for i in (0, 1)], axis=1)
    return k0s, k1s, np.array(refs), np.array(moved), track


def _real_drive_filter(name, run, grade, model_kwargs, kw, gps_window, slow_speed):
    """The :class:`~filterwnn.navigation.gpsdr.GPSDRFilter` ``name`` for a real drive, set from ``grade``
    (or the settings ``kw``), started at the drive's first state with 1 m position sigma."""
    aug = name.endswith("-8")
    dt = run.scenario.dt
    if grade is not None:
        model = GPSDRModel.from_grade(grade, dt, augmented=aug, **({} if aug else {"rate_bias": False}),
                                      **(model_kwargs or {}))
    else:
        model = GPSDRModel(dt=dt, augmented=aug, **kw)
    x0 = np.concatenate([run.x0, model.x0[6:]])
    P0 = model.P0.copy()
    P0[0, 0] = P0[3, 3] = 1.0
    low = {} if slow_speed is None else {"low_speed": slow_speed}
    return GPSDRFilter(model, _KIND[name], x0=x0, P0=P0, gps_window=gps_window, **low)


_REAL_META = ("starts", "moved", "length", "end_steps", "reference", "name", "track", "t", "end_xy")


def _dr_mech_ends(run, k0s, k1s, track=None):
    """Mechanised dead reckoning over each outage ``k0..k1``: ``s [sin theta, cos theta]``
    summed from the reference position before it (the truth, else ``track``)."""
    ends = np.empty((len(k0s), 2))
    for j, (k0, k1) in enumerate(zip(k0s, k1s)):
        if track is None:
            p = run.x_true[k0 - 1, [0, 3]] if k0 > 0 else run.x0[[0, 3]]
        else:
            p = track[k0 - 1] if k0 > 0 else run.x0[[0, 3]]
        z = run.z_dr[k0:k1 + 1]
        ends[j] = p + np.sum(z[:, 1:2] * np.stack([np.sin(z[:, 0]), np.cos(z[:, 0])], axis=1), axis=0)
    return ends


def _outage_ends(f, name, run, k0s, k1s, starts, gps, sig):
    """The east/north of filter ``f`` at the end of each outage: one pass with GPS, a
    snapshot at each outage start, then each outage alone (DR only)."""
    ends = np.empty((len(k0s), 2))
    snaps = {}
    for k in range(max(k0s) + 1):
        if k in k0s:
            snaps[k] = copy.deepcopy(f)
        f.predict()
        f.update(run.z_dr[k], gps[k], sig[k])
    for j, (k0, k1) in enumerate(zip(k0s, k1s)):
        g = copy.deepcopy(snaps[k0])
        for k in range(k0, k1 + 1):
            g.predict()
            g.update(run.z_dr[k], None)
        if not np.all(np.isfinite(g.x)):
            raise FloatingPointError(f"{name}: non-finite state at step {k1} (outage at {starts[j]:.1f} s)")
        ends[j] = g.x[[0, 3]]
    return ends


def real_drive_table(res, min_moved=100.0):
    """Markdown: median/p90/max end-of-outage error over all placements and moving ones."""
    mv = res["moved"] >= min_moved
    names = [k for k in res if k not in _REAL_META]
    lines = [f"### real drive {res.get('name', CAR_DRIVE)}: {len(res['starts'])} GPS outages of {res['length']:g} s "
             f"({int(mv.sum())} with >= {min_moved:g} m driven), error at the outage ends against the "
             f"{res.get('reference', 'truth')} (m)", "",
             "| filter | median all | p90 all | max all | median moving | max moving |", "|---|---|---|---|---|---|"]
    for n in names:
        e = res[n]
        em = e[mv] if mv.any() else np.array([np.nan])
        lines.append(f"| {n} | {np.median(e):.2f} | {np.percentile(e, 90):.2f} | {e.max():.2f} | "
                     f"{np.median(em):.2f} | {em.max():.2f} |")
    return "\n".join(lines) + "\n"


def _slug(text):
    return "".join(c if c.isalnum() else "_" for c in str(text)).strip("_").lower()


def write_real_drive(res, out_dir, figures=True):
    """Write one real drive's table (``real_drive_<name>.md``) and figure; returns the paths."""
    os.makedirs(out_dir, exist_ok=True)
    slug = _slug(res["name"])
    p = os.path.join(out_dir, f"real_drive_{slug}_outage_errors.md")
    with open(p, "w") as fh:
        fh.write(real_drive_table(res))
    paths = [p]
    if figures:
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        from . import plotting

        fig = plotting.dr_real_drive(res)
        p = os.path.join(out_dir, f"real_drive_{slug}_track_and_outage_end_errors.png")
        fig.savefig(p, dpi=110, bbox_inches="tight")
        plt.close(fig)
        paths.append(p)
    return paths


def add_arguments(parser):
    """Options of ``filterwnn study dr``."""
    parser.add_argument("--runs", type=options.positive_int, default=10, help="Monte-Carlo runs per scenario")
    parser.add_argument("--seed", type=options.seed, default=0,
                        help="root seed, an integer >= 0 (run i uses SeedSequence(seed).spawn(runs)[i])")
    parser.add_argument("--jobs", type=options.joblib_jobs, default=2,
                        help="joblib workers, -1 for all cores (the numbers do not depend on it)")
    parser.add_argument("--backend", type=options.joblib_backend, default=None,
                        help="joblib backend (loky, threading, dask, ...); default joblib's (loky)")
    parser.add_argument("--scheduler", default=None,
                        help="with --backend dask: the address of a dask.distributed scheduler "
                             "(default: a local cluster of --jobs workers)")
    parser.add_argument("--cache", default=None, metavar="DIR",
                        help="checkpoint folder (default none): each finished (scenario, run) is stored "
                             "there as <hash of its settings>.npz (no pickle: nothing in it can run code) and "
                             "read back instead of run, timings included, so an interrupted study resumes "
                             "with the same numbers; an entry written by other code (any change to the "
                             "package's source), another task, or damaged is named on stderr and recomputed")
    parser.add_argument("--scenarios", type=options.name_list(SCENARIOS), default=",".join(DEFAULT_SCENARIOS),
                        help=f"comma-separated subset of {', '.join(SCENARIOS)}")
    names = tuple(dict.fromkeys([f.name for f in FILTER_TABLE] + list(REAL_FILTERS)))
    simulated = tuple(dict.fromkeys(f.name for f in FILTER_TABLE))
    parser.add_argument("--filters", type=options.name_list(names), default=None,
                        help=f"comma-separated filters: on the simulated scenarios a subset of {', '.join(simulated)} "
                             f"(default all that apply to each scenario, but {', '.join(OPT_IN)}); with --drive a "
                             f"subset of {', '.join(REAL_FILTERS)} (default all)")
    parser.add_argument("--factor", type=options.positive_float, default=None,
                        help="override the DR noise factor at 150 s of the DR-only scenarios (default each "
                             "scenario's own)")
    parser.add_argument("--out", default="results/dr", help="output folder")
    parser.add_argument("--no-figures", action="store_true", help="write the tables only (no PNG figures)")
    options.add_progress_flag(parser, "--quiet")
    parser.add_argument("--real", action="store_true",
                        help=f"also run the GPS/DR filters on onavdata's car drives {', '.join(CAR_DRIVES)} "
                             "(needs the data extra), set from --grade (default survey)")
    parser.add_argument("--drive", action="append", default=None, metavar="CSV",
                        help="run the GPS/DR filters on one's own drive, a CSV with the columns of "
                             "filterwnn.navigation.drives.DRIVE_CSV_COLUMNS ('sample' for the shipped sample drive); "
                             "repeatable; with --drive only the drives run, not the simulated scenarios")
    parser.add_argument("--no-plausibility", action="store_true",
                        help="with --drive: skip the checks of the drive against its own GPS fixes (sample "
                             "interval over 2 s, a heading or speed that contradicts the fixes' course or "
                             "distance, lat/lon swapped), for a drive that really is so")
    parser.add_argument("--outage-length", type=options.positive_float, default=30.0, help="GPS outage length on drives (s)")
    parser.add_argument("--outages", type=options.positive_int, default=20, help="number of outages spread over each drive")
    parser.add_argument("--outage-starts", type=options.float_list, default=None,
                        help="comma-separated outage start times (s) on --drive drives, instead of spreading them")
    parser.add_argument("--min-speed", type=options.nonnegative_float, default=0.0,
                        help="spread outages only over windows with at least this mean speed (m/s)")
    parser.add_argument("--grade", choices=sorted(SENSOR_GRADES), default=None,
                        help="sensor grade for the GPS/DR settings (survey, phone; see "
                             "filterwnn.navigation.dead_reckoning.SENSOR_GRADES); default phone for --drive, survey for --real")


def run(args):
    """Entry point of ``filterwnn study dr``."""
    drives = getattr(args, "drive", None)
    if drives:
        return _run_drives(args, drives, args.filters)
    with runner.dask_client(getattr(args, "backend", None), getattr(args, "scheduler", None), args.jobs):
        res = run_study(scenarios=args.scenarios, n_runs=args.runs, filters=args.filters, seed=args.seed,
                        jobs=args.jobs, factor=args.factor, progress=not args.no_progress,
                        backend=getattr(args, "backend", None), cache_dir=getattr(args, "cache", None))
    paths = write_outputs(res, args.out, figures=not args.no_figures)
    print(markdown_table(res))
    if getattr(args, "real", False):
        grade = args.grade or "survey"
        results, texts = [], []
        for name in CAR_DRIVES:
            try:
                drive = load_car_drive(name)
            except ImportError as exc:
                print(f"skipping the real drives: {exc}")
                break
            rd = real_drive_outages(drive, grade=grade, use_gps_sigma=True)
            results.append(rd)
            texts.append(real_drive_table(rd))
            print(texts[-1])
        if results:
            p = os.path.join(args.out, "dr_real_drive.md")
            with open(p, "w") as fh:
                fh.write(f"Settings: sensor grade {grade!r} (filterwnn.navigation.dead_reckoning.SENSOR_GRADES), each fix's "
                         f"reported accuracy as its noise; nothing tuned on these drives.\n\n" + "\n".join(texts))
            paths.append(p)
            paths += write_outputs(None, args.out, figures=not args.no_figures, real_drives=results)
    print("wrote:", ", ".join(paths))
    return 0


def _run_drives(args, drives, filters):
    """``--drive``: the GPS/DR filters on one's own drives, with each fix's accuracy when given."""
    from ..navigation.drives import sample_drive_path

    starts = args.outage_starts or None
    fl = tuple(filters) if filters else REAL_FILTERS
    results = []
    for path in drives:
        run = read_drive_csv(sample_drive_path() if path == "sample" else path,
                             checks=not getattr(args, "no_plausibility", False),
                             progress=None if not getattr(args, "no_progress", False) else False)
        try:
            res = real_drive_outages(run, n_placements=args.outages, length=args.outage_length, filters=fl,
                                     starts=starts, min_speed=args.min_speed,
                                     use_gps_sigma=run.gps_sigma is not None,
                                     grade=getattr(args, "grade", None) or "phone")
        except ValueError as exc:  # name the drive (and the options behind the outages)
            raise ValueError(f"{path}: {exc} (outages from --outage-length, --outages, --outage-starts, "
                             "--min-speed)") from None
        results.append(res)
        print(real_drive_table(res))
    paths = write_outputs(None, args.out, figures=not args.no_figures, real_drives=results)
    print("wrote:", ", ".join(paths))
    return 0

