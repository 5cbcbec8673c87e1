"""A heading half a second off on the phone analogs (issue 23, stop 51).

``heading_latency.py``'s question at 10 Hz: the phone analogs of ``tests/_held_out_drives.py`` (seeds 0-2), their
heading read 0.5 s before (``+0.5``) or after (``-0.5``) its stamp along the shorter arc (a fused orientation's
delay, or a heading on another clock than the fixes and the speed), scored as ``filterwnn study dr --drive FILE
--grade phone`` scores them. Each line: DR-mech and the 8-state kinds' median / max at the outage ends (m). Run with
the package at ``ROOT`` (stop 51 ran it on 5e3d0a6), one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_latency_phone.py ROOT

(``heading_latency_phone.txt``.)
"""
import os
import sys
import tempfile
import warnings

import numpy as np
ROOT = os.path.abspath(sys.argv[1]); sys.path[:0] = [ROOT, ROOT + "/tests"]
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.studies.dr import real_drive_outages
KINDS = ("DR-mech", "EKF-8", "UKF-8", "SUKF-8")
tmp = tempfile.mkdtemp()
for seed in (0, 1, 2):
    c = held_out.columns("phone", seed)
    for lag in (0.0, 0.5, -0.5):
        t = c["time"]
        cc = dict(c, heading=np.mod(np.interp(t - lag, t, np.unwrap(c["heading"])), 2 * np.pi))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cc))
            res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
        print("phone", seed, f"heading {lag:+.1f} s late |", " | ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in KINDS), flush=True)
