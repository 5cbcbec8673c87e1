"""Convert the phone app's log (sim_obd.py's files) into filterwnn's drive CSV, carefully, and write one
CSV per realistic mistake.

    python convert.py --log LOGDIR --out OUTDIR [--rate 10]

careful.csv: one row per DR sample on a regular grid (--rate Hz) on the phone's clock, in epoch seconds with
milliseconds; `speed` = OBD PID 0x0D km/h / 3.6 linearly interpolated onto the grid (the adapter's hangs
bridged by that interpolation); `yaw_rate` (rad/s, clockwise positive) = minus the gyro's rate about the
vertical (gravity from the accelerometer at the standstills, Android's axes counter-clockwise positive),
each row the mean of the gyro rows within half a row's interval of its time; each GPS fix on a row of its own
at its own time (heading/speed empty) with `gps_lat`, `gps_lon`, `gps_sigma` = Android accuracy (68 % radius)
/ 1.51; truth `true_lat`/`true_lon` on the DR rows (from truth.csv, which a real user would not have).
Every variant is the careful file with one thing done the way a user plausibly gets it wrong.
"""
import argparse
import csv
import json
import os

import numpy as np


def load(path, delim=","):
    with open(path) as f:
        r = csv.reader(f, delimiter=delim)
        head = next(r)
        rows = list(r)
    return head, rows


def num(rows, i):
    return np.array([float(x[i]) for x in rows])


def window_mean(t_src, x_src, t_dst, half):
    """Mean of x_src over |t_src - t| < half for each t in t_dst (interpolated where none)."""
    cs = np.concatenate([[0.0], np.cumsum(x_src)])
    lo = np.searchsorted(t_src, t_dst - half, side="left")
    hi = np.searchsorted(t_src, t_dst + half, side="left")
    cnt = hi - lo
    out = np.full(len(t_dst), np.nan)
    ok = cnt > 0
    out[ok] = (cs[hi[ok]] - cs[lo[ok]]) / cnt[ok]
    if (~ok).any():
        out[~ok] = np.interp(t_dst[~ok], t_src, x_src)
    return out


def circ_window_mean(t_src, deg_src, t_dst, half):
    s = window_mean(t_src, np.sin(np.deg2rad(deg_src)), t_dst, half)
    c = window_mean(t_src, np.cos(np.deg2rad(deg_src)), t_dst, half)
    return np.mod(np.rad2deg(np.arctan2(s, c)), 360.0)


def fmt(x, spec):
    if x is None or (isinstance(x, float) and np.isnan(x)):
        return ""
    return format(x, spec)


def write_drive(path, dr_t, dr_cols, fix_t=None, fix_cols=None, time_spec=".3f", extra_rows=None,
                fix_on_dr_rows=None):
    """dr_cols/fix_cols: {name: (array, format spec)}. Fixes on rows of their own unless fix_on_dr_rows
    gives {name: (array on the DR rows with NaN where none, spec)}."""
    names = ["time"] + list(dr_cols)
    if fix_cols:
        names += [k for k in fix_cols if k not in names]
    if fix_on_dr_rows:
        names += [k for k in fix_on_dr_rows if k not in names]
    rows = []
    for i, t in enumerate(dr_t):
        d = {k: fmt(float(v[0][i]), v[1]) for k, v in dr_cols.items()}
        if fix_on_dr_rows:
            d.update({k: fmt(float(v[0][i]), v[1]) for k, v in fix_on_dr_rows.items()})
        rows.append((t, 0, d))
    if fix_cols:
        for i, t in enumerate(fix_t):
            rows.append((t, 1, {k: fmt(float(v[0][i]), v[1]) for k, v in fix_cols.items()}))
    rows.sort(key=lambda r: (r[0], r[1]))
    if extra_rows:
        rows = extra_rows(rows)
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for t, _, d in rows:
            f.write(format(t, time_spec) + "," + ",".join(d.get(k, "") for k in names[1:]) + "\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--log", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--rate", type=float, default=10.0)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    L = lambda n: os.path.join(a.log, n)
    notes = {}

    # ---------------- read the app's files (ms -> s on the phone's clock)
    _, g = load(L("gps.csv"))
    t_fix = num(g, 0) / 1000.0
    lat, lon, acc68 = num(g, 1), num(g, 2), num(g, 3)
    gspeed, gbearing = num(g, 5), num(g, 6)
    _, gy = load(L("gyroscope.csv"))
    t_gy = num(gy, 0) / 1000.0
    W = np.stack([num(gy, 1), num(gy, 2), num(gy, 3)], axis=1)
    _, ac = load(L("accelerometer.csv"))
    t_ac = num(ac, 0) / 1000.0
    A = np.stack([num(ac, 1), num(ac, 2), num(ac, 3)], axis=1)
    _, ori = load(L("orientation.csv"))
    t_or, azim = num(ori, 0) / 1000.0, num(ori, 1)
    _, ob = load(L("obd.csv"), ";")
    ob = [r for r in ob if r[1].upper() == "0X0D"]          # vehicle speed only
    t_obd = np.array([float(r[0]) for r in ob]) / 1000.0
    kmh = np.array([float(r[3]) for r in ob])
    _, tr = load(L("truth.csv"))
    t_tr = num(tr, 0) / 1000.0
    tr_lat, tr_lon = num(tr, 1), num(tr, 2)

    # ---------------- the DR grid: regular, on the phone's clock, inside the OBD and gyro spans
    dt = 1.0 / a.rate
    t_start = np.ceil(max(t_obd[0], t_gy[0]) / dt) * dt + dt
    t_end = np.floor(min(t_obd[-1], t_gy[-1]) / dt) * dt
    tg = np.round(np.arange(t_start, t_end + dt / 2, dt), 3)
    speed = np.interp(tg, t_obd, kmh) / 3.6

    # ---------------- the vertical from gravity: accelerometer mean where the OBD speed reads 0
    still_ac = np.interp(t_ac, t_obd, kmh) == 0
    gvec = A[still_ac].mean(axis=0)
    up = gvec / np.linalg.norm(gvec)
    notes["up_unit_phone_frame"] = up.round(4).tolist()
    notes["gravity_norm"] = round(float(np.linalg.norm(gvec)), 3)
    w_up = W @ up                                   # CCW about the vertical (Android's right-hand axes)
    yaw_cw = -window_mean(t_gy, w_up, tg, dt / 2)   # rad/s, clockwise positive

    tr_lat_g = np.interp(tg, t_tr, tr_lat)
    tr_lon_g = np.interp(tg, t_tr, tr_lon)
    fix = {"gps_lat": (lat, ".7f"), "gps_lon": (lon, ".7f"), "gps_sigma": (acc68 / 1.51, ".2f")}
    truth = {"true_lat": (tr_lat_g, ".8f"), "true_lon": (tr_lon_g, ".8f")}
    in_span = (t_fix > tg[0]) & (t_fix < tg[-1])
    tf = t_fix[in_span]
    fixc = {k: (v[0][in_span], v[1]) for k, v in fix.items()}

    def base(**over):
        cols = {"yaw_rate": (yaw_cw, ".6f"), "speed": (speed, ".3f")}
        cols.update(truth)
        for k, v in over.items():
            if v is None:
                cols.pop(k, None)
            else:
                cols[k] = v
        return cols

    out = lambda n: os.path.join(a.out, n + ".csv")
    write_drive(out("careful"), tg, base(), tf, fixc)
    variants = {"careful": "the careful conversion"}

    def V(name, desc, *args, **kw):
        variants[name] = desc
        write_drive(out(name), *args, **kw)

    # 1 speed left in km/h
    V("speed_kmh", "OBD speed left in km/h in `speed`", tg, base(speed=(speed * 3.6, ".3f")), tf, fixc)
    # 2 the raw z axis (a phone lying flat would turn about z), Android sign flipped
    yaw_z = -window_mean(t_gy, W[:, 2], tg, dt / 2)
    V("gyro_raw_z", "phone gyro z axis as the yaw rate (sign flipped to clockwise), the 30 deg tilt ignored",
      tg, base(yaw_rate=(yaw_z, ".6f")), tf, fixc)
    # 3 Android's counter-clockwise sign kept
    V("gyro_ccw", "rate about the vertical in Android's counter-clockwise sign", tg,
      base(yaw_rate=(-yaw_cw, ".6f")), tf, fixc)
    # 4 the axis nearest the vertical (the docs' advice for an upright phone), not the vertical itself
    k_near = int(np.argmax(np.abs(up)))
    yaw_near = -np.sign(up[k_near]) * window_mean(t_gy, W[:, k_near], tg, dt / 2)
    notes["nearest_axis"] = "xyz"[k_near]
    V("gyro_nearest_axis", f"the phone axis nearest the vertical ({'xyz'[k_near]}) as the yaw rate", tg,
      base(yaw_rate=(yaw_near, ".6f")), tf, fixc)
    # 5 time left in epoch milliseconds
    V("time_ms", "time left in epoch milliseconds", tg * 1000, base(), tf * 1000, fixc, time_spec=".0f")
    # 6 DR rows at the OBD poll times, no resampling
    tp = t_obd[(t_obd > t_gy[0] + 0.5) & (t_obd < t_gy[-1] - 0.5)]
    half = np.concatenate([[0.15], np.diff(tp) / 2])
    # the gyro mean over each poll's preceding interval
    cs = np.concatenate([[0.0], np.cumsum(w_up)])
    lo = np.searchsorted(t_gy, tp - 2 * half)
    hi = np.searchsorted(t_gy, tp)
    yaw_p = -(cs[hi] - cs[lo]) / np.maximum(hi - lo, 1)
    tfp = t_fix[(t_fix > tp[0]) & (t_fix < tp[-1])]
    fixp = {k: (v[0][(t_fix > tp[0]) & (t_fix < tp[-1])], v[1]) for k, v in fix.items()}
    V("obd_poll_rows", "DR rows at the OBD poll times (2-4 Hz, jittered, adapter hangs), not resampled", tp,
      {"yaw_rate": (yaw_p, ".6f"), "speed": (np.interp(tp, t_obd, kmh) / 3.6, ".3f"),
       "true_lat": (np.interp(tp, t_tr, tr_lat), ".8f"), "true_lon": (np.interp(tp, t_tr, tr_lon), ".8f")},
      tfp, fixp)
    # 7 grid kept but the rows inside the adapter's hangs dropped (no speed there)
    last_poll = t_obd[np.maximum(np.searchsorted(t_obd, tg, side="right") - 1, 0)]
    next_poll = t_obd[np.minimum(np.searchsorted(t_obd, tg, side="left"), len(t_obd) - 1)]
    keep = (next_poll - last_poll) < 0.9
    notes["rows_dropped_in_hangs"] = int((~keep).sum())
    V("obd_gaps_left", "the adapter's 1-3 s hangs left as gaps (grid rows without an OBD poll dropped)",
      tg[keep], {k: (v[0][keep], v[1]) for k, v in base().items()}, tf, fixc)
    # 8 GPS bearing as heading (held onto the grid)
    idx = np.maximum(np.searchsorted(t_fix, tg, side="right") - 1, 0)
    V("gps_bearing_heading", "GPS bearing (held) as heading_deg instead of the gyro", tg,
      base(yaw_rate=None, heading_deg=(gbearing[idx], ".1f")), tf, fixc)
    # 9 fused orientation azimuth (magnetometer) as heading
    az = circ_window_mean(t_or, azim, tg, dt / 2)
    V("fused_azimuth_heading", "Android orientation azimuth (magnetic, fused) as heading_deg", tg,
      base(yaw_rate=None, heading_deg=(az, ".2f")), tf, fixc)
    # 10 the 68 % radius given as the per-axis sigma
    V("accuracy_as_sigma", "Android accuracy (68 % radius) given as gps_sigma undivided", tg, base(), tf,
      dict(fixc, gps_sigma=(acc68[in_span], ".2f")))
    # 11 accuracy taken for a 95 % radius
    V("accuracy_as_95", "accuracy taken for a 95 % radius (divided by 2.45)", tg, base(), tf,
      dict(fixc, gps_sigma=(acc68[in_span] / 2.45, ".2f")))
    # 12 accuracy in gps_hdop
    V("accuracy_as_hdop", "accuracy given as gps_hdop (taken for Torque's HDOP)", tg, base(), tf,
      {"gps_lat": fixc["gps_lat"], "gps_lon": fixc["gps_lon"], "gps_hdop": (acc68[in_span], ".1f")})

    # 13 duplicated rows (a merge that repeats every 50th DR row)
    def dup(rows):
        outr = []
        for i, r in enumerate(rows):
            outr.append(r)
            if r[1] == 0 and i % 50 == 0:
                outr.append(r)
        return outr
    V("duplicated_rows", "every 50th DR row written twice (a join's duplicates)", tg, base(), tf, fixc,
      extra_rows=dup)
    # 14 speed as a zero-order hold of the polls
    ip = np.maximum(np.searchsorted(t_obd, tg, side="right") - 1, 0)
    V("speed_zoh", "OBD speed held (previous poll) instead of interpolated", tg,
      base(speed=(kmh[ip] / 3.6, ".3f")), tf, fixc)
    # 15 rad/s written to yaw_rate_deg
    V("yaw_rad_in_deg_col", "yaw rate in rad/s written to yaw_rate_deg", tg,
      base(yaw_rate=None, yaw_rate_deg=(yaw_cw, ".6f")), tf, fixc)
    # 16 the last fix carried forward on every DR row (Torque's export)
    ifx = np.searchsorted(t_fix, tg, side="right") - 1
    okf = ifx >= 0
    lat_r = np.where(okf, lat[np.maximum(ifx, 0)], np.nan)
    lon_r = np.where(okf, lon[np.maximum(ifx, 0)], np.nan)
    sig_r = np.where(okf, acc68[np.maximum(ifx, 0)] / 1.51, np.nan)
    V("gps_every_row", "last fix carried forward onto every DR row (a logger's wide export)", tg, base(),
      fix_on_dr_rows={"gps_lat": (lat_r, ".7f"), "gps_lon": (lon_r, ".7f"), "gps_sigma": (sig_r, ".2f")})
    # 17 GNSS speed as the speed
    V("gps_speed_as_speed", "the phone's GPS speed (interpolated) instead of the OBD speed", tg,
      base(speed=(np.interp(tg, t_fix, gspeed), ".3f")), tf, fixc)
    # 18 heading integrated by the user from 0
    head_self = np.mod(np.rad2deg(np.concatenate([[0.0], np.cumsum(0.5 * (yaw_cw[1:] + yaw_cw[:-1]) * dt)])), 360)
    V("self_integrated_heading", "the user integrated the yaw rate into heading_deg starting at 0", tg,
      base(yaw_rate=None, heading_deg=(head_self, ".3f")), tf, fixc)
    # 19 lat/lon swapped
    V("latlon_swapped", "gps_lat and gps_lon swapped", tg, base(), tf,
      dict(fixc, gps_lat=fixc["gps_lon"], gps_lon=fixc["gps_lat"]))
    # 20 one row per sensor message: raw gyro rows (vertical rate), OBD rows, fix rows, stacked
    gsel = (t_gy > tg[0]) & (t_gy < tg[-1])
    osel = (t_obd > tg[0]) & (t_obd < tg[-1])
    rows_msg = []
    for t, w in zip(t_gy[gsel], -w_up[gsel]):
        rows_msg.append((t, 2, {"yaw_rate": format(w, ".6f")}))
    for t, s in zip(t_obd[osel], kmh[osel] / 3.6):
        rows_msg.append((t, 3, {"speed": format(s, ".3f"),
                                "true_lat": format(np.interp(t, t_tr, tr_lat), ".8f"),
                                "true_lon": format(np.interp(t, t_tr, tr_lon), ".8f")}))
    variants["stacked_messages"] = ("one row per sensor message: raw ~100 Hz gyro rows (yaw_rate only), OBD rows "
                                    "(speed only), fix rows, stacked")
    write_stacked(out("stacked_messages"), tf, fixc, rows_msg)
    # 21 time written with 10 significant digits (%.10g): every stamp cut to the second
    V("time_10g", "time written with %.10g (stamps cut to whole seconds)", tg, base(), tf, fixc,
      time_spec=".10g")
    # 22 speed cast to integer m/s
    V("speed_int_ms", "speed cast to whole m/s (int())", tg, base(speed=(np.floor(speed), ".0f")), tf, fixc)
    # 23 gyro sampled at the nearest row instead of averaged
    inn = np.clip(np.searchsorted(t_gy, tg), 0, len(t_gy) - 1)
    V("gyro_point_sample", "the gyro row nearest each DR time instead of the window's mean", tg,
      base(yaw_rate=(-w_up[inn], ".6f")), tf, fixc)
    # 24 the fix rows on the DR grid's nearest row (not a mistake per the docs; a control)
    near = np.clip(np.round((tf - tg[0]) / dt).astype(int), 0, len(tg) - 1)
    fr = {}
    for k, v in fixc.items():
        arr = np.full(len(tg), np.nan)
        arr[near] = v[0]
        fr[k] = (arr, v[1])
    V("fix_on_nearest_row", "control: each fix on the nearest DR row instead of a row of its own", tg, base(),
      fix_on_dr_rows=fr)

    with open(os.path.join(a.out, "variants.json"), "w") as f:
        json.dump({"variants": variants, "notes": notes, "rate_hz": a.rate, "dr_rows": len(tg),
                   "fixes": int(len(tf)), "t0": float(tg[0])}, f, indent=1)
    print(json.dumps(notes), len(variants), "files")


def write_stacked(path, tf, fixc, rows_msg):
    names = ["time", "yaw_rate", "speed", "gps_lat", "gps_lon", "gps_sigma", "true_lat", "true_lon"]
    rows = [(t, 1, {k: format(float(v[0][i]), v[1]) for k, v in fixc.items()}) for i, t in enumerate(tf)]
    rows = sorted(rows + rows_msg, key=lambda r: (r[0], r[1]))
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for t, _, d in rows:
            f.write(format(t, ".3f") + "," + ",".join(d.get(k, "") for k in names[1:]) + "\n")


if __name__ == "__main__":
    main()
