"""Extra variants (run after make_variants.py):
  crawlturn_rep / crawlturn_rep_ctrl: NEW truth: in one stop (the first stop after 100 s) a queue of
     3 identical blocks [roll at 1.2 m/s for ~2.6 s, stand 2 s, crawl 0.5 m/s for 20 s turning +90 deg,
     stand 3 s], then a last roll; _rep has the 0.8 m/s wheel-speed cutoff, _ctrl honest speeds.
     The three crawls are separate 'stops' to the filter (the rolls read > 0.8 m/s) with the same
     heading slope, back to back: the case where the zero-rate re-acquisition could take them for a gyro.
  dither (control for quant): speed + uniform(-0.139, 0.139) m/s (the 1 km/h quantisation's error
     size, no low-speed structure), clipped at 0 and kept 0 where the sensor read 0.
"""
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import make_variants as mv  # noqa: E402


def rep_route(n_blocks=3, turn=90.0):
    def route(rng, duration, dt, standing, speeds, accel=2.0, turn_every=40.0):
        changes, turns = mv._orig_route(rng, duration, dt, standing, speeds, accel, turn_every)
        starts = sorted(c[0] for c in changes if c[2] > 0)
        stops = [(c[1], min([s for s in starts if s >= c[1]], default=duration) - c[1]) for c in changes if c[2] < 0]
        s, length = [x for x in stops if x[0] > 100.0][0]
        g = lambda x: max(1.0, np.round(x / dt)) * dt  # whole samples
        a = s + g(min(2.0, length / 2))
        seg_c, seg_t, eps = [], [], []
        t = a
        for b in range(n_blocks + 1):
            r = g(1.2 / 1.5)
            seg_c += [(t, t + r, 1.2), (t + r + g(1.0), t + 2 * r + g(1.0), -1.2)]  # a roll
            t += 2 * r + g(1.0)
            if b == n_blocks:
                break
            t += g(2.0)
            ramp, T = g(1.0), g(20.0)
            seg_c += [(t, t + ramp, 0.5), (t + ramp + T, t + 2 * ramp + T, -0.5)]
            seg_t += [(t + ramp + dt, t + ramp + T - dt, turn)]
            eps.append(dict(t_start=t, t_end=t + 2 * ramp + T, speed=0.5, crawl_s=T, ramp_s=ramp,
                            distance=0.5 * (T + ramp), turn_deg=turn))
            t += 2 * ramp + T + g(3.0)
        D = t - a
        sh = lambda w: (w[0] + D, w[1] + D, w[2]) if w[0] >= a else w
        changes = sorted([sh(c) for c in changes] + seg_c)
        turns = sorted([sh(w) for w in turns] + seg_t)
        mv.CAPTURE["episodes"] = eps
        return tuple(c for c in changes if c[1] < duration), tuple(w for w in turns if w[1] < duration)
    return route


def main():
    summ = []
    for name in ("phone", "city"):
        cols, cap = mv.gen(name)
        r = np.random.default_rng(4242)
        q = 0.5 / 3.6
        d = dict(cols, speed=np.where(cols["speed"] > 0, np.maximum(cols["speed"] + r.uniform(-q, q, len(cols["speed"])), 0.0), 0.0))
        mv.write(name, "dither", d); summ.append(mv.summary(name, "dither", d, cap))
        cc, capc = mv.gen(name, rep_route())
        meta = dict(episodes=capc["episodes"])
        mv.write(name, "crawlturn_rep_ctrl", cc, meta); summ.append(mv.summary(name, "crawlturn_rep_ctrl", cc, capc))
        cx = mv.cutoff(cc, capc)
        mv.write(name, "crawlturn_rep", cx, meta); summ.append(mv.summary(name, "crawlturn_rep", cx, capc))
        print(name, meta)
    (mv.OUT / "summary_extra.json").write_text(json.dumps(summ, indent=1))
    for s in summ:
        print(s)


if __name__ == "__main__":
    main()
