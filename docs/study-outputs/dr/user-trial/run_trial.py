"""The user trials rerun: the drives of ``gen_drives.py`` (trial 1, stop 69), ``gen_drives_2.py`` (``--trial 2``,
stop 69), ``gen_drives_3.py`` (``--trial 3``, stop 70) or ``gen_drives_4.py`` (``--trial 4``, stop 71) through the
command, both grades.

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/user-trial/run_trial.py [--trial 2|3|4|6|7] > docs/study-outputs/dr/user-trial/trial_<...>.txt

Each line: the drive and grade, the exit code, the median / max at the outage ends (m) of DR-mech, EKF-8, UKF-8 and
SUKF-8, the number of warning lines on stderr, and the table's header (how many outages, and the drive's own gaps of
fixes where it has any). D4's speed is in km/h: it is refused as it is (exit 2) and run with ``--speed-scale 3.6``.
Trial 3 runs each drive beside its ``_clean`` twin (the same drive and noise without the fault), the ferry drive
split where the reader finds the car carried (229-593 s) as two drives (one line each), and two remedies that user
tried: the ferry with the covariance scale estimated, the car park with the gyro's scale state. Trial 4 likewise (its
d3 and d4 are refused as written, d3 run with the ``--fill-gaps`` its refusal names; d5 also with its two faults
apart), and d1 with the ``--gyro-bias-instability`` value the reader's warning names on it (read from that warning).
Trial 6 (``--trial 6``, ``gen_drives_6.py``, stop 72; the fifth trial was of the API, from Python) runs its five drives
beside their twins, the smoothed fixes with the latency the reader names, the compass disturbed by the car's
electrics with the heading noise the filters name, and the clean twin of the restarted logger's drive (a fused
heading without a rate bias) with a residual gyro bias of 0.005 deg/s in place of the phone grade's 0.05, and (stop
73) with the one the filters' warning of a rate bias the fixes taught names on it. Trial 7 (``--trial 7``,
``gen_drives_7.py``, stop 74) runs its five drives beside their twins (the first, whose clock steps an hour, is
refused naming the step), the first split at that step as two drives and filled as stop 73's refusal offered (an
hour of interpolated dead reckoning), the arrival-stamped fixes with a latency state
from the start, the gyro shaken at idle with ``--hold-heading-at-stops``, and the RTK drive with the bias instability
the reader names on it; since stop 75 also the arrival-stamped fixes re-stamped on the receiver's grid
(``--restamp-fixes``, the remedy the reader's warning names). ``--only PREFIX`` runs only the lines whose label
starts with it (stop 75 reran trial 7's d3 lines alone: ``--trial 7 --only d3 > trial_7_stop75_d3.txt``). Trial 8
(``--trial 8``, ``gen_drives_8.py``, stop 75) runs its five drives beside their twins, the Doppler speed's drive with
the spoofer's remedy stop 74's reader named on it, the track drive with the filters' gyro-scale remedy and with that
user's own (its cold start's fixes dropped as well), and the lever arm's twin with the correlated fixes inflated.
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
RUNS_3 = [(f"{name}{twin}", f"{name}{twin}.csv", []) for name in ("ferry", "snow", "utm", "carpark", "spoof", "wrap")
          for twin in ("", "_clean")] + [("ferry split at 229-593 s", "ferry.csv", ["--split", "229,593"]),
                                         ("ferry --gps-scale-window 30", "ferry.csv", ["--gps-scale-window", "30"]),
                                         ("carpark --gyro-scale-sd 0.01", "carpark.csv", ["--gyro-scale-sd", "0.01"])]
RUNS_4 = [(f"{name}_{twin}", f"{name}_{twin}.csv", []) for name in (
    "d1_gyro_warmup", "d2_speed_quant_cutoff", "d3_jitter_drops", "d4_nan_dups", "d5_gyro_sat_odo_drift", "d6_garage_reacq")
    for twin in ("fault", "clean")] + [
    ("d3 --fill-gaps 0.42", "d3_jitter_drops_fault.csv", ["--fill-gaps", "0.42"]),
    ("d5 saturation alone", "d5_gyro_sat_odo_drift_satonly.csv", []),
    ("d5 scale drift alone", "d5_gyro_sat_odo_drift_driftonly.csv", []),
    ("d1 --gyro-bias-instability (the warning's)", "d1_gyro_warmup_fault.csv",
     ["--from-warning", r"--gyro-bias-instability (\d+)"])]
RUNS_6 = [(f"{name}{twin}", f"{name}{twin}.csv", []) for name in ("dualrx", "smoothed", "magsteps", "sigma99",
                                                                   "enu_restart") for twin in ("", "_clean")] + [
    ("smoothed --gps-latency 1.5 (the reader's remedy)", "smoothed.csv", ["--gps-latency", "1.5"]),
    ("magsteps --heading-noise 1.5 (the filters' remedy)", "magsteps.csv", ["--heading-noise", "1.5"]),
    ("enu_restart_clean --gyro-bias 0.005", "enu_restart_clean.csv", ["--gyro-bias", "0.005"]),
    ("enu_restart_clean --gyro-bias (the warning's)", "enu_restart_clean.csv",
     ["--from-warning", r"--gyro-bias [\d.]+\d"])]
RUNS_7 = [(f"{name}{twin}", f"{name}{twin}.csv", []) for name in ("d1_dst_jump", "d2_latlon_4dp", "d3_fix_latency",
                                                                   "d4_idle_vibration", "d5_rtk_float")
          for twin in ("", "_clean")] + [
    ("d1 split at its clock's step (the refusal's remedy)", "d1_dst_jump.csv", ["--split", "298.7,3898.6"]),
    ("d1 --fill-gaps 3600.1 (stop 73's refusal's first remedy)", "d1_dst_jump.csv", ["--fill-gaps", "3600.1"]),
    ("d3 --gps-latency-sd 0.5", "d3_fix_latency.csv", ["--gps-latency-sd", "0.5"]),
    ("d3 --restamp-fixes (stop 75)", "d3_fix_latency.csv", ["--restamp-fixes"]),
    ("d4 --hold-heading-at-stops", "d4_idle_vibration.csv", ["--hold-heading-at-stops"]),
    ("d5 --gyro-bias-instability (the reader's)", "d5_rtk_float.csv",
     ["--from-warning", r"--gyro-bias-instability (\d+)"])]
TRIAL = int(sys.argv[sys.argv.index("--trial") + 1]) if "--trial" in sys.argv else 1
ONLY = sys.argv[sys.argv.index("--only") + 1] if "--only" in sys.argv else ""
GENERATOR = {1: "gen_drives.py", 2: "gen_drives_2.py", 3: "gen_drives_3.py", 4: "gen_drives_4.py",
             6: "gen_drives_6.py", 7: "gen_drives_7.py", 8: "gen_drives_8.py"}[TRIAL]


RUNS_8 = [(f"{name}{twin}", f"{name}{twin}.csv", []) for name in ("d1_leverarm", "d2_doppler", "d3_spare", "d4_track",
                                                                   "d5_pessimistic") for twin in ("", "_clean")] + [
    ("d2 --drop-fixes 100,230 (stop 74's reader's remedy)", "d2_doppler.csv", ["--drop-fixes", "100,230"]),
    ("d4 --gyro-scale-sd 0.01 (the filters' remedy)", "d4_track.csv", ["--gyro-scale-sd", "0.01"]),
    ("d4 --drop-fixes 0,55 --gyro-scale-sd 0.01 (that user's own)", "d4_track.csv",
     ["--drop-fixes", "0,55", "--gyro-scale-sd", "0.01"]),
    ("d1_clean --correlated-fixes inflate (that user's own)", "d1_leverarm_clean.csv", ["--correlated-fixes", "inflate"])]


def split(path, within):
    """The drive ``path`` as two CSVs: its rows before and after the times ``within`` (s, "a,b")."""
    a, b = (float(v) for v in within.split(","))
    with open(path) as fh:
        header, *rows = fh.read().splitlines()
    parts = []
    for name, keep in (("before", lambda t: t < a), ("after", lambda t: t > b)):
        part = path[:-4] + f"_{name}.csv"
        with open(part, "w") as fh:
            fh.write("\n".join([header] + [r for r in rows if keep(float(r.split(",")[0]))]) + "\n")
        parts.append(part)
    return parts


def cells(text):
    """Per drive table in the command's output: its name and the kinds' median / max."""
    out = []
    for block in re.split(r"^### real drive ", text, flags=re.M)[1:]:
        row = []
        for k in KINDS:
            m = re.search(rf"^\| {re.escape(k)} \| ([\d.]+) \| [\d.]+ \| ([\d.]+) \|", block, re.M)
            row.append(f"{k} {m.group(1)} / {m.group(2)}" if m else f"{k} -")
        head = re.match(r"(\S+): (.*?), error at", block)
        out.append((head.group(1), row, head.group(2)) if head else ("?", row, ""))
    return out

with tempfile.TemporaryDirectory() as folder:
    subprocess.run([sys.executable, os.path.join(HERE, GENERATOR), folder], check=True, capture_output=True)
    for label, csv, extra in {1: RUNS, 2: RUNS_2, 3: RUNS_3, 4: RUNS_4, 6: RUNS_6, 7: RUNS_7, 8: RUNS_8}[TRIAL]:
        if not label.startswith(ONLY):
            continue
        drives = [os.path.join(folder, csv)]
        if "--split" in extra:
            drives = split(drives[0], extra[extra.index("--split") + 1])
            extra = []
        for grade in ("phone", "survey"):
            cmd = [sys.executable, "-m", "filterwnn.cli", "study", "dr", *sum((["--drive", d] for d in drives), []),
                   "--grade", grade, "--jobs", "1", "--no-progress", "--no-figures",
                   "--out", os.path.join(folder, "out")]
            if "--from-warning" in extra:  # the remedy's value as the warning names it on the drive as it is
                said = subprocess.run(cmd, capture_output=True, text=True).stderr
                found = re.search(extra[extra.index("--from-warning") + 1], said)
                extra = found.group(0).split() if found else []
                label += f" = {' '.join(extra)}" if found else " (not named)"
            p = subprocess.run(cmd + extra, capture_output=True, text=True)
            n_warn = sum(1 for line in p.stderr.splitlines() if "warning:" in line)
            refused = "" if p.returncode == 0 else " | " + p.stderr.strip().splitlines()[-1][:160]
            tables = cells(p.stdout) or [("", [f"{k} -" for k in KINDS], "")]
            for name, row, header in tables:
                part = f" ({name})" if len(tables) > 1 else ""
                print(f"{label}{part} {grade} | rc {p.returncode} | " + " | ".join(row) + f" | {n_warn} warnings"
                      + (f" | {header}" if header else "") + refused, flush=True)
