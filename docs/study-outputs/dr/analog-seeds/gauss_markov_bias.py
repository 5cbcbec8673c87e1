"""Tried and not kept (issue 23): the fixes' correlated error as two Gauss-Markov position-bias states.

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/analog-seeds/gauss_markov_bias.py city,phone 0,1 base,15:0.9,15:0.5,60:0.5,60:0.9
    python docs/study-outputs/dr/analog-seeds/gauss_markov_bias.py city,phone 0,1 base,15:0.9,15:0.5 0

(the second with ``whiteness_window=0``: no ``gps_correlation`` weighting of the calibration).

An experiment, not package code: the phone grade's EKF-8 (``GPSDRFilter``, every default) with two
more states ``b = [b_e, b_n]``, ``b_k = phi b_{k-1} + w`` (``phi = exp(-dt / tau)``), a fix modelled
as ``position + b + v``; of the fix's reported variance ``sigma^2`` the share ``frac`` goes to ``b``
(its stationary variance, also its prior) and the rest to ``v``. Each ``tau:frac`` is one variant
(``base``: the filter as shipped), scored on the held-out drive analogs of the design seeds as
``filterwnn study dr --drive FILE --grade phone`` scores them (20 outages of 30 s; median / max at
the ends, median at the starts, m). The analogs' own errors: city, all of it correlated over 15 s;
phone, half over 20 s and half white; so ``15:0.9`` and ``15:0.5`` are near the truth (an oracle),
``60:*`` a wrong correlation time.
"""
import os, sys, tempfile, warnings
import numpy as np
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]
import _held_out_drives as held_out
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.gpsdr import GPSDRFilter
from filterwnn.studies.dr._real import _outage_plan, _outage_ends, _start_refs, _dr_mech_ends

class GMModel(GPSDRModel):
    def __init__(self, base, tau, frac):
        self.__dict__.update(base.__dict__)
        self.base, self.tau, self.frac = base, tau, frac
        n0 = base.dim_x; self.n0 = n0; self.dim_x = n0 + 2
        self.phi = np.exp(-self.dt / tau)
        F = np.zeros((n0 + 2, n0 + 2)); F[:n0, :n0] = base.F; F[n0:, n0:] = self.phi * np.eye(2); self.F = F
        Q = np.zeros_like(F); Q[:n0, :n0] = base.Q; self.Q = Q
        self.set_bias_sigma(base.sigma_gps)
        self.x0 = np.r_[base.x0, 0.0, 0.0]
        P0 = np.zeros_like(F); P0[:n0, :n0] = base.P0; P0[n0:, n0:] = frac * base.sigma_gps**2 * np.eye(2); self.P0 = P0
    def set_bias_sigma(self, s):
        self.Q[self.n0:, self.n0:] = self.frac * s**2 * (1 - self.phi**2) * np.eye(2)
    def fx(self, x, dt=None, **kw):
        x = np.asarray(x, float); out = x.copy()
        out[..., :self.n0] = self.base.fx(x[..., :self.n0], dt); out[..., self.n0:] = self.phi * x[..., self.n0:]
        return out
    def FJacobian(self, x=None, dt=None, **kw):
        return self.F
    def hx(self, x, gps=True, velocity=False, **kw):
        x = np.asarray(x, float)
        z = self.base.hx(x[..., :self.n0], gps=gps, velocity=velocity)
        if gps:
            z = z.copy(); z[..., 2:] += x[..., self.n0:]
        return z
    def HJacobian(self, x, gps=True, velocity=False, **kw):
        x = np.asarray(x, float)
        H0 = self.base.HJacobian(x[..., :self.n0], gps=gps, velocity=velocity)
        H = np.zeros(H0.shape[:-1] + (self.dim_x,)); H[..., :self.n0] = H0
        if gps:
            H[..., 2, self.n0] = H[..., 3, self.n0 + 1] = 1.0
        return H
    def measurement_for(self, z_dr, z_gps=None, *, gps_sigma=None, **kw):
        z, R, a = self.base.measurement_for(z_dr, z_gps, gps_sigma=gps_sigma, **kw)
        if a["gps"]:
            R = R.copy(); R[2:, 2:] *= (1 - self.frac)
        return z, R, a

class GMFilter(GPSDRFilter):
    def __init__(self, model, **kw):
        super().__init__(model, "ekf", **kw)
        n0 = model.n0
        self.kf.F, self.kf.Q = model.F, model.Q
        cal = np.arange(6, n0); self._cal = cal
        self._cal_mean = self.kf.x[cal].copy()
        self._cal_F = model.F[np.ix_(cal, cal)]; self._cal_Q = model.Q[np.ix_(cal, cal)]
        self._cal_P = model.P0[np.ix_(cal, cal)].copy()
        self.held_states = np.array([0, 3] + list(range(6, n0)))
        self._b0 = False
    def update(self, z_dr, z_gps=None, gps_sigma=None):
        if z_gps is not None:
            s = self._fix_sigma(gps_sigma)
            self.model.set_bias_sigma(s)
            if not self._b0:
                n0 = self.model.n0; P = self.kf.P.copy(); P[n0:, n0:] = self.model.frac * s * s * np.eye(2); self.kf.P = P; self._b0 = True
        return super().update(z_dr, z_gps, gps_sigma)
    def _check_fix(self, z_gps, gps_sigma, test=True, scaled=True):
        # the base test with the fix predicted as position + bias, and its white part's covariance
        n0 = self.model.n0
        Hp = np.zeros((2, self.model.dim_x)); Hp[0, 0] = Hp[1, 3] = 1.0; Hp[0, n0] = Hp[1, n0 + 1] = 1.0
        z_gps = np.asarray(z_gps, float)
        y = z_gps - Hp @ self.kf.x
        sigma = self._fix_sigma(gps_sigma)
        S = Hp @ self.kf.P @ Hp.T + (1 - self.model.frac) * sigma**2 * np.eye(2)
        self._innovation = y, S
        self.nis = nis = float(y @ np.linalg.solve(S, y)); self.n_fixes += 1
        if nis <= self.reject_gate or not test:
            self._monitor(min(nis, self.reject_gate))
        if nis <= self.gate or not test:
            self._in_a_row = 0; self.fix_status = "accepted"; self.nis_accepted.append(nis); return z_gps, gps_sigma
        if nis <= self.reject_gate:
            self._in_a_row = 0; self.fix_status = "down-weighted"; self.n_downweighted += 1
            return z_gps, sigma * np.sqrt(nis / self.gate)
        if self._in_a_row >= self.reacquire_after:
            self._reacquire(y); self._in_a_row = 0; self.fix_status = "reacquired"; self.n_reacquired += 1; return z_gps, gps_sigma
        self._in_a_row += 1; self.fix_status = "rejected"; self.n_rejected += 1; self.rejected_steps.append(self.step)
        return None, gps_sigma

def score(run, tau, frac, whiteness=60):
    out, (k0s, k1s, refs) = _outage_plan(run, 30.0, None, 20, 0.0)
    base = GPSDRModel.from_grade("phone", run.scenario.dt, augmented=True)
    if tau is None:
        model, cls = base, (lambda m, **kw: GPSDRFilter(m, "ekf", **kw))
    else:
        model, cls = GMModel(base, tau, frac), GMFilter
    x0 = np.r_[run.x0, model.x0[6:]]; P0 = model.P0.copy(); P0[0, 0] = P0[3, 3] = 1.0
    f = cls(model, x0=x0, P0=P0, whiteness_window=whiteness)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        ends, begins = _outage_ends(f, "x", run, k0s, k1s, out["starts"], run.gps_list(), run.gps_sigma_list())
    e = np.hypot(*(ends - refs).T); st = np.hypot(*(begins - _start_refs(run, k0s)).T)
    return e, st

if __name__ == "__main__":
    names = sys.argv[1].split(","); seeds = [int(s) for s in sys.argv[2].split(",")]
    cfgs = [None if c == "base" else tuple(map(float, c.split(":"))) for c in sys.argv[3].split(",")]
    white = int(sys.argv[4]) if len(sys.argv) > 4 else 60  # the whiteness window (0: gps_correlation off)
    tmp = tempfile.mkdtemp()
    for name in names:
        for seed in seeds:
            run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed)))
            for c in cfgs:
                e, st = score(run, *(c if c else (None, None)), whiteness=white)
                print(f"{name} s{seed} {'base' if c is None else f'tau={c[0]:g} frac={c[1]:g}'} | EKF-8 {np.median(e):.2f} / {e.max():.2f} start {np.median(st):.2f}", flush=True)
