"""Single-sample spikes in the speed or the heading (issue 23, stop 50).

A CAN bus frame's glitch logs a speed of 255 km/h (70.8 m/s) for one sample; a wheel slips for one; a phone's
fused orientation jumps for one sample. Each such sample, integrated, moves the dead-reckoned track by its excess
times the interval. The analogs of ``tests/_held_out_drives.py`` (seeds 0-2) written as logged (``clean``), with 20
moving samples (over 3 m/s, drawn from ``SeedSequence([50, 7, seed])``) set to 70.8 m/s (``speed spikes``) or
turned by 90 degrees (``heading spikes``). Each line: DR-mech and the 8-state kinds' median / max at the outage
ends (phone grade), then whether the drive reader warned of spikes. Run with the package at ``ROOT``, one BLAS
thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/spikes.py ROOT NAMES

(``spikes.txt``: on 7590cf0, read as logged, then on stop 50's reader, which interpolates a sample that leaves
both its neighbours and comes back faster than a car can: over 1 g of acceleration, or of lateral acceleration
at its speed.)
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
KINDS = ("DR-mech", "EKF-8", "UKF-8", "SUKF-8")

with tempfile.TemporaryDirectory() as tmp:
    for name in sys.argv[2].split(","):
        for seed in (0, 1, 2):
            c = held_out.columns(name, seed)
            k = np.random.default_rng([50, 7, seed]).choice(np.flatnonzero(c["speed"] > 3.0), 20, replace=False)
            for case in ("clean", "speed spikes", "heading spikes"):
                cols = dict(c)
                if case == "speed spikes":
                    cols["speed"] = c["speed"].copy()
                    cols["speed"][k] = 70.8  # 255 km/h
                elif case == "heading spikes":
                    cols["heading"] = c["heading"].copy()
                    cols["heading"][k] = np.mod(c["heading"][k] + np.pi / 2, 2 * np.pi)
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
                said = [str(w.message).split(" sample(s)")[0] for w in caught if "spikes (" in str(w.message)]
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
                cells = [f"{q} {np.median(res[q]):.2f} / {res[q].max():.2f}" for q in KINDS]
                print(f"{name} {seed} {case:14s} | " + " | ".join(cells)
                      + f" | spikes warned: {', '.join(said) or 'none'}", flush=True)
