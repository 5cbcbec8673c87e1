"""The API reference builds with Sphinx, warnings as errors, and covers every public module."""

import pkgutil
import subprocess
import sys
from pathlib import Path

import pytest

import filterwnn

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"

pytest.importorskip("sphinx")
pytest.importorskip("numpydoc")
pytest.importorskip("myst_nb")


def _public_modules():
    names = ["filterwnn"]
    for info in pkgutil.walk_packages(filterwnn.__path__, "filterwnn."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            names.append(info.name)
    return names


def test_every_public_module_has_an_api_page():
    pages = {p.stem for p in (DOCS / "api").glob("filterwnn.*.rst")}
    missing = [m for m in _public_modules()[1:] if m not in pages]
    assert not missing, f"add docs/api/<module>.rst and list it in docs/api/index.rst for {missing}"
    index = (DOCS / "api" / "index.rst").read_text()
    unlisted = [p for p in sorted(pages) if f"   {p}\n" not in index]
    assert not unlisted, f"list {unlisted} in a toctree of docs/api/index.rst"
    stale = [p for p in sorted(pages) if p not in _public_modules()]
    assert not stale, f"docs/api pages for modules that do not exist: {stale}"


def test_sphinx_build_has_no_warnings(tmp_path):
    out = tmp_path / "html"
    proc = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-E", "-q", "-b", "html",
         "-d", str(tmp_path / "doctrees"), str(DOCS), str(out)],
        cwd=ROOT, capture_output=True, text=True, timeout=300,
    )
    assert proc.returncode == 0, proc.stderr[-6000:]
    assert "WARNING" not in proc.stderr and "ERROR" not in proc.stderr, proc.stderr[-6000:]
    for page in ["index", "guide", "gps_dr", "wnn_study", "performance", "api/index", "api/filterwnn.kalman.unscented", "api/filterwnn.cli"]:
        assert (out / f"{page}.html").exists(), page
    # the README is the guide, with its figures copied in
    guide = (out / "guide.html").read_text()
    assert "The first five minutes" in guide and "_images/" in guide
    # the four notebooks are rendered (from the stored files, never executed)
    stored = sorted(p.stem for p in (ROOT / "notebooks").glob("*.ipynb"))
    assert len(stored) == 4
    assert sorted(p.stem for p in (out / "notebooks").glob("*.html")) == stored
