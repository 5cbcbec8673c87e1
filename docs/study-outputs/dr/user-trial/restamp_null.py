"""The arrival stamps' warning (stop 75) over drive files nobody wrote for it: every user trial's drives (their
generators, run into a temporary folder), the three held-out analogs' seeds 0-4 and the shipped sample, each read by
the drive reader; which tell fixes stamped on arrival (``filterwnn.navigation.scenarios._arrival_stamps``), with the
test's figures for those that do.

    python docs/study-outputs/dr/user-trial/restamp_null.py > docs/study-outputs/dr/user-trial/restamp_null.txt
"""
import os
import tempfile

from null_files import drive_files, reader_warnings

with tempfile.TemporaryDirectory() as folder:
    files = drive_files(folder, sample=True)
    hits = []
    for f in files:
        said = [w.split(":")[0] for w in reader_warnings(f) if "stamped when the logger received them" in w]
        if said:
            hits.append((os.path.relpath(f, folder) if f.startswith(folder) else os.path.basename(f), said[0]))
print(f"{len(files)} drive files read; told: {len(hits)}")
for name, said in hits:
    print(f"  {name}: {said}")
