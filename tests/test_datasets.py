"""Tests of filterwnn.datasets: the SISO benchmark of the first paper's eq. (12)."""

import numpy as np
import pytest

from filterwnn.datasets import make_siso_benchmark, siso_plant


def test_shapes_and_seed0_variance():
    X_train, y_train, X_test, y_test = make_siso_benchmark(rng=0)
    assert X_train.shape == X_test.shape == (100, 5)
    assert y_train.shape == y_test.shape == (100,)
    assert y_test.var() == pytest.approx(1.66, abs=0.005)


def test_regressors_follow_the_recursion():
    rng = np.random.default_rng(3)
    u = rng.uniform(-1, 1, 300)  # the first draw of the same stream
    X_train, y_train, X_test, y_test = make_siso_benchmark(rng=3)
    X = np.vstack([X_train, X_test])
    y = np.concatenate([y_train, y_test])
    # k = 3: regressors [u(2), u(1), y(2), y(1), y(0) = 0]
    np.testing.assert_allclose(X[:, 0], u[2:202])
    np.testing.assert_allclose(X[:, 1], u[1:201])
    assert X[0, 4] == 0.0
    np.testing.assert_allclose(y, siso_plant(X[:, 0], X[:, 2]), rtol=1e-14)
    np.testing.assert_allclose(X[1:, 2], y[:-1])  # y(k-1) is the previous target
    np.testing.assert_allclose(X[1:, 3], X[:-1, 2])
    np.testing.assert_allclose(X[1:, 4], X[:-1, 3])


def test_reproducible_and_seed_dependent():
    a = make_siso_benchmark(rng=np.random.SeedSequence(5))
    b = make_siso_benchmark(rng=np.random.SeedSequence(5))
    c = make_siso_benchmark(rng=6)
    for p, q in zip(a, b):
        np.testing.assert_array_equal(p, q)
    assert not np.array_equal(a[0], c[0])


def test_bad_rng():
    with pytest.raises(TypeError, match="rng"):
        make_siso_benchmark(rng="zero")
