"""Repository-wide pytest set-up: one BLAS thread per process, small notebooks.

Notebooks executed by nbmake inherit this process's environment, so they run at
their small size (FILTERWNN_NOTEBOOK_SIZE=small) unless the caller set it.
"""

import os

os.environ.setdefault("FILTERWNN_NOTEBOOK_SIZE", "small")
os.environ.setdefault("MPLBACKEND", "Agg")
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

try:  # numpy may already be loaded by a plugin: limit its pool too
    from threadpoolctl import threadpool_limits

    threadpool_limits(1)
except ImportError:  # pragma: no cover
    pass
