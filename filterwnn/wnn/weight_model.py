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
to predict (``P_prior = P + Q``; :class:`filterwnn.kalman.unscented.UnscentedKalmanFilter` takes
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

**The posterior of the weights.** With ``Q = 0`` the weights are a static parameter and
the model is a Bayesian regression: prior :math:`\theta \sim N(x_0, P_0)` and likelihood
:math:`\prod_k N(y_k; \mathrm{WNN}(\theta, x_k), R)`. :meth:`WNNWeightModel.log_likelihood`,
:meth:`~WNNWeightModel.grad_log_likelihood` (``J^T (y - f) / R`` from the network's batched
Jacobian ``J``) and :meth:`~WNNWeightModel.log_prior` / :meth:`~WNNWeightModel.grad_log_prior`
give what a gradient-based MCMC move or an SMC sampler (:mod:`filterwnn.monte_carlo.smc`) needs,
batched over particles. :func:`scaled_prior` is a Gaussian prior matched to the scaled
start (:func:`filterwnn.wnn.network.init_scaled`).

>>> X, y = np.full((3, 5), 0.3), np.zeros(3)
>>> m.log_likelihood(thetas, X, y).shape, m.grad_log_likelihood(thetas, X, y).shape
((7,), (7, 160))
>>> m.log_prior(thetas).shape, m.grad_log_prior(thetas[0]).shape
((7,), (160,))
"""

from __future__ import annotations

import numpy as np

from . import network as wnn
from .._validation import as_state, check_choice, check_covariance, check_positive, check_positive_int, check_rng
from ..models import StateSpaceModel

__all__ = ["WNNWeightModel", "scaled_prior"]


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
        self._prior_chol = None

    # ------------------------------------------------------------------ posterior pieces
    def _rows(self, X, y):
        X = np.asarray(X, dtype=float)
        if X.ndim == 1:
            X = X[None, :]
        y = np.asarray(y, dtype=float).reshape(-1)
        if X.ndim != 2 or X.shape[1] != self.n_inputs:
            raise ValueError(f"X must have shape (n_rows, {self.n_inputs}), got shape {X.shape}")
        if y.shape[0] != X.shape[0]:
            raise ValueError(f"y must have one entry per row of X ({X.shape[0]}), got {y.shape[0]}")
        return X, y

    def log_likelihood(self, thetas, X, y):
        """Gaussian log-likelihood ``sum_k log N(y_k; WNN(theta, x_k), R)`` of the rows.

        Parameters
        ----------
        thetas : array-like of shape (dim_x,) or (n_particles, dim_x)
        X : array-like of shape (n_rows, n_inputs)
        y : array-like of shape (n_rows,)

        Returns
        -------
        float or ndarray of shape (n_particles,)
        """
        X, y = self._rows(X, y)
        r = float(self.R[0, 0])
        resid = y - wnn.forward(thetas, X, self.wavelet)
        return -0.5 * np.sum(resid * resid, axis=-1) / r - 0.5 * len(y) * np.log(2.0 * np.pi * r)

    def log_likelihood_and_grad(self, thetas, X, y):
        """:meth:`log_likelihood` and its gradient ``J^T (y - f) / R`` in one pass.

        Returns
        -------
        loglik : float or ndarray of shape (n_particles,)
        grad : ndarray of shape (dim_x,) or (n_particles, dim_x)
        """
        X, y = self._rows(X, y)
        r = float(self.R[0, 0])
        resid = y - wnn.forward(thetas, X, self.wavelet)  # (..., n)
        J = wnn.jacobian(thetas, X, self.wavelet)  # (..., n, d)
        ll = -0.5 * np.sum(resid * resid, axis=-1) / r - 0.5 * len(y) * np.log(2.0 * np.pi * r)
        grad = np.matmul(resid[..., None, :], J)[..., 0, :] / r
        return ll, grad

    def grad_log_likelihood(self, thetas, X, y):
        """Gradient of :meth:`log_likelihood` with respect to ``theta``: ``(dim_x,)`` or ``(n_particles, dim_x)``."""
        return self.log_likelihood_and_grad(thetas, X, y)[1]

    def _chol_P0(self):
        if self._prior_chol is None:
            try:
                self._prior_chol = np.linalg.cholesky(self.P0)
            except np.linalg.LinAlgError:
                raise ValueError(
                    "P0 must be positive definite for the prior density N(x0, P0) (Cholesky failed); "
                    "pass a positive P0"
                ) from None
        return self._prior_chol

    def log_prior(self, thetas):
        """Log-density of the prior ``N(x0, P0)``: a float or ``(n_particles,)``."""
        return self.log_prior_and_grad(thetas)[0]

    def grad_log_prior(self, thetas):
        """Gradient ``-P0^{-1} (theta - x0)`` of :meth:`log_prior` (by Cholesky solves)."""
        return self.log_prior_and_grad(thetas)[1]

    def log_prior_and_grad(self, thetas):
        """:meth:`log_prior` and :meth:`grad_log_prior` in one pass."""
        from scipy.linalg import cho_solve, solve_triangular

        L = self._chol_P0()
        dev = np.asarray(thetas, dtype=float) - self.x0
        D = np.atleast_2d(dev)
        white = solve_triangular(L, D.T, lower=True)  # (d, N)
        logdet = 2.0 * np.sum(np.log(np.diag(L)))
        lp = -0.5 * np.sum(white * white, axis=0) - 0.5 * (logdet + self.dim_x * np.log(2.0 * np.pi))
        grad = -cho_solve((L, True), D.T).T
        if dev.ndim == 1:
            return float(lp[0]), grad[0]
        return lp, grad

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


def scaled_prior(X, n_hidden, *, output_scale=1.0, dilation_sd=0.5):
    """A diagonal Gaussian prior on the weights matched to the scaled start.

    Moments of :func:`filterwnn.wnn.network.init_scaled`'s draws, with a wider output layer:
    ``W_jk ~ N(0, 1 / (n_inputs var x_k))``, ``v_j ~ N(0, output_scale**2)``,
    ``a_j ~ N(1, dilation_sd**2)`` (the start's ``U[0.5, 1.5] * std(W_j . x)`` has mean
    about 1, since ``W_j . x`` has unit variance on average) and ``b_j ~ N(0, s_b^2)`` with
    ``s_b^2 = mean_k (var x_k + mean x_k^2) / var x_k``, the start's second moment of
    ``b_j = W_j . x_r``.

    Parameters
    ----------
    X : array-like of shape (n_samples, n_inputs)
        Training inputs.
    n_hidden : int
    output_scale : float, default 1.0
        Prior standard deviation of the output weights ``v`` (the start's default is 0.1;
        1.0 is the prior the SMC trainer uses).
    dilation_sd : float, default 0.5

    Returns
    -------
    x0 : ndarray of shape (n_params,)
        Prior mean.
    variance : ndarray of shape (n_params,)
        Prior variances (``P0 = diag(variance)``).

    Examples
    --------
    >>> import numpy as np
    >>> x0, var = scaled_prior(np.random.default_rng(0).uniform(-1, 1, (50, 5)), n_hidden=20)
    >>> x0.shape, var.shape, bool(np.all(var > 0))
    ((160,), (160,), True)
    """
    X = np.asarray(X, dtype=float)
    if X.ndim != 2 or X.shape[0] < 2:
        raise ValueError(f"X must have shape (n_samples >= 2, n_inputs), got shape {X.shape}")
    n_hidden = check_positive_int(n_hidden, "n_hidden")
    output_scale = check_positive(output_scale, "output_scale")
    dilation_sd = check_positive(dilation_sd, "dilation_sd")
    d = X.shape[1]
    var = X.var(axis=0)
    var = np.where(var > 0, var, 1.0)
    mean = X.mean(axis=0)
    var_W = np.tile(1.0 / (d * var), n_hidden)
    var_b = float(np.mean((var + mean**2) / var))
    x0 = wnn.pack(np.zeros((n_hidden, d)), np.zeros(n_hidden), np.ones(n_hidden), np.zeros(n_hidden))
    variance = np.concatenate(
        [var_W, np.full(n_hidden, output_scale**2), np.full(n_hidden, dilation_sd**2), np.full(n_hidden, var_b)]
    )
    return x0, variance
