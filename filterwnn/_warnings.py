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
import warnings

#: Steps a folded warning lists before "...".
STEPS_LISTED = 8

_STEP = re.compile(r"\bstep (\d+)")


def fold_messages(texts):
    """The first of ``texts`` (warnings of one kind) with a note of the others' steps."""
    line = texts[0]
    if len(texts) > 1:
        steps = [m.group(1) for m in (_STEP.search(t) for t in texts[1:]) if m]
        listed = ", ".join(steps[:STEPS_LISTED]) + (", ..." if len(steps) > STEPS_LISTED else "")
        at = f", at step{'s' if len(steps) > 1 else ''} {listed}" if steps else ""
        line += f" (and {len(texts) - 1} more like it{at})"
    return line


@contextlib.contextmanager
def folded_warnings(prefix=None, stacklevel=4):
    """Collect the block's warnings and re-issue them folded, one per kind, each prefixed with
    ``prefix + ": "`` when given. ``stacklevel`` 4 points them at the caller of the function whose
    ``with`` statement this is."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield
    groups = {}
    for w in caught:
        text = str(w.message)
        groups.setdefault((w.category, _STEP.split(text)[0]), []).append(text)
    for (category, _), texts in groups.items():
        line = fold_messages(texts)
        warnings.warn(line if prefix is None else f"{prefix}: {line}", category, stacklevel=stacklevel)
