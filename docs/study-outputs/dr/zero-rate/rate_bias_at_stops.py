"""What the stops teach the gyro rate bias on the analogs (issue 23): the state at the end of each drive.

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/zero-rate/rate_bias_at_stops.py > docs/study-outputs/dr/zero-rate/rate_bias_at_stops.txt

Each analog of ``tests/_held_out_drives.py`` (seed 0, and phone seed 16) is run once over the whole
drive with its fixes by the phone grade's EKF-8 (``GPSDRFilter`` defaults): the stops used, rejected
and held, and the rate-bias state and its sigma at the end (deg/s) against the analog's true rate bias.
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.dead_reckoning import GPSDRModel  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.navigation.gpsdr import GPSDRFilter  # noqa: E402

TRUE_RATE = {"phone": 0.005, "city": 0.015, "one_hz": 0.05}  # deg/s, as tests/_held_out_drives.py draws them

with tempfile.TemporaryDirectory() as tmp:
    for name, seed in (("phone", 0), ("phone", 16), ("city", 0), ("one_hz", 0)):
        run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed)))
        m = GPSDRModel.from_grade("phone", run.scenario.dt)
        f = GPSDRFilter(m, "ekf", x0=np.r_[run.x0, m.x0[6:]])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            est = f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
        print(f"{name} seed {seed}: stops used {f.n_zero_rate}, rejected {f.n_zero_rate_rejected}, held "
              f"{f.n_zero_rate_held}; rate bias at the end {np.rad2deg(est[-1, 8]):.4f} +- "
              f"{np.rad2deg(np.sqrt(f.P[8, 8])):.4f} deg/s (true {TRUE_RATE[name]})")
