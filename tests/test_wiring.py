"""Models wire themselves into filters in one place: ``models.from_model`` and ``models.wire``."""

import re
from pathlib import Path

import numpy as np
import pytest
from filterpy.kalman import ExtendedKalmanFilter, KalmanFilter
from filterpy.kalman import UnscentedKalmanFilter as FilterpyUKF

from filterwnn.kalman import UnscentedKalmanFilter, make_points
from filterwnn.models import GammaNoiseModel, LinearGaussianModel, StateSpaceModel, from_model, wire
from filterwnn.monte_carlo.gaussian_sum import GaussianSumFilter
from filterwnn.monte_carlo.particle_filter import BootstrapParticleFilter, UnscentedParticleFilter
from filterwnn.navigation.dead_reckoning import DRModel, GPSDRModel, dr_residual, dr_z_mean

PACKAGE = Path(__file__).resolve().parents[1] / "filterwnn"
LIN = LinearGaussianModel.random(dim_x=3, dim_z=2, rng=4)


def test_a_kalman_filter_gets_every_matrix_as_a_copy():
    kf = from_model(KalmanFilter, LIN)
    for name, want in (("F", LIN.F), ("H", LIN.H), ("Q", LIN.Q), ("R", LIN.R), ("x", LIN.x0), ("P", LIN.P0)):
        got = getattr(kf, name)
        np.testing.assert_array_equal(got, want)
        assert not np.shares_memory(got, want), name
    kf.predict()
    kf.update(np.ones(2))
    np.testing.assert_array_equal(LIN.x0, np.zeros(3))  # the model is untouched


def test_the_constructor_gets_the_functions_it_names_and_the_model_has():
    dr = DRModel(dt=0.1)
    ukf = from_model(UnscentedKalmanFilter, dr, points=make_points("gpsdr-ukf", 6))
    assert (ukf._dim_x, ukf._dim_z, ukf._dt) == (6, 2, 0.1)
    assert ukf.residual_z is dr_residual and ukf.z_mean is dr_z_mean
    ekf = from_model(ExtendedKalmanFilter, GPSDRModel(augmented=True))
    assert ekf.dim_x == 8 and ekf.dim_z == 4
    np.testing.assert_array_equal(ekf.F, GPSDRModel(augmented=True).F)


def test_the_base_class_residual_is_not_passed():
    ukf = from_model(FilterpyUKF, LIN, points=make_points("merwe", 3))
    assert ukf.residual_z is np.subtract  # filterpy's default, not StateSpaceModel's placeholder


def test_particle_filters_get_the_model_densities_and_settings_pass_through():
    g = GammaNoiseModel()
    pf = from_model(BootstrapParticleFilter, g, n_particles=20, vectorized=True, rng=0)
    assert pf.n_particles == 20 and pf.vectorized
    assert pf.process_sampler == g.process_sampler and pf.transition_logpdf == g.transition_logpdf
    assert pf.FJacobian == g.FJacobian


def test_fx_none_is_a_random_walk_without_the_model_jacobian():
    g = GammaNoiseModel()
    pf = from_model(UnscentedParticleFilter, g, fx=None, n_particles=10, rng=0)
    assert pf.fx is None and pf.FJacobian is None and pf.HJacobian == g.HJacobian
    gsf = from_model(GaussianSumFilter, g, fx=None, component="ekf")  # would refuse fx without FJacobian
    np.testing.assert_array_equal(gsf.Q, g.Q)


def test_overrides_are_checked_and_named():
    x0, P0 = np.array([1.0, 2.0, 3.0]), 2.0 * np.eye(3)
    kf = wire(KalmanFilter(3, 2), LIN, x0=x0, P0=P0, Q=np.zeros((3, 3)))
    np.testing.assert_array_equal(kf.x, x0)
    np.testing.assert_array_equal(kf.P, P0)
    assert not np.any(kf.Q) and not np.shares_memory(kf.x, x0)
    with pytest.raises(ValueError, match="x0 must have length 3"):
        wire(KalmanFilter(3, 2), LIN, x0=[1.0, 2.0])
    with pytest.raises(ValueError, match="P0"):
        from_model(KalmanFilter, LIN, P0=-np.eye(3))
    with pytest.raises(ValueError, match="R"):
        from_model(KalmanFilter, LIN, R=np.eye(3))


def test_a_model_without_hx_is_refused_by_the_filter():
    class Bare(StateSpaceModel):
        dim_x, dim_z = 2, 1
        x0, P0, Q, R = np.zeros(2), np.eye(2), np.eye(2), np.eye(1)

    with pytest.raises(TypeError, match="hx"):
        from_model(FilterpyUKF, Bare(), points=make_points("merwe", 2))


def test_the_model_helpers_are_from_model():
    kf = LIN.kalman_filter()
    np.testing.assert_array_equal(kf.H, LIN.H)
    g = GammaNoiseModel()
    pf = g.particle_filter(BootstrapParticleFilter, 15, rng=1)
    np.testing.assert_array_equal(pf.Q, g.Q)
    ekf = DRModel().ekf(x0=np.arange(6.0))
    np.testing.assert_array_equal(ekf.x, np.arange(6.0))


def test_no_module_copies_a_model_into_a_filter_by_hand():
    assign = re.compile(r"^\s*(self\.)?(kf|pf|ukf|f)\.(F|H|x|P|Q|R)\b.*=[^=].*\b(model|m|self|prior)\."
                        r"(F|H|x0|P0|Q|R)\b")
    found = [f"{p.relative_to(PACKAGE)}:{i}" for p in sorted(PACKAGE.rglob("*.py"))
             for i, line in enumerate(p.read_text().splitlines(), 1) if assign.search(line)]
    assert not found, f"wire a model with filterwnn.models.from_model or wire: {found}"
