"""The drive reader's check of fixes dragged away from the dead-reckoned track (a spoofer's walk) on 530
simulated drives without one: the analogs of ``tests/_held_out_drives.py`` (seeds 0-109 of each; seeds 0-4 with a
3 % gyro scale error either way; the phone and 1 Hz analogs' seeds 0-4 with a 0.3 deg/s rate bias) and the random
drives 200-279 of protocols 2 and 3; then any drive files given (the user trials' drives).

    python docs/study-outputs/dr/user-trial/drag_null.py [DRIVE.csv ...] > docs/study-outputs/dr/user-trial/drag_null.txt

Each line: the drive, its windows (:func:`filterwnn.navigation._plausibility.drag_windows`), the least p of the windows
that could count (the drag at least ``DRAG_MIN_SPEED``, the car turning at least ``DRAG_MIN_TURN_DEG``) with that
window's start, drag speed and turn, the least p a stretch could be named at (the larger p of two such windows at
most two spacings apart: ``DRAG_MIN_WINDOWS``), and whether the reader (checks on) warned of a drag. The last lines
give the margins against ``DRAG_LEVEL``.
"""
import os
import sys
import tempfile
import warnings

import numpy as np
from joblib import Parallel, delayed

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "docs", "study-outputs", "dr", "random-drives"))

import random_drives as rd  # noqa: E402
from filterwnn.navigation import _plausibility as P  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402


def summary(run, said):
    heading = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]]
    wins = P.drag_windows(float(run.t[1] - run.t[0]), heading, run.z_dr[:, 1], run.gps_steps, run.z_gps)
    could = [w for w in wins if np.hypot(w[3], w[4]) >= P.DRAG_MIN_SPEED and w[5] >= P.DRAG_MIN_TURN_DEG]
    best = min(could, key=lambda w: w[2]) if could else None
    pair = min((max(a[2], b[2]) for i, a in enumerate(could) for b in could[i + 1:]
                if b[0] - a[0] <= 2 * P.DRAG_EVERY_S + 1e-6), default=1.0)
    return len(wins), best, pair, said


def read(path):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            run = read_drive_csv(path, progress=False)
        except ValueError as exc:
            return f"refused: {str(exc).replace(str(path), os.path.basename(str(path)))[:100]}"
    return summary(run, any("walk away from the dead-reckoned track" in str(w.message) for w in caught))


def one(kind, seed, kw):
    with tempfile.TemporaryDirectory() as tmp:
        cols = (rd.drive(seed, protocol=int(kind[-1]))[1] if kind.startswith("protocol")
                else rd.held_out.columns(kind, seed, **kw))
        return read(rd.held_out.write_csv(os.path.join(tmp, "d.csv"), cols))


def line(name, r):
    if isinstance(r, str):
        return f"{name} | {r}"
    n, best, pair, said = r
    most = (f"least p {best[2]:.2g} at {best[0]:.0f} s, {np.hypot(best[3], best[4]):.2f} m/s, turn {best[5]:.0f} deg"
            if best else "no window could count")
    return f"{name} | {n} windows | {most} | pair {pair:.2g} | {'WARNED' if said else 'no warning'}"


def margins(label, out):
    got = [r for r in out if not isinstance(r, str)]
    ps = sorted(r[1][2] for r in got if r[1] is not None)
    pairs = sorted(r[2] for r in got)
    fast = [np.hypot(r[1][3], r[1][4]) for r in got if r[1] is not None and r[1][2] < 1e-6]
    print(f"{label}: {len(out)} drives, {len(got)} read, {sum(r[3] for r in got)} warned; the least window p "
          f"{ps[0]:.2g} (next {ps[1]:.2g}), the least pair p {pairs[0]:.2g} (next {pairs[1]:.2g}); the fastest drag "
          f"of those windows under 1e-6: {max(fast, default=0):.2f} m/s ({len(fast)}); DRAG_LEVEL {P.DRAG_LEVEL:g}")


if __name__ == "__main__":
    jobs = [(f"protocol {p}", s, {}) for p in (2, 3) for s in range(200, 280)]
    jobs += [(k, s, {}) for k in ("phone", "city", "one_hz") for s in range(110)]
    jobs += [(k, s, {"gyro_scale": g}) for k in ("phone", "city", "one_hz") for s in range(5) for g in (-0.03, 0.03)]
    jobs += [(k, s, {"rate_bias": 0.3}) for k in ("phone", "one_hz") for s in range(5)]
    out = Parallel(n_jobs=2)(delayed(one)(*j) for j in jobs)
    for (kind, seed, kw), r in zip(jobs, out):
        print(line(f"{kind} {seed}" + "".join(f", {k} {v:g}" for k, v in kw.items()), r))
    files = [read(p) for p in sys.argv[1:]]
    for path, r in zip(sys.argv[1:], files):
        print(line(os.path.basename(path), r))
    margins("simulated drives without a drag", out)
    if files:
        margins("drive files", files)
