"""The recorded drives (survey grade, EKF) without and with a latency state from the start (gps_latency_sd 0.5 s):
the monitor's z-score and estimate, the state and its sd at a quarter, half, three quarters and the end of
each drive, and the warnings. Run from the repository root: python docs/study-outputs/dr/latency/recorded_state.py (needs onavdata)."""
import warnings, numpy as np
from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive
from filterwnn.navigation.dead_reckoning import GPSDRModel, SENSOR_GRADES
from filterwnn.navigation.gpsdr import GPSDRFilter
for name in CAR_DRIVES:
    run = load_car_drive(name)
    for sd in (0.0, 0.5):
        m = GPSDRModel.from_grade(dict(SENSOR_GRADES["survey"], gps_latency_sd=sd), run.scenario.dt)
        x0 = np.concatenate([run.x0, m.x0[6:]]); P0 = m.P0.copy(); P0[0,0]=P0[3,3]=1.0
        f = GPSDRFilter(m, "ekf", x0=x0, P0=P0)
        zs=[]; lat=[]
        with warnings.catch_warnings(record=True) as w:
            warnings.simplefilter("always")
            for k in range(len(run.z_dr)):
                f.predict(); f.update(run.z_dr[k], run.gps_list()[k], run.gps_sigma_list()[k])
                zs.append(f.latency_z if f.latency_z is not None else np.nan)
                if m.latency: lat.append((f.x[-1], np.sqrt(f.P[-1,-1])))
        zs=np.array(zs)
        print(name, "sd", sd, "len", len(run.z_dr)*run.scenario.dt, "s; monitor z max", np.nanmax(np.abs(zs)) if np.isfinite(zs).any() else None,
              "final est", f.latency_estimate, "z", f.latency_z, "added", f.latency_added)
        if lat:
            lat=np.array(lat); n=len(lat)
            print("   state at 25/50/75/100 %:", [tuple(np.round(lat[int(q*(n-1))],3)) for q in (0.25,0.5,0.75,1.0)])
        print("   warnings:", len(w), [str(x.message)[:100] for x in w[:3]])
