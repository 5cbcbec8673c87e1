"""A failed step leaves a filter as it was: attributes, list lengths and the RNG's state.

A filter's ``predict``/``update`` rebinds many attributes (particles, weights, moments,
the step count), appends to its histories and draws from its ``rng``; an exception half
way (an impossible measurement, a non-finite prediction) would leave some changed and the
random stream advanced, so that retrying, or going on with another measurement, gives
numbers no uninterrupted run gives. :func:`rolls_back_on_error` wraps such a method:
before it runs it keeps a shallow copy of the instance's attributes, the length of each
list attribute and ``rng.bit_generator.state``; if the method raises, all three are put
back and the exception goes on. The cost is one dictionary copy per call, a scan of its
values for lists and the generator's state (a few microseconds).

>>> import numpy as np
>>> class Counter:
...     def __init__(self):
...         self.n, self.log, self.rng = 0, [], np.random.default_rng(0)
...     @rolls_back_on_error
...     def step(self, fail=False):
...         self.n += 1
...         self.log.append(self.rng.random())
...         if fail:
...             raise ValueError("rejected")
>>> c = Counter()
>>> before = c.rng.bit_generator.state
>>> try:
...     c.step(fail=True)
... except ValueError:
...     pass
>>> c.n, c.log, c.rng.bit_generator.state == before
(0, [], True)
"""

from __future__ import annotations

import functools

__all__ = ["rolls_back_on_error", "slot_names", "slot_values"]


@functools.lru_cache(maxsize=None)
def slot_names(cls):
    """The attribute names ``cls`` and its bases keep in ``__slots__`` (a class that also has a ``__dict__``
    keeps its growing histories there, out of filterpy's ``Saver``), as a frozenset."""
    names = set()
    for klass in cls.__mro__:
        slots = klass.__dict__.get("__slots__", ())
        names.update((slots,) if isinstance(slots, str) else slots)
    return frozenset(names - {"__dict__", "__weakref__"})


def slot_values(obj):
    """``{name: value}`` of the slots ``obj`` has set (:func:`slot_names`)."""
    return {name: getattr(obj, name) for name in slot_names(type(obj)) if hasattr(obj, name)}


def _part_dicts(saved, names):
    """``[(part, copy of its __dict__)]`` for the named attributes of ``saved`` that have one."""
    return [(saved[name], dict(saved[name].__dict__)) for name in names
            if getattr(saved.get(name), "__dict__", None) is not None]


def rolls_back_on_error(method):
    """Decorate a method so that, when it raises, the instance is restored (see the module docstring).

    Restored: every attribute's binding (``self.__dict__``, and the slots the class keeps:
    :func:`slot_values`), the bindings of the parts the
    class names in ``_rollback_parts`` (owned objects it steps, e.g. a filter bank), the length
    of every list attribute (appended entries are removed; entries changed in place are not
    undone) and the state of ``self.rng``'s bit generator when there is one. A class that
    names its list attributes in ``_rollback_lists`` (its histories) has only those
    truncated, without a scan of every attribute per call.
    """

    @functools.wraps(method)
    def wrapper(self, *args, **kwargs):
        saved = self.__dict__.copy()  # references: what the step rebinds needs no copy
        slotted = slot_values(self)
        names = getattr(self, "_rollback_parts", None)
        parts = _part_dicts(saved, names) if names else None
        lists = getattr(self, "_rollback_lists", None)
        every = {**saved, **slotted}
        values = every.values() if lists is None else map(every.get, lists)
        lengths = [(v, len(v)) for v in values if isinstance(v, list)]
        rng = saved.get("rng")
        bits = None if rng is None else getattr(rng, "bit_generator", None)
        rng_state = None if bits is None else bits.state
        try:
            return method(self, *args, **kwargs)
        except BaseException:
            self.__dict__.clear()
            self.__dict__.update(saved)
            for name in slot_names(type(self)):
                if name in slotted:
                    setattr(self, name, slotted[name])
                elif hasattr(self, name):
                    delattr(self, name)
            if parts:
                for obj, attrs in parts:
                    obj.__dict__.clear()
                    obj.__dict__.update(attrs)
            for v, n in lengths:
                del v[n:]
            if rng_state is not None:
                bits.state = rng_state
            raise

    return wrapper
