"""Tests of filterwnn.studies.runner: keyed seed streams, the task runner and its cache, numbers."""

import json

import numpy as np
import pytest

from filterwnn.studies import runner


def _square(task):
    return {"x": task["x"] ** 2}


def test_child_is_the_spawned_child_and_depends_only_on_its_key():
    root = np.random.SeedSequence(42)
    spawned = root.spawn(3)[2]
    for seed in (runner.child(root, 2), runner.child((42, ()), 2)):
        assert seed.generate_state(4).tolist() == spawned.generate_state(4).tolist()
    a = runner.child(spawned, 7).generate_state(2)
    assert a.tolist() == runner.child((42, (2,)), 7).generate_state(2).tolist()
    assert a.tolist() != runner.child(spawned, 8).generate_state(2).tolist()


@pytest.mark.parametrize("serializer", [runner.JSON, runner.NPZ])
def test_run_tasks_order_cache_and_cached_only(tmp_path, serializer):
    tasks = [{"x": i} for i in range(5)]
    want = [_square(t) for t in tasks]
    assert runner.run_tasks(tasks, _square, n_jobs=2, backend="threading") == want
    assert runner.run_tasks(tasks[:3], _square, cache_dir=str(tmp_path), serializer=serializer) == want[:3]
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted(runner.task_key(t) + serializer.suffix for t in tasks[:3])
    got = runner.run_tasks(tasks, _square, cache_dir=str(tmp_path), cached_only=True, serializer=serializer)
    assert got == want[:3] + [None, None]

    def fail(task):
        raise AssertionError("cached task ran")

    assert runner.run_tasks(tasks[:3], fail, n_jobs=2, cache_dir=str(tmp_path), serializer=serializer) == want[:3]


def test_task_key_is_the_sha1_of_the_sorted_json():
    import hashlib

    task = ("fit", ("ekf", (1, (0,)), 3, 10), {"run": 0})
    text = json.dumps(task, sort_keys=True, default=list)
    assert runner.task_key(task) == hashlib.sha1(text.encode()).hexdigest()[:20]


def test_dask_client_only_for_dask():
    with runner.dask_client("loky") as client:
        assert client is None


def test_quantile_and_fmt():
    assert runner.quantile([1.0, np.nan, 3.0, np.inf], 0.5) == 2.0
    assert np.isnan(runner.quantile([np.nan], 0.5))
    assert runner.fmt(0.0123456) == "0.0123" and runner.fmt(None) == "-" and runner.fmt(3) == "3"
    assert runner.fmt(2.345, 2, fixed=True) == "2.35" and runner.fmt(12345.6, 2, fixed=True) == "12346"
    assert runner.fmt(float("nan"), 2, fixed=True, missing="nan") == "nan"
