"""Simulate an urban test drive as a real logger writes it.

Writes (in this folder):
  nmea.log      logger time (s since logger start), NMEA sentence  (5 Hz u-blox: GGA, RMC, GST)
  can.csv       50 Hz CAN: t_log, wheel speeds FL FR RL RR (km/h, unsigned, 0.01), yaw rate deg/s ISO 8855, gear
  timesync.txt  UTC date/time of logger start
  truth.csv     50 Hz truth in logger time: t_log, east, north, lat, lon, heading_deg (cw from N), speed (signed m/s)
"""
import numpy as np, datetime as dtm, os
rng = np.random.default_rng(12345)
DT = 0.02
here = os.path.dirname(os.path.abspath(__file__))

v_cmd, r_cmd, gear = [], [], []   # signed speed m/s, yaw rate deg/s clockwise (nav), gear
state = {"v": 0.0}
tunnel_marks, multipath_marks = [], []

def push(v, r, g):
    v_cmd.append(v); r_cmd.append(r); gear.append(g); state["v"] = v

def stop(T, g="D"):
    for _ in range(int(round(T / DT))): push(0.0, 0.0, g)

def speed_to(vt, a=1.5, g="D"):
    v = state["v"]
    while abs(vt - v) > 1e-9:
        v = v + np.clip(vt - v, -a * DT, a * DT); push(v, 0.0, g)

def cruise(dist, g="D"):
    d = 0.0
    while d < dist:
        push(state["v"], 0.0, g); d += abs(state["v"]) * DT

def turn(angle_deg, radius, ramp=1.0, g="D"):
    """turn at current speed; positive angle = right (clockwise)"""
    v = abs(state["v"]); rmax = np.degrees(v / radius)
    tr = ramp; total = abs(angle_deg)
    # trapezoid: 2 ramps give rmax*tr deg total; constant part the rest
    if rmax * tr > total: rmax = total / tr
    tc = (total - rmax * tr) / rmax
    n_r, n_c = int(round(tr / DT)), int(round(tc / DT))
    prof = np.r_[np.linspace(0, rmax, n_r), np.full(n_c, rmax), np.linspace(rmax, 0, n_r)]
    prof *= total / (prof.sum() * DT)
    for x in prof: push(state["v"], np.sign(angle_deg) * x, g)

def mark(lst):
    lst.append(len(v_cmd) * DT)

# ---- the drive ----
stop(12, "P"); stop(8, "D")
speed_to(12); cruise(250); speed_to(6, 2.0); turn(90, 12); speed_to(13); cruise(300)
speed_to(0, 2.5); stop(35)                                   # light 1
speed_to(11); cruise(150); mark(multipath_marks); cruise(200); mark(multipath_marks)
speed_to(5, 2.0); turn(-90, 10); speed_to(12); cruise(120)
mark(tunnel_marks); cruise(480); mark(tunnel_marks)          # tunnel ~40 s at 12 m/s
cruise(100); speed_to(0, 2.5); stop(50)                      # light 2
speed_to(7); turn(90, 15); speed_to(14); cruise(400); speed_to(6, 2.0); turn(-90, 12)
speed_to(10); cruise(200); speed_to(3, 1.5); turn(180, 6)    # U-turn
speed_to(12); cruise(180); speed_to(0, 2.5); stop(25)        # light 3
speed_to(9); cruise(120); mark(multipath_marks); speed_to(5); turn(90, 10); speed_to(10); cruise(150); mark(multipath_marks)
speed_to(0, 2.0); stop(4)
# parking: reverse ~10 m into a space, with a 30 deg swing
stop(1.5, "R"); state["v"] = 0.0
v = 0.0
while v > -1.5: v -= 1.0 * DT; push(v, 0.0, "R")
turn(-30, 6, ramp=1.5, g="R"); cruise(3.5, g="R")
while state["v"] < 0: push(min(0.0, state["v"] + 1.0 * DT), 0.0, "R")
stop(2, "R"); stop(20, "P"); stop(3, "D")
speed_to(4); turn(60, 8); speed_to(12); cruise(300)
speed_to(0, 2.5); stop(60)                                   # light 4
speed_to(13); cruise(350); speed_to(6, 2.0); turn(-90, 12); speed_to(11); cruise(250)
speed_to(6, 2.0); turn(90, 12); speed_to(12); cruise(200); speed_to(0, 2.0); stop(20)
speed_to(10); cruise(200); speed_to(0, 2.0); stop(40)                  # light 5
speed_to(12); cruise(300); speed_to(6, 2.0); turn(90, 12); speed_to(13); cruise(450)
speed_to(5, 2.0); turn(90, 10); speed_to(11); cruise(250); speed_to(0, 2.5); stop(30)   # light 6
speed_to(10); cruise(200); speed_to(6, 2.0); turn(-90, 12); speed_to(12); cruise(300)
speed_to(0, 2.0); stop(15, "D"); stop(5, "P")

v = np.array(v_cmd); r = np.array(r_cmd); gear = np.array(gear)
n = len(v); t = np.arange(n) * DT
psi0 = 20.0
psi = psi0 + np.cumsum(r) * DT                              # deg clockwise from north
east = np.cumsum(v * np.sin(np.radians(psi))) * DT
north = np.cumsum(v * np.cos(np.radians(psi))) * DT
print(f"drive {t[-1]:.0f} s, {np.sum(np.abs(v))*DT/1000:.2f} km, reversed {np.sum(-v[v<0])*DT:.1f} m")
print("tunnel", tunnel_marks, "multipath", multipath_marks)

# geodesy: local tangent plane about origin
LAT0, LON0 = 48.137154, 11.576124
a, f = 6378137.0, 1 / 298.257223563; e2 = f * (2 - f)
s = np.sin(np.radians(LAT0))
RN = a / np.sqrt(1 - e2 * s * s); RM = a * (1 - e2) / (1 - e2 * s * s) ** 1.5
def enu2ll(e, nn):
    return LAT0 + np.degrees(nn / RM), LON0 + np.degrees(e / (RN * np.cos(np.radians(LAT0))))
lat, lon = enu2ll(east, north)

# clocks: the logger starts at 08:59:57.930 UTC; t_log = 0 there
date = dtm.date(2025, 5, 14)
start_utc = dtm.datetime(2025, 5, 14, 8, 59, 57, 930000, tzinfo=dtm.timezone.utc)
start_tod = 8 * 3600 + 59 * 60 + 57.93
with open(os.path.join(here, "timesync.txt"), "w") as fh:
    fh.write(f"logger_start_utc={start_utc.isoformat()}\n")

np.savetxt(os.path.join(here, "truth.csv"), np.c_[t, east, north, lat, lon, psi % 360, v],
           delimiter=",", header="t_log,east,north,lat,lon,heading_deg,speed", comments="", fmt="%.4f,%.4f,%.4f,%.9f,%.9f,%.4f,%.4f")

# ---- CAN 50 Hz ----
TRACK = 1.6
r_iso = -r                                          # deg/s, CCW positive
w = np.radians(r_iso)
scale = 1.0 + 0.01                                  # tyres read 1 % high
wl = (v - w * TRACK / 2) * scale; wr = (v + w * TRACK / 2) * scale
wheels = []
for base in (wl * 1.002, wr * 1.002, wl, wr):       # front a touch more (Ackermann)
    kmh = np.abs(base) * 3.6 + rng.normal(0, 0.05, n) * (np.abs(v) > 0)
    wheels.append(np.round(np.clip(kmh, 0, None), 2))
yaw_meas = np.round(r_iso + 0.2 + rng.normal(0, 0.1, n), 2)
with open(os.path.join(here, "can.csv"), "w") as fh:
    fh.write("t_log,whl_spd_fl_kmh,whl_spd_fr_kmh,whl_spd_rl_kmh,whl_spd_rr_kmh,yaw_rate_dps,gear\n")
    for k in range(n):
        fh.write(f"{t[k]:.3f},{wheels[0][k]:.2f},{wheels[1][k]:.2f},{wheels[2][k]:.2f},{wheels[3][k]:.2f},{yaw_meas[k]:.2f},{gear[k]}\n")

# ---- GNSS 5 Hz ----
ep_log = np.arange(1.87, t[-1] - 0.5, 0.2)           # fix epochs in logger time (UTC .0/.2/...)
ne = len(ep_log)
def gm(tau, sig):
    x = np.zeros(ne); phi = np.exp(-0.2 / tau)
    x[0] = rng.normal(0, sig)
    for k in range(1, ne): x[k] = phi * x[k - 1] + rng.normal(0, sig * np.sqrt(1 - phi ** 2))
    return x
err_e, err_n = gm(20, 2.0), gm(20, 2.0)
# multipath jumps near tall buildings: 4 episodes of 4-10 s, 10-30 m
mp_episodes = []
for (t1, t2) in [(multipath_marks[0], multipath_marks[1]), (multipath_marks[2], multipath_marks[3])]:
    for ts0 in (t1, (t1 + t2) / 2):
        ts = ts0 + rng.uniform(0, max((t2 - t1) / 2 - 8, 0.5)); L = rng.uniform(4, 8); mag = rng.uniform(10, 30); ang = rng.uniform(0, 2 * np.pi)
        mp_episodes.append((ts, L, mag))
        sel = (ep_log >= ts) & (ep_log < ts + L)
        err_e[sel] += mag * np.sin(ang); err_n[sel] += mag * np.cos(ang)
print("multipath episodes (t_log start, length, m):", [(round(a_, 1), round(b_, 1), round(c_, 1)) for a_, b_, c_ in mp_episodes])
in_tunnel = (ep_log >= tunnel_marks[0]) & (ep_log < tunnel_marks[1])
hdop = np.clip(0.9 + 0.3 * gm(30, 1.0), 0.6, 2.5)
sig_rep = np.clip(1.2 + 1.0 * hdop + 0.3 * gm(10, 1.0), 1.0, 4.0)   # GST sigma per axis (m)
te = np.interp(ep_log, t, east); tn = np.interp(ep_log, t, north)
fe, fn = te + err_e, tn + err_n
flat, flon = enu2ll(fe, fn)
vt = np.interp(ep_log, t, v); pt = np.interp(ep_log, t, psi)
cog = np.where(vt < 0, pt + 180, pt) % 360

def cs(body):
    c = 0
    for ch in body: c ^= ord(ch)
    return f"${body}*{c:02X}"
def hms(tod):
    tod = tod % 86400; h = int(tod // 3600); m = int(tod % 3600 // 60); s_ = tod - 3600 * h - 60 * m
    return f"{h:02d}{m:02d}{s_:05.2f}"
def dm(deg, lon=False):
    d = int(abs(deg)); m = (abs(deg) - d) * 60
    return f"{d:03d}{m:08.5f}" if lon else f"{d:02d}{m:08.5f}"

lines = []
ddmmyy = date.strftime("%d%m%y")
for k in range(ne):
    tod = start_tod + ep_log[k]; T = hms(tod)
    rx = ep_log[k] + rng.uniform(0.1, 0.3)
    nsat = int(np.clip(round(10 + 3 * hdop[k] * 0 + rng.normal(0, 1)), 5, 16))
    if in_tunnel[k]:
        gga = cs(f"GPGGA,{T},,,,,0,00,99.99,,,,,,")
        rmc = cs(f"GPRMC,{T},V,,,,,,,{ddmmyy},,,N")
        gst = cs(f"GPGST,{T},,,,,,,")
    else:
        gga = cs(f"GPGGA,{T},{dm(flat[k])},N,{dm(flon[k], True)},E,1,{nsat:02d},{hdop[k]:.2f},{520 + rng.normal(0, 2):.1f},M,47.4,M,,")
        sog = abs(vt[k]) * 1.943844 + rng.normal(0, 0.05); sog = max(sog, 0.0)
        rmc = cs(f"GPRMC,{T},A,{dm(flat[k])},N,{dm(flon[k], True)},E,{sog:.3f},{cog[k]:.2f},{ddmmyy},,,A")
        sl = sig_rep[k] * rng.uniform(0.85, 1.15); so = np.sqrt(max(2 * sig_rep[k] ** 2 - sl ** 2, 0.5))
        gst = cs(f"GPGST,{T},{np.hypot(sl, so) * 1.2:.1f},{max(sl, so) * 1.1:.2f},{min(sl, so):.2f},{rng.uniform(0, 180):.1f},{sl:.2f},{so:.2f},{2 * sig_rep[k]:.2f}")
    for j, sen in enumerate((rmc, gga, gst)):
        lines.append((rx + 0.004 * j, sen))
lines.sort()
with open(os.path.join(here, "nmea.log"), "w") as fh:
    fh.write("# t_log_s,sentence\n")
    for tr, sen in lines: fh.write(f"{tr:.3f},{sen}\n")
# keep true fix errors for reference
np.savetxt(os.path.join(here, "fix_errors.csv"), np.c_[ep_log, err_e, err_n, sig_rep, hdop, in_tunnel],
           delimiter=",", header="t_log_epoch,err_e,err_n,gst_sigma,hdop,tunnel", comments="", fmt="%.3f")
print("first sentence at t_log", lines[0][0], "n sentences", len(lines))
print("fix error: median horiz", np.median(np.hypot(err_e, err_n)[~in_tunnel]).round(2), "p95", np.percentile(np.hypot(err_e, err_n)[~in_tunnel], 95).round(2))
