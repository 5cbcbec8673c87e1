"""How many seeds of each analog the worst 8-state kind meets the issue's targets on, by blocks of seeds.

    python docs/study-outputs/dr/analog-seeds/count_met.py FILE [FILE ...] [--blocks 0-19,20-29,...]

Each file is the output of ``../gps-scale/run_gps_scale.py analogs`` (one line per analog and seed). Prints, per
analog and block, the seeds met (the worst of EKF-8, UKF-8 and SUKF-8, median and max at the outage ends, against
phone 10 / 30, city 20 / 50, 1 Hz 6 / 30 m), then each seed missed with the worst kind's numbers and dead
reckoning's from the true start. The README's table of seeds comes from this (stop 57: ``count_met_0_69.txt``).
"""
import argparse
import re

T = {"phone": (10, 30), "city": (20, 50), "one_hz": (6, 30)}


def parse(files):
    out = {}
    for fn in files:
        for line in open(fn):
            m = re.match(r"(\w+) seed (\d+) ", line)
            if m:
                cells = {k: (float(a), float(b)) for k, a, b in
                         re.findall(r"(DR-mech|EKF-8|UKF-8|SUKF-8) ([\d.]+) / ([\d.]+)", line)}
                out[m.group(1), int(m.group(2))] = cells
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--blocks", default="0-19,20-29,30-39,40-49,50-59,60-69")
    args = ap.parse_args()
    rows = parse(args.files)
    blocks = [tuple(int(x) for x in b.split("-")) for b in args.blocks.split(",")]
    for name, (tm, tx) in T.items():
        counts, missed = [], []
        for lo, hi in blocks:
            seeds = [s for s in range(lo, hi + 1) if (name, s) in rows]
            met = 0
            for s in seeds:
                c = rows[name, s]
                w = (max(c[k][0] for k in ("EKF-8", "UKF-8", "SUKF-8")), max(c[k][1] for k in ("EKF-8", "UKF-8", "SUKF-8")))
                if w[0] <= tm and w[1] <= tx:
                    met += 1
                else:
                    missed.append(f"{s} ({w[0]:.2f} / {w[1]:.2f}; DR {c['DR-mech'][0]:.2f} / {c['DR-mech'][1]:.2f})")
            counts.append(f"{lo}-{hi}: {met} of {len(seeds)}")
        print(f"{name}: " + ", ".join(counts))
        print(f"  missed: {', '.join(missed) if missed else 'none'}")


if __name__ == "__main__":
    main()
