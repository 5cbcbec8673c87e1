"""Shared fixtures: a seeded generator and a small linear-Gaussian model."""

import numpy as np
import pytest

from filterwnn.models import LinearGaussianModel


@pytest.fixture
def rng():
    """A fresh, seeded generator (tests never touch the global NumPy RNG)."""
    return np.random.default_rng(20261126)


@pytest.fixture
def linear_model():
    """A random stable 4-state, 2-measurement linear-Gaussian model."""
    return LinearGaussianModel.random(dim_x=4, dim_z=2, rng=7)
