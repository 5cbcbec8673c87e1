"""Why protocol 2's seed 221 splits the kinds (stop 56; RUN.md): UKF-8 and SUKF-8 over the whole drive with every
fix (phone grade, as the command sets them), at each fix from T0 to T1 s: the error against the truth (m), the
speed, the heading bias and the gyro rate bias (deg, deg/s) against the truth's (``thb``: the drawn offset plus the
rate bias times t), their sigmas, ``gps_correlation`` after the fix, the counts (rejected, down-weighted,
re-acquired, heading jumps, calibration-off fixes) and the fix's NIS. Run from the repository root::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/split_221.py 2 221 UKF-8,SUKF-8 10 140 > docs/study-outputs/dr/random-drives/split_221.txt
"""
import os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", "..", ".."))
sys.path[:0] = [HERE, ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr"]
import random_drives
from drive_sets import read
from filterwnn.studies.dr._real import _real_drive_filter, REAL_MODEL
proto, seed = int(sys.argv[1]), int(sys.argv[2]); kinds = sys.argv[3].split(","); t0, t1 = float(sys.argv[4]), float(sys.argv[5])
d, cols, _ = random_drives.drive(seed, proto)
run = read(tempfile.mkdtemp(), cols)
print(random_drives.describe(d, proto))
gps, sig, offs = run.gps_list(), run.gps_sigma_list(), run.gps_offset_list()
tr = run.x_true
warnings.simplefilter("ignore")
out = {}
cnt = ("n_rejected", "n_downweighted", "n_reacquired", "n_heading_jumps", "n_calibration_error")
for name in kinds:
    f = _real_drive_filter(name, run, "phone", None, dict(REAL_MODEL), 0, None)
    rows = []
    for k in range(len(run.t)):
        f.predict(); f.update(run.z_dr[k], gps[k], sig[k], offs[k])
        if gps[k] is not None and t0 <= run.t[k] <= t1:
            rows.append((run.t[k], np.hypot(*(f.x[[0, 3]] - tr[k, [0, 3]])), np.hypot(f.x[1], f.x[4]), np.degrees(f.x[7]), np.degrees(f.x[8]),
                         np.degrees(np.sqrt(f.P[7, 7])), np.degrees(np.sqrt(f.P[8, 8])), getattr(f, "gps_correlation", 0), [getattr(f, c, -1) for c in cnt], float(f.nis)))
    out[name] = rows
print("t (s), true speed, true heading bias | per kind: error, speed, heading bias, rate bias, their sigmas, gps_correlation, counts, NIS")
for i in range(len(out[kinds[0]])):
    r0 = out[kinds[0]][i]
    tt = r0[0]; true_hb = d["offset"] + d["rate_bias"] * tt
    print(f"{tt:6.0f} v {np.hypot(tr[int(round(tt/d['dt'])),1], tr[int(round(tt/d['dt'])),4]):5.1f} thb {true_hb:+5.2f} | " + " || ".join(
        "e {:5.1f} v {:5.1f} hb {:+6.2f} rb {:+.3f} sd {:.2f} {:.3f} c {:4.1f} {} nis {:.1f}".format(*out[k][i][1:8], out[k][i][8], out[k][i][9]) for k in kinds))
