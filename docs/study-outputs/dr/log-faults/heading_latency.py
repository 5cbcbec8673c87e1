"""A heading stamped late: half an interval for a heading averaged over each sample's (issue 23, stop 51).

A log thinned to 1 Hz by averaging gives each sample the mean heading of its second, the heading half a second
before its stamp in a turn; a heading on another clock than the speed and the fixes is late (or early) by their
offset. The 1 Hz analogs of ``tests/_held_out_drives.py`` (seeds 0-2), their heading read that long before its
stamp (interpolated along the shorter arc), were scored as ``filterwnn study dr --drive FILE --grade phone``
scores them: as read, and with the drive reader's ``heading_latency`` (``--heading-latency``) at the value the
filters' warnings name and at the true one. Each line: DR-mech and the 8-state kinds' median / max at the outage
ends, then the EKF-8's latency warnings (the fixes' and the speed's estimates, and whether they name the
heading). Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_latency.py ROOT

(``heading_latency.txt``.)
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
KINDS = ("DR-mech", "EKF-8", "UKF-8", "SUKF-8")


def late(heading, t, lag):
    """The heading ``lag`` s before each stamp (along the shorter arc; the first held)."""
    return np.mod(np.interp(t - lag, t, np.unwrap(heading)), 2 * np.pi)


def run(cols, tmp, **kw):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols), **kw)
        res = real_drive_outages(r, filters=KINDS, use_gps_sigma=True, grade="phone")
    told = [str(w.message) for w in caught if str(w.message).startswith("EKF-8") and "latency" in str(w.message)]
    named = [m for m in told if "heading_latency=" in m]
    found = [re.search(r"(the (?:fixes'|speed's) latency): by step (\d+) the fixes show (?:themselves|the speed) "
                       r"([-+][\d.]+) s", m) for m in told]
    said = "; ".join(f.expand(r"\1 \3 s at step \2") for f in found if f)
    value = re.search(r"heading_latency=([-\d.]+)", named[0]).group(1) if named else None
    cells = " | ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in KINDS)
    return f"{cells} | EKF-8 told: {said or 'nothing'}; heading named: {value or 'no'}", value


with tempfile.TemporaryDirectory() as tmp:
    for seed in (0, 1, 2):
        c = held_out.columns("one_hz", seed)
        print(f"one_hz {seed} clean           | {run(c, tmp)[0]}", flush=True)
        for lag in (0.5, 1.0, -0.5):
            cc = dict(c, heading=late(c["heading"], c["time"], lag))
            line, value = run(cc, tmp)
            print(f"one_hz {seed} heading {lag:+.1f} s late | {line}", flush=True)
            if value is not None:
                print(f"one_hz {seed}   read with --heading-latency {value} (named) | "
                      f"{run(cc, tmp, heading_latency=float(value))[0]}", flush=True)
            print(f"one_hz {seed}   read with --heading-latency {lag:g} (true) | "
                  f"{run(cc, tmp, heading_latency=lag)[0]}", flush=True)
