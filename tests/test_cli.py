"""The console script's parser and its demo."""

import pytest

from filterwnn.cli import main


def test_demo_runs(capsys):
    assert main(["demo"]) == 0
    out = capsys.readouterr().out
    assert "MinimalSkewSigmaPoints" in out and "SphericalSimplexSigmaPoints" in out


def test_version(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0
    assert "filterwnn" in capsys.readouterr().out


def test_unknown_command_exits_with_usage():
    with pytest.raises(SystemExit) as info:
        main(["nonsense"])
    assert info.value.code == 2
