"""Does the drive reader take fixes for a log's last fix carried forward where they are not? (issue 23, stop 48)

Every drive as it comes (the analogs' seeds 0-49, the random drives of protocol 2, seeds 0-89, the sample, both
recorded drives), read as ``filterwnn study dr --drive`` reads it; a line per drive whose reader warned of held
fixes, then the count. Run from the repository root::

    python docs/study-outputs/dr/log-faults/held_fixes_none.py     # held_fixes_none.txt
"""
import os, sys, tempfile, warnings, numpy as np
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr/random-drives"]
import _held_out_drives as held_out
import random_drives as rd
from filterwnn.navigation.drives import read_drive_csv, sample_drive_path, load_car_drive, CAR_DRIVES
tmp = tempfile.mkdtemp()
hits = n = 0
def check(label, fn):
    global hits, n
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        try:
            fn()
        except ValueError as e:
            print(label, "refused", str(e)[:100])
    n += 1
    if any("carries its last fix forward" in str(w.message) for w in rec):
        hits += 1; print("HIT", label, flush=True)
for name in held_out.HELD_OUT:
    for s in range(50):
        p = held_out.write_csv(os.path.join(tmp, "a.csv"), held_out.columns(name, s))
        check(f"{name} {s}", lambda: read_drive_csv(p))
for s in range(90):
    _, cols, _ = rd.drive(s, 2)
    p = held_out.write_csv(os.path.join(tmp, "r.csv"), cols)
    check(f"random {s}", lambda: read_drive_csv(p))
check("sample", lambda: read_drive_csv(sample_drive_path()))
for d in CAR_DRIVES:
    check(d, lambda: load_car_drive(d))
print(f"{hits} of {n} drives warned")
