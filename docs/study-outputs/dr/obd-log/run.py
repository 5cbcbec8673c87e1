"""Rerun the whole study from scratch: simulate the log, convert it (careful + every mistake), run
`filterwnn study dr --drive CSV --grade phone` on each (one at a time), the careful one with --grade survey
too, retry every run whose messages name a command-line setting with a value (the remedy they give), score
the drive's own tunnel (real_outages.py), and write results.md.

    python run.py --work DIR [--filterwnn PATH] [--only NAME,NAME] [--no-remedies]
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
FILTERS = ["DR-mech", "EKF", "EKF-8", "UKF-8", "SUKF-8"]
FLAG = re.compile(r"(--(?:gyro-bias|gyro-bias-instability|heading-offset|speed-scale|gps-latency|odometer-latency|"
                  r"heading-latency|fill-gaps|stop-reopen|min-fix-interval|hdop-sigma|gyro-scale-sd|"
                  r"gps-latency-sd|gps-scale-window|intervals|correlated-fixes)) ([-+]?\d+(?:\.\d+)?|stamps|grid|inflate)")


def run_one(fw, csv, out, extra=()):
    cmd = [fw, "study", "dr", "--drive", csv, "--out", out, "--no-figures", "--no-progress"] + list(extra)
    if "--grade" not in extra:
        cmd[5:5] = ["--grade", "phone"]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t0
    rows = {}
    for line in p.stdout.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if cells and cells[0] in FILTERS and len(cells) > 4:
            rows[cells[0]] = {"median": cells[1], "p90": cells[2], "max": cells[3], "median_moving": cells[4],
                              "max_moving": cells[5], "start": cells[6], "fixes": cells[8]}
    msgs = [l for l in p.stderr.splitlines() if l.startswith("filterwnn:")]
    other = [l for l in p.stderr.splitlines() if l.strip() and not l.startswith("filterwnn:")]
    return {"cmd": " ".join(os.path.relpath(c) if os.path.exists(c) and c != fw else c for c in cmd),
            "rc": p.returncode, "wall_s": round(wall, 1), "rows": rows, "msgs": msgs, "other_stderr": other[-20:]}


def named_flags(msgs):
    """The settings with a value that the messages name (the remedy they give), first mention of each."""
    got = {}
    for m in msgs:
        for flag, val in FLAG.findall(m):
            got.setdefault(flag, val)
        need = re.search(r"--fill-gaps, interpolates gaps up to that long; this one needs ([\d.]+)", m)
        if need:
            got.setdefault("--fill-gaps", need.group(1))
    return got


# settings a user tries without a message naming them (each a question the messages leave open)
EXTRA = {
    "careful": [("the app's GPS delivery latency the docs mention (0.15-0.45 s), given", ["--gps-latency", "0.27"]),
                ("the ECU's 2.7 % overread, given", ["--speed-scale", "1.027"]),
                ("the gyro's true vertical bias, given", ["--gyro-bias", "0.13"])],
    "gyro_nearest_axis": [("a wider gyro scale prior than the message's 0.01", ["--gyro-bias", "0.3", "--gyro-scale-sd", "0.05"])],
    "fused_azimuth_heading": [("the azimuth's true offset (mount 10 deg + declination 3.6 deg), not named by the reader",
                               ["--heading-offset", "-13.6"])],
}


def cell(r, f):
    if f not in r["rows"]:
        return "-"
    x = r["rows"][f]
    return f"{x['median']} / {x['max']}"


def kind_of(msg):
    m = re.match(r"filterwnn: (warning|error): (?:(?:DR-mech|EKF|EKF-8|UKF-8|SUKF-8): )?(.*)", msg)
    if not m:
        return msg[:120]
    return m.group(1) + ": " + m.group(2)[:160]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    ap.add_argument("--filterwnn", default=os.path.join(os.path.dirname(sys.executable), "filterwnn"))
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--only", default="")
    ap.add_argument("--no-remedies", action="store_true")
    a = ap.parse_args()
    W = os.path.abspath(a.work)
    if os.path.exists(W):
        shutil.rmtree(W)
    os.makedirs(W)
    py = sys.executable
    subprocess.run([py, os.path.join(HERE, "sim_obd.py"), "--out", f"{W}/log", "--seed", str(a.seed)], check=True)
    subprocess.run([py, os.path.join(HERE, "convert.py"), "--log", f"{W}/log", "--out", f"{W}/csv"], check=True)
    var = json.load(open(f"{W}/csv/variants.json"))
    sim = json.load(open(f"{W}/log/sim_info.json"))
    names = list(var["variants"])
    if a.only:
        names = [n for n in names if n in a.only.split(",")]
    os.chdir(W)
    res = {}
    for n in names:
        r = run_one(a.filterwnn, f"csv/{n}.csv", f"runs/{n}")
        res[n] = r
        print(f"{n:26s} rc={r['rc']} EKF-8 {cell(r, 'EKF-8'):>20s} msgs={len(r['msgs'])} {r['wall_s']} s", flush=True)
        if n == "careful":
            rs = run_one(a.filterwnn, "csv/careful.csv", "runs/careful_survey", ["--grade", "survey"])
            res["careful --grade survey"] = rs
            print(f"{'careful --grade survey':26s} rc={rs['rc']} EKF-8 {cell(rs, 'EKF-8'):>20s} "
                  f"msgs={len(rs['msgs'])}", flush=True)
        if not a.no_remedies:
            extra, msgs, tag = [], r["msgs"], n
            for round_ in (1, 2):                   # the remedy named, then any the rerun names on top
                fl = {k: v for k, v in named_flags(msgs).items() if k not in extra}
                if not fl:
                    break
                extra = extra + [x for kv in fl.items() for x in kv]
                tag = n + " + remedy" + ("" if round_ == 1 else " 2")
                rr = run_one(a.filterwnn, f"csv/{n}.csv", f"runs/{n}_remedy{round_}", extra)
                rr["remedy"] = " ".join(extra)
                res[tag] = rr
                print(f"{tag:26s} rc={rr['rc']} EKF-8 {cell(rr, 'EKF-8'):>20s} ({rr['remedy']}) "
                      f"msgs={len(rr['msgs'])}", flush=True)
                msgs = rr["msgs"]
        for i, (why, extra) in enumerate(EXTRA.get(n, [])):
            tag = f"{n} + {' '.join(extra)}"
            rr = run_one(a.filterwnn, f"csv/{n}.csv", f"runs/{n}_extra{i}", extra)
            rr["remedy"] = " ".join(extra) + f" (not named by a message: {why})"
            res[tag] = rr
            print(f"{tag:26s} rc={rr['rc']} EKF-8 {cell(rr, 'EKF-8'):>20s} msgs={len(rr['msgs'])}", flush=True)
    json.dump(res, open(f"{W}/results.json", "w"), indent=1)
    p = subprocess.run([py, os.path.join(HERE, "real_outages.py"), "--work", W], capture_output=True, text=True)
    tunnel = p.stdout + ("\n" + p.stderr if p.returncode else "")
    open(f"{W}/real_outages.txt", "w").write(tunnel)

    L = []
    L.append("# results: filterwnn study dr on a phone + OBD-II log\n")
    L.append(f"Written by `python run.py --work {a.work}` (all from scratch). Simulated log: "
             f"{sim['duration_s']:.0f} s, {sim['distance_m']:.0f} m; careful rate {var['rate_hz']} Hz, "
             f"{var['dr_rows']} DR rows, {var['fixes']} fixes. Each cell: median / max error at the 20 outage "
             "ends (m). Every command: `filterwnn study dr --drive CSV --grade phone --out DIR --no-figures "
             "--no-progress` unless said.\n")
    L.append("| run | exit | " + " | ".join(FILTERS) + " | messages | s |")
    L.append("|---|---|" + "---|" * len(FILTERS) + "---|---|")
    for n, r in res.items():
        desc = n if n in var["variants"] else n
        L.append(f"| {desc} | {r['rc']} | " + " | ".join(cell(r, f) for f in FILTERS)
                 + f" | {len(r['msgs'])} | {r['wall_s']} |")
    L.append("\n## What each variant is\n")
    for n, d in var["variants"].items():
        L.append(f"- `{n}`: {d}")
    L.append("\n## The drive's own tunnel (real_outages.py)\n\n```text\n" + tunnel.strip() + "\n```\n")
    L.append("## Every message, by run\n")
    for n, r in res.items():
        L.append(f"### {n}\n\n`{r['cmd']}` -> exit {r['rc']}" + (f" (remedy tried: `{r['remedy']}`)" if "remedy" in r else ""))
        L.append("")
        if r["msgs"]:
            L.append("```text")
            L.extend(r["msgs"])
            L.append("```")
        else:
            L.append("(no warning or error)")
        if r["other_stderr"]:
            L.append("\nother stderr (last lines):\n```text")
            L.extend(r["other_stderr"])
            L.append("```")
        L.append("")
    open(os.path.join(HERE, "results.md"), "w").write("\n".join(L) + "\n")
    open(f"{W}/results.md", "w").write("\n".join(L) + "\n")
    print("wrote", os.path.join(HERE, "results.md"))


if __name__ == "__main__":
    main()
