"""The stop update on recorded data: onavdata's two car drives run with the phone grade (issue 23).

Run from the repository root, one BLAS thread (needs ``onavdata``)::

    python docs/study-outputs/dr/zero-rate/recorded_phone.py > docs/study-outputs/dr/zero-rate/recorded_phone.txt

The drives' scored grade is ``survey``, which has no rate-bias state, so their scored numbers do not
change. With the phone grade the filter does have the state, and the stops run the update on a real
gyro. Section A: median / max at the ends of the 20 outages of 30 s (scored as ``filterwnn study dr
--real --grade phone``), with and without the update, and the stops used / rejected. Section B: the
gyro-integrated heading against the reference INS heading while the car stands at the start: the real
drift the update measures. Section C: the 2021-03-29 drive's outages one by one.
"""
import warnings

import numpy as np

from filterwnn.navigation import drives as d
from filterwnn.navigation.gpsdr import GPSDRFilter
from filterwnn.studies.dr import real_drive_outages


def scored(run, on):
    GPSDRFilter.__init__.__kwdefaults__["zero_rate_update"] = on
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = real_drive_outages(run, filters=("DR-mech", "EKF-8", "UKF-8", "SUKF-8"), grade="phone",
                                 use_gps_sigma=True)
    GPSDRFilter.__init__.__kwdefaults__["zero_rate_update"] = True
    return res


print("A. phone grade, median / max at the outage ends (m)")
runs = {name: d.load_car_drive(name) for name in d.CAR_DRIVES}
per_outage = {}
for name, run in runs.items():
    for on in (False, True):
        res = scored(run, on)
        ig = res["integrity"]["EKF-8"]
        stops = "-" if ig["n_zero_rate"] is None else f"{ig['n_zero_rate']} used / {ig['n_zero_rate_rejected']} rejected"
        print(f"  {name} stop update {'on ' if on else 'off'} | "
              + " | ".join(f"{k} {np.median(res[k]):.2f} / {res[k].max():.2f}" for k in ("DR-mech", "EKF-8", "UKF-8", "SUKF-8"))
              + f" | stops (EKF-8): {stops}")
        per_outage[name, on] = res

print("\nB. gyro-integrated heading minus the reference heading (deg), from the first sample")
for name in d.CAR_DRIVES:
    folder = d._onav_dir(name)
    att = d._read_zipped_csv(folder, "n380-attitude")
    imu = d._read_zipped_csv(folder, "n380-imu-nav")
    oka = (att["SystemTov"] > 0) & (att["InsGnssBIT.InsMode"] == 4)
    ta, hd = att["SystemTov"][oka], np.rad2deg(np.unwrap(att["EulerAttitude[2]"][oka]))
    ti, cum = imu["SystemTov"], np.rad2deg(np.cumsum(imu["DeltaTheta[0]"]))
    t0 = ta[0]
    cells = []
    for s in (0, 20, 40, 60, 80, 100, 120):
        ref = np.interp(t0 + s, ta, hd) - np.interp(t0, ta, hd)
        gyro = np.interp(t0 + s, ti, cum) - np.interp(t0, ti, cum)
        cells.append(f"{s} s: {gyro - ref:+.2f} (ref {ref:+.2f})")
    print(f"  {name}: " + ", ".join(cells))

print("\nC. 2021-03-29, outage by outage: start (s), metres driven, end error (m) of DR-mech and EKF-8 off / on")
off, on = per_outage[d.CAR_DRIVES[1], False], per_outage[d.CAR_DRIVES[1], True]
for j, s in enumerate(off["starts"]):
    print(f"  {s:5.1f} s {off['moved'][j]:5.0f} m | DR {off['DR-mech'][j]:5.2f} | EKF-8 off {off['EKF-8'][j]:5.2f} on {on['EKF-8'][j]:5.2f}")

print("\nD. the gyro heading minus the track (the direction of the reference velocity), median per 10 s window "
      "while moving faster than 2 m/s (deg)")
for name, run in runs.items():
    ve, vn = run.x_true[:, 1], run.x_true[:, 4]
    off = np.rad2deg(np.angle(np.exp(1j * (run.z_dr[:, 0] - np.arctan2(ve, vn)))))
    moving = np.hypot(ve, vn) > 2.0
    cells = []
    for t0 in np.arange(0.0, run.t[-1], 10.0):
        w = moving & (run.t >= t0) & (run.t < t0 + 10.0)
        if w.any():
            cells.append(f"{t0:.0f} s: {np.median(off[w]):+.2f}")
    print(f"  {name}: " + ", ".join(cells))

print("\nE. 2021-03-29, the phone grade's EKF-8 with all fixes: its heading bias and rate bias through the stand")
from filterwnn.navigation.dead_reckoning import GPSDRModel  # noqa: E402

run = runs[d.CAR_DRIVES[1]]
m = GPSDRModel.from_grade("phone", run.scenario.dt)
for on in (False, True):
    f = GPSDRFilter(m, "ekf", x0=np.r_[run.x0, m.x0[6:]], zero_rate_update=on)
    gps, sig = run.gps_list(), run.gps_sigma_list()
    cells = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        for k in range(len(run.t)):
            f.predict()
            f.update(run.z_dr[k], gps[k], sig[k])
            if round(run.t[k], 1) in (30.0, 60.0, 66.0, 70.0, 80.0, 90.0):
                cells.append(f"{run.t[k]:.0f} s: b {np.rad2deg(f.x[7]):+.2f} deg, r {np.rad2deg(f.x[8]):+.4f} deg/s")
    print(f"  stop update {'on ' if on else 'off'}: " + "; ".join(cells))
