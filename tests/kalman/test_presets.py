"""Named sigma-point presets: one definition per setting, used by every filter of the package."""

import re
from pathlib import Path

import numpy as np
import pytest
from filterpy.kalman import MerweScaledSigmaPoints

from filterwnn.kalman import POINT_PRESETS, SphericalSimplexSigmaPoints, make_points
from filterwnn.monte_carlo.particle_filter import SimplexUnscentedParticleFilter, UnscentedParticleFilter

PACKAGE = Path(__file__).resolve().parents[2] / "filterwnn"


@pytest.mark.parametrize("name", sorted(POINT_PRESETS))
@pytest.mark.parametrize("n", [1, 3, 6])
def test_every_preset_reproduces_mean_and_covariance(name, n):
    pts = make_points(name, n)
    assert pts.n == n
    rng = np.random.default_rng(n)
    A = rng.standard_normal((n, n))
    P, x = A @ A.T + n * np.eye(n), rng.standard_normal(n)
    sig = pts.sigma_points(x, P)
    assert sig.shape == (pts.num_sigmas(), n)
    np.testing.assert_allclose(pts.Wm.sum(), 1.0, atol=1e-12)
    np.testing.assert_allclose(pts.Wm @ sig, x, atol=1e-10)
    d = sig - x
    # Wc differs from Wm only at the centre, where the deviation is zero
    np.testing.assert_allclose((d.T * pts.Wc) @ d, P, atol=1e-9)


@pytest.mark.parametrize("name,cls,settings", [
    ("merwe", MerweScaledSigmaPoints, dict(alpha=1.0, beta=2.0, kappa=0.0)),
    ("gpsdr-ukf", MerweScaledSigmaPoints, dict(alpha=0.5, beta=2.0, kappa=0.0)),
    ("merwe-kappa", MerweScaledSigmaPoints, dict(alpha=0.5, beta=2.0, kappa=-1.0)),
    ("supf", SphericalSimplexSigmaPoints, dict(alpha=1.0, beta=2.0, w0=0.0)),
    ("simplex", SphericalSimplexSigmaPoints, dict(alpha=1.0, beta=0.0, w0=0.0)),
    ("gpsdr-sukf", SphericalSimplexSigmaPoints, dict(alpha=0.5, beta=2.0, kappa=0.0)),
])
def test_presets_are_the_documented_settings_bit_for_bit(name, cls, settings):
    pts, ref = make_points(name, 4), cls(4, **settings)
    assert type(pts) is cls
    np.testing.assert_array_equal(pts.Wm, ref.Wm)
    np.testing.assert_array_equal(pts.Wc, ref.Wc)
    np.testing.assert_array_equal(pts.sigma_points(np.ones(4), np.eye(4)), ref.sigma_points(np.ones(4), np.eye(4)))


@pytest.mark.parametrize("n", [6, 8, 9])
def test_the_gpsdr_sukf_points_lie_on_the_gpsdr_ukf_sphere_with_its_centre_weights(n):
    # the GPS/DR SUKF and UKF spread their points equally far (Merwe's radius alpha sqrt(n))
    sukf, ukf = make_points("gpsdr-sukf", n), make_points("gpsdr-ukf", n)
    radius = lambda p: np.linalg.norm(p.sigma_points(np.zeros(n), np.eye(n))[1:], axis=1)  # noqa: E731
    np.testing.assert_allclose(radius(sukf), ukf.alpha * np.sqrt(n), rtol=1e-12)
    np.testing.assert_allclose(radius(ukf).max(), ukf.alpha * np.sqrt(n), rtol=1e-12)
    np.testing.assert_allclose([sukf.Wm[0], sukf.Wc[0]], [ukf.Wm[0], ukf.Wc[0]], rtol=1e-12)


def test_the_particle_filters_default_to_the_presets():
    hx = lambda x: x[..., :1]  # noqa: E731
    supf = SimplexUnscentedParticleFilter(3, 1, 1.0, hx, None, 10, rng=0)
    upf = UnscentedParticleFilter(3, 1, 1.0, hx, None, 10, rng=0)
    for pf, name in ((supf, "supf"), (upf, "merwe")):
        np.testing.assert_array_equal(pf.proposal.points.Wc, make_points(name, 3).Wc)


def test_the_wnn_simplex_is_the_unscaled_set_not_the_supf_preset():
    from filterwnn.wnn.trainers import merwe_points, simplex_points

    assert simplex_points(5).beta == 0.0 and make_points("supf", 5).beta == 2.0
    assert simplex_points(5, alpha=0.5).alpha == 0.5
    assert merwe_points(5, alpha=0.5).beta == 2.0


def test_an_unknown_preset_or_setting_is_refused_with_the_names():
    with pytest.raises(ValueError, match=r"one of \['gpsdr-sukf'.*got 'julier'"):
        make_points("julier", 3)
    with pytest.raises(TypeError, match=r"preset 'supf' sets \['alpha', 'beta', 'w0'\]; \['kappa'\]"):
        make_points("supf", 3, kappa=1.0)
    with pytest.raises(TypeError, match="read-only|does not support item assignment"):
        POINT_PRESETS["mine"] = None


def test_no_module_builds_merwe_or_simplex_points_outside_the_preset_home():
    pattern = re.compile(r"(SphericalSimplexSigmaPoints|MerweScaledSigmaPoints)\(")
    home = {PACKAGE / "kalman" / "presets.py", PACKAGE / "kalman" / "sigma_points.py"}
    found = [f"{p.relative_to(PACKAGE)}:{i}" for p in sorted(PACKAGE.rglob("*.py")) if p not in home
             for i, line in enumerate(p.read_text().splitlines(), 1) if pattern.search(line)]
    assert not found, f"build points with filterwnn.kalman.make_points(name, n): {found}"
