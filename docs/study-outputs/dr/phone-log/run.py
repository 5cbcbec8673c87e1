"""A phone log converted as a new user would, read and scored untuned (stop 58).

    python docs/study-outputs/dr/phone-log/run.py DIR > docs/study-outputs/dr/phone-log/run.txt   # 7 minutes

Simulates the log into ``DIR`` (``simulate_sensorlog.py``), writes every variant of ``convert.py``, and says what
the drive reader does with each (read, with its warnings but the stamps' jitter, or its refusal); then scores the
ones it reads as ``filterwnn study dr --drive FILE --grade G`` does, run as a user runs it, and prints each
filter's median / max at the outage ends (m; DR-mech: dead reckoning from the true start).
"""
import pathlib
import subprocess
import sys
import warnings

from filterwnn.navigation.drives import read_drive_csv

HERE = pathlib.Path(__file__).resolve().parent
VARIANTS = ["yaw_cw", "follow_advice", "yaw_aligned", "gyro", "onrow", "mistake_yaw_raw", "mistake_carried",
            "mistake_speed_m1", "mistake_gyro_ccw", "mistake_acc_radius"]
#: (variant, grade, extra options): the runs scored
RUNS = [("yaw_aligned", "phone", []), ("yaw_aligned", "survey", []), ("yaw_cw", "phone", ["--heading-offset", "-139"]),
        ("onrow", "phone", []), ("gyro", "phone", []), ("gyro", "phone", ["--gyro-bias", "0.31"]),
        ("mistake_carried", "phone", []), ("mistake_acc_radius", "phone", [])]


def main():
    out = pathlib.Path(sys.argv[1])
    subprocess.run([sys.executable, str(HERE / "simulate_sensorlog.py"), str(out)], check=True,
                   stdout=subprocess.DEVNULL)
    for v in VARIANTS:
        subprocess.run([sys.executable, str(HERE / "convert.py"), str(out), v, str(out / f"drive_{v}.csv")],
                       check=True, stdout=subprocess.DEVNULL)
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            try:
                read_drive_csv(out / f"drive_{v}.csv")
                said = "read"
            except ValueError as exc:
                said = "REFUSED: " + str(exc).split(": ", 1)[1][:400]
        print(f"{v}: {said}")
        for w in seen:
            if "jitter" not in str(w.message):
                print(f"  warns: {str(w.message)[:400]}")
        sys.stdout.flush()
    for v, grade, extra in RUNS:
        cmd = ["filterwnn", "study", "dr", "--drive", str(out / f"drive_{v}.csv"), "--grade", grade, "--no-progress",
               "--out", str(out / f"out_{v}_{grade}{''.join(extra)}")] + extra
        proc = subprocess.run(cmd, capture_output=True, text=True)
        cells = {}
        for line in proc.stdout.splitlines():
            parts = [p.strip() for p in line.split("|")]
            if len(parts) > 4 and parts[1] in ("DR-mech", "EKF", "EKF-8", "UKF-8", "SUKF-8"):
                cells[parts[1]] = f"{parts[2]} / {parts[4]}"
        print(f"{v} --grade {grade} {' '.join(extra)}: exit {proc.returncode}; "
              + "; ".join(f"{k} {c}" for k, c in cells.items()), flush=True)


if __name__ == "__main__":
    main()
