"""EKF-8 (phone grade, default outages) on one drive of ``run_sensor_faults.sh`` with the zero-velocity
update's sigma set to ``SIGMA`` m/s (the grade's is 0.01): median / max at the outage ends (m).

Usage: ``python zupt_sigma.py DRIVES_DIR DRIVE SIGMA`` (e.g. ``/tmp/sensor-faults/drives phone_crawl 0.46``).
"""
import sys
import warnings

import numpy as np

from filterwnn.navigation.drives import read_drive_csv
from filterwnn.studies.dr._real import real_drive_outages

folder, drive, sigma = sys.argv[1], sys.argv[2], float(sys.argv[3])
warnings.simplefilter("ignore")
run = read_drive_csv(f"{folder}/{drive}.csv")
e = np.asarray(real_drive_outages(run, filters=("EKF-8",), grade="phone", model_kwargs={"sigma_zupt": sigma})["EKF-8"])
print(f"{drive} sigma_zupt {sigma}: {np.median(e):.2f} / {e.max():.2f}")
