"""Write the drive CSVs of the five new users' logs at hand (stops 58-62), without scoring them, into ``DIR``: the
u-blox user's 28 (``../ublox-log``: simulate, convert), the OBD-II user's 25 (``../obd-log``), the phone-log user's 10
(``../phone-log``) and the NMEA + CAN and ROS bag users' 25 (``../two-logs``, every variant its ``run.py`` writes).
Each simulator and converter is run as its own ``run.py`` runs it (the same seeds). Run from the repository root::

    python docs/study-outputs/dr/log-faults/users_csvs.py DIR

then a probe's ``files`` mode reads them, from ``DIR``: ``ublox/csv/*.csv obd/csv/*.csv phone/drive_*.csv
nmea_can/drive_*.csv ros_bag/drive_*.csv`` (``gps_derived.py``: ``gps_derived_users.txt``).
"""
import os
import pathlib
import shutil
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
DR = HERE.parent
out = pathlib.Path(sys.argv[1])


def py(*args, cwd=None):
    subprocess.run([sys.executable, *map(str, args)], check=True, stdout=subprocess.DEVNULL, cwd=cwd)


sys.path.insert(0, str(DR / "ublox-log"))
from convert import convert  # noqa: E402
from sim_ublox import simulate  # noqa: E402

for d in ("log", "csv"):
    os.makedirs(out / "ublox" / d, exist_ok=True)
simulate(str(out / "ublox" / "log"), 7)  # (run.py's default seed)
convert(str(out / "ublox" / "log"), str(out / "ublox" / "csv"))
py(DR / "obd-log" / "sim_obd.py", "--out", out / "obd" / "log", "--seed", 7)
py(DR / "obd-log" / "convert.py", "--log", out / "obd" / "log", "--out", out / "obd" / "csv")
import importlib.util  # noqa: E402


def variants(folder):
    """The ``VARIANTS`` of ``folder``'s ``run.py`` (each user's list of conversions)."""
    spec = importlib.util.spec_from_file_location(f"run_{folder}", DR / folder / "run.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.VARIANTS


py(DR / "phone-log" / "simulate_sensorlog.py", out / "phone")
for v in variants("phone-log"):
    py(DR / "phone-log" / "convert.py", out / "phone", v, out / "phone" / f"drive_{v}.csv")
for log, sim in (("nmea_can", "simulate_log.py"), ("ros_bag", "simulate_bag.py")):
    d = out / log
    d.mkdir(parents=True, exist_ok=True)
    shutil.copy(DR / "two-logs" / f"{log}_simulate.py", d / sim)
    shutil.copy(DR / "two-logs" / f"{log}_convert.py", d / "convert.py")
    py(d / sim, cwd=d)
for log, v, opts in variants("two-logs"):
    py(out / log / "convert.py", out / log / f"drive_{v}.csv", *opts, cwd=out / log)
print("wrote", sum(len(list(out.glob(g))) for g in ("ublox/csv/*.csv", "obd/csv/*.csv", "phone/drive_*.csv",
                                                  "nmea_can/drive_*.csv", "ros_bag/drive_*.csv")), "drive CSVs")
