"""How many seeds of each analog the worst 8-state kind meets the issue's targets on, by blocks of seeds.

    python docs/study-outputs/dr/analog-seeds/count_met.py FILE [FILE ...] [--blocks 0-19,20-29,...]

Each file is the output of ``../gps-scale/run_gps_scale.py analogs`` (one line per analog and seed). Prints, per
analog and block, the seeds met (the worst of EKF-8, UKF-8 and SUKF-8, median and max at the outage ends, against
phone 10 / 30, city 20 / 50, 1 Hz 6 / 30 m), then each seed missed with the worst kind's numbers and dead
reckoning's from the true start. The README's table of seeds comes from this (stop 57: ``count_met_0_69.txt``).
"""
import argparse
import pathlib
import re
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "zero-rate"))
from summarise import T, met, parse, worst  # noqa: E402  (the targets, and the worst kind as summarise.py reads it)

DR = re.compile(r"(\w+) seed (\d+) .*?DR-mech ([\d.]+) / ([\d.]+)")


def dead_reckoning(files):
    """``{(analog, seed): (median, max)}`` of dead reckoning from the true start, from the files' lines."""
    return {(m.group(1), int(m.group(2))): (float(m.group(3)), float(m.group(4)))
            for fn in files for m in map(DR.match, open(fn)) if m}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--blocks", default="0-19,20-29,30-39,40-49,50-59,60-69")
    args = ap.parse_args()
    rows, dr = parse(args.files), dead_reckoning(args.files)
    blocks = [tuple(int(x) for x in b.split("-")) for b in args.blocks.split(",")]
    for name in T:
        counts, missed = [], []
        for lo, hi in blocks:
            seeds = [s for s in range(lo, hi + 1) if (name, s) in rows]
            met_here = 0
            for s in seeds:
                w = worst(rows[name, s])
                if met(name, w):
                    met_here += 1
                else:
                    missed.append(f"{s} ({w[0]:.2f} / {w[1]:.2f}; DR {dr[name, s][0]:.2f} / {dr[name, s][1]:.2f})")
            counts.append(f"{lo}-{hi}: {met_here} of {len(seeds)}")
        print(f"{name}: " + ", ".join(counts))
        print(f"  missed: {', '.join(missed) if missed else 'none'}")


if __name__ == "__main__":
    main()
