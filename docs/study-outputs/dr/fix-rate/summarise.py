"""Per seed, the worst 8-state kind's median / max at the outage ends, and the seeds meeting the city
targets (20 / 50 m), for each stored run of ``fix_rate.py`` (and the 1 Hz analog's, zero-rate/seeds_0_9.txt).

Run from the repository root: ``python docs/study-outputs/dr/fix-rate/summarise.py``
"""

import os
import re
import statistics

HERE = os.path.dirname(os.path.abspath(__file__))
TABLES = (
    ("City analog, seeds 0-9 (looked at while choosing)", (
        ("1 Hz fixes (the analog as stored)", os.path.join("..", "zero-rate", "seeds_0_9.txt")),
        ("5 Hz, every fix (default)", "city_5hz_seeds_0_9.txt"),
        ("5 Hz, window 12 s (= the old 60 fixes)", "city_5hz_seeds_0_9_window_12s.txt"),
        ("5 Hz, correlated_fixes=inflate", "city_5hz_seeds_0_9_inflate.txt"),
        ("5 Hz, every 5th fix kept (the probe)", "city_5hz_seeds_0_9_keep_every_5.txt"),
        ("5 Hz, min_fix_interval=1", "city_5hz_seeds_0_9_min_fix_interval_1.txt"))),
    ("City analog, seeds 10-19 (held out, each run once)", (
        ("5 Hz, every fix (default)", "city_5hz_seeds_10_19.txt"),
        ("5 Hz, min_fix_interval=1", "city_5hz_seeds_10_19_min_fix_interval_1.txt"))),
    ("The city analog's drive with white 5 m fixes at 5 Hz, seeds 0-4 (the cost of thinning)", (
        ("every fix (default)", "white_5hz_seeds_0_4.txt"),
        ("min_fix_interval=1", "white_5hz_seeds_0_4_min_fix_interval_1.txt"))),
)


def worst(path):
    rows = {}
    for line in open(os.path.join(HERE, path)):
        if not line.startswith("city"):
            continue
        cells = re.findall(r"(EKF-8|UKF-8|SUKF-8) ([\d.]+) / ([\d.]+)", line)
        seed = int(re.search(r"seed (\d+)", line).group(1))
        rows[seed] = (max(float(c[1]) for c in cells), max(float(c[2]) for c in cells))
    return rows


def table(title, runs):
    runs = [(label, worst(path)) for label, path in runs]
    print(f"## {title}\n")
    print("| seed | " + " | ".join(label for label, _ in runs) + " |")
    print("|---" * (len(runs) + 1) + "|")
    for seed in sorted(runs[0][1]):
        print(f"| {seed} | " + " | ".join(
            f"{r[seed][0]:.2f} / {r[seed][1]:.2f}" + (" *" if r[seed][0] > 20 or r[seed][1] > 50 else "")
            for _, r in runs) + " |")
    print("| met (of %d) | " % len(runs[0][1]) + " | ".join(
        str(sum(m <= 20 and x <= 50 for m, x in r.values())) for _, r in runs) + " |")
    print("| median over seeds | " + " | ".join(
        f"{statistics.median(m for m, _ in r.values()):.2f} / {statistics.median(x for _, x in r.values()):.2f}"
        for _, r in runs) + " |\n")


def main():
    print("The worst 8-state kind's median / max at the outage ends (m); * misses the city targets (20 / 50 m).\n")
    for title, runs in TABLES:
        table(title, runs)


if __name__ == "__main__":
    main()
