"""Drives nobody here drew (issue 23, stop 44): random drives over a wide range of rates, routes, sensors and
fixes, each run as a user would run their own log, to find what the three analogs never tried.

Run from the repository root, one BLAS thread, two drives at a time::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/random_drives.py --seeds 0-99 > docs/study-outputs/dr/random-drives/random_drives.txt

Each drive (seed ``s`` draws from ``SeedSequence([23, 44, s])``; the draws and the flags below were fixed
before the first run, see ``RUN.md``) is written as a drive CSV with its truth and run through
``filterwnn study dr --drive FILE --grade G --no-figures`` for G in phone and survey (20 outages of 30 s, every
filter). Each line: the draw, then per grade the exit code, the median / max at the outage ends (m) of dead
reckoning alone from the true start and of each 8-state kind, the kinds that warned, and the flags:

* ``CRASH``: an exit code other than 0, or a traceback;
* ``SILENT k``: kind ``k`` ends worse than dead reckoning from the true start plus the fixes' own error
  (its median past DR-mech's median + 2 x the fixes' median horizontal error, or its max past DR-mech's max +
  2 x their 95th percentile) and nothing warned of it (neither kind ``k`` nor the drive reader);
* ``WARNED k``: the same, with a warning;
* ``SPLIT``: the kinds' medians differ by more than 5 m and a factor of 1.5 (one kind wrong alone).
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests"))

import _held_out_drives as held_out  # noqa: E402

KINDS = ("EKF-8", "UKF-8", "SUKF-8")
FILTERS = ("DR-mech",) + KINDS


#: protocol 3's faults: ``(name, probability)``, each drawn on its own (see :func:`faults`)
FAULTS = (("gyro_scale", 0.3), ("gps_latency", 0.3), ("speed_latency", 0.2), ("cutoff", 0.3), ("dropouts", 0.3),
          ("spikes", 0.2), ("stop_steps", 0.3), ("far_better", 0.3), ("held", 0.15))


def faults(seed):
    """Protocol 3's sensor and log faults for drive ``seed``, from ``SeedSequence([23, 44, seed, 3])``: each of
    :data:`FAULTS` on with its probability, its size drawn whether on or not (so the draws do not depend on which
    are on). ``gyro_scale``: the gyro turns 1 +- 1-3 % times the car; ``gps_latency``: fixes 0.2-1 s late;
    ``speed_latency``: the speed 0.2-0.6 s late; ``cutoff``: the speed reads 0 under 0.3-1 m/s; ``dropouts``:
    0.1-1 % of the samples at 2 m/s or more read 0; ``spikes``: 5-20 samples read 70.8 m/s and 5-20 headings
    turned by 90-180 degrees; ``stop_steps``: the heading steps by 0.5-2 degrees (either way) halfway through
    each stop of 5 s or more; ``far_better``: 1-5 % of the fixes report a sigma 5-10 times smaller than their
    street's (in pairs on half of such drives); ``held``: the log carries each fix forward to every DR row."""
    rng = np.random.default_rng(np.random.SeedSequence([23, 44, seed, 3]))
    on = {name: bool(rng.random() < p) for name, p in FAULTS}
    size = dict(gyro_scale=rng.choice([-1, 1]) * rng.uniform(0.01, 0.03), gps_latency=rng.uniform(0.2, 1.0),
                speed_latency=rng.uniform(0.2, 0.6), cutoff=rng.uniform(0.3, 1.0), dropouts=rng.uniform(0.001, 0.01),
                spikes=(int(rng.integers(5, 21)), int(rng.integers(5, 21))), stop_steps=rng.uniform(0.5, 2.0),
                far_better=(rng.uniform(0.01, 0.05), rng.uniform(5.0, 10.0), bool(rng.random() < 0.5)), held=True)
    return {k: size[k] for k, _ in FAULTS if on[k]}, rng


def _describe_faults(f):
    words = {"gyro_scale": lambda v: f"gyro scale {100 * v:+.1f} %", "gps_latency": lambda v: f"fixes {v:.2f} s late",
             "speed_latency": lambda v: f"speed {v:.2f} s late", "cutoff": lambda v: f"speed cutoff {v:.2f} m/s",
             "dropouts": lambda v: f"{100 * v:.2f} % dropouts",
             "spikes": lambda v: f"{v[0]} speed + {v[1]} heading spikes",
             "stop_steps": lambda v: f"{v:.2f} deg heading steps at stops",
             "far_better": lambda v: f"{100 * v[0]:.1f} % fixes claiming /{v[1]:.1f}{' in pairs' if v[2] else ''}",
             "held": lambda v: "fixes carried forward"}
    return "; faults: " + (", ".join(words[k](v) for k, v in f.items()) or "none")


def draw(seed, protocol=1):
    """The drive's settings, drawn from ``SeedSequence([23, 44, seed])``. ``protocol=2`` draws the odometer's
    noise per sample as a wheel tick's quantization (0.002-0.015 m) and a speed's noise (0.02-0.2 m/s) times the
    sample interval, from ``SeedSequence([23, 44, seed, 2])`` (every other draw the same): protocol 1's 0.005-0.1
    m a sample, whatever the interval, is 0.1-2 m/s of speed noise at 20 Hz, which no wheel-speed sensor has."""
    rng = np.random.default_rng(np.random.SeedSequence([23, 44, seed]))
    dt = float(rng.choice([0.05, 0.1, 0.2, 0.5, 1.0]))
    d = dict(dt=dt, duration=float(np.round(rng.uniform(600.0, 1500.0))), standing=rng.uniform(0.0, 0.45),
             speeds=[(3.0, 10.0), (8.0, 25.0), (15.0, 33.0)][rng.integers(3)], accel=rng.uniform(1.0, 2.5),
             turn_every=rng.uniform(15.0, 60.0), heading=rng.uniform(0.0, 360.0),
             scale=1.0 + rng.uniform(-0.03, 0.03), odo=rng.uniform(0.005, 0.1), offset=rng.uniform(-3.0, 3.0),
             rate_bias=rng.uniform(-0.1, 0.1), arw=rng.uniform(0.1, 1.0), white=rng.uniform(0.1, 0.5),
             gps_rate=5.0 if dt <= 0.2 and rng.random() < 0.2 else 1.0,
             sigma=float(np.exp(rng.uniform(np.log(2.5), np.log(20.0)))), optimism=rng.uniform(0.8, 1.4),
             correlated=rng.uniform(0.0, 0.9), tau=rng.uniform(5.0, 30.0), jumps=rng.uniform(0.0, 0.08),
             tunnel=rng.uniform(20.0, 90.0) if rng.random() < 0.3 else 0.0)
    if protocol >= 2:
        odo = np.random.default_rng(np.random.SeedSequence([23, 44, seed, 2]))
        d["odo"] = float(np.hypot(odo.uniform(0.002, 0.015), odo.uniform(0.02, 0.2) * dt))
    return d, rng


def describe(d, protocol=1):
    odometer = f", odometer {d['odo']:.3f} m" if protocol >= 2 else ""
    tunnel = f", a {d['tunnel']:.0f} s tunnel" if d["tunnel"] else ""
    return (f"dt {d['dt']:g} s, {d['duration']:.0f} s, {100 * d['standing']:.0f} % standing, "
            f"{d['speeds'][0]:g}-{d['speeds'][1]:g} m/s, scale {d['scale']:.3f}, offset {d['offset']:+.1f} deg, "
            f"rate bias {d['rate_bias']:+.3f} deg/s, arw {d['arw']:.2f}{odometer}, fixes {d['gps_rate']:g} Hz "
            f"sigma {d['sigma']:.1f} m x{d['optimism']:.2f} ({100 * d['correlated']:.0f} % over {d['tau']:.0f} s, "
            f"{100 * d['jumps']:.1f} % jumps{tunnel})" + (_describe_faults(d["faults"]) if protocol == 3 else ""))


def drive(seed, protocol=1):
    """The drive CSV's columns and its fixes' horizontal errors."""
    d, rng = draw(seed, protocol)
    f, frng = faults(seed) if protocol == 3 else ({}, None)
    d["faults"] = f
    t, x, heading, speed = held_out._drive(
        rng, d["dt"], d["duration"], d["standing"], d["speeds"], d["heading"],
        dict(scale=d["scale"], odo=d["odo"], offset=d["offset"], rate_bias=d["rate_bias"], arw=d["arw"],
             white=d["white"], gyro_scale=f.get("gyro_scale", 0.0)), accel=d["accel"], turn_every=d["turn_every"])
    rows = held_out._fix_rows(t, d["gps_rate"])
    m = int(rows.sum())
    # a reported sigma changing from street to street (every 20-60 s), the true error that times `optimism`,
    # part of its variance correlated over `tau`, jumps of 20-80 m, and a tunnel with no fix at all
    edges = np.cumsum(rng.uniform(20.0, 60.0, m))
    level = d["sigma"] * np.exp(rng.normal(0.0, 0.25, m))[np.searchsorted(edges, np.arange(m) / d["gps_rate"])]
    c = d["correlated"]
    err = d["optimism"] * level[:, None] * (np.sqrt(c) * held_out.gauss_markov(rng, m, 1.0 / d["gps_rate"], d["tau"], (2,))
                                            + np.sqrt(1.0 - c) * rng.standard_normal((m, 2)))
    jump = rng.random(m) < d["jumps"]
    ang = rng.uniform(0.0, 2 * np.pi, m)
    err += (jump * rng.uniform(20.0, 80.0, m))[:, None] * np.stack([np.sin(ang), np.cos(ang)], axis=1)
    reported = np.round(level * np.exp(rng.normal(0.0, 0.15, m)), 1)
    if "far_better" in f:
        share, factor, pairs = f["far_better"]
        lie = frng.random(m) < (share / 2 if pairs else share)
        if pairs:
            lie[1:] |= lie[:-1]
        reported = np.where(lie, np.maximum(np.round(reported / factor, 1), 0.1), reported)
    cols = held_out._columns(t, x, heading, speed, rows, err, reported, f.get("gps_latency", 0.0),
                             f.get("speed_latency", 0.0))
    if protocol == 3:
        _sensor_faults(cols, f, frng, d["dt"])
    if d["tunnel"]:
        t0 = rng.uniform(0.2, 0.8) * d["duration"]
        gone = (t >= t0) & (t < t0 + d["tunnel"])
        for k in ("gps_east", "gps_north", "gps_sigma"):
            cols[k][gone] = np.nan
    if "held" in f:
        _carry_forward(cols)
    return d, cols, np.hypot(err[:, 0], err[:, 1])


def _sensor_faults(cols, f, rng, dt):
    """Protocol 3's faults of the DR columns and the log, in place (the fixes' own are made with them)."""
    v, h = cols["speed"], cols["heading"]
    if "stop_steps" in f:  # before the cutoff: a stop is where the car stands
        s = np.r_[0, (v == 0).astype(int), 0]
        dd = np.diff(s)
        for a, b in zip(np.flatnonzero(dd == 1), np.flatnonzero(dd == -1)):
            if (b - a) * dt >= 5.0:
                h[(a + b) // 2:] += np.deg2rad(f["stop_steps"]) * rng.choice([-1, 1])
    if "cutoff" in f:
        v[v < f["cutoff"]] = 0.0
    if "dropouts" in f:
        fast = np.flatnonzero(v >= 2.0)
        v[fast[rng.random(len(fast)) < f["dropouts"]]] = 0.0
    if "spikes" in f:
        moving = np.flatnonzero(v > 1.0)
        if len(moving):
            v[rng.choice(moving, f["spikes"][0])] = 70.8
            at = rng.choice(moving, f["spikes"][1])
            h[at] += np.deg2rad(rng.uniform(90.0, 180.0, len(at))) * rng.choice([-1, 1], len(at))
    cols["heading"] = np.mod(h, 2 * np.pi)


def _carry_forward(cols):
    """The log's last fix carried forward to every row after it (through a tunnel too), as a sample-and-hold
    logger writes it."""
    n = len(cols["time"])
    last = np.maximum.accumulate(np.where(np.isfinite(cols["gps_east"]), np.arange(n), -1))
    for k in ("gps_east", "gps_north", "gps_sigma"):
        cols[k] = np.where(last >= 0, cols[k][np.maximum(last, 0)], np.nan)


def command(path, out, grade):
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    cmd = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--grade", grade, "--no-figures",
           "--no-progress", "--jobs", "1", "--out", out, "--filters", ",".join(FILTERS)]
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=out)
    rows = {}
    for line in p.stdout.splitlines():
        cells = [x.strip() for x in line.split("|")]
        if len(cells) > 4 and cells[1] in FILTERS:
            rows[cells[1]] = (float(cells[2]), float(cells[4]))
    warned = {k for k in KINDS if re.search(rf"warning: {re.escape(k)}: ", p.stderr)}
    reader = bool(re.search(r"warning: (?!(EKF|UKF|SUKF|DR)[-\w]*: )", p.stderr))
    return p.returncode, "Traceback" in p.stderr, rows, warned, reader, p.stderr


def one(seed, keep=None, protocol=1):
    d, cols, fix_err = drive(seed, protocol)
    m50, m95 = np.median(fix_err), np.percentile(fix_err, 95)
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        path = held_out.write_csv(os.path.join(tmp, f"random_{seed}.csv"), cols)
        for grade in ("phone", "survey"):
            rc, tb, rows, warned, reader, err = command(path, tmp, grade)
            flags = ["CRASH"] if rc or tb or len(rows) < len(FILTERS) else []
            if not flags:
                dm, dx = rows["DR-mech"]
                for k in KINDS:
                    if rows[k][0] > dm + 2 * m50 or rows[k][1] > dx + 2 * m95:
                        flags.append(("WARNED " if k in warned or reader else "SILENT ") + k)
                meds = [rows[k][0] for k in KINDS]
                if max(meds) - min(meds) > 5.0 and max(meds) > 1.5 * min(meds):
                    flags.append("SPLIT")
            cells = " | ".join(f"{k} {rows[k][0]:.2f} / {rows[k][1]:.2f}" for k in FILTERS if k in rows)
            tail = err.strip().splitlines()[-1][:200] if flags and flags[0] == "CRASH" and err.strip() else ""
            out.append(f"    {grade} | rc {rc} | {cells} | warned {','.join(sorted(warned)) or '-'}"
                       f"{' +reader' if reader else ''} | {' '.join(flags) or 'ok'}{' | ' + tail if tail else ''}")
            if keep:
                with open(os.path.join(keep, f"random_{seed}_{grade}.stderr"), "w") as fh:
                    fh.write(err)
        if keep:
            import shutil
            shutil.copy(path, keep)
    return f"seed {seed}: {describe(d, protocol)}; fixes' error median {m50:.1f} m, p95 {m95:.1f} m\n" + "\n".join(out)


def seeds(spec):
    out = []
    for part in spec.split(","):
        a, _, b = part.partition("-")
        out += list(range(int(a), int(b or a) + 1))
    return out


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", default="0-99")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--keep", help="a folder to keep each drive's CSV and the command's stderr in")
    ap.add_argument("--protocol", type=int, choices=(1, 2, 3), default=1,
                    help="2: the odometer's noise a sensor's (see draw); 3: protocol 2 with sensor and log faults "
                         "(see faults)")
    a = ap.parse_args()
    from joblib import Parallel, delayed
    for line in Parallel(n_jobs=a.jobs, return_as="generator")(delayed(one)(s, a.keep, a.protocol)
                                                                for s in seeds(a.seeds)):
        print(line, flush=True)
