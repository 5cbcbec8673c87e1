"""Sphinx configuration of the filterwnn API reference.

Build it from the repository root (the tests do, with warnings as errors)::

    sphinx-build -W -b html docs docs/_build/html

The pages are ``index.rst``, ``guide.md`` (the README), ``gps_dr.md`` (GPS/DR on one's own drive, in
detail), ``wnn_study.md`` (the first paper's study in full), ``performance.md`` (the benchmarks'
findings), ``notebooks.rst`` with the four notebooks (rendered from the stored files, never executed: ``nb_execution_mode = "off"``)
and one page per public module under ``api/``. ``figures/`` and ``study-outputs/`` hold
files the README links to; only their Markdown tables are pages.
"""

import os
import sys

# Document the checkout these docs sit in, not another installed copy.
sys.path.insert(0, os.path.abspath(".."))

import filterwnn  # noqa: E402

project = "filterwnn"
author = "filterwnn contributors"
copyright = "filterwnn contributors"
version = release = filterwnn.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_nb",
]

root_doc = "index"
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
exclude_patterns = ["_build", "**/.ipynb_checkpoints", "figures"]

# Every cross-reference inside the package must resolve; names from other packages
# (numpy, scipy, filterpy, scikit-learn, ...) are not linked, since the build runs offline.
nitpicky = True
nitpick_ignore_regex = [
    (r"py:.*", r"(?!filterwnn\b)\w+\..*"),  # numpy.ndarray, filterpy.kalman..., importlib.resources
    (r"py:.*", r"(int|float|str|bool|callable|object|tuple|list|dict|None|optional)"),
    (r"py:class", r"filterwnn\.(\w+\.)*_\w+(\.\w+)?"),  # private base classes (or in private modules)
]

# autodoc: members come from each module's __all__.
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "none"

# numpydoc: no member tables (they would need autosummary stubs); types are plain text.
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks = set()

# myst / myst-nb: notebooks are shown as stored, never run during the build.
nb_execution_mode = "off"
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]



def _resolve_reexport(app, env, node, contnode):
    """Resolve ``filterwnn.Name`` (a re-export) to where ``Name`` is documented.

    The docstrings cite public names the way users import them (``filterwnn.NeuralFilter``);
    the reference documents each object once, in its module (``filterwnn.navigation.neural_filter``).
    """
    target = node.get("reftarget", "")
    if node.get("refdomain") != "py" or not target.startswith("filterwnn.") or target.count(".") != 1:
        return None
    obj = getattr(filterwnn, target.split(".", 1)[1], None)
    module, qualname = getattr(obj, "__module__", None), getattr(obj, "__qualname__", None)
    if not (module and qualname) or f"{module}.{qualname}" == target:
        return None
    node["reftarget"] = f"{module}.{qualname}"
    return env.get_domain("py").resolve_xref(env, node["refdoc"], app.builder, node["reftype"],
                                             node["reftarget"], node, contnode)


def _skip_member(app, what, name, obj, skip, options):
    """Skip the ``set_*_request`` methods scikit-learn generates on every estimator."""
    if name.startswith("set_") and name.endswith("_request"):
        return True
    return None


def setup(app):
    app.connect("missing-reference", _resolve_reexport)
    app.connect("autodoc-skip-member", _skip_member)


html_theme = "alabaster"
html_title = f"filterwnn {release}"
html_static_path = []
