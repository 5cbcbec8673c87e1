"""Resampling schemes: edge cases, unbiasedness, the registry, property tests."""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from filterwnn.monte_carlo import resampling
from filterwnn.monte_carlo.resampling import (
    SCHEMES,
    effective_sample_size,
    normalize_log_weights,
    resample,
)

NAMES = sorted(SCHEMES)


@pytest.mark.parametrize("name", NAMES)
def test_equal_weights_keep_every_particle_for_low_variance_schemes(name, rng):
    n = 17
    idx = resample(np.full(n, 1 / n), name, rng=rng)
    assert idx.shape == (n,)
    if name == "multinomial":  # the only scheme allowed to duplicate here
        assert np.all((idx >= 0) & (idx < n))
    else:
        np.testing.assert_array_equal(np.sort(idx), np.arange(n))


@pytest.mark.parametrize("name", NAMES)
def test_one_hot_weight_copies_that_particle(name, rng):
    w = np.zeros(9)
    w[4] = 1.0
    for n in (1, 9, 25):
        np.testing.assert_array_equal(resample(w, name, rng=rng, n=n), np.full(n, 4))


@pytest.mark.parametrize("name", NAMES)
def test_weight_only_on_even_indices_gives_only_even_indices(name, rng):
    w = np.zeros(20)
    w[::2] = rng.random(10) + 0.01
    for _ in range(50):
        idx = resample(w, name, rng=rng, n=31)
        assert np.all(idx % 2 == 0)


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("n", [3, 10, 40])
def test_up_and_down_sampling_give_requested_count(name, n, rng):
    w = rng.random(10)
    idx = resample(w, name, rng=rng, n=n)
    assert idx.shape == (n,)
    assert idx.dtype.kind == "i"
    assert np.all((idx >= 0) & (idx < 10))


@pytest.mark.parametrize("name", NAMES)
def test_schemes_are_unbiased(name):
    """Mean copy counts over R repetitions equal n * w.

    Tolerance: each count's variance is at most that of multinomial resampling,
    n w (1 - w), so the mean of R draws has standard error <= sqrt(n w (1 - w) / R);
    we allow 5 standard errors (plus 1e-9), a false-alarm rate below 1e-5 per entry.
    """
    gen = np.random.default_rng(11)
    w = gen.random(7) ** 2
    w /= w.sum()
    n, R = 13, 4000
    counts = np.zeros(w.size)
    for _ in range(R):
        counts += np.bincount(resample(w, name, rng=gen, n=n), minlength=w.size)
    mean = counts / R
    se = np.sqrt(n * w * (1 - w) / R)
    np.testing.assert_array_less(np.abs(mean - n * w), 5 * se + 1e-9)


def test_residual_gives_floor_copies_deterministically(rng):
    w = np.array([0.55, 0.3, 0.15])
    for _ in range(20):
        c = np.bincount(resample(w, "residual", rng=rng, n=10), minlength=3)
        assert np.all(c >= np.floor(10 * w))
        assert c.sum() == 10


def test_residual_is_unbiased_where_filterpy_is_not():
    """filterpy issue #290: its residual_resample is biased; ours matches n*w."""
    gen = np.random.default_rng(3)
    w = np.array([0.05, 0.05, 0.1, 0.8])
    R = 4000
    counts = np.zeros(4)
    for _ in range(R):
        counts += np.bincount(resample(w, "residual", rng=gen), minlength=4)
    np.testing.assert_allclose(counts / R, 4 * w, atol=5 * np.sqrt(4 * 0.25 / R))


def test_unknown_scheme_lists_valid_names():
    with pytest.raises(ValueError, match="unknown resampling scheme 'magic'; valid: 'multinomial', 'residual'"):
        resample([0.5, 0.5], "magic")


@pytest.mark.parametrize(
    "weights, match",
    [
        ([0.5, np.nan], "weights must be finite"),
        ([0.5, -0.1], "weights must be non-negative"),
        ([0.0, 0.0], "weights must have a positive sum"),
        ([[0.5, 0.5]], "weights must be a non-empty 1-D array"),
        ([], "weights must be a non-empty 1-D array"),
    ],
)
def test_bad_weights_raise(weights, match, rng):
    for fn in SCHEMES.values():
        with pytest.raises(ValueError, match=match):
            fn(weights, rng)


def test_bad_n_and_rng_raise():
    with pytest.raises(ValueError, match="n must be >= 1, got 0"):
        resampling.systematic([1.0], 0, n=0)
    with pytest.raises(TypeError, match="rng must be None, an int seed"):
        resampling.systematic([1.0], "seed")


def test_same_seed_same_indices():
    w = np.random.default_rng(1).random(50)
    for name in NAMES:
        np.testing.assert_array_equal(resample(w, name, rng=5), resample(w, name, rng=5))


def test_effective_sample_size():
    assert effective_sample_size(np.ones(10)) == pytest.approx(10.0)
    assert effective_sample_size([0, 0, 1.0]) == pytest.approx(1.0)
    assert effective_sample_size([1.0, 1.0, 2.0]) == pytest.approx(16 / 6)


def test_normalize_log_weights_survives_underflow():
    w, lse = normalize_log_weights(np.array([-2000.0, -2001.0, -np.inf]))
    np.testing.assert_allclose(w, [1 / (1 + np.exp(-1)), np.exp(-1) / (1 + np.exp(-1)), 0.0])
    assert lse == pytest.approx(-2000 + np.log1p(np.exp(-1)))
    w, lse = normalize_log_weights(np.array([-np.inf, -np.inf]))
    assert lse == -np.inf and np.all(np.isnan(w))
    with pytest.raises(ValueError, match="NaN"):
        normalize_log_weights(np.array([0.0, np.nan]))


# --- property tests ---------------------------------------------------------------------

weights_strategy = st.lists(
    st.one_of(st.just(0.0), st.floats(1e-12, 1e6, allow_nan=False, allow_infinity=False)),
    min_size=1,
    max_size=60,
).filter(lambda w: sum(w) > 0)


@settings(max_examples=100, deadline=None)
@given(
    w=weights_strategy,
    n=st.integers(1, 200),
    name=st.sampled_from(NAMES),
    seed=st.integers(0, 2**32 - 1),
)
def test_property_indices_valid_and_only_positive_weights(w, n, name, seed):
    w = np.asarray(w)
    idx = resample(w, name, rng=seed, n=n)
    assert idx.shape == (n,)
    assert np.all((idx >= 0) & (idx < w.size))
    assert np.all(w[idx] > 0)


@settings(max_examples=100, deadline=None)
@given(
    w=weights_strategy,
    n=st.integers(1, 200),
    name=st.sampled_from(["systematic", "stratified", "residual"]),
    seed=st.integers(0, 2**32 - 1),
)
def test_property_low_variance_counts_bounded(w, n, name, seed):
    """Systematic and residual counts lie within one of n*w; stratified within two."""
    w = np.asarray(w) / np.sum(w)
    counts = np.bincount(resample(w, name, rng=seed, n=n), minlength=w.size)
    slack = {"systematic": 1, "stratified": 2}.get(name)
    if name == "residual":
        assert np.all(counts >= np.floor(n * w * (1 - 1e-12)))
    else:
        assert np.all(np.abs(counts - n * w) <= slack + 1e-9)


def test_a_callable_is_accepted_wherever_a_scheme_name_is():
    from filterpy.monte_carlo import systematic_resample

    from filterwnn import BootstrapParticleFilter
    from filterwnn.monte_carlo.resampling import SCHEMES, get_scheme

    w = np.array([0.1, 0.2, 0.3, 0.4])
    idx = resample(w, systematic_resample)
    assert idx.shape == (4,) and set(idx) <= {0, 1, 2, 3}
    mine = resample(w, lambda w, rng, n: np.repeat(np.argmax(w), n), rng=0, n=3)
    np.testing.assert_array_equal(mine, [3, 3, 3])
    with pytest.raises(ValueError, match="one-argument resampling function draws len"):
        get_scheme(systematic_resample)(w, None, 5)
    assert sorted(SCHEMES) == ["multinomial", "residual", "stratified", "systematic"]
    pf = BootstrapParticleFilter(1, 1, 1.0, lambda x: x, None, 20, vectorized=True, rng=0,
                                 resampling=systematic_resample)
    pf.predict()
    pf.update(np.array([0.3]))
    assert pf.resampled_history == [True]


@pytest.mark.parametrize("name", ["systematic", "stratified", "residual", "multinomial"])
def test_our_filterpy_named_function_given_to_a_filter_draws_from_the_filters_rng(name):
    """``resampling=systematic_resample`` (ours) is the scheme ``"systematic"``: the filter's
    ``rng`` decides the run, the global state is neither read nor needed."""
    from filterwnn import BootstrapParticleFilter

    def run(scheme):
        pf = BootstrapParticleFilter(1, 1, 1.0, lambda X: X**2 / 20, lambda X, dt: X / 2 + 25 * X / (1 + X**2),
                                     100, vectorized=True, rng=0, resampling=scheme, ess_threshold=1.0)
        pf.x, pf.P, pf.Q, pf.R = np.zeros(1), np.array([[5.0]]), np.array([[10.0]]), np.array([[1.0]])
        for k in range(8):
            pf.predict()
            pf.update(np.array([1.0 + k]))
        return pf.particles.copy()

    fn = getattr(resampling, f"{name}_resample")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a filter's rng is given: the drop-in never says it is unseeded
        np.testing.assert_array_equal(run(fn), run(name))
    np.testing.assert_array_equal(run(fn), run(fn))
    w = np.array([0.1, 0.2, 0.3, 0.4])
    np.testing.assert_array_equal(resample(w, fn, rng=5), resample(w, name, rng=5))


# --- filterpy's names and seeding ----------------------------------------------------------

FILTERPY_NAMES = ["systematic", "stratified", "residual", "multinomial"]


@pytest.fixture
def filterpy_stream(monkeypatch):
    """filterpy's resampling functions draw from ``numpy.random.random`` (the global state):
    here from a ``RandomState`` set by the returned function instead, so no test touches the
    global state."""
    from filterpy.monte_carlo import resampling as fp

    def seed(s):
        monkeypatch.setattr(fp, "random", np.random.RandomState(s).random)

    return seed


@pytest.mark.parametrize("name", ["systematic", "stratified", "multinomial"])
def test_filterpy_named_functions_give_filterpys_indices_for_the_same_seed(name, rng, filterpy_stream):
    from filterpy.monte_carlo import resampling as fp

    import filterwnn.monte_carlo as mc

    ours_fn, theirs_fn = getattr(mc, f"{name}_resample"), getattr(fp, f"{name}_resample")
    for seed in range(50):
        w = rng.dirichlet(np.ones(1 + seed % 40))
        filterpy_stream(seed)
        theirs = theirs_fn(w)
        np.testing.assert_array_equal(ours_fn(w, np.random.RandomState(seed)), np.sort(theirs))


@pytest.mark.parametrize("name", FILTERPY_NAMES)
def test_filterpy_named_functions_take_a_randomstate_or_an_rng_and_never_the_global_state(name, monkeypatch):
    fn = getattr(resampling, f"{name}_resample")
    w = np.array([0.05, 0.15, 0.3, 0.5, 0.0, 0.0, 0.0, 0.0])
    np.testing.assert_array_equal(fn(w, np.random.RandomState(7)), fn(w, np.random.RandomState(7)))
    np.testing.assert_array_equal(fn(w, 5), fn(w, np.random.default_rng(5)))
    assert np.all(w[fn(w, np.random.RandomState(0))] > 0)
    with pytest.raises(ValueError, match="weights"):
        fn([0.5, -0.5], 0)

    def global_draw(*args, **kwargs):
        raise AssertionError("drew from NumPy's global state")

    monkeypatch.setattr(np.random, "random", global_draw)
    monkeypatch.setattr(np.random, "random_sample", global_draw)
    monkeypatch.setattr(resampling, "_UNSEEDED_WARNED", set())
    said = rf"{name}_resample\(weights\) without rng draws from a fresh np.random.default_rng\(\): "
    with pytest.warns(UserWarning, match=said + r"unlike filterpy's, it does not follow np.random.seed"):
        first = fn(w)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # said once per function and process
        second = fn(w)
    assert first.shape == second.shape == (8,) and np.all(w[first] > 0) and np.all(w[second] > 0)


def test_filterpy_named_residual_is_unbiased_where_filterpys_is_not(filterpy_stream):
    from filterpy.monte_carlo import residual_resample as fp_residual

    w = np.array([0.42, 0.33, 0.13, 0.07, 0.05])
    n_runs = 4000
    filterpy_stream(11)
    g = np.random.default_rng(11)
    ours = np.mean([np.bincount(resampling.residual_resample(w, g), minlength=5) for _ in range(n_runs)], axis=0)
    theirs = np.mean([np.bincount(fp_residual(w), minlength=5) for _ in range(n_runs)], axis=0)
    sd = np.sqrt(5 * w * (1 - w) / n_runs)  # a multinomial bound on the count's standard error
    assert np.all(np.abs(ours - 5 * w) < 4 * sd)
    assert np.any(np.abs(theirs - 5 * w) > 8 * sd)


@pytest.mark.parametrize("name", sorted(resampling.SCHEMES))
def test_a_scheme_promising_sorted_indices_keeps_it_and_count_distinct_agrees(name):
    impl = resampling.get_scheme(name)
    rng = np.random.default_rng(7)
    for n_out in (1, 5, 50, 400):
        w = rng.random(50) ** 6  # uneven: many particles dropped, some copied
        w /= w.sum()
        idx = impl(w, rng, n_out)
        if impl.sorted_indices:
            assert np.all(np.diff(idx) >= 0)
        expected = int(np.unique(idx).size)
        assert resampling.count_distinct(idx, 50, impl) == expected
        assert resampling.count_distinct(idx, 50) == expected
    assert resampling.count_distinct(np.array([2, 0, 2], dtype=np.intp), 3, lambda w, r, n: None) == 2
