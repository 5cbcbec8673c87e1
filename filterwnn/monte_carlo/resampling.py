r"""Resampling schemes for particle filters, and log-weight arithmetic.

A particle filter carries normalised weights :math:`w_i` (``sum w_i = 1``). Resampling
replaces the weighted cloud by an (equally weighted) one in which particle ``i`` appears
:math:`N_i` times, with :math:`E[N_i] = n\,w_i` (*unbiasedness*) for ``n`` draws. The
four classic schemes differ only in how much extra variance :math:`\operatorname{Var}(N_i)`
they add (Douc, Cappe and Moulines 2005; Hol, Schon and Gustafsson 2006):

``multinomial``
    ``n`` independent draws from the categorical distribution ``w`` (the most variance).
``stratified``
    one uniform draw in each stratum :math:`[(k + u_k)/n]`, ``k = 0 .. n-1``.
``systematic``
    one uniform :math:`u`, then the points :math:`(k + u)/n` (the least variance in
    practice; the default).
``residual``
    first :math:`\lfloor n w_i \rfloor` deterministic copies of each particle, then the
    remaining :math:`n - \sum_i \lfloor n w_i \rfloor` draws multinomially from the
    residual weights :math:`n w_i - \lfloor n w_i \rfloor` (renormalised). filterpy's
    ``residual_resample`` gets this wrong (filterpy issue #290: it draws the residual
    part from the *original* weights' cumulative sum over ``N`` instead of ``n - sum``
    draws of the residual weights, and its output is not unbiased); the version here is.

Every scheme is a pure function ``scheme(weights, rng, n=None) -> indices`` that returns
``n`` (default ``len(weights)``) integer indices into the particle array; ``n`` may be
larger (up-sampling) or smaller (down-sampling) than the cloud. Each scheme is registered
where it is defined (:func:`register`, a decorator); :func:`resample` and the filters'
``resampling=`` accept a registered name or a callable (filterpy's ``systematic_resample``
included, see :func:`get_scheme`). Weights are validated (finite, non-negative, positive sum) and
normalised internally.

filterpy's names, ``systematic_resample(weights)``, ``stratified_resample``,
``residual_resample`` and ``multinomial_resample``, sit beside them with filterpy's
signature. They never touch NumPy's global state: without a generator they draw from a fresh
``np.random.default_rng()`` (unseeded, and they say once that ``np.random.seed`` no longer
repeats the run); ``rng=`` takes any ``rng`` the schemes accept, or a legacy ``RandomState``.
With ``rng=np.random.RandomState(s)``, ``systematic_resample`` and ``stratified_resample``
return the indices filterpy's return with NumPy's global state seeded ``s``,
``multinomial_resample`` filterpy's sorted, and ``residual_resample`` differs where
filterpy's is biased.

Weights are best kept on the log scale: :func:`normalize_log_weights` turns unnormalised
log-weights into normalised weights with ``logsumexp``, without underflow.

>>> import numpy as np
>>> w = np.array([0.1, 0.2, 0.3, 0.4])
>>> resample(w, "systematic", rng=0).shape
(4,)
>>> np.sort(resample([0.0, 1.0, 0.0], "residual", rng=1, n=5))
array([1, 1, 1, 1, 1])
>>> effective_sample_size(np.full(8, 1 / 8))
8.0
>>> w, lse = normalize_log_weights(np.array([-1000.0, -1000.0]))
>>> w, round(lse, 4)
(array([0.5, 0.5]), -999.3069)

References
----------
R. Douc, O. Cappe and E. Moulines, "Comparison of resampling schemes for particle
filtering", ISPA 2005.
J. D. Hol, T. B. Schon and F. Gustafsson, "On resampling algorithms for particle
filters", NSSPW 2006.
"""

from __future__ import annotations

import inspect
import warnings

import numpy as np
from scipy.special import logsumexp

from .._validation import check_choice, check_positive_int, check_rng, check_weights
from ..metrics import effective_sample_size  # re-exported: one definition, in metrics

__all__ = [
    "multinomial",
    "stratified",
    "systematic",
    "residual",
    "resample",
    "systematic_resample",
    "stratified_resample",
    "residual_resample",
    "multinomial_resample",
    "SCHEMES",
    "register",
    "get_scheme",
    "count_distinct",
    "effective_sample_size",
    "normalize_log_weights",
]


def _check_n(n, size):
    return size if n is None else check_positive_int(n, "n")


def _search(w, u):
    """Indices ``i`` with ``c[i-1] <= u < c[i]`` for the cumulative sum ``c`` of ``w``.

    The cumulative sum is divided by its last entry, so it ends at exactly 1.0, and a
    zero-weight particle can never be selected (its cumulative value equals its
    predecessor's, and ``side="right"`` picks the first strictly larger one).
    """
    c = np.cumsum(w)
    c /= c[-1]
    return np.searchsorted(c, u, side="right")


# --- the registry ----------------------------------------------------------------------

#: Registry of scheme names -> public (validating) functions, filled by :func:`register`;
#: each function's ``impl`` attribute is the unvalidated ``impl(w, rng, n)`` the filters call.
SCHEMES = {}

_DOC = """{title} resampling.

    Parameters
    ----------
    weights : array-like of shape (n_particles,)
        Non-negative weights with a positive sum (normalised here).
    rng : None, int, SeedSequence, BitGenerator or Generator
        Source of randomness (normalised with :func:`numpy.random.default_rng`).
    n : int, optional
        Number of indices to draw (default ``n_particles``); larger or smaller than
        ``n_particles`` up- or down-samples.

    Returns
    -------
    indices : ndarray of int, shape (n,)
        Indices into the particle array; ``E[count of i] = n * weights[i]``.
    {extra}
    """


def register(name, title, extra="", *, sorted_indices=False):
    """Decorator: register the unvalidated scheme ``impl(w, rng, n)`` under ``name`` and
    return its public, validating version ``scheme(weights, rng, n=None)``.

    ``sorted_indices=True`` promises indices in non-decreasing order (kept as
    ``impl.sorted_indices``; :func:`count_distinct` then compares neighbours; the tests hold
    every registered scheme to its promise)."""

    def deco(impl):
        def scheme(weights, rng, n=None):
            w = check_weights(weights)
            return impl(w, check_rng(rng), _check_n(n, w.size))

        scheme.__name__ = scheme.__qualname__ = name
        scheme.__doc__ = _DOC.format(title=title, extra=extra)
        scheme.impl = impl
        impl.sorted_indices = bool(sorted_indices)
        SCHEMES[name] = scheme
        return scheme

    return deco


# --- the schemes (registered where defined) ----------------------------------------------


@register("multinomial", "Multinomial", "Indices come out sorted.", sorted_indices=True)
def multinomial(w, rng, n):
    return np.sort(_search(w, rng.random(n)))


@register("stratified", "Stratified", "Indices come out sorted.", sorted_indices=True)
def stratified(w, rng, n):
    return _search(w, (np.arange(n) + rng.random(n)) / n)


@register("systematic", "Systematic",
          "Indices come out sorted; equal weights with ``n = n_particles`` keep every particle.",
          sorted_indices=True)
def systematic(w, rng, n):
    # point k = (k + u) / n goes to the first i with k + u < n c_i, so the points below c_i
    # number ceil(n c_i - u): counts are their differences (O(n), no binary search)
    u = rng.random()
    c = np.cumsum(w)
    c *= n / c[-1]
    c -= u
    m = np.ceil(c, out=c)  # >= 0 (c >= 0, u < 1); the last is n up to rounding: pin it
    m[-1] = n
    counts = np.empty(m.size, dtype=np.intp)
    counts[0] = m[0]
    np.subtract(m[1:], m[:-1], out=counts[1:], casting="unsafe")
    return np.repeat(np.arange(w.size), counts)


@register("residual", "Residual (correct, unlike filterpy's: its issue #290)",
          "Indices come out sorted; particle ``i`` gets at least ``floor(n * w_i)`` copies.",
          sorted_indices=True)
def residual(w, rng, n):
    nw = n * w
    counts = np.floor(nw).astype(np.intp)
    n_rest = n - int(counts.sum())
    if n_rest > 0:
        rest = nw - counts
        rest = np.clip(rest, 0.0, None)
        counts += np.bincount(_search(rest, rng.random(n_rest)), minlength=w.size)
    return np.repeat(np.arange(w.size), counts)


# --- filterpy's names and seeding -------------------------------------------------------

_FILTERPY_DOC = """{title} resampling with filterpy's signature: ``{name}_resample(weights)``.

    A drop-in for :func:`filterpy.monte_carlo.{name}_resample` that never touches NumPy's
    global random state: pass ``rng`` to repeat a run ({note}). Weights are validated and
    normalised (filterpy's are used as given).

    Parameters
    ----------
    weights : array-like of shape (n_particles,)
        Non-negative weights with a positive sum.
    rng : None, numpy.random.RandomState, or any ``rng`` of :func:`{name}`
        ``None`` (default): a fresh ``np.random.default_rng()``, unseeded. Unlike filterpy's,
        the function does not follow ``np.random.seed``; the first call without ``rng``
        says so with a ``UserWarning`` (once per function and process). A ``RandomState``
        is used as given (``RandomState(s)`` draws what filterpy's function draws from the
        global state seeded ``s``); anything else is normalised with
        :func:`numpy.random.default_rng`. Given as a filter's ``resampling=``, this function
        is the scheme ``"{name}"``, drawing from the filter's ``rng``.

    Returns
    -------
    indices : ndarray of int, shape (n_particles,)
        Sorted indices into the particle array; ``E[count of i] = n_particles * weights[i]``.

    Examples
    --------
    New code passes its own generator (the same seed, the same indices):

    >>> import numpy as np
    >>> a = {name}_resample([0.1, 0.2, 0.3, 0.4], rng=np.random.default_rng(3))
    >>> b = {name}_resample([0.1, 0.2, 0.3, 0.4], rng=np.random.default_rng(3))
    >>> bool(np.array_equal(a, b)), a.shape
    (True, (4,))

    A ``RandomState(s)`` draws what filterpy's function draws from the global state seeded
    ``s``, without touching the global state:

    >>> c = {name}_resample([0.1, 0.2, 0.3, 0.4], rng=np.random.RandomState(3))
    >>> c.shape
    (4,)
    """

_FILTERPY_NOTE = {
    "systematic": "for the same stream it returns filterpy's indices",
    "stratified": "for the same stream it returns filterpy's indices",
    "multinomial": "for the same stream it returns filterpy's indices, sorted",
    "residual": ("unlike filterpy's, its issue #290, it is unbiased: the residual draws come "
                 "from the residual weights, so for the same stream the indices may differ"),
}


_UNSEEDED_WARNED = set()  # the drop-ins that have said, once per process, that rng=None is unseeded


def _legacy_rng(rng, name):
    """``rng`` for a filterpy-named drop-in: a ``RandomState`` as given (filterpy's stream), None
    a fresh ``np.random.default_rng()`` (once per drop-in and process, a warning that
    ``np.random.seed`` no longer reaches it), anything else :func:`check_rng`'s."""
    if isinstance(rng, np.random.RandomState):
        return rng
    if rng is None and name not in _UNSEEDED_WARNED:
        _UNSEEDED_WARNED.add(name)
        warnings.warn(
            f"{name}_resample(weights) without rng draws from a fresh np.random.default_rng(): unlike "
            "filterpy's, it does not follow np.random.seed, so a run does not repeat; pass "
            f"rng=np.random.default_rng(seed) (or rng=np.random.RandomState(seed) for the indices filterpy's "
            "gives with np.random.seed at that seed)", UserWarning, stacklevel=3)
    return check_rng(rng)


def _filterpy_named(name):
    impl = SCHEMES[name].impl

    def scheme(weights, rng=None):
        w = check_weights(weights)
        return impl(w, _legacy_rng(rng, name), w.size)

    scheme.__name__ = scheme.__qualname__ = f"{name}_resample"
    scheme._filterwnn_impl = impl  # given to a filter: the named scheme, drawing from the filter's rng
    title = {"residual": "Residual (unbiased)"}.get(name, name.capitalize())
    scheme.__doc__ = _FILTERPY_DOC.format(title=title, name=name, note=_FILTERPY_NOTE[name])
    return scheme


systematic_resample = _filterpy_named("systematic")
stratified_resample = _filterpy_named("stratified")
residual_resample = _filterpy_named("residual")
multinomial_resample = _filterpy_named("multinomial")


def _from_callable(fn):
    """A user scheme: ``fn(weights, rng, n)``, or filterpy's one-argument ``fn(weights)``
    (which draws from numpy's *global* random state and returns ``len(weights)`` indices)."""
    try:
        params = [p for p in inspect.signature(fn).parameters.values()
                  if p.default is p.empty and p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    except (TypeError, ValueError):
        params = [None, None, None]
    if len(params) == 1:
        def one_arg(w, rng, n):
            if n != w.size:
                raise ValueError(f"a one-argument resampling function draws len(weights) = {w.size} indices, not n = {n}")
            return np.asarray(fn(w), dtype=np.intp)

        return one_arg

    def scheme(w, rng, n):
        return np.asarray(fn(w, rng, n), dtype=np.intp)

    return scheme


def count_distinct(indices, n, scheme=None):
    """How many distinct particles ``indices`` (ints in ``[0, n)``, a resampling's output) keep.

    For a ``scheme`` (an implementation from :func:`get_scheme`) that promises sorted
    indices, one comparison of neighbours (at n = 10,000 a fifth of a ``bincount``'s time);
    otherwise ``bincount``.

    >>> count_distinct(np.array([0, 0, 2, 3, 3]), 5, get_scheme("systematic"))
    3
    >>> count_distinct(np.array([3, 0, 3]), 4)
    2
    """
    if getattr(scheme, "sorted_indices", False) and indices.size:
        return 1 + int(np.count_nonzero(indices[1:] != indices[:-1]))
    return int(np.count_nonzero(np.bincount(indices, minlength=n)))


def get_scheme(name):
    """The unvalidated implementation of scheme ``name`` (for the filters' loops).

    ``name`` is a registered name or a callable: ``fn(weights, rng, n) -> indices``, or a
    one-argument ``fn(weights)`` such as filterpy's ``systematic_resample`` (note: filterpy's
    functions draw from numpy's global random state, so ``rng`` no longer makes the run
    reproducible; seed ``np.random`` yourself). This package's drop-ins of those functions
    (:func:`systematic_resample` and its siblings) are their named schemes, and draw from
    ``rng``. Raises ``ValueError`` listing the valid names for an unknown one.
    """
    if callable(name):
        impl = getattr(name, "_filterwnn_impl", None)
        return _from_callable(name) if impl is None else impl
    if not isinstance(name, str):
        raise TypeError(f"resampling must be a scheme name (str) or a callable, got {type(name).__name__}")
    check_choice(name, "resampling scheme", SCHEMES)
    return SCHEMES[name].impl


def resample(weights, scheme="systematic", rng=None, n=None):
    """Draw ``n`` particle indices from ``weights`` with the named scheme.

    Parameters
    ----------
    weights : array-like of shape (n_particles,)
        Non-negative weights with a positive sum.
    scheme : {"systematic", "stratified", "residual", "multinomial"} or callable
        Name of the scheme (an unknown name raises ``ValueError`` listing the valid ones),
        or a callable as :func:`get_scheme` accepts.
    rng : None, int, SeedSequence, BitGenerator or Generator
    n : int, optional
        Number of indices (default ``n_particles``).

    Returns
    -------
    indices : ndarray of int, shape (n,)

    Examples
    --------
    >>> resample([0.5, 0.5], "systematic", rng=0)
    array([0, 1])
    >>> resample([1.0], "magic")
    Traceback (most recent call last):
    ...
    ValueError: unknown resampling scheme 'magic'; valid: 'multinomial', 'residual', 'stratified', 'systematic'
    """
    impl = get_scheme(scheme)
    w = check_weights(weights)
    return impl(w, check_rng(rng), _check_n(n, w.size))


def normalize_log_weights(log_weights):
    """Normalised weights and the log of their sum, from unnormalised log-weights.

    Parameters
    ----------
    log_weights : array-like of shape (n_particles,)
        Unnormalised log-weights; ``-inf`` (weight 0) is allowed, NaN is not.

    Returns
    -------
    weights : ndarray of shape (n_particles,)
        ``exp(log_weights - logsumexp(log_weights))``, summing to 1.
    log_sum : float
        ``logsumexp(log_weights)``; ``-inf`` when every weight is 0 (then ``weights``
        is all NaN and the caller must raise).
    """
    lw = np.asarray(log_weights, dtype=float)
    if lw.ndim != 1 or lw.size == 0:
        raise ValueError(f"log_weights must be a non-empty 1-D array, got shape {lw.shape}")
    if np.any(np.isnan(lw)):
        raise ValueError("log_weights must not contain NaN")
    if np.any(lw == np.inf):
        raise ValueError("log_weights must not contain +inf")
    lse = logsumexp(lw)
    if not np.isfinite(lse):
        return np.full(lw.shape, np.nan), float(lse)
    return np.exp(lw - lse), float(lse)
