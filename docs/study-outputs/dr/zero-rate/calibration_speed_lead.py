"""Tried and dropped (issue 23): the calibration's speed gate at 2.5 m/s, the DR sample's form kept at 5.

``low_speed_lead.py`` moved ``GPSDRFilter(low_speed=...)``, which decides both the DR sample's form and
the speed above which the calibration learns from fixes. This script moves only the calibration's gate
(the filter's ``_held_rows`` and ``classify`` patched in memory by ``calibration_gate.py``; nothing here is
used by the package).
Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/zero-rate/calibration_speed_lead.py recorded
    python docs/study-outputs/dr/zero-rate/calibration_speed_lead.py city 0,10

EKF-8, median / max at the outage ends (m): the recorded drives with the survey grade (their scored
setting), the analogs with the phone grade.
"""
import os, sys, tempfile, warnings, numpy as np
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]
import _held_out_drives as held_out
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation import drives as d
from filterwnn.studies.dr import real_drive_outages
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from calibration_gate import GATE as CAL, patch  # the calibration's gate, moved in memory
patch()
tmp = tempfile.mkdtemp()
what = sys.argv[1]
vals = [float(v) for v in sys.argv[3].split(",")] if len(sys.argv) > 3 else [5.0, 2.5]
def score(run, grade, kinds):
    out = []
    for c in vals:
        CAL[0] = c
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            res = real_drive_outages(run, filters=kinds, use_gps_sigma=True, grade=grade)
        out.append(f"cal {c}: " + " ".join(f"{k} {np.median(res[k]):.2f}/{res[k].max():.2f}" for k in kinds))
    return " | ".join(out)
if what == "recorded":
    for name in d.CAR_DRIVES:
        print(name, score(d.load_car_drive(name), "survey", ("EKF-8",)), flush=True)
else:
    for name in what.split(","):
        for seed in [int(s) for s in sys.argv[2].split(",")]:
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, f"d{os.getpid()}.csv"), held_out.columns(name, seed)))
            print(name, seed, score(run, "phone", ("EKF-8",)), flush=True)
