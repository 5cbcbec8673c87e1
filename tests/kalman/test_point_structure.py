"""The structure protocol of sigma-point sets: a declared staircase, filterpy's symmetric sets, dense."""

import numpy as np
import pytest
from filterpy.kalman import JulierSigmaPoints, MerweScaledSigmaPoints, SimplexSigmaPoints

from filterwnn.kalman.sigma_points import (MinimalSkewSigmaPoints, SphericalSimplexSigmaPoints, batched_sigma_points,
                                           point_structure, sigma_deviations, unit_sigma_points,
                                           unit_transpose_apply)


class DeclaredStaircase:
    """A set of someone else's that is a staircase and says so (the protocol, no subclassing)."""

    def __init__(self, inner):
        self.inner, self.n, self.Wm, self.Wc = inner, inner.n, inner.Wm, inner.Wc
        self.staircase = inner.staircase

    def num_sigmas(self):
        return self.inner.num_sigmas()

    def sigma_points(self, x, P):
        return self.inner.sigma_points(x, P)


@pytest.mark.parametrize("points,kind", [
    (SphericalSimplexSigmaPoints(3, alpha=0.5), "staircase"),
    (MinimalSkewSigmaPoints(3), "staircase"),
    (DeclaredStaircase(SphericalSimplexSigmaPoints(3, w0=0.2)), "staircase"),
    (MerweScaledSigmaPoints(3, alpha=0.5, beta=2.0, kappa=0.0), "symmetric"),
    (JulierSigmaPoints(3, kappa=1.0), "symmetric"),
    (SimplexSigmaPoints(3), "dense"),
])
def test_each_kind_gives_the_dense_products(points, kind, rng=np.random.default_rng(3)):
    assert point_structure(points)[0] == kind
    A = rng.standard_normal((4, 3, 3))
    P = A @ np.swapaxes(A, -1, -2) + np.eye(3)
    L = np.linalg.cholesky(P)
    Z = unit_sigma_points(points)
    x = rng.standard_normal((4, 3))
    np.testing.assert_allclose(sigma_deviations(points, np.swapaxes(L, -1, -2)), Z @ np.swapaxes(L, -1, -2),
                               atol=1e-12)
    np.testing.assert_allclose(batched_sigma_points(points, x, L), x[:, None] + Z @ np.swapaxes(L, -1, -2),
                               atol=1e-12)
    B = rng.standard_normal((4, Z.shape[0], 2))
    np.testing.assert_allclose(unit_transpose_apply(points, Z, B), np.matmul(Z.T, B), atol=1e-12)


def test_the_staircase_is_read_before_the_merwe_base_class():
    pts = SphericalSimplexSigmaPoints(4)
    assert isinstance(pts, MerweScaledSigmaPoints)
    kind, (a, b) = point_structure(pts)
    assert kind == "staircase" and a.shape == b.shape == (4,)
    Z = unit_sigma_points(pts)
    np.testing.assert_array_equal(Z[1, :], a)  # row 1 holds a in every column
