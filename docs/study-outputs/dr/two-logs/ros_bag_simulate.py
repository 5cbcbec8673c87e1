"""Simulate a ROS 2 bag of a car drive, exported one CSV per topic (as rosbag2 CSV exporters write them).
Writes bag_csv/imu_data.csv, bag_csv/odom.csv, bag_csv/gps_fix.csv and truth.csv (ground truth, separate)."""
import numpy as np, os
rng = np.random.default_rng(42)
DT = 0.01
T0 = 1718000000.0          # epoch of the start (true time)
LAT0, LON0 = 48.1500, 11.5800
R_E = 6378137.0
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bag_csv"); os.makedirs(out, exist_ok=True)

# ---- the route: segments (kind, params) ----
# heading psi is ENU yaw (from east, CCW). curvature k>0 = left turn.
segs = [("stop", 25), ("straight", 150, 8), ("turn", -90, 12, 6), ("straight", 200, 10),
        ("stop", 40), ("straight", 80, 7),
        ("round", 270, 15, 5), ("straight", 250, 11), ("turn", 90, 12, 6), ("straight", 120, 8),
        ("stop", 15), ("straight", 100, 9), ("turn", -90, 10, 5), ("straight", 1500, 12),     # long straight
        ("stop", 90), ("straight", 120, 8), ("round", 180, 18, 5), ("straight", 300, 10),
        ("turn", 90, 12, 6), ("straight", 150, 8),
        ("threepoint",), ("straight", 200, 9), ("turn", -90, 12, 6), ("straight", 250, 10),
        ("stop", 10), ("straight", 200, 10), ("round", 360, 15, 5), ("straight", 180, 9),
        ("turn", -90, 12, 5), ("straight", 400, 11), ("turn", 90, 10, 5), ("straight", 300, 10), ("turn", 90, 12, 6), ("straight", 350, 9), ("stop", 60)]

t = [0.0]; x = [0.0]; y = [0.0]; psi = [np.deg2rad(30.0)]; v = [0.0]; w = [0.0]
ACC = 1.5
def step(v_target, k, acc=ACC):
    vv = v[-1]; dv = np.clip(v_target - vv, -acc * DT, acc * DT); vn = vv + dv
    wn = k * vn
    # smooth yaw rate (steering lag)
    wn = w[-1] + np.clip(wn - w[-1], -0.3 * DT, 0.3 * DT)
    pn = psi[-1] + wn * DT
    vm = 0.5 * (vv + vn)
    x.append(x[-1] + vm * np.cos(pn) * DT); y.append(y[-1] + vm * np.sin(pn) * DT)
    psi.append(pn); v.append(vn); w.append(wn); t.append(t[-1] + DT)

def drive_dist(d, vt, k=0.0):
    s = 0.0
    while s < d:
        # brake in time for the end (stop at end only handled by 'stop')
        step(vt, k); s += abs(v[-1]) * DT
def stop(T):
    while v[-1] > 0.01 or abs(w[-1]) > 1e-3:
        step(0.0, 0.0, 2.0)
    v[-1] = 0.0; w[-1] = 0.0
    for _ in range(int(T / DT)): step(0.0, 0.0)
def turn(ang, R, vt):
    # slow to vt, then turn by ang deg with radius R
    while abs(v[-1] - vt) > 0.05: step(vt, 0.0)
    p0 = psi[-1]; k = np.sign(ang) / R
    while abs(psi[-1] - p0) < abs(np.deg2rad(ang)) - abs(w[-1]) ** 2 / 0.6:
        step(vt, k)
    while abs(w[-1]) > 1e-3: step(vt, 0.0)

for s in segs:
    if s[0] == "stop": stop(s[1])
    elif s[0] == "straight": drive_dist(s[1], s[2])
    elif s[0] in ("turn",): turn(s[1], s[2], s[3])
    elif s[0] == "round":   # right-hand traffic: enter with a right flick, go round CCW, exit right
        turn(-30, 10, s[3]); turn(s[1] + 60, s[2], s[3]); turn(-30, 10, s[3])
    elif s[0] == "threepoint":
        stop(3)
        n = 0
        while (psi[-1] - psi[-1 - n if n else -1]) < 1e9 and n < 1: n += 1
        p0 = psi[-1]
        while psi[-1] - p0 < np.deg2rad(80): step(2.0, 1 / 5.0)        # forward hard left
        stop(2)
        s0 = len(v)
        while psi[-1] - p0 < np.deg2rad(120): step(-1.5, -1 / 5.0)     # reverse, steering right -> yaw increases (left)
        stop(2)
        while psi[-1] - p0 < np.deg2rad(180) - 0.05: step(2.5, 1 / 5.0)
        while abs(w[-1]) > 1e-3: step(3.0, 0.0)
t = np.array(t); x = np.array(x); y = np.array(y); psi = np.array(psi); v = np.array(v); w = np.array(w)
print(f"drive {t[-1]/60:.1f} min, {np.sum(np.abs(v))*DT/1000:.2f} km, v max {v.max():.1f}, min {v.min():.2f}")
N = len(t)

def to_latlon(e, n):
    lat = LAT0 + np.rad2deg(n / R_E); lon = LON0 + np.rad2deg(e / (R_E * np.cos(np.deg2rad(LAT0))))
    return lat, lon
def yaw_quat(yaw, roll=0, pitch=0):
    cy, sy = np.cos(yaw / 2), np.sin(yaw / 2); cr, sr = np.cos(roll / 2), np.sin(roll / 2); cp, sp = np.cos(pitch / 2), np.sin(pitch / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)

# ---- truth ----
lat, lon = to_latlon(x, y)
np.savetxt(os.path.join(os.path.dirname(out), "truth.csv"),
           np.c_[T0 + t, x, y, lat, lon, np.rad2deg(psi), v, w], delimiter=",", fmt=["%.3f"] + ["%.4f"] * 2 + ["%.9f"] * 2 + ["%.5f"] * 3,
           header="time_epoch_s,east_m,north_m,lat,lon,yaw_enu_deg,speed_mps,yaw_rate_enu_rads", comments="")

def ns(ts):  # epoch seconds -> (sec, nanosec)
    tn = np.round(ts * 1e9).astype(np.int64); return tn // 10**9, tn % 10**9

# ---- /imu/data at 100 Hz, IMU driver clock 15 ms ahead, jitter 1 ms ----
bias = np.deg2rad(0.4) + np.cumsum(rng.normal(0, np.deg2rad(0.0003) * np.sqrt(DT), N))   # turn-on bias plus a slow walk
gz = w + bias + rng.normal(0, 0.02, N)
# AHRS yaw: true ENU yaw + 4 deg declination error + magnetic disturbances + noise
dist = np.zeros(N)
for tc, amp in [(150, 15), (300, -18), (700, 12), (820, 20)]:
    dist += np.deg2rad(amp) * np.exp(-0.5 * ((t - tc) / 10.0) ** 2)
ahrs_yaw = psi + np.deg2rad(4.0) + dist + np.convolve(rng.normal(0, np.deg2rad(0.5), N), np.ones(50) / 50, "same")
roll = rng.normal(0, 0.01, N); pitch = rng.normal(0, 0.01, N)
q = np.array(yaw_quat(ahrs_yaw, roll, pitch)).T
imu_hdr = T0 + t + 0.015 + rng.normal(0, 0.001, N)
imu_rx = T0 + t + 0.004 + rng.exponential(0.002, N)
s_, n_ = ns(imu_hdr)
with open(os.path.join(out, "imu_data.csv"), "w") as f:
    f.write("timestamp,header.stamp.sec,header.stamp.nanosec,header.frame_id,orientation.x,orientation.y,orientation.z,orientation.w,"
            "angular_velocity.x,angular_velocity.y,angular_velocity.z,linear_acceleration.x,linear_acceleration.y,linear_acceleration.z\n")
    acc_x = np.gradient(v, DT) + rng.normal(0, 0.05, N); acc_y = v * w + rng.normal(0, 0.05, N)
    for i in range(N):
        f.write(f"{int(round(imu_rx[i]*1e9))},{s_[i]},{n_[i]},imu_link,{q[i,0]:.7f},{q[i,1]:.7f},{q[i,2]:.7f},{q[i,3]:.7f},"
                f"{rng.normal(0,0.02):.5f},{rng.normal(0,0.02):.5f},{gz[i]:.5f},{acc_x[i]:.4f},{acc_y[i]:.4f},{9.81+rng.normal(0,0.05):.4f}\n")

# ---- /odom at 20 Hz, 2 % scale error, odom driver clock 30 ms behind ----
io = np.arange(0, N, 5)
vs = 1.02 * v[io] + rng.normal(0, 0.02, len(io)) * (np.abs(v[io]) > 0)
# the driver integrates pose with its own wheel-based yaw (differential wheel speeds: 3 % scale error on turns, plus drift)
wo = 1.03 * w[io] + np.deg2rad(0.3)
po = np.cumsum(wo) * 0.05; xo = np.cumsum(vs * np.cos(po)) * 0.05; yo = np.cumsum(vs * np.sin(po)) * 0.05
qo = np.array(yaw_quat(po)).T
od_hdr = T0 + t[io] - 0.030
od_rx = T0 + t[io] + 0.002 + rng.exponential(0.003, len(io))
s_, n_ = ns(od_hdr)
with open(os.path.join(out, "odom.csv"), "w") as f:
    f.write("timestamp,header.stamp.sec,header.stamp.nanosec,header.frame_id,child_frame_id,pose.pose.position.x,pose.pose.position.y,pose.pose.position.z,"
            "pose.pose.orientation.x,pose.pose.orientation.y,pose.pose.orientation.z,pose.pose.orientation.w,"
            "twist.twist.linear.x,twist.twist.linear.y,twist.twist.linear.z,twist.twist.angular.x,twist.twist.angular.y,twist.twist.angular.z\n")
    for i in range(len(io)):
        f.write(f"{int(round(od_rx[i]*1e9))},{s_[i]},{n_[i]},odom,base_link,{xo[i]:.4f},{yo[i]:.4f},0.0,{qo[i,0]:.6f},{qo[i,1]:.6f},{qo[i,2]:.6f},{qo[i,3]:.6f},"
                f"{vs[i]:.4f},0.0,0.0,0.0,0.0,{wo[i]:.5f}\n")

# ---- /gps/fix at 1 Hz; fix epochs on whole seconds; stamped with ROS time on arrival (~0.2 s later) ----
ep = np.arange(1.0, t[-1] - 1, 1.0)
ig = np.round(ep / DT).astype(int)
ng = len(ep)
sig_rep = np.full(ng, 2.5)              # reported per-axis sigma
sig_true = np.full(ng, 2.5)
# environment: trees (errors larger than reported), canopy outage, multipath
trees = ((ep > 300) & (ep < 380)) | ((ep > 760) & (ep < 830))
sig_true[trees] = 5.0; sig_rep[trees] = 2.0
sig_true[(ep > 550) & (ep < 650)] = 3.5; sig_rep[(ep > 550) & (ep < 650)] = 3.0
# time-correlated errors: Gauss-Markov tau 20 s
a = np.exp(-1 / 20.0)
err = np.zeros((ng, 2)); e = rng.normal(0, 1, 2)
for k in range(ng):
    e = a * e + np.sqrt(1 - a * a) * rng.normal(0, 1, 2); err[k] = e * sig_true[k]
mp = np.zeros((ng, 2))
for t0_, L, d in [(480, 8, (25, -15)), (860, 6, (-30, 25))]:
    m = (ep >= t0_) & (ep < t0_ + L); mp[m] = np.array(d) * rng.uniform(0.7, 1.2, (m.sum(), 1))
ge = x[ig] + err[:, 0] + mp[:, 0]; gn = y[ig] + err[:, 1] + mp[:, 1]
glat, glon = to_latlon(ge, gn)
alt = 520 + rng.normal(0, 3, ng)
status = np.where(rng.random(ng) < 0.2, 2, 0)
canopy = (ep >= 700) & (ep < 725)
status[canopy] = -1; glat[canopy] = np.nan; glon[canopy] = np.nan
covtype = np.full(ng, 2); covtype[(ep > 200) & (ep < 260)] = 1     # approximated for a minute
covtype[(ep >= 40) & (ep < 46)] = 0                                  # first fixes: unknown
gps_hdr = T0 + ep + 0.2 + rng.normal(0, 0.03, ng)
gps_rx = gps_hdr + 0.001 + rng.exponential(0.002, ng)
s_, n_ = ns(gps_hdr)
with open(os.path.join(out, "gps_fix.csv"), "w") as f:
    f.write("timestamp,header.stamp.sec,header.stamp.nanosec,header.frame_id,status.status,status.service,latitude,longitude,altitude,"
            + ",".join(f"position_covariance.{j}" for j in range(9)) + ",position_covariance_type\n")
    for k in range(ng):
        if covtype[k] == 0: cov = [0.0] * 9
        elif status[k] == -1: cov = [0.0] * 9
        else:
            s2 = sig_rep[k] ** 2; cov = [s2, 0, 0, 0, s2, 0, 0, 0, (2 * sig_rep[k]) ** 2]
        la = "nan" if np.isnan(glat[k]) else f"{glat[k]:.9f}"; lo = "nan" if np.isnan(glon[k]) else f"{glon[k]:.9f}"
        f.write(f"{int(round(gps_rx[k]*1e9))},{s_[k]},{n_[k]},gps,{status[k]},1,{la},{lo},{alt[k]:.3f},"
                + ",".join(f"{c:.4f}" for c in cov) + f",{covtype[k]}\n")
print("wrote", out, "GPS rows", ng, "fix error median", np.median(np.hypot(err[:, 0] + mp[:, 0], err[:, 1] + mp[:, 1])))
