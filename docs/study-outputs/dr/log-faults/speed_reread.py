"""What an online speed-latency state could give at best after the tell (issue 23, stop 49): not built.

The 1 Hz analog of ``tests/_held_out_drives.py``, seeds 0-9, with the speed 1 s late. Each line, EKF-8's median / max
at the outage ends: as read; the monitor's tell (step, estimate; ``speed_told.py``); the drive re-read with
``odometer_latency`` at that estimate from the told step on (before it, as read: what a state started at the tell
could at best give); re-read at the estimate throughout; and re-read at the truth (1 s). Run with the package at
``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/speed_reread.py ROOT > speed_reread.txt
"""
import os
import re
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

TOLD = re.compile(r"speed's latency: by step (\d+) the fixes show the speed ([-+0-9.e]+) s")


def score(run):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        e = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone")["EKF-8"]
    told = [TOLD.search(str(w.message)).groups() for w in caught if TOLD.search(str(w.message))]
    return f"{np.median(e):.2f} / {e.max():.2f}", told


with tempfile.TemporaryDirectory() as tmp:
    for seed in range(10):
        path = held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns("one_hz", seed, odometer_latency=1.0))
        run = read_drive_csv(path)
        as_read, told = score(run)
        if not told:
            print(f"one_hz {seed} speed +1 s | as read {as_read} | not told", flush=True)
            continue
        k, est = int(told[0][0]), float(told[0][1])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            at_est, at_truth = read_drive_csv(path, odometer_latency=est), read_drive_csv(path, odometer_latency=1.0)
        z = run.z_dr.copy()
        z[k:] = at_est.z_dr[k:]
        print(f"one_hz {seed} speed +1 s | as read {as_read} | told at step {k}, {est:+.2f} s | from the tell on "
              f"{score(run._replace(z_dr=z))[0]} | throughout {score(at_est)[0]} | at the truth {score(at_truth)[0]}",
              flush=True)
