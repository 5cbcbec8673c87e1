"""Write 5 synthetic drive CSVs with plain numpy (no filterwnn imports).

Run: python gen_drives_2.py [FOLDER] (default: the current folder). (Stop 69: the second user trial's drives,
written by a helper who had not read the package's code; kept as written but for the output folder. See RUN.md.)
"""
import os
import sys

import numpy as np

A_WGS = 6378137.0
E2 = 6.69437999014e-3
OUT = os.path.join(sys.argv[1] if len(sys.argv) > 1 else ".", "")


def radii(lat_deg):
    s = np.sin(np.radians(lat_deg))
    rn = A_WGS / np.sqrt(1 - E2 * s * s)
    rm = A_WGS * (1 - E2) / (1 - E2 * s * s) ** 1.5
    return rm, rn


def en_to_ll(e, n, lat0, lon0):
    rm, rn = radii(lat0)
    lat = lat0 + np.degrees(n / rm)
    lon = lon0 + np.degrees(e / (rn * np.cos(np.radians(lat0))))
    lon = (lon + 180.0) % 360.0 - 180.0
    return lat, lon


def trajectory(rng, duration, dt_int=0.01, stop_at=None, stop_len=0.0, vmax=(8, 18),
               n_stops=3, grade=None):
    """Piecewise road: straights + turns, speed with intersections stops.
    Returns t, east, north, heading(rad), speed along path (3D if grade), horizontal speed."""
    n = int(round(duration / dt_int)) + 1
    t = np.arange(n) * dt_int
    yaw_rate = np.zeros(n)
    k = 0
    while k < n:
        straight = int(rng.uniform(15, 50) / dt_int)
        k += straight
        turn_T = rng.uniform(5, 12)
        ang = np.radians(rng.choice([90, -90, 45, -45, 30, -120, 180 if rng.random() < 0.1 else 60]))
        m = int(turn_T / dt_int)
        prof = np.sin(np.linspace(0, np.pi, m)) ** 2
        prof = prof / prof.sum() / dt_int * ang
        yaw_rate[k:k + m] = prof[: max(0, min(m, n - k))]
        k += m
        # gentle curves too
    yaw_rate += np.radians(1.5) * np.sin(2 * np.pi * t / 37.0) * (rng.random() < 2)
    # speed target
    vt = np.zeros(n)
    k = 0
    while k < n:
        seg = int(rng.uniform(20, 60) / dt_int)
        vt[k:k + seg] = rng.uniform(*vmax)
        k += seg
    # slow in turns
    big = np.abs(yaw_rate) > np.radians(4)
    vt[big] = np.minimum(vt[big], 6.0)
    stops = []
    for _ in range(n_stops):
        s0 = rng.uniform(60, duration - 60)
        stops.append((s0, rng.uniform(8, 25)))
    if stop_at is not None:
        stops.append((stop_at, stop_len))
    for s0, L in stops:
        vt[(t >= s0) & (t < s0 + L)] = 0.0
    # first-order lag to a realistic acceleration (limit 2.5 m/s^2)
    v = np.zeros(n)
    for i in range(1, n):
        dv = np.clip((vt[i] - v[i - 1]) / 3.0, -2.5, 2.0) * dt_int
        v[i] = max(0.0, v[i - 1] + dv)
    # hold the first 5 s at zero
    v[t < 5] = 0.0
    # exact standstill where target zero and v small
    v[(vt == 0) & (v < 0.05)] = 0.0
    # no turning at standstill
    yaw_rate[v < 0.3] = 0.0
    psi = np.cumsum(yaw_rate) * dt_int + rng.uniform(0, 2 * np.pi)
    if grade is not None:
        g = grade(t)
        vh = v / np.sqrt(1 + g ** 2)
    else:
        vh = v
    east = np.cumsum(vh * np.sin(psi)) * dt_int
    north = np.cumsum(vh * np.cos(psi)) * dt_int
    return t, east, north, psi, v, vh


def ar1(rng, n, sigma, tau, dt):
    a = np.exp(-dt / tau)
    e = np.zeros(n)
    e[0] = rng.normal(0, sigma)
    w = rng.normal(0, sigma * np.sqrt(1 - a * a), n)
    for i in range(1, n):
        e[i] = a * e[i - 1] + w[i]
    return e


def write(name, cols, fmt):
    keys = list(cols)
    n = len(cols[keys[0]])
    with open(OUT + name, "w") as f:
        f.write(",".join(keys) + "\n")
        for i in range(n):
            row = []
            for k in keys:
                v = cols[k][i]
                if v is None or (isinstance(v, float) and np.isnan(v)):
                    row.append("")
                else:
                    row.append(fmt.get(k, "%.4f") % v)
            f.write(",".join(row) + "\n")
    print("wrote", name, n, "rows")


def sample(t_int, x, dt):
    step = int(round(dt / 0.01))
    return x[::step]


def base(rng, duration, dr_dt=0.1, **kw):
    t, e, nn, psi, v, vh = trajectory(rng, duration, **kw)
    step = int(round(dr_dt / 0.01))
    return t[::step], e[::step], nn[::step], psi[::step], v[::step], vh[::step]


def speed_meas(rng, v):
    s = v * 1.015 + rng.normal(0, 0.05, v.size)
    s[v == 0] = 0.0
    return np.maximum(s, 0.0)


def fixes(rng, t, e, n, every, sigma, tau=5.0):
    idx = np.arange(0, t.size, every)
    dtf = t[every] - t[0]
    ee = ar1(rng, idx.size, sigma, tau, dtf)
    en = ar1(rng, idx.size, sigma, tau, dtf)
    fe = np.full(t.size, np.nan)
    fn = np.full(t.size, np.nan)
    fe[idx] = e[idx] + ee
    fn[idx] = n[idx] + en
    return fe, fn, idx


FMT_LL = {"time": "%.2f", "gps_lat": "%.8f", "gps_lon": "%.8f", "true_lat": "%.8f", "true_lon": "%.8f",
          "heading_deg": "%.3f", "speed": "%.3f", "gps_sigma": "%.2f", "heading": "%.5f"}


def drive_A():
    """Compass heading: direction-dependent deviation + steel structures. Oslo, 10 min, 10 Hz."""
    rng = np.random.default_rng(101)
    t, e, n, psi, v, vh = base(rng, 600.0)
    dev = (np.radians(7) * np.sin(psi + 0.6) + np.radians(4) * np.cos(2 * psi + 0.3)
           + np.radians(3.0))  # declination-like constant
    steel = np.zeros_like(t)
    for c in rng.uniform(30, 580, 8):
        L = rng.uniform(4, 12)
        amp = np.radians(rng.choice([-1, 1]) * rng.uniform(8, 15))
        m = (t > c) & (t < c + L)
        steel[m] = amp * np.sin(np.pi * (t[m] - c) / L)
    hd = psi + dev + steel + rng.normal(0, np.radians(1.0), t.size)
    fe, fn, idx = fixes(rng, t, e, n, 10, 3.0)
    lat0, lon0 = 59.91, 10.75
    glat, glon = en_to_ll(fe, fn, lat0, lon0)
    tlat, tlon = en_to_ll(e, n, lat0, lon0)
    sig = np.full(t.size, np.nan)
    sig[idx] = 3.0
    write("A_compass_oslo.csv", {"time": t, "heading_deg": np.degrees(hd) % 360, "speed": speed_meas(rng, v),
                                 "gps_lat": glat, "gps_lon": glon, "gps_sigma": sig,
                                 "true_lat": tlat, "true_lon": tlon}, FMT_LL)


def drive_B():
    """Phone rotated 90 deg in its holder, Tierra del Fuego lat -54.8, 12 min, 10 Hz, 1 Hz phone fixes."""
    rng = np.random.default_rng(202)
    t, e, n, psi, v, vh = base(rng, 720.0)
    hd = psi + np.radians(90.0) + np.radians(1.0) + ar1(rng, t.size, np.radians(0.5), 60, 0.1) \
        + rng.normal(0, np.radians(0.5), t.size)
    acc68 = np.clip(rng.normal(6.0, 1.5, t.size), 3.5, 12)
    sig = acc68 / 1.51
    fe, fn, idx = fixes(rng, t, e, n, 10, 1.0)
    # scale each fix error by its own sigma
    fe[idx] = e[idx] + (fe[idx] - e[idx]) * sig[idx]
    fn[idx] = n[idx] + (fn[idx] - n[idx]) * sig[idx]
    lat0, lon0 = -54.80, -68.30
    glat, glon = en_to_ll(fe, fn, lat0, lon0)
    tlat, tlon = en_to_ll(e, n, lat0, lon0)
    s = np.full(t.size, np.nan)
    s[idx] = sig[idx]
    write("B_rot90_south54.csv", {"time": t, "heading_deg": np.degrees(hd) % 360, "speed": speed_meas(rng, v),
                                  "gps_lat": glat, "gps_lon": glon, "gps_sigma": s,
                                  "true_lat": tlat, "true_lon": tlon}, FMT_LL)


def drive_C():
    """Crossing longitude 180 (Taveuni, Fiji), 5 Hz GNSS 1-2 m, 10 Hz speed/heading, 8 min."""
    rng = np.random.default_rng(303)
    t, e, n, psi, v, vh = base(rng, 480.0)
    hd = psi + np.radians(0.8) + rng.normal(0, np.radians(0.3), t.size)
    sigf = rng.uniform(1.0, 2.0, t.size)
    fe, fn, idx = fixes(rng, t, e, n, 2, 1.0, tau=2.0)
    fe[idx] = e[idx] + (fe[idx] - e[idx]) * sigf[idx]
    fn[idx] = n[idx] + (fn[idx] - n[idx]) * sigf[idx]
    # start so the track crosses 180: put the track's mean east at lon 180
    lat0 = -16.80
    rm, rn = radii(lat0)
    emid = 0.5 * (e.min() + e.max())
    lon0 = 180.0 - np.degrees(emid / (rn * np.cos(np.radians(lat0))))
    glat, glon = en_to_ll(fe, fn, lat0, lon0)
    tlat, tlon = en_to_ll(e, n, lat0, lon0)
    s = np.full(t.size, np.nan)
    s[idx] = sigf[idx]
    write("C_dateline_5hz.csv", {"time": t, "heading": hd % (2 * np.pi), "speed": speed_meas(rng, v),
                                 "gps_lat": glat, "gps_lon": glon, "gps_sigma": s,
                                 "true_lat": tlat, "true_lon": tlon}, FMT_LL)
    print("C lon range (true):", np.nanmin(tlon), np.nanmax(tlon), "crossings:",
          int(np.sum(np.abs(np.diff(tlon)) > 180)))


def drive_D():
    """Hills 10-15 % grades, speed along the slope, fixes horizontal; 7-min idling standstill; E/N frame, 15 min."""
    rng = np.random.default_rng(404)

    def grade(tt):
        return 0.125 * np.sign(np.sin(2 * np.pi * tt / 90.0)) * (0.8 + 0.2 * np.abs(np.sin(tt / 13.0)))
    dur = 900.0
    t, e, n, psi, v, vh = base(rng, dur, stop_at=300.0, stop_len=420.0, n_stops=1, grade=grade)
    hd = psi + np.radians(1.2) + rng.normal(0, np.radians(0.4), t.size)
    # idling: heading vibration, speed 0
    sp = speed_meas(rng, v)
    fe, fn, idx = fixes(rng, t, e, n, 10, 3.0)
    stand = (t > 305) & (t < 718)
    # GPS wander 2-5 m during standstill: slow random walk bounded
    w_e = ar1(rng, t.size, 3.5, 60.0, 0.1)
    w_n = ar1(rng, t.size, 3.5, 60.0, 0.1)
    fe[idx] += np.where(stand[idx], w_e[idx], 0)
    fn[idx] += np.where(stand[idx], w_n[idx], 0)
    s = np.full(t.size, np.nan)
    s[idx] = 3.0
    write("D_hills_idle_en.csv", {"time": t, "heading": hd % (2 * np.pi), "speed": sp,
                                  "gps_east": fe + 1000.0, "gps_north": fn - 500.0, "gps_sigma": s,
                                  "true_east": e + 1000.0, "true_north": n - 500.0},
          {"time": "%.2f", "heading": "%.5f", "speed": "%.3f", "gps_east": "%.3f", "gps_north": "%.3f",
           "gps_sigma": "%.2f", "true_east": "%.3f", "true_north": "%.3f"})
    print("D standstill speed zero fraction in 305-718:", np.mean(sp[stand] == 0))


def drive_E():
    """Accuracy column is a 95 % radius; logger restart duplicates a 15 s block (time jumps back). Madrid, 9 min."""
    rng = np.random.default_rng(505)
    t, e, n, psi, v, vh = base(rng, 540.0)
    hd = psi + np.radians(1.0) + rng.normal(0, np.radians(0.5), t.size)
    sig = np.clip(rng.normal(4.0, 1.0, t.size), 2.5, 8)
    fe, fn, idx = fixes(rng, t, e, n, 10, 1.0)
    fe[idx] = e[idx] + (fe[idx] - e[idx]) * sig[idx]
    fn[idx] = n[idx] + (fn[idx] - n[idx]) * sig[idx]
    r95 = np.full(t.size, np.nan)
    r95[idx] = 2.45 * sig[idx]
    lat0, lon0 = 40.42, -3.70
    glat, glon = en_to_ll(fe, fn, lat0, lon0)
    tlat, tlon = en_to_ll(e, n, lat0, lon0)
    cols = {"time": t, "heading_deg": np.degrees(hd) % 360, "speed": speed_meas(rng, v),
            "gps_lat": glat, "gps_lon": glon, "gps_sigma": r95, "true_lat": tlat, "true_lon": tlon}
    # variant 1: 95% radius only (clean time)
    write("E_r95_madrid.csv", cols, FMT_LL)
    # variant 2: logger restart: rows 250.0-264.9 s written again after row 264.9 (duplicated block)
    a = int(250.0 / 0.1)
    b = int(265.0 / 0.1)
    order = np.r_[np.arange(0, b), np.arange(a, b), np.arange(b, t.size)]
    write("E2_r95_dupblock.csv", {k: np.asarray(c)[order] for k, c in cols.items()}, FMT_LL)
    # variant 3: logger restart with time reset to 0 at 300 s (time jumps backwards, data continuous)
    t3 = t.copy()
    k = int(300.0 / 0.1)
    t3[k:] = t[k:] - t[k]
    c3 = dict(cols)
    c3["time"] = t3
    write("E3_r95_timereset.csv", c3, FMT_LL)


if __name__ == "__main__":
    drive_A()
    drive_B()
    drive_C()
    drive_D()
    drive_E()
