"""Five simulated car drives (town / suburban), each with one realistic logger or sensor
fault, and a _clean twin (same truth, same noise draws, no fault).

    python gen_drives_7.py FOLDER

writes FOLDER/<name>.csv, FOLDER/<name>_clean.csv and FOLDER/truth_notes.txt.
Plain numpy, seeded (root seed 7).

Drives (10 Hz DR rows, 1 Hz GPS fixes on the rows of whole seconds, lat/lon WGS84):
  d1_dst_jump       heading_deg + CAN speed; the time column is local time and jumps +3600 s
                    mid-drive (a logger whose clock switches to summer time while it writes).
  d2_latlon_4dp     yaw_rate_deg + CAN speed; the export wrote gps_lat/gps_lon with '%.4f'
                    (0.0001 deg = 11.1 m north, 7.4 m east at 48 deg N).
  d3_fix_latency    heading_deg + CAN speed; each fix written on the row at which the logger
                    received it: latency varying 0.2-1.5 s (slowly, plus jitter).
  d4_idle_vibration yaw_rate_deg + CAN speed; a 4-minute wait at a level crossing; while the car
                    stands with the engine idling, the phone's MEMS gyro shakes in its holder:
                    white noise 0.8 deg/s and a vibration-rectified offset of +0.15 deg/s.
  d5_rtk_float      yaw_rate_deg + CAN speed; an RTK receiver (2 cm fixed) drops to a float
                    solution (0.5-1.0 m errors, sigma reported honestly) for 4 stretches and back.
"""
import os
import sys

import numpy as np

A_WGS = 6378137.0
F_WGS = 1 / 298.257223563
E2 = F_WGS * (2 - F_WGS)

DT = 0.1          # DR row interval (s)
SUB = 5           # simulation sub-steps per row
FIX_EVERY = 10    # rows between fixes (1 Hz)


def radii(lat_rad):
    s2 = np.sin(lat_rad) ** 2
    rn = A_WGS / np.sqrt(1 - E2 * s2)            # prime vertical
    rm = A_WGS * (1 - E2) / (1 - E2 * s2) ** 1.5  # meridian
    return rm, rn


# --------------------------------------------------------------------------- the route plan
def plan_route(rng, minutes, level_crossing_at=None):
    """A list of actions: ('cruise', length_m, v_cruise), ('stop', wait_s),
    ('turn', angle_deg (+ right, clockwise), radius_m, v_turn)."""
    acts = []
    t_est = 0.0
    target = minutes * 60.0
    lc_done = level_crossing_at is None
    vc = 11.1
    while t_est < target - 40:
        r = rng.random()
        if r < 0.15:
            vc = 8.3
        elif r < 0.55:
            vc = 13.9
        elif r < 0.8:
            vc = 11.1
        elif r < 0.93:
            vc = 16.7
        else:
            vc = 19.4
        vc *= rng.uniform(0.92, 1.05)
        L = rng.uniform(90, 450)
        acts.append(("cruise", L, vc))
        t_est += L / vc + 6
        if not lc_done and t_est > level_crossing_at:
            acts.append(("stop", 240.0))
            t_est += 250
            lc_done = True
            continue
        e = rng.random()
        if e < 0.33:  # junction turn, maybe after a stop
            if rng.random() < 0.4:
                w = rng.uniform(3, 40)
                acts.append(("stop", w))
                t_est += w + 8
            ang = rng.choice([-90.0, 90.0]) + rng.normal(0, 8)
            R = rng.uniform(9, 16) if ang > 0 else rng.uniform(14, 24)
            acts.append(("turn", ang, R, rng.uniform(4.2, 6.0)))
            t_est += 10
        elif e < 0.53:  # traffic light
            w = rng.uniform(5, 45)
            acts.append(("stop", w))
            t_est += w + 10
        elif e < 0.78:  # a bend in the road at speed
            ang = rng.choice([-1, 1]) * rng.uniform(15, 45)
            acts.append(("turn", ang, rng.uniform(70, 200), min(vc, rng.uniform(9, 13))))
            t_est += 8
        elif e < 0.9:  # roundabout (right-hand traffic: in right, round left, out right)
            exit_ang = rng.choice([90.0, 180.0, 270.0])
            acts.append(("turn", 35.0, 12.0, 5.5))
            acts.append(("turn", -(exit_ang + 70.0), 14.0, 5.5))
            acts.append(("turn", 35.0, 12.0, 5.5))
            t_est += 25
        else:  # a stop sign and a turn
            acts.append(("stop", rng.uniform(1, 4)))
            ang = rng.choice([-90.0, 90.0]) + rng.normal(0, 10)
            acts.append(("turn", ang, rng.uniform(10, 20), rng.uniform(4, 5.5)))
            t_est += 15
    acts.append(("cruise", rng.uniform(80, 200), 11.1))
    acts.append(("stop", 20.0))  # parks at the end
    return acts


def entry_speed(act):
    if act is None:
        return 0.0
    if act[0] == "stop":
        return 0.0
    if act[0] == "turn":
        return act[3]
    return act[2]


def simulate_truth(rng, acts, lat0, lon0, psi0):
    """Integrate speed and curvature through the actions at DT/SUB; return the rows."""
    h = DT / SUB
    v, a, kap, psi = 0.0, 0.0, 0.0, psi0
    lat, lon = np.radians(lat0), np.radians(lon0)
    e = n = 0.0
    out_t, out_v, out_psi, out_r, out_lat, out_lon, out_e, out_n = ([] for _ in range(8))
    t = 0.0
    step = 0
    # start: 15 s parked
    queue = [("stop", 15.0)] + list(acts)
    i = 0
    st = {}
    while i < len(queue):
        act = queue[i]
        nxt = queue[i + 1] if i + 1 < len(queue) else None
        kind = act[0]
        if not st:
            st = {"s0": 0.0, "t0": t, "turned": 0.0, "phase": 0}
        done = False
        # targets
        kap_target = 0.0
        if kind == "stop":
            v_target = 0.0
            if v <= 1e-3:
                v = 0.0
                a = 0.0
                if t - st["t0"] >= act[1]:
                    done = True
            else:
                st["t0"] = t
        elif kind == "cruise":
            rem = act[1] - st["s0"]
            v_next = entry_speed(nxt)
            v_target = min(act[2], np.sqrt(max(v_next ** 2 + 2 * 1.3 * max(rem - 2.0, 0.0), 0.0)))
            if rem <= 0 or (v_next == 0.0 and v < 0.25 and rem < 6.0):
                done = True
                if v_next == 0.0:
                    v_target = 0.0
        else:  # turn
            ang = np.radians(act[1])
            v_target = act[3]
            sgn = np.sign(ang)
            if st["phase"] == 0:
                kap_target = sgn / act[2]
                if abs(st["turned"]) + abs(kap) * v * 0.8 >= abs(ang):
                    st["phase"] = 1
            if st["phase"] == 1:
                kap_target = 0.0
                if abs(kap) < 2e-4:
                    done = True
        # speed dynamics: commanded accel, low-passed (jerk limit)
        a_cmd = np.clip(1.2 * (v_target - v), -2.6, 1.6)
        if kind == "stop" and v > 0:
            a_cmd = min(a_cmd, -0.6 if v > 0.6 else -max(v, 0.15))
        a += (a_cmd - a) * h / 0.45
        kap += (kap_target - kap) * h / 0.8
        v_new = max(v + a * h, 0.0)
        if v_new == 0.0:
            a = max(a, 0.0)
        vm = 0.5 * (v + v_new)
        r = vm * kap
        psi_mid = psi + 0.5 * r * h
        de, dn = vm * np.sin(psi_mid) * h, vm * np.cos(psi_mid) * h
        rm, rn = radii(lat)
        lat += dn / rm
        lon += de / (rn * np.cos(lat))
        e += de
        n += dn
        psi += r * h
        st["turned"] += r * h
        st["s0"] += vm * h
        v = v_new
        t += h
        step += 1
        if step % SUB == 0:
            out_t.append(round(t, 6))
            out_v.append(v)
            out_psi.append(psi)
            out_r.append(v * kap)
            out_lat.append(np.degrees(lat))
            out_lon.append(np.degrees(lon))
            out_e.append(e)
            out_n.append(n)
        if done:
            i += 1
            st = {}
    T = np.array(out_t)
    T = T - T[0]
    return dict(t=T, v=np.array(out_v), psi=np.array(out_psi), r=np.array(out_r),
                lat=np.array(out_lat), lon=np.array(out_lon), e=np.array(out_e), n=np.array(out_n))


# --------------------------------------------------------------------------- sensors
def gauss_markov(rng, n, sigma, tau, dt):
    phi = np.exp(-dt / tau)
    x = np.empty(n)
    x[0] = rng.normal(0, sigma)
    w = rng.normal(0, sigma * np.sqrt(1 - phi ** 2), n)
    for k in range(1, n):
        x[k] = phi * x[k - 1] + w[k]
    return x


def phone_fixes(rng, n_fix, env_sigma=(2.2, 1.0)):
    """Per-axis errors (m) and the reported sigma for a phone-grade 1 Hz receiver."""
    env = 1.0 + 0.6 * (0.5 + 0.5 * np.tanh(gauss_markov(rng, n_fix, 1.0, 90.0, 1.0)))
    ee = env * (gauss_markov(rng, n_fix, env_sigma[0], 25.0, 1.0) + rng.normal(0, env_sigma[1], n_fix))
    en = env * (gauss_markov(rng, n_fix, env_sigma[0], 25.0, 1.0) + rng.normal(0, env_sigma[1], n_fix))
    sig = env * np.hypot(*env_sigma) * rng.uniform(0.9, 1.15, n_fix)
    return ee, en, sig


def offset_latlon(lat, lon, de, dn):
    rm, rn = radii(np.radians(lat))
    return lat + np.degrees(dn / rm), lon + np.degrees(de / (rn * np.cos(np.radians(lat))))


def can_speed(rng, v):
    scale = 1.0 + rng.normal(0, 0.008)
    s = v * scale + rng.normal(0, 0.03, v.size)
    s = np.round(np.maximum(s, 0.0), 3)
    s[v < 0.01] = 0.0
    return s, scale


def fused_heading(rng, psi):
    n = psi.size
    err = np.radians(0.7) + np.radians(gauss_markov(rng, n, 0.4, 150.0, DT)) + np.radians(rng.normal(0, 0.3, n))
    return np.degrees(np.mod(psi + err, 2 * np.pi)), err


def gyro_rate(rng, r):
    n = r.size
    bias = 0.03 + np.cumsum(rng.normal(0, 0.0004, n))  # deg/s, slow random walk
    meas = np.degrees(r) + bias + rng.normal(0, 0.12, n)
    return meas, bias


# --------------------------------------------------------------------------- writing
def fmt(x, spec):
    return "" if x is None or (isinstance(x, float) and np.isnan(x)) else format(x, spec)


def write_csv(path, cols, specs):
    names = list(cols)
    n = len(cols[names[0]])
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for k in range(n):
            f.write(",".join(fmt(cols[c][k], specs[c]) for c in names) + "\n")


SPECS = dict(time=".2f", heading_deg=".3f", yaw_rate_deg=".4f", speed=".3f", gps_lat=".8f",
             gps_lon=".8f", gps_sigma=".2f", true_lat=".8f", true_lon=".8f")


def base_columns(tr, heading_kind, rng):
    n = tr["t"].size
    cols = {"time": tr["t"].copy()}
    notes = {}
    if heading_kind == "heading":
        hd, err = fused_heading(rng, tr["psi"])
        cols["heading_deg"] = hd
        notes["heading"] = "phone fused heading: +0.7 deg offset, GM drift 0.4 deg (150 s), white 0.3 deg"
    else:
        yr, bias = gyro_rate(rng, tr["r"])
        cols["yaw_rate_deg"] = yr
        notes["heading"] = (f"MEMS gyro yaw rate: bias 0.03 deg/s + random walk (ends {bias[-1]:+.3f}), "
                            "white 0.12 deg/s")
    sp, scale = can_speed(rng, tr["v"])
    cols["speed"] = sp
    notes["speed"] = f"CAN speed: scale {scale:.4f}, white 0.03 m/s, 0 at standstill"
    return cols, notes


def fix_rows(n):
    return np.arange(0, n, FIX_EVERY)


def put_fixes(n, rows, lat, lon, sig):
    glat = np.full(n, np.nan)
    glon = np.full(n, np.nan)
    gs = np.full(n, np.nan)
    glat[rows], glon[rows], gs[rows] = lat, lon, sig
    return glat, glon, gs


def drive_summary(tr):
    moving = tr["v"] > 0.1
    starts = np.sum(np.diff(moving.astype(int)) == 1)
    dist = np.sum(tr["v"]) * DT
    turned = np.sum(np.abs(tr["r"])) * DT
    return (f"{tr['t'][-1] / 60:.1f} min, {dist / 1000:.2f} km, max speed {tr['v'].max() * 3.6:.0f} km/h, "
            f"{starts} starts from standstill, standing {np.mean(~moving) * 100:.0f} % of the time, "
            f"total heading change {np.degrees(turned):.0f} deg")


def main(folder):
    os.makedirs(folder, exist_ok=True)
    root = np.random.SeedSequence(7)
    seeds = root.spawn(5)
    notes = []

    # ---------------- d1: DST jump
    rng = np.random.default_rng(seeds[0])
    tr = simulate_truth(rng, plan_route(rng, 11), 48.1372, 11.5756, np.radians(rng.uniform(0, 360)))
    n = tr["t"].size
    cols, nt = base_columns(tr, "heading", rng)
    rows = fix_rows(n)
    ee, en, sig = phone_fixes(rng, rows.size)
    flat, flon = offset_latlon(tr["lat"][rows], tr["lon"][rows], ee, en)
    cols["gps_lat"], cols["gps_lon"], cols["gps_sigma"] = put_fixes(n, rows, flat, flon, sig)
    cols["true_lat"], cols["true_lon"] = tr["lat"], tr["lon"]
    write_csv(f"{folder}/d1_dst_jump_clean.csv", cols, SPECS)
    k_jump = int(np.searchsorted(tr["t"], 0.45 * tr["t"][-1]))
    cols["time"] = tr["t"] + 3600.0 * (np.arange(n) >= k_jump)
    write_csv(f"{folder}/d1_dst_jump.csv", cols, SPECS)
    notes.append(("d1_dst_jump", drive_summary(tr), nt,
                  f"FAULT: time column jumps +3600 s at row {k_jump + 2} of the file (t = {tr['t'][k_jump]:.1f} s "
                  f"-> {tr['t'][k_jump] + 3600:.1f}): a clock switching to summer time mid-log; all sensors on "
                  "the same clock, no data lost"))

    # ---------------- d2: lat/lon to 4 decimals
    rng = np.random.default_rng(seeds[1])
    tr = simulate_truth(rng, plan_route(rng, 13), 48.1510, 11.5420, np.radians(rng.uniform(0, 360)))
    n = tr["t"].size
    cols, nt = base_columns(tr, "yaw", rng)
    rows = fix_rows(n)
    ee, en, sig = phone_fixes(rng, rows.size)
    flat, flon = offset_latlon(tr["lat"][rows], tr["lon"][rows], ee, en)
    cols["gps_lat"], cols["gps_lon"], cols["gps_sigma"] = put_fixes(n, rows, flat, flon, sig)
    cols["true_lat"], cols["true_lon"] = tr["lat"], tr["lon"]
    write_csv(f"{folder}/d2_latlon_4dp_clean.csv", cols, SPECS)
    s4 = dict(SPECS, gps_lat=".4f", gps_lon=".4f")
    write_csv(f"{folder}/d2_latlon_4dp.csv", cols, s4)
    rm, rn = radii(np.radians(48.151))
    notes.append(("d2_latlon_4dp", drive_summary(tr), nt,
                  f"FAULT: gps_lat/gps_lon exported with '%.4f': steps of {np.radians(1e-4) * rm:.1f} m north, "
                  f"{np.radians(1e-4) * rn * np.cos(np.radians(48.151)):.1f} m east (rounding error sd "
                  f"{np.radians(1e-4) * rm / np.sqrt(12):.1f} / {np.radians(1e-4) * rn * np.cos(np.radians(48.151)) / np.sqrt(12):.1f} m); "
                  "gps_sigma still the receiver's (~2.4-3.9 m); truth at full precision"))

    # ---------------- d3: variable fix latency
    rng = np.random.default_rng(seeds[2])
    tr = simulate_truth(rng, plan_route(rng, 12), 48.1290, 11.6010, np.radians(rng.uniform(0, 360)))
    n = tr["t"].size
    cols, nt = base_columns(tr, "heading", rng)
    rows = fix_rows(n)
    ee, en, sig = phone_fixes(rng, rows.size)
    flat, flon = offset_latlon(tr["lat"][rows], tr["lon"][rows], ee, en)
    cols["true_lat"], cols["true_lon"] = tr["lat"], tr["lon"]
    cols["gps_lat"], cols["gps_lon"], cols["gps_sigma"] = put_fixes(n, rows, flat, flon, sig)
    write_csv(f"{folder}/d3_fix_latency_clean.csv", cols, SPECS)
    slow = 0.5 + 0.5 * np.tanh(1.3 * gauss_markov(rng, rows.size, 1.0, 60.0, 1.0))
    lat_s = np.clip(0.2 + 1.3 * slow + rng.normal(0, 0.08, rows.size), 0.2, 1.5)
    new_rows = rows + np.ceil(lat_s / DT - 1e-9).astype(int)
    keep = new_rows < n
    keep &= np.r_[True, np.diff(new_rows) > 0]
    glat, glon, gs = put_fixes(n, new_rows[keep], flat[keep], flon[keep], sig[keep])
    cols["gps_lat"], cols["gps_lon"], cols["gps_sigma"] = glat, glon, gs
    write_csv(f"{folder}/d3_fix_latency.csv", cols, SPECS)
    eff = (new_rows - rows)[keep] * DT
    notes.append(("d3_fix_latency", drive_summary(tr), nt,
                  f"FAULT: each fix written on the row the logger received it: latency (to the next 0.1 s row) "
                  f"{eff.min():.1f}-{eff.max():.1f} s, mean {eff.mean():.2f} s, median {np.median(eff):.2f} s, "
                  f"sd {eff.std():.2f} s, varying slowly (GM tau 60 s) plus 0.08 s jitter; {np.sum(~keep)} fixes lost "
                  "to collisions/end"))

    # ---------------- d4: idle vibration at a level crossing
    rng = np.random.default_rng(seeds[3])
    tr = simulate_truth(rng, plan_route(rng, 11, level_crossing_at=300.0), 48.1650, 11.5900,
                        np.radians(rng.uniform(0, 360)))
    n = tr["t"].size
    cols, nt = base_columns(tr, "yaw", rng)
    rows = fix_rows(n)
    ee, en, sig = phone_fixes(rng, rows.size)
    flat, flon = offset_latlon(tr["lat"][rows], tr["lon"][rows], ee, en)
    cols["gps_lat"], cols["gps_lon"], cols["gps_sigma"] = put_fixes(n, rows, flat, flon, sig)
    cols["true_lat"], cols["true_lon"] = tr["lat"], tr["lon"]
    write_csv(f"{folder}/d4_idle_vibration_clean.csv", cols, SPECS)
    stand = tr["v"] < 1e-3
    stand[: int(15 / DT)] = False   # engine started only at the end of the initial parking
    stand[-int(20 / DT):] = False   # engine off at the end
    vib = rng.normal(0, 0.8, n) + 0.15
    yr = cols["yaw_rate_deg"].copy()
    yr[stand] += vib[stand]
    cols["yaw_rate_deg"] = yr
    write_csv(f"{folder}/d4_idle_vibration.csv", cols, SPECS)
    # find the long stop
    d = np.diff(np.r_[0, stand.astype(int), 0])
    st_, en_ = np.where(d == 1)[0], np.where(d == -1)[0]
    longest = np.argmax(en_ - st_)
    notes.append(("d4_idle_vibration", drive_summary(tr), nt,
                  f"FAULT: while standing with the engine idling ({stand.sum() * DT:.0f} s in {st_.size} stops; the "
                  f"longest a level crossing {tr['t'][st_[longest]]:.0f}-{tr['t'][en_[longest] - 1]:.0f} s), "
                  "the gyro reads +0.15 deg/s vibration-rectified offset and 0.8 deg/s white noise on top of its "
                  f"own; integrated over the stops that is {0.15 * stand.sum() * DT:.0f} deg of false turn; "
                  "while moving the gyro is as in the clean twin"))

    # ---------------- d5: RTK fixed / float
    rng = np.random.default_rng(seeds[4])
    tr = simulate_truth(rng, plan_route(rng, 10), 48.1200, 11.5500, np.radians(rng.uniform(0, 360)))
    n = tr["t"].size
    cols, nt = base_columns(tr, "yaw", rng)
    rows = fix_rows(n)
    nf = rows.size
    ee = gauss_markov(rng, nf, 0.01, 30.0, 1.0) + rng.normal(0, 0.008, nf)
    en = gauss_markov(rng, nf, 0.01, 30.0, 1.0) + rng.normal(0, 0.008, nf)
    sig = np.full(nf, 0.02)
    cols["true_lat"], cols["true_lon"] = tr["lat"], tr["lon"]
    flat, flon = offset_latlon(tr["lat"][rows], tr["lon"][rows], ee, en)
    cols["gps_lat"], cols["gps_lon"], cols["gps_sigma"] = put_fixes(n, rows, flat, flon, sig)
    write_csv(f"{folder}/d5_rtk_float_clean.csv", cols, SPECS)
    fe = gauss_markov(rng, nf, 0.55, 40.0, 1.0)
    fn = gauss_markov(rng, nf, 0.55, 40.0, 1.0)
    mag = rng.uniform(0.5, 1.0)
    flt = np.zeros(nf, bool)
    spans = []
    for frac in (0.15, 0.38, 0.6, 0.8):
        s0 = int(frac * nf + rng.integers(-15, 15))
        L = int(rng.uniform(40, 120))
        flt[s0:s0 + L] = True
        spans.append((s0, min(s0 + L, nf)))
    ee2, en2, sig2 = ee.copy(), en.copy(), sig.copy()
    scale = mag / 0.55
    ee2[flt] = scale * fe[flt] * 0.8 + rng.normal(0, 0.1, flt.sum())
    en2[flt] = scale * fn[flt] * 0.8 + rng.normal(0, 0.1, flt.sum())
    sig2[flt] = np.clip(np.hypot(ee2[flt], en2[flt]) / 1.2 + rng.uniform(0.3, 0.5, flt.sum()), 0.5, 1.0)
    flat, flon = offset_latlon(tr["lat"][rows], tr["lon"][rows], ee2, en2)
    cols["gps_lat"], cols["gps_lon"], cols["gps_sigma"] = put_fixes(n, rows, flat, flon, sig2)
    write_csv(f"{folder}/d5_rtk_float.csv", cols, SPECS)
    err_f = np.hypot(ee2[flt], en2[flt])
    notes.append(("d5_rtk_float", drive_summary(tr), nt,
                  "FAULT (receiver behaviour): RTK fixed solution (2 cm, reported gps_sigma 0.02) drops to a "
                  f"float solution for {len(spans)} stretches (s): {spans}; float errors (2-D) median "
                  f"{np.median(err_f):.2f} m, max {err_f.max():.2f} m, reported sigma 0.5-1.0 m (honest); the "
                  "clean twin stays RTK fixed throughout"))

    with open(f"{folder}/truth_notes.txt", "w") as f:
        f.write("gen_drives_7.py, root seed 7. 10 Hz DR rows, 1 Hz fixes (lat/lon WGS84, gps_sigma per-axis "
                "sd in m), truth true_lat/true_lon on every row. Fix errors (phone drives): env factor 1.0-1.6 x "
                "(GM 2.2 m tau 25 s + white 1.0 m) per axis. Truth integrated on the ellipsoid from speed and "
                "curvature (jerk-limited accel, curvature lag 0.8 s).\n\n")
        for name, summ, nt, fault in notes:
            f.write(f"{name}: {summ}\n  heading: {nt['heading']}\n  speed: {nt['speed']}\n  {fault}\n\n")
    print(open(f"{folder}/truth_notes.txt").read())


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "drives")
