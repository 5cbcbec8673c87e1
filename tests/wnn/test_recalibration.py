"""The split-conformal width factor of a Gaussian predictive (filterwnn.wnn.predictive) and the
study's recalibrated row (protocol 6)."""

import numpy as np
import pytest
from scipy.special import ndtri

from filterwnn.studies import wnn as study
from filterwnn.wnn.predictive import GaussianPredictive, StudentTMixture, conformal_factor, recalibrate


LEVELS = np.linspace(0.05, 0.95, 19)


def test_the_conformal_quantile_is_monotone_in_the_level():
    r = np.random.default_rng(0).standard_t(3, size=200)
    q = [conformal_factor(r, a) * ndtri(0.5 + 0.5 * a) for a in LEVELS]   # s_(k(level))
    assert np.all(np.diff(q) >= 0)


def test_recalibration_is_a_monotone_map_of_the_half_widths():
    g = GaussianPredictive(np.zeros(5), std=np.array([0.1, 0.5, 1.0, 2.0, 4.0]))
    half = recalibrate(g, 0.6).interval(0.9)[1]
    assert np.all(np.diff(half) > 0)
    np.testing.assert_allclose(half, 0.6 * g.interval(0.9)[1])


def test_the_factor_is_one_on_a_calibrated_gaussian_sample():
    """n = 10 000 draws of N(0, 1): the 90 % quantile of |z| has standard deviation
    sqrt(0.9 * 0.1 / n) / (2 phi(1.645)) = 0.0145, the factor 0.0145 / 1.645 = 0.0088; 4 of them."""
    r = np.random.default_rng(1).standard_normal(10_000)
    assert conformal_factor(r, 0.9) == pytest.approx(1.0, abs=4 * 0.0088)
    g = GaussianPredictive(np.zeros(3), np.ones(3))
    np.testing.assert_allclose(recalibrate(g, 1.0).interval(0.9), g.interval(0.9))


@pytest.mark.parametrize("width", [1.7, 0.5])
def test_coverage_comes_out_at_the_level_on_a_miscalibrated_example(width):
    """A predictive ``width`` times too wide (or narrow), its factor fitted on 1000 calibration rows,
    scored on 10 000 new rows. Given the calibration rows the coverage is Beta(k, n + 1 - k)
    (sd sqrt(0.9 * 0.1 / 1002) = 0.0095), the test rows add a binomial's sd sqrt(0.09 / 10 000) = 0.003:
    in all 0.010; tolerance 4 of them around 0.9 (the mean lies in [0.9, 0.9 + 1/1001])."""
    rng = np.random.default_rng(2)
    m_cal, m_test = rng.normal(size=1000), rng.normal(size=10_000)
    y_cal, y_test = m_cal + 0.3 * rng.normal(size=1000), m_test + 0.3 * rng.normal(size=10_000)
    c = conformal_factor((y_cal - m_cal) / (width * 0.3), 0.9)
    assert c == pytest.approx(1 / width, rel=0.1)
    g = recalibrate(GaussianPredictive(m_test, std=np.full(10_000, width * 0.3)), c)
    assert np.mean(g.covers(y_test, 0.9)) == pytest.approx(0.9, abs=4 * 0.010)
    assert abs(np.mean(GaussianPredictive(m_test, std=np.full(10_000, width * 0.3)).covers(y_test, 0.9)) - 0.9) > 0.05


def test_errors_name_the_argument():
    with pytest.raises(ValueError, match="residuals must be"):
        conformal_factor([], 0.9)
    with pytest.raises(ValueError, match="residuals must be"):
        conformal_factor([1.0, np.nan], 0.9)
    with pytest.raises(ValueError, match="level must be"):
        conformal_factor([1.0], 1.0)
    with pytest.raises(ValueError, match="factor must be positive"):
        recalibrate(GaussianPredictive(np.zeros(1), np.ones(1)), np.inf)
    with pytest.raises(ValueError, match="dist must be a GaussianPredictive"):
        recalibrate(StudentTMixture(np.zeros((1, 1)), np.ones(1), np.ones(1)), 1.0)
    assert conformal_factor(np.ones(5), 0.95) == np.inf   # k = ceil(6 * 0.95) = 6 > 5


def test_recal_row_is_smc_noise_10x10_with_its_intervals_rescaled():
    """The same fits as smc-noise-10x10 (its test MSE to the digit), the factor fitted on the tuning
    runs' validation split, the unrecalibrated scores kept as *_base."""
    kw = dict(n_runs=1, n_epochs=1, pf_epochs=1, n_particles=4, seed=3, paper_table=False,
              references=(), sweep_particles=(), tune_runs=1)
    res = study.run_study(trainers=["smc-noise-10x10-recal", "smc-noise-10x10"], **kw)
    recal, base = (next(r for r in res.runs if r["trainer"] == t) for t in ("smc-noise-10x10-recal", "smc-noise-10x10"))
    assert recal["test_mse"] == base["test_mse"]
    cal = res.config["calibration"]["smc-noise-10x10-recal"]
    assert cal["n_residuals"] == 20 and cal["level"] == 0.9
    assert recal["recal_factor"] == cal["factor"]
    assert recal["coverage90_base"] == base["coverage90"] and recal["nlpd_base"] == base["nlpd"]
    assert "smc-noise-10x10-recal" not in study.ALL_TRAINERS
    assert "recalibrated on the tuning runs' validation split" in study.row_label("smc-noise-10x10-recal", 60)


def test_recal_row_refuses_a_study_without_tuning_runs():
    with pytest.raises(ValueError, match="tune_runs must be >= 1"):
        study.run_study(n_runs=1, n_epochs=1, n_particles=4, paper_table=False, references=(), sweep_particles=(),
                        tune_runs=0, trainers=["smc-noise-10x10-recal"])
