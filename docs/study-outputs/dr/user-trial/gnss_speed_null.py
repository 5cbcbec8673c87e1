"""The GNSS speed's warning (stop 75: a speed that reads 0 where the receiver has no fix either, between samples of a
car moving) over drive files nobody wrote for it: every user trial's drives (their generators, run into a temporary
folder), the three held-out analogs' seeds 0-4 and the shipped sample, each read by the drive reader; which tell it,
with the warning's first words.

    python docs/study-outputs/dr/user-trial/gnss_speed_null.py > docs/study-outputs/dr/user-trial/gnss_speed_null.txt
"""
import os
import tempfile

from null_files import drive_files, reader_warnings

with tempfile.TemporaryDirectory() as folder:
    files = drive_files(folder, sample=True)
    hits = []
    for f in files:
        said = [w.split(": a car braking")[0] for w in reader_warnings(f) if "where the GPS receiver has no fix" in w]
        if said:
            hits.append((os.path.relpath(f, folder) if f.startswith(folder) else os.path.basename(f), said[0]))
print(f"{len(files)} drive files read; told: {len(hits)}")
for name, said in hits:
    print(f"  {name}: {said}")
