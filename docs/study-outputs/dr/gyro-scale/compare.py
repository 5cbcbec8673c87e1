"""Worst 8-state kind per analog and seed, two run_gps_scale.py outputs side by side (usage: compare.py BEFORE AFTER)."""
import re, sys
T = {"phone": (10, 30), "city": (20, 50), "one_hz": (6, 30)}
def parse(path):
    out = {}
    for line in open(path):
        m = re.match(r"(\w+) seed (\d+)", line)
        if not m: continue
        vals = re.findall(r"(EKF-8|UKF-8|SUKF-8) ([\d.]+) / ([\d.]+)", line)
        med = max(float(a) for _, a, _ in vals); mx = max(float(b) for _, _, b in vals)
        out[(m.group(1), int(m.group(2)))] = (med, mx)
    return out
a, b = parse(sys.argv[1]), parse(sys.argv[2])
met = {}
for k in sorted(a):
    t = T[k[0]]
    ma = a[k][0] <= t[0] and a[k][1] <= t[1]; mb = b[k][0] <= t[0] and b[k][1] <= t[1]
    met.setdefault(k[0], [0, 0]); met[k[0]][0] += ma; met[k[0]][1] += mb
    print(f"{k[0]:7s} {k[1]:2d} | worst kind before {a[k][0]:6.2f} / {a[k][1]:6.2f} {'met' if ma else 'MISS'} | after {b[k][0]:6.2f} / {b[k][1]:6.2f} {'met' if mb else 'MISS'}")
print(met)
import numpy as np
for d in T:
    ka = [a[k] for k in a if k[0] == d]; kb = [b[k] for k in b if k[0] == d]
    print(d, "mean of worst-kind medians", round(np.mean([x[0] for x in ka]), 2), "->", round(np.mean([x[0] for x in kb]), 2),
          "| mean of maxima", round(np.mean([x[1] for x in ka]), 2), "->", round(np.mean([x[1] for x in kb]), 2))
