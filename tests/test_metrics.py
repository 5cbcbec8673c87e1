"""Scores: the effective sample size's checked and unchecked forms agree."""

import numpy as np
import pytest

from filterwnn.metrics import effective_sample_size, kish_ess


def test_kish_ess_is_the_checked_ess_of_normalised_weights():
    w = np.random.default_rng(0).dirichlet(np.ones(50))
    assert kish_ess(w) == pytest.approx(effective_sample_size(w), rel=1e-15)
    assert kish_ess(np.full(8, 1 / 8)) == pytest.approx(8.0)
    assert kish_ess(np.eye(5)[2]) == 1.0


def test_only_the_checked_form_refuses_bad_weights():
    with pytest.raises(ValueError, match="weights must be non-negative"):
        effective_sample_size([0.5, -0.1, 0.6])
