"""The DR study's filters: one :class:`DRFilter` row each in :data:`FILTER_TABLE`, run by :func:`run_filter`.

A row names a filter, the scenarios it applies to (``"dr"`` or ``"gpsdr"``), how it is
built on a run (a ``build(run, x0, rng, context) -> _Steps`` function) and its fixed
random-stream key; :func:`run_filter` is the one predict/update/store loop they all run
through. A new filter is one new row here.
"""

from __future__ import annotations

from functools import partial
from typing import Callable, NamedTuple

import numpy as np
from filterpy.kalman import ExtendedKalmanFilter

from ...kalman.adaptive import AdaptiveExtendedKalmanFilter
from ...kalman.presets import make_points
from ...models import from_model
from ...kalman.unscented import UnscentedKalmanFilter
from ...navigation.dead_reckoning import DRModel, GPSDRModel, dr_residual
from ...navigation.gpsdr import GPSDRFilter
from ...navigation.neural_filter import (
    NeuralFilter,
    make_training_set,
    paper_training_states,
    random_motion_states,
)

UPF_PARTICLES = 50


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
    kf = from_model(AdaptiveExtendedKalmanFilter if adaptive else ExtendedKalmanFilter, model, x0=x0)

    def update(k):
        R = np.diag(run.R_true[k]) if true_R else None
        kf.update(run.z_dr[k], model.HJacobian, model.hx, R=R, residual=dr_residual)

    return _Steps(kf.predict, update, lambda: kf.x)


def _ukf(model, points, x0, P0, gps):
    # hx per point with GPS (its dim_z varies with the fix), vectorized without
    return from_model(UnscentedKalmanFilter, model, points=points, x0=x0, P0=P0, vectorized=not gps)


def _points(kind, n):
    return make_points("gpsdr-ukf" if kind == "merwe" else "gpsdr-sukf", n)


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
    from ...monte_carlo.particle_filter import UnscentedParticleFilter

    model = DRModel(dt=run.scenario.dt)
    pf = from_model(UnscentedParticleFilter, model, x0=x0, n_particles=n_particles, points=_points("merwe", 6),
                    vectorized=True, rng=rng, carry_covariance=False)
    return _Steps(pf.predict, lambda k: pf.update(run.z_dr[k]), lambda: pf.x)


#: ``{GPS/DR filter name: GPSDRFilter kind}`` (``"ekf"``, ``"ukf"``, ``"sukf"``), read by the real-drive runs.
FILTER_KIND = {"EKF": "ekf", "EKF-8": "ekf", "DR-only": "ekf", "UKF-8": "ukf", "SUKF-8": "sukf"}


def _gpsdr_steps(run, x0, rng, context, kind="ekf", augmented=False, gps=True):
    """A :class:`~filterwnn.navigation.gpsdr.GPSDRFilter` (6 states, or 8 with odometer scale and heading
    bias), with the run's fixes and their accuracies, or without GPS (``gps=False``)."""
    sc = run.scenario
    model = GPSDRModel(dt=sc.dt, augmented=augmented, sigma_gps=sc.sigma_gps)
    f = GPSDRFilter(model, kind, x0=np.concatenate([x0, [1.0, 0.0]]) if augmented else x0)
    n = len(run.t)
    fixes = run.gps_list() if gps else [None] * n
    sigmas = run.gps_sigma_list() if gps else [None] * n
    offsets = run.gps_offset_list()
    return _Steps(f.predict, lambda k: f.update(run.z_dr[k], fixes[k], sigmas[k], offsets[k]), lambda: f.kf.x)


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


def scenario_kind(scenario):
    """``"gpsdr"`` for a scenario with GPS fixes (``gps_rate > 0``), else ``"dr"``: the key of
    :data:`FILTER_TABLE` rows and :data:`ORACLE`."""
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
