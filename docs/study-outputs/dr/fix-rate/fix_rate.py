"""The city analog with its fixes at another rate: the worst outage ends of every 8-state kind.

The same urban-canyon error process (a street's multipath, correlated over 15 s, and jumps on
4 % of the fixes), sampled ``--rate`` times a second instead of once; the odometry and the gyro
are the 1 Hz analog's (5 Hz). Phone grade, the fixes' reported sigma, twenty 30 s outages, as
``filterwnn study dr --drive``. ``--whiteness-window`` and ``--correlated-fixes`` override
``GPSDRFilter``'s defaults.

Run from the repository root::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/fix-rate/fix_rate.py --rate 5 --seeds 0-9
"""

import argparse
import os
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", "..", ".."))
sys.path[:0] = [os.path.join(ROOT, "tests"), os.path.join(HERE, "..", "gps-scale")]

import _held_out_drives as held_out  # noqa: E402
from run_gps_scale import EXTRA, KINDS8, TARGETS, _run  # noqa: E402

from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.navigation.gpsdr import GPSDRFilter  # noqa: E402


def seeds(text):
    a, _, b = text.partition("-")
    return range(int(a), int(b or a) + 1)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--rate", type=float, default=5.0, help="fixes per second (default 5)")
    p.add_argument("--seeds", type=seeds, default=seeds("0-9"), help="analog seeds, e.g. 0-9")
    p.add_argument("--whiteness-window", type=float, default=None,
                   help="GPSDRFilter's whiteness_window (default: the package's)")
    p.add_argument("--min-fix-interval", type=float, default=None,
                   help="GPSDRFilter's min_fix_interval (default: the package's)")
    p.add_argument("--white", type=float, default=None,
                   help="replace the fixes' errors by white ones of this sigma per axis (m), reported as such")
    p.add_argument("--keep-every", type=int, default=1,
                   help="use every n-th fix only (the others dropped before the filters see them; default 1)")
    p.add_argument("--correlated-fixes", choices=["calibration", "inflate"], default="calibration",
                   help="GPSDRFilter's correlated_fixes (default calibration, as in the package)")
    a = p.parse_args(argv)
    EXTRA["correlated_fixes"] = a.correlated_fixes
    if a.min_fix_interval is not None:  # real_drive_outages passes it on (its own default is the filter's)
        EXTRA["min_fix_interval"] = a.min_fix_interval
    if a.whiteness_window is not None:
        GPSDRFilter.__init__.__kwdefaults__["whiteness_window"] = a.whiteness_window
    print(f"# city analog, fixes at {a.rate:g} Hz, whiteness_window="
          f"{GPSDRFilter.__init__.__kwdefaults__['whiteness_window']}, correlated_fixes={a.correlated_fixes}"
          + f", min_fix_interval={EXTRA.get('min_fix_interval', 0.0)}"
          + (f", every {a.keep_every}th fix kept" if a.keep_every > 1 else "")
          + (f", white fix errors of {a.white:g} m" if a.white is not None else ""))
    target = TARGETS["city"]
    with tempfile.TemporaryDirectory() as tmp:
        for seed in a.seeds:
            t0 = time.perf_counter()
            cols = held_out.columns("city", seed, gps_rate=a.rate)
            if a.white is not None:
                fix = np.isfinite(cols["gps_east"])
                rng = np.random.default_rng(np.random.SeedSequence([23, 37, seed]))
                for c in ("east", "north"):
                    cols[f"gps_{c}"][fix] = cols[f"true_{c}"][fix] + a.white * rng.standard_normal(int(fix.sum()))
                cols["gps_sigma"][fix] = a.white
            if a.keep_every > 1:
                fix = np.flatnonzero(np.isfinite(cols["gps_east"]))
                drop = np.setdiff1d(fix, fix[a.keep_every - 1::a.keep_every])
                for c in ("gps_east", "gps_north", "gps_sigma"):
                    cols[c][drop] = np.nan
            path = held_out.write_csv(os.path.join(tmp, f"city_{seed}.csv"), cols)
            _run(f"city {a.rate:g} Hz seed {seed} (target {target[0]:g} / {target[1]:g})",
                 read_drive_csv(path), ("DR-mech",) + KINDS8, [0], use_gps_sigma=True, grade="phone")
            print(f"#   {time.perf_counter() - t0:.0f} s", file=sys.stderr)


if __name__ == "__main__":
    main()
