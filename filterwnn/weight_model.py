r"""A wavelet network's weights as the state of a state-space model.

Training a WNN with a filter F is running F on the model (Niu, Wu and Li, eqs. 10-11)

.. math::

    \theta_k = \theta_{k-1} + u_k, \quad u_k \sim N(0, Q), \qquad
    y_k = \mathrm{WNN}(\theta_k, x_k) + v_k, \quad v_k \sim N(0, R),

one training sample ``(x_k, y_k)`` per filter step, epoch after epoch. The state is the
parameter vector ``theta`` (layout of :mod:`filterwnn.wnn`), the measurement the scalar
target, and the *input* ``x_k`` of the current sample is passed to the measurement function
as a keyword: ``hx(thetas, x=x_k)``, which is filterpy's ``update(z, **hx_args)`` route
(``ukf.update(y_k, x=x_k)``).

The transition is a random walk: ``fx`` is the identity, so a filter needs no sigma points
to predict (``P_prior = P + Q``; :class:`filterwnn.unscented.UnscentedKalmanFilter` takes
``fx=None`` for exactly this).

``hx`` and ``HJacobian`` are vectorized over sigma points and particles: ``thetas`` of
shape ``(dim_x,)`` gives ``(1,)``, shape ``(n_points, dim_x)`` gives ``(n_points, 1)``.

>>> import numpy as np
>>> m = WNNWeightModel(n_inputs=5, n_hidden=20, Q=1e-5, R=0.1)
>>> m.dim_x, m.dim_z
(160, 1)
>>> thetas = np.random.default_rng(0).uniform(size=(7, 160))   # e.g. sigma points
>>> x_k = np.full(5, 0.3)
>>> m.hx(thetas, x=x_k).shape, m.hx(thetas[0], x=x_k).shape
((7, 1), (1,))
>>> m.HJacobian(thetas[0], x=x_k).shape
(1, 160)
>>> np.array_equal(m.fx(thetas), thetas)
True
"""

from __future__ import annotations

import numpy as np

from . import wnn
from ._validation import as_state, check_choice, check_covariance, check_positive, check_positive_int, check_rng
from .models import StateSpaceModel

__all__ = ["WNNWeightModel"]


def _as_cov(value, name, dim):
    """A scalar means ``value * eye(dim)``; a 1-D array a diagonal; else a checked matrix."""
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 1 and arr.size == dim:
        arr = np.diag(arr)
    return check_covariance(arr, name, dim, require_pd=False)


class WNNWeightModel(StateSpaceModel):
    """Random-walk weights, WNN output as the measurement.

    Parameters
    ----------
    n_inputs : int
        Inputs of the network.
    n_hidden : int
        Wavelet nodes.
    wavelet : {"morlet", "mexican_hat"}
    Q : float, array-like of shape (dim_x,) or (dim_x, dim_x)
        Process noise of the random walk (a scalar means ``Q * eye(dim_x)``).
    R : float or array-like of shape (1, 1)
        Measurement noise variance.
    x0 : array-like of shape (dim_x,), optional
        Prior mean of the weights (default zeros).
    P0 : float or array-like, optional
        Prior covariance (default identity).

    Attributes
    ----------
    dim_x : int
        ``n_hidden * (n_inputs + 3)``.
    dim_z : int
        1.
    """

    def __init__(self, n_inputs, n_hidden, wavelet="morlet", Q=0.0, R=0.1, x0=None, P0=1.0, dt=1.0):
        self.n_inputs = check_positive_int(n_inputs, "n_inputs")
        self.n_hidden = check_positive_int(n_hidden, "n_hidden")
        self.wavelet = check_choice(wavelet, "wavelet", wnn.WAVELETS)
        self.dim_x = wnn.n_params(self.n_inputs, self.n_hidden)
        self.dim_z = 1
        self.dt = check_positive(dt, "dt")
        self.Q = _as_cov(Q, "Q", self.dim_x)
        self.R = check_covariance(R, "R", 1)
        self.x0 = np.zeros(self.dim_x) if x0 is None else as_state(x0, "x0", self.dim_x)
        self.P0 = _as_cov(P0, "P0", self.dim_x)

    def fx(self, x, dt=None, **fx_args):
        """Random walk: the identity on ``(dim_x,)`` or ``(n_points, dim_x)``."""
        return np.asarray(x, dtype=float)

    def FJacobian(self, x, dt=None, **fx_args):
        """The identity matrix ``(dim_x, dim_x)``."""
        return np.eye(self.dim_x)

    def hx(self, thetas, x=None, **hx_args):
        """Network output for the current input ``x`` of shape ``(n_inputs,)``.

        Parameters
        ----------
        thetas : ndarray of shape (dim_x,) or (..., dim_x)
        x : ndarray of shape (n_inputs,)

        Returns
        -------
        ndarray of shape (1,) or (..., 1)
        """
        if x is None:
            raise TypeError("WNNWeightModel.hx needs the current input as hx(thetas, x=x_k)")
        X = np.asarray(x, dtype=float).reshape(1, self.n_inputs)
        return wnn.forward(thetas, X, self.wavelet)

    def HJacobian(self, thetas, x=None, **hx_args):
        """Jacobian of :meth:`hx`: ``(1, dim_x)`` or ``(..., 1, dim_x)``."""
        if x is None:
            raise TypeError("WNNWeightModel.HJacobian needs the current input as HJacobian(theta, x=x_k)")
        X = np.asarray(x, dtype=float).reshape(1, self.n_inputs)
        return wnn.jacobian(thetas, X, self.wavelet)

    def simulate(self, n_steps, rng=None, x0=None, X=None):
        """Simulate weights drifting as the random walk and noisy network outputs.

        Parameters
        ----------
        n_steps : int
        rng : None, int, SeedSequence or Generator
        x0 : array-like of shape (dim_x,), optional
            Start (default: a draw from ``N(x0, P0)``).
        X : array-like of shape (n_steps, n_inputs), optional
            Inputs (default ``U[-1, 1]`` draws from ``rng``).

        Returns
        -------
        thetas : ndarray of shape (n_steps, dim_x)
        zs : ndarray of shape (n_steps, 1)
        """
        n_steps = check_positive_int(n_steps, "n_steps")
        rng = check_rng(rng)
        if X is None:
            X = rng.uniform(-1.0, 1.0, (n_steps, self.n_inputs))
        X = np.asarray(X, dtype=float)
        if X.shape != (n_steps, self.n_inputs):
            raise ValueError(f"X must have shape ({n_steps}, {self.n_inputs}), got {X.shape}")
        if x0 is None:
            theta = self.x0 + np.linalg.cholesky(self.P0) @ rng.standard_normal(self.dim_x)
        else:
            theta = np.asarray(x0, dtype=float).reshape(self.dim_x)
        evals, evecs = np.linalg.eigh(self.Q)
        Lq = evecs * np.sqrt(np.clip(evals, 0.0, None))
        r = float(np.sqrt(self.R[0, 0]))
        thetas = np.empty((n_steps, self.dim_x))
        zs = np.empty((n_steps, 1))
        for k in range(n_steps):
            theta = theta + Lq @ rng.standard_normal(self.dim_x)
            thetas[k] = theta
            zs[k] = self.hx(theta, x=X[k]) + r * rng.standard_normal()
        return thetas, zs
