"""A drive scored without a truth, its fixes between the DR samples (issue 23, stop 50).

Without a truth, ``real_drive_outages`` (``filterwnn study dr --drive``) scores each outage end against the last
fix withheld in it, so the score includes that fix's own error. Since stop 49 a fix logged between the samples of a
slow log keeps its time less its sample's (``DRRun.gps_offset``) and the filters move it back along their velocity;
the score's reference did not: at 1 Hz a fix 0.4 s after its sample is 4-6 m ahead of the position there at
10-15 m/s. (Moving it back along the dead reckoning's velocity was tried first: with the 1 Hz analog's MEMS gyro
the raw heading drifts by tens of degrees, and seed 2's maxima stayed 15.2-15.5 m.)

The 1 Hz analog of ``tests/_held_out_drives.py``, seeds 0-2, each fix the truth at its own time (linearly
interpolated between the samples) plus the analog's own fix error, its fixes at the samples' times (``on rows``),
0.4 s after them (``+0.4 s``) or U(-0.5, 0.5) s from them (``scattered``); each scored with its truth and without
it (the truth dropped). Each line, per 8-state kind, the median / max at the outage ends (phone grade). Run with
the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/no_truth_offset.py ROOT

(``no_truth_offset.txt``: on 1ff168e, the reference fix as logged, then on stop 50's, which takes the fixes' track
at the sample's time, the fixes at their own times interpolated.)
"""
import os
import sys
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.scenarios import DRRun  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

assert real_drive_outages.__code__.co_filename.startswith(ROOT)
KINDS = ("EKF-8", "UKF-8", "SUKF-8")
for seed in range(3):
    base = held_out.columns("one_hz", seed)
    rows = np.flatnonzero(~np.isnan(base["gps_east"]))
    t = base["time"]
    err = np.stack([base["gps_east"][rows] - base["true_east"][rows],
                    base["gps_north"][rows] - base["true_north"][rows]], axis=1)
    scattered = np.random.default_rng([49, seed]).uniform(-0.5, 0.5, len(rows))
    for case, offset in (("on rows", 0.0), ("+0.4 s", 0.4), ("scattered", scattered)):
        gps_t = t[rows] + offset
        east = np.interp(gps_t, t, base["true_east"]) + err[:, 0]
        north = np.interp(gps_t, t, base["true_north"]) + err[:, 1]
        for truth in (True, False):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                run = DRRun.from_arrays(t, base["heading"], speed=base["speed"], gps_t=gps_t, east=east, north=north,
                                        gps_sigma=base["gps_sigma"][rows],
                                        truth=np.stack([base["true_east"], base["true_north"]], axis=1) if truth
                                        else None)
                res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
            cells = [f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in KINDS]
            print(f"one_hz {seed} {case:>9} {res['reference']:>12} | " + " | ".join(cells), flush=True)
