"""The WNN study's rows: which trainer each runs, with what fixed settings, its label and the
constants the plan, the runs and the tables share (see :mod:`filterwnn.studies.wnn`)."""

from __future__ import annotations

from typing import NamedTuple

from ...wnn.trainers import TRAINERS

__all__ = [
    "StudyRow",
    "MOVE_ROWS",
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
    "Z90",
    "VALIDATION_FRACTION",
    "PAPER_TABLE1",
    "row_label",
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


#: The scikit-learn references fitted on the same runs (:func:`~filterwnn.studies.wnn.fit_reference`).
REFERENCES = ("MLPRegressor", "GaussianProcessRegressor")


#: The columns of ``table1.csv`` and of :attr:`StudyResult.table` rows, in order.
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
#: (see :func:`~filterwnn.studies.wnn.candidates`).
TUNING_GRID = {name: [dict(c) for c in grid] for name, grid in _specs_with("grid").items()}


#: The single filter whose step each particle filter's proposal (or Gaussian sum's component) runs
#: (the entries' ``parent``).
PROPOSAL_PARENT = _specs_with("parent")


#: Factors applied to the parent's chosen Q (:func:`~filterwnn.studies.wnn.candidates`).
Q_FACTORS = (0.01, 0.1, 1.0, 10.0, 100.0)


#: Window of the running median that smooths the validation curve before its minimum is taken.
SMOOTHING_WINDOW = 5


#: Half-width of the central 90 % interval of a normal, in standard deviations.
Z90 = 1.6448536269514722


#: Fraction of a tuning run's training rows (the last ones) held out for validation.
VALIDATION_FRACTION = 0.2


#: The paper's Table 1: trainer -> (test MSE, training time in s) (the entries' ``paper``). It has no SUKF row.
PAPER_TABLE1 = _specs_with("paper")
