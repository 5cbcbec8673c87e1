"""The second user trial's compass drive (``gen_drives_2.py``'s ``drive_A``, kept as written there) and two more
drives with the same compass on other routes (seeds 102 and 103 in place of its 101: the same deviation, other
roads and other steel), through the command, phone grade (stop 70).

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/user-trial/compass.py > docs/study-outputs/dr/user-trial/compass.txt

Per drive: the drive reader's deviation warning (the card it measured from the drive's own fixes, or none), and the
median / max at the outage ends (m) of DR-mech (dead reckoning alone from the true start) and the 8-state kinds,
read as given, with the card the reader measured on that drive, and with the card measured on drive 101 (a
compass swing done once, applied to later drives). The drive's true deviation, as a function of the true
heading psi: 7 sin(psi + 0.6) + 4 cos(2 psi + 0.3) + 3 degrees, and 8-15 degree bumps near steel.
"""
import os
import re
import subprocess
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
_argv, sys.argv = sys.argv, sys.argv[:1]
import gen_drives_2 as g  # noqa: E402
sys.argv = _argv

from filterwnn.navigation.drives import read_drive_csv  # noqa: E402

KINDS = ("DR-mech", "EKF-8", "UKF-8", "SUKF-8")


def compass_drive(seed, folder):
    """``gen_drives_2.drive_A`` with its generator's seed ``seed`` (101 writes the trial's drive, to the byte)."""
    np_rng = np.random.default_rng
    g.np.random.default_rng = lambda _seed: np_rng(seed)  # drive_A draws from default_rng(101)
    g.OUT = os.path.join(folder, f"{seed}_")
    try:
        g.drive_A()
    finally:
        g.np.random.default_rng = np_rng
    return g.OUT + "A_compass_oslo.csv"


def card_of(path):
    """The card the drive reader warns of (a list of four degrees), or None, and the warning's first words."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        read_drive_csv(path)
    for w in caught:
        m = re.search(r"--heading-deviation (\S+)\)", str(w.message))
        if m:
            span = re.search(r"from (\S+) to (\S+) degrees", str(w.message))
            p = re.search(r"p = (\S+) beside", str(w.message))
            return m.group(1), f"from {span.group(1)} to {span.group(2)} deg, p = {p.group(1)}"
    return None, "no deviation warning"


def scores(path, folder, card=None):
    cmd = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--grade", "phone", "--jobs", "1",
           "--no-progress", "--no-figures", "--out", os.path.join(folder, "out")]
    if card:
        cmd += ["--heading-deviation", card]
    p = subprocess.run(cmd, capture_output=True, text=True)
    cells = []
    for k in KINDS:
        m = re.search(rf"^\| {re.escape(k)} \| ([\d.]+) \| [\d.]+ \| ([\d.]+) \|", p.stdout, re.M)
        cells.append(f"{k} {m.group(1)} / {m.group(2)}" if m else f"{k} -")
    said = sum(1 for line in p.stderr.splitlines() if "direction of travel" in line)
    return f"rc {p.returncode} | " + " | ".join(cells) + f" | deviation warnings {said}"


with tempfile.TemporaryDirectory() as folder:
    with open(os.devnull, "w") as quiet:
        _out, sys.stdout = sys.stdout, quiet  # (the generator prints what it wrote)
        paths = {seed: compass_drive(seed, folder) for seed in (101, 102, 103)}
        sys.stdout = _out
    cards = {}
    for seed, path in paths.items():
        cards[seed], said = card_of(path)
        print(f"drive {seed}: the reader: {said}" + (f"; card {cards[seed]}" if cards[seed] else ""), flush=True)
    for seed, path in paths.items():
        print(f"drive {seed}, as given | {scores(path, folder)}", flush=True)
        if cards[seed]:
            print(f"drive {seed}, its own card {cards[seed]} | {scores(path, folder, cards[seed])}", flush=True)
        if seed != 101 and cards[101]:
            print(f"drive {seed}, drive 101's card {cards[101]} | {scores(path, folder, cards[101])}", flush=True)
