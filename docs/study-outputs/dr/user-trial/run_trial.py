"""Stop 69's user trials rerun: the drives of ``gen_drives.py`` (trial 1) or ``gen_drives_2.py`` (``--trial 2``)
through the command, both grades.

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/user-trial/run_trial.py [--trial 2] > docs/study-outputs/dr/user-trial/trial_<...>.txt

Each line: the drive and grade, the exit code, the median / max at the outage ends (m) of DR-mech, EKF-8, UKF-8 and
SUKF-8, the number of warning lines on stderr, and the table's header (how many outages, and the drive's own gaps of
fixes where it has any). D4's speed is in km/h: it is refused as it is (exit 2) and run with ``--speed-scale 3.6``.
"""
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
KINDS = ("DR-mech", "EKF-8", "UKF-8", "SUKF-8")
RUNS = [("D1", "D1_parking_reverse_quantised.csv", []), ("D2", "D2_highway_1Hz_tunnel.csv", []),
        ("D3", "D3_gyro_bias_multipath.csv", []), ("D4", "D4_roundabout_kmh.csv", []),
        ("D4 --speed-scale 3.6", "D4_roundabout_kmh.csv", ["--speed-scale", "3.6"]),
        ("D5", "D5_midstart_gyro_bias.csv", [])]
RUNS_2 = [("A", "A_compass_oslo.csv", []), ("B --heading-offset 91", "B_rot90_south54.csv", ["--heading-offset", "91"]),
          ("C", "C_dateline_5hz.csv", []), ("D", "D_hills_idle_en.csv", []), ("E", "E_r95_madrid.csv", []),
          ("E --outage-starts 0", "E_r95_madrid.csv", ["--outage-starts", "0"]),
          ("E2", "E2_r95_dupblock.csv", [])]
TRIAL = 2 if "--trial" in sys.argv and sys.argv[sys.argv.index("--trial") + 1] == "2" else 1

with tempfile.TemporaryDirectory() as folder:
    subprocess.run([sys.executable, os.path.join(HERE, "gen_drives.py" if TRIAL == 1 else "gen_drives_2.py"), folder],
                   check=True, capture_output=True)
    for label, csv, extra in (RUNS if TRIAL == 1 else RUNS_2):
        for grade in ("phone", "survey"):
            cmd = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", os.path.join(folder, csv),
                   "--grade", grade, "--jobs", "1", "--no-progress", "--no-figures", "--out", os.path.join(folder, "out")]
            p = subprocess.run(cmd + extra, capture_output=True, text=True)
            cells = []
            for k in KINDS:
                m = re.search(rf"^\| {re.escape(k)} \| ([\d.]+) \| [\d.]+ \| ([\d.]+) \|", p.stdout, re.M)
                cells.append(f"{k} {m.group(1)} / {m.group(2)}" if m else f"{k} -")
            header = re.search(r"^### real drive \S+: (.*?), error at", p.stdout, re.M)
            n_warn = sum(1 for line in p.stderr.splitlines() if "warning:" in line)
            refused = "" if p.returncode == 0 else " | " + p.stderr.strip().splitlines()[-1][:160]
            print(f"{label} {grade} | rc {p.returncode} | " + " | ".join(cells) + f" | {n_warn} warnings"
                  + (f" | {header.group(1)}" if header else "") + refused, flush=True)
