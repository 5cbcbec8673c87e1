"""A heading that steps (or starts to drift) while the car moves, cut into the analogs (issue 23, stop 46).

Run from the repository root, one BLAS thread, one analog per process::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_jump.py phone
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_jump.py one_hz
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_jump.py city

(``heading_jump.txt``: the three runs' lines.)

The drives: the analogs of ``tests/_held_out_drives.py``, seeds 0-2. From the first sample at or after 40 %
of the drive at which the car moves at 3 m/s or more, the measured heading steps by 2, 5 or 10 degrees (a
phone's fused orientation re-aligning to its compass while the car drives), or starts to drift at 0.05 deg/s
(a gyro whose bias changed by that much, ten times the phone grade's bias instability over an hour). Each
line: the analog, seed, fault and its time, then per 8-state kind its median / max at the ends of the 20
outages of 30 s (``filterwnn study dr --drive FILE --grade phone``'s placement and settings) with the
heading-jump detector (the default) and without it (``heading_jump_z=None``), the steps it found
(``n_heading_jumps``) and whether the consistency monitor warned of a gyro scale error; dead reckoning from the
true start last.
"""

import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests"))

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

KINDS = ("EKF-8", "UKF-8", "SUKF-8")
FAULTS = (("none", 0.0), ("step", 2.0), ("step", 5.0), ("step", 10.0), ("drift", 0.05))


def faulted(cols, fault, size):
    """The drive with ``fault`` (``step`` of ``size`` deg, or ``drift`` of ``size`` deg/s) from the first sample at
    or after 40 % of it at which the car moves at 3 m/s or more; and that time (s)."""
    c = {k: np.asarray(v, dtype=float).copy() for k, v in cols.items()}
    t = c["time"]
    k = int(np.flatnonzero((np.arange(len(t)) >= int(0.4 * len(t))) & (c["speed"] >= 3.0))[0])
    if fault == "step":
        c["heading"][k:] = np.mod(c["heading"][k:] + np.deg2rad(size), 2 * np.pi)
    elif fault == "drift":
        c["heading"][k:] = np.mod(c["heading"][k:] + np.deg2rad(size) * (t[k:] - t[k]), 2 * np.pi)
    return c, float(t[k])


def main(name):
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(3):
            cols = held_out.columns(name, seed)
            for fault, size in FAULTS:
                c, at = faulted(cols, fault, size)
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), c))
                cells = []
                for kind in KINDS:
                    cell = []
                    for z in ("default", None):
                        kw = {} if z == "default" else {"heading_jump_z": None}
                        with warnings.catch_warnings(record=True) as record:
                            warnings.simplefilter("always")
                            res = real_drive_outages(run, filters=(kind,), use_gps_sigma=True, grade="phone", **kw)
                        e = res[kind]
                        scale = any("the gyro's scale" in str(w.message) for w in record)
                        jumps = res["integrity"][kind]["n_heading_jumps"]
                        cell.append(f"{np.median(e):.2f} / {e.max():.2f}" + (f" ({jumps} found)" if z else "")
                                    + (" (scale warned)" if scale else ""))
                    cells.append(f"{kind} {cell[0]}, off {cell[1]}")
                dr = real_drive_outages(run, filters=("DR-mech",))["DR-mech"]
                what = "none" if fault == "none" else f"{fault} {size:g} {'deg' if fault == 'step' else 'deg/s'} at {at:.0f} s"
                print(f"{name} seed {seed} {what} | " + " | ".join(cells) + f" | DR {np.median(dr):.2f} / {dr.max():.2f}",
                      flush=True)


if __name__ == "__main__":
    main(sys.argv[1])
