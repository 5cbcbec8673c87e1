"""Faults of real drive logs, each cut into one simulated drive and run as a user would (issue 23).

Run from the repository root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/log_faults.py

(``PYTHONPATH=<an older checkout>`` runs that version's command on the same variants.)

The drive: the phone analog of ``tests/_held_out_drives.py`` (seed 0), its first 360 s (10 Hz DR, 1 Hz
fixes, truth). Each variant is written as a CSV and run by ``filterwnn study dr --drive FILE --grade phone``
(20 outages of 30 s, or the starts given); each line gives the command's exit code, EKF-8's (and SUKF-8's)
median / max at the outage ends (m), its fixes column, and the warnings that name a cause (the
consistency monitor's are counted, not quoted).
"""

import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests"))

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.scenarios import en_to_latlon  # noqa: E402

N = 3600
LAT0, LON0 = 48.137, 11.575


def base():
    return {k: np.asarray(v[:N], dtype=float).copy() for k, v in held_out.columns("phone").items()}


def latlon(c):
    o = {k: c[k] for k in ("time", "heading", "speed")}
    o["gps_lat"], o["gps_lon"] = en_to_latlon(c["gps_east"], c["gps_north"], LAT0, LON0)
    o["gps_sigma"] = c["gps_sigma"]
    o["true_lat"], o["true_lon"] = en_to_latlon(c["true_east"], c["true_north"], LAT0, LON0)
    return o


def write(path, cols):
    def cell(v, c):
        if np.isnan(v):
            return ""
        if c == "time":
            return f"{v:.3f}"
        if c.endswith(("_lat", "_lon")):
            return f"{v:.8f}"
        return f"{v:.6g}" if c == "gps_sigma" else f"{v:.4f}"

    with open(path, "w") as fh:
        fh.write(",".join(cols) + "\n")
        for k in range(len(cols["time"])):
            fh.write(",".join(cell(cols[c][k], c) for c in cols) + "\n")
    return path


def variants():
    c = base()
    t, fk = c["time"], np.flatnonzero(np.isfinite(c["gps_east"]))
    yield "clean", c, ()
    e = {k: v.copy() for k, v in c.items()}
    e["time"] = e["time"] + 1.7e9
    yield "Unix-epoch times", e, ()
    s = {k: v.copy() for k, v in c.items()}
    for j in range(1, 11):  # the 120 s fix re-sent for 10 s at about 23 m/s
        for a in ("gps_east", "gps_north", "gps_sigma"):
            s[a][1200 + 10 * j] = s[a][1200]
    yield "clean, outages at 60, 129, 133, 200 s", c, ("--outage-starts", "60,129,133,200")
    yield "a stale fix re-sent for 10 s, same outages", s, ("--outage-starts", "60,129,133,200")
    n = latlon({k: v.copy() for k, v in c.items()})
    yield "lat/lon", n, ()
    n = latlon({k: v.copy() for k, v in c.items()})
    n["gps_lat"][fk[:3]] = n["gps_lon"][fk[:3]] = 0.0
    yield "lat/lon, the first 3 fixes at 0, 0 (null fixes)", n, ()
    d = {k: v.copy() for k, v in c.items()}
    sel = fk[(t[fk] >= 150) & (t[fk] < 180)]
    d["gps_east"][sel] += 90.0
    d["gps_north"][sel] -= 120.0
    yield "30 s of fixes 150 m off (another datum)", d, ()
    j = {k: v.copy() for k, v in c.items()}
    j["time"] = j["time"] + np.random.default_rng(7).uniform(-0.005, 0.005, N)
    yield "time stamps jittered by +-5 ms", j, ()
    j = {k: v.copy() for k, v in c.items()}
    j["time"] = j["time"] + np.random.default_rng(8).normal(0.0, 0.006, N)
    yield "time stamps jittered by 6 ms sd (intervals up to 27 % off)", j, ()
    lag = {k: v.copy() for k, v in c.items()}
    for g, tr in (("gps_east", "true_east"), ("gps_north", "true_north")):
        lag[g][fk] += c[tr][fk - 3] - c[tr][fk]
    yield "fixes 0.3 s old (a receiver's latency)", lag, ()
    yield "fixes 0.3 s old, --gps-latency 0.3", lag, ("--gps-latency", "0.3")
    z = {k: v.copy() for k, v in c.items()}
    z["speed"][np.sort(np.random.default_rng(9).choice(np.flatnonzero(c["speed"] > 3.0), 10, replace=False))] = 0.0
    yield "the speed 0 for one sample, 10 times while moving (a CAN frame lost and logged as 0)", z, ()


def main():
    tmp = tempfile.mkdtemp()
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    for i, (label, cols, extra) in enumerate(variants()):
        path = write(os.path.join(tmp, f"v{i}.csv"), cols)
        cmd = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--grade", "phone", "--no-figures", "--no-progress",
               "--jobs", "1", "--out", os.path.join(tmp, f"o{i}"), "--filters", "EKF-8,SUKF-8", *extra]
        if "--gps-latency" in extra and "--gps-latency" not in subprocess.run(
                cmd[:5] + ["--help"], capture_output=True, text=True, env=env, cwd=tmp).stdout:
            print(f"{label} | (no --gps-latency in this version)", flush=True)
            continue
        p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=tmp)  # not this checkout's by its cwd
        rows = {}
        for line in p.stdout.splitlines():
            cells = [x.strip() for x in line.split("|")]
            if len(cells) > 9 and cells[1] in ("EKF-8", "SUKF-8"):
                rows[cells[1]] = f"{cells[2]} / {cells[4]}" + (f" ({cells[9]})" if cells[1] == "EKF-8" else "")
        warned = [w for w in p.stderr.splitlines() if "warning" in w and "inconsistent" not in w]
        monitor = sum("inconsistent" in w for w in p.stderr.splitlines())
        print(f"{label} | rc {p.returncode} | EKF-8 {rows.get('EKF-8', '-')} | SUKF-8 {rows.get('SUKF-8', '-')} | "
              f"consistency warnings {monitor}", flush=True)
        for w in warned if p.returncode == 0 else p.stderr.strip().splitlines()[-1:]:
            print(f"    {w[:300]}", flush=True)


if __name__ == "__main__":
    main()
