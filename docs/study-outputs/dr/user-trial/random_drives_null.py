"""Stop 75's two reader warnings over the random drives (``../random-drives/random_drives.py``, protocols 1 and 3,
seeds 200-279: 160 drives nobody here drew, protocol 3's with sensor faults drawn at random, among them speed dropouts
and tunnels), each read by the drive reader: how many tell fixes stamped on arrival, and a speed lost with the
receiver's fixes (the GNSS speed's warning); beside them, how many tell the speed dropouts of the rule before stop 75.

    python docs/study-outputs/dr/user-trial/random_drives_null.py > docs/study-outputs/dr/user-trial/random_drives_null.txt
"""
import os
import pathlib
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "random-drives"))
sys.path.insert(0, str(HERE.parents[3] / "tests"))
import _held_out_drives as held_out  # noqa: E402
import random_drives  # noqa: E402
from null_files import reader_warnings  # noqa: E402

WORDS = {"stamped on arrival": "stamped when the logger received them",
         "a speed lost with the fixes": "where the GPS receiver has no fix",
         "speed dropouts (the rule before stop 75)": "so these are dropouts"}
told = {k: [] for k in WORDS}
with tempfile.TemporaryDirectory() as tmp:
    for protocol in (1, 3):
        for seed in range(200, 280):
            path = held_out.write_csv(os.path.join(tmp, f"p{protocol}_{seed}.csv"),
                                      random_drives.drive(seed, protocol)[1])
            seen = reader_warnings(path)
            for k, words in WORDS.items():
                if any(words in w for w in seen):
                    told[k].append(f"{protocol}/{seed}")
print("160 random drives read (protocols 1 and 3, seeds 200-279)")
for k, v in told.items():
    print(f"{k}: {len(v)}" + (f" ({', '.join(v)})" if v else ""))
