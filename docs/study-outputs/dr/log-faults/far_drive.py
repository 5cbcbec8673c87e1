"""How far from the first fix can a lat/lon drive go before the reader's map hurts (stop 60)? An analog (seed s)
placed after a straight highway prefix of D km at a bearing (30 m/s, 3 m white fixes at 1 Hz), its truth integrated
on the WGS84 ellipsoid and its fixes' errors added in local metres; scored as the command does (EKF-8, phone grade,
20 outages of 30 s over the analog's part). With ``flat`` the same drive is written in metres (no map). Run from the
repository root::

    python docs/study-outputs/dr/log-faults/far_drive.py phone 0 0/0,100/0,60/45
    python docs/study-outputs/dr/log-faults/far_drive.py phone 0 100/0,60/45 flat
"""
import os
import sys
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "tests"))
import _held_out_drives as ho
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.scenarios import earth_radii
from filterwnn.studies.dr._real import real_drive_outages

FLAT = False


def ell_path(lat0, lon0, dE, dN):
    lat = np.empty(len(dE) + 1); lon = np.empty(len(dE) + 1); lat[0], lon[0] = lat0, lon0
    for k in range(len(dE)):
        la = np.deg2rad(lat[k]); rn, rm = earth_radii(la)
        lat[k + 1] = lat[k] + np.rad2deg(dN[k] / rm)
        lon[k + 1] = lon[k] + np.rad2deg(dE[k] / (rn * np.cos(la)))
    return lat, lon

def offset(lat, lon, e, n):
    la = np.deg2rad(lat); rn, rm = earth_radii(la)
    return lat + np.rad2deg(n / rm), lon + np.rad2deg(e / (rn * np.cos(la)))

def drive(name, seed, km, bearing, lat0=50.0):
    c = ho.columns(name, seed)
    te, tn = c["true_east"], c["true_north"]
    dt = np.median(np.diff(c["time"]))
    v = 30.0
    npre = int(round(km * 1000 / v / dt)) if km else 0
    b = np.deg2rad(bearing)
    dE = np.concatenate([np.full(npre, v * dt * np.sin(b)), np.diff(te)])
    dN = np.concatenate([np.full(npre, v * dt * np.cos(b)), np.diff(tn)])
    lat, lon = ell_path(lat0, 8.0, dE, dN)  # truth at each sample (npre + len(te))
    n = len(lat)
    fe = np.concatenate([np.zeros(npre), c["gps_east"] - te]); fn = np.concatenate([np.zeros(npre), c["gps_north"] - tn])
    glat, glon = offset(lat, lon, fe, fn)
    pre_fix = np.zeros(npre, bool); pre_fix[::int(round(1 / dt))] = True
    has = np.concatenate([pre_fix, np.isfinite(c["gps_east"])])
    rng = np.random.default_rng(1)
    pre_err = rng.normal(0, 3.0, (npre, 2))
    gl2, go2 = offset(lat[:npre], lon[:npre], pre_err[:, 0], pre_err[:, 1])
    glat[:npre], glon[:npre] = gl2, go2
    glat[~has] = np.nan; glon[~has] = np.nan
    mv = npre + int(np.flatnonzero(np.hypot(np.diff(te), np.diff(tn)) > 0.5 * dt)[0])
    h0 = c["heading"][mv - npre] - np.arctan2(dE[mv], dN[mv])
    heading = np.concatenate([np.full(npre, b + h0), c["heading"]])
    speed = np.concatenate([np.full(npre, v), c["speed"]])
    sig = np.concatenate([np.full(npre, 3.0), c["gps_sigma"]])
    t = np.arange(n) * dt
    if FLAT:
        E = np.concatenate([[0.0], np.cumsum(dE)]); N = np.concatenate([[0.0], np.cumsum(dN)])
        fe2, fn2 = fe.copy(), fn.copy(); fe2[:npre], fn2[:npre] = pre_err[:, 0], pre_err[:, 1]
        ge, gn = E + fe2, N + fn2; ge[~has] = np.nan; gn[~has] = np.nan
        return dict(time=t, heading=heading, speed=speed, gps_east=ge, gps_north=gn, gps_sigma=sig,
                    true_east=E, true_north=N), npre * dt, c["time"][-1]
    return dict(time=t, heading=heading, speed=speed, gps_lat=glat, gps_lon=glon, gps_sigma=sig,
                true_lat=lat, true_lon=lon), npre * dt, c["time"][-1]

def write(path, cols):
    names = list(cols)
    with open(path, "w") as fh:
        fh.write(",".join(names) + "\n")
        for k in range(len(cols["time"])):
            fh.write(",".join("" if np.isnan(cols[c][k]) else f"{cols[c][k]:.9f}" if c in ("gps_lat","gps_lon","true_lat","true_lon") else f"{cols[c][k]:.4f}" if c != "time" else f"{cols[c][k]:.6g}" for c in names) + "\n")
    return path

if __name__ == "__main__":
    import tempfile
    TMP = tempfile.mkdtemp()
    name = sys.argv[1]; seeds = [int(s) for s in sys.argv[2].split(",")]
    cases = [tuple(int(v) for v in c.split("/")) for c in sys.argv[3].split(",")]
    FLAT = len(sys.argv) > 4
    for seed in seeds:
        for km, bearing in cases:
            cols, t_pre, dur = drive(name, seed, km, bearing)
            p = write(os.path.join(TMP, f"{name}{seed}_{km}_{bearing}.csv"), cols)
            with warnings.catch_warnings(record=True) as w:
                warnings.simplefilter("always")
                run = read_drive_csv(p)
                starts = t_pre + np.linspace(0.0, dur - 31.0, 20)
                res = real_drive_outages(run, filters=("EKF-8",), grade="phone", use_gps_sigma=True, starts=starts)
            e = res["EKF-8"]
            print(f"{name} seed {seed} prefix {km:>3} km bearing {bearing:>2}{' (in metres, no map)' if FLAT else ''}: EKF-8 {np.median(e):6.2f} / {e.max():6.2f}"
                  f"  ({len(w)} warnings{': ' + str(w[0].message)[:150] if w else ''})", flush=True)
