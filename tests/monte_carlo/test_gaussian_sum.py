"""GaussianSumFilter: the closed-form posterior of a Gaussian-mixture prior, for every component kind."""

import numpy as np
import pytest

from filterwnn import GaussianSumFilter, NumericalError

from _linear_model import LIN, lin_F, lin_fx, lin_H, lin_hx  # noqa: E402

TOL = 1e-8


def make(component, **kw):
    f = GaussianSumFilter(3, 2, 1.0, lin_hx, lin_fx, component=component, FJacobian=lin_F, HJacobian=lin_H,
                          vectorized=True, **kw)
    f.Q, f.R = LIN.Q.copy(), LIN.R.copy()
    return f


def closed_form(means, covs, weights, zs):
    """Exact posterior mixture: each component is a Kalman filter, weights times N(z; Hm, S)."""
    F, H, Q, R = LIN.F, LIN.H, LIN.Q, LIN.R
    M, C, w = [m.copy() for m in means], [c.copy() for c in covs], np.array(weights, float)
    for z in zs:
        lik = []
        for i in range(len(M)):
            m, P = F @ M[i], F @ C[i] @ F.T + Q
            S = H @ P @ H.T + R
            K = np.linalg.solve(S, H @ P).T
            y = z - H @ m
            lik.append(np.exp(-0.5 * y @ np.linalg.solve(S, y)) / np.sqrt(np.linalg.det(2 * np.pi * S)))
            M[i], C[i] = m + K @ y, P - K @ S @ K.T
        w = w * np.array(lik)
        w /= w.sum()
    return np.array(M), np.array(C), w


@pytest.mark.parametrize("component", ["ekf", "ukf", "sukf"])
def test_posterior_mixture_equals_the_closed_form(component):
    zs = LIN.simulate(8, rng=4)[1]
    means = [LIN.x0 + 1.0, LIN.x0 - 1.0]
    covs = [LIN.P0, 0.5 * LIN.P0]
    weights = [0.3, 0.7]
    f = make(component)
    f.initialize(means, np.array(covs), weights)
    f.batch_filter(zs)
    M, C, w = closed_form(means, covs, weights, zs)
    np.testing.assert_allclose(f.means, M, atol=TOL)
    np.testing.assert_allclose(f.covariances, C, atol=TOL)
    np.testing.assert_allclose(f.weights, w, atol=TOL)
    x = w @ M
    d = M - x
    np.testing.assert_allclose(f.x, x, atol=TOL)
    np.testing.assert_allclose(f.P, (d.T * w) @ d + np.tensordot(w, C, axes=1), atol=TOL)


@pytest.mark.parametrize("component", ["ekf", "ukf", "sukf"])
def test_one_component_is_the_kalman_filter_and_its_likelihood(component):
    xs, zs = LIN.simulate(10, rng=5)
    kf = LIN.kalman_filter()
    ref, _, _, _ = kf.batch_filter(zs)
    f = make(component)
    f.x, f.P = LIN.x0.copy(), LIN.P0.copy()
    means, _ = f.batch_filter(zs)
    np.testing.assert_allclose(means, ref, atol=1e-9)
    kf = LIN.kalman_filter()
    total = 0.0
    for z in zs:
        kf.predict()
        kf.update(z)
        total += kf.log_likelihood
    assert f.log_marginal_likelihood == pytest.approx(total, abs=1e-8)


def test_tempering_scales_the_log_weights_and_combine_mean_is_the_unweighted_average():
    zs = LIN.simulate(6, rng=6)[1]
    starts = np.random.default_rng(0).normal(size=(5, 3))
    lw = {}
    for tau in (1.0, 0.01):
        f = make("ukf", tempering=tau)
        f.initialize(starts, LIN.P0)
        f.batch_filter(zs)
        lw[tau] = f.log_weights
    d = lw[0.01] - 0.01 * lw[1.0]
    np.testing.assert_allclose(d, d[0], atol=1e-9)
    f = make("ukf", combine="mean")
    f.initialize(starts, LIN.P0)
    f.batch_filter(zs)
    np.testing.assert_allclose(f.x, f.means.mean(axis=0), atol=1e-12)


def test_component_resampling_when_the_ess_falls():
    zs = LIN.simulate(6, rng=7)[1]
    starts = np.random.default_rng(1).normal(scale=3.0, size=(20, 3))
    f = make("ekf", ess_threshold=1.0, rng=2)
    f.initialize(starts, LIN.P0)
    f.batch_filter(zs)
    assert all(f.resampled_history) and min(f.n_distinct_history) < 20
    g = make("ekf")
    g.initialize(starts, LIN.P0)
    g.batch_filter(zs)
    assert not any(g.resampled_history) and g.n_distinct == 20


def test_bad_arguments():
    with pytest.raises(ValueError, match="unknown component 'pf'"):
        make("pf")
    with pytest.raises(ValueError, match="needs HJacobian"):
        GaussianSumFilter(3, 2, 1.0, lin_hx, lin_fx, component="ekf", FJacobian=lin_F)
    with pytest.raises(ValueError, match="unknown combine 'median'"):
        make("ukf", combine="median")
    f = make("ukf")
    with pytest.raises(ValueError, match=r"means must be finite of shape \(n_components, 3\)"):
        f.initialize(np.zeros((2, 2)), np.eye(3))
    C = np.tile(np.eye(3), (2, 1, 1))
    C[1] = -np.eye(3)
    f.initialize(np.zeros((2, 3)), C)
    with pytest.raises(NumericalError, match=r"not positive definite at step 1 \(particle 1\)"):
        f.predict()


def test_x_and_P_set_mid_run_are_refused():
    f = make("ukf")
    f.x, f.P = LIN.x0.copy(), LIN.P0.copy()  # before the first predict: the start N(x, P)
    f.predict()
    with pytest.raises(ValueError, match=r"x cannot be set once the components exist \(step 1\)"):
        f.x = np.zeros(3)
    with pytest.raises(ValueError, match="P cannot be set once the components exist"):
        f.P = np.eye(3)
