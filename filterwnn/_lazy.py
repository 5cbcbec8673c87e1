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
import types
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


def module_exports(names_by_module):
    """The ``exports`` of :func:`lazy_exports` from ``{module: names}``: each name as
    ``"module:name"``, after every module itself under its own name (``"module"``).

    >>> module_exports({"angles": ("wrap",)})
    {'angles': 'angles', 'wrap': 'angles:wrap'}
    """
    exports = {mod: mod for mod in names_by_module}
    for mod, names in names_by_module.items():
        exports.update((name, f"{mod}:{name}") for name in names)
    return exports


class _MovedLoader(importlib.abc.Loader):
    """An old path: the new module itself, or a module that reads through several new homes."""

    def __init__(self, homes):
        self.homes = homes

    def create_module(self, spec):
        where = " and ".join(self.homes)
        warnings.warn(f"{spec.name} moved to {where}: import it from there", DeprecationWarning, stacklevel=4)
        if len(self.homes) == 1:
            module = importlib.import_module(self.homes[0])
            self._spec = module.__spec__
            return module
        self._spec = None
        return _ReadThrough(spec.name, [importlib.import_module(h) for h in self.homes])

    def exec_module(self, module):
        if self._spec is not None:
            module.__spec__ = self._spec  # the import system set the alias's spec on the real module


class _ReadThrough(types.ModuleType):
    """A module whose names are those of its homes, the first home that has the name."""

    def __init__(self, name, homes):
        super().__init__(name, f"Moved: its names are in {', '.join(h.__name__ for h in homes)}.")
        self._homes = homes

    def __getattr__(self, name):
        for home in self._homes:
            if hasattr(home, name):
                return getattr(home, name)
        raise AttributeError(f"module {self.__name__!r} has no attribute {name!r}")

    def __dir__(self):
        return sorted(set().union(*(dir(h) for h in self._homes)))


class MovedModules(importlib.abc.MetaPathFinder):
    """Resolves ``package.old`` to ``package.new`` for each entry of ``moved``."""

    def __init__(self, package, moved):
        self.package = package
        self.moved = {old: (new,) if isinstance(new, str) else tuple(new) for old, new in moved.items()}

    def find_spec(self, fullname, path=None, target=None):
        head, _, tail = fullname.partition(".")
        if head != self.package or tail not in self.moved:
            return None
        return importlib.util.spec_from_loader(fullname, _MovedLoader([f"{head}.{h}" for h in self.moved[tail]]))


def install_moved(package, moved):
    """Register the old paths of ``package`` once (idempotent on re-import).

    ``moved`` maps each old module (relative to ``package``) to its new home, or to a tuple of
    homes when its names went to several modules (the first home that has a name gives it).
    """
    if not any(isinstance(f, MovedModules) and f.package == package for f in sys.meta_path):
        sys.meta_path.append(MovedModules(package, moved))
