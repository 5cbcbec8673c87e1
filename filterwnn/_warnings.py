"""Warnings that a long run gives many times, folded into one line per kind.

A filter run over a drive can warn at many steps for one cause (the consistency monitor each
time the fixes turn optimistic again, the calibration bound each time a state reaches it).
:func:`folded_warnings` collects what its block warns and re-issues it once per kind (the same
category and the same text up to its first ``step N``), with the steps of the repeats:

>>> import warnings
>>> with warnings.catch_warnings(record=True) as seen:
...     warnings.simplefilter("always")
...     with folded_warnings("EKF-8"):
...         for k in (5, 9, 12):
...             warnings.warn(f"inconsistent at step {k}: NIS {k}", RuntimeWarning)
>>> [str(w.message) for w in seen]
['EKF-8: inconsistent at step 5: NIS 5 (and 2 more like it, at steps 9, 12)']

The outer warning filters apply to the re-issued lines as to any warning (``-W error`` raises,
once the block has ended).
"""

from __future__ import annotations

import contextlib
import re
import sys
import warnings

import numpy as np

#: Steps a folded warning lists before "...".
STEPS_LISTED = 8

_STEP = re.compile(r"\bstep (\d+)")


def _time(times, k):
    """The time of step ``k`` as text (``None`` past the end of ``times``)."""
    if not 0 <= k < len(times):
        return None
    return np.format_float_positional(float(times[k]), precision=2, trim="-")


def with_times(text, times):
    """``text`` with each ``step N`` followed by the time of step N, ``times[N]`` (a drive's own
    time column, in seconds): ``"at step 508"`` -> ``"at step 508 (t = 1508.2 s)"``. A step
    past the end of ``times`` is left as it is.

    >>> with_times("P lost positive definiteness at step 2", [10.0, 10.2, 10.4])
    'P lost positive definiteness at step 2 (t = 10.4 s)'
    """
    def at(m):
        t = _time(times, int(m.group(1)))
        return m.group(0) if t is None else f"{m.group(0)} (t = {t} s)"
    return _STEP.sub(at, text)


def fold_messages(texts, times=None):
    """The first of ``texts`` (warnings of one kind) with a note of the others' steps; with
    ``times`` (the time of each step), each step named is followed by its time."""
    line = texts[0] if times is None else with_times(texts[0], times)
    if len(texts) > 1:
        steps = [m.group(1) for m in (_STEP.search(t) for t in texts[1:]) if m]
        shown = steps[:STEPS_LISTED]
        listed = ", ".join(shown) + (", ..." if len(steps) > STEPS_LISTED else "")
        at = f", at step{'s' if len(steps) > 1 else ''} {listed}" if steps else ""
        stamps = [] if times is None else [_time(times, int(k)) for k in shown]
        if stamps and None not in stamps:
            at += f" (t = {', '.join(stamps)}{', ...' if len(steps) > STEPS_LISTED else ''} s)"
        line += f" (and {len(texts) - 1} more like it{at})"
    return line


@contextlib.contextmanager
def folded_warnings(prefix=None, stacklevel=4, times=None):
    """Collect the block's warnings and re-issue them folded, one per kind, each prefixed with
    ``prefix + ": "`` when given. ``stacklevel`` 4 points them at the caller of the function whose
    ``with`` statement this is. ``times``, the time of each step (a drive's ``t``), follows each
    step the lines name with its time, so that a warning can be found in the user's own log. A block that
    raises gives its warnings too, before the exception goes on (what a filter warned of before it failed)."""
    # (+4: the frames of _fold_and_warn, this lambda, _recorded and its __exit__ under this generator's)
    with _recorded(lambda caught: _fold_and_warn(caught, prefix, stacklevel + 4, times)):
        yield


@contextlib.contextmanager
def _recorded(then):
    """Record every warning the block gives, whatever the warning filters outside say, and call
    ``then(caught)`` with them (``warnings.WarningMessage`` s) once the recording has stopped: when the block
    ends, or as it raises."""
    caught = []
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            yield
    finally:
        then(caught)


def recorded_call(fn, *args, **kwargs):
    """``fn(*args, **kwargs)`` with its warnings recorded, for a worker process to send back:
    ``(its result, its warnings [(category, text)], None)``, or ``(None, its warnings, the exception)`` where it
    raised. :func:`give_again` gives them in the parent."""
    result = failed = None
    told = []
    with _recorded(lambda caught: told.extend((w.category, str(w.message)) for w in caught)):
        try:
            result = fn(*args, **kwargs)
        except Exception as exc:  # noqa: BLE001 -- raised by give_again, after the warnings it followed
            failed = exc
    return result, told, failed


def give_again(told, failed=None, stacklevel=2):
    """Issue the warnings ``told`` (``[(category, text)]``, from :func:`recorded_call`) here, in order, then raise
    ``failed`` if it is an exception. ``stacklevel`` is ``warnings.warn``'s as seen from the caller."""
    for category, text in told:
        warnings.warn(text, category, stacklevel=stacklevel + 1)
    if failed is not None:
        raise failed


def _fold_and_warn(caught, prefix, stacklevel, times):
    """Issue the recorded warnings ``caught`` folded, one per kind (see :func:`folded_warnings`)."""
    groups = {}
    for w in caught:
        text = str(w.message)
        groups.setdefault((w.category, _STEP.split(text)[0]), []).append(text)
    for (category, _), texts in groups.items():
        line = fold_messages(texts, times)
        warnings.warn(line if prefix is None else f"{prefix}: {line}", category, stacklevel=stacklevel)


def _origin(filename):
    """The module whose source is ``filename`` and its warning registry, so that a warning issued again from
    there is filtered (by module) and shown once (``default``) as the first was; ``(None, None)`` if none."""
    for name, module in list(sys.modules.items()):
        if getattr(module, "__file__", None) == filename:
            return name, module.__dict__.setdefault("__warningregistry__", {})
    return None, None


@contextlib.contextmanager
def kept_warnings(kept):
    """Append the text of every warning the block gives to the list ``kept`` (one line each, whatever the
    warning filters say), and issue each again when the block ends, or raises, from where it was given: the
    filters outside then show it, ignore it or raise it as they would have (only later, with the block's
    others). A report keeps with its numbers what the run warned of (``filterwnn study dr`` writes them under
    a drive's table).

    >>> import warnings
    >>> kept = []
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     with kept_warnings(kept):
    ...         warnings.warn("the fixes read 0.2 s late", RuntimeWarning)
    >>> kept
    ['the fixes read 0.2 s late']
    """
    def keep_and_give_again(caught):
        kept.extend(" ".join(str(w.message).split()) for w in caught)
        for w in caught:
            module, registry = _origin(w.filename)
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, module=module, registry=registry)

    with _recorded(keep_and_give_again):
        yield
