"""The summary of a ``random_drives.py`` output that ``RUN.md`` quotes: per drive the phone grade's worst 8-state
kind (its median and its maximum at the outage ends), then over the drives the median, 90th percentile and
largest of those medians, the median and largest of the maxima, and on how many drives the worst kind ends under
dead reckoning from the true start (in median, in max).

    python docs/study-outputs/dr/random-drives/summarise.py docs/study-outputs/dr/random-drives/random_drives_protocol2_0_59.txt
"""
import re, sys, numpy as np
for f in sys.argv[1:]:
    med, mx, dm, dx = [], [], [], []
    for line in open(f):
        if line.strip().startswith("phone |"):
            cells = {m.group(1): (float(m.group(2)), float(m.group(3))) for m in re.finditer(r"(DR-mech|EKF-8|UKF-8|SUKF-8) ([\d.]+) / ([\d.]+)", line)}
            k = [c for c in ("EKF-8", "UKF-8", "SUKF-8")]
            med.append(max(cells[c][0] for c in k)); mx.append(max(cells[c][1] for c in k))
            dm.append(cells["DR-mech"][0]); dx.append(cells["DR-mech"][1])
    med, mx, dm, dx = map(np.array, (med, mx, dm, dx))
    print(f, len(med), f"median {np.median(med):.2f} p90 {np.percentile(med, 90):.2f} max {med.max():.2f}; maxima median {np.median(mx):.2f} max {mx.max():.2f}; under DR median {np.sum(med < dm)} max {np.sum(mx < dx)}")
