"""The analogs' stops creeping (a generator bug, stop 44) against exact stops: EKF-8 on seeds 0-9.

Run from the repository root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/analog-seeds/exact_stops.py > docs/study-outputs/dr/analog-seeds/exact_stops.txt

``tests/_held_out_drives.py``'s ``_truth`` integrates each speed change over the fine grid points inside its
window, and a point on a window's edge is taken or not by rounding: a window may integrate a twentieth of a
sample more or less, and every later stop keeps the remainder. ``exact_stops=True`` integrates each window by
index (the car stands at exactly 0). Each line: the analog and seed, the share of its standing samples at which
the default's car creeps and how fast (max, m/s), and EKF-8's median / max at the ends of the 20 outages of 30 s
(``filterwnn study dr --drive FILE --grade phone``'s placement and settings) with the default and with exact stops.
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


def creep(name, seed):
    seen = {}
    orig = held_out._truth

    def spy(*a, **k):
        out = orig(*a, **k)
        v = out[3]
        low = v < 0.05
        seen["share"] = float(((v > 0) & low).sum() / max(1, low.sum()))
        seen["max"] = float(v[(v > 0) & low].max()) if ((v > 0) & low).any() else 0.0
        return out

    held_out._truth = spy
    try:
        held_out.columns(name, seed)
    finally:
        held_out._truth = orig
    return seen


def score(cols, tmp):
    path = held_out.write_csv(os.path.join(tmp, "d.csv"), cols)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = real_drive_outages(read_drive_csv(path), filters=("EKF-8",), use_gps_sigma=True, grade="phone")
    return f"{np.median(res['EKF-8']):.2f} / {res['EKF-8'].max():.2f}"


def main():
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("phone", "city", "one_hz"):
            for seed in range(10):
                c = creep(name, seed)
                print(f"{name} seed {seed} | creeps on {100 * c['share']:.0f} % of its standing samples, up to "
                      f"{c['max']:.3f} m/s | EKF-8 {score(held_out.columns(name, seed), tmp)} | exact stops "
                      f"{score(held_out.columns(name, seed, exact_stops=True), tmp)}", flush=True)


if __name__ == "__main__":
    main()
