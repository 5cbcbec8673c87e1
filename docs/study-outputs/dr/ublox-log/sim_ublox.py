"""Simulate a u-blox ADR (ZED-F9K / NEO-M8L style) drive logged as pyubx2-style CSVs.

numpy only. Writes, into OUTDIR:
  nav_pvt.csv   UBX NAV-PVT at 1 Hz: iTOW, fixType, flags, gnssFixOK, lat, lon (1e-7 deg),
                hAcc (mm), gSpeed (mm/s), headMot (1e-5 deg)
  esf_meas.csv  UBX ESF-MEAS, one row per measurement: sTtag (ms, module clock, wraps 2^32),
                dataType (5 gyro z, 8 rear-left ticks, 9 rear-right ticks), dataField (raw 24-bit
                unsigned as in the message)
  truth.csv     t_gps (s of GPS week), lat, lon, heading_deg (cw from north), speed (m/s), at 50 Hz
  sim_meta.json the faults drawn (seed, gyro bias, clock offset, outages, ...)

usage: python sim_ublox.py OUTDIR [--seed N]
"""
import json
import sys

import numpy as np

A_WGS, F_WGS = 6378137.0, 1 / 298.257223563
E2 = F_WGS * (2 - F_WGS)


def radii(lat_rad):
    s2 = np.sin(lat_rad) ** 2
    rn = A_WGS / np.sqrt(1 - E2 * s2)
    rm = A_WGS * (1 - E2) / (1 - E2 * s2) ** 1.5
    return rm, rn


def build_route(rng):
    """Legs: dict(L, vmax, turn_deg, radius, dwell, tag)."""
    legs = []
    n_legs = 24
    tunnel_leg, garage_leg = 7, 19
    for k in range(n_legs):
        if k == tunnel_leg:
            legs.append(dict(L=900.0, vmax=16.5, turn_deg=20.0, radius=400.0, dwell=0.0, tag="tunnel"))
            continue
        if k == garage_leg:
            # slow ramp spiral down into a garage, a stop, out again
            legs.append(dict(L=60.0, vmax=4.0, turn_deg=180.0, radius=8.0, dwell=0.0, tag="garage"))
            legs.append(dict(L=40.0, vmax=3.0, turn_deg=90.0, radius=6.0, dwell=25.0, tag="garage"))
            legs.append(dict(L=50.0, vmax=4.0, turn_deg=-90.0, radius=6.0, dwell=0.0, tag="garage"))
            legs.append(dict(L=60.0, vmax=4.0, turn_deg=180.0, radius=8.0, dwell=0.0, tag="garage"))
            continue
        L = rng.uniform(150, 650)
        vmax = rng.choice([8.3, 11.1, 13.9, 16.7, 19.4])
        turn = rng.choice([90.0, -90.0, 90.0, -90.0, 45.0, -45.0, 0.0])
        radius = rng.uniform(9, 16) if abs(turn) >= 90 else rng.uniform(20, 60)
        dwell = rng.uniform(10, 60) if rng.random() < 0.4 else 0.0
        legs.append(dict(L=L, vmax=float(vmax), turn_deg=float(turn), radius=float(radius), dwell=float(dwell), tag=""))
    return legs


def route_profile(legs, ds=0.05, a_acc=1.6, a_dec=2.2, a_lat=2.5):
    kap, vlim, tags, stops = [], [], [], []
    for lg in legs:
        n_str = int(lg["L"] / ds)
        kap += [0.0] * n_str
        vlim += [lg["vmax"]] * n_str
        tags += [lg["tag"]] * n_str
        if lg["dwell"] > 0:  # stop at the light at the end of the straight, before the turn
            stops.append((len(kap) - 1, lg["dwell"]))
        if lg["turn_deg"] != 0:
            arc = np.deg2rad(abs(lg["turn_deg"])) * lg["radius"]
            n_arc = max(int(arc / ds), 1)
            k = np.sign(lg["turn_deg"]) / lg["radius"]  # + = clockwise (right turn)
            kap += [k] * n_arc
            vlim += [min(lg["vmax"], np.sqrt(a_lat * lg["radius"]))] * n_arc
            tags += [lg["tag"]] * n_arc
    kap = np.array(kap)
    vlim = np.array(vlim)
    n = len(kap)
    vlim[0] = 0.0
    vlim[-1] = 0.0
    for i, _ in stops:
        vlim[i] = 0.0
    v = vlim.copy()
    for i in range(1, n):
        v[i] = min(v[i], np.sqrt(v[i - 1] ** 2 + 2 * a_acc * ds))
    for i in range(n - 2, -1, -1):
        v[i] = min(v[i], np.sqrt(v[i + 1] ** 2 + 2 * a_dec * ds))
    s = np.arange(n) * ds
    dt = 2 * ds / np.maximum(v[:-1] + v[1:], 1e-9)
    t = np.concatenate([[0.0], np.cumsum(dt)])
    # dwell at stops (and at start / end): insert a duplicate s point later in time
    dwell_at = {0: 8.0, n - 1: 10.0}
    for i, d in stops:
        dwell_at[i] = d
    ts, ss, idx = [], [], []
    shift = 0.0
    for i in range(n):
        ts.append(t[i] + shift)
        ss.append(s[i])
        idx.append(i)
        if i in dwell_at:
            shift += dwell_at[i]
            ts.append(t[i] + shift)
            ss.append(s[i])
            idx.append(i)
    return np.array(ts), np.array(ss), kap, np.array(tags, dtype=object), ds


def simulate(outdir, seed=7):
    rng = np.random.default_rng(seed)
    legs = build_route(rng)
    ts, ss, kap, tags, ds = route_profile(legs)
    # path geometry on the s grid
    n = len(kap)
    psi = np.concatenate([[0.0], np.cumsum(kap[:-1] * ds)]) + np.deg2rad(rng.uniform(0, 360))
    east = np.concatenate([[0.0], np.cumsum(np.sin(psi[:-1]) * ds)])
    north = np.concatenate([[0.0], np.cumsum(np.cos(psi[:-1]) * ds)])

    # truth at 50 Hz
    dt = 0.02
    T = ts[-1]
    t = np.arange(0.0, T, dt)
    s_t = np.interp(t, ts, ss)
    i_s = np.clip((s_t / ds).astype(int), 0, n - 1)
    frac = s_t / ds - i_s
    e_t = np.interp(s_t, np.arange(n) * ds, east)
    n_t = np.interp(s_t, np.arange(n) * ds, north)
    psi_t = np.interp(s_t, np.arange(n) * ds, psi)
    v_t = np.gradient(s_t, dt)
    v_t[v_t < 1e-6] = 0.0
    r_t = kap[i_s] * v_t  # yaw rate, rad/s, clockwise positive
    tag_t = tags[i_s]

    lat0, lon0 = np.deg2rad(48.1372), np.deg2rad(11.5755)
    rm, rn = radii(lat0)
    lat_t = np.rad2deg(lat0 + n_t / rm)
    lon_t = np.rad2deg(lon0 + e_t / (rn * np.cos(lat0)))

    itow0_s = 388_800.0 + 3 * 3600 + 17 * 60 + 12.0  # Thursday 03:17:12 GPS time
    tg = itow0_s + t  # GPS time of week, s

    # outages: GNSS lost on the tunnel leg and the garage legs (plus a few metres either side)
    outages = []
    for tag in ("tunnel", "garage"):
        m = tag_t == tag
        if tag == "tunnel":
            # inside only the middle of the tunnel leg: ~45 s
            tt = t[m]
            a, b = tt[0] + 8.0, tt[-1] - 6.0
        else:
            tt = t[m]
            a, b = tt[0] + 3.0, min(tt[-1] - 3.0, tt[0] + 58.0)
        outages.append((float(a), float(b)))

    # ---- NAV-PVT at 1 Hz
    tp = np.arange(np.ceil(t[0]), np.floor(t[-1]) + 1e-9, 1.0)
    k = np.round(tp / dt).astype(int)
    npv = len(tp)
    # Gauss-Markov errors per axis, tau 15 s, sigma 1.8 m
    tau, sig = 15.0, 1.8
    phi = np.exp(-1.0 / tau)
    gm = np.zeros((npv, 2))
    gm[0] = rng.normal(0, sig, 2)
    for i in range(1, npv):
        gm[i] = phi * gm[i - 1] + rng.normal(0, sig * np.sqrt(1 - phi ** 2), 2)
    # multipath excursions: 6 events of 10-30 m for 5-20 s, ramping up and down
    mp = np.zeros((npv, 2))
    mp_events = []
    for _ in range(6):
        c = rng.integers(60, npv - 60)
        d = rng.integers(5, 21)
        amp = rng.uniform(10, 30)
        ang = rng.uniform(0, 2 * np.pi)
        w = np.sin(np.linspace(0, np.pi, d)) ** 0.5
        mp[c:c + d] += amp * w[:, None] * np.array([np.sin(ang), np.cos(ang)])
        mp_events.append(dict(t_start=float(tp[c]), dur=int(d), amp_m=float(amp)))
    err = gm + mp
    true_sig_axis = np.sqrt(sig ** 2 + 0.0)
    hacc_m = np.sqrt(2) * (true_sig_axis * rng.uniform(0.8, 1.2, npv))  # DRMS-ish
    mp_mag = np.hypot(mp[:, 0], mp[:, 1])
    hacc_m = hacc_m + 0.3 * mp_mag  # receiver sees only part of the multipath

    fixtype = np.full(npv, 4)
    fixtype[tp < 60.0] = 3  # sensor fusion not yet calibrated: GNSS only
    fixtype[tp < 3.0] = 0
    gfix = (fixtype > 0).astype(int)
    e_fix = e_t[k] + err[:, 0]
    n_fix = n_t[k] + err[:, 1]
    in_out = np.zeros(npv, bool)
    # module's own dead reckoning in the outages: from its last fused fix, heading error growing
    dr_params = []
    for a, b in outages:
        m = (tp >= a) & (tp <= b)
        in_out |= m
        ii = np.nonzero(m)[0]
        i0 = ii[0] - 1
        dpsi0 = np.deg2rad(rng.normal(0, 0.6))
        drift = np.deg2rad(rng.choice([-1, 1]) * rng.uniform(0.015, 0.04))  # rad/s
        scale = 1 + rng.normal(0, 0.006)
        pe, pn = e_fix[i0], n_fix[i0]
        jj = np.arange(k[i0], k[ii[-1]] + 1)
        dpsi = dpsi0 + drift * (t[jj] - t[jj[0]])
        ve = v_t[jj] * np.sin(psi_t[jj] + dpsi) * scale
        vn = v_t[jj] * np.cos(psi_t[jj] + dpsi) * scale
        pe_t = pe + np.concatenate([[0], np.cumsum(ve[:-1] * dt)])
        pn_t = pn + np.concatenate([[0], np.cumsum(vn[:-1] * dt)])
        for i in ii:
            j = k[i] - jj[0]
            e_fix[i], n_fix[i] = pe_t[j], pn_t[j]
            hacc_m[i] = hacc_m[i0] + 0.05 * (tp[i] - tp[i0]) ** 1.3
        dr_params.append(dict(start=a, end=b, heading_err0_deg=float(np.rad2deg(dpsi0)),
                              drift_deg_s=float(np.rad2deg(drift)), scale=float(scale)))
    fixtype[in_out] = 1
    gfix[in_out] = 0
    lat_f = np.rad2deg(lat0 + n_fix / rm)
    lon_f = np.rad2deg(lon0 + e_fix / (rn * np.cos(lat0)))
    lat_i = np.round(lat_f * 1e7).astype(np.int64)
    lon_i = np.round(lon_f * 1e7).astype(np.int64)
    hacc = np.round(hacc_m * 1000).astype(np.int64)
    nofix = fixtype == 0
    lat_i[nofix] = 0
    lon_i[nofix] = 0
    hacc[nofix] = 4294967295
    gspeed = np.round(np.maximum(v_t[k] + rng.normal(0, 0.05, npv), 0) * 1000).astype(np.int64)
    gspeed[nofix] = 0
    head = np.rad2deg(psi_t[k] + rng.normal(0, np.deg2rad(0.5), npv)) % 360
    # headMot frozen while stopped
    for i in range(1, npv):
        if v_t[k[i]] < 0.5:
            head[i] = head[i - 1]
    headmot = np.round(head * 1e5).astype(np.int64)
    headmot[nofix] = 0
    itow = np.round((itow0_s + tp) * 1000).astype(np.int64)
    flags = gfix.copy()  # bit0 gnssFixOK (other bits 0)
    with open(f"{outdir}/nav_pvt.csv", "w") as f:
        f.write("iTOW,fixType,flags,gnssFixOK,lat,lon,hAcc,gSpeed,headMot\n")
        for row in zip(itow, fixtype, flags, gfix, lat_i, lon_i, hacc, gspeed, headmot):
            f.write(",".join(str(int(x)) for x in row) + "\n")

    # ---- ESF-MEAS
    # module clock: sTtag_ms = (tg - clk_off) * 1000 * (1 + drift), mod 2^32
    clk_off = float(itow0_s - rng.uniform(4.2e6, 4.29e6))  # tg - sensor_time, s
    # make the counter wrap ~5 minutes into the drive
    sens0 = 2 ** 32 / 1000.0 - 300.0  # sensor seconds at t=0
    clk_off = itow0_s - sens0
    ppm = 15e-6
    gyro_bias = 0.18  # deg/s
    gyro_scale = 1.004
    # gyro at 50 Hz (the truth grid), phase 7 ms later
    r_deg = np.rad2deg(r_t)
    gz = gyro_bias + gyro_scale * r_deg + rng.normal(0, 0.07, len(t))
    gz_q = np.round(gz * 4096).astype(np.int64)
    gz_raw = gz_q & 0xFFFFFF  # 24-bit two's complement as in the message
    st_g = np.floor(((t + 0.007) + sens0) * (1 + ppm) * 1000).astype(np.int64) % 2 ** 32
    # wheel ticks at 10 Hz
    tw = np.arange(0.0, T, 0.1)
    track = 1.55
    circ_l, circ_r, tpr = 1.932, 1.927, 96
    vw = np.interp(tw, t, v_t)
    kw = np.interp(tw, t, kap[i_s])
    dl = np.concatenate([[0], np.cumsum((vw * (1 + kw * track / 2))[:-1] * 0.1)])
    dr_ = np.concatenate([[0], np.cumsum((vw * (1 - kw * track / 2))[:-1] * 0.1)])
    # integrate more finely for accuracy
    d_true = np.concatenate([[0], np.cumsum(v_t[:-1] * dt)])
    kk = kap[i_s]
    dL = np.concatenate([[0], np.cumsum((v_t * (1 + kk * track / 2))[:-1] * dt)])
    dR = np.concatenate([[0], np.cumsum((v_t * (1 - kk * track / 2))[:-1] * dt)])
    dl = np.interp(tw, t, dL)
    dr_ = np.interp(tw, t, dR)
    c0l, c0r = 2 ** 23 - 21000, 2 ** 23 - 35000
    tick_l = (c0l + np.floor(dl / (circ_l / tpr)).astype(np.int64)) % 2 ** 23
    tick_r = (c0r + np.floor(dr_ / (circ_r / tpr)).astype(np.int64)) % 2 ** 23
    st_w = np.floor((tw + sens0) * (1 + ppm) * 1000).astype(np.int64) % 2 ** 32
    rows = [(st_g[i], 5, int(gz_raw[i])) for i in range(len(t))]
    rows += [(st_w[i], 8, int(tick_l[i])) for i in range(len(tw))]
    rows += [(st_w[i], 9, int(tick_r[i])) for i in range(len(tw))]
    # log order: by true time (sTtag wraps, so sort by the unwrapped time)
    order_key = np.concatenate([t + 0.007, tw, tw])
    order = np.argsort(order_key, kind="stable")
    with open(f"{outdir}/esf_meas.csv", "w") as f:
        f.write("sTtag,dataType,dataField\n")
        for o in order:
            a, b, c = rows[o]
            f.write(f"{int(a)},{b},{c}\n")

    # ---- truth
    with open(f"{outdir}/truth.csv", "w") as f:
        f.write("t_gps,lat,lon,heading_deg,speed\n")
        for i in range(len(t)):
            f.write(f"{tg[i]:.3f},{lat_t[i]:.9f},{lon_t[i]:.9f},{np.rad2deg(psi_t[i]) % 360:.4f},{v_t[i]:.4f}\n")

    meta = dict(seed=seed, duration_s=float(T), distance_m=float(d_true[-1]),
                n_stops=int(sum(1 for lg in legs if lg["dwell"] > 0)),
                stop_dwells_s=[round(lg["dwell"], 1) for lg in legs if lg["dwell"] > 0],
                gnss_error=dict(gauss_markov_tau_s=tau, sigma_axis_m=sig, multipath=mp_events,
                                hAcc="sqrt(2)*1.8 m*U(0.8,1.2) + 0.3*|multipath| (mm)"),
                outages_receiver_dr=dr_params,
                gyro=dict(bias_deg_s=gyro_bias, scale=gyro_scale, noise_deg_s_50hz=0.07,
                          sign="z down: clockwise (right turn) positive"),
                wheels=dict(ticks_per_rev=tpr, circ_left_m=circ_l, circ_right_m=circ_r, track_m=track,
                            counter_start_left=c0l, counter_start_right=c0r, rate_hz=10),
                clock=dict(sensor_s_at_t0=sens0, gps_tow_at_t0=itow0_s, drift_ppm=ppm * 1e6,
                           sTtag_wraps_at_drive_s=float((2 ** 32 / 1000.0 / (1 + ppm)) - sens0)),
                itow0_s=itow0_s)
    with open(f"{outdir}/sim_meta.json", "w") as f:
        json.dump(meta, f, indent=1)
    return meta


if __name__ == "__main__":
    out = sys.argv[1]
    seed = int(sys.argv[sys.argv.index("--seed") + 1]) if "--seed" in sys.argv else 7
    print(json.dumps(simulate(out, seed), indent=1))
