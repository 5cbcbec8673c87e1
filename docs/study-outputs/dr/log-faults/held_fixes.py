"""A log that carries its last fix forward to every DR sample (sample and hold; issue 23, stop 48).

The analog ``NAME`` (seed 0) of ``tests/_held_out_drives.py`` with each fix (and its sigma) repeated on every row
until the next, run through ``filterwnn study dr --drive FILE --grade phone`` (DR-mech, EKF-8, UKF-8; extra
arguments go to the command). Run from the repository root::

    python docs/study-outputs/dr/log-faults/held_fixes.py phone > docs/study-outputs/dr/log-faults/held_fixes.txt
    python docs/study-outputs/dr/log-faults/held_fixes.py city >> docs/study-outputs/dr/log-faults/held_fixes.txt

(each: the command's warnings, then its table.)
"""
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "tests"))
import _held_out_drives as h  # noqa: E402

name = sys.argv[1]
c = h.columns(name, 0)
for k in ("gps_east", "gps_north", "gps_sigma"):
    v = c[k].copy()
    idx = np.where(~np.isnan(v), np.arange(len(v)), 0)
    np.maximum.accumulate(idx, out=idx)
    held = v[idx]
    held[:np.flatnonzero(~np.isnan(v))[0]] = np.nan
    c[k] = held
tmp = tempfile.mkdtemp(); p = h.write_csv(os.path.join(tmp, 'held.csv'), c)
out = subprocess.run(["filterwnn", "study", "dr", "--drive", p, "--grade", "phone", "--no-figures", "--no-progress", "--out", tmp, "--filters", "DR-mech,EKF-8,UKF-8"] + sys.argv[2:], capture_output=True, text=True, env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
print(out.stderr[-3000:]); print("\n".join(l[:200] for l in out.stdout.splitlines() if l.startswith("|")))
