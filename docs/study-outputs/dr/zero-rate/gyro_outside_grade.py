"""A gyro outside its grade (stop 35, issue 23): the phone and 1 Hz analogs of seed 0 with a rate bias of
0.3 or 0.7 deg/s, run with the phone grade (0.05 deg/s; its calibration bound three prior sigmas, 0.15).

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/zero-rate/gyro_outside_grade.py phone,one_hz 0.3,0.7 > docs/study-outputs/dr/zero-rate/gyro_outside_grade.txt

Per drive: dead reckoning alone from the true start, and the EKF-8 (median / max at the ends of the 20
outages of 30 s, as ``filterwnn study dr --drive FILE --grade phone`` scores it) with the stops'
re-acquisition (``zero_rate_reacquire_after=3``, the default) and without (0); the stops used / rejected /
re-acquisitions, and how many warning lines the filter gave (one per kind: the study folds repeats). The
analogs are drawn with the gyro's rate bias changed (``columns(name, 0, rate_bias=...)``, the same draws); nothing here is used by the package.
"""
import os, sys, tempfile, warnings, numpy as np
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]
import _held_out_drives as h
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation import gpsdr
from filterwnn.studies.dr import real_drive_outages
tmp = tempfile.mkdtemp()
for name in sys.argv[1].split(","):
  for bias in [float(b) for b in sys.argv[2].split(",")]:
    run = read_drive_csv(h.write_csv(os.path.join(tmp, "d.csv"), h.columns(name, 0, rate_bias=bias)))
    cells = []
    for n in (3, 0):
        gpsdr.GPSDRFilter.__init__.__kwdefaults__["zero_rate_reacquire_after"] = n
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            res = real_drive_outages(run, filters=("DR-mech", "EKF-8"), use_gps_sigma=True, grade="phone")
        ig = res["integrity"]["EKF-8"]
        msgs = sorted({str(x.message)[:60] for x in w})
        cells.append(f"reacq {n}: EKF-8 {np.median(res['EKF-8']):.2f}/{res['EKF-8'].max():.2f} stops {ig['n_zero_rate']}/{ig['n_zero_rate_rejected']}/{ig['n_zero_rate_reacquired']} warns {len(msgs)}")
    print(name, bias, f"DR {np.median(res['DR-mech']):.2f}/{res['DR-mech'].max():.2f}", " | ".join(cells), flush=True)
