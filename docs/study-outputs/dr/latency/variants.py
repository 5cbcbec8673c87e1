"""The monitor's design, each part switched off in turn (monkeypatched; the package keeps the first, "shipped"):
one EKF pass (phone grade, warning only) over drives with a gyro scale error, fixes stamped late, and the hard
bench's drive that starts 150 degrees off (no error the model lacks; its bad start leaves the calibration off).

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/latency/variants.py shipped > variants.txt
    (then innovations, no-nuisance, last-correlation and first, appended)

- ``shipped``: the joint test, each fix's information counted at the correlation of the innovations less what
  the estimated errors explain, when it came, and the calibration states' errors as nuisance parameters;
- ``innovations``: each fix counted at the innovations' own correlation (``gps_correlation``) when it came;
- ``no-nuisance``: without the nuisance parameters;
- ``last-correlation``: every fix counted at the last fix's ``gps_correlation`` (the stop-40 scale monitor's
  z-score), with the nuisance parameters;
- ``first``: the last without the nuisance parameters (the first version of the joint test).
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..")
sys.path[:0] = [os.path.join(ROOT, "tests"), os.path.join(ROOT, "tests", "navigation")]
import _held_out_drives as held_out  # noqa: E402
import test_hard_drives as th  # noqa: E402
import filterwnn.navigation.gpsdr as gpsdr  # noqa: E402
from filterwnn.navigation.dead_reckoning import GPSDRModel  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from monitor import one_pass  # noqa: E402  (this folder's: the one-pass loop)

variant = sys.argv[1]
F = gpsdr.GPSDRFilter
if variant in ("no-nuisance", "first"):
    def _listen(self):
        self._listening = True
    F._listen = _listen
if variant == "innovations":
    F._residual_correlation = lambda self: max(self.gps_correlation, 1.0)
if variant in ("last-correlation", "first"):
    estimate = F._estimate_errors

    def _estimate_errors(self):
        J, self._J = self._J, self._I * max(self.gps_correlation, 1.0)
        try:
            estimate(self)
        finally:
            self._J = J
    F._estimate_errors = _estimate_errors


def one(label, run, grade):
    m = GPSDRModel.from_grade(grade, run.scenario.dt)
    f = F(m, "ekf", x0=np.r_[run.x0, m.x0[6:]], latency_on_detection=False, scale_on_detection=False)
    top, fired = one_pass(f, run, ["gyro_scale", "latency"])
    print(f"{variant:16s} {label:34s} | scale max |z| {abs(top['gyro_scale']):5.2f}, warned at {fired['gyro_scale']}, "
          f"end {100 * f.gyro_scale_estimate:+.2f} % | latency max |z| {abs(top['latency']):5.2f}, warned at "
          f"{fired['latency']}, end {f.latency_estimate:+.3f} s", flush=True)


with tempfile.TemporaryDirectory() as tmp:
    for name, seed, kw in (("phone", 0, {"gyro_scale": 0.01}), ("phone", 1, {"gyro_scale": 0.01}),
                           ("phone", 0, {"gyro_scale": 0.03}), ("one_hz", 0, {"gyro_scale": 0.03}),
                           ("phone", 0, {"gps_latency": 0.5}), ("phone", 1, {"gps_latency": 0.5}),
                           ("one_hz", 1, {"gps_latency": 0.5})):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed, **kw)))
        one(f"{name} seed {seed} {kw}", run, "phone")
d = th.unknown_heading
run, grade, _ = d(np.random.default_rng(np.random.SeedSequence([23, th.DRIVES.index(d)])))
one("hard bench: unknown_heading", run, grade)
