"""A fifth response to a found heading step, tried and not kept (issue 23, stop 47; ``RUN.md``): widen the
position too, by what the step left in it (the onset's position sensitivity times the step), beside the heading
bias. Stop 46's table of responses, its rows, with the default (widened) and this variant.

The variant is one line of ``GPSDRFilter._take_jump`` (on 1cacb54)::

    -        self._widen((HEADING_BIAS,), (theta,))
    +        pos = self._js[[0, 3], j] * theta
    +        self._widen((0, 3, HEADING_BIAS), (pos[0], pos[1], theta))

Run from the repository root of a copy with it (and of one without), one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/jump_position.py COPY

(``jump_position.txt``: without, then with, line by line.) The criterion, fixed before the numbers were read:
taken if phone seed 2's 5 degree step no longer ends past its maximum without the detector (73.27 m), and no
other row's median or maximum is worse than the default's by more than 0.5 m.
"""
import os, sys, tempfile, warnings
import numpy as np
ROOT = sys.argv[1]
sys.path.insert(0, ROOT); sys.path.insert(0, os.path.join(ROOT, "tests")); sys.path.insert(0, os.path.join(ROOT, "docs/study-outputs/dr/log-faults"))
import _held_out_drives as held_out
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation import gpsdr
from filterwnn.studies.dr import real_drive_outages
import heading_jump as hj
assert gpsdr.__file__.startswith(ROOT)
rows = [("phone", 16, "none", 0, "EKF-8"), ("phone", 16, "none", 0, "UKF-8"), ("phone", 2, "step", 5.0, "EKF-8"),
        ("phone", 1, "step", 5.0, "EKF-8"), ("phone", 2, "drift", 0.05, "EKF-8"), ("one_hz", 0, "drift", 0.05, "EKF-8"),
        ("one_hz", 24, "none", 0, "SUKF-8")]
with tempfile.TemporaryDirectory() as tmp:
    for name, seed, fault, size, kind in rows:
        c, at = hj.faulted(held_out.columns(name, seed), fault, size)
        run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), c))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=(kind,), use_gps_sigma=True, grade="phone")
        e = res[kind]
        print(name, seed, fault, size, kind, f"{np.median(e):.2f} / {e.max():.2f}", res["integrity"][kind]["n_heading_jumps"], flush=True)
