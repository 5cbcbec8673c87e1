"""python calibration_speed_variant.py MIN_SPEED -- run_gps_scale args: calibration learns from an accepted fix while the car moves
at MIN_SPEED m/s or more (slow included), instead of only at low_speed (5 m/s) and above.
Stop 35's ``../zero-rate/calibration_speed_lead.py`` patch, run through ``run_gps_scale.py``. An experiment
outside the package (stop 66), run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/analog-seeds/calibration_speed_variant.py 2 -- analogs --seeds 0,1,2,3,4 --windows 0   # and 5-9
"""
import os, runpy, sys
import numpy as np
import filterwnn.navigation.gpsdr as g
cut = float(sys.argv[1])
orig_classify = g.GPSDRFilter.classify
def classify(self, z_dr):
    self._speed_now = float(z_dr[1]) / self.model.dt
    return orig_classify(self, z_dr)
def _held_rows(self, gps):
    if not gps:
        return self.held_states if self.hold_without_gps else np.zeros(0, dtype=int)
    if not self._cal.size:
        return self._cal
    fast = self.motion == "moving" or (self.motion == "slow" and getattr(self, "_speed_now", 0.0) >= cut)
    observable = fast and self.fix_status == "accepted"
    return np.zeros(0, dtype=int) if observable else self._cal
g.GPSDRFilter.classify = classify
g.GPSDRFilter._held_rows = _held_rows
sys.argv = ["run_gps_scale.py"] + sys.argv[3:]
runpy.run_path("docs/study-outputs/dr/gps-scale/run_gps_scale.py", run_name="__main__")
