"""Simulated car drives, each with one real-world fault, for `filterwnn study dr --drive`.

python gen_drives_3.py [OUTDIR]      (seeded: the same files every time; default the current folder)

(Stop 70: the third user trial's drives, written by a helper who had not read the package's code; kept as written
but for the output folder's default. See RUN.md.)

Drives
  ferry.csv    10 Hz DR / 1 Hz GPS, 12.5 min: 4 min on a car ferry, wheel speed 0 while the
               fixes move ~1.2 km at 5 m/s (the fused heading follows the ferry's turns)
  snow.csv     5 Hz DR / 1 Hz GPS, 10 min: wheel spin on snow (speed reads 30-60 % high for
               4-12 s when pulling away / accelerating) and wheel lock when braking (reads 0
               while the car slides 1-2.5 s): +~150 m of odometer in ~5.4 km
  utm.csv      2 Hz DR / 2 Hz GPS, 10 min: fixes and truth in a UTM grid (E ~ 689 km,
               N ~ 5335 km, zone 32N-like) with the grid's 1.9 deg convergence vs true north
  carpark.csv  10 Hz DR (gyro yaw_rate_deg, +0.8 % scale, 0.03 deg/s bias) / 1 Hz GPS, 11 min:
               a multi-storey car park: 5 circles up a 12 m helix, 90 s parked, 5 circles down
               the other way, ~4.5 min without fixes, degraded fixes for 15 s after exit
  spoof.csv    5 Hz DR / 2 Hz GPS, 11 min: GNSS spoofing drag: the fixes walk away at
               0.33 m/s for 240 s (to 80 m) with their accuracy unchanged, then snap back
  wrap.csv     10 Hz DR / 1 Hz GPS, 10 min: heading_deg written 0..360 for the first half and
               -180..180 for the second (two logger firmwares / a concatenated export)
With --long also long50hz.csv: 2 h at 50 Hz DR / 1 Hz GPS, no fault (a size test).
Each NAME.csv has a NAME_clean.csv: the same drive and noise without the fault (the baseline).
"""
import os
import sys

import numpy as np

DT_INT = 0.01          # internal integration step (s)
A_WGS = 6378137.0
F_WGS = 1 / 298.257223563
E2 = F_WGS * (2 - F_WGS)


def enu_to_latlon(e, n, lat0, lon0):
    phi = np.radians(lat0)
    rm = A_WGS * (1 - E2) / (1 - E2 * np.sin(phi) ** 2) ** 1.5
    rn = A_WGS / np.sqrt(1 - E2 * np.sin(phi) ** 2)
    return lat0 + np.degrees(n / rm), lon0 + np.degrees(e / (rn * np.cos(phi)))


class Track:
    """Integrates a car's path from speed / yaw-rate commands at DT_INT."""

    def __init__(self, v0=0.0, psi0=0.0):
        self.t, self.x, self.y, self.psi, self.v, self.wheel, self.flag = [], [], [], [], [], [], []
        self.cx, self.cy, self.cpsi, self.cv, self.ct = 0.0, 0.0, psi0, v0, 0.0
        self.mode = "road"            # road / ferry
        self.cflag = 0

    def _step(self, a, r):
        self.cv = max(0.0, self.cv + a * DT_INT)
        self.cpsi += r * DT_INT
        self.cx += self.cv * np.sin(self.cpsi) * DT_INT
        self.cy += self.cv * np.cos(self.cpsi) * DT_INT
        self.ct += DT_INT
        self.t.append(self.ct); self.x.append(self.cx); self.y.append(self.cy)
        self.psi.append(self.cpsi); self.v.append(self.cv)
        self.wheel.append(0.0 if self.mode == "ferry" else self.cv)
        self.flag.append(self.cflag)

    def speed_to(self, v, a=1.5):
        a = abs(a) if v > self.cv else -abs(a)
        while (a > 0 and self.cv < v) or (a < 0 and self.cv > v):
            self._step(a, 0.0)
        self.cv = v

    def cruise(self, T):
        for _ in range(int(round(T / DT_INT))):
            self._step(0.0, 0.0)

    def turn(self, deg, radius):
        """turn by deg (clockwise +) at the present speed on a circle of radius."""
        v = max(self.cv, 0.5)
        rate = v / radius * np.sign(deg)
        n = int(round(np.radians(abs(deg)) / abs(rate) / DT_INT))
        for _ in range(n):
            self._step(0.0, rate)

    def wiggle(self, T, amp_deg=3.0, period=20.0):
        """gentle road curvature."""
        n = int(round(T / DT_INT))
        for i in range(n):
            r = np.radians(amp_deg) * 2 * np.pi / period * np.cos(2 * np.pi * i * DT_INT / period)
            self._step(0.0, r)

    def stop(self, T, decel=2.0):
        self.speed_to(0.0, decel)
        self.cruise(T)

    def arrays(self):
        return {k: np.array(getattr(self, k)) for k in ("t", "x", "y", "psi", "v", "wheel", "flag")}


def random_town(tr, rng, T_end):
    """random town driving until T_end."""
    while tr.ct < T_end:
        vt = rng.uniform(8, 17)
        tr.speed_to(vt, rng.uniform(1.0, 2.2))
        tr.wiggle(rng.uniform(8, 40), amp_deg=rng.uniform(1, 5), period=rng.uniform(15, 30))
        u = rng.uniform()
        if u < 0.3:
            tr.stop(rng.uniform(4, 25), rng.uniform(1.5, 3.0))
            tr.speed_to(rng.uniform(5, 7), 1.5)
            tr.turn(rng.choice([-90, 90]), rng.uniform(8, 15))
        elif u < 0.75:
            tr.speed_to(rng.uniform(5, 8), 2.0)
            tr.turn(rng.choice([-90, 90, -45, 45]), rng.uniform(10, 25))
        else:
            tr.turn(rng.uniform(-30, 30), rng.uniform(60, 150))


def gps_noise(rng, t, sigma_gm=2.5, tau=30.0, white=0.8):
    """first-order Gauss-Markov + white error per axis at times t."""
    out = np.zeros((len(t), 2))
    e = rng.normal(0, sigma_gm, 2)
    for i in range(len(t)):
        if i:
            dt = t[i] - t[i - 1]
            phi = np.exp(-dt / tau)
            e = phi * e + np.sqrt(1 - phi ** 2) * sigma_gm * rng.normal(size=2)
        out[i] = e
    return out + rng.normal(0, white, out.shape)


def sample(track, dr_hz, gps_hz, rng, heading_bias_deg=0.6, heading_noise_deg=0.3,
           speed_noise=0.03, speed_scale=1.004):
    """DR samples at dr_hz (heading = mean over last internal steps, speed at the instant),
    fixes on the rows at gps_hz."""
    A = track.arrays()
    step = int(round(1 / dr_hz / DT_INT))
    idx = np.arange(step - 1, len(A["t"]), step)
    t = np.round(A["t"][idx], 3)
    n = len(idx)
    drift = np.cumsum(rng.normal(0, 0.01, n))          # slow drift of the fused heading (deg)
    hdg = np.degrees(A["psi"][idx]) + heading_bias_deg + drift + rng.normal(0, heading_noise_deg, n)
    wheel = A["wheel"][idx]
    spd = np.where(wheel > 0, wheel * speed_scale + rng.normal(0, speed_noise, n), 0.0)
    spd = np.maximum(spd, 0.0)
    every = int(round(dr_hz / gps_hz))
    has_fix = np.zeros(n, bool)
    has_fix[::every] = True
    ne = gps_noise(rng, t)
    ge = A["x"][idx] + ne[:, 0]
    gn = A["y"][idx] + ne[:, 1]
    sig = np.round(3.0 + 0.4 * rng.standard_normal(n).clip(-2, 2), 1)
    return dict(t=t, idx=idx, A=A, hdg=hdg, spd=spd, has_fix=has_fix, ge=ge, gn=gn, sig=sig,
                te=A["x"][idx], tn=A["y"][idx], flag=A["flag"][idx], psi=A["psi"][idx])


def write_csv(path, cols, rows_fix=None):
    """cols: ordered dict name -> (array, fmt); NaN written as empty cell."""
    names = list(cols)
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        n = len(next(iter(cols.values()))[0])
        for i in range(n):
            cells = []
            for k in names:
                arr, fmt = cols[k]
                v = arr[i]
                cells.append("" if (isinstance(v, float) and np.isnan(v)) else fmt % v)
            f.write(",".join(cells) + "\n")


def latlon_cols(S, lat0, lon0, heading=True, hdg_override=None):
    glat, glon = enu_to_latlon(S["ge"], S["gn"], lat0, lon0)
    tlat, tlon = enu_to_latlon(S["te"], S["tn"], lat0, lon0)
    nofix = ~S["has_fix"]
    glat = np.where(nofix, np.nan, glat); glon = np.where(nofix, np.nan, glon)
    sig = np.where(nofix, np.nan, S["sig"])
    cols = {"time": (S["t"], "%.3f")}
    if heading:
        h = S["hdg"] % 360.0 if hdg_override is None else hdg_override
        cols["heading_deg"] = (h, "%.3f")
    cols.update({"speed": (S["spd"], "%.3f"), "gps_lat": (glat, "%.8f"), "gps_lon": (glon, "%.8f"),
                 "gps_sigma": (sig, "%.1f"), "true_lat": (tlat, "%.8f"), "true_lon": (tlon, "%.8f")})
    return cols


def drive_ferry(out, rng, clean=False):
    tr = Track()
    random_town(tr, rng, 200.0)
    # drive onto the ferry and park
    tr.speed_to(3.0, 1.0); tr.turn(90, 15); tr.cruise(6); tr.stop(30, 1.5)
    tr.mode = "road" if clean else "ferry"; tr.cflag = 1
    # the ferry pulls away: 5 m/s, a gentle 40 deg turn over the crossing, then slows
    tr.speed_to(5.0, 0.15); tr.cruise(60); tr.turn(40, 600); tr.cruise(60); tr.turn(-25, 500)
    tr.speed_to(0.0, 0.15)
    tr.cruise(20)
    tr.mode = "road"; tr.cflag = 0
    tr.speed_to(3.0, 1.0); tr.cruise(5); tr.turn(-90, 12)
    random_town(tr, rng, 750.0)
    tr.stop(5)
    S = sample(tr, 10, 1, rng)
    cols = latlon_cols(S, 59.4, 10.5)
    write_csv(os.path.join(out, "ferry%s.csv" % ("_clean" if clean else "")), cols)
    on = S["flag"] == 1
    moved = np.sum(np.hypot(np.diff(S["te"]), np.diff(S["tn"]))[on[1:]])
    return f"ferry: {on.sum() / 10:.0f} s on board, ferry carried the car {moved:.0f} m with speed 0"


def drive_snow(out, rng, clean=False):
    tr = Track()
    random_town(tr, rng, 600.0)
    tr.stop(5)
    S = sample(tr, 5, 1, rng)
    t, v, spd = S["t"], S["A"]["v"][S["idx"]], S["spd"].copy()
    acc = np.gradient(v, t)
    # wheel spin: episodes starting where the car pulls away or accelerates hard
    starts = np.where((acc > 1.0) & (v > 0.2) & (v < 12))[0]
    chosen, last = [], -1e9
    for i in starts:
        if t[i] - last > 40 and len(chosen) < 10:
            chosen.append(i); last = t[i]
    extra = 0.0
    for i in chosen:
        dur = rng.uniform(4, 12)
        k = (t >= t[i]) & (t < t[i] + dur)
        slip = rng.uniform(0.3, 0.6)
        prof = slip * np.sin(np.pi * (t[k] - t[i]) / dur) ** 0.5
        add = spd[k] * prof
        spd[k] += add
        extra += np.sum(add) / 5
    # wheel lock: when braking hard, speed reads 0 for 1-2.5 s while the car slides
    brakes = np.where((acc < -1.8) & (v > 4))[0]
    lockd, last = 0.0, -1e9
    nlock = 0
    for i in brakes:
        if t[i] - last > 40 and nlock < 6:
            dur = rng.uniform(1.0, 2.5)
            k = (t >= t[i]) & (t < t[i] + dur)
            lockd += np.sum(spd[k]) / 5
            spd[k] = 0.0
            last = t[i]; nlock += 1
    if not clean:
        S["spd"] = spd
    cols = latlon_cols(S, 61.2, 25.0)
    write_csv(os.path.join(out, "snow%s.csv" % ("_clean" if clean else "")), cols)
    dist = np.sum(v) / 5
    return (f"snow: {len(chosen)} spin episodes (+{extra:.0f} m), {nlock} lock-ups (-{lockd:.0f} m), "
            f"drive {dist:.0f} m")


def drive_utm(out, rng, clean=False):
    tr = Track(psi0=np.radians(30))
    random_town(tr, rng, 600.0)
    tr.stop(5)
    S = sample(tr, 2, 2, rng)
    gamma = np.radians(1.9)          # grid convergence: grid north is 1.9 deg off true north
    E0, N0 = 689234.0, 5335812.0
    if clean:
        gamma, E0, N0 = 0.0, 0.0, 0.0
    def to_grid(e, n):
        c, s = np.cos(gamma), np.sin(gamma)
        return E0 + c * e - s * n, N0 + s * e + c * n
    ge, gn = to_grid(S["ge"], S["gn"])
    te, tn = to_grid(S["te"], S["tn"])
    nofix = ~S["has_fix"]
    cols = {"time": (S["t"], "%.3f"), "heading_deg": (S["hdg"] % 360, "%.3f"),
            "speed": (S["spd"], "%.3f"),
            "gps_east": (np.where(nofix, np.nan, ge), "%.3f"),
            "gps_north": (np.where(nofix, np.nan, gn), "%.3f"),
            "gps_sigma": (np.where(nofix, np.nan, S["sig"]), "%.1f"),
            "true_east": (te, "%.3f"), "true_north": (tn, "%.3f")}
    write_csv(os.path.join(out, "utm%s.csv" % ("_clean" if clean else "")), cols)
    return "utm: E ~ 6.9e5 m, N ~ 5.34e6 m, grid convergence 1.9 deg"


def drive_carpark(out, rng, clean=False):
    tr = Track()
    random_town(tr, rng, 180.0)
    tr.speed_to(4.0, 1.5); tr.turn(90, 10); tr.cruise(5)
    tr.cflag = 1                                     # inside: no fixes
    tr.cruise(8); tr.turn(5 * 360, 12)               # up the helix, 5 clockwise circles
    tr.cruise(10); tr.turn(-90, 6); tr.cruise(4); tr.stop(90, 1.5)   # park
    tr.speed_to(3.0, 1.0); tr.turn(90, 6); tr.cruise(10)
    tr.turn(-5 * 360, 12)                            # down the other helix, counter-clockwise
    tr.cruise(8)
    tr.cflag = 2                                     # outside, fixes degraded for 15 s
    t_out = tr.ct
    tr.cruise(3); tr.turn(-90, 10)
    random_town(tr, rng, 660.0)
    tr.stop(5)
    # gyro: 0.8 % scale error, 0.03 deg/s bias, noise
    A = tr.arrays()
    dr_hz = 10
    step = int(round(1 / dr_hz / DT_INT))
    idx = np.arange(step - 1, len(A["t"]), step)
    t = np.round(A["t"][idx], 3)
    rate = np.degrees(np.diff(np.r_[0.0, A["psi"][idx]])) * dr_hz
    rate[0] = 0.0
    n = len(idx)
    yr = rate * 1.008 + 0.03 + rng.normal(0, 0.15, n)
    S = sample(tr, dr_hz, 1, rng)
    flag = S["flag"]
    if not clean:
        S["has_fix"] &= flag != 1
    bad = (flag == 2) & (t < t_out + 15) & (not clean)
    ramp = np.clip(1 - (t - t_out) / 15, 0, 1)
    S["ge"] = S["ge"] + bad * ramp * 18.0
    S["gn"] = S["gn"] - bad * ramp * 10.0
    S["sig"] = np.where(bad, 8.0, S["sig"])
    cols = latlon_cols(S, 52.5, 13.4, heading=False)
    cols = {"time": cols["time"], "yaw_rate_deg": (yr, "%.4f"), **{k: v for k, v in cols.items() if k != "time"}}
    write_csv(os.path.join(out, "carpark%s.csv" % ("_clean" if clean else "")), cols)
    nf = (flag == 1).sum() / dr_hz
    return f"carpark: {nf:.0f} s without fixes, 10 circles of r=12 m, gyro scale +0.8 %, out at {t_out:.0f} s"


def drive_spoof(out, rng, clean=False):
    tr = Track()
    random_town(tr, rng, 660.0)
    tr.stop(5)
    S = sample(tr, 5, 2, rng)
    t = S["t"]
    t0, T = 240.0, 240.0
    k = (t >= t0) & (t < t0 + T)
    d = np.where(k & (not clean), 0.333 * (t - t0), 0.0)
    ang = np.radians(60)
    S["ge"] = S["ge"] + d * np.sin(ang)
    S["gn"] = S["gn"] + d * np.cos(ang)
    cols = latlon_cols(S, 44.6, 33.5)
    write_csv(os.path.join(out, "spoof%s.csv" % ("_clean" if clean else "")), cols)
    return f"spoof: fixes dragged 0->80 m over {t0:.0f}-{t0 + T:.0f} s, then snap back"


def drive_wrap(out, rng, clean=False):
    tr = Track()
    random_town(tr, rng, 600.0)
    tr.stop(5)
    S = sample(tr, 10, 1, rng)
    h = S["hdg"] % 360.0
    half = S["t"] > S["t"][-1] / 2
    h = np.where(half & (not clean), (h + 180.0) % 360.0 - 180.0, h)
    cols = latlon_cols(S, 48.1, 11.6, hdg_override=h)
    write_csv(os.path.join(out, "wrap%s.csv" % ("_clean" if clean else "")), cols)
    return f"wrap: heading_deg 0..360 before {S['t'][-1] / 2:.0f} s, -180..180 after ({(h < 0).sum()} rows negative)"


def drive_long(out, rng, clean=False):
    """2 hours at 50 Hz DR / 1 Hz GPS: does the command finish, how long, how much memory."""
    if clean:
        return ""
    tr = Track()
    random_town(tr, rng, 7200.0)
    tr.stop(5)
    S = sample(tr, 50, 1, rng)
    cols = latlon_cols(S, 50.1, 8.7)
    write_csv(os.path.join(out, "long50hz.csv"), cols)
    return f"long50hz: {S['t'][-1]:.0f} s at 50 Hz, {len(S['t'])} rows"


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    out = args[0] if args else "."
    os.makedirs(out, exist_ok=True)
    for i, f in enumerate([drive_ferry, drive_snow, drive_utm, drive_carpark, drive_spoof, drive_wrap] + ([drive_long] if '--long' in sys.argv else [])):
        for clean in (False, True):          # *_clean.csv: the same drive, same noise, no fault
            rng = np.random.default_rng(7000 + i)
            msg = f(out, rng, clean)
            if not clean:
                print(msg)


if __name__ == "__main__":
    main()
