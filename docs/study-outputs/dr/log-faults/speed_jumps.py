"""Heading steps found where there is none, on drives whose speed is stamped late (issue 23, stop 48).

A speed sample ``odometer_latency`` s late moves the dead-reckoned car along its track at each start and stop.
The consistency monitor tells it (the speed's latency, with its remedy), but the heading-jump detector tests
its onsets without it among the nuisance parameters, and takes part of it for steps. The analogs
of ``tests/_held_out_drives.py``, seeds 0-2, the speed 0.5 s late, 0.5 s early and 1 s late; each line, per
8-state kind, the median / max at the outage ends (``filterwnn study dr --drive FILE --grade phone``'s scoring)
and the steps found (estimate in degrees @ onset step). Every step found is a false alarm.

Run with the package at ``ROOT`` (a copy of the repository), one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/speed_jumps.py ROOT

(``speed_jumps.txt``: the package, then with ``speed_jumps_variant.patch`` applied to a copy: the onsets tested
with the speed's latency among their nuisance parameters; ``speed_jumps_variant_heading_jump.txt``: criterion
(2)'s runs with it.) The criterion, fixed before the variant's numbers were read (stop 36's way): kept if (1) here, fewer steps are found in all than before (15); (2) on
``heading_jump.py``'s faults (steps of 2, 5 and 10 degrees and a drift, every analog, seeds 0-2) no kind's
median or maximum is worse by more than 0.5 m, and every line that found a step still finds one; (3) on
``jump_false_alarms_analogs.py`` (seeds 0-49, no fault) no more steps are found in all and no fewer seeds meet
the targets; (4) the recorded drives stay within the issue's bounds.
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
    for lat in (0.5, -0.5, 1.0):
        for name in ("phone", "city", "one_hz"):
            for seed in (0, 1, 2):
                cols = held_out.columns(name, seed, odometer_latency=lat)
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
                cells = []
                for k in KINDS:
                    e, ig = res[k], res["integrity"][k]
                    cells.append(f"{k} {np.median(e):.2f} / {e.max():.2f} ({ig['n_heading_jumps']} jumped"
                                 + "".join(f" {np.degrees(j[2]):+.2f}@{j[1]}" for j in ig["heading_jumps"]) + ")")
                print(f"{name} {seed} speed {lat:+g} s | " + " | ".join(cells), flush=True)
