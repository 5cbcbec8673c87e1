"""filterpy's UKF arithmetic, operation for operation, with less Python around it.

The loop mode of :class:`filterwnn.kalman.unscented.UnscentedKalmanFilter` promises
filterpy's numbers bit for bit. These functions compute exactly what filterpy 2.0 computes
(the same floating-point operations in the same order) with fewer NumPy calls:

* :func:`merwe_sigma_points`: ``MerweScaledSigmaPoints.sigma_points`` with its default
  square root is one LAPACK ``potrf`` (the call :func:`scipy.linalg.cholesky` makes,
  without its wrapper's checks) and two broadcast additions (``x - (-u)`` is ``x + u``
  exactly in IEEE arithmetic);
* :func:`unscented_transform`: filterpy's dense ``y.T @ diag(Wc) @ y`` with the diagonal
  product as a row scaling (every term of that product but one is an exact zero);
* :func:`weighted_outer_sum`: filterpy's ``for i: P += Wc[i] * outer(a_i, b_i)`` as one
  stacked product and a sum over the first axis, which NumPy accumulates slice by slice in
  the loop's order.

``tests/kalman/test_filterpy_book.py`` and ``tests/kalman/test_unscented.py`` check the
results with ``np.array_equal`` against filterpy's own filter.
"""

from __future__ import annotations

import numpy as np
from filterpy.kalman import MerweScaledSigmaPoints
from scipy.linalg import cholesky
from scipy.linalg.lapack import dpotrf

__all__ = ["is_plain_merwe", "merwe_sigma_points", "unscented_transform", "weighted_outer_sum"]


def is_plain_merwe(points):
    """True for filterpy's own Merwe set with its default square root and subtraction."""
    return type(points) is MerweScaledSigmaPoints and points.sqrt is cholesky and points.subtract is np.subtract


def merwe_sigma_points(points, x, P):
    """``points.sigma_points(x, P)`` for a plain Merwe set (:func:`is_plain_merwe`).

    Raises :class:`numpy.linalg.LinAlgError` where scipy's Cholesky would; ``x`` of shape
    ``(n,)`` and ``P`` of shape ``(n, n)``, both float.
    """
    n = points.n
    lambda_ = points.alpha**2 * (n + points.kappa) - n
    U, info = dpotrf((lambda_ + n) * P, lower=0, clean=1, overwrite_a=1)
    if info != 0:
        raise np.linalg.LinAlgError(f"{info}-th leading minor of the array is not positive definite")
    sigmas = np.empty((2 * n + 1, n))
    sigmas[0] = x
    np.add(x, U, out=sigmas[1 : n + 1])
    np.subtract(x, U, out=sigmas[n + 1 :])
    return sigmas


def weighted_outer_sum(W, A, B):
    """``sum_i W[i] * outer(A[i], B[i])``, accumulated in filterpy's order (i = 0, 1, ...)."""
    T = A[:, :, None] * B[:, None, :]
    T *= W[:, None, None]
    return T.sum(axis=0)


def unscented_transform(sigmas, Wm, Wc, noise_cov=None, mean_fn=None, residual_fn=None):
    """:func:`filterpy.kalman.unscented_transform`, the same numbers."""
    x = np.dot(Wm, sigmas) if mean_fn is None else mean_fn(sigmas, Wm)
    if residual_fn is np.subtract or residual_fn is None:
        y = sigmas - x[np.newaxis, :]
        P = np.dot(y.T, Wc[:, None] * y)
    else:
        y = np.array([residual_fn(s, x) for s in sigmas], dtype=float)
        P = weighted_outer_sum(Wc, y, y)
    if noise_cov is not None:
        P += noise_cov
    return x, P
