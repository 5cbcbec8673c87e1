"""Convert ``simulate_sensorlog.py``'s phone log into the package's drive CSV, as a new user read the docs (stop 58).

    python docs/study-outputs/dr/phone-log/convert.py DIR VARIANT OUT.csv

``DIR`` holds ``sensorlog_drive.csv`` and ``truth_at_log.npz``. The variants (the helper's, ported from pandas to
the standard library; the same CSVs to the byte):

* ``yaw_cw``: ``heading_deg = -motionYaw`` (clockwise), its zero left as the phone's (142 degrees off north);
* ``follow_advice``: ``yaw_cw``'s heading as ``90 - heading_deg``, what the reader's refusal of ``yaw_cw`` said until
  stop 58 ("counter-clockwise from east");
* ``yaw_aligned``: ``yaw_cw`` plus the offset the user fitted to the GPS course;
* ``gyro``: ``yaw_rate_deg = -gyroRotationZ`` (clockwise), which the reader integrates;
* ``onrow``: ``yaw_aligned`` with each fix on the log row where it first shows (not on a row of its own);
* ``mistake_yaw_raw``: ``heading = motionYaw`` as logged; ``mistake_carried``: the fix's columns on every row, as
  logged; ``mistake_speed_m1``: ``locationSpeed`` as logged (-1 where unknown); ``mistake_gyro_ccw``: ``yaw_rate =
  gyroRotationZ`` as logged; ``mistake_acc_radius``: ``gps_sigma`` the 68 % radius, not divided by 1.51.

The speed: a phone has no odometer, so the GNSS Doppler speed, -1 read as 0, interpolated from the fixes' times
onto the log's rows. Every other variant places each fix on a row of its own at its own time (the reader's row per
sensor message layout).
"""
import csv
import pathlib
import sys
from datetime import datetime

import numpy as np

folder, variant, out = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3]
with open(folder / "sensorlog_drive.csv", newline="") as f:
    rows = list(csv.reader(f))
head, body = rows[0], rows[1:]
col = {h: [r[i] for r in body] for i, h in enumerate(head)}


def num(name):
    return np.array([float(v) for v in col[name]])


tlog = np.array([datetime.fromisoformat(s).timestamp() for s in col["loggingTime(txt)"]])
acc_all, lat_all = num("locationHorizontalAccuracy(m)"), num("locationLatitude(WGS84)")
stamp = num("locationTimestamp_since1970(s)")
valid = (acc_all > 0) & (lat_all != 0)  # not the invalid fix (accuracy < 0, lat = lon = 0)
first = valid & (np.r_[1.0, np.diff(stamp)] != 0)  # one per distinct locationTimestamp
first_row = np.flatnonzero(first)
t_fix = stamp[first]
lat_f, lon_f = lat_all[first], num("locationLongitude(WGS84)")[first]
speed_f, course_f, acc_f = num("locationSpeed(m/s)")[first], num("locationCourse(deg)")[first], acc_all[first]

speed = np.interp(tlog, t_fix, speed_f.clip(0, None), left=0.0)  # -1 (unknown, standing) as 0
yaw = num("motionYaw(rad)")
hd_cw = (-np.rad2deg(yaw)) % 360
ok = (course_f >= 0) & (speed_f > 5)
d = np.deg2rad(course_f[ok] - hd_cw[first_row[ok]])
offset = np.rad2deg(np.arctan2(np.sin(d).mean(), np.cos(d).mean()))
print(f"the offset of -motionYaw to the GPS course: {offset:.2f} deg over {ok.sum()} fixes")

tr = np.load(folder / "truth_at_log.npz")
LAT0, LON0 = 48.137154, 11.576124
a_wgs, e2 = 6378137.0, 6.69437999014e-3
s = np.sin(np.deg2rad(LAT0))
M, N = a_wgs * (1 - e2) / (1 - e2 * s * s) ** 1.5, a_wgs / np.sqrt(1 - e2 * s * s)


def to_latlon(e, n):
    return LAT0 + np.rad2deg(n / M), LON0 + np.rad2deg(e / (N * np.cos(np.deg2rad(LAT0))))


assert np.allclose(tr["t_log_epoch"], tlog, atol=2e-3)
true_lat, true_lon = to_latlon(tr["east"], tr["north"])

table = {"time": np.round(tlog, 3)}
if variant == "yaw_cw":
    table["heading_deg"] = np.round(hd_cw, 4)
elif variant == "follow_advice":
    table["heading_deg"] = (90.0 - np.round(hd_cw, 4)) % 360
elif variant in ("yaw_aligned", "onrow", "mistake_carried", "mistake_speed_m1", "mistake_acc_radius"):
    table["heading_deg"] = np.round((hd_cw + offset) % 360, 4)
elif variant == "gyro":
    table["yaw_rate_deg"] = np.round(-np.rad2deg(num("gyroRotationZ(rad/s)")), 5)
elif variant == "mistake_yaw_raw":
    table["heading"] = yaw
elif variant == "mistake_gyro_ccw":
    table["yaw_rate"] = num("gyroRotationZ(rad/s)")
else:
    raise SystemExit(f"unknown variant {variant}")
table["speed"] = num("locationSpeed(m/s)") if variant == "mistake_speed_m1" else np.round(speed, 3)
table["true_lat"], table["true_lon"] = np.round(true_lat, 8), np.round(true_lon, 8)
sigma = acc_f if variant == "mistake_acc_radius" else acc_f / 1.51
n = len(tlog)
empty = np.full(n, np.nan)
if variant == "onrow":
    for name, values in (("gps_lat", lat_f), ("gps_lon", lon_f), ("gps_sigma", np.round(sigma, 3))):
        table[name] = empty.copy()
        table[name][first_row] = values
elif variant == "mistake_carried":
    table["gps_lat"] = np.where(valid, lat_all, np.nan)
    table["gps_lon"] = np.where(valid, num("locationLongitude(WGS84)"), np.nan)
    table["gps_sigma"] = np.where(valid, np.round(acc_all / 1.51, 3), np.nan)
else:  # a row per sensor message: each fix on a row of its own at its own time, heading and speed empty
    flat, flon = to_latlon(tr["fix_east"], tr["fix_north"])
    idx = np.searchsorted(np.round(tr["t_fix_epoch"], 3), np.round(t_fix, 3))
    fix = {"time": np.round(t_fix, 3), "gps_lat": lat_f, "gps_lon": lon_f, "gps_sigma": np.round(sigma, 3),
           "true_lat": np.round(flat[idx], 8), "true_lon": np.round(flon[idx], 8)}
    names = list(table) + ["gps_lat", "gps_lon", "gps_sigma"]
    both = {h: np.r_[table.get(h, empty), fix.get(h, np.full(len(t_fix), np.nan))] for h in names}
    order = np.argsort(both["time"], kind="stable")
    table = {h: v[order] for h, v in both.items()}


def cell(v):
    return "" if np.isnan(v) else f"{v:.13g}"


with open(out, "w", newline="") as f:
    w = csv.writer(f, lineterminator="\n")
    w.writerow(list(table))
    for k in range(len(table["time"])):
        w.writerow([cell(table[h][k]) for h in table])
print(f"wrote {out}: {len(table['time'])} rows, {int(np.isfinite(table['gps_lat']).sum())} fix cells")
