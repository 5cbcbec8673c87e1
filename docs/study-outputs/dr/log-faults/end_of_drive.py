"""What the error monitor's estimates and z-scores are at the end of each drive at hand (stop 62): the fixes' latency,
the speed's latency and the gyro scale error, with the true faults of protocol 3's drives, through the phone grade's
EKF-8 with its fixes. A test made once, when a drive ends, may take a lower gate than the monitor's (which looks at
every fix); this is the scan of how the end's z-scores fall on drives with and without each error. Half the drives
for ``part`` 0, the other half for 1 (two processes). Run from the repository root::

    python docs/study-outputs/dr/log-faults/end_of_drive.py 0 > docs/study-outputs/dr/log-faults/end_of_drive_0.txt
    python docs/study-outputs/dr/log-faults/end_of_drive.py 1 > docs/study-outputs/dr/log-faults/end_of_drive_1.txt
"""
import json, os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import drives_with_rest, read_at_hand  # puts tests/ and tests/navigation on the path
import random_drives
from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.gpsdr import GPSDRFilter
part = int(sys.argv[1])
drives = drives_with_rest()
keys = list(drives)[part::2]


def r(v, d=3):
    return None if v is None else round(float(v), d)


with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
    warnings.simplefilter("ignore")
    for key in keys:
        run = read_at_hand(drives[key](), tmp)
        model = GPSDRModel.from_grade("phone", run.scenario.dt)
        f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
        f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
        true = {}
        if key.startswith("p3 "):
            true = {k: (round(v, 3) if isinstance(v, float) else v) for k, v in random_drives.faults(int(key[4:]))[0].items()
                    if k in ("gyro_scale", "gps_latency", "speed_latency")}
        print(json.dumps(dict(key=key, true=true, dt=run.scenario.dt,
                              latency=[r(f.latency_estimate), r(f.latency_z, 2), f.latency_added],
                              odometer_latency=[r(f.odometer_latency_estimate), r(f.odometer_latency_z, 2)],
                              gyro_scale=[r(f.gyro_scale_estimate, 4), r(f.gyro_scale_z, 2), f.gyro_scale_added])),
              flush=True)
print("DONE", len(keys), "drives")
