"""Where a city analog's outage starts with its calibration off (stop 66): at each outage's start, the EKF-8's
heading bias and odometer scale against the truth's, with their standard deviations, and the outage's start and end
errors; then, at every tenth fix over the drive, the scale, its standard deviation and the filter's motion class.

    python docs/study-outputs/dr/analog-seeds/outage_start_calibration.py 93 98 > outage_start_calibration_93_98.txt

Each seed's city analog (``tests/_held_out_drives.py``), read and scored as ``filterwnn study dr --drive FILE
--grade phone`` does (20 outages of 30 s, every fix with its reported sigma). The truth's heading bias is the
measured heading less the true course (meaningless standing: those outages are marked), its scale the odometer's
distance over the true distance while moving.
"""
import copy
import pathlib
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[4] / "tests"))
import _held_out_drives as held_out  # noqa: E402
import filterwnn.studies.dr._real as real  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402

warnings.simplefilter("ignore")
SNAPS, TRACE = {}, []


def _outage_ends(f, name, run, k0s, k1s, starts, gps, sig, bar=None):
    """``filterwnn.studies.dr._real._outage_ends``, keeping each outage's starting state and the scale's track."""
    ends, begins = np.empty((len(k0s), 2)), np.empty((len(k0s), 2))
    snaps, offsets = {}, run.gps_offset_list()
    for k in range(len(run.t)):
        if k in k0s:
            snaps[k] = copy.deepcopy(f)
        f.predict()
        f.update(run.z_dr[k], gps[k], sig[k], offsets[k])
        if gps[k] is not None:
            TRACE.append((run.t[k], f.x[6], np.sqrt(f.P[6, 6]), f.motion, np.hypot(f.x[1], f.x[4])))
    for j, (k0, k1) in enumerate(zip(k0s, k1s)):
        g = copy.deepcopy(snaps[k0])
        begins[j] = g.x[[0, 3]]
        SNAPS[j] = (k0, np.array(g.x, float), np.sqrt(np.diag(np.array(g.P, float))))
        for k in range(k0, k1 + 1):
            g.predict()
            g.update(run.z_dr[k], None)
        ends[j] = g.x[[0, 3]]
    return ends, begins


real._outage_ends = _outage_ends
for seed in [int(a) for a in sys.argv[1:]]:
    SNAPS.clear()
    TRACE.clear()
    with tempfile.TemporaryDirectory() as d:
        run = read_drive_csv(held_out.write_csv(pathlib.Path(d) / "c.csv", held_out.columns("city", seed)))
    res = real.real_drive_outages(run, filters=("EKF-8",), grade="phone", use_gps_sigma=True)
    e, s = np.asarray(res["EKF-8"]), np.asarray(res["start_err"]["EKF-8"])
    xt = run.x_true
    course = np.arctan2(xt[:, 1], xt[:, 4])
    speed = np.hypot(xt[:, 1], xt[:, 4])
    moving = speed > 1.0
    bias = np.angle(np.exp(1j * (run.z_dr[:, 0] - course)))
    zeta = np.sum(run.z_dr[moving, 1]) / np.sum(speed[moving] * run.scenario.dt)
    print(f"city {seed}: EKF-8 {np.median(e):.2f} / {e.max():.2f} m; the truth's odometer scale {zeta:.4f}")
    for j in sorted(SNAPS):
        k0, x, sd = SNAPS[j]
        b = np.degrees(np.angle(np.exp(1j * (x[7] - bias[k0]))))
        standing = " (standing)" if speed[k0] < 1.0 else ""
        print(f"  outage {j + 1:2d} at {run.t[k0]:5.1f} s: start {s[j]:5.2f} m, end {e[j]:5.2f} m (grows "
              f"{e[j] - s[j]:+6.2f}); heading bias off {b:+7.2f} deg (sd {np.degrees(sd[7]):.2f}){standing}, "
              f"scale off {100 * (x[6] / zeta - 1):+5.2f} % (sd {100 * sd[6]:.2f}); speed {speed[k0]:.1f} m/s")
    print("  every tenth fix: t (s), scale, its sd, motion, the filter's speed (m/s)")
    for t, z, sd, motion, v in TRACE[::10]:
        print(f"    {t:6.1f} {z:.4f} {sd:.4f} {motion:6s} {v:4.1f}")
