"""Whether the reader's refusal of a gps_sigma not in metres (stop 60) refuses any drive at hand: the analogs'
seeds 0-9 and the random drives of protocols 2 and 3 (seeds 0-29, 200-279), read as written; prints the refused
and the largest median sigmas. Run from the repository root:
``python docs/study-outputs/dr/log-faults/accuracy_units_reader.py > docs/study-outputs/dr/log-faults/accuracy_units_reader.txt``
"""
import os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.join(HERE, "..", "..", "..", "..", "tests"), os.path.join(HERE, "..", "random-drives")]
import _held_out_drives as held_out, random_drives
from filterwnn.navigation.drives import read_drive_csv
drives = {}
for name in ("phone", "city", "one_hz"):
    for seed in range(10):
        drives[f"{name}{seed}"] = held_out.columns(name, seed)
for s in list(range(0, 30)) + list(range(200, 280)):
    for p in (2, 3):
        drives[f"p{p} s{s}"] = random_drives.drive(s, p)[1]
bad = []
med = []
with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
    warnings.simplefilter("ignore")
    for key, cols in drives.items():
        try:
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
            if run.gps_sigma is not None: med.append(float(np.median(run.gps_sigma)))
        except ValueError as e:
            bad.append((key, str(e)[:200]))
print(len(drives), "drives; refused:", len(bad))
for b in bad: print(" ", b)
print("largest median sigma", sorted(med)[-5:])
