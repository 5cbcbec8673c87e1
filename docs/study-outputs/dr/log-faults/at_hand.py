"""The drives at hand that the log-faults probes scan for false alarms (stops 60-61): the analogs' seeds 0-9 (phone,
city, 1 Hz) and the random drives of protocols 2 and 3, seeds 0-29 and 200-279; 250 drives, each a function that
builds its drive CSV's columns (``_held_out_drives.write_csv`` writes them), in this order."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TESTS = os.path.join(HERE, "..", "..", "..", "..", "tests")
sys.path[:0] = [TESTS, os.path.join(TESTS, "navigation"), os.path.join(HERE, "..", "random-drives")]
import _held_out_drives as held_out  # noqa: E402
import random_drives  # noqa: E402


def drives_at_hand():
    """``{name: function returning the drive's columns}`` for the 250 drives."""
    drives = {}
    for name in ("phone", "city", "one_hz"):
        for seed in range(10):
            drives[f"{name}{seed}"] = lambda name=name, seed=seed: held_out.columns(name, seed)
    for s in list(range(0, 30)) + list(range(200, 280)):
        for p in (2, 3):
            drives[f"p{p} s{s}"] = lambda s=s, p=p: random_drives.drive(s, p)[1]
    return drives


def drives_with_rest():
    """The 271 drives the filter's probes scan (stops 61-62): the tests' drive from rest (``FROM_REST``) over seeds
    0-19, then :func:`drives_at_hand`, then the shipped sample; each a function returning a ``DRRun``, the columns of
    a drive CSV, or the sample's path (:func:`read_at_hand` reads any of them)."""
    from test_gpsdr import FROM_REST
    from filterwnn.navigation.drives import sample_drive_path
    from filterwnn.navigation.scenarios import simulate_scenario

    drives = {f"rest{s}": (lambda s=s: simulate_scenario(FROM_REST, rng=s)) for s in range(20)}
    drives.update(drives_at_hand())
    drives["sample"] = sample_drive_path
    return drives


def scanned(args):
    """``(drives, keys)`` a probe scans for its command line ``args``: ``files CSV...``, the CSVs given (each a
    function returning its path); else ``[mode] PART``, half the drives of :func:`drives_with_rest` and onavdata's two
    (part 0 or 1, every other one)."""
    if args[0] == "files":
        drives = {p: (lambda p=p: p) for p in args[1:]}
        return drives, list(drives)
    from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive

    drives = drives_with_rest()
    for c in CAR_DRIVES:
        drives[f"onav {c}"] = lambda c=c: load_car_drive(c)
    return drives, list(drives)[int(args[-1])::2]


def read_at_hand(obj, tmp):
    """The ``DRRun`` of what a function of :func:`drives_with_rest` returned (a CSV written in the folder ``tmp``)."""
    from filterwnn.navigation.drives import read_drive_csv

    if isinstance(obj, str):
        return read_drive_csv(obj)
    if hasattr(obj, "z_dr"):
        return obj
    return read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), obj))


def ekf8_command(path, tmp, extra=()):
    """``filterwnn study dr --drive path --grade phone --filters EKF-8`` (one BLAS thread, outputs in ``tmp``) with
    the settings ``extra``: the EKF-8's "median / max" at the outage ends (or "rc N" where it exits without a table)
    and the command's stderr."""
    import subprocess

    cmd = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", path, "--grade", "phone", "--no-figures",
           "--no-progress", "--jobs", "1", "--out", tmp, "--filters", "EKF-8", *extra]
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
    row = [line for line in p.stdout.splitlines() if line.startswith("| EKF-8 |")]
    cells = [c.strip() for c in row[0].split("|")] if row else None
    return (f"{cells[2]} / {cells[4]}" if cells else f"rc {p.returncode}"), p.stderr
