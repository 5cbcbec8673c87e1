"""Whether a gyro scale error told once at a drive's end (stop 62's question: the test ``end_of_drive`` makes of the
fixes' latency, made of the scale error too) would mend the drive by its rerun: each drive at hand on which
``end_of_drive_0.txt`` / ``end_of_drive_1.txt`` put the scale monitor's end z-score past 4.0 (an estimate of 0.5 % or
more, the error not told before), and the phone analog (seed 0) with its gyro turning 0.7 % more than the car, through ``filterwnn study dr --drive CSV --grade phone --filters EKF-8``, then
again with the scale state from the start (``--gyro-scale-sd 0.01``, a MEMS gyro's +-3 % as three sigmas). Per drive:
the true scale error, the end's estimate, and the outage ends (median / max, m) before and after. Run from the
repository root::

    python docs/study-outputs/dr/log-faults/scale_at_end_remedy.py > docs/study-outputs/dr/log-faults/scale_at_end_remedy.txt
"""
import os, sys, tempfile
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import drives_at_hand, ekf8_command, held_out  # puts tests/ and the random drives on the path
import random_drives

#: (drive, the scale monitor's estimate at the end) from end_of_drive_*.txt
DRIVES = [("p3 s210", -0.0092), ("p3 s259", 0.0308), ("p3 s6", 0.009), ("p3 s219", 0.0164), ("p3 s256", -0.0175),
          ("p3 s275", -0.0218), ("p3 s276", -0.0148)]


def command(path, tmp, extra=()):
    return ekf8_command(path, tmp, extra)[0]


with tempfile.TemporaryDirectory() as tmp:
    every = drives_at_hand()
    every["phone0 +0.7 %"] = lambda: held_out.columns("phone", 0, gyro_scale=0.007)
    for key, est in DRIVES + [("phone0 +0.7 %", 0.0113)]:
        true = random_drives.faults(int(key[4:]))[0].get("gyro_scale", 0.0) if key.startswith("p3 ") else 0.007
        path = held_out.write_csv(os.path.join(tmp, "d.csv"), every[key]())
        print(f"{key:13s} scale {100 * true:+.1f} % | end estimate {100 * est:+.2f} % | EKF-8 {command(path, tmp)} -> "
              f"{command(path, tmp, ['--gyro-scale-sd', '0.01'])}", flush=True)
