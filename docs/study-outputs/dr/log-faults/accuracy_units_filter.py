"""Whether the filter's warning of fixes whose sigma is far past their errors (a window's mean NIS under
NIS_FAR_BELOW, stop 60) fires on any drive at hand: the same 250 drives as ``accuracy_units_reader.py``, each
through the EKF of the phone grade (8 states) and of the survey grade, with their fixes' own sigmas. Half the drives
for ``part`` 0, the other half for 1 (two processes). Run from the repository root::

    python docs/study-outputs/dr/log-faults/accuracy_units_filter.py 0 > accuracy_units_filter_0.txt
    python docs/study-outputs/dr/log-faults/accuracy_units_filter.py 1 > accuracy_units_filter_1.txt
"""
import os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import drives_at_hand, held_out
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.gpsdr import GPSDRFilter
part = int(sys.argv[1])
drives = drives_at_hand()
keys = list(drives)[part::2]
fired = []
with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
    warnings.simplefilter("ignore")
    for key in keys:
        run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), drives[key]()))
        for grade in ("phone", "survey"):
            model = GPSDRModel.from_grade(grade, run.scenario.dt)
            f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
            f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
            if f.nis_low_step is not None:
                fired.append((key, grade, f.nis_low_step))
        print(key, flush=True)
print("DONE", len(keys), "drives x 2 grades; fired:", fired)
