"""The WNN study's rows and the data it owns: which trainer each row runs, with what fixed
settings, its search grid (or the filter it centres on), its cost, its label, the paper's
Table 1 row and settings (:data:`STUDY`, keyed by row), and the constants the plan, the runs
and the tables share (see :mod:`filterwnn.studies.wnn`).

:class:`~filterwnn.wnn.trainers.TrainerSpec` says only how to train; a registered trainer
without an entry here has a row with the defaults of :class:`StudyEntry` (its name as label,
no search, not in the paper table).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

from ..._validation import check_choice
from ...wnn.trainers import TRAINERS

__all__ = [
    "StudyEntry",
    "StudyRow",
    "STUDY",
    "RENAMED_ROWS",
    "check_row",
    "study_entry",
    "ROWS",
    "ALL_TRAINERS",
    "PARTICLE_TRAINERS",
    "SWEEP_TRAINERS",
    "COPY_SETTINGS",
    "REFERENCES",
    "TABLE_COLUMNS",
    "TUNING_GRID",
    "PROPOSAL_PARENT",
    "Q_FACTORS",
    "SMOOTHING_WINDOW",
    "Z50",
    "Z90",
    "Z95",
    "SCORE_COLUMNS",
    "VALIDATION_FRACTION",
    "PAPER_TABLE1",
    "row_label",
]


@dataclass(frozen=True)
class StudyEntry:
    """What the WNN study knows about one row (all optional).

    Parameters
    ----------
    trainer : str, optional
        The registered trainer the row runs (default: the row's key).
    label : str, optional
        The row's algorithm name (``{N}``: the number of particles); default the key.
    fixed : dict
        Fixed ``WNNRegressor`` keywords of the row (``{"tempering": 0.01}``, ``{"move": "mala"}``).
    epochs : int, optional
        Fixed epochs (not searched).
    grid : tuple of dict
        Candidates of the settings search (``WNNRegressor`` keywords); empty: not searched on a grid.
    parent : str, optional
        Search Q around the value chosen for this row (its P0 kept) instead of a grid.
    copy_settings : str, optional
        Copy this row's chosen settings and epochs instead of searching.
    q_factors : tuple of float, optional
        With ``parent``: the factors applied to the parent's chosen Q (default
        :data:`~filterwnn.studies.wnn.rows.Q_FACTORS`).
    cost : float
        Rough seconds per epoch and particle (long tasks are scheduled first).
    paper : (float, float), optional
        The paper's Table 1 row: test MSE, training time (s).
    paper_settings : dict, optional
        Keywords over :data:`~filterwnn.wnn.trainers.PAPER_SETTINGS` for the paper-settings
        table; ``None`` leaves the row out of that table.
    default : bool
        Whether the study runs the row by default (:data:`~filterwnn.studies.wnn.rows.ALL_TRAINERS`).
    recalibrate : float, optional
        The row's Gaussian predictive is rescaled by one factor fitted at this central level on
        the tuning runs' validation split (:func:`~filterwnn.wnn.predictive.conformal_factor`;
        the fit itself is ``trainer``'s, unchanged); None: not recalibrated.
    """

    trainer: str = None
    label: str = None
    fixed: dict = field(default_factory=dict)
    epochs: int = None
    grid: tuple = ()
    parent: str = None
    copy_settings: str = None
    q_factors: tuple = None
    cost: float = 1.0
    paper: tuple = None
    paper_settings: dict = None
    default: bool = True
    recalibrate: float = None


#: Factors applied to the parent's chosen Q by default (a row's ``q_factors`` widens them;
#: :func:`~filterwnn.studies.wnn.candidates`).
Q_FACTORS = (0.01, 0.1, 1.0, 10.0, 100.0)


def _grid(qs, p0s):
    return tuple({"process_noise": q, "initial_covariance": p} for q in qs for p in p0s)


_PF_PAPER = {"ess_threshold": 1.0, "tempering": 1.0}  # the paper resamples at every step
_GSF = {"tempering": 0.01}
_GSF_LABEL = "Gaussian-sum filter of {N} %ss (tempering 0.01)"

#: The study's data, keyed by row: the registered trainers' rows (in :data:`~filterwnn.wnn.trainers.TRAINERS`
#: order) and the study-only rows (``trainer`` set: a registered trainer with fixed keywords), which
#: follow the last particle filter. The grids are the protocol's (``docs/study-outputs/wnn/PROTOCOL.md``).
STUDY = {
    "bp": StudyEntry(label="BP", grid=tuple({"learning_rate": lr} for lr in (0.02, 0.05, 0.1, 0.2, 0.5)), cost=1,
                     paper=(1.6605, 7.9), paper_settings={}),
    "ekf": StudyEntry(label="EKF", grid=_grid((1e-5, 1e-4, 1e-3, 1e-2, 1e-1), (0.01, 0.1, 1.0, 10.0)), cost=1,
                      paper=(0.2672, 9.8), paper_settings={}),
    "ukf": StudyEntry(label="UKF", grid=_grid((1e-8, 1e-7, 1e-6, 1e-5, 1e-4), (0.01, 0.1)), cost=6,
                      paper=(0.1258, 12.4), paper_settings={}),
    "sukf": StudyEntry(label="SUKF (simplex points)", grid=_grid((1e-8, 1e-7, 1e-6, 1e-5, 1e-4), (0.01, 0.1)),
                       cost=6, paper_settings={}),
    "spf": StudyEntry(label="SPF (bootstrap)", grid=_grid((1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2), (0.01,)), cost=0.4,
                      paper=(0.0859, 7.6), paper_settings={"ess_threshold": 1.0}),
    "epf": StudyEntry(label="EPF (textbook)", parent="ekf", q_factors=(1e-3,) + Q_FACTORS, cost=1.2,
                      paper=(0.0601, 8.4), paper_settings=_PF_PAPER),
    "upf": StudyEntry(label="UPF (textbook)", parent="ukf", cost=4, paper=(0.0226, 17.9), paper_settings=_PF_PAPER),
    "supf": StudyEntry(label="SUPF (textbook)", parent="sukf", cost=4, paper=(0.0245, 10.1),
                       paper_settings=_PF_PAPER),
    # IBIS (Chopin 2002): the bootstrap step with Q = 0 reweights by each row's likelihood, and the
    # move rejuvenates after each resampling; formerly "upf+mala", whose UKF proposal at Q = 0 never
    # moved a particle (EPF, UPF and SUPF with the move gave bit-identical predictions)
    "ibis-mala": StudyEntry(trainer="spf", label="IBIS (bootstrap reweighting, MALA moves)", fixed={"move": "mala"},
                            epochs=1, cost=3),
    "ibis-hmc": StudyEntry(trainer="spf", label="IBIS (bootstrap reweighting, HMC moves)", fixed={"move": "hmc"},
                           epochs=1, cost=5, default=False),
    # Gaussian sums: the settings the study chose for the former "bank" weighting of epf/upf/supf
    "gsf-ekf": StudyEntry(label=_GSF_LABEL % "EKF", fixed=_GSF, parent="ekf", cost=1),
    "gsf-ukf": StudyEntry(label=_GSF_LABEL % "UKF", fixed=_GSF, parent="ukf", q_factors=Q_FACTORS + (1e3,), cost=4),
    "gsf-sukf": StudyEntry(label=_GSF_LABEL % "SUKF", fixed=_GSF, parent="sukf", q_factors=Q_FACTORS + (1e3,),
                           cost=3),
    "ekf-ensemble": StudyEntry(label="{N} independent EKFs, averaged", copy_settings="gsf-ekf", cost=1),
    "smc": StudyEntry(label="SMC sampler (HMC moves)", epochs=1, cost=40),
    "smc-noise": StudyEntry(label="SMC sampler, noise R learned (HMC moves)", epochs=1, cost=40),
    # protocol 4 (docs/study-outputs/wnn-protocol4): the moves chosen on the d = 160 known posterior
    "smc-noise-10x10": StudyEntry(label="SMC sampler, noise R learned (10 HMC steps x 10 leapfrogs per rung)",
                                  epochs=1, cost=70, default=False),
    # protocol 5 (docs/study-outputs/wnn-protocol5): smc-noise-10x10's sampler, Student-t likelihood
    "smc-student-10x10": StudyEntry(label="SMC sampler, Student-t likelihood, scale and nu learned "
                                          "(10 HMC steps x 10 leapfrogs per rung)",
                                    epochs=1, cost=70, default=False),
    # protocol 6 (docs/study-outputs/wnn-protocol6): smc-noise-10x10's fits, its Gaussian's width
    # rescaled by one split-conformal factor fitted at 90 % on the tuning runs' validation split
    "smc-noise-10x10-recal": StudyEntry(trainer="smc-noise-10x10",
                                        label="SMC sampler, noise R learned (10 HMC steps x 10 leapfrogs per rung), "
                                              "intervals recalibrated on the tuning runs' validation split",
                                        epochs=1, cost=70, default=False, recalibrate=0.9),
}

#: Former row keys -> the row that runs what they ran (:func:`check_row` names it).
RENAMED_ROWS = {"upf+mala": "ibis-mala", "spf+mala": "ibis-mala", "epf+mala": "ibis-mala",
                "supf+mala": "ibis-mala", "upf+hmc": "ibis-hmc"}


class StudyRow(NamedTuple):
    """One row of the study as the runs read it: the trainer it runs, its fixed ``WNNRegressor``
    keywords, its fixed epochs (None: searched, or the study's epochs) and its label (``{N}``:
    the number of particles)."""

    trainer: str
    fixed: dict
    epochs: object
    label: str


def study_entry(key):
    """Row ``key``'s :class:`StudyEntry` (the defaults for a registered trainer without one)."""
    return STUDY.get(key) or StudyEntry()


def check_row(key):
    """``key`` if it is a row; ``ValueError`` naming the new key of a renamed row, else listing the rows."""
    if key in RENAMED_ROWS:
        raise ValueError(
            f"the WNN study's row {key!r} is now {RENAMED_ROWS[key]!r}: with Q = 0 the Kalman proposal "
            "never moved a particle, so what ran was IBIS (bootstrap reweighting) with the move; "
            f"use {RENAMED_ROWS[key]!r}"
        )
    return check_choice(key, "trainer", _rows())


def _rows():
    """key -> :class:`StudyRow`: each registered trainer's row, and the study-only rows of
    :data:`STUDY` after the last particle filter; read when called, so that a trainer registered
    later has its row."""
    particle = [name for name, spec in TRAINERS.items() if spec.accepts_move]
    extra = {k: e for k, e in STUDY.items() if e.trainer is not None and e.trainer in TRAINERS}
    rows = {}
    for name in TRAINERS:
        e = study_entry(name)
        rows[name] = StudyRow(name, dict(e.fixed), e.epochs, e.label or name)
        if particle and name == particle[-1]:
            rows.update({k: StudyRow(e.trainer, dict(e.fixed), e.epochs, e.label or k) for k, e in extra.items()})
    return rows


def _uses_particles(key):
    """Whether row ``key``'s trainer carries ``n_particles`` particles or components."""
    return TRAINERS[_rows()[key].trainer].uses_particles


def _specs_with(attr):
    """``row -> entry.<attr>`` for the rows whose ``attr`` is set (not None or empty)."""
    return {k: getattr(study_entry(k), attr) for k in _rows() if getattr(study_entry(k), attr) not in (None, (), {})}


def _sweep_rows():
    """Rows of the particle sweep: the registered particle filters."""
    return [name for name, spec in TRAINERS.items() if spec.accepts_move]


def _cost():
    """Rough seconds per epoch and particle of every row, for scheduling the longest tasks first."""
    return {k: study_entry(k).cost for k in _rows()}


def _in_paper_table(key):
    """Whether row ``key`` also runs at the paper's literal settings."""
    return study_entry(key).paper_settings is not None


#: The study's rows at import (:class:`StudyRow` tuples): every registered trainer's row, and
#: the study-only rows of :data:`STUDY`. See ``docs/study-outputs/wnn/PROTOCOL.md``.
ROWS = _rows()


#: The rows run by default: those whose :class:`StudyEntry` says ``default`` (all but the opt-in
#: ``ibis-hmc``, ``smc-noise-10x10``, ``smc-student-10x10`` and ``smc-noise-10x10-recal``).
ALL_TRAINERS = tuple(k for k in ROWS if study_entry(k).default)


#: Rows whose trainer carries ``n_particles`` particles or components.
PARTICLE_TRAINERS = tuple(k for k in ROWS if _uses_particles(k))


#: Rows of the particle sweep (Figs. 3-4): the papers' particle filters (the particle family).
SWEEP_TRAINERS = tuple(_sweep_rows())


#: Rows that copy another row's chosen settings and epochs instead of searching (the entries' ``copy_settings``).
COPY_SETTINGS = _specs_with("copy_settings")


#: The scikit-learn references fitted on the same runs (:func:`~filterwnn.studies.wnn.fit_reference`).
REFERENCES = ("MLPRegressor", "GaussianProcessRegressor")


#: Half-width of the central 50 % interval of a normal, in standard deviations.
Z50 = 0.6744897501960817

#: Half-width of the central 90 % interval of a normal, in standard deviations.
Z90 = 1.6448536269514722

#: Half-width of the central 95 % interval of a normal, in standard deviations.
Z95 = 1.959963984540054

#: The predictive distribution's scores of every run and row (medians over runs in the table):
#: coverage of the central 50, 90 and 95 % intervals and the mean negative log predictive density
#: (:func:`~filterwnn.studies.wnn.predictive_scores`).
SCORE_COLUMNS = ("coverage50", "coverage90", "coverage95", "nlpd")


#: The columns of ``table1.csv`` and of :attr:`StudyResult.table` rows, in order.
TABLE_COLUMNS = (
    "trainer", "algorithm", "settings", "test_mse_median", "test_mse_q1", "test_mse_q3", "fit_time_median",
    "mean_ess", "distinct_particles", "distinct_ancestors", *SCORE_COLUMNS,
)


def row_label(key, n_particles):
    """The algorithm's name for row ``key`` (e.g. ``"Gaussian-sum filter of 20 EKFs (tempering 0.01)"``)."""
    rows = _rows()
    return rows[key].label.format(N=n_particles) if key in rows else key


#: Candidates tried on the validation split, per trainer (``WNNRegressor`` keywords; the entries'
#: ``grid``). EPF/UPF/SUPF and the Gaussian sums are not listed: they search ``Q x Q_FACTORS``
#: around the Q chosen for their proposal's filter (:data:`PROPOSAL_PARENT`) and keep its P0
#: (see :func:`~filterwnn.studies.wnn.candidates`).
TUNING_GRID = {name: [dict(c) for c in grid] for name, grid in _specs_with("grid").items()}


#: The single filter whose step each particle filter's proposal (or Gaussian sum's component) runs
#: (the entries' ``parent``).
PROPOSAL_PARENT = _specs_with("parent")


#: Window of the running median that smooths the validation curve before its minimum is taken.
SMOOTHING_WINDOW = 5


#: Fraction of a tuning run's training rows (the last ones) held out for validation.
VALIDATION_FRACTION = 0.2


#: The paper's Table 1: trainer -> (test MSE, training time in s) (the entries' ``paper``). It has no SUKF row.
PAPER_TABLE1 = _specs_with("paper")
