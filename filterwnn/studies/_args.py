"""Old private home of :mod:`filterwnn.studies.options`, kept so that existing imports work."""

from .options import (  # noqa: F401
    HelpFormatter,
    add_progress_flag,
    float_list,
    int_list,
    joblib_backend,
    joblib_jobs,
    name_list,
    nonnegative_float,
    nonnegative_int,
    positive_float,
    positive_int,
    seed,
)
