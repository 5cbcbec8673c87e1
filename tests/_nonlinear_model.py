"""A small nonlinear model written on the last axis (one point ``(n,)`` or rows ``(m, n)``), shared
by the UKF and filter-bank tests."""

import numpy as np


def fx(x, dt):
    out = np.empty_like(x)
    out[..., 0] = x[..., 0] + dt * x[..., 1]
    out[..., 1] = x[..., 1] + dt * np.sin(x[..., 0]) * 0.5
    out[..., 2] = 0.9 * x[..., 2] + 0.1 * x[..., 0] * x[..., 1]
    return out


def hx(x):
    return np.stack([np.sqrt(1.0 + x[..., 0] ** 2 + x[..., 2] ** 2), np.arctan(x[..., 1])], axis=-1)
