"""Collect runs/<drive>_<variant>/{stdout,stderr} into one markdown summary (stdout)."""
import re
import sys
from pathlib import Path

ROOT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("runs")
VARIANTS = ["clean", "quant", "dither", "cutoff", "crawl_ctrl", "crawl", "crawlturn_ctrl", "crawlturn", "crawlturn_rep_ctrl", "crawlturn_rep", "delay"]
FILTERS = ["DR-mech", "EKF", "EKF-8", "UKF-8", "SUKF-8"]


def table(path):
    rows = {}
    header = None
    for line in path.read_text().splitlines():
        if line.startswith("| filter"):
            header = [c.strip() for c in line.strip("|").split("|")]
        elif line.startswith("| ") and header and not line.startswith("|---"):
            cells = [c.strip() for c in line.strip("|").split("|")]
            rows[cells[0]] = dict(zip(header, cells))
    return rows


def warnings(path):
    out = []
    for line in path.read_text().splitlines():
        if not line.startswith("filterwnn: warning:") and "Warning" not in line:
            continue
        m = re.search(r"\(and (\d+) more like it", line)
        more = int(m.group(1)) if m else 0
        body = line.replace("filterwnn: warning: ", "")
        m2 = re.match(r"([A-Za-z0-9-]+): (.*)", body)
        who, rest = (m2.group(1), m2.group(2)) if m2 else ("reader", body)
        lead = "GPSDRFilter: " if rest.startswith("GPSDRFilter: ") else ""
        first = who + ": " + lead + re.split(r"(?<=[a-z0-9)])[:;.] ", rest[len(lead):], maxsplit=1)[0]
        out.append((first, 1 + more, body))
    return out


def main():
    for drive in ("phone", "city"):
        print(f"## {drive}\n")
        print("| variant | DR-mech med/max | EKF med/max | EKF-8 med/max | UKF-8 med/max | SUKF-8 med/max | "
              "EKF-8 stops used/rej/reacq/held | UKF-8 stops | SUKF-8 stops | EKF-8 rej/dw/reacq fixes | EKF-8 NIS |")
        print("|---" * 11 + "|")
        for v in VARIANTS:
            d = ROOT / f"{drive}_{v}"
            if not (d / "stdout").exists():
                continue
            t = table(d / "stdout")
            if not t:
                print(f"| {v} | (no table; see {d}/stderr) |")
                continue
            mm = [f"{t[f]['median all']} / {t[f]['max all']}" if f in t else "-" for f in FILTERS]
            sk = [k for k in t["EKF-8"] if k.startswith("stops")][0]
            fk = [k for k in t["EKF-8"] if k.startswith("fixes rejected")][0]
            nk = [k for k in t["EKF-8"] if k.startswith("mean NIS")][0]
            print(f"| {v} | " + " | ".join(mm) + f" | {t['EKF-8'][sk]} | {t['UKF-8'][sk]} | {t['SUKF-8'][sk]} | "
                  f"{t['EKF-8'][fk]} | {t['EKF-8'][nk]} |")
        print()
        for v in VARIANTS:
            d = ROOT / f"{drive}_{v}"
            if not (d / "stderr").exists():
                continue
            print(f"### {drive}_{v} warnings\n")
            for first, n, body in warnings(d / "stderr"):
                print(f"- x{n}: {first[:300]}")
            print()


if __name__ == "__main__":
    main()
