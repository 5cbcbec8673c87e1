"""What a GPS/DR filter's integrity costs: seconds per hour of drive against filterpy's EKF (issue 23).

A user with a long log asks how long ``filterwnn study dr --drive`` takes. Its filters are
:class:`~filterwnn.navigation.gpsdr.GPSDRFilter` (the fixes' gate, staleness, thinning and
whiteness, calibration only where observable, covariance repair) around filterpy's
``ExtendedKalmanFilter`` or our ``UnscentedKalmanFilter``. The baseline is what a filterpy user
would write without them: filterpy's ``ExtendedKalmanFilter`` on the same 8-state model
(``GPSDRModel.from_grade("phone")``), ``predict()`` and ``update()`` with
``GPSDRModel.measurement_for`` at every sample, every fix taken as it comes; for the unscented
kinds, filterpy's ``UnscentedKalmanFilter`` on the same model with the UKF-8's sigma points.

Drives: the held-out analogs of ``tests/_held_out_drives.py``, seed 0: the phone drive (10 Hz DR,
1 Hz fixes, 900 s) and the city drive with 5 Hz fixes (5 Hz DR, a fix at every sample, 720 s: the
whiteness window holds 300 fixes there, its costliest case). One pass over the whole drive with
every fix (no outages), the filters taking turns within each repeat; the median of the repeats,
scaled to one hour of drive. One BLAS thread.

Run: ``python benchmarks/bench_gpsdr.py [--repeats 5]``.
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import tempfile
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # this checkout's filterwnn
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))  # the drive analogs
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from filterpy.kalman import ExtendedKalmanFilter  # noqa: E402
from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF  # noqa: E402
from threadpoolctl import threadpool_limits  # noqa: E402

import _held_out_drives as analogs  # noqa: E402
from filterwnn.navigation.dead_reckoning import GPSDRModel, dr_residual  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.kalman.presets import make_points  # noqa: E402
from filterwnn.models import from_model  # noqa: E402
from filterwnn.navigation.gpsdr import GPSDRFilter  # noqa: E402

DRIVES = {"phone, 10 Hz DR, 1 Hz fixes": ("phone", {}),
          "city, 5 Hz DR, 5 Hz fixes": ("city", {"gps_rate": 5.0})}
BASELINE, UKF_BASELINE = "filterpy EKF", "filterpy UKF"
#: each filter and the baseline its ratio is against
FILTERS = {BASELINE: BASELINE, "EKF-8": BASELINE, UKF_BASELINE: UKF_BASELINE, "UKF-8": UKF_BASELINE,
           "SUKF-8": UKF_BASELINE}


def _drive(name, kw, folder):
    path = analogs.write_csv(Path(folder) / f"{name}.csv", analogs.columns(name, 0, **kw))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return read_drive_csv(path)


def _filterpy_ekf(model, run, gps, sig):
    """filterpy's EKF on the model: every sample, every fix as it comes."""
    kf = ExtendedKalmanFilter(model.dim_x, 2)
    kf.F, kf.Q = model.F.copy(), model.Q.copy()
    kf.x, kf.P = np.concatenate([run.x0, model.x0[6:]]), model.P0.copy()
    for k in range(len(run.t)):
        kf.predict()
        z, R, kw = model.measurement_for(run.z_dr[k], gps[k], gps_sigma=sig[k])
        args = (kw["gps"], kw["velocity"])
        kf.update(z, model.HJacobian, model.hx, R=R, args=args, hx_args=args,
                  residual=np.subtract if kw["velocity"] else dr_residual)
    return kf.x


def _filterpy_ukf(model, run, gps, sig):
    """filterpy's UKF on the model with the UKF-8's points: every sample, every fix as it comes
    (a velocity update with a linear mean and a plain residual, as GPSDRFilter's)."""
    kf = from_model(FilterpyUKF, model, points=make_points("gpsdr-ukf", model.dim_x),
                    x0=np.concatenate([run.x0, model.x0[6:]]), P0=model.P0.copy())
    heading_mean, heading_residual = kf.z_mean, kf.residual_z
    for k in range(len(run.t)):
        kf.predict()
        z, R, kw = model.measurement_for(run.z_dr[k], gps[k], gps_sigma=sig[k])
        plain = kw["velocity"]
        kf.z_mean, kf.residual_z = (None, np.subtract) if plain else (heading_mean, heading_residual)
        kf.update(z, R=R, gps=kw["gps"], velocity=plain)
    return kf.x


def _gpsdr(kind, model, run, gps, sig):
    f = GPSDRFilter(model, kind, x0=np.concatenate([run.x0, model.x0[6:]]), P0=model.P0.copy())
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for k in range(len(run.t)):
            f.predict()
            f.update(run.z_dr[k], gps[k], sig[k])
    return f.x


def time_once(name, model, run, gps, sig):
    t0 = time.perf_counter()
    if name in (BASELINE, UKF_BASELINE):
        x = (_filterpy_ekf if name == BASELINE else _filterpy_ukf)(model, run, gps, sig)
    else:
        x = _gpsdr(name.split("-")[0].lower(), model, run, gps, sig)
    secs = time.perf_counter() - t0
    if not np.all(np.isfinite(x)):
        raise FloatingPointError(f"{name}: non-finite state")
    return secs


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5)
    args = p.parse_args(argv)
    print(f"{platform.processor() or platform.machine()}, numpy {np.__version__}, one BLAS thread, "
          f"median of {args.repeats}; seconds per hour of drive, and the ratio to filterpy's filter of the same kind")
    with tempfile.TemporaryDirectory() as folder, threadpool_limits(1):
        for label, (name, kw) in DRIVES.items():
            run = _drive(name, kw, folder)
            model = GPSDRModel.from_grade("phone", run.scenario.dt)
            gps, sig = run.gps_list(), run.gps_sigma_list()
            times = {f: [] for f in FILTERS}
            for _ in range(args.repeats):
                for f in FILTERS:
                    times[f].append(time_once(f, model, run, gps, sig))
            hours = run.t[-1] / 3600.0
            med = {f: float(np.median(v)) / hours for f, v in times.items()}
            print(f"\n{label} ({len(run.t)} samples, {len(run.z_gps)} fixes, {run.t[-1]:.0f} s)")
            print("| filter | s per hour of drive | against | ratio |\n|---|---|---|---|")
            for f, base in FILTERS.items():
                print(f"| {f} | {med[f]:.1f} | {base} | {med[f] / med[base]:.2f} |")


if __name__ == "__main__":
    main()
