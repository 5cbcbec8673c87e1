"""Shared fixtures: a seeded generator and a small linear-Gaussian model."""

import os

import numpy as np
import pytest

from filterwnn.models import LinearGaussianModel


def pytest_configure(config):
    """One BLAS thread in each of pytest-xdist's workers: ``setup.cfg`` runs the suite with
    ``-n auto`` (a worker a core), and each worker's BLAS would otherwise start a thread a core
    too. Set here, in the process that starts the workers, before they import NumPy; a
    setting of the user's own wins."""
    if getattr(config.option, "numprocesses", None):
        for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
            os.environ.setdefault(name, "1")


@pytest.fixture
def rng():
    """A fresh, seeded generator (tests never touch the global NumPy RNG)."""
    return np.random.default_rng(20261126)


@pytest.fixture
def linear_model():
    """A random stable 4-state, 2-measurement linear-Gaussian model."""
    return LinearGaussianModel.random(dim_x=4, dim_z=2, rng=7)
