"""Does the crawl test fire where no car creeps? (issue 23, stop 53)

Stop 53's ``crawl_test`` (``GPSDRFilter``: while the speed reads 0, a generalized likelihood ratio of the fixes,
a constant offset and a crawl along the heading against the offset alone, guarded by an offset that jumps once)
changes nothing where it never decides. Per drive and kind (phone grade unless named, as ``filterwnn study dr
--drive FILE`` scores it, every pass: the one with the fixes and each outage's), its decisions (``crawl``), the
largest statistic it reached without deciding (``glr``, which must pass log(1e9) = 20.7, and then the jump guard,
log(100)), and the outage ends' median / max (m). Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_count.py ROOT analogs 0 10 > crawl_count_analogs.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_count.py ROOT recorded > crawl_count_recorded.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_count.py ROOT hard > crawl_count_hard.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_count.py ROOT random 1 0 40 > crawl_count_random_1.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_count.py ROOT random 2 0 40 > crawl_count_random_2.txt

(The sets but ``files`` are ``../drive_sets.py``'s, shared with ``../log-faults/reversing_count.py``; ``recorded``
needs the ``data`` extra; ``random P LO HI``: ``random_drives.drive(seed, P)``, EKF-8 only; ``hard``:
``tests/navigation/test_hard_drives.py``'s five drives, scored as there; ``analogs LO HI [NAMES]``: the analogs of
``tests/_held_out_drives.py``; ``files CSV ...``: drive CSVs, each with the test and without, ``KINDS`` from the
environment.)
"""
import os
import sys
import warnings

import numpy as np
ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr", ROOT + "/docs/study-outputs/dr/random-drives"]
from filterwnn.navigation import gpsdr  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402
from drive_sets import run_set  # noqa: E402
C = {"n": 0, "glr": -np.inf}
orig = gpsdr.GPSDRFilter._test_crawl


def test(self, z_gps, gps_sigma):
    before = self.n_crawl
    out = orig(self, z_gps, gps_sigma)
    if self.n_crawl > before:
        C["n"] += 1
    else:
        C["glr"] = max(C["glr"], self._crawl["glr"])
    return out


gpsdr.GPSDRFilter._test_crawl = test


def go(label, run, kinds=("EKF-8", "UKF-8", "SUKF-8"), grade="phone", sig=True, **kw):
    out = []
    for kd in kinds:
        C["n"], C["glr"] = 0, -np.inf
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=(kd,), use_gps_sigma=sig and run.gps_sigma is not None, grade=grade,
                                     **kw)
        out.append(f"{kd} {np.median(res[kd]):.2f}/{res[kd].max():.2f} crawl {C['n']} glr {C['glr']:.1f}")
    print(label, "|", " | ".join(out), flush=True)


which = sys.argv[2]
if which == "files":
    kinds = tuple(os.environ.get("KINDS", "EKF-8,UKF-8,SUKF-8").split(","))
    for f in sys.argv[3:]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = read_drive_csv(f)
        go(os.path.basename(f), run, kinds=kinds)
        go(os.path.basename(f) + " off", run, kinds=kinds, crawl_test=False)
else:
    run_set(ROOT, which, sys.argv[3:], go)
