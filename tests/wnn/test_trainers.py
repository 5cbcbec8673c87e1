"""Tests of filterwnn.wnn.trainers: the trainer table, registration, and a toy trainer run end to end."""

import os
import sys

import numpy as np
import pytest

from filterwnn import WNNRegressor
from filterwnn.wnn import regressor
from filterwnn.datasets import make_siso_benchmark
from filterwnn.studies import wnn as study
from filterwnn.wnn.trainers import (
    AUTO_SETTINGS,
    TRAINERS,
    BaseTrainer,
    TrainerSpec,
    make_trainer,
    register_trainer,
    unregister_trainer,
)

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from _gradcheck import assert_rows_gradient  # noqa: E402


class MeanTrainer(BaseTrainer):
    """The toy: predicts the mean of the rows it trained on (no filter at all)."""

    def __init__(self, model, theta0, settings, rng, spec=None):
        super().__init__(model, theta0, settings, rng, spec)
        self.x = np.array(theta0, dtype=float)
        self.mean, self.var = 0.0, 1.0

    @property
    def theta(self):
        return self.x

    def epoch(self, X, y):
        self.mean = float(np.mean(y))
        self.var = float(np.var(y)) + float(self.model.R[0, 0])
        self._record("n_rows", len(y))

    def predict(self, X):
        return np.full(len(X), self.mean), np.full(len(X), self.var)


AUTO = {"Q": 0.0, "P0": 1.0}
TOY = TrainerSpec("toy", MeanTrainer, "single", {"scaled": AUTO, "paper": AUTO}, doc="predicts the training mean")


@pytest.fixture
def toy(monkeypatch):
    """The toy trainer, registered in this one place for one test and removed after it, with its
    study row (label, and a place in the paper-settings table) in the study's own table."""
    monkeypatch.setitem(study.STUDY, "toy", study.StudyEntry(label="mean predictor", paper_settings={}))
    spec = register_trainer(TOY)
    try:
        yield spec
    finally:
        unregister_trainer(TOY.name)


def test_a_registered_trainer_runs_in_the_estimator_and_the_study(toy):
    X, y, X_test, _ = make_siso_benchmark(rng=0)
    reg = WNNRegressor(trainer="toy", n_hidden=2, n_epochs=2, random_state=0).fit(X, y)
    np.testing.assert_allclose(reg.predict(X_test), np.mean(y))
    assert reg.n_iter_ == 2 and reg.diagnostics_ == {"n_rows": [100, 100]}
    assert reg.settings_["Q"] == 0.0 and reg.settings_["trainer"] == "toy"
    with pytest.raises(ValueError, match=r"valid: 'bp', .*'toy', 'ukf', 'upf'"):
        WNNRegressor(trainer="nope").fit(X, y)
    with pytest.raises(ValueError, match=r"move is for the particle-filter trainers \('spf', 'epf', 'upf', 'supf'\)"):
        WNNRegressor(trainer="toy", move="mala").fit(X, y)

    res = study.run_study(trainers=["toy"], n_runs=1, n_epochs=2, pf_epochs=1, n_particles=2, seed=1,
                          references=(), sweep_particles=(), tune_runs=1, paper_runs=1)
    assert [(r["table"], r["algorithm"]) for r in res.table] == [("working", "mean predictor"),
                                                                ("paper", "mean predictor")]
    assert res.tuning == [] and all(r["status"] == "ok" for r in res.runs)  # no grid, no parent: not searched
    assert res.table[0]["test_mse_median"] == pytest.approx(res.runs[0]["var_test"], rel=0.5)
    assert study.candidates("toy") == [{}] and study.row_label("toy", 3) == "mean predictor"


def test_registering_and_removing_leaves_the_table_as_it_was():
    before = (list(TRAINERS), dict(AUTO_SETTINGS), list(study._rows()))
    register_trainer(TOY)
    try:
        assert "toy" in TRAINERS and AUTO_SETTINGS[("toy", "paper")] is AUTO and "toy" in study._rows()
    finally:
        assert unregister_trainer("toy") is TOY
    assert (list(TRAINERS), dict(AUTO_SETTINGS), list(study._rows())) == before
    assert "toy" not in study.ALL_TRAINERS  # the module's names are computed at import


def test_register_refuses_duplicates_and_bad_entries():
    ekf = TRAINERS["ekf"]
    with pytest.raises(ValueError, match="trainer 'ekf' is already registered; pass replace=True"):
        register_trainer(ekf)
    names = list(TRAINERS)
    assert register_trainer(ekf, replace=True) is ekf and list(TRAINERS) == names  # same place in the table
    with pytest.raises(TypeError, match="spec must be a TrainerSpec, got dict"):
        register_trainer({"name": "x"})
    bad = [
        (dict(family="adam"), r"unknown family 'adam'; valid: 'gaussian-sum', 'gradient', 'particle'"),
        (dict(auto={"scaled": {"Q": 1.0}, "paper": AUTO}), r"auto\['scaled'\] of trainer 'x' must set \['P0'\]"),
        (dict(family="gradient"), r"auto\['scaled'\] of trainer 'x' must set \['learning_rate'\]"),
        (dict(family="particle"), "a particle trainer needs its filter class"),
        (dict(name="x+y"), "name must be a non-empty string without '\\+', got 'x\\+y'"),
    ]
    for change, match in bad:
        kw = {**dict(name="x", trainer=MeanTrainer, family="single", auto={"scaled": AUTO, "paper": AUTO}), **change}
        with pytest.raises(ValueError, match=match):
            register_trainer(TrainerSpec(**kw))
    assert list(TRAINERS) == names
    with pytest.raises(ValueError, match="unknown trainer 'toy'"):
        unregister_trainer("toy")


def test_the_table_is_what_the_estimator_and_the_study_read():
    assert regressor.TRAINERS is TRAINERS and regressor.AUTO_SETTINGS is AUTO_SETTINGS
    assert regressor.make_trainer is make_trainer
    for name, spec in TRAINERS.items():
        assert spec.name == name
        assert AUTO_SETTINGS[(name, "scaled")] is spec.auto["scaled"]
        if spec.family in ("particle", "gaussian-sum"):
            assert spec.filter is not None, name
    # the study's data live in the study's table, keyed by row; a spec says only how to train
    assert study.PAPER_TABLE1 == {n: e.paper for n, e in study.STUDY.items() if e.paper}
    assert study.PROPOSAL_PARENT == {n: e.parent for n, e in study.STUDY.items() if e.parent}
    assert set(study.TUNING_GRID) == {n for n, e in study.STUDY.items() if e.grid}
    assert study._cost()["upf"] == study.STUDY["upf"].cost
    for gone in ("grid", "parent", "copy_settings", "cost", "paper", "paper_settings", "label", "study",
                 "study_epochs"):
        assert not hasattr(TRAINERS["upf"], gone), gone
    # one class per way of training, no class that only names a trainer
    assert len({s.trainer for s in TRAINERS.values()}) == 8  # smc-student-10x10: another likelihood, its own class


def test_each_particle_trainer_builds_its_entrys_filter_and_points():
    from filterwnn.wnn.weight_model import WNNWeightModel

    X, y, _, _ = make_siso_benchmark(rng=0)
    model = WNNWeightModel(5, 2, Q=1e-4, R=0.1, P0=0.01)
    settings = {"n_particles": 3, "ess_threshold": 0.5, "tempering": 1.0, "move": None}
    for name in ("spf", "epf", "upf", "supf"):
        spec = TRAINERS[name]
        tr = make_trainer(name, model, np.zeros((3, model.dim_x)), settings, rng=0)
        assert type(tr.pf) is spec.filter and tr.name == name
        if spec.points is not None:
            assert type(tr.pf.proposal.points) is type(spec.points(model.dim_x)), name


def test_smc_noise_target_gradients_and_its_fixed_noise_special_case():
    """s = log R joins the weights: the gradients match finite differences, and at s = log R the
    likelihood is the weight model's."""
    from filterwnn.wnn.trainers import _LearnedNoise
    from filterwnn.wnn.weight_model import WNNWeightModel

    X, y, _, _ = make_siso_benchmark(rng=0)
    X, y = X[:15], y[:15]
    model = WNNWeightModel(5, 2, Q=0.0, R=0.1, P0=0.5)
    target = _LearnedNoise(model, np.log(0.1), 2.0)
    th = np.random.default_rng(0).normal(size=(3, target.dim_x)) * 0.5
    for fn in (lambda t: target.log_likelihood_and_grad(t, X, y), target.log_prior_and_grad):
        assert_rows_gradient(fn, th)
    th[:, -1] = np.log(0.1)
    np.testing.assert_allclose(target.log_likelihood(th, X, y), model.log_likelihood(th[:, :-1], X, y))


def test_smc_noise_learns_r_and_predicts_with_it():
    X, y, X_test, _ = make_siso_benchmark(rng=1)
    reg = WNNRegressor(trainer="smc-noise", n_hidden=2, n_particles=10, n_epochs=1, random_state=0).fit(X, y)
    tr = reg._final
    assert tr.particles.shape[1] == reg.theta_.size + 1 and np.all(tr.noise > 0)
    mean, std = reg.predict(X_test, return_std=True)
    Y = np.stack([wnn_forward(p, X_test) for p in tr.particles[:, :-1]])
    np.testing.assert_allclose(std**2, Y.var(axis=0) + tr.noise.mean())
    assert "noise_prior_sd" in reg.settings_ and reg.settings_["noise_prior_mean"] == 0.1


def wnn_forward(theta, X):
    from filterwnn.wnn import network

    return network.forward(theta, X, "morlet")


def test_smc_noise_prior_rejects_non_finite_rows():
    """A leapfrog step that overflowed leaves non-finite rows: density 0, gradient 0 (no ValueError)."""
    from filterwnn.wnn.trainers import _LearnedNoise
    from filterwnn.wnn.weight_model import WNNWeightModel

    target = _LearnedNoise(WNNWeightModel(5, 2, Q=0.0, P0=0.5), np.log(0.1), 2.0)
    th = np.zeros((2, target.dim_x))
    th[1, 3] = np.nan
    lp, grad = target.log_prior_and_grad(th)
    assert np.isfinite(lp[0]) and lp[1] == -np.inf and np.all(grad[1] == 0)


def test_smc_noise_10x10_is_smc_noise_with_10_hmc_steps_per_rung():
    """The protocol-4 row runs smc-noise's sampler with 10 HMC steps of 10 leapfrogs per rung,
    every other setting smc-noise's (its name promises the moves, nothing else)."""
    X, y, _, _ = make_siso_benchmark(rng=1)
    kw = dict(n_hidden=2, n_particles=6, n_epochs=1, random_state=0)
    long = WNNRegressor(trainer="smc-noise-10x10", **kw).fit(X[:30], y[:30])
    base = WNNRegressor(trainer="smc-noise", **kw).fit(X[:30], y[:30])
    assert type(long._final) is type(base._final)
    assert {k: v for k, v in long.settings_.items() if base.settings_.get(k) != v} == {
        "n_moves": 10, "trainer": "smc-noise-10x10"}
    move = long._final.move
    assert (move.n_steps, move.n_leapfrog) == (10, 10) and base._final.move.n_steps == 6
    # opt-in: the default study (docs/study-outputs/wnn-default) does not run it
    assert "smc" in study.ALL_TRAINERS and "smc-noise-10x10" not in study.ALL_TRAINERS
