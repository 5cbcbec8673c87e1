"""The stops each analog drive gives the gyro rate bias (issue 23): used, rejected, re-acquisitions, held.

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/zero-rate/stops_per_seed.py > docs/study-outputs/dr/zero-rate/stops_per_seed.txt

Per analog and seed 0-29, the phone grade's EKF-8 over the whole drive with every fix (as the drive
table's integrity counts are taken): ``name seed used rejected re-acquired held``. Where the
re-acquired count is 0 (three stops in a row the state could not follow, rejected or held at the
calibration bound, never came), the re-acquisition cannot change any number.
"""
import os, sys, tempfile, warnings
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]
import _held_out_drives as held_out
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.studies.dr._real import _real_drive_filter, REAL_MODEL
tmp = tempfile.mkdtemp()
for name in ("phone", "city", "one_hz"):
    for seed in range(30):
        run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed)))
        f = _real_drive_filter("EKF-8", run, "phone", None, dict(REAL_MODEL), 0, None)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
        print(name, seed, f.n_zero_rate, f.n_zero_rate_rejected, f.n_zero_rate_reacquired, f.n_zero_rate_held, flush=True)
