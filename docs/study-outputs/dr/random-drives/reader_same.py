"""Whether the drive reader's output moved between two versions of the package (stop 56): each drive read with
``read_drive_csv`` and its DR measurements (``z_dr``) compared to the bit. Drives: the analogs' seeds 0-2 as
written, with the spikes study's 20 speed spikes and with its 20 heading spikes (``log-faults/spikes.py``), and
protocols 2 and 3's seeds 0-29 and 200-279 of ``random_drives.py`` (247 in all). Run from the repository root::

    python docs/study-outputs/dr/random-drives/reader_same.py dump ROOT_A a.npz
    python docs/study-outputs/dr/random-drives/reader_same.py dump ROOT_B b.npz
    python docs/study-outputs/dr/random-drives/reader_same.py compare a.npz b.npz
"""
import os
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def dump(root, out):
    sys.path[:0] = [os.path.abspath(root), os.path.join(HERE, "..", "..", "..", "..", "tests"), HERE]
    import _held_out_drives as held_out
    import random_drives
    from filterwnn.navigation.drives import read_drive_csv
    assert read_drive_csv.__code__.co_filename.startswith(os.path.abspath(root))
    drives = {}
    for name in ("phone", "city", "one_hz"):
        for seed in (0, 1, 2):
            c = held_out.columns(name, seed)
            k = np.random.default_rng([50, 7, seed]).choice(np.flatnonzero(c["speed"] > 3.0), 20, replace=False)
            drives[f"{name}{seed}"] = c
            drives[f"{name}{seed} speed spikes"] = dict(c, speed=np.where(np.isin(np.arange(len(c["speed"])), k),
                                                                          70.8, c["speed"]))
            h = c["heading"].copy()
            h[k] = np.mod(h[k] + np.pi / 2, 2 * np.pi)
            drives[f"{name}{seed} heading spikes"] = dict(c, heading=h)
    for s in list(range(0, 30)) + list(range(200, 280)):
        for p in (2, 3):
            drives[f"protocol {p} seed {s}"] = random_drives.drive(s, p)[1]
    z = {}
    with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for key, cols in drives.items():
            z[key] = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols)).z_dr
    np.savez(out, **z)


if __name__ == "__main__":
    if sys.argv[1] == "dump":
        dump(sys.argv[2], sys.argv[3])
    else:
        a, b = np.load(sys.argv[2]), np.load(sys.argv[3])
        moved = [k for k in a if not np.array_equal(a[k], b[k])]
        print(f"{len(a)} drives; the reader's output differs on {len(moved)}: {', '.join(moved) or 'none'}")
