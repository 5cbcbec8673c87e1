"""The scale-error monitor on the held-out analogs (seeds given, default 0-4) with gyro scale errors of 0, 1 %,
3 % and -2 %: one EKF pass (phone grade: a rate-bias state, no scale state) over each whole drive with every
fix; its estimate, z-score and mean gps_correlation at the end, and the step at which it warned.

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/gyro-scale/monitor.py ekf 0,1,2
"""
import os, sys, tempfile, warnings
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "tests"))
import numpy as np
import _held_out_drives as h
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.gpsdr import GPSDRFilter
tmp = tempfile.mkdtemp()
kind = sys.argv[1] if len(sys.argv) > 1 else "ekf"
seeds = [int(s) for s in (sys.argv[2] if len(sys.argv) > 2 else "0,1,2,3,4").split(",")]
for name in ("phone", "city", "one_hz"):
    for seed in seeds:
        for err in (0.0, 0.01, 0.03, -0.02):
            path = h.write_csv(os.path.join(tmp, "d.csv"), h.columns(name, seed, gyro_scale=err))
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                run = read_drive_csv(path)
            m = GPSDRModel.from_grade("phone", run.scenario.dt)
            f = GPSDRFilter(m, kind, x0=np.r_[run.x0, m.x0[6:]])
            with warnings.catch_warnings(record=True) as w:
                warnings.simplefilter("always")
                for k in range(len(run.z_dr)):
                    f.predict(); f.update(run.z_dr[k], run.gps_list()[k], run.gps_sigma_list()[k])
            said = [str(x.message) for x in w if "scale factor error" in str(x.message)]
            step = said[0].split("by step ")[1].split(" ")[0] if said else "-"
            print(f"{name} seed {seed} error {err:+.2f}: estimate {100*f.gyro_scale_estimate:+.2f} % z {f.gyro_scale_z:+.1f} corr {f.gps_correlation_mean:.1f} warned at {step}", flush=True)
