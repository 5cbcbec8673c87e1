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


def _ar1(phi, n, rng):
    """Unit-variance AR(1) 2-vectors of lag-one correlation ``phi``."""
    out = [rng.standard_normal(2)]
    for e in rng.standard_normal((n - 1, 2)):
        out.append(phi * out[-1] + np.sqrt(1 - phi * phi) * e)
    return out


def test_integrated_autocorrelation_is_1_for_white_and_near_theory_for_ar1():
    from filterwnn.metrics import integrated_autocorrelation

    rng = np.random.default_rng(1)
    assert integrated_autocorrelation(list(rng.standard_normal((200, 2)))) == 1.0
    # AR(1) with phi = 0.8: (1 + phi) / (1 - phi) = 9 (the truncated sum falls a little short)
    c = integrated_autocorrelation(_ar1(0.8, 2000, rng))
    assert 6.0 < c < 10.0, c


def test_integrated_autocorrelation_pairs_nothing_across_a_break():
    from filterwnn.metrics import integrated_autocorrelation

    rng = np.random.default_rng(2)
    # the same vector repeated within each block is perfectly correlated; blocks of 1 are not
    one_each = []
    for v in rng.standard_normal((120, 2)):
        one_each += [v, None]
    assert integrated_autocorrelation(one_each) == 1.0
    assert integrated_autocorrelation([None, None, None]) == 1.0
    assert integrated_autocorrelation([]) == 1.0


def _lag_by_lag(u, min_pairs=10, n_se=2.0):
    """integrated_autocorrelation as its docstring states it, one lag at a time (the form before it
    was vectorised): the reference the fast form must equal."""
    ok = np.array([v is not None for v in u], dtype=bool)
    if not ok.any():
        return 1.0
    d = len(u[int(np.argmax(ok))])
    U = np.array([np.zeros(d) if v is None else np.asarray(v, dtype=float) for v in u])
    breaks = np.cumsum(~ok)
    c = 1.0
    for m in range(1, len(U) // 4):
        pair = ok[m:] & ok[:-m] & (breaks[m:] == breaks[:-m])
        n_pairs = int(pair.sum())
        if n_pairs < min_pairs:
            break
        a, b = U[m:][pair], U[:-m][pair]
        r = float(np.sum(a * b) / (0.5 * np.sum(a * a + b * b)))
        if r < n_se / np.sqrt(U.shape[1] * n_pairs):
            break
        c += 2.0 * r
    return c


def test_integrated_autocorrelation_equals_its_lag_by_lag_definition():
    from filterwnn.metrics import integrated_autocorrelation

    rng = np.random.default_rng(3)
    seen = set()
    for _ in range(300):
        n, d = int(rng.integers(0, 320)), int(rng.integers(1, 4))
        phi, p_break = rng.uniform(0.0, 0.99), rng.choice([0.0, 0.02, 0.2, 0.6])
        x, u = np.zeros(d), []
        for _ in range(n):
            x = phi * x + np.sqrt(1 - phi * phi) * rng.standard_normal(d)
            u.append(None if rng.random() < p_break else x.copy())
        want = _lag_by_lag(u)
        assert integrated_autocorrelation(u) == pytest.approx(want, rel=1e-12)
        assert integrated_autocorrelation(u, min_pairs=3, n_se=1.0) == pytest.approx(
            _lag_by_lag(u, min_pairs=3, n_se=1.0), rel=1e-12)
        seen.add(want > 1.0)
    assert seen == {True, False}  # both white-looking and correlated sequences were compared
