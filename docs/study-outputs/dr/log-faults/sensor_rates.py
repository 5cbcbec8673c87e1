"""Heading and speed logged at different rates, each on rows of its own (issue 23, stop 50).

The analogs of ``tests/_held_out_drives.py`` (``NAMES``, seeds 0-2): the heading at every sample, the speed on rows
of its own every ``EVERY`` samples (20 ms after them, its value then: an OBD speed polled at 1 Hz beside a phone's
heading), each fix on a row of its own. ``read_drive_csv`` reads such a log at the rate of the sensor with fewer
rows, the other interpolated; beside it, the drive as one row per sample, and the same 1 Hz speed interpolated to
every sample and read at the heading's rate. Each line: the sample interval read, then per 8-state kind the
median / max at the outage ends (phone grade). Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/sensor_rates.py ROOT phone 10
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/sensor_rates.py ROOT city 5

(``sensor_rates_phone.txt``, ``sensor_rates_city.txt``, on stop 50's code.)
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

KINDS = ("EKF-8", "UKF-8", "SUKF-8")


def score(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(path)
        res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
    return f"dt {run.scenario.dt:g} | " + " | ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in KINDS)


every = int(sys.argv[3]) if len(sys.argv) > 3 else 10
with tempfile.TemporaryDirectory() as tmp:
    for name in sys.argv[2].split(","):
        for seed in (0, 1, 2):
            c = held_out.columns(name, seed)
            t = c["time"]
            fix = ~np.isnan(c["gps_east"])
            print(f"{name} {seed} rows per sample           | "
                  f"{score(held_out.write_csv(os.path.join(tmp, 'rows.csv'), c))}", flush=True)
            slow = np.arange(len(t)) % every == 0
            vs = np.interp(t + 0.02, t, c["speed"])
            path = os.path.join(tmp, "m.csv")  # the speed every `every` samples on its own rows, the heading at each
            with open(path, "w") as fh:
                fh.write(",".join(held_out.COLUMNS) + "\n")
                for k in range(len(t)):
                    fh.write(f"{t[k]:.6g},{c['heading'][k]:.4f},,,,,{c['true_east'][k]:.4f},{c['true_north'][k]:.4f}\n")
                    if slow[k]:
                        fh.write(f"{t[k] + 0.02:.6g},,{vs[k]:.4f},,,,,\n")
                    if fix[k]:
                        fh.write(f"{t[k]:.6g},,,{c['gps_east'][k]:.4f},{c['gps_north'][k]:.4f},"
                                 f"{c['gps_sigma'][k]:.6g},,\n")
            try:
                print(f"{name} {seed} slow speed, as read       | {score(path)}", flush=True)
            except ValueError as e:
                print(f"{name} {seed} slow speed, as read       | refused: {str(e)[:300]}", flush=True)
            # the alternative: samples at the heading's rows, the slow speed interpolated to them
            c2 = dict(c)
            c2["speed"] = np.interp(t, t[slow] + 0.02, vs[slow])
            print(f"{name} {seed} slow speed, at heading rate | "
                  f"{score(held_out.write_csv(os.path.join(tmp, 'alt.csv'), c2))}", flush=True)
