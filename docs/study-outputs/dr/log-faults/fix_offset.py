"""Fixes logged between the DR samples of a 1 Hz log (issue 23, stop 49).

``DRRun.from_arrays`` (and the drive reader, for a log with a row per sensor message) places each fix on the DR
sample nearest its time and uses it as the position at that sample. At 1 Hz that is up to 0.5 s off, and a
``gps_latency`` below 0.5 s moves no fix. The 1 Hz analog of ``tests/_held_out_drives.py``, seeds 0-2, each fix
the truth at its own time (linearly interpolated between the samples) plus the analog's own fix error:

* ``on rows``: each fix at its sample's time (the analog as it is);
* ``+0.4 s``: each fix 0.4 s after its sample;
* ``scattered``: each fix U(-0.5, 0.5) s from its sample;
* ``0.3 s late, read at 0.3``: each fix the truth 0.3 s before its sample's time, read with ``gps_latency=0.3``.

Each line, per 8-state kind, the median / max at the outage ends (``filterwnn study dr``'s scoring, phone grade)
and the step at which each kind added its latency state. Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/fix_offset.py ROOT

(``fix_offset.txt``: on 59b7460, each fix used as the position at its sample's time, then on stop 49's code,
which keeps each fix's offset from its sample, ``DRRun.gps_offset``, and moves the fix back along the filter's
velocity, ``GPSDRFilter.update(gps_offset=)``.)
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
    for case, offset, latency in (("on rows", 0.0, 0.0), ("+0.4 s", 0.4, 0.0), ("scattered", scattered, 0.0),
                                  ("0.3 s late, read at 0.3", 0.0, 0.3)):
        gps_t = t[rows] + offset  # each fix stamped here, the truth at gps_t - latency
        east = np.interp(gps_t - latency, t, base["true_east"]) + err[:, 0]
        north = np.interp(gps_t - latency, t, base["true_north"]) + err[:, 1]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = DRRun.from_arrays(t, base["heading"], speed=base["speed"], gps_t=gps_t, east=east, north=north,
                                    gps_sigma=base["gps_sigma"][rows], gps_latency=latency,
                                    truth=np.stack([base["true_east"], base["true_north"]], axis=1))
            res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
        cells = [f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in KINDS]
        added = [res["integrity"][k]["latency_added"] for k in KINDS]
        print(f"one_hz {seed} {case:>23} | " + " | ".join(cells) + f" | latency state added at {added}", flush=True)
