"""How long ``filterwnn study dr --drive`` takes on a long, high-rate log, in one process and with ``--jobs``.

A CAN logger writes 50-100 Hz; each GPS/DR filter passes over the drive with its fixes, then runs each outage
again, in Python, step by step. From 40,000 steps times filters (``filterwnn.studies.dr._real.PARALLEL_STEPS``)
the command runs the filters side by side in ``--jobs`` worker processes. The baseline is the same command with
``--jobs 1`` (what every earlier version did), run in the same session.

Drive: the phone analog's route and sensors (``tests/_held_out_drives.py``, seed 0's draws) sampled at 50 Hz
(15 minutes: 45,000 steps, 1 Hz fixes), written as a drive CSV; the command as a user runs it (``--grade phone``,
the four filters, 20 outages of 30 s, ``--no-figures --no-progress``), timed as a whole (start-up and reading
included). The saved tables of every run must be identical. Median of the repeats; ``--jobs 1`` and ``--jobs
J`` take turns within each repeat.

Run: ``python benchmarks/bench_drive_jobs.py [--repeats 3] [--jobs 2] [--rate 50]``.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))  # the drive analogs

import numpy as np  # noqa: E402

import _held_out_drives as held_out  # noqa: E402


def write_drive(path, rate):
    """The phone analog (seed 0's generator) at ``rate`` Hz, 1 Hz fixes, as a drive CSV; and its steps."""
    cols = held_out.columns("phone", 0, dt=1.0 / rate)
    return held_out.write_csv(path, cols), len(cols["time"])


def run_command(drive, out, jobs):
    """Seconds of ``filterwnn study dr --drive`` with ``--jobs``, and its saved table's text."""
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", PYTHONWARNINGS="ignore")
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", drive, "--grade", "phone",
                    "--out", out, "--no-figures", "--no-progress", "--jobs", str(jobs)],
                   check=True, capture_output=True, env=env, cwd=ROOT)
    seconds = time.perf_counter() - t0
    table = next(Path(out).glob("real_drive_*_outage_errors.md")).read_text()
    return seconds, table


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--rate", type=float, default=50.0, help="DR samples per second (default 50)")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        drive, n = write_drive(os.path.join(tmp, f"phone_{args.rate:g}hz.csv"), args.rate)
        times, tables = {1: [], args.jobs: []}, set()
        for r in range(args.repeats):
            for jobs in times:
                s, table = run_command(drive, os.path.join(tmp, f"out_{r}_{jobs}"), jobs)
                times[jobs].append(s)
                tables.add(table)
        if len(tables) != 1:
            raise SystemExit("the saved tables differ between runs")
    base = float(np.median(times[1]))
    print(f"{platform.machine()}, {os.cpu_count()} cores, median of {args.repeats}; the phone analog at "
          f"{args.rate:g} Hz ({n} steps, 900 s, 1 Hz fixes), four filters; the saved tables identical")
    print("| command | seconds | against --jobs 1 |")
    print("|---|---|---|")
    for jobs, ts in times.items():
        med = float(np.median(ts))
        print(f"| --jobs {jobs} | {med:.1f} ({', '.join(f'{t:.1f}' for t in ts)}) | {med / base:.2f} |")


if __name__ == "__main__":
    main()
