"""Tests of filterwnn.wnn.regressor: trainer registry and the WNNRegressor estimator."""

import copy
import pickle

import numpy as np
import pytest
from sklearn.base import clone
from sklearn.model_selection import GridSearchCV

from filterwnn import NumericalError, wnn
from filterwnn.datasets import make_siso_benchmark
from filterwnn.wnn.regressor import TRAINERS, WNNRegressor, make_trainer
from filterwnn.wnn.weight_model import WNNWeightModel

SINGLE = ["bp", "ekf", "ukf", "sukf"]
PARTICLE = ["spf", "epf", "upf", "supf"]
GAUSSIAN_SUM = ["gsf-ekf", "gsf-ukf", "gsf-sukf", "ekf-ensemble"]


@pytest.fixture(scope="module")
def data():
    X, y, X_test, y_test = make_siso_benchmark(rng=0)
    return X[:40], y[:40], X_test, y_test


def _mse_start(reg, X, y):
    """Training MSE of the estimator's own start (same rng, zero epochs of training)."""
    rng = np.random.default_rng(reg.random_state)
    theta0 = wnn.init_scaled(X, reg.n_hidden, rng=rng)
    return np.mean((wnn.forward(theta0, X) - y) ** 2)


@pytest.mark.parametrize("trainer", SINGLE)
def test_single_filter_trainers_lower_training_mse(data, trainer):
    X, y, _, _ = data
    reg = WNNRegressor(n_hidden=4, trainer=trainer, n_epochs=3, random_state=0).fit(X, y)
    factor = 0.9 if trainer == "bp" else 0.5  # plain gradient descent is slow from a small start
    assert reg.loss_curve_[-1] < factor * _mse_start(reg, X, y)


def test_particle_trainers_lower_training_mse(data):
    pytest.importorskip("filterwnn.monte_carlo.particle_filter")
    X, y, _, _ = data
    gen = np.random.default_rng(0)  # the estimator's own starts: one scaled draw per particle
    starts = np.stack([wnn.init_scaled(X, 3, rng=gen) for _ in range(5)])
    start = np.mean((wnn.forward(starts, X).mean(axis=0) - y) ** 2)
    for trainer in PARTICLE:
        reg = WNNRegressor(n_hidden=3, trainer=trainer, n_epochs=2, n_particles=5, random_state=0).fit(X, y)
        assert reg.loss_curve_[-1] < start, trainer
        assert len(reg.diagnostics_["mean_ess"]) == 2


def test_fit_returns_self_and_attributes(data):
    X, y, X_test, _ = data
    reg = WNNRegressor(n_hidden=4, n_epochs=3, random_state=0)
    assert reg.fit(X, y) is reg
    assert reg.theta_.shape == (wnn.n_params(5, 4),)
    assert len(reg.loss_curve_) == 3 and reg.n_iter_ == 3
    assert reg.n_features_in_ == 5
    assert reg.fit_time_ > 0
    mean, std = reg.predict(X_test, return_std=True)
    assert mean.shape == std.shape == (100,)
    assert np.all(std >= np.sqrt(0.1))  # R = 0.1 is part of the predictive variance
    np.testing.assert_allclose(reg.predict(X_test), wnn.forward(reg.theta_, X_test))


def test_same_seed_same_theta_and_clone(data):
    X, y, _, _ = data
    a = WNNRegressor(n_hidden=4, n_epochs=2, random_state=3).fit(X, y)
    b = clone(a).fit(X, y)
    np.testing.assert_array_equal(a.theta_, b.theta_)
    c = WNNRegressor(n_hidden=4, n_epochs=2, random_state=4).fit(X, y)
    assert not np.array_equal(a.theta_, c.theta_)
    assert clone(a).get_params() == a.get_params()


def test_grid_search(data):
    X, y, _, _ = data
    gs = GridSearchCV(
        WNNRegressor(n_hidden=3, n_epochs=2, random_state=0), {"process_noise": [1e-4, 1e-3]}, cv=2
    ).fit(X, y)
    assert gs.best_params_["process_noise"] in (1e-4, 1e-3)


def test_unknown_trainer_lists_valid_names(data):
    X, y, _, _ = data
    with pytest.raises(ValueError, match="valid: 'bp', 'ekf', 'ekf-ensemble', 'epf', 'gsf-ekf', 'gsf-sukf', "
                       "'gsf-ukf', 'smc', 'smc-noise', 'smc-noise-10x10', 'smc-student-10x10', 'spf', 'sukf', 'supf', 'ukf', 'upf'"):
        WNNRegressor(trainer="lbfgs").fit(X, y)
    with pytest.raises(ValueError, match="trainer"):
        make_trainer("nope", None, None, {})
    assert set(TRAINERS) == set(SINGLE + PARTICLE + GAUSSIAN_SUM + ["smc", "smc-noise", "smc-noise-10x10", "smc-student-10x10"])  # smc-noise: test_trainers.py


def test_gaussian_sum_trainers_lower_training_mse_and_are_gaussian_sum_filters(data):
    from filterwnn.monte_carlo.gaussian_sum import GaussianSumFilter

    X, y, _, _ = data
    gen = np.random.default_rng(0)
    starts = np.stack([wnn.init_scaled(X, 3, rng=gen) for _ in range(5)])
    start = np.mean((wnn.forward(starts, X).mean(axis=0) - y) ** 2)
    for trainer in GAUSSIAN_SUM:
        reg = WNNRegressor(n_hidden=3, trainer=trainer, n_epochs=2, n_particles=5, random_state=0).fit(X, y)
        assert isinstance(reg._trainer.pf, GaussianSumFilter), trainer
        assert reg.settings_["tempering"] == 1.0
        assert reg.settings_["weighting"] == ("unweighted average" if trainer == "ekf-ensemble" else "gaussian-sum")
        assert reg._trainer.pf.combine == ("mean" if trainer == "ekf-ensemble" else "mixture")
        assert reg.loss_curve_[-1] < start, trainer
    reg = WNNRegressor(n_hidden=3, trainer="gsf-ukf", n_epochs=1, n_particles=5, tempering=0.01, random_state=0)
    assert reg.fit(X, y)._trainer.pf.tempering == 0.01


def test_ekf_ensemble_is_the_plain_average_of_standalone_ekf_fits(data):
    X, y, X_test, _ = data
    reg = WNNRegressor(n_hidden=3, trainer="ekf-ensemble", n_epochs=2, n_particles=4, random_state=0).fit(X, y)
    gen = np.random.default_rng(0)  # the estimator's starts: one scaled draw per member
    starts = [wnn.init_scaled(X, 3, rng=gen) for _ in range(4)]
    model = WNNWeightModel(5, 3, Q=reg.settings_["Q"], R=0.1, P0=reg.settings_["P0"])
    preds = []
    for theta0 in starts:
        tr = make_trainer("ekf", model, theta0, dict(reg.settings_, ekf_backend="rank1"), rng=0)
        tr.epoch(X, y)
        tr.epoch(X, y)
        preds.append(tr.predict_mean(X_test))
    # same equations, other arithmetic (GaussianSumFilter's EKF step vs the rank-1 EKF): rounding only
    np.testing.assert_allclose(reg.predict(X_test), np.mean(preds, axis=0), rtol=0, atol=1e-5)
    # the weights would differ: the ensemble ignores them
    assert not np.allclose(reg._trainer.pf.weights, 0.25)


@pytest.mark.parametrize("move", ["mala", "hmc"])
def test_particle_trainer_with_a_move_targets_the_rows_seen(data, move):
    X, y, X_test, y_test = data
    reg = WNNRegressor(n_hidden=3, trainer="spf", move=move, n_epochs=1, n_particles=8, random_state=0).fit(X, y)
    tr = reg._trainer
    assert tr.pf.move is tr.move and tr.move.target.n_rows == len(X)  # every row, added before its update
    assert np.all(tr.pf.Q == 0) and reg.settings_["Q"] == 0.0 and reg.settings_["move"] == move
    assert 0 < reg.diagnostics_["acceptance"][-1] < 1  # the move ran and moved
    assert reg.diagnostics_["distinct"][-1] > 1  # moved particles are distinct after resampling
    mean, std = reg.predict(X_test, return_std=True)
    assert np.all(np.isfinite(mean)) and np.all(std > 0)
    # IBIS's predictive: the cloud's weighted spread plus R (no Kalman covariance in the particles)
    from filterwnn.wnn import network

    Y, w = network.forward(tr.particles, X_test, "morlet"), tr.weights
    np.testing.assert_allclose(std**2, w @ (Y - w @ Y) ** 2 + reg.settings_["R"])


def test_move_and_weighting_errors(data):
    X, y, _, _ = data
    with pytest.raises(ValueError, match="move is for the particle-filter trainers"):
        WNNRegressor(trainer="ekf", move="mala").fit(X, y)
    with pytest.raises(ValueError, match="process_noise must be 0"):
        WNNRegressor(trainer="spf", move="mala", process_noise=1e-4).fit(X, y)
    for kalman in ("epf", "upf", "supf"):  # at Q = 0 the Kalman proposal never moves a particle: IBIS
        with pytest.raises(ValueError, match=rf"trainer='{kalman}'.*IBIS.*use trainer='spf' with move='hmc'"):
            WNNRegressor(trainer=kalman, move="hmc").fit(X, y)
    with pytest.raises(ValueError, match="unknown move 'gibbs'"):
        WNNRegressor(trainer="upf", move="gibbs").fit(X, y)
    with pytest.raises(TypeError, match="unexpected keyword argument 'weighting'"):  # removed: use gsf-*
        WNNRegressor(trainer="epf", weighting="bank")


def test_bad_arguments(data):
    X, y, _, _ = data
    with pytest.raises(ValueError, match="n_hidden"):
        WNNRegressor(n_hidden=0).fit(X, y)
    with pytest.raises(ValueError, match="validation_fraction"):
        WNNRegressor(early_stopping=True, validation_fraction=1.5).fit(X, y)
    with pytest.raises(ValueError, match="init"):
        WNNRegressor(init="zeros").fit(X, y)


def test_rank1_ekf_equals_filterpy(data):
    X, y, _, _ = data
    a = WNNRegressor(n_hidden=3, n_epochs=2, random_state=1).fit(X, y)
    b = WNNRegressor(n_hidden=3, n_epochs=2, random_state=1, ekf_backend="filterpy").fit(X, y)
    np.testing.assert_allclose(a.theta_, b.theta_, rtol=1e-5, atol=1e-8)
    np.testing.assert_allclose(a._final.cov, b._final.cov, rtol=1e-5, atol=1e-8)


def test_early_stopping_keeps_best_epoch(data):
    X, y, _, _ = data
    reg = WNNRegressor(n_hidden=4, n_epochs=15, early_stopping=True, n_iter_no_change=3, random_state=0).fit(X, y)
    assert len(reg.validation_scores_) == reg.n_iter_ <= 15
    assert reg.validation_scores_[reg.best_epoch_ - 1] == min(reg.validation_scores_)


def test_warm_start_and_partial_fit_resume(data):
    X, y, _, _ = data
    full = WNNRegressor(n_hidden=3, n_epochs=4, random_state=2).fit(X, y)
    half = WNNRegressor(n_hidden=3, n_epochs=2, random_state=2, warm_start=True).fit(X, y)
    resumed = pickle.loads(pickle.dumps(half)).fit(X, y)  # checkpoint, then two more epochs
    np.testing.assert_allclose(resumed.theta_, full.theta_, rtol=1e-12)
    assert resumed.n_iter_ == 4
    step = WNNRegressor(n_hidden=3, random_state=2)
    for _ in range(4):
        step.partial_fit(X, y)
    np.testing.assert_allclose(step.theta_, full.theta_, rtol=1e-12)
    np.testing.assert_allclose(step.loss_curve_, full.loss_curve_, rtol=1e-12)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_non_finite_weights_raise_numerical_error(data):
    X, y, _, _ = data
    with pytest.raises(NumericalError, match="non-finite"):
        WNNRegressor(trainer="bp", learning_rate=1e200, n_hidden=3, n_epochs=2, random_state=0).fit(X, y * 1e200)


def test_paper_init_and_mexican_hat(data):
    X, y, _, _ = data
    reg = WNNRegressor(n_hidden=4, init="paper", wavelet="mexican_hat", n_epochs=2, random_state=0).fit(X, y)
    assert reg.settings_["Q"] == 1e-2 and reg.settings_["P0"] == 0.01
    assert np.all(np.isfinite(reg.theta_))


def test_make_trainer_runs_on_a_model():
    model = WNNWeightModel(2, 2, Q=1e-4, R=0.1, P0=0.1)
    X = np.linspace(-1, 1, 20)[:, None] * [1.0, -1.0]
    tr = make_trainer("ekf", model, wnn.init_scaled(X, 2, rng=0), {"ekf_backend": "rank1"}, rng=0)
    tr.epoch(X, np.sin(X[:, 0]))
    assert tr.theta.shape == (10,)


def test_random_state_is_the_seed_scikit_learn_sets(data):
    from sklearn.utils._testing import set_random_state

    X, y, _, _ = data
    params = WNNRegressor().get_params()
    assert "random_state" in params and "rng" not in params and "progress" not in params
    reg = WNNRegressor(n_hidden=3, n_epochs=1)
    set_random_state(reg, 7)  # what check_estimator does
    assert reg.random_state == 7
    a = reg.fit(X, y).theta_.copy()
    np.testing.assert_array_equal(a, WNNRegressor(n_hidden=3, n_epochs=1, random_state=7).fit(X, y).theta_)
    with pytest.raises(TypeError, match="random_state must be None, an int seed"):
        WNNRegressor(random_state=np.random.RandomState(0)).fit(X, y)


def test_verbose_levels(data, capsys):
    X, y, _, _ = data
    WNNRegressor(n_hidden=3, n_epochs=2, random_state=0).fit(X, y)
    assert capsys.readouterr().out == ""
    reg = WNNRegressor(n_hidden=3, n_epochs=2, random_state=0, verbose=2, early_stopping=True).fit(X, y)
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 2
    assert lines[1] == (f"iteration 2: training MSE {reg.loss_curve_[1]:.6g}, "
                        f"validation MSE {reg.validation_scores_[1]:.6g}")
    WNNRegressor(n_hidden=3, n_epochs=2, random_state=0, verbose=True).fit(X, y)  # a bar, no lines
    out = capsys.readouterr()
    assert out.out == "" and "WNN/ekf" in out.err
    reg.partial_fit(X[:5], y[:5])  # no bar for one pass, the line still
    assert capsys.readouterr().out == f"iteration 3: training MSE {reg.loss_curve_[2]:.6g}\n"


# ---------------------------------------------------------------------------- online training
CHUNKS = [7, 20, 21]  # 40 rows as 7, 13, 1 and 19


def _online(reg, X, y, cuts=CHUNKS):
    for rows in np.split(np.arange(len(X)), cuts):
        reg.partial_fit(X[rows], y[rows])
    return reg


@pytest.mark.parametrize("trainer, extra", [(t, {}) for t in SINGLE + PARTICLE + GAUSSIAN_SUM]
                         + [("ekf", {"ekf_backend": "filterpy"})])
def test_partial_fit_in_chunks_equals_one_pass_bit_for_bit(data, trainer, extra):
    X, y, X_test, _ = data
    kw = dict(trainer=trainer, n_hidden=3, n_particles=5, init="paper", random_state=0, **extra)
    whole = WNNRegressor(**kw).partial_fit(X, y)
    chunked = _online(WNNRegressor(**kw), X, y)
    np.testing.assert_array_equal(chunked.theta_, whole.theta_)
    mean_w, std_w = whole.predict(X_test, return_std=True)
    mean_c, std_c = chunked.predict(X_test, return_std=True)
    np.testing.assert_array_equal(mean_c, mean_w)
    if trainer != "bp":  # bp's std is the RMSE of the last call's rows
        np.testing.assert_array_equal(std_c, std_w)  # the covariance (or particle bank) too
    assert (whole.n_iter_, whole.t_) == (1, 40)
    assert (chunked.n_iter_, chunked.t_, len(chunked.loss_curve_)) == (4, 40, 4)


def test_partial_fit_learns_from_every_chunk(data):
    """The issue's symptom: 5 disjoint chunks gave the weights of 5 epochs on the first."""
    X, y, _, _ = data
    kw = dict(n_hidden=3, init="paper", random_state=0)
    online = _online(WNNRegressor(**kw), X, y, cuts=[8, 16, 24, 32])
    first_chunk = WNNRegressor(n_epochs=5, **kw).fit(X[:8], y[:8])
    assert not np.allclose(online.theta_, first_chunk.theta_)
    np.testing.assert_array_equal(online.theta_, WNNRegressor(**kw).partial_fit(X, y).theta_)


def test_partial_fit_loss_curve_is_the_mse_on_the_rows_of_each_call(data):
    X, y, _, _ = data
    reg = WNNRegressor(n_hidden=3, random_state=0).partial_fit(X[:10], y[:10])
    assert reg.loss_curve_[-1] == pytest.approx(np.mean((reg.predict(X[:10]) - y[:10]) ** 2), rel=1e-12)
    t0 = reg.fit_time_
    reg.partial_fit(X[10:], y[10:])
    assert reg.loss_curve_[-1] == pytest.approx(np.mean((reg.predict(X[10:]) - y[10:]) ** 2), rel=1e-12)
    assert reg.fit_time_ > t0 and reg.best_epoch_ == reg.n_iter_ == 2


def test_repeated_partial_fit_on_all_rows_equals_fit_epochs(data):
    X, y, _, _ = data
    full = WNNRegressor(n_hidden=3, n_epochs=3, random_state=2).fit(X, y)
    step = WNNRegressor(n_hidden=3, random_state=2)
    for _ in range(3):
        step.partial_fit(X, y)
    np.testing.assert_array_equal(step.theta_, full.theta_)
    np.testing.assert_array_equal(step._final.cov, full._final.cov)
    assert step.loss_curve_ == full.loss_curve_


def test_partial_fit_after_fit_continues_from_the_kept_weights(data):
    X, y, _, _ = data
    reg = WNNRegressor(n_hidden=3, n_epochs=8, early_stopping=True, n_iter_no_change=2, random_state=0).fit(X, y)
    assert reg.best_epoch_ < reg.n_iter_  # early stopping kept an earlier epoch's weights
    kept = copy.deepcopy(reg._final)
    kept.epoch(X[:5], y[:5])
    reg.partial_fit(X[:5], y[:5])
    np.testing.assert_array_equal(reg.theta_, kept.theta)
    assert reg.best_epoch_ == reg.n_iter_ == len(reg.loss_curve_)


def test_warm_start_fit_trains_on_the_rows_it_is_given(data):
    X, y, _, _ = data
    reg = WNNRegressor(n_hidden=3, n_epochs=2, warm_start=True, random_state=0).fit(X[:20], y[:20])
    other = pickle.loads(pickle.dumps(reg)).fit(X[20:], y[20:])
    same = pickle.loads(pickle.dumps(reg)).fit(X[:20], y[:20])
    assert not np.allclose(other.theta_, same.theta_)
    assert other.t_ == same.t_ == 80


def test_particle_trainer_with_a_move_resumes_from_a_pickle_exactly(data):
    X, y, X_test, _ = data
    kw = dict(trainer="spf", move="mala", n_hidden=2, n_particles=4, random_state=3)
    full = WNNRegressor(n_epochs=2, **kw).fit(X, y)
    part = WNNRegressor(n_epochs=1, warm_start=True, **kw).fit(X, y)
    resumed = pickle.loads(pickle.dumps(part)).fit(X, y)
    np.testing.assert_array_equal(resumed.predict(X_test), full.predict(X_test))
    assert resumed._trainer.move.target.n_rows == 2 * len(X)  # each pass counts the rows once more


@pytest.mark.parametrize("trainer", ["ekf", "ukf"])
def test_anneal_brings_q_to_zero_and_shrinks_the_weight_covariance(data, trainer):
    X, y, X_test, _ = data
    reg = WNNRegressor(trainer=trainer, n_hidden=2, n_epochs=3, process_noise=1e-2, random_state=0).fit(X, y)
    before = reg.predict(X_test, return_std=True)[1]
    n_iter = reg.n_iter_
    assert reg.anneal(X, y, n_epochs=3) is reg and reg.n_iter_ == n_iter + 3
    tr = reg._final
    Q = tr._Q if trainer == "ekf" else tr.kf.Q
    assert np.all(Q == 0)  # the last pass ran at Q = 0
    after = reg.predict(X_test, return_std=True)[1]
    assert np.median(after) < np.median(before)  # no more accumulated Q in P
    with pytest.raises(ValueError, match="anneal is for the Kalman trainers.*got trainer='spf'"):
        WNNRegressor(trainer="spf", n_hidden=2, n_particles=3, n_epochs=1, random_state=0).fit(X, y).anneal(X, y)
