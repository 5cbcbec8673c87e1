"""Correlated fixes counted by their own share of the innovation (issue 23, stop 48): screened, with its criterion.

Stop 36's ``"inflate"`` (each used fix's covariance times the fixes' measured correlation ``c``) mends the city
analogs and 2021-03-29 and breaks 2021-04-27C's maximum (15.21 -> 17.47 m): there the innovations are correlated
by the model's errors (a car's manoeuvres against a white-jerk model), not by the fixes (``RUN.md``). An
innovation is the fix's error plus the prediction's; only the first is the fixes' correlation to count. The
variants here inflate each fix's covariance by ``c_eff = 1 + (c - 1) rho``, ``rho = r / (r + p)``, ``r`` the fix's
variance per axis as used and ``p`` the prediction's position variance per axis (half the trace of ``H P H^T``):
the fixes' correlation in the share of the innovation that is theirs. Nothing is fitted; ``rho`` is the filter's
own at each fix.

* ``base``: the package's default (``correlated_fixes="calibration"``);
* ``share``: the default, and each used fix's covariance times ``c_eff``;
* ``share-cons``: each used fix's covariance times ``c_eff``, the calibration's own ``1 / c`` dropped (as
  ``"inflate"`` drops it).

The criterion, written before any of its numbers was read (stop 36's protocol):
(a) with the survey grade, EKF-8: 2021-04-27C within the issue's 1.66 / 15.3 m, 2021-03-29 no worse than the
default (1.48 / 8.73 m); the sample (phone grade) median within 3.57 m; (b) on analog seeds 0-29 (EKF-8, the
screen of ``screen.py``), meeting the targets on at least as many seeds per analog as ``base`` and on more in all;
then every kind on the hard bench (better than dead reckoning) and on fresh seeds.

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/inflation/share.py recorded
    python docs/study-outputs/dr/inflation/share.py analogs 0,1,2,3,4,5,6,7,8,9,10,11,12,13,14
"""
import os, sys, tempfile, warnings, numpy as np
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]
from filterwnn.navigation import gpsdr
from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive, read_drive_csv, sample_drive_path
from filterwnn.studies.dr import real_drive_outages
F = gpsdr.GPSDRFilter
GW, CF = F._gain_weights, F._check_fix


def cf_share(self, z_gps, gps_sigma, test=True, scaled=True):
    z, s = CF(self, z_gps, gps_sigma, test, scaled)
    c = self.gps_correlation
    if z is not None and c > 1.0:
        r = self._fix_sigma(s) ** 2
        _, S = self._innovation
        p = max(0.5 * np.trace(S) - self._check_r, 0.0)  # the prediction's share of what the check tested
        rho = r / (r + p)
        s = np.sqrt(r * (1.0 + (c - 1.0) * rho))
    return z, s


def cf_wrap(self, z_gps, gps_sigma, test=True, scaled=True):
    # the variance the check tested with (before a down-weight): S = P_pos + sigma^2 I
    lam = self.gps_scale if scaled else 1.0
    sig = self._fix_sigma(gps_sigma)
    self._check_r = (sig * np.sqrt(lam) if (gps_sigma is not None and lam != 1.0) else sig) ** 2
    return cf_share(self, z_gps, gps_sigma, test, scaled)


def gw_nocal(self, gps):
    held = self._held_rows(gps)
    if not held.size:
        return None
    w = np.ones(self.model.dim_x)
    w[held] = 0.0
    return w


VARIANTS = {"base": (GW, CF), "share": (GW, cf_wrap), "share-cons": (gw_nocal, cf_wrap)}
T = {"phone": (10, 30), "city": (20, 50), "one_hz": (6, 30)}


def score(run, filters, **kw):
    out = []
    for label, (gw, cf) in VARIANTS.items():
        F._gain_weights, F._check_fix = gw, cf
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                res = real_drive_outages(run, filters=filters, **kw)
        finally:
            F._gain_weights, F._check_fix = GW, CF
        out.append((label, {k: res[k] for k in filters}))
    return out


def main():
    what = sys.argv[1]
    if what == "recorded":
        for name in CAR_DRIVES:
            for label, r in score(load_car_drive(name), ("EKF-8",), grade="survey", use_gps_sigma=True):
                e = r["EKF-8"]
                print(f"{name} | {label} EKF-8 {np.median(e):.2f} / {e.max():.2f}", flush=True)
        run = read_drive_csv(sample_drive_path())
        for label, r in score(run, ("EKF-8", "UKF-8", "SUKF-8"), grade="phone", use_gps_sigma=True):
            print("sample | " + label + " " + " ".join(f"{k} {np.median(e):.2f} / {e.max():.2f}" for k, e in r.items()),
                  flush=True)
    elif what == "analogs":
        import _held_out_drives as held_out
        seeds = [int(s) for s in sys.argv[2].split(",")]
        names = sys.argv[3].split(",") if len(sys.argv) > 3 else list(T)
        tmp = tempfile.mkdtemp()
        for name in names:
            for seed in seeds:
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed)))
                cells = []
                for label, r in score(run, ("EKF-8",), use_gps_sigma=True, grade="phone"):
                    e = r["EKF-8"]
                    ok = np.median(e) <= T[name][0] and e.max() <= T[name][1]
                    cells.append(f"{label} {np.median(e):.2f}/{e.max():.2f}{'' if ok else '*'}")
                print(f"{name} {seed} | " + " | ".join(cells), flush=True)


if __name__ == "__main__":
    main()
