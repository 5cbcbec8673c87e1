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

A model wires itself into a filter in one place: :func:`from_model` builds any filter whose
constructor speaks filterpy's names (``dim_x, dim_z, dt, hx, fx``, the Jacobians,
``residual_z``, ...) from the model, and :func:`wire` copies the start ``x0, P0`` and the
noise ``Q, R`` (and ``F``/``H`` where both have them) onto a filter already built.

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
>>> from filterpy.kalman import UnscentedKalmanFilter
>>> from filterwnn.kalman import make_points
>>> ukf = from_model(UnscentedKalmanFilter, m, points=make_points("merwe", 3))
>>> np.array_equal(ukf.Q, m.Q), ukf.fx == m.fx, ukf.x is m.x0
(True, True, False)
"""

from __future__ import annotations

import inspect

import numpy as np
from scipy.special import gammaln

from ._validation import as_state, check_covariance, check_positive, check_positive_int, check_rng

__all__ = ["StateSpaceModel", "LinearGaussianModel", "GammaNoiseModel", "from_model", "wire"]

#: What :func:`from_model` hands to a filter's constructor, where the constructor names it.
MODEL_ARGUMENTS = ("dim_x", "dim_z", "dt", "hx", "fx", "FJacobian", "HJacobian", "residual_z", "z_mean_fn",
                   "process_sampler", "transition_logpdf")
#: The matrices :func:`wire` copies onto a filter that has them (filterpy's ``KalmanFilter``, EKF).
MODEL_MATRICES = ("F", "H")


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

        return from_model(KalmanFilter, self)


class GammaNoiseModel(StateSpaceModel):
    """The scalar benchmark of van der Merwe, Doucet, de Freitas and Wan (2000).

    *The unscented particle filter* (CUED/F-INFENG/TR 380), sec. 6: a peaked likelihood and
    non-Gaussian (gamma) process noise,

    ``x_k = 1 + sin(omega pi (k - 1)) + phi1 x_{k-1} + v_{k-1}``, ``v ~ Gamma(shape, scale)``,

    ``z_k = phi2 x_k^2 + n_k`` for ``k <= switch``, ``phi3 x_k - 2 + n_k`` after, ``n_k ~ N(0, R)``.

    The paper's Gamma(3, 2) is shape 3 and *rate* 2 (``scale = 0.5``): mean 1.5 and variance
    3/4, the Q = 3/4 its Kalman filters use. The Kalman-type filters and proposals see the
    moment-matched model (``fx`` adds the noise mean, ``Q`` is its variance); the particle
    weights use the exact gamma density (:meth:`transition_logpdf`, :meth:`process_sampler`).

    Every function takes the step ``k`` as a keyword (``predict(k=k)``, ``update(z, k=k)``)
    and works on one state ``(1,)`` or on rows ``(n, 1)`` (``vectorized=True`` filters).

    Parameters
    ----------
    omega, phi1, phi2, phi3 : float
    shape, scale : float
        Gamma process noise.
    R : float
        Measurement noise variance (stored as the ``(1, 1)`` matrix ``R``, filterpy's name).
    n_steps, switch : int
        Length of a run and the last step of the quadratic measurement.
    x0, P0 : float
        Initial state and the filters' initial variance (stored as ``(1,)`` and ``(1, 1)``).

    >>> m = GammaNoiseModel()
    >>> float(m.Q[0, 0]), float(m.noise_mean)
    (0.75, 1.5)
    >>> xs, zs = m.simulate(rng=0)
    >>> xs.shape, zs.shape
    ((60, 1), (60, 1))
    """

    dim_x = 1
    dim_z = 1
    dt = 1.0

    def __init__(self, omega=0.04, phi1=0.5, phi2=0.2, phi3=0.5, shape=3.0, scale=0.5, R=1e-5, n_steps=60,
                 switch=30, x0=1.0, P0=0.75):
        self.omega, self.phi1, self.phi2, self.phi3 = (float(v) for v in (omega, phi1, phi2, phi3))
        self.shape = check_positive(shape, "shape")
        self.scale = check_positive(scale, "scale")
        self.n_steps = check_positive_int(n_steps, "n_steps")
        self.switch = int(switch)
        self.x0 = np.array([float(x0)])
        self.P0 = np.array([[check_positive(P0, "P0")]])
        self.noise_mean = self.shape * self.scale
        self.Q = np.array([[self.shape * self.scale**2]])
        self.R = np.array([[check_positive(R, "R")]])

    def _drift(self, x_prev, k):
        return 1.0 + np.sin(self.omega * np.pi * (k - 1)) + self.phi1 * np.asarray(x_prev, dtype=float)

    def fx(self, x, dt=None, k=1, **fx_args):
        """Mean of ``x_k`` given ``x_{k-1} = x`` (the gamma noise's mean included)."""
        return self._drift(x, k) + self.noise_mean

    def FJacobian(self, x, dt=None, k=1, **fx_args):
        """``phi1``: ``(1, 1)`` for one state, ``(n, 1, 1)`` for rows."""
        return np.full(np.shape(x) + (1,), self.phi1)

    def hx(self, x, k=1, **hx_args):
        x = np.asarray(x, dtype=float)
        return self.phi2 * x**2 if k <= self.switch else self.phi3 * x - 2.0

    def HJacobian(self, x, k=1, **hx_args):
        x = np.asarray(x, dtype=float)
        slope = 2.0 * self.phi2 * x if k <= self.switch else np.full_like(x, self.phi3)
        return slope[..., None]

    def process_sampler(self, x_prev, rng, k=1):
        """An exact draw of ``x_k`` given rows ``x_prev`` (the particle filters' ``process_sampler``)."""
        return self._drift(x_prev, k) + rng.gamma(self.shape, self.scale, size=np.shape(x_prev))

    def transition_logpdf(self, x, x_prev, k=1):
        """Exact ``log p(x_k | x_{k-1})`` per row, ``-inf`` off the gamma's support."""
        v = (np.asarray(x, dtype=float) - self._drift(x_prev, k))[..., 0]
        out = np.full(v.shape, -np.inf)
        pos = v > 0
        out[pos] = ((self.shape - 1) * np.log(v[pos]) - v[pos] / self.scale - gammaln(self.shape)
                    - self.shape * np.log(self.scale))
        return out

    def simulate(self, n_steps=None, rng=None, x0=None):
        """A ground-truth run ``(xs, zs)`` of shapes ``(n_steps, 1)``, steps ``k = 1..n_steps``."""
        n_steps = self.n_steps if n_steps is None else check_positive_int(n_steps, "n_steps")
        rng = check_rng(rng)
        x = self.x0.copy() if x0 is None else as_state(x0, "x0", 1)
        xs, zs = np.empty((n_steps, 1)), np.empty((n_steps, 1))
        for k in range(1, n_steps + 1):
            x = self.process_sampler(x, rng, k)
            xs[k - 1] = x
            zs[k - 1] = self.hx(x, k) + np.sqrt(self.R[0, 0]) * rng.standard_normal(1)
        return xs, zs

    def particle_filter(self, cls, n_particles, rng=None, **kwargs):
        """A particle filter of class ``cls`` (one of :mod:`filterwnn.monte_carlo.particle_filter`'s presets)
        set up on this model: vectorized, exact gamma weights, ``x``/``P``/``Q``/``R`` set.

        Run it with ``pf.predict(k=k); pf.update(z, k=k)`` for ``k = 1..n_steps``, or
        :meth:`run`.
        """
        return from_model(cls, self, n_particles=n_particles, vectorized=True, rng=rng, **kwargs)

    def run(self, pf, zs):
        """Filter ``zs`` (steps ``1..len(zs)``) with ``pf``; returns the means, shape ``(len(zs), 1)``."""
        zs = np.asarray(zs, dtype=float).reshape(-1, 1)
        means = np.empty_like(zs)
        for k, z in enumerate(zs, start=1):
            pf.predict(k=k)
            pf.update(z, k=k)
            means[k - 1] = pf.x
        return means


# --------------------------------------------------------------------------- wiring


def _model_value(model, name):
    """``model.name``, or None where the model lacks it or only inherits the base class's placeholder."""
    value = getattr(model, name, None)
    placeholder = getattr(StateSpaceModel, name, None)
    if placeholder is not None and callable(placeholder) and getattr(type(model), name, None) is placeholder:
        return None
    return value


def wire(filt, model, *, x0=None, P0=None, Q=None, R=None):
    """Copy a model's start and noise onto a filter: ``x, P, Q, R`` (and ``F``, ``H``).

    Every value is a fresh float array, so the filter never shares (and never changes) the
    model's. ``F`` and ``H`` are copied where the model has them and the filter has the
    attribute (filterpy's ``KalmanFilter``; ``F`` of its ``ExtendedKalmanFilter``).

    Parameters
    ----------
    filt : filter
        Any filter with filterpy's attributes ``x, P, Q, R`` (filterpy's, this package's
        unscented, particle and Gaussian-sum filters).
    model : StateSpaceModel
        Anything with ``dim_x, dim_z, x0, P0, Q, R``.
    x0 : array-like of shape (dim_x,), optional
        A start other than ``model.x0`` (checked: finite, of length ``dim_x``).
    P0, Q, R : array-like, optional
        Covariances other than the model's (checked; ``Q`` may be singular).

    Returns
    -------
    filt
        The same filter, wired.
    """
    n = model.dim_x
    for name in MODEL_MATRICES:
        value = getattr(model, name, None)
        if value is not None and hasattr(filt, name):
            setattr(filt, name, np.array(value, dtype=float))
    filt.x = np.array(model.x0 if x0 is None else as_state(x0, "x0", n), dtype=float)
    filt.P = np.array(model.P0 if P0 is None else check_covariance(P0, "P0", n), dtype=float)
    filt.Q = np.array(model.Q if Q is None else check_covariance(Q, "Q", n, require_pd=False), dtype=float)
    filt.R = np.array(model.R if R is None else check_covariance(R, "R", model.dim_z), dtype=float)
    return filt


def from_model(cls, model, *, x0=None, P0=None, Q=None, R=None, **kwargs):
    """A filter of class ``cls`` built from ``model`` and wired to it (:func:`wire`).

    The constructor gets, of ``MODEL_ARGUMENTS`` (``dim_x, dim_z, dt, hx, fx``, the
    Jacobians, ``residual_z``, ``z_mean_fn``, ``process_sampler``, ``transition_logpdf``),
    those it names and the model has, as keywords; ``kwargs`` go to it too and win, so
    ``fx=None`` asks for a random walk (and then the model's ``FJacobian`` is not passed) and
    ``points=...``, ``n_particles=...`` are the filter's own settings. A model that only
    inherits :class:`StateSpaceModel`'s ``residual_z`` passes none (the filter's default
    subtraction). filterpy's own constructors stay as they are: this is a function beside them.

    Parameters
    ----------
    cls : type
        E.g. filterpy's ``KalmanFilter``, ``ExtendedKalmanFilter`` or ``UnscentedKalmanFilter``,
        :class:`~filterwnn.kalman.unscented.UnscentedKalmanFilter`, a particle filter of
        :mod:`filterwnn.monte_carlo.particle_filter` or the Gaussian-sum filter.
    model : StateSpaceModel
    x0, P0, Q, R : array-like, optional
        Passed to :func:`wire`.
    **kwargs
        The constructor's other arguments.

    Returns
    -------
    filt : cls
    """
    params = inspect.signature(cls).parameters
    for name in MODEL_ARGUMENTS:
        if name in params and name not in kwargs:
            value = _model_value(model, name)
            if value is not None and not (name == "FJacobian" and kwargs.get("fx", True) is None):
                kwargs[name] = value
    return wire(cls(**kwargs), model, x0=x0, P0=P0, Q=Q, R=R)
