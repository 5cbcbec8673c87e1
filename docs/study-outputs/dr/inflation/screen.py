"""How correlated fixes are counted (issue 23, stop 36): four ways, screened with the EKF-8 on analog seeds.

Run from the repository root, one BLAS thread (two processes, one per half of the seeds)::

    python docs/study-outputs/dr/inflation/screen.py 0,1,2,3,4,5,6,7,8,9,10,11,12,13,14 > a.txt
    python docs/study-outputs/dr/inflation/screen.py 15,16,17,18,19,20,21,22,23,24,25,26,27,28,29 > b.txt

(``screen_seeds_0_29.txt`` is ``a.txt`` then ``b.txt``.) Per analog and seed, the phone grade's EKF-8 scored as
``filterwnn study dr --drive FILE --grade phone`` scores it (median / max at the ends of 20 outages of 30 s, m;
``*``: the issue's target missed), with the fixes' measured correlation ``c`` (``gps_correlation``) used as:

* ``base``: the package's default, ``correlated_fixes="calibration"`` (the heading bias and rate bias take
  ``1 / c`` of their gain, the other states each fix as independent);
* ``pos1/sqrt(c)``: that, and the position rows of the gain times ``1 / sqrt(c)``;
* ``Rc``: each used fix's covariance times ``c`` on top of the calibration's ``1 / c`` (counted twice);
* ``Rc-cons``: each used fix's covariance times ``c``, the calibration's own ``1 / c`` dropped: what
  ``correlated_fixes="inflate"`` does.

The variants other than ``base`` are patched in memory (``Rc-cons`` as the option has it).
"""
import os, sys, tempfile, warnings, numpy as np
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]
import _held_out_drives as held_out
from filterwnn.navigation import gpsdr
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.studies.dr import real_drive_outages
F = gpsdr.GPSDRFilter
GW, CF = F._gain_weights, F._check_fix

def gw_pos_sqrt(self, gps):
    w = GW(self, gps); c = self.gps_correlation if gps else 1.0
    if c <= 1.0: return w
    w = np.ones(self.model.dim_x) if w is None else w
    w[[0, 3]] *= c ** -0.5
    return w

def cf_rc(self, z_gps, gps_sigma, test=True, scaled=True):
    z, s = CF(self, z_gps, gps_sigma, test, scaled)
    if z is not None and self.gps_correlation > 1.0:
        s = self._fix_sigma(s) * np.sqrt(self.gps_correlation)
    return z, s

def gw_nocal(self, gps):  # the calibration's own 1/c dropped (R x c already carries it)
    held = self._held_rows(gps)
    if not held.size: return None
    w = np.ones(self.model.dim_x); w[held] = 0.0
    return w

VARIANTS = {"base": (GW, CF), "pos1/sqrt(c)": (gw_pos_sqrt, CF), "Rc": (GW, cf_rc), "Rc-cons": (gw_nocal, cf_rc)}
T = {"phone": (10, 30), "city": (20, 50), "one_hz": (6, 30)}
seeds = [int(s) for s in sys.argv[1].split(",")]
names = sys.argv[2].split(",") if len(sys.argv) > 2 else list(T)
tmp = tempfile.mkdtemp()
for name in names:
    for seed in seeds:
        run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed)))
        cells = []
        for label, (gw, cf) in VARIANTS.items():
            F._gain_weights, F._check_fix = gw, cf
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                e = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone")["EKF-8"]
            ok = np.median(e) <= T[name][0] and e.max() <= T[name][1]
            cells.append(f"{label} {np.median(e):.2f}/{e.max():.2f}{'' if ok else '*'}")
        F._gain_weights, F._check_fix = GW, CF
        print(f"{name} {seed} | " + " | ".join(cells), flush=True)
