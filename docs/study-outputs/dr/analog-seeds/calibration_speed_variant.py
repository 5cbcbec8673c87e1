"""python calibration_speed_variant.py MIN_SPEED -- run_gps_scale args: calibration learns from an accepted fix while
the car moves at MIN_SPEED m/s or more (slow included), instead of only at low_speed (5 m/s) and above.
Stop 35's gate (``../zero-rate/calibration_gate.py``, which ``calibration_speed_lead.py`` uses), run through
``run_gps_scale.py``. An experiment outside the package (stop 66), run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/analog-seeds/calibration_speed_variant.py 2 -- analogs --seeds 0,1,2,3,4 --windows 0   # and 5-9
"""
import os
import runpy
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "zero-rate"))
from calibration_gate import patch  # noqa: E402

patch(float(sys.argv[1]))
sys.argv = ["run_gps_scale.py"] + sys.argv[3:]
runpy.run_path("docs/study-outputs/dr/gps-scale/run_gps_scale.py", run_name="__main__")
