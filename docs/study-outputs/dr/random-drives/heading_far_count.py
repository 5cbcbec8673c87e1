"""Where does a heading far from the filter's come on drives nobody drew? (issue 23, stop 51)

Stop 51's ``heading_linear_limit`` (``GPSDRFilter``: a moving car's DR sample whose heading, less the heading bias,
is more than 30 degrees from the filter's enters as the measured velocity vector) changes nothing where it never
fires. This counts, per random drive (``random_drives.drive(seed, PROTOCOL)``), the samples where it fired in any
pass of the EKF-8 of ``filterwnn study dr --drive FILE --grade phone`` (the pass with the fixes and each outage's),
the largest difference over its moving samples (``max``), and the outage ends' median / max. Run with the package at ``ROOT``, one BLAS
thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/heading_far_count.py ROOT 1 0 110 > heading_far_count_1.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/heading_far_count.py ROOT 2 0 110 > heading_far_count_2.txt

``heading_far_compare.py`` then runs the drives where it fired with the rule off and on.
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
C = {"n": 0, "max": 0.0}
orig = gpsdr.GPSDRFilter._heading_far
def far(self, z_dr):
    x = self.kf.x
    b = x[7] if self.model.augmented else 0.0
    d = abs(float(gpsdr.wrap_angle(float(z_dr[0]) - b - np.arctan2(x[1], x[4]))))
    C["max"] = max(C["max"], d)
    r = orig(self, z_dr)
    C["n"] += r
    return r
gpsdr.GPSDRFilter._heading_far = far
proto = int(sys.argv[2]); lo, hi = int(sys.argv[3]), int(sys.argv[4])
tot = 0
with tempfile.TemporaryDirectory() as tmp:
    for seed in range(lo, hi):
        d, cols, _ = random_drives.drive(seed, proto)
        C["n"], C["max"] = 0, 0.0
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
            res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone")
        tot += C["n"]
        print(proto, seed, f"dt {d['dt']:.2f} far {C['n']} max {np.degrees(C['max']):.1f} deg EKF-8 {np.median(res['EKF-8']):.2f}/{res['EKF-8'].max():.2f}", flush=True)
print("total far", tot)
