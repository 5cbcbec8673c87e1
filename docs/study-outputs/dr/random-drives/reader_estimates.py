"""The drive reader's estimates on the random drives (stop 44): the speed scale and the heading's offset and
drift it reads from the drive's own fixes, against the drawn ones, and whether it refuses the drive.

Run from the repository root::

    python docs/study-outputs/dr/random-drives/reader_estimates.py --seeds 0-59 > docs/study-outputs/dr/random-drives/reader_estimates.txt

Each line: the seed, the drawn odometer scale, heading offset (deg) and rate bias (deg/s), and the reader's
``speed_scale``, ``heading_offset`` (offset +- its standard error, drift, median residual about the line), or
its refusal; the warnings it gave (``plausibility: ...``). The last lines: the median and largest error of
each estimate over the drives read.
"""
import argparse
import os
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import random_drives as rd  # noqa: E402
from filterwnn.navigation import _plausibility as P  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402


def one(seed, tmp):
    d, cols, _ = rd.drive(seed)
    path = rd.held_out.write_csv(os.path.join(tmp, f"random_{seed}.csv"), cols)
    head = f"seed {seed}: scale {d['scale']:.3f}, offset {d['offset']:+.1f}, rate bias {d['rate_bias']:+.3f}"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            read_drive_csv(path)
        except ValueError as e:
            return head + f" | REFUSED: {str(e)[:160]}", None
        run = read_drive_csv(path, checks=False)
    heading = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]]  # the reader's headings (the first sample's for the start)
    args = (float(run.t[1] - run.t[0]), heading, run.z_dr[:, 1], run.gps_steps, run.z_gps,
            float(np.median(run.gps_sigma)))
    r, h = P.speed_scale(*args), P.heading_offset(*args)
    said = [str(w.message)[:90] for w in caught if "plausibility" in str(w.message)]
    line = (f"{head} | read: scale {r[0]:.3f} +- {r[1]:.3f}, offset {h[0]:+.1f} +- {h[1]:.1f}, drift {h[2]:+.3f}, "
            f"residual {h[3]:.1f} | {'; '.join(said) or 'no warning'}")
    return line, (100 * abs(r[0] / d["scale"] - 1), abs(h[0] - d["offset"]), abs(h[2] - d["rate_bias"]))


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", default="0-59")
    a = ap.parse_args()
    errs = []
    with tempfile.TemporaryDirectory() as tmp:
        for s in rd.seeds(a.seeds):
            line, e = one(s, tmp)
            print(line, flush=True)
            if e:
                errs.append(e)
    e = np.array(errs)
    refused = len(rd.seeds(a.seeds)) - len(e)
    print(f"read {len(e)}, refused {refused}")
    for k, name in enumerate(("speed scale (%)", "heading offset (deg)", "drift (deg/s)")):
        print(f"{name}: error median {np.median(e[:, k]):.3g}, max {e[:, k].max():.3g}")
