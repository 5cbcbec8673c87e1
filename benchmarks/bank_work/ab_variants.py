"""A variant of the bank's step against main's, in one process, in turn (issue 25, h23).

Copies this checkout's ``filterwnn/`` twice into a temporary folder, as packages ``fw_a``
(as it is) and ``fw_b`` (with ``variants/<name>.patch`` applied; ``none``: an A/A control),
then runs ``--procs`` processes; each builds bench_peers' bank at ``--B`` with either
package and times blocks of steps (CPU clock, ``time.process_time``) for ``--rounds``
rounds, A and B in turn (the order alternating), and prints the median of the paired ratios
B / A. Separate processes because one process's memory layout moves a bank's time by up
to 10 % for the whole run (the ratio a process prints is then off by as much); the median
over processes is the number to read. Prints, per process, the two medians and the paired
ratio, then the median (and range) over the processes. Any package change goes through
the patch: the numbers and errors of the variant are its own.

    python benchmarks/bank_work/ab_variants.py VARIANT [--B 1000] [--procs 8] [--rounds 100]
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]

CHILD = r"""
import importlib, sys, time
sys.path.insert(0, sys.argv[1]); sys.path.insert(0, sys.argv[2])
import numpy as np
from bench_peers import _six, _merwe6
from bench_particle import six_fx, six_hx, DT6
B, R = int(sys.argv[3]), int(sys.argv[4])
prob, x, z = _six(B)
banks = []
for pkg in ("fw_a", "fw_b"):
    b = importlib.import_module(pkg + ".kalman.bank").UnscentedKalmanFilterBank(B, 6, 3, DT6, six_hx, six_fx, _merwe6())
    b.x, b.P, b.Q, b.R = x, prob["P0"], prob["Q"], prob["R"]
    banks.append(b)
k = max(2, 4000 // B)
def block(b):
    t = time.process_time()
    for _ in range(k):
        b.predict(); b.update(z)
    return (time.process_time() - t) / k / B * 1e6
for b in banks:
    block(b); block(b)
ta, tb = [], []
for r in range(R):
    res = {}
    for i in ((0, 1) if r % 2 == 0 else (1, 0)):
        res[i] = block(banks[i])
    ta.append(res[0]); tb.append(res[1])
ta, tb = np.array(ta), np.array(tb)
print(f"{np.median(ta):.3f} {np.median(tb):.3f} {np.median(tb / ta):.4f}")
"""


def _packages(tmp, variant):
    shutil.copytree(ROOT / "filterwnn", tmp / "fw_a", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(ROOT / "filterwnn", tmp / "fw_b", ignore=shutil.ignore_patterns("__pycache__"))
    if variant != "none":
        patch = HERE / "variants" / f"{variant}.patch"
        # the patch names filterwnn/...: strip that component and apply it inside fw_b
        subprocess.run(["patch", "-s", "-p2", "-d", str(tmp / "fw_b"), "-i", str(patch)], check=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("variant", help="a patch name in variants/ (without .patch), or none")
    ap.add_argument("--B", type=int, default=1000)
    ap.add_argument("--procs", type=int, default=8)
    ap.add_argument("--rounds", type=int, default=100)
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        _packages(tmp, a.variant)
        ratios = []
        print(f"variant {a.variant}, B = {a.B:,}: per process median A, median B (us per filter-step), paired B / A")
        for _ in range(a.procs):
            out = subprocess.run([sys.executable, "-c", CHILD, str(tmp), str(ROOT / "benchmarks"), str(a.B),
                                  str(a.rounds)], capture_output=True, text=True, check=True).stdout.split()
            print(f"  {out[0]}  {out[1]}  {out[2]}")
            ratios.append(float(out[2]))
        print(f"median over {a.procs} processes of the paired ratio B / A: {statistics.median(ratios):.3f} "
              f"(range {min(ratios):.3f}-{max(ratios):.3f})")


if __name__ == "__main__":
    main()
