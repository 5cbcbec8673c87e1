"""The README's Python examples run as written, and its first block holds two commands."""

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


@pytest.mark.parametrize("code", blocks("python"))
def test_python_examples_run(code, capsys):
    exec(compile(code, str(README), "exec"), {"__name__": "__readme__"})


def test_ci_runs_the_readme_test_command():
    ci = (README.parent / ".ci" / "run").read_text()
    assert 'pip install ".[test]" && python -m pytest' in ci
