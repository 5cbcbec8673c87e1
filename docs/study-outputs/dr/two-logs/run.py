"""Two more new users' logs, converted as they would, read and scored untuned (stop 59).

    python docs/study-outputs/dr/two-logs/run.py DIR > docs/study-outputs/dr/two-logs/run.txt   # about 20 minutes

``nmea_can_*``: a test engineer's NMEA log of a 5 Hz receiver (GGA, RMC, GST) beside a 50 Hz CAN log (four wheel
speeds in km/h, an ISO 8855 yaw rate, the gear) on the logger's own clock; ``ros_bag_*``: a ROS 2 bag exported a
CSV per topic (/imu/data at 100 Hz, /odom at 20 Hz, /gps/fix NavSatFix at 1 Hz). Each simulator and converter is
the helper's own, unchanged; each writes next to itself, so both are copied into ``DIR/<log>/`` and run there.
For every variant of each converter (the right conversion and the mistakes a user makes) it says what the drive
reader does (read, with its warnings but the stamps' jitter, but where receipt times are the variant, or its
refusal); then it scores the runs of ``RUNS``
as ``filterwnn study dr --drive FILE`` does, run as a user runs it, and prints each filter's median / max at the
outage ends (m; DR-mech: dead reckoning from the true start).
"""
import pathlib
import shutil
import subprocess
import sys
import warnings

from filterwnn.navigation.drives import read_drive_csv

HERE = pathlib.Path(__file__).resolve().parent
#: (log, variant, converter options)
VARIANTS = [
    ("nmea_can", "ok", []), ("nmea_can", "kmh", ["--kmh"]), ("nmea_can", "iso_yaw", ["--iso-yaw"]),
    ("nmea_can", "utc_time_of_day", ["--clock", "utc"]), ("nmea_can", "start_offset", ["--clock", "offset2"]),
    ("nmea_can", "receipt_time", ["--rx-time"]), ("nmea_can", "gear_ignored", ["--ignore-gear"]),
    ("nmea_can", "hdop_as_sigma", ["--hdop-sigma"]), ("nmea_can", "tunnel_zeros", ["--tunnel-zeros"]),
    ("nmea_can", "rmc_speed", ["--rmc-speed"]), ("nmea_can", "rmc_course", ["--rmc-course"]),
    ("ros_bag", "ok", ["--type0", "drop"]), ("ros_bag", "ahrs_yaw_as_is", ["--heading", "ahrs_raw", "--type0", "drop"]),
    ("ros_bag", "rad_s_as_deg_s", ["--yawrate", "rad_in_deg", "--type0", "drop"]),
    ("ros_bag", "ccw", ["--yawrate", "ccw_rad", "--type0", "drop"]), ("ros_bag", "ns", ["--time", "ns", "--type0", "drop"]),
    ("ros_bag", "variance_as_sigma", ["--sigma", "var", "--type0", "drop"]),
    ("ros_bag", "type0_zero", ["--type0", "zero"]), ("ros_bag", "status_nan", ["--status", "nan", "--type0", "drop"]),
    ("ros_bag", "pose_differentiated", ["--speed", "posediff", "--type0", "drop"]),
    ("ros_bag", "ahrs_converted", ["--heading", "ahrs_conv", "--type0", "drop"]),
    ("ros_bag", "ffill_100hz", ["--layout", "ffill100", "--type0", "drop"]),
    ("ros_bag", "ffill_20hz", ["--layout", "ffill20", "--type0", "drop"]),
    ("ros_bag", "bag_receipt_stamps", ["--stamp", "bag", "--type0", "drop"]),
    ("ros_bag", "gps_speed", ["--speed", "gps", "--type0", "drop"]),
]
#: (log, variant, grade, extra options): the runs scored
RUNS = [("nmea_can", "ok", "phone", []), ("nmea_can", "ok", "survey", []),
        ("nmea_can", "ok", "phone", ["--gyro-bias", "0.2"]),
        ("ros_bag", "ok", "phone", []), ("ros_bag", "ok", "survey", []),
        ("ros_bag", "ok", "phone", ["--gyro-bias", "0.4"]),
        ("ros_bag", "bag_receipt_stamps", "phone", ["--gyro-bias", "0.4"])]


def main():
    out = pathlib.Path(sys.argv[1])
    for log, sim in (("nmea_can", "simulate_log.py"), ("ros_bag", "simulate_bag.py")):
        d = out / log
        d.mkdir(parents=True, exist_ok=True)
        shutil.copy(HERE / f"{log}_simulate.py", d / sim)
        shutil.copy(HERE / f"{log}_convert.py", d / "convert.py")
        subprocess.run([sys.executable, str(d / sim)], check=True, stdout=subprocess.DEVNULL, cwd=d)
    for log, v, opts in VARIANTS:
        path = out / log / f"drive_{v}.csv"
        subprocess.run([sys.executable, str(out / log / "convert.py"), str(path)] + opts, check=True,
                       stdout=subprocess.DEVNULL, cwd=out / log)
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            try:
                read_drive_csv(path)
                said = "read"
            except ValueError as exc:
                said = "REFUSED: " + str(exc).split(": ", 1)[1][:400]
        print(f"{log} {v}: {said}")
        for w in seen:
            if not str(w.message).startswith("the sample times jitter") or v == "bag_receipt_stamps":
                print(f"  warns: {str(w.message)[:300]}")
        sys.stdout.flush()
    for log, v, grade, extra in RUNS:
        cmd = ["filterwnn", "study", "dr", "--drive", str(out / log / f"drive_{v}.csv"), "--grade", grade,
               "--no-progress", "--no-figures", "--out", str(out / f"out_{log}_{v}_{grade}{''.join(extra)}")] + extra
        proc = subprocess.run(cmd, capture_output=True, text=True)
        cells = {}
        for line in proc.stdout.splitlines():
            parts = [p.strip() for p in line.split("|")]
            if len(parts) > 4 and parts[1] in ("DR-mech", "EKF", "EKF-8", "UKF-8", "SUKF-8"):
                cells[parts[1]] = f"{parts[2]} / {parts[4]}"
        print(f"{log} {v} --grade {grade} {' '.join(extra)}: exit {proc.returncode}; "
              + "; ".join(f"{k} {c}" for k, c in cells.items()), flush=True)


if __name__ == "__main__":
    main()
