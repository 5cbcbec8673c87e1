"""The drive files a reader warning's null runs over (``decimals_null.py``, ``restamp_null.py``): every user trial's
drives (their generators, run into a folder), the three held-out analogs' seeds 0-4 and, with ``sample``, the
shipped sample; and the warnings the drive reader gives on one of them."""
import glob
import os
import pathlib
import subprocess
import sys
import warnings

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[3] / "tests"))
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv, sample_drive_path  # noqa: E402

GENERATORS = ("gen_drives.py", "gen_drives_2.py", "gen_drives_3.py", "gen_drives_4.py", "gen_drives_6.py",
              "gen_drives_7.py")


def drive_files(folder, sample=False):
    """The drive files, written into ``folder``: the trials' (in generator order, each sorted) and the analogs'."""
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
    return files + ([str(sample_drive_path())] if sample else [])


def reader_warnings(path):
    """The drive reader's warnings on ``path`` (a refused drive's as far as it was read)."""
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        try:
            read_drive_csv(path)
        except ValueError:
            pass
    return [str(w.message) for w in seen]


def print_told(words, cut, sample=True):
    """Read every drive file (:func:`drive_files`) and print which tell the warning holding ``words``, with its text
    up to ``cut``."""
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        files = drive_files(folder, sample=sample)
        hits = []
        for f in files:
            said = [w.split(cut)[0] for w in reader_warnings(f) if words in w]
            if said:
                hits.append((os.path.relpath(f, folder) if f.startswith(folder) else os.path.basename(f), said[0]))
    print(f"{len(files)} drive files read; told: {len(hits)}")
    for name, said in hits:
        print(f"  {name}: {said}")
