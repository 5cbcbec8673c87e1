"""A grade more pessimistic than the DR sensors: would lowering its noise help? (stop 69)

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/dr-noise/pessimistic_grade.py > docs/study-outputs/dr/dr-noise/pessimistic_grade.txt

The online estimate of stop 68 (``GPSDRFilter(dr_noise_window=100)``) only raises a DR sensor's noise: where the
grade says more than the sensor has (onavdata's heading under the survey grade: a window NIS ratio of 0.06-0.07,
``dr_noise.txt`` part C) nothing is lowered and nothing is said. This measures what lowering would give, with the
noise given by hand (``heading_noise_deg``), the estimate on as shipped:

A. onavdata's two drives, survey grade (0.2 degrees), ``filterwnn study dr --real``'s protocol (20 outages of 30 s,
   each fix's own sigma): the heading noise at the grade's 0.2 degrees and at 0.1, 0.05 and 0.02 (the sensor's own,
   from the ratio: about 0.05); every 8-state kind, median / max at the outage ends (m).
B. The three analogs of issue 23's drives (seeds 0-2, ``tests/_held_out_drives.py``), phone grade (0.5 degrees): at
   the grade's 0.5 and at 0.3 (the analogs' own white heading noise) and 0.15; the EKF-8.
"""

import os
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "..", "tests"))

import _held_out_drives as H  # noqa: E402

from filterwnn.navigation.dead_reckoning import SENSOR_GRADES  # noqa: E402
from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive, read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

warnings.simplefilter("ignore")
KINDS = ("EKF-8", "UKF-8", "SUKF-8")


def line(run, grade, degrees, kinds, use_gps_sigma):
    g = dict(SENSOR_GRADES[grade], heading_noise_deg=degrees)
    out = real_drive_outages(run, filters=kinds, grade=g, use_gps_sigma=use_gps_sigma)
    return " | ".join(f"{k} {np.median(out[k]):.2f} / {np.max(out[k]):.2f}" for k in kinds)


print("A. onavdata, survey grade (0.2 deg): heading noise given (deg) -> median / max at the outage ends (m)")
for name in CAR_DRIVES:
    run = load_car_drive(name)
    for degrees in (0.2, 0.1, 0.05, 0.02):
        print(f"{name} {degrees:.2f} deg | {line(run, 'survey', degrees, KINDS, True)}", flush=True)

print("\nB. the analogs (seeds 0-2), phone grade (0.5 deg): heading noise given (deg) -> EKF-8 median / max (m)")
with tempfile.TemporaryDirectory() as folder:
    for drive in ("phone", "city", "one_hz"):
        for seed in (0, 1, 2):
            path = H.write_csv(os.path.join(folder, f"{drive}{seed}.csv"), H.columns(drive, seed))
            run = read_drive_csv(path)
            cells = [f"{d:.2f} deg {line(run, 'phone', d, ('EKF-8',), run.gps_sigma is not None)}" for d in (0.5, 0.3, 0.15)]
            print(f"{drive} seed {seed} | " + " | ".join(cells), flush=True)
