"""Convert the per-topic bag CSVs to filterwnn's drive CSV (docs/gps_dr.md), with switches for user mistakes."""
import argparse, os, numpy as np
p = argparse.ArgumentParser()
p.add_argument("out")
p.add_argument("--heading", default="gyro", choices=["gyro", "ahrs_raw", "ahrs_conv"])
p.add_argument("--yawrate", default="cw_rad", choices=["cw_rad", "rad_in_deg", "ccw_rad"])
p.add_argument("--time", default="sec", choices=["sec", "ns"])
p.add_argument("--stamp", default="header", choices=["header", "bag"])
p.add_argument("--sigma", default="std", choices=["std", "var", "none"])
p.add_argument("--type0", default="empty", choices=["empty", "zero", "drop"])
p.add_argument("--status", default="drop", choices=["drop", "nan", "zero"])
p.add_argument("--speed", default="twist", choices=["twist", "posediff", "gps"])
p.add_argument("--fixes", default="gps", choices=["gps", "odompose"])
p.add_argument("--layout", default="rows", choices=["rows", "ffill100", "ffill20"])
p.add_argument("--truth", default=1, type=int)
a = p.parse_args()
D = os.path.dirname(os.path.abspath(__file__))
def load(name):
    with open(os.path.join(D, "bag_csv", name)) as f:
        hdr = f.readline().strip().split(",")
    raw = np.genfromtxt(os.path.join(D, "bag_csv", name), delimiter=",", skip_header=1, dtype=str)
    cols = {h: raw[:, i] for i, h in enumerate(hdr)}
    if a.stamp == "header":
        tns = cols["header.stamp.sec"].astype(np.int64) * 10**9 + cols["header.stamp.nanosec"].astype(np.int64)
    else:
        tns = cols["timestamp"].astype(np.int64)
    return cols, tns
imu, t_imu = load("imu_data.csv"); od, t_od = load("odom.csv"); gp, t_gp = load("gps_fix.csv")
tref = t_od[0]
s = lambda tn: (tn - tref) * 1e-9       # relative s, for arithmetic only
ti, to, tg = s(t_imu), s(t_od), s(t_gp)
f = lambda c, k: c[k].astype(float)
R_E = 6378137.0
# ---- DR rows: one per /odom message (20 Hz) ----
if a.layout == "ffill100":
    tr = ti                                  # a row per IMU message, latest of each topic
else:
    tr = to
gz = f(imu, "angular_velocity.z")
# mean of the gyro rates within half a row's interval of each row
half = 0.5 * np.median(np.diff(tr))
cs = np.r_[0, np.cumsum(gz)]
lo = np.searchsorted(ti, tr - half); hi = np.searchsorted(ti, tr + half, side="right")
gmean = (cs[hi] - cs[lo]) / np.maximum(hi - lo, 1)
qx, qy, qz, qw = (f(imu, k) for k in ("orientation.x", "orientation.y", "orientation.z", "orientation.w"))
yaw_enu = np.arctan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
yaw_enu_r = np.interp(tr, ti, np.unwrap(yaw_enu))
vx = f(od, "twist.twist.linear.x")
if a.layout in ("ffill100", "ffill20"):
    idx = np.clip(np.searchsorted(to, tr, side="right") - 1, 0, None)
    speed = vx[idx]
else:
    speed = vx.copy()
if a.speed == "posediff":
    px, py = f(od, "pose.pose.position.x"), f(od, "pose.pose.position.y")
    speed = np.r_[0, np.hypot(np.diff(px), np.diff(py)) / np.diff(to)]
# ---- fixes ----
st = gp["status.status"].astype(int); lat = f(gp, "latitude"); lon = f(gp, "longitude")
cov = np.stack([f(gp, f"position_covariance.{j}") for j in range(9)], 1); ctype = gp["position_covariance_type"].astype(int)
keep = np.ones(len(tg), bool)
if a.status == "drop": keep &= (st >= 0) & np.isfinite(lat)
elif a.status == "zero": lat = np.where(st < 0, 0.0, lat); lon = np.where(st < 0, 0.0, lon)
if a.type0 == "drop": keep &= ctype > 0
if a.sigma == "std": sig = np.sqrt(0.5 * (cov[:, 0] + cov[:, 4]))
elif a.sigma == "var": sig = 0.5 * (cov[:, 0] + cov[:, 4])
else: sig = np.full(len(tg), np.nan)
sig_txt = np.array([("" if (ctype[k] == 0 and a.type0 == "empty") or not np.isfinite(sig[k]) else f"{sig[k]:.3f}") for k in range(len(tg))])
if a.sigma == "none": sig_txt[:] = ""
fix_lat, fix_lon = lat, lon
if a.fixes == "odompose":          # odom pose (odom frame, x east?) placed at the first fix as lat/lon
    px, py = f(od, "pose.pose.position.x"), f(od, "pose.pose.position.y")
    ex, ny = np.interp(tg, to, px), np.interp(tg, to, py)
    lat0, lon0 = lat[np.isfinite(lat)][0], lon[np.isfinite(lon)][0]
    fix_lat = lat0 + np.rad2deg(ny / R_E); fix_lon = lon0 + np.rad2deg(ex / (R_E * np.cos(np.deg2rad(lat0))))
# ---- truth (separate file, true epoch time) interpolated to the row times ----
T = np.genfromtxt(os.path.join(D, "truth.csv"), delimiter=",", names=True)
tt = (np.round(T["time_epoch_s"] * 1e3).astype(np.int64) * 10**6 - tref) * 1e-9
tlat, tlon = np.interp(tr, tt, T["lat"]), np.interp(tr, tt, T["lon"])
if a.speed == "gps":     # speed from consecutive fixes, carried to the rows
    E = np.deg2rad(fix_lon - fix_lon[keep][0]) * R_E * np.cos(np.deg2rad(48.15)); N = np.deg2rad(fix_lat - fix_lat[keep][0]) * R_E
    kk = np.flatnonzero(keep); vg = np.hypot(np.diff(E[kk]), np.diff(N[kk])) / np.diff(tg[kk])
    speed = np.interp(tr, tg[kk][1:], vg)
def tfmt(x_rel):
    tn = tref + np.round(x_rel * 1e9).astype(np.int64)
    if a.time == "ns": return [str(v) for v in tn]
    return [f"{v / 1e9:.3f}" for v in tn]
hcol = {"gyro": "yaw_rate", "ahrs_raw": "heading", "ahrs_conv": "heading"}[a.heading]
if a.heading == "gyro":
    if a.yawrate == "cw_rad": hval = -gmean
    elif a.yawrate == "ccw_rad": hval = gmean
    else: hcol = "yaw_rate_deg"; hval = -gmean          # rad/s written in the deg/s column
elif a.heading == "ahrs_raw": hval = np.mod(yaw_enu_r, 2 * np.pi)
else: hval = np.mod(np.pi / 2 - yaw_enu_r, 2 * np.pi)
rows = []
tr_txt = tfmt(tr)
for i in range(len(tr)):
    tru = f"{tlat[i]:.9f},{tlon[i]:.9f}" if a.truth else ""
    rows.append((tr[i], f"{tr_txt[i]},{hval[i]:.6f},{speed[i]:.4f},,,{',' + tru if a.truth else ''}"))
if a.layout in ("ffill100", "ffill20"):
    # every row holds the latest fix (forward filled), fix columns on every row after the first fix
    kk = np.flatnonzero(keep)
    j = np.searchsorted(tg[kk], tr, side="right") - 1
    rows = []
    for i in range(len(tr)):
        tru = f",{tlat[i]:.9f},{tlon[i]:.9f}" if a.truth else ""
        if j[i] >= 0:
            k = kk[j[i]]; fx = f"{fix_lat[k]:.9f},{fix_lon[k]:.9f},{sig_txt[k]}"
        else: fx = ",,"
        rows.append((tr[i], f"{tr_txt[i]},{hval[i]:.6f},{speed[i]:.4f},{fx}{tru}"))
else:
    tg_txt = tfmt(tg)
    for k in np.flatnonzero(keep):
        la = "nan" if not np.isfinite(fix_lat[k]) else f"{fix_lat[k]:.9f}"; lo_ = "nan" if not np.isfinite(fix_lon[k]) else f"{fix_lon[k]:.9f}"
        rows.append((tg[k], f"{tg_txt[k]},,,{la},{lo_},{sig_txt[k]}{',,' if a.truth else ''}"))
rows.sort(key=lambda r: r[0])
with open(a.out, "w") as fo:
    fo.write(f"time,{hcol},speed,gps_lat,gps_lon,gps_sigma" + (",true_lat,true_lon" if a.truth else "") + "\n")
    for _, r in rows: fo.write(r + "\n")
print("wrote", a.out, len(rows), "rows")
