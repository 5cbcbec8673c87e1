"""The phone grade's EKF-8 with and without its gyro rate-bias state, on the analogs of seeds 0-9 (issue 23).

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/analog-seeds/rate_bias_off.py phone
    python docs/study-outputs/dr/analog-seeds/rate_bias_off.py city

The issue saw, on its recorded phone drive, the filter end outages at twice dead reckoning's
error with the rate-bias state and at 9.9 / 30.7 m without it (the state took GPS noise for
calibration). Here each analog is scored as ``filterwnn study dr --drive FILE --grade phone``
scores it (median / max at the outage ends, m): the grade as it is (rate bias on), and with
``rate_bias=False``.
"""
import os, sys, tempfile, warnings
import numpy as np
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]
import _held_out_drives as held_out
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.studies.dr import real_drive_outages
tmp = tempfile.mkdtemp()
name = sys.argv[1]
for seed in range(10):
    run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed)))
    cells = []
    for mk in (None, {"rate_bias": False}):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone", model_kwargs=mk)
        cells.append(f"{np.median(res['EKF-8']):.2f}/{res['EKF-8'].max():.2f}")
    print(name, seed, "rate-bias on", cells[0], "off", cells[1], flush=True)
