"""Rerun the u-blox ADR new-user study from scratch.

    python docs/study-outputs/dr/ublox-log/run.py [--work DIR] [--only NAME,NAME] [--seed N]

Simulates the log (sim_ublox.py), converts it (convert.py) into the careful drive CSV and one CSV
per user mistake, runs `filterwnn study dr --drive CSV --grade G --out ... --no-figures` on each
(one process at a time), and writes DIR/results.md: exit code, every warning/error line, and the
table rows (median / max at the outage ends, each filter).  Then scores the drive's own outages
(the tunnel and the garage) with real_outages.py.  Scratch goes to DIR (default /tmp/ublox-user/work).
"""
import json
import os
import re
import subprocess
import sys
import time

sys.dont_write_bytecode = True  # write nothing but the scripts into this folder
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from convert import convert  # noqa: E402
from sim_ublox import simulate  # noqa: E402

RUNS = [
    # (csv name, grade, extra args)
    ("ok", "phone", []),
    ("ok", "survey", []),
    ("ok", "phone", ["--gyro-bias", "0.18"]),
    ("ok_bias_removed", "phone", []),
    ("ok_bias_removed", "survey", []),
    ("receiver_dr_as_fixes", "phone", []),
    ("receiver_dr_as_fixes", "survey", []),
    ("nofix_rows_kept", "phone", []),
    ("latlon_1e7", "phone", []),
    ("latlon_1e7_truth_too", "phone", []),
    ("hacc_mm", "phone", []),
    ("hacc_not_divided", "phone", []),
    ("gspeed_mm_as_speed", "phone", []),
    ("gspeed_ms_as_speed", "phone", []),
    ("headmot_raw_as_heading_deg", "phone", []),
    ("headmot_deg_as_heading_deg", "phone", []),
    ("gyro_raw_counts", "phone", []),
    ("gyro_no_sign_extension", "phone", []),
    ("gyro_in_yaw_rate_rad_column", "phone", []),
    ("gyro_sign_flipped", "phone", []),
    ("esf_clock_unaligned", "phone", []),
    ("esf_clock_off_2s", "phone", []),
    ("esf_clock_off_5s", "phone", []),
    ("esf_clock_off_30s", "phone", []),
    ("esf_clock_off_3600s", "phone", []),
    ("sttag_wrap_not_handled", "phone", []),
    ("tick_wrap_not_handled", "phone", []),
    ("one_wheel_left", "phone", []),
    ("ticks_not_scaled", "phone", []),
    ("tick_delta_as_speed", "phone", []),
    ("itow_ms_as_time", "phone", []),
    ("itow_ms_fixes_only", "phone", []),
]


def run_one(work, name, grade, extra):
    tag = f"{name}__{grade}" + ("__" + "_".join(a.strip("-") for a in extra) if extra else "")
    out = os.path.join(work, "out", tag)
    cmd = ["filterwnn", "study", "dr", "--drive", os.path.join(work, "csv", f"drive_{name}.csv"),
           "--grade", grade, "--out", out, "--no-figures", "--no-progress"] + extra
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
    wall = time.time() - t0
    text = p.stdout + p.stderr
    with open(os.path.join(work, "logs", tag + ".txt"), "w") as f:
        f.write("$ " + " ".join(cmd) + f"\nexit {p.returncode}, {wall:.0f} s\n\n" + text)
    msgs = [ln for ln in text.splitlines() if re.search(r"warning|error|Error|refus|Traceback", ln)]
    rows = {}
    for ln in text.splitlines():
        m = re.match(r"\| (DR-mech|EKF|EKF-8|UKF-8|SUKF-8) \| ([^|]+)\| ([^|]+)\| ([^|]+)\|", ln)
        if m:
            rows[m.group(1)] = (m.group(2).strip(), m.group(4).strip())
    return dict(tag=tag, cmd=" ".join(cmd), rc=p.returncode, wall=round(wall), msgs=msgs, rows=rows)


def main():
    work = sys.argv[sys.argv.index("--work") + 1] if "--work" in sys.argv else "/tmp/ublox-user/work"
    seed = int(sys.argv[sys.argv.index("--seed") + 1]) if "--seed" in sys.argv else 7
    only = sys.argv[sys.argv.index("--only") + 1].split(",") if "--only" in sys.argv else None
    for d in ("log", "csv", "out", "logs"):
        os.makedirs(os.path.join(work, d), exist_ok=True)
    meta = simulate(os.path.join(work, "log"), seed)
    _, info = convert(os.path.join(work, "log"), os.path.join(work, "csv"))
    print(json.dumps(info), flush=True)
    results = []
    for name, grade, extra in RUNS:
        if only and name not in only:
            continue
        r = run_one(work, name, grade, extra)
        results.append(r)
        print(r["tag"], "exit", r["rc"], r["wall"], "s", r["rows"], flush=True)
        with open(os.path.join(work, "results.json"), "w") as f:
            json.dump(dict(meta=meta, info=info, results=results), f, indent=1)
    with open(os.path.join(work, "results.md"), "w") as f:
        f.write("| run | exit | DR-mech | EKF | EKF-8 | UKF-8 | SUKF-8 | messages |\n|---|---|---|---|---|---|---|---|\n")
        for r in results:
            cells = [" / ".join(r["rows"][k]) if k in r["rows"] else "-" for k in
                     ("DR-mech", "EKF", "EKF-8", "UKF-8", "SUKF-8")]
            f.write(f"| {r['tag']} | {r['rc']} | " + " | ".join(cells) + f" | {len(r['msgs'])} |\n")
    if not only or "real_outages" in only:
        subprocess.run([sys.executable, os.path.join(HERE, "real_outages.py"), work], check=False)


if __name__ == "__main__":
    main()
