"""Chapter 12 of Labbe's book, the robot particle filter, as a filterpy user has it.

Our own version of the problem from its description: a robot drives a diagonal from the
origin (heading change 0, distance 1.414 per step, with noise on both), measures its range
to four landmarks (std 0.1), and a cloud of particles drawn uniformly over the 20 x 20
field, heading included, finds it. The hand-written filter (predict, weight, resample when
``N_eff < N/2``) draws from one stream, as the book's does from NumPy's global state (here a
``RandomState``, so that no test touches the global state): with that stream given as ``rng``,
``filterwnn.monte_carlo.systematic_resample`` gives filterpy's run exactly;
``BootstrapParticleFilter`` on the same problem keeps track. Also: ``pf.weights`` is settable
and refuses edits in place, and the degeneracy warning only counts a collapse whose best
particle cannot explain ``z``.
"""

import warnings

import numpy as np
import pytest
from filterpy.monte_carlo import resampling as fp_resampling

from filterwnn import BootstrapParticleFilter, DegeneracyWarning
from filterwnn.monte_carlo import systematic_resample

LANDMARKS = np.array([[-1.0, 2.0], [5.0, 10.0], [12.0, 14.0], [18.0, 21.0]])
STEP = np.array([0.0, 1.414])  # heading change, distance
MOVE_STD = (0.2, 0.05)
SENSOR_STD = 0.1


def book_filter(resample_fn, r, n=2000, iters=12):
    """The hand-written filter, the book's way, over one drive: every draw from the stream ``r``."""
    p = np.column_stack([r.uniform(0, 20, n), r.uniform(0, 20, n), r.uniform(0, 2 * np.pi, n)])
    w = np.full(n, 1.0 / n)
    pos, estimates = np.zeros(2), []
    for _ in range(iters):
        pos = pos + 1.0
        z = np.linalg.norm(LANDMARKS - pos, axis=1) + r.randn(4) * SENSOR_STD
        p[:, 2] += STEP[0] + r.randn(n) * MOVE_STD[0]
        dist = STEP[1] + r.randn(n) * MOVE_STD[1]
        p[:, 0] += np.cos(p[:, 2]) * dist
        p[:, 1] += np.sin(p[:, 2]) * dist
        d = np.linalg.norm(LANDMARKS[None] - p[:, None, :2], axis=-1)
        w *= np.prod(np.exp(-0.5 * ((d - z) / SENSOR_STD) ** 2), axis=1)
        w += 1e-300
        w /= w.sum()
        if 1.0 / np.sum(w**2) < n / 2:
            idx = resample_fn(w)
            p, w = p[idx], np.full(n, 1.0 / n)
        estimates.append(np.average(p[:, :2], weights=w, axis=0))
    return np.array(estimates)


def test_the_books_filter_runs_unchanged_with_filterwnns_systematic_resample(monkeypatch):
    ours = np.random.RandomState(0)
    theirs = np.random.RandomState(0)
    monkeypatch.setattr(fp_resampling, "random", theirs.random)  # filterpy's draws, from the same stream
    np.testing.assert_array_equal(book_filter(lambda w: systematic_resample(w, rng=ours), ours),
                                  book_filter(fp_resampling.systematic_resample, theirs))


def hx(X):
    return np.linalg.norm(LANDMARKS[None, :, :] - X[:, None, :2], axis=-1)


def fx(X, dt, u):
    h = X[:, 2] + u[0]
    return np.stack([X[:, 0] + np.cos(h) * u[1], X[:, 1] + np.sin(h) * u[1], h], axis=-1)


def sampler(X, rng, u):
    """The book's motion noise: on the heading and on the distance (not additive)."""
    h = X[:, 2] + u[0] + rng.normal(0, MOVE_STD[0], len(X))
    d = u[1] + rng.normal(0, MOVE_STD[1], len(X))
    return np.stack([X[:, 0] + np.cos(h) * d, X[:, 1] + np.sin(h) * d, h], axis=-1)


def bootstrap_run(seed, n=5000, iters=18):
    rng = np.random.default_rng(seed)
    pf = BootstrapParticleFilter(3, 4, 1.0, hx, fx, n, vectorized=True, rng=seed, process_sampler=sampler,
                                 ess_threshold=0.5)
    pf.Q, pf.R = np.diag([0.05**2, 0.05**2, 0.2**2]), np.eye(4) * SENSOR_STD**2
    pf.initialize(np.column_stack([rng.uniform(0, 20, n), rng.uniform(0, 20, n), rng.uniform(0, 2 * np.pi, n)]))
    pos, errors = np.zeros(2), []
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        for _ in range(iters):
            pos = pos + 1.0
            pf.predict(u=STEP)
            pf.update(np.linalg.norm(LANDMARKS - pos, axis=1) + rng.normal(0, SENSOR_STD, 4))
            errors.append(np.linalg.norm(pf.x[:2] - pos))
    return np.array(errors), [w for w in rec if issubclass(w.category, DegeneracyWarning)]


def test_bootstrap_particle_filter_finds_and_keeps_the_robot():
    errors, _ = bootstrap_run(seed=4)
    assert errors[-6:].max() < 0.5


def test_a_collapse_onto_a_particle_that_explains_z_does_not_warn():
    """Seed 4: ESS < 2 at the first updates, but the best particle's d^2 is within chi^2."""
    _, warned = bootstrap_run(seed=4)
    assert not warned


def test_a_collapse_whose_best_particle_cannot_explain_z_warns_and_says_so():
    """Seed 7: the cloud settles on a wrong mode, which no particle explains; it warns (once)."""
    errors, warned = bootstrap_run(seed=7)
    assert errors[-1] > 1.0 and len(warned) == 1
    said = str(warned[0].message)  # (at the first step no particle explains by far, stop 69; else after three)
    assert ("the best particle d^2 = " in said and "cannot explain z" in said) or (
        "no particle explains the measurement at step" in said and "particles that have lost the state" in said)


def simple_pf(n=5):
    pf = BootstrapParticleFilter(2, 1, 1.0, lambda X: X[:, :1], lambda X, dt: X, n, vectorized=True, rng=0)
    pf.predict()
    return pf


def test_weights_are_settable_and_normalised():
    pf = simple_pf()
    pf.weights = [1.0, 1.0, 2.0, 0.0, 0.0]
    np.testing.assert_allclose(pf.weights, [0.25, 0.25, 0.5, 0.0, 0.0])
    np.testing.assert_allclose(np.exp(pf.log_weights), pf.weights)
    with pytest.raises(ValueError, match=r"weights must have shape \(5,\), got \(3,\)"):
        pf.weights = np.ones(3)
    with pytest.raises(ValueError, match="weights must be non-negative"):
        pf.weights = [1.0, -1.0, 1.0, 1.0, 1.0]


def test_an_edit_of_the_weights_in_place_is_refused_not_lost():
    pf = simple_pf()
    with pytest.raises(ValueError, match="read-only"):
        pf.weights.fill(0.2)  # the book's habit on its own array; here it would change a copy
