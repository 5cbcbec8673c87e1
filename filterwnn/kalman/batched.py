r"""The batched Kalman step: predict and update N Gaussians at once (EKF, UKF, SUKF).

Every Gaussian :math:`N(x_i, P_i)`, ``x (N, n)``, ``P (N, n, n)``, takes one Kalman step
in a few stacked NumPy calls: one :func:`numpy.linalg.cholesky` factors every covariance,
:func:`~filterwnn.kalman.sigma_points.batched_sigma_points` builds all sigma points in
O(n^2) each from the set's structure, and with ``vectorized=True`` the model is called
*once* on all ``N * n_sigmas`` points (one row per point). A long stack of small states
(``filterwnn._linalg.columns_layout``: ``n <= 8``, ``N >= 256``, where it measured faster)
takes the column path instead: the factors by ``filterwnn._linalg.cholesky_columns``
(the member axis last, a few length-N vector operations per entry), the sigma points
``x + Z L^T`` as one BLAS product per state component; the numbers agree with the LAPACK
path to rounding (the tests pin both to filterpy at 1e-12), and so do the errors.

Predict (unscented): :math:`x^-_i = \sum_j W^m_j f(\chi_{ij})`,
:math:`P^-_i = \sum_j W^c_j (f(\chi_{ij}) - x^-_i)(\cdot)^T + Q`; (extended):
:math:`x^-_i = f(x_i)`, :math:`P^-_i = F_i P_i F_i^T + Q`. ``fx=None`` is a random walk,
:math:`x^- = x`, :math:`P^- = P + Q`.

Update with fresh sigma points of :math:`(x^-_i, P^-_i)` (as filterpy 2.0's UKF), or the
Jacobian :math:`H_i` (extended):

.. math::
    S_i = P_{yy,i} + R, \quad K_i = P_{xy,i} S_i^{-1}, \quad
    \hat x_i = x^-_i + K_i (z_i - \hat z_i), \quad \hat P_i = P^-_i - K_i S_i K_i^T ,

and the innovation log-likelihood :math:`\log N(z_i; \hat z_i, S_i)`. With
``dim_z == 1`` the gain needs no solve and :math:`\hat P = P^- - P_{xy} P_{xy}^T / S`
(a rank-1 downdate, exactly symmetric). ``z`` is one measurement shared by every member,
``(dim_z,)``, or one per member, ``(N, dim_z)``; ``mask (N,)`` (True: observed) leaves the
unobserved members at their prediction, with a zero log-likelihood.

``Q`` and ``R`` are ``(n, n)`` shared or ``(N, n, n)`` per member (the model's when not
given). The proposals of :mod:`filterwnn.monte_carlo.proposals`, the Gaussian-sum filter
and the filter banks of :mod:`filterwnn.kalman.bank` all run this step.

>>> import numpy as np
>>> from filterwnn.kalman.presets import make_points
>>> model = KalmanModel(2, 1, dt=1.0, fx=None, hx=lambda X: X[:, :1] ** 2,
...                     Q=0.01 * np.eye(2), R=np.array([[0.1]]), vectorized=True)
>>> step = UnscentedStep(make_points("merwe", 2))   # Merwe's set, alpha 1, beta 2, kappa 0
>>> pred = step.predict(model, np.ones((3, 2)), np.tile(np.eye(2), (3, 1, 1)))
>>> upd = step.update(model, pred, np.array([[1.2], [0.9], [1.0]]))
>>> upd.x.shape, upd.P.shape, upd.log_likelihood.shape
((3, 2), (3, 2, 2), (3,))
>>> skip = step.update(model, pred, np.array([[1.2], [0.9], [1.0]]), mask=[True, False, True])
>>> bool(np.all(skip.x[1] == pred.x[1])), float(skip.log_likelihood[1])
(True, 0.0)

References
----------
S. J. Julier and J. K. Uhlmann, "A new extension of the Kalman filter to nonlinear
systems", SPIE 3068, 1997 (the unscented step).
R. van der Merwe, A. Doucet, N. de Freitas and E. Wan, "The unscented particle filter",
CUED/F-INFENG/TR 380, 2000 (one such step per particle).
"""

from __future__ import annotations

import warnings
from functools import cached_property
from typing import NamedTuple, Optional

import numpy as np
from scipy.linalg import solve_triangular

from .._linalg import COLUMNS_MAX_N, LOG_2PI, NoiseFactor, cholesky, columns_layout, repair_pd, solve_lower_columns
from .._validation import NumericalError, check_covariance, check_points_protocol, check_symmetric
from . import _compiled
from ._rowcheck import CALL_ERRORS, on_single_rows, one_point_error, rows_differ
from .sigma_points import batched_sigma_points, unit_sigma_points, unit_transpose_apply

__all__ = [
    "KalmanModel",
    "KalmanPrediction",
    "KalmanUpdate",
    "UnscentedStep",
    "ExtendedStep",
    "LinearStep",
    "batched_step",
    "finish_update",
]


# ---------------------------------------------------------------------------
# Calling the model on rows
# ---------------------------------------------------------------------------


def apply_rows(f, X, out_dim, vectorized, name, args=(), kwargs=None, checked=None):
    """``f`` on every row of ``X (m, n)`` -> ``(m, out_dim)``; one call when vectorized.

    Parameters
    ----------
    f : callable
        ``f(X, *args, **kwargs)`` on all rows at once when ``vectorized``, else ``f(x, ...)``
        on one row ``x (n,)``.
    X : ndarray of shape (m, n)
    out_dim : int
        Length of each output row.
    vectorized : bool
    name : str
        The model function's name (``"fx"``, ``"hx"``), used in the error messages.
    args : tuple, optional
    kwargs : dict, optional
    checked : dict, optional
        ``{name: function}`` of the functions already checked (a model's
        :attr:`KalmanModel.rows_checked`): a vectorized ``f`` not in it is compared, on this
        first call, with ``f`` on a few single rows (:mod:`filterwnn.kalman._rowcheck`).

    Returns
    -------
    ndarray of shape (m, out_dim)

    Raises
    ------
    ValueError
        If ``f`` returns the wrong number of values (checked on the first row in the loop),
        or, on its first vectorized call, if it is written for one point: the message names
        it, says what differed and shows the fix.
    """
    kwargs = {} if kwargs is None else kwargs
    if vectorized:
        return _apply_vectorized(f, X, out_dim, name, args, kwargs, checked)
    return _apply_loop(f, X, out_dim, name, args, kwargs)


def _apply_vectorized(f, X, out_dim, name, args, kwargs, checked):
    """:func:`apply_rows` with ``vectorized=True``: one call, its shape checked, and on the
    first call of ``f`` (not yet in ``checked``) its rows compared with single-row calls."""
    m = X.shape[0]
    first = checked is not None and checked.get(name) is not f
    try:
        Y = np.asarray(f(X, *args, **kwargs), dtype=float)
    except CALL_ERRORS as exc:
        if first and on_single_rows(f, X, [0], out_dim, args, kwargs) is not None:
            raise one_point_error(name, f"on all {m} points it raised {type(exc).__name__}: {exc}") from exc
        raise
    if Y.size != m * out_dim:
        if first and on_single_rows(f, X, [0], out_dim, args, kwargs) is not None:  # (stop 69: as the UKF says)
            raise one_point_error(name, f"on all {m} points it returned shape {Y.shape}, not ({m}, {out_dim})")
        raise ValueError(
            f"{name} with vectorized=True must return one row per point, shape "
            f"({m}, {out_dim}), got shape {Y.shape}"
        )
    Y = Y.reshape(m, out_dim)
    if first and np.isfinite(Y).all():  # non-finite output: the step's own check names it first
        detail = rows_differ(Y, X, f, args, kwargs)
        if detail is not None:
            raise one_point_error(name, detail)
        checked[name] = f
    return Y


def _apply_loop(f, X, out_dim, name, args, kwargs):
    """:func:`apply_rows` with ``vectorized=False``: ``f`` once per row, the first row's
    output checked fully, the rest assigned without per-call checks (the hot loop)."""
    m = X.shape[0]
    Y = np.empty((m, out_dim))
    if m == 0:
        return Y
    y0 = np.asarray(f(X[0], *args, **kwargs), dtype=float)
    if y0.size != out_dim:
        raise ValueError(f"{name} must return {out_dim} values, got shape {y0.shape}")
    Y[0] = y0.reshape(out_dim)
    try:
        for i in range(1, m):
            Y[i] = f(X[i], *args, **kwargs)
    except ValueError as exc:
        raise ValueError(f"{name} must return {out_dim} values for every point: {exc}") from exc
    return Y


def _residual(fn, a, b, vectorized):
    """``fn(a, b)`` broadcasting ``b`` against ``a (..., d)``; ``a - b`` when ``fn`` is None.

    Deviations from a mean, ``a (N, S, d)`` less ``b (N, 1, d)``: ``b`` is first repeated
    along each row by one BLAS product with ``[I I ... I]`` (exact: one unit term per
    entry), so that the subtraction runs over rows of ``S d`` values; the broadcast ran
    NumPy's inner loop over ``d`` only (the bank step 0.88-0.95x the time at B = 1,000,
    paired runs; unchanged at 10,000).
    """
    if fn is None or fn is np.subtract:
        if a.ndim == 3 and np.shape(b) == (a.shape[0], 1, a.shape[2]) and a.flags.c_contiguous:
            N, S, d = a.shape
            rows = np.matmul(b[:, 0, :], _repeater(d, S))
            return np.subtract(a.reshape(N, S * d), rows, out=rows).reshape(N, S, d)
        return a - b
    if vectorized:
        return np.asarray(fn(a, b), dtype=float).reshape(np.broadcast_shapes(np.shape(a), np.shape(b)))
    a, b = np.broadcast_arrays(a, b)
    d = a.shape[-1]
    A, B = a.reshape(-1, d), b.reshape(-1, d)
    out = np.array([fn(A[i], B[i]) for i in range(A.shape[0])], dtype=float)
    return out.reshape(a.shape)


_REPEATERS = {}  # (d, S) -> [I I ... I], read-only


def _repeater(d, S):
    """``np.tile(np.eye(d), S)``, ``(d, S * d)``, made once per shape (read-only)."""
    E = _REPEATERS.get((d, S))
    if E is None:
        E = np.tile(np.eye(d), S)
        E.flags.writeable = False
        _REPEATERS[(d, S)] = E
    return E


def _weighted_mean(fn, pts, W):
    """Weighted mean of ``pts (N, S, d)`` over axis 1 -> ``(N, d)``, or ``fn(pts_i, W)``."""
    if fn is None:
        return np.matmul(W, pts)
    return np.array([np.asarray(fn(p, W), dtype=float).reshape(pts.shape[-1]) for p in pts])


def _times_weights(d, W):
    """``d (N, S, k)`` times the sigma weights ``W (S,)`` along axis 1, computed on the
    ``(N, S * k)`` view: NumPy's inner loop then runs over ``S * k`` values, not ``k``
    (a ``W[:, None]`` broadcast; about 2.5x faster for ``k = 6``, ``N = 1,000``)."""
    N, S, k = d.shape
    return (d.reshape(N, S * k) * np.repeat(W, k)).reshape(N, S, k)


def _jacobians(J, X, shape, vectorized, name, args, kwargs):
    """Jacobians at every row of ``X (N, n)`` -> ``(N,) + shape``.

    Vectorized: one call ``J(X, ...)`` returning ``(N,) + shape`` (or ``shape``, the same
    for every row). Otherwise one call per row.
    """
    N = X.shape[0]
    if vectorized:
        out = np.asarray(J(X, *args, **kwargs), dtype=float)
        if out.shape == shape:
            return np.broadcast_to(out, (N,) + shape)
        if out.size != N * int(np.prod(shape)):
            raise ValueError(f"{name} must return shape {(N,) + shape} or {shape}, got {out.shape}")
        return out.reshape((N,) + shape)
    out = np.empty((N,) + shape)
    for i in range(N):
        Ji = np.asarray(J(X[i], *args, **kwargs), dtype=float)
        if Ji.size != int(np.prod(shape)):
            raise ValueError(f"{name} must return shape {shape}, got {Ji.shape}")
        out[i] = Ji.reshape(shape)
    return out


def noise_matrix(M, name, dim):
    """A noise covariance as a float ``(dim, dim)`` array (a scalar means ``M * I``).

    ``name`` (``"Q"``, ``"R"``) is named in the ``ValueError`` raised for a wrong shape or a
    non-finite entry. Symmetry and definiteness are the caller's to check.
    """
    M = np.asarray(M, dtype=float)
    if M.ndim == 0:
        M = float(M) * np.eye(dim)
    elif M.size == dim * dim:
        M = M.reshape(dim, dim)
    else:
        raise ValueError(f"{name} must have shape ({dim}, {dim}), got shape {M.shape}")
    if not np.all(np.isfinite(M)):
        raise ValueError(f"{name} must be finite, got non-finite entries")
    return M


def solve_lower(L, B):
    """``L^{-1} B`` for stacked lower-triangular ``L (N, n, n)`` and ``B (N, n, m)``.

    Forward substitution vectorized over the stack (``n`` small steps) for small ``n``,
    where scipy's batched ``solve_triangular`` (a Python loop over the stack) is slow;
    scipy's for large ``n``. A stack that ``filterwnn._linalg.columns_layout`` factors by
    columns is solved by columns (``solve_lower_columns``, the member axis last).
    """
    N, n, m = B.shape
    if columns_layout(N, n):
        X = solve_lower_columns(L.transpose(1, 2, 0), np.ascontiguousarray(B.transpose(1, 2, 0)))
        return X.transpose(2, 0, 1)
    if n > 64:
        return solve_triangular(L, B, lower=True, check_finite=False)
    X = np.empty(B.shape)
    for j in range(n):
        r = B[:, j, :]
        if j:
            r = r - np.matmul(L[:, j : j + 1, :j], X[:, :j, :])[:, 0, :]
        X[:, j, :] = r / L[:, j, j][:, None]
    return X

def check_callable(f, name, allow_none=True):
    """``f`` when it is callable (or None where allowed), else ``TypeError`` naming ``name``."""
    if f is None and allow_none:
        return None
    if not callable(f):
        raise TypeError(f"{name} must be callable{' or None' if allow_none else ''}, got {type(f).__name__}")
    return f


# ---------------------------------------------------------------------------
# The model side of a Kalman step
# ---------------------------------------------------------------------------


_FLOAT64 = np.dtype(np.float64)  # native float64 (another byte order takes the array_equal path)


class KalmanModel:
    """What a batched Kalman step uses of a state-space model: a small object, not a filter.

    Parameters
    ----------
    dim_x, dim_z : int
    dt : float
        Passed to ``fx`` as ``fx(x, dt, **fx_args)``.
    fx : callable or None
        Transition mean (``None``: a random walk).
    hx : callable
        Measurement function.
    Q, R : array-like of shape (dim_x, dim_x) and (dim_z, dim_z), or scalars
        Process and measurement noise (``Q`` may be singular). Each is checked and
        factored once, again only when it changes (:meth:`noise`).
    vectorized : bool
        The callables take one 2-D array, one row per point.
    FJacobian, HJacobian, x_mean_fn, z_mean_fn, residual_x, residual_z : callable, optional
        As in filterpy's ``UnscentedKalmanFilter`` and ``ExtendedKalmanFilter``.
    recover : bool
        Repair a non-PD covariance (with a warning) instead of raising, where a caller
        runs the step through ``repairing``.

    Attributes are plain and may be reassigned.
    """

    def __init__(self, dim_x, dim_z, dt=1.0, fx=None, hx=None, Q=None, R=None, *, vectorized=False,
                 FJacobian=None, HJacobian=None, x_mean_fn=None, z_mean_fn=None, residual_x=None,
                 residual_z=None, recover=False):
        self.dim_x, self.dim_z, self.dt = dim_x, dim_z, dt
        self.fx, self.hx = fx, hx
        self.Q = np.eye(dim_x) if Q is None else Q
        self.R = np.eye(dim_z) if R is None else R
        self.vectorized = vectorized
        self.FJacobian, self.HJacobian = FJacobian, HJacobian
        self.x_mean_fn, self.z_mean_fn = x_mean_fn, z_mean_fn
        self.residual_x, self.residual_z = residual_x, residual_z
        self.recover = recover
        self._factors = {}

    def noise(self, name, check=True):
        """The ``NoiseFactor`` (the checked Cholesky factor, in ``filterwnn._linalg``) of ``"Q"`` or ``"R"``.

        Validated (shape, finite, symmetric; ``Q`` positive semi-definite, ``R`` positive
        definite) and factored when the matrix changed since the last call, else cached.
        ``check=False`` trusts the cache without comparing (inside one filter step, after
        the filter's own check).
        """
        M = getattr(self, name)
        hit = self._factors.get(name)
        if hit is not None:
            if not check:
                return hit[1]
            if type(M) is np.ndarray and M.dtype is _FLOAT64:  # the usual case: compare the bytes
                if M.shape == hit[0].shape and M.tobytes() == hit[2]:
                    return hit[1]
            elif np.shape(M) == hit[0].shape and np.array_equal(hit[0], M):
                return hit[1]
        dim = self.dim_x if name == "Q" else self.dim_z
        A = check_symmetric(noise_matrix(M, name, dim), name)
        if name == "R":
            check_covariance(A, "R", dim)
        factor = NoiseFactor(A, name)
        kept = np.array(M, dtype=float, copy=True)
        self._factors[name] = (kept, factor, kept.tobytes())
        return factor

    # --- the model on rows -------------------------------------------------------------
    def transition_mean(self, x_prev, fx_args):
        """``fx(x_prev)`` on every row -> ``(N, dim_x)`` (``x_prev`` for a random walk)."""
        if self.fx is None:
            return x_prev
        return apply_rows(self.fx, x_prev, self.dim_x, self.vectorized, "fx", (self.dt,), fx_args,
                          self.rows_checked)

    def measure(self, X, hx_args):
        """``hx`` on every row -> ``(N, dim_z)``."""
        return apply_rows(self.hx, X, self.dim_z, self.vectorized, "hx", (), hx_args, self.rows_checked)

    @property
    def rows_checked(self):
        """``{name: function}``: the vectorized model functions whose first call was checked
        row by row (``apply_rows``); a function assigned later is checked again."""
        checked = self.__dict__.get("_rows_checked")
        if checked is None:
            checked = self._rows_checked = {}
        return checked

    def residual_x_rows(self, a, b):
        """``residual_x(a, b)`` broadcast over rows (``a - b`` by default)."""
        return _residual(self.residual_x, a, b, self.vectorized)

    def residual_z_rows(self, a, b):
        """``residual_z(a, b)`` broadcast over rows (``a - b`` by default)."""
        return _residual(self.residual_z, a, b, self.vectorized)

    def mean_x(self, X, w):
        """Weighted mean of the rows ``X (N, dim_x)`` (``x_mean_fn(X, w)`` when given)."""
        if self.x_mean_fn is None:
            return w @ X
        x = np.asarray(self.x_mean_fn(X, w), dtype=float).reshape(-1)
        if x.shape != (self.dim_x,) or not np.all(np.isfinite(x)):
            raise ValueError(f"x_mean_fn(particles, weights) must return {self.dim_x} finite values, got {x}")
        return x


# ---------------------------------------------------------------------------
# The batched step
# ---------------------------------------------------------------------------


class KalmanPrediction(NamedTuple):
    """Per-particle predicted moments.

    Attributes
    ----------
    x : ndarray of shape (n_particles, dim_x)
    P : ndarray of shape (n_particles, dim_x, dim_x)
    """

    x: np.ndarray
    P: np.ndarray


class KalmanUpdate(NamedTuple):
    r"""Per-particle Kalman update: the proposal ``N(x, P)`` and the innovation.

    Attributes
    ----------
    x : ndarray of shape (n_particles, dim_x)
        Posterior means :math:`\hat x_i`.
    P : ndarray of shape (n_particles, dim_x, dim_x)
        Posterior covariances :math:`\hat P_i`.
    z_pred : ndarray of shape (n_particles, dim_z)
        Predicted measurements :math:`\\hat y_i`.
    S : ndarray of shape (n_particles, dim_z, dim_z)
        Innovation covariances.
    Pxy : ndarray of shape (n_particles, dim_x, dim_z)
        Cross covariances.
    log_likelihood : ndarray of shape (n_particles,)
        :math:`\log N(y; \hat y_i, S_i)` (the bank weight).
    L_prior : ndarray of shape (n_particles, dim_x, dim_x) or None
        Lower Cholesky factors ``L_i`` of the predicted covariances, when computed.
    LinvPxy : ndarray of shape (n_particles, dim_x, dim_z) or None
        :math:`L_i^{-1} P_{xy,i}` when known without a solve (unscented:
        :math:`Z^T (W_c \circ \Delta Y)`, since :math:`P_{xy} = L Z^T (W_c \circ \Delta Y)`).
    H : ndarray of shape (n_particles, dim_z, dim_x) or None
        Measurement Jacobians (extended): :math:`L^{-1} P_{xy} = L^T H^T`.
    """

    x: np.ndarray
    P: np.ndarray
    z_pred: np.ndarray
    S: np.ndarray
    Pxy: np.ndarray
    log_likelihood: np.ndarray
    L_prior: Optional[np.ndarray]
    LinvPxy: Optional[np.ndarray] = None
    H: Optional[np.ndarray] = None


def _as_z(z, N, m):
    """A measurement shared by every member ``(m,)`` -> ``(1, m)``; one per member stays ``(N, m)``."""
    z = np.asarray(z, dtype=float)
    if z.ndim == 1:
        return z[None, :]
    if z.shape != (N, m):
        raise ValueError(f"z must have shape ({m},) (shared) or ({N}, {m}) (one per member), got shape {z.shape}")
    return z


def finish_update(model, x_prior, P_prior, z, z_pred, S, Pxy, L_prior, step, LinvPxy=None, H=None, R=None,
                  rhs=None):
    r"""Gain, posterior and innovation likelihood from the batched moments -> :class:`KalmanUpdate`.

    ``S`` is the predicted measurement spread *without* ``R``; ``z`` is ``(dim_z,)`` or
    ``(N, dim_z)``; ``R`` is ``(dim_z, dim_z)`` or ``(N, dim_z, dim_z)`` (the model's by
    default). With ``dim_z > 1`` one Cholesky factor :math:`S = L_S L_S^T` and one forward
    substitution give :math:`G = L_S^{-1} P_{xy}^T` and :math:`e = L_S^{-1} y`, and then
    :math:`\hat x = x^- + G^T e`, :math:`\hat P = P^- - G^T G` (exactly symmetric) and
    :math:`\log N = -\tfrac12 |e|^2 - \sum \log L_{S,jj} - \tfrac m2 \log 2\pi`.
    ``rhs`` (from a caller on the column path, ``_cross_columns``) is that solve's
    right-hand side ``(dim_z, n + 1, N)`` with :math:`P_{xy}^T` already in ``[:, :n]``
    (``Pxy`` a view of it).
    """
    R = noise_matrix(model.R, "R", model.dim_z) if R is None else R
    S = S + R
    y = _residual(model.residual_z, _as_z(z, x_prior.shape[0], model.dim_z), z_pred, model.vectorized)
    if model.dim_z == 1:
        s = S[:, 0, 0]
        if not np.all(s > 0) or not np.all(np.isfinite(s)):
            raise NumericalError(f"S is not positive at step {step} (min {np.min(s):.3g})", matrix="S", step=step)
        pxy = Pxy[:, :, 0]
        x = x_prior + pxy * (y / s[:, None])
        # rank-1 downdate with v v^T, v = Pxy / sqrt(S): exactly symmetric, no extra pass
        v = pxy / np.sqrt(s)[:, None]
        P = v[:, :, None] * v[:, None, :]
        np.subtract(P_prior, P, out=P)
        loglik = -0.5 * (y[:, 0] ** 2 / s + np.log(s) + LOG_2PI)
        return KalmanUpdate(x, P, z_pred, S, Pxy, loglik, L_prior, LinvPxy, H)
    Ls = cholesky(S, "S", step)
    N, n = x_prior.shape
    m = model.dim_z
    if rhs is None:
        rhs = np.empty((m, n + 1, N))  # member axis last: one long vector operation per entry
        rhs[:, :n] = Pxy.transpose(2, 1, 0)
    rhs[:, n] = y.T
    E = solve_lower_columns(Ls.transpose(1, 2, 0), rhs)  # [L_S^{-1} Pxy^T | L_S^{-1} y]
    G, e = E[:, :n], E[:, n]
    x = x_prior + np.einsum("kib,kb->ib", G, e).T  # (G * e[:, None]).sum(axis=0).T's sums, no temporary
    GtG = G[0, :, None] * G[0]
    for k in range(1, m):
        GtG += G[k, :, None] * G[k]
    P = P_prior - GtG.transpose(2, 0, 1)
    log_det = np.sum(np.log(np.diagonal(Ls, axis1=1, axis2=2)), axis=1)
    loglik = -0.5 * np.sum(e * e, axis=0) - log_det - 0.5 * m * LOG_2PI
    return KalmanUpdate(x, P, z_pred, S, Pxy, loglik, L_prior, LinvPxy, H)


def _cross_columns(L, LinvPxy):
    """``P_xy = L (L^{-1} P_xy)`` for factors ``L (N, n, n)`` stored member axis last, written
    into the right-hand side of :func:`finish_update`'s solve, ``rhs (m, n + 1, N)``, as
    :math:`P_{xy}^T` in ``rhs[:, :n]`` -> ``(Pxy (N, n, m), a view; rhs)``.

    One ``einsum`` over the member axis (the products summed over ``j`` in order) in place
    of a batched product of small matrices and a transposed copy: NumPy 1.x's ``np.matmul``
    numbers bit for bit; NumPy 2.x's batched product goes through BLAS (fused multiply-adds),
    so there the two differ in the last bit (the bank's agreement with filterpy's UKF, 1e-12,
    is tested).
    """
    N, n, m = LinvPxy.shape
    rhs = np.empty((m, n + 1, N))
    np.einsum("ijb,jkb->kib", L.transpose(1, 2, 0), np.ascontiguousarray(LinvPxy.transpose(1, 2, 0)),
              out=rhs[:, :n])
    return rhs[:, :n].transpose(2, 1, 0), rhs


def _observed(mask, N):
    """The observed members' indices from ``mask (N,)`` (None: every member observed)."""
    if mask is None:
        return None
    mask = np.asarray(mask)
    if mask.shape != (N,) or mask.dtype != bool:
        raise ValueError(f"mask must be a boolean array of shape ({N},) (True: observed), got "
                         f"{mask.dtype} of shape {mask.shape}")
    return None if mask.all() else np.flatnonzero(mask)


def _take(a, idx):
    """Rows ``idx`` of a per-member stack; a shared ``(d, d)`` matrix as it is."""
    return a if a is None or np.ndim(a) < 3 else a[idx]


def _scatter(prediction, idx, sub):
    """A full :class:`KalmanUpdate` from the observed members' ``sub``: the others keep their
    prediction, NaN innovation moments and a zero log-likelihood (factors not kept)."""
    xp, Pp = prediction
    N = xp.shape[0]
    x, P = np.array(xp), np.array(Pp)
    x[idx], P[idx] = sub.x, sub.P
    m = sub.z_pred.shape[1]
    z_pred = np.full((N, m), np.nan)
    S = np.full((N, m, m), np.nan)
    Pxy = np.full(Pp.shape[:2] + (m,), np.nan)
    loglik = np.zeros(N)
    z_pred[idx], S[idx], Pxy[idx], loglik[idx] = sub.z_pred, sub.S, sub.Pxy, sub.log_likelihood
    return KalmanUpdate(x, P, z_pred, S, Pxy, loglik, None)


def repairing(model, fn, C, step, what, stacklevel=5):
    """``fn(C)``; with ``model.recover`` a covariance failure repairs ``C`` once (warning
    with the step) and retries. Returns ``(result, C_used)``."""
    try:
        return fn(C), C
    except NumericalError as exc:
        if not model.recover or exc.matrix not in ("P", "P_prior") or C is None:
            raise
        C2, n_bad = repair_pd(C)
        warnings.warn(
            f"step {step}: {n_bad} particle {what} covariance(s) not positive definite ({exc}); "
            "eigenvalues clipped (recover=True)",
            RuntimeWarning,
            stacklevel=stacklevel,
        )
        return fn(C2), C2


class _Step:
    """The shared half of a batched Kalman step: ``update`` with a mask, on top of ``_update``."""

    kind = None

    def check(self, dim_x):
        """Raise ``ValueError`` when the step does not fit a ``dim_x`` state."""

    def update(self, model, prediction, z, hx_args=None, step=None, *, R=None, mask=None):
        """Batched update of every member with ``z (dim_z,)`` or ``(N, dim_z)`` -> :class:`KalmanUpdate`.

        Parameters
        ----------
        model : KalmanModel
        prediction : KalmanPrediction
            ``x (N, n)``, ``P (N, n, n)``.
        z : array-like of shape (dim_z,) or (N, dim_z)
            One measurement for every member, or one each.
        hx_args : dict, optional
        step : int, optional
            For error messages.
        R : ndarray of shape (dim_z, dim_z) or (N, dim_z, dim_z), optional
            The model's ``R`` by default.
        mask : array-like of bool, shape (N,), optional
            True where the member is observed; the others keep their prediction (their
            ``z`` rows are not read).
        """
        return self._masked(model, prediction, z, {} if hx_args is None else hx_args, step, R, mask)

    def _masked(self, model, prediction, z, arg, step, R, mask):
        xp = prediction[0]
        idx = _observed(mask, xp.shape[0])
        if idx is None:
            return self._update(model, prediction, z, arg, step, R)
        sub_pred = KalmanPrediction(xp[idx], prediction[1][idx])
        z = np.asarray(z, dtype=float)
        sub = self._update(model, sub_pred, z if z.ndim == 1 else z[idx], _take(arg, idx), step, _take(R, idx))
        return _scatter(prediction, idx, sub)


class ExtendedStep(_Step):
    """One extended Kalman step per member.

    Predict: :math:`x^-_i = f(x_i)`, :math:`P^-_i = F_i P_i F_i^T + Q` with
    ``F_i = FJacobian(x_i, dt, **fx_args)`` (random walk when ``fx`` is None). Update:
    ``H_i = HJacobian(x^-_i, **hx_args)``, :math:`P_{xy} = P^- H^T`,
    :math:`S = H P^- H^T + R`. With ``vectorized=True`` the Jacobians are called once on
    all members (``(N, dim_x)`` in, ``(N, rows, dim_x)`` or one shared matrix out).
    """

    kind = "ekf"

    def predict(self, model, x, P, fx_args=None, step=None, *, Q=None):
        """Predicted ``(x (N, n), P (N, n, n))`` from ``x (N, n)``, ``P (N, n, n)``."""
        fx_args = {} if fx_args is None else fx_args
        Q = noise_matrix(model.Q, "Q", model.dim_x) if Q is None else Q
        if model.fx is None:
            return KalmanPrediction(x.copy(), P + Q)
        n = model.dim_x
        F = _jacobians(model.FJacobian, x, (n, n), model.vectorized, "FJacobian", (model.dt,), fx_args)
        xp = apply_rows(model.fx, x, n, model.vectorized, "fx", (model.dt,), fx_args, model.rows_checked)
        Pp = np.matmul(np.matmul(F, P), np.swapaxes(F, -1, -2)) + Q
        return KalmanPrediction(xp, 0.5 * (Pp + np.swapaxes(Pp, -1, -2)))

    def _update(self, model, prediction, z, hx_args, step, R):
        xp, Pp = prediction
        n, m = model.dim_x, model.dim_z
        H = _jacobians(model.HJacobian, xp, (m, n), model.vectorized, "HJacobian", (), hx_args)
        zp = apply_rows(model.hx, xp, m, model.vectorized, "hx", (), hx_args, model.rows_checked)
        Pxy = np.matmul(Pp, np.swapaxes(H, -1, -2))
        S = np.matmul(H, Pxy)
        return finish_update(model, xp, Pp, z, zp, S, Pxy, None, step, H=H, R=R)

    def __repr__(self):
        return "ExtendedStep()"


class LinearStep(_Step):
    """One linear Kalman step per member: ``x^- = F x``, ``z = H x`` (filterpy's ``KalmanFilter``).

    ``F`` is ``(n, n)`` or ``(N, n, n)``, ``H`` ``(m, n)`` or ``(N, m, n)``, passed to each
    call; the model's ``fx``/``hx`` are not used.
    """

    kind = "kf"

    def predict(self, model, x, P, F, step=None, *, Q=None):
        """``x^- = F x``, ``P^- = F P F^T + Q`` for every member."""
        Q = noise_matrix(model.Q, "Q", model.dim_x) if Q is None else Q
        xp = np.matmul(F, x[:, :, None])[:, :, 0] if F.ndim == 3 else x @ F.T
        Pp = np.matmul(np.matmul(F, P), np.swapaxes(F, -1, -2)) + Q
        return KalmanPrediction(xp, 0.5 * (Pp + np.swapaxes(Pp, -1, -2)))

    def update(self, model, prediction, z, H, step=None, *, R=None, mask=None):
        """Batched linear update with ``H (m, n)`` or ``(N, m, n)``; ``z``, ``R``, ``mask`` as in
        :meth:`ExtendedStep.update`."""
        return self._masked(model, prediction, z, np.asarray(H, dtype=float), step, R, mask)

    def _update(self, model, prediction, z, H, step, R):
        xp, Pp = prediction
        zp = np.matmul(H, xp[:, :, None])[:, :, 0] if H.ndim == 3 else xp @ H.T
        Pxy = np.matmul(Pp, np.swapaxes(H, -1, -2))
        S = np.matmul(H, Pxy)
        H = np.broadcast_to(H, S.shape[:1] + H.shape[-2:])
        return finish_update(model, xp, Pp, z, zp, S, Pxy, None, step, H=H, R=R)

    def __repr__(self):
        return "LinearStep()"


def _own_functions(mean_fn, residual_fn):
    """True when a model has a mean or residual function of the user's (not plain subtraction)."""
    return mean_fn is not None or residual_fn not in (None, np.subtract)


class UnscentedStep(_Step):
    """One unscented Kalman step per member (UKF with Merwe points; SUKF with reduced points).

    Parameters
    ----------
    points : sigma-point object
        Any filterpy-protocol set (``n``, ``Wm``, ``Wc``, ``num_sigmas()``,
        ``sigma_points(x, P)``); Merwe, Julier and the package's staircase sets are
        built in O(n^2) per member.

    Notes
    -----
    As filterpy 2.0 does, the update draws fresh sigma points from the predicted
    ``(x^-_i, P^-_i)``; the update keeps the factor of ``P^-_i`` (``L_prior``) and
    :math:`L^{-1} P_{xy}` (``LinvPxy``), which the unscented particle filter samples with.
    """

    kind = "ukf"

    def __init__(self, points, *, compiled=False):
        check_points_protocol(points, ("n", "Wm", "Wc", "num_sigmas", "sigma_points"))
        self.points = points
        self._Z = unit_sigma_points(points)
        self.compiled = bool(compiled)

    def runs_compiled(self, n):
        """True when this step runs the compiled kernels (``filterwnn.kalman._compiled``) on a
        model with ``n`` states: ``compiled`` set and ``n <= 8``. The user's mean and residual
        functions, when given, are called in NumPy as on the NumPy step, and the kernels take
        the deviations they give."""
        return bool(self.__dict__.get("compiled")) and n <= COLUMNS_MAX_N

    def _compiled_for(self, n):
        """The compiled kernels when :meth:`runs_compiled`, else None."""
        return _compiled.kernels() if self.runs_compiled(n) else None

    @cached_property
    def _weights(self):
        """``(Wm, Wc, Z)`` as C-ordered float64 arrays, for the compiled kernels."""
        return tuple(np.ascontiguousarray(a, dtype=float) for a in (self.points.Wm, self.points.Wc, self._Z))

    def _sigmas_compiled(self, kern, x, P):
        """``(L (n, n, N), rows (N * S, n))`` by the compiled kernel, or None when a member's
        covariance is not positive definite (the NumPy path then raises its error)."""
        N, n = x.shape
        Z = self._weights[2]
        L = np.empty((n, n, N))
        sig = np.empty((n, N, Z.shape[0]))
        if kern[0](np.ascontiguousarray(x, dtype=float), np.ascontiguousarray(P, dtype=float), Z, L, sig) >= 0:
            return None
        return L, sig.transpose(1, 2, 0).reshape(N * Z.shape[0], n)  # rows member by member, a view

    @cached_property
    def _Zx(self):
        """``[Z | 1]^T`` ``(n + 1, S)``: ``x + Z L^T`` in one product (derived, so a step pickled
        before it existed still loads)."""
        return np.vstack([self._Z.T, np.ones(self._Z.shape[0])])

    def check(self, dim_x):
        """Raise ``ValueError`` unless ``points.n == dim_x``."""
        if self.points.n != dim_x:
            raise ValueError(f"points.n must equal dim_x={dim_x}, got {self.points.n}")

    def _sigmas(self, x, P, step, name):
        """Factors and sigma points of every member -> ``(L (N, n, n), sig (N, S, n))``.

        A stack that ``filterwnn._linalg.columns_layout`` factors by columns (small ``n``,
        many members) gets ``x + Z L^T`` as one matrix product per state component on the
        factors stored member axis last: ``sig`` is then a view of an ``(n, N, S)`` array
        (its ``reshape(N * S, n)`` a view too, no copy), else the C-ordered array of
        :func:`~filterwnn.kalman.sigma_points.batched_sigma_points`.
        """
        N, n = x.shape
        if not columns_layout(N, n):
            L = cholesky(P, name, step)
            return L, batched_sigma_points(self.points, x, L)
        Lx = np.zeros((n, n + 1, N))  # [L_b | x_b] per component, member axis last
        L = cholesky(P, name, step, out=Lx[:, :n])  # the factors written in place (L: a view of Lx)
        Lx[:, n] = x.T
        sig = np.matmul(Lx.transpose(0, 2, 1), self._Zx)  # (n, N, S): x_b[i] + sum_j L_b[i, j] Z[s, j]
        return L, sig.transpose(1, 2, 0)

    def predict(self, model, x, P, fx_args=None, step=None, *, Q=None):
        """Predicted ``(x (N, n), P (N, n, n))`` by the unscented transform through ``fx``."""
        fx_args = {} if fx_args is None else fx_args
        self.check(model.dim_x)
        Q = noise_matrix(model.Q, "Q", model.dim_x) if Q is None else Q
        if model.fx is None:
            return KalmanPrediction(x.copy(), P + Q)
        N, n = x.shape
        kern = self._compiled_for(n)
        if kern is not None:
            got = self._sigmas_compiled(kern, x, P)
            if got is not None:
                Wm, Wc, Z = self._weights
                F = apply_rows(model.fx, got[1], n, model.vectorized, "fx", (model.dt,), fx_args, model.rows_checked)
                F = np.ascontiguousarray(F, dtype=float).reshape(N, Z.shape[0], n)
                xp, Pp = np.empty((N, n)), np.empty((N, n, n))
                centred = _own_functions(model.x_mean_fn, model.residual_x)
                if centred:  # the user's mean and residual, called as on the NumPy step
                    xp = _weighted_mean(model.x_mean_fn, F, Wm)
                    F = np.ascontiguousarray(_residual(model.residual_x, F, xp[:, None, :], model.vectorized))
                kern[1](F, Wm, Wc, np.ascontiguousarray(Q, dtype=float).reshape(-1, n, n), xp, Pp, centred)
                return KalmanPrediction(xp, Pp)
        _, sig = self._sigmas(x, P, step, "P")
        S_ = sig.shape[1]
        F = apply_rows(model.fx, sig.reshape(N * S_, n), n, model.vectorized, "fx", (model.dt,), fx_args,
                       model.rows_checked)
        F = F.reshape(N, S_, n)
        del sig  # dead temporaries go back at once: a lower peak, fewer fresh pages per step
        Wm, Wc = self.points.Wm, self.points.Wc
        xp = _weighted_mean(model.x_mean_fn, F, Wm)
        dX = _residual(model.residual_x, F, xp[:, None, :], model.vectorized)
        del F
        Pp = np.matmul(np.swapaxes(_times_weights(dX, Wc), -1, -2), dX)
        Pp += Q
        P_sym = Pp + np.swapaxes(Pp, -1, -2)
        P_sym *= 0.5
        return KalmanPrediction(xp, P_sym)

    def _update(self, model, prediction, z, hx_args, step, R):
        self.check(model.dim_x)
        xp, Pp = prediction
        N, n = xp.shape
        m = model.dim_z
        kern = self._compiled_for(n)
        if kern is not None:
            upd = self._update_compiled(kern, model, xp, Pp, z, hx_args, R)
            if upd is not None:
                return upd
        L, sig = self._sigmas(xp, Pp, step, "P_prior")
        S_ = sig.shape[1]
        Hs = apply_rows(model.hx, sig.reshape(N * S_, n), m, model.vectorized, "hx", (), hx_args,
                        model.rows_checked).reshape(N, S_, m)
        del sig  # as in predict
        Wm, Wc = self.points.Wm, self.points.Wc
        zp = _weighted_mean(model.z_mean_fn, Hs, Wm)
        dY = _residual(model.residual_z, Hs, zp[:, None, :], model.vectorized)
        del Hs
        WdY = _times_weights(dY, Wc)
        S = np.matmul(np.swapaxes(dY, -1, -2), WdY)
        # Pxy = D^T (Wc dY) = L (Z^T (Wc dY)); the bracket is L^{-1} Pxy for the sampling
        LinvPxy = unit_transpose_apply(self.points, self._Z, WdY)
        if columns_layout(N, n):  # L: a view of the factors stored member axis last (_sigmas)
            Pxy, rhs = _cross_columns(L, LinvPxy)
            return finish_update(model, xp, Pp, z, zp, S, Pxy, L, step, LinvPxy=LinvPxy, R=R, rhs=rhs)
        Pxy = np.matmul(L, LinvPxy)
        return finish_update(model, xp, Pp, z, zp, S, Pxy, L, step, LinvPxy=LinvPxy, R=R)

    def _update_compiled(self, kern, model, xp, Pp, z, hx_args, R):
        """:meth:`_update` by the compiled kernels, or None where a member's ``P^-`` or ``S`` is
        not positive definite (the NumPy path then raises its error). ``L_prior`` is kept (a
        view of the factors stored member axis last); ``LinvPxy`` is not."""
        got = self._sigmas_compiled(kern, xp, Pp)
        if got is None:
            return None
        L, rows = got
        N, n = xp.shape
        m = model.dim_z
        Wm, Wc, Z = self._weights
        Hs = apply_rows(model.hx, rows, m, model.vectorized, "hx", (), hx_args, model.rows_checked)
        del rows
        Hs = np.ascontiguousarray(Hs, dtype=float).reshape(N, Z.shape[0], m)
        R = noise_matrix(model.R, "R", m) if R is None else R
        zz = np.ascontiguousarray(_as_z(z, N, m), dtype=float)
        x, P = np.empty((N, n)), np.empty((N, n, n))
        zp, S, Pxy, loglik = np.empty((N, m)), np.empty((N, m, m)), np.empty((N, n, m)), np.empty(N)
        centred = _own_functions(model.z_mean_fn, model.residual_z)
        if centred:  # the user's mean and residual, called as on the NumPy step; the kernel takes y
            zp = _weighted_mean(model.z_mean_fn, Hs, Wm)
            Hs = np.ascontiguousarray(_residual(model.residual_z, Hs, zp[:, None, :], model.vectorized))
            y = _residual(model.residual_z, zz, zp, model.vectorized)
            zz = np.ascontiguousarray(np.broadcast_to(y, (N, m)), dtype=float)
        bad = kern[2](Hs, L, Z, np.ascontiguousarray(xp, dtype=float), np.ascontiguousarray(Pp, dtype=float), zz,
                      np.ascontiguousarray(R, dtype=float).reshape(-1, m, m), Wm, Wc, x, P, zp, S, Pxy, loglik,
                      centred)
        if bad >= 0:
            return None
        return KalmanUpdate(x, P, zp, S, Pxy, loglik, L.transpose(2, 0, 1))

    def __repr__(self):
        if self.__dict__.get("compiled"):
            return f"UnscentedStep(points={type(self.points).__name__}(n={self.points.n}), compiled=True)"
        return f"UnscentedStep(points={type(self.points).__name__}(n={self.points.n}))"


STEPS = ("ekf", "ukf", "sukf")


def batched_step(kind, points=None):
    """The batched step of a kind: ``"ekf"`` -> :class:`ExtendedStep`; ``"ukf"`` and
    ``"sukf"`` (the unscented step on reduced points) -> :class:`UnscentedStep` on ``points``.

    >>> from filterwnn.kalman.presets import make_points
    >>> step = batched_step("sukf", make_points("supf", 3))
    >>> type(step).__name__, type(step.points).__name__, step.points.n
    ('UnscentedStep', 'SphericalSimplexSigmaPoints', 3)
    """
    if kind not in STEPS:
        raise ValueError(f"kind must be one of {', '.join(map(repr, STEPS))}, got {kind!r}")
    if kind == "ekf":
        return ExtendedStep()
    if points is None:
        raise ValueError(f"kind={kind!r} needs points (a filterpy-protocol sigma-point set), got None")
    return UnscentedStep(points)
