"""Tests of filterwnn.studies.wnn: reproducibility across workers and backends, outputs."""

import csv
import re

import numpy as np
import pytest

from filterwnn.cli import main
from filterwnn.studies import wnn as study

TINY = dict(n_runs=2, n_epochs=2, pf_epochs=1, n_particles=3, trainers=["bp", "ekf", "spf"],
            paper_table=True, paper_runs=1, references=(), sweep_particles=(2,), sweep_runs=1, seed=7,
            tune_runs=1)


def _numbers(res):
    return [(r["table"], r["trainer"], r["run"], r["n_particles"], r["test_mse"], r["train_mse"],
             r["mean_ess"], tuple(r["curve_test"])) for r in res.runs]


@pytest.fixture(scope="module")
def serial():
    return study.run_study(**TINY, n_jobs=1)


def test_identical_numbers_for_one_and_two_jobs(serial):
    two = study.run_study(**TINY, n_jobs=2)
    np.testing.assert_equal(_numbers(two), _numbers(serial))  # NaN == NaN here; exact otherwise


def test_local_dask_cluster_gives_the_same_numbers(serial):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False) as cluster:
        with distributed.Client(cluster):
            res = study.run_study(**TINY, n_jobs=2, backend="dask")
    np.testing.assert_equal(_numbers(res), _numbers(serial))


def test_runs_redraw_data_and_table_rows(serial):
    ekf = [r for r in serial.runs if r["trainer"] == "ekf" and r["table"] == "working"]
    assert len(ekf) == 2 and ekf[0]["var_test"] != ekf[1]["var_test"]  # each run its own data
    assert [(r["table"], r["trainer"]) for r in serial.table] == [
        ("working", "bp"), ("working", "ekf"), ("working", "spf"),
        ("paper", "bp"), ("paper", "ekf"), ("paper", "spf"),
    ]
    row = serial.table[1]
    assert row["test_mse_q1"] <= row["test_mse_median"] <= row["test_mse_q3"]
    assert row["paper_mse"] == study.PAPER_TABLE1["ekf"][0]
    assert {s["n_particles"] for s in serial.sweep} == {2, 3}
    epochs = {r["trainer"]: r["epochs"] for r in serial.table if r["table"] == "working"}
    assert all(len(r["curve_test"]) == epochs[r["trainer"]] for r in serial.runs if r["table"] == "working")


def test_run_seeds_are_spawned_children():
    seeds = study.run_seeds(3, 4)
    ss = np.random.SeedSequence(3).spawn(4)
    assert seeds[2] == (ss[2].entropy, tuple(ss[2].spawn_key))


def test_reference_rows(tmp_path):
    r = study.fit_reference("MLPRegressor", study.run_seeds(0, 1)[0])
    assert r["test_mse"] < 0.1
    with pytest.raises(ValueError, match="reference"):
        study.fit_reference("SVR", study.run_seeds(0, 1)[0])


def test_cli_writes_table_csv_and_figures(tmp_path, capsys):
    out = tmp_path / "wnn"
    rc = main(["study", "wnn", "--runs", "1", "--epochs", "2", "--pf-epochs", "1", "--particles", "2",
               "--trainers", "ekf,supf", "--sweep-particles", "3", "--sweep-runs", "1", "--paper-runs", "1",
               "--out", str(out), "--no-progress"])
    assert rc == 0
    text = capsys.readouterr().out
    assert "reduced protocol" in text and "MLPRegressor" in text
    with open(out / "table1.csv") as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == list(study.TABLE_COLUMNS)
    assert {r["trainer"] for r in rows} == {"ekf", "supf", "MLPRegressor", "GaussianProcessRegressor"}
    for name in ("table1.md", "runs.csv", "fig3_particles_mse.png", "fig4_particles_time.png",
                 "fig5_supf_convergence.png"):
        assert (out / name).stat().st_size > 0


def test_cache_resumes_with_identical_numbers(tmp_path, serial):
    cache = tmp_path / "cache"
    small = dict(TINY, paper_table=False, sweep_particles=())
    first = study.run_study(**small, cache_dir=str(cache))
    n_tune = sum(len(study.candidates(t)) for t in TINY["trainers"])  # one tuning run each
    assert len(list(cache.glob("*.json"))) == 6 + n_tune
    again = study.run_study(**small, cache_dir=str(cache), cached_only=True)
    np.testing.assert_equal(_numbers(again), _numbers(first))
    working = [n for n in _numbers(serial) if n[0] == "working"]
    np.testing.assert_equal(_numbers(first), working)
    empty = study.run_study(**small, cache_dir=str(tmp_path / "none"), cached_only=True)
    assert empty.table == [] and empty.config["n_done"] == 0
    assert "Settings search incomplete" in study.markdown_table(empty)
    assert "Incomplete: 0 of 6" in study.markdown_table(study.run_study(
        **{**small, "tune_runs": 0}, cache_dir=str(tmp_path / "none"), cached_only=True))


# ---------------------------------------------------------------------------- settings search
def test_working_runs_use_the_settings_chosen_on_validation(serial):
    chosen = {r["trainer"]: r for r in serial.tuning if r["chosen"]}
    assert set(chosen) == {"bp", "ekf", "spf"}
    assert sum(r["trainer"] == "ekf" for r in serial.tuning) == len(study.TUNING_GRID["ekf"])
    for row in serial.table:
        if row["table"] != "working":
            continue
        c = chosen[row["trainer"]]
        assert row["epochs"] == c["best_epoch"]
        for key, name in (("process_noise", "Q"), ("initial_covariance", "P0"), ("learning_rate", "lr")):
            if key in c["params"]:
                assert f"{name}={c['params'][key]:g}," in row["settings"] + ","
    assert "validation split" in study.markdown_table(serial)
    assert "**yes**" in study.tuning_table(serial)


def test_tuning_never_reads_the_test_rows(monkeypatch):
    real = study.runs.make_siso_benchmark

    def poisoned(rng=None):
        X, y, X_test, y_test = real(rng=rng)
        return X, y, np.full_like(X_test, np.nan), np.full_like(y_test, np.nan)

    monkeypatch.setattr(study.runs, "make_siso_benchmark", poisoned)
    r = study.tune_run("ekf", study.tune_seeds(0, 1)[0], 3, params={"process_noise": 1e-3})
    assert r["status"] == "ok" and np.all(np.isfinite(r["curve_val"])) and len(r["curve_val"]) == 3
    assert "test_mse" not in r


def test_tune_seeds_are_independent_of_run_seeds():
    runs = {tuple(k) for _, k in study.run_seeds(5, 50)}
    tune = {tuple(k) for _, k in study.tune_seeds(5, 5)}
    assert not runs & tune


def test_select_settings_prefers_the_lowest_median_and_skips_failures():
    def res(c, curve, status="ok"):
        return {"trainer": "ukf", "candidate": c, "params": {"process_noise": 10.0 ** -c}, "curve_val": curve,
                "status": status}

    inf = float("inf")
    rs = [res(0, [1.0, 0.5, 0.6]), res(0, [1.0, 0.7, 0.4]),
          res(1, [0.1, inf, inf], "failed: P not positive definite"), res(1, [0.2, inf, inf], "failed: x")]
    chosen, rows = study.select_settings(rs)
    # median curve [1, 0.6, 0.5]; smoothed (running median of 5): 0.6 everywhere; the raw minimum breaks the tie
    assert chosen == {"params": {"process_noise": 1.0}, "epochs": 3, "val_mse": 0.6}
    assert [r["n_failed"] for r in rows] == [0, 2] and rows[0]["chosen"] and not rows[1]["chosen"]


def test_epoch_criterion_is_the_minimum_of_the_smoothed_curve():
    curve = [1.0, 0.9, 0.2, 0.9, 0.8, 0.5, 0.5, 0.5, 0.6, 0.7]  # one lucky dip at epoch 3
    chosen, _ = study.select_settings([{"trainer": "ekf", "candidate": 0, "params": {}, "curve_val": curve,
                                        "status": "ok"}])
    assert chosen["epochs"] == 6 and chosen["val_mse"] == 0.5  # not the dip: the smoothed minimum (first of 6-8)


def test_rows_name_the_algorithm_and_fixed_rows_are_not_searched():
    assert study.row_label("gsf-ekf", 20) == "Gaussian-sum filter of 20 EKFs (tempering 0.01)"
    assert study.row_label("ekf-ensemble", 20) == "20 independent EKFs, averaged"
    assert study.row_label("upf", 20) == "UPF (textbook)"
    assert study.candidates("ibis-mala") == [{}] and study.candidates("ekf-ensemble") == [{}]
    assert len(study.candidates("gsf-ukf")) == len(study.Q_FACTORS) + 1  # widened upward (protocol 3)
    assert len(study.candidates("upf")) == len(study.Q_FACTORS)
    for key, (trainer, fixed, _, _) in study.ROWS.items():
        assert trainer in study.TRAINERS, key
    for col in ("algorithm", "distinct_particles", "coverage90"):
        assert col in study.TABLE_COLUMNS


def test_new_rows_report_coverage_and_distinct_particles():
    res = study.run_study(n_runs=1, n_epochs=2, pf_epochs=1, n_particles=3, seed=3, paper_table=False,
                          references=("GaussianProcessRegressor",), sweep_particles=(), tune_runs=1,
                          trainers=["gsf-ekf", "ekf-ensemble", "ibis-mala"])
    rows = {r["trainer"]: r for r in res.table}
    ens, gsf = rows["ekf-ensemble"], rows["gsf-ekf"]
    assert ens["epochs"] == gsf["epochs"]  # the ensemble copies the Gaussian sum's settings and epochs
    assert "tempering=0.01" in gsf["settings"] and "move=mala" in rows["ibis-mala"]["settings"]
    assert np.isnan(gsf["distinct_particles"]) and rows["ibis-mala"]["distinct_particles"] >= 1
    for r in res.table:  # every row here has a predictive distribution, the GP included
        assert 0 <= r["coverage90"] <= 1, r["trainer"]


def test_particle_candidates_centre_on_their_proposal_filter():
    got = study.candidates("epf", {"ekf": {"process_noise": 1e-3, "initial_covariance": 0.1}})
    assert [c["process_noise"] for c in got] == [1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1]  # x 0.001 added
    assert {c["initial_covariance"] for c in got} == {0.1}
    auto = study.candidates("supf")  # parent not searched: its AUTO_SETTINGS
    assert auto[2]["process_noise"] == study.AUTO_SETTINGS[("sukf", "scaled")]["Q"]


def test_no_search_uses_auto_settings_and_all_epochs():
    res = study.run_study(**{**TINY, "paper_table": False, "sweep_particles": (), "tune_runs": 0})
    assert res.tuning == [] and all(r["epochs"] == (2 if r["trainer"] != "spf" else 1) for r in res.table)


def test_renamed_rows_fail_naming_the_row_that_runs_what_they_ran():
    for old, new in (("upf+mala", "ibis-mala"), ("supf+mala", "ibis-mala"), ("upf+hmc", "ibis-hmc")):
        with pytest.raises(ValueError, match=rf"row '{re.escape(old)}' is now '{new}'.*IBIS"):
            study.run_study(**{**TINY, "trainers": [old]})
    assert study.ROWS["ibis-mala"].trainer == "spf" and study.ROWS["ibis-mala"].fixed == {"move": "mala"}
    assert "ibis-mala" in study.ALL_TRAINERS and "ibis-hmc" not in study.ALL_TRAINERS


def test_cli_runs_opt_in_rows_by_name_and_leaves_them_out_by_default():
    """ibis-hmc and smc-noise-10x10 are opt-in: `--trainers` accepts them, its default omits them."""
    import argparse

    from filterwnn.studies.wnn.cli import add_arguments

    parser = argparse.ArgumentParser()
    add_arguments(parser)
    assert parser.parse_args(["--trainers", "smc-noise-10x10,ibis-hmc"]).trainers == ["smc-noise-10x10", "ibis-hmc"]
    default = parser.parse_args([]).trainers
    assert "smc-noise" in default and "smc-noise-10x10" not in default and "ibis-hmc" not in default
    with pytest.raises(SystemExit):
        parser.parse_args(["--trainers", "smc-noise-6x10"])
