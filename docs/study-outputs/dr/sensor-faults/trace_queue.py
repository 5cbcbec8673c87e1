"""Trace EKF-8 (phone grade, as the command sets it) with every fix through one queue of the phone
analog with crawls (``crawl``: the speed reads 0 below 0.8 m/s; ``crawl_ctrl``: honest speed): at each
fix, the motion class, the true and estimated speed, the position error, the position's standard
deviation, the fix's NIS and what became of it.

Usage: ``python trace_queue.py VARIANT T0 T1`` (e.g. ``crawl 630 740``).
"""
import sys
import tempfile
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_variants as mv  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr._real import REAL_MODEL, _real_drive_filter  # noqa: E402

variant, t0, t1 = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
cols, cap = mv.gen("phone", mv.make_crawl_route(8, 0))
if variant == "crawl":
    cols = mv.cutoff(cols, cap)
v, te, tn = cap["v"][1:], cols["true_east"][1:], cols["true_north"][1:]  # run step k is CSV row k + 1
with tempfile.TemporaryDirectory() as d, warnings.catch_warnings():
    warnings.simplefilter("ignore")
    path = mv.h.write_csv(Path(d) / "drive.csv", cols)
    run = read_drive_csv(path, progress=False)
    f = _real_drive_filter("EKF-8", run, "phone", None, dict(REAL_MODEL), 0, None)
    gps, sig = run.gps_list(), run.gps_sigma_list()
    print("t (s) | motion | true speed | estimated speed | position error (m) | position sd (m) | NIS | fix")
    for k in range(len(run.t)):
        f.predict()
        f.update(run.z_dr[k], gps[k], sig[k])
        if t0 <= run.t[k] <= t1 and gps[k] is not None:
            x, P = f.x, f.P
            print(f"{run.t[k]:.1f} | {f.motion} | {v[k]:.2f} | {np.hypot(x[1], x[4]):.2f} | "
                  f"{np.hypot(x[0] - te[k], x[3] - tn[k]):.2f} | {np.sqrt((P[0, 0] + P[3, 3]) / 2):.2f} | "
                  f"{f.nis:.1f} | {f.fix_status}")
