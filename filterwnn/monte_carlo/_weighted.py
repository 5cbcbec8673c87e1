"""What the weighted-mixture filters share: :class:`~filterwnn.ParticleFilter` (a cloud of
weighted particles) and :class:`~filterwnn.GaussianSumFilter` (a bank of weighted Gaussian
components).

Both keep the estimate in ``x``/``P`` (refused once the members exist: it would be ignored),
record the effective sample size per update, re-attach their resampling scheme after
unpickling and run ``batch_filter`` the same way.
"""

from __future__ import annotations

import math

import numpy as np

from .._state import slot_names, slot_values
from .resampling import get_scheme

__all__ = ["logsumexp", "ModelAttribute", "WeightedMixtureFilter"]


def logsumexp(a):
    """``log(sum(exp(a)))`` of a 1-D array (``-inf`` if every entry is ``-inf``).

    Kept beside :func:`scipy.special.logsumexp`, whose log1p form (scipy 1.15) rounds the last
    bit differently for about 2 % of inputs and so would move the studies' numbers.

    >>> logsumexp(np.log([1.0, 3.0]))
    1.3862943611198906
    """
    m = a.max()  # the array methods: the same reductions without numpy's Python wrappers
    if not math.isfinite(m):
        return float(m)
    e = a - m
    e = np.exp(e, out=e) if e.dtype.kind == "f" else np.exp(e)  # in place: one temporary, not two
    return float(m + np.log(e.sum()))


class ModelAttribute:
    """A filter attribute that lives on the filter's one model object (``self._model``).

    ``pf.Q`` reads ``pf._model.Q`` and ``pf.Q = ...`` writes it (through ``check(value,
    name)`` when given), so the model the proposals and Kalman steps see is always the
    filter's, with no per-step copying; an in-place edit (``pf.Q[0, 0] = 2``) edits the
    model's matrix, which the model's noise check compares at the next step.
    """

    def __init__(self, check=None, doc=None):
        self.check = check
        self.__doc__ = doc

    def __set_name__(self, owner, name):
        self.name = name

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        return getattr(obj._model, self.name)

    def __set__(self, obj, value):
        setattr(obj._model, self.name, value if self.check is None else self.check(value, self.name))


class SettledAttribute(property):
    """A moment a filter forms when it is read: ``obj.<name>`` is ``obj._<name>``.

    On read, ``obj._settle()`` first forms what ``predict`` left pending (every read, or with
    ``when_missing=True`` only while ``obj._<name>`` is None); ``obj.<name> = value`` stores
    ``value``, after ``obj._refuse_mid_run(name)`` with ``guarded=True`` (a starting state set
    once the members exist would be ignored, so it raises instead). A ``property``, so that
    filterpy's ``Saver``, which reads a filter's properties at each ``save()``, records ``x`` and
    ``P`` (the pending ones formed then), not the ``None`` that ``_x`` holds while they wait.
    """

    def __init__(self, doc, *, when_missing=False, guarded=False):
        super().__init__(doc=doc)
        self.when_missing = when_missing
        self.guarded = guarded

    def __set_name__(self, owner, name):
        self.name = name
        self.slot = "_" + name

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        if not self.when_missing or getattr(obj, self.slot) is None:
            obj._settle()
        return getattr(obj, self.slot)

    def __set__(self, obj, value):
        if self.guarded:
            obj._refuse_mid_run(self.name)
        setattr(obj, self.slot, value)


class WeightedMixtureFilter:
    """Base of the weighted-mixture filters (no constructor: the subclasses set the state).

    A subclass sets ``_members_attr`` (the attribute that holds the members once they exist),
    ``_members_word`` and ``_restart_hint`` (for the error when ``x`` or ``P`` is set mid-run),
    and keeps ``dim_x``, ``step``, ``resampling``, ``_resample``, ``_x``, ``_P`` and the
    ``ess``/``n_distinct`` histories.
    """

    #: The histories are slots, out of ``__dict__`` (read and set as any attribute): filterpy's ``Saver`` copies
    #: ``__dict__`` at each ``save()`` and stacks each entry in ``to_array()``, and a list that grows at every
    #: update cannot be stacked (it raised ``could not convert ess_history``).
    __slots__ = ("ess_history", "n_distinct_history", "resampled_history", "__dict__", "__weakref__")

    _members_attr = "particles"
    _members_word = "particles"
    _restart_hint = "call initialize(...) to restart"

    def _filterpy_defaults(self):
        """filterpy's starting values: ``x = 0``, ``P = Q = I``, ``R = I``; prior and posterior alike."""
        self._x = np.zeros(self.dim_x)
        self._P = np.eye(self.dim_x)
        self.Q = np.eye(self.dim_x)
        self.R = np.eye(self.dim_z)
        self.x_prior, self.P_prior = self._x.copy(), self._P.copy()
        self.x_post, self.P_post = self._x.copy(), self._P.copy()

    x = SettledAttribute("""State estimate, shape ``(dim_x,)``; set it with ``P`` before the first
        ``predict`` (a Gaussian start ``N(x, P)``), or use ``initialize``.""", when_missing=True, guarded=True)
    P = SettledAttribute("State covariance, shape ``(dim_x, dim_x)``.", when_missing=True, guarded=True)

    def _settle(self):
        """Form the moments a subclass left pending (``_x``/``_P`` None until first read)."""

    def _refuse_mid_run(self, name):
        if getattr(self, self._members_attr) is not None:
            raise ValueError(
                f"{name} cannot be set once the {self._members_word} exist (step {self.step}): it would be "
                f"ignored; {self._restart_hint}"
            )

    _keep_history = True
    #: The list attributes a failed step truncates back (``filterwnn._state.rolls_back_on_error``).
    _rollback_lists = ("ess_history", "n_distinct_history", "resampled_history")

    @property
    def keep_history(self):
        """What ``ess_history``, ``n_distinct_history`` and ``resampled_history`` keep:
        ``True`` (default) every update's entry, ``False`` none (flat memory on long runs),
        an int ``n >= 0`` the last ``n``."""
        return self._keep_history

    @keep_history.setter
    def keep_history(self, value):
        if not isinstance(value, (bool, np.bool_)) and (not isinstance(value, (int, np.integer)) or value < 0):
            raise ValueError(f"keep_history must be True, False or an int >= 0 (the last n entries), got {value!r}")
        self._keep_history = bool(value) if isinstance(value, (bool, np.bool_)) else int(value)

    def _record(self, ess, n_distinct, resampled):
        self.ess, self.n_distinct = float(ess), int(n_distinct)
        keep = self._keep_history
        if keep is False:
            return
        self.ess_history.append(self.ess)
        self.n_distinct_history.append(self.n_distinct)
        self.resampled_history.append(bool(resampled))
        if keep is not True:
            for hist in (self.ess_history, self.n_distinct_history, self.resampled_history):
                if len(hist) > keep:
                    del hist[: len(hist) - keep]

    def __getstate__(self):
        state = self.__dict__.copy()
        state.update(slot_values(self))
        del state["_resample"]  # a scheme's raw implementation (or a wrapped callable): looked up again
        return state

    def __setstate__(self, state):
        slots = slot_names(type(self))
        for name, value in state.items():
            if name in slots:
                setattr(self, name, value)
            else:
                self.__dict__[name] = value
        self._resample = get_scheme(self.resampling)

    def batch_filter(self, zs, fx_args=None, hx_args=None, saver=None):
        """Run ``predict``/``update`` over a sequence of measurements.

        Parameters
        ----------
        zs : sequence of length n_steps of array-like of shape (dim_z,) or None
            ``None`` entries skip the update.
        fx_args, hx_args : dict, optional
            Keywords for every ``predict``/``update`` call.
        saver : filterpy.common.Saver, optional
            ``saver.save()`` after every step, as filterpy's ``batch_filter`` calls it.

        Returns
        -------
        means : ndarray of shape (n_steps, dim_x)
        covariances : ndarray of shape (n_steps, dim_x, dim_x)
            ``x`` and ``P`` after each update.
        """
        fx_args = {} if fx_args is None else dict(fx_args)
        hx_args = {} if hx_args is None else dict(hx_args)
        n = len(zs)
        means = np.empty((n, self.dim_x))
        covs = np.empty((n, self.dim_x, self.dim_x))
        for k, z in enumerate(zs):
            self.predict(**fx_args)
            self.update(z, **hx_args)
            means[k], covs[k] = self.x, self.P  # (formed here if the update left them pending)
            if saver is not None:
                saver.save()
        return means, covs
