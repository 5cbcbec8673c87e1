"""Worst 8-state kind per analog and seed, against the issue's targets: before (first files) and after (second).

    python docs/study-outputs/dr/zero-rate/summarise.py BEFORE1.txt,BEFORE2.txt AFTER1.txt,AFTER2.txt

Each file is the output of ``run_gps_scale.py analogs`` (one line per analog and seed). A line of the
summary: the worst of EKF-8, UKF-8 and SUKF-8 (median / max at the outage ends, m) before ("old") and
after ("new"), whether it meets the target (phone 10 / 30, city 20 / 50, 1 Hz 6 / 30), and the EKF-8's
own numbers. Per analog: the seeds that meet the targets, the medians over the seeds of the worst
kind's median and max, and on how many seeds each went down.
"""
import re
import sys

import numpy as np

T = {"phone": (10, 30), "city": (20, 50), "one_hz": (6, 30)}


def parse(files):
    """``{(analog, seed): {kind: (median, max)}}`` from the files' lines."""
    out = {}
    for fn in files:
        for line in open(fn):
            m = re.match(r"(\w+) seed (\d+) ", line)
            if m:
                out[m.group(1), int(m.group(2))] = {k: (float(a), float(b)) for k, a, b in
                                                    re.findall(r"(EKF-8|UKF-8|SUKF-8) ([\d.]+) / ([\d.]+)", line)}
    return out


def worst(cells):
    return max(v[0] for v in cells.values()), max(v[1] for v in cells.values())


def met(name, w):
    return w[0] <= T[name][0] and w[1] <= T[name][1]


def main():
    old, new = parse(sys.argv[1].split(",")), parse(sys.argv[2].split(","))
    for name in T:
        seeds = sorted(s for nm, s in new if nm == name)
        wo, wn = np.array([worst(old[name, s]) for s in seeds]), np.array([worst(new[name, s]) for s in seeds])
        for s, o, w in zip(seeds, wo, wn):
            e = new[name, s]["EKF-8"]
            print(f"{name:7s} {s:2d} old {o[0]:6.2f} / {o[1]:6.2f} {'met' if met(name, o) else 'MISS'}  "
                  f"new {w[0]:6.2f} / {w[1]:6.2f} {'met' if met(name, w) else 'MISS'}   (EKF-8 {e[0]:.2f}/{e[1]:.2f})")
        print(f"{name}: met old {sum(met(name, o) for o in wo)}, new {sum(met(name, w) for w in wn)} of {len(seeds)}; "
              f"median over the seeds of the worst median {np.median(wo[:, 0]):.2f} -> {np.median(wn[:, 0]):.2f}, "
              f"of the worst max {np.median(wo[:, 1]):.2f} -> {np.median(wn[:, 1]):.2f}; lower median on "
              f"{int((wn[:, 0] < wo[:, 0]).sum())}, lower max on {int((wn[:, 1] < wo[:, 1]).sum())} of {len(seeds)}\n")


if __name__ == "__main__":
    main()
