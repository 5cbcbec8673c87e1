r"""Compiled kernels of the unscented step for many small filters (numba, optional).

The batched unscented step (:class:`~filterwnn.kalman.batched.UnscentedStep`) is written in
NumPy: one call per operation over every member. For a bank of many small filters
(``dim_x <= 8``) each of those calls does little work, and what is left of a step is the
fixed cost of some 100 NumPy calls and the array passes between them. These kernels do the
same arithmetic in three compiled loops over blocks of members, the member axis innermost
(so that the loops vectorize), with the user's ``fx`` and ``hx`` still called once each on
every sigma point, as rows (and the user's mean and residual functions, when given, called
in NumPy as on the NumPy step: the kernels then take the deviations they give):

``sigma_kernel``
    the lower Cholesky factor of every ``P`` and the sigma points ``x + L z_s``;
``predict_kernel``
    the weighted mean and covariance of the propagated points, plus ``Q``;
``update_kernel``
    the measurement moments, ``S = P_yy + R``, ``P_xy = L (Z^T W_c dY)``, the Cholesky
    factor of ``S``, the gain by forward substitution, the posterior and the innovation
    log-likelihood.

They are the equations of the NumPy path, summed in another order: the two agree to
rounding (the tests hold them, and filterpy's UKF, to 1e-12), not bit for bit. A member
whose matrix is not positive definite makes a kernel return its index; the caller then
runs the NumPy path, which raises its usual error (the same message, member and step).

The kernels live in ``filterwnn.kalman._kernels``, which imports numba; :func:`kernels` loads
it when a kernel is first needed (``pip install "filterwnn[fast]"``), and :func:`available`
says whether it can (not with ``NUMBA_DISABLE_JIT=1``). They are compiled once per machine
and cached (numba's ``cache=True``; a new process loads them in well under a second) in
:func:`cache_dir`, the user's cache folder, not beside the installed module: a cache written
into ``site-packages/filterwnn`` outlived ``pip uninstall`` there, and an editable install made
afterwards imported that leftover folder instead of the package.
"""

from __future__ import annotations

import importlib.util
import os
import threading

__all__ = ["available", "kernels", "cache_dir", "BLOCK"]

#: members per block: the block's work arrays (a few ``(n, S, BLOCK)`` arrays) stay in the
#: first-level cache for ``n <= 8``
BLOCK = 64

_KERNELS = None
_LOCK = threading.Lock()


def available():
    """True when numba can be imported and compiles (the compiled path can run).

    With ``NUMBA_DISABLE_JIT`` set (numba's switch for debugging) the kernels would run as
    plain Python, far slower than the NumPy step: False then.
    """
    if os.environ.get("NUMBA_DISABLE_JIT", "0").strip() not in ("", "0"):
        return False
    return importlib.util.find_spec("numba") is not None


def cache_dir():
    """Where numba caches the compiled kernels: ``NUMBA_CACHE_DIR`` when set (numba's own
    setting, for every package), else ``filterwnn/numba`` in the user's cache folder
    (``$XDG_CACHE_HOME``, by default ``~/.cache``). numba names each cached module's subfolder
    after its path, so two installs of filterwnn keep apart."""
    import numba

    if numba.config.CACHE_DIR:
        return numba.config.CACHE_DIR
    root = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(root, "filterwnn", "numba")


def kernels():
    """``(sigma_kernel, predict_kernel, update_kernel)`` (``filterwnn.kalman._kernels``, which
    imports numba), compiled on first use and cached in :func:`cache_dir`."""
    global _KERNELS
    with _LOCK:
        if _KERNELS is None:
            import numba

            # numba places a function's cache when it is decorated, from numba.config.CACHE_DIR (where
            # NUMBA_CACHE_DIR lands); set for the decoration of ours alone, so other packages' stay put
            before = numba.config.CACHE_DIR
            numba.config.CACHE_DIR = cache_dir()
            try:
                from . import _kernels
            finally:
                numba.config.CACHE_DIR = before
            _KERNELS = (_kernels.sigma_kernel, _kernels.predict_kernel, _kernels.update_kernel)
    return _KERNELS
