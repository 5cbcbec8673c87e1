r"""filterpy's unscented Kalman filter, vectorized, with loud numerical failures.

:class:`UnscentedKalmanFilter` subclasses :class:`filterpy.kalman.UnscentedKalmanFilter`
with the same constructor (filterpy's order: ``dim_x, dim_z, dt, hx, fx, points, ...``),
attributes and methods, and adds three things its users lack:

``vectorized=True``
    ``fx(sigmas, dt, **fx_args)`` and ``hx(sigmas, **hx_args)`` receive *all* sigma
    points as one ``(n_sigmas, dim)`` array and return ``(n_sigmas, dim_out)``: one
    call per step instead of one per point, the unscented transform and the cross
    covariance as matrix products, and the sigma points built from the set's
    structure in O(n^2) (:func:`filterwnn.kalman.sigma_points.sigma_deviations`).
    ``predict``, ``update``, ``batch_filter`` and ``rts_smoother`` all honour it.
``fx=None``
    a random walk, ``x_k = x_{k-1} + w_k`` (every parameter-estimation problem):
    ``predict`` is ``x_prior = x, P_prior = P + Q`` with no sigma points and no
    factorisation, so a step costs one Cholesky where filterpy's costs two.
:class:`~filterwnn.NumericalError`
    when ``P``, ``P_prior`` or ``S`` stops being positive definite, with the matrix
    name and the time step in its message and attributes, and the filter's state left
    as it was before the failing call. A ``z`` with NaN or inf raises ``ValueError``
    (``z=None`` skips the update, as in filterpy); a column ``z`` of shape
    ``(dim_z, 1)`` is flattened in both modes. Every covariance error says how to fix it
    (a scalar ``Q`` is refused, as filterpy would add it to every entry: the message
    says ``Q = q * np.eye(dim_x)``).

``step`` is the time step, as in every filter of the package: ``predict`` advances it
by one, ``update`` (and its errors) report the current one; a failing call leaves it
unchanged.

With ``vectorized=False`` and a given ``fx`` the numbers are filterpy's own.

Angles: in vectorized mode the residual and mean functions receive all sigma points at
once, so a filterpy-style ``y[1] = wrap(y[1])`` would wrap sigma point 1, not column 1.
Each one is checked on its first call (its shape, and its result against a row-by-row
call on the first sigma set), with a ``ValueError`` naming it; the ready-made
:func:`filterwnn.angles.angle_residual` and :func:`filterwnn.angles.angle_mean` are right
in both modes.

The update with sigma points :math:`\chi_i = x^- + D_i` and weights ``Wm, Wc`` is

.. math::
    \hat z = \sum_i W^m_i h(\chi_i), \quad
    S = \sum_i W^c_i (h_i - \hat z)(h_i - \hat z)^T + R, \quad
    P_{xz} = \sum_i W^c_i D_i (h_i - \hat z)^T,

    K = P_{xz} S^{-1}, \quad x = x^- + K (z - \hat z), \quad P = P^- - K S K^T,

with ``K`` from a Cholesky solve, never an explicit inverse.

>>> import numpy as np
>>> from filterwnn.kalman import make_points
>>> def hx(X):                      # all sigma points at once: (n_sigmas, 2) -> (n_sigmas, 1)
...     return np.sin(X[:, :1]) + X[:, 1:]
>>> ukf = UnscentedKalmanFilter(2, 1, 1.0, hx=hx, fx=None,
...                             points=make_points("simplex", 2), vectorized=True)
>>> ukf.Q *= 1e-4; ukf.R *= 0.01
>>> ukf.predict(); ukf.update(np.array([0.5]))
>>> ukf.x.shape, ukf.P.shape
((2,), (2, 2))
>>> ukf.update(np.array([np.nan]))
Traceback (most recent call last):
...
ValueError: z must be finite (use z=None for a missing measurement), got [nan]
"""

from __future__ import annotations

import math
import numbers
import operator
import sys

import numpy as np
from filterpy.kalman import UnscentedKalmanFilter as _FilterpyUKF
from filterpy.kalman import unscented_transform
from scipy.linalg import cho_factor, cho_solve, cholesky
from scipy.linalg.lapack import dpotrf, dpotrs

from .._linalg import cholesky as checked_cholesky
from .._linalg import cholesky_lower, cholesky_lower_raw, not_pd_error, smallest_eigenvalue
from .._validation import (
    NumericalError,
    check_covariance,
    check_points_protocol,
    check_positive,
    check_positive_int,
    check_symmetric,
)
from . import _filterpy_arithmetic as fpa
from ._rowcheck import CALL_ERRORS, ONE_POINT_FIX, on_single_rows, one_point_error, rows_differ
from .sigma_points import point_structure, sigma_deviations

__all__ = ["UnscentedKalmanFilter", "fast_unscented_transform"]

# What each covariance error tells the user to do.
_SHAPE_FIX = {
    "P": "a scalar is not a covariance here (filterpy would add it to every entry): "
         "use P = p * np.eye({n}) or np.diag(variances)",
    "Q": "a scalar is not a covariance here (filterpy would add it to every entry): "
         "use Q = q * np.eye({n}) or filterpy.common.Q_discrete_white_noise",
    "R": "use R = np.diag(variances) (one per measurement entry)",
}
_PD_FIX = {
    "P": "set P to a symmetric positive definite matrix, e.g. P = np.diag(variances)",
    "P_prior": "the predicted covariance lost definiteness: make Q positive semi-definite "
               "and, with a negative centre weight (Julier kappa < 0, alpha << 1), use w0 >= 0 "
               "or a larger Q",
    "S": "S = (transformed P) + R: make R positive definite, e.g. R = np.diag(variances)",
}


def _with_fix(check, M, name, *args, **kwargs):
    """Run a ``_validation`` check, adding the remedy to its message."""
    try:
        return check(M, name, *args, **kwargs)
    except ValueError as exc:
        msg = str(exc)
        if "symmetric" in msg and "semi" not in msg:
            fix = f"symmetrise it: {name} = 0.5 * ({name} + {name}.T)"
        elif "semi-definite" in msg:
            fix = f"{name} must be a covariance, e.g. {name} = np.diag(variances)"
        else:
            fix = f"{name} must be a finite symmetric covariance, e.g. {name} = np.diag(variances)"
        raise ValueError(f"{msg}; {fix}") from exc


def _shape(M):
    """``np.shape(M)``, without its wrapper for an array (the step's checks call it on each)."""
    return M.shape if type(M) is np.ndarray else np.shape(M)


def _each_row(residual, A, b):
    """``residual(A[i], b)`` for every row, as filterpy's loops call it (one array op for np.subtract)."""
    if residual is np.subtract:
        return A - b
    return np.array([residual(a, b) for a in A], dtype=float)


def _positive_definite(S):
    """Whether the (symmetric) ``S`` is positive definite; 1x1 and 2x2 without a LAPACK call."""
    if S.shape == (1, 1):
        return bool(S[0, 0] > 0)
    if S.shape == (2, 2):  # Sylvester's criterion
        return bool(S[0, 0] > 0 and S[0, 0] * S[1, 1] - S[0, 1] * S[1, 0] > 0)
    return cholesky_lower(S) is not None


def _downdate(P, u):
    """``P - u u^T`` in a fresh array, exactly symmetric when ``P`` is, on every machine.

    Entry ``(i, j)`` is ``P_ij - fl(u_i u_j)``: NumPy's elementwise product and difference,
    each rounded once, and ``u_i u_j`` is ``u_j u_i`` bit for bit. BLAS ``dger`` (a third of
    the time at n = 160) is not used: its kernels fuse the multiply-add (FMA, one rounding) in
    their vector body but not in their tail, so ``(i, j)`` and ``(j, i)`` can differ in the
    last bit when the two fall on different sides (OpenBLAS's Haswell kernel at n = 24), and
    a filter fed in chunks then differs from one fed at once wherever ``P`` is symmetrized.
    """
    out = np.multiply.outer(u, u)
    return np.subtract(P, out, out=out)


def _downdate_finite(P, u):
    """Whether ``P - u u^T`` is finite, known in O(n) when ``P`` passed a Cholesky this step.

    A symmetric positive definite ``P`` has ``|P_ij| <= max_k P_kk`` (up to rounding and the
    package's symmetry tolerance, ``1e-8`` relative: a factor 2 covers both), so no entry of
    the downdate can overflow while ``2 max_k P_kk + max_i u_i^2`` is far below the largest
    float; a NaN in ``u`` fails the comparison. False means unknown: the caller scans.
    """
    b = float(np.abs(u).max())
    return 2.0 * float(P.diagonal().max()) + b * b < 1e300


def fast_unscented_transform(sigmas, Wm, Wc, noise_cov=None):
    """Unscented transform for linear residuals, as matrix products.

    Equal to :func:`filterpy.kalman.unscented_transform` with the default mean and
    residual functions, without forming filterpy's dense ``diag(Wc)``.

    Parameters
    ----------
    sigmas : ndarray of shape (n_sigmas, dim)
    Wm, Wc : ndarray of shape (n_sigmas,)
    noise_cov : ndarray of shape (dim, dim), optional

    Returns
    -------
    x : ndarray of shape (dim,)
    P : ndarray of shape (dim, dim)
    """
    x = Wm @ sigmas
    y = sigmas - x
    P = (y.T * Wc) @ y
    if noise_cov is not None:
        P = P + noise_cov
    return x, P


def _stored(obj, attr):
    """``(obj.__dict__, the value behind attr)`` for :class:`_Watched` and :class:`_Kept`
    (stored under ``attr.now``); an unset one is an ``AttributeError`` naming ``attr.name``."""
    d = obj.__dict__
    try:
        return d, d[attr.now]
    except KeyError:
        raise AttributeError(attr.name) from None


class _Watched(property):
    """``x`` and ``P`` of :class:`UnscentedKalmanFilter`: compared only when they may have changed.

    A ``property`` (subclass), so that tools which look for a filter's properties, as
    filterpy's ``Saver``, still record ``x`` and ``P``.

    The value lives in ``_<name>_now``; ``_<name>_out`` says whether anyone outside the filter
    may hold it (it was assigned, or read since the filter made it). A value the filter made
    in its last step and nobody has read since cannot have been edited, so the next step skips
    its comparison. Its first read keeps a copy (``_mark``) before handing it out, so an edit in
    place through that reference is seen at the next step like an assignment.
    """

    def __set_name__(self, owner, name):
        self.name, self.now, self.out = name, f"_{name}_now", f"_{name}_out"

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        d, value = _stored(obj, self)
        if not d.get(self.out, True):
            obj._mark(self.name, value)
            for kept in _Kept.NAMES:  # P_prior or P_post may be this very array: theirs is a copy
                if d.get(kept) is value:
                    d[kept] = value.copy()
            d[self.out] = True
        return value

    def __set__(self, obj, value):
        obj.__dict__[self.now] = value
        obj.__dict__[self.out] = True


class _Kept(property):
    """``P_prior`` and ``P_post`` of :class:`UnscentedKalmanFilter`: copies of ``P``, made when needed.

    A step that made ``P`` (held by nobody outside, see :class:`_Watched`) stores that array
    itself here, since the filter never writes into its arrays in place; the copy filterpy's
    users get is made when either is first handed out: at a read of this attribute, or at
    the first read of ``P``. So an edit in place of one never shows in the other.
    """

    NAMES = ("_P_prior_now", "_P_post_now")

    def __set_name__(self, owner, name):
        self.name, self.now = name, f"_{name}_now"

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        d, value = _stored(obj, self)
        if value is d.get("_P_now"):
            value = d[self.now] = value.copy()
        return value

    def __set__(self, obj, value):
        obj.__dict__[self.now] = value


def _references(value):
    """``sys.getrefcount(value)``, or None where the interpreter keeps no count."""
    count = getattr(sys, "getrefcount", None)
    return None if count is None else count(value)


class _CountOnSet:
    """A descriptor that records what :func:`_references` sees in ``__set__`` (for :data:`_TEMPORARY`)."""

    def __set_name__(self, owner, name):
        self.seen = []

    def __set__(self, obj, value):
        self.seen.append(_references(value))


def _temporary_references():
    """What ``_Owned.__set__`` counts for a temporary (``obj.Q = np.empty(0)``), measured at import
    on a descriptor of the same shape; None (never trust a count) unless it is the same each time
    and a named array (``obj.Q = a``) counts more. An interpreter that pushes a local's value
    without a reference of its own (as CPython 3.14's borrowed loads may) counts both alike:
    there every ``Q`` is compared at every step, as before."""
    probe = type("Probe", (), {"value": _CountOnSet()})()
    for _ in range(3):
        probe.value = np.empty(0)
    named = np.empty(0)
    probe.value = named
    seen = type(probe).__dict__["value"].seen
    temporary = seen[0]
    if temporary is None or len(set(seen[:3])) != 1 or not seen[3] > temporary:
        return None
    return temporary


_TEMPORARY = _temporary_references()


class _Owned(property):
    """``Q`` of :class:`UnscentedKalmanFilter`: validated once assigned, compared only once shared.

    A ``property`` (subclass), like :class:`_Watched`. The value lives in ``_Q_now``;
    ``_Q_out`` says whether anyone outside the filter may hold it, and ``_Q_checked`` whether
    the value assigned has been checked. A value assigned as a temporary (``ukf.Q = np.eye(n) *
    1e-5``: the assignment holds its only reference, which CPython's reference count tells) is
    the filter's alone, so once checked it cannot change unseen and the step skips its O(n^2)
    comparison. Anything else is compared at every step, as before: an array the caller keeps a
    name for, any read of ``ukf.Q`` (so an edit in place, ``ukf.Q[0, 0] = ...`` or ``ukf.Q *=
    2``, is seen like an assignment), a copied or unpickled filter's (``__setstate__``), and
    every value where the interpreter's count cannot tell a temporary from a named array
    (:func:`_temporary_references`). What a count cannot see: C code (a Cython function, say)
    that assigns an array it keeps in a local and edits it in place before the next step.
    """

    def __set_name__(self, owner, name):
        self.name, self.now, self.out, self.checked = name, f"_{name}_now", f"_{name}_out", f"_{name}_checked"

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        d, value = _stored(obj, self)
        d[self.out] = True
        return value

    def __set__(self, obj, value):
        d = obj.__dict__
        # a view shares its memory with an array someone else may hold: only an array owning it counts
        alone = type(value) is np.ndarray and value.base is None and _references(value) == _TEMPORARY
        d[self.out] = _TEMPORARY is None or not alone
        d[self.now] = value
        d[self.checked] = False


class UnscentedKalmanFilter(_FilterpyUKF):
    """filterpy's ``UnscentedKalmanFilter`` with ``vectorized=``, ``fx=None`` and clear errors.

    Parameters
    ----------
    dim_x, dim_z : int
        State and measurement sizes.
    dt : float
        Time step passed to ``fx`` (``> 0``).
    hx : callable
        ``hx(x, **hx_args)``; with ``vectorized=True``, ``hx(sigmas, **hx_args)`` taking
        ``(n_sigmas, dim_x)`` and returning ``(n_sigmas, dim_z)``.
    fx : callable or None
        ``fx(x, dt, **fx_args)`` (vectorized alike), or ``None`` for a random walk.
    points : sigma-point object
        Any filterpy-protocol set: filterpy's Merwe/Julier/simplex points, or
        :class:`~filterwnn.MinimalSkewSigmaPoints`,
        :class:`~filterwnn.SphericalSimplexSigmaPoints`.
    sqrt_fn, x_mean_fn, z_mean_fn, residual_x, residual_z, state_add : callable, optional
        As in filterpy. In vectorized mode, ``residual_x``/``residual_z`` are called
        on whole arrays (``residual(sigmas, mean)`` broadcasting a row), so write them
        with NumPy operations on the last axis (``y[..., 1]``, not ``y[1]``), or use
        :func:`filterwnn.angles.angle_residual` and :func:`filterwnn.angles.angle_mean`;
        each is checked on its first call (a ``ValueError`` names it).
    vectorized : bool, default False
        Evaluate ``fx``/``hx`` once per step on all sigma points.

    Attributes
    ----------
    step : int
        The time step: ``predict`` advances it by one; ``update`` and its errors
        report the current step. A call that raises leaves it unchanged.

    Notes
    -----
    filterpy 2.0 re-draws the sigma points from the predicted ``(x, P)`` at the end of
    ``predict``; this class does the same (lazily, in ``update``) in both modes, so the
    numbers agree with filterpy's at every step.

    With ``vectorized=True`` and Merwe or Julier points, ``sigmas_f`` is one of two
    arrays the filter keeps and refills in turn (no fresh ``(2n + 1, n)`` array a step):
    copy it to keep it past the next two draws, as with filterpy, whose ``predict``
    fills ``sigmas_f`` in place. ``x``, ``P``, ``Q`` and ``R`` are validated when their
    values change (compared with private copies, so an edit in place is seen like an
    assignment), not on every step; an ``x`` or ``P`` the vectorized step made and nobody
    has read since is not even compared (it cannot have changed), nor a ``Q`` assigned as a
    temporary (``ukf.Q = np.eye(n) * q``) and not read back since (see ``_Owned``).
    """

    x = _Watched()
    P = _Watched()
    Q = _Owned()
    P_prior = _Kept()
    P_post = _Kept()

    def __init__(self, dim_x, dim_z, dt, hx, fx, points, sqrt_fn=None, x_mean_fn=None, z_mean_fn=None,
                 residual_x=None, residual_z=None, state_add=None, vectorized=False):
        dim_x = check_positive_int(dim_x, "dim_x")
        dim_z = check_positive_int(dim_z, "dim_z")
        dt = check_positive(dt, "dt")
        if not callable(hx):
            raise TypeError(f"hx must be callable, got {type(hx).__name__}")
        if fx is not None and not callable(fx):
            raise TypeError(f"fx must be callable or None (random walk), got {type(fx).__name__}")
        check_points_protocol(points, ("num_sigmas", "sigma_points", "Wm", "Wc"))  # n is optional here
        if getattr(points, "n", dim_x) != dim_x:
            raise ValueError(f"points.n must equal dim_x={dim_x}, got {points.n}")
        super().__init__(dim_x, dim_z, dt, hx, fx, points, sqrt_fn=sqrt_fn, x_mean_fn=x_mean_fn,
                         z_mean_fn=z_mean_fn, residual_x=residual_x, residual_z=residual_z, state_add=state_add)
        self.vectorized = bool(vectorized)
        self.step = 0
        self._sigmas_stale = True  # sigmas_f must be drawn from (x, P) before update
        self._deviations = None  # the dense deviations D of the last draw (sigmas = x + D)
        self._half = None  # or, for the symmetric sets, their scaled factor c U (D = [0, cU, -cU])
        self._trusted = {}  # copies of the x, P and Q last checked (or produced) here
        self._chol = None  # (P_prior object, its factor from _factor), vectorized mode
        self._checked = {}  # role -> the residual/mean callable already checked on arrays
        self._work = {}  # constant-shaped work arrays of the vectorized step (see _sigmas)

    def __setstate__(self, state):
        # a copy (copy.copy passes the original's own __dict__ here) or an unpickled filter may
        # share its arrays with another: both compare them from now on
        for name in ("x", "P", "Q"):
            if name in state:  # a pickle from before x, P and Q were watched
                state[f"_{name}_now"] = state.pop(name)
            if f"_{name}_now" in state:
                state[f"_{name}_out"] = True
        state.setdefault("_Q_checked", False)
        for name in ("P_prior", "P_post"):  # ... or P_prior and P_post kept
            if name in state:
                state[f"_{name}_now"] = state.pop(name)
        self.__dict__.update(state)

    # ------------------------------------------------------------------ helpers
    def _fast_points(self):
        """True when sigma points may be built as x + sigma_deviations(chol(P))."""
        pts = self.points_fn
        return (
            getattr(pts, "sqrt", None) is cholesky
            and getattr(pts, "subtract", np.subtract) is np.subtract
        )

    def _check_state(self, when, check_Q=False):
        """Shapes, finiteness and symmetry of ``x``, ``P`` (and ``Q``); ``when`` is for messages."""
        d = self.__dict__  # the values themselves: reading x, P or Q would hand them out
        x, P, Q, n = d["_x_now"], d["_P_now"], d["_Q_now"], self._dim_x
        if _shape(x) != (n,):
            raise ValueError(f"x must have shape ({n},), got {np.shape(x)}")
        for name, M in (("P", P), ("Q", Q)):
            if _shape(M) != (n, n):
                raise ValueError(f"{name} must have shape ({n}, {n}), got {np.shape(M)}; "
                                 + _SHAPE_FIX[name].format(n=n))
        # Finiteness and symmetry cost full passes: check what the user set, not what we
        # produced. What the filter last produced or checked is kept by content, not
        # identity, so an edit in place (P *= 4, P[0, 2] += 0.5) is seen like an
        # assignment; it also makes the cached factor and the update's sigma points stale
        # (both modes redraw them). An x the filter made and nobody has read was finite
        # when made (each step checks the x it makes), and cannot have changed.
        P_same = not d["_P_out"] or self._unchanged("P", P)
        if not ((not d["_x_out"] or np.isfinite(x).all()) and (P_same or np.isfinite(P).all())):
            raise NumericalError(
                f"x and P must be finite {when}; set them again (x_post and P_post hold the "
                "last update's values)", matrix="P", step=self.step)
        if not P_same:
            _with_fix(check_symmetric, P, "P")
            self._chol = None
            self._sigmas_stale = True
            self._mark("P", P)
        if d["_x_out"] and not self._unchanged("x", x):
            self._sigmas_stale = True
            self._mark("x", x)
        # Q: compared once assigned, then at every step only if someone outside may hold it (_Owned)
        if check_Q and (d["_Q_out"] or not d["_Q_checked"]):
            if not self._unchanged("Q", Q):
                # once per Q: finite, symmetric, positive semi-definite (a Cholesky settles
                # the usual positive definite Q; eigenvalues only for a singular one)
                _with_fix(check_symmetric, Q, "Q")
                if cholesky_lower(Q) is None:
                    _with_fix(check_covariance, Q, "Q", n, allow_scalar=False, require_pd=False)
                self._mark("Q", Q)
            d["_Q_checked"] = True

    def _unchanged(self, name, M):
        """True when ``M`` holds what the filter last produced or checked as ``name``.

        The filter keeps a private copy of each (:meth:`_mark`) and compares values
        (``!=`` into a kept boolean array, then ``any``): an assignment and an edit in
        place (``P *= 4``, ``P[0, 2] += 0.5``) are seen alike, a NaN never compares
        equal, and a ``-0.0`` for ``0.0`` is the same matrix. Nothing is allocated: at
        n = 160 a fresh 200 kB buffer per check (``tobytes``) cost about 100 us a step
        in page faults, more than the comparison itself.
        """
        seen = self._trusted.get(name)
        if seen is None or type(M) is not np.ndarray or M.dtype != float or M.shape != seen[0].shape:
            return False
        if M.size == 1:  # a 1x1 R: the same comparison on the Python floats (NaN != NaN too)
            return M.item() == seen[0].item()
        return not np.not_equal(M, seen[0], out=seen[1]).any()

    def _mark(self, name, M):
        """Keep a copy of ``M`` as ``name``'s checked value (into the kept array when it fits)."""
        seen = self._trusted.get(name)
        M = np.asarray(M, dtype=float)
        if seen is not None and seen[0].shape == M.shape:
            np.copyto(seen[0], M)  # a copy: later edits in place show
        else:
            self._trusted[name] = (M.copy(), np.empty(M.shape, dtype=bool))

    def _sigmas(self, x, P, what, fresh=False):
        """Sigma points of N(x, P); NumericalError naming ``what`` if P is not PD.

        ``fresh=True`` (the smoother) returns a new array and leaves the kept draw alone.
        """
        if self.vectorized and self._fast_points():
            if fresh:
                return x + sigma_deviations(self.points_fn, self._cholesky(P, what).T)
            if self._chol is not None and self._chol[0] is P:
                L = self._chol[1]  # factored at predict (P_prior's check)
            else:
                L = self._factor(P, what)
            return self._draw(x, L)
        if not fresh:
            self._deviations = self._half = None
        try:
            if fpa.is_plain_merwe(self.points_fn) and type(P) is np.ndarray and P.dtype == float:
                return fpa.merwe_sigma_points(self.points_fn, np.asarray(x, dtype=float), P)
            return np.asarray(self.points_fn.sigma_points(x, P), dtype=float)
        except np.linalg.LinAlgError as exc:
            raise self._not_pd(what, P) from exc

    def _symmetric_scale(self):
        """``c`` when the points are ``[0, c I, -c I]`` (Merwe, Julier) at this size, else None."""
        kind, c = point_structure(self.points_fn)
        if kind != "symmetric" or self.points_fn.num_sigmas() != 2 * self._dim_x + 1:
            return None
        return c

    def _factor(self, P, what):
        """Lower Cholesky factor of ``P`` for :meth:`_draw`; NumericalError naming ``what``.

        The symmetric sets read one triangle of it, so they take LAPACK's uncleaned factor
        (:func:`~filterwnn._linalg.cholesky_lower_raw`: no zeroing pass); others numpy's.
        """
        if self._symmetric_scale() is not None:
            return cholesky_lower_raw(P, what, self.step, _PD_FIX[what])
        return self._cholesky(P, what)

    def _draw(self, x, L):
        """``x + Z L^T`` into a kept buffer (:meth:`_sigma_buffer`), the deviations kept too.

        For the symmetric sets (``Z = [0, c I, -c I]``) the rows are ``x``, ``x + c U_i`` and
        ``x - c U_i`` (``U = L^T``): ``c U`` is written from ``L``'s lower triangle only into
        a kept ``(n, n)`` array whose strict lower triangle stays zero, and kept as
        ``_half`` for the cross covariance. ``x - cU`` is ``x + (-(cU))`` exactly: the numbers
        of ``x + sigma_deviations(points, U)``, without the ``(2n + 1, n)`` array ``D``
        (at n = 160 its fill cost more than the sigma points). Other sets keep ``D``.
        ``_half`` and ``D`` are private: only the update that drew them reads them.
        """
        c = self._symmetric_scale()
        if c is None:
            D = sigma_deviations(self.points_fn, L.T)
            self._deviations, self._half = D, None
            return np.add(x, D, out=self._sigma_buffer(D.shape))
        n = L.shape[0]
        work = self._work.get("half")
        if work is None or work[0].shape != (n, n):
            work = self._work["half"] = (np.zeros((n, n)), np.triu(np.ones((n, n), dtype=bool)))
        cU, upper = work
        np.multiply(c, L.T, out=cU, where=upper)
        sig = self._sigma_buffer((2 * n + 1, n))
        sig[0] = x
        np.add(x, cU, out=sig[1 : n + 1])
        np.subtract(x, cU, out=sig[n + 1 :])
        self._deviations, self._half = None, cU
        return sig

    def _sigma_buffer(self, shape):
        """One of two kept arrays for the sigma points, never the one ``sigmas_f`` holds.

        Two take turns, so a call that raises and restores ``sigmas_f`` gets its points
        back intact; a reference to ``sigmas_f`` kept by the caller is overwritten two
        draws later (filterpy's own ``predict`` fills ``sigmas_f`` in place every step).
        """
        bufs = self._work.setdefault("sigmas", [])
        for b in bufs:
            if b is not self.sigmas_f and b.shape == shape:
                return b
        b = np.empty(shape)
        bufs[:] = [b] + [o for o in bufs if o is self.sigmas_f and o.shape == shape]
        return b

    def _cholesky(self, P, what):
        """Lower Cholesky factor of ``P``; NumericalError naming ``what`` if it fails."""
        return checked_cholesky(P, what, self.step, _PD_FIX[what])

    def _not_pd(self, what, M):
        return not_pd_error(what, M, self.step, _PD_FIX[what])

    # References suffice: this class never writes into these arrays in place, it rebinds
    # them (its predict does not call filterpy's, which fills sigmas_f in place); the kept
    # buffers (_sigma_buffer, _draw) are refilled only by a draw, which a restore marks stale.
    _SNAPSHOT = ("_x_now", "_P_now", "_x_out", "_P_out", "x_prior", "_P_prior_now", "x_post", "_P_post_now",
                 "sigmas_f", "sigmas_h", "K", "y", "z", "S", "SI", "_sigmas_stale", "_deviations", "_half",
                 "_log_likelihood", "_likelihood", "_mahalanobis", "step", "_chol")
    _GET_SNAPSHOT = operator.attrgetter(*_SNAPSHOT)  # one C call: a tuple in that order

    def _snapshot(self):
        return self._GET_SNAPSHOT(self)

    def _restore(self, snap):
        for k, v in zip(self._SNAPSHOT, snap):
            setattr(self, k, v)

    def _call(self, fn, sigmas, name, dim_out, *args, **kwargs):
        """Evaluate fx/hx on all sigma points (vectorized) or row by row."""
        if not self.vectorized:  # as filterpy's compute_process_sigmas: row i of an array
            out = np.empty((sigmas.shape[0], dim_out))
            try:
                for i, s in enumerate(sigmas):
                    out[i] = fn(s, *args, **kwargs)
            except ValueError as exc:
                raise self._loop_shape_error(name, np.shape(fn(sigmas[0], *args, **kwargs)), dim_out) from exc
            return out
        first = self._checked.get(name) is not fn
        try:
            out = np.asarray(fn(sigmas, *args, **kwargs), dtype=float)
        except CALL_ERRORS as exc:
            if first and on_single_rows(fn, sigmas, [0], dim_out, args, kwargs) is not None:
                raise one_point_error(name, f"on all {sigmas.shape[0]} sigma points it raised "
                                             f"{type(exc).__name__}: {exc}") from exc
            raise
        if out.ndim == 1 and dim_out == 1:
            out = out[:, None]
        if out.shape != (sigmas.shape[0], dim_out):
            msg = (f"vectorized {name} must map ({sigmas.shape[0]}, {sigmas.shape[1]}) sigma "
                   f"points to shape ({sigmas.shape[0]}, {dim_out}), got {out.shape}")
            got = on_single_rows(fn, sigmas, [0], dim_out, args, kwargs) if first else None
            if got is not None and got[1]:
                raise one_point_error(name, msg)
            raise ValueError(msg)
        if first:
            detail = rows_differ(out, sigmas, fn, args, kwargs)
            if detail is not None:
                raise one_point_error(name, detail)
            self._checked[name] = fn
        return out

    def _loop_shape_error(self, name, one, dim_out):
        what = "a scalar" if one == () else f"shape {one}"
        example = "np.array([x[0]])" if name == "hx" else "np.array([x[0] + dt * x[1], ...])"
        return ValueError(
            f"{name} must return an array of shape ({dim_out},) for one point, got {what}; return "
            f"a 1-D array, e.g. {example} (filterpy would fail later with 'shapes ... not aligned')"
        )

    def _residual(self, role, fn, A, b):
        """``fn(A, b)`` on all rows at once, checked against a row-by-row call the first time.

        ``role`` is the constructor argument's name (``"residual_x"``, ``"residual_z"``). A
        function written for one row (filterpy's ``y[1] = wrap(y[1])``) wraps a sigma point
        instead of a column: it is compared with row-by-row calls on this first sigma set,
        and on a probe whose residuals all exceed pi (where a wrap of the wrong entries
        shows even if the sigma points are close together).
        """
        if self._checked.get(role) is fn:
            return fn(A, b)
        b = np.copy(b)
        try:
            out = np.asarray(fn(A.copy(), b.copy()), dtype=float)
        except CALL_ERRORS as exc:
            if on_single_rows(fn, A, [0], A.shape[1], (b,)) is not None:
                raise one_point_error(role, f"on all {A.shape[0]} sigma points it raised "
                                             f"{type(exc).__name__}: {exc}") from exc
            raise
        if out.shape != A.shape:
            raise ValueError(
                f"vectorized {role} must map sigma points of shape {A.shape} and a mean of "
                f"shape {np.shape(b)} to shape {A.shape}, got {out.shape}; {ONE_POINT_FIX[role]}"
            )
        probe = np.asarray(b, dtype=float) + 4.0 * (1.0 + np.arange(A.size).reshape(A.shape))
        for label, X in (("sigma points", A), ("a probe with residuals above pi", probe)):
            vec = out if X is A else np.asarray(fn(X.copy(), b.copy()), dtype=float)
            detail = rows_differ(vec, X, fn, (b,))
            if detail is not None:
                raise one_point_error(role, f"on {label}, {detail}")
        self._checked[role] = fn
        return out

    def _mean(self, role, fn, sigmas):
        """``fn(sigmas, Wm)`` (filterpy's mean signature), its shape checked the first time."""
        if fn is None:
            return self.Wm @ sigmas
        m = np.asarray(fn(sigmas, self.Wm), dtype=float)
        if self._checked.get(role) is not fn:
            if m.shape != (sigmas.shape[1],):
                raise ValueError(
                    f"{role} must map sigma points of shape {sigmas.shape} and Wm of shape "
                    f"{self.Wm.shape} to shape ({sigmas.shape[1]},), got {m.shape}; use "
                    "filterwnn.angles.angle_mean(columns) for angles"
                )
            self._checked[role] = fn
        return m

    def _vectorized_ut(self, sigmas, mean_fn, residual_fn, noise_cov, roles):
        """Unscented transform on all rows at once; returns ``(mean, cov, residuals)``."""
        m = self._mean(roles[0], mean_fn, sigmas)
        if residual_fn is np.subtract:
            y = sigmas - m
        else:
            y = self._residual(roles[1], residual_fn, sigmas, m)
        P = (y.T * self.Wc) @ y + noise_cov
        return m, P, y

    # ------------------------------------------------------------------ predict
    def predict(self, dt=None, UT=None, fx=None, **fx_args):
        """Predict step; ``fx=None`` (here and at construction) is a random walk.

        Advances ``step`` by one. On return ``x``, ``P`` (and ``x_prior``, ``P_prior``)
        hold the prediction, and ``P_prior`` is known to be positive definite (both
        modes). Raises ``ValueError`` for a bad ``x``, ``P`` or ``Q`` (shape, symmetry,
        a ``Q`` that is not positive semi-definite) and :class:`~filterwnn.NumericalError`
        if ``P`` or ``P_prior`` is not positive definite or ``fx`` returns non-finite
        values, with the state (and ``step``) left as they were.
        """
        self._check_state(f"before step {self.step + 1}", check_Q=True)
        dt = self._dt if dt is None else check_positive(dt, "dt")
        fx = self.fx if fx is None else fx
        snap = self._snapshot()
        before = (self._x_now, self._P_now)
        self.step += 1
        try:
            if fx is None:  # random walk: no sigma points here
                self.P = self._P_now + self.__dict__["_Q_now"]  # (not self.Q: a read hands Q out)
                self.x = self._x_now.copy()
            else:
                sigmas = self._sigmas(self._x_now, self._P_now, "P")
                self.sigmas_f = self._call(fx, sigmas, "fx", self._dim_x, dt, **fx_args)
                if self.vectorized and UT is None:
                    self.x, self.P, _ = self._vectorized_ut(
                        self.sigmas_f, self.x_mean, self.residual_x, self.__dict__["_Q_now"],
                        ("x_mean_fn", "residual_x"),
                    )
                else:  # filterpy's own arithmetic (bit-identical in loop mode)
                    # a user's UT gets Q as filterpy hands it (a read: compared from now on)
                    Q = self.__dict__["_Q_now"] if UT is None else self.Q
                    UT = fpa.unscented_transform if UT is None else UT
                    self.x, self.P = UT(self.sigmas_f, self.Wm, self.Wc, Q, self.x_mean, self.residual_x)
                if not (np.isfinite(self.x).all() and np.isfinite(self.P).all()):
                    raise NumericalError(
                        f"fx produced a non-finite prediction (x_prior or P_prior) at step {self.step}; "
                        "check fx at the sigma points of (x, P)",
                        matrix="P_prior", step=self.step,
                    )
            if self.vectorized:
                if fx is not None:  # P + Q is already symmetric
                    self.P = 0.5 * (self.P + self.P.T)
                # P_prior must be positive definite, as loop mode checks by drawing the
                # sigma points; the factor is kept for the update's sigma points
                self._chol = (self.P, self._factor(self.P, "P_prior"))
                self._sigmas_stale = True  # filterpy 2.0 re-draws sigmas from the prior
            else:  # as filterpy 2.0: the update's sigma points are the prior's
                self.sigmas_f = self._sigmas(self.x, self.P, "P_prior")
                self._sigmas_stale = False
        except Exception:
            self._restore(snap)
            raise
        self.x_prior = np.array(self.x)  # np.copy's numbers, without its wrapper
        made = self.vectorized and UT is None and self.x_mean is None  # this class's arithmetic made x
        self._settle_state(before, fx is None or made, fx is None or self.vectorized, "_P_prior_now")

    def compute_process_sigmas(self, dt, fx=None, **fx_args):
        """filterpy's helper: ``sigmas_f`` = the sigma points passed through ``fx``."""
        fx = self.fx if fx is None else fx
        sigmas = self._sigmas(self._x_now, self._P_now, "P")
        if fx is None:
            self.sigmas_f = sigmas
        else:  # the draw's deviations are not those of fx's points: the update uses sigmas_f - x
            self.sigmas_f = self._call(fx, sigmas, "fx", self._dim_x, dt, **fx_args)
            self._deviations = self._half = None
        self._sigmas_stale = False

    # ------------------------------------------------------------------ update
    def update(self, z, R=None, UT=None, hx=None, **hx_args):
        """Update with measurement ``z`` (``None`` skips the update, as in filterpy).

        ``z`` of shape ``(dim_z,)``, or ``(dim_z, 1)`` (flattened, in both modes). Does
        not advance ``step``: errors report the current time step. Raises
        ``ValueError`` for a non-finite ``z`` and :class:`~filterwnn.NumericalError`
        when ``P`` or ``S`` is not positive definite; either way the filter's state is
        left as it was.
        """
        if z is None:
            self.z = np.array([[None] * self._dim_z]).T
            self.x_post = self._x_now.copy()
            self.P_post = self._P_now.copy()
            return
        try:
            z_arr = np.asarray(z, dtype=float)
        except (TypeError, ValueError) as exc:
            raise TypeError(f"z must be array-like of numbers or None, got {type(z).__name__}") from exc
        if not (math.isfinite(z_arr.item()) if z_arr.size == 1 else np.isfinite(z_arr).all()):
            raise ValueError(
                f"z must be finite (use z=None for a missing measurement), got {np.ravel(z_arr)}"
            )
        self._check_state(f"at step {self.step} (update)")
        z_arr, R = self._check_measurement(z_arr, R)
        snap = self._snapshot()
        before = (self._x_now, self._P_now)
        try:
            if self._sigmas_stale:
                self.sigmas_f = self._sigmas(self._x_now, self._P_now, "P")
                self._sigmas_stale = False
            if not self.vectorized:
                hx = self.hx if hx is None else hx
                self._check_loop_hx(hx, z_arr.size, hx_args)
                try:  # filterpy's update gets the checked z: a column z is flattened as in vectorized mode
                    if UT is None and type(self).cross_variance is _FilterpyUKF.cross_variance:
                        self._loop_update(z_arr, R, hx, **hx_args)
                    else:
                        super().update(z_arr, R=R, UT=UT, hx=hx, **hx_args)
                except np.linalg.LinAlgError as exc:
                    raise self._not_pd("S", self.S) from exc
                # filterpy inverts S without asking whether it is positive definite
                if np.isfinite(self.S).any() and not _positive_definite(self.S):
                    raise self._not_pd("S", self.S)
                P_finite = False
            else:
                P_finite = self._vectorized_update(z_arr, R, UT, hx, **hx_args)
            if not (np.isfinite(self.x).all() and (P_finite or np.isfinite(self.P).all())):
                raise NumericalError(
                    f"the update produced non-finite x or P at step {self.step}", matrix="P", step=self.step
                )
        except Exception:
            self._restore(snap)
            raise
        self._sigmas_stale = True
        self._chol = None
        self._settle_state(before, self.vectorized and self.state_add is np.add, self.vectorized, "_P_post_now")

    def _settle_state(self, before, fresh_x, fresh_P, kept):
        """After a step: an ``x`` or ``P`` it made (``fresh_*``, not ``before``'s object) is
        held by nobody outside, so the next step skips its comparison (:class:`_Watched`);
        any other is kept as a copy to compare with. ``kept`` (``P_prior``'s or ``P_post``'s
        slot) gets ``P`` itself when it was made here (:class:`_Kept` copies it when needed),
        else a copy."""
        d = self.__dict__
        for name, fresh, old in (("x", fresh_x, before[0]), ("P", fresh_P, before[1])):
            value = d[f"_{name}_now"]
            if fresh and value is not old:
                d[f"_{name}_out"] = False
            else:
                self._mark(name, value)
        P = d["_P_now"]
        d[kept] = P if not d["_P_out"] else P.copy()

    def _loop_update(self, z, R, hx, **hx_args):
        """filterpy's ``update`` (UT and cross variance at their defaults): the same
        floating-point operations (:mod:`._filterpy_arithmetic`) with fewer calls."""
        self.sigmas_h = np.atleast_2d([hx(s, **hx_args) for s in self.sigmas_f])
        zp, self.S = fpa.unscented_transform(self.sigmas_h, self.Wm, self.Wc, R, self.z_mean, self.residual_z)
        self.SI = self.inv(self.S)
        dx = _each_row(self.residual_x, self.sigmas_f, self.x)
        dz = _each_row(self.residual_z, self.sigmas_h, zp)
        self.K = np.dot(fpa.weighted_outer_sum(self.Wc, dx, dz), self.SI)
        self.y = self.residual_z(z, zp)
        self.x = self.state_add(self.x, np.dot(self.K, self.y))
        self.P = self.P - np.dot(self.K, np.dot(self.S, self.K.T))
        self._store_posterior(z)

    def _store_posterior(self, z):
        self.z = z.copy()
        self.x_post = self.x.copy()  # P_post: at _settle_state
        self._log_likelihood = None
        self._likelihood = None
        self._mahalanobis = None

    def _check_loop_hx(self, hx, dim_z, hx_args):
        """Once per ``hx``: one point must give ``dim_z`` values as an array (not a scalar)."""
        if self._checked.get("hx") is hx:
            return
        h = np.shape(hx(self.sigmas_f[0], **hx_args))
        if h != (dim_z,) and not (len(h) == 2 and np.prod(h) == dim_z):
            raise self._loop_shape_error("hx", h, dim_z)
        self._checked["hx"] = hx

    def _check_measurement(self, z, R):
        """Validate ``z`` and ``R`` together; returns ``(z, R)`` as float arrays.

        Without an ``R`` argument, ``z`` must have ``dim_z`` entries and ``self.R`` be
        ``(dim_z, dim_z)``; with one (another sensor, as filterpy allows), ``R`` must be
        square and match the length of ``z``.
        """
        given = R is not None
        R = self.R if R is None else R
        if type(R) is not np.ndarray and isinstance(R, numbers.Real):  # (an ABC check: skipped for arrays)
            if not given and self._dim_z > 1:  # filterpy's update takes a scalar argument as R * I, but adds a
                raise ValueError(  # scalar attribute to every entry of S: a noise fully correlated between them
                    f"R must have shape ({self._dim_z}, {self._dim_z}), got the scalar {R!r}: a scalar is not a "
                    "covariance here (filterpy would add it to every entry of S, a noise shared by all the "
                    f"measurement's entries): use R = {R!r} * np.eye({self._dim_z}), or np.diag(variances)")
            R = np.eye(self._dim_z if not given else np.size(z)) * R
        R = np.asarray(R, dtype=float)
        z = z.reshape(1) if z.ndim == 0 else z  # np.atleast_1d of the array update made
        m = self._dim_z if not given else (R.shape[0] if R.ndim == 2 else self._dim_z)
        if z.size == m and z.ndim > 1:
            z = z.reshape(m)
        if not given and z.shape != (m,):
            raise ValueError(f"z must have {m} entries, got shape {np.shape(z)}")
        if z.ndim != 1:
            raise ValueError(f"z must be 1-D, got shape {z.shape}")
        if R.shape != (z.size, z.size):
            raise ValueError(f"R must have shape ({z.size}, {z.size}), got shape {R.shape}; "
                             + _SHAPE_FIX["R"].format(n=z.size))
        if not self._unchanged("R", R):  # checked once per content, not every step
            if not np.isfinite(R).all():
                raise ValueError("R must be finite, got non-finite entries; use R = np.diag(variances)")
            _with_fix(check_symmetric, R, "R")
            if cholesky_lower(R) is None:  # a sign slip, or a perfect measurement: P would lose definiteness
                raise ValueError(  # a step later (check_covariance's test, with the step and the remedy)
                    f"R must be positive definite (a measurement noise covariance), got smallest eigenvalue "
                    f"{smallest_eigenvalue(R):.3g} at step {self.step}: R = np.diag(variances) with every variance "
                    "> 0 (R = 0, a perfect measurement, leaves P singular: give it a small variance)")
            self._mark("R", R)
        return z, R

    def _vectorized_update(self, z, R, UT, hx, **hx_args):
        """The vectorized update; returns True when the new ``P`` is known to be finite."""
        hx = self.hx if hx is None else hx
        sig = self.sigmas_f
        # z may change size between sensors (filterpy allows it): the size is R's
        # (R comes from _check_measurement: always square 2-D)
        dim_z = R.shape[0]
        self.sigmas_h = self._call(hx, sig, "hx", dim_z, **hx_args)
        if UT is None:
            zp, S, dz = self._vectorized_ut(
                self.sigmas_h, self.z_mean, self.residual_z, R, ("z_mean_fn", "residual_z")
            )
        else:
            zp, S = UT(self.sigmas_h, self.Wm, self.Wc, R, self.z_mean, self.residual_z)
            dz = self._residual("residual_z", self.residual_z, self.sigmas_h, zp)
        Pxz = self._cross_covariance(sig, dz)
        if S.shape != (1, 1):  # a 1x1 S is its own symmetric part, bit for bit
            S = 0.5 * (S + S.T)
        self.S = S
        self.SI, self.K, u = self._gain(S, Pxz)
        self.y = self.residual_z(z.reshape(np.shape(zp)), zp)
        self.x = self.state_add(self._x_now, self.K @ self.y)
        P_prior = self._P_now
        if u is not None:  # 1x1 S: K S K^T = u u^T, a rank-1 downdate symmetric by construction
            self.P = _downdate(P_prior, u)
        else:
            P = P_prior - self.K @ S @ self.K.T
            self.P = 0.5 * (P + P.T)
        self._store_posterior(z)
        # whether P is known finite without a scan: the points were drawn from P_prior's
        # Cholesky factor (so it is positive definite) and the downdate cannot overflow
        drawn = self._half is not None or self._deviations is not None
        return u is not None and drawn and _downdate_finite(P_prior, u)

    def _cross_covariance(self, sig, dz):
        """``P_xz = sum_i Wc_i (chi_i - x)(h_i - z_hat)^T``, from the draw's deviations if kept."""
        wdz = dz * self.Wc[:, None]
        if self.residual_x is np.subtract and self._half is not None:  # D = [0, cU, -cU]
            n = self._half.shape[0]
            return self._half.T @ (wdz[1 : n + 1] - wdz[n + 1 :])
        if self.residual_x is np.subtract and self._deviations is not None:
            return self._deviations.T @ wdz
        return self._residual("residual_x", self.residual_x, sig, self._x_now).T @ wdz

    def _gain(self, S, Pxz):
        """``(S^-1, K = P_xz S^-1, u)``, ``u = P_xz / sqrt(s)`` for a 1x1 ``S = [[s]]`` (else None).

        A 1x1 ``S`` is divided by (LAPACK's wrappers cost more than the work: a WNN's ``S``
        is 1x1); a larger one is factored and solved (scipy's ``cho_factor``/``cho_solve``
        are these LAPACK calls, without their checks). NumericalError if ``S`` is not PD.
        """
        if S.shape == (1, 1):
            s = float(S[0, 0])
            if not (math.isfinite(s) and s > 0):
                raise self._not_pd("S", S)
            return np.array([[1.0 / s]]), Pxz / s, Pxz[:, 0] / math.sqrt(s)
        c, info = dpotrf(S, lower=1, clean=0)
        if info != 0 or not np.isfinite(S).all():
            raise self._not_pd("S", S)
        return dpotrs(c, np.eye(S.shape[0]), lower=1)[0], dpotrs(c, Pxz.T, lower=1)[0].T, None

    def _rows_residual(self, A, b):
        """``residual_x`` of every row of ``A`` against ``b``, in either mode."""
        if self.residual_x is np.subtract:
            return A - b
        if self.vectorized:
            return self._residual("residual_x", self.residual_x, A, b)
        return np.array([self.residual_x(a, b) for a in A], dtype=float)

    # ------------------------------------------------------------------ smoother
    def rts_smoother(self, Xs, Ps, Qs=None, dts=None, UT=None):
        """Rauch-Tung-Striebel smoother over ``batch_filter`` output (filterpy's API).

        Honours ``vectorized`` and ``fx=None`` (then the smoother gain is
        ``P_k (P_k + Q)^{-1}``, applied by solves).

        Returns
        -------
        xs : ndarray of shape (n_steps, dim_x)
        Ps : ndarray of shape (n_steps, dim_x, dim_x)
        Ks : ndarray of shape (n_steps, dim_x, dim_x)
        """
        if self.fx is not None and not self.vectorized:
            return super().rts_smoother(Xs, Ps, Qs=Qs, dts=dts, UT=UT)
        if len(Xs) != len(Ps):
            raise ValueError(f"Xs and Ps must have the same length, got {len(Xs)} and {len(Ps)}")
        Xs = np.asarray(Xs, dtype=float)
        n, dim_x = Xs.shape
        dts = [self._dt] * n if dts is None else ([dts] * n if np.isscalar(dts) else dts)
        Qs = [self.Q] * n if Qs is None else Qs
        UT = unscented_transform if UT is None else UT
        xs, ps = Xs.copy(), np.array(Ps, dtype=float)
        Ks = np.zeros((n, dim_x, dim_x))
        for k in reversed(range(n - 1)):
            sigmas = self._sigmas(xs[k], ps[k], "P", fresh=True)
            if self.fx is None:
                sigmas_f = sigmas
            else:
                sigmas_f = self._call(self.fx, sigmas, "fx", dim_x, dts[k])
            xb, Pb = UT(sigmas_f, self.Wm, self.Wc, Qs[k], self.x_mean, self.residual_x)
            dyf = self._rows_residual(sigmas_f, xb)
            dzs = self._rows_residual(sigmas, Xs[k])
            Pxb = (dzs.T * self.Wc) @ dyf
            try:
                cf = cho_factor(0.5 * (Pb + Pb.T), lower=True)
            except np.linalg.LinAlgError as exc:
                raise NumericalError(
                    f"predicted covariance is not positive definite at smoother step {k}",
                    matrix="P_prior", step=k,
                ) from exc
            K = cho_solve(cf, Pxb.T).T
            xs[k] = xs[k] + K @ self.residual_x(xs[k + 1], xb)
            ps[k] = ps[k] + K @ (ps[k + 1] - Pb) @ K.T
            Ks[k] = K
        return xs, ps, Ks
