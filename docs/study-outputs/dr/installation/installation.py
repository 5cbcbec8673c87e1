"""Faults of a sensor's installation (issue 23, stop 43): the held-out analogs of seed 0 with a constant added to
every heading (``heading``), every speed scaled (``speed``), or both (``both``: +15 degrees and the speed
times 1.10), run as a user would, then again as the drive
reader's warning (or refusal) tells.

Run from the repository root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/installation/installation.py heading > docs/study-outputs/dr/installation/heading_offset.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/installation/installation.py speed > docs/study-outputs/dr/installation/speed_scale.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/installation/installation.py both > docs/study-outputs/dr/installation/both.txt

A phone mounted askew in its holder, or a heading from a magnetometer (magnetic north: off by the
declination, up to 20 degrees in much of North America and Europe's north), reads a constant more than the
car's course; a speedometer's signal reads high by up to 10 % (a wheel-speed signal with the wrong tyre
circumference by a few per cent). Each line: the drive and the fault added (deg, or the factor);
``filterwnn study dr --drive FILE --grade phone`` (20 outages of 30 s) as run first: its exit code, the
median / max at the outage ends (m) of dead reckoning alone from the true start and of each 8-state kind,
and the value the reader's warning or refusal names (``--heading-offset X`` or ``--speed-scale X``, read
from its text; "-" when it names none); then the same command with it. The analogs' own errors (the phone's
1 degree and 2 % scale, the city's 1 %, the 1 Hz drive's 1.5 %) stay in the drives.
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests"))

import _held_out_drives as held_out  # noqa: E402

FILTERS = ("DR-mech", "EKF-8", "UKF-8", "SUKF-8")
FAULTS = {"heading": ("--heading-offset", (5.0, 10.0, 15.0, -15.0, 20.0, 30.0, 90.0)),
          "speed": ("--speed-scale", (0.92, 1.04, 1.06, 1.10, 1.20)),
          "both": ("--(?:heading-offset|speed-scale)", ((15.0, 1.10),))}


def command(path, out, option, *extra):
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    cmd = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--grade", "phone", "--no-figures",
           "--no-progress", "--jobs", "1", "--out", out, "--filters", ",".join(FILTERS), *extra]
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=out)
    rows = {}
    for line in p.stdout.splitlines():
        cells = [x.strip() for x in line.split("|")]
        if len(cells) > 4 and cells[1] in FILTERS:
            rows[cells[1]] = f"{cells[2]} / {cells[4]}"
    refused = p.stderr.strip().splitlines()[-1].replace(os.path.dirname(path), "<tmp>") if p.stderr.strip() else ""
    cells = " | ".join(f"{k} {rows[k]}" for k in FILTERS) if rows else refused[:160]
    told = re.findall("(" + option + r") (-?[0-9.]+)\)", p.stderr)
    return p.returncode, cells, [a for pair in dict(told).items() for a in pair]


def main(fault):
    option, values = FAULTS[fault]
    tmp = tempfile.mkdtemp()
    for name in ("phone", "city", "one_hz"):
        base = held_out.columns(name, 0)
        for v in values:
            deg, factor = (v, 1.0) if fault == "heading" else (0.0, v) if fault == "speed" else v
            cols = dict(base, heading=np.mod(base["heading"] + np.deg2rad(deg), 2 * np.pi), speed=base["speed"] * factor)
            label = " ".join(([f"{deg:+g} deg"] if deg else []) + ([f"speed x{factor:g}"] if factor != 1.0 else []))
            path = held_out.write_csv(os.path.join(tmp, f"{name}_{'both' if fault == 'both' else f'{v:g}'}.csv"), cols)
            rc, cells, told = command(path, tmp, option)
            print(f"{name} {label} | rc {rc} | {cells} | told: {' '.join(told[1::2]) or '-'}", flush=True)
            if told:
                rc, cells, _ = command(path, tmp, option, *told)
                print(f"    as told, {' '.join(told)} | rc {rc} | {cells}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1])
