"""A heading far from the filter's: the [heading, distance] update overshoots (issue 23, stop 51).

Stop 50 traced one 90 degree heading glitch at 3 m/s (the 1 Hz analog of ``tests/_held_out_drives.py``, seed 0,
sample 125, as the car pulls away) sending the 8-state EKF's velocity to 51 m/s against an odometer of 15 m/s, and
an outage 815 m off, and did not find why. The update of ``[heading, distance]`` is linearised about the filter's
heading: a heading 90 degrees off moves the velocity along the tangent, past the measured heading and longer than
the odometer's speed; the acceleration state takes the difference, the next prediction is farther off, and the
filter oscillates with a growing amplitude. Stop 51 takes such a sample (farther than ``heading_linear_limit``,
30 degrees, from the filter's heading) as the measured velocity vector, linear in the velocity.

The drive reader's spike rules are switched off here, so the filters meet the glitches. Three parts, each line the
8-state kinds' median / max at the outage ends (phone grade) and ``n_heading_far``, with the rule ``off``
(``heading_linear_limit=None``, the filter as before) and ``on`` (the default):

1. the one glitch at sample 125 of the 1 Hz analog (seed 0), turned by 20 to 180 degrees;
2. ``spikes.py``'s drives (analogs seeds 0-2, 20 moving samples set to 70.8 m/s or turned by 90 degrees), for
   the names given;
3. (``clean``) the analogs as logged, seeds 0-9, for the names given: ``n_heading_far`` (0: every number as before).

Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_linear.py ROOT glitch
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_linear.py ROOT spikes one_hz,city
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_linear.py ROOT spikes phone
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_linear.py ROOT clean one_hz,phone,city

(``heading_linear.txt``, the four runs in turn.)
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation import gpsdr, scenarios  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

assert real_drive_outages.__code__.co_filename.startswith(ROOT)
KINDS = ("EKF-8", "UKF-8", "SUKF-8")
DEFAULTS = gpsdr.GPSDRFilter.__init__.__kwdefaults__


def read(cols, tmp, spikes_off=True):
    keep = scenarios._heading_spikes, scenarios._speed_spikes
    if spikes_off:  # let the glitches through: the filter's own answer to them
        scenarios._heading_spikes = lambda t, h, s: h
        scenarios._speed_spikes = lambda t, s: s
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
    finally:
        scenarios._heading_spikes, scenarios._speed_spikes = keep


def score(run, rule):
    DEFAULTS["heading_linear_limit"] = gpsdr.HEADING_LINEAR_LIMIT if rule == "on" else None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = real_drive_outages(run, filters=KINDS, use_gps_sigma=True, grade="phone")
    return " | ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f} ({res['integrity'][k]['n_heading_far']} far)"
                      for k in KINDS)


part = sys.argv[2]
names = sys.argv[3].split(",") if len(sys.argv) > 3 else []
with tempfile.TemporaryDirectory() as tmp:
    if part == "glitch":
        c = held_out.columns("one_hz", 0)
        for deg in (20, 30, 45, 60, 90, 135, 180):
            g = dict(c, heading=c["heading"].copy())
            g["heading"][125] = np.mod(c["heading"][125] + np.radians(deg), 2 * np.pi)
            run = read(g, tmp)
            for rule in ("off", "on"):
                print(f"one_hz 0 one glitch of {deg:3d} deg at 3 m/s, rule {rule:3s} | {score(run, rule)}", flush=True)
    elif part == "spikes":
        for name in names:
            for seed in (0, 1, 2):
                c = held_out.columns(name, seed)
                k = np.random.default_rng([50, 7, seed]).choice(np.flatnonzero(c["speed"] > 3.0), 20, replace=False)
                for case in ("speed spikes", "heading spikes"):
                    cols = dict(c)
                    if case == "speed spikes":
                        cols["speed"] = c["speed"].copy()
                        cols["speed"][k] = 70.8  # 255 km/h
                    else:
                        cols["heading"] = c["heading"].copy()
                        cols["heading"][k] = np.mod(c["heading"][k] + np.pi / 2, 2 * np.pi)
                    run = read(cols, tmp)
                    for rule in ("off", "on"):
                        print(f"{name} {seed} {case:14s} rule {rule:3s} | {score(run, rule)}", flush=True)
    elif part == "clean":
        for name in names:
            for seed in range(10):
                run = read(held_out.columns(name, seed), tmp, spikes_off=False)
                print(f"{name} {seed} clean, rule on | {score(run, 'on')}", flush=True)
