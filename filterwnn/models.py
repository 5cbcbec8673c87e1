"""State-space models: the small objects every filter and test consumes.

A model is separate from any filter. It holds

``dim_x, dim_z, dt``
    sizes and the time step;
``fx(x, dt, **fx_args)`` and ``hx(x, **hx_args)``
    the transition and measurement functions in filterpy's signatures. Every model in
    this package writes them on the last axis (``x[..., i]``), so the *same* function
    serves one state of shape ``(dim_x,)`` and a stack of points of shape
    ``(n_points, dim_x)`` -- which is what ``vectorized=True`` filters pass;
``Q, R``
    process and measurement noise covariances;
``FJacobian(x, dt, **fx_args)``, ``HJacobian(x, **hx_args)``
    optional analytic Jacobians (filterpy's ``ExtendedKalmanFilter`` convention);
``residual_z(a, b)``
    measurement difference (``np.subtract`` unless angles need wrapping);
``simulate(n_steps, rng)``
    a ground-truth run ``(xs, zs)`` of shapes ``(n_steps, dim_x)`` and ``(n_steps, dim_z)``.

The linear-Gaussian model below is the reference against which every nonlinear filter is
pinned: on it the unscented and particle filters must reproduce filterpy's
``KalmanFilter``.

>>> import numpy as np
>>> m = LinearGaussianModel.random(dim_x=3, dim_z=2, rng=0)
>>> xs, zs = m.simulate(5, rng=1)
>>> xs.shape, zs.shape
((5, 3), (5, 2))
>>> np.allclose(m.hx(xs), xs @ m.H.T)
True
"""

from __future__ import annotations

import numpy as np

from ._validation import as_state, check_covariance, check_positive, check_positive_int, check_rng

__all__ = ["StateSpaceModel", "LinearGaussianModel"]


class StateSpaceModel:
    """Base class of the model protocol (see the module docstring).

    Subclasses set ``dim_x``, ``dim_z``, ``dt``, ``Q``, ``R``, ``x0``, ``P0`` and
    implement ``fx`` and ``hx``; ``FJacobian``/``HJacobian`` are optional.
    ``simulate`` draws Gaussian noise from ``Q`` and ``R``.
    """

    dim_x: int
    dim_z: int
    dt: float = 1.0

    def fx(self, x, dt=None, **fx_args):  # pragma: no cover - abstract
        raise NotImplementedError

    def hx(self, x, **hx_args):  # pragma: no cover - abstract
        raise NotImplementedError

    @staticmethod
    def residual_z(a, b):
        """Measurement residual ``a - b`` (override for angles)."""
        return np.subtract(a, b)

    def simulate(self, n_steps, rng=None, x0=None):
        """Simulate ``n_steps`` steps from ``x0`` (default: a draw from ``N(x0, P0)``).

        Returns
        -------
        xs : ndarray of shape (n_steps, dim_x)
            True states ``x_1 .. x_n`` (after each transition).
        zs : ndarray of shape (n_steps, dim_z)
            Measurements of those states.
        """
        n_steps = check_positive_int(n_steps, "n_steps")
        rng = check_rng(rng)
        if x0 is not None:
            x0 = as_state(x0, "x0", self.dim_x)
        Lq = np.linalg.cholesky(self.Q) if np.any(self.Q) else np.zeros_like(self.Q)
        Lr = np.linalg.cholesky(self.R)
        if x0 is None:
            x = self.x0 + np.linalg.cholesky(self.P0) @ rng.standard_normal(self.dim_x)
        else:
            x = x0.copy()
        xs = np.empty((n_steps, self.dim_x))
        zs = np.empty((n_steps, self.dim_z))
        for k in range(n_steps):
            x = self.fx(x, self.dt) + Lq @ rng.standard_normal(self.dim_x)
            xs[k] = x
            zs[k] = self.hx(x) + Lr @ rng.standard_normal(self.dim_z)
        return xs, zs


class LinearGaussianModel(StateSpaceModel):
    """``x_k = F x_{k-1} + w``, ``z_k = H x_k + v``, with ``w ~ N(0, Q)``, ``v ~ N(0, R)``.

    Parameters
    ----------
    F : ndarray of shape (dim_x, dim_x)
    H : ndarray of shape (dim_z, dim_x)
    Q : ndarray of shape (dim_x, dim_x)
    R : ndarray of shape (dim_z, dim_z)
    x0 : ndarray of shape (dim_x,), optional
        Prior mean (default zeros).
    P0 : ndarray of shape (dim_x, dim_x), optional
        Prior covariance (default identity).
    dt : float
        Time step (unused by the maths; kept for filterpy's signatures).
    """

    def __init__(self, F, H, Q, R, x0=None, P0=None, dt=1.0):
        self.F = np.atleast_2d(np.asarray(F, dtype=float))
        self.H = np.atleast_2d(np.asarray(H, dtype=float))
        self.dim_x = self.F.shape[0]
        self.dim_z = self.H.shape[0]
        if self.F.ndim != 2 or self.F.shape != (self.dim_x, self.dim_x):
            raise ValueError(f"F must be square, got shape {self.F.shape}")
        if self.H.ndim != 2 or self.H.shape[1] != self.dim_x:
            raise ValueError(f"H must have shape (dim_z, {self.dim_x}), got {self.H.shape}")
        for name, M in (("F", self.F), ("H", self.H)):
            if not np.all(np.isfinite(M)):
                raise ValueError(f"{name} must be finite, got non-finite entries")
        self.Q = check_covariance(Q, "Q", self.dim_x, require_pd=False)
        self.R = check_covariance(R, "R", self.dim_z)
        self.x0 = np.zeros(self.dim_x) if x0 is None else as_state(x0, "x0", self.dim_x)
        self.P0 = np.eye(self.dim_x) if P0 is None else check_covariance(P0, "P0", self.dim_x)
        self.dt = check_positive(dt, "dt")

    @classmethod
    def random(cls, dim_x=4, dim_z=2, rng=None, q=0.1, r=0.5):
        """A random stable linear-Gaussian model (spectral radius 0.95), for tests."""
        dim_x = check_positive_int(dim_x, "dim_x")
        dim_z = check_positive_int(dim_z, "dim_z")
        q = check_positive(q, "q")
        r = check_positive(r, "r")
        rng = check_rng(rng)
        A = rng.standard_normal((dim_x, dim_x))
        F = 0.95 * A / max(np.abs(np.linalg.eigvals(A)).max(), 1e-12)
        H = rng.standard_normal((dim_z, dim_x))
        B = rng.standard_normal((dim_x, dim_x))
        Q = q * (B @ B.T / dim_x + 0.1 * np.eye(dim_x))
        C = rng.standard_normal((dim_z, dim_z))
        R = r * (C @ C.T / dim_z + 0.5 * np.eye(dim_z))
        return cls(F, H, Q, R)

    def fx(self, x, dt=None, **fx_args):
        """``F x`` for one state ``(dim_x,)`` or rows ``(n, dim_x)``."""
        return np.asarray(x) @ self.F.T

    def hx(self, x, **hx_args):
        """``H x`` for one state ``(dim_x,)`` or rows ``(n, dim_x)``."""
        return np.asarray(x) @ self.H.T

    def FJacobian(self, x, dt=None, **fx_args):
        return self.F

    def HJacobian(self, x, **hx_args):
        return self.H

    def kalman_filter(self):
        """A filterpy ``KalmanFilter`` set up on this model (the reference answer)."""
        from filterpy.kalman import KalmanFilter

        kf = KalmanFilter(dim_x=self.dim_x, dim_z=self.dim_z)
        kf.F, kf.H, kf.Q, kf.R = self.F.copy(), self.H.copy(), self.Q.copy(), self.R.copy()
        kf.x, kf.P = self.x0.copy(), self.P0.copy()
        return kf
