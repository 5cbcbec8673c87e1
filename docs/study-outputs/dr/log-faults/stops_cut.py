"""Where the filter's finding of standstills cut into pieces (``reopen_on_detection``, stop 61) fires on the drives
at hand: the tests' drive from rest (``FROM_REST``) over seeds 0-19, the analogs' seeds 0-9, the random drives 0-29
and 200-279 of protocols 2 and 3, and the shipped sample; each through the phone grade's EKF-8 with its fixes, the
step printed (None: never). Half the drives for ``part`` 0, the other half for 1 (two processes). Run from the
repository root::

    python docs/study-outputs/dr/log-faults/stops_cut.py 0 > docs/study-outputs/dr/log-faults/stops_cut_0.txt
    python docs/study-outputs/dr/log-faults/stops_cut.py 1 > docs/study-outputs/dr/log-faults/stops_cut_1.txt
"""
import os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import drives_with_rest, read_at_hand  # puts tests/ and tests/navigation on the path
from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.gpsdr import GPSDRFilter
part = int(sys.argv[1])
drives = drives_with_rest()
keys = list(drives)[part::2]
fired = []
with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
    warnings.simplefilter("ignore")
    for key in keys:
        run = read_at_hand(drives[key](), tmp)
        model = GPSDRModel.from_grade("phone", run.scenario.dt)
        f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
        f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
        if f.stops_cut_step is not None:
            fired.append((key, f.stops_cut_step))
        print(key, f.stops_cut_step, flush=True)
print("DONE", len(keys), "drives; fired:", fired)
