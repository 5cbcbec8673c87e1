"""The console script's parser and its demo."""

import pytest

from filterwnn.cli import main


def test_demo_runs(capsys):
    assert main(["demo"]) == 0
    out = capsys.readouterr().out
    assert "MinimalSkewSigmaPoints" in out and "SphericalSimplexSigmaPoints" in out
    import re

    gaps = re.findall(r"max \|x - x_KF\| (.+)", out)
    assert gaps == ["< 1e-12"] * 3  # every point set gives the Kalman filter's answer
    mse, var = map(float, re.search(r"test MSE ([0-9.]+) \(predicting the mean: ([0-9.]+)\)", out).groups())
    assert mse < 0.2 * var  # the network learned the plant
    dr_err, gps_err = map(float, re.search(r"raw dead reckoning ([0-9.]+) m, GPS/DR EKF ([0-9.]+) m",
                                           out).groups())
    assert gps_err < dr_err


def test_version(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0
    assert "filterwnn" in capsys.readouterr().out


def test_unknown_command_exits_with_usage():
    with pytest.raises(SystemExit) as info:
        main(["nonsense"])
    assert info.value.code == 2


# --- argument validation: exit 2, one argparse error line, no traceback ------------------

import argparse  # noqa: E402
import re  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import warnings  # noqa: E402

from filterwnn.cli import _build_parser  # noqa: E402
from filterwnn.studies import options as _args  # noqa: E402

BAD = [
    (["study", "wnn", "--runs", "0"], "--runs", ">= 1"),
    (["study", "wnn", "--epochs", "-1"], "--epochs", ">= 1"),
    (["study", "wnn", "--jobs", "0"], "--jobs", "negative"),
    (["study", "wnn", "--trainers", "ekf,sukff"], "--trainers", "'sukff'; valid: bp, ekf"),
    (["study", "wnn", "--trainers", ""], "--trainers", "at least one"),
    (["study", "wnn", "--sweep-particles", "5,0"], "--sweep-particles", ">= 1"),
    (["study", "wnn", "--backend", "lokky"], "--backend", "valid:"),
    (["study", "wnn", "--seed", "-1"], "--seed", ">= 0"),
    (["study", "wnn", "--tune-runs", "x"], "--tune-runs", "integer"),
    (["study", "dr", "--runs", "0"], "--runs", ">= 1"),
    (["study", "dr", "--jobs", "0"], "--jobs", ">= 1"),
    (["study", "dr", "--factor", "-3"], "--factor", "> 0"),
    (["study", "dr", "--factor", "inf"], "--factor", "finite"),
    (["study", "dr", "--scenarios", "straight,turnz"], "--scenarios", "'turnz'; valid: straight"),
    (["study", "dr", "--filters", "EKF,ukf"], "--filters", "'ukf'; valid: EKF"),
    (["study", "dr", "--filters", "EKF,EKF"], "--filters", "repeat"),
    (["demo", "--seed", "-2"], "--seed", ">= 0"),
    (["study", "dr", "--out", __file__], "--out", "must be a folder"),  # refused before the study runs
    (["study", "wnn", "--out", __file__ + "/sub"], "--out", "is a file"),
]


@pytest.mark.parametrize("argv, option, rule", BAD, ids=[" ".join(a) for a, _, _ in BAD])
def test_bad_value_exits_2_with_one_error_line(argv, option, rule, capsys):
    with pytest.raises(SystemExit) as info:
        main(argv)
    assert info.value.code == 2
    err = capsys.readouterr().err
    errors = [line for line in err.splitlines() if "error:" in line]
    assert len(errors) == 1, err
    assert f"argument {option}:" in errors[0] and rule in errors[0], errors[0]
    assert "Traceback" not in err


def test_bad_value_in_a_subprocess_has_no_traceback():
    proc = subprocess.run([sys.executable, "-m", "filterwnn.cli", "study", "dr", "--factor", "-3"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert proc.stderr.strip().splitlines()[-1].startswith("filterwnn study dr: error: argument --factor:")
    assert proc.stdout == ""


def _subparsers(parser):
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sp in action.choices.items():
                yield name, sp
                yield from ((f"{name} {n}", p) for n, p in _subparsers(sp))


def _commands():
    return dict(_subparsers(_build_parser()))


def test_every_option_has_help_and_one_progress_flag():
    commands = _commands()
    assert {"demo", "study wnn", "study dr"} <= set(commands)
    for name, sp in commands.items():
        for action in sp._actions:
            if action.option_strings and action.help is not argparse.SUPPRESS:
                assert action.help, f"{name} {action.option_strings} has no help"
        visible = {s for a in sp._actions if a.help is not argparse.SUPPRESS for s in a.option_strings}
        assert "--quiet" not in visible
        if name.startswith("study "):
            assert "--no-progress" in visible, name


@pytest.mark.parametrize("command, option, names", [
    ("study wnn", "--trainers", ("bp", "ekf", "sukf", "supf")),
    ("study dr", "--filters", ("EKF-oracle", "AEKF", "SUKF-8", "DR-only", "UPF")),
    ("study dr", "--scenarios", ("straight", "heading180", "gpsdr")),
])
def test_help_lists_valid_names(command, option, names):
    text = _commands()[command].format_help()
    flat = " ".join(text.split())
    block = flat[flat.index(f"{option} {option.lstrip('-').upper()} ", flat.index("options:")):]
    for n in names:
        assert n in block[:400], (option, n)


def test_help_shows_defaults(capsys):
    with pytest.raises(SystemExit):
        main(["study", "wnn", "--help"])
    flat = " ".join(capsys.readouterr().out.split())
    assert "(default: 3)" in flat  # --runs
    assert "(default: 2026)" in flat  # --seed
    assert "(default: False)" not in flat and "(default: None)" not in flat


def test_top_level_help_has_no_rst_markup(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--help"])
    assert info.value.code == 0
    out = capsys.readouterr().out
    assert "``" not in out and not re.search(r":(func|class|data|mod):", out)
    for command in ("demo", "study wnn", "study dr"):
        assert f"filterwnn {command}" in out


def test_quiet_is_a_deprecated_alias_of_no_progress():
    parser = _build_parser()
    assert parser.parse_args(["study", "dr"]).no_progress is False
    assert parser.parse_args(["study", "dr", "--no-progress"]).no_progress is True
    with pytest.warns(FutureWarning, match="--quiet is deprecated; use --no-progress"):
        assert parser.parse_args(["study", "dr", "--quiet"]).no_progress is True
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        parser.parse_args(["study", "wnn", "--no-progress"])


def test_list_options_parse_to_lists():
    parser = _build_parser()
    args = parser.parse_args(["study", "wnn", "--trainers", " ekf, ukf ", "--sweep-particles", ""])
    assert args.trainers == ["ekf", "ukf"] and args.sweep_particles == []
    assert parser.parse_args(["study", "wnn"]).sweep_particles == [5, 10, 20]
    args = parser.parse_args(["study", "dr", "--scenarios", "turns", "--factor", "2.5", "--jobs", "1"])
    assert args.scenarios == ["turns"] and args.factor == 2.5 and args.filters is None


def test_argument_types_raise_argparse_errors():
    with pytest.raises(argparse.ArgumentTypeError, match="must be an integer >= 1, got '0'"):
        _args.positive_int("0")
    assert _args.joblib_jobs("-2") == -2
    with pytest.raises(argparse.ArgumentTypeError, match="valid: a, b"):
        _args.name_list(("a", "b"))("a,c")
    assert _args.name_list(("a", "b"), allow_empty=True)("") == []
    with pytest.raises(argparse.ArgumentTypeError, match="finite"):
        _args.positive_float("nan")


# --- errors at run time: one stderr line and an exit status, never a traceback ----------

import os  # noqa: E402

from filterwnn import cli  # noqa: E402


def _dr_with(monkeypatch, exc):
    from filterwnn.studies import dr

    def boom(args):
        raise exc

    monkeypatch.setattr(dr, "run", boom)


@pytest.mark.parametrize("exc, code, text", [
    (ValueError("drive.csv: column 'time' must hold numbers;\n data row 3 (line 4) has 'x'"), 2,
     "filterwnn: error: drive.csv: column 'time' must hold numbers; data row 3 (line 4) has 'x'"),
    (FileNotFoundError(2, "No such file or directory", "nope.csv"), 2, "nope.csv"),
    (KeyboardInterrupt(), 130, "filterwnn: interrupted"),
    (cli._Terminated(), 143, "filterwnn: terminated"),
    (IndexError("index 3 is out of bounds"), 1, "internal error: IndexError: index 3"),
])
def test_run_time_errors_are_one_line_with_their_exit_status(monkeypatch, capsys, exc, code, text):
    _dr_with(monkeypatch, exc)
    assert main(["study", "dr"]) == code
    captured = capsys.readouterr()
    assert len(captured.err.strip().splitlines()) == 1 and text in captured.err, captured.err
    assert "Traceback" not in captured.err


@pytest.mark.parametrize("argv, line", [
    (["study", "dr"], "filterwnn: interrupted (Ctrl-C); --cache DIR keeps the finished runs for the next one"),
    (["study", "dr", "--cache", "CACHE"], "filterwnn: interrupted (Ctrl-C); the finished runs are kept in CACHE: the "
                                          "same command resumes"),
    (["study", "dr", "--real"], "filterwnn: interrupted (Ctrl-C); --cache DIR keeps the finished runs for the next "
                                "one"),  # (--real runs the simulated study too)
    (["study", "dr", "--drive", "sample"], "filterwnn: interrupted (Ctrl-C)"),  # drives are not cached
    (["study", "wnn", "--out", "OUT"], "filterwnn: interrupted (Ctrl-C); the finished fits are kept in OUT/cache: the "
                                       "same command resumes"),  # (the WNN study's cache is on by default)
    (["study", "wnn", "--cache", "none"], "filterwnn: interrupted (Ctrl-C)"),
])
def test_an_interrupt_says_where_the_finished_tasks_are_kept_only_where_they_are(monkeypatch, capsys, tmp_path, argv,
                                                                                line):
    """A long drive interrupted by Ctrl-C was told "finished tasks are kept in --cache when one is given", which
    --drive refuses, and the WNN study, whose cache is on by default, was told to give one."""
    from filterwnn.studies import wnn

    _dr_with(monkeypatch, KeyboardInterrupt())
    monkeypatch.setattr(wnn, "run", lambda args: (_ for _ in ()).throw(KeyboardInterrupt()))
    where = {"CACHE": str(tmp_path / "cache"), "OUT": str(tmp_path / "out")}
    assert main([where.get(a, a) for a in argv]) == 130
    assert capsys.readouterr().err.strip() == line.replace("CACHE", where["CACHE"]).replace(
        "OUT/cache", os.path.join(where["OUT"], "cache"))


def test_debug_shows_the_traceback(monkeypatch):
    _dr_with(monkeypatch, ValueError("bad drive"))
    with pytest.raises(ValueError, match="bad drive"):
        main(["study", "dr", "--debug"])
    with pytest.raises(ValueError, match="bad drive"):
        main(["--debug", "study", "dr"])


def test_a_warning_is_one_line_on_stderr(monkeypatch, capsys):
    from filterwnn.studies import dr, runner

    def warns(args):
        warnings.warn("cache C: not using C/x.npz: made by other code", runner.CacheEntryWarning)
        return 0

    monkeypatch.setattr(dr, "run", warns)
    assert main(["study", "dr"]) == 0
    assert capsys.readouterr().err == "filterwnn: warning: cache C: not using C/x.npz: made by other code\n"


def test_missing_drive_file_in_a_subprocess_is_one_line(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "filterwnn.cli", "study", "dr", "--drive", str(tmp_path / "no.csv"),
                           "--out", str(tmp_path)], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "no.csv" in lines[0] and lines[0].startswith("filterwnn: error:"), proc.stderr


def test_dr_help_keeps_the_drive_only_filters_apart():
    flat = " ".join(_commands()["study dr"].format_help().split())
    block = flat[flat.index("--filters FILTERS "):]
    simulated = block[:block.index("with --drive")]
    assert "DR-mech" not in simulated and "DR-mech" in block[:600]


def test_wnn_help_states_the_default_cache_and_its_invalidation_rule():
    flat = " ".join(_commands()["study wnn"].format_help().split())
    block = flat[flat.index("--cache CACHE "):][:500]
    assert "default OUT/cache" in block and "hash of every filterwnn .py file" in block and "'none'" in block


def test_dr_knows_which_options_apply_to_drives_only():
    """Every option whose help says "with --drive" is in DRIVE_ONLY; those and ON_DRIVES are options of the command."""
    from filterwnn.studies.dr._cli import DRIVE_ONLY, ON_DRIVES, SIMULATED_ONLY

    actions = {s: a for a in _commands()["study dr"]._actions for s in a.option_strings}
    said = {s for s, a in actions.items() if s.startswith("--") and (a.help or "").startswith("with --drive")}
    groups = set(DRIVE_ONLY), set(ON_DRIVES), set(SIMULATED_ONLY)
    assert said <= groups[0] and set().union(*groups) <= set(actions)
    assert sum(len(g) for g in groups) == len(set().union(*groups))  # apart


@pytest.mark.parametrize("argv, text", [
    (["--gyro-bias", "0.3"], "--gyro-bias applies to --drive drives only"),
    (["--real", "--fill-gaps", "1", "--heading-offset", "3"], "--fill-gaps, --heading-offset apply to --drive drives only"),
    (["--outage-length", "60"], "--outage-length applies to drives (--drive or --real) only"),
    (["--heading-jump-z", "off", "--grade", "phone"], "--heading-jump-z, --grade apply to drives (--drive or --real)"),
    (["--real", "--drive", "sample"], "--real with --drive: --drive runs the given drives only"),
    (["--drive", "sample", "--runs", "3", "--scenarios", "turns"],
     "--runs, --scenarios apply to the simulated scenarios (not run with --drive) only"),
    (["--scheduler", "tcp://127.0.0.1:8786"], "--scheduler applies with --backend dask only"),
])
def test_dr_refuses_options_where_they_would_be_ignored(argv, text, tmp_path, capsys, monkeypatch):
    """An option given where it does not apply is refused with one line, before anything runs (it was ignored:
    ``--real --gyro-bias 0.3`` ran the survey grade's filters as if it were not there)."""
    import filterwnn.studies.dr._cli as dr_cli

    monkeypatch.setattr(dr_cli, "run_study", lambda **kw: pytest.fail("the study ran"))
    assert main(["study", "dr", "--out", str(tmp_path), *argv]) == 2
    assert text in capsys.readouterr().err


def test_dr_real_drives_take_the_outages_options(tmp_path, monkeypatch):
    """--real places its outages as --outages, --outage-length and --min-speed say (they applied to --drive
    drives only, and --real used 20 of 30 s whatever was given)."""
    import filterwnn.studies.dr._cli as dr_cli

    seen = []

    class Stop(Exception):
        pass

    def record(drive, **kw):
        seen.append(kw)
        raise Stop

    monkeypatch.setattr(dr_cli, "run_study", lambda **kw: None)
    monkeypatch.setattr(dr_cli, "write_outputs", lambda *a, **kw: [])
    monkeypatch.setattr(dr_cli, "markdown_table", lambda res: "")
    monkeypatch.setattr(dr_cli, "load_car_drive", lambda name: name)
    monkeypatch.setattr(dr_cli, "real_drive_outages", record)
    with pytest.raises(Stop):
        dr_cli.run(_build_parser().parse_args(["study", "dr", "--real", "--outages", "7", "--outage-length", "45",
                                               "--min-speed", "2", "--heading-jump-z", "off"]))
    kw, = seen
    assert (kw["n_placements"], kw["length"], kw["min_speed"], kw["heading_jump_z"]) == (7, 45.0, 2.0, None)
    assert kw["grade"] == "survey"


@pytest.mark.parametrize("argv, text", [
    (["--no-paper-table", "--paper-runs", "5"], "--paper-runs does not apply with --no-paper-table"),
    (["--no-paper-table", "--paper-pf-epochs", "5"], "--paper-pf-epochs does not apply with --no-paper-table"),
    (["--sweep-particles", "", "--sweep-runs", "3"], "--sweep-runs does not apply with --sweep-particles ''"),
    (["--cache", "none", "--cached-only"], "--cached-only does not apply with --cache none"),
])
def test_wnn_refuses_options_where_they_would_be_ignored(argv, text, tmp_path, capsys, monkeypatch):
    import filterwnn.studies.wnn.cli as wnn_cli

    monkeypatch.setattr(wnn_cli, "run_study", lambda **kw: pytest.fail("the study ran"))
    assert main(["study", "wnn", "--out", str(tmp_path), *argv]) == 2
    assert text in capsys.readouterr().err


def test_dr_reads_every_drive_and_places_its_outages_before_it_runs_one(tmp_path, capsys, monkeypatch):
    """Several --drive: a file that cannot be read, or whose outages cannot be placed, is refused before any drive
    runs (it stopped the command after the drives before it had run, their outputs unwritten)."""
    import filterwnn.studies.dr._cli as dr_cli

    bad = tmp_path / "bad.csv"
    bad.write_text("time,heading,speed\n0,0,1\n")
    monkeypatch.setattr(dr_cli, "real_drive_outages", lambda *a, **kw: pytest.fail("a drive ran"))
    assert main(["study", "dr", "--drive", "sample", "--drive", str(bad), "--out", str(tmp_path)]) == 2
    assert "bad.csv" in capsys.readouterr().err
    argv = ["study", "dr", "--drive", "sample", "--outage-starts", "10,500", "--out", str(tmp_path)]
    assert main(argv) == 2
    assert "sample: starts must lie in [0, 150]" in capsys.readouterr().err
