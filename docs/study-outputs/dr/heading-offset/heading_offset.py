"""A heading whose zero is off (issue 23, stop 43): the held-out analogs of seed 0 with a constant added to
every heading, run as a user would, then again as the drive reader's warning (or refusal) tells.

Run from the repository root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/heading-offset/heading_offset.py > docs/study-outputs/dr/heading-offset/heading_offset.txt

A phone mounted askew in its holder, or a heading from a magnetometer (magnetic north: off by the
declination, up to 20 degrees in much of North America and Europe's north), reads a constant more than the
car's course. Each line: the drive and the offset added (deg); ``filterwnn study dr --drive FILE --grade
phone`` (20 outages of 30 s) as run first: its exit code, the median / max at the outage ends (m) of dead
reckoning alone from the true start and of each 8-state kind, and the offset the reader's warning or refusal
names (``--heading-offset X``, read from its text; "-" when it names none); then the same command with
``--heading-offset X``. The analogs' own heading offsets (phone: 1 degree) stay in the drives.
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
OFFSETS = (5.0, 10.0, 15.0, -15.0, 20.0, 30.0, 90.0)


def command(path, out, *extra):
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
    told = re.findall(r"--heading-offset (-?[0-9.]+)\)", p.stderr)
    return p.returncode, cells, (told[0] if told else None)


def main():
    tmp = tempfile.mkdtemp()
    for name in ("phone", "city", "one_hz"):
        base = held_out.columns(name, 0)
        for deg in OFFSETS:
            cols = dict(base, heading=np.mod(base["heading"] + np.deg2rad(deg), 2 * np.pi))
            path = held_out.write_csv(os.path.join(tmp, f"{name}_{deg:g}.csv"), cols)
            rc, cells, told = command(path, tmp)
            print(f"{name} {deg:+g} deg | rc {rc} | {cells} | told: {told or '-'}", flush=True)
            if told:
                rc, cells, _ = command(path, tmp, "--heading-offset", told)
                print(f"    as told, --heading-offset {told} | rc {rc} | {cells}", flush=True)


if __name__ == "__main__":
    main()
