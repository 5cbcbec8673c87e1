"""The bank's step right after each neighbour of the rotation (see RESULTS.md; run from a checkout of f1fa75c)."""
import resource
import sys
import time

import numpy as np
from threadpoolctl import threadpool_limits

from _rotation import rotation

reps = int(sys.argv[1])


def _faults():
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt


with threadpool_limits(1):
    for B in (1000, 10000):
        kept, fresh, nb = rotation(B)
        nb = {"none": lambda: None, **{k: nb[k] for k in ("floor", "loop", "dynamax")}}
        for f in nb.values():
            f()
        res = {}
        for r in range(reps):
            for name, g in nb.items():
                pair = (("kept", kept), ("fresh", fresh))
                for bk, s in pair if r % 2 == 0 else pair[::-1]:
                    g()
                    f0, c0 = _faults(), time.process_time()
                    s()
                    c1 = time.process_time()
                    res.setdefault((name, bk), []).append(((c1 - c0) / B * 1e6, _faults() - f0))

        def med(name, bk, i):
            return np.median([v[i] for v in res[(name, bk)]])
        print(f"B={B}: " + "; ".join(
            f"after {n}: kept {med(n, 'kept', 0):.2f} ({med(n, 'kept', 1):.0f} flt) "
            f"fresh {med(n, 'fresh', 0):.2f} ({med(n, 'fresh', 1):.0f} flt)" for n in nb))
