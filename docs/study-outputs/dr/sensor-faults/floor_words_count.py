"""Where does the consistency monitor name fixes reporting far better than they are, on drives without them?
(issue 23, stop 55)

Since stop 55 the filter acts on those words: from then on every fix's sigma is floored at the median of the last
30 reported (``GPSDRFilter(floor_on_detection=True)``). Per drive and kind (phone grade unless named, as ``filterwnn
study dr --drive FILE`` scores it, every pass: the one with the fixes and each outage's), the times the warning of
inconsistency named such fixes (``named``: ``_floored_words`` returned words), and the outage ends' median / max (m).
Run on the code before the raise (5043b6d), where naming changes nothing, with the package at ``ROOT``, one BLAS
thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/floor_words_count.py ROOT analogs 0 10 > floor_words_count_analogs.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/floor_words_count.py ROOT recorded > floor_words_count_recorded.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/floor_words_count.py ROOT hard > floor_words_count_hard.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/floor_words_count.py ROOT random 1 0 40 > floor_words_count_random_1.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/floor_words_count.py ROOT random 2 0 40 > floor_words_count_random_2.txt

(The sets are ``../drive_sets.py``'s; ``recorded`` needs the ``data`` extra; ``random P LO HI``: EKF-8 only.)
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

C = {"n": 0}
orig = gpsdr.GPSDRFilter._floored_words


def words(self):
    w = orig(self)
    C["n"] += bool(w)
    return w


gpsdr.GPSDRFilter._floored_words = words


def go(label, run, kinds=("EKF-8", "UKF-8", "SUKF-8"), grade="phone", **kw):
    out = []
    for kd in kinds:
        C["n"] = 0
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=(kd,), use_gps_sigma=run.gps_sigma is not None, grade=grade, **kw)
        out.append(f"{kd} {np.median(res[kd]):.2f}/{res[kd].max():.2f} named {C['n']}")
    print(label, "|", " | ".join(out), flush=True)


run_set(ROOT, sys.argv[2], sys.argv[3:], go)
