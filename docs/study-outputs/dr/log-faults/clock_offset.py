"""A clock offset between the fixes and the DR samples, found by the drive reader (issue 23, stop 48).

A log whose fixes are stamped by one clock and its DR samples by another carries their offset: GPS time leads
UTC by 18 s, and a logger that writes a receiver's GPS-time stamps beside a phone's UTC ones shifts every fix by
that much. Before stop 48 nothing named it: with a truth the reader refused the drive as "another frame", without
one it warned of a 22 degree heading offset (the phone analog, 18 s), and the filters re-acquired and warned of
inconsistent fixes. The reader now looks for it (``filterwnn.navigation._plausibility.clock_offset``): the chords
between fixes against the dead-reckoned displacement over the same stretch, moved by each offset within 30 s,
and a sign test over the chords (at the gate's 0.1 %, times the 121 offsets tried) that the best offset fits
better than none. Past 3 s (the filters' latency state's bound) it warns with the value and the reader's remedy.

Run from the repository root::

    python docs/study-outputs/dr/log-faults/clock_offset.py      # clock_offset.txt

Part 1, what it finds: the analogs of ``tests/_held_out_drives.py`` (seeds 0-2) with their fixes stamped 5 s late
or early, 10 s and 18 s late (the generator's ``gps_latency``), each line the offset found, the test's ``p``, the
chords compared, and whether the reader warned. Part 2, where there is none: the analogs' seeds 0-49, the random
drives of ``../random-drives/random_drives.py`` (protocol 2, seeds 0-89), the shipped sample, the two recorded
drives and the hard bench; each line a drive whose reader warned of an offset (a false alarm), then the counts.
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests"), os.path.join(ROOT, "tests", "navigation"),
                os.path.join(ROOT, "docs", "study-outputs", "dr", "random-drives")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation import _plausibility as P  # noqa: E402
from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive, read_drive_csv, sample_drive_path  # noqa: E402


def read(path):
    """The drive read as ``filterwnn study dr --drive`` reads it, and whether the reader warned of a clock offset."""
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        try:
            run = read_drive_csv(path)
        except ValueError as exc:
            return None, "clock offset" in str(exc) and "gps_latency=" in str(exc), str(exc)
    said = [str(w.message) for w in record if "gps_latency=" in str(w.message)]
    return run, bool(said), said[0] if said else ""


def found(run):
    heading, step = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]], run.z_dr[:, 1]
    sigma = None if run.gps_sigma is None else float(np.median(run.gps_sigma))
    return P.clock_offset(run.scenario.dt, heading, step, run.gps_steps, run.z_gps, sigma)


def main():
    tmp = tempfile.mkdtemp()
    print("# part 1: fixes stamped off")
    for name in held_out.HELD_OUT:
        for lat in (5.0, -5.0, 10.0, 18.0):
            for seed in (0, 1, 2):
                path = held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed, gps_latency=lat))
                _, warned, _ = read(path)
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    f = found(read_drive_csv(path, checks=False))
                cell = "too few chords" if f is None else f"found {f[0]:+g} s, p {f[1]:.2g}, {f[2]} of {f[3]} chords"
                print(f"{name} {seed} fixes {lat:+g} s: {cell}; {'warned' if warned else 'not warned'}", flush=True)
    print("# part 2: fixes on time")
    drives = [(f"{name} {seed}", held_out.write_csv(os.path.join(tmp, f"{name}_{seed}.csv"), held_out.columns(name, seed)))
              for name in held_out.HELD_OUT for seed in range(50)]
    import random_drives as rd
    for seed in range(90):
        _, cols, _ = rd.drive(seed, 2)
        drives.append((f"random {seed}", held_out.write_csv(os.path.join(tmp, f"random_{seed}.csv"), cols)))
    drives.append(("sample", sample_drive_path()))
    alarms = 0
    for label, path in drives:
        _, warned, said = read(path)
        if warned:
            alarms += 1
            print(f"{label}: {said[:200]}", flush=True)
    import test_hard_drives as th
    others = [(d, load_car_drive(d)) for d in CAR_DRIVES]
    others += [(d.__name__, d(np.random.default_rng(np.random.SeedSequence([23, th.DRIVES.index(d)])))[0])
               for d in th.DRIVES]
    for label, run in others:
        f = found(run)
        if f is not None and abs(f[0]) > P.CLOCK_OFFSET_WARN_S and f[1] <= 1e-3:
            alarms += 1
            print(f"{label}: found {f[0]:+g} s, p {f[1]:.2g}", flush=True)
    print(f"# {alarms} false alarms over {len(drives) + len(others)} drives with their fixes on time "
          f"(analogs 0-49, random drives 0-89, the sample, the recorded drives, the hard bench)")


if __name__ == "__main__":
    main()
