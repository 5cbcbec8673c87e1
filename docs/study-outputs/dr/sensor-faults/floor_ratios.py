"""How far below the floor's medians do honest reported sigmas go? (issue 23, stop 55)

``GPSDRFilter(gps_sigma_floor=SIGMA_FLOOR)`` takes a fix's reported sigma no smaller than ``SIGMA_FLOOR`` times the
lower of the medians of the last ``FLOOR_FIXES`` and ``FLOOR_WINDOW`` reported sigmas (this fix's among them). Per
drive with a ``gps_sigma`` column: its fixes, the lowest ratio of a fix's reported sigma to that median, and the fixes
the default floor takes up (``floored``); then the lowest ratio and the drives floored per family. The drive sets are
``../drive_sets.py``'s (the analogs' seeds LO to HI - 1, the sample and onavdata's drives, the hard bench, the
random drives), as the filter reads them. Run with the package at ``ROOT``::

    python docs/study-outputs/dr/sensor-faults/floor_ratios.py ROOT > floor_ratios.txt

(all sets: the analogs' seeds 0-49, ``recorded``, ``hard`` and the random drives' seeds 0-129 of protocols 1 and 2;
``recorded`` needs the ``data`` extra.)
"""
import os
import sys
from collections import deque

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr", ROOT + "/docs/study-outputs/dr/random-drives"]
from filterwnn.navigation.gpsdr import FLOOR_FIXES, FLOOR_WINDOW, SIGMA_FLOOR  # noqa: E402
from drive_sets import run_set  # noqa: E402

FAMILY = {}


def go(label, run, **kw):
    if run.gps_sigma is None:
        print(label, "| no gps_sigma column", flush=True)
        return
    last, low, n = deque(maxlen=FLOOR_WINDOW), np.inf, 0
    for s in run.gps_sigma:
        last.append(float(s))
        typical = min(np.median(list(last)[-FLOOR_FIXES:]), np.median(last))
        low = min(low, s / typical)
        n += s < SIGMA_FLOOR * typical
    print(f"{label} | fixes {len(run.gps_sigma)} | lowest ratio {low:.2f} | floored {n}", flush=True)
    fam = FAMILY.setdefault(WHICH[0] if WHICH[0] != "analogs" else label.split()[0], [np.inf, 0, 0])
    fam[0], fam[1], fam[2] = min(fam[0], low), fam[1] + (n > 0), fam[2] + 1


for WHICH in (("analogs", "0", "50"), ("recorded",), ("hard",), ("random", "1", "0", "130"), ("random", "2", "0", "130")):
    print(f"# {' '.join(WHICH)}", flush=True)
    run_set(ROOT, WHICH[0], WHICH[1:], go)
print(f"# per family, SIGMA_FLOOR {SIGMA_FLOOR}, FLOOR_FIXES {FLOOR_FIXES}, FLOOR_WINDOW {FLOOR_WINDOW}")
for fam, (low, floored, drives) in FAMILY.items():
    print(f"{fam}: lowest ratio {low:.2f}, {floored} of {drives} drives floored")
