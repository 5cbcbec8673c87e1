"""Does the heading-jump test's order (the likeliest onset first, then its bounds) ever block a valid onset?
(issue 23, stop 48)

:meth:`GPSDRFilter._test_jumps` takes the onset of largest |z| and then checks its estimate against the bounds
(at least the grade's white heading noise, at most the heading bias's calibration bound): where the likeliest
onset is out of bounds, no other is taken, even one past the gate and in bounds. This counts such tests. The
test is re-implemented here with a counter (the package's arithmetic, unchanged), on ``heading_jump.py``'s
faulted drives (every analog, seeds 0-2, no fault, steps of 2, 5 and 10 degrees, a drift), EKF-8.

Run with the package at ``ROOT`` (a copy of the repository), one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/onset_order.py ROOT    # onset_order.txt

Each line: the drive, its fault, the steps the filter found, and the tests at which the order blocked another
onset (with the likeliest onset's estimate and z-score, and the others').
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests"), os.path.join(ROOT, "docs", "study-outputs", "dr", "log-faults")]

import _held_out_drives as held_out  # noqa: E402
import heading_jump as hj  # noqa: E402
from filterwnn.navigation import gpsdr  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

assert gpsdr.__file__.startswith(ROOT)
blocked = []


def test_jumps(self):
    """``GPSDRFilter._test_jumps``, counting the tests whose likeliest onset is out of bounds while another
    onset is past the gate and in them."""
    I, u, B = self._jump_nuisance() if hasattr(self, "_jump_nuisance") else (self._I, self._u, self._jB)
    Iinv = self._information_inverse(I)
    if Iinv is None:
        return
    IB = Iinv @ B
    s = self._jd - (B * IB).sum(axis=0)
    ok = s > 1e-9 * np.maximum(self._jd, 1e-300)
    if not ok.any():
        return
    s = np.where(ok, s, 1.0)
    theta = (self._ju - IB.T @ u) / s
    var = np.maximum(self._jc, 1.0) / s
    z = np.where(ok, theta / np.sqrt(var), 0.0)
    j = int(np.argmax(np.abs(z)))
    most = gpsdr.CALIBRATION_SIGMAS * np.sqrt(self.model.P0[gpsdr.HEADING_BIAS, gpsdr.HEADING_BIAS])
    inside = (self.model.sigma_heading <= np.abs(theta)) & (np.abs(theta) <= most)
    over = np.abs(z) > self.heading_jump_z
    if over[j] and not inside[j] and (over & inside).any():
        blocked.append((self.step, round(float(np.degrees(theta[j])), 2), round(float(z[j]), 2),
                        np.degrees(theta[over & inside]).round(2).tolist(), z[over & inside].round(2).tolist()))
    if abs(z[j]) > self.heading_jump_z and self.model.sigma_heading <= abs(theta[j]) <= most:
        self._take_jump(j, float(theta[j]), float(var[j]), float(z[j]))


gpsdr.GPSDRFilter._test_jumps = test_jumps
with tempfile.TemporaryDirectory() as tmp:
    for name in ("phone", "city", "one_hz"):
        for seed in (0, 1, 2):
            for fault, size in hj.FAULTS:
                c, _ = hj.faulted(held_out.columns(name, seed), fault, size)
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), c))
                blocked.clear()
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone")
                print(f"{name} {seed} {fault} {size:g}: {res['integrity']['EKF-8']['n_heading_jumps']} found, "
                      f"{len(blocked)} blocked {blocked}", flush=True)
