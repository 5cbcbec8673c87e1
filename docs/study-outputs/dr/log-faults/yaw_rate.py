"""A log with the gyro's yaw rate in place of a heading (issue 23, stop 49).

A car's CAN bus and an IMU give the yaw rate, not a heading. The analogs of ``tests/_held_out_drives.py`` (seed 0 of
each) written with a ``yaw_rate_deg`` column, the rate at each sample that their heading's increments give (central
differences of the unwrapped heading), in place of the heading; read by ``read_drive_csv`` and scored as ``filterwnn
study dr --drive FILE --grade phone`` scores it, beside the same drive with its heading. Each line: the median / max
at the outage ends per 8-state kind, and the reader's warning of the start heading it took (or the refusal). The
analogs' headings start at 70 deg (phone, whose gyro is 1 deg off), 320 deg (1 Hz) and 200 deg (city). The third line
of each: the yaw rate counter-clockwise positive (negated, as ROS and ENU frames count it). Run with the
package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/yaw_rate.py ROOT

(``yaw_rate.txt``: on c81d7b7, then on stop 49's reader, which integrates the yaw rate.)
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
with tempfile.TemporaryDirectory() as tmp:
    for name in ("phone", "one_hz", "city"):
        c = held_out.columns(name, 0)
        rate = np.degrees(np.gradient(np.unwrap(c["heading"]), c["time"]))
        names = [("yaw_rate_deg" if k == "heading" else k) for k in held_out.COLUMNS]
        paths = [("heading", held_out.write_csv(os.path.join(tmp, "heading.csv"), c))]
        for label, sign in (("yaw rate", 1.0), ("yaw rate counter-clockwise", -1.0)):
            c["yaw_rate_deg"] = sign * rate
            paths.append((label, os.path.join(tmp, f"yaw{sign:+.0f}.csv")))
            with open(paths[-1][1], "w") as fh:
                fh.write(",".join(names) + "\n")
                for k in range(len(c["time"])):
                    fh.write(",".join("" if np.isnan(c[x][k]) else f"{c[x][k]:.6g}" if x in ("time", "gps_sigma")
                                      else f"{c[x][k]:.5f}" for x in names) + "\n")
        for label, path in paths:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                try:
                    res = real_drive_outages(read_drive_csv(path), filters=KINDS, use_gps_sigma=True, grade="phone")
                except ValueError as e:
                    print(f"{name} 0, {label} | refused: {str(e)[len(path) + 2:]}", flush=True)
                    continue
            said = [str(w.message).split(" (a line")[0] for w in caught if "yaw rate integrated" in str(w.message)]
            print(f"{name} 0, {label} | " + " | ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}"
                                                     for k in KINDS) + (f" | {said[0]}" if said else ""), flush=True)
