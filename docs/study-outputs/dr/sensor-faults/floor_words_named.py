"""What the raised floor costs where the monitor named far-too-good fixes on drives without them (issue 23, stop 55).

``floor_words_count_random_*.txt`` found the monitor's words on five random drives (protocol 1 seeds 1, 18, 19;
protocol 2 seeds 18, 19: reported sigmas that change by street, every fix 1.1-1.4 times optimistic), and on none of
the analogs' seeds 0-9, the recorded drives or the hard bench. Per drive, EKF-8 as ``floor_words_count.py`` scores
it: the outage ends' median / max (m) with the floor raised there (``floor_on_detection=True``, the default) and
without, the fixes floored and the step it was raised at. Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/floor_words_named.py ROOT > floor_words_named.txt
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr", ROOT + "/docs/study-outputs/dr/random-drives"]
import random_drives  # noqa: E402
from drive_sets import read  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

for proto, seed in ((1, 1), (1, 18), (1, 19), (2, 18), (2, 19)):
    run = read(tempfile.mkdtemp(), random_drives.drive(seed, proto)[1])
    out = []
    for raise_it in (True, False):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=("EKF-8",), grade="phone", use_gps_sigma=True,
                                     floor_on_detection=raise_it)
        ig = res["integrity"]["EKF-8"]
        out.append(f"{'raised' if raise_it else 'not raised'} {np.median(res['EKF-8']):.2f}/{res['EKF-8'].max():.2f} "
                   f"floored {ig['n_floored']} at step {ig['floor_raised']}")
    print(f"{proto} {seed} | EKF-8 " + " | ".join(out), flush=True)
