"""The drive reader's yaw-rate start of stop 71 on 148 simulated drives whose gyro neither saturates nor warms up:
the analogs of ``tests/_held_out_drives.py`` (seeds 0-39 of each; the phone and 1 Hz analogs' seeds 0-4 with a 0.3
deg/s rate bias; seeds 0-2 of each with a 3 % gyro scale error either way) written with a ``yaw_rate_deg`` column as
``../log-faults/yaw_rate.py`` writes it. Each line: the drive, and whether the reader told its rate saturated
(SATURATED), started it by the piecewise line (PIECEWISE) or by the straight one (line); the last line counts them.

    python docs/study-outputs/dr/user-trial/yaw_null.py > docs/study-outputs/dr/user-trial/yaw_null.txt
"""
import os
import sys
import tempfile
import warnings

import numpy as np
from joblib import Parallel, delayed

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402


def one(name, seed, kw):
    """The reader's verdict on one analog written with its yaw rate."""
    c = held_out.columns(name, seed, **kw)
    rate = np.degrees(np.gradient(np.unwrap(c["heading"]), c["time"]))
    names = [("yaw_rate_deg" if k == "heading" else k) for k in held_out.COLUMNS]
    c["yaw_rate_deg"] = rate
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "y.csv")
        with open(path, "w") as fh:
            fh.write(",".join(names) + "\n")
            for k in range(len(c["time"])):
                fh.write(",".join("" if np.isnan(c[x][k]) else f"{c[x][k]:.6g}" if x in ("time", "gps_sigma")
                                  else f"{c[x][k]:.5f}" for x in names) + "\n")
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                read_drive_csv(path)
            except ValueError as e:
                return f"refused: {str(e)[-120:]}"
    said = [str(w.message) for w in caught]
    sat = any("largest value" in w for w in said)
    pw = any("piecewise line" in w for w in said)
    return ("SATURATED " if sat else "") + ("PIECEWISE" if pw else "") or "line"

if __name__ == "__main__":
    jobs = [(k, s, {}) for k in ("phone", "city", "one_hz") for s in range(40)]
    jobs += [(k, s, {"rate_bias": 0.3}) for k in ("phone", "one_hz") for s in range(5)]
    jobs += [(k, s, {"gyro_scale": g}) for k in ("phone", "city", "one_hz") for s in range(3) for g in (-0.03, 0.03)]
    out = Parallel(n_jobs=2)(delayed(one)(*j) for j in jobs)
    for j, o in zip(jobs, out):
        print(j[0], j[1], "".join(f", {k} {v:g}" for k, v in j[2].items()), "|", o)
    print(len(jobs), "drives:", sum("SATURATED" in o for o in out), "told saturated,",
          sum("PIECEWISE" in o for o in out), "started piecewise,", sum(o.startswith("refused") for o in out), "refused")
