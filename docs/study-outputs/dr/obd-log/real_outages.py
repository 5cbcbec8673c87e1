"""Score the drive's own GPS outage (the ~40 s underpass) with the README's Python API example: the EKF-8
(GPSDRFilter "ekf" on GPSDRModel.from_grade("phone")), error at the end of the real outage against the truth.

    python real_outages.py --work DIR [--variants careful,gyro_raw_z,...]   (default: every CSV that reads)

The outage is found as a user would: the longest gap between fixes in the CSV; its end is the first fix after
it, and the error is taken at the last step before that fix (as the README's example takes step 130 s - 1).
"""
import argparse
import csv
import json
import os
import warnings

import numpy as np

from filterwnn import GPSDRFilter, read_drive_csv
from filterwnn.navigation.dead_reckoning import GPSDRModel


def fix_and_sample_times(path):
    tf, ts, last = [], [], None
    with open(path) as f:
        for row in csv.DictReader(f):
            t = float(row["time"])
            if row.get("gps_lat") and (row["gps_lat"], row["gps_lon"]) != last:   # a fix carried forward: once
                tf.append(t)
                last = (row["gps_lat"], row["gps_lon"])
            if row.get("speed") or row.get("yaw_rate") or row.get("heading_deg"):
                ts.append(t)
    return np.array(tf), np.array(ts)


def score(path, kinds=("ekf",)):
    tf, ts = fix_and_sample_times(path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run = read_drive_csv(path)
        gaps = np.diff(tf)
        i = int(np.argmax(gaps))
        t_in = tf[i] - ts[0]
        t_out = tf[i + 1] - ts[0]
        k_in = np.searchsorted(run.t, t_in)
        k = np.searchsorted(run.t, t_out) - 1
        model = GPSDRModel.from_grade("phone", run.scenario.dt)
        out = {"gap_s": round(float(gaps[i]), 2), "outage_rel_s": [round(float(t_in), 1), round(float(t_out), 1)]}
        for kind in kinds:
            kf = GPSDRFilter(model, kind, x0=np.r_[run.x0, model.x0[6:]])
            est = kf.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
            err_end = float(np.hypot(*(est[k, [0, 3]] - run.x_true[k, [0, 3]])))
            err_in = float(np.hypot(*(est[k_in, [0, 3]] - run.x_true[k_in, [0, 3]])))
            out[kind] = {"start_m": round(err_in, 2), "end_m": round(err_end, 2)}
    out["warnings"] = len(caught)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    ap.add_argument("--variants", default="")
    a = ap.parse_args()
    d = os.path.join(a.work, "csv")
    var = json.load(open(os.path.join(d, "variants.json")))["variants"]
    names = a.variants.split(",") if a.variants else list(var)
    print(f"{'csv':26s} gap(s)  EKF-8 error at the outage's start / end (m)")
    for n in names:
        try:
            kinds = ("ekf", "ukf", "sukf") if n == "careful" else ("ekf",)
            r = score(os.path.join(d, n + ".csv"), kinds)
        except Exception as e:                                   # a refused drive
            print(f"{n:26s} refused: {type(e).__name__}: {str(e)[:160]}")
            continue
        extra = "".join(f"  {k.upper()}-8 {r[k]['start_m']:.2f} / {r[k]['end_m']:.2f}" for k in ("ukf", "sukf") if k in r)
        print(f"{n:26s} {r['gap_s']:6.1f}  {r['ekf']['start_m']:6.2f} / {r['ekf']['end_m']:7.2f}"
              f"   (outage {r['outage_rel_s'][0]}-{r['outage_rel_s'][1]} s, {r['warnings']} warnings){extra}")


if __name__ == "__main__":
    main()
