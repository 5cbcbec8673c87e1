"""filterpy's ``Saver`` on the package's filters, as a filterpy user records a run (stop 64).

``Saver(f)`` copies the filter's ``__dict__`` (and reads its properties) at each ``save()``; ``to_array()`` stacks each
entry over the steps, and raises on the first that will not stack. Histories that grow with the run, and buffers whose
shape changes, cannot: ``Saver`` on a ``GPSDRFilter`` raised ``could not convert _nis into np.array`` and, copying
those buffers at every step, needed memory that grew with the square of the drive's length. They are now slots (read
and set as any attribute, out of ``__dict__``), and what ``Saver`` records is the state, a row per step. The particle
filters and the Gaussian-sum filter raised so on ``ess_history``, and recorded no ``x``: their moments are formed when
read, and ``Saver`` read ``_x``, None while they waited; ``x`` and ``P`` are now properties, which ``Saver`` reads.
"""

import copy
import pickle
import warnings

import numpy as np
import pytest
from filterpy.common import Saver

from filterwnn import (BootstrapParticleFilter, ExtendedKalmanParticleFilter, GaussianSumFilter, GPSDRFilter,
                       SimplexUnscentedParticleFilter, UnscentedParticleFilter, read_drive_csv)
from filterwnn.models import LinearGaussianModel
from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.drives import sample_drive_path


@pytest.fixture(scope="module")
def sample():
    return read_drive_csv(sample_drive_path())


@pytest.mark.parametrize("kind", ["ekf", "ukf", "sukf"])
def test_saver_records_a_gpsdr_filter_over_a_drive(sample, kind):
    run = sample
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    f = GPSDRFilter(model, kind, x0=np.r_[run.x0, model.x0[6:]])
    g = GPSDRFilter(model, kind, x0=np.r_[run.x0, model.x0[6:]])
    n = 600
    s = Saver(f)
    gps, sig = run.gps_list(), run.gps_sigma_list()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for k in range(n):
            f.predict()
            f.update(run.z_dr[k], gps[k], sig[k])
            s.save()
        est = g.batch_filter(run.z_dr[:n], gps[:n], sig[:n])
    s.to_array()
    assert s.x.shape == (n, 9) and s.P.shape == (n, 9, 9)  # (the phone grade's rate-bias state from the start)
    np.testing.assert_allclose(s.x, est)  # each step's state, as batch_filter gives it
    assert s.n_fixes.shape == (n,) and s.n_fixes[-1] == f.n_fixes
    assert not {"_nis", "nis_accepted", "zero_rate_steps", "rejected_steps"} & set(s.keys)  # histories: read on f
    assert len(f.nis_accepted) > 0 and f.nis_accepted == g.nis_accepted


def test_batch_filter_takes_a_saver_as_filterpys_does(sample):
    """``batch_filter(..., saver=s)`` calls ``s.save()`` after every step, as filterpy's ``batch_filter`` does (stop
    72): the covariances of the means it returns, which it did not record."""
    run = sample
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
    s = Saver(f)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        est = f.batch_filter(run.z_dr[:300], run.gps_list()[:300], run.gps_sigma_list()[:300], saver=s)
    s.to_array()
    assert s.P.shape == (300, 9, 9) and np.all(np.linalg.eigvalsh(s.P) > 0)
    np.testing.assert_array_equal(s.x, est)


def test_a_gpsdr_filter_copies_and_pickles_whole(sample):
    """The slots travel with the filter: a copy or a pickle goes on as the original (the study snapshots a filter
    at each outage's start)."""
    run = sample
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
    gps, sig = run.gps_list(), run.gps_sigma_list()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        f.batch_filter(run.z_dr[:400], gps[:400], sig[:400])
        twins = [copy.deepcopy(f), pickle.loads(pickle.dumps(f))]
        for h in [f] + twins:
            h.batch_filter(run.z_dr[400:800], gps[400:800], sig[400:800])
    for h in twins:
        np.testing.assert_array_equal(h.x, f.x)
        assert h.nis_accepted == f.nis_accepted and h.rejected_steps == f.rejected_steps and h.step == f.step
    assert twins[0].nis_accepted is not f.nis_accepted  # a deep copy, not the same list
    f.my_note = "kept"  # an attribute of the user's own still goes in __dict__
    assert f.__dict__["my_note"] == "kept"


def _mixture(name, m):
    if name == "GaussianSumFilter":
        f = GaussianSumFilter(2, 1, 1.0, m.hx, m.fx, component="ukf", vectorized=True)
        f.Q, f.R = m.Q, m.R
        f.initialize([[1.0, 0.0], [-1.0, 0.0]], np.eye(2))
        return f
    cls = {c.__name__: c for c in (BootstrapParticleFilter, ExtendedKalmanParticleFilter, UnscentedParticleFilter,
                                   SimplexUnscentedParticleFilter)}[name]
    extra = dict(FJacobian=m.FJacobian, HJacobian=m.HJacobian) if cls is ExtendedKalmanParticleFilter else {}
    f = cls(2, 1, 1.0, m.hx, m.fx, n_particles=100, vectorized=True, rng=2, **extra)
    f.Q, f.R = m.Q, m.R
    return f


def _recorded_like_batch_filter(f, g, zs):
    """``Saver(f)`` over ``predict``/``update(z)`` for each of ``zs``, stacked; its ``x`` and ``P`` are those
    ``g.batch_filter(zs, saver=Saver(g))`` returns for a twin ``g``, and that saver's ``x`` too. The ``Saver``."""
    s = Saver(f)
    for z in zs:
        f.predict()
        f.update(z)
        s.save()
    s.to_array()
    sg = Saver(g)  # and batch_filter's own saver, as filterpy's batch_filter takes one (stop 72)
    means, covs = g.batch_filter(np.asarray(zs), saver=sg)
    np.testing.assert_array_equal(s.x, means)  # each step's, as batch_filter gives them (not one array seen twice)
    np.testing.assert_array_equal(s.P, covs)
    sg.to_array()
    np.testing.assert_array_equal(sg.x, means)
    return s


@pytest.mark.parametrize("name", ["BootstrapParticleFilter", "ExtendedKalmanParticleFilter", "UnscentedParticleFilter",
                                  "SimplexUnscentedParticleFilter", "GaussianSumFilter"])
def test_saver_records_the_mixture_filters(name):
    m = LinearGaussianModel.random(dim_x=2, dim_z=1, rng=0)
    _, zs = m.simulate(40, rng=1)
    f, g = _mixture(name, m), _mixture(name, m)
    s = _recorded_like_batch_filter(f, g, zs)  # the moments after each update
    assert s.ess.shape == (40,) and len(f.ess_history) == 40 and f.ess_history == g.ess_history
    assert "ess_history" not in s.keys
    twin = pickle.loads(pickle.dumps(f))  # the histories travel with a pickle, and the filter goes on
    assert twin.ess_history == f.ess_history and twin.resampled_history == f.resampled_history
    for h in (f, twin):
        h.predict()
        h.update(zs[0])
    np.testing.assert_array_equal(twin.x, f.x)
    assert len(twin.ess_history) == 41


def test_a_failed_step_still_takes_its_history_entry_back():
    """The histories, now slots, are still truncated when a step raises after its entry was made
    (``filterwnn._state.rolls_back_on_error``): here the degeneracy watch after it, as ``-W error`` would."""
    m = LinearGaussianModel.random(dim_x=2, dim_z=1, rng=0)
    _, zs = m.simulate(5, rng=1)
    f = _mixture("BootstrapParticleFilter", m)
    for z in zs[:3]:
        f.predict()
        f.update(z)
    f.predict()
    before = (list(f.ess_history), list(f.resampled_history), f.ess, f.x.copy())

    def watch(ess, log_lik):
        raise RuntimeError("raised after the history's entry")

    f._watch_degeneracy = watch
    with pytest.raises(RuntimeError, match="after the history"):
        f.update(zs[3])
    assert (f.ess_history, f.resampled_history, f.ess) == before[:3] and len(f.ess_history) == 3
    np.testing.assert_array_equal(f.x, before[3])


def test_saver_records_the_neural_filter():
    """The paper's neural filter kept its last network input, a tuple of arrays of several shapes, where ``Saver``
    stacks (``could not convert _last``)."""
    from filterwnn.navigation.dead_reckoning import DRModel
    from filterwnn.navigation.neural_filter import NeuralFilter, make_training_set, paper_training_states

    model = DRModel(dt=0.1)
    Xp, Z, X = make_training_set(paper_training_states(), model, rng=0, n_repeats=5)
    nf = NeuralFilter(model, rng=1).fit(Xp, Z, X)
    nf.x = model.x0.copy()
    twin = pickle.loads(pickle.dumps(nf))
    s = Saver(nf)
    x, xs = model.x0.copy(), []
    for _ in range(20):
        x = model.fx(x)
        nf.predict()
        nf.update(model.hx(x))
        s.save()
        twin.predict()
        twin.update(model.hx(x))
        xs.append(twin.x.copy())
    s.to_array()
    np.testing.assert_array_equal(s.x, xs)  # (and the pickled twin, its _last with it, goes on alike)


@pytest.mark.parametrize("bank", ["KalmanFilterBank", "UnscentedKalmanFilterBank"])
def test_saver_records_a_bank_under_its_names(bank):
    """A bank's ``x`` and ``P`` were recorded only as ``_x`` and ``_P`` (descriptors that ``Saver`` does not read);
    each step's, not one array seen through every row."""
    from filterwnn.kalman import KalmanFilterBank, UnscentedKalmanFilterBank
    from filterwnn.kalman.presets import make_points

    def make():
        if bank == "KalmanFilterBank":
            b = KalmanFilterBank(3, 2, 1, 1.0)
            b.F, b.H = np.array([[1.0, 1.0], [0.0, 1.0]]), np.array([[1.0, 0.0]])
        else:
            b = UnscentedKalmanFilterBank(3, 2, 1, 1.0, lambda X: X[:, :1],
                                          lambda X, dt: X @ np.array([[1.0, dt], [0.0, 1.0]]).T, make_points("merwe", 2))
        b.R = np.array([[0.5]])
        return b

    zs = [np.array([[k], [2.0 * k], [np.nan]]) for k in range(10)]  # member 2 never observed
    _recorded_like_batch_filter(make(), make(), zs)
