r"""Reduced sigma-point sets (n + 2 points) for filterpy's unscented filters.

An unscented transform represents a Gaussian ``N(x, P)`` by sigma points
:math:`\chi_i = x + (Z U)_i` with weights ``Wm`` (mean) and ``Wc`` (covariance), where
``U`` is the upper Cholesky factor (``P = U^T U``, filterpy's convention) and ``Z`` is a
fixed set of *unit points* whose weighted mean is 0 and weighted covariance the
identity. filterpy's :class:`~filterpy.kalman.MerweScaledSigmaPoints` uses the
symmetric set of ``2n + 1`` points. The two classes here use ``n + 2``:

:class:`MinimalSkewSigmaPoints`
    Julier and Uhlmann (2002), the *minimal skew simplex*. Weights
    :math:`W_1 = W_2 = (1 - W_0) / 2^n`, :math:`W_j = 2^{j-2} W_1` for
    ``j = 3 .. n+1`` (they sum to 1), and unit points built column by column:
    for dimension ``j`` the points ``1..j`` get :math:`-1/\sqrt{2 W_{j+1}}` and point
    ``j+1`` gets :math:`+1/\sqrt{2 W_{j+1}}`. It matches the first three moments with
    the least skew, but the points spread like :math:`2^{n/2}` (about ``1e24`` at
    ``n = 160``, with weights near ``1e-49``), so it is for small states only.

:class:`SphericalSimplexSigmaPoints`
    Julier (2003), the *spherical simplex*. Equal weights
    :math:`W_i = (1 - W_0)/(n + 1)`; for dimension ``j`` the points ``1..j`` get
    :math:`-1/\sqrt{j (j+1) W_1}` and point ``j+1`` gets :math:`j/\sqrt{j (j+1) W_1}`.
    All outer points lie on a sphere of radius :math:`\sqrt{n / (1 - W_0)}`. This is the
    set that equations (1)-(4) of Niu, Wu and Li (the first paper) describe once the
    extraction damage is undone (equal weights ``(1 - W0)/(n + 1)``, the ``j(j+1)``
    recursion), and the one that works for a 160-dimensional weight vector.

Both use the *scaled* unscented transformation of Julier (2002): points
:math:`\chi_0 + \alpha (\chi_i - \chi_0)`, weights
:math:`W'_0 = W_0/\alpha^2 + 1 - 1/\alpha^2`, :math:`W'_i = W_i / \alpha^2`, and
:math:`W^c_0 = W'_0 + 1 - \alpha^2 + \beta` for the covariance. With ``alpha = 1`` and
``beta = 0`` they are the unscaled sets.

Both subclass filterpy's :class:`~filterpy.kalman.MerweScaledSigmaPoints` and take its
arguments, ``(n, alpha, beta, kappa, sqrt_method=None, subtract=None)``, positionally and
with its meanings: ``kappa`` sets the unscaled centre weight ``w0 = kappa / (n + kappa)``
(the weight it gives the symmetric set), so the centre weights are Merwe's for the same
``(alpha, beta, kappa)``; the reduced set's own parameter ``w0=`` is keyword-only. So they
drop into ``filterpy.kalman.UnscentedKalmanFilter(points=...)`` unchanged, and
``from filterwnn import SphericalSimplexSigmaPoints as MerweScaledSigmaPoints`` runs
filterpy's own ``test_ukf.py`` (``tests/kalman/test_filterpy_suite.py``).

>>> import numpy as np
>>> pts = SphericalSimplexSigmaPoints(3, w0=0.2)
>>> pts.num_sigmas()
5
>>> sig = pts.sigma_points(np.zeros(3), np.eye(3))
>>> np.allclose(pts.Wm @ sig, 0), np.allclose((sig.T * pts.Wc) @ sig, np.eye(3))
(True, True)
>>> np.allclose(np.linalg.norm(sig[1:], axis=1), np.sqrt(3 / 0.8))
True

Which to use
------------
Measured in ``notebooks/01_sigma_points.ipynb`` and ``benchmarks/bench_sigma_points.py``:

* the most accurate transform, when model calls are cheap: filterpy's
  :class:`~filterpy.kalman.MerweScaledSigmaPoints` (``2n + 1`` points);
* fewer model calls and less time at any ``n``: :class:`SphericalSimplexSigmaPoints`.
  With ``w0 = 0`` it is filterpy's :class:`~filterpy.kalman.SimplexSigmaPoints`
  reflected through the mean, plus a centre of weight 0 (which filterpy's UKF still
  evaluates; ``w0 > 0`` makes it count). Over many runs of a range-bearing tracker the
  two, and Merwe's set, track equally well; a single run can favour either orientation.
  Its points are built without a Python loop, so in filterpy's own UKF a step costs
  less than with Merwe's set from ``n = 2``;
* :class:`MinimalSkewSigmaPoints` for small ``n`` only (its accuracy falls with ``n``
  and its points spread like ``2^{n/2}``; it warns above ``n = 20``).

References
----------
S. J. Julier and J. K. Uhlmann, "Reduced sigma point filters for the propagation of
means and covariances through nonlinear transformations", ACC 2002.
S. J. Julier, "The scaled unscented transformation", ACC 2002.
S. J. Julier, "The spherical simplex unscented transformation", ACC 2003.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from filterpy.common import pretty_str
from filterpy.kalman import JulierSigmaPoints, MerweScaledSigmaPoints

from .._linalg import staircase_apply, staircase_sigma_points, staircase_transpose_apply, symmetric_sigma_points
from .._validation import NumericalError, check_points_protocol, check_positive_int, check_symmetric

__all__ = [
    "MinimalSkewSigmaPoints",
    "SphericalSimplexSigmaPoints",
    "centre_weight",
    "unit_sigma_points",
    "point_structure",
    "sigma_deviations",
    "batched_sigma_points",
    "unit_transpose_apply",
]

#: Above this size :class:`MinimalSkewSigmaPoints` warns that its points spread too far.
MINIMAL_SKEW_WARN_N = 20

#: Up to this size ``sigma_points`` forms ``Z @ U`` densely (fewer NumPy calls, faster at
#: small n); above it the O(n^2) staircase recursion (benchmarks/bench_sigma_points.py).
_DENSE_MAX_N = 32


def _nearly_symmetric(P, tol=1e-8):
    """A fast pre-check of the package's symmetry rule (``check_symmetric``).

    For a covariance ``max|P|`` is on the diagonal, so the diagonal sets the scale; when
    this says no (an asymmetric or an indefinite ``P``), ``check_symmetric`` decides.
    """
    return float(np.abs(P - P.T).max()) <= tol * float(P.diagonal().max())


def _check_scaling(alpha, beta, w0):
    for name, value in (("alpha", alpha), ("beta", beta), ("w0", w0)):
        if isinstance(value, bool) or not np.isscalar(value) or not np.isfinite(value):
            raise ValueError(f"{name} must be a finite real number, got {value!r}")
    if alpha <= 0:
        raise ValueError(f"alpha must be > 0, got {alpha}")
    if not w0 < 1:
        raise ValueError(f"w0 must satisfy w0 < 1 (the outer points share 1 - w0), got {w0}")
    return float(alpha), float(beta), float(w0)


def centre_weight(n, kappa=0.0, w0=None):
    r"""The reduced set's unscaled centre weight ``w0`` from filterpy's ``kappa``, or ``w0`` itself.

    filterpy's :class:`~filterpy.kalman.MerweScaledSigmaPoints` is Julier's (2002) scaled
    transform applied to the symmetric set whose centre weight is
    :math:`W_0 = \kappa / (n + \kappa)`. Applying the same scaling to an ``n + 2`` set
    with that centre weight gives *Merwe's* centre weights for the same
    ``(alpha, beta, kappa)``: :math:`W^m_0 = \lambda / (n + \lambda)` and
    :math:`W^c_0 = W^m_0 + 1 - \alpha^2 + \beta` with
    :math:`\lambda = \alpha^2 (n + \kappa) - n`, and (for the spherical simplex) the
    outer points on Merwe's sphere, radius :math:`\alpha \sqrt{n + \kappa}`.

    Parameters
    ----------
    n : int
    kappa : float, default 0.0
        filterpy's ``kappa``; needs ``n + kappa > 0`` (filterpy's scaled transform
        divides by it).
    w0 : float, optional
        The centre weight itself (``w0 < 1``); then ``kappa`` must stay 0.

    Returns
    -------
    w0 : float

    Examples
    --------
    >>> centre_weight(3, kappa=1.0), centre_weight(3, w0=0.2)
    (0.25, 0.2)
    """
    if isinstance(kappa, bool) or not np.isscalar(kappa) or not np.isfinite(kappa):
        raise ValueError(f"kappa must be a finite real number, got {kappa!r}")
    if w0 is not None:
        if kappa != 0:
            raise ValueError(
                f"give kappa (filterpy's meaning: w0 = kappa / (n + kappa)) or w0=, not both; "
                f"got kappa={kappa} and w0={w0}"
            )
        return w0
    if not n + kappa > 0:
        raise ValueError(
            f"kappa must satisfy n + kappa > 0 (filterpy's scaled transform divides by it), got "
            f"kappa={kappa} with n={n}; kappa = 3 - n is filterpy's usual choice, or set the "
            "centre weight directly with w0= (any w0 < 1)"
        )
    return float(kappa) / (n + float(kappa))


def _staircase(a, b):
    """Unit points of a staircase simplex: rows ``0..n+1`` by columns ``0..n-1``.

    Column ``j - 1`` (dimension ``j``) holds ``a[j-1]`` in rows ``1..j``, ``b[j-1]``
    in row ``j + 1`` and zeros elsewhere; row 0 (the centre) is zero.
    """
    n = a.size
    Z = np.zeros((n + 2, n))
    for j in range(1, n + 1):
        Z[1 : j + 1, j - 1] = a[j - 1]
        Z[j + 1, j - 1] = b[j - 1]
    return Z


class _StaircaseSimplex(MerweScaledSigmaPoints):
    """Shared machinery of the two ``n + 2`` sets (a private base)."""

    def __init__(self, n, alpha=1.0, beta=0.0, kappa=0.0, sqrt_method=None, subtract=None, *, w0=None):
        n = check_positive_int(n, "n")
        alpha, beta, w0 = _check_scaling(alpha, beta, centre_weight(n, kappa, w0))
        self.w0 = w0
        # MerweScaledSigmaPoints.__init__ stores n, alpha, beta, kappa, sqrt and
        # subtract, then calls our _compute_weights.
        super().__init__(n, alpha, beta, float(kappa), sqrt_method=sqrt_method, subtract=subtract)
        self._default_sqrt = sqrt_method is None

    # -- the two subclasses define these -------------------------------------
    def _unscaled(self):  # pragma: no cover - abstract
        """Return (W, a, b): unscaled outer weights (n+1,) and the staircase entries."""
        raise NotImplementedError

    # -- filterpy's protocol --------------------------------------------------
    def num_sigmas(self):
        """Number of sigma points, ``n + 2``."""
        return self.n + 2

    def _compute_weights(self):
        W, a, b = self._unscaled()
        alpha2 = self.alpha**2
        self.Wm = np.empty(self.n + 2)
        self.Wm[0] = self.w0 / alpha2 + 1.0 - 1.0 / alpha2
        self.Wm[1:] = W / alpha2
        self.Wc = self.Wm.copy()
        self.Wc[0] += 1.0 - alpha2 + self.beta
        # structured unit points, scaled by alpha: sigmas = x + Z @ U
        self._a = self.alpha * a
        self._b = self.alpha * b
        self.Z = _staircase(self._a, self._b)

    @property
    def staircase(self):
        """``(a, b)``, each of shape ``(n,)``: column ``j`` of ``Z`` holds ``a[j]`` in rows
        ``1 .. j+1`` and ``b[j]`` in row ``j + 2`` (see :func:`point_structure`)."""
        return self._a, self._b

    def sigma_points(self, x, P):
        """Sigma points of ``N(x, P)`` as ``x + Z @ U`` (``U = sqrt(P)``, upper).

        Parameters
        ----------
        x : scalar or array-like of shape (n,)
        P : scalar or array-like of shape (n, n)
            A scalar means ``P * eye(n)``.

        Returns
        -------
        sigmas : ndarray of shape (n + 2, n)
            Row 0 is ``x``; rows ``1 .. n+1`` the outer points.

        Notes
        -----
        This is the hot path of filterpy's UKF (two calls per ``predict``), so it is
        built for small ``n``: the unit points and weights are computed once, at
        construction; with the default square root the factor is
        ``numpy.linalg.cholesky(P).T`` (the same upper factor as filterpy's
        ``scipy.linalg.cholesky(P)``, without its overhead); up to ``n = 32`` the
        deviations are the dense product ``Z @ U``, above it the O(n^2) staircase.
        Finiteness is checked once, on the result; a non-finite result is traced back
        to ``x`` or ``P`` for the message.
        """
        n = self.n
        x = np.asarray(x, dtype=float)
        if x.shape != (n,):
            if x.size != n:
                raise ValueError(f"x must have size n={n}, got size {x.size}")
            x = x.reshape(n)
        if type(P) is not np.ndarray or P.dtype != float or P.shape != (n, n):
            P = self._as_covariance(P)
        # Cholesky reads one triangle only: an asymmetric P must not pass silently
        if not _nearly_symmetric(P):
            check_symmetric(P, "P")
        try:
            U = np.linalg.cholesky(P).T if self._default_sqrt else self.sqrt(P)
        except np.linalg.LinAlgError as exc:
            self._check_finite(x, P)
            raise NumericalError(
                f"P must be positive definite (its square root failed: {exc}); make P "
                "symmetric positive definite, e.g. P = np.diag(variances)", matrix="P"
            ) from exc
        if n <= _DENSE_MAX_N:
            D = self.Z @ U
        else:
            D = staircase_apply(self._a, self._b, U)
        if self.subtract is np.subtract:
            sigmas = x + D
        else:  # a custom subtract (angles): x - (-d), as filterpy does
            sigmas = np.array([self.subtract(x, -d) for d in D])
        if not math.isfinite(sigmas.sum()):
            self._check_finite(x, P)
            if not np.all(np.isfinite(sigmas)):
                raise NumericalError(
                    "sigma points are not finite although x and P are (P's square root "
                    "overflowed); rescale the state", matrix="P"
                )
        return sigmas

    def _as_covariance(self, P):
        """``P`` as a float ``(n, n)`` array; a scalar means ``P * eye(n)``."""
        n = self.n
        if np.isscalar(P):
            return np.eye(n) * float(P)
        P = np.atleast_2d(np.asarray(P, dtype=float))
        if P.shape != (n, n):
            raise ValueError(f"P must have shape ({n}, {n}), got {P.shape}")
        return P

    def _check_finite(self, x, P):
        if not np.all(np.isfinite(P)):
            raise ValueError("P must be finite, got non-finite entries")
        if not np.all(np.isfinite(x)):
            raise ValueError(f"x must be finite, got {x}")

    def __repr__(self):
        return "\n".join(
            [
                f"{type(self).__name__} object",
                pretty_str("n", self.n),
                pretty_str("alpha", self.alpha),
                pretty_str("beta", self.beta),
                pretty_str("kappa", self.kappa),
                pretty_str("w0", self.w0),
                pretty_str("Wm", self.Wm),
                pretty_str("Wc", self.Wc),
                pretty_str("subtract", self.subtract),
                pretty_str("sqrt", self.sqrt),
            ]
        )


class MinimalSkewSigmaPoints(_StaircaseSimplex):
    r"""Julier and Uhlmann's (2002) minimal skew simplex: ``n + 2`` sigma points.

    Weights :math:`W_1 = W_2 = (1 - W_0)/2^n` and :math:`W_j = 2^{j-2} W_1` for
    ``j = 3 .. n+1`` (so that they sum to 1; ``2^{j-1}``, a common misreading, does
    not), unit points by the recursion of Julier and Uhlmann (2002, sec. 4): for
    dimension ``j`` the points ``1..j`` take :math:`-1/\sqrt{2 W_{j+1}}` and point
    ``j + 1`` takes :math:`+1/\sqrt{2 W_{j+1}}`; then the scaled form of Julier (2002,
    "The scaled unscented transformation") with ``alpha`` and ``beta``.

    The points spread like :math:`2^{n/2}`: it warns above ``n = 20`` (use
    :class:`SphericalSimplexSigmaPoints` there) and refuses sizes whose weights
    would underflow. ``2^{-n}`` is computed with :func:`numpy.ldexp`.

    Parameters
    ----------
    n : int
        Dimension of the state.
    alpha : float, default 1.0
        Spread of the points about the mean (``> 0``); weights are rescaled so that
        mean and covariance stay exact.
    beta : float, default 0.0
        Prior knowledge of the distribution (2 is optimal for a Gaussian), added to
        the centre's covariance weight.
    kappa : float, default 0.0
        filterpy's ``kappa``, with its meaning in the scaled transform: the unscaled
        centre weight is ``w0 = kappa / (n + kappa)`` (:func:`centre_weight`), so the
        centre weights ``Wm[0]``, ``Wc[0]`` equal
        ``MerweScaledSigmaPoints(n, alpha, beta, kappa)``'s. Needs ``n + kappa > 0``.
    sqrt_method : callable, optional
        Matrix square root returning an *upper* factor (default
        :func:`scipy.linalg.cholesky`), as in filterpy.
    subtract : callable, optional
        ``subtract(x, y)`` for states that do not subtract linearly (angles).
    w0 : float, optional, keyword-only
        The centre weight before scaling (``w0 < 1``; Julier's sets use
        ``0 <= w0 < 1``), in place of ``kappa``. Default: from ``kappa`` (0 for
        ``kappa = 0``).

    Attributes
    ----------
    Wm, Wc : ndarray of shape (n + 2,)
        Mean and covariance weights.
    Z : ndarray of shape (n + 2, n)
        Unit points (scaled by ``alpha``): ``sigma_points(x, P) == x + Z @ sqrt(P)``.

    Examples
    --------
    Swap it into filterpy's own filter:

    >>> import numpy as np
    >>> from filterpy.kalman import UnscentedKalmanFilter
    >>> pts = MinimalSkewSigmaPoints(2)
    >>> pts.num_sigmas(), pts.Wm
    (4, array([0.  , 0.25, 0.25, 0.5 ]))
    >>> ukf = UnscentedKalmanFilter(2, 1, 1.0, hx=lambda x: x[:1],
    ...                             fx=lambda x, dt: x, points=pts)
    """

    def __init__(self, n, alpha=1.0, beta=0.0, kappa=0.0, sqrt_method=None, subtract=None, *, w0=None):
        n_checked = check_positive_int(n, "n")
        w = centre_weight(n_checked, kappa, w0)
        tiny = np.ldexp(1.0 - (w if np.isscalar(w) and w < 1 else 0.0), -n_checked)
        if tiny < np.finfo(float).tiny:
            raise ValueError(
                f"n must be small enough for the minimal-skew weights 2^-n to be "
                f"representable (n <= 1021), got {n}; use SphericalSimplexSigmaPoints"
            )
        if n_checked > MINIMAL_SKEW_WARN_N:
            warnings.warn(
                f"MinimalSkewSigmaPoints with n={n_checked}: the points spread like "
                f"2^(n/2) (~{2 ** (n_checked / 2):.1e}) and the weights fall to "
                f"~{np.ldexp(1.0, -n_checked):.1e}; use SphericalSimplexSigmaPoints "
                "for n > 20",
                UserWarning,
                stacklevel=2,
            )
        super().__init__(n, alpha, beta, kappa, sqrt_method=sqrt_method, subtract=subtract, w0=w0)

    def _unscaled(self):
        n = self.n
        W1 = np.ldexp(1.0 - self.w0, -n)
        W = np.empty(n + 1)
        W[0] = W[1] = W1
        # W_j = 2^(j-2) W1, j = 3..n+1  (indices 2..n here)
        W[2:] = np.ldexp(W1, np.arange(1, n))
        c = 1.0 / np.sqrt(2.0 * W[1:])  # 1/sqrt(2 W_{j+1}), j = 1..n
        return W, -c, c


class SphericalSimplexSigmaPoints(_StaircaseSimplex):
    r"""Julier's (2003) spherical simplex: ``n + 2`` sigma points on a sphere.

    Equal outer weights :math:`W_i = (1 - W_0)/(n + 1)`; unit points by the recursion
    of Julier (2003): for dimension ``j`` the points ``1..j`` take
    :math:`-1/\sqrt{j (j+1) W_1}` and point ``j + 1`` takes :math:`j/\sqrt{j (j+1) W_1}`,
    so every outer point lies at radius :math:`\sqrt{n/(1 - W_0)}`; then the scaled form
    of Julier (2002) with ``alpha`` and ``beta``. This is what the first paper's
    eqs. (1)-(4) describe (see the module docstring), and the reduced set that stays
    well conditioned at any ``n``.

    Parameters
    ----------
    n : int
        Dimension of the state.
    alpha : float, default 1.0
        Spread (``> 0``).
    beta : float, default 0.0
        Added to the centre's covariance weight (2 is optimal for a Gaussian).
    kappa : float, default 0.0
        filterpy's ``kappa``: ``w0 = kappa / (n + kappa)`` (:func:`centre_weight`),
        which puts the outer points on Merwe's sphere, radius
        ``alpha * sqrt(n + kappa)``, with Merwe's centre weights. Needs ``n + kappa > 0``.
    sqrt_method, subtract : callable, optional
        As in filterpy's sigma-point classes.
    w0 : float, optional, keyword-only
        Centre weight before scaling (``w0 < 1``), in place of ``kappa``.

    Attributes
    ----------
    Wm, Wc : ndarray of shape (n + 2,)
    Z : ndarray of shape (n + 2, n)
        Unit points (scaled by ``alpha``).

    Examples
    --------
    >>> pts = SphericalSimplexSigmaPoints(160)
    >>> pts.num_sigmas(), float(pts.Wm[1]) * 161
    (162, 1.0)
    """

    def __init__(self, n, alpha=1.0, beta=0.0, kappa=0.0, sqrt_method=None, subtract=None, *, w0=None):
        super().__init__(n, alpha, beta, kappa, sqrt_method=sqrt_method, subtract=subtract, w0=w0)

    def _unscaled(self):
        n = self.n
        W1 = (1.0 - self.w0) / (n + 1)
        W = np.full(n + 1, W1)
        j = np.arange(1, n + 1, dtype=float)
        c = 1.0 / np.sqrt(j * (j + 1) * W1)
        return W, -c, j * c


# ---------------------------------------------------------------------------
# Structure: unit points and O(n^2) deviations for any filterpy-protocol set
# ---------------------------------------------------------------------------


def unit_sigma_points(points):
    """Unit points ``Z`` of a filterpy-protocol sigma-point object.

    ``points.sigma_points(x, P) == x + Z @ U`` with ``U = points.sqrt(P)`` (upper), for
    the default Cholesky square root.

    Parameters
    ----------
    points : sigma-point object
        Ours, or filterpy's Merwe, Julier or simplex points.

    Returns
    -------
    Z : ndarray of shape (num_sigmas, n)
    """
    check_points_protocol(points)
    Z = getattr(points, "Z", None)
    if Z is not None:
        return Z
    n = points.n
    # sqrt(c * I) = sqrt(c) * I for a Cholesky square root, so this reads off Z
    return np.asarray(points.sigma_points(np.zeros(n), np.eye(n)), dtype=float)


def _sqrt(v):
    """``float(np.sqrt(v))`` (NaN and numpy's warning below 0), by ``math.sqrt`` for a scalar ``v >= 0``."""
    return math.sqrt(v) if v >= 0 else float(np.sqrt(v))


def _symmetric_scale(points):
    """``c`` if the set is ``[0, c I, -c I]`` (filterpy's Merwe or Julier points), else None."""
    n = points.n
    if isinstance(points, MerweScaledSigmaPoints):
        lam = points.alpha**2 * (n + points.kappa) - n
        return _sqrt(lam + n)
    if isinstance(points, JulierSigmaPoints):
        return _sqrt(n + points.kappa)
    return None


def point_structure(points):
    """The structure of a set's unit points ``Z``, which the O(n^2) helpers below use.

    A set that has a ``staircase`` attribute ``(a, b)`` (both ``n + 2`` sets here; any set of
    that form may declare it) is a staircase; filterpy's Merwe and Julier sets are the
    symmetric ``Z = [0, c I, -c I]``; any other set is dense. The declaration is read first,
    so a staircase subclass of filterpy's Merwe class is never taken for the symmetric set.

    Returns
    -------
    kind : {"staircase", "symmetric", "dense"}
    detail : tuple of two ndarray of shape (n,), float or None
        ``(a, b)``, ``c`` or None.

    >>> point_structure(SphericalSimplexSigmaPoints(2))[0]
    'staircase'
    >>> point_structure(MerweScaledSigmaPoints(2, alpha=1.0, beta=2.0, kappa=1.0))
    ('symmetric', 1.7320508075688772)
    """
    stairs = getattr(points, "staircase", None)
    if stairs is not None:
        return "staircase", stairs
    c = _symmetric_scale(points)
    return ("dense", None) if c is None else ("symmetric", c)


def sigma_deviations(points, U):
    """Deviations ``Z @ U`` of the sigma points from the mean, using the set's structure.

    Costs O(n^2) per factor for the symmetric (Merwe, Julier) and staircase (minimal
    skew, spherical simplex) sets, never a dense ``(S, n) @ (n, n)`` product; other
    sets fall back to the dense product.

    Parameters
    ----------
    points : sigma-point object
    U : ndarray of shape (..., n, n)
        Upper square-root factors (``P = U^T U``), e.g. ``np.linalg.cholesky(P).mT``.

    Returns
    -------
    D : ndarray of shape (..., num_sigmas, n)
        ``sigmas = x[..., None, :] + D``.
    """
    check_points_protocol(points)
    U = np.asarray(U, dtype=float)
    n = points.n
    if U.ndim < 2 or U.shape[-2:] != (n, n):
        raise ValueError(f"U must have shape (..., {n}, {n}), got {U.shape}")
    kind, detail = point_structure(points)
    if kind == "staircase":
        return staircase_apply(*detail, U)
    if kind == "symmetric":
        c = detail
        D = np.zeros(U.shape[:-2] + (2 * n + 1, n))
        D[..., 1 : n + 1, :] = c * U
        D[..., n + 1 :, :] = -c * U
        return D
    return unit_sigma_points(points) @ U


def batched_sigma_points(points, x, L):
    """Sigma points ``x_i + Z @ L_i^T`` of every particle, ``(N, n_sigmas, n)``, in O(n^2) each.

    The same numbers as ``x[:, None] + sigma_deviations(points, swapaxes(L))`` (up to
    rounding), fused with the addition of the means: for the symmetric sets
    (``[0, c U, -c U]``) three passes over the output; for the staircase sets (minimal
    skew, spherical simplex) the suffix sums are accumulated row by row in an
    ``(N, n)`` buffer, about half the time of the stacked reverse ``cumsum``. Other
    sets use :func:`sigma_deviations`.

    Parameters
    ----------
    points : sigma-point object
    x : ndarray of shape (N, n)
    L : ndarray of shape (N, n, n)
        Lower Cholesky factors (``P_i = L_i L_i^T``).
    """
    N, n = x.shape
    U = np.swapaxes(L, -1, -2)
    kind, detail = point_structure(points)
    if kind == "staircase":
        return staircase_sigma_points(*detail, x, U)
    if kind == "symmetric" and points.num_sigmas() == 2 * n + 1:
        return symmetric_sigma_points(detail, x, U)
    sig = sigma_deviations(points, U)
    sig += x[:, None, :]
    return sig


def unit_transpose_apply(points, Z, B):
    """``Z^T B`` for unit points ``Z (S, n)`` and ``B (N, S, m)`` -> ``(N, n, m)``, O(S n m).

    Symmetric sets ``[0, c I, -c I]``: ``c (B[1:n+1] - B[n+1:])``. Staircase sets: a
    prefix sum above ``filterwnn._linalg.STAIRCASE_LOOP_ABOVE_N`` (16) dimensions. Others:
    the dense product.
    """
    n = Z.shape[1]
    kind, detail = point_structure(points)
    if kind == "staircase":
        return staircase_transpose_apply(*detail, Z, B)
    if kind == "symmetric" and Z.shape[0] == 2 * n + 1:
        return detail * (B[:, 1 : n + 1, :] - B[:, n + 1 :, :])
    return np.matmul(Z.T, B)
