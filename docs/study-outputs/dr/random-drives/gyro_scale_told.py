"""When each 8-state kind's monitor told a protocol-3 drive's gyro scale error (stop 56), from the command's stderr
kept by ``random_drives.py --keep FOLDER``: per drive with the fault, its sample interval and length, and per kind
the step and time of the warning "the gyro's scale: by step N" (``never``: not told). Run from the repository root::

    python docs/study-outputs/dr/random-drives/gyro_scale_told.py OUTPUT.txt FOLDER [OUTPUT.txt FOLDER ...]
"""
import os
import re
import sys

for out, keep in zip(sys.argv[1::2], sys.argv[2::2]):
    for line in open(out):
        m = re.match(r"seed (\d+): dt ([\d.]+) s, (\d+) s,.*faults: .*gyro scale ([+-][\d.]+) %", line)
        if not m:
            continue
        seed, dt, dur, scale = int(m.group(1)), float(m.group(2)), int(m.group(3)), m.group(4)
        err = open(os.path.join(keep, f"random_{seed}_phone.stderr")).read()
        cells = []
        for kind in ("EKF-8", "UKF-8", "SUKF-8"):
            told = re.search(rf"{kind}: GPSDRFilter, the gyro's scale: by step (\d+)", err)
            cells.append(f"{kind} step {told.group(1)} at {int(told.group(1)) * dt:.0f} s" if told else f"{kind} never")
        print(f"seed {seed}: dt {dt:g} s, {dur} s, gyro scale {scale} % | " + " | ".join(cells))
