"""The prototype (exitproto.py) on drive CSVs: one line per gap of 30 s or more (summary.txt's d6 column:
``python try.py /tmp/t4/d6_garage_reacq_fault.csv`` after ``gen_drives_4.py /tmp/t4``, the settings from COLS, WIN, SETTLE)."""
import os, sys, numpy as np, warnings
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exitproto as E
from filterwnn.navigation.drives import read_drive_csv
for p in sys.argv[1:]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(p, progress=False)
    heading = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]]
    for e in E.exits(float(run.t[1]-run.t[0]), heading, run.z_dr[:, 1], run.gps_steps, run.z_gps):
        print(p.split("/")[-1], "gap %.0f-%.0f run to %.0f (%d) max %.1f m s %.2f c %.2f coh %.2f p %.2g" % e)
