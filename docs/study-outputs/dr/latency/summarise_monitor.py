"""Counts of monitor.py's outputs: per analog, error and monitored error, the drives on which it warned of that
error ("found"), the warnings of an error the drive did not have ("false alarms": label, error, step), and the
largest |z| of each monitored error on drives without it. Usage, from this folder:

    python summarise_monitor.py monitor_seeds_0_5.txt monitor_seeds_0_5_survey.txt monitor_other.txt > monitor_summary.txt
"""
import re, sys, collections
for fn in sys.argv[1:]:
    print("==", fn)
    det = collections.defaultdict(lambda: [0, 0]); false = []; topfalse = {}
    for line in open(fn):
        if "|" not in line: continue
        label = line.split("|")[0].strip()
        m = re.match(r"(\w+) seed (\d+), (.*)", label)
        cells = re.findall(r"(\w+) ([+-]?[\d.]+|-) \S+ z ([+-]?[\d.]+|-) \(max \|z\| ([\d.inf]+)\) warned at (\S+)", line)
        err = m.group(3) if m else "other"
        drive = m.group(1) if m else label
        for name, est, z, mx, at in cells:
            own = {"gyro_scale": "scale", "latency": "latency", "odometer_latency": "speed"}[name]
            if err.startswith(own):
                det[(drive, name, err)][0] += at != "-"; det[(drive, name, err)][1] += 1
            else:
                if at != "-": false.append((label, name, at))
                key = (name, "none" if err == "none" or not m else "other errors")
                topfalse[key] = max(topfalse.get(key, 0), float(mx))
    for k, v in sorted(det.items()): print("  found", k, f"{v[0]} of {v[1]}")
    print("  false alarms:", false)
    print("  largest |z| where not the error:", {k: round(v, 2) for k, v in sorted(topfalse.items())})
