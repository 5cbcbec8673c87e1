"""Simulate 5 car drives, each with one realistic log fault, plus a _clean twin of each.

numpy only, seeded. Writes FOLDER/<name>.csv and <name>_clean.csv (default /tmp/t6/drives) and truth_notes.txt.
The sixth user trial's generator (stop 72), kept as that user wrote it but for the output folder's argument:

    python gen_drives_6.py FOLDER
DR at 10 Hz (time, heading_deg, speed), fixes at 1 Hz (2 Hz for the two-receiver log),
truth true_lat/true_lon on every row.
"""
import os
import numpy as np

import sys

OUT = sys.argv[1] if len(sys.argv) > 1 else "/tmp/t6/drives"
DT = 0.1
LAT0, LON0 = 48.137, 11.575          # Munich-ish
R_E = 6378137.0


def to_latlon(e, n):
    lat = LAT0 + np.degrees(n / R_E)
    lon = LON0 + np.degrees(e / (R_E * np.cos(np.radians(LAT0))))
    return lat, lon


def make_route(rng, duration, town=True):
    """Legs: (length m, cruise speed m/s, turn deg after, turn radius m, stop s after)."""
    legs = []
    total_t = 0.0
    while total_t < duration * 1.15:
        if town:
            L = rng.uniform(80, 400)
            v = rng.choice([8.3, 11.1, 13.9])
        else:
            L = rng.uniform(300, 1500)
            v = rng.choice([16.7, 22.2, 27.8])
        turn = rng.choice([-90, 90, -90, 90, 0, 0, -45, 30, 120, -135]) + rng.normal(0, 5)
        R = rng.uniform(8, 15) if abs(turn) >= 80 else rng.uniform(20, 80)
        stop = rng.uniform(8, 45) if rng.random() < 0.35 else 0.0
        legs.append((L, v, turn, R, stop))
        total_t += L / v + stop + 10
    return legs


def simulate(rng, duration, town=True, a_acc=1.5, a_dec=2.0, a_lat=2.5):
    legs = make_route(rng, duration, town)
    ds = 0.05
    # curvature and speed limit along distance
    kap, vlim, stops = [], [], []
    s = 0.0
    for (L, v, turn, R, stop) in legs:
        n = int(L / ds)
        kap.append(np.zeros(n)); vlim.append(np.full(n, v))
        s += n * ds
        arc = np.radians(abs(turn)) * R
        m = max(int(arc / ds), 1)
        kap.append(np.full(m, np.sign(turn) / R)); vlim.append(np.full(m, min(v, np.sqrt(a_lat * R))))
        s += m * ds
        if stop > 0:
            stops.append((s, stop))
    kap = np.concatenate(kap); vlim = np.concatenate(vlim)
    stop_idx = {int(round(sp / ds)) - 1: dw for sp, dw in stops}
    for i in stop_idx:
        if 0 <= i < len(vlim):
            vlim[i] = 0.0
    vlim[0] = 0.0
    # accel / decel limits over distance
    vp = vlim.copy()
    for i in range(1, len(vp)):
        vp[i] = min(vp[i], np.sqrt(vp[i - 1] ** 2 + 2 * a_acc * ds))
    for i in range(len(vp) - 2, -1, -1):
        vp[i] = min(vp[i], np.sqrt(vp[i + 1] ** 2 + 2 * a_dec * ds))
    psi = np.cumsum(kap * ds)            # heading change (rad, clockwise positive)
    h0 = rng.uniform(0, 2 * np.pi)
    # integrate in time
    n_t = int(duration / DT)
    t = np.arange(n_t) * DT
    S = np.zeros(n_t); V = np.zeros(n_t)
    s = 0.0; v = 0.0; dwell = 0.0; passed = set()
    stop_pts = sorted(stop_idx.items())
    # wobble of the speed around the profile (traffic)
    wob = np.zeros(n_t); w = 0.0
    for k in range(n_t):
        w += -w * DT / 20 + 0.25 * np.sqrt(DT) * rng.normal()
        wob[k] = w
    for k in range(n_t):
        if dwell > 0:
            dwell -= DT; v = 0.0
        else:
            i = min(int(s / ds), len(vp) - 1)
            target = max(vp[i] * (1 + 0.08 * np.tanh(wob[k])), 0.0)
            target = max(target, 0.4) if vp[i] < 0.4 else target
            dv = np.clip(target - v, -a_dec * DT, a_acc * DT)
            v = max(v + dv, 0.0)
            s_new = s + v * DT
            for (si, dw) in stop_pts:
                if si not in passed and s < si * ds <= s_new:
                    passed.add(si); dwell = dw; s_new = si * ds; v = 0.0
            s = s_new
        S[k] = s; V[k] = v
    idx = np.minimum((S / ds).astype(int), len(psi) - 1)
    head = (h0 + psi[idx]) % (2 * np.pi)
    e = np.cumsum(V * np.sin(head) * DT); nn = np.cumsum(V * np.cos(head) * DT)
    e -= e[0]; nn -= nn[0]
    return t, e, nn, head, V


def gm(rng, n, sd, tau, dt):
    a = np.exp(-dt / tau); x = np.zeros(n); x[0] = rng.normal(0, sd)
    q = sd * np.sqrt(1 - a * a)
    for k in range(1, n):
        x[k] = a * x[k - 1] + q * rng.normal()
    return x


def base(seed, duration, town=True, head_noise=0.5):
    rng = np.random.default_rng(seed)
    t, e, n, h, v = simulate(rng, duration, town)
    N = len(t)
    # DR sensors: speed with 1 % scale error and noise; heading (AHRS) with slow bias + noise
    speed = np.maximum(v * 1.01 + rng.normal(0, 0.05, N) * (v > 0), 0.0)
    hb = 1.0 + gm(rng, N, 0.5, 300, DT)
    heading = np.degrees(h) + hb + rng.normal(0, head_noise, N)
    # GPS noise processes (two receivers), 1 Hz base
    gA = np.stack([gm(rng, N, 1.5, 20, DT) + rng.normal(0, 1.0, N) for _ in range(2)], 1)
    gB = np.stack([gm(rng, N, 1.5, 20, DT) + rng.normal(0, 1.0, N) for _ in range(2)], 1)
    sig = 1.8 * np.exp(gm(rng, N, 0.2, 60, DT))
    return dict(rng=rng, t=t, e=e, n=n, h=h, v=v, speed=speed, heading=heading, gA=gA, gB=gB, sig=sig)


def write(name, d, fix_rows, fe, fn, fsig):
    t = d["t"]; N = len(t)
    tl, tn = to_latlon(d["e"], d["n"])
    glat = np.full(N, np.nan); glon = np.full(N, np.nan); gs = np.full(N, np.nan)
    la, lo = to_latlon(fe, fn)
    glat[fix_rows] = la; glon[fix_rows] = lo; gs[fix_rows] = fsig
    hd = d["heading_out"] if "heading_out" in d else d["heading"] % 360
    with open(os.path.join(OUT, name + ".csv"), "w") as f:
        f.write("time,heading_deg,speed,gps_lat,gps_lon,gps_sigma,true_lat,true_lon\n")
        for k in range(N):
            if np.isfinite(glat[k]):
                g = f"{glat[k]:.8f},{glon[k]:.8f},{gs[k]:.2f}"
            else:
                g = ",,"
            f.write(f"{t[k]:.1f},{hd[k]:.2f},{d['speed'][k]:.3f},{g},{tl[k]:.8f},{tn[k]:.8f}\n")


def fixes_1hz(d, lag=0):
    rows = np.arange(0, len(d["t"]), 10)
    return rows


def main():
    os.makedirs(OUT, exist_ok=True)
    notes = []

    # 1. dualrx: two receivers interleaved (A at whole s, B at half s), B offset 5.5 m
    d = base(101, 720)
    rA = np.arange(0, len(d["t"]), 10); rB = np.arange(5, len(d["t"]), 10)
    rows = np.sort(np.r_[rA, rB])
    isB = (rows % 10) == 5
    off = np.array([4.2, -3.6])
    g = np.where(isB[:, None], d["gB"][rows], d["gA"][rows])
    fe = d["e"][rows] + g[:, 0]; fn = d["n"][rows] + g[:, 1]
    write("dualrx_clean", d, rows, fe, fn, d["sig"][rows])
    write("dualrx", d, rows, fe + off[0] * isB, fn + off[1] * isB, d["sig"][rows])
    notes.append("dualrx: 12 min town drive, DR 10 Hz; fixes at 2 Hz from two receivers interleaved "
                 "(A at whole seconds, B at half seconds). B's fixes are offset by a constant +4.2 m E, -3.6 m N "
                 "(5.5 m) from A's (different antenna/datum/lever arm). Both report gps_sigma ~1.8 m (0.8-1.4x). "
                 "Twin: same fixes, no offset.")

    # 2. smoothed: phone smooths fixes, first-order low-pass tau 2.5 s, reports sigma 1-2 m
    d = base(202, 660)
    rows = np.arange(0, len(d["t"]), 10)
    fe_raw = d["e"][rows] + d["gA"][rows, 0]; fn_raw = d["n"][rows] + d["gA"][rows, 1]
    write("smoothed_clean", d, rows, fe_raw, fn_raw, d["sig"][rows] * 1.0)
    a = 1 - np.exp(-1.0 / 2.5)
    fe = fe_raw.copy(); fn = fn_raw.copy()
    for k in range(1, len(rows)):
        fe[k] = fe[k - 1] + a * (fe_raw[k] - fe[k - 1]); fn[k] = fn[k - 1] + a * (fn_raw[k] - fn[k - 1])
    sig = 1.0 + 1.0 * (d["sig"][rows] - d["sig"][rows].min()) / np.ptp(d["sig"][rows])
    write("smoothed", d, rows, fe, fn, sig)
    notes.append("smoothed: 11 min town drive; 1 Hz fixes passed through a first-order low-pass (tau 2.5 s, "
                 "alpha 0.33 per fix) by the phone's location smoother: the fix lags the car by ~v*2.5 s on straights "
                 "(20-35 m at 8-14 m/s) and cuts corners in turns; gps_sigma rescaled to 1.0-2.0 m. "
                 "Twin: raw fixes (errors GM 1.5 m/20 s + white 1 m per axis), sigma ~1.8 m.")

    # 3. magsteps: magnetometer heading with steps from the car's electrics
    d = base(303, 840, head_noise=1.5)
    t = d["t"]
    steps = [(110, 290, 8.0), (400, 580, -12.0), (650, 760, 6.0)]
    hs = np.zeros(len(t))
    for (a0, a1, dd) in steps:
        # switch on/off within ~1 s
        with np.errstate(over="ignore"):
            hs += dd * (1 / (1 + np.exp(-(t - a0) / 0.3)) - 1 / (1 + np.exp(-(t - a1) / 0.3)))
    rows = np.arange(0, len(t), 10)
    fe = d["e"][rows] + d["gA"][rows, 0]; fn = d["n"][rows] + d["gA"][rows, 1]
    write("magsteps_clean", d, rows, fe, fn, d["sig"][rows])
    d["heading_out"] = (d["heading"] + hs) % 360
    write("magsteps", d, rows, fe, fn, d["sig"][rows])
    notes.append("magsteps: 14 min town drive; heading_deg from a magnetometer (white noise 1.5 deg, slow bias "
                 "~1+-0.5 deg) disturbed by the car's electrics: +8 deg from 110-290 s (A/C compressor), "
                 "-12 deg from 400-580 s (rear-window heater), +6 deg from 650-760 s (blower), each switching in ~1 s. "
                 "Twin: no steps.")

    # 4. sigma99: receiver writes placeholder accuracy 99.9 m for stretches (accuracy field missing)
    d = base(404, 780, town=False)
    rows = np.arange(0, len(d["t"]), 10)
    fe = d["e"][rows] + d["gA"][rows, 0]; fn = d["n"][rows] + d["gA"][rows, 1]
    sig = d["sig"][rows].copy()
    write("sigma99_clean", d, rows, fe, fn, sig)
    tr = d["t"][rows]
    bad = ((tr >= 150) & (tr < 260)) | ((tr >= 420) & (tr < 520)) | ((tr >= 640) & (tr < 720))
    sig2 = sig.copy(); sig2[bad] = 99.9
    write("sigma99", d, rows, fe, fn, sig2)
    notes.append("sigma99: 13 min suburban/highway drive (8-28 m/s); in 3 stretches (150-260 s, 420-520 s, "
                 "640-720 s; 290 of 780 fixes, 37 %) the logger wrote the placeholder accuracy 99.9 m (the field "
                 "was missing in the NMEA/Android record) though the fixes are as good as elsewhere (~1.8 m). "
                 "Twin: the true reported sigma there.")

    # 5. enu_restart: heading column switches to ENU yaw (CCW from east) after a logger node restart
    d = base(505, 600)
    rows = np.arange(0, len(d["t"]), 10)
    fe = d["e"][rows] + d["gA"][rows, 0]; fn = d["n"][rows] + d["gA"][rows, 1]
    write("enu_restart_clean", d, rows, fe, fn, d["sig"][rows])
    hd = d["heading"] % 360
    sw = d["t"] >= 250.0
    enu = (90.0 - d["heading"] + 180) % 360 - 180
    hd = np.where(sw, enu, hd)
    d["heading_out"] = hd
    write("enu_restart", d, rows, fe, fn, d["sig"][rows])
    notes.append("enu_restart: 10 min town drive; from t=250 s on (after a logger node restart that loaded "
                 "another launch file) heading_deg is the ENU yaw, counter-clockwise from east, in (-180,180]: "
                 "yaw = 90 - heading. Before 250 s (42 %) it is the correct clockwise-from-north heading. "
                 "Twin: clockwise-from-north throughout.")
    with open(os.path.join(OUT, "truth_notes.txt"), "w") as f:
        f.write("Common: DR 10 Hz, speed = 1.01*v + N(0,0.05) m/s, heading_deg AHRS (bias GM ~1+-0.5 deg, "
                "noise 0.5 deg unless said), fixes 1 Hz, errors per axis GM(1.5 m, 20 s)+white 1 m, "
                "gps_sigma ~1.8 m slowly varying, truth true_lat/true_lon at 48.137N 11.575E.\n")
        for s in notes:
            f.write(s + "\n")


if __name__ == "__main__":
    main()
