"""The three worst outages of the two variants of ``phone_fixes.py`` that miss their target (stop 57).

    python docs/study-outputs/dr/recorded-motion/worst_outages.py > docs/study-outputs/dr/recorded-motion/worst_outages.txt

For each (phone seed 8, city seed 3): the outage's number and start, the metres driven in it, the EKF-8's error
when it starts and when it ends, and dead reckoning's from the true start at its end (m).
"""
import pathlib
import sys
import tempfile
import warnings

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parents[3] / "tests")]
import _held_out_drives as held_out  # noqa: E402
import phone_fixes as pf  # noqa: E402
from filterwnn.navigation.drives import load_car_drive, read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

warnings.simplefilter("ignore")
run = load_car_drive(pf.DRIVE)
for name, seed in [("phone", 8), ("city", 3)]:
    rng = np.random.default_rng(np.random.SeedSequence([23, 57, list(pf.TARGETS).index(name), seed]))
    with tempfile.TemporaryDirectory() as d:
        drive = read_drive_csv(held_out.write_csv(pathlib.Path(d) / "d.csv", pf.variant(run, name, rng)))
        res = real_drive_outages(drive, filters=("DR-mech", "EKF-8"), grade="phone", use_gps_sigma=True)
    e, s = np.asarray(res["EKF-8"]), np.asarray(res["start_err"]["EKF-8"])
    for i in np.argsort(e)[::-1][:3]:
        print(f"{name} {seed} outage {i + 1} at {res['starts'][i]:.0f} s, moved {res['moved'][i]:.0f} m: start "
              f"{s[i]:.2f}, end {e[i]:.2f}, DR {np.asarray(res['DR-mech'])[i]:.2f}", flush=True)
