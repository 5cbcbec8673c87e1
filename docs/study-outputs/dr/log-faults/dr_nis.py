"""The DR sample's own normalised innovation squared, before its update (issue 23, stop 51).

For a test of each DR sample as each fix is tested (not built): per drive, the EKF-8's outage ends (median / max,
m) and, per motion the filter took (``still``: the zero-velocity update, ``slow``: the velocity vector, ``moving``),
the largest NIS of the sample's two rows (``H P H^T + R`` from the prior), its 99.99th percentile and the samples
past 41.4 (the fixes' reject gate) and 1e3, over every pass. ``analogs``: seeds 0-1 as logged, the sample and
onavdata's drives (survey grade); ``spikes``: ``spikes.py``'s 1 Hz and city drives (seed 0) with twenty 255 km/h
speed spikes, the reader's spike rules off. Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/dr_nis.py ROOT analogs
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/dr_nis.py ROOT spikes
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/dr_nis.py ROOT analogs 2 10
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/dr_nis.py ROOT random 2 0 55
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/dr_nis.py ROOT random 2 55 110

(``dr_nis.txt``: the first two in turn, on stop 51's code; ``dr_nis_more.txt``: the other three, on 0d2c451:
``random`` runs ``random-drives/random_drives.py``'s drives of the protocol given, seeds from, to.)
"""
import os
import sys
import tempfile
import warnings

import numpy as np
ROOT = os.path.abspath(sys.argv[1]); sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr/random-drives"]
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation import gpsdr, scenarios
from filterwnn.navigation.drives import read_drive_csv, sample_drive_path, load_car_drive, CAR_DRIVES
from filterwnn.studies.dr import real_drive_outages
REC = []
orig = gpsdr.GPSDRFilter._update
def _update(self, z, R, kw):
    m = self.model
    x, P = self.kf.x, self.kf.P
    H = np.asarray(m.HJacobian(x, **kw))[:2]
    h = np.asarray(m.hx(x, **kw))[:2]
    y = z[:2] - h
    if not kw["velocity"]:
        y[0] = (y[0] + np.pi) % (2 * np.pi) - np.pi
    S = H @ P @ H.T + R[:2, :2]
    REC.append((float(y @ np.linalg.solve(S, y)), self.motion))
    return orig(self, z, R, kw)
gpsdr.GPSDRFilter._update = _update
def go(label, run, grade="phone", sig=True, kinds=("EKF-8",)):
    for kd in kinds:
        REC.clear()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=(kd,), use_gps_sigma=sig and run.gps_sigma is not None, grade=grade)
        out = []
        for mo in ("still", "slow", "moving"):
            r = np.array([a for a, b in REC if b == mo])
            if len(r):
                out.append(f"{mo} max {r.max():.3g} p9999 {np.quantile(r, .9999):.3g} n>41 {int((r > 41.4).sum())} n>1e3 {int((r > 1e3).sum())}")
        print(label, kd, f"{np.median(res[kd]):.2f}/{res[kd].max():.2f}", "|", " | ".join(out), flush=True)
tmp = tempfile.mkdtemp()
which = sys.argv[2]
if which == "analogs":
    lo, hi = (int(sys.argv[3]), int(sys.argv[4])) if len(sys.argv) > 4 else (0, 2)
    for name in ("one_hz", "phone", "city"):
        for seed in range(lo, hi):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed)))
            go(f"{name} {seed}", run)
    if lo == 0:
        run = read_drive_csv(sample_drive_path()); go("sample", run)
        for d in CAR_DRIVES:
            go(d, load_car_drive(d), "survey", sig=False)
elif which == "random":
    import random_drives  # noqa: E402
    for seed in range(int(sys.argv[4]), int(sys.argv[5])):
        d, cols, _ = random_drives.drive(seed, int(sys.argv[3]))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
        go(f"protocol {sys.argv[3]} seed {seed} dt {d['dt']:g}", run)
elif which == "spikes":
    scenarios._heading_spikes = lambda t, h, s: h
    scenarios._speed_spikes = lambda t, s: s
    for name in ("one_hz", "city"):
        c = held_out.columns(name, 0)
        k = np.random.default_rng([50, 7, 0]).choice(np.flatnonzero(c["speed"] > 3.0), 20, replace=False)
        c["speed"] = c["speed"].copy(); c["speed"][k] = 70.8
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), c))
        go(f"{name} 0 speed spikes", run)
