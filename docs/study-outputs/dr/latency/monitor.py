"""The error monitor (one generalized likelihood ratio test of a gyro scale factor error, of the fixes'
latency and, since stop 42, of the speed's latency) on the held-out analogs and on the drives it must leave alone: one EKF pass (phone grade) over each
whole drive with every fix, warning only (``scale_on_detection=False, latency_on_detection=False``). Per drive:
each error's estimate and z-score at the end, the largest |z| on the way, and the step at which it warned.

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/latency/monitor.py analogs 0,1,2,3,4,5 > monitor_seeds_0_5.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/latency/monitor.py others > monitor_other.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/latency/monitor.py analogs 0,1,2,3,4,5 survey > monitor_seeds_0_5_survey.txt

(the last with the survey grade's model, which has no rate-bias state and so no scale monitor, on analogs
whose gyros have a rate bias it lacks.)
"""
import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..")
sys.path[:0] = [os.path.join(ROOT, "tests"), os.path.join(ROOT, "tests", "navigation")]
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.dead_reckoning import GPSDRModel  # noqa: E402
from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive, read_drive_csv, sample_drive_path  # noqa: E402
from filterwnn.navigation.gpsdr import GPSDRFilter  # noqa: E402

#: (label, the analogs' generator keywords)
ERRORS = (("none", {}), ("scale +1 %", {"gyro_scale": 0.01}), ("scale +3 %", {"gyro_scale": 0.03}),
          ("scale -2 %", {"gyro_scale": -0.02}), ("latency +0.5 s", {"gps_latency": 0.5}),
          ("latency +1 s", {"gps_latency": 1.0}), ("latency -0.5 s", {"gps_latency": -0.5}),
          ("speed +0.5 s", {"odometer_latency": 0.5}), ("speed -0.5 s", {"odometer_latency": -0.5}))
#: (monitored error, unit, factor on its estimate)
TESTED = (("gyro_scale", "%", 100.0), ("latency", "s", 1.0), ("odometer_latency", "s", 1.0))


def _fmt(v, f):
    return "-" if v is None else format(v, f)


def one_pass(f, run, names):
    """``f`` over the whole of ``run`` with every fix, warnings silenced: per monitored error in ``names``, its
    z-score largest in size on the way, and the step at which it warned (None: it did not)."""
    gps, sig = run.gps_list(), run.gps_sigma_list()
    top, fired = dict.fromkeys(names, 0.0), dict.fromkeys(names)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for k in range(len(run.z_dr)):
            f.predict()
            f.update(run.z_dr[k], gps[k], sig[k])
            for name in names:
                z = getattr(f, f"{name}_z")
                if z is not None and abs(z) > abs(top[name]):
                    top[name] = z
                if fired[name] is None and name in f._warned_errors:
                    fired[name] = k
    return top, fired


def one(label, run, grade, kind="ekf"):
    m = GPSDRModel.from_grade(grade, run.scenario.dt)
    f = GPSDRFilter(m, kind, x0=np.r_[run.x0, m.x0[6:]], scale_on_detection=False, latency_on_detection=False)
    top, fired = one_pass(f, run, [name for name, *_ in TESTED])
    cells = []
    for name, unit, times in TESTED:
        est = getattr(f, f"{name}_estimate")
        cells.append(f"{name} {_fmt(None if est is None else times * est, '+.2f')} {unit} z {_fmt(getattr(f, f'{name}_z'), '+.2f')}"
                     f" (max |z| {abs(top[name]):.2f}) warned at {_fmt(fired[name], 'd')}")
    print(f"{label:45s} | " + " | ".join(cells) + f" | gps_correlation mean {_fmt(f.gps_correlation_mean, '.2f')}",
          flush=True)


def analogs(seeds, grade="phone"):
    with tempfile.TemporaryDirectory() as tmp:
        for name in held_out.HELD_OUT:
            for seed in seeds:
                for label, kw in ERRORS:
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"),
                                                                held_out.columns(name, seed, **kw)))
                    one(f"{name} seed {seed}, {label}", run, grade)


def others():
    import test_hard_drives as th

    for d in th.DRIVES:
        run, grade, _ = d(np.random.default_rng(np.random.SeedSequence([23, th.DRIVES.index(d)])))
        one(f"hard bench: {d.__name__} ({grade})", run, grade)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(sample_drive_path())
    for kind in ("ekf", "ukf", "sukf"):
        one(f"sample ({kind})", run, "phone", kind)
    for name in CAR_DRIVES:
        for grade in ("survey", "phone"):
            one(f"{name} ({grade})", load_car_drive(name), grade)


if __name__ == "__main__":
    if sys.argv[1] == "analogs":
        analogs([int(s) for s in sys.argv[2].split(",")], *sys.argv[3:4])
    else:
        others()
