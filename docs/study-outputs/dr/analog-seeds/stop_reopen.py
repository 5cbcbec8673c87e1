"""``GPSDRFilter(stop_reopen=2.0)`` against the default (stop 44): EKF-8 on the analogs' seeds 0-9 and on
random drive 10 of protocol 2, whose stops creep (``../random-drives``).

Run from the repository root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/analog-seeds/stop_reopen.py > docs/study-outputs/dr/analog-seeds/stop_reopen.txt

Each line: the drive, EKF-8's median / max at the ends of the 20 outages of 30 s (``filterwnn study dr --drive
FILE --grade phone``'s placement and settings) with the default (``stop_reopen=0``), and with ``stop_reopen=2``
(``--stop-reopen 2``): a stop that starts again within 2 s, the car having moved at most 0.5 m, is the same stop
to the gyro rate bias's update.
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [os.path.join(ROOT, "tests"), os.path.join(ROOT, "docs", "study-outputs", "dr", "random-drives")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402


def score(path, reopen):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = real_drive_outages(read_drive_csv(path), filters=("EKF-8",), use_gps_sigma=True, grade="phone",
                                 stop_reopen=reopen)
    return f"{np.median(res['EKF-8']):.2f} / {res['EKF-8'].max():.2f}"


def main():
    import random_drives

    with tempfile.TemporaryDirectory() as tmp:
        drives = [(f"{n} seed {s}", held_out.columns(n, s)) for n in ("phone", "city", "one_hz") for s in range(10)]
        drives.append(("random drive 10, protocol 2", random_drives.drive(10, 2)[1]))
        for label, cols in drives:
            path = held_out.write_csv(os.path.join(tmp, "d.csv"), cols)
            print(f"{label} | EKF-8 {score(path, 0.0)} | stop_reopen=2 {score(path, 2.0)}", flush=True)


if __name__ == "__main__":
    main()
