"""Write my own test drives with plain numpy (no filterwnn import).

Truth: integrate a smooth speed and yaw-rate profile. Sensors = truth + faults.
Fixes = truth + white noise (plus the faults named per drive).
Run: python gen_drives.py [FOLDER]  -> writes D*.csv there (default: the current folder).

(Stop 69: written by a helper acting as a new user, who had not read the package's code or its simulators; kept
as it was written but for the output folder. See RUN.md.)
"""
import os
import sys

import numpy as np

OUT = sys.argv[1] if len(sys.argv) > 1 else "."

LAT0, LON0 = 48.137, 11.575
R = 6378137.0


def smooth(x, n):
    if n <= 1:
        return x
    k = np.ones(n) / n
    xp = np.r_[np.full(n, x[0]), x, np.full(n, x[-1])]
    return np.convolve(xp, k, mode="same")[n:-n]


def profile(segs, dt, smooth_s=3.0):
    """segs: list of (duration s, speed m/s, yaw rate deg/s). Piecewise, then smoothed."""
    v, r = [], []
    for d, s, w in segs:
        n = int(round(d / dt))
        v += [s] * n
        r += [w] * n
    n = max(1, int(round(smooth_s / dt)))
    v = smooth(np.array(v, float), n)
    r = smooth(np.array(r, float), n)
    # no yaw rate while (almost) stopped
    r = np.where(np.abs(v) < 0.05, 0.0, r)
    return v, np.deg2rad(r)


def integrate(v, r, dt, psi0=0.0, sub=10):
    n = len(v)
    e = np.zeros(n); nn = np.zeros(n); psi = np.zeros(n)
    psi[0] = psi0
    E = N = 0.0; P = psi0
    for k in range(1, n):
        h = dt / sub
        for j in range(sub):
            a = (j + 0.5) / sub
            vv = v[k - 1] + a * (v[k] - v[k - 1])
            rr = r[k - 1] + a * (r[k] - r[k - 1])
            Pm = P + 0.5 * h * rr
            E += vv * np.sin(Pm) * h
            N += vv * np.cos(Pm) * h
            P += rr * h
        e[k], nn[k], psi[k] = E, N, P
    return e, nn, psi


def to_latlon(e, n):
    lat = LAT0 + np.rad2deg(n / R)
    lon = LON0 + np.rad2deg(e / (R * np.cos(np.deg2rad(LAT0))))
    return lat, lon


def fmt(x, f):
    return "" if (x is None or not np.isfinite(x)) else f % x


def write(path, cols, fmts):
    names = list(cols)
    n = len(cols["time"])
    with open(path, "w") as fh:
        fh.write(",".join(names) + "\n")
        for k in range(n):
            fh.write(",".join(fmt(cols[c][k], fmts[c]) for c in names) + "\n")
    print("wrote", path, n, "rows")


def fixes(t, e, n, every, sigma_true, rng, t0_phase=0.0):
    """fix on rows where (t - t0_phase) is a multiple of `every` (to the sample)."""
    dt = t[1] - t[0]
    has = np.abs(((t - t0_phase + 1e-9) % every)) < dt / 2
    ge = np.where(has, e + sigma_true * rng.standard_normal(len(t)), np.nan)
    gn = np.where(has, n + sigma_true * rng.standard_normal(len(t)), np.nan)
    return has, ge, gn


# ---------------------------------------------------------------- D1
def d1(rng):
    """Parking-space reverse with an unsigned CAN speed; heading quantised to whole degrees. 10 Hz, 8 min."""
    dt = 0.1
    segs = [(8, 0, 0), (10, -1.3, -9.0), (4, 0, 0)]  # reverse out, swinging ~ -90 deg
    # city: accel, cruise, right turns, lights
    for i in range(8):
        segs += [(20, 12, 0), (6, 7, 15 if i % 2 == 0 else -15), (15, 13, 0),
                 (6, 6, 15), (8, 0, 0) if i % 3 == 0 else (4, 9, 0), (10, 11, 1.0)]
    v, r = profile(segs, dt, 2.0)
    n = int(480 / dt)
    v, r = v[:n], r[:n]
    t = np.arange(n) * dt
    e, nn, psi = integrate(v, r, dt, psi0=np.deg2rad(200))
    speed = np.abs(v) * 1.01 + 0.03 * rng.standard_normal(n) * (v != 0)  # unsigned CAN speed
    speed = np.maximum(speed, 0)
    head = np.round(np.rad2deg(psi) % 360)  # whole degrees, gyro/compass fused, no noise
    has, ge, gn = fixes(t, e, nn, 1.0, 2.5, rng)
    glat, glon = to_latlon(ge, gn)
    tlat, tlon = to_latlon(e, nn)
    sig = np.where(has, 2.5, np.nan)
    write(os.path.join(OUT, "D1_parking_reverse_quantised.csv"),
          dict(time=t, heading_deg=head, speed=speed, gps_lat=glat, gps_lon=glon, gps_sigma=sig,
               true_lat=tlat, true_lon=tlon),
          dict(time="%.1f", heading_deg="%.0f", speed="%.3f", gps_lat="%.8f", gps_lon="%.8f",
               gps_sigma="%.1f", true_lat="%.8f", true_lon="%.8f"))


# ---------------------------------------------------------------- D2
def d2(rng):
    """Highway 30 m/s, 1 Hz DR, log starts mid-motion, fixes at 0.2 Hz and a 3-min tunnel. 12 min."""
    dt = 1.0
    segs = [(60, 30, 0), (40, 30, 0.6), (120, 31, 0), (60, 29, -0.5), (200, 30, 0),
            (50, 28, 0.8), (120, 30, 0), (80, 30, -0.3), (60, 31, 0)]
    v, r = profile(segs, dt, 8.0)
    n = 720
    v, r = v[:n], r[:n]
    t = 1000.0 + np.arange(n) * dt  # stamps start at 1000 s
    e, nn, psi = integrate(v, r, dt, psi0=np.deg2rad(35))
    speed = v * 1.005 + 0.05 * rng.standard_normal(n)
    head = np.rad2deg(psi) + 0.3 * rng.standard_normal(n)
    has, ge, gn = fixes(t, e, nn, 5.0, 3.0, rng)
    tunnel = (t >= 1300) & (t < 1480)
    ge[tunnel] = np.nan; gn[tunnel] = np.nan
    has = np.isfinite(ge)
    sig = np.where(has, 3.0, np.nan)
    write(os.path.join(OUT, "D2_highway_1Hz_tunnel.csv"),
          dict(time=t, heading_deg=head % 360, speed=speed, gps_east=ge, gps_north=gn, gps_sigma=sig,
               true_east=e, true_north=nn),
          dict(time="%.1f", heading_deg="%.3f", speed="%.3f", gps_east="%.2f", gps_north="%.2f",
               gps_sigma="%.1f", true_east="%.3f", true_north="%.3f"))


# ---------------------------------------------------------------- D3
def d3(rng):
    """Gyro heading with slowly varying bias + 1.5 deg white noise; 60 s of 15 m multipath reported 3 m. 10 Hz, 10 min."""
    dt = 0.1
    segs = [(5, 0, 0)]
    for i in range(10):
        segs += [(25, 14, 0), (7, 8, 12 if i % 2 else -12), (20, 15, 0.5), (6, 7, -13), (12, 0, 0) if i % 4 == 0 else (5, 10, 0)]
    v, r = profile(segs, dt, 2.5)
    n = 6000
    v, r = v[:n], r[:n]
    t = np.arange(n) * dt
    e, nn, psi = integrate(v, r, dt, psi0=np.deg2rad(80))
    bias = 2.0 + 4.0 * np.sin(2 * np.pi * t / 420.0) + 0.004 * t
    head = np.rad2deg(psi) + bias + 1.5 * rng.standard_normal(n)
    speed = v * 0.985 + 0.04 * rng.standard_normal(n) * (v > 0)
    speed = np.maximum(speed, 0)
    has, ge, gn = fixes(t, e, nn, 1.0, 2.5, rng)
    mp = (t >= 250) & (t < 310)
    ge[mp & has] += 10.6; gn[mp & has] += 10.6  # 15 m constant offset
    glat, glon = to_latlon(ge, gn)
    tlat, tlon = to_latlon(e, nn)
    sig = np.where(has, 3.0, np.nan)
    write(os.path.join(OUT, "D3_gyro_bias_multipath.csv"),
          dict(time=t, heading_deg=head % 360, speed=speed, gps_lat=glat, gps_lon=glon, gps_sigma=sig,
               true_lat=tlat, true_lon=tlon),
          dict(time="%.1f", heading_deg="%.3f", speed="%.3f", gps_lat="%.8f", gps_lon="%.8f",
               gps_sigma="%.1f", true_lat="%.8f", true_lon="%.8f"))


# ---------------------------------------------------------------- D4
def d4(rng, kmh=True):
    """Roundabout circled three times; speed logged in km/h by mistake; gyro yaw_rate_deg with 0.1 deg/s bias. 5 Hz, 7 min."""
    dt = 0.2
    segs = [(5, 0, 0), (40, 13, 0), (8, 8, 0)]
    # roundabout radius ~20 m at 8 m/s -> 22.9 deg/s, 3 laps = 1080 deg -> 47 s
    segs += [(3, 8, -8), (47.2, 8, 22.9), (3, 8, -8)]
    segs += [(60, 14, 0), (8, 7, -14), (60, 15, 0.3), (10, 0, 0), (50, 13, 0), (8, 7, 14),
             (70, 14, 0), (8, 7, -14), (40, 12, 0), (12, 0, 0), (40, 12, 0)]
    v, r = profile(segs, dt, 2.0)
    n = int(420 / dt)
    v, r = v[:n], r[:n]
    t = np.arange(n) * dt
    e, nn, psi = integrate(v, r, dt, psi0=np.deg2rad(300))
    yr = np.rad2deg(r) + 0.1 + 0.05 * rng.standard_normal(n)
    speed = (v + 0.04 * rng.standard_normal(n) * (v > 0)).clip(0)
    if kmh:
        speed = speed * 3.6
    has, ge, gn = fixes(t, e, nn, 1.0, 2.0, rng)
    sig = np.where(has, 2.0, np.nan)
    name = "D4_roundabout_kmh.csv" if kmh else "D4b_roundabout_ms.csv"
    write(os.path.join(OUT, name),
          dict(time=t, yaw_rate_deg=yr, speed=speed, gps_east=ge, gps_north=gn, gps_sigma=sig,
               true_east=e, true_north=nn),
          dict(time="%.1f", yaw_rate_deg="%.4f", speed="%.3f", gps_east="%.2f", gps_north="%.2f",
               gps_sigma="%.1f", true_east="%.3f", true_north="%.3f"))


# ---------------------------------------------------------------- D5
def d5(rng):
    """Log starts mid-motion at 20 m/s; raw phone gyro yaw_rate (rad/s) with 0.3 deg/s bias; phone fixes. 10 Hz, 9 min."""
    dt = 0.1
    segs = [(60, 20, 0), (10, 12, 9), (40, 20, 0), (15, 9, -12), (8, 0, 0), (30, 12, 0)]
    for i in range(6):
        segs += [(30, 16, 0.4), (8, 7, -12 if i % 2 else 12), (20, 14, 0), (10, 0, 0) if i % 2 else (6, 10, 0)]
    segs += [(200, 18, 0)]
    v, r = profile(segs, dt, 2.0)
    v[: int(10 / dt)] = 20.0  # already at 20 m/s on the first row
    n = int(540 / dt)
    v, r = v[:n], r[:n]
    t = np.arange(n) * dt
    e, nn, psi = integrate(v, r, dt, psi0=np.deg2rad(170))
    yr = r + np.deg2rad(0.3) + np.deg2rad(0.08) * rng.standard_normal(n)
    speed = (v + 0.05 * rng.standard_normal(n) * (v > 0)).clip(0)
    has, ge, gn = fixes(t, e, nn, 1.0, 3.5, rng)
    glat, glon = to_latlon(ge, gn)
    tlat, tlon = to_latlon(e, nn)
    acc68 = np.where(has, 3.5 * 1.51 + rng.uniform(-0.5, 0.5, n), np.nan)
    write(os.path.join(OUT, "D5_midstart_gyro_bias.csv"),
          dict(time=t, yaw_rate=yr, speed=speed, gps_lat=glat, gps_lon=glon, gps_sigma=acc68 / 1.51,
               true_lat=tlat, true_lon=tlon),
          dict(time="%.1f", yaw_rate="%.6f", speed="%.3f", gps_lat="%.8f", gps_lon="%.8f",
               gps_sigma="%.2f", true_lat="%.8f", true_lon="%.8f"))


if __name__ == "__main__":
    rng = np.random.default_rng(69)
    d1(rng); d2(rng); d3(rng); d4(rng, True); d5(rng)
    d4(np.random.default_rng(70), False)
