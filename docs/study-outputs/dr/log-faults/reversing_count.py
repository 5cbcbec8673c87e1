"""Does the reversing test fire on drives that never reverse? (issue 23, stop 52)

Stop 52's ``reversing_test`` (``GPSDRFilter``: while the car moves, Wald's sequential test of the fixes against the
dead reckoning's displacement taken the way the car goes and the other way) changes nothing where it never decides.
Per drive and kind (phone grade unless named, as ``filterwnn study dr --drive FILE`` scores it, every pass: the one
with the fixes and each outage's), its decisions (``rev``: reversing or forward again), the largest log-likelihood
ratio the test reached
against the direction taken (``llr``, the sequential test's, which must pass log(1e9) = 20.7), the largest of the
smaller of it and the offset path's (``both``), and where the sequential test and the last two fixes would turn the
car (``REVERSING_FIXES``), the largest the offset path's guard reached (``guard``, which must pass log(100) = 4.6;
"-": never got so far), and the outage ends' median / max (m). Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/reversing_count.py ROOT analogs 0 10 > reversing_count_analogs.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/reversing_count.py ROOT recorded > reversing_count_recorded.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/reversing_count.py ROOT hard > reversing_count_hard.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/reversing_count.py ROOT random 1 0 55 > a.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/reversing_count.py ROOT random 1 55 110 > b.txt
    cat a.txt b.txt > reversing_count_random_1.txt  # and protocol 2 likewise, reversing_count_random_2.txt

(The sets are ``../drive_sets.py``'s, shared with ``../sensor-faults/crawl_count.py``; ``recorded`` needs the
``data`` extra; ``random P LO HI``: ``random_drives.drive(seed, P)``, EKF-8 only; ``hard``:
``tests/navigation/test_hard_drives.py``'s five drives, scored as there. Stop 52 ran it on 5db4d1c.)
"""
import os
import sys
import warnings

import numpy as np
ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr", ROOT + "/docs/study-outputs/dr/random-drives"]
from filterwnn.navigation import gpsdr  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402
from drive_sets import run_set  # noqa: E402
C = {"n": 0, "llr": -np.inf, "both": -np.inf, "guard": -np.inf}
orig = gpsdr.GPSDRFilter._test_reversing


def test(self, z_dr, z_gps, gps_sigma):
    before = self.n_reversing + self.n_forward_again
    st = self._stretch
    out = orig(self, z_dr, z_gps, gps_sigma)
    if self.n_reversing + self.n_forward_again > before:
        C["n"] += 1
    elif self._stretch is st:  # not started again: the statistics of this fix
        C["llr"] = max(C["llr"], st["llr"])
        C["both"] = max(C["both"], min(st["llr"], st["glr"]))
        if st["llr"] > np.log(1e9) and st["streak"] >= gpsdr.REVERSING_FIXES and st["n"] > gpsdr.REVERSING_FIXES:
            C["guard"] = max(C["guard"], st["glr"])
    return out


gpsdr.GPSDRFilter._test_reversing = test


def go(label, run, kinds=("EKF-8", "UKF-8", "SUKF-8"), grade="phone", sig=True, **kw):
    out = []
    for kd in kinds:
        C["n"], C["llr"], C["both"], C["guard"] = 0, -np.inf, -np.inf, -np.inf
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=(kd,), use_gps_sigma=sig and run.gps_sigma is not None, grade=grade,
                                     **kw)
        out.append(f"{kd} {np.median(res[kd]):.2f}/{res[kd].max():.2f} rev {C['n']} llr {C['llr']:.1f} both {C['both']:.1f} "
                   f"guard {'-' if C['guard'] == -np.inf else format(C['guard'], '.1f')}")
    print(label, "|", " | ".join(out), flush=True)


which = sys.argv[2]
run_set(ROOT, which, sys.argv[3:], go)
