"""An interrupted study's last line (stop 66): ``filterwnn study dr`` with two worker processes, sent SIGINT when its
first task is cached (every other run up to 1.5 s later), ``RUNS`` times, beside ``LOAD`` busy processes (a CI
machine running the test suite). Each line: the run, the delay, the exit code, the seconds from the signal to the
exit, and whether the command's own line was the last on stderr with no traceback; then any run where it was not,
with its stderr. Run from the repository root::

    python docs/study-outputs/interrupts/ctrl_c_last_line.py 20 2 > docs/study-outputs/interrupts/ctrl_c_last_line.txt
"""
import os
import pathlib
import random
import signal
import subprocess
import sys
import tempfile
import time

runs, load = int(sys.argv[1]), int(sys.argv[2])
random.seed(0)
env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
busy = [subprocess.Popen([sys.executable, "-c", "while 1: pass"]) for _ in range(load)]
bad = 0
try:
    for k in range(runs):
        with tempfile.TemporaryDirectory() as d:
            d = pathlib.Path(d)
            argv = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--runs", "6", "--scenarios", "straight",
                    "--filters", "EKF,UKF", "--jobs", "2", "--out", str(d / "o"), "--no-figures", "--no-progress",
                    "--cache", str(d / "cache")]
            p = subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                 preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
            delay = random.uniform(0.0, 1.5) if k % 2 else 0.0
            t0 = time.monotonic()
            while not list((d / "cache").glob("*.npz")) and p.poll() is None and time.monotonic() - t0 < 180:
                time.sleep(0.02)
            time.sleep(delay)
            p.send_signal(signal.SIGINT)
            sent = time.monotonic()
            _, err = p.communicate(timeout=120)
            took = time.monotonic() - sent
        lines = err.strip().splitlines()
        ok = p.returncode == 130 and bool(lines) and lines[-1].startswith("filterwnn: interrupted") \
            and "Traceback" not in err
        finished = p.returncode == 0  # the study ended before the signal came: nothing to check
        print(f"run {k:2d}: delay {delay:.2f} s, exit {p.returncode}, {took:.2f} s after the signal, "
              + ("finished before it" if finished else "line last" if ok else "NOT LAST"), flush=True)
        if not ok and not finished:
            bad += 1
            print(err, flush=True)
finally:
    for b in busy:
        b.kill()
print(f"{bad} of {runs} runs without the command's line last")
