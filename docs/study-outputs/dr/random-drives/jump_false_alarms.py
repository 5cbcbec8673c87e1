"""Does the heading-jump detector find steps that are not there? The random drives of protocol 2, phone grade (stop 46).

Run from the repository root, one BLAS thread (seeds ``LO`` to ``HI - 1``)::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/jump_false_alarms.py 0 30
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/jump_false_alarms.py 30 60

(``jump_false_alarms.txt``: the two runs' lines, on two cores, and their totals summed on its last line.)

Each drive (``random_drives.drive(seed, 2)``) has no heading step: its gyro heading drifts, with white noise
and an angle random walk drawn per drive, at sample intervals of 0.05-1 s, its fixes' accuracy and
correlation drawn too. Each line: the drive's interval, the steps the EKF-8 of ``filterwnn study dr --drive
FILE --grade phone`` found while the car moved (``n_heading_jumps``: every one a false alarm, or a heading
bias the filter held off), with each one's estimate and z-score, and its median / max at the outage ends
(m) with the detector (the default) and without it (``heading_jump_z=None``).
"""

import os
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "..", "tests"))
sys.path.insert(0, HERE)

import _held_out_drives as held_out  # noqa: E402
import random_drives  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402


def main(lo, hi):
    total = 0
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(lo, hi):
            d, cols, _ = random_drives.drive(seed, 2)
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
            cells = []
            for kw in ({}, {"heading_jump_z": None}):
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone", **kw)
                cells.append((res["integrity"]["EKF-8"]["heading_jumps"], res["EKF-8"]))
            (jumps, e), (_, off) = cells
            total += len(jumps)
            found = " ".join(f"[{np.degrees(s):+.2f} deg, z {z:+.2f}]" for _, _, s, z in jumps)
            print(seed, f"dt {d['dt']:.2f} found {len(jumps)}{' ' + found if found else ''} EKF-8 "
                  f"{np.median(e):.2f} / {e.max():.2f}, off {np.median(off):.2f} / {off.max():.2f}", flush=True)
    print("total found", total)


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]))
