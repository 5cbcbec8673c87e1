"""A 10-minute urban drive written as an iOS SensorLog-style CSV at 10 Hz (stop 58; written by a helper who tried
the package as a new user, with a simulation of their own, not the package's).

    python docs/study-outputs/dr/phone-log/simulate_sensorlog.py OUT_DIR

Writes ``OUT_DIR/sensorlog_drive.csv`` (the log as the app writes it: ISO times, the last fix repeated on the rows
after it, -1 for an unknown speed and course, ``motionYaw`` counter-clockwise from an arbitrary zero, a raw
``gyroRotationZ`` counter-clockwise with a 0.3 deg/s bias) and the truth, ``OUT_DIR/truth_at_log.npz``.
"""
import csv
import pathlib
import sys
from datetime import datetime, timedelta, timezone

import numpy as np

OUT = pathlib.Path(sys.argv[1])
OUT.mkdir(parents=True, exist_ok=True)

rng = np.random.default_rng(42)
DT = 0.01  # internal integration step (100 Hz)

# ---------------- motion plan -----------------
# segments: ("stop", seconds) / ("speed", target m/s, accel m/s^2) / ("cruise", seconds)
#           ("turn", +90 right / -90 left, speed while turning, radius m)
plan = [
    ("stop", 8),
    ("speed", 12, 2.0), ("cruise", 18), ("speed", 6, -2.0), ("turn", +90, 6, 12),
    ("speed", 13, 1.8), ("cruise", 22), ("speed", 0, -2.2), ("stop", 35),        # light 1
    ("speed", 10, 2.2), ("cruise", 12), ("speed", 5.5, -2.0), ("turn", -90, 5.5, 11),
    ("speed", 14, 1.6), ("cruise", 28), ("speed", 0, -2.0), ("stop", 120),       # long stop 2 min
    ("speed", 11, 2.0), ("cruise", 16), ("speed", 5, -2.0), ("turn", -90, 5, 10),
    ("speed", 15, 1.5), ("cruise", 20), ("speed", 0, -2.5), ("stop", 24),        # light 2
    ("speed", 9, 2.2), ("cruise", 10), ("speed", 6, -1.5), ("turn", +90, 6, 13),
    ("speed", 12, 1.8), ("cruise", 24), ("speed", 0, -2.0), ("stop", 55),        # light 3
    ("speed", 13, 2.0), ("cruise", 15), ("speed", 6, -2.0), ("turn", +90, 6, 12),
    ("speed", 8, 1.5), ("cruise", 45), ("speed", 11, 1.5), ("cruise", 25), ("speed", 0, -1.8), ("stop", 13),
]

v_cmd, r_cmd = [], []   # speed, yaw rate (clockwise positive, rad/s) at 100 Hz
v = 0.0
for seg in plan:
    kind = seg[0]
    if kind == "stop":
        n = int(seg[1] / DT); v_cmd += [0.0] * n; r_cmd += [0.0] * n
    elif kind == "cruise":
        n = int(seg[1] / DT)
        # a little speed wander and gentle road curvature
        wander = 0.4 * np.sin(np.linspace(0, rng.uniform(1, 3) * np.pi, n))
        curv = rng.normal(0, 0.0006) * np.sin(np.linspace(0, np.pi, n))
        v_cmd += list(v + wander * np.sin(np.linspace(0, np.pi, n)))
        r_cmd += list(curv * v)
    elif kind == "speed":
        target, a = seg[1], abs(seg[2])
        n = int(abs(target - v) / a / DT)
        v_cmd += list(np.linspace(v, target, n)); r_cmd += [0.0] * n; v = target
    elif kind == "turn":
        ang, vt, R = np.deg2rad(seg[1]), seg[2], seg[3]
        rate = np.sign(ang) * vt / R
        n = int(abs(ang / rate) / DT)
        v_cmd += [vt] * n; r_cmd += [rate] * n; v = vt

v_cmd, r_cmd = np.array(v_cmd), np.array(r_cmd)
# smooth (jerk limit, steering ramp): 1 s moving average for speed, 0.8 s for yaw rate
def smooth(x, w):
    k = np.ones(int(w / DT)); k /= k.sum()
    return np.convolve(np.r_[np.full(len(k), x[0]), x, np.full(len(k), x[-1])], k, "same")[len(k):-len(k)]
speed = np.clip(smooth(v_cmd, 1.0), 0, None)
speed[speed < 0.02] = 0.0
yawrate = smooth(r_cmd, 0.8)
yawrate[speed == 0] = 0.0
# re-normalise each turn so it is exactly 90 deg after smoothing (smoothing keeps the integral)
n = len(speed)
t = np.arange(n) * DT
psi0 = np.deg2rad(35.0)    # initial heading, clockwise from north
psi = psi0 + np.r_[0, np.cumsum(0.5 * (yawrate[1:] + yawrate[:-1]) * DT)]
east = np.r_[0, np.cumsum(0.5 * (speed[1:] * np.sin(psi[1:]) + speed[:-1] * np.sin(psi[:-1])) * DT)]
north = np.r_[0, np.cumsum(0.5 * (speed[1:] * np.cos(psi[1:]) + speed[:-1] * np.cos(psi[:-1])) * DT)]
print(f"drive: {t[-1]:.1f} s, {np.sum(speed) * DT:.0f} m, max speed {speed.max():.1f} m/s, "
      f"net heading change {np.rad2deg(psi[-1] - psi0):.1f} deg, standing {np.mean(speed == 0) * 100:.0f} %")

# ---------------- geodesy -----------------
LAT0, LON0 = 48.137154, 11.576124
a_wgs, e2 = 6378137.0, 6.69437999014e-3
s = np.sin(np.deg2rad(LAT0))
M = a_wgs * (1 - e2) / (1 - e2 * s * s) ** 1.5
N = a_wgs / np.sqrt(1 - e2 * s * s)
def to_latlon(e, nn):
    return LAT0 + np.rad2deg(nn / M), LON0 + np.rad2deg(e / (N * np.cos(np.deg2rad(LAT0))))


# ---------------- logging clock -----------------
T_START = datetime(2024, 5, 14, 8, 21, 33, 140000, tzinfo=timezone.utc).timestamp()  # epoch of t = 0
T_LOG_END = t[-1] - 0.2
k = np.arange(int(T_LOG_END / 0.1))
t_log = 0.1 * k + 0.013 + rng.uniform(-0.004, 0.004, len(k))   # SensorLog rows, jitter of a few ms
t_log = t_log[t_log < t[-1]]

def interp(x, tt):
    return np.interp(tt, t, x)

# ---------------- motion sensors -----------------
# raw gyro z (counter-clockwise positive), uncalibrated MEMS bias 0.3 deg/s, slowly moving
gyro_bias = np.deg2rad(0.30) + np.deg2rad(0.02) * np.sin(2 * np.pi * t_log / 900)
gyro_z = -interp(yawrate, t_log) + gyro_bias + rng.normal(0, np.deg2rad(0.15), len(t_log))
# engine / road vibration while moving
gyro_z += rng.normal(0, np.deg2rad(0.1), len(t_log)) * (interp(speed, t_log) > 0)
# CoreMotion fused yaw (xArbitraryZVertical): ccw positive, arbitrary zero, residual drift 0.01 deg/s
yaw_zero = 2.417  # rad, arbitrary
resid = np.deg2rad(0.01) * t_log + np.cumsum(rng.normal(0, np.deg2rad(0.002), len(t_log)))
motion_yaw = yaw_zero - interp(psi, t_log) + resid + rng.normal(0, np.deg2rad(0.05), len(t_log))
motion_yaw = (motion_yaw + np.pi) % (2 * np.pi) - np.pi

# ---------------- GPS (1 Hz, correlated errors) -----------------
t_fix = np.arange(1.0, t[-1] - 0.5, 1.0) + 0.000   # fix epochs on whole seconds of t
nf = len(t_fix)
acc = np.empty(nf)   # reported 68 % radius, 5-10 m, slowly varying
x = 0.0
for i in range(nf):
    x = 0.97 * x + np.sqrt(1 - 0.97 ** 2) * rng.normal()
    acc[i] = 7.5 + 2.5 * np.tanh(x)
acc = np.round(acc, 1)
sig = acc / 1.51   # true per-axis sigma matches the reported accuracy
tau = 20.0
phi = np.exp(-1.0 / tau)
err = np.zeros((nf, 2))
err[0] = rng.normal(0, sig[0], 2)
for i in range(1, nf):
    err[i] = phi * err[i - 1] + np.sqrt(1 - phi ** 2) * sig[i] * rng.normal(size=2)
fe = interp(east, t_fix) + err[:, 0]
fn = interp(north, t_fix) + err[:, 1]
flat, flon = to_latlon(fe, fn)
vf = interp(speed, t_fix)
gspeed = np.clip(vf + rng.normal(0, 0.15, nf), 0, None)
gspeed = np.where(vf < 0.3, -1.0, np.round(gspeed, 2))
gcourse = (np.rad2deg(interp(psi, t_fix)) + rng.normal(0, 1.5, nf)) % 360
gcourse = np.where(vf < 1.0, -1.0, np.round(gcourse, 1))
# each fix reaches the app 0.15-0.45 s after its time stamp; it shows from the first row after that
t_avail = t_fix + rng.uniform(0.15, 0.45, nf)
print(f"GPS error per axis: rms {np.sqrt(np.mean(err ** 2)):.2f} m, max radial {np.hypot(*err.T).max():.1f} m")

# ---------------- write SensorLog CSV -----------------
cols = ["loggingTime(txt)", "loggingSample(N)", "identifierForVendor(txt)",
        "locationTimestamp_since1970(s)", "locationLatitude(WGS84)", "locationLongitude(WGS84)",
        "locationAltitude(m)", "locationSpeed(m/s)", "locationCourse(deg)",
        "locationVerticalAccuracy(m)", "locationHorizontalAccuracy(m)",
        "motionTimestamp_sinceReboot(s)", "motionYaw(rad)", "motionRoll(rad)", "motionPitch(rad)",
        "gyroTimestamp_sinceReboot(s)", "gyroRotationX(rad/s)", "gyroRotationY(rad/s)", "gyroRotationZ(rad/s)"]
tz = timezone(timedelta(hours=2))
boot = 183654.2871  # seconds since reboot at t = 0
with open(OUT / "sensorlog_drive.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(cols)
    j = -1
    for i, tl in enumerate(t_log):
        while j + 1 < nf and t_avail[j + 1] <= tl:
            j += 1
        lt = datetime.fromtimestamp(T_START + tl, tz).isoformat(timespec="milliseconds")
        if j < 0:   # no fix yet: SensorLog writes zeros / -1
            loc = ["0", "0", "0", "0", "-1", "-1", "-1", "-1"]
        else:
            loc = [f"{T_START + t_fix[j]:.3f}", f"{flat[j]:.8f}", f"{flon[j]:.8f}", "521.3",
                   f"{gspeed[j]:g}", f"{gcourse[j]:g}", "4.0", f"{acc[j]:g}"]
        w.writerow([lt, i, "5B1F2A4C-6D0E-4C6B-9C6F-4A0D2C1E9F11"] + loc +
                   [f"{boot + tl - 0.004:.6f}", f"{motion_yaw[i]:.6f}", f"{rng.normal(0, 0.003):.6f}",
                    f"{rng.normal(0.02, 0.003):.6f}",
                    f"{boot + tl - 0.006:.6f}", f"{rng.normal(0, 0.004):.6f}", f"{rng.normal(0, 0.004):.6f}",
                    f"{gyro_z[i]:.6f}"])
# truth at the log rows and at the fix times, for the conversion's truth columns
np.savez(OUT / "truth_at_log.npz", t_log_epoch=T_START + t_log,
         east=interp(east, t_log), north=interp(north, t_log), psi=interp(psi, t_log), speed=interp(speed, t_log),
         t_fix_epoch=T_START + t_fix, fix_east=interp(east, t_fix), fix_north=interp(north, t_fix))
print(f"wrote {len(t_log)} rows, {nf} fixes")
