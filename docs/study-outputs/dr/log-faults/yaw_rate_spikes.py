"""Spikes in a yaw-rate column (issue 23, stop 50).

A gyro's glitch (a bus error, a saturated sample) logs one yaw rate far from the car's; integrated by the reader
(``yaw_rate`` column), it turns every later heading by its excess times its interval: 1.5 rad/s for a sample of a
1 Hz log is 86 degrees. The 1 Hz and phone analogs of ``tests/_held_out_drives.py`` (seed 0) written with a yaw
rate in place of the heading (the heading's gradient over the samples' times), as they are (``clean``) and with
20 moving samples (over 3 m/s, drawn from ``SeedSequence([50, 8])``) replaced by 1.5 rad/s (``rate spikes``).
Each line: DR-mech and the 8-state kinds' median / max at the outage ends (phone grade), or the refusal, and the
reader's warning of yaw-rate spikes. Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/yaw_rate_spikes.py ROOT

(``yaw_rate_spikes.txt``: on e33ed70, then on stop 50's reader, which interpolates a run of up to 3 yaw-rate
samples past what a car turns at its speed.)
"""
import os
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
KINDS = ("DR-mech", "EKF-8", "UKF-8", "SUKF-8")
NAMES = ("time", "yaw_rate", "speed", "gps_east", "gps_north", "gps_sigma", "true_east", "true_north")


def write(path, cols, rate):
    cols = dict(cols, yaw_rate=rate)
    with open(path, "w") as fh:
        fh.write(",".join(NAMES) + "\n")
        for k in range(len(cols["time"])):
            fh.write(",".join("" if np.isnan(cols[c][k]) else f"{cols[c][k]:.6g}" for c in NAMES) + "\n")
    return path


with tempfile.TemporaryDirectory() as tmp:
    for name in ("one_hz", "phone"):
        c = held_out.columns(name, 0)
        rate = np.gradient(np.unwrap(c["heading"]), c["time"])
        k = np.random.default_rng([50, 8]).choice(np.flatnonzero(c["speed"] > 3.0), 20, replace=False)
        for case in ("clean", "rate spikes"):
            r = rate.copy()
            if case == "rate spikes":
                r[k] = 1.5
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                try:
                    run = read_drive_csv(write(os.path.join(tmp, "y.csv"), c, r))
                except ValueError as e:
                    print(f"{name} 0 {case:11s} | refused: {str(e).split(': ', 1)[1][:160]}...", flush=True)
                    continue
            said = [str(w.message).split(" run(s)")[0] + " run(s)" for w in caught if "yaw rate sample" in str(w.message)]
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
            cells = [f"{q} {np.median(res[q]):.2f} / {res[q].max():.2f}" for q in KINDS]
            print(f"{name} 0 {case:11s} | " + " | ".join(cells) + f" | spikes warned: {', '.join(said) or 'none'}",
                  flush=True)
