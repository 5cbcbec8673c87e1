"""Convert the u-blox CSVs (nav_pvt.csv, esf_meas.csv, truth.csv) into filterwnn drive CSVs.

`convert(logdir, outdir)` writes the careful conversion (drive_ok.csv) and one CSV per user mistake
(drive_<mistake>.csv). Every conversion here is done from the README / docs/gps_dr.md alone.

Careful conversion:
  * ESF sTtag (ms, module clock, wraps at 2^32) -> unwrap -> seconds; the offset to GPS time is found
    by matching the wheel-tick speed against NAV-PVT gSpeed (coarse 0.5 s grid, then 5 ms).
  * gyro z (dataType 5): 24-bit two's complement, * 2^-12 -> deg/s; u-blox vehicle frame is z down,
    so positive = clockwise = the reader's convention; each DR row gets the mean of the gyro samples
    within half a row interval of its time (the docs' advice for a 50-100 Hz gyro).
  * wheel ticks (dataType 8, 9): bits 0-22 a counter (unwrapped mod 2^23), bit 23 direction;
    ticks * 1.93 m / 96 -> metres; odometer = mean of rear-left and rear-right.
  * DR rows at the wheel-tick messages (10 Hz): time (GPS s of week), yaw_rate_deg, odometer, truth.
  * fix rows of their own at iTOW / 1000 s: only fixType 3 or 4 with gnssFixOK; lat/lon * 1e-7;
    gps_sigma = hAcc / 1000 / sqrt(2) (hAcc taken as a DRMS-like 1-sigma radius -> per axis).
"""
import os

import numpy as np

CIRC, TPR = 1.93, 96


def read_csv(path):
    a = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding=None)
    return a


def unwrap_counter(x, modulus):
    x = np.asarray(x, dtype=np.int64)
    d = np.diff(x)
    d = np.where(d < -modulus // 2, d + modulus, d)
    d = np.where(d > modulus // 2, d - modulus, d)
    return np.concatenate([[x[0]], x[0] + np.cumsum(d)])


def sign24(raw):
    raw = np.asarray(raw, dtype=np.int64)
    return np.where(raw >= 2 ** 23, raw - 2 ** 24, raw)


def load(logdir):
    pvt = read_csv(os.path.join(logdir, "nav_pvt.csv"))
    esf = read_csv(os.path.join(logdir, "esf_meas.csv"))
    truth = read_csv(os.path.join(logdir, "truth.csv"))
    return pvt, esf, truth


def esf_parts(esf, unwrap_time=True, unwrap_ticks=True):
    st = esf["sTtag"].astype(np.int64)
    ts = (unwrap_counter(st, 2 ** 32) if unwrap_time else st) / 1000.0
    typ = esf["dataType"]
    raw = esf["dataField"].astype(np.int64)
    g = typ == 5
    L, R = typ == 8, typ == 9
    out = dict(tg=ts[g], graw=raw[g], tw=ts[L], tl=raw[L], tr=raw[R])
    assert np.all(ts[L] == ts[R])
    for key, sel in (("cl", L), ("cr", R)):
        cnt = raw[sel] & 0x7FFFFF
        out[key] = unwrap_counter(cnt, 2 ** 23) if unwrap_ticks else cnt
        out[key + "_dir"] = raw[sel] >> 23
    return out


def find_clock_offset(tw, dist, itow_s, gspeed):
    """GPS time = sensor time + off: match the wheel speed to gSpeed."""
    v = np.gradient(dist, tw)
    base = itow_s[0] - tw[0]
    best = None
    for grid in (np.arange(-300, 300, 0.5), None):
        if grid is None:
            grid = np.arange(best - 1.0, best + 1.0, 0.005)
        else:
            grid = base + grid
        cost = []
        for off in grid:
            vi = np.interp(itow_s - off, tw, v, left=np.nan, right=np.nan)
            ok = np.isfinite(vi)
            cost.append(np.mean((vi[ok] - gspeed[ok]) ** 2) if ok.sum() > 0.5 * len(vi) else np.nan)
        best = grid[int(np.nanargmin(cost))]
    return best


def write_drive(path, dr, fixes, truth_cols=True):
    """dr: dict of DR columns (time + others), fixes: dict(time, gps_lat, gps_lon, gps_sigma...)."""
    cols = ["time"] + [c for c in dr if c != "time"] + [c for c in fixes if c != "time" and c not in dr]
    rows = []
    n = len(dr["time"])
    for i in range(n):
        rows.append((dr["time"][i], {c: dr[c][i] for c in dr}))
    for i in range(len(fixes["time"])):
        rows.append((fixes["time"][i], {c: fixes[c][i] for c in fixes}))
    rows.sort(key=lambda r: r[0])
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        for _, r in rows:
            vals = []
            for c in cols:
                if c in r:
                    x = r[c]
                    vals.append(repr(int(x)) if isinstance(x, (np.integer, int)) else f"{x:.10g}" if c not in (
                        "time", "gps_lat", "gps_lon", "true_lat", "true_lon", "odometer") else f"{x:.9f}")
                else:
                    vals.append("")
            f.write(",".join(vals) + "\n")


def convert(logdir, outdir):
    os.makedirs(outdir, exist_ok=True)
    pvt, esf, truth = load(logdir)
    e = esf_parts(esf)
    itow_s = pvt["iTOW"] / 1000.0
    gsp = pvt["gSpeed"] / 1000.0
    dist_l = (e["cl"] - e["cl"][0]) * CIRC / TPR
    dist_r = (e["cr"] - e["cr"][0]) * CIRC / TPR
    odo = 0.5 * (dist_l + dist_r)
    off = find_clock_offset(e["tw"], odo, itow_s, gsp)
    tw_gps = e["tw"] + off
    tg_gps = e["tg"] + off
    gyro = sign24(e["graw"]) / 4096.0
    # each DR row: mean of gyro samples within +-0.05 s
    half = 0.05
    lo = np.searchsorted(tg_gps, tw_gps - half)
    hi = np.searchsorted(tg_gps, tw_gps + half)
    cs = np.concatenate([[0], np.cumsum(gyro)])
    yaw = (cs[hi] - cs[lo]) / np.maximum(hi - lo, 1)
    keep = hi > lo
    t_dr = tw_gps[keep]
    tt = truth["t_gps"]
    dr = dict(time=t_dr, yaw_rate_deg=yaw[keep], odometer=odo[keep],
              true_lat=np.interp(t_dr, tt, truth["lat"]), true_lon=np.interp(t_dr, tt, truth["lon"]))
    good = (pvt["gnssFixOK"] == 1) & np.isin(pvt["fixType"], [3, 4])
    fx = dict(time=itow_s[good], gps_lat=pvt["lat"][good] * 1e-7, gps_lon=pvt["lon"][good] * 1e-7,
              gps_sigma=pvt["hAcc"][good] / 1000.0 / np.sqrt(2))
    info = dict(clock_offset_s=float(off), n_dr=len(t_dr), n_fix=int(good.sum()),
                n_receiver_dr=int((pvt["fixType"] == 1).sum()), n_nofix=int((pvt["fixType"] == 0).sum()))

    def var(name, dr_over=None, fx_over=None, dr_drop=(), fx_sel=None):
        d = {k: v for k, v in dr.items() if k not in dr_drop}
        d.update(dr_over or {})
        f = dict(fx) if fx_sel is None else {k: v for k, v in fx_sel.items()}
        f.update(fx_over or {})
        path = os.path.join(outdir, f"drive_{name}.csv")
        write_drive(path, d, f)
        return path

    paths = {}
    paths["ok"] = var("ok")
    # a careful user who also removes the gyro bias measured over the first standstill
    still = (odo[keep] == odo[keep][0]) & (t_dr < t_dr[0] + 7.5)
    b0 = float(np.mean(yaw[keep][still]))
    info["gyro_bias_at_start_deg_s"] = b0
    paths["ok_bias_removed"] = var("ok_bias_removed", dr_over=dict(yaw_rate_deg=yaw[keep] - b0))

    # --- mistakes
    all_ok = pvt["gnssFixOK"] >= 0
    rdr = all_ok & (pvt["fixType"] > 0)  # fixType 1 (receiver DR) kept as fixes
    paths["receiver_dr_as_fixes"] = var("receiver_dr_as_fixes", fx_sel=dict(
        time=itow_s[rdr], gps_lat=pvt["lat"][rdr] * 1e-7, gps_lon=pvt["lon"][rdr] * 1e-7,
        gps_sigma=pvt["hAcc"][rdr] / 1000.0 / np.sqrt(2)))
    paths["nofix_rows_kept"] = var("nofix_rows_kept", fx_sel=dict(
        time=itow_s, gps_lat=pvt["lat"] * 1e-7, gps_lon=pvt["lon"] * 1e-7, gps_sigma=pvt["hAcc"] / 1000.0 / np.sqrt(2)))
    paths["latlon_1e7"] = var("latlon_1e7", fx_over=dict(gps_lat=pvt["lat"][good].astype(np.int64),
                                                          gps_lon=pvt["lon"][good].astype(np.int64)),
                              dr_drop=("true_lat", "true_lon"))
    paths["latlon_1e7_truth_too"] = var("latlon_1e7_truth_too", fx_over=dict(
        gps_lat=pvt["lat"][good].astype(np.int64), gps_lon=pvt["lon"][good].astype(np.int64)),
        dr_over=dict(true_lat=np.round(dr["true_lat"] * 1e7), true_lon=np.round(dr["true_lon"] * 1e7)))
    paths["hacc_mm"] = var("hacc_mm", fx_over=dict(gps_sigma=pvt["hAcc"][good].astype(np.int64)))
    paths["hacc_not_divided"] = var("hacc_not_divided", fx_over=dict(gps_sigma=pvt["hAcc"][good] / 1000.0))
    gs_dr = np.interp(t_dr, itow_s, pvt["gSpeed"])
    paths["gspeed_mm_as_speed"] = var("gspeed_mm_as_speed", dr_over=dict(speed=gs_dr), dr_drop=("odometer",))
    paths["gspeed_ms_as_speed"] = var("gspeed_ms_as_speed", dr_over=dict(speed=gs_dr / 1000.0), dr_drop=("odometer",))
    # headMot as heading_deg (sample-and-hold to the DR rows)
    j = np.clip(np.searchsorted(itow_s, t_dr, side="right") - 1, 0, len(itow_s) - 1)
    paths["headmot_raw_as_heading_deg"] = var("headmot_raw_as_heading_deg",
                                             dr_over=dict(heading_deg=pvt["headMot"][j].astype(np.int64)),
                                             dr_drop=("yaw_rate_deg",))
    paths["headmot_deg_as_heading_deg"] = var("headmot_deg_as_heading_deg",
                                             dr_over=dict(heading_deg=pvt["headMot"][j] * 1e-5),
                                             dr_drop=("yaw_rate_deg",))
    paths["gyro_raw_counts"] = var("gyro_raw_counts", dr_over=dict(yaw_rate_deg=yaw[keep] * 4096.0))
    g_nosign = e["graw"] / 4096.0
    cs2 = np.concatenate([[0], np.cumsum(g_nosign)])
    paths["gyro_no_sign_extension"] = var("gyro_no_sign_extension", dr_over=dict(
        yaw_rate_deg=((cs2[hi] - cs2[lo]) / np.maximum(hi - lo, 1))[keep]))
    paths["gyro_in_yaw_rate_rad_column"] = var("gyro_in_yaw_rate_rad_column", dr_over=dict(yaw_rate=yaw[keep]),
                                              dr_drop=("yaw_rate_deg",))
    paths["gyro_sign_flipped"] = var("gyro_sign_flipped", dr_over=dict(yaw_rate_deg=-yaw[keep]))
    # clock: ESF time not aligned to GPS
    t_sens = e["tw"][keep]
    tr_sens = dict(true_lat=np.interp(t_sens + off, tt, truth["lat"]), true_lon=np.interp(t_sens + off, tt, truth["lon"]))
    paths["esf_clock_unaligned"] = var("esf_clock_unaligned", dr_over=dict(time=t_sens, **tr_sens))
    for sh in (2.0, 5.0, 30.0, 3600.0):
        # DR rows shifted by sh seconds (a partial alignment); truth kept with the DR samples' sensor time
        paths[f"esf_clock_off_{sh:g}s"] = var(f"esf_clock_off_{sh:g}s", dr_over=dict(
            time=t_dr + sh, true_lat=dr["true_lat"], true_lon=dr["true_lon"]))
    # sTtag wrap not handled
    e_nw = esf_parts(esf, unwrap_time=False)
    paths["sttag_wrap_not_handled"] = var("sttag_wrap_not_handled", dr_over=dict(time=e_nw["tw"][keep] + off))
    # tick counter wrap not handled
    e_nt = esf_parts(esf, unwrap_ticks=False)
    odo_nw = 0.5 * ((e_nt["cl"] - e_nt["cl"][0]) + (e_nt["cr"] - e_nt["cr"][0])) * CIRC / TPR
    paths["tick_wrap_not_handled"] = var("tick_wrap_not_handled", dr_over=dict(odometer=odo_nw[keep]))
    paths["one_wheel_left"] = var("one_wheel_left", dr_over=dict(odometer=dist_l[keep]))
    paths["ticks_not_scaled"] = var("ticks_not_scaled", dr_over=dict(
        odometer=0.5 * ((e["cl"] - e["cl"][0]) + (e["cr"] - e["cr"][0]))[keep].astype(float)))
    # speed per message from ticks as 'speed' (m per 0.1 s, i.e. not divided by dt)
    dd = np.diff(odo[keep], prepend=odo[keep][0])
    paths["tick_delta_as_speed"] = var("tick_delta_as_speed", dr_over=dict(speed=dd), dr_drop=("odometer",))
    # iTOW in ms left as time (fixes in ms; DR rows put in ms too)
    paths["itow_ms_as_time"] = var("itow_ms_as_time", dr_over=dict(time=t_dr * 1000.0),
                                   fx_over=dict(time=itow_s[good] * 1000.0))
    # iTOW in ms for the fixes only, DR rows in s
    paths["itow_ms_fixes_only"] = var("itow_ms_fixes_only", fx_over=dict(time=itow_s[good] * 1000.0))
    # survey/phone common: receiver DR fixes kept AND their 'hAcc' as is
    return paths, info


if __name__ == "__main__":
    import json
    import sys
    p, i = convert(sys.argv[1], sys.argv[2])
    print(json.dumps(i, indent=1))
    print("\n".join(sorted(p)))
