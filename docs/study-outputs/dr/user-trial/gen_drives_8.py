#!/usr/bin/env python
"""Five simulated drives (and their _clean twins) for filterwnn's GPS/DR reader.

python gen_drives_8.py OUTDIR      (root seed 8; plain numpy only)

Columns (docs/gps_dr.md, "The columns"): time, heading (rad from north, clockwise) or
yaw_rate_deg (deg/s, clockwise +), speed (m/s), gps_lat, gps_lon, gps_sigma (m per axis) on fix
rows, and the truth in true_lat / true_lon on every row.

Faults (each drive's twin has the same truth and the same random draws, without them):
  d1_leverarm   GPS antenna 2.6 m ahead and 0.3 m right of the point the odometer and heading
                describe (the truth): each fix is offset by that vector turned with the heading.
  d2_doppler    the speed column is the receiver's Doppler speed (10 Hz, noisy, never exactly 0
                at a stand): under 7 bridges / underpasses (3-8 s each, at speed) the receiver has
                no fix and the logger writes speed 0 there.
  d3_spare      speed is the left-rear wheel's ABS speed (reads v + yaw_rate * 0.775 m: the
                outside wheel in right turns), and at a 4-minute stop the punctured wheel was
                replaced by a space-saver spare, after which the wheel speed reads 3.0 % high.
  d4_track      test track, 7 clockwise laps and 1 anticlockwise: yaw rate gyro (yaw_rate_deg)
                with a +2.5 % scale factor error; and a GPS cold start: the first 55 s of fixes
                are hundreds of metres off (350 m -> a few m, shrinking), with a large but
                shrinking reported sigma.
  d5_pessimistic  the receiver's reported gps_sigma is 5 times its real error's sigma; and the
                time column is written as ISO 8601 local date-times with a +02:00 offset.
"""
import sys
import os
import numpy as np

DT = 0.1
A_WGS = 6378137.0
E2 = 6.69437999014e-3
LAT0, LON0 = 47.3769, 8.5417
T_EPOCH0 = 1718009400.0  # 2024-06-10T08:50:00Z
D4_SCALE, D4_COLD = True, True  # gen_variants.py switches them to isolate d4's two faults


def radii(lat0):
    s = np.sin(np.radians(lat0))
    M = A_WGS * (1 - E2) / (1 - E2 * s * s) ** 1.5
    N = A_WGS / np.sqrt(1 - E2 * s * s)
    return M, N


def enu_to_ll(e, n):
    M, N = radii(LAT0)
    lat = LAT0 + np.degrees(n / M)
    lon = LON0 + np.degrees(e / (N * np.cos(np.radians(LAT0))))
    return lat, lon


def tukey(n, frac=0.4):
    w = np.ones(n)
    m = max(1, int(frac * n / 2))
    ramp = 0.5 * (1 - np.cos(np.pi * np.arange(m) / m))
    w[:m] = ramp
    w[n - m:] = ramp[::-1]
    return w


class Schedule:
    """Target speed per 10 Hz sample and turn events (centre time, angle deg, duration)."""

    def __init__(self):
        self.v = []        # list of (duration_s, v_target)
        self.turns = []    # (t_start, angle_deg, duration_s)
        self.t = 0.0
        self.bridges = []  # (t_start, t_end) spans without GPS

    def hold(self, d, v):
        self.v.append((d, v))
        self.t += d

    def turn(self, angle, d, v, lead=8.0, tail=3.0):
        self.hold(lead, v)
        self.turns.append((self.t, angle, d))
        self.hold(d + tail, v)

    def curve_in_cruise(self, d_cruise, v, angle, d_turn):
        t0 = self.t
        self.hold(d_cruise, v)
        self.turns.append((t0 + (d_cruise - d_turn) / 2, angle, d_turn))

    def stop(self, wait, decel_time=12.0):
        self.hold(decel_time + wait, 0.0)


def build_truth(sch, rng_unused=None):
    n = int(round(sch.t / DT))
    vcmd = np.zeros(n)
    k = 0
    for d, v in sch.v:
        m = int(round(d / DT))
        vcmd[k:k + m] = v
        k += m
    vcmd[k:] = 0.0
    # acceleration-limited follower then 2 s moving average: smooth speed
    v = np.zeros(n)
    for i in range(1, n):
        dv = vcmd[i] - v[i - 1]
        dv = np.clip(dv, -2.5 * DT, 1.6 * DT)
        v[i] = v[i - 1] + dv
    ker = np.ones(20) / 20
    v = np.convolve(np.r_[np.zeros(19), v], ker, mode="valid")
    v[v < 1e-3] = 0.0
    r = np.zeros(n)  # yaw rate rad/s clockwise
    for ts, ang, d in sch.turns:
        i0 = int(round(ts / DT))
        m = int(round(d / DT))
        w = tukey(m)
        r[i0:i0 + m] += np.radians(ang) * w / (w.sum() * DT)
    r[v < 0.3] = 0.0  # never turn standing (schedules do not put turns there anyway)
    return v, r


def integrate(v, r, psi0):
    n = len(v)
    psi = psi0 + np.r_[0.0, np.cumsum(0.5 * (r[1:] + r[:-1]) * DT)]
    vm = 0.5 * (v[1:] + v[:-1])
    pm = 0.5 * (psi[1:] + psi[:-1])
    e = np.r_[0.0, np.cumsum(vm * np.sin(pm) * DT)]
    nn = np.r_[0.0, np.cumsum(vm * np.cos(pm) * DT)]
    return psi, e, nn


def gm_noise(rng, n, tau, dt):
    a = np.exp(-dt / tau)
    x = np.empty(n)
    x[0] = rng.standard_normal()
    w = rng.standard_normal(n) * np.sqrt(1 - a * a)
    for i in range(1, n):
        x[i] = a * x[i - 1] + w[i]
    return x


def town_schedule(rng, minutes, highway=False, bridges=0):
    s = Schedule()
    s.stop(20.0, decel_time=0.0)  # parked at the start
    target = minutes * 60.0
    nb = 0
    while s.t < target - 40:
        u = rng.random()
        if u < 0.35:
            ang = rng.choice([-90.0, 90.0]) * rng.uniform(0.9, 1.05)
            s.turn(ang, rng.uniform(6.0, 9.0), rng.uniform(6.0, 8.5))
        elif u < 0.55:
            s.stop(rng.uniform(8.0, 40.0))
        else:
            vv = rng.uniform(18.0, 27.0) if highway else rng.uniform(9.0, 17.0)
            d = rng.uniform(30.0, 70.0)
            if rng.random() < 0.6:
                s.curve_in_cruise(d, vv, rng.uniform(-45, 45), rng.uniform(8, 16))
            else:
                s.hold(d, vv)
            if nb < bridges and vv > 10:
                # a bridge / underpass in the middle of the cruise, at speed
                te = s.t - d / 2
                ln = rng.uniform(3.0, 8.0)
                s.bridges.append((te, te + ln))
                nb += 1
    s.stop(15.0)
    return s


def track_schedule(rng):
    """Oval test track: 300 m straights at 22-26 m/s, 180 deg bends at 14-16 m/s."""
    s = Schedule()
    s.stop(20.0, decel_time=0.0)
    s.hold(10.0, 10.0)  # pit exit
    laps = [1] * 4 + [-1] + [1] * 3
    for i, sgn in enumerate(laps):
        for _ in range(2):
            vs = rng.uniform(22.0, 26.0)
            s.hold(300.0 / vs + 6.0, vs)
            vb = rng.uniform(14.0, 16.0)
            radius = 60.0
            d = np.pi * radius / vb * 1.15
            s.turn(sgn * 180.0, d, vb, lead=6.0, tail=2.0)
        if i in (3, 5):
            s.stop(25.0)  # pit stop
            s.hold(10.0, 10.0)
    s.stop(15.0)
    return s


def base_draws(rng, n, nfix):
    """All random draws a drive uses, so that a fault and its twin share them."""
    return dict(
        head_noise=rng.standard_normal(n),
        head_bias=np.radians(rng.uniform(-0.5, 0.5)),
        gyro_noise=rng.standard_normal(n),
        gyro_bias=rng.uniform(-0.04, 0.04),
        speed_noise=rng.standard_normal(n),
        fix_e=gm_noise(rng, nfix, 15.0, 1.0),
        fix_n=gm_noise(rng, nfix, 15.0, 1.0),
        sig_path=gm_noise(rng, nfix, 90.0, 1.0),
        sig_rep=rng.standard_normal(nfix),
        stand_noise=np.abs(rng.standard_normal(n)),
        cold_dir=rng.uniform(0, 2 * np.pi),
        cold_wander=gm_noise(rng, nfix, 10.0, 1.0),
    )


def write_csv(path, cols, fmt):
    names = list(cols)
    n = len(cols[names[0]])
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for i in range(n):
            cells = []
            for c in names:
                x = cols[c][i]
                if isinstance(x, str):
                    cells.append(x)
                elif x is None or (isinstance(x, float) and np.isnan(x)):
                    cells.append("")
                else:
                    cells.append(fmt[c] % x)
            f.write(",".join(cells) + "\n")


FMT = dict(time="%.3f", heading="%.5f", yaw_rate_deg="%.4f", speed="%.3f",
           gps_lat="%.8f", gps_lon="%.8f", gps_sigma="%.1f",
           true_lat="%.9f", true_lon="%.9f")


def iso(t, offset_h=2):
    # local time with offset, millisecond precision, plain numpy
    sec = np.floor(t)
    ms = int(round((t - sec) * 1000))
    if ms == 1000:
        sec += 1
        ms = 0
    loc = np.datetime64(int(sec), "s") + np.timedelta64(offset_h, "h")
    return "%s.%03d+%02d:00" % (str(loc), ms, offset_h)


def make_drive(name, rng, sch, heading_kind="heading", fault=None):
    v, r = build_truth(sch)
    n = len(v)
    psi0 = rng.uniform(0, 2 * np.pi)
    psi, e, nn = integrate(v, r, psi0)
    t = np.arange(n) * DT
    fix_idx = np.arange(0, n, 10)  # 1 Hz fixes on the rows of whole seconds
    fix_idx = fix_idx[fix_idx > 0]
    nfix = len(fix_idx)
    D = base_draws(rng, n, nfix)
    # fix accuracy: sigma per axis wandering between 2 and 5 m, reported with 10 % noise
    sig = 3.5 + 1.5 * np.tanh(D["sig_path"])
    err_e = sig * D["fix_e"]
    err_n = sig * D["fix_n"]
    rep = sig * np.exp(0.1 * D["sig_rep"])

    def assemble(faulted):
        cols = {}
        tt = T_EPOCH0 + t
        cols["time"] = tt
        psi_f = psi[fix_idx]
        fe = e[fix_idx] + err_e
        fn = nn[fix_idx] + err_n
        rep_f = rep.copy()
        keep = np.ones(nfix, bool)
        # speed: CAN/wheel speed with 0.03 m/s noise, exactly 0 when standing
        spd = np.where(v > 0.05, v + 0.03 * D["speed_noise"], 0.0)
        spd = np.maximum(spd, 0.0)
        if heading_kind == "heading":
            h = psi + D["head_bias"] + np.radians(0.3) * D["head_noise"]
            cols["heading"] = np.mod(h, 2 * np.pi)
        else:
            scale = 1.0
            if faulted and fault == "track" and D4_SCALE:
                scale = 1.025
            rate_deg = np.degrees(r) * scale + D["gyro_bias"] + 0.1 * D["gyro_noise"]
            cols["yaw_rate_deg"] = rate_deg
        info = {}
        if fault == "leverarm" and faulted:
            fwd, right = 2.6, 0.3
            fe = fe + fwd * np.sin(psi_f) + right * np.cos(psi_f)
            fn = fn + fwd * np.cos(psi_f) - right * np.sin(psi_f)
        if fault == "doppler":
            # Doppler speed: 0.05 m/s noise, never exactly 0 at a stand
            dop = np.where(v > 0.05, v + 0.05 * D["speed_noise"], 0.03 * D["stand_noise"])
            dop = np.maximum(dop, 0.0)
            spd = dop
            for a, b in sch.bridges:
                inb = (t[fix_idx] >= a) & (t[fix_idx] <= b)
                keep &= ~inb  # no fix under a bridge (both drive and twin)
                if faulted:
                    spd = np.where((t >= a) & (t <= b), 0.0, spd)
            info["bridges"] = [(round(a, 1), round(b, 1)) for a, b in sch.bridges]
            info["bridge_zero_rows"] = int(sum(((t >= a) & (t <= b)).sum() for a, b in sch.bridges))
            info["bridge_dist_m"] = float(sum(v[(t >= a) & (t <= b)].sum() * DT for a, b in sch.bridges))
        if fault == "spare" and faulted:
            wheel = v + r * 0.775  # left-rear wheel, outside wheel in right (clockwise) turns
            spd = np.where(v > 0.05, wheel + 0.03 * D["speed_noise"], 0.0)
            # the long stop: the spare is fitted there
            ts = sch.spare_time
            spd = np.where(t > ts, spd * 1.03, spd)
            spd = np.maximum(spd, 0.0)
            info["spare_from_s"] = ts
        if fault == "track" and faulted and D4_COLD:
            tf = t[fix_idx]
            cold = tf < 55.0
            off = 350.0 * np.exp(-tf / 12.0)  # 350 m at t=0, 4 m at 54 s
            ang = D["cold_dir"] + 0.4 * D["cold_wander"]
            fe = np.where(cold, fe + off * np.sin(ang), fe)
            fn = np.where(cold, fn + off * np.cos(ang), fn)
            rep_f = np.where(cold, rep_f + 0.8 * off, rep_f)
            info["cold_start_first_offsets_m"] = [round(float(x), 1) for x in off[:5]]
        if fault == "pessimistic" and faulted:
            rep_f = rep_f * 5.0
        cols["speed"] = spd
        lat, lon = enu_to_ll(fe, fn)
        glat = np.full(n, np.nan)
        glon = np.full(n, np.nan)
        gsig = np.full(n, np.nan)
        glat[fix_idx[keep]] = lat[keep]
        glon[fix_idx[keep]] = lon[keep]
        gsig[fix_idx[keep]] = np.round(rep_f[keep], 1)
        cols["gps_lat"], cols["gps_lon"], cols["gps_sigma"] = glat, glon, gsig
        tl, tn = enu_to_ll(e, nn)
        cols["true_lat"], cols["true_lon"] = tl, tn
        if fault == "pessimistic" and faulted:
            cols["time"] = [iso(x) for x in tt]
        return cols, info

    stats = dict(duration_min=round(n * DT / 60, 2), length_km=round(float(v.sum() * DT / 1000), 2),
                 max_speed=round(float(v.max()), 1), turn_total_deg=round(float(np.degrees(np.abs(r).sum() * DT))),
                 turn_net_deg=round(float(np.degrees(r.sum() * DT))),
                 max_rate_deg=round(float(np.degrees(np.abs(r).max())), 1),
                 stand_s=round(float((v < 0.05).sum() * DT)), fixes=int(nfix))
    return assemble(True), assemble(False), stats


def main(out):
    os.makedirs(out, exist_ok=True)
    root = np.random.SeedSequence(8)
    seeds = root.spawn(5)
    specs = [("d1_leverarm", "leverarm", "heading", 10),
             ("d2_doppler", "doppler", "heading", 12),
             ("d3_spare", "spare", "heading", 10),
             ("d4_track", "track", "yaw", None),
             ("d5_pessimistic", "pessimistic", "heading", 9)]
    for (name, fault, hk, minutes), ss in zip(specs, seeds):
        rng = np.random.default_rng(ss)
        if fault == "track":
            sch = track_schedule(rng)
        elif fault == "spare":
            # 5 minutes, the 4-minute wheel change, 5 more minutes
            a = town_schedule(rng, 5)
            sch = a
            sch.stop(240.0)
            sch.spare_time = sch.t - 120.0
            b = town_schedule(rng, 5)
            for d, vv in b.v[1:]:
                pass
            t0 = sch.t
            for d, vv in b.v[1:]:  # skip b's parked start
                sch.v.append((d, vv))
            for ts, ang, d in b.turns:
                sch.turns.append((ts - 20.0 + t0, ang, d))
            sch.t = t0 + b.t - 20.0
        elif fault == "doppler":
            sch = town_schedule(rng, minutes, highway=True, bridges=8)
        else:
            sch = town_schedule(rng, minutes)
        (fc, finfo), (cc, _), stats = make_drive(name, rng, sch, hk, fault)
        write_csv(os.path.join(out, name + ".csv"), fc, FMT)
        write_csv(os.path.join(out, name + "_clean.csv"), cc, FMT)
        print(name, stats, finfo)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "drives")
