"""Build the low-speed speed-sensor fault variants of the phone and city analogs (seed 0).

Writes DIR/{phone,city}_{variant}.csv and DIR/{name}_{variant}_meta.json (crawl episodes); DIR is the first
argument (default drives/ beside this script).

Variants (only the sensor columns change unless new truth is needed):
  clean        the analog as generated
  quant        speed rounded to 1 km/h steps: round(speed*3.6)/3.6
  cutoff       speed reported 0 whenever the TRUE speed < 0.8 m/s
  crawl_ctrl   NEW truth: 8 queue-crawl episodes (0.3-0.7 m/s, 10-40 s, <= 25 m each), two per
               stop in 4 stops, each followed by 3 s standing; sensors honest (control: no cutoff)
  crawl        same drive, speed reported 0 whenever true speed < 0.8 m/s
  crawlturn_ctrl  like crawl_ctrl but in 5 of the 8 episodes the heading turns 45-180 deg while crawling
  crawlturn    same drive, cutoff at 0.8 m/s
  delay        speed delayed 0.5 s vs heading/fixes (10 Hz: 5 samples; 5 Hz city: linear interp at t-0.5)

New-truth drives: the analog's route() is drawn with the analog's own rng (same draws), then the crawl
episodes are inserted with a separate rng (SeedSequence 777) and every later window is shifted by the
episode's length; the rest of the analog's generator (sensor noise, gyro error, fix errors) runs
unchanged on the new truth, so the fix error sequence is identical to the analog's.
"""
import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[3] / "tests"))  # the repository's tests/: the drive analogs
import _held_out_drives as h  # noqa: E402

OUT = Path(sys.argv[1]) if len(sys.argv) > 1 else HERE / "drives"
OUT.mkdir(parents=True, exist_ok=True)
CUT = 0.8
_orig_drive = h._drive
_orig_route = h.route
CAPTURE = {}


def capturing_drive(rng, dt, *a, **kw):
    t, x, heading, speed = _orig_drive(rng, dt, *a, **kw)
    CAPTURE.update(t=t, v=np.hypot(x[:, 1], x[:, 4]), dt=dt)
    return t, x, heading, speed


def make_crawl_route(n_eps=8, n_turn=0, seed=777):
    """A route() replacement: the analog's route, then crawl episodes inserted into stops."""
    def route(rng, duration, dt, standing, speeds, accel=2.0, turn_every=40.0):
        changes, turns = _orig_route(rng, duration, dt, standing, speeds, accel, turn_every)  # the analog's draws
        r2 = np.random.default_rng(np.random.SeedSequence([seed, int(round(1 / dt))]))
        changes, turns = list(changes), list(turns)
        # stops: the end of a braking window (negative amount) -> next start
        starts = sorted(c[0] for c in changes if c[2] > 0)
        stop_ends = [(c[1], min([s for s in starts if s >= c[1]], default=duration) - c[1]) for c in changes if c[2] < 0]
        # stops in the first 70 % of the drive (so that they survive the shift); n_eps // 2 of them get
        # two crawl episodes each (a queue: stand, crawl, stand 3 s, crawl, stand)
        cand = [(s, length) for s, length in stop_ends if 20.0 < s < 0.7 * duration]
        n_stops = min(len(cand), n_eps // 2)
        pick = sorted(r2.choice(len(cand), size=n_stops, replace=False))
        turn_eps = set(r2.choice(2 * n_stops, size=min(n_turn, 2 * n_stops), replace=False).tolist()) if n_turn else set()
        eps = []
        shift = 0.0
        inserts = []
        for j in range(2 * n_stops):
            s, length = cand[pick[j // 2]]
            vc = r2.uniform(0.3, 0.7)
            T = min(r2.uniform(10.0, 40.0), 25.0 / vc - 2.0)
            T = max(1.0, np.round(T / dt)) * dt
            ramp = max(1.0, np.round((vc / 0.5) / dt)) * dt  # 0.5 m/s^2
            ang = (r2.choice([-1.0, 1.0]) * r2.uniform(45.0, 180.0)) if j in turn_eps else 0.0
            off = np.round(min(2.0, length / 2) / dt) * dt
            inserts.append((s + off, j, vc, T, ramp, ang))
        inserts.sort()
        k = 0
        allw = sorted([("c",) + tuple(c) for c in changes] + [("t",) + tuple(w) for w in turns], key=lambda w: w[1])
        out_c, out_t = [], []
        for w in allw:
            while k < len(inserts) and inserts[k][0] <= w[1]:
                t0, _, vc, T, ramp, ang = inserts[k]
                a = t0 + shift
                out_c.append((a, a + ramp, vc))
                out_c.append((a + ramp + T, a + 2 * ramp + T, -vc))
                if ang:
                    out_t.append((a + ramp + 1.0 * dt, a + ramp + T - 1.0 * dt, ang))
                eps.append(dict(t_start=a, t_end=a + 2 * ramp + T, speed=vc, crawl_s=T, ramp_s=ramp,
                                distance=vc * (T + ramp), turn_deg=ang))
                shift += 2 * ramp + T + np.round(3.0 / dt) * dt  # then 3 s standing
                k += 1
            kind, t0, t1, amt = w
            (out_c if kind == "c" else out_t).append((t0 + shift, t1 + shift, amt))
        CAPTURE["episodes"] = eps
        return (tuple(c for c in out_c if c[1] < duration), tuple(w for w in out_t if w[1] < duration))
    return route


def gen(name, route_fn=None):
    h._drive = capturing_drive
    h.route = route_fn or _orig_route
    try:
        cols = h.columns(name, 0)
    finally:
        h._drive, h.route = _orig_drive, _orig_route
    return cols, dict(CAPTURE)


def cutoff(cols, cap):
    c = dict(cols)
    c["speed"] = np.where(cap["v"] < CUT, 0.0, cols["speed"])
    return c


def write(name, variant, cols, meta=None):
    h.write_csv(OUT / f"{name}_{variant}.csv", cols)
    if meta is not None:
        (OUT / f"{name}_{variant}_meta.json").write_text(json.dumps(meta, indent=1))


def summary(name, variant, cols, cap):
    v, s = cap["v"], cols["speed"]
    dt = cap["dt"]
    moving_zero = (v > 0) & (s < 0.05)
    return dict(drive=name, variant=variant, n=len(v), dt=dt,
                true_moving_but_speed_below_0p05_s=float(moving_zero.sum() * dt),
                distance_driven_while_speed_below_0p05_m=float((v * moving_zero).sum() * dt),
                true_distance_m=float(v.sum() * dt), odometer_distance_m=float(s.sum() * dt))


def main():
    summ = []
    for name in ("phone", "city"):
        cols, cap = gen(name)
        write(name, "clean", cols); summ.append(summary(name, "clean", cols, cap))
        q = dict(cols, speed=np.round(cols["speed"] * 3.6) / 3.6)
        write(name, "quant", q); summ.append(summary(name, "quant", q, cap))
        c = cutoff(cols, cap)
        write(name, "cutoff", c); summ.append(summary(name, "cutoff", c, cap))
        t = cols["time"]
        d = dict(cols, speed=np.interp(t - 0.5, t, cols["speed"], left=0.0))
        write(name, "delay", d); summ.append(summary(name, "delay", d, cap))
        for base, n_turn in (("crawl", 0), ("crawlturn", 5)):
            cc, capc = gen(name, make_crawl_route(8, n_turn))
            meta = dict(episodes=capc["episodes"])
            write(name, base + "_ctrl", cc, meta); summ.append(summary(name, base + "_ctrl", cc, capc))
            cx = cutoff(cc, capc)
            write(name, base, cx, meta); summ.append(summary(name, base, cx, capc))
            # sanity: fix errors identical to the analog's
            fe = np.nanmax(np.abs((cc["gps_east"] - cc["true_east"]) - (cols["gps_east"] - cols["true_east"])))
            summ[-1]["fix_err_diff_vs_analog_m"] = float(fe)
    (OUT / "summary.json").write_text(json.dumps(summ, indent=1))
    for s in summ:
        print(s)


if __name__ == "__main__":
    main()
