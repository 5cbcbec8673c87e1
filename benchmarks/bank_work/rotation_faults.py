"""Minor page faults and CPU time of each call in bench_peers' bank row (issue 25, h23).

Runs ``bench_peers.row_bank`` at B = 1,000 and 10,000 with every variant's call wrapped to
count minor page faults (``getrusage``) and CPU time (``time.process_time``), and prints them
per call (the warm-up call first) and the row's medians. Run it once as it is and once with
``MALLOC_TRIM_THRESHOLD_=1000000000 MALLOC_MMAP_THRESHOLD_=1000000000`` (glibc then keeps
freed memory: no faults) to see what the faults cost the bank in the rotation.

    python benchmarks/bank_work/rotation_faults.py
"""

from __future__ import annotations

import resource
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))  # this checkout's filterwnn
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import bench_peers as bp  # noqa: E402

_measure = bp._measure


def _counting(row, repeats):
    for v in row.values():
        if isinstance(v, bp.Timed):
            fn, log = v.fn, []

            def wrapped(fn=fn, log=log):
                f0, t0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt, time.process_time()
                fn()
                log.append((resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0, time.process_time() - t0))

            v.fn, v.log = wrapped, log
    out = _measure(row, repeats)
    for k, v in row.items():
        if isinstance(v, bp.Timed):
            print(f"  {k}: faults per call {[f for f, _ in v.log]}, CPU ms {[round(t * 1e3, 2) for _, t in v.log]}")
    return out


def main():
    bp._measure = _counting
    with bp.threadpool_limits(1):
        for B in (1000, 10000):
            print(f"B = {B:,}")
            res, _ = bp.row_bank(B, 5)
            print("  medians (us per filter-step, wall clock as bench_peers): "
                  + ", ".join(f"{k} {v * 1e6:.2f}" for k, v in res.items() if k in ("filterwnn bank", "dynamax jit(vmap)", "NumPy floor")))


if __name__ == "__main__":
    main()
