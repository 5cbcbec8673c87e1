"""Worst 8-state kind per analog and seed, against the issue's targets: before (first files) and after (second).

    python docs/study-outputs/dr/zero-rate/summarise.py BEFORE1.txt,BEFORE2.txt AFTER1.txt,AFTER2.txt

Each file is the output of ``run_gps_scale.py analogs`` (one line per analog and seed). A line of the
summary: the worst of EKF-8, UKF-8 and SUKF-8 (median / max at the outage ends, m) before and after,
whether it meets the target (phone 10 / 30, city 20 / 50, 1 Hz 6 / 30), and the EKF-8's own numbers.
"""
import re, sys
T = {"phone": (10, 30), "city": (20, 50), "one_hz": (6, 30)}
def parse(files):
    out = {}
    for fn in files:
        for line in open(fn):
            m = re.match(r"(\w+) seed (\d+) ", line)
            if not m: continue
            cells = {k: (float(a), float(b)) for k, a, b in re.findall(r"(EKF-8|UKF-8|SUKF-8) ([\d.]+) / ([\d.]+)", line)}
            out[(m.group(1), int(m.group(2)))] = cells
    return out
old = parse(sys.argv[1].split(","))
new = parse(sys.argv[2].split(","))
for name in T:
    met_o = met_n = n = 0
    for (nm, seed), c in sorted(new.items()):
        if nm != name: continue
        wm = max(v[0] for v in c.values()); wx = max(v[1] for v in c.values())
        ok = wm <= T[name][0] and wx <= T[name][1]
        co = old.get((nm, seed))
        s = ""
        if co:
            om = max(v[0] for v in co.values()); ox = max(v[1] for v in co.values())
            oko = om <= T[name][0] and ox <= T[name][1]; met_o += oko
            s = f"old {om:6.2f} / {ox:6.2f} {'met' if oko else 'MISS'}"
        met_n += ok; n += 1
        ekf = c["EKF-8"]
        print(f"{name:7s} {seed:2d} {s}  new {wm:6.2f} / {wx:6.2f} {'met' if ok else 'MISS'}   (EKF-8 {ekf[0]:.2f}/{ekf[1]:.2f})")
    print(f"{name}: met old {met_o}, new {met_n} of {n}\n")
