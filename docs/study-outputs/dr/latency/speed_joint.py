"""The speed's latency tested all jointly with the other errors (this stop's first design, not kept), against the
shipped monitor, which estimates the gyro scale and the fixes' latency as without it: the fixes' latency on the
phone analogs of seeds 0-5 with +0.5, +1 and -0.5 s, one EKF pass each (phone grade, warnings only). Per drive
and monitor: the step at which it warned of the fixes' latency (-: not) and its largest |z|.

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/latency/speed_joint.py > speed_joint.txt

"all jointly" monkeypatches GPSDRFilter._estimate_errors to take every estimate from the system with the speed's
latency's row and column (what the shipped one does for the speed's latency alone).
"""
import os
import sys
import tempfile
import warnings

import numpy as np

from monitor import one_pass  # noqa: E402  (this folder's; it puts tests/ on the path)
import _held_out_drives as held_out  # noqa: E402
import filterwnn.navigation.gpsdr as gpsdr  # noqa: E402
from filterwnn.navigation.dead_reckoning import GPSDRModel  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402

F = gpsdr.GPSDRFilter
shipped_solve = F._solve


def all_jointly(self):
    """The shipped method with the first solve on the whole system (the speed's latency's row and column too)."""
    if self._so is None or not self._Ioo > 0.0:
        return shipped(self)
    I = np.block([[self._I, self._Ixo[:, None]], [self._Ixo[None, :], np.array([[self._Ioo]])]])
    J = np.block([[self._J, self._Jxo[:, None]], [self._Jxo[None, :], np.array([[self._Joo]])]])
    every = shipped_solve(I, J, np.r_[self._u, self._uo])
    n = len(self._u)  # the others' estimates from the whole system; the speed's latency's as shipped
    F._solve = staticmethod(lambda I_, J_, u_: every if len(u_) > n or every is None else (every[0][:-1], every[1][:-1]))
    try:
        return shipped(self)
    finally:
        F._solve = staticmethod(shipped_solve)


shipped = F._estimate_errors
with tempfile.TemporaryDirectory() as tmp:
    for seed in range(6):
        for tau in (0.5, 1.0, -0.5):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"),
                                                        held_out.columns("phone", seed, gps_latency=tau)))
            cells = []
            for label, method in (("shipped", shipped), ("all jointly", all_jointly)):
                F._estimate_errors = method
                m = GPSDRModel.from_grade("phone", run.scenario.dt)
                f = F(m, "ekf", x0=np.r_[run.x0, m.x0[6:]], scale_on_detection=False, latency_on_detection=False)
                top, fired = one_pass(f, run, ["latency"])
                cells.append(f"{label}: warned at {'-' if fired['latency'] is None else fired['latency']}, "
                             f"max |z| {abs(top['latency']):.2f}")
            print(f"phone seed {seed}, latency {tau:+g} s | " + " | ".join(cells), flush=True)
F._estimate_errors = shipped
