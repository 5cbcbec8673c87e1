"""Whether the remedy of the end-of-drive latency warning (stop 62, ``GPSDRFilter.end_of_drive``) mends the drives it
fires on: each drive at hand on which ``end_of_drive_0.txt`` / ``end_of_drive_1.txt`` put the monitor's end z-score
past ``LATENCY_END_Z`` (an estimate of 0.1 s or more, the latency not told before), and the phone analog (seed 0)
with its fixes 0.3 s late, through ``filterwnn study dr --drive CSV --grade phone --filters EKF-8``; then again with
the ``--gps-latency`` the command's warning names. Per drive: the true latency, the value named, and the outage ends
(median / max, m) before and after. Run from the repository root::

    python docs/study-outputs/dr/log-faults/latency_at_end_remedy.py > docs/study-outputs/dr/log-faults/latency_at_end_remedy.txt
"""
import os, re, sys, tempfile
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import drives_at_hand, ekf8_command, held_out  # puts tests/ and the random drives on the path
import random_drives

DRIVES = ["p2 s209", "p3 s7", "p3 s201", "p3 s202", "p3 s222", "p3 s226", "p3 s269", "p3 s271"]


def command(path, tmp, extra=()):
    """The EKF-8's outage ends and the ``--gps-latency`` the end-of-drive warning names (None: none)."""
    ends, err = ekf8_command(path, tmp, extra)
    named = re.search(r"over the whole drive .*?--gps-latency ([-\d.]+)", err)
    return ends, (named.group(1) if named else None)


def at_hand(key):
    return {**drives_at_hand()}[key]()


with tempfile.TemporaryDirectory() as tmp:
    cases = [(k, lambda k=k: at_hand(k)) for k in DRIVES]
    cases.append(("phone0 +0.3 s", lambda: held_out.columns("phone", 0, gps_latency=0.3)))
    for key, make in cases:
        true = random_drives.faults(int(key[4:]))[0].get("gps_latency", 0.0) if key.startswith("p3 ") else (
            0.3 if key.startswith("phone0") else 0.0)
        path = held_out.write_csv(os.path.join(tmp, "d.csv"), make())
        before, named = command(path, tmp)
        after = command(path, tmp, ["--gps-latency", named])[0] if named else "-"
        print(f"{key:14s} fixes {true:.2f} s late | named {named or '-':>5s} s | EKF-8 {before} -> {after}", flush=True)
