"""Protocol 2's seed 221 split the kinds (stop 56; RUN.md): the variant of ``correlation_variant_patch.py`` against
the shipped filter, per drive the outage ends' median / max (m) of each kind, scored as the command does. Drives:
``p2:SEED`` (a random drive of protocol 2) or ``NAME:SEED`` (an analog of ``tests/_held_out_drives.py``). Run from
the repository root, one BLAS thread::

    MODES=none,before,max OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/correlation_variant.py EKF-8,SUKF-8 p2:221 one_hz:0
    MODES=none,max OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/random-drives/correlation_variant.py EKF-8,SUKF-8 phone:0 city:0 phone:1 city:1 p2:200 p2:201 p2:202 p2:203 p2:205 p2:207
"""
import os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", "..", ".."))
sys.path[:0] = [HERE, ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr"]
import correlation_variant_patch as cprior, random_drives, _held_out_drives as ho
from drive_sets import read
from filterwnn.studies.dr import real_drive_outages
kinds = tuple(sys.argv[1].split(","))
modes = [None if m == "none" else m for m in os.environ.get("MODES", "none,before,max").split(",")]
for spec in sys.argv[2:]:
    src, seed = spec.split(":")
    cols = random_drives.drive(int(seed), int(src[1:]))[1] if src in ("p1", "p2", "p3") else ho.columns(src, int(seed))
    run = read(tempfile.mkdtemp(), cols)
    line = []
    for m in modes:
        cprior.MODE["m"] = m
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=kinds, grade="phone", use_gps_sigma=True)
        line.append(f"{m}: " + " ".join(f"{k} {np.median(res[k]):.2f}/{res[k].max():.2f}" for k in kinds))
    print(spec, " | ".join(line), flush=True)
