"""How long the README's test command takes: ``python -m pytest`` from the repository root (the default run,
a worker a core by ``setup.cfg``'s ``-n auto``), and with ``--one-process`` also ``python -m pytest -n 0``
beside it. Prints each wall time and the machine's cores; the guide keeps the default run under 10 minutes
on a 2-core machine.

    python benchmarks/bench_test_suite.py [--one-process] >> benchmarks/bench_test_suite_results.txt
"""
import argparse
import datetime
import os
import platform
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def timed(extra):
    start = time.perf_counter()
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", *extra], cwd=ROOT, capture_output=True, text=True)
    last = (run.stdout.strip().splitlines() or [""])[-1]
    return time.perf_counter() - start, run.returncode, last


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--one-process", action="store_true", help="also time the suite with -n 0")
    a = ap.parse_args()
    model = platform.processor() or platform.machine()
    if os.path.exists("/proc/cpuinfo"):
        model = next((ln.split(":", 1)[1].strip() for ln in open("/proc/cpuinfo") if ln.startswith("model name")), model)
    head = subprocess.run(["git", "log", "-1", "--format=%h"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    print(f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, commit {head}, {os.cpu_count()} cores "
          f"({model})")
    for label, extra in [("python -m pytest", [])] + ([("python -m pytest -n 0", ["-n", "0"])] if a.one_process else []):
        seconds, rc, last = timed(extra)
        print(f"  {label}: {seconds:.0f} s, rc {rc}: {last}", flush=True)
