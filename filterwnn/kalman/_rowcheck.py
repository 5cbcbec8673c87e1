"""Is a vectorized model function really vectorized? The check of its first call.

With ``vectorized=True`` a filter passes ``fx``/``hx``/a residual every point at once as rows.
A function written for one point (``x[1]`` where ``x[..., 1]`` is meant) then reads a sigma point
or a particle instead of a column and returns an array of the right shape with the wrong
numbers. :func:`rows_differ` compares a batch with the same function on a few single rows, and
:func:`one_point_error` says which function, what differed and the fix. Used by the unscented
filter and by :func:`filterwnn.kalman.batched.apply_rows` (the particle filters, the Gaussian-sum
filter and the filter banks).
"""

from __future__ import annotations

import numpy as np

__all__ = ["one_point_error", "on_single_rows", "rows_differ", "ONE_POINT_FIX", "CALL_ERRORS"]

# What a function written for one point should become in vectorized mode.
_LAST_AXIS = "index the last axis (x[..., 1], not x[1])"
ONE_POINT_FIX = {
    "fx": f"{_LAST_AXIS}: out = np.empty_like(x); out[..., 0] = x[..., 0] + dt * x[..., 1]; ...",
    "hx": f"{_LAST_AXIS} and return shape (n_sigmas, dim_z), e.g. "
          "np.stack([np.hypot(x[..., 0], x[..., 2]), np.arctan2(x[..., 2], x[..., 0])], axis=-1)",
    "residual_x": "wrap on the last axis (y = a - b; y[..., 2] = wrap(y[..., 2]), not y[2] = ...) or use "
                  "filterwnn.angles.angle_residual(columns)",
    "residual_z": "wrap on the last axis (y = a - b; y[..., 1] = wrap(y[..., 1]), not y[1] = ...) or use "
                  "filterwnn.angles.angle_residual(columns)",
}
CALL_ERRORS = (IndexError, ValueError, TypeError)  # what a one-point function raises on a batch


def one_point_error(role, detail):
    # an `if` on the points' values raises "truth value of an array ... is ambiguous" however the code indexes
    # (a user's hx on x[..., 0] with `if r < 1:` was told to index the last axis, which it did: stop 69)
    branch = ("an `if` (or `and`, `or`, `max`) on the points' values: compute both branches and pick with "
              "np.where(condition, a, b); " if "truth value of an array" in detail else "")
    return ValueError(
        f"vectorized {role} looks written for one point: {detail}. With vectorized=True it receives "
        "all sigma points as one (n_sigmas, dim) array, so an index such as x[1] selects a sigma "
        f"point, not a column. Fix: {branch}{ONE_POINT_FIX[role]}; or use vectorized=False"
    )


def on_single_rows(fn, X, rows, size, args=(), kwargs=None):
    """``fn`` on single rows of ``X``, each given as ``(1, d)`` or else as ``(d,)``.

    Returns ``(outputs, one_d)``: the flattened outputs of ``size`` entries and whether
    the ``(d,)`` form was needed (a function written for one point), or ``None`` when
    ``fn`` takes neither form (it needs the whole batch: nothing to compare).
    """
    kwargs = kwargs or {}
    outs, one_d = [], False
    for i in rows:
        for flat, arg in ((False, X[i : i + 1]), (True, X[i])):
            try:
                v = np.asarray(fn(arg.copy(), *args, **kwargs), dtype=float).reshape(-1)
            except CALL_ERRORS:
                continue
            if v.size == size:
                outs.append(v)
                one_d |= flat
                break
        else:
            return None
    return outs, one_d


def rows_differ(batch, X, fn, args=(), kwargs=None):
    """The first of a few rows where ``batch`` differs from ``fn`` on that row alone, or None."""
    S = X.shape[0]
    rows = sorted({0, min(1, S - 1), S - 1})
    got = on_single_rows(fn, X, rows, batch[0].size, args, kwargs)
    if got is None:
        return None
    for i, v in zip(rows, got[0]):
        b = batch[i].reshape(-1)
        bad = ~np.isclose(b, v, rtol=1e-9, atol=1e-12 * max(1.0, float(np.max(np.abs(v), initial=0.0))),
                          equal_nan=True)
        if bad.any():
            j = int(np.argmax(bad))
            return (f"row {i}, entry {j} of the batch is {b[j]:.6g}, but {v[j]:.6g} when that "
                    "row is passed alone")
    return None
