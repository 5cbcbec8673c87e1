"""python scale_gain_variant.py POWER -- run_gps_scale args: the odometer scale's gain share 1 / gps_correlation**POWER
(the shipped filter: 0) in the calibration mode.
An experiment outside the package (stop 66), run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/analog-seeds/scale_gain_variant.py 1 -- analogs --seeds 0,1,2,3,4 --windows 0   # and 5-9
"""
import runpy, sys
import filterwnn.navigation.gpsdr as g
power = float(sys.argv[1])
orig = g.GPSDRFilter._gain_weights
def _gain_weights(self, gps):
    """The shipped weights, the scale's share taken from the heading bias's (``1 / c``, ``c`` the correlation the
    shipped filter used) to the power ``power``; a held scale stays held."""
    w = orig(self, gps)
    if w is not None and self._cal.size > 1 and w[self._cal[0]] != 0.0:
        w[self._cal[0]] = w[self._cal[1]] ** power
    return w
g.GPSDRFilter._gain_weights = _gain_weights
sys.argv = ["run_gps_scale.py"] + sys.argv[3:]
runpy.run_path("docs/study-outputs/dr/gps-scale/run_gps_scale.py", run_name="__main__")
