r"""Banks of independent Kalman filters in one object: B filters, one call per step.

Monte Carlo runs, a fleet of targets, the components of a Gaussian sum: many filters of
the same model, each with its own state. A Python loop over B filter objects pays the
fixed cost of a step B times; a bank keeps the states stacked, ``x (B, n)``,
``P (B, n, n)``, and runs every member's step in one batched call of
:mod:`filterwnn.kalman.batched` (one stacked Cholesky, the model called once on all
``B * n_sigmas`` sigma points).

The banks read like filterpy's filters, with a leading member axis:

:class:`UnscentedKalmanFilterBank`
    ``(B, dim_x, dim_z, dt, hx, fx, points)`` as filterpy's ``UnscentedKalmanFilter``
    (Merwe points for the UKF, reduced ones such as
    :class:`~filterwnn.kalman.sigma_points.SphericalSimplexSigmaPoints` for the SUKF);
:class:`ExtendedKalmanFilterBank`
    the same with ``FJacobian``/``HJacobian`` (the extended step);
:class:`KalmanFilterBank`
    ``(B, dim_x, dim_z)`` with the matrices ``F`` and ``H``, as filterpy's ``KalmanFilter``.

Each member ``i`` is the filter

.. math::
    x^-_i, P^-_i = \mathrm{predict}(x_i, P_i; Q_i), \qquad
    x_i, P_i = \mathrm{update}(x^-_i, P^-_i, z_i; R_i),

with ``Q``/``R`` shared, ``(n, n)``, or one per member, ``(B, n, n)``, checked when they
are assigned (not on every step). ``update(z)`` takes one measurement per member,
``z (B, dim_z)``, or one shared ``(dim_z,)``; a NaN row (or ``mask[i] = False``, or
``z=None`` for all) leaves that member at its prediction with ``log_likelihood[i] = 0``.
``fx``/``hx`` with ``vectorized=True`` (the default) receive every member's sigma points
at once, one row per point, ``(B * n_sigmas, dim_x)``; ``vectorized=False`` calls them
once per point (filterpy's signature). For a bank of small filters (``n <= 8``, 256 members or more)
the rows are a strided view of an array stored state-component first, not a C-ordered
copy: NumPy code reads it the same; code that needs C order (numba with a C layout,
``.view``) should call ``np.ascontiguousarray`` first. Write the result to a new array,
not into the rows. Errors name the member and the step.

A bank agrees with B independent filterpy (or filterwnn) filters to 1e-12 (see
``tests/kalman/test_bank.py``).

With numba installed (``pip install "filterwnn[fast]"``), :class:`UnscentedKalmanFilterBank`
runs its arithmetic for ``dim_x <= 8`` in compiled kernels (``filterwnn.kalman._compiled``;
``compiled=None``, the default, takes them when numba imports): the model is called as
before, and the numbers agree with the NumPy step to rounding (1e-12, not bit for bit), a
member's numbers the same wherever it sits in the bank. It is 1.4-1.9x faster than the NumPy
step at 1,000-10,000 members (``benchmarks/bench_peers.py``); ``compiled=False`` keeps the
NumPy step.

>>> import numpy as np
>>> from filterwnn.kalman.presets import make_points
>>> fx = lambda X, dt: X @ np.array([[1.0, dt], [0.0, 1.0]]).T
>>> hx = lambda X: X[:, :1]
>>> bank = UnscentedKalmanFilterBank(3, 2, 1, 1.0, hx, fx, make_points("merwe", 2))
>>> bank.R = np.array([[0.5]])
>>> bank.predict()
>>> bank.update(np.array([[1.0], [np.nan], [2.0]]))      # member 1 not observed
>>> bank.x.shape, bank.P.shape, float(bank.log_likelihood[1])
((3, 2), (3, 2, 2), 0.0)
>>> means, covs = bank.batch_filter(np.zeros((4, 3, 1)))
>>> means.shape, covs.shape
((4, 3, 2), (4, 3, 2, 2))
"""

from __future__ import annotations

import numpy as np

from .._linalg import first_not_pd
from .._validation import NumericalError, cholesky_lower, check_points_protocol, check_positive, check_positive_int
from . import _compiled
from .batched import ExtendedStep, KalmanModel, KalmanPrediction, LinearStep, UnscentedStep, check_callable, repairing

__all__ = ["UnscentedKalmanFilterBank", "ExtendedKalmanFilterBank", "KalmanFilterBank"]


def _stack(M, name, B, dim, *, kind):
    """``M`` as a float ``(dim, dim)`` (shared) or ``(B, dim, dim)`` (per member) matrix, checked.

    ``kind``: ``"pd"`` positive definite, ``"psd"`` positive semi-definite, ``"any"`` square.
    A scalar means ``M * I``. The error names the first failing member.
    """
    M = np.asarray(M, dtype=float)
    if M.ndim == 0:
        M = float(M) * np.eye(dim)
    if M.shape not in ((dim, dim), (B, dim, dim)):
        raise ValueError(f"{name} must have shape ({dim}, {dim}) (shared) or ({B}, {dim}, {dim}) (one per "
                         f"member), got shape {M.shape}")
    rows = M.reshape(-1, dim, dim)
    finite = np.isfinite(rows).all(axis=(1, 2))
    if not finite.all():
        raise ValueError(f"{name} must be finite, got non-finite entries{_of_member(M, np.argmin(finite))}")
    if kind == "any":
        return M
    asym = np.abs(rows - np.swapaxes(rows, -1, -2)).max(axis=(1, 2)) > 1e-8 * np.maximum(
        1.0, np.abs(rows).max(axis=(1, 2)))
    if asym.any():
        raise ValueError(f"{name} must be symmetric{_of_member(M, np.argmax(asym))}")
    if kind == "pd" and cholesky_lower(rows) is None:
        bad = first_not_pd(rows)
        raise ValueError(f"{name} must be positive definite{_of_member(M, bad)}")
    if kind == "psd":
        low = np.linalg.eigvalsh(rows).min(axis=1) < -1e-10 * np.maximum(np.abs(rows).max(axis=(1, 2)), 1e-300)
        if low.any():
            raise ValueError(f"{name} must be positive semi-definite{_of_member(M, np.argmax(low))}")
    return M


def _of_member(M, i):
    return f" (member {int(i)})" if np.ndim(M) == 3 else ""


class _Checked(property):
    """A bank attribute kept as ``_<name>`` and checked when assigned: ``bank.<name> = value``
    stores ``check(bank, value)`` (which raises ``ValueError`` naming the attribute). A ``property``
    (as :class:`_Copy`), so that filterpy's ``Saver``, which reads a filter's properties at each
    ``save()``, records ``x`` and ``P`` under their names."""

    def __init__(self, check, doc=None):
        super().__init__(doc=doc)
        self.check = check

    def __set_name__(self, owner, name):
        self.slot = "_" + name

    def __get__(self, obj, objtype=None):
        return self if obj is None else getattr(obj, self.slot)

    def __set__(self, obj, value):
        setattr(obj, self.slot, self.check(obj, value))


def _member_states(bank, value):
    """``x`` as ``(B, dim_x)`` finite floats (one ``(dim_x,)`` for all members); the error names the member."""
    X = np.asarray(value, dtype=float)
    if X.shape == (bank.dim_x,):
        X = np.broadcast_to(X, (bank.B, bank.dim_x))
    if X.shape != (bank.B, bank.dim_x):
        raise ValueError(f"x must have shape ({bank.B}, {bank.dim_x}) or ({bank.dim_x},), got shape {X.shape}")
    bad = ~np.isfinite(X).all(axis=1)
    if bad.any():
        raise ValueError(f"x must be finite, got non-finite entries (member {int(np.argmax(bad))})")
    return np.array(X)


def _member_covariances(bank, value):
    """``P`` as ``(B, dim_x, dim_x)`` positive-definite matrices (one shared is copied to every member)."""
    P = _stack(value, "P", bank.B, bank.dim_x, kind="pd")
    return np.array(np.broadcast_to(P, (bank.B, bank.dim_x, bank.dim_x)))


def _measurement_matrix(bank, value):
    """``H`` as a finite ``(dim_z, dim_x)`` (shared) or ``(B, dim_z, dim_x)`` array."""
    H = np.asarray(value, dtype=float)
    if H.shape not in ((bank.dim_z, bank.dim_x), (bank.B, bank.dim_z, bank.dim_x)) or not np.isfinite(H).all():
        raise ValueError(f"H must be finite of shape ({bank.dim_z}, {bank.dim_x}) or ({bank.B}, {bank.dim_z}, "
                         f"{bank.dim_x}), got shape {H.shape}")
    return H


class _Copy(property):
    """``x_prior``/``P_prior``/``x_post``/``P_post``: the step keeps a reference (``bank._pending``),
    copied at the first read of any of them or of ``x``/``P`` (:meth:`_Bank._settle`), so a
    bank whose copies nobody reads never makes them; what a reader sees is the eager copy."""

    def __set_name__(self, owner, name):
        self.name, self.slot = name, "_" + name

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        obj._settle()
        return obj.__dict__.get(self.slot)

    def __set__(self, obj, value):
        obj._settle()
        obj.__dict__[self.slot] = value


class _Live(_Checked):
    """``x``/``P``: as :class:`_Checked`, and a read first makes the copies the step left pending
    (an edit in place of the array read must not reach ``x_prior`` and the others)."""

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        if obj.__dict__.get("_pending"):
            obj._settle()
        return getattr(obj, self.slot)


class _Bank:
    """What the banks share: the stacked state, the noise checked when assigned, the step loop."""

    _kind = "filter"
    #: keep copies in ``x_prior``/``P_prior``/``x_post``/``P_post`` (a bank of components does not)
    _keep_copies = True

    @classmethod
    def of_components(cls, model, kalman_step, x, P):
        """A bank around a filter's own ``model`` and batched ``kalman_step`` (the components of a
        mixture filter): ``x``/``P`` taken as they are, ``Q``/``R`` read from the model (checked
        by its owner), ``model.recover`` repairing a non-PD covariance with a warning, and no
        prior/posterior copies kept."""
        bank = cls.__new__(cls)
        bank.B, bank.dim_x, bank.dim_z, bank.dt = x.shape[0], model.dim_x, model.dim_z, model.dt
        bank._model, bank._step = model, kalman_step
        bank._x, bank._P, bank._Q, bank._R = x, P, None, None
        bank.step, bank.log_likelihood = 0, np.zeros(bank.B)
        bank._keep_copies = False
        bank.x_prior = bank.P_prior = bank.x_post = bank.P_post = None
        return bank

    def set_state(self, x, P):
        """Replace every member's ``x (B, n)`` and ``P (B, n, n)`` as they are, unchecked (for an
        owner that produced them, e.g. a mixture filter resampling its components)."""
        self._x, self._P = x, P

    def _setup(self, B, dim_x, dim_z, dt):
        self.B = check_positive_int(B, "B")
        self.dim_x = check_positive_int(dim_x, "dim_x")
        self.dim_z = check_positive_int(dim_z, "dim_z")
        self.dt = check_positive(dt, "dt")
        self._x = np.zeros((self.B, self.dim_x))
        self._P = np.broadcast_to(np.eye(self.dim_x), (self.B, self.dim_x, self.dim_x)).copy()
        self._Q = np.eye(self.dim_x)
        self._R = np.eye(self.dim_z)
        self.step = 0
        self.log_likelihood = np.zeros(self.B)
        self._pending = None
        self.x_prior, self.P_prior = self._x.copy(), self._P.copy()
        self.x_post, self.P_post = self._x.copy(), self._P.copy()

    # --- the state, checked when assigned --------------------------------------------------
    x = _Live(_member_states, "Member states, shape ``(B, dim_x)``; assign ``(B, dim_x)`` or one "
              "``(dim_x,)`` for all.")
    P = _Live(_member_covariances, "Member covariances, shape ``(B, dim_x, dim_x)``; assign one per "
              "member or one for all.")
    Q = _Checked(lambda bank, value: _stack(value, "Q", bank.B, bank.dim_x, kind="psd"),
                 """Process noise, ``(dim_x, dim_x)`` shared or ``(B, dim_x, dim_x)``; checked (symmetric,
        positive semi-definite) when assigned. Replace it rather than edit it in place.""")
    R = _Checked(lambda bank, value: _stack(value, "R", bank.B, bank.dim_z, kind="pd"),
                 """Measurement noise, ``(dim_z, dim_z)`` shared or ``(B, dim_z, dim_z)``; checked (symmetric,
        positive definite) when assigned.""")

    x_prior, P_prior, x_post, P_post = _Copy(), _Copy(), _Copy(), _Copy()

    def _keep(self, which):
        """After a step: ``x_<which>``/``P_<which>`` are to be copies of ``x``/``P`` (made when read)."""
        if self._keep_copies:
            pending = self.__dict__.get("_pending") or {}
            pending[which] = (self._x, self._P)
            self._pending = pending

    def __setstate__(self, state):
        for name in ("x_prior", "P_prior", "x_post", "P_post"):  # pickled when they were plain attributes
            if name in state:
                state["_" + name] = state.pop(name)
        self.__dict__.update(state)

    def _settle(self):
        """Make the copies the steps left pending (see :class:`_Copy`)."""
        pending = self.__dict__.get("_pending")
        if pending:
            self._pending = None
            for which, (x, P) in pending.items():
                self.__dict__["_x_" + which], self.__dict__["_P_" + which] = x.copy(), P.copy()

    # --- errors that name the member -------------------------------------------------------
    def _numerical(self, exc, stage, P, step):
        """``exc`` from a batched step, re-raised naming the member (the first non-PD ``P``)."""
        bad = first_not_pd(P)
        who = f"member {bad}" if bad is not None else "a member"
        remedy = "check Q" if stage == "predict" else "check R and the measurement function"
        return NumericalError(f"{type(self).__name__}.{stage} at step {step}, {who}: {exc}; {remedy}",
                              matrix=exc.matrix, step=step)

    def _check_finite(self, x, P, stage, step, remedy):
        if np.isfinite(x).all() and np.isfinite(P).all():  # one pass each; the member is found only on failure
            return
        bad = ~(np.isfinite(x).all(axis=1) & np.isfinite(P).all(axis=(1, 2)))
        if bad.any():
            raise NumericalError(f"{type(self).__name__}.{stage} at step {step}: non-finite result for member "
                                 f"{int(np.argmax(bad))} ({remedy})", matrix="P", step=step)

    def _measurements(self, z, mask):
        """``z`` as ``(dim_z,)`` or ``(B, dim_z)`` and the observed mask (None: all)."""
        z = np.asarray(z, dtype=float)
        if z.shape not in ((self.dim_z,), (self.B, self.dim_z)):
            if z.shape == () and self.dim_z == 1:
                z = z.reshape(1)
            else:
                raise ValueError(f"z must have shape ({self.B}, {self.dim_z}) (one per member) or "
                                 f"({self.dim_z},) (shared), got shape {z.shape}")
        rows = z.reshape(-1, self.dim_z)
        if mask is None and np.isfinite(rows).all():  # the usual case in one pass: every member observed
            return z, None
        nan = np.isnan(rows)
        part = nan.any(axis=1) & ~nan.all(axis=1)
        if part.any() or np.isinf(rows).any():
            i = int(np.argmax(part | np.isinf(rows).any(axis=1)))
            raise ValueError(f"z of member {i} must be finite, or all NaN for a missing measurement, got {rows[i]}")
        observed = ~nan.all(axis=1)
        if mask is not None:
            m = np.asarray(mask)
            if m.shape != (self.B,) or m.dtype != bool:
                raise ValueError(f"mask must be a boolean array of shape ({self.B},), got {m.dtype} {m.shape}")
            observed = observed & m
        if observed.size == 1:
            observed = np.broadcast_to(observed, (self.B,))
        return z, (None if observed.all() else observed)

    # --- filterpy's loop ----------------------------------------------------------------
    def predict(self, **fx_args):
        """Advance the step and predict every member; ``fx_args`` go to ``fx`` (and ``FJacobian``)."""
        step = self.step + 1
        try:
            pred, _ = repairing(self._model, lambda C: self._predict(C, fx_args, step), self._P, step, "posterior",
                                stacklevel=6)
        except NumericalError as exc:
            raise self._numerical(exc, "predict", self._P, step) from exc
        self._check_finite(pred.x, pred.P, "predict", step, "check fx and Q")
        self._x, self._P = pred
        self.step = step
        self._keep("prior")

    def update(self, z, R=None, mask=None, **hx_args):
        """Update every observed member with its measurement.

        Parameters
        ----------
        z : array-like of shape (B, dim_z) or (dim_z,), or None
            One measurement per member (a NaN row: that member is not observed), or one
            shared by all; None observes no member.
        R : array-like of shape (dim_z, dim_z) or (B, dim_z, dim_z), optional
            This update's measurement noise (checked), else ``self.R``.
        mask : array-like of bool, shape (B,), optional
            False for members not observed now.
        **hx_args
            Passed to ``hx`` (and ``HJacobian``).

        An update that is refused (a bad ``z``, ``R`` or ``mask``) or fails (``NumericalError``
        naming the member and the step) leaves ``x``, ``P`` and ``log_likelihood`` as they were.
        """
        if z is None:
            self.log_likelihood = np.zeros(self.B)
            self._posterior()
            return
        z, observed = self._measurements(z, mask)
        R = self._R if R is None else _stack(R, "R", self.B, self.dim_z, kind="pd")
        if observed is not None and not observed.any():
            self.log_likelihood = np.zeros(self.B)
            self._posterior()
            return
        try:
            upd = self._update(KalmanPrediction(self._x, self._P), z, R, observed, hx_args)
        except NumericalError as exc:
            raise self._numerical(exc, "update", self._P, self.step) from exc
        self._check_finite(upd.x, upd.P, "update", self.step, "check hx and R")
        self._x, self._P, self.log_likelihood = upd.x, upd.P, upd.log_likelihood
        self._posterior()

    def _posterior(self):
        self._keep("post")

    def batch_filter(self, zs, fx_args=None, hx_args=None, saver=None):
        """Run ``predict``/``update`` over a sequence of measurements.

        Parameters
        ----------
        zs : array-like of shape (n_steps, B, dim_z) or (n_steps, dim_z), or a sequence with None
            One measurement per member and step (NaN rows: missing), or one shared per step.
        fx_args, hx_args : dict, optional
            Keywords for every ``predict``/``update``.
        saver : filterpy.common.Saver, optional
            ``saver.save()`` after every step, as filterpy's ``batch_filter`` calls it.

        Returns
        -------
        means : ndarray of shape (n_steps, B, dim_x)
        covariances : ndarray of shape (n_steps, B, dim_x, dim_x)
            The posterior of every member after each update.
        """
        fx_args = {} if fx_args is None else dict(fx_args)
        hx_args = {} if hx_args is None else dict(hx_args)
        n = len(zs)
        means = np.empty((n, self.B, self.dim_x))
        covs = np.empty((n, self.B, self.dim_x, self.dim_x))
        for k in range(n):
            self.predict(**fx_args)
            self.update(zs[k], **hx_args)
            means[k], covs[k] = self._x, self._P
            if saver is not None:
                saver.save()
        return means, covs

    def __repr__(self):
        return f"{type(self).__name__}(B={self.B}, dim_x={self.dim_x}, dim_z={self.dim_z}, step={self.step})"


class _NonlinearBank(_Bank):
    """A bank whose step runs the model's callables (unscented or extended)."""

    def _predict(self, P, fx_args, step):
        return self._step.predict(self._model, self._x, P, fx_args, step, Q=self._Q)

    def _update(self, prediction, z, R, observed, hx_args):
        return self._step.update(self._model, prediction, z, hx_args, self.step, R=R, mask=observed)


class UnscentedKalmanFilterBank(_NonlinearBank):
    """B independent unscented Kalman filters, stepped together (filterpy's UKF, batched).

    Parameters
    ----------
    B : int
        Number of members.
    dim_x, dim_z : int
    dt : float
        Passed to ``fx(X, dt, **fx_args)``.
    hx : callable
        ``hx(X, **hx_args)``: with ``vectorized=True`` ``X`` holds every member's sigma
        points, ``(B * n_sigmas, dim_x)`` (members in order, each member's points in
        ``points``' order), and it returns ``(B * n_sigmas, dim_z)``; else one point.
    fx : callable or None
        ``fx(X, dt, **fx_args)`` likewise; None is a random walk (``P^- = P + Q``).
    points : sigma-point object
        filterpy's protocol (``n == dim_x``): Merwe's set for the UKF, a reduced set
        (:class:`~filterwnn.kalman.sigma_points.SphericalSimplexSigmaPoints`) for the SUKF.
    x_mean_fn, z_mean_fn, residual_x, residual_z : callable, optional
        As in filterpy's ``UnscentedKalmanFilter`` (with ``vectorized=True`` the residuals
        get whole arrays; the mean functions get one member's points and the weights).
    vectorized : bool, default True
    compiled : bool or None, default None
        Run the step's arithmetic in compiled kernels (``filterwnn.kalman._compiled``,
        numba) for ``dim_x <= 8``: 1.4-1.9x as fast for a bank of many small filters, the
        same numbers to rounding (not bit for bit), the same errors. Mean and residual
        functions (an angle residual, a circular mean) are called in NumPy as on the NumPy
        step, and the kernels take the deviations they give. None: when numba is installed
        (``pip install "filterwnn[fast]"``); True: required (``ImportError`` without numba);
        False: the NumPy step. ``fx`` and ``hx`` are called as without it. The first use on a
        machine compiles the kernels (a few seconds, cached beside the module).

    Attributes
    ----------
    x : ndarray of shape (B, dim_x)
    P : ndarray of shape (B, dim_x, dim_x)
    Q, R : ndarray of shape (n, n) or (B, n, n)
        Identity by default (filterpy's); checked when assigned.
    x_prior, P_prior, x_post, P_post : ndarray
        After the last ``predict`` / ``update`` (copies, made when first read).
    log_likelihood : ndarray of shape (B,)
        ``log N(z_i; z_pred_i, S_i)`` at the last update (0 for members not observed).
    step : int
    compiled : bool
        Whether the steps run the compiled kernels (read-only): False without numba, with
        ``compiled=False`` and for ``dim_x > 8``.
    """

    _kind = "ukf"
    x, P, Q, R = _Bank.x, _Bank.P, _Bank.Q, _Bank.R  # (in this class's namespace, so that its page documents them)

    def __init__(self, B, dim_x, dim_z, dt, hx, fx, points, *, x_mean_fn=None, z_mean_fn=None,
                 residual_x=None, residual_z=None, vectorized=True, compiled=None):
        self._setup(B, dim_x, dim_z, dt)
        check_points_protocol(points, ("n", "Wm", "Wc", "num_sigmas", "sigma_points"))
        if points.n != self.dim_x:
            raise ValueError(f"points.n must equal dim_x={self.dim_x}, got {points.n}")
        self.points = points
        if compiled is None:
            compiled = _compiled.available()
        elif compiled and not _compiled.available():
            raise ImportError("compiled=True needs numba: pip install \"filterwnn[fast]\" (or compiled=False: "
                              "the NumPy step, the same numbers to rounding)")
        self._step = UnscentedStep(points, compiled=compiled)
        self._model = KalmanModel(
            self.dim_x, self.dim_z, self.dt, check_callable(fx, "fx"), check_callable(hx, "hx", False),
            vectorized=bool(vectorized), x_mean_fn=check_callable(x_mean_fn, "x_mean_fn"),
            z_mean_fn=check_callable(z_mean_fn, "z_mean_fn"),
            residual_x=check_callable(residual_x, "residual_x"),
            residual_z=check_callable(residual_z, "residual_z"),
        )


    @property
    def compiled(self):
        return self._step.runs_compiled(self.dim_x)


class ExtendedKalmanFilterBank(_NonlinearBank):
    """B independent extended Kalman filters, stepped together.

    Parameters
    ----------
    B, dim_x, dim_z, dt, hx, fx
        As in :class:`UnscentedKalmanFilterBank`, with ``vectorized=True`` called on the
        members' states, ``(B, dim_x)``.
    FJacobian : callable
        ``FJacobian(X, dt, **fx_args)`` -> ``(B, dim_x, dim_x)`` (or one shared matrix);
        needed unless ``fx`` is None.
    HJacobian : callable
        ``HJacobian(X, **hx_args)`` -> ``(B, dim_z, dim_x)`` (or one shared matrix).
    residual_z : callable, optional
    vectorized : bool, default True

    Attributes are those of :class:`UnscentedKalmanFilterBank`.
    """

    _kind = "ekf"
    x, P, Q, R = _Bank.x, _Bank.P, _Bank.Q, _Bank.R  # (in this class's namespace, so that its page documents them)

    def __init__(self, B, dim_x, dim_z, dt, hx, fx, FJacobian, HJacobian, *, residual_z=None, vectorized=True):
        self._setup(B, dim_x, dim_z, dt)
        if fx is not None and FJacobian is None:
            raise ValueError("ExtendedKalmanFilterBank needs FJacobian when fx is given, got None")
        self._step = ExtendedStep()
        self._model = KalmanModel(
            self.dim_x, self.dim_z, self.dt, check_callable(fx, "fx"), check_callable(hx, "hx", False),
            vectorized=bool(vectorized), FJacobian=check_callable(FJacobian, "FJacobian"),
            HJacobian=check_callable(HJacobian, "HJacobian", False),
            residual_z=check_callable(residual_z, "residual_z"),
        )


class KalmanFilterBank(_Bank):
    """B independent linear Kalman filters, stepped together (filterpy's ``KalmanFilter``, batched).

    Parameters
    ----------
    B, dim_x, dim_z : int
    dt : float, default 1.0
        Kept for symmetry with the other banks (``F`` holds the dynamics).

    Attributes
    ----------
    F : ndarray of shape (dim_x, dim_x) or (B, dim_x, dim_x)
        State transition (identity by default); checked when assigned.
    H : ndarray of shape (dim_z, dim_x) or (B, dim_z, dim_x)
        Measurement matrix (zeros by default, as filterpy's).
    x, P, Q, R, x_prior, P_prior, x_post, P_post, log_likelihood, step
        As in :class:`UnscentedKalmanFilterBank`.
    """

    _kind = "kf"
    x, P, Q, R = _Bank.x, _Bank.P, _Bank.Q, _Bank.R  # (in this class's namespace, so that its page documents them)

    def __init__(self, B, dim_x, dim_z, dt=1.0):
        self._setup(B, dim_x, dim_z, dt)
        self._step = LinearStep()
        self._model = KalmanModel(self.dim_x, self.dim_z, self.dt)
        self._F = np.eye(self.dim_x)
        self._H = np.zeros((self.dim_z, self.dim_x))

    F = _Checked(lambda bank, value: _stack(value, "F", bank.B, bank.dim_x, kind="any"))
    H = _Checked(_measurement_matrix)

    def _predict(self, P, fx_args, step):
        if fx_args:
            raise TypeError(f"KalmanFilterBank.predict takes no keywords (F holds the model), got {sorted(fx_args)}")
        return self._step.predict(self._model, self._x, P, self._F, step, Q=self._Q)

    def _update(self, prediction, z, R, observed, hx_args):
        if hx_args:
            raise TypeError(f"KalmanFilterBank.update takes no model keywords (H holds the model), got {sorted(hx_args)}")
        return self._step.update(self._model, prediction, z, self._H, self.step, R=R, mask=observed)
