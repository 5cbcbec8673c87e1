"""Far-too-good reported sigmas on the phone and city analogs (issue 23, stop 55).

``placeholder_fixes.py`` tried the 1 Hz analog; here the phone analog (1 Hz fixes reporting 5-8 m) and the city
analog (1 Hz fixes over 5 Hz odometry, reporting 10-16 m, themselves optimistic), seed 0, with 5 % of their fixes
(drawn with seed 5) claiming 1 m, scored as ``filterwnn study dr --drive FILE --grade phone`` scores them (every
8-state kind, 20 outages of 30 s, median / max at the outage ends, m; targets phone 10 / 30, city 20 / 50), with
the defaults (both floors: ``gps_sigma_floor``, ``floor_on_detection``) and with neither; ``fl``: the fixes
floored, ``at``: the step the floor was raised at (None: never). Run with the package at ``ROOT``, one BLAS
thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/placeholder_other_analogs.py ROOT phone > placeholder_other_analogs_phone.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/placeholder_other_analogs.py ROOT city > placeholder_other_analogs_city.txt
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, ROOT + "/tests"]
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

KINDS = ("EKF-8", "UKF-8", "SUKF-8")
name = sys.argv[2]
base = held_out.columns(name)
fix = np.flatnonzero(np.isfinite(base["gps_east"]))
pick = np.random.default_rng(5).choice(fix, size=len(fix) // 20, replace=False)
tmp = tempfile.mkdtemp()
for label, sigma in (("clean", None), ("1 m on 5 %", 1.0)):
    cols = {k: v.copy() for k, v in base.items()}
    if sigma:
        cols["gps_sigma"][pick] = sigma
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(held_out.write_csv(os.path.join(tmp, f"{name}.csv"), cols))
    settings = (("defaults", {}), ("neither", dict(gps_sigma_floor=0.0, floor_on_detection=False)))
    for setting, kw in settings if sigma else settings[:1]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=KINDS, grade="phone", use_gps_sigma=True, **kw)
        print(name, label, setting, " | ".join(
            f"{k} {np.median(res[k]):.2f}/{res[k].max():.2f} fl {res['integrity'][k]['n_floored']} "
            f"at {res['integrity'][k]['floor_raised']}" for k in KINDS), flush=True)
