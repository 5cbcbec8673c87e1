"""The bank and dynamax's jit(vmap) cold (right after the filterpy loop, as in bench_peers.py's
rotation) and warm (the third of three calls in a row), same process, in turn (issue 25).

``bench_peers.py`` times one call of each variant per repeat, each after the others: the bank
then steps after 200 filterpy UKFs (or dynamax, or the NumPy floor). This measures how much
of the bank's time there is that placement, and how much dynamax pays for the same. Wall clock
(``perf_counter``, as bench_peers), us per filter-step, medians over the repeats.

    python benchmarks/bank_work/cold_warm.py [--repeats 15] [--B 1000]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))  # this checkout's filterwnn
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402
import bench_peers as bp  # noqa: E402


def _timed(fn):
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=15)
    ap.add_argument("--B", type=int, default=1000)
    a = ap.parse_args(argv)
    B = a.B
    prob, x, z = bp._six(B)
    bank = bp._bank(prob, x)

    def ours():
        bank.predict()
        bank.update(z)

    def loop():
        for i in range(bp.LOOP_SAMPLE):
            f = bp._filterpy_six(prob, x[i])
            f.predict()
            f.update(z[i])

    dyn = bp._dynamax_bank(prob, x, z)["dynamax jit(vmap)"]
    if not isinstance(dyn, bp.Timed):
        print(f"dynamax {dyn}")
        return
    variants = {"filterwnn bank": ours, "dynamax jit(vmap)": dyn.fn}
    res = {k: {"cold": [], "warm": []} for k in variants}
    for fn in variants.values():
        fn()
    for _ in range(a.repeats):
        for k, fn in variants.items():
            loop()
            res[k]["cold"].append(_timed(fn))
            fn()
            fn()
            res[k]["warm"].append(_timed(fn))
    print(f"B = {B:,}, {a.repeats} repeats, us per filter-step (wall clock, medians)")
    for k, r in res.items():
        cold, warm = (float(np.median(r[s])) / B * 1e6 for s in ("cold", "warm"))
        print(f"  {k:18s} cold (after the filterpy loop) {cold:5.2f}   warm (3rd call in a row) {warm:5.2f}   "
              f"cold / warm {cold / warm:.2f}")
    b, d = res["filterwnn bank"], res["dynamax jit(vmap)"]
    for s in ("cold", "warm"):
        print(f"  bank / dynamax, {s}: {np.median(b[s]) / np.median(d[s]):.2f}")


if __name__ == "__main__":
    with bp.threadpool_limits(1):
        main()
