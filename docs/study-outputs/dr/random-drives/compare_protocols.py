"""Protocol 3 against protocol 2 on the same seeds (stop 56): the same drive, with and without its faults.

Per seed, the phone grade's worst 8-state kind (median / max at the outage ends, m) on the clean drive (protocol 2)
and on the faulty one (protocol 3), dead reckoning from the true start on each, and the faults; then, over the
drives with each fault, the median of the worst kind's change in median and in max (faulty less clean), and the
drives whose worst kind ends past the clean drive's by more than 5 m in median or 15 m in max.

    python docs/study-outputs/dr/random-drives/compare_protocols.py \\
        docs/study-outputs/dr/random-drives/random_drives_protocol2_200_239.txt \\
        docs/study-outputs/dr/random-drives/random_drives_protocol3_200_239.txt
"""
import re
import sys

import numpy as np

KINDS = ("EKF-8", "UKF-8", "SUKF-8")


def read(path):
    out, seed = {}, None
    for line in open(path):
        m = re.match(r"seed (\d+): .*?(?:; faults: (.*?))?; fixes' error", line)
        if m:
            seed, faults = int(m.group(1)), m.group(2) or ""
            out[seed] = {"faults": faults}
        elif line.strip().startswith(("phone |", "survey |")) and seed is not None:
            grade = line.split("|")[0].strip()
            cells = {c.group(1): (float(c.group(2)), float(c.group(3)))
                     for c in re.finditer(r"(DR-mech|EKF-8|UKF-8|SUKF-8) ([\d.]+) / ([\d.]+)", line)}
            flags = line.rsplit("|", 1)[-1].strip()
            out[seed][grade] = (cells, flags)
    return out


def worst(cells):
    return max(cells[k][0] for k in KINDS), max(cells[k][1] for k in KINDS)


if __name__ == "__main__":
    clean, faulty = read(sys.argv[1]), read(sys.argv[2])
    seeds = sorted(set(clean) & set(faulty))
    print("| seed | faults | DR clean | DR faulty | worst kind clean | worst kind faulty | flags clean / faulty |")
    print("|---|---|---|---|---|---|---|")
    by_fault, far = {}, []
    for s in seeds:
        (cc, fc), (cf, ff) = clean[s]["phone"], faulty[s]["phone"]
        (a, b), (c, d) = worst(cc), worst(cf)
        print(f"| {s} | {faulty[s]['faults'] or 'none'} | {cc['DR-mech'][0]:.2f} / {cc['DR-mech'][1]:.2f} | "
              f"{cf['DR-mech'][0]:.2f} / {cf['DR-mech'][1]:.2f} | {a:.2f} / {b:.2f} | {c:.2f} / {d:.2f} | {fc} / {ff} |")
        for name in re.findall(r"(gyro scale|fixes [\d.]+ s late|speed [\d.]+ s late|speed cutoff|dropouts|spikes|"
                               r"heading steps|claiming|carried forward)", faulty[s]["faults"]):
            name = re.sub(r"[\d.]+ s ", "", name)
            by_fault.setdefault(name, []).append((c - a, d - b))
        if c - a > 5.0 or d - b > 15.0:
            far.append(s)
    print()
    for name, v in sorted(by_fault.items()):
        v = np.array(v)
        print(f"{name}: {len(v)} drives, worst kind's change median {np.median(v[:, 0]):+.2f} m (largest "
              f"{v[:, 0].max():+.2f}), max {np.median(v[:, 1]):+.2f} m (largest {v[:, 1].max():+.2f})")
    print(f"worst kind past its clean drive's by > 5 m median or > 15 m max: {far or 'none'}")
