"""Whether the reader's refusal of a gps_sigma not in metres (stop 60) refuses any drive at hand: the analogs'
seeds 0-9 and the random drives of protocols 2 and 3 (seeds 0-29, 200-279), read as written; prints the refused
and the largest median sigmas. Run from the repository root:
``python docs/study-outputs/dr/log-faults/accuracy_units_reader.py > docs/study-outputs/dr/log-faults/accuracy_units_reader.txt``
"""
import os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import drives_at_hand, held_out
from filterwnn.navigation.drives import read_drive_csv
drives = {key: make() for key, make in drives_at_hand().items()}
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
