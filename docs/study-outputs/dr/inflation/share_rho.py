"""The fixes' share ``rho`` of the innovation and their measured correlation ``c`` at each fix ``share.py``'s rule
inflates (EKF-8 over the whole drive with every fix; percentiles 10 / 50 / 90), on the recorded drives (survey grade)
and analog seed 0 of the phone and the city (phone grade). Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/inflation/share_rho.py      # share_rho.txt
"""
import os, sys, warnings, tempfile, numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests"), HERE]
import share
from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive, read_drive_csv
from filterwnn.studies.dr._real import _real_drive_filter, REAL_MODEL
import _held_out_drives as held_out
F = share.F
log = []
def cf(self, z, g, test=True, scaled=True):
    out = share.cf_wrap(self, z, g, test, scaled)
    if out[0] is not None and self.gps_correlation > 1:
        _, S = self._innovation
        r = self._check_r; p = max(0.5*np.trace(S) - r, 0)
        log.append((r/(r+p), self.gps_correlation, np.sqrt(r), np.sqrt(p)))
    return out
F._check_fix = cf
def go(label, run, grade):
    log.clear()
    f = _real_drive_filter("EKF-8", run, grade, None, dict(REAL_MODEL), 0, None)
    gps, sig = run.gps_list(), run.gps_sigma_list()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for k in range(len(run.t)):
            f.predict(); f.update(run.z_dr[k], gps[k], sig[k])
    a = np.array(log)
    q = lambda v: " ".join(f"{x:.3g}" for x in np.percentile(v, [10, 50, 90]))
    print(f"{label}: fixes {len(a)}; rho p10/50/90 {q(a[:,0])}; c {q(a[:,1])}; sigma {q(a[:,2])}; pred sd {q(a[:,3])}")
for name in CAR_DRIVES:
    go(name, load_car_drive(name), "survey")
tmp = tempfile.mkdtemp()
for n in ("phone", "city"):
    go(f"{n} 0", read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(n, 0))), "phone")
