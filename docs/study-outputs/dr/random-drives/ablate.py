"""One drive of protocol 3 (stop 56) with all its faults, none, each alone and all but each: per line, DR-mech and the
given kinds' median / max at the outage ends (m), the phone grade, scored as the command does. Each set draws the
drive again with the other faults left out (``faults`` patched; the fault generator's draws are made whether a fault
is on or not, so each fault is the same in every set). Run from the repository root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/ablate.py 201 EKF-8 > docs/study-outputs/dr/random-drives/ablate_201.txt
"""
import os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.environ.get("ROOT", os.path.abspath(os.path.join(HERE, "..", "..", "..", "..")))
sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr", ROOT + "/docs/study-outputs/dr/random-drives"]
import random_drives as rd
from drive_sets import read
from filterwnn.studies.dr import real_drive_outages
seed = int(sys.argv[1]); kinds = tuple(sys.argv[2].split(","))
orig = rd.faults
allf = orig(seed)[0]
sets = [("all", list(allf)), ("none", [])] + [(f"only {k}", [k]) for k in allf] + [(f"all but {k}", [x for x in allf if x != k]) for k in allf]
for label, keep in sets:
    rd.faults = lambda s, keep=keep: ({k: v for k, v in orig(s)[0].items() if k in keep}, orig(s)[1])
    run = read(tempfile.mkdtemp(), rd.drive(seed, 3)[1])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = real_drive_outages(run, filters=("DR-mech",) + kinds, grade="phone", use_gps_sigma=True)
    print(f"{seed} {label:28s} " + " | ".join(f"{k} {np.median(res[k]):.2f}/{res[k].max():.2f}" for k in ("DR-mech",) + kinds), flush=True)
