"""Tests of the dead-reckoning study: reproducibility, jobs-independence, outputs."""

import argparse
import os

import numpy as np
import pytest

from filterwnn.studies import dr

SMALL = dict(scenarios=["straight", "gpsdr"], n_runs=2, n_steps=120,
             filters=["EKF", "EKF-oracle", "AEKF", "NN", "EKF-8", "DR-only"], seed=3)


def _numbers(res):
    return [{k: v for k, v in r.items() if k != "us_per_step"} for r in res.table]


@pytest.fixture(scope="module")
def small_result():
    return dr.run_study(**SMALL)


def test_same_seed_same_numbers(small_result):
    again = dr.run_study(**SMALL)
    assert _numbers(small_result) == _numbers(again)
    for name in small_result.errors:
        for f, e in small_result.errors[name]["filters"].items():
            np.testing.assert_array_equal(e, again.errors[name]["filters"][f])
    other = dr.run_study(**{**SMALL, "seed": 4})
    assert _numbers(small_result) != _numbers(other)


def test_jobs_do_not_change_numbers(small_result):
    par = dr.run_study(**{**SMALL, "jobs": 2})
    assert _numbers(small_result) == _numbers(par)


def test_table_contents(small_result):
    rows = {(r["scenario"], r["filter"]): r for r in small_result.table}
    assert set(rows) == {("straight", f) for f in ("EKF", "EKF-oracle", "AEKF", "NN")} | {
        ("gpsdr", f) for f in ("EKF", "EKF-8", "DR-only")}
    for r in small_result.table:
        assert r["runs"] == 2 and np.isfinite(r["final_median"]) and r["div"] >= 0
    assert rows[("straight", "EKF-oracle")]["div"] == 0
    e = small_result.errors["straight"]["filters"]["EKF"]
    assert e.shape == (2, 120, 2)


def test_common_random_numbers_across_filters():
    # EKF and the oracle EKF see identical data: identical before the noise switch
    res = dr.run_study(scenarios=["straight"], n_runs=2, n_steps=200, filters=["EKF", "EKF-oracle"], seed=1)
    f = res.errors["straight"]["filters"]
    np.testing.assert_array_equal(f["EKF"], f["EKF-oracle"])


def test_write_outputs_and_cli(small_result, tmp_path):
    paths = dr.write_outputs(small_result, str(tmp_path))
    names = {os.path.basename(p) for p in paths}
    assert {"dr_table.md", "dr_table.csv", "dr_straight_road.png", "gps_dr_with_outages.png"} <= names
    text = (tmp_path / "dr_table.md").read_text()
    assert "| EKF-oracle |" in text and "EKF-8" in text
    parser = argparse.ArgumentParser()
    dr.add_arguments(parser)
    args = parser.parse_args(["--runs", "1", "--scenarios", "straight", "--filters", "EKF",
                              "--out", str(tmp_path / "cli"), "--no-figures", "--no-progress", "--jobs", "1"])
    assert dr.run(args) == 0
    assert (tmp_path / "cli" / "dr_table.csv").exists()


def test_bad_arguments():
    with pytest.raises(ValueError, match="scenario"):
        dr.run_study(scenarios=["moon"], n_runs=1)
    with pytest.raises(ValueError, match="filters"):
        dr.run_study(scenarios=["straight"], n_runs=1, filters=["KF9"])


@pytest.mark.slow
def test_long_run_100k_steps_stays_finite():
    from filterwnn.navigation.dead_reckoning import DRModel, dr_residual
    from filterwnn.navigation.scenarios import SCENARIOS, simulate_scenario
    from filterwnn.navigation.neural_filter import NeuralFilter, make_training_set, paper_training_states

    sc = SCENARIOS["turns"](duration=10000.0, turns=((20.0, 9990.0, 3000.0),), speed_changes=())
    run = simulate_scenario(sc, rng=0)
    assert len(run.t) == 100_000
    m = DRModel()
    kf = m.ekf(x0=run.x0)
    for z in run.z_dr:
        kf.predict()
        kf.update(z, m.HJacobian, m.hx, residual=dr_residual)
    assert np.all(np.isfinite(kf.x)) and np.all(np.isfinite(kf.P))
    assert np.all(np.linalg.eigvalsh(kf.P) > 0)
    Xp, Z, X = make_training_set(paper_training_states(), m, rng=0)
    nf = NeuralFilter(m, rng=1).fit(Xp, Z, X)
    means = nf.reset(run.x0).batch_filter(run.z_dr)
    assert np.all(np.isfinite(means))


def test_real_drive_outages_never_nan():
    """The onavdata car drive: outages anywhere, including before the car first moves."""
    pytest.importorskip("onavdata", reason="the real drive needs the optional 'onavdata' package (data extra)")
    run = dr.load_car_drive()
    n = len(run.t)
    assert run.x_true.shape == (n, 6) and run.z_dr.shape == (n, 2)
    assert np.all(np.isfinite(run.x_true)) and np.all(np.isfinite(run.z_dr)) and np.all(np.isfinite(run.z_gps))
    assert np.all(run.z_dr[:, 1] >= 0) and np.any(run.z_dr[:, 1] == 0)  # stands still at times
    first_move = run.t[np.argmax(np.hypot(run.x_true[:, 1], run.x_true[:, 4]) > 1.0)]
    assert first_move > 30.0
    cut = dr.with_outage(run, 0.0, 30.0)
    assert np.all(cut.t[cut.gps_steps] >= 30.0) and len(cut.gps_steps) < len(run.gps_steps)
    res = dr.real_drive_outages(run, n_placements=3, length=30.0)
    assert res["starts"][0] == 0.0 and res["starts"][0] < first_move
    for name in ("DR-mech", "EKF", "EKF-8"):
        assert res[name].shape == (3,) and np.all(np.isfinite(res[name]))
    assert "| EKF-8 |" in dr.real_drive_table(res)


def test_real_drive_skips_cleanly_without_onavdata(monkeypatch):
    import importlib.resources

    def missing(name):
        raise ModuleNotFoundError(f"No module named {name!r}")

    monkeypatch.setattr(importlib.resources, "files", missing)
    with pytest.raises(ImportError, match="pip install"):
        dr.load_car_drive(dr.CAR_DRIVE)


CACHED = dict(scenarios=["straight", "gpsdr"], n_runs=2, n_steps=60, filters=["EKF", "NN", "EKF-8"], seed=5)


def test_jobs_and_cache_give_identical_tables(tmp_path, monkeypatch):
    one = dr.run_study(**CACHED, cache_dir=str(tmp_path))
    assert len(list(tmp_path.glob("*.npz"))) == 4  # one per (scenario, run)
    two = dr.run_study(**CACHED, jobs=2)
    assert _numbers(one) == _numbers(two)

    def must_not_run(*args, **kwargs):
        raise AssertionError("a cached run ran again")

    monkeypatch.setattr(dr._run, "run_one", must_not_run)  # where run_study's tasks look it up
    again = dr.run_study(**CACHED, cache_dir=str(tmp_path))
    assert dr.markdown_table(again) == dr.markdown_table(one)  # timings come from the cache too
    for name in one.errors:
        for f, e in one.errors[name]["filters"].items():
            np.testing.assert_array_equal(e, again.errors[name]["filters"][f])


def test_stream_keys_are_fixed_per_name(monkeypatch):
    for kind in ("dr", "gpsdr"):
        keys = [f.stream for f in dr.FILTER_TABLE if f.scenario == kind]
        assert len(keys) == len(set(keys)), kind
    sc = dr.SCENARIOS["straight"](duration=8.0)
    seed = np.random.SeedSequence(11).spawn(1)[0]
    before = dr.run_one(sc, ["EKF", "NN"], seed)["est"]
    # a new filter (placed first, with a new key) changes no other filter's numbers
    new = dr.DRFilter("NN-new", "dr", dr.FILTERS[("dr", "NN")].build, 99)
    monkeypatch.setitem(dr.FILTERS, ("dr", "NN-new"), new)  # the one lookup every module of the study reads
    after = dr.run_one(sc, ["NN-new", "EKF", "NN"], seed)["est"]
    for f in ("EKF", "NN"):
        np.testing.assert_array_equal(before[f], after[f])
    assert not np.array_equal(after["NN-new"], after["NN"])  # its own stream, not NN's


def test_cli_cache_and_backend_options(tmp_path):
    parser = argparse.ArgumentParser()
    dr.add_arguments(parser)
    args = parser.parse_args(["--runs", "1", "--scenarios", "straight", "--filters", "EKF", "--out", str(tmp_path),
                              "--no-figures", "--no-progress", "--jobs", "1", "--backend", "threading",
                              "--cache", str(tmp_path / "cache")])
    assert dr.run(args) == 0
    assert len(list((tmp_path / "cache").glob("*.npz"))) == 1


def test_drive_table_separates_the_causes():
    """Issue 23: the error at the outage start, its growth, the fixes rejected and the NIS per filter."""
    from filterwnn.navigation.drives import read_drive_csv, sample_drive_path

    run = read_drive_csv(sample_drive_path())
    res = dr.real_drive_outages(run, starts=[40.0, 100.0], filters=("DR-mech", "EKF-8"), use_gps_sigma=True,
                                grade="phone")
    np.testing.assert_array_equal(res["start_err"]["DR-mech"], 0.0)
    assert np.all(res["start_err"]["EKF-8"] >= 0) and res["start_err"]["EKF-8"].shape == (2,)
    ig = res["integrity"]["EKF-8"]
    assert ig["n_fixes"] == len(run.gps_steps) and ig["rejected_xy"].shape == (ig["n_rejected"], 2)
    table = dr.real_drive_table(res)
    assert "median at start | median growth | fixes rejected / down-weighted / re-acquired | mean NIS" in table
    row = next(line for line in table.splitlines() if line.startswith("| EKF-8 |"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    e, s = res["EKF-8"], res["start_err"]["EKF-8"]
    assert cells[6] == f"{np.median(s):.2f}" and cells[7] == f"{np.median(e - s):.2f}"
    assert cells[8].endswith(f"of {ig['n_fixes']}") and cells[9] == f"{ig['nis_mean']:.2f}"
    assert cells[10] == "-" and ig["gps_scale_mean"] is None  # the covariance scale is not estimated by default
    # the fixes' correlation is measured by default, and is at least 1
    assert cells[11] == f"{ig['gps_correlation_mean']:.2f}" and ig["gps_correlation_mean"] >= 1.0
    assert "mean fix correlation (1: white)" in table
    # the sample stands at its start and at a light: the stops' heading drift teaches the gyro rate bias
    assert cells[12] == (f"{ig['n_zero_rate']} / {ig['n_zero_rate_rejected']} / {ig['n_zero_rate_reacquired']} / "
                         f"{ig['n_zero_rate_held']}")
    assert ig["n_zero_rate"] >= 1 and ig["n_zero_rate_held"] == 0 and ig["n_zero_rate_turned"] == 0
    turned = dict(ig, n_zero_rate_rejected=3, n_zero_rate_turned=2)  # a drive with two turning crawls
    assert dr._real._integrity_cells(turned).endswith(
        f"| {ig['n_zero_rate']} / 3 (2 turned) / {ig['n_zero_rate_reacquired']} / {ig['n_zero_rate_held']}")
    assert ig["n_zero_rate_stepped"] == 0 and ig["n_calibration_error"] == 0 and ig["n_heading_jumps"] == 0
    assert ig["heading_jumps"] == []  # (step found, onset step, estimate, z) per step found
    jumped = dict(ig, n_heading_jumps=2)  # a fused heading that re-aligns while the car moves
    assert dr._real._integrity_cells(jumped).startswith(
        f"{ig['n_rejected']} / {ig['n_downweighted']} / {ig['n_reacquired']} of {ig['n_fixes']} (2 jumped) | ")
    stepped = dict(ig, n_zero_rate_stepped=4, n_calibration_error=17)  # a fused heading that re-aligns at stops
    assert dr._real._integrity_cells(stepped).endswith(
        f"| {ig['gps_correlation_mean']:.2f} (off at 17 fixes) | {ig['n_zero_rate']} / {ig['n_zero_rate_rejected']} / "
        f"{ig['n_zero_rate_reacquired']} / {ig['n_zero_rate_held']} (4 stepped)")
    held = run._replace(z_dr=np.where((run.z_dr[:, 1:] == 0.0) | (run.z_dr[:, 1:] / run.scenario.dt < 0.05),
                                      [[0.5, 0.0]], run.z_dr))  # a heading source that holds 0.5 rad standing
    ig_held = dr.real_drive_outages(held, starts=[100.0], filters=("EKF-8",), use_gps_sigma=True,
                                    grade="phone")["integrity"]["EKF-8"]
    assert ig_held["n_zero_rate"] == 0 and ig_held["n_zero_rate_held"] >= 1
    res = dr.real_drive_outages(run, starts=[40.0], filters=("EKF-8",), use_gps_sigma=True, grade="phone",
                                scale_window=30)
    ig = res["integrity"]["EKF-8"]
    row = next(line for line in dr.real_drive_table(res).splitlines() if line.startswith("| EKF-8 |"))
    assert row.strip("|").split("|")[10].strip() == f"{ig['gps_scale_mean']:.2f}" and ig["gps_scale_mean"] >= 1.0


def test_a_drive_shows_each_filters_progress_and_the_bar_changes_no_number(capsys, monkeypatch):
    """An hour of a 100 Hz log takes each filter minutes: ``progress=True`` shows a bar per filter over its steps
    (the pass with the fixes, then each outage again), named by the drive and the filter and cleared when it is
    done; None shows it on a terminal only. The numbers and the warnings are the same with it and without."""
    import sys
    import warnings

    from filterwnn.navigation.drives import read_drive_csv, sample_drive_path
    from filterwnn.studies.dr import _real

    run = read_drive_csv(sample_drive_path())
    kw = dict(starts=[40.0, 100.0], filters=("DR-mech", "EKF-8"), use_gps_sigma=True, grade="phone")
    counted, ends = [], _real._outage_ends

    def outage_ends(*a):  # the bar's count when the filter is done, and its total
        out = ends(*a)
        counted.append((a[-1].n, a[-1].total))
        return out

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        plain = dr.real_drive_outages(run, **kw)
        capsys.readouterr()
        monkeypatch.setattr(_real, "_outage_ends", outage_ends)
        shown = dr.real_drive_outages(run, progress=True, **kw)
        monkeypatch.undo()
    err = capsys.readouterr().err
    steps = len(run.t) + sum(int(k1) - int(k0) + 1 for k0, k1 in zip(*_real._outage_windows(
        run, plain["starts"], plain["length"])[:2]))
    assert counted == [(steps, steps)]  # one bar, for the filter (dead reckoning is instant), run to its end
    assert f"{run.scenario.name}: EKF-8" in err and "step/s" in err and "DR-mech" not in err
    assert err.rstrip(" ").endswith("\r")  # cleared (leave=False): the filter's warnings come on a clean line
    for key in ("DR-mech", "EKF-8"):
        np.testing.assert_array_equal(shown[key], plain[key])
    assert shown["warnings"] == plain["warnings"]
    for tty, shows in ((False, False), (True, True)):  # None: a bar on a terminal only, after a while
        monkeypatch.setattr(sys.stderr, "isatty", lambda tty=tty: tty, raising=False)
        with _real._steps_bar(None, run, "EKF-8", [], []) as bar:
            assert (not isinstance(bar, _real._NoBar)) == shows
            assert not shows or bar.delay == _real.PROGRESS_DELAY
    assert "EKF-8" not in capsys.readouterr().err  # (not shown before its delay)
    assert dr._cli._drive_running(argparse.Namespace(no_progress=True, jobs=2)) == dict(progress=False, n_jobs=2)
    assert dr._cli._drive_running(argparse.Namespace(jobs=-1)) == dict(progress=None, n_jobs=-1)


def test_a_long_drives_filters_run_side_by_side_with_the_same_numbers_and_warnings(monkeypatch):
    """``n_jobs``: the GPS/DR filters of a drive of at least ``PARALLEL_STEPS`` steps times filters run in worker
    processes, one each; the scores, the integrity counts and the warnings (the same lines, in the filters'
    order) are those of the run in this process. A shorter drive runs here."""
    import warnings

    from filterwnn.navigation.drives import read_drive_csv, sample_drive_path
    from filterwnn.studies.dr import _real

    run = read_drive_csv(sample_drive_path())
    kw = dict(starts=[40.0, 100.0], filters=("DR-mech", "EKF", "EKF-8"), use_gps_sigma=True, grade="phone",
              gps_sigma_floor=0.0)
    res = {}
    for jobs in (1, 2):
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            res[jobs] = dr.real_drive_outages(run, n_jobs=jobs, **kw)
        res[jobs]["seen"] = [(w.category, str(w.message)) for w in seen]
    for bad in (0, 1.5, True, "2"):
        with pytest.raises(ValueError, match="n_jobs must be an integer"):
            dr.real_drive_outages(run, n_jobs=bad, **kw)
        with pytest.raises(ValueError, match="n_jobs must be an integer"):
            next(dr.score_drives([(run, kw), (run, kw)], n_jobs=bad))
    assert len(run.t) * 2 < _real.PARALLEL_STEPS  # the sample stays in this process ...
    monkeypatch.setattr(_real, "PARALLEL_STEPS", 0)  # ... unless told otherwise
    ran = []
    monkeypatch.setattr(_real, "_merge_scored", lambda out, name, *a, merge=_real._merge_scored: (
        ran.append(name), merge(out, name, *a)))
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        side = dr.real_drive_outages(run, n_jobs=2, **kw)
    assert ran == ["EKF", "EKF-8"]  # both from the workers
    assert [(w.category, str(w.message)) for w in seen] == res[1]["seen"] and res[1]["seen"]
    assert side["warnings"] == res[1]["warnings"] == res[2]["warnings"]
    for name in kw["filters"]:
        np.testing.assert_array_equal(side[name], res[1][name])
        np.testing.assert_array_equal(side["start_err"][name], res[1]["start_err"][name])
        np.testing.assert_array_equal(side["end_xy"][name], res[1]["end_xy"][name])
    for name in ("EKF", "EKF-8"):
        a, b = side["integrity"][name], res[1]["integrity"][name]
        assert a.keys() == b.keys()
        for key in a:
            np.testing.assert_array_equal(np.asarray(a[key], dtype=object), np.asarray(b[key], dtype=object))


def test_several_drives_run_side_by_side_with_the_same_output(monkeypatch, capsys, tmp_path):
    """``filterwnn study dr --drive A --drive B --jobs 2``: drives whose steps times filters reach
    ``PARALLEL_STEPS`` in all run a drive to a worker; what the command prints (the tables, the warnings in
    their order) and saves is what it prints and saves in one process."""
    import shutil

    from filterwnn.cli import main
    from filterwnn.navigation.drives import sample_drive_path
    from filterwnn.studies.dr import _real

    other = tmp_path / "other.csv"
    shutil.copy(sample_drive_path(), other)
    monkeypatch.setattr(_real, "PARALLEL_STEPS", 0)
    from filterwnn.studies import runner

    ran = []
    monkeypatch.setattr(runner, "run_tasks", lambda tasks, fn, run=runner.run_tasks, **kw: (
        ran.append((fn.__name__, len(tasks), kw["n_jobs"])), run(tasks, fn, **kw))[1])
    shown = {}
    for jobs in ("1", "2"):
        out = tmp_path / f"out{jobs}"
        argv = ["study", "dr", "--drive", "sample", "--drive", str(other), "--filters", "DR-mech,EKF,EKF-8",
                "--outages", "4", "--out", str(out), "--no-figures", "--jobs", jobs]
        assert main(argv) == 0
        cap = capsys.readouterr()
        shown[jobs] = (cap.out.replace(str(out), "OUT"), cap.err,
                       sorted((p.name, p.read_text()) for p in out.glob("*.md")))
    assert ran == [("_drive_scored", 2, 2)]  # --jobs 2: the two drives, each in a worker; --jobs 1: here
    assert shown["2"] == shown["1"] and "warning" in shown["1"][1] and len(shown["1"][2]) == 2


def test_a_filter_that_fails_gives_its_warnings_first_here_and_in_a_worker(monkeypatch):
    """What a filter warned of before it failed comes before its error, whether it ran here (the folded
    warnings are given as the block raises) or in a worker (its warnings are given here, then its exception)."""
    import warnings

    from filterwnn._validation import NumericalError
    from filterwnn._warnings import folded_warnings
    from filterwnn.studies.dr import _real

    with pytest.warns(RuntimeWarning) as record, pytest.raises(NumericalError, match="step 9"):
        with folded_warnings("UKF-8"):
            for step in (3, 5):
                warnings.warn(f"GPSDRFilter is inconsistent at step {step}", RuntimeWarning)
            raise NumericalError("P is not positive definite at step 9")
    assert [str(w.message) for w in record] == ["UKF-8: GPSDRFilter is inconsistent at step 3 (and 1 more like it, "
                                                "at step 5)"]

    def failing(out, name, *args, **kw):
        with folded_warnings(name):
            warnings.warn("GPSDRFilter is inconsistent at step 3", RuntimeWarning)
            raise NumericalError("P is not positive definite at step 9")

    monkeypatch.setattr(_real, "_score_filter", failing)
    scores, told, failed = _real._scored(("UKF-8", None, None, True, {}, None, None))  # what a worker returns
    assert scores is None and isinstance(failed, NumericalError)
    out = {key: {} for key in _real._SCORED}
    with pytest.warns(RuntimeWarning, match="UKF-8: GPSDRFilter is inconsistent at step 3"), \
            pytest.raises(NumericalError, match="step 9"):
        _real._merge_scored(out, "UKF-8", scores, told, failed)
    assert out == {key: {} for key in _real._SCORED}


def test_a_new_scenario_is_one_entry_of_scenarios(monkeypatch):
    """A scenario is added in one place (an entry of ``SCENARIOS``) and the study runs it."""
    from filterwnn.navigation.scenarios import SCENARIOS, Scenario

    monkeypatch.setitem(SCENARIOS, "slow-turn", lambda **kw: Scenario(
        **{"name": "slow-turn", "title": "a slow turn", "figure": "dr_slow_turn", "factor": 5.0,
           "turns": ((2.0, 6.0, 5.0),), **kw}))
    res = dr.run_study(scenarios=["slow-turn"], n_runs=1, filters=["EKF"], n_steps=80, seed=3)
    assert "slow-turn" in res.scenarios and np.all(np.isfinite(res.errors["slow-turn"]["filters"]["EKF"]))


def test_a_filters_warnings_name_it_and_repeats_are_summarised():
    """A drive runs several filters: each warning it gives is re-issued with the filter's name, and the
    repeats of one kind (the same text up to the step) come in one line with their steps."""
    import warnings

    from filterwnn._warnings import folded_warnings as _warnings_named

    with pytest.warns(RuntimeWarning) as record:
        with _warnings_named("EKF-8"):
            for step in (5, 9, 12):
                warnings.warn(f"GPSDRFilter is inconsistent at step {step}: NIS {step}", RuntimeWarning)
            warnings.warn("GPSDRFilter: the heading bias state ran past 3 sigma at step 7 (x)", RuntimeWarning)
            warnings.warn("GPSDRFilter: the heading bias state ran past 3 sigma at step 8 (y)", RuntimeWarning)
    lines = [str(w.message) for w in record]
    assert lines == ["EKF-8: GPSDRFilter is inconsistent at step 5: NIS 5 (and 2 more like it, at steps 9, 12)",
                     "EKF-8: GPSDRFilter: the heading bias state ran past 3 sigma at step 7 (x) (and 1 more like it, "
                     "at step 8)"]
    with pytest.warns(RuntimeWarning) as record:  # with the drive's time column, each step named gets its time
        with _warnings_named("EKF-8", times=100.0 + 0.2 * np.arange(20)):
            for step in (5, 9, 12):
                warnings.warn(f"GPSDRFilter is inconsistent at step {step}: NIS {step}", RuntimeWarning)
            warnings.warn("GPSDRFilter: a stop since step 3 ended at step 19, and at step 20", RuntimeWarning)
    assert [str(w.message) for w in record] == [
        "EKF-8: GPSDRFilter is inconsistent at step 5 (t = 101 s): NIS 5 (and 2 more like it, at steps 9, 12 "
        "(t = 101.8, 102.4 s))",
        "EKF-8: GPSDRFilter: a stop since step 3 (t = 100.6 s) ended at step 19 (t = 103.8 s), and at step 20"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the outer filters still apply: -W error raises
        with pytest.raises(RuntimeWarning, match="^UKF-8: no step here$"):
            with _warnings_named("UKF-8"):
                warnings.warn("no step here", RuntimeWarning)
