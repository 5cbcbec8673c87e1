"""A gyro whose bias moves faster than the grade allows: the phone grade's rate-bias state against a larger
bias instability (issue 23, stop 47).

Run from the repository root, one BLAS thread, one analog per process::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/gyro_bias_instability.py phone
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/gyro_bias_instability.py one_hz
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/gyro_bias_instability.py city

(``gyro_bias_instability.txt``: the three runs' lines.) The analogs of ``tests/_held_out_drives.py``, seeds 0-2,
as they are and with ``heading_jump.py``'s drift (the measured heading drifting at 0.05 deg/s from 40 % of the
drive: a gyro whose bias changed by that much). Each line: per bias instability of the grade
(``gyro_bias_instability_deg_h``: the phone grade's 10 deg/h, 30 and 100, ``--gyro-bias-instability``), EKF-8's
median / max at the ends of the 20 outages of 30 s (``filterwnn study dr --drive FILE``'s placement and
settings) and the consistency monitor's warnings (``nis``).
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
import heading_jump  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

INSTABILITIES = (10.0, 30.0, 100.0)


def main(name):
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(3):
            for fault, size in (("none", 0.0), ("drift", 0.05)):
                c, at = heading_jump.faulted(held_out.columns(name, seed), fault, size)
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), c))
                cells = []
                for inst in INSTABILITIES:
                    with warnings.catch_warnings(record=True) as record:
                        warnings.simplefilter("always")
                        res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True,
                                                 grade={"gyro_bias_instability_deg_h": inst})
                    e = res["EKF-8"]
                    nis = sum("is inconsistent" in str(w.message) for w in record)
                    cells.append(f"{inst:g} deg/h {np.median(e):.2f} / {e.max():.2f} (nis {nis})")
                what = "none" if fault == "none" else f"drift {size:g} deg/s at {at:.0f} s"
                print(f"{name} seed {seed} {what} | " + " | ".join(cells), flush=True)


if __name__ == "__main__":
    main(sys.argv[1])
