"""Stop 72's reader-side test of fixes right after a gap (tried, not shipped): ``exitproto.exits`` on gaps cut into the
null drives of ``../drag_null.py`` (30, 60, 120 and 300 s each, where the drive is long enough) and the random drives'
own tunnels. Settings from the environment: COLS (the drag test's nuisance columns kept: 0,1 offset, 2 speed scale, 3
speed latency, 4 heading offset, 5 drift, 6 quadratic drift, 7 gyro scale, 8 heading latency), WIN (s after the exit
the fit reaches), SETTLE (s after the exit it starts).

    COLS=0,1,2,4 WIN=75 SETTLE=15 python docs/study-outputs/dr/user-trial/exit-test-tried/null.py > OUT.txt

The last line counts the exits and lists the least p of those with a run of 3 or more fixes off.
"""
import os, sys, tempfile, warnings
import numpy as np
from joblib import Parallel, delayed
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "docs", "study-outputs", "dr", "random-drives"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import random_drives as rd
import exitproto as E
from filterwnn.navigation.drives import read_drive_csv

def cut(cols, seed):
    rng = np.random.default_rng([72, seed])
    t = cols["time"]; T = t[-1] - t[0]
    cols = dict(cols)
    for k in ("gps_east", "gps_north", "gps_sigma"):
        cols[k] = cols[k].copy()
    for g in (30.0, 60.0, 120.0, 300.0):
        if T < g + 400: continue
        a = t[0] + rng.uniform(60.0, T - g - 200.0)
        sel = (t >= a) & (t < a + g)
        for k in ("gps_east", "gps_north", "gps_sigma"):
            cols[k][sel] = np.nan
    return cols

def read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            run = read_drive_csv(path, progress=False, checks=False)
        except ValueError as exc:
            return "refused"
    heading = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]]
    return E.exits(float(run.t[1] - run.t[0]), heading, run.z_dr[:, 1], run.gps_steps, run.z_gps)

def one(kind, seed, kw, gaps):
    with tempfile.TemporaryDirectory() as tmp:
        cols = (rd.drive(seed, protocol=int(kind[-1]))[1] if kind.startswith("protocol")
                else rd.held_out.columns(kind, seed, **kw))
        if gaps: cols = cut(cols, seed)
        return read(rd.held_out.write_csv(os.path.join(tmp, "d.csv"), cols))

if __name__ == "__main__":
    jobs = [(f"protocol {p}", s, {}, g) for p in (2, 3) for s in range(200, 280) for g in (False, True)]
    jobs += [(k, s, {}, True) for k in ("phone", "city", "one_hz") for s in range(110)]
    jobs += [(k, s, {"gyro_scale": g}, True) for k in ("phone", "city", "one_hz") for s in range(5) for g in (-0.03, 0.03)]
    jobs += [(k, s, {"rate_bias": 0.3}, True) for k in ("phone", "one_hz") for s in range(5)]
    out = Parallel(n_jobs=2)(delayed(one)(*j) for j in jobs)
    allx = []
    for j, r in zip(jobs, out):
        if isinstance(r, str): print(j[:2], r); continue
        for e in r:
            allx.append(e)
            print(j[0], j[1], j[3], "gap %.0f-%.0f run to %.0f (%d) max %.1f m s %.2f c %.2f coh %.2f p %.2g" % e)
    ps = sorted((e[-1], e[3], e[4]) for e in allx if e[3] >= E.EXIT_MIN_RUN)
    print("exits", len(allx), "with a run >= min", len(ps), "least p", ps[:5])
