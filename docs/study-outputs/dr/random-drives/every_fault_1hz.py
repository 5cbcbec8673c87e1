"""The 1 Hz analog with seven faults at once (stop 56; ``tests/navigation/test_held_out_drives.py``'s
``_every_fault``, the fixes 0.5 s late and the gyro 2 % off): each 8-state kind's median / max at the outage ends (m),
scored as the command does (phone grade), and the warnings that name the car reversing or the gyro's scale. Run with
the package at ``ROOT`` (the drive is this checkout's), one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/every_fault_1hz.py ROOT
"""
import os
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TESTS = os.path.abspath(os.path.join(HERE, "..", "..", "..", "..", "tests"))
sys.path[:0] = [os.path.abspath(sys.argv[1]), TESTS, os.path.join(TESTS, "navigation")]
import _held_out_drives as held_out  # noqa: E402
from test_held_out_drives import _every_fault  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

assert read_drive_csv.__code__.co_filename.startswith(os.path.abspath(sys.argv[1]))
cols = _every_fault(held_out.columns("one_hz", 0, gps_latency=0.5, gyro_scale=0.02), np.random.default_rng(56))
kinds = ("DR-mech", "EKF-8", "UKF-8", "SUKF-8")
with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
    res = real_drive_outages(run, filters=kinds, grade="phone", use_gps_sigma=True)
print(" | ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in kinds))
for w in caught:
    text = str(w.message)
    if "measured heading is" in text or "the gyro's scale" in text or "jump away" in text:
        print("  " + text[:170])
