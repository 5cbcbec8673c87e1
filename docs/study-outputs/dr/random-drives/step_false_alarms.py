"""Does the stop update find heading steps that are not there? The random drives of protocol 2, phone grade (stop 45).

Run from the repository root, one BLAS thread (seeds ``LO`` to ``HI - 1``)::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/step_false_alarms.py 0 30
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/step_false_alarms.py 30 60

(``step_false_alarms.txt``: the two runs' lines, on two cores, and their totals summed on its last line.)

Each drive (``random_drives.drive(seed, 2)``) has no heading step: its gyro heading drifts, with white noise
and an angle random walk drawn per drive (0.1-0.5 deg and 0.1-1 deg/sqrt(h), up to the phone grade's and
past it), at sample intervals of 0.05-1 s. Each line: the drive's interval, heading noise and random walk, the
stops the EKF-8 of ``filterwnn study dr --drive FILE --grade phone`` tested, how many of them it found stepped
(``n_zero_rate_stepped``: every one a false alarm), and its median / max at the outage ends (m).
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
            path = held_out.write_csv(os.path.join(tmp, "d.csv"), cols)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                res = real_drive_outages(read_drive_csv(path), filters=("EKF-8",), use_gps_sigma=True, grade="phone")
            ig = res["integrity"]["EKF-8"]  # every stop tested is used or rejected
            total += ig["n_zero_rate_stepped"]
            print(seed, f"dt {d['dt']:.2f} white {d['white']:.2f} arw {d['arw']:.2f} stops tested "
                  f"{ig['n_zero_rate'] + ig['n_zero_rate_rejected']} stepped {ig['n_zero_rate_stepped']} EKF-8 "
                  f"{np.median(res['EKF-8']):.2f} / "
                  f"{res['EKF-8'].max():.2f}", flush=True)
    print("total stepped", total)


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]))
