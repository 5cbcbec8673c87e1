"""A car that reverses 14 m inside a 45 s outage (tests/navigation/test_drives.py's drive): each 8-state kind,
phone grade, with the signed speed (read as reversing), with the car standing instead, and with the unsigned
speed (the remedy the reader once asked for); the error at the outage's end (m).

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/reversing.py > docs/study-outputs/dr/log-faults/reversing.txt
"""
import os
import sys
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "tests", "navigation"))
from test_drives import _reversing_drive  # noqa: E402

from filterwnn import GPSDRFilter  # noqa: E402
from filterwnn.navigation.dead_reckoning import GPSDRModel  # noqa: E402
from filterwnn.navigation.scenarios import DRRun, with_outage  # noqa: E402

t, v, e, fix, noise = _reversing_drive()
for label, speed, truth_speed in (("signed speed (reversing)", v, v), ("the car stands instead", np.maximum(v, 0), np.maximum(v, 0)),
                                  ("unsigned speed", np.abs(v), v)):
    ee = np.r_[0.0, np.cumsum(truth_speed[1:] * 0.1)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = DRRun.from_arrays(t, np.full(len(t), np.pi / 2), speed=speed, gps_t=t[fix], east=ee[fix] + noise[fix, 0],
                                north=noise[fix, 1], gps_sigma=3.0, truth=np.stack([ee, 0 * ee], 1))
    cells = []
    for kind in ("ekf", "ukf", "sukf"):
        r = with_outage(run, start=25.0, length=45.0)
        m = GPSDRModel.from_grade("phone", r.scenario.dt)
        f = GPSDRFilter(m, kind, x0=np.r_[r.x0, m.x0[6:]])
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            est = f.batch_filter(r.z_dr, r.gps_list(), r.gps_sigma_list())
        k = np.searchsorted(r.t, 70.0) - 1
        cells.append(f"{kind.upper()}-8 {np.hypot(est[k, 0] - r.x_true[k, 0], est[k, 3] - r.x_true[k, 3]):.2f}")
    print(f"{label} | " + " | ".join(cells), flush=True)
