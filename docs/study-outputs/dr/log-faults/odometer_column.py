"""A drive logged with a cumulative odometer in place of a speed (issue 23, stop 49).

``DRIVE_CSV_COLUMNS`` takes either a ``speed`` (m/s) or an ``odometer`` (cumulative m) column. The models measure
the speed at each sample. An odometer's increment over an interval is the mean speed over it, the speed at its
middle: read as the speed at the interval's end (the reader did so until stop 49), each speed is half an interval
late, which at 1 Hz is 0.5 s.

The analogs of ``tests/_held_out_drives.py``, seeds 0-9 at 1 Hz and 0-2 for the phone and the city, each written
twice: with its speed column, and with an odometer column in its place, the cumulative trapezoid sum of the same
speed samples (the odometer of a logger that integrates its speed). Each line, per 8-state kind, the median / max
at the outage ends (``filterwnn study dr --drive FILE --grade phone``'s scoring), then whether the filters warned
of the speed's latency (the count of kinds that did, and the first warning's estimate).

Run with the package at ``ROOT`` (a copy of the repository), one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/odometer_column.py ROOT

(``odometer_column.txt``: on 4c579b3, the reader before stop 49, then on stop 49's.)
"""
import os
import re
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

assert real_drive_outages.__code__.co_filename.startswith(ROOT)
KINDS = ("EKF-8", "UKF-8", "SUKF-8")
TOLD = re.compile(r"speed's latency: by step (\d+) the fixes show the speed ([-+0-9.e]+) s")


def write(path, cols, odometer):
    """The drive CSV, with the speed column or an odometer column in its place."""
    cols, names = dict(cols), list(held_out.COLUMNS)
    if odometer:
        t, v = cols["time"], cols["speed"]
        cols["odometer"] = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
        names[names.index("speed")] = "odometer"
    with open(path, "w") as fh:
        fh.write(",".join(names) + "\n")
        for k in range(len(cols["time"])):
            fh.write(",".join("" if np.isnan(cols[c][k]) else f"{cols[c][k]:.6g}" if c in ("time", "gps_sigma")
                              else f"{cols[c][k]:.4f}" for c in names) + "\n")
    return path


with tempfile.TemporaryDirectory() as tmp:
    for name, seeds in (("one_hz", range(10)), ("phone", range(3)), ("city", range(3))):
        for seed in seeds:
            cols = held_out.columns(name, seed)
            for odometer in (False, True):
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    run = read_drive_csv(write(os.path.join(tmp, "d.csv"), cols, odometer))
                    res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
                told = [TOLD.search(str(w.message)).groups() for w in caught if TOLD.search(str(w.message))]
                cells = [f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in KINDS]
                said = f"speed late: {len(told)} kind(s)" + (f", first {told[0][1]} s at step {told[0][0]}" if told else "")
                print(f"{name} {seed} {'odometer' if odometer else 'speed   '} | " + " | ".join(cells) + f" | {said}",
                      flush=True)
