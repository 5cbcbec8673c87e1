"""Tried and not kept (issue 23): correlated fixes given less weight on the position, on the design seeds.

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/analog-seeds/position_weights.py > docs/study-outputs/dr/analog-seeds/position_weights.txt

The variants, each on the phone and city analogs of seeds 0 and 1 (EKF-8, phone grade, scored as
``filterwnn study dr --drive FILE --grade phone``): ``base`` the filter as shipped; ``pos 1/c`` and
``pos+vel 1/c`` the position (and velocity) rows of each fix's gain times ``1 / gps_correlation``
(the Schmidt update the calibration states already get), ``pos 1/sqrt(c)`` times its square root;
``R x4/x16/x64`` every fix's reported variance times a fixed factor. The lines give the median /
max at the outage ends and the median error at the outage starts (m). The script patches the
filter in memory; nothing here is used by the package.
"""

import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation import gpsdr  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

ORIGINAL = gpsdr.GPSDRFilter._gain_weights


def _weights(rows, power):
    def gain_weights(self, gps):
        w = ORIGINAL(self, gps)
        c = self.gps_correlation if gps else 1.0
        if c <= 1.0:
            return w
        w = np.ones(self.model.dim_x) if w is None else w
        w[rows] *= c ** -power
        return w
    return gain_weights


VARIANTS = {"base": (None, 1.0), "pos 1/c": (([0, 3], 1.0), 1.0), "pos+vel 1/c": (([0, 1, 3, 4], 1.0), 1.0),
            "pos 1/sqrt(c)": (([0, 3], 0.5), 1.0), "R x4": (None, 4.0), "R x16": (None, 16.0),
            "R x64": (None, 64.0)}


def main():
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("phone", "city"):
            for seed in (0, 1):
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, f"{name}{seed}.csv"),
                                                        held_out.columns(name, seed)))
                for label, (weights, scale) in VARIANTS.items():
                    gpsdr.GPSDRFilter._gain_weights = ORIGINAL if weights is None else _weights(*weights)
                    r = run._replace(gps_sigma=run.gps_sigma * np.sqrt(scale))
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore", RuntimeWarning)
                        res = real_drive_outages(r, filters=("EKF-8",), use_gps_sigma=True, grade="phone")
                    e = res["EKF-8"]
                    print(f"{name} seed {seed} {label:14s} | EKF-8 {np.median(e):.2f} / {e.max():.2f}, "
                          f"start {np.median(res['start_err']['EKF-8']):.2f}", flush=True)
    gpsdr.GPSDRFilter._gain_weights = ORIGINAL


if __name__ == "__main__":
    main()
