"""The fixes' covariance scale (``GPSDRFilter(scale_window=...)``, issue 23) measured off and on.

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/gps-scale/run_gps_scale.py analogs --seeds 0,1
    python docs/study-outputs/dr/gps-scale/run_gps_scale.py hard sample recorded

``analogs``: the held-out drive analogs of ``tests/_held_out_drives.py`` (phone, city, one_hz) for
each seed, scored as ``tests/navigation/test_held_out_drives.py`` scores them (``filterwnn study dr
--drive F --grade phone``: 20 outages of 30 s, the fixes' sigma, every 8-state kind and dead
reckoning from the true start); ``hard``: the bench of ``tests/navigation/test_hard_drives.py``;
``sample``: ``filterwnn study dr --drive sample``; ``recorded``: onavdata's two car drives as
``filterwnn study dr --real`` runs them (survey grade, the receiver's sigma; needs ``onavdata``).
Each line: median / max at the outage ends (m), and per filter the mean NIS of the accepted fixes,
the fixes rejected / down-weighted and the mean covariance scale.
"""

import argparse
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [os.path.join(ROOT, "tests"), os.path.join(ROOT, "tests", "navigation")]

from filterwnn.navigation.dead_reckoning import SENSOR_GRADES  # noqa: E402
from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive, read_drive_csv, sample_drive_path  # noqa: E402
from filterwnn.navigation.gpsdr import GPSDRFilter  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

KINDS8 = ("EKF-8", "UKF-8", "SUKF-8")
TARGETS = {"phone": (10.0, 30.0), "city": (20.0, 50.0), "one_hz": (6.0, 30.0)}


def _line(label, res, filters):
    cells = []
    for k in filters:
        e, ig = res[k], res["integrity"].get(k)
        c = f"{k} {np.median(e):.2f} / {e.max():.2f}"
        if ig:
            scale = "-" if ig["gps_scale_mean"] is None else f"{ig['gps_scale_mean']:.2f}"
            c += f" (NIS {ig['nis_mean']:.2f}, {ig['n_rejected']}/{ig['n_downweighted']} rej/dw, scale {scale})"
        cells.append(c)
    print(f"{label} | " + " | ".join(cells), flush=True)


#: Settings of every run (``--correlated-fixes``).
EXTRA = {}
#: The analogs' generator keywords (``--gyro-scale-error``).
ANALOG_KW = {}
#: the drive reader's settings for the analogs (``odometer_latency``)
READ_KW = {}


def _run(label, run, filters, windows, **kw):
    for w in windows:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # the filters' own alarms
            res = real_drive_outages(run, filters=filters, scale_window=w, **EXTRA, **kw)
        _line(f"{label} scale_window={w}", res, filters)


def analogs(seeds, windows):
    import _held_out_drives as held_out

    with tempfile.TemporaryDirectory() as tmp:
        for name in TARGETS:
            for seed in seeds:
                path = held_out.write_csv(os.path.join(tmp, f"{name}_{seed}.csv"),
                                          held_out.columns(name, seed, **ANALOG_KW))
                _run(f"{name} seed {seed} (target {TARGETS[name][0]:g} / {TARGETS[name][1]:g})",
                     read_drive_csv(path, **READ_KW), ("DR-mech",) + KINDS8, windows, use_gps_sigma=True, grade="phone")


def hard(windows):
    import test_hard_drives as th

    for d in th.DRIVES:
        run, grade, first = d(np.random.default_rng(np.random.SeedSequence([23, th.DRIVES.index(d)])))
        _run(d.__name__, run, ("DR-mech",) + KINDS8, windows, length=30.0,
             starts=np.linspace(first, run.t[-1] - 32.0, 4), use_gps_sigma=True, grade=grade)


def sample(windows):
    run = read_drive_csv(sample_drive_path())
    _run("sample", run, ("DR-mech", "EKF", "EKF-8", "UKF-8", "SUKF-8"), windows,
         use_gps_sigma=run.gps_sigma is not None, grade="phone")


def recorded(windows):
    for name in CAR_DRIVES:
        _run(name, load_car_drive(name), ("DR-mech", "EKF", "EKF-8"), windows, grade="survey", use_gps_sigma=True)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("what", nargs="+", choices=["analogs", "hard", "sample", "recorded"])
    p.add_argument("--seeds", default="0,1", help="analog seeds (comma-separated)")
    p.add_argument("--windows", default="0,30", help="scale_window values to run (0: off)")
    p.add_argument("--zero-rate", choices=["on", "off"], default="on",
                   help="GPSDRFilter's zero angular rate update at stops (default on, as in the package)")
    p.add_argument("--correlated-fixes", choices=["calibration", "inflate"], default="calibration",
                   help="GPSDRFilter's correlated_fixes (default calibration, as in the package)")
    p.add_argument("--gyro-scale-sd", type=float, default=0.0,
                   help="the phone grade's gyro_scale_sd: estimate the gyro's scale factor error as a state "
                        "(default 0, as in the package)")
    p.add_argument("--gps-latency-sd", type=float, default=0.0,
                   help="every grade's gps_latency_sd: estimate the fixes' latency as a state from the start "
                        "(default 0, as in the package)")
    p.add_argument("--scale-on-detection", choices=["on", "off"], default="on",
                   help="GPSDRFilter's scale_on_detection: add the gyro scale state when the monitor finds an "
                        "error (default on, as in the package)")
    p.add_argument("--gyro-scale-error", type=float, default=0.0,
                   help="the analogs' gyro turns 1 + this times the car (default 0, the analogs as stored)")
    p.add_argument("--latency-on-detection", choices=["on", "off"], default="on",
                   help="GPSDRFilter's latency_on_detection: add the latency state when the monitor finds the "
                        "fixes late (default on, as in the package)")
    p.add_argument("--gps-latency-error", type=float, default=0.0,
                   help="the analogs' fixes are the truth this many seconds before their time stamps (default 0, "
                        "the analogs as stored)")
    p.add_argument("--odometer-latency-error", type=float, default=0.0,
                   help="the analogs' speed samples are the ones this many seconds before their time stamps "
                        "(default 0, the analogs as stored)")
    p.add_argument("--odometer-latency", type=float, default=0.0,
                   help="the drive reader's odometer_latency for the analogs (default 0, as in the package)")
    a = p.parse_args(argv)
    # the analogs' faults: generator keywords
    ANALOG_KW.update({key: v for key, v in (("gyro_scale", a.gyro_scale_error), ("gps_latency", a.gps_latency_error),
                                            ("odometer_latency", a.odometer_latency_error)) if v})
    if a.odometer_latency:
        READ_KW["odometer_latency"] = a.odometer_latency
    EXTRA["correlated_fixes"] = a.correlated_fixes
    for flag, on in (("scale_on_detection", a.scale_on_detection), ("latency_on_detection", a.latency_on_detection),
                     ("zero_rate_update", a.zero_rate)):
        if on == "off":
            GPSDRFilter.__init__.__kwdefaults__[flag] = False
    if a.gyro_scale_sd:
        SENSOR_GRADES["phone"]["gyro_scale_sd"] = a.gyro_scale_sd
    if a.gps_latency_sd:
        for spec in SENSOR_GRADES.values():
            spec["gps_latency_sd"] = a.gps_latency_sd
    windows = [int(w) for w in a.windows.split(",")]
    for what in a.what:
        if what == "analogs":
            analogs([int(s) for s in a.seeds.split(",")], windows)
        else:
            globals()[what](windows)


if __name__ == "__main__":
    main()
