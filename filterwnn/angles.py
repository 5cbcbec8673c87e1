r"""Angles: wrapping, and the residual and circular mean unscented filters need, in both call modes.

This module is the package's one home of angle arithmetic: the dead-reckoning models'
``wrap_angle``, ``dr_residual`` and ``dr_z_mean`` (heading in measurement column 0) are
:func:`wrap`, :func:`angle_residual` and :func:`angle_mean`.

A state or measurement with an angle (a bearing, a heading) needs two things in an
unscented filter: the residual ``a - b`` wrapped to :math:`[-\pi, \pi)`, and a
*circular* mean :math:`\operatorname{atan2}(\sum_i W_i \sin\theta_i, \sum_i W_i \cos\theta_i)`
(the linear mean of 179 and -179 degrees is 0, not 180).

filterpy's examples write the residual for one row (``y[1] = wrap(y[1])``). In
:class:`filterwnn.UnscentedKalmanFilter` with ``vectorized=True`` the residual receives
*all* sigma points at once, shape ``(n_sigmas, dim)``, and ``y[1]`` is then the second
sigma point, not the second column. The functions made here index the last axis, so the
same object is right in both modes and in filterpy's own filter:

>>> import numpy as np
>>> residual_z = angle_residual([1])         # column 1 is a bearing (rad)
>>> z_mean = angle_mean([1])
>>> residual_z(np.array([10.0, 3.1]), np.array([9.0, -3.1]))        # one row
array([ 1.        , -0.08318531])
>>> sig = np.array([[10.0, 3.1], [10.0, -3.1]])                      # all rows
>>> residual_z(sig, np.array([10.0, 3.1]))
array([[0.        , 0.        ],
       [0.        , 0.08318531]])
>>> z_mean(sig, np.array([0.5, 0.5]))                                # circular: pi, not 0
array([10.        ,  3.14159265])

Pass them as filterpy does: ``UnscentedKalmanFilter(..., residual_z=residual_z,
z_mean_fn=z_mean)`` (and ``residual_x``/``x_mean_fn`` for angles in the state).
"""

from __future__ import annotations

import numbers

import numpy as np

__all__ = ["wrap", "angle_residual", "angle_mean"]

_TWO_PI = 2.0 * np.pi


def wrap(a):
    r"""Wrap angles (rad) to :math:`[-\pi, \pi)`; any shape.

    >>> float(wrap(3 * np.pi / 2))
    -1.5707963267948966
    """
    return (np.asarray(a, dtype=float) + np.pi) % _TWO_PI - np.pi


def _columns(columns):
    if isinstance(columns, numbers.Integral) and not isinstance(columns, bool):
        columns = [columns]
    try:
        cols = [int(c) for c in columns]
    except TypeError as exc:
        raise TypeError(f"columns must be an int or a sequence of ints, got {columns!r}") from exc
    if not cols or any(isinstance(c, bool) or not isinstance(c, numbers.Integral) for c in columns):
        raise ValueError(f"columns must be a non-empty sequence of ints, got {columns!r}")
    return np.array(sorted(set(cols)), dtype=int)


def angle_residual(columns):
    r"""A residual ``residual(a, b) = a - b`` with the given columns wrapped to :math:`[-\pi, \pi)`.

    Parameters
    ----------
    columns : int or sequence of int
        Indices on the last axis that hold angles (radians).

    Returns
    -------
    residual : callable
        ``residual(a, b)`` for ``a`` of shape ``(dim,)`` or ``(n_points, dim)`` and ``b``
        broadcasting against it; returns a new array of the broadcast shape.

    Examples
    --------
    >>> r = angle_residual(0)
    >>> r(np.array([np.pi - 0.1, 5.0]), np.array([-np.pi + 0.1, 2.0]))
    array([-0.2,  3. ])
    """
    cols = _columns(columns)

    def residual(a, b):
        d = np.subtract(a, b, dtype=float)
        if d.ndim == 0 or d.shape[-1] <= cols[-1]:
            raise ValueError(
                f"angle_residual({cols.tolist()}) needs at least {cols[-1] + 1} entries on the "
                f"last axis, got shape {d.shape}"
            )
        d[..., cols] = wrap(d[..., cols])
        return d

    residual.__qualname__ = residual.__name__ = f"angle_residual({cols.tolist()})"
    residual.angle_columns = cols
    return residual


def angle_mean(columns):
    r"""A weighted mean ``mean(sigmas, Wm)`` that is circular in the given columns.

    The angle columns get :math:`\operatorname{atan2}(\sum_i W_i \sin\theta_i, \sum_i W_i
    \cos\theta_i)`, the others :math:`\sum_i W_i z_i`; this is filterpy's ``x_mean_fn`` /
    ``z_mean_fn`` signature. Negative weights (Julier's ``kappa < 0``) are allowed.

    Parameters
    ----------
    columns : int or sequence of int
        Indices of the angle columns.

    Returns
    -------
    mean : callable
        ``mean(sigmas, Wm)`` with ``sigmas`` of shape ``(n_sigmas, dim)`` and ``Wm`` of
        shape ``(n_sigmas,)``; returns shape ``(dim,)``.

    Examples
    --------
    >>> m = angle_mean([0])
    >>> m(np.array([[np.pi - 0.1, 1.0], [-np.pi + 0.3, 3.0]]), np.array([0.5, 0.5]))
    array([-3.04159265,  2.        ])
    """
    cols = _columns(columns)

    def mean(sigmas, Wm):
        sigmas = np.asarray(sigmas, dtype=float)
        Wm = np.asarray(Wm, dtype=float)
        if sigmas.ndim != 2 or sigmas.shape[1] <= cols[-1] or Wm.shape != (sigmas.shape[0],):
            raise ValueError(
                f"angle_mean({cols.tolist()}) needs sigmas of shape (n_sigmas, dim > "
                f"{cols[-1]}) and Wm of shape (n_sigmas,), got {sigmas.shape} and {Wm.shape}"
            )
        m = Wm @ sigmas
        for c in cols:  # one dot product per column (the DR heading's numbers, bit for bit)
            m[c] = np.arctan2(Wm @ np.sin(sigmas[:, c]), Wm @ np.cos(sigmas[:, c]))
        return m

    mean.__qualname__ = mean.__name__ = f"angle_mean({cols.tolist()})"
    mean.angle_columns = cols
    return mean
