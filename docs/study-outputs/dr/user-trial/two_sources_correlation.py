"""Two sources taking turns in one column hide their correlation from the filter (stop 73): the sixth trial's
``dualrx_clean`` (two receivers at alternate half seconds, the same error process each) against ``smoothed_clean``
(one receiver's fixes at 1 Hz, the same errors), phone grade, the EKF-8 run whole as the command starts it.

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/user-trial/two_sources_correlation.py > docs/study-outputs/dr/user-trial/two_sources_correlation.txt

Per 10 s of the first 150 s of ``dualrx_clean``: ``gps_correlation`` and the lag-one and lag-two autocorrelations of
the whiteness window's whitened innovations (east component); then, per drive, the share of the fixes at which
``gps_correlation`` reads 1 and its median.
"""
import os
import subprocess
import sys
import tempfile
import warnings

import numpy as np

from filterwnn.navigation import GPSDRFilter, GPSDRModel
from filterwnn.navigation.drives import read_drive_csv

HERE = os.path.dirname(os.path.abspath(__file__))


def run(path, trace=False):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        drive = read_drive_csv(path, progress=False)
        model = GPSDRModel.from_grade("phone", dt=drive.scenario.dt)
        P0 = model.P0.copy()
        P0[0, 0] = P0[3, 3] = 1.0
        f = GPSDRFilter(model, x0=np.r_[drive.x0, model.x0[6:]], P0=P0)
        cs = []
        for k, (z, fix, s) in enumerate(zip(drive.z_dr, drive.gps_list(), drive.gps_sigma_list())):
            f.predict()
            f.update(z, fix, s)
            if fix is not None:
                cs.append(f.gps_correlation)
            if trace and k % 100 == 99 and 30 <= drive.t[k] <= 150:
                a = np.array([u for u in f._white if u is not None])[:, 0]
                r1, r2 = (np.corrcoef(a[:-m], a[m:])[0, 1] for m in (1, 2))
                print(f"t {drive.t[k]:4.0f} s: gps_correlation {f.gps_correlation:5.1f}, lag one {r1:+.2f}, "
                      f"lag two {r2:+.2f}")
    cs = np.array(cs)
    print(f"{os.path.basename(path)}: gps_correlation 1 at {np.mean(cs == 1.0):.0%} of {len(cs)} fixes, median "
          f"{np.median(cs):.2f}, mean {np.mean(cs):.2f}")


with tempfile.TemporaryDirectory() as folder:
    subprocess.run([sys.executable, os.path.join(HERE, "gen_drives_6.py"), folder], check=True, capture_output=True)
    run(os.path.join(folder, "dualrx_clean.csv"), trace=True)
    run(os.path.join(folder, "smoothed_clean.csv"))
