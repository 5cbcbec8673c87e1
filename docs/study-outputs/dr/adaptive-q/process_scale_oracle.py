"""Would a process-noise scale help the city analog? An oracle bound (issue 23), design seeds only.

Hypothesis tested: the city car's sensors are better than the phone grade, the 8-state filter
believes its dead reckoning drifts faster than it does, so it follows the urban-canyon fixes;
an online estimate of a process-noise scale ``lam`` in ``[1/k, 1]`` (times the grade's) would
let it average the fixes longer.

Before building any online estimator, this measures what the best *fixed* scale could do: the
filter run with the grade's noises times ``lam`` for ``lam`` = 1, 1/4, 1/16, 1/64, chosen by
hand (an oracle no online estimate can beat by much: an estimate bounded to ``[1/k, 1]`` picks a
value inside this range at each step). Run from the repository root, one BLAS thread::

    PYTHONPATH=. OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/adaptive-q/process_scale_oracle.py \
        > docs/study-outputs/dr/adaptive-q/process_scale_oracle.txt

Only the design seeds 0 and 1 of the analogs of ``tests/_held_out_drives.py``, scored as
``filterwnn study dr --drive FILE --grade phone`` scores them (20 outages of 30 s, median / max of
the horizontal error at the outage ends, m; mean NIS of the accepted fixes).

A. ``all x lam``: every process noise (the jerk PSD ``q``, the random walks of the odometer scale,
   heading bias and rate bias) and the DR sensors' noise (heading, odometer; variances) times
   ``lam``; ``q x lam``: the jerk PSD alone. All three 8-state kinds.
B. Where the filter's position variance between fixes comes from (EKF-8, the drive run with all
   its fixes): per fix, the predicted position sigma, its growth since the last fix (m^2, mean of
   the two axes), the heading-bias sigma (deg), the NIS and the error at the fixes.
C. The analog's own sensor numbers as the grade (an oracle: the truth that no filter is given),
   all of them, then the calibration priors alone and the noises alone (EKF-8).
"""

import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests"))

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.dead_reckoning import SENSOR_GRADES, _grade_settings  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402
from filterwnn.studies.dr._real import REAL_MODEL, _real_drive_filter  # noqa: E402

SEEDS = (0, 1)
NAMES = ("city", "phone", "one_hz")
KINDS8 = ("EKF-8", "UKF-8", "SUKF-8")
PHONE = _grade_settings(dict(SENSOR_GRADES["phone"]), True)


def all_noise(lam):
    """The phone grade's process and DR sensor noises times ``lam`` (variances)."""
    return dict(q=PHONE["q"] * lam, q_scale=PHONE["q_scale"] * lam, q_bias=PHONE["q_bias"] * lam,
                q_rate=PHONE["q_rate"] * lam, sigma_heading=PHONE["sigma_heading"] * np.sqrt(lam),
                sigma_odometer=PHONE["sigma_odometer"] * np.sqrt(lam))


#: Each analog's own sensors (tests/_held_out_drives.py) written as a grade: an oracle.
TRUE_NOISES = {
    "city": dict(heading_noise_deg=0.2, gyro_arw_deg_rt_h=0.5, odometer_noise_m=0.01),
    "phone": dict(heading_noise_deg=0.3, gyro_arw_deg_rt_h=0.3, odometer_noise_m=0.01),
    "one_hz": dict(heading_noise_deg=0.5, gyro_arw_deg_rt_h=1.0, odometer_noise_m=0.1),
}
TRUE_PRIORS = {  # |scale - 1|, |heading offset| (1 deg where it is 0: a prior needs a spread), rate bias
    "city": dict(odometer_scale_sd=0.01, heading_bias_sd_deg=1.0, gyro_bias_deg_s=0.015),
    "phone": dict(odometer_scale_sd=0.02, heading_bias_sd_deg=1.0, gyro_bias_deg_s=0.005),
    "one_hz": dict(odometer_scale_sd=0.015, heading_bias_sd_deg=1.0, gyro_bias_deg_s=0.05),
}


def score(run, kinds, grade="phone", model_kwargs=None):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        res = real_drive_outages(run, filters=kinds, use_gps_sigma=True, grade=grade, model_kwargs=model_kwargs)
    return " | ".join(f"{k} {np.median(res[k]):6.2f} / {res[k].max():6.2f} (NIS {res['integrity'][k]['nis_mean']:.2f})"
                      for k in kinds)


def growth(run, model_kwargs=None):
    f = _real_drive_filter("EKF-8", run, "phone", model_kwargs, dict(REAL_MODEL), 0, None)
    gps, sig = run.gps_list(), run.gps_sigma_list()
    pre, grow, hb, nis, err, last = [], [], [], [], [], None
    pos = np.ix_([0, 3], [0, 3])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        for k in range(len(run.t)):
            f.predict()
            if gps[k] is not None:
                p = np.trace(f.P[pos]) / 2
                pre.append(p)
                if last is not None:
                    grow.append(p - last)
            f.update(run.z_dr[k], gps[k], sig[k])
            if gps[k] is not None:
                last = np.trace(f.P[pos]) / 2
                hb.append(np.rad2deg(np.sqrt(f.P[7, 7])))
                nis.append(f.nis)
                err.append(np.hypot(*(f.x[[0, 3]] - run.x_true[k, [0, 3]])))
    med = lambda a: np.median(a)  # noqa: E731
    return (f"pos sigma {med(np.sqrt(pre)):5.2f} m, growth/fix {med(grow):5.2f} m^2, heading-bias sigma "
            f"{med(hb):5.2f} deg, NIS (all fixes) {np.mean(nis):.2f}, error at the fixes {med(err):5.2f} m (medians)")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        runs = {(n, s): read_drive_csv(held_out.write_csv(os.path.join(tmp, f"{n}_{s}.csv"), held_out.columns(n, s)))
                for n in NAMES for s in SEEDS}
        print("## A. A fixed process-noise scale (median / max at the outage ends, m)")
        cfgs = [("phone grade", None)] + [(f"all x 1/{1 / lam:g}", all_noise(lam)) for lam in (1 / 4, 1 / 16, 1 / 64)] \
            + [(f"q x 1/{1 / lam:g}", dict(q=PHONE["q"] * lam)) for lam in (1 / 4, 1 / 16)]
        for (n, s), run in runs.items():
            for label, mk in cfgs:
                print(f"{n} seed {s} | {label:12s} | {score(run, KINDS8, model_kwargs=mk)}", flush=True)
        print("\n## B. The position variance between fixes (EKF-8, all fixes, no outage)")
        for s in SEEDS:
            for label, mk in [("phone grade", None), ("all x 1/16", all_noise(1 / 16)), ("all x 1/64", all_noise(1 / 64))]:
                print(f"city seed {s} | {label:12s} | {growth(runs['city', s], mk)}", flush=True)
        print("\n## C. The analog's own sensor numbers as the grade (an oracle; EKF-8)")
        for (n, s), run in runs.items():
            for label, grade in [("phone grade", "phone"), ("true, all", dict(TRUE_NOISES[n], **TRUE_PRIORS[n])),
                                 ("true priors", dict(TRUE_PRIORS[n])), ("true noises", dict(TRUE_NOISES[n]))]:
                print(f"{n} seed {s} | {label:12s} | {score(run, ('EKF-8',), grade=grade)}", flush=True)


if __name__ == "__main__":
    main()
