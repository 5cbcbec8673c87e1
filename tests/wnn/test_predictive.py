"""Tests of filterwnn.wnn.predictive and the Student-t SMC row: the t likelihood and its gradient,
the mixture's quantiles and density, and the Gaussian rows' scores unchanged."""

import os
import sys

import numpy as np
import pytest
from scipy import stats

from filterwnn import WNNRegressor
from filterwnn.datasets import make_siso_benchmark
from filterwnn.studies import wnn as study
from filterwnn.wnn import network
from filterwnn.wnn.predictive import GaussianPredictive, StudentTMixture
from filterwnn.wnn.trainers import _StudentNoise, _weight_prior
from filterwnn.wnn.weight_model import WNNWeightModel

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from _gradcheck import assert_rows_gradient  # noqa: E402


@pytest.fixture(scope="module")
def student_model():
    rng = np.random.default_rng(0)
    X, y = rng.normal(size=(7, 2)), rng.normal(size=7)
    prior, _ = _weight_prior(X, WNNWeightModel(2, 3, P0=0.1), {"P0": 1.0, "output_scale": 1.0})
    model = _StudentNoise(prior, np.log(0.1), 2.0, 2.0, 0.1)
    return model, X, y, model.sample_prior(5, rng)


def test_student_log_likelihood_is_scipy_t(student_model):
    model, X, y, th = student_model
    f = network.forward(th[:, :-2], X, "morlet")
    want = stats.t.logpdf(y, df=np.exp(th[:, -1])[:, None], loc=f, scale=np.exp(0.5 * th[:, -2])[:, None]).sum(1)
    np.testing.assert_allclose(model.log_likelihood(th, X, y), want, rtol=1e-12)
    np.testing.assert_allclose(model.log_likelihood_and_grad(th, X, y)[0], want, rtol=1e-12)


@pytest.mark.parametrize("part", ["likelihood", "prior"])
def test_student_gradients_match_finite_differences(student_model, part):
    model, X, y, th = student_model
    fn = (lambda t: model.log_likelihood_and_grad(t, X, y)) if part == "likelihood" else model.log_prior_and_grad
    assert_rows_gradient(fn, th)


def test_student_prior_on_log_nu_is_a_gamma_on_nu(student_model):
    model, _, _, th = student_model
    lp = model.log_prior_and_grad(th)[0]
    rest = (model.prior.log_prior_and_grad(th[:, :-2])[0]
            + stats.norm.logpdf(th[:, -2], np.log(0.1), 2.0))
    u = th[:, -1]
    np.testing.assert_allclose(lp - rest, stats.gamma.logpdf(np.exp(u), 2.0, scale=10.0) + u, rtol=1e-12)
    draws = np.exp(model.sample_prior(4000, np.random.default_rng(1))[:, -1])
    assert stats.kstest(draws, stats.gamma(2.0, scale=10.0).cdf).pvalue > 0.01


def test_student_rejects_non_finite_rows(student_model):
    model, X, y, th = student_model
    bad = th[:2].copy()
    bad[1, 0] = np.nan
    bad[0, -1] = 800.0  # nu = exp(800) overflows
    ll, grad = model.log_likelihood_and_grad(bad, X, y)
    assert np.all(ll == -np.inf) and np.all(grad == 0)
    lp, gp = model.log_prior_and_grad(bad)
    assert np.all(lp == -np.inf) and np.all(gp == 0)


def test_one_component_mixture_is_scipy_t():
    loc, s2, nu = np.array([[0.3, -1.0, 2.0]]), np.array([0.04]), np.array([3.5])
    t = StudentTMixture(loc, s2, nu)
    for level in (0.5, 0.9, 0.95):
        lo, hi = t.interval(level)
        want_lo, want_hi = stats.t.interval(level, nu[0], loc=loc[0], scale=0.2)
        np.testing.assert_allclose(lo, want_lo, rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(hi, want_hi, rtol=1e-9, atol=1e-12)
    y = np.array([0.1, -0.5, 5.0])
    np.testing.assert_allclose(t.logpdf(y), stats.t.logpdf(y, nu[0], loc=loc[0], scale=0.2), rtol=1e-12)
    np.testing.assert_allclose(t.var, np.full(3, 0.04 * 3.5 / 1.5))


def test_two_component_mixture_quantiles_and_density_match_sampling():
    loc, s2, nu = np.array([[0.0, 1.0], [2.0, 1.5]]), np.array([0.25, 1.0]), np.array([2.5, 8.0])
    t = StudentTMixture(loc, s2, nu)
    rng = np.random.default_rng(3)
    n = 400_000
    comp = rng.integers(0, 2, size=n)
    draws = loc[comp] + np.sqrt(s2[comp])[:, None] * rng.standard_t(nu[comp])[:, None]
    for level in (0.5, 0.9, 0.95):
        lo, hi = t.interval(level)
        np.testing.assert_allclose(lo, np.quantile(draws, 0.5 - level / 2, axis=0), atol=0.02)
        np.testing.assert_allclose(hi, np.quantile(draws, 0.5 + level / 2, axis=0), atol=0.02)
        np.testing.assert_allclose(t.cdf(hi) - t.cdf(lo), level, atol=1e-9)
    y = np.array([0.7, 3.0])
    dens = 0.5 * sum(stats.t.pdf(y, nu[i], loc=loc[i], scale=np.sqrt(s2[i])) for i in range(2))
    np.testing.assert_allclose(t.logpdf(y), np.log(dens), rtol=1e-12)


def test_mixture_variance_is_inf_below_two_degrees_of_freedom():
    t = StudentTMixture(np.zeros((2, 3)), np.ones(2), np.array([1.5, 30.0]))
    assert np.all(np.isinf(t.var)) and np.all(np.isfinite(t.interval(0.9)[1]))
    with pytest.raises(ValueError, match="scale2 and df must have shape"):
        StudentTMixture(np.zeros((2, 3)), np.ones(3), np.ones(2))
    with pytest.raises(ValueError, match="level must be in"):
        t.interval(1.0)


def test_gaussian_scores_are_the_old_formulas_to_the_digit():
    """The Gaussian rows' coverage and NLPD through the predictive: the formulas the study used before."""
    rng = np.random.default_rng(4)
    mean, std, y = rng.normal(size=200), rng.uniform(0.1, 2.0, size=200), rng.normal(size=200)
    z = np.abs(y - mean) / std
    old = {f"coverage{c}": float(np.mean(z <= q)) for c, q in zip((50, 90, 95), (study.Z50, study.Z90, study.Z95))}
    old["nlpd"] = float(np.mean(0.5 * np.log(2.0 * np.pi * std**2) + 0.5 * z**2))
    assert study.predictive_scores(mean, std, y) == old
    assert study.distribution_scores(GaussianPredictive(mean, std=std), y) == old


def test_regressor_intervals_of_a_gaussian_row_are_mean_pm_z_std():
    X, y, X_test, y_test = make_siso_benchmark(rng=2)
    reg = WNNRegressor(trainer="ekf", n_epochs=2, random_state=0).fit(X, y)
    mean, std = reg.predict(X_test, return_std=True)
    lo, hi = reg.predict_interval(X_test, level=0.9)
    np.testing.assert_array_equal(lo, mean - study.Z90 * std)
    np.testing.assert_array_equal(hi, mean + study.Z90 * std)
    np.testing.assert_allclose(reg.predict_log_density(X_test, y_test), stats.norm.logpdf(y_test, mean, std))
    assert study.distribution_scores(reg.predictive(X_test), y_test) == study.predictive_scores(mean, std, y_test)
    with pytest.raises(ValueError, match="one target per row"):
        reg.predict_log_density(X_test, y_test[:3])


def test_student_row_predicts_with_its_mixture():
    X, y, X_test, y_test = make_siso_benchmark(rng=1)
    reg = WNNRegressor(trainer="smc-student-10x10", n_hidden=2, n_particles=6, n_epochs=1,
                       random_state=0).fit(X[:30], y[:30])
    tr = reg._final
    assert tr.particles.shape[1] == reg.theta_.size + 2 and np.all(tr.noise > 0) and np.all(tr.df > 0)
    dist = reg.predictive(X_test)
    assert isinstance(dist, StudentTMixture)
    Y = np.stack([network.forward(p, X_test, "morlet") for p in tr.particles[:, :-2]])
    np.testing.assert_allclose(dist.mean, Y.mean(axis=0))
    np.testing.assert_allclose(dist.loc, Y)
    lo, hi = reg.predict_interval(X_test, 0.9)
    np.testing.assert_allclose(dist.cdf(hi) - dist.cdf(lo), 0.9, atol=1e-9)
    mean, std = reg.predict(X_test, return_std=True)
    np.testing.assert_allclose(mean, dist.mean)
    want = Y.var(axis=0) + np.mean(np.where(tr.df > 2, tr.noise * tr.df / (tr.df - 2), np.inf))
    np.testing.assert_allclose(std**2, want)
    assert reg.diagnostics_["noise_df"][-1] == pytest.approx(np.median(tr.df))


def test_student_row_is_smc_noise_10x10_with_a_t_likelihood():
    """Its name promises smc-noise-10x10's sampler and a Student-t likelihood: only the nu prior is added."""
    X, y, _, _ = make_siso_benchmark(rng=1)
    kw = dict(n_hidden=2, n_particles=6, n_epochs=1, random_state=0)
    t = WNNRegressor(trainer="smc-student-10x10", **kw).fit(X[:30], y[:30])
    base = WNNRegressor(trainer="smc-noise-10x10", **kw).fit(X[:30], y[:30])
    assert {k: v for k, v in t.settings_.items() if base.settings_.get(k) != v} == {
        "df_prior_shape": 2.0, "df_prior_rate": 0.1, "trainer": "smc-student-10x10"}
    assert (t._final.move.n_steps, t._final.move.n_leapfrog) == (10, 10)
    assert "smc-student-10x10" not in study.ALL_TRAINERS and "smc-student-10x10" in study.ROWS


def test_student_row_runs_in_the_study_at_the_tiny_size():
    res = study.run_study(n_runs=1, n_epochs=1, pf_epochs=1, n_particles=4, seed=3, paper_table=False,
                          references=(), sweep_particles=(), tune_runs=0, trainers=["smc-student-10x10"])
    (run,) = res.runs
    assert run["status"] == "ok" and 0 <= run["coverage90"] <= 1 and np.isfinite(run["nlpd"])
    assert run["noise_scale2"] > 0 and run["noise_df"] > 0
    assert "Student-t likelihood" in run["settings"] and "Gamma(2, rate 0.1)" in run["settings"]
