"""The README's Python examples run and print what it shows, the demo too, and its first block holds two commands."""

import pathlib
import re

import pytest

README = pathlib.Path(__file__).resolve().parents[1] / "README.md"


def blocks(lang):
    text = README.read_text()
    return re.findall(rf"```{lang}\n(.*?)```", text, flags=re.S)


def test_first_block_has_exactly_the_two_commands():
    text = README.read_text()
    first = re.search(r"```(\w*)\n(.*?)```", text, flags=re.S).group(2)
    lines = [ln for ln in first.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    assert len(lines) == 2
    assert lines[0].startswith("pip install") and "filterwnn" in lines[0]
    assert lines[1] == 'pip install ".[test]" && python -m pytest'


def examples():
    """Each ```python block, with the ```text block that follows it (its printed output), if any."""
    text = README.read_text()
    return [(m.group(1), m.group(2)) for m in re.finditer(r"```python\n(.*?)```\s*(?:```text\n(.*?)```)?", text, flags=re.S)]


@pytest.mark.parametrize("code, expected", examples())
def test_python_examples_run_and_print_what_the_readme_shows(code, expected, capsys):
    exec(compile(code, str(README), "exec"), {"__name__": "__readme__"})
    if expected is not None:
        assert capsys.readouterr().out.strip() == expected.strip()


def test_the_demo_prints_what_the_readme_shows(capsys):
    from filterwnn.cli import main

    shown = re.search(r"```text\n\$ filterwnn demo\n(.*?)```", README.read_text(), flags=re.S).group(1)
    main(["demo"])
    out = capsys.readouterr().out
    printed = out[: out.rindex("\n(")]  # the last line is the elapsed time
    assert printed.strip() == shown.strip()


def test_ci_runs_the_readme_test_command():
    ci = (README.parent / ".ci" / "run").read_text()
    assert 'pip install ".[test]" && python -m pytest' in ci


def test_the_test_command_runs_a_worker_a_core_each_with_one_blas_thread():
    """``python -m pytest`` spreads the suite over the machine's cores (``-n auto`` in
    ``setup.cfg``, pytest-xdist): a worker's BLAS must not start a thread a core as well."""
    import os

    from threadpoolctl import threadpool_info

    if not os.environ.get("PYTEST_XDIST_WORKER"):
        pytest.skip("run in one process (-n 0 or -p no:xdist)")
    blas = [lib for lib in threadpool_info() if lib["user_api"] == "blas"]
    assert blas and all(lib["num_threads"] == 1 for lib in blas), blas


@pytest.mark.parametrize("page", ["README.md", "docs/gps_dr.md", "docs/wnn_study.md", "docs/performance.md"])
def test_every_repository_path_a_page_names_exists(page):
    """A path into the repository that the README or a page of docs/ beside it names (a script, a study's
    output, a test) is there: moved or renamed, the page must say so."""
    text = (README.parent / page).read_text()
    named = set(re.findall(r"(?<![\w/.-])((?:docs|tests|benchmarks|notebooks|filterwnn)/[\w/.\-]+\w)", text))
    missing = sorted(p for p in named if "_build" not in p and not (README.parent / p.split("::")[0]).exists())
    assert not missing, f"{page} names paths that do not exist: {missing}"
