"""Filter consistency on a linear-Gaussian model (issue 8, part 6): NEES and NIS.

For a consistent filter the normalised estimation error squared
``e_k^T P_k^{-1} e_k`` is chi-square with ``dim_x`` degrees of freedom, so its average
over ``M`` independent (seeded) Monte-Carlo runs lies in
:func:`filterwnn.metrics.chi2_bounds` ``(dim_x, M)`` at about 95 % of the steps; NIS
is the same for the innovation with ``dim_z`` degrees of freedom (Bar-Shalom, Li and
Kirubarajan 2001, sec. 5.4). Every test also has a *negative control*: the same filter
told a process noise 20 times too small must fail the same check, so the check has
power.

Particle filters: the bootstrap filter and the Kalman-proposal filters with
the Gaussian-sum filter (the former ``weighting="bank"``) are tested. (With ``weighting="textbook"`` the EPF/UPF/SUPF on this
model degenerate -- effective sample size near 1 out of 100, a single distinct particle
and a collapsed sample covariance at some steps -- a property of carrying each particle's
posterior covariance into the next proposal, not of this package's arithmetic, which
``tests/monte_carlo/test_particle_filter.py`` pins to closed forms.)

Runs are independent streams from ``np.random.SeedSequence(seed).spawn(M)`` and the
numbers are deterministic; the thresholds (fraction of steps inside the 95 % band,
overall average) leave room for the sampling spread of a correct filter.
"""

import numpy as np
import pytest
from filterpy.kalman import MerweScaledSigmaPoints

from filterwnn import (
    LinearGaussianModel,
    MinimalSkewSigmaPoints,
    SphericalSimplexSigmaPoints,
    UnscentedKalmanFilter,
)
from filterwnn.monte_carlo import particle_filter as pf_module
from filterwnn.monte_carlo.gaussian_sum import GaussianSumFilter
from filterwnn.metrics import chi2_bounds, nees, nis

N_RUNS = 50
N_STEPS = 30
MODEL = LinearGaussianModel.random(dim_x=3, dim_z=2, rng=11)
# a model whose measurement sees little of the state, so the prior matters
MODEL.P0 = np.eye(3)

# fraction of steps whose run-averaged NEES lies in the 95 % band: a consistent filter
# scores about 0.95; 0.8 leaves room for the spread of 40 correlated steps.
MIN_FRACTION = 0.8


def _scenarios(seed=2026):
    """Ground truth and measurements of ``N_RUNS`` independent runs (seeded)."""
    streams = np.random.SeedSequence(seed).spawn(N_RUNS)
    return [MODEL.simulate(N_STEPS, rng=np.random.default_rng(s)) for s in streams]


SCENARIOS = _scenarios()
TRUTH = np.stack([xs for xs, _ in SCENARIOS])  # (n_runs, n_steps, dim_x)


def band_fraction(stat, dof):
    """Fraction of steps whose run average of ``stat (n_runs, n_steps)`` is in the band."""
    lo, hi = chi2_bounds(dof, n_runs=stat.shape[0])
    avg = stat.mean(axis=0)
    return float(np.mean((avg >= lo) & (avg <= hi)))


def overall_ok(stat, dof, rel=0.15):
    """The grand average is within ``rel`` of ``dof``."""
    return abs(stat.mean() / dof - 1.0) < rel


POINTS = {
    "merwe": lambda n: MerweScaledSigmaPoints(n, alpha=1.0, beta=2.0, kappa=0.0),
    "simplex": lambda n: SphericalSimplexSigmaPoints(n),
    "minimal-skew": lambda n: MinimalSkewSigmaPoints(n),
}


def run_ukf(points, vectorized, q_scale=1.0):
    """NEES (runs, steps) and NIS (runs, steps) of the UKF over the seeded runs."""
    m = MODEL
    est = np.empty((N_RUNS, N_STEPS, m.dim_x))
    cov = np.empty((N_RUNS, N_STEPS, m.dim_x, m.dim_x))
    inn = np.empty((N_RUNS, N_STEPS, m.dim_z))
    inn_cov = np.empty((N_RUNS, N_STEPS, m.dim_z, m.dim_z))
    for r, (xs, zs) in enumerate(SCENARIOS):
        ukf = UnscentedKalmanFilter(m.dim_x, m.dim_z, m.dt, m.hx, m.fx, POINTS[points](m.dim_x),
                                    vectorized=vectorized)
        ukf.Q, ukf.R = m.Q * q_scale, m.R.copy()
        ukf.x, ukf.P = m.x0.copy(), m.P0.copy()
        for k in range(N_STEPS):
            ukf.predict()
            ukf.update(zs[k])
            est[r, k], cov[r, k], inn[r, k], inn_cov[r, k] = ukf.x, ukf.P, ukf.y, ukf.S
    return nees(TRUTH, est, cov), nis(inn, inn_cov)


@pytest.mark.parametrize(
    "points, vectorized", [("merwe", False), ("simplex", True), ("minimal-skew", True), ("minimal-skew", False)]
)
def test_ukf_is_nees_and_nis_consistent(points, vectorized):
    ne, ni = run_ukf(points, vectorized)
    assert band_fraction(ne, MODEL.dim_x) >= MIN_FRACTION
    assert band_fraction(ni, MODEL.dim_z) >= MIN_FRACTION
    assert overall_ok(ne, MODEL.dim_x) and overall_ok(ni, MODEL.dim_z)


def test_kalman_filter_reference_passes_the_same_check():
    """The check is calibrated: filterpy's exact KF passes it on the same runs."""
    ne = np.empty((N_RUNS, N_STEPS))
    ni = np.empty((N_RUNS, N_STEPS))
    for r, (xs, zs) in enumerate(SCENARIOS):
        kf = MODEL.kalman_filter()
        for k in range(N_STEPS):
            kf.predict()
            kf.update(zs[k])
            ne[r, k] = nees(xs[k], kf.x, kf.P)
            ni[r, k] = nis(kf.y, kf.S)
    assert band_fraction(ne, MODEL.dim_x) >= MIN_FRACTION
    assert band_fraction(ni, MODEL.dim_z) >= MIN_FRACTION
    ukf_ne, _ = run_ukf("simplex", True)
    np.testing.assert_allclose(ukf_ne, ne, rtol=1e-8)  # UKF == KF on a linear model


def test_overconfident_ukf_fails_the_check():
    """Negative control: Q 20 times too small makes the filter inconsistent."""
    ne, ni = run_ukf("simplex", True, q_scale=0.05)
    assert band_fraction(ne, MODEL.dim_x) < 0.3
    assert ne.mean() > 1.5 * MODEL.dim_x
    assert ni.mean() > 1.2 * MODEL.dim_z


# --------------------------------------------------------------------------- particle filters

N_RUNS_PF = 30
PF_CASES = {
    # name: (class, n_particles, keywords)
    "bootstrap-300": ("BootstrapParticleFilter", 300, {}),
    "gsf-ekf-30": ("ekf", 30, {}),
    "gsf-ukf-30": ("ukf", 30, {}),
    "gsf-sukf-30": ("sukf", 30, {"resampling": "stratified"}),
}


def run_pf(case, q_scale=1.0):
    """NEES of the posterior and NIS of the predicted measurement ``H x_prior``,
    ``S = H P_prior H^T + R``, over the first ``N_RUNS_PF`` seeded runs."""
    name, n, kw = PF_CASES[case]
    m = MODEL
    seeds = np.random.SeedSequence(4).spawn(N_RUNS_PF)
    est = np.empty((N_RUNS_PF, N_STEPS, m.dim_x))
    cov = np.empty((N_RUNS_PF, N_STEPS, m.dim_x, m.dim_x))
    inn = np.empty((N_RUNS_PF, N_STEPS, m.dim_z))
    inn_cov = np.empty((N_RUNS_PF, N_STEPS, m.dim_z, m.dim_z))
    for r in range(N_RUNS_PF):
        _, zs = SCENARIOS[r]
        if name in ("ekf", "ukf", "sukf"):  # the Gaussian-sum filter (the former bank), its old start
            pf = GaussianSumFilter(m.dim_x, m.dim_z, m.dt, m.hx, m.fx, component=name, FJacobian=m.FJacobian,
                                   HJacobian=m.HJacobian, vectorized=True, rng=seeds[r], ess_threshold=1.0, **kw)
            L = np.linalg.cholesky(m.P0)
            pf.initialize(m.x0 + pf.rng.standard_normal((n, m.dim_x)) @ L.T, m.P0)
        else:
            pf = getattr(pf_module, name)(m.dim_x, m.dim_z, m.dt, m.hx, m.fx, n, FJacobian=m.FJacobian,
                                          HJacobian=m.HJacobian, vectorized=True, rng=seeds[r], **kw)
            pf.x, pf.P = m.x0.copy(), m.P0.copy()
        pf.Q, pf.R = m.Q * q_scale, m.R.copy()
        for k in range(N_STEPS):
            pf.predict()
            inn[r, k] = zs[k] - m.H @ pf.x_prior
            inn_cov[r, k] = m.H @ pf.P_prior @ m.H.T + m.R
            pf.update(zs[k])
            est[r, k], cov[r, k] = pf.x, pf.P
    return nees(TRUTH[:N_RUNS_PF], est, cov), nis(inn, inn_cov)


@pytest.mark.parametrize("case", sorted(PF_CASES))
def test_particle_filters_are_nees_and_nis_consistent(case):
    ne, ni = run_pf(case)
    assert band_fraction(ne, MODEL.dim_x) >= MIN_FRACTION
    assert band_fraction(ni, MODEL.dim_z) >= MIN_FRACTION
    # the particle approximation adds Monte-Carlo error: allow 20 % on the grand average
    assert overall_ok(ne, MODEL.dim_x, rel=0.2) and overall_ok(ni, MODEL.dim_z, rel=0.2)


def test_overconfident_particle_filter_fails_the_check():
    ne, ni = run_pf("gsf-ukf-30", q_scale=0.05)
    assert band_fraction(ne, MODEL.dim_x) < 0.3
    assert ne.mean() > 1.5 * MODEL.dim_x and ni.mean() > 1.2 * MODEL.dim_z
