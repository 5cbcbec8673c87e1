"""Kept and fresh banks inside bench_peers' rotation (see RESULTS.md; run from a checkout of f1fa75c)."""
import sys
import time

import numpy as np
from threadpoolctl import threadpool_limits

import filterwnn
from _rotation import bp, rotation

print(filterwnn.__file__)
reps = int(sys.argv[1])
with threadpool_limits(1):
    for B in (1000, 10000):
        kept, fresh, nb = rotation(B)
        row = {"kept": (kept, B), "fresh": (fresh, B), "loop": (nb["loop"], bp.LOOP_SAMPLE),
               "floor": (nb["floor"], B), "dynamax": (nb["dynamax"], B)}
        for f, _ in row.values():
            f()
        wall = {k: [] for k in row}
        cpu = {k: [] for k in row}
        for r in range(reps):
            keys = list(row) if r % 2 == 0 else ["fresh", "kept", "loop", "floor", "dynamax"]
            for k in keys:
                f, per = row[k]
                t0, c0 = time.perf_counter(), time.process_time()
                f()
                c1, t1 = time.process_time(), time.perf_counter()
                wall[k].append((t1 - t0) / per * 1e6)
                cpu[k].append((c1 - c0) / per * 1e6)
        w = {k: np.median(v) for k, v in wall.items()}
        pr = np.median(np.array(wall["kept"]) / np.array(wall["fresh"]))
        print(f"B={B}: wall us/filter-step " + ", ".join(f"{k} {v:.2f}" for k, v in w.items() if k != "loop")
              + f"; kept/fresh paired {pr:.3f}; kept/dynamax {w['kept']/w['dynamax']:.2f} "
              f"fresh/dynamax {w['fresh']/w['dynamax']:.2f}"
              + f"; cpu kept {np.median(cpu['kept']):.2f} fresh {np.median(cpu['fresh']):.2f}")
