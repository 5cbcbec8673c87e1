"""Per analog and seed, the worst 8-state kind's median / max at the outage ends in two outputs of
``../gps-scale/run_gps_scale.py analogs`` (a base and a variant), met or missed, and the changes (stop 66).

    python docs/study-outputs/dr/analog-seeds/compare_worst.py BASE[,BASE2] VARIANT[,VARIANT2]
"""
import sys
sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[1] / "zero-rate"))
from summarise import parse, worst
import numpy as np
a, b = parse(sys.argv[1].split(",")), parse(sys.argv[2].split(","))
T = {"phone": (10, 30), "city": (20, 50), "one_hz": (6, 30)}
rows = []
for k in sorted(set(a) & set(b)):
    wa, wb = worst(a[k]), worst(b[k])
    rows.append((k, wa, wb))
    ma = wa[0] <= T[k[0]][0] and wa[1] <= T[k[0]][1]; mb = wb[0] <= T[k[0]][0] and wb[1] <= T[k[0]][1]
    print(f"{k[0]:7s} {k[1]:3d}  base {wa[0]:6.2f} / {wa[1]:6.2f} {'met ' if ma else 'MISS'}  variant {wb[0]:6.2f} / {wb[1]:6.2f} {'met ' if mb else 'MISS'}  d {wb[0]-wa[0]:+6.2f} / {wb[1]-wa[1]:+6.2f}")
for an in ("phone", "city", "one_hz"):
    d = np.array([(r[2][0]-r[1][0], r[2][1]-r[1][1]) for r in rows if r[0][0] == an])
    if len(d): print(an, "median change: median", np.median(d[:,0]).round(2), "max", np.median(d[:,1]).round(2), "| medians better", (d[:,0]<0).sum(), "of", len(d), "| maxima better", (d[:,1]<0).sum())
