"""Simulate a phone-app car log: OBD-II speed through an ELM327, the phone's GPS, gyroscope,
accelerometer and fused orientation, the phone in a tilted dashboard mount. numpy only, seeded.

    python sim_obd.py --out DIR [--seed 7]

Writes, as such an app exports them (every time stamp: the phone's clock, epoch milliseconds):
  DIR/gps.csv            timestamp_ms,latitude,longitude,accuracy_m,altitude_m,speed_mps,bearing_deg,provider
  DIR/gyroscope.csv      timestamp_ms,x,y,z                 (rad/s, phone frame, Android: CCW positive)
  DIR/accelerometer.csv  timestamp_ms,x,y,z                 (m/s^2, phone frame, with gravity)
  DIR/orientation.csv    timestamp_ms,azimuth,pitch,roll    (deg, Android's fused orientation, magnetic)
  DIR/obd.csv            Car Scanner style, ';'-separated: timestamp_ms;pid;name;value;units (0x0D and 0x0C)
and the ground truth, which the app does not have:
  DIR/truth.csv          timestamp_ms,lat,lon,east_m,north_m,heading_deg,speed_mps,yaw_rate_cw_deg_s,in_tunnel
  DIR/sim_info.json      every simulated number (biases, mount, tunnel, multipath, reverse, ...)
"""
import argparse
import json
import os

import numpy as np

DT = 0.01                       # truth grid, s
T0_MS = 1796395200000           # 2026-12-05 12:00:00 UTC, phone clock
LAT0, LON0 = 48.1374, 11.5755   # somewhere in Munich
R_EARTH = 6378137.0
G = 9.80665


class Route:
    """Speed and clockwise yaw rate, step by step at DT."""

    def __init__(self, rng):
        self.rng = rng
        self.v, self.r, self.env = [], [], []   # env: 0 urban, 1 suburban, 2 tunnel, 3 parking
        self.cur_v = 0.0
        self.cur_env = 0

    def _push(self, v, r):
        self.v.extend(v)
        self.r.extend(r)
        self.env.extend([self.cur_env] * len(v))
        if len(v):
            self.cur_v = float(v[-1])

    @property
    def t(self):
        return len(self.v) * DT

    def accel_to(self, vt, a=1.5):
        n = max(1, int(round(abs(vt - self.cur_v) / a / DT)))
        self._push(np.linspace(self.cur_v, vt, n + 1)[1:], np.zeros(n))

    def cruise(self, dur):
        n = int(round(dur / DT))
        self._push(np.full(n, self.cur_v), np.zeros(n))

    def turn(self, angle_deg, dur):
        n = int(round(dur / DT))
        tt = (np.arange(n) + 0.5) * DT
        rate = np.deg2rad(angle_deg) * (1 - np.cos(2 * np.pi * tt / dur)) / dur
        self._push(np.full(n, self.cur_v), rate)

    def stop(self, dur):
        self.accel_to(0.0, 2.0)
        n = int(round(dur / DT))
        self._push(np.zeros(n), np.zeros(n))


def build_route(rng):
    R = Route(rng)
    info = {"lights": [], "turns90": 0, "curves": 0}
    R.cur_env = 0
    R.stop(25.0)                                   # engine on, app logging, still parked
    # --- urban: blocks, lights, right angles
    while R.t < 520:
        R.accel_to(rng.uniform(11, 14), rng.uniform(1.2, 2.0))
        R.cruise(rng.uniform(6, 18))
        u = rng.uniform()
        if u < 0.40:
            d = float(rng.uniform(10, 60))
            info["lights"].append([round(R.t, 1), round(d, 1)])
            R.stop(d)
        elif u < 0.80:
            R.accel_to(rng.uniform(4.5, 6.0), 2.0)
            R.turn(float(rng.choice([-90, 90])), rng.uniform(4.5, 6.5))
            info["turns90"] += 1
        else:
            R.turn(float(rng.uniform(-35, 35)), rng.uniform(6, 10))
            info["curves"] += 1
    # --- suburban, with the underpass
    R.cur_env = 1
    tunnel_done = False
    while R.t < 1040:
        R.accel_to(rng.uniform(16, 20), rng.uniform(1.0, 1.8))
        R.cruise(rng.uniform(10, 30))
        if not tunnel_done and R.t > 700:
            R.accel_to(15.0, 1.0)
            R.cruise(3.0)
            R.cur_env = 2
            t_in = R.t
            R.cruise(20.0)
            R.turn(12.0, 8.0)                          # a gentle bend inside
            R.cruise(12.0)
            info["tunnel"] = [round(t_in, 2), round(R.t, 2)]
            R.cur_env = 1
            tunnel_done = True
            continue
        u = rng.uniform()
        if u < 0.45:
            R.turn(float(rng.uniform(-45, 45)), rng.uniform(8, 15))
            info["curves"] += 1
        elif u < 0.70:
            d = float(rng.uniform(10, 45))
            info["lights"].append([round(R.t, 1), round(d, 1)])
            R.stop(d)
        else:
            R.accel_to(6.0, 2.0)
            R.turn(float(rng.choice([-90, 90])), 6.0)
            info["turns90"] += 1
    # --- back into town
    R.cur_env = 0
    while R.t < 1230:
        R.accel_to(rng.uniform(10, 13), 1.5)
        R.cruise(rng.uniform(6, 15))
        if rng.uniform() < 0.5:
            d = float(rng.uniform(10, 40))
            info["lights"].append([round(R.t, 1), round(d, 1)])
            R.stop(d)
        else:
            R.accel_to(5.0, 2.0)
            R.turn(float(rng.choice([-90, 90])), 5.5)
            info["turns90"] += 1
    # --- parking lot: slow manoeuvres, a short reverse into a space
    R.cur_env = 3
    R.accel_to(3.0, 1.5)
    R.turn(90.0, 7.0)
    R.cruise(8.0)
    R.turn(-90.0, 8.0)
    R.accel_to(2.0, 1.0)
    R.cruise(6.0)
    R.stop(4.0)
    t_rev = R.t
    R.accel_to(-1.2, 0.6)                            # reverse, turning into the space
    n = int(round(5.0 / DT))
    tt = (np.arange(n) + 0.5) * DT
    R._push(np.full(n, -1.2), np.deg2rad(-60.0) * (1 - np.cos(2 * np.pi * tt / 5.0)) / 5.0)
    R.cruise(1.5)
    R.accel_to(0.0, 0.6)
    info["reverse"] = [round(t_rev, 2), round(R.t, 2)]
    R.stop(3.0)
    R.accel_to(0.8, 0.5)
    R.cruise(2.0)
    R.stop(15.0)
    v = np.array(R.v)
    r = np.array(R.r)
    env = np.array(R.env)
    return v, r, env, info


def ou(rng, n, sd, tau):
    """Gauss-Markov sequence at DT, stationary sd, correlation time tau."""
    phi = np.exp(-DT / tau)
    e = rng.standard_normal(n) * sd * np.sqrt(1 - phi ** 2)
    x = np.empty(n)
    x[0] = rng.standard_normal() * sd
    for k in range(1, n):
        x[k] = phi * x[k - 1] + e[k]
    return x


def ou_at(rng, t, sd, tau):
    """Gauss-Markov sequence at arbitrary increasing times t."""
    x = np.empty(len(t))
    x[0] = rng.standard_normal() * sd
    for k in range(1, len(t)):
        phi = np.exp(-(t[k] - t[k - 1]) / tau)
        x[k] = phi * x[k - 1] + rng.standard_normal() * sd * np.sqrt(1 - phi ** 2)
    return x


def irregular_stamps(rng, t_end, dt, jitter, gap_every, gap_range):
    ts, t = [], 0.0
    next_gap = rng.uniform(*gap_every)
    while t < t_end:
        ts.append(t)
        step = max(0.3 * dt, dt + rng.normal(0, jitter))
        if t > next_gap:
            step += rng.uniform(*gap_range)
            next_gap = t + rng.uniform(*gap_every)
        t += step
    return np.array(ts)


def rot_z(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="obd_log")
    ap.add_argument("--seed", type=int, default=7)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    os.makedirs(a.out, exist_ok=True)

    v, r_cw, env, info = build_route(rng)
    n = len(v)
    t = np.arange(n) * DT
    moving = np.abs(v) > 0.05
    # speed wobble while cruising (a driver's foot), never crossing zero
    wob = 1.0 + np.clip(ou(rng, n, 0.03, 4.0), -0.08, 0.08)
    v = np.where(np.abs(v) > 4.0, v * wob, v)
    psi0 = np.deg2rad(rng.uniform(0, 360))
    psi = psi0 + np.concatenate([[0.0], np.cumsum(0.5 * (r_cw[1:] + r_cw[:-1]) * DT)])
    east = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] * np.sin(psi[1:]) + v[:-1] * np.sin(psi[:-1])) * DT)])
    north = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] * np.cos(psi[1:]) + v[:-1] * np.cos(psi[:-1])) * DT)])
    east += 350.0
    north -= 120.0
    lat = LAT0 + np.rad2deg(north / R_EARTH)
    lon = LON0 + np.rad2deg(east / (R_EARTH * np.cos(np.deg2rad(LAT0))))
    a_long = np.gradient(v, DT)
    tunnel = env == 2

    # ---- car body motion (x forward, y left, z up): small pitch/roll, yaw CCW = -r_cw
    mv = moving.astype(float)
    a_lat = v * (-r_cw)                                            # left positive
    roll = np.deg2rad(0.4) * ou(rng, n, 1.0, 0.8) * mv + np.deg2rad(3.0) * a_lat / G
    pitch = np.deg2rad(0.3) * ou(rng, n, 1.0, 0.8) * mv - np.deg2rad(1.5) * a_long / G
    w_car = np.stack([np.gradient(roll, DT), np.gradient(pitch, DT), -r_cw], axis=1)
    # specific force in the car frame: longitudinal, lateral (left positive), gravity up
    f_car = np.stack([a_long + G * np.sin(pitch), a_lat - G * np.sin(roll),
                      G * np.cos(pitch) * np.cos(roll)], axis=1)

    # ---- the phone: portrait, reclined 30 deg (top towards the windscreen), yawed 10 deg
    tilt = np.deg2rad(30.0)
    mount_yaw = np.deg2rad(10.0)
    px = np.array([0.0, -1.0, 0.0])                                 # phone x: car's right
    py = np.array([np.sin(tilt), 0.0, np.cos(tilt)])                # phone y: up, leaning forward
    pz = np.cross(px, py)                                           # screen normal: back and up
    R_cp = rot_z(mount_yaw) @ np.stack([px, py, pz], axis=1)        # phone axes in car coordinates
    w_phone = w_car @ R_cp                                          # = (R_cp^T w)^T
    f_phone = f_car @ R_cp

    # ---- gyroscope, ~100 Hz, irregular stamps, gaps
    tg = irregular_stamps(rng, t[-1], 0.01, 0.0015, (40, 100), (0.05, 0.2))
    bias0 = np.deg2rad(rng.uniform(0.1, 0.5, 3) * rng.choice([-1, 1], 3))
    warm = np.deg2rad(np.array([0.02, -0.03, 0.025]))             # warm-up drift over the drive
    gyro_scale = 1.0 + rng.normal(0, 0.004, 3)
    gyro = np.empty((len(tg), 3))
    for i in range(3):
        gyro[:, i] = gyro_scale[i] * np.interp(tg, t, w_phone[:, i])
    gyro += bias0 + warm * (1 - np.exp(-tg / 400.0))[:, None]
    vib = np.interp(tg, t, mv)[:, None]
    gyro += rng.normal(0, np.deg2rad(0.08), gyro.shape) + vib * rng.normal(0, np.deg2rad(0.25), gyro.shape)

    # ---- accelerometer, own irregular stamps
    ta = irregular_stamps(rng, t[-1], 0.01, 0.0015, (40, 100), (0.05, 0.2))
    acc = np.stack([np.interp(ta, t, f_phone[:, i]) for i in range(3)], axis=1)
    acc += rng.uniform(-0.06, 0.06, 3) + rng.normal(0, 0.03, acc.shape)
    acc += np.interp(ta, t, mv)[:, None] * rng.normal(0, 0.25, acc.shape)

    # ---- fused orientation azimuth (magnetic, disturbed by the car), ~20 Hz
    to = irregular_stamps(rng, t[-1], 0.05, 0.005, (60, 120), (0.05, 0.2))
    declination = 3.6
    head_true_deg = np.rad2deg(psi)
    h = np.deg2rad(np.interp(to, t, head_true_deg))
    dist = 7.0 * np.sin(h + 0.7) + 3.0 * np.sin(2 * h - 0.4)         # hard/soft iron of the car
    dist += ou_at(rng, to, 4.0, 30.0)                                 # electrical loads, wandering
    tin = np.interp(to, t, tunnel.astype(float)) > 0.5
    dist += np.where(tin, 25.0 * np.sin(np.linspace(0, 3, len(to))) , 0.0)   # steel in the underpass
    azimuth = np.interp(to, t, head_true_deg) + np.rad2deg(mount_yaw) * -1 - declination + dist
    azimuth = np.mod(azimuth + rng.normal(0, 0.8, len(to)), 360.0)
    opitch = -60.0 + rng.normal(0, 0.5, len(to))
    oroll = rng.normal(0, 0.5, len(to))

    # ---- GPS, 1 Hz, delivered 0.15-0.40 s after the fix's epoch
    t_fix = np.arange(1.0, t[-1], 1.0)
    t_fix = t_fix[np.interp(t_fix, t, tunnel.astype(float)) < 0.5]
    env_fix = np.interp(t_fix, t, env).round().astype(int)
    sig_env = np.where(env_fix == 0, 4.5, np.where(env_fix == 3, 3.5, 2.2))   # per axis, m
    tau = 15.0
    ge = ou_at(rng, t_fix, 1.0, tau) * sig_env
    gn = ou_at(rng, t_fix, 1.0, tau) * sig_env
    ge += rng.normal(0, 0.4, len(t_fix)) * sig_env
    gn += rng.normal(0, 0.4, len(t_fix)) * sig_env
    # reacquisition after the tunnel
    t_out = info["tunnel"][1]
    since = t_fix - t_out
    reacq = (since > 0) & (since < 6)
    ramp = np.where(reacq, np.exp(-since / 2.0), 0.0)
    ge += ramp * 9.0
    gn += ramp * -6.0
    # two multipath excursions of 15-30 m
    urban_idx = np.flatnonzero(env_fix == 0)
    mp = []
    for k in (urban_idx[len(urban_idx) // 4], urban_idx[(3 * len(urban_idx)) // 4 + 5]):
        t_mp = t_fix[k]
        mag = rng.uniform(15, 30)
        ang = rng.uniform(0, 2 * np.pi)
        dur = rng.uniform(8, 14)
        sh = np.clip((t_fix - t_mp) / 2.0, 0, 1) * np.clip((t_mp + dur - t_fix) / 2.0, 0, 1)
        ge += sh * mag * np.sin(ang)
        gn += sh * mag * np.cos(ang)
        mp.append([round(float(t_mp), 1), round(float(dur), 1), round(float(mag), 1)])
    fe = np.interp(t_fix, t, east) + ge
    fn = np.interp(t_fix, t, north) + gn
    acc68 = 1.51 * sig_env * np.exp(rng.normal(0, 0.15, len(t_fix)))
    acc68 = acc68 * (1 + 2.0 * ramp)
    acc68 = np.clip(acc68, 3.0, 30.0)
    acc68 = np.round(acc68, 1)
    gspeed = np.abs(np.interp(t_fix, t, v)) + rng.normal(0, 0.15, len(t_fix))
    gspeed = np.round(np.clip(gspeed, 0, None), 2)
    course = np.mod(np.interp(t_fix, t, head_true_deg) + np.where(np.interp(t_fix, t, v) < 0, 180, 0)
                    + rng.normal(0, 2.0, len(t_fix)), 360)
    bearing = course.copy()
    last = bearing[0]
    for k in range(len(bearing)):                                # frozen/garbage when slow
        if gspeed[k] < 1.0:
            bearing[k] = last if rng.uniform() < 0.7 else rng.uniform(0, 360)
        else:
            last = bearing[k]
    bearing = np.round(bearing, 1)
    glat = LAT0 + np.rad2deg(fn / R_EARTH)
    glon = LON0 + np.rad2deg(fe / (R_EARTH * np.cos(np.deg2rad(LAT0))))
    t_gps_log = t_fix + rng.uniform(0.15, 0.40, len(t_fix))

    # ---- OBD-II: PID 0x0D (integer km/h, 2.5 % high, 0 below 3 km/h, unsigned), polled 2-4 Hz
    ecu_scale = 1.0 + rng.uniform(0.02, 0.03)
    tp, tt_ = [], 0.5
    next_hang = rng.uniform(60, 150)
    while tt_ < t[-1] - 0.1:
        tp.append(tt_)
        tt_ += rng.uniform(0.25, 0.5)
        if tt_ > next_hang:
            tt_ += rng.uniform(1.0, 3.0)
            next_hang = tt_ + rng.uniform(60, 150)
    tp = np.array(tp)
    ecu_latency = 0.12                                       # value sampled this much before the stamp
    kmh = np.abs(np.interp(tp - ecu_latency, t, v)) * 3.6 * ecu_scale
    kmh = np.where(kmh < 3.0, 0, np.floor(kmh + 0.5)).astype(int)
    rpm = np.round(800 + 95 * np.abs(np.interp(tp, t, v)) * 3.6 / 3.6 + rng.normal(0, 20, len(tp)))
    hang_gaps = np.diff(tp)[np.diff(tp) > 0.9]

    ms = lambda s: np.round(T0_MS + 1000 * s).astype(np.int64)
    with open(os.path.join(a.out, "gps.csv"), "w") as f:
        f.write("timestamp_ms,latitude,longitude,accuracy_m,altitude_m,speed_mps,bearing_deg,provider\n")
        for i in range(len(t_fix)):
            f.write(f"{ms(t_gps_log[i])},{glat[i]:.7f},{glon[i]:.7f},{acc68[i]:.1f},"
                    f"{520 + rng.normal(0, 3):.1f},{gspeed[i]:.2f},{bearing[i]:.1f},gps\n")
    for name, tx, arr, fmt in (("gyroscope", tg, gyro, "{:.6f}"), ("accelerometer", ta, acc, "{:.4f}")):
        with open(os.path.join(a.out, name + ".csv"), "w") as f:
            f.write("timestamp_ms,x,y,z\n")
            stamps = ms(tx)
            for i in range(len(tx)):
                f.write(f"{stamps[i]}," + ",".join(fmt.format(x) for x in arr[i]) + "\n")
    with open(os.path.join(a.out, "orientation.csv"), "w") as f:
        f.write("timestamp_ms,azimuth,pitch,roll\n")
        stamps = ms(to)
        for i in range(len(to)):
            f.write(f"{stamps[i]},{azimuth[i]:.2f},{opitch[i]:.2f},{oroll[i]:.2f}\n")
    with open(os.path.join(a.out, "obd.csv"), "w") as f:
        f.write("timestamp_ms;pid;name;value;units\n")
        stamps = ms(tp)
        for i in range(len(tp)):
            f.write(f"{stamps[i]};0x0D;Vehicle speed;{kmh[i]};km/h\n")
            if i % 3 == 0:
                f.write(f"{stamps[i] + 37};0x0C;Engine RPM;{int(rpm[i])};rpm\n")
    with open(os.path.join(a.out, "truth.csv"), "w") as f:
        f.write("timestamp_ms,lat,lon,east_m,north_m,heading_deg,speed_mps,yaw_rate_cw_deg_s,in_tunnel\n")
        stamps = ms(t)
        for i in range(0, n):
            f.write(f"{stamps[i]},{lat[i]:.8f},{lon[i]:.8f},{east[i]:.3f},{north[i]:.3f},"
                    f"{np.mod(head_true_deg[i], 360):.3f},{v[i]:.4f},{np.rad2deg(r_cw[i]):.4f},{int(tunnel[i])}\n")

    up_phone = R_cp.T @ np.array([0, 0, 1.0])
    gps_err = np.hypot(ge, gn)
    sim = {
        "seed": a.seed, "t0_ms": T0_MS, "duration_s": round(float(t[-1]), 2),
        "distance_m": round(float(np.sum(np.abs(v)) * DT), 1),
        "max_speed_mps": round(float(v.max()), 2), "standing_fraction": round(float(np.mean(~moving)), 3),
        "lights": info["lights"], "n_turns90": info["turns90"], "n_curves": info["curves"],
        "tunnel_s": info["tunnel"], "reverse_s": info["reverse"],
        "reverse_m": round(float(np.sum(np.abs(v[v < 0])) * DT), 2),
        "mount_tilt_deg": 30.0, "mount_yaw_deg": 10.0,
        "up_in_phone_frame": up_phone.round(4).tolist(),
        "gyro_bias0_deg_s": np.rad2deg(bias0).round(3).tolist(),
        "gyro_bias_vertical_deg_s": round(float(np.rad2deg(bias0 @ up_phone)), 3),
        "gyro_warmup_drift_deg_s": np.rad2deg(warm).round(3).tolist(),
        "gyro_scale": gyro_scale.round(4).tolist(),
        "gyro_rows": len(tg), "gyro_gaps_over_50ms": int(np.sum(np.diff(tg) > 0.05)),
        "gps_fixes": len(t_fix), "gps_sigma_axis_m": {"urban": 4.5, "suburban": 2.2, "parking": 3.5},
        "gps_tau_s": tau, "gps_delivery_latency_s": [0.15, 0.40],
        "gps_error_median_m": round(float(np.median(gps_err)), 2),
        "gps_error_p95_m": round(float(np.percentile(gps_err, 95)), 2),
        "gps_accuracy68_range_m": [float(acc68.min()), float(np.median(acc68)), float(acc68.max())],
        "multipath_t_dur_mag": mp,
        "obd_polls": len(tp), "obd_scale": round(float(ecu_scale), 4), "obd_latency_s": ecu_latency,
        "obd_hangs_s": np.round(hang_gaps, 2).tolist(),
        "orientation_declination_deg": declination,
    }
    with open(os.path.join(a.out, "sim_info.json"), "w") as f:
        json.dump(sim, f, indent=1)
    print(json.dumps({k: sim[k] for k in ("duration_s", "distance_m", "max_speed_mps", "tunnel_s", "reverse_s",
                                          "reverse_m", "gyro_bias_vertical_deg_s", "gps_error_median_m",
                                          "gps_error_p95_m", "obd_scale", "standing_fraction")}))


if __name__ == "__main__":
    main()
