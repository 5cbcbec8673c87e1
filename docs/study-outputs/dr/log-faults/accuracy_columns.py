"""Each fix's accuracy as loggers write it (issue 23, stop 50).

``gps_sigma`` is the fix's standard deviation per axis (m). Receivers and loggers report other things: a phone's
``accuracy`` is the radius of 68 % confidence (1.51 sigma per axis for a round Gaussian), some receivers give a
95 % radius (2.45 sigma), and an NMEA log's GGA sentence gives the HDOP, a dilution of precision without a unit
(about 1), which a log's "accuracy" column may well hold. Until stop 50 the reader had no column for an HDOP.

The analogs of ``tests/_held_out_drives.py`` (``name`` seeds), each written with its fixes' accuracy as:

* ``sigma``: the sigma per axis, as the analogs report it (the phone's and the 1 Hz drive's honest, the city's
  optimistic);
* ``r68``, ``r95``: the 68 % and 95 % radius of that sigma, in ``gps_sigma``;
* ``hdop>sigma``: an HDOP in ``gps_sigma``, the sigma over 5 m (a receiver whose fixes have a 5 m sigma per axis at
  HDOP 1) rounded to 0.1 as GGA writes it, at least 0.5;
* ``gps_hdop``: that HDOP in the ``gps_hdop`` column, read with ``hdop_sigma=5`` (what ``filterwnn study dr --drive
  --grade phone`` passes: the grade's GPS sigma);
* ``gps_hdop/3``, ``gps_hdop/8``: an HDOP of a receiver whose sigma at HDOP 1 is 3 m or 8 m (the sigma over 3 or 8),
  read with the same ``hdop_sigma=5``: each fix's sigma then 1.67 or 0.63 times its own;
* ``none``: no accuracy column (every fix the grade's 5 m).

Each line: per 8-state kind the median / max at the outage ends (``filterwnn study dr --drive FILE --grade phone``'s
scoring), then the kinds that warned of inconsistency and those whose warning named an HDOP.

Run with the package at ``ROOT`` (a copy of the repository), one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/accuracy_columns.py ROOT NAMES SEEDS [VARIANTS]

(``accuracy_columns.txt``: ``one_hz,phone,city 0,1,2,3,4`` and ``one_hz,phone,city 5,6,7,8,9 sigma``.)
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
KINDS = ("EKF-8", "UKF-8", "SUKF-8")
HDOP_SIGMA = 5.0  # the phone grade's GPS sigma, what the command passes as hdop_sigma


def hdop(sigma, at_one=HDOP_SIGMA):
    return np.maximum(0.5, np.round(sigma / at_one, 1))


VARIANTS = {"sigma": ("gps_sigma", lambda s: s), "r68": ("gps_sigma", lambda s: 1.5096 * s),
            "r95": ("gps_sigma", lambda s: 2.4477 * s), "hdop>sigma": ("gps_sigma", hdop),
            "gps_hdop": ("gps_hdop", hdop), "gps_hdop/3": ("gps_hdop", lambda s: hdop(s, 3.0)),
            "gps_hdop/8": ("gps_hdop", lambda s: hdop(s, 8.0)), "none": (None, None)}


def write(path, cols, column, values):
    names = [c for c in held_out.COLUMNS if c != "gps_sigma"] + ([column] if column else [])
    cols = dict(cols)
    if column:
        cols[column] = values
    with open(path, "w") as fh:
        fh.write(",".join(names) + "\n")
        for k in range(len(cols["time"])):
            fh.write(",".join("" if np.isnan(cols[c][k]) else f"{cols[c][k]:.6g}" if c in ("time", column)
                              else f"{cols[c][k]:.4f}" for c in names) + "\n")
    return path


names, seeds = sys.argv[2].split(","), [int(s) for s in sys.argv[3].split(",")]
variants = sys.argv[4].split(",") if len(sys.argv) > 4 else list(VARIANTS)
with tempfile.TemporaryDirectory() as tmp:
    for name in names:
        for seed in seeds:
            cols = held_out.columns(name, seed)
            for v in variants:
                column, f = VARIANTS[v]
                path = write(os.path.join(tmp, "d.csv"), cols, column, f(cols["gps_sigma"]) if f else None)
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    run = read_drive_csv(path, hdop_sigma=HDOP_SIGMA)
                    res = real_drive_outages(run, filters=KINDS, use_gps_sigma=run.gps_sigma is not None,
                                             grade="phone")
                said = [str(w.message) for w in caught if "is inconsistent" in str(w.message)]
                told = [m for m in said if "HDOP" in m]
                cells = [f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in KINDS]
                print(f"{name} {seed} {v:10s} | " + " | ".join(cells)
                      + f" | inconsistent: {len(said)} kind(s), HDOP named: {len(told)}", flush=True)
