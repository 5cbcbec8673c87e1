"""The drive reader's compass-deviation check, and its check of a car carried, on 530 simulated drives with neither
(stop 70): the analogs of
``tests/_held_out_drives.py`` (seeds 0-109 of each; seeds 0-4 with a 3 % gyro scale error either way; the phone and
1 Hz analogs' seeds 0-4 with a 0.3 deg/s rate bias) and the random drives 200-279 of protocols 2 and 3.

    python docs/study-outputs/dr/user-trial/compass_null.py > docs/study-outputs/dr/user-trial/compass_null.txt

Each line: the drive, the test's p-value, the deviation fitted over the courses driven (deg), the card (B, C, D, E,
deg), the chords fitted, and whether the reader (checks on) warned of a deviation; "not judged": too few straight
stretches for the fit; "carried" where the reader said the car was carried. The last line counts them.
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


def fit(run):
    heading = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]]
    sigma = float(np.median(run.gps_sigma)) if run.gps_sigma is not None and len(run.gps_sigma) else None
    return P.heading_deviation(float(run.t[1] - run.t[0]), heading, run.z_dr[:, 1], run.gps_steps, run.z_gps, sigma)


def one(kind, seed, kw):
    with tempfile.TemporaryDirectory() as tmp:
        cols = (rd.drive(seed, protocol=int(kind[-1]))[1] if kind.startswith("protocol")
                else rd.held_out.columns(kind, seed, **kw))
        path = rd.held_out.write_csv(os.path.join(tmp, "d.csv"), cols)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                run = read_drive_csv(path)
            except ValueError as exc:
                return None, f"refused: {str(exc)[:100]}", False
        said = any("turns with the direction of travel" in str(w.message) for w in caught)
        carried = any("the car was carried" in str(w.message) for w in caught)
    return fit(run), said, carried


if __name__ == "__main__":
    jobs = [(f"protocol {p}", s, {}) for p in (2, 3) for s in range(200, 280)]
    jobs += [(k, s, {}) for k in ("phone", "city", "one_hz") for s in range(110)]
    jobs += [(k, s, {"gyro_scale": g}) for k in ("phone", "city", "one_hz") for s in range(5) for g in (-0.03, 0.03)]
    jobs += [(k, s, {"rate_bias": 0.3}) for k in ("phone", "one_hz") for s in range(5)]
    out = Parallel(n_jobs=2)(delayed(one)(*j) for j in jobs)
    judged, warned, ps = 0, 0, []
    carried = sum(c for _, _, c in out)
    for (kind, seed, kw), (r, said, c) in zip(jobs, out):
        name = f"{kind} {seed}" + "".join(f", {k} {v:g}" for k, v in kw.items())
        if r is None:
            print(f"{name} | {said if isinstance(said, str) else 'not judged'}" + (" | carried" if c else ""))
            continue
        judged, warned = judged + 1, warned + bool(said)
        ps.append(r[3])
        print(f"{name} | p {r[3]:.2g} | deviation {r[1]:+.1f} to {r[2]:+.1f} deg | card "
              f"{', '.join(f'{c:+.1f}' for c in r[0])} | {r[4]} chords | {'WARNED' if said else 'no warning'}")
    print(f"{len(jobs)} drives: {judged} judged, {warned} warned; the smallest p {min(ps):.2g}, the next "
          f"{sorted(ps)[1]:.2g}; {carried} told carried")
