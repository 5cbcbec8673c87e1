"""When the consistency monitor tells a speed stamped late (issue 23, stop 49).

The phone and 1 Hz analogs of ``tests/_held_out_drives.py``, seeds 0-9, with the speed 1 s late, 0.5 s late and 0.5 s
early (``odometer_latency``), run as ``filterwnn study dr --drive FILE --grade phone`` runs them (EKF-8). Each line:
the step and estimate of the speed's-latency warning (none: not told), the median / max at the outage ends, the heading
steps taken, the monitor's last z-score and estimate of the speed's latency, and the step at which the fixes'
latency state was added (a late speed is partly taken for it). Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/speed_told.py ROOT phone,one_hz 1.0,0.5,-0.5 0 10
"""
import os
import re
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

TOLD = re.compile(r"speed's latency: by step (\d+) the fixes show the speed ([-+0-9.e]+) s")
names, lats = sys.argv[2].split(","), [float(x) for x in sys.argv[3].split(",")]
with tempfile.TemporaryDirectory() as tmp:
    for lat in lats:
        for name in names:
            for seed in range(int(sys.argv[4]), int(sys.argv[5])):
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"),
                                                        held_out.columns(name, seed, odometer_latency=lat)))
                with warnings.catch_warnings(record=True) as caught:
                    warnings.simplefilter("always")
                    res = real_drive_outages(run, filters=("EKF-8",), use_gps_sigma=True, grade="phone")
                told = [TOLD.search(str(w.message)).groups() for w in caught if TOLD.search(str(w.message))]
                e, ig = res["EKF-8"], res["integrity"]["EKF-8"]
                print(f"{name} {seed} speed {lat:+g} | told {told} | EKF-8 {np.median(e):.2f} / {e.max():.2f} "
                      f"j{ig['n_heading_jumps']} z{ig['odometer_latency_z']:+.1f} est{ig['odometer_latency_estimate']:+.2f} "
                      f"lat{ig['latency_added']}", flush=True)
