"""A speed stamped late reads to the fixes as fixes stamped early (stop 64): what the monitors tell, and what each
remedy they name gives.

1. The 1 Hz and phone analogs' generators on ``default_rng(0..5)`` with the speed 0.7 s late, through the phone
   grade's EKF-8 (``batch_filter``): the speed's latency and the fixes' latency the monitors estimate, the step at
   which the fixes' latency state was added, and the fixes' latency told at the end.
2. ``filterwnn study dr --drive FILE --grade phone --filters EKF-8`` on two of them and on protocol 3's random drive
   260 (its speed 0.43 s late), as is and with each remedy the warnings name: the EKF-8's median / max at the outage
   ends and the latency warnings' first words.

    python docs/study-outputs/dr/log-faults/speed_late_fixes_early.py > docs/study-outputs/dr/log-faults/speed_late_fixes_early.txt
"""
import os
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import ekf8_command  # noqa: E402  (puts tests/ and tests/navigation on the path)
import _held_out_drives as held_out  # noqa: E402
import random_drives  # noqa: E402
from filterwnn.navigation.dead_reckoning import GPSDRModel  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.navigation.gpsdr import GPSDRFilter  # noqa: E402


def r(v, d=3):
    return None if v is None else round(float(v), d)


with tempfile.TemporaryDirectory() as tmp:
    print("## 1. batch_filter, the speed 0.7 s late")
    for name in ("one_hz", "phone"):
        for seed in range(6):
            path = held_out.write_csv(os.path.join(tmp, f"{name}{seed}.csv"),
                                      held_out.HELD_OUT[name](np.random.default_rng(seed), odometer_latency=0.7))
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                run = read_drive_csv(path)
                model = GPSDRModel.from_grade("phone", run.scenario.dt)
                f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
                f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
            print(f"{name} default_rng({seed}): speed {r(f.odometer_latency_estimate)} (z {r(f.odometer_latency_z, 2)}), "
                  f"fixes {r(f.latency_estimate)} (z {r(f.latency_z, 2)}), fixes' state added at step {f.latency_added}, "
                  f"told at the end {f.latency_at_end}", flush=True)
    print("\n## 2. the command, as is and with the remedies named")
    cases = []
    for name, seed in (("one_hz", 1), ("phone", 4)):
        cases.append((f"{name} default_rng({seed}), speed 0.7 s late", os.path.join(tmp, f"{name}{seed}.csv")))
    cols = random_drives.drive(260, 3)[1]
    cases.append(("protocol 3 seed 260, speed 0.43 s late", held_out.write_csv(os.path.join(tmp, "p3s260.csv"), cols)))
    for label, path in cases:
        base, err = ekf8_command(path, os.path.join(tmp, "out"))
        told = [line for line in err.splitlines() if "latency" in line]
        print(f"### {label}\nas is: {base}")
        for line in told:
            print("   ", line[:200], "..." if len(line) > 200 else "")
        speed = next((line.split("--odometer-latency ")[1].split(")")[0] for line in told if "--odometer-latency" in line),
                     None)
        fixes = next((line.split("--gps-latency ")[1].split(";")[0].split(")")[0] for line in told
                      if "over the whole drive" in line), None)
        if fixes is None:
            fixes = next((line.split("show themselves ")[1].split(" s")[0] for line in told if "show themselves" in line),
                         None)
        for extra in ([["--odometer-latency", speed]] if speed else []) + ([["--gps-latency", fixes]] if fixes else []) + (
                [["--odometer-latency", speed, "--gps-latency", fixes]] if speed and fixes else []):
            got, err2 = ekf8_command(path, os.path.join(tmp, "out"), extra)
            again = [line[:120] for line in err2.splitlines() if "latency" in line]
            print(f"{' '.join(extra)}: {got}" + (f"  (warned: {'; '.join(again)})" if again else ""))
print("DONE")
