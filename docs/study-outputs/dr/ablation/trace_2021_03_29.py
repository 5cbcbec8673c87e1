"""2021-03-29's worst outage (it starts at 75 s): the 8-state EKF's calibration when it starts, with and
without calibration only where observable (survey grade). Run from the repository root::

    python docs/study-outputs/dr/ablation/trace_2021_03_29.py > docs/study-outputs/dr/ablation/trace_2021_03_29.txt
"""
import warnings, numpy as np
from filterwnn.navigation import drives as d, gpsdr
from filterwnn.studies.dr._real import _real_drive_filter, REAL_MODEL
run = d.load_car_drive("2021-03-29-automotive-stoplight-to-stoplight")
orig = gpsdr.GPSDRFilter._held_rows
def nogate(self, gps):
    if not gps:
        return self.held_states if self.hold_without_gps else np.zeros(0, dtype=int)
    return np.zeros(0, dtype=int)
for label, hr in (("obs gate on", orig), ("obs gate off", nogate)):
    gpsdr.GPSDRFilter._held_rows = hr
    f = _real_drive_filter("EKF-8", run, "survey", None, dict(REAL_MODEL), 0, None)
    gps, sig = run.gps_list(), run.gps_sigma_list()
    taught = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for k in range(len(run.t)):
            if run.t[k] >= 75.0: break
            f.predict(); f.update(run.z_dr[k], gps[k], sig[k])
            if gps[k] is not None and f.motion == "moving" and f.fix_status == "accepted": taught += 1
    v = run.z_dr[:k, 1] / run.scenario.dt
    print(label, "t", run.t[k], "fixes before 75 s", sum(g is not None for g in gps[:k]), "moving fixes", taught,
          "first moving (>=5 m/s) at %.1f s" % run.t[np.argmax(v >= 5)],
          "scale %.4f hb %.2f deg (sd %.2f)" % (f.x[6], np.rad2deg(f.x[7]), np.rad2deg(np.sqrt(f.P[7, 7]))))
