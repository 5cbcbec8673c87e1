"""The first paper's WNN study: Table 1 and Figs. 3-5 (Niu, Wu and Li).

``filterwnn study wnn`` trains a 5-20-1 Morlet wavelet network on the SISO benchmark of
the paper's eq. (12) (:func:`filterwnn.make_siso_benchmark`) with the rows of ``ROWS`` (one per
trainer of :data:`filterwnn.wnn.trainers.TRAINERS`, plus the study-only rows of
:data:`~filterwnn.studies.wnn.rows.STUDY`, the table of the study's own data), each named for the
algorithm it runs: the paper's seven trainers plus the SUKF (``bp, ekf, ukf, sukf, spf, epf,
upf, supf``; the particle filters with textbook weights), IBIS with MALA moves (``ibis-mala``:
the bootstrap step at Q = 0 reweights by each row's likelihood, a MALA move after each
resampling; ``ibis-hmc`` with HMC moves is opt-in; the former ``upf+mala`` ran this, its UKF
proposal never moving a particle at Q = 0), the Gaussian-sum filters of N EKFs, UKFs and
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
    empty for non-particle rows), ``coverage50``, ``coverage90``, ``coverage95`` (medians over
    runs of the share of test targets inside the central 50 / 90 / 95 % interval of the row's
    own predictive, :meth:`filterwnn.wnn.regressor.WNNRegressor.predictive`: for every row but
    ``smc-student-10x10`` the Gaussian of ``predict(return_std=True)``, whose interval is
    ``mean +- z std``; for that row the particles' mixture of Student-t's, whose interval is
    made of the mixture's quantiles; for ``smc-noise-10x10-recal`` ``smc-noise-10x10``'s
    Gaussian with its std multiplied by the split-conformal factor fitted on the tuning runs'
    validation split, :func:`~filterwnn.wnn.predictive.recalibrate`; the GP's Gaussian std
    included) and ``nlpd`` (median over
    runs of the mean negative log density of that predictive; :func:`distribution_scores`).
    What each row's variance holds is in its trainer's ``predict`` (see
    :meth:`filterwnn.wnn.regressor.WNNRegressor.predict`);
``runs.csv``
    one line per (table, trainer, run): test/train MSE, fit time, ESS, distinct particles,
    the predictive's scores; for ``smc-student-10x10`` also the learned noise
    (``noise_scale2``, ``noise_df``: the particles' median squared scale and degrees of freedom);
    for a recalibrated row the factor (``recal_factor``) and the scores before recalibration
    (``coverage50_base`` ... ``nlpd_base``);
``calibration.csv``
    for the recalibrated rows (``smc-noise-10x10-recal``): the width factor, its level, the
    number of validation residuals it was fitted on and the validation fits' median MSE;
``tuning.md``, ``tuning.csv``
    every candidate setting tried on the validation split, its best epoch and validation
    MSE, and which one was chosen;
``fig3_particles_mse.png``, ``fig4_particles_time.png``, ``fig5_supf_convergence.png``
    test MSE and training time against the number of particles for the four particle
    filters, and the SUPF convergence curve (training and test MSE per epoch).

**Settings.** Before the runs, each trainer tries the candidates of :data:`~filterwnn.studies.wnn.rows.TUNING_GRID`
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

**Modules.** :mod:`~filterwnn.studies.wnn.rows` (the study's rows and constants),
:mod:`~filterwnn.studies.wnn.plan` (seeds, the search's candidates and choice, the task lists),
:mod:`~filterwnn.studies.wnn.runs` (the fits and :func:`run_study`),
:mod:`~filterwnn.studies.wnn.tables` (the Markdown and CSV files),
:mod:`~filterwnn.studies.wnn.figures` (the PNG figures) and :mod:`~filterwnn.studies.wnn.cli`
(``filterwnn study wnn``); every public name is importable from here.

>>> res = run_study(n_runs=2, n_epochs=2, pf_epochs=1, n_particles=3, trainers=["ekf", "spf"],
...                 paper_table=False, references=(), sweep_particles=(), seed=1, tune_runs=1)
>>> [row["trainer"] for row in res.table]
['ekf', 'spf']
>>> res.table[1]["algorithm"], sorted(res.table[0])[:3]
('SPF (bootstrap)', ['algorithm', 'coverage50', 'coverage90'])
"""

from __future__ import annotations

from ...wnn.trainers import AUTO_SETTINGS, TRAINERS
from .cli import add_arguments, run
from .plan import StudyResult, candidates, run_seeds, select_settings, tune_seeds
from .rows import (
    ALL_TRAINERS,
    COPY_SETTINGS,
    RENAMED_ROWS,
    STUDY,
    StudyEntry,
    check_row,
    study_entry,
    PAPER_TABLE1,
    PARTICLE_TRAINERS,
    PROPOSAL_PARENT,
    Q_FACTORS,
    REFERENCES,
    ROWS,
    SMOOTHING_WINDOW,
    SWEEP_TRAINERS,
    TABLE_COLUMNS,
    TUNING_GRID,
    VALIDATION_FRACTION,
    Z50,
    Z90,
    Z95,
    SCORE_COLUMNS,
    StudyRow,
    _cost,
    _rows,
    row_label,
)
from .runs import (calibration_run, distribution_scores, fit_reference, fit_run, predictive_scores, run_study,
                   run_tasks, summarize, tune_run)
from .figures import write_figures
from .tables import is_reduced, markdown_table, tuning_table, write_outputs

__all__ = [
    "ALL_TRAINERS",
    "STUDY",
    "StudyEntry",
    "RENAMED_ROWS",
    "PARTICLE_TRAINERS",
    "PAPER_TABLE1",
    "REFERENCES",
    "TABLE_COLUMNS",
    "SCORE_COLUMNS",
    "TUNING_GRID",
    "PROPOSAL_PARENT",
    "StudyResult",
    "run_seeds",
    "tune_seeds",
    "candidates",
    "tune_run",
    "calibration_run",
    "select_settings",
    "fit_run",
    "predictive_scores",
    "distribution_scores",
    "fit_reference",
    "run_tasks",
    "summarize",
    "run_study",
    "write_outputs",
    "write_figures",
    "markdown_table",
    "tuning_table",
    "is_reduced",
    "add_arguments",
    "run",
]
