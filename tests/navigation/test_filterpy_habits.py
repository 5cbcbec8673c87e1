"""A filterpy user's habits with :class:`GPSDRFilter` (stop 71: a user who ran it from their own Python loop): what
was silently ignored or wrong is refused or told, and what filterpy takes is taken."""

import copy
import re
import warnings

import numpy as np
import pytest

from filterwnn.navigation import GPSDRFilter, GPSDRModel
from filterwnn.navigation.drives import read_drive_csv, sample_drive_path
from filterwnn.navigation.scenarios import DRRun, with_outage


@pytest.fixture(scope="module")
def run():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return read_drive_csv(sample_drive_path())


def _filter(run):
    return GPSDRFilter(GPSDRModel.from_grade("phone", dt=run.scenario.dt), x0=None)


def test_r_and_q_are_read_and_setting_them_is_refused_naming_where_they_come_from(run):
    f = _filter(run)
    f.predict()
    f.update(run.z_dr[0], run.z_gps[0], 3.0)
    assert f.R.shape == (4, 4) and f.Q.shape == (f.model.dim_x, f.model.dim_x)
    with pytest.raises(AttributeError, match=r"builds R at each update: .* gps_sigma"):
        f.R = 100.0 * np.eye(4)
    with pytest.raises(AttributeError, match=r"Q comes from its model"):
        f.Q = np.eye(f.model.dim_x)


def test_a_shallow_copy_stepped_on_leaves_the_original_as_it_was(run):
    f = _filter(run)
    for k in range(20):
        f.predict()
        f.update(run.z_dr[k])
    x, step = f.x.copy(), f.step
    g = copy.copy(f)
    for k in range(20, 80):
        g.predict()
        g.update(run.z_dr[k])
    assert f.step == step and g.step == step + 60
    np.testing.assert_array_equal(f.x, x)


def test_a_loop_that_forgets_predict_a_heading_in_degrees_and_a_speed_for_a_distance_are_told_once(run):
    f = _filter(run)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        f.predict()
        f.update(run.z_dr[0])
        f.update(run.z_dr[1])  # no predict
        f.update(run.z_dr[2])
        f.predict()
        f.update([np.degrees(2.0), run.z_dr[3, 1]])
        f.predict()
        f.update([run.z_dr[4, 0], 15.0])  # a speed of 15 m/s given as the distance: 150 m/s at 10 Hz
    said = [str(w.message) for w in caught if str(w.message).startswith("GPSDRFilter: ")]
    assert sum("without predict()" in w for w in said) == 1
    assert sum("is past 2 pi: the heading is in radians" in w for w in said) == 1
    assert sum(bool(re.search(r"z_dr\[1\] = [\d.]+ m at step \d+ is 150 m/s", w)) for w in said) == 1
    ok = _filter(run)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ok.batch_filter(run.z_dr[:200], run.gps_list()[:200], run.gps_sigma_list()[:200])
    assert not [w for w in caught if re.search(r"without predict\(\)|is past 2 pi|past what a car drives",
                                               str(w.message))]


def test_batch_filter_takes_one_sigma_for_every_fix_and_update_a_column_vector(run):
    n = 300
    one = _filter(run).batch_filter(run.z_dr[:n], run.gps_list()[:n], 4.0)
    each = _filter(run).batch_filter(run.z_dr[:n], run.gps_list()[:n], [4.0] * n)
    np.testing.assert_array_equal(one, each)
    a, b = _filter(run), _filter(run)
    for k in range(50):
        a.predict()
        b.predict()
        z = run.gps_list()[k]
        a.update(run.z_dr[k], z)
        b.update(run.z_dr[k], None if z is None else np.asarray(z).reshape(2, 1))
    np.testing.assert_array_equal(a.x, b.x)


def test_with_outage_refuses_a_length_not_positive_and_tells_an_outage_that_drops_no_fix():
    t = 1000.0 + 0.1 * np.arange(3001)  # a log's own clock
    h = np.full(len(t), 0.5)
    fix = np.arange(len(t)) % 10 == 0
    e = 10.0 * (t - t[0]) * np.sin(0.5)
    nn = 10.0 * (t - t[0]) * np.cos(0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = DRRun.from_arrays(t, h, speed=np.full(len(t), 10.0), gps_t=t[fix], east=e[fix], north=nn[fix])
    with pytest.raises(ValueError, match="length"):
        with_outage(run, 100.0, 0.0)
    with pytest.warns(RuntimeWarning, match=r"with_outage drops no fix: \[1250, 1280\) s .* run 1 to 300 s; the "
                                            r"log's own clock started at 1000 s \(run.t_start\)"):
        same = with_outage(run, 1250.0, 30.0)
    assert len(same.gps_steps) == len(run.gps_steps)
    assert len(with_outage(run, 250.0, 30.0).gps_steps) == len(run.gps_steps) - 30
