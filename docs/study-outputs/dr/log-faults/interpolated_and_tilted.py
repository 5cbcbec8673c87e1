"""Whether the reader's two warnings of stop 61 fire on any drive at hand: a speed or heading interpolated between the
fixes (its slope changing only at them) and a course that turns 0.3-0.6 of the fixes' turns (a gyro axis tilted far
off the vertical). The drives: the 250 of ``at_hand.py``, the shipped sample, and the CSVs in each folder given (the
u-blox log's 28: ``python docs/study-outputs/dr/ublox-log/run.py --work W`` writes them to ``W/csv``; the OBD-II
user's: ``python docs/study-outputs/dr/obd-log/run.py --work V`` to ``V/csv``). Prints each drive refused or warned,
each drive's turn ratio (nan: fewer than five turns), and the lowest. Run from the repository root::

    python docs/study-outputs/dr/log-faults/interpolated_and_tilted.py W/csv V/csv > docs/study-outputs/dr/log-faults/interpolated_and_tilted.txt
"""
import glob, os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import drives_at_hand, held_out
from filterwnn.navigation import _plausibility
from filterwnn.navigation.drives import read_drive_csv, sample_drive_path
drives = drives_at_hand()
drives["sample"] = sample_drive_path
for folder in sys.argv[1:]:
    for f in sorted(glob.glob(os.path.join(folder, "*.csv"))):
        drives[os.path.join(os.path.basename(os.path.dirname(os.path.dirname(os.path.abspath(f)))),
                            os.path.basename(f))] = lambda f=f: f
ratios, warned = {}, {"interpolated": [], "tilted": []}
told = _plausibility._warn_tilted


def _recording(heading, step, steps, z_gps, pairs):  # the reader's own turn ratio, kept
    ratios[key] = _plausibility._turn_ratio(heading, step, steps, z_gps, pairs)[0]
    return told(heading, step, steps, z_gps, pairs)


_plausibility._warn_tilted = _recording
with tempfile.TemporaryDirectory() as tmp:
    for key, make in drives.items():
        obj = make()
        path = obj if isinstance(obj, str) else held_out.write_csv(os.path.join(tmp, "d.csv"), obj)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                read_drive_csv(path)
            except ValueError as e:
                print(key, "refused:", str(e)[:120], flush=True)
                continue
        for what, words in (("interpolated", "runs straight between"), ("tilted", "tilted far off the vertical")):
            said = [str(w.message) for w in caught if words in str(w.message)]
            if said:
                warned[what].append(key)
                print(key, "WARNED:", said[0][:300], flush=True)
        print(key, "turn ratio", round(ratios.get(key, float("nan")), 3), flush=True)
low = sorted((r, k) for k, r in ratios.items() if np.isfinite(r))
print(len(drives), "drives; warned:", warned)
print("lowest turn ratios:", [(k, round(r, 3)) for r, k in low[:8]])
