"""Phone seed 8 of ``phone_fixes.py``, the first 200 s (stop 57): every 5 s the EKF-8's position error, its heading
bias and rate bias, and the sensor's heading less the car's course from the reference velocity (above 1 m/s;
the course is the car's, so this is the gyro's drift plus the IMU's mounting against the car, which the heading
bias should learn); and the gyro's heading less the reference INS's heading (``gyro-ref``, defined standing too:
the gyro's own drift, without the mounting), from 0 at the start.

    python docs/study-outputs/dr/recorded-motion/heading_bias_phone8.py > docs/study-outputs/dr/recorded-motion/heading_bias_phone8.txt
"""
import sys, pathlib, tempfile, warnings
HERE = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parents[3] / "tests")]
import numpy as np
import phone_fixes as pf
import _held_out_drives as held_out
from filterwnn.navigation import drives as onav
from filterwnn.navigation.drives import load_car_drive, read_drive_csv
from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn import GPSDRFilter
warnings.simplefilter("ignore")
run = load_car_drive(pf.DRIVE)
seed = 8
rng = np.random.default_rng(np.random.SeedSequence([23, 57, 0, seed]))
cols = pf.variant(run, "phone", rng)
with tempfile.TemporaryDirectory() as d:
    drive = read_drive_csv(held_out.write_csv(pathlib.Path(d) / "d.csv", cols))
model = GPSDRModel.from_grade("phone", drive.scenario.dt)
kf = GPSDRFilter(model, "ekf", x0=np.r_[drive.x0, model.x0[6:]])
est = kf.batch_filter(drive.z_dr, drive.gps_list(), drive.gps_sigma_list(), drive.gps_offset_list())
t = drive.t; xt = drive.x_true
true_course = np.arctan2(xt[:, 1], xt[:, 4])
hdg_err = np.rad2deg(np.angle(np.exp(1j * (drive.z_dr[:, 0] - true_course))))
v = np.hypot(xt[:, 1], xt[:, 4])
# the reference INS's heading on the drive's grid, as load_car_drive reads its attitude
folder = onav._onav_dir(pf.DRIVE)
att = onav._read_zipped_csv(folder, "n380-attitude")
pos = onav._read_zipped_csv(folder, "n380-position")
t0 = pos["SystemTov"][(pos["SystemTov"] > 0) & (pos["InsGnssBIT.InsMode"] == 4)][0]
oka = (att["SystemTov"] > 0) & (att["InsGnssBIT.InsMode"] == 4)
ref = np.interp(run.t + t0, att["SystemTov"][oka], np.unwrap(att["EulerAttitude[2]"][oka]))
drift = np.rad2deg(np.unwrap(run.z_dr[:, 0]) - ref)
drift -= drift[0]
for k in range(0, len(t), 50):
    if t[k] <= 200:
        e = np.hypot(*(est[k, [0, 3]] - xt[k, [0, 3]]))
        print(f"{t[k]:6.1f} v {v[k]:5.2f} err {e:6.2f} hb {np.rad2deg(est[k,7]):6.2f} deg  sensor heading err {hdg_err[k] if v[k]>1 else float('nan'):6.2f}  rb {np.rad2deg(est[k,8])*1:7.4f} deg/s  gyro-ref {drift[k]:6.2f} deg")
