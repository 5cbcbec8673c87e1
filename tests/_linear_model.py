"""The 3-state linear-Gaussian reference model shared by the particle-filter and Gaussian-sum tests.

Module-level functions (not lambdas), so that filters built on them pickle.
"""

from filterwnn.models import LinearGaussianModel

LIN = LinearGaussianModel.random(dim_x=3, dim_z=2, rng=3)


def lin_fx(x, dt):
    return LIN.fx(x, dt)


def lin_hx(x):
    return LIN.hx(x)


def lin_F(x, dt):
    return LIN.F


def lin_H(x):
    return LIN.H
