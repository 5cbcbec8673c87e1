"""Which integrity part moves a drive's numbers (issue 23): each switched off alone, then together.

Run from the repository root, one BLAS thread (the recorded drives need ``onavdata``)::

    python docs/study-outputs/dr/ablation/ablation.py 2021-03-29-automotive-stoplight-to-stoplight survey
    python docs/study-outputs/dr/ablation/ablation.py 2021-04-27C-car-hill-drive survey
    python docs/study-outputs/dr/ablation/ablation.py sample phone

EKF-8, median / max at the ends of the 20 outages of 30 s (as ``filterwnn study dr --real`` or
``--drive sample`` scores them), and where the worst outage starts. The parts: the fixes' whiteness
(``whiteness_window=0``), the fixes' gate (``gate=inf``), calibration only where observable (the
calibration learns from every fix: ``_held_rows`` patched), the calibration bound (patched off).
Patched in memory; nothing here is used by the package, and nothing is tuned by it.
"""
import warnings, numpy as np
from filterwnn.navigation import drives as d, gpsdr
from filterwnn.studies.dr import real_drive_outages
import sys
run = d.load_car_drive(sys.argv[1]) if sys.argv[1] != "sample" else __import__("filterwnn.navigation.drives", fromlist=["x"]).read_drive_csv(__import__("filterwnn.navigation.drives", fromlist=["x"]).sample_drive_path())
GRADE = sys.argv[2]
K = gpsdr.GPSDRFilter.__init__.__kwdefaults__
base = dict(K)
orig_held, orig_bound = gpsdr.GPSDRFilter._held_rows, gpsdr.GPSDRFilter._bound_calibration
def held_nogate(self, gps):
    if not gps:
        return self.held_states if self.hold_without_gps else np.zeros(0, dtype=int)
    return np.zeros(0, dtype=int)
variants = {
 "base": {},
 "no whiteness": {"whiteness_window": 0},
 "no gate": {"gate": np.inf},
 "no obs-gate": "held",
 "no bound": "bound",
 "no whiteness+obs": ("held", {"whiteness_window": 0}),
 "all off": ("both", {"whiteness_window": 0, "gate": np.inf}),
}
for name, v in variants.items():
    K.clear(); K.update(base)
    gpsdr.GPSDRFilter._held_rows, gpsdr.GPSDRFilter._bound_calibration = orig_held, orig_bound
    kw = v[1] if isinstance(v, tuple) else (v if isinstance(v, dict) else {})
    mode = v[0] if isinstance(v, tuple) else (v if isinstance(v, str) else "")
    K.update(kw)
    if mode in ("held", "both"): gpsdr.GPSDRFilter._held_rows = held_nogate
    if mode in ("bound", "both"): gpsdr.GPSDRFilter._bound_calibration = lambda self: False
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = real_drive_outages(run, filters=("EKF-8",), grade=GRADE, use_gps_sigma=True)
    e = res["EKF-8"]
    print(f"{name:20s} {np.median(e):.2f} / {e.max():.2f}  argmax start {res['starts'][e.argmax()]:.0f} s", flush=True)
