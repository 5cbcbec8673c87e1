"""The reader's clock-offset check with its warning past 1 s (stop 60; 3 s before): the offset it finds, and its
significance, on every drive on time at hand (the analogs' seeds 0-9, the random drives of protocols 2 and 3, seeds
0-29 and 200-279, and the u-blox log's right conversions) and on the analogs (seeds 0-2) with their fixes stamped
0.5-2 s off either way. A line per drive: (offset found (s), p, wins, chords); "WARNS" where the check warns (p at
most 1e-3 and the offset past CLOCK_OFFSET_WARN_S). Run from the repository root, after the u-blox log's run.py
(its CSVs in DIR, default /tmp/ublox-user/work/csv)::

    python docs/study-outputs/dr/log-faults/clock_offset_1s.py [DIR] > docs/study-outputs/dr/log-faults/clock_offset_1s.txt
"""
import glob
import os
import sys
import tempfile
import warnings

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.join(HERE, "..", "..", "..", "..", "tests"), os.path.join(HERE, "..", "random-drives")]
import _held_out_drives as held_out  # noqa: E402
import random_drives  # noqa: E402
from filterwnn.navigation import _plausibility as P  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402

seen = []
_found = P.clock_offset
P.clock_offset = lambda *a, **k: seen.append(_found(*a, **k)) or seen[-1]


def found(path):
    seen.clear()
    try:
        read_drive_csv(path)
    except ValueError:
        pass
    r = seen[0] if seen else None
    warns = r is not None and r[1] <= P._CLOCK_LEVEL and abs(r[0]) > P.CLOCK_OFFSET_WARN_S
    return r, warns


def main(ublox):
    on_time = {}
    for name in held_out.HELD_OUT:
        for seed in range(10):
            on_time[f"{name} seed {seed}"] = lambda name=name, seed=seed: held_out.columns(name, seed)
    for s in list(range(0, 30)) + list(range(200, 280)):
        for p in (2, 3):
            on_time[f"protocol {p} seed {s}"] = lambda s=s, p=p: random_drives.drive(s, p)[1]
    late = {f"{name} seed {seed} stamped {lat:+g} s": (lambda name=name, seed=seed, lat=lat:
                                                          held_out.columns(name, seed, gps_latency=lat))
            for name in held_out.HELD_OUT for lat in (0.5, 1.0, 1.5, 2.0, -1.0, -2.0) for seed in (0, 1, 2)}
    with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for title, drives in (("on time", on_time), ("stamped off", late)):
            n_warn = 0
            for key, cols in drives.items():
                r, warns = found(held_out.write_csv(os.path.join(tmp, "d.csv"), cols()))
                n_warn += warns
                print(f"{key}: {r}{' WARNS' if warns else ''}", flush=True)
            print(f"## {title}: {len(drives)} drives, the check warns on {n_warn}\n", flush=True)
        paths = sorted(glob.glob(os.path.join(ublox, "drive_ok*.csv"))) + [
            os.path.join(ublox, f"drive_esf_clock_off_{s}s.csv") for s in (2, 5)]
        for path in paths:
            r, warns = found(path)
            print(f"u-blox {os.path.basename(path)}: {r}{' WARNS' if warns else ''}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "/tmp/ublox-user/work/csv")
