"""The scale-error monitor on the shipped sample (phone grade, each kind), the hard bench (each drive's grade)
and onavdata's recorded drives (survey grade: since the monitor needs a rate-bias state, this calls it on a
model without one only through the code of the commit that ran it, see RUN.md). EKF unless named.

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/gyro-scale/monitor_other.py
"""
import os, sys, warnings
_T = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "tests")
sys.path[:0] = [_T, os.path.join(_T, "navigation")]
import numpy as np
from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive, read_drive_csv, sample_drive_path
from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.gpsdr import GPSDRFilter
import test_hard_drives as th
def go(label, run, grade, kind="ekf"):
    m = GPSDRModel.from_grade(grade, run.scenario.dt)
    f = GPSDRFilter(m, kind, x0=np.r_[run.x0, m.x0[6:]])
    sig = run.gps_sigma_list() if run.gps_sigma is not None else [None] * len(run.z_dr)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        zs = []
        for k in range(len(run.z_dr)):
            f.predict(); f.update(run.z_dr[k], run.gps_list()[k], sig[k])
            if f.gyro_scale_z is not None: zs.append(f.gyro_scale_z)
    said = [str(x.message)[:120] for x in w if "scale factor error" in str(x.message)]
    print(label, kind, "final est", None if f.gyro_scale_estimate is None else f"{100*f.gyro_scale_estimate:+.2f} %", "max |z|", round(max(map(abs, zs)), 1) if zs else None, said[:1], flush=True)
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    sample = read_drive_csv(sample_drive_path())
for kind in ("ekf", "ukf", "sukf"):
    go("sample", sample, "phone", kind)
for d in th.DRIVES:
    run, grade, first = d(np.random.default_rng(np.random.SeedSequence([23, th.DRIVES.index(d)])))
    go(d.__name__, run, grade)
for name in CAR_DRIVES:
    go(name, load_car_drive(name), "survey")
