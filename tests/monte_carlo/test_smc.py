"""Tests of filterwnn.monte_carlo.smc: the MALA move and the tempered SMC sampler.

The closed-form reference is Bayesian linear regression with known noise, written with the
same interface as :class:`filterwnn.wnn.weight_model.WNNWeightModel` (``x0``, ``P0``, ``R``,
``log_prior_and_grad``, ``log_likelihood_and_grad``, ``log_likelihood``).

Tolerances (set once here). With ``N`` particles, an i.i.d. sample's mean has standard error
``sd / sqrt(N)`` and its variance a relative standard error ``sqrt(2 / N)`` (0.063 at
N = 500). SMC particles are correlated through resampling, so the tests allow 5 i.i.d.
standard errors: ``Z_TOL = 5`` on the mean, ``VAR_RTOL = 0.3`` on the variances. Over seeds
0-9 (N = 500, 10 MALA steps per rung) the worst coordinate's |z| was 0.9-3.5 and the worst relative
variance error 0.04-0.18. The log-evidence estimate is unbiased here with a seed-to-seed sd of
0.09 (MALA) to 0.14 (HMC, 2 steps of 5 leapfrogs) over seeds 0-19 (largest error 0.36), so
``LOGZ_ATOL = 0.6`` is about 4 sd.
"""

import numpy as np
import pytest
from scipy.linalg import cho_solve
from scipy.stats import multivariate_normal

from filterwnn.monte_carlo.smc import HMCMove, MALAMove, RowsTarget, make_weight_model_move, smc_sampler
from filterwnn.wnn.weight_model import WNNWeightModel

Z_TOL = 5.0
VAR_RTOL = 0.3
LOGZ_ATOL = 0.6


class BayesianLinearRegression:
    """``y = x . theta + N(0, r)``, ``theta ~ N(x0, P0)``: the weight model's interface, linear."""

    def __init__(self, x0, P0, r):
        self.x0, self.P0 = np.asarray(x0, float), np.asarray(P0, float)
        self.dim_x = len(self.x0)
        self.R = np.array([[r]])
        self._L = np.linalg.cholesky(self.P0)

    def log_prior_and_grad(self, thetas):
        dev = thetas - self.x0
        s = cho_solve((self._L, True), dev.T).T
        const = np.sum(np.log(np.diag(self._L))) + 0.5 * self.dim_x * np.log(2 * np.pi)
        return -0.5 * np.sum(dev * s, axis=1) - const, -s

    def log_likelihood_and_grad(self, thetas, X, y):
        r = self.R[0, 0]
        resid = y - thetas @ X.T
        return -0.5 * np.sum(resid**2, axis=1) / r - 0.5 * len(y) * np.log(2 * np.pi * r), resid @ X / r

    def log_likelihood(self, thetas, X, y):
        return self.log_likelihood_and_grad(thetas, X, y)[0]

    def posterior(self, X, y):
        r = self.R[0, 0]
        prec = np.linalg.inv(self.P0) + X.T @ X / r
        S = np.linalg.inv(prec)
        mu = S @ (np.linalg.solve(self.P0, self.x0) + X.T @ y / r)
        evidence = multivariate_normal(X @ self.x0, X @ self.P0 @ X.T + r * np.eye(len(y))).logpdf(y)
        return mu, S, evidence


@pytest.fixture
def blr():
    rng = np.random.default_rng(1)
    X = rng.normal(size=(30, 3))
    model = BayesianLinearRegression(np.zeros(3), np.diag([1.0, 4.0, 0.25]), 0.25)
    y = X @ rng.normal(size=3) + 0.5 * rng.normal(size=30)
    return model, X, y


@pytest.mark.parametrize("kernel", [MALAMove, HMCMove])
@pytest.mark.parametrize("preconditioner", ["diag", "cov"])
def test_smc_matches_closed_form_posterior(blr, kernel, preconditioner):
    model, X, y = blr
    mu, S, log_z = model.posterior(X, y)
    target = RowsTarget(model, X, y)
    n = 500
    steps = dict(n_steps=10) if kernel is MALAMove else dict(n_steps=2, n_leapfrog=5)
    res = smc_sampler(target, n_particles=n, rng=0, move=kernel(target, preconditioner=preconditioner, **steps))
    p = res.particles
    assert p.shape == (n, 3)
    z = (p.mean(axis=0) - mu) / np.sqrt(np.diag(S) / n)
    assert np.all(np.abs(z) < Z_TOL), z
    np.testing.assert_allclose(np.cov(p, rowvar=False).diagonal(), S.diagonal(), rtol=VAR_RTOL)
    # off-diagonal: correlations within 5 i.i.d. standard errors (about 1 / sqrt(N))
    corr = np.corrcoef(p, rowvar=False)
    corr_ref = S / np.sqrt(np.outer(np.diag(S), np.diag(S)))
    np.testing.assert_allclose(corr, corr_ref, atol=5 / np.sqrt(n))
    assert abs(res.log_evidence - log_z) < LOGZ_ATOL
    np.testing.assert_allclose(res.log_likelihood, model.log_likelihood(p, X, y))


def test_smc_ladder_and_records(blr):
    model, X, y = blr
    res = smc_sampler(RowsTarget(model, X, y), n_particles=200, rng=3, n_moves=5, ess_fraction=0.5)
    betas = np.array(res.betas)
    assert betas[-1] == 1.0 and np.all(np.diff(betas) > 0) and betas[0] > 0
    k = len(betas)
    records = (res.ess, res.acceptance, res.step_sizes, res.distinct_particles, res.distinct_ancestors)
    assert all(len(v) == k for v in records)
    # every rung but the last is set by bisection to ESS = N/2; the last (beta = 1) keeps at least N/2
    np.testing.assert_allclose(res.ess[:-1], 100.0, rtol=1e-6)
    assert res.ess[-1] >= 100.0 - 1e-6
    assert all(0 < a <= 1 for a in res.acceptance)
    assert 1 <= res.distinct_ancestors[-1] <= 200 and np.all(np.diff(res.distinct_ancestors) <= 0)
    assert res.ancestors.shape == (200,)
    # reproducible from the seed
    again = smc_sampler(RowsTarget(model, X, y), n_particles=200, rng=3, n_moves=5)
    np.testing.assert_array_equal(again.particles, res.particles)


@pytest.mark.parametrize("kernel", [MALAMove, HMCMove])
def test_move_leaves_posterior_invariant(blr, rng, kernel):
    model, X, y = blr
    mu, S, _ = model.posterior(X, y)
    n = 2000
    exact = rng.multivariate_normal(mu, S, size=n)
    move = kernel(RowsTarget(model, X, y), n_steps=20)
    moved = move(exact, rng)
    assert moved.shape == exact.shape and not np.shares_memory(moved, exact)
    assert len(move.acceptance_) == 20 and 0.3 < np.mean(move.acceptance_) < 0.99
    z = (moved.mean(axis=0) - mu) / np.sqrt(np.diag(S) / n)
    assert np.all(np.abs(z) < Z_TOL), z
    np.testing.assert_allclose(np.cov(moved, rowvar=False).diagonal(), S.diagonal(), rtol=VAR_RTOL)
    # the particles really moved (not a frozen kernel)
    assert np.mean(np.any(moved != exact, axis=1)) > 0.9


def test_mala_move_wrong_target_is_detected(blr, rng):
    """The invariance test can fail: a move on the prior (no rows) drifts away from the posterior."""
    model, X, y = blr
    mu, S, _ = model.posterior(X, y)
    exact = rng.multivariate_normal(mu, S, size=500)
    moved = MALAMove(RowsTarget(model), n_steps=20)(exact, rng)
    z = (moved.mean(axis=0) - mu) / np.sqrt(np.diag(S) / 500)
    assert np.any(np.abs(z) > Z_TOL)


def test_collapsed_population_still_moves(blr, rng):
    """A population of identical particles (after resampling collapsed) is unfrozen by the floor."""
    model, X, y = blr
    move = MALAMove(RowsTarget(model, X, y), n_steps=5, var_floor=1e-2)
    same = np.tile(model.x0 + 0.1, (20, 1))
    moved = move(same, rng)
    assert np.unique(moved, axis=0).shape[0] > 1


def test_rows_target_grows(blr):
    model, X, y = blr
    t = RowsTarget(model)
    thetas = np.zeros((4, 3)) + 0.3
    np.testing.assert_array_equal(t.log_likelihood(thetas), 0.0)
    for xk, yk in zip(X[:5], y[:5]):
        t.append(xk, yk)
    assert t.n_rows == 5
    np.testing.assert_allclose(t.log_likelihood(thetas), model.log_likelihood(thetas, X[:5], y[:5]))
    draws = t.sample_prior(4000, rng=0)
    np.testing.assert_allclose(draws.var(axis=0), np.diag(model.P0), rtol=0.1)


def test_bad_arguments(blr):
    model, X, y = blr
    t = RowsTarget(model, X, y)
    with pytest.raises(ValueError, match="ess_fraction must be in"):
        smc_sampler(t, ess_fraction=1.0)
    with pytest.raises(ValueError, match="particles must have shape"):
        MALAMove(t)(np.zeros((5, 4)))
    with pytest.raises(ValueError, match="unknown preconditioner"):
        MALAMove(t, preconditioner="full")
    with pytest.raises(ValueError, match="X must have shape"):
        RowsTarget(model, X, y[:-1])
    with pytest.raises(ValueError, match="particles must have shape"):
        smc_sampler(t, n_particles=10, particles=np.zeros((9, 3)))


def test_wnn_posterior_smoke():
    """The weight model through the same interface: a tiny network, a handful of particles."""
    rng = np.random.default_rng(5)
    model = WNNWeightModel(2, 3, R=0.1, P0=0.5)
    X = rng.uniform(-1, 1, (20, 2))
    y = np.sin(2 * X[:, 0])
    res = smc_sampler(RowsTarget(model, X, y), n_particles=20, rng=0, n_moves=3)
    assert res.particles.shape == (20, 15) and res.betas[-1] == 1.0
    assert np.all(np.isfinite(res.particles))
    move = make_weight_model_move(model, X[:3], y[:3], n_steps=2)
    assert move.target.n_rows == 3
    assert move(res.particles, 0).shape == (20, 15)


# ---------------------------------------------------------------- WNNRegressor(trainer="smc")
def test_regressor_smc_trainer():
    from filterwnn import WNNRegressor

    rng = np.random.default_rng(2)
    X = rng.uniform(-1, 1, (30, 2))
    y = np.sin(2 * X[:, 0]) + 0.1 * rng.normal(size=30)
    reg = WNNRegressor(trainer="smc", n_hidden=2, n_particles=12, n_epochs=2, random_state=0).fit(X, y)
    assert reg.settings_["Q"] == 0.0 and reg.settings_["n_particles"] == 12
    d = reg.diagnostics_
    assert len(d["mean_ess"]) == 1 and d["mean_ess"][0] >= 12 / 2 - 1e-6
    assert len(d["acceptance"]) == 2 and len(d["distinct"]) == 2  # sampler, then one rejuvenation epoch
    assert 1 <= d["distinct_ancestors"][-1] <= 12
    mean, std = reg.predict(X[:5], return_std=True)
    P = reg._final.particles
    assert P.shape == (12, reg.theta_.size)
    from filterwnn import wnn

    Y = wnn.forward(P, X[:5])
    np.testing.assert_allclose(mean, Y.mean(axis=0))
    np.testing.assert_allclose(std**2, Y.var(axis=0) + 0.1)
    again = WNNRegressor(trainer="smc", n_hidden=2, n_particles=12, n_epochs=2, random_state=0).fit(X, y)
    np.testing.assert_array_equal(again.predict(X[:5]), mean)
    # the SMC fit beats the mean predictor on its training rows
    assert np.mean((reg.predict(X) - y) ** 2) < np.var(y)


def test_cov_preconditioner_refuses_no_more_particles_than_dimensions(blr, rng):
    """N <= d: the population's covariance does not leave the target invariant, so it is refused;
    N > d runs (and the shrunk covariance stays positive definite)."""
    model, X, y = blr
    move = MALAMove(RowsTarget(model, X, y), n_steps=2, preconditioner="cov")
    with pytest.raises(ValueError, match=r"needs more particles than dimensions, got 3 particles in 3 dim.*'diag'"):
        move(rng.normal(size=(3, 3)), rng)
    out = move(rng.normal(size=(4, 3)), rng)
    assert out.shape == (4, 3) and np.all(np.isfinite(out))


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_zero_likelihood_raises_numerical_error(blr):
    from filterwnn import NumericalError

    model, X, y = blr
    with pytest.raises(NumericalError, match="rung 1") as info:
        smc_sampler(RowsTarget(model, X, y * np.inf), n_particles=10, rng=0)
    assert info.value.step == 1


def test_added_rows_reach_the_posterior_of_all_rows(blr):
    """Sampling old rows, then tempering new rows in, matches the closed form on all rows."""
    from filterwnn.monte_carlo.smc import AddedRowsTarget

    model, X, y = blr
    mu, S, _ = model.posterior(X, y)
    base = RowsTarget(model, X[:10], y[:10])
    first = smc_sampler(base, n_particles=500, rng=0, n_moves=10)
    added = AddedRowsTarget(base, X[10:], y[10:])
    res = smc_sampler(added, n_particles=500, rng=1, n_moves=10, particles=first.particles)
    z = (res.particles.mean(axis=0) - mu) / np.sqrt(np.diag(S) / 500)
    assert np.all(np.abs(z) < Z_TOL), z
    np.testing.assert_allclose(np.cov(res.particles, rowvar=False).diagonal(), S.diagonal(), rtol=VAR_RTOL)


def test_regressor_smc_partial_fit_learns_new_rows():
    from filterwnn import WNNRegressor

    rng = np.random.default_rng(2)
    X = rng.uniform(-1, 1, (30, 2))
    y = np.sin(2 * X[:, 0])
    reg = WNNRegressor(trainer="smc", n_hidden=2, n_particles=12, random_state=0)
    reg.partial_fit(X[:15], y[:15]).partial_fit(X[15:], y[15:])
    target = reg._trainer.move.target
    assert target.n_rows == 30 and len(reg.diagnostics_["mean_ess"]) == 2
