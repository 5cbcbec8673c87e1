"""A heading that steps during a stop (a fused orientation re-aligning), cut into the analogs (issue 23, stop 45).

Run from the repository root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_step.py > docs/study-outputs/dr/log-faults/heading_step.txt

(``PYTHONPATH=<an older checkout>`` runs that version's filters on the same drives: ``heading_step_before_a1d6794.txt``.)

The drives: the phone and 1 Hz analogs of ``tests/_held_out_drives.py``, seeds 0-2, with exact stops
(``exact_stops=True``: the car stands at exactly 0, so each stop is one). In every stop of at least 5 s the
heading steps, halfway through, by 0, 0.5, 1 or 2 degrees, up or down (drawn per stop from the seed): what a
phone's fused orientation does when it re-aligns to its compass, or a logger's heading to GPS. Each line: the
analog, seed and step, then each 8-state kind's median / max at the ends of the 20 outages of 30 s
(``filterwnn study dr --drive FILE --grade phone``'s placement and settings) and how many of its stops it
found stepped (``n_zero_rate_stepped``; "-" in a version without it).
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
STEPS_DEG = (0.0, 0.5, 1.0, 2.0)


def stops(speed, dt, seconds=5.0):
    """The ``(first, end)`` sample indices of the runs of zero speed lasting at least ``seconds``."""
    s = np.asarray(speed) == 0
    d = np.diff(np.concatenate([[0], s.astype(int), [0]]))
    return [(a, b) for a, b in zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1)) if (b - a) * dt >= seconds]


def stepped(cols, deg, seed):
    c = {k: v.copy() for k, v in cols.items()}
    dt = c["time"][1] - c["time"][0]
    rng = np.random.default_rng(seed)
    for a, b in stops(c["speed"], dt):
        m = (a + b) // 2
        c["heading"][m:] = np.mod(c["heading"][m:] + np.deg2rad(deg) * rng.choice([-1, 1]), 2 * np.pi)
    return c


def main():
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("phone", "one_hz"):
            for seed in range(3):
                cols = {k: np.asarray(v, dtype=float) for k, v in held_out.columns(name, seed, exact_stops=True).items()}
                n_stops = len(stops(cols["speed"], cols["time"][1] - cols["time"][0]))
                for deg in STEPS_DEG:
                    path = held_out.write_csv(os.path.join(tmp, "d.csv"), stepped(cols, deg, seed))
                    cells = []
                    for kind in KINDS:
                        with warnings.catch_warnings():
                            warnings.simplefilter("ignore")
                            res = real_drive_outages(read_drive_csv(path), filters=(kind,), use_gps_sigma=True,
                                                     grade="phone")
                        found = res["integrity"][kind].get("n_zero_rate_stepped")  # (None: a version without it)
                        cells.append(f"{kind} {np.median(res[kind]):.2f} / {res[kind].max():.2f} "
                                     f"(stepped {'-' if found is None else found})")
                    print(f"{name} seed {seed} ({n_stops} stops of 5 s or more), step {deg:g} deg | " + " | ".join(cells),
                          flush=True)


if __name__ == "__main__":
    main()
