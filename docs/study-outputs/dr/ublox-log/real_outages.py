"""Score the drive's OWN outages (the tunnel and the garage, where the receiver output fixType 1).

    python real_outages.py WORKDIR

`filterwnn study dr` cuts its own 30 s outages and reports those; a user with a tunnel in the log wants
to know how the filter did there, against the receiver's own dead reckoning (the fixType-1 positions).
This runs the README's API example (read_drive_csv, GPSDRModel.from_grade, GPSDRFilter.batch_filter)
on drive_ok.csv (and drive_ok_bias_removed.csv), with the drive's real outages only, and prints each
filter's error at the last sample before GNSS came back, and the receiver's own DR error at its last
fixType-1 epoch, both against the truth.
"""
import os
import sys
import warnings

import numpy as np

from filterwnn import GPSDRFilter, read_drive_csv
from filterwnn.navigation.dead_reckoning import GPSDRModel

work = sys.argv[1]
pvt = np.genfromtxt(os.path.join(work, "log", "nav_pvt.csv"), delimiter=",", names=True)
truth = np.genfromtxt(os.path.join(work, "log", "truth.csv"), delimiter=",", names=True)
itow = pvt["iTOW"] / 1000.0
ft = pvt["fixType"]
lat0 = np.deg2rad(48.1372)
RM, RN = 6373000.0, 6390000.0  # enough for metre-level differences here


def metres(lat_a, lon_a, lat_b, lon_b):
    dn = np.deg2rad(lat_a - lat_b) * RM
    de = np.deg2rad(lon_a - lon_b) * RN * np.cos(lat0)
    return float(np.hypot(de, dn))


# the receiver's outages: runs of fixType 1
runs = []
i = 0
while i < len(ft):
    if ft[i] == 1:
        j = i
        while j + 1 < len(ft) and ft[j + 1] == 1:
            j += 1
        runs.append((i, j))
        i = j + 1
    else:
        i += 1

lines = []
for i, j in runs:
    t_end = itow[j]
    tl = np.interp(t_end, truth["t_gps"], truth["lat"])
    tn = np.interp(t_end, truth["t_gps"], truth["lon"])
    e_rx = metres(pvt["lat"][j] * 1e-7, pvt["lon"][j] * 1e-7, tl, tn)
    lines.append(f"outage {itow[i] - itow[0]:.0f}-{t_end - itow[0]:.0f} s of the log ({j - i + 1} epochs of fixType 1): "
                 f"receiver's own DR ends {e_rx:.2f} m off")

for name, grade in (("ok", "phone"), ("ok", {"gyro_bias_deg_s": 0.18}), ("ok", "survey"),
                    ("ok_bias_removed", "phone"), ("ok_bias_removed", "survey"),
                    ("receiver_dr_as_fixes", "phone"), ("receiver_dr_as_fixes", {"gyro_bias_deg_s": 0.18})):
    path = os.path.join(work, "csv", f"drive_{name}.csv")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(path)
        t0 = float(np.genfromtxt(path, delimiter=",", names=True, max_rows=1)["time"])
        model = GPSDRModel.from_grade(grade, run.scenario.dt)
        for kind in ("ekf", "ukf", "sukf"):
            kf = GPSDRFilter(model, kind, x0=np.r_[run.x0, model.x0[6:]])
            est = kf.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
            errs = []
            for i, j in runs:
                t_end = itow[j] + 0.5  # the last DR sample before the first GNSS fix back (at itow[j] + 1)
                k = int(np.searchsorted(run.t + t0, t_end)) - 1
                errs.append(float(np.hypot(*(est[k, [0, 3]] - run.x_true[k, [0, 3]]))))
            lines.append(f"{name:16s} grade={grade!s:28s} {kind:5s} ({model.x0.size} states): error at the real "
                         f"outages' ends " + ", ".join(f"{e:.2f}" for e in errs) + " m")
print("\n".join(lines))
with open(os.path.join(work, "real_outages.txt"), "w") as f:
    f.write("\n".join(lines) + "\n")
