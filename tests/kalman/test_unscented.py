"""Our UnscentedKalmanFilter against filterpy's, in both modes, and its failures."""

import copy
import pickle

import numpy as np
import pytest
from filterpy.kalman import MerweScaledSigmaPoints
from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF

from filterwnn import NumericalError, SphericalSimplexSigmaPoints
from filterwnn.kalman.unscented import UnscentedKalmanFilter

ATOL = 1e-9  # same numbers as filterpy up to rounding


# a nonlinear model, written on the last axis: works for (n,) and (n_sigmas, n)
from _nonlinear_model import fx, hx  # noqa: E402


def make(cls, points, vectorized=None, f=fx):
    kw = {} if vectorized is None else {"vectorized": vectorized}
    ukf = cls(3, 2, 0.1, hx, f, points, **kw)
    ukf.x = np.array([0.3, -0.2, 1.0])
    ukf.P = np.diag([0.5, 0.3, 0.2])
    ukf.Q = np.eye(3) * 1e-3
    ukf.R = np.diag([0.05, 0.02])
    return ukf


def simulate(n=30, seed=0):
    rng = np.random.default_rng(seed)
    x = np.array([0.5, 0.1, 0.8])
    zs = []
    for _ in range(n):
        x = fx(x, 0.1) + rng.normal(0, 0.03, 3)
        zs.append(hx(x) + rng.normal(0, 0.1, 2))
    return np.array(zs)


POINTS = {
    "merwe": lambda: MerweScaledSigmaPoints(3, alpha=0.5, beta=2.0, kappa=0.0),
    "simplex": lambda: SphericalSimplexSigmaPoints(3, alpha=0.8, beta=2.0, w0=0.1),
}


@pytest.mark.parametrize("points", sorted(POINTS))
@pytest.mark.parametrize("vectorized", [False, True])
def test_equals_filterpy_on_nonlinear_model_at_every_step(points, vectorized):
    ref = make(FilterpyUKF, POINTS[points]())
    ours = make(UnscentedKalmanFilter, POINTS[points](), vectorized)
    for z in simulate():
        ref.predict()
        ours.predict()
        np.testing.assert_allclose(ours.x_prior, ref.x_prior, atol=ATOL)
        np.testing.assert_allclose(ours.P_prior, ref.P_prior, atol=ATOL)
        ref.update(z)
        ours.update(z)
        np.testing.assert_allclose(ours.x, ref.x, atol=ATOL)
        np.testing.assert_allclose(ours.P, ref.P, atol=ATOL)
        np.testing.assert_allclose(ours.log_likelihood, ref.log_likelihood, rtol=1e-9)
    assert ours.step == 30  # the time step: predict advances it, update does not


def test_non_vectorized_is_bit_identical_to_filterpy():
    ref = make(FilterpyUKF, POINTS["merwe"]())
    ours = make(UnscentedKalmanFilter, POINTS["merwe"](), False)
    for z in simulate(10):
        ref.predict(); ours.predict(); ref.update(z); ours.update(z)
    assert np.array_equal(ours.x, ref.x) and np.array_equal(ours.P, ref.P)


@pytest.mark.parametrize("vectorized", [False, True])
def test_random_walk_equals_filterpy_with_identity_fx(vectorized):
    ident = lambda x, dt: x.copy()  # noqa: E731
    ref = make(FilterpyUKF, POINTS["merwe"](), f=ident)
    ours = make(UnscentedKalmanFilter, POINTS["merwe"](), vectorized, f=None)
    for z in simulate():
        ref.predict(); ours.predict()
        np.testing.assert_allclose(ours.P_prior, ref.P_prior, atol=ATOL)
        ref.update(z); ours.update(z)
        np.testing.assert_allclose(ours.x, ref.x, atol=ATOL)
        np.testing.assert_allclose(ours.P, ref.P, atol=ATOL)


def test_random_walk_step_needs_one_factorisation(monkeypatch):
    """predict factors P_prior once (its check), and update reuses the factor."""
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True, f=None)
    ukf.predict(); ukf.update(np.array([1.2, 0.1]))  # the first predict also checks Q, once
    calls = []
    real = np.linalg.cholesky
    monkeypatch.setattr(np.linalg, "cholesky", lambda a: calls.append(1) or real(a))
    for z in ([1.2, 0.1], [1.1, 0.0]):
        ukf.predict()
        ukf.update(np.array(z))
    assert len(calls) == 2  # one Cholesky per step


@pytest.mark.parametrize("vectorized", [False, True])
def test_batch_filter_and_rts_smoother_match_filterpy(vectorized):
    zs = simulate(25)
    ref = make(FilterpyUKF, POINTS["merwe"]())
    ours = make(UnscentedKalmanFilter, POINTS["merwe"](), vectorized)
    mu_r, cov_r = ref.batch_filter(zs)
    mu_o, cov_o = ours.batch_filter(zs)
    np.testing.assert_allclose(mu_o, mu_r, atol=ATOL)
    np.testing.assert_allclose(cov_o, cov_r, atol=ATOL)
    xs_r, ps_r, _ = ref.rts_smoother(mu_r, cov_r)
    xs_o, ps_o, _ = ours.rts_smoother(mu_o, cov_o)
    np.testing.assert_allclose(xs_o, xs_r, atol=1e-8)
    np.testing.assert_allclose(ps_o, ps_r, atol=1e-8)


def test_rts_smoother_random_walk_equals_identity_fx():
    zs = simulate(15)
    ident = lambda x, dt: x.copy()  # noqa: E731
    ref = make(FilterpyUKF, POINTS["merwe"](), f=ident)
    ours = make(UnscentedKalmanFilter, POINTS["merwe"](), True, f=None)
    mu, cov = ref.batch_filter(zs)
    xs_r, ps_r, _ = ref.rts_smoother(mu, cov)
    xs_o, ps_o, _ = ours.rts_smoother(mu, cov)
    np.testing.assert_allclose(xs_o, xs_r, atol=1e-8)
    np.testing.assert_allclose(ps_o, ps_r, atol=1e-8)


def test_z_none_skips_update():
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    ukf.predict()
    x, P = ukf.x.copy(), ukf.P.copy()
    ukf.update(None)
    assert np.array_equal(ukf.x, x) and np.array_equal(ukf.P_post, P)


@pytest.mark.parametrize("vectorized", [False, True])
@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_non_finite_z_raises_and_leaves_state(vectorized, bad):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized)
    ukf.predict()
    x, P, step = ukf.x.copy(), ukf.P.copy(), ukf.step
    with pytest.raises(ValueError, match="z must be finite"):
        ukf.update(np.array([1.0, bad]))
    assert np.array_equal(ukf.x, x) and np.array_equal(ukf.P, P) and ukf.step == step


@pytest.mark.parametrize("vectorized", [False, True])
def test_not_positive_definite_P_raises_numerical_error_with_step(vectorized):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized)
    ukf.predict(); ukf.update(np.array([1.2, 0.1]))
    ukf.P = -np.eye(3)
    x = ukf.x.copy()
    with pytest.raises(NumericalError, match="P is not positive definite at step 2") as info:
        ukf.predict()
    assert info.value.matrix == "P" and info.value.step == 2 and ukf.step == 1
    assert isinstance(info.value, np.linalg.LinAlgError) and isinstance(info.value, ValueError)
    assert np.array_equal(ukf.x, x) and np.array_equal(ukf.P, -np.eye(3))


def _NOT_PD_UT(sigmas, Wm, Wc, *args, **kwargs):
    """An unscented transform whose ``S`` is not positive definite: a failed update (an ``R`` that is not positive
    definite is refused before it, stop 69)."""
    return Wm @ sigmas, -10 * np.eye(sigmas.shape[1])


@pytest.mark.parametrize("R, said", [(-np.eye(2), "smallest eigenvalue -1 at step 1"),
                                     (np.zeros((2, 2)), "smallest eigenvalue 0 at step 1")])
def test_an_R_that_is_not_positive_definite_is_refused_at_its_update(R, said):
    """A sign slip in R (-1: S stayed positive definite) went through, and the next predict blamed P, a step later;
    R = 0 (a perfect measurement) left P singular the same way (stop 69)."""
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    ukf.predict()
    x, P = ukf.x.copy(), ukf.P.copy()
    with pytest.raises(ValueError, match="R must be positive definite .* " + said):
        ukf.update(np.array([1.0, 0.0]), R=R)
    assert np.array_equal(ukf.x, x) and np.array_equal(ukf.P, P)
    ukf.R = R
    with pytest.raises(ValueError, match="R must be positive definite"):
        ukf.update(np.array([1.0, 0.0]))


def test_a_scalar_R_attribute_is_refused_where_filterpy_would_add_it_to_every_entry():
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), False)
    ukf.R = 0.25
    ukf.predict()
    with pytest.raises(ValueError, match=r"R must have shape \(2, 2\), got the scalar 0.25: .* use R = 0.25 \* "
                                         r"np.eye\(2\)"):
        ukf.update(np.array([1.0, 0.0]))
    ukf.update(np.array([1.0, 0.0]), R=0.25)  # an argument: filterpy's update takes it as 0.25 * I too


def test_not_positive_definite_S_raises():
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    ukf.predict()
    with pytest.raises(NumericalError, match="S is not positive definite at step 1") as info:
        ukf.update(np.array([1.0, 0.0]), UT=_NOT_PD_UT)
    assert info.value.matrix == "S"


def test_vectorized_hx_shape_is_checked():
    ukf = UnscentedKalmanFilter(3, 2, 0.1, lambda X: X[:, :1], fx, POINTS["simplex"](), vectorized=True)
    ukf.predict()
    with pytest.raises(ValueError, match=r"vectorized hx must map \(5, 3\) sigma points to shape \(5, 2\), got \(5, 1\)"):
        ukf.update(np.zeros(2))


@pytest.mark.parametrize(
    "args, match",
    [
        ((0, 2, 0.1), "dim_x must be >= 1, got 0"),
        ((3, 0, 0.1), "dim_z must be >= 1, got 0"),
        ((3, 2, 0.0), r"dt must be finite and > 0, got 0.0"),
        ((3, 2, -1.0), r"dt must be finite and > 0, got -1.0"),
        ((4, 2, 0.1), "points.n must equal dim_x=4, got 3"),
    ],
)
def test_constructor_errors(args, match):
    with pytest.raises(ValueError, match=match):
        UnscentedKalmanFilter(*args, hx, fx, POINTS["simplex"]())


def test_wrong_shapes_of_state_raise():
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    ukf.x = np.zeros(4)
    with pytest.raises(ValueError, match=r"x must have shape \(3,\), got \(4,\)"):
        ukf.predict()
    ukf.x = np.zeros(3)
    ukf.P = np.eye(2)
    with pytest.raises(ValueError, match=r"P must have shape \(3, 3\), got \(2, 2\)"):
        ukf.predict()


def test_pickle_mid_run_continues_identically():
    zs = simulate(20)
    a = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    for z in zs[:10]:
        a.predict(); a.update(z)
    b = pickle.loads(pickle.dumps(a))
    for z in zs[10:]:
        a.predict(); a.update(z); b.predict(); b.update(z)
    assert np.array_equal(a.x, b.x) and np.array_equal(a.P, b.P)


def test_vectorized_measurement_size_may_change_with_R():
    """Like filterpy: a second sensor with another z size, given its own hx and R."""
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    ukf.predict()
    ukf.update(np.array([0.4]), R=np.eye(1) * 0.1, hx=lambda X: X[:, :1])
    assert ukf.x.shape == (3,) and ukf.K.shape == (3, 1)


# --------------------------------------------------------------------------- issue 15: drop-in
def filterpy_style_residual_z(a, b):
    """As filterpy's examples write it: for ONE row (wraps entry 1)."""
    y = a - b
    y[1] = (y[1] + np.pi) % (2 * np.pi) - np.pi
    return y


def test_vectorized_per_row_residual_is_detected_on_first_call():
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    ukf.residual_z = filterpy_style_residual_z
    ukf.predict()
    x, P = ukf.x.copy(), ukf.P.copy()
    with pytest.raises(ValueError, match=r"vectorized residual_z looks written for one point: .*when that row "
                                         r"is passed alone.*x\[1\] selects a sigma point.*angle_residual"):
        ukf.update(np.array([1.2, 0.1]))
    assert np.array_equal(ukf.x, x) and np.array_equal(ukf.P, P) and ukf.step == 1


def test_per_row_residual_is_fine_in_loop_mode():
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), False)
    ukf.residual_z = filterpy_style_residual_z
    ukf.predict()
    ukf.update(np.array([1.2, 0.1]))


def test_vectorized_residual_x_and_shapes_are_checked():
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    ukf.residual_x = lambda a, b: (a - b)[..., :2]
    with pytest.raises(ValueError, match=r"vectorized residual_x must map sigma points of shape \(5, 3\)"):
        ukf.predict()
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    ukf.z_mean = lambda s, w: w @ s[:, :1]
    ukf.predict()
    with pytest.raises(ValueError, match=r"z_mean_fn must map sigma points of shape \(5, 2\).*got \(1,\)"):
        ukf.update(np.array([1.2, 0.1]))


def test_a_last_axis_residual_passes_and_equals_loop_mode():
    def residual(a, b):
        y = np.subtract(a, b)
        y[..., 1] = (y[..., 1] + np.pi) % (2 * np.pi) - np.pi
        return y

    runs = []
    for vectorized in (False, True):
        ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized)
        ukf.residual_z = residual
        for z in simulate(5):
            ukf.predict(); ukf.update(z)
        runs.append(ukf)
    np.testing.assert_allclose(runs[1].x, runs[0].x, atol=ATOL)


@pytest.mark.parametrize("vectorized", [False, True])
def test_column_z_is_flattened_in_both_modes(vectorized):
    a = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized)
    b = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized)
    z = np.array([1.2, 0.1])
    a.predict(); a.update(z)
    b.predict(); b.update(z.reshape(2, 1))
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.P, b.P)


@pytest.mark.parametrize("vectorized", [False, True])
def test_negative_Q_fails_at_predict_and_says_the_fix(vectorized):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized, f=None)
    ukf.Q = -np.eye(3)
    with pytest.raises(ValueError, match=r"Q must be positive semi-definite; smallest eigenvalue -1; "
                                         r"Q must be a covariance, e.g. Q = np.diag\(variances\)"):
        ukf.predict()
    assert ukf.step == 0


@pytest.mark.parametrize("vectorized", [False, True])
def test_indefinite_P_prior_fails_at_predict_in_both_modes(vectorized):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized, f=lambda x, dt: 0.0 * x)
    ukf.Q = np.zeros((3, 3))  # every sigma point maps to 0: P_prior = 0
    x = ukf.x.copy()
    with pytest.raises(NumericalError, match="P_prior is not positive definite at step 1") as info:
        ukf.predict()
    assert info.value.matrix == "P_prior" and ukf.step == 0 and np.array_equal(ukf.x, x)


@pytest.mark.parametrize("name", ["P", "Q"])
def test_scalar_covariance_message_says_eye(name):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    setattr(ukf, name, 0.1)
    with pytest.raises(ValueError, match=rf"{name} must have shape \(3, 3\), got \(\); .*"
                                         rf"use {name} = {name.lower()} \* np.eye\(3\)"):
        ukf.predict()


@pytest.mark.parametrize("vectorized", [False, True])
def test_step_is_the_time_step(vectorized):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized)
    assert ukf.step == 0
    ukf.predict()
    assert ukf.step == 1
    ukf.update(np.array([1.2, 0.1]))
    assert ukf.step == 1
    ukf.predict(); ukf.update(None)
    assert ukf.step == 2
    with pytest.raises(NumericalError, match="S is not positive definite at step 2") as info:
        ukf.update(np.array([1.2, 0.1]), UT=_NOT_PD_UT)
    assert info.value.step == 2 and ukf.step == 2


# --------------------------------------------------------------------------- issue 26.6: P edits
def _estimate_after_edit(vectorized, edit):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized)
    ukf.predict()
    edit(ukf)
    ukf.update(np.array([1.2, 0.1]))
    return ukf.x


def _assign(ukf):
    ukf.P = ukf.P * 4


def _in_place(ukf):
    ukf.P *= 4


@pytest.mark.parametrize("vectorized", [False, True])
def test_reassigning_P_and_scaling_it_in_place_give_the_same_estimate(vectorized):
    """The caches (symmetry checked, Cholesky factor, update's sigma points) follow P's content."""
    a = _estimate_after_edit(vectorized, _assign)
    b = _estimate_after_edit(vectorized, _in_place)
    np.testing.assert_array_equal(a, b)
    untouched = _estimate_after_edit(vectorized, lambda ukf: None)
    assert not np.allclose(a, untouched)  # the edit mattered: its sigma points were redrawn


def test_both_modes_see_an_edit_between_predict_and_update_alike():
    np.testing.assert_allclose(_estimate_after_edit(False, _in_place), _estimate_after_edit(True, _in_place),
                               atol=ATOL)


@pytest.mark.parametrize("vectorized", [False, True])
@pytest.mark.parametrize("when", ["before update", "before predict"])
def test_an_asymmetric_edit_in_place_is_refused(vectorized, when):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized)
    ukf.predict(); ukf.update(np.array([1.2, 0.1]))
    if when == "before update":
        ukf.predict()
    ukf.P[0, 2] += 0.5
    call = (lambda: ukf.update(np.array([1.2, 0.1]))) if when == "before update" else ukf.predict
    with pytest.raises(ValueError, match=r"P must be symmetric; max \|P - P.T\| = 0.5; symmetrise it"):
        call()


@pytest.mark.parametrize("vectorized", [False, True])
def test_a_Q_edited_in_place_is_checked_again(vectorized):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized)
    ukf.predict()
    ukf.Q *= -1
    with pytest.raises(ValueError, match="Q must be positive semi-definite"):
        ukf.predict()


def _Q_comparisons(ukf, n_steps):
    """How often ``n_steps`` predicts compare Q with the kept copy (its O(n^2) check)."""
    seen = []
    unchanged = ukf._unchanged
    ukf._unchanged = lambda name, M: seen.append(name) or unchanged(name, M)
    for _ in range(n_steps):
        ukf.predict()
        ukf.update(np.array([1.2, 0.1]))
    del ukf._unchanged
    return seen.count("Q")


@pytest.mark.parametrize("vectorized", [False, True])
def test_a_Q_assigned_as_a_temporary_is_checked_once_not_every_step(vectorized):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), vectorized)
    ukf.Q = np.eye(3) * 0.02
    assert _Q_comparisons(ukf, 5) == 1
    Q = np.eye(3) * 0.02  # a Q the caller keeps a name for may change under the filter: compared every step
    ukf.Q = Q
    assert _Q_comparisons(ukf, 5) == 5


def test_where_a_reference_count_cannot_tell_every_Q_is_compared_every_step(monkeypatch):
    import filterwnn.kalman.unscented as unscented

    monkeypatch.setattr(unscented, "_TEMPORARY", None)  # as on an interpreter that counts both alike
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    ukf.Q = np.eye(3) * 0.02
    assert _Q_comparisons(ukf, 5) == 5


@pytest.mark.parametrize("edit", ["through ukf.Q", "through the caller's name", "through the array viewed",
                                  "through a shallow copy"])
def test_an_edit_of_Q_by_any_route_is_still_seen(edit):
    ukf = make(UnscentedKalmanFilter, POINTS["simplex"](), True)
    big, Q = np.eye(4) * 0.02, np.eye(3) * 0.02
    if edit == "through the array viewed":
        ukf.Q = big[:3, :3]
    elif edit == "through the caller's name":
        ukf.Q = Q  # the caller keeps its name for the array it assigned
    else:
        ukf.Q = np.eye(3) * 0.02
    ukf.predict(); ukf.update(np.array([1.2, 0.1]))
    if edit == "through ukf.Q":
        ukf.Q[0, 0] = -1.0
    elif edit == "through the caller's name":
        Q[0, 0] = -1.0
    elif edit == "through the array viewed":
        big[0, 0] = -1.0
    else:
        copy.copy(ukf).Q[0, 0] = -1.0
    with pytest.raises(ValueError, match="Q must be positive semi-definite"):
        ukf.predict()


def test_kept_sigma_buffers_leave_a_restored_sigmas_f_intact():
    # the vectorized step draws Merwe sigma points into two kept arrays that take turns:
    # a failed update restores sigmas_f with its points unchanged, and the numbers are
    # those of fresh arrays (x + sigma_deviations)
    from filterwnn.kalman.sigma_points import sigma_deviations

    pts = MerweScaledSigmaPoints(3, 1.0, 2.0, 0.0)
    ukf = UnscentedKalmanFilter(3, 1, 1.0, lambda X: X[:, :1], None, pts, vectorized=True)
    ukf.Q = np.eye(3) * 0.1
    ukf.predict(); ukf.update(np.array([0.3]))
    kept, before = ukf.sigmas_f, ukf.sigmas_f.copy()
    ukf.predict()
    prior_x, prior_P = ukf.x.copy(), ukf.P.copy()
    with pytest.raises(NumericalError, match="S is not positive definite"):
        ukf.update(np.array([0.3]), UT=_NOT_PD_UT)
    assert ukf.sigmas_f is kept and np.array_equal(ukf.sigmas_f, before)
    ukf.update(np.array([0.2]))
    want = prior_x + sigma_deviations(pts, np.linalg.cholesky(prior_P).T)
    assert ukf.sigmas_f is not kept and np.array_equal(ukf.sigmas_f, want)


@pytest.mark.parametrize("name", ["merwe", "simplex"])
def test_update_after_compute_process_sigmas_uses_the_propagated_points(name):
    # filterpy's update takes P_xz from sigmas_f - x; after compute_process_sigmas with an fx
    # the vectorized step's kept deviations are those of the unpropagated points, and the
    # gain differed from loop mode's by up to 0.19 before they were dropped there
    Ks = []
    for vectorized in (False, True):
        ukf = make(UnscentedKalmanFilter, POINTS[name](), vectorized)
        ukf.predict()
        ukf.update(np.array([1.0, 0.5]))
        ukf.compute_process_sigmas(ukf._dt)
        ukf.update(np.array([1.2, 0.4]))
        Ks.append(ukf.K)
    np.testing.assert_allclose(Ks[1], Ks[0], rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("vectorized", [False, True])
def test_an_edit_through_a_reference_kept_across_a_failed_update_is_seen(vectorized):
    # the vectorized step skips comparing an x or P nobody read since it made them; a read
    # hands the value out, and a failed update must not forget that it was
    ukf = make(UnscentedKalmanFilter, POINTS["merwe"](), vectorized)
    ukf.predict(); ukf.update(np.array([1.2, 0.1]))
    ukf.predict()
    P = ukf.P
    with pytest.raises(NumericalError, match="S is not positive definite"):
        ukf.update(np.array([1.2, 0.1]), UT=_NOT_PD_UT)
    P[0, 2] += 0.5
    with pytest.raises(ValueError, match=r"P must be symmetric; max \|P - P.T\| = 0.5"):
        ukf.update(np.array([1.2, 0.1]))


def _in_old_layout(ukf, names, watched):
    """``ukf`` pickled and restored with ``names`` as plain attributes (the layout before they
    were descriptors; ``watched`` ones also carried an ``_<name>_out`` flag)."""
    state = pickle.loads(pickle.dumps(ukf)).__dict__.copy()
    for name in names:
        state[name] = state.pop(f"_{name}_now")
        if watched:
            del state[f"_{name}_out"]
    old = UnscentedKalmanFilter.__new__(UnscentedKalmanFilter)
    old.__setstate__(state)
    return old


def test_a_pickle_from_before_x_and_P_were_watched_loads():
    ukf = make(UnscentedKalmanFilter, POINTS["merwe"](), True)
    ukf.predict(); ukf.update(np.array([1.2, 0.1]))
    old = _in_old_layout(ukf, ("x", "P"), watched=True)
    old.predict(); old.update(np.array([1.0, 0.2]))
    ukf.predict(); ukf.update(np.array([1.0, 0.2]))
    np.testing.assert_array_equal(old.x, ukf.x)


@pytest.mark.parametrize("vectorized", [False, True])
def test_filterpys_saver_records_x_and_P_at_every_step(vectorized):
    from filterpy.common import Saver

    ukf = make(UnscentedKalmanFilter, POINTS["merwe"](), vectorized)
    saver, xs, Ps = Saver(ukf), [], []
    for z in simulate(5):
        ukf.predict(); ukf.update(z)
        saver.save()
        xs.append(ukf.x.copy()); Ps.append(ukf.P.copy())
    saver.to_array()
    np.testing.assert_array_equal(saver.x, np.array(xs))
    np.testing.assert_array_equal(saver.P, np.array(Ps))


@pytest.mark.parametrize("f", [fx, None])
@pytest.mark.parametrize("first", ["P", "kept"])
def test_P_prior_and_P_post_are_arrays_of_their_own(f, first):
    # the step stores the P it made as P_prior / P_post until either is handed out:
    # an edit in place of one, whichever is read first, must not show in the other
    ukf = make(UnscentedKalmanFilter, POINTS["merwe"](), True, f=f)
    for step in ("predict", "update"):
        ukf.predict() if step == "predict" else ukf.update(np.array([1.2, 0.1]))
        name = "P_prior" if step == "predict" else "P_post"
        a, b = (ukf.P, getattr(ukf, name)) if first == "P" else (getattr(ukf, name), ukf.P)
        assert a is not b
        np.testing.assert_array_equal(a, b)
        saved = b.copy()
        a[0, 0] += 1.0
        np.testing.assert_array_equal(b, saved)
        a[0, 0] -= 1.0


def test_a_pickle_from_before_P_prior_and_P_post_were_kept_loads():
    ukf = make(UnscentedKalmanFilter, POINTS["merwe"](), True)
    ukf.predict(); ukf.update(np.array([1.2, 0.1]))
    old = _in_old_layout(ukf, ("P_prior", "P_post"), watched=False)
    np.testing.assert_array_equal(old.P_post, ukf.P_post)
    old.predict(); ukf.predict()
    np.testing.assert_array_equal(old.P_prior, ukf.P_prior)


def test_the_scalar_update_keeps_P_exactly_symmetric_at_every_size():
    """A 1x1 ``S`` updates ``P`` by the rank-1 downdate ``P - u u^T``: exactly symmetric, bit for bit,
    on every machine (BLAS ``dger`` was not: OpenBLAS's Haswell kernel fuses the multiply-add in
    its vector body only, and left entries 1 ulp apart at n = 24)."""
    rng = np.random.default_rng(3)
    for n in range(1, 41):
        A = rng.standard_normal((n, n))
        f = UnscentedKalmanFilter(n, 1, 1.0, lambda X: np.sin(X).sum(axis=1, keepdims=True), None,
                                  MerweScaledSigmaPoints(n, 1.0, 2.0, 0.0), vectorized=True)
        f.x, f.P, f.Q, f.R = rng.standard_normal(n), A @ A.T / n + np.eye(n), np.eye(n) * 0.01, np.eye(1) * 0.1
        for _ in range(3):
            f.predict()
            f.update(np.array([0.3]))
            assert np.array_equal(f.P, f.P.T), n
