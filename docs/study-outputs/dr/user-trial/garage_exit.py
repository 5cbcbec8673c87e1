"""The fourth trial's garage exit (d6 of ``gen_drives_4.py``): after 640 s without fixes, 30 s of fixes off by
35 exp(-t / 8) m, reporting 10 m then 3. What the 8-state EKF (phone grade) sees at the exit, what an outage that
starts there ends at, and the remedy of dropping those fixes (``--drop-fixes``), beside the twin without the fault.

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/user-trial/garage_exit.py > docs/study-outputs/dr/user-trial/garage_exit.txt

First the filter's first twelve fixes after the exit: the predicted position's standard deviations (m, east and
north), the fix's reported sigma, its distance from the prediction, its NIS (gate 13.8) and what became of it. Then
the command's median / max at the outage ends (m) of DR-mech and EKF-8: one outage at a time placed at 1000, 1010 and
1022 s, and the 20 outages spread as the command places them, on the drive as it is, with the fixes of 992-1010 s
dropped, and on the twin.
"""
import os
import re
import subprocess
import sys
import tempfile
import warnings

import numpy as np

from filterwnn.navigation import GPSDRFilter, GPSDRModel
from filterwnn.navigation.drives import read_drive_csv

HERE = os.path.dirname(os.path.abspath(__file__))


def trace(path, t0=991.5, count=12):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(path, progress=False)
        model = GPSDRModel.from_grade("phone", dt=run.scenario.dt)
        f = GPSDRFilter(model, x0=np.r_[run.x0, model.x0[6:]])
        for k, (z, fix, sigma) in enumerate(zip(run.z_dr, run.gps_list(), run.gps_sigma_list())):
            f.predict()
            prior, P = f.x.ravel().copy(), f.P.copy()
            f.update(z, fix, sigma)
            if run.t[k] >= t0 and fix is not None and count:
                count -= 1
                off = float(np.hypot(fix[0] - prior[0], fix[1] - prior[3]))
                print(f"t {run.t[k]:.0f} s | prior sd {np.sqrt(P[0, 0]):.1f} / {np.sqrt(P[3, 3]):.1f} m | sigma "
                      f"{sigma:.1f} m | {off:.1f} m from the prediction | NIS {f.nis:.1f} | {f.fix_status}")


def table(csv, folder, *extra):
    cmd = [sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", csv, "--grade", "phone", "--filters",
           "DR-mech,EKF-8", "--jobs", "1", "--no-progress", "--no-figures", "--out", os.path.join(folder, "out"),
           *extra]
    p = subprocess.run(cmd, capture_output=True, text=True)
    got = [re.search(rf"^\| {k} \| ([\d.]+) \| [\d.]+ \| ([\d.]+) \|", p.stdout, re.M) for k in ("DR-mech", "EKF-8")]
    gaps = re.search(r"gaps of fixes, ([^)]*)\)", p.stdout)
    return (f"rc {p.returncode} | " + " | ".join(f"{k} {m.group(1)} / {m.group(2)}" if m else f"{k} -"
                                               for k, m in zip(("DR-mech", "EKF-8"), got))
            + (f" | the drive's gaps of fixes {gaps.group(1)}" if gaps else ""))


with tempfile.TemporaryDirectory() as folder:
    subprocess.run([sys.executable, os.path.join(HERE, "gen_drives_4.py"), folder], check=True, capture_output=True)
    fault, clean = (os.path.join(folder, f"d6_garage_reacq_{t}.csv") for t in ("fault", "clean"))
    print("## the EKF-8 at the exit (phone grade)")
    trace(fault)
    print("## outage ends (m), median / max")
    for start in ("1000", "1010", "1022"):
        for name, csv, extra in (("as it is", fault, []), ("fixes of 992-1010 s dropped", fault,
                                                           ["--drop-fixes", "992,1010"]), ("twin", clean, [])):
            if name.startswith("fixes") and start == "1000":
                continue  # (no fix there to start an outage from)
            print(f"outage at {start} s, {name} | " + table(csv, folder, "--outage-starts", start, *extra), flush=True)
    for name, csv, extra in (("as it is", fault, []), ("fixes of 992-1010 s dropped", fault,
                                                       ["--drop-fixes", "992,1010"]), ("twin", clean, [])):
        print(f"20 outages spread, {name} | " + table(csv, folder, *extra), flush=True)
