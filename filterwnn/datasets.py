r"""Data sets of the papers' studies.

:func:`make_siso_benchmark` is the single-input single-output plant of Niu, Wu and Li
(eq. 12):

.. math::

    y(k) = \frac{16 u(k-1) + 8 y(k-1)}{3 + 4 u(k-1)^2 + 4 y(k-1)^2}
           + 0.2\, u(k-1) + 0.2\, y(k-1),

driven by ``u ~ U[-1, 1]`` with ``y(0) = 0``. 300 points are simulated; the regressor rows
``[u(k-1), u(k-2), y(k-1), y(k-2), y(k-3)] -> y(k)`` for ``k = 3..202`` give 200 samples,
the first 100 for training and the rest for test. Only ``u(k-1)`` and ``y(k-1)`` enter the
plant: the other three regressors are distractors, which is what limits a 5-20-1 WNN
(measured by least-squares fits, 10 data seeds x 20 starts: zeroing the three
distractors lowers the WNN's median test MSE about 60-fold, from about 0.1 to 0.0015).

The test set's variance depends on the seed (1.66 for seed 0, 2.35 median over seeds
0-9), so a study that re-draws the data per run must say so.

>>> X_train, y_train, X_test, y_test = make_siso_benchmark(rng=0)
>>> X_train.shape, y_train.shape, X_test.shape, y_test.shape
((100, 5), (100,), (100, 5), (100,))
>>> round(float(y_test.var()), 2)
1.66
"""

from __future__ import annotations

import numpy as np

from ._validation import check_rng

__all__ = ["siso_plant", "make_siso_benchmark"]


def siso_plant(u_prev, y_prev):
    """One step of the plant of eq. (12): ``y(k)`` from ``u(k-1)`` and ``y(k-1)`` (elementwise)."""
    u_prev = np.asarray(u_prev, dtype=float)
    y_prev = np.asarray(y_prev, dtype=float)
    return (16 * u_prev + 8 * y_prev) / (3 + 4 * u_prev**2 + 4 * y_prev**2) + 0.2 * u_prev + 0.2 * y_prev


def make_siso_benchmark(rng=None):
    """The paper's SISO benchmark: 100 training and 100 test regressor rows.

    Parameters
    ----------
    rng : None, int, SeedSequence, BitGenerator or Generator
        Source of the input signal; ``u = rng.uniform(-1, 1, 300)`` is its first draw.

    Returns
    -------
    X_train : ndarray of shape (100, 5)
        Rows ``[u(k-1), u(k-2), y(k-1), y(k-2), y(k-3)]`` for ``k = 3..102``.
    y_train : ndarray of shape (100,)
        ``y(k)`` for ``k = 3..102``.
    X_test : ndarray of shape (100, 5)
        The same for ``k = 103..202``.
    y_test : ndarray of shape (100,)
    """
    rng = check_rng(rng)
    u = rng.uniform(-1.0, 1.0, 300)
    y = np.zeros(300)
    for k in range(1, 300):
        y[k] = siso_plant(u[k - 1], y[k - 1])
    k = np.arange(3, 203)
    X = np.column_stack([u[k - 1], u[k - 2], y[k - 1], y[k - 2], y[k - 3]])
    t = y[k]
    return X[:100], t[:100], X[100:], t[100:]
