"""Tried and not kept (issue 23): the calibration's gain share 1/gps_correlation from a steadier estimate.

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/analog-seeds/correlation_variants.py base,window120,holdmax30,holdmax60 \
        phone,city,one_hz 0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19

An experiment, not package code. Phone seed 16 showed ``gps_correlation`` dropping to 1 (every
lag-1 autocorrelation below two standard errors) at 120 s on fixes correlated over 20 s, so the
heading and rate-bias states learned at full gain. Variants of the estimate the share uses:
``window120``, ``WHITENESS_WINDOW`` 120 fixes instead of 60; ``holdmaxN``, the largest estimate of
the last N fixes. Each scores the phone grade's EKF-8 (the three kinds differ little) on the
analogs of ``tests/_held_out_drives.py`` as ``filterwnn study dr --drive FILE --grade phone`` does.
"""
import os, sys, tempfile, warnings
from multiprocessing import Pool
import numpy as np
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]
import _held_out_drives as held_out
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation import gpsdr
from filterwnn.studies.dr import real_drive_outages

def patch(variant):
    G = gpsdr.GPSDRFilter
    if variant == "base":
        return
    if variant.startswith("window"):
        gpsdr.WHITENESS_WINDOW = int(variant[6:])
        # the default argument was bound at definition: patch __init__ defaults
        G.__init__.__kwdefaults__["whiteness_window"] = int(variant[6:])
        return
    if variant.startswith("holdmax"):
        n = int(variant[7:])
        orig = G._whiteness
        def _whiteness(self):
            orig(self)
            h = self.__dict__.setdefault("_chist", [])
            h.append(self.gps_correlation)
            del h[:-n]
            self.gps_correlation = max(h)
        G._whiteness = _whiteness

def one(args):
    variant, name, seed = args
    patch(variant)
    warnings.simplefilter("ignore")
    tmp = tempfile.mkdtemp()
    run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed)))
    res = real_drive_outages(run, filters=("EKF-8",), grade="phone", use_gps_sigma=True)
    e = res["EKF-8"]
    return variant, name, seed, float(np.median(e)), float(e.max())

if __name__ == "__main__":
    variants = sys.argv[1].split(",")
    names = sys.argv[2].split(",")
    seeds = [int(s) for s in sys.argv[3].split(",")]
    jobs = [(v, n, s) for v in variants for n in names for s in seeds]
    with Pool(2, maxtasksperchild=1) as p:
        for v, n, s, med, mx in p.imap(one, jobs):
            print(f"{v} {n} s{s} EKF-8 {med:.2f} / {mx:.2f}", flush=True)
