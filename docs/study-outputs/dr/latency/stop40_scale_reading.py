"""What the scale monitor alone (stop 40's code, before the joint test) made of fixes stamped late: one EKF pass
(phone grade) over the 1 Hz and phone analogs (seeds 0, 1) with the fixes 0.5 s and 1 s late; its estimate and
z-score at the end, and the step at which it added a scale state. Run against a checkout of e294294:

    PYTHONPATH=<checkout of e294294> OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/latency/stop40_scale_reading.py
"""
import os
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "tests"))
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.dead_reckoning import GPSDRModel  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.navigation.gpsdr import GPSDRFilter  # noqa: E402

with tempfile.TemporaryDirectory() as tmp:
    for name in ("one_hz", "phone"):
        for seed in (0, 1):
            for tau in (0.5, 1.0):
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"),
                                                            held_out.columns(name, seed, gps_latency=tau)))
                    m = GPSDRModel.from_grade("phone", run.scenario.dt)
                    f = GPSDRFilter(m, "ekf", x0=np.r_[run.x0, m.x0[6:]])
                    f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
                print(f"{name} seed {seed}, fixes {tau:g} s late | scale estimate {100 * f.gyro_scale_estimate:+.2f} % "
                      f"z {f.gyro_scale_z:+.2f} | scale state added at step {f.gyro_scale_added}"
                      + ("" if f.gyro_scale_added is None else f", its last value {100 * f.x[9]:+.2f} %"), flush=True)
