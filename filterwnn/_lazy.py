"""Lazy exports (PEP 562) and the old flat module paths, for the package's ``__init__`` files.

``import filterwnn`` imports nothing heavy: each exported name is imported from its home
module the first time it is read, so scikit-learn, the studies and matplotlib load only
when a user reaches for them. The modules that moved into the subpackages keep their old
paths (``filterwnn.sigma_points`` is ``filterwnn.kalman.sigma_points``, the same module
object, so old pickles and imports work); importing an old path warns once with the new one.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings


def lazy_exports(package, exports):
    """``__getattr__`` and ``__dir__`` for a package whose names live in its modules.

    ``exports`` maps each public name to ``"module"`` or ``"module:attr"`` (relative to
    ``package``); ``"module"`` alone exports the module itself.
    """

    def __getattr__(name):
        try:
            target = exports[name]
        except KeyError:
            raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        mod, _, attr = target.partition(":")
        value = importlib.import_module(f"{package}.{mod}")
        if attr:
            value = getattr(value, attr)
        setattr(sys.modules[package], name, value)
        return value

    def __dir__():
        return sorted(set(sys.modules[package].__dict__) | set(exports))

    return __getattr__, __dir__


class _MovedLoader(importlib.abc.Loader):
    def __init__(self, new):
        self.new = new

    def create_module(self, spec):
        warnings.warn(f"{spec.name} moved to {self.new}: import it from there", DeprecationWarning, stacklevel=4)
        module = importlib.import_module(self.new)
        self._spec = module.__spec__
        return module

    def exec_module(self, module):
        module.__spec__ = self._spec  # the import system set the alias's spec on the real module


class MovedModules(importlib.abc.MetaPathFinder):
    """Resolves ``package.old`` to ``package.new`` for each entry of ``moved``."""

    def __init__(self, package, moved):
        self.package = package
        self.moved = dict(moved)

    def find_spec(self, fullname, path=None, target=None):
        head, _, tail = fullname.partition(".")
        if head != self.package or tail not in self.moved:
            return None
        return importlib.util.spec_from_loader(fullname, _MovedLoader(f"{head}.{self.moved[tail]}"))


def install_moved(package, moved):
    """Register the old paths of ``package`` once (idempotent on re-import)."""
    if not any(isinstance(f, MovedModules) and f.package == package for f in sys.meta_path):
        sys.meta_path.append(MovedModules(package, moved))
