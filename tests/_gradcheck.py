"""Central finite differences of a target's log-density over a stack of particles, for the tests
of the SMC sampler's targets (``log_likelihood_and_grad``, ``log_prior_and_grad``)."""

import numpy as np


def assert_rows_gradient(fn, th, eps=1e-6, rtol=1e-5, atol=1e-6):
    """Check ``fn(th) -> (value (N,), grad (N, d))`` against central differences of ``value``
    in each of the ``d`` coordinates of every row of ``th (N, d)``."""
    grad = fn(th)[1]
    num = np.zeros_like(th)
    for j in range(th.shape[1]):
        e = np.zeros_like(th)
        e[:, j] = eps
        num[:, j] = (fn(th + e)[0] - fn(th - e)[0]) / (2 * eps)
    np.testing.assert_allclose(num, grad, rtol=rtol, atol=atol)
