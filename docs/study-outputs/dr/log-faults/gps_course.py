"""A heading (and a speed) that is the GPS receiver's, logged on every DR row (issue 23, stop 50).

A phone log may hold no gyro heading but the receiver's bearing (its course over ground), and its Doppler speed:
each changes when a fix comes and holds until the next. Such a drive has no dead reckoning of its own, yet outages
cut into it (``filterwnn study dr --drive``) keep the withheld fixes' course and speed in those columns.

The phone and city analogs of ``tests/_held_out_drives.py`` (seeds 0-1; 10 Hz and 5 Hz rows, 1 Hz fixes), written
as logged (``gyro``), with the heading replaced by the true course at each fix plus N(0, 3 deg) held until the
next (kept at a standstill below 1 m/s: ``course``), and with the speed too replaced by the true speed at each fix
plus N(0, 0.2 m/s) held (``course+speed``). Each line: DR-mech and the 8-state kinds' median / max at the outage
ends (phone grade), then the reader's warnings of a column held between the fixes. Run with the package at
``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/gps_course.py ROOT

(``gps_course.txt``: on stop 50's code, which warns of them.)
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


def from_fixes(c, seed, speed_too):
    """The columns with the heading (and the speed) the receiver's at each fix, held until the next."""
    rng = np.random.default_rng([50, seed])
    de, dn = np.gradient(c["true_east"]), np.gradient(c["true_north"])
    course, v = np.arctan2(de, dn), np.hypot(de, dn) / np.gradient(c["time"])
    fix = ~np.isnan(c["gps_east"])
    h, s = np.empty_like(course), np.empty_like(course)
    last, lv = c["heading"][0], 0.0
    for k in range(len(h)):
        if fix[k]:
            if v[k] > 1.0:
                last = np.mod(course[k] + np.deg2rad(3.0) * rng.standard_normal(), 2 * np.pi)
            lv = max(0.0, v[k] + 0.2 * rng.standard_normal())
        h[k], s[k] = last, lv
    return {**c, "heading": h, **({"speed": s} if speed_too else {})}


with tempfile.TemporaryDirectory() as tmp:
    for name in ("phone", "city"):
        for seed in (0, 1):
            c = held_out.columns(name, seed)
            for case, cols in (("gyro", c), ("course", from_fixes(c, seed, False)),
                               ("course+speed", from_fixes(c, seed, True))):
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
                said = [str(w.message) for w in caught if "changes only where there is a GPS fix" in str(w.message)]
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
                cells = [f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in KINDS]
                named = ", ".join(m.split(" changes only")[0].split("moves the ")[1] for m in said) or "none"
                print(f"{name} {seed} {case:12s} | " + " | ".join(cells) + f" | held at the fixes: {named}", flush=True)
