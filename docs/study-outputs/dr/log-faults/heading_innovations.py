"""How far is a moving car's measured heading from the filter's, on clean drives? (issue 23, stop 51)

Per drive and 8-state kind (phone grade unless named, as ``filterwnn study dr --drive FILE`` scores it): the outage
ends' median / max (m), and over every update while the car moves (the pass with the fixes and each outage's) the
largest difference between the measured heading, less the heading bias, and the filter's ``atan2(v_e, v_n)``
before the update (degrees), its 99.9th percentile and the samples past 20 and 30 degrees. Run with the package at
``ROOT`` (stop 51 ran it on 128a4b8, before ``heading_linear_limit``), one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_innovations.py ROOT analogs 0 3
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_innovations.py ROOT recorded
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_innovations.py ROOT analogs 3 10

(``heading_innovations.txt``: the three in turn, the last on stop 51's code; ``recorded`` needs the ``data``
extra.)
"""
import os
import sys
import tempfile
import warnings

import numpy as np
ROOT = os.path.abspath(sys.argv[1]); sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr/random-drives"]
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation import gpsdr
from filterwnn.navigation.drives import read_drive_csv, sample_drive_path, load_car_drive, CAR_DRIVES
from filterwnn.studies.dr import real_drive_outages
REC = []
orig = gpsdr.GPSDRFilter.update
def update(self, z_dr, z_gps=None, *a, **k):
    if self.classify(z_dr) == "moving":
        x = self.kf.x
        pred = np.arctan2(x[1], x[4]) + (x[7] if self.model.augmented else 0.0)
        REC.append(abs((z_dr[0] - pred + np.pi) % (2 * np.pi) - np.pi))
    return orig(self, z_dr, z_gps, *a, **k)
gpsdr.GPSDRFilter.update = update
KINDS = ("EKF-8", "UKF-8", "SUKF-8")
def go(label, run, grade="phone", sig=True):
    out = []
    for kd in KINDS:
        REC.clear()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=(kd,), use_gps_sigma=sig and run.gps_sigma is not None, grade=grade)
        r = np.degrees(np.array(REC))
        out.append(f"{kd} {np.median(res[kd]):.2f}/{res[kd].max():.2f} max {r.max():.1f} p999 {np.quantile(r, .999):.1f} n>20 {int((r > 20).sum())} n>30 {int((r > 30).sum())}")
    print(label, "|", " | ".join(out), flush=True)
which = sys.argv[2]
tmp = tempfile.mkdtemp()
if which == "analogs":
    for name in ("one_hz", "phone", "city"):
        for seed in range(int(sys.argv[3]), int(sys.argv[4])):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed)))
            go(f"{name} {seed}", run)
elif which == "recorded":
    run = read_drive_csv(sample_drive_path())
    go("sample phone", run); go("sample survey", run, "survey")
    for d in CAR_DRIVES:
        run = load_car_drive(d)
        go(f"{d} survey", run, "survey", sig=False); go(f"{d} phone", run, "phone", sig=False)
