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

# names the study's users and tests reach through this module
from ...navigation.dead_reckoning import SENSOR_GRADES, DRModel, GPSDRModel  # noqa: F401
from ...navigation.drives import CAR_DRIVE, CAR_DRIVES, load_car_drive, read_drive_csv  # noqa: F401
from ...navigation.scenarios import SCENARIOS, outage_starts, simulate_scenario, with_outage  # noqa: F401
from ._cli import add_arguments, run
from ._filters import (
    DR_FILTERS,
    FILTER_TABLE,
    FILTERS,
    GPSDR_FILTERS,
    OPT_IN,
    ORACLE,
    UPF_PARTICLES,
    DRFilter,
    run_filter,
    train_general_nn,
)
from ._real import REAL_FILTERS, REAL_MODEL, real_drive_outages, real_drive_table, score_drives
from ._run import DEFAULT_SCENARIOS, DIV_FACTOR, DIV_FLOOR, StudyResult, run_one, run_study, summarize
from ._tables import markdown_table, scenario_figure, write_outputs, write_real_drive

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
    "score_drives",
    "real_drive_table",
    "write_real_drive",
    "REAL_FILTERS",
    "REAL_MODEL",
]
