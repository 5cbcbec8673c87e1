"""The bank's step with and without its kept work arrays, in turn in one process (CPU clock).

One :class:`~filterwnn.kalman.bank.UnscentedKalmanFilterBank` of ``bench_peers.py``'s 6-state
model (Merwe points, 3 measurements) steps with its :class:`~filterwnn.kalman.batched.Workspace`
("kept"), a second of the same members without one ("fresh": every scratch array allocated
per step, as before the workspace), the two in turn (A B B A ...), each step timed by the
process's CPU clock and its minor page faults counted. Two settings: the banks stepping
alone, and each step right after one call of the benchmark's NumPy floor (as inside
``bench_peers.py``, where the floor's arrays come and go between the bank's steps).

    OPENBLAS_NUM_THREADS=1 python benchmarks/bank_work/bench_bank_work.py --repeats 60
"""

from __future__ import annotations

import argparse
import resource
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from bench_peers import _bank, _merwe6, _six, numpy_ukf_step  # noqa: E402

import filterwnn  # noqa: E402


def _timed(fn):
    f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    t0 = time.process_time()
    fn()
    t1 = time.process_time()
    return t1 - t0, resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0


def run(B, after_floor, repeats):
    """Median us per filter-step (kept, fresh), the median paired ratio, faults per step."""
    prob, x, z = _six(B)
    kept, fresh = _bank(prob, x), _bank(prob, x)
    fresh._workspace = lambda: None  # the step without a workspace: its scratch allocated each step
    pts, c = _merwe6(), np.sqrt(6.0)
    P0 = np.broadcast_to(prob["P0"], (B, 6, 6)).copy()

    def floor():
        numpy_ukf_step(x, P0, prob["Q"], prob["R"], z, pts.Wm, pts.Wc, c)

    def stepper(bank):
        def one():
            bank.predict()
            bank.update(z)
        return one

    steps = {"kept": stepper(kept), "fresh": stepper(fresh)}
    for f in steps.values():
        f()
    res = {k: [] for k in steps}
    for r in range(repeats):
        for k in (("kept", "fresh") if r % 2 == 0 else ("fresh", "kept")):
            if after_floor:
                floor()
            res[k].append(_timed(steps[k]))
    t = {k: np.array([v[0] for v in res[k]]) for k in res}
    faults = {k: float(np.median([v[1] for v in res[k]])) for k in res}
    assert np.array_equal(kept.x, fresh.x) and np.array_equal(kept.P, fresh.P)  # the same numbers, bit for bit
    return (float(np.median(t["kept"])) / B * 1e6, float(np.median(t["fresh"])) / B * 1e6,
            float(np.median(t["kept"] / t["fresh"])), faults)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=60)
    ap.add_argument("--sizes", type=int, nargs="+", default=[1000, 10000])
    args = ap.parse_args(argv)
    print(f"bench_bank_work: {args.repeats} steps each, in turn; CPU clock; numpy {np.__version__}; "
          f"{filterwnn.__file__}")
    print("| B | setting | kept us/filter-step | fresh us/filter-step | kept / fresh (median of pairs) | "
          "minor faults per step kept / fresh |")
    print("|---|---|---|---|---|---|")
    for B in args.sizes:
        for after in (False, True):
            k, f, ratio, faults = run(B, after, args.repeats)
            print(f"| {B:,} | {'after the floor' if after else 'alone'} | {k:.2f} | {f:.2f} | {ratio:.3f} | "
                  f"{faults['kept']:.0f} / {faults['fresh']:.0f} |")


if __name__ == "__main__":
    main()
