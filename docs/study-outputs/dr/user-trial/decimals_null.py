"""The coarse coordinates' warning (stop 74) over drive files nobody wrote for it: every user trial's drives (their
generators, run into a temporary folder) and the three held-out analogs' seeds 0-4, each read by the drive reader;
which tell their fixes' decimals.

    python docs/study-outputs/dr/user-trial/decimals_null.py > docs/study-outputs/dr/user-trial/decimals_null.txt
"""
import os
import tempfile

from null_files import drive_files, reader_warnings

with tempfile.TemporaryDirectory() as folder:
    files = drive_files(folder)
    hits = [os.path.relpath(f, folder) for f in files if any("decimals (steps of" in w for w in reader_warnings(f))]
print(f"{len(files)} drive files read; told: {len(hits)}")
for h in hits:
    print("  " + h)
