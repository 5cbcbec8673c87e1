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
in task order whatever the number of workers.

Cache. With ``cache_dir`` each result is written to ``<key><suffix>`` (``key``:
:func:`task_key`, a hash of the task's JSON) as soon as it finishes and read back instead
of run the next time, so an interrupted study (Ctrl-C, SIGKILL) resumes with the same
numbers. An entry carries its task key and settings, the :func:`code_version` that wrote
it (a hash of the package's source and :data:`CACHE_FORMAT`) and a checksum; one that
does not parse, belongs to another task, comes from other code, fails its checksum or
holds non-finite values its run did not write is never used: a one-line
:class:`CacheEntryWarning` names the file and the task runs again. So after any change to
the package's source every entry is recomputed. Entries are JSON (:data:`JSON`) or
``.npz`` with a JSON header (:data:`NPZ`, read with ``allow_pickle=False``): nothing read
from a cache folder can run code. Each writer writes a temporary file of a unique name
and renames it into place, so several processes can share one folder.

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
import functools
import hashlib
import json
import os
import tempfile
import warnings
from typing import Callable, NamedTuple

import numpy as np

__all__ = [
    "child",
    "task_key",
    "Serializer",
    "JSON",
    "NPZ",
    "CACHE_FORMAT",
    "CacheEntryWarning",
    "code_version",
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
    """How a cache entry is stored: file ``suffix``, ``dump(entry, fh)``, ``load(fh) -> entry``, binary or text.

    An entry is ``{"meta": {...}, "result": result}``; ``load`` must not be able to run code
    (no pickle), since a cache folder may hold files from anyone.
    """

    suffix: str
    dump: Callable
    load: Callable
    binary: bool


#: The layout of a cache entry; raise it when the meaning of a stored result changes
#: without a change to the package source (which :func:`code_version` already hashes).
CACHE_FORMAT = 2


class CacheEntryWarning(UserWarning):
    """A cache entry was not used (unreadable, another task's, other code's, a checksum or
    non-finite mismatch): the task is run again and its entry rewritten."""


@functools.lru_cache(maxsize=1)
def code_version():
    """The version a cache entry must carry to be used: a hash of :data:`CACHE_FORMAT` and of
    every ``.py`` file of the installed ``filterwnn`` package (path and bytes).

    Any edit to the package's source (a default setting, a fix) changes it, so results
    cached by other code are never read back; the first 16 hex digits of a SHA-256.
    """
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    h = hashlib.sha256(f"cache-format {CACHE_FORMAT}".encode())
    files = sorted(os.path.relpath(os.path.join(d, f), root) for d, _, fs in os.walk(root)
                   for f in fs if f.endswith(".py"))
    for rel in files:
        with open(os.path.join(root, rel), "rb") as fh:
            h.update(rel.replace(os.sep, "/").encode() + b"\0" + fh.read() + b"\0")
    return h.hexdigest()[:16]


def _json_text(obj):
    return json.dumps(obj, sort_keys=True, default=list)


def _n_nonfinite(obj):
    """How many non-finite floats ``obj`` holds (nested dicts, lists, arrays, numbers)."""
    if isinstance(obj, dict):
        return sum(_n_nonfinite(v) for v in obj.values())
    if isinstance(obj, (list, tuple)):
        return sum(_n_nonfinite(v) for v in obj)
    if isinstance(obj, (float, np.floating, np.ndarray)) and np.asarray(obj).dtype.kind in "fc":
        return int(np.sum(~np.isfinite(obj)))
    return 0


def _json_dump(entry, fh):
    json.dump(entry, fh, sort_keys=True, default=list)


def _json_checksum(result):
    return hashlib.sha256(_json_text(result).encode()).hexdigest()


def _to_tree(obj, arrays):
    """``obj`` as JSON with each array replaced by ``{"__npz__": name}`` (stored in ``arrays``)."""
    if isinstance(obj, dict):
        if "__npz__" in obj or not all(isinstance(k, str) for k in obj):
            raise TypeError(f"the NPZ cache stores dicts with str keys other than '__npz__', got keys {list(obj)}")
        return {k: _to_tree(obj[k], arrays) for k in sorted(obj)}  # sorted: the names do not depend on order
    if isinstance(obj, (list, tuple)):
        return [_to_tree(v, arrays) for v in obj]
    if isinstance(obj, np.ndarray):
        if obj.dtype.hasobject:
            raise TypeError("the NPZ cache does not store object arrays (they would need pickle)")
        name = f"a{len(arrays)}"
        arrays[name] = obj
        return {"__npz__": name}
    if isinstance(obj, np.generic):
        return obj.item()
    if obj is None or isinstance(obj, (bool, int, float, str)):
        return obj
    raise TypeError(f"the NPZ cache stores dicts, lists, arrays, numbers and str, got {type(obj).__name__}")


def _from_tree(tree, arrays):
    if isinstance(tree, dict):
        if set(tree) == {"__npz__"}:
            return arrays[tree["__npz__"]]
        return {k: _from_tree(v, arrays) for k, v in tree.items()}
    if isinstance(tree, list):
        return [_from_tree(v, arrays) for v in tree]
    return tree


def _npz_checksum(tree_text, arrays):
    h = hashlib.sha256(tree_text.encode())
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name} {a.dtype.str} {a.shape}".encode() + a.tobytes())
    return h.hexdigest()


def _npz_dump(entry, fh):
    arrays = {}
    tree = _to_tree(entry["result"], arrays)
    text = _json_text({"meta": entry["meta"], "tree": tree})
    np.savez(fh, __entry__=np.array(text), **arrays)


def _npz_load(fh):
    with np.load(fh, allow_pickle=False) as z:
        arrays = {k: z[k] for k in z.files if k != "__entry__"}
        head = json.loads(str(z["__entry__"][()]))
    return {"meta": head["meta"], "result": _from_tree(head["tree"], arrays)}


#: Entries as JSON (``<key>.json``): plain dicts, lists and numbers.
JSON = Serializer(".json", _json_dump, json.load, False)
#: Entries as ``.npz`` (``<key>.npz``, read with ``allow_pickle=False``): nested dicts and
#: lists of arrays, numbers and str, the structure as JSON inside; tuples come back as lists.
NPZ = Serializer(".npz", _npz_dump, _npz_load, True)


def _checksum(result, serializer):
    if serializer.suffix == ".npz":
        arrays = {}
        return _npz_checksum(_json_text(_to_tree(result, arrays)), arrays)
    return _json_checksum(json.loads(_json_text(result)))


def __getattr__(name):
    if name == "PICKLE":
        warnings.warn("filterwnn.studies.runner.PICKLE is gone: cache entries are never pickled (a pickle from "
                      "a shared folder can run code); use runner.NPZ, which stores arrays as .npz + JSON",
                      DeprecationWarning, stacklevel=2)
        return NPZ
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _path(cache_dir, key, serializer):
    return os.path.join(cache_dir, key + serializer.suffix)


def _meta(task, result, serializer):
    return {"key": task_key(task), "task": json.loads(_json_text(task)), "code": code_version(),
            "format": CACHE_FORMAT, "checksum": _checksum(result, serializer), "nonfinite": _n_nonfinite(result)}


def _read_entry(path, task, serializer):
    """``(result, None)`` for a valid entry of ``task`` at ``path``, ``(None, reason)`` otherwise
    (``(None, None)``: no entry)."""
    try:
        with open(path, "rb" if serializer.binary else "r") as fh:
            entry = serializer.load(fh)
        meta, result = entry["meta"], entry["result"]
        key, stored_task, code = meta["key"], meta["task"], meta["code"]
    except FileNotFoundError:
        return None, None
    except Exception as exc:  # noqa: BLE001 -- whatever a damaged or foreign file raises: never used
        return None, f"unreadable or truncated ({type(exc).__name__})"
    if key != task_key(task) or _json_text(stored_task) != _json_text(task):
        return None, "another task's entry under this task's name"
    if code != code_version() or meta.get("format") != CACHE_FORMAT:
        return None, f"made by other code (version {code}, this is {code_version()})"
    try:
        ok = meta.get("checksum") == _checksum(result, serializer)
    except (TypeError, ValueError):
        ok = False
    if not ok:
        return None, "checksum mismatch (edited or damaged)"
    if _n_nonfinite(result) != meta.get("nonfinite"):
        return None, "non-finite values the run did not write"
    return result, None


_WARNED = set()  # (path, size, mtime, reason) already reported in this process: one line per damaged file


def _file_id(path):
    try:
        st = os.stat(path)
        return st.st_size, st.st_mtime_ns
    except OSError:
        return None


def _warn_rejected(cache_dir, rejected):
    """One :class:`CacheEntryWarning` line per reason, naming the first file and the count
    (a file already reported in this process, unchanged since, is not reported again)."""
    by_reason = {}
    for path, reason in rejected:
        key = (path, _file_id(path), reason)
        if key in _WARNED:
            continue
        _WARNED.add(key)
        by_reason.setdefault(reason, []).append(path)
    for reason, paths in by_reason.items():
        more = f" and {len(paths) - 1} more" if len(paths) > 1 else ""
        warnings.warn(f"cache {cache_dir}: not using {paths[0]}{more}: {reason}; running the task again",
                      CacheEntryWarning, stacklevel=3)


def load_cached(tasks, cache_dir, serializer=JSON):
    """The cached result of each task, ``None`` where there is no valid entry (or no ``cache_dir``).

    An entry is used only when it parses, carries this task's key and settings, this
    :func:`code_version`, a matching checksum and as many non-finite values as the run
    wrote; any other entry is named in a :class:`CacheEntryWarning` (one line per reason)
    and treated as missing. Nothing read can run code (JSON and ``allow_pickle=False``).
    """
    out = [None] * len(tasks)
    if cache_dir is None:
        return out
    rejected = []
    for i, task in enumerate(tasks):
        path = _path(cache_dir, task_key(task), serializer)
        out[i], reason = _read_entry(path, task, serializer)
        if reason is not None:
            rejected.append((path, reason))
    _warn_rejected(cache_dir, rejected)
    return out


def _save(cache_dir, task, result, serializer):
    """Write one entry atomically: a temporary file of a unique name in ``cache_dir``, then
    ``os.replace``, so two processes on one folder never publish a half-written file."""
    path = _path(cache_dir, task_key(task), serializer)
    entry = {"meta": _meta(task, result, serializer), "result": result}
    fd, tmp = tempfile.mkstemp(dir=cache_dir, prefix=f".{task_key(task)}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb" if serializer.binary else "w") as fh:
            serializer.dump(entry, fh)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


#: A temporary entry file older than this (s) was left by a writer that was killed.
STALE_TEMPORARY_AGE = 86400.0


def _remove_stale_temporaries(cache_dir):
    """Delete ``.<key>.*.tmp`` files older than :data:`STALE_TEMPORARY_AGE` (a writer killed
    mid-write leaves one; a live writer's is seconds old)."""
    import time

    now = time.time()
    for name in os.listdir(cache_dir):
        if name.startswith(".") and name.endswith(".tmp"):
            path = os.path.join(cache_dir, name)
            with contextlib.suppress(OSError):
                if now - os.path.getmtime(path) > STALE_TEMPORARY_AGE:
                    os.unlink(path)


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
        :data:`JSON` (default) or :data:`NPZ` (results holding arrays).

    Returns
    -------
    list
        One result per task (``None`` for a task skipped by ``cached_only``).
    """
    if cache_dir is not None:
        os.makedirs(cache_dir, exist_ok=True)
        _remove_stale_temporaries(cache_dir)
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
                _save(cache_dir, tasks[i], r, serializer)
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

    backend = backend or "loky"
    # loky workers outlive a parent killed by a signal; this initializer ends them with it
    extra = {"initializer": _end_with_parent} if backend == "loky" else {}
    # parallel_config registers external backends such as "dask" on first use
    with parallel_config(backend=backend, n_jobs=n_jobs, **extra):
        yield from Parallel(return_as="generator_unordered")(delayed(_indexed)(fn, i, tasks[i]) for i in pending)


def _end_with_parent(poll=0.5):
    """Worker initializer: a daemon thread that ends this worker once its parent is gone.

    A loky worker whose parent dies (SIGKILL, SIGTERM, a crash) is re-parented and would
    otherwise keep its memory until loky's idle timeout, or for good; this one checks
    ``os.getppid()`` every ``poll`` seconds and exits when it changes.
    """
    import threading
    import time

    parent = os.getppid()

    def watch():
        while os.getppid() == parent:
            time.sleep(poll)
        os._exit(1)

    threading.Thread(target=watch, name="filterwnn-end-with-parent", daemon=True).start()


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

    Raises
    ------
    ValueError
        A ``scheduler`` with another backend (it would be ignored).
    """
    if backend != "dask":
        if scheduler:
            raise ValueError(f"--scheduler applies with --backend dask only (got --backend {backend or 'loky'}), "
                             "and would be ignored here")
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
