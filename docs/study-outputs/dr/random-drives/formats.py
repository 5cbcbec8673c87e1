"""Random drives written the ways loggers write them (issue 23, stop 49).

Stop 49 changed how the drive reader reads a cumulative odometer, placed fixes logged between the DR samples
(``DRRun.gps_offset``) and read logs whose heading and speed come on rows of their own. This runs drives nobody
drew for those changes, ``random_drives.py``'s protocol 2 (seeds given), each written four ways:

* ``rows``: one row per DR sample, its fix on it (``random_drives.py``'s CSV);
* ``odometer``: the same with a cumulative odometer (the trapezoid sum of the speed samples) in place of the speed;
* ``messages``: each fix on a row of its own 30 ms after its sample (the truth then plus its error);
* ``sensors``: as ``messages``, and the speed on rows of its own 20 ms after each heading (its value then).

Each line: the draw; per format the 8-state EKF's and SUKF's median / max at the outage ends (m; scored as
``filterwnn study dr --drive FILE --grade phone`` scores them) or the refusal; and the flags ``ERROR`` (a format
refused or raised where ``rows`` ran) and ``APART`` (a kind's median more than 1 m and 25 % from its ``rows``
median, or its max more than 5 m and 25 % from its ``rows`` max). Run from the repository root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/formats.py 90 105 > docs/study-outputs/dr/random-drives/formats_90_105.txt
"""
import os
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.join(HERE, "..", "..", "..", "..", "tests")]

import _held_out_drives as held_out  # noqa: E402
import random_drives  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

KINDS = ("EKF-8", "SUKF-8")


def write_messages(path, c, sensors):
    """The drive as a log with a row per message: the fixes 30 ms after their samples, and with ``sensors`` the
    speed 20 ms after each heading."""
    t = c["time"]
    fix = ~np.isnan(c["gps_east"])
    at = lambda k, dt: np.interp(t + dt, t, c[k])  # noqa: E731
    east = c["gps_east"] + at("true_east", 0.03) - c["true_east"]
    north = c["gps_north"] + at("true_north", 0.03) - c["true_north"]
    speed = at("speed", 0.02)
    with open(path, "w") as fh:
        fh.write(",".join(held_out.COLUMNS) + "\n")
        for k in range(len(t)):
            if sensors:
                fh.write(f"{t[k]:.6g},{c['heading'][k]:.4f},,,,,{c['true_east'][k]:.4f},{c['true_north'][k]:.4f}\n")
                fh.write(f"{t[k] + 0.02:.6g},,{speed[k]:.4f},,,,,\n")
            else:
                fh.write(f"{t[k]:.6g},{c['heading'][k]:.4f},{c['speed'][k]:.4f},,,,{c['true_east'][k]:.4f},"
                         f"{c['true_north'][k]:.4f}\n")
            if fix[k]:
                fh.write(f"{t[k] + 0.03:.6g},,,{east[k]:.4f},{north[k]:.4f},{c['gps_sigma'][k]:.6g},,\n")
    return path


def score(path):
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(read_drive_csv(path), filters=KINDS, use_gps_sigma=True, grade="phone")
    except Exception as exc:  # noqa: BLE001 -- every refusal or failure is a finding here
        return None, f"{type(exc).__name__}: {str(exc)[len(path) + 2:][:160]}"
    cells = {k: (float(np.median(res[k])), float(res[k].max())) for k in KINDS}
    return cells, " ".join(f"{k} {m:.2f} / {x:.2f}" for k, (m, x) in cells.items())


def apart(a, b):
    return any(abs(a[k][0] - b[k][0]) > max(1.0, 0.25 * b[k][0]) or abs(a[k][1] - b[k][1]) > max(5.0, 0.25 * b[k][1])
               for k in KINDS)


first, last = int(sys.argv[1]), int(sys.argv[2])
with tempfile.TemporaryDirectory() as tmp:
    for seed in range(first, last + 1):
        d, cols, _ = random_drives.drive(seed, protocol=2)
        paths = {"rows": held_out.write_csv(os.path.join(tmp, "rows.csv"), cols),
                 "odometer": held_out.write_csv(os.path.join(tmp, "odo.csv"), cols, odometer=True),
                 "messages": write_messages(os.path.join(tmp, "msg.csv"), cols, False),
                 "sensors": write_messages(os.path.join(tmp, "sensors.csv"), cols, True)}
        got = {f: score(p) for f, p in paths.items()}
        flags = []
        base = got["rows"][0]
        for f in ("odometer", "messages", "sensors"):
            if base is not None and got[f][0] is None:
                flags.append(f"ERROR {f}")
            elif base is not None and apart(got[f][0], base):
                flags.append(f"APART {f}")
        print(f"seed {seed}: {random_drives.describe(d, 2)}", flush=True)
        for f in paths:
            print(f"    {f:>8} | {got[f][1]}", flush=True)
        print(f"    flags: {' '.join(flags) or 'none'}", flush=True)
