"""A log with the heading, the speed and the fixes each on rows of their own (issue 23, stop 49).

The analogs of ``tests/_held_out_drives.py`` (seed 0 of each) written as a logger that writes each sensor's message
on a row of its own would: the gyro heading at each sample's time, the speed 20 ms later (its value then, linearly
interpolated), each fix 30 ms after its sample (the truth then plus the fix's error); read by ``read_drive_csv``
and scored as ``filterwnn study dr --drive FILE --grade phone`` scores it, beside the same drive as one row per
sample. Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/sensor_rows.py ROOT

(``sensor_rows.txt``: on f6b44d8, then on stop 49's reader, which reads such a log.)
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


def score(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = real_drive_outages(read_drive_csv(path), filters=KINDS, use_gps_sigma=True, grade="phone")
    return " | ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in KINDS)


with tempfile.TemporaryDirectory() as tmp:
    for name in ("phone", "one_hz", "city"):
        c = held_out.columns(name, 0)
        t = c["time"]
        fix = ~np.isnan(c["gps_east"])
        print(f"{name} 0, one row per sample          | {score(held_out.write_csv(os.path.join(tmp, 'rows.csv'), c))}",
              flush=True)
        speed = np.interp(t + 0.02, t, c["speed"])
        east = c["gps_east"] + np.interp(t + 0.03, t, c["true_east"]) - c["true_east"]
        north = c["gps_north"] + np.interp(t + 0.03, t, c["true_north"]) - c["true_north"]
        path = os.path.join(tmp, "messages.csv")
        with open(path, "w") as fh:
            fh.write(",".join(held_out.COLUMNS) + "\n")
            for k in range(len(t)):
                fh.write(f"{t[k]:.6g},{c['heading'][k]:.4f},,,,,{c['true_east'][k]:.4f},{c['true_north'][k]:.4f}\n")
                fh.write(f"{t[k] + 0.02:.6g},,{speed[k]:.4f},,,,,\n")
                if fix[k]:
                    fh.write(f"{t[k] + 0.03:.6g},,,{east[k]:.4f},{north[k]:.4f},{c['gps_sigma'][k]:.6g},,\n")
        try:
            print(f"{name} 0, a row per sensor message   | {score(path)}", flush=True)
        except ValueError as e:
            print(f"{name} 0, a row per sensor message   | refused: {str(e)[len(path) + 2:]}", flush=True)
