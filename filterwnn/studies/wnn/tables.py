"""The WNN study's tables: ``table1.md``, ``tuning.md`` and the CSV files."""

from __future__ import annotations

import csv
import os

from .. import runner
from .rows import TABLE_COLUMNS, VALIDATION_FRACTION

__all__ = [
    "RUNS_COLUMNS",
    "TUNING_COLUMNS",
    "is_reduced",
    "markdown_table",
    "tuning_table",
    "write_outputs",
]

_q = runner.quantile


def is_reduced(config):
    """True when the protocol is smaller than the paper's (50 runs, 200 epochs, 50 particles)."""
    return (
        config["n_runs"] < 50 or config["n_epochs"] < 200 or config["pf_epochs"] < 200 or config["n_particles"] < 50
    )


def _fmt(v, digits=3):
    return runner.fmt(v, digits)


def _run_variances(runs):
    """var(y_test) once per run (run ``i`` has the same data in every table; the sweep's runs too)."""
    return list({r["run"]: r["var_test"] for r in runs if r["table"] != "tuning"}.values())


def markdown_table(result):
    """The study's tables as Markdown text (working settings, paper settings, references)."""
    c = result.config
    lines = [
        "# WNN study (Niu, Wu and Li, Table 1)",
        "",
        f"Protocol: {c['n_runs']} runs (SeedSequence({c['seed']}).spawn), {c['n_epochs']} epochs "
        f"(particle filters {c['pf_epochs']}), {c['n_particles']} particles, 5-20-1 Morlet WNN, "
        "SISO plant of eq. (12), 100 train / 100 test rows. Each run re-draws its data from its own "
        "seed, so the test-set variance differs between runs (median var(y_test) over the "
        f"{len(_run_variances(result.runs))} runs {_fmt(_q(_run_variances(result.runs), 0.5))}; predicting the "
        "mean scores that).",
    ]
    if c.get("n_done", 0) < c.get("n_tasks", 0):
        lines += ["", f"**Incomplete: {c['n_done']} of {c['n_tasks']} fits finished** (the rows say how many "
                  "runs each has)."]
    if is_reduced(c):
        lines += ["", "**This is a reduced protocol** (the paper: 50 runs, 200 epochs, 50 particles); "
                  "scale it with --runs, --epochs, --pf-epochs, --particles."]
    lines += ["", f"Timings: median seconds per fit with {c['n_jobs']} joblib worker(s) ({c['backend']}), "
              "one BLAS thread each; parallel workers contend for memory bandwidth."]
    head = ("| algorithm | settings | epochs | test MSE median | q1 | q3 | fit time (s) | mean ESS | distinct particles "
            "| distinct ancestors | coverage 50 / 90 / 95 % | NLPD | runs | paper MSE | paper time (s) |")
    sep = "|---" * 15 + "|"
    if c.get("tune_runs"):
        working_title = (f"Working settings (scaled start; Q, P0 or learning rate and the epochs chosen on a "
                         f"validation split of {c['tune_runs']} separate tuning run(s), never on test data)")
    else:
        working_title = "Working settings (scaled start, AUTO_SETTINGS, no search)"
    if c.get("tune_runs") and not c.get("tuning_complete", True):
        lines += ["", "**Settings search incomplete**: trainers whose search has not finished have no row."]
    for table, title in (
        ("working", working_title),
        ("paper", "Paper's settings (U[0,1] start, Q = 1, P0 = 1, R = 0.1, textbook weights, resampling every step)"),
        ("reference", "References on the same runs"),
    ):
        rows = [r for r in result.table if r["table"] == table]
        if not rows:
            continue
        lines += ["", f"## {title}", "", head, sep]
        for r in rows:
            failed = f" ({r['n_failed']} failed)" if r["n_failed"] else ""
            lines.append(
                f"| {r['algorithm']} | {r['settings'].split(': ', 1)[-1]} | {r['epochs'] or '-'} | "
                f"{_fmt(r['test_mse_median'])}{failed} | "
                f"{_fmt(r['test_mse_q1'])} | {_fmt(r['test_mse_q3'])} | {_fmt(r['fit_time_median'])} | "
                f"{_fmt(r['mean_ess'])} | {_fmt(r['distinct_particles'])} | {_fmt(r['distinct_ancestors'])} | "
                f"{_fmt(r['coverage50'], 2)} / {_fmt(r['coverage90'], 2)} / {_fmt(r['coverage95'], 2)} | "
                f"{_fmt(r['nlpd'])} | {r['n_runs']} | "
                f"{_fmt(r['paper_mse'], 4)} | {_fmt(r['paper_time'])} |"
            )
    for t, cal in (c.get("calibration") or {}).items():
        lines += ["", f"Recalibrated row `{t}`: its Gaussian's standard deviation multiplied by "
                  f"{_fmt(cal['factor'], 4)}, the split-conformal factor at {cal['level']:.0%} from "
                  f"{cal['n_residuals']} standardized residuals of the tuning runs' validation split "
                  "(runs.csv: the scores before recalibration as `*_base`)."]
    if result.sweep:
        lines += ["", "## Particle sweep (Figs. 3-4)", "", "| trainer | particles | test MSE median | fit time (s) | runs |",
                  "|---|---|---|---|---|"]
        for s in result.sweep:
            lines.append(f"| {s['trainer']} | {s['n_particles']} | {_fmt(s['test_mse_median'])} | "
                         f"{_fmt(s['fit_time_median'])} | {s['n_runs']} |")
    return "\n".join(lines) + "\n"


def _params_text(params):
    names = {"process_noise": "Q", "initial_covariance": "P0", "learning_rate": "lr"}
    return ", ".join(f"{names.get(k, k)}={v:g}" for k, v in params.items())


def tuning_table(result):
    """The settings search as Markdown: every candidate, its best epoch and validation MSE."""
    c = result.config
    lines = [
        "# Settings search on a validation split",
        "",
        f"Each candidate trained on the first {1 - c.get('validation_fraction', VALIDATION_FRACTION):.0%} of the "
        f"training rows of {c.get('tune_runs', 0)} tuning run(s) (seeds independent of the table's runs) and was "
        "scored on the remaining rows after every epoch; the row marked chosen (lowest median validation MSE "
        "smoothed by a running median of 5 epochs, "
        "at its best epoch) is what the table's runs use. Test rows are never used.",
        "",
        "| trainer | candidate | best epoch | validation MSE (smoothed median) | at the last epoch (median) | runs | failed | chosen |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in result.tuning:
        lines.append(f"| {r['trainer']} | {_params_text(r['params'])} | {r['best_epoch']} | {_fmt(r['val_mse'])} | "
                     f"{_fmt(r['val_mse_last'])} | {r['n_runs']} | {r['n_failed']} | {'**yes**' if r['chosen'] else ''} |")
    return "\n".join(lines) + "\n"


#: Columns of ``runs.csv`` (one line per table, trainer and run).
RUNS_COLUMNS = ("table", "trainer", "run", "n_particles", "epochs", "test_mse", "train_mse", "fit_time", "mean_ess",
                "distinct", "ancestors", "coverage50", "coverage90", "coverage95", "nlpd", "var_test", "status", "settings",
                "noise_scale2", "noise_df", "recal_factor", "coverage50_base", "coverage90_base", "coverage95_base",
                "nlpd_base")
#: Columns of ``tuning.csv`` (one line per trainer and candidate).
TUNING_COLUMNS = ("trainer", "candidate", "settings", "best_epoch", "val_mse", "val_mse_last", "n_runs", "n_failed",
                  "chosen")


def _write_text(path, text, paths):
    with open(path, "w") as f:
        f.write(text)
    paths.append(path)


def _write_csv(path, fields, rows, paths):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(fields), extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)
    paths.append(path)


def write_outputs(result, out, figures=True):
    """Write ``table1.md``, ``table1.csv``, ``runs.csv``, the search's ``tuning.md`` and
    ``tuning.csv`` (when it ran), the recalibrated rows' ``calibration.csv`` (when there are
    any) and the figures (:func:`write_figures`)
    into ``out``.

    Returns
    -------
    list of str
        The paths written.
    """
    os.makedirs(out, exist_ok=True)
    paths = []
    _write_text(os.path.join(out, "table1.md"), markdown_table(result), paths)
    _write_csv(os.path.join(out, "table1.csv"), TABLE_COLUMNS, result.table, paths)
    _write_csv(os.path.join(out, "runs.csv"), RUNS_COLUMNS, result.runs, paths)
    if result.tuning:
        _write_text(os.path.join(out, "tuning.md"), tuning_table(result), paths)
        rows = [dict(r, settings=_params_text(r["params"])) for r in result.tuning]
        _write_csv(os.path.join(out, "tuning.csv"), TUNING_COLUMNS, rows, paths)
    calibration = result.config.get("calibration") or {}
    if calibration:
        _write_csv(os.path.join(out, "calibration.csv"), ("trainer", "factor", "level", "n_residuals", "val_mse_median"),
                   [dict(v, trainer=k) for k, v in calibration.items()], paths)
    if figures:
        from .figures import write_figures

        paths += write_figures(result, out)
    return paths
