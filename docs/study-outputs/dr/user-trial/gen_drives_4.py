#!/usr/bin/env python
"""Seeded simulated car drives with logger faults, each with a _clean twin.

python gen_drives_4.py FOLDER  -> writes d1..d6 *_fault.csv and *_clean.csv plus truth_notes.txt

(Stop 71: the fourth user trial's drives, written by a helper who had not read the package's code; kept as written
but for the output folder's default, the current folder. See RUN.md.)

Plain numpy. Truth: kinematic car integrated at 50 Hz from speed and yaw-rate commands
(yaw rate = curvature(s) * v along a route of straights and turns), logged at 10 Hz DR,
GPS at 1 Hz drawn from the truth (white + Gauss-Markov error). Noise arrays are drawn
first from per-drive seeded streams, faults applied afterwards, so twin and fault share
truth and noise.
"""
import os
import sys

import numpy as np

R_EARTH = 6378137.0
LAT0, LON0 = 48.137, 11.575
DT_IN = 0.02      # truth integration step
DR_EVERY = 5      # 10 Hz DR
GPS_EVERY = 50    # 1 Hz fixes


def make_route(rng, length_m, straight=(80, 400), radius=(12, 40), tight_frac=0.0, tight_r=(7, 9)):
    ds = 0.1
    n = int(length_m / ds)
    kappa = np.zeros(n)
    s = 0.0
    while True:
        s += rng.uniform(*straight)
        ang = np.deg2rad(rng.choice([90, 90, 90, 45, 60, 120]) * rng.choice([-1, 1]))
        R = rng.uniform(*tight_r) if rng.random() < tight_frac else rng.uniform(*radius)
        L = abs(ang) * R
        i0, i1 = int(s / ds), int((s + L) / ds)
        if i1 + 100 >= n:
            break
        seg = np.ones(i1 - i0)
        ramp = min(50, (i1 - i0) // 3)  # 5 m ramps
        if ramp > 0:
            r = 0.5 - 0.5 * np.cos(np.linspace(0, np.pi, ramp))
            seg[:ramp] = r
            seg[-ramp:] = r[::-1]
        seg *= np.sign(ang) / R
        # normalise so the turn angle is exact
        seg *= abs(ang) / (np.sum(np.abs(seg)) * ds)
        kappa[i0:i1] = seg
        s += L
    return kappa, ds


def simulate(rng, T, kappa, ds, stops, vdes_fn, a_lat=2.0, a_dec=1.5, a_acc=1.3, start_still=20.0):
    """stops: list of dict(s=distance, hold=seconds, crawl=(speed, seconds) or None)."""
    n = int(round(T / DT_IN)) + 1
    t = np.arange(n) * DT_IN
    v_turn = np.sqrt(a_lat / np.maximum(np.abs(kappa), 1e-4))
    v_turn = np.minimum(v_turn, 30.0)
    s = 0.0; v = 0.0; psi = rng.uniform(0, 2 * np.pi); e = 0.0; nn = 0.0
    E = np.zeros(n); N = np.zeros(n); V = np.zeros(n); PSI = np.zeros(n); W = np.zeros(n); S = np.zeros(n)
    stops = sorted(stops, key=lambda d: d["s"])
    si = 0
    hold_until = start_still
    crawl_until = -1.0; crawl_v = 0.0; post_hold = 0.0
    look = int(80 / ds)
    for k in range(n):
        tk = t[k]
        i = min(int(s / ds), len(kappa) - 1)
        kap = kappa[i]
        if tk < hold_until:
            target = 0.0
        elif tk < crawl_until:
            target = crawl_v
        else:
            if post_hold > 0:
                hold_until = tk + post_hold; post_hold = 0.0
                target = 0.0
            else:
                seg = v_turn[i:i + look]
                d = np.arange(len(seg)) * ds
                vl = np.min(np.sqrt(seg ** 2 + 2 * a_dec * d))
                target = min(vdes_fn(s), vl)
                if si < len(stops):
                    dstop = stops[si]["s"] - s
                    target = min(target, np.sqrt(2 * a_dec * max(dstop - 0.3, 0.0)))
                    if dstop < 1.0 and v < 0.3:
                        st = stops[si]; si += 1
                        hold_until = tk + st["hold"]
                        if st.get("crawl"):
                            crawl_until = hold_until + st["crawl"][1]
                            crawl_v = st["crawl"][0]
                            post_hold = st["hold"]
        acc = np.clip((target - v) / 0.6, -3.0, a_acc)
        v = max(v + acc * DT_IN, 0.0)
        if target == 0.0 and v < 0.05:
            v = 0.0
        w = kap * v
        E[k], N[k], V[k], PSI[k], W[k], S[k] = e, nn, v, psi, w, s
        # midpoint integration
        psi_m = psi + 0.5 * w * DT_IN
        e += v * np.sin(psi_m) * DT_IN
        nn += v * np.cos(psi_m) * DT_IN
        psi += w * DT_IN
        s += v * DT_IN
    return dict(t=t, e=E, n=N, v=V, psi=PSI, w=W, s=S)


def gm(rng, n, dt, sigma, tau):
    a = np.exp(-dt / tau)
    x = np.zeros(n)
    q = sigma * np.sqrt(1 - a * a)
    w = rng.standard_normal(n)
    x[0] = sigma * w[0]
    for k in range(1, n):
        x[k] = a * x[k - 1] + q * w[k]
    return x


def wrap2pi(a):
    return np.mod(a, 2 * np.pi)


def en_to_ll(e, n):
    lat = LAT0 + np.rad2deg(n / R_EARTH)
    lon = LON0 + np.rad2deg(e / (R_EARTH * np.cos(np.deg2rad(lat))))
    return lat, lon


def fmt(x, nd):
    if x is None or (isinstance(x, float) and np.isnan(x)):
        return ""
    return f"{x:.{nd}f}"


def write_csv(path, cols, rows_data, nd, nan_style=None):
    """cols: names; rows_data: dict name->array (NaN = empty cell)."""
    n = len(rows_data[cols[0]])
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        for r in range(n):
            cells = []
            for c in cols:
                x = rows_data[c][r]
                if isinstance(x, str):
                    cells.append(x)
                elif np.isnan(x):
                    cells.append("")
                else:
                    cells.append(f"{x:.{nd[c]}f}")
            f.write(",".join(cells) + "\n")


def base_drive(seed, T, route_kw=None, stop_every=(300, 900), hold=(5, 40), crawl_frac=0.0,
               vdes=12.0, extra_stops=(), vdes_fn=None):
    rng = np.random.default_rng([seed, 0])
    kappa, ds = make_route(rng, 40000, **(route_kw or {}))
    stops = []
    s = 0.0
    while s < 39000:
        s += rng.uniform(*stop_every)
        st = dict(s=s, hold=rng.uniform(*hold))
        if rng.random() < crawl_frac:
            st["crawl"] = (rng.uniform(0.7, 1.2), rng.uniform(25, 45))
            st["hold"] = rng.uniform(4, 8)
        stops.append(st)
    stops += list(extra_stops)
    if vdes_fn is None:
        vd = vdes
        vdes_fn = lambda s_: vd
    tr = simulate(rng, T, kappa, ds, stops, vdes_fn)
    # sample at 10 Hz
    idx = np.arange(0, len(tr["t"]), DR_EVERY)
    d = {k: v[idx] for k, v in tr.items()}
    n = len(idx)
    nz = np.random.default_rng([seed, 1])
    d["noise_v"] = 0.05 * nz.standard_normal(n)
    d["noise_h"] = np.deg2rad(0.3) * nz.standard_normal(n)
    d["noise_w"] = 0.1 * nz.standard_normal(n)           # deg/s white, gyro
    d["gps_white_e"] = 2.0 * nz.standard_normal(n)
    d["gps_white_n"] = 2.0 * nz.standard_normal(n)
    d["gps_gm_e"] = gm(nz, n, 0.1, 1.5, 30.0)
    d["gps_gm_n"] = gm(nz, n, 0.1, 1.5, 30.0)
    d["gps_sig"] = np.round(2.5 + 0.8 * nz.random(n), 1)   # reported sigma per axis (true ~2.5)
    d["fix"] = (np.arange(n) % (GPS_EVERY // DR_EVERY)) == 0
    d["rng_fault"] = np.random.default_rng([seed, 2])
    return d


def assemble(d, *, heading_mode, speed, frame, heading=None, yaw_deg=None, fix=None, gps_e=None,
             gps_n=None, gps_sigma=None, time=None):
    n = len(d["t"])
    fix = d["fix"] if fix is None else fix
    ge = d["e"] + d["gps_white_e"] + d["gps_gm_e"] if gps_e is None else gps_e
    gn = d["n"] + d["gps_white_n"] + d["gps_gm_n"] if gps_n is None else gps_n
    gs = d["gps_sig"] if gps_sigma is None else gps_sigma
    out = {"time": d["t"].copy() if time is None else time}
    cols = ["time"]
    nd = {"time": 2 if time is None else 3}
    if heading_mode == "heading":
        out["heading"] = heading; cols.append("heading"); nd["heading"] = 5
    else:
        out["yaw_rate_deg"] = yaw_deg; cols.append("yaw_rate_deg"); nd["yaw_rate_deg"] = 4
    out["speed"] = speed; cols.append("speed"); nd["speed"] = 3
    nanv = np.full(n, np.nan)
    if frame == "ll":
        la, lo = en_to_ll(ge, gn)
        tla, tlo = en_to_ll(d["e"], d["n"])
        out["gps_lat"] = np.where(fix, la, nanv); out["gps_lon"] = np.where(fix, lo, nanv)
        out["gps_sigma"] = np.where(fix, gs, nanv)
        out["true_lat"] = tla; out["true_lon"] = tlo
        cols += ["gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"]
        nd.update(gps_lat=8, gps_lon=8, gps_sigma=1, true_lat=8, true_lon=8)
    else:
        out["gps_east"] = np.where(fix, ge, nanv); out["gps_north"] = np.where(fix, gn, nanv)
        out["gps_sigma"] = np.where(fix, gs, nanv)
        out["true_east"] = d["e"]; out["true_north"] = d["n"]
        cols += ["gps_east", "gps_north", "gps_sigma", "true_east", "true_north"]
        nd.update(gps_east=3, gps_north=3, gps_sigma=1, true_east=3, true_north=3)
    return cols, out, nd


def heading_meas(d, bias_deg=0.5):
    return wrap2pi(d["psi"] + np.deg2rad(bias_deg) + d["noise_h"])


def speed_meas(d, scale=1.01):
    v = d["v"] * scale + d["noise_v"]
    return np.where(d["v"] == 0.0, 0.0, np.maximum(v, 0.0))


def main(folder):
    os.makedirs(folder, exist_ok=True)
    notes = []

    # ---- D1: MEMS gyro warm-up: bias 0.5 -> 0.05 deg/s, tau 150 s (settled by 10 min); 14 min
    d = base_drive(101, 14 * 60)
    t = d["t"]
    rate_true = np.rad2deg(d["w"])
    bias_f = 0.05 + 0.45 * np.exp(-t / 150.0)
    bias_c = 0.05 * np.ones_like(t)
    sp = speed_meas(d)
    for tag, b in (("fault", bias_f), ("clean", bias_c)):
        y = rate_true * 1.003 + b + d["noise_w"]
        cols, out, nd = assemble(d, heading_mode="yaw", yaw_deg=y, speed=sp, frame="ll")
        write_csv(f"{folder}/d1_gyro_warmup_{tag}.csv", cols, out, nd)
    notes.append(f"d1: 14 min, 10 Hz yaw_rate_deg, 1 Hz lat/lon fixes; fault: gyro bias 0.05+0.45*exp(-t/150) deg/s "
                 f"(0.50 at t=0, {bias_f[int(300/0.1)]:.3f} at 5 min, {bias_f[int(600/0.1)]:.3f} at 10 min); clean: 0.05 deg/s constant; "
                 f"moving {np.mean(d['v']>0.5)*100:.0f}%, dist {d['s'][-1]:.0f} m")

    # ---- D2: CAN speed in 1 km/h steps (truncated) and reading 0 below 1.5 m/s; queues with crawls; 12 min
    d = base_drive(202, 12 * 60, stop_every=(250, 600), crawl_frac=0.4, vdes=11.0)
    v_clean = speed_meas(d)
    kmh = np.floor(v_clean * 3.6)             # CAN speed: integer km/h, truncated
    v_fault = kmh / 3.6
    v_fault[v_clean < 1.5] = 0.0              # wheel-speed sensor cutoff
    h = heading_meas(d)
    for tag, v in (("fault", v_fault), ("clean", v_clean)):
        cols, out, nd = assemble(d, heading_mode="heading", heading=h, speed=v, frame="ll")
        write_csv(f"{folder}/d2_speed_quant_cutoff_{tag}.csv", cols, out, nd)
    crawl_t = np.mean((d["v"] > 0.05) & (d["v"] < 1.5)) * T_frac(d)
    notes.append(f"d2: 12 min, heading (rad, 0.5 deg bias, 0.3 deg noise), lat/lon; fault: speed floor(km/h)/3.6 and 0 below 1.5 m/s; "
                 f"time at 0.05-1.5 m/s: {crawl_t:.0f} s, distance lost to cutoff {np.sum(v_clean[v_fault==0])*0.1:.1f} m, "
                 f"to truncation {np.sum(v_clean - v_fault)*0.1:.1f} m total of {d['s'][-1]:.0f} m")

    # ---- D3: jittered stamps (+-15 ms uniform) and 1.5 % dropped rows (some runs of 2-3); 10 min
    d = base_drive(303, 10 * 60)
    rf = d["rng_fault"]
    n = len(d["t"])
    h = heading_meas(d); sp = speed_meas(d)
    cols, out, nd = assemble(d, heading_mode="heading", heading=h, speed=sp, frame="en")
    write_csv(f"{folder}/d3_jitter_drops_clean.csv", cols, out, nd)
    jit = rf.uniform(-0.015, 0.015, n)
    keep = np.ones(n, bool)
    starts = rf.choice(np.arange(5, n - 5), size=int(0.01 * n), replace=False)
    lens = rf.choice([1, 1, 1, 2, 3], size=len(starts))
    for s0, L in zip(starts, lens):
        keep[s0:s0 + L] = False
    tj = d["t"] + jit
    out2 = {k: v[keep] for k, v in out.items()}
    out2["time"] = tj[keep]
    nd2 = dict(nd); nd2["time"] = 3
    write_csv(f"{folder}/d3_jitter_drops_fault.csv", cols, out2, nd2)
    dtk = np.diff(d["t"][keep])
    notes.append(f"d3: 10 min, heading rad, east/north; fault: stamps +-15 ms uniform jitter, {np.sum(~keep)} of {n} rows dropped "
                 f"({np.sum(~keep)/n*100:.1f} %; longest gap {dtk.max():.1f} s), fixes on dropped rows lost ({np.sum(d['fix'] & ~keep)})")

    # ---- D4: empty/NaN cells and duplicated rows; 9 min
    d = base_drive(404, 9 * 60)
    rf = d["rng_fault"]
    n = len(d["t"])
    h = heading_meas(d); sp = speed_meas(d)
    cols, out, nd = assemble(d, heading_mode="heading", heading=h, speed=sp, frame="en")
    write_csv(f"{folder}/d4_nan_dups_clean.csv", cols, out, nd)
    o = {k: v.astype(object) for k, v in out.items()}
    nan_sp = rf.choice(np.arange(10, n - 10), 15, replace=False)
    nan_h = rf.choice(np.arange(10, n - 10), 15, replace=False)
    for r in nan_sp:
        o["speed"][r] = ""          # empty cell
    for r in nan_h:
        o["heading"][r] = "nan"     # NaN written by pandas/numpy
    dup = np.zeros(n, bool)
    dup[rf.choice(np.arange(10, n - 10), int(0.005 * n), replace=False)] = True
    order = np.concatenate([[i, i] if dup[i] else [i] for i in range(n)])
    with open(f"{folder}/d4_nan_dups_fault.csv", "w") as f:
        f.write(",".join(cols) + "\n")
        for r in order:
            cells = []
            for c in cols:
                x = o[c][r]
                if isinstance(x, str):
                    cells.append(x)
                elif np.isnan(float(x)):
                    cells.append("")
                else:
                    cells.append(f"{float(x):.{nd[c]}f}")
            f.write(",".join(cells) + "\n")
    notes.append(f"d4: 9 min, heading rad, east/north; fault: 15 empty speed cells, 15 'nan' heading cells, "
                 f"{dup.sum()} rows written twice (exact duplicates)")

    # ---- D5: gyro saturating at +-20 deg/s in tight turns + odometer scale drifting 0.985 -> 1.005; 12 min
    d = base_drive(505, 12 * 60, route_kw=dict(tight_frac=0.35, tight_r=(6, 8)))
    t = d["t"]
    rate_true = np.rad2deg(d["w"])
    y_clean = rate_true * 1.003 + 0.05 + d["noise_w"]
    y_fault = np.clip(y_clean, -20.0, 20.0)
    sc_f = 0.985 + 0.02 * t / t[-1]
    v_f = np.where(d["v"] == 0, 0.0, np.maximum(d["v"] * sc_f + d["noise_v"], 0))
    v_c = np.where(d["v"] == 0, 0.0, np.maximum(d["v"] * 0.985 + d["noise_v"], 0))
    # diagnostic variants: each fault alone
    for tag, y, v in (("fault", y_fault, v_f), ("clean", y_clean, v_c),
                      ("satonly", y_fault, v_c), ("driftonly", y_clean, v_f)):
        cols, out, nd = assemble(d, heading_mode="yaw", yaw_deg=y, speed=v, frame="en")
        write_csv(f"{folder}/d5_gyro_sat_odo_drift_{tag}.csv", cols, out, nd)
    sat = np.abs(y_clean) > 20
    lost = np.sum((y_clean - y_fault)[sat]) * 0.1
    notes.append(f"d5: 12 min, yaw_rate_deg (bias 0.05), east/north; fault: gyro clipped at +-20 deg/s "
                 f"({sat.sum()} samples = {sat.sum()*0.1:.0f} s saturated, max true rate {np.abs(rate_true).max():.1f} deg/s, "
                 f"heading lost in total (signed sum) {lost:.0f} deg, abs {np.sum(np.abs(y_clean-y_fault))*0.1:.0f} deg) "
                 f"and odometer scale 0.985->1.005 linear (clean 0.985 constant)")

    # ---- D6: 10-min underground garage (no fixes), then 30 s of bad re-acquisition fixes; 18 min
    g0, g1 = None, None
    # garage: distance window 2600-3100 m driven at 2.5 m/s with a 6 min park inside
    def vdes6(s_):
        return 2.5 if 2600 <= s_ <= 3200 else 12.0
    extra = [dict(s=2900.0, hold=380.0)]
    d = base_drive(606, 18 * 60, vdes_fn=vdes6, extra_stops=extra, stop_every=(500, 1000))
    t = d["t"]
    ing = (d["s"] >= 2600) & (d["s"] <= 3200)
    tin = t[ing]
    t_g0, t_g1 = tin[0], tin[-1]
    fixf = d["fix"] & ~ing
    h = heading_meas(d); sp = speed_meas(d)
    rf = d["rng_fault"]
    ang = rf.uniform(0, 2 * np.pi)
    after = (t > t_g1) & (t < t_g1 + 30)
    mag = np.where(after, 35.0 * np.exp(-(t - t_g1) / 8.0), 0.0)
    ge = d["e"] + d["gps_white_e"] + d["gps_gm_e"] + mag * np.sin(ang)
    gn = d["n"] + d["gps_white_n"] + d["gps_gm_n"] + mag * np.cos(ang)
    gs = np.where(after, np.round(np.maximum(3.0, 10.0 * np.exp(-(t - t_g1) / 10.0)), 1), d["gps_sig"])
    cols, out, nd = assemble(d, heading_mode="heading", heading=h, speed=sp, frame="ll",
                             fix=fixf, gps_e=ge, gps_n=gn, gps_sigma=gs)
    write_csv(f"{folder}/d6_garage_reacq_fault.csv", cols, out, nd)
    cols, out, nd = assemble(d, heading_mode="heading", heading=h, speed=sp, frame="ll")
    write_csv(f"{folder}/d6_garage_reacq_clean.csv", cols, out, nd)
    notes.append(f"d6: 18 min, heading rad, lat/lon; fault: no fixes {t_g0:.0f}-{t_g1:.0f} s ({t_g1-t_g0:.0f} s; garage, "
                 f"{d['s'][ing][-1]-d['s'][ing][0]:.0f} m driven at <=2.5 m/s, parked ~380 s), then 30 s of re-acquisition fixes "
                 f"off by 35*exp(-dt/8) m (35 m at exit, 10 m at +10 s) reporting sigma 10->3 m; clean: fixes throughout, no offset")

    with open(f"{folder}/truth_notes.txt", "w") as f:
        f.write("\n".join(notes) + "\n")
    print("\n".join(notes))


def T_frac(d):
    return d["t"][-1]


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
