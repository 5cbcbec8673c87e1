"""The ranges the README quotes, read from ``bench_peers_results.txt``.

    python benchmarks/bench_peers_summary.py --prefix Z        # the runs named Z1, Z2, ...
    python benchmarks/bench_peers_summary.py --prefix Y --protocol steady

For each row of ``bench_peers.py``: the range of filterwnn / floor and of filterwnn / the peer
the row's target names, with how many runs meet each target; for the 160-weight row also the
hand-written NumPy step's ratio to the floor and ours to it. Nothing is measured here: it reads
the runs as they were written.
"""

from __future__ import annotations

import argparse
import re
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "bench_peers_results.txt"


def _num(cell):
    return float(cell.split()[0].replace(",", ""))


def runs(text, prefix, protocol=None):
    """``{run name: [(work, cells), ...]}`` for the runs whose name starts with ``prefix``."""
    out = {}
    for block in text.split("\n## run ")[1:]:
        name = block.split()[0]
        if not re.fullmatch(re.escape(prefix) + r"\d+", name):
            continue
        m = re.search(r"protocol (\w+)", block)
        if protocol is not None and (m.group(1) if m else "turns") != protocol:
            continue
        rows = [[c.strip() for c in line.split("|")[1:-1]] for line in block.splitlines()
                if line.startswith("| ") and not line.startswith("| work")]
        out[name] = rows
    return out


def summarize(found):
    table = {}
    for rows in found.values():
        for cells in rows:
            work, ours, alts, floor, ratios = cells
            got = table.setdefault(work, {"floor": [], "peer": [], "hand": [], "ours/hand": [], "met": [0, 0],
                                          "peer_met": [0, 0], "numpy/peer": [], "compiled/numpy": []})
            rs = re.findall(r"([\d.]+)x \(target <= ([\d.]+)x: (yes|no)\)", ratios)
            got["floor"].append(float(rs[0][0]))
            got["met"][0] += rs[0][2] == "yes"
            got["met"][1] += 1
            if len(rs) > 1:
                got["peer"].append(float(rs[1][0]))
                got["peer_met"][0] += rs[1][2] == "yes"
                got["peer_met"][1] += 1
            nb = re.search(r"filterwnn bank, NumPy step ([\d,.]+) us", alts)
            dx = re.search(r"dynamax jit\(vmap\) ([\d,.]+) us", alts)
            if nb:  # the bank's NumPy step beside its compiled one
                numpy_step = float(nb.group(1).replace(",", ""))
                got["compiled/numpy"].append(_num(ours) / numpy_step)
                if dx:
                    got["numpy/peer"].append(numpy_step / float(dx.group(1).replace(",", "")))
            h = re.search(r"NumPy by hand ([\d,.]+) us", alts)
            if h:
                hand = float(h.group(1).replace(",", ""))
                got["hand"].append(hand / _num(floor))
                got["ours/hand"].append(_num(ours) / hand)
    return table


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--prefix", required=True, help="the runs' name prefix (Y for Y1, Y2, ...)")
    ap.add_argument("--protocol", choices=("turns", "steady"), default=None, help="only the runs of this protocol")
    ap.add_argument("--results", default=str(RESULTS))
    args = ap.parse_args(argv)
    found = runs(Path(args.results).read_text(), args.prefix, args.protocol)
    if not found:
        raise SystemExit(f"no run named {args.prefix}<n> in {args.results}")
    print(f"{len(found)} runs: {', '.join(found)}")
    for work, got in summarize(found).items():
        line = (f"{work}: / floor {min(got['floor']):.2f}-{max(got['floor']):.2f}x "
                f"(target met {got['met'][0]} of {got['met'][1]})")
        if got["peer"]:
            line += (f"; / peer {min(got['peer']):.2f}-{max(got['peer']):.2f}x "
                     f"(target met {got['peer_met'][0]} of {got['peer_met'][1]})")
        if got["compiled/numpy"]:
            line += f"; compiled / NumPy step {min(got['compiled/numpy']):.2f}-{max(got['compiled/numpy']):.2f}x"
        if got["numpy/peer"]:
            line += f"; NumPy step / peer {min(got['numpy/peer']):.2f}-{max(got['numpy/peer']):.2f}x"
        if got["hand"]:
            line += (f"; NumPy by hand / floor {min(got['hand']):.2f}-{max(got['hand']):.2f}x, "
                     f"ours / by hand {min(got['ours/hand']):.2f}-{max(got['ours/hand']):.2f}x")
        print(line)


if __name__ == "__main__":
    main()
