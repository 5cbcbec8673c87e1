"""When does the monitor name a heading late? (issue 23, stop 51)

Stop 51's note in the fixes' and the speed's latency warnings names the heading late (``heading_latency``) when the
two show the same sign. Two errors read alike: both early against the heading is the heading late, but a speed
alone late can make the fixes' test read them late too. The analogs of ``tests/_held_out_drives.py`` (seeds 0-5,
1 Hz and phone) with their speed 0.5 s late or early (``odometer_latency``; the heading and the fixes on time), and
with their heading 0.5 s late or early, run through the phone grade's EKF-8 (one pass with every fix, as the
monitor's tests in ``tests/navigation/test_latency.py``). Each line: the drive, the warnings that tell a latency
(the fixes' or the speed's, with the estimate and the step) and the heading latency named (or ``-``). Run with the
package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/heading_latency_named.py ROOT

(``heading_latency_named.txt``.)
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
from filterwnn.navigation.dead_reckoning import GPSDRModel  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.navigation.gpsdr import GPSDRFilter  # noqa: E402

assert GPSDRFilter.__init__.__code__.co_filename.startswith(ROOT)

with tempfile.TemporaryDirectory() as tmp:
    for name in ("one_hz", "phone"):
        for seed in range(6):
            for what, lag in (("speed", 0.5), ("speed", -0.5), ("heading", 0.5), ("heading", -0.5)):
                if what == "speed":
                    cols = held_out.columns(name, seed, odometer_latency=lag)
                else:
                    cols = held_out.columns(name, seed)
                    t = cols["time"]
                    cols["heading"] = np.mod(np.interp(t - lag, t, np.unwrap(cols["heading"])), 2 * np.pi)
                with warnings.catch_warnings(record=True) as seen:
                    warnings.simplefilter("always")
                    run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))
                    m = GPSDRModel.from_grade("phone", run.scenario.dt)
                    f = GPSDRFilter(m, "ekf", x0=np.r_[run.x0, m.x0[6:]])
                    f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list())
                told, named = [], "-"
                for w in seen:
                    s = str(w.message)
                    hit = re.search(r"(the (?:fixes'|speed's) latency): by step (\d+) the fixes show (?:themselves|the "
                                    r"speed) ([-+][\d.]+) s", s)
                    if hit:
                        told.append(hit.expand(r"\1 \3 s at step \2"))
                        h = re.search(r"heading_latency=([-\d.]+)", s)
                        named = h.group(1) if h else named
                print(f"{name} {seed} {what} {lag:+.1f} s late | told: {'; '.join(told) or 'nothing'} | heading named: "
                      f"{named}", flush=True)
