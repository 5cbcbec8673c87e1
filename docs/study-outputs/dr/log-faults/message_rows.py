"""A log with a row per sensor message, its fixes 30 ms after their samples (issue 23, stops 48 and 49).

The phone analog (seed 0) of ``tests/_held_out_drives.py`` written with each fix on a row of its own 30 ms after its
DR sample, the DR rows without fix cells, read by ``read_drive_csv`` and scored as ``filterwnn study dr --drive FILE
--grade phone`` scores it. Two ways to write the fix: ``as on the sample`` (the fix's value as on the one-row-per-
sample file, the truth at the sample's time plus its error: stop 48's check, which gave the clean 6.68 / 28.16 m),
and ``at its own time`` (the truth 30 ms later, linearly interpolated, plus the same error: what such a log holds).
Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/message_rows.py ROOT

(``message_rows.txt``: on 59b7460, each fix used as the position at its sample; then on stop 49's code, each moved
back along the filter's velocity by its 30 ms.)
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

assert real_drive_outages.__code__.co_filename.startswith(ROOT)
KINDS = ("EKF-8", "UKF-8", "SUKF-8")
LATER = 0.03
c = held_out.columns("phone", 0)
t = c["time"]
fix = ~np.isnan(c["gps_east"])
with tempfile.TemporaryDirectory() as tmp:
    for how in ("as on the sample", "at its own time"):
        east, north = c["gps_east"].copy(), c["gps_north"].copy()
        if how == "at its own time":
            east[fix] += np.interp(t[fix] + LATER, t, c["true_east"]) - c["true_east"][fix]
            north[fix] += np.interp(t[fix] + LATER, t, c["true_north"]) - c["true_north"][fix]
        path = os.path.join(tmp, "messages.csv")
        with open(path, "w") as fh:
            fh.write(",".join(held_out.COLUMNS) + "\n")
            for k in range(len(t)):
                fh.write(f"{t[k]:.6g},{c['heading'][k]:.4f},{c['speed'][k]:.4f},,,,"
                         f"{c['true_east'][k]:.4f},{c['true_north'][k]:.4f}\n")
                if fix[k]:
                    fh.write(f"{t[k] + LATER:.6g},,,{east[k]:.4f},{north[k]:.4f},{c['gps_sigma'][k]:.6g},,\n")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(read_drive_csv(path), filters=KINDS, use_gps_sigma=True, grade="phone")
        print(f"phone 0, fixes 30 ms after their samples, {how:>16} | "
              + " | ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in KINDS), flush=True)
