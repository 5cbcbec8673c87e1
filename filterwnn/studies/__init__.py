"""Runners that reproduce the two papers' studies.

Each study module exposes ``add_arguments(parser)`` and ``run(args)`` for the
``filterwnn study NAME`` command, plus plain functions that return arrays and tables
(no plotting here: :mod:`filterwnn.studies.plotting` draws from their results).
"""

STUDIES = {
    "wnn": "filterwnn.studies.wnn",
    "dr": "filterwnn.studies.dr",
}
