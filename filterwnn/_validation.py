"""Boundary checks shared by every public entry point, and the package's error type.

Every check raises a ``ValueError`` or ``TypeError`` whose message names the argument,
the rule and the value given, so that a user sees *what* was wrong, not a traceback from
deep inside LAPACK. Hot inner loops do not call these; public constructors, setters and
``predict``/``update``/``fit`` do.

>>> import numpy as np
>>> check_covariance(np.eye(2), "P", dim=2).shape
(2, 2)
>>> check_covariance([[1.0, 2.0], [2.0, 1.0]], "P")
Traceback (most recent call last):
...
ValueError: P must be positive definite (Cholesky failed); smallest eigenvalue -1
"""

from __future__ import annotations

import math
import numbers

import numpy as np

__all__ = [
    "NumericalError",
    "as_state",
    "as_measurement",
    "check_covariance",
    "check_rng",
    "check_positive_int",
    "check_symmetric",
    "check_seed",
    "check_positive",
    "check_choice",
    "cholesky_lower",
    "check_points_protocol",
    "MAX_ABS",
    "as_real",
    "check_scale",
]


class NumericalError(np.linalg.LinAlgError):
    """A filter met a numerical failure during a run.

    Raised, for example, when a covariance stops being positive definite, when every
    particle weight underflows, or when trained weights become non-finite. It is a
    subclass of :class:`numpy.linalg.LinAlgError` (and so of ``ValueError``), so code
    that already catches those keeps working.

    Attributes
    ----------
    matrix : str or None
        Name of the offending quantity (``"P"``, ``"S"``, ``"weights"``, ...).
    step : int or None
        The step at which the failure happened (the count of ``predict``/``update``
        calls, or the training sample index, as the raiser documents).
    """

    def __init__(self, message, *, matrix=None, step=None):
        super().__init__(message)
        self.matrix = matrix
        self.step = step


#: The largest magnitude a state, particle or measurement entry may have: beyond it the
#: squares in a covariance overflow to inf (``1e155 ** 2 > 1.8e308``).
MAX_ABS = 1e150


def as_real(value, name, what="array-like of numbers"):
    """``value`` as a float array; ``TypeError`` naming ``name`` for complex values (a cast
    would drop the imaginary part silently) or for anything that is not ``what``."""
    try:
        is_complex = bool(np.iscomplexobj(value))
        arr = None if is_complex else np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be {what}, got {type(value).__name__}") from exc
    if is_complex:
        raise TypeError(f"{name} must be real, got complex values (the imaginary part would be dropped)")
    return arr


def check_scale(arr, name, limit=MAX_ABS):
    """Require ``max|arr| <= limit`` (default :data:`MAX_ABS`); return ``arr``."""
    big = float(np.max(np.abs(arr))) if np.size(arr) else 0.0
    if big > limit:
        raise ValueError(f"{name} must have entries of magnitude <= {limit:.0e} (their squares, in a covariance, "
                         f"overflow), got max |{name}| = {big:.3g}: rescale the units")
    return arr


def as_state(x, name="x", dim=None):
    """Return ``x`` as a finite 1-D float array, optionally of length ``dim``.

    Scalars become arrays of length 1; column vectors ``(n, 1)`` are flattened. Complex
    values and entries beyond :data:`MAX_ABS` are refused.
    """
    arr = as_real(x, name)
    if arr.ndim == 2 and 1 in arr.shape:
        arr = arr.reshape(-1)
    arr = np.atleast_1d(arr)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be 1-D, got shape {arr.shape}")
    if dim is not None and arr.shape[0] != dim:
        raise ValueError(f"{name} must have length {dim}, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite, got {arr}")
    return check_scale(arr, name)


def as_measurement(z, dim_z, name="z"):
    """Return a measurement as a finite 1-D array of length ``dim_z``.

    NaN or infinite entries raise ``ValueError``: a missing measurement is said with
    ``z=None``, never with NaN.
    """
    if type(z) is np.ndarray and z.dtype == np.float64 and z.shape == (dim_z,):
        arr = z  # the usual case (a filter's inner loop): as_real would return it as it is
    else:
        arr = as_real(z, name, "array-like of numbers or None")
        arr = np.atleast_1d(arr).reshape(-1) if arr.size == dim_z else arr
        if arr.ndim != 1 or arr.shape[0] != dim_z:
            raise ValueError(f"{name} must have {dim_z} entries, got shape {np.shape(z)}")
    finite = all(map(math.isfinite, arr.tolist())) if dim_z <= 8 else np.isfinite(arr).all()  # small z: no ufunc
    if not finite:
        raise ValueError(
            f"{name} must be finite (use z=None for a missing measurement), got {arr}"
        )
    return arr


def cholesky_lower(P):
    """Lower Cholesky factor of ``P`` (stacked over leading axes), or ``None`` if it fails."""
    try:
        L = np.linalg.cholesky(P)
    except np.linalg.LinAlgError:
        return None
    if not np.all(np.isfinite(L)):
        return None
    return L


def check_points_protocol(points, attrs=("n", "num_sigmas", "sigma_points", "Wm", "Wc")):
    """TypeError unless ``points`` has filterpy's sigma-point attributes ``attrs``."""
    for attr in attrs:
        if not hasattr(points, attr):
            raise TypeError(
                f"points must follow filterpy's sigma-point protocol (missing {attr!r}), "
                f"got {type(points).__name__}"
            )


def check_covariance(P, name="P", dim=None, *, allow_scalar=True, require_pd=True, sym_tol=1e-8):
    """Validate a covariance matrix and return it as a float ``(dim, dim)`` array.

    Parameters
    ----------
    P : scalar or array-like of shape (dim, dim)
        A scalar means ``P * eye(dim)`` (as in filterpy) when ``allow_scalar``.
    name : str
        Argument name used in messages.
    dim : int, optional
        Required size.
    require_pd : bool
        Require positive definiteness (checked by a Cholesky factorisation). When
        false, positive *semi*-definiteness is still required (smallest eigenvalue
        ``>= -sqrt(eps) * max|P|``), so a singular ``Q`` passes and a negative one does not.
    sym_tol : float
        Relative tolerance for symmetry, ``|P - P.T| <= sym_tol * max|P|``.
    """
    arr = as_real(P, name, "a matrix of numbers")
    if arr.ndim == 0:
        if not allow_scalar or dim is None:
            raise ValueError(f"{name} must be a square matrix, got scalar {arr}")
        arr = float(arr) * np.eye(dim)
    if arr.ndim == 1 and arr.size == 1 and dim == 1:
        arr = arr.reshape(1, 1)
    if arr.ndim != 2 or arr.shape[0] != arr.shape[1]:
        raise ValueError(f"{name} must be a square matrix, got shape {arr.shape}")
    if dim is not None and arr.shape[0] != dim:
        raise ValueError(f"{name} must have shape ({dim}, {dim}), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite, got non-finite entries")
    scale = max(np.max(np.abs(arr)), np.finfo(float).tiny)
    check_symmetric(arr, name, sym_tol)
    if require_pd and cholesky_lower(arr) is None:
        ev = _min_eigenvalue(arr, scale)
        raise ValueError(f"{name} must be positive definite (Cholesky failed); smallest eigenvalue {ev:.3g}")
    if not require_pd and arr.size:
        ev = _min_eigenvalue(arr, scale)
        if ev < -np.sqrt(np.finfo(float).eps) * scale:
            raise ValueError(f"{name} must be positive semi-definite; smallest eigenvalue {ev:.3g}")
    return arr


def check_symmetric(M, name="P", tol=1e-8):
    """Require ``max|M - M^T| <= tol * max|M|`` (stacked over leading axes); return ``M``.

    The one symmetry rule of the package, used wherever a covariance enters.
    """
    M = np.asarray(M, dtype=float)
    if M.size:
        scale = max(float(np.max(np.abs(M))), np.finfo(float).tiny)
        asym = float(np.max(np.abs(M - np.swapaxes(M, -1, -2))))
        if asym > tol * scale:
            raise ValueError(f"{name} must be symmetric; max |{name} - {name}.T| = {asym:.3g}")
    return M


def _min_eigenvalue(arr, scale):
    """Smallest eigenvalue of the symmetric part, computed on ``arr / scale`` (no overflow)."""
    unit = arr / scale
    return float(np.linalg.eigvalsh(0.5 * (unit + unit.T)).min()) * scale


def check_rng(rng, name="rng"):
    """Normalise ``rng`` with :func:`numpy.random.default_rng` (SPEC 7).

    Accepts ``None``, an int, a :class:`numpy.random.SeedSequence`, a ``BitGenerator``
    or a ``Generator``; anything else raises ``TypeError``. The legacy
    ``RandomState`` is refused: it would tie results to the global stream.
    ``name`` is the argument the messages name (an estimator's ``random_state``).
    """
    if rng is None or isinstance(
        rng, (numbers.Integral, np.random.SeedSequence, np.random.BitGenerator, np.random.Generator)
    ):
        if isinstance(rng, numbers.Integral) and rng < 0:
            raise ValueError(f"{name} seed must be >= 0, got {rng}")
        return np.random.default_rng(rng)
    raise TypeError(
        f"{name} must be None, an int seed, a SeedSequence, a BitGenerator or a "
        f"numpy.random.Generator, got {type(rng).__name__}"
    )


def check_positive_int(value, name, minimum=1):
    """Return ``value`` as an int, requiring ``value >= minimum``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {type(value).__name__} {value!r}")
    if value < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {value}")
    return int(value)


def check_positive(value, name, *, strict=True):
    """Return ``value`` as a float, requiring ``value > 0`` (or ``>= 0`` if not strict)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__} {value!r}")
    value = float(value)
    if not np.isfinite(value) or (value <= 0 if strict else value < 0):
        rule = "> 0" if strict else ">= 0"
        raise ValueError(f"{name} must be finite and {rule}, got {value}")
    return value


def check_finite(value, name, unit, note=""):
    """Return ``value`` as a float of either sign, requiring it finite; the message names its ``unit`` and what
    its sign means (``note``, e.g. ``" (negative: the speed is early)"``)."""
    value_f = float(as_real(value, name, f"a number of {unit}"))
    if not np.isfinite(value_f):
        raise ValueError(f"{name} must be a finite number of {unit}{note}, got {value!r}")
    return value_f


def check_choice(value, name, choices):
    """Require ``value`` to be one of ``choices``; the message lists the valid names."""
    if value not in choices:
        valid = ", ".join(repr(c) for c in sorted(choices))
        raise ValueError(f"unknown {name} {value!r}; valid: {valid}")
    return value


def check_seed(seed, name="seed"):
    """A root seed for :class:`numpy.random.SeedSequence`: an int ``>= 0``."""
    return check_positive_int(seed, name, minimum=0)


def check_weights(weights, name="weights"):
    """Finite, non-negative, positive-sum 1-D weights, returned normalised."""
    w = as_real(weights, name)
    if w.ndim != 1 or w.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-D array, got shape {w.shape}")
    if not np.all(np.isfinite(w)):
        raise ValueError(f"{name} must be finite, got non-finite entries")
    if np.any(w < 0):
        raise ValueError(f"{name} must be non-negative, got min {w.min()}")
    total = w.sum()
    if not total > 0:
        raise ValueError(f"{name} must have a positive sum, got {total}")
    return w / total
