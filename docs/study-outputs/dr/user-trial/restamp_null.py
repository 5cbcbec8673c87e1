"""The arrival stamps' warning (stop 75) over drive files nobody wrote for it: every user trial's drives (their
generators, run into a temporary folder), the three held-out analogs' seeds 0-4 and the shipped sample, each read by
the drive reader; which tell fixes stamped on arrival (``filterwnn.navigation.scenarios._arrival_stamps``), with the
test's figures for those that do.

    python docs/study-outputs/dr/user-trial/restamp_null.py > docs/study-outputs/dr/user-trial/restamp_null.txt
"""
import glob
import os
import pathlib
import subprocess
import sys
import tempfile
import warnings

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[3] / "tests"))
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv, sample_drive_path  # noqa: E402

GENERATORS = ("gen_drives.py", "gen_drives_2.py", "gen_drives_3.py", "gen_drives_4.py", "gen_drives_6.py",
              "gen_drives_7.py")


def told(path):
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        try:
            read_drive_csv(path)
        except ValueError:
            pass  # (refused drives are read as far as their fixes)
    return [str(w.message).split(":")[0] for w in seen if "stamped when the logger received them" in str(w.message)]


with tempfile.TemporaryDirectory() as folder:
    files = []
    for gen in GENERATORS:
        out = os.path.join(folder, gen[:-3])
        os.makedirs(out)
        subprocess.run([sys.executable, str(HERE / gen), out], check=True, capture_output=True)
        files += sorted(glob.glob(os.path.join(out, "*.csv")))
    for name in ("phone", "city", "one_hz"):
        for seed in range(5):
            files.append(str(held_out.write_csv(pathlib.Path(folder) / f"{name}_{seed}.csv",
                                                held_out.columns(name, seed))))
    files.append(str(sample_drive_path()))
    hits = [(os.path.relpath(f, folder) if f.startswith(folder) else os.path.basename(f), said)
            for f in files for said in [told(f)] if said]
print(f"{len(files)} drive files read; told: {len(hits)}")
for name, said in hits:
    print(f"  {name}: {said[0]}")
