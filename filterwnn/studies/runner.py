"""What both studies share: seed streams keyed by name, the task runner, table numbers.

Seeds. A study's randomness enters once, as a root :class:`numpy.random.SeedSequence`;
run ``i`` is ``SeedSequence(seed).spawn(n_runs)[i]``, and every consumer inside a run
draws from a child keyed by a fixed name, :func:`child` ``(run_seed, *keys)``, built as
``SeedSequence(entropy, spawn_key=run_seed.spawn_key + keys)`` without ``spawn``. So a
stream depends only on its key, never on how many streams were drawn before it, which
tasks ran first or on which worker: adding a consumer with a new key changes nobody
else's numbers.

Tasks. :func:`run_tasks` runs ``fn(task)`` for every task through joblib (any backend:
``loky``, ``threading``, or ``dask`` inside :func:`dask_client`) and returns the results
in task order whatever the number of workers. With ``cache_dir`` each result is written
to ``<key><suffix>`` (``key``: :func:`task_key`, a hash of the task's JSON) as soon as
it finishes, atomically, and read back instead of run the next time, so an interrupted
study resumes with the same numbers. :data:`JSON` and :data:`PICKLE` are the two
serializers (plain dicts; anything picklable, such as arrays).

Tables. :func:`quantile` ignores non-finite values; :func:`fmt` writes one number.

>>> import numpy as np
>>> a = child(np.random.SeedSequence(7).spawn(3)[2], 5)
>>> b = child((7, (2,)), 5)
>>> a.generate_state(2).tolist() == b.generate_state(2).tolist()
True
>>> run_tasks([1, 2, 3], abs)
[1, 2, 3]
>>> fmt(0.012345), fmt(1234.5, 2, fixed=True), fmt(float("nan"))
('0.0123', '1234', '-')
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import pickle
from typing import Callable, NamedTuple

import numpy as np

__all__ = [
    "child",
    "task_key",
    "Serializer",
    "JSON",
    "PICKLE",
    "load_cached",
    "run_tasks",
    "dask_client",
    "quantile",
    "fmt",
]


def child(seed, *keys):
    """The child stream of ``seed`` at the fixed ``keys`` (no ``spawn``, so no call history).

    Parameters
    ----------
    seed : numpy.random.SeedSequence or (entropy, spawn_key)
        A run's seed, or the picklable pair :func:`filterwnn.studies.wnn.run_seeds` gives.
    *keys : int
        Appended to the spawn key: ``SeedSequence(entropy, spawn_key=spawn_key + keys)``.

    Returns
    -------
    numpy.random.SeedSequence
    """
    if isinstance(seed, np.random.SeedSequence):
        entropy, key = seed.entropy, seed.spawn_key
    else:
        entropy, key = seed
    return np.random.SeedSequence(entropy, spawn_key=tuple(key) + tuple(keys))


def task_key(task):
    """The cache name of a task: the first 20 hex digits of the SHA-1 of its sorted JSON."""
    return hashlib.sha1(json.dumps(task, sort_keys=True, default=list).encode()).hexdigest()[:20]


class Serializer(NamedTuple):
    """How a task's result is stored: file ``suffix``, ``dump(obj, fh)``, ``load(fh)``, binary or text."""

    suffix: str
    dump: Callable
    load: Callable
    binary: bool


#: Results as JSON (``<key>.json``): plain dicts, lists and numbers.
JSON = Serializer(".json", json.dump, json.load, False)
#: Results as pickles (``<key>.pkl``): anything picklable, arrays included.
PICKLE = Serializer(".pkl", pickle.dump, pickle.load, True)


def _path(cache_dir, key, serializer):
    return os.path.join(cache_dir, key + serializer.suffix)


def load_cached(tasks, cache_dir, serializer=JSON):
    """The cached result of each task, ``None`` where there is none (or no ``cache_dir``)."""
    out = [None] * len(tasks)
    if cache_dir is None:
        return out
    mode = "rb" if serializer.binary else "r"
    for i, task in enumerate(tasks):
        path = _path(cache_dir, task_key(task), serializer)
        if os.path.exists(path):
            with open(path, mode) as fh:
                out[i] = serializer.load(fh)
    return out


def _save(cache_dir, key, result, serializer):
    """Write one result atomically (a temporary file, then ``os.replace``)."""
    path = _path(cache_dir, key, serializer)
    with open(path + ".tmp", "wb" if serializer.binary else "w") as fh:
        serializer.dump(result, fh)
    os.replace(path + ".tmp", path)


def _indexed(fn, i, task):
    return i, fn(task)


def run_tasks(tasks, fn, n_jobs=1, backend=None, progress=False, cache_dir=None, cached_only=False,
              desc="tasks", unit="task", serializer=JSON):
    """``[fn(task) for task in tasks]`` through joblib, in task order whatever ``n_jobs``.

    Parameters
    ----------
    tasks : list
        JSON-serialisable descriptions; each names its result in the cache (:func:`task_key`).
    fn : callable
        ``fn(task) -> result``; picklable (a module-level function or a ``functools.partial``
        of one) when ``n_jobs != 1``.
    n_jobs : int
        joblib workers (``-1``: all cores). ``1`` without a backend runs in this process.
    backend : str, optional
        joblib backend name ("loky", "threading", "dask", ...); ``None`` is joblib's default
        (loky). "dask" needs a ``dask.distributed.Client`` (:func:`dask_client`).
    progress : bool
        A tqdm bar over the tasks that run, labelled ``desc`` and ``unit``.
    cache_dir : str, optional
        Checkpoint folder: each finished result is saved there, and results already there
        are loaded instead of run.
    cached_only : bool
        Only load cached results; tasks not in the cache give ``None``.
    serializer : Serializer
        :data:`JSON` (default) or :data:`PICKLE`.

    Returns
    -------
    list
        One result per task (``None`` for a task skipped by ``cached_only``).
    """
    if cache_dir is not None:
        os.makedirs(cache_dir, exist_ok=True)
    out = load_cached(tasks, cache_dir, serializer)
    pending = [] if cached_only else [i for i in range(len(tasks)) if out[i] is None]
    bar = None
    if progress and pending:
        from tqdm.auto import tqdm

        bar = tqdm(total=len(pending), desc=desc, unit=unit)
    try:
        for i, r in _finished(fn, tasks, pending, n_jobs, backend):
            out[i] = r
            if cache_dir is not None:
                _save(cache_dir, task_key(tasks[i]), r, serializer)
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
    return out


def _finished(fn, tasks, pending, n_jobs, backend):
    """``(i, fn(tasks[i]))`` for each pending task as it finishes (in this process when
    ``n_jobs == 1`` and no backend is named)."""
    if n_jobs == 1 and backend is None:
        for i in pending:
            yield i, fn(tasks[i])
        return
    if not pending:
        return
    from joblib import Parallel, delayed, parallel_config

    # parallel_config registers external backends such as "dask" on first use
    with parallel_config(backend=backend or "loky", n_jobs=n_jobs):
        yield from Parallel(return_as="generator_unordered")(delayed(_indexed)(fn, i, tasks[i]) for i in pending)


@contextlib.contextmanager
def dask_client(backend, scheduler=None, n_jobs=-1):
    """A ``dask.distributed.Client`` while the block runs when ``backend == "dask"``, else nothing.

    Parameters
    ----------
    backend : str or None
        The joblib backend; only ``"dask"`` starts a client.
    scheduler : str, optional
        A scheduler address (``tcp://host:8786``); default a local cluster of ``n_jobs``
        single-threaded workers (``-1`` or ``None``: one per core).
    n_jobs : int

    Yields
    ------
    dask.distributed.Client or None
    """
    if backend != "dask":
        yield None
        return
    from dask.distributed import Client, LocalCluster

    if scheduler:
        client = Client(scheduler)
    else:
        n = os.cpu_count() if n_jobs in (None, -1) else max(1, n_jobs)
        client = Client(LocalCluster(n_workers=n, threads_per_worker=1))
    try:
        yield client
    finally:
        client.close()


def quantile(values, q):
    """The ``q``-quantile of the finite ``values`` (NaN when none is finite)."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    return float(np.quantile(v, q)) if v.size else float("nan")


def fmt(v, digits=3, fixed=False, missing="-"):
    """One table cell: ``digits`` significant digits (``fixed``: decimals, none from 1000 up).

    ``None`` and non-finite floats give ``missing``; anything not a float gives ``str(v)``.
    """
    if v is None or (isinstance(v, float) and not np.isfinite(v)):
        return missing
    if isinstance(v, float):
        if fixed:
            return f"{v:.0f}" if abs(v) >= 1000 else f"{v:.{digits}f}"
        return f"{v:.{digits}g}"
    return str(v)
