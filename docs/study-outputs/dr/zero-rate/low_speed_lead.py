"""A lead for the next stop, not shipped (issue 23): the calibration's low-speed gate at 2.5 m/s instead of 5.

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/zero-rate/low_speed_lead.py city 0,1,2,10
    python docs/study-outputs/dr/zero-rate/low_speed_lead.py phone,one_hz 0,1

``GPSDRFilter(low_speed=...)`` sets both the speed under which a DR sample enters as a velocity vector
and the speed above which the calibration learns from fixes. The city analog drives at 3-10 m/s, so
its heading bias learns rarely (sigma 12-14 deg on seed 10). EKF-8, phone grade, scored as
``filterwnn study dr --drive FILE --grade phone``: median / max at the outage ends and the median
error at the outage starts (m). The script sets the default in memory; nothing here is used by the
package.
"""
import os, sys, tempfile, warnings, numpy as np
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]
import _held_out_drives as held_out
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation import gpsdr
from filterwnn.studies.dr import real_drive_outages
tmp = tempfile.mkdtemp()
names = sys.argv[1].split(","); seeds = [int(s) for s in sys.argv[2].split(",")]
for name in names:
    for seed in seeds:
        run = read_drive_csv(held_out.write_csv(os.path.join(tmp, f"d{os.getpid()}.csv"), held_out.columns(name, seed)))
        cells = []
        for ls in (5.0, 2.5):
            gpsdr.GPSDRFilter.__init__.__kwdefaults__["low_speed"] = ls
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone")
            cells.append(f"low_speed {ls}: {np.median(res['EKF-8']):.2f}/{res['EKF-8'].max():.2f} start {np.median(res['start_err']['EKF-8']):.2f}")
        print(name, seed, " | ".join(cells), flush=True)
