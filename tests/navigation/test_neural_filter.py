"""Tests of the neural filter: phase 1, the phase-2 gradient, the filterpy-style API."""

import numpy as np
import pytest

from filterwnn.navigation.dead_reckoning import DRModel, dr_residual
from filterwnn.navigation.scenarios import SCENARIOS, simulate_scenario
from filterwnn.navigation.neural_filter import (
    NeuralFilter,
    make_training_set,
    paper_training_states,
    random_motion_states,
)


@pytest.fixture(scope="module")
def model():
    return DRModel(dt=0.1)


@pytest.fixture(scope="module")
def fitted(model):
    Xp, Z, X = make_training_set(paper_training_states(), model, rng=0, n_repeats=3)
    return NeuralFilter(model, rng=1, n_epochs=200).fit(Xp, Z, X)


def test_training_states_and_set_shapes(model):
    S = paper_training_states()
    assert S.shape == (30, 6)
    np.testing.assert_allclose(S[0, [0, 3]], [-6, -6])
    np.testing.assert_allclose(S[-1, [0, 3]], [0, 0])
    np.testing.assert_allclose(S[:, [1, 4]], 10.0)
    Xp, Z, X = make_training_set(S, model, rng=0, n_repeats=2)
    assert Xp.shape == (60, 6) and Z.shape == (60, 2) and X.shape == (60, 6)
    np.testing.assert_allclose(X, model.fx(np.repeat(S, 2, axis=0)))
    R = random_motion_states(50, rng=3)
    assert R.shape == (50, 6)
    with pytest.raises(ValueError, match="states"):
        make_training_set(np.zeros((3, 5)), model, rng=0)


def test_fit_learns_and_is_reproducible(model):
    Xp, Z, X = make_training_set(paper_training_states(), model, rng=0)
    a = NeuralFilter(model, rng=4, n_epochs=50).fit(Xp, Z, X)
    b = NeuralFilter(model, rng=4, n_epochs=50).fit(Xp, Z, X)
    assert a.loss_curve_[-1] < 0.1 * a.loss_curve_[0]
    for k in a.params_:
        np.testing.assert_array_equal(a.params_[k], b.params_[k])
    assert a.params_["W1"].shape == (12, 8) and a.params_["W2"].shape == (6, 12)
    c = NeuralFilter(model, n_hidden=5, rng=4, n_epochs=5).fit(Xp, Z, X)
    assert c.params_["W1"].shape == (5, 8)


def test_api_and_errors(model, fitted):
    nf = fitted
    nf.reset()
    assert nf.P is None
    nf.predict()
    np.testing.assert_allclose(nf.x_prior, model.fx(model.x0))
    nf.update(None)  # no measurement: keep the prediction
    np.testing.assert_allclose(nf.x, nf.x_prior)
    with pytest.raises(ValueError, match="finite"):
        nf.update([np.nan, 1.0])
    with pytest.raises(ValueError, match="not fitted"):
        NeuralFilter(model).update([0.1, 1.0])
    with pytest.raises(ValueError, match="form"):
        NeuralFilter(model, form="magic")
    with pytest.raises(ValueError, match="zs"):
        nf.batch_filter(np.zeros((5, 3)))


def test_passthrough_keeps_integrated_position(model, fitted):
    run = simulate_scenario(SCENARIOS["straight"](duration=5.0), rng=0)
    nf = fitted.reset(run.x0)
    prev = nf.x.copy()
    for z in run.z_dr:
        nf.predict()
        nf.update(z)
        pos_pred = prev[[0, 3]] + 0.1 * prev[[1, 4]] + 0.005 * prev[[2, 5]]
        np.testing.assert_allclose(nf.x[[0, 3]], pos_pred, atol=1e-12)
        prev = nf.x.copy()


def test_noise_free_straight_run_is_tracked(model, fitted):
    sc = SCENARIOS["straight"](sigma_heading=1e-6, sigma_odometer=1e-8, factor=1.0, duration=60.0)
    run = simulate_scenario(sc, rng=1)
    means = fitted.reset(run.x0).batch_filter(run.z_dr)
    assert means.shape == (600, 6)
    err = np.hypot(*(means[:, [0, 3]] - run.x_true[:, [0, 3]]).T)
    assert err.max() < 0.5


def test_absolute_form_cannot_leave_its_training_box(model):
    # the paper's faithful form: trained on positions in [-6, 0] it cannot output km
    Xp, Z, X = make_training_set(paper_training_states(), model, rng=0)
    nf = NeuralFilter(model, form="absolute", features="angle", rng=1, n_epochs=100).fit(Xp, Z, X)
    run = simulate_scenario(SCENARIOS["straight"](duration=30.0), rng=1)
    means = nf.reset(run.x0).batch_filter(run.z_dr)
    assert np.hypot(*(means[-1, [0, 3]] - run.x_true[-1, [0, 3]])) > 100.0


@pytest.mark.parametrize("form", ["passthrough", "relative", "absolute"])
def test_online_gradient_matches_finite_differences(model, form):
    """Phase 2's gradient of 0.5 ||h(Phi x(k-1)(W)) - y||^2 equals finite differences."""
    Xp, Z, X = make_training_set(paper_training_states(), model, rng=0)
    nf = NeuralFilter(model, form=form, rng=2, n_epochs=20, learning_rate_online=0.0).fit(Xp, Z, X)
    nf.reset(model.x0)
    nf.predict()
    nf.update(np.array([0.80, 1.40]))
    U, off, xp_prev = nf._last
    z = np.array([0.75, 1.45])

    def loss(p):
        out, _ = nf._forward(U[None, :], p)
        x_prev = nf._state(out[0], off, xp_prev)
        r = dr_residual(model.hx(model.fx(x_prev)), z)
        return 0.5 * float(r @ r)

    p0 = {k: v.copy() for k, v in nf.params_.items()}
    nf.predict()
    out, Hh = nf._forward(U[None, :], p0)
    r = dr_residual(model.hx(nf.x_prior), z)
    g_state = (r @ model.HJacobian(nf.x_prior)) @ model.F
    grads = nf._backward(U[None, :], Hh, (g_state * nf.state_scale * nf._output_mask())[None, :], p0)
    eps = 1e-6
    for k in ("W1", "b2", "W2"):
        fd = np.zeros_like(p0[k])
        for idx in np.ndindex(p0[k].shape):
            pp = {kk: vv.copy() for kk, vv in p0.items()}
            pm = {kk: vv.copy() for kk, vv in p0.items()}
            pp[k][idx] += eps
            pm[k][idx] -= eps
            fd[idx] = (loss(pp) - loss(pm)) / (2 * eps)
        np.testing.assert_allclose(grads[k], fd, atol=1e-8, rtol=1e-5)
    # and update() applies exactly this step
    nf.learning_rate_online = 1e-2
    nf.update(z)
    np.testing.assert_allclose(nf.params_["b2"], p0["b2"] - 1e-2 * grads["b2"])


def test_same_seed_same_filter_output(model):
    run = simulate_scenario(SCENARIOS["straight"](duration=10.0), rng=3)
    outs = []
    for _ in range(2):
        Xp, Z, X = make_training_set(paper_training_states(), model, rng=5)
        nf = NeuralFilter(model, rng=6, n_epochs=30).fit(Xp, Z, X)
        outs.append(nf.reset(run.x0).batch_filter(run.z_dr))
    np.testing.assert_array_equal(outs[0], outs[1])


def test_step_is_the_time_step(fitted, model):
    """As in every filter (issue 15): predict advances step, update reports it."""
    nf = fitted.reset()
    assert nf.step == 0
    nf.predict()
    assert nf.step == 1
    nf.update(model.hx(nf.x_prior))
    nf.update(None)
    assert nf.step == 1
    nf.predict(); nf.update(None)
    assert nf.step == 2
    assert nf.reset().step == 0
