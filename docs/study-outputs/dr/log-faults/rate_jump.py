"""A step in the gyro's rate bias as a second kind of onset of the heading-jump detector: tried, not kept
(issue 23, stop 47; ``RUN.md``).

The prototype is ``rate_jump_prototype.patch`` (``GPSDRFilter(rate_jump_z=...)``: at each onset a step in the
rate bias beside the heading's, tested alike, taken between the rate that moves the heading by the grade's white
noise over the window and the rate bias's bound; on a find the rate bias and the heading bias are widened).
It applies to 46d79f2. From the repository root, a worktree there with the patch applied, then this script
on it (its first argument), one BLAS thread::

    git worktree add /tmp/rj 46d79f2 && git -C /tmp/rj apply "$PWD/docs/study-outputs/dr/log-faults/rate_jump_prototype.patch"
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/rate_jump.py /tmp/rj phone "range(3)" EKF-8
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/rate_jump.py /tmp/rj one_hz "range(3)" EKF-8

(``rate_jump.txt``: both runs' lines.) Each line: the analog, seed, fault (``heading_jump.py``'s) and its time,
then median / max at the ends of the 20 outages of 30 s without the rate onsets and with them (``+r``,
``rate_jump_z=6.1``), the heading steps (``h``) and rate steps (``r``) found, and each rate step's (step found,
onset, deg/s, z-score).
"""
import os, sys, tempfile, warnings
import numpy as np
ROOT = sys.argv[1]
sys.path.insert(0, ROOT); sys.path.insert(0, os.path.join(ROOT, "tests"))
sys.path.insert(0, os.path.join(ROOT, "docs/study-outputs/dr/log-faults"))
import _held_out_drives as held_out
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation import gpsdr
from filterwnn.studies.dr import real_drive_outages
import heading_jump as hj
assert gpsdr.__file__.startswith(ROOT), gpsdr.__file__
name = sys.argv[2]; seeds = eval(sys.argv[3]); kinds = sys.argv[4].split(",")
faults = eval(sys.argv[5]) if len(sys.argv) > 5 else (("none", 0.0), ("drift", 0.05), ("step", 10.0))
K = gpsdr.GPSDRFilter.__init__.__kwdefaults__
with tempfile.TemporaryDirectory() as tmp:
    for seed in seeds:
        cols = held_out.columns(name, seed)
        for fault, size in faults:
            c, at = hj.faulted(cols, fault, size)
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), c))
            cells = []
            for kind in kinds:
                for rz in (None, 6.1):
                    K["rate_jump_z"] = rz
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        res = real_drive_outages(run, filters=(kind,), use_gps_sigma=True, grade="phone")
                    e = res[kind]; ig = res["integrity"][kind]
                    cells.append(f"{kind}{'+r' if rz else ''} {np.median(e):.2f} / {e.max():.2f} h{ig['n_heading_jumps']} r{ig['n_rate_jumps']}"
                                 + ("".join(f" [{a} {b} {np.degrees(t):.3f} {zz:.1f}]" for a, b, t, zz in ig['rate_jumps']) if rz else ""))
            print(f"{name} {seed} {fault} {size:g} at {at:.0f} | " + " | ".join(cells), flush=True)
