"""The random drives where ``heading_linear_limit`` fired, with it off (``None``, the filter before stop 51) and on
(the default), EKF-8, phone grade (issue 23, stop 51). Each line: the drive, dead reckoning alone's median / max
at the outage ends, then the EKF-8's with the rule off and on and the samples where it fired in the pass with the
fixes (``n_heading_far``; firing only in an outage's pass shows as 0). Run with the package at ``ROOT``, one BLAS
thread, the seeds ``heading_far_count.py`` found::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/heading_far_compare.py ROOT 1 1,8,10,16,21,22,24,26,31,37,39,43,48,55,61,68,74,75,77,79,80,95,101,103 > heading_far_compare_1.txt
"""
import os
import sys
import tempfile
import warnings

import numpy as np
ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr/random-drives"]
import _held_out_drives as held_out  # noqa: E402
import random_drives  # noqa: E402
from filterwnn.navigation import gpsdr
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.studies.dr import real_drive_outages
D = gpsdr.GPSDRFilter.__init__.__kwdefaults__
proto = int(sys.argv[2]); kinds = tuple(sys.argv[4].split(",")) if len(sys.argv) > 4 else ("EKF-8",)
with tempfile.TemporaryDirectory() as tmp:
    for seed in map(int, sys.argv[3].split(",")):
        d, cols, _ = random_drives.drive(seed, proto)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
        cells = []
        for rule in ("off", "on"):
            D["heading_linear_limit"] = None if rule == "off" else gpsdr.HEADING_LINEAR_LIMIT
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                res = real_drive_outages(run, filters=("DR-mech",) + kinds, use_gps_sigma=True, grade="phone")
            if rule == "off":
                cells.append(f"DR-mech {np.median(res['DR-mech']):.2f} / {res['DR-mech'].max():.2f}")
            cells.append(f"{rule}: " + " ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f} ({res['integrity'][k]['n_heading_far']} far)" for k in kinds))
        print(proto, seed, f"dt {d['dt']:g}", " | ".join(cells), flush=True)
