"""Convert nmea.log + can.csv (+ truth.csv) to filterwnn's drive CSV (docs/gps_dr.md, 'Reading a drive').

Correct conversion (default):
  * DR rows at 10 Hz on the logger clock (s since logger start): speed = mean of the 4 wheel speeds / 3.6,
    negative while gear == R; yaw_rate_deg = -(ISO 8855 yaw rate) (clockwise positive), each the mean of the
    50 Hz frames within half a row interval of the row time.
  * fixes on rows of their own at the fix epoch: UTC time-of-day from GGA minus the logger start's UTC
    (timesync.txt); gps_lat/gps_lon from ddmm.mmmm; quality 0 -> no row; gps_sigma = RMS of GST lat/lon sigma.
  * truth (true_lat/true_lon) on DR rows for scoring.
Mistake flags reproduce what a user might get wrong.
"""
import argparse, csv, datetime as dtm, os
import numpy as np

p = argparse.ArgumentParser()
p.add_argument("out")
p.add_argument("--kmh", action="store_true", help="leave wheel speed in km/h")
p.add_argument("--iso-yaw", action="store_true", help="yaw rate sign left CCW positive")
p.add_argument("--clock", default="aligned", choices=["aligned", "utc", "offset2"],
               help="utc: fixes at UTC seconds of day; offset2: fix times = receive time - 2 s ... no, = UTC tod - first-UTC + 2")
p.add_argument("--rx-time", action="store_true", help="fix time = logger receive time")
p.add_argument("--ignore-gear", action="store_true")
p.add_argument("--hdop-sigma", action="store_true", help="HDOP in gps_sigma")
p.add_argument("--hdop-column", action="store_true", help="HDOP as gps_hdop column")
p.add_argument("--tunnel-zeros", action="store_true")
p.add_argument("--per-message", action="store_true", help="a row per CAN message (speed frame, yaw frame) + fix rows")
p.add_argument("--rmc-speed", action="store_true", help="speed from RMC SOG (held between fixes)")
p.add_argument("--rmc-course", action="store_true", help="heading_deg from RMC course instead of yaw rate")
p.add_argument("--no-truth", action="store_true")
p.add_argument("--no-sigma", action="store_true")
p.add_argument("--rate", type=float, default=10.0)
p.add_argument("--debias", action="store_true", help="subtract the yaw-rate mean of the first standstill")
a = p.parse_args()
here = os.path.dirname(os.path.abspath(__file__))

# --- time sync
line = open(os.path.join(here, "timesync.txt")).read().strip()
start = dtm.datetime.fromisoformat(line.split("=", 1)[1])
start_tod = start.hour * 3600 + start.minute * 60 + start.second + start.microsecond * 1e-6

# --- CAN
can = np.genfromtxt(os.path.join(here, "can.csv"), delimiter=",", names=True, dtype=None, encoding="utf-8")
tc = can["t_log"].astype(float)
wheels = np.c_[can["whl_spd_fl_kmh"], can["whl_spd_fr_kmh"], can["whl_spd_rl_kmh"], can["whl_spd_rr_kmh"]].mean(axis=1)
spd = wheels if a.kmh else wheels / 3.6
if not a.ignore_gear:
    spd = np.where(can["gear"] == "R", -spd, spd)
yaw = can["yaw_rate_dps"].astype(float)
if not a.iso_yaw:
    yaw = -yaw
if a.debias:
    still = (tc < 19.0)
    yaw = yaw - yaw[still].mean()

# --- NMEA
def ll(v, h, lon=False):
    if v == "": return np.nan
    d = int(v[:3] if lon else v[:2]); m = float(v[3:] if lon else v[2:])
    x = d + m / 60
    return -x if h in "SW" else x
def tod(s):
    return int(s[:2]) * 3600 + int(s[2:4]) * 60 + float(s[4:])
fixes = {}
for row in open(os.path.join(here, "nmea.log")):
    if row.startswith("#"): continue
    rx, sen = row.strip().split(",", 1)
    body = sen[1:].split("*")[0].split(",")
    T = tod(body[1]); f = fixes.setdefault(T, {"rx": float(rx)})
    f["rx"] = min(f["rx"], float(rx))
    if body[0] == "GPGGA":
        f.update(q=int(body[6]), lat=ll(body[2], body[3]), lon=ll(body[4], body[5], True), hdop=float(body[8] or "nan"))
    elif body[0] == "GPRMC" and body[2] == "A":
        f.update(sog=float(body[7]) * 0.514444, cog=float(body[8]))
    elif body[0] == "GPGST" and body[6]:
        f.update(slat=float(body[6]), slon=float(body[7]))
F = []
for T in sorted(fixes):
    f = fixes[T]
    if f.get("q", 0) == 0 and not a.tunnel_zeros: continue
    if a.clock == "aligned": t = T - start_tod
    elif a.clock == "utc": t = T
    else: t = T - sorted(fixes)[0]                  # UTC relative to the first fix, start offset ignored
    if a.rx_time: t = f["rx"]
    lat, lon = (0.0, 0.0) if f.get("q", 0) == 0 else (f["lat"], f["lon"])
    sig = np.sqrt((f["slat"] ** 2 + f["slon"] ** 2) / 2) if "slat" in f else np.nan
    if a.hdop_sigma: sig = f["hdop"] if f.get("q", 0) else np.nan
    F.append((t, lat, lon, sig, f.get("hdop", np.nan), f.get("sog", np.nan), f.get("cog", np.nan)))
F = np.array(F)

# --- truth
tr = np.genfromtxt(os.path.join(here, "truth.csv"), delimiter=",", names=True)

def fmt(x, p=9):
    return "" if x is None or (isinstance(x, float) and np.isnan(x)) else f"{x:.{p}f}"

cols = ["time"]
cols += ["heading_deg"] if a.rmc_course else ["yaw_rate_deg"]
cols += ["speed", "gps_lat", "gps_lon"]
sigcol = None if a.no_sigma else ("gps_hdop" if a.hdop_column else "gps_sigma")
if sigcol: cols.append(sigcol)
if not a.no_truth: cols += ["true_lat", "true_lon"]
rows = []
if a.per_message:
    for k in range(len(tc)):
        r = {"time": tc[k], "speed": spd[k]}
        if not a.no_truth: r.update(true_lat=tr["lat"][k], true_lon=tr["lon"][k])
        rows.append(r)
        rows.append({"time": tc[k] + 0.007, "yaw_rate_deg": yaw[k]})
else:
    dt = 1.0 / a.rate; half = dt / 2
    tg = np.arange(0.0, tc[-1] - half + 1e-9, dt)
    cs_s = np.r_[0, np.cumsum(spd)]; cs_y = np.r_[0, np.cumsum(yaw)]
    lo = np.searchsorted(tc, tg - half + 1e-9); hi = np.searchsorted(tc, tg + half - 1e-9, side="right")
    lo = np.maximum(lo, 0)
    ms = (cs_s[hi] - cs_s[lo]) / (hi - lo); my = (cs_y[hi] - cs_y[lo]) / (hi - lo)
    ktr = np.searchsorted(tr["t_log"], tg - 1e-9)
    for j, t in enumerate(tg):
        r = {"time": t, "speed": ms[j], "yaw_rate_deg": my[j]}
        if not a.no_truth: r.update(true_lat=tr["lat"][ktr[j]], true_lon=tr["lon"][ktr[j]])
        rows.append(r)
    if a.rmc_speed or a.rmc_course:
        # hold the last RMC value (what a user merging streams with 'last value' would do)
        good = ~np.isnan(F[:, 5])
        idx = np.searchsorted(F[good, 0], tg, side="right") - 1
        for j, r in enumerate(rows):
            if idx[j] < 0: 
                if a.rmc_speed: r["speed"] = 0.0
                if a.rmc_course: r["heading_deg"] = F[good, 6][0]
                continue
            if a.rmc_speed: r["speed"] = F[good, 5][idx[j]]
            if a.rmc_course: r["heading_deg"] = F[good, 6][idx[j]]; r.pop("yaw_rate_deg", None)
        if a.rmc_course:
            for r in rows: r.pop("yaw_rate_deg", None)
for f in F:
    r = {"time": f[0], "gps_lat": f[1], "gps_lon": f[2]}
    if sigcol == "gps_sigma": r["gps_sigma"] = f[3]
    elif sigcol == "gps_hdop": r["gps_hdop"] = f[4]
    rows.append(r)
rows.sort(key=lambda r: r["time"])
with open(a.out, "w", newline="") as fh:
    w = csv.writer(fh); w.writerow(cols)
    for r in rows:
        out = []
        for c in cols:
            v = r.get(c)
            if v is None: out.append("")
            elif c == "time": out.append(f"{v:.3f}")
            elif c in ("gps_lat", "gps_lon", "true_lat", "true_lon"): out.append(fmt(float(v), 9))
            else: out.append(fmt(float(v), 4))
        w.writerow(out)
print(f"wrote {a.out}: {len(rows)} rows, {len(F)} fixes")
