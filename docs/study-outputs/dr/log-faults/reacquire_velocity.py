"""Tried, not kept: a re-acquisition that re-takes the velocity from the dead reckoning (issue 23, stop 50).

``spikes.py`` traced one heading glitch of 90 degrees at 3 m/s (1 Hz analog, seed 0, sample 125) sending the
EKF-8's velocity to 51 m/s against an odometer of 5-15 m/s, and a re-acquisition that reset its position but not
its velocity. ``reacquire_velocity.patch`` (on 62383ca) also widens the velocity variances at a re-acquisition by
the difference between the filter's velocity and the dead reckoning's (odometer over scale, heading less bias),
when ``REACQ_VEL`` is set in the environment. The drive reader's spike rule is switched off here, so the filter
meets the glitch. Each line, per 8-state kind, the median / max at the outage ends (phone grade) and the count of
re-acquisitions; then clean analogs and an HDOP in ``gps_sigma`` (``accuracy_columns.py``'s form). Run with the
patched package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/reacquire_velocity.py ROOT
    REACQ_VEL=1 OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/reacquire_velocity.py ROOT

(``reacquire_velocity.txt``: off, then on.)
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation import scenarios  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

assert real_drive_outages.__code__.co_filename.startswith(ROOT)
scenarios._heading_spikes = lambda t, h, s: h  # let the glitch through: the filter's own answer to it
KINDS = ("EKF-8", "UKF-8", "SUKF-8")


def score(cols, tmp):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols), hdop_sigma=5.0)
        res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
    return " | ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f} ({res['integrity'][k]['n_reacquired']})"
                      for k in KINDS)


with tempfile.TemporaryDirectory() as tmp:
    c = held_out.columns("one_hz", 0)
    glitch = dict(c, heading=c["heading"].copy())
    glitch["heading"][125] = np.mod(c["heading"][125] + np.pi / 2, 2 * np.pi)
    print("one_hz 0 one spike at 3 m/s |", score(glitch, tmp), flush=True)
    for name, seeds in (("city", range(5)), ("phone", (0, 1)), ("one_hz", (0, 1))):
        for seed in seeds:
            print(f"{name} {seed} clean |", score(held_out.columns(name, seed), tmp), flush=True)
    for name in ("phone", "one_hz"):
        c = held_out.columns(name, 1)
        c["gps_sigma"] = np.maximum(0.5, np.round(c["gps_sigma"] / 5, 1))
        print(f"{name} 1 hdop in gps_sigma |", score(c, tmp), flush=True)
