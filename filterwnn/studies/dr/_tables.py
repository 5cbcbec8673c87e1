"""The DR study's outputs: Markdown and CSV tables, and the figures named in words.

:func:`write_outputs` writes ``dr_table.md``, ``dr_table.csv`` and one figure per
scenario (:func:`scenario_figure` names it from its settings), and each real drive's
table and figure (:func:`write_real_drive`); the drawing itself is
:mod:`filterwnn.studies.plotting`'s.
"""

from __future__ import annotations

import csv
import os

from .. import runner
from ._filters import ORACLE, scenario_kind
from ._real import real_drive_table
from ._run import DIV_FACTOR

_DR_COLS = [
    ("filter", "filter"), ("rmse_e_before", "RMSE e <150"), ("rmse_n_before", "RMSE n <150"),
    ("rmse_e_after", "RMSE e >=150"), ("rmse_n_after", "RMSE n >=150"),
    ("final_median", "median err@end"), ("final_p95", "p95 err@end"),
    ("vel_rmse_after", "vel RMSE >=150 [m/s]"), ("div", "div"), ("us_per_step", "us/step"),
]
_GPS_COLS = [
    ("filter", "filter"), ("rmse_gps", "horiz RMSE GPS on"), ("rmse_outage", "horiz RMSE in outages"),
    ("outage_end_median", "median err at outage ends"), ("final_median", "median err@end"),
    ("div", "div"), ("us_per_step", "us/step"),
]


def markdown_table(result):
    """The study's tables as Markdown (one per scenario)."""
    lines = []
    for name, sc in result.scenarios.items():
        rows = [r for r in result.table if r["scenario"] == name]
        cols = _GPS_COLS if sc.gps_rate > 0 else _DR_COLS
        head = f"### {name}: "
        if sc.gps_rate > 0:
            head += (f"GPS {sc.gps_rate:g} Hz ({sc.sigma_gps:g} m), outages {list(sc.outages)}, "
                     f"odometer scale {sc.odometer_scale:g}, heading bias {sc.heading_bias:g} deg")
        else:
            head += f"noise x{sc.factor:g} at {sc.t_switch:g} s" + (
                f", {sc.outlier_prob:.0%} heading outliers of {sc.outlier_deg:g} deg" if sc.outlier_prob else "")
        n = rows[0]["runs"] if rows else 0
        oracle = ORACLE[scenario_kind(sc)]
        lines += [head + f" ({n} runs, positions in m; div: error > {DIV_FACTOR:g}x {oracle} RMS envelope)", ""]
        lines.append("| " + " | ".join(c[1] for c in cols) + " |")
        lines.append("|" + "---|" * len(cols))
        for r in rows:
            lines.append("| " + " | ".join(runner.fmt(r.get(c[0], ""), 2, fixed=True, missing="nan") for c in cols) + " |")
        lines.append("")
    return "\n".join(lines)


def write_outputs(result, out_dir, figures=True, real_drives=()):
    """Write the tables and figures to ``out_dir``; returns the paths.

    ``result`` (a :class:`StudyResult`, or ``None`` for real drives only) gives
    ``dr_table.md``, ``dr_table.csv`` and a figure per scenario, named in words by
    :func:`scenario_figure` (``dr_straight_road.png``, ``gps_dr_with_outages.png``); each of ``real_drives``
    (results of :func:`real_drive_outages`) gives ``real_drive_<name>_outage_errors.md``
    and ``real_drive_<name>_track_and_outage_end_errors.png`` (:func:`write_real_drive`).
    """
    os.makedirs(out_dir, exist_ok=True)
    paths = []
    for res in real_drives:
        paths += write_real_drive(res, out_dir, figures)
    if result is None:
        return paths
    md = os.path.join(out_dir, "dr_table.md")
    with open(md, "w") as fh:
        s = result.settings
        fh.write(f"# Dead-reckoning study (seed {s['seed']}, {s['n_runs']} runs per scenario)\n\n")
        fh.write(markdown_table(result))
    paths.append(md)
    keys = []
    for r in result.table:
        keys += [k for k in r if k not in keys]
    csv_path = os.path.join(out_dir, "dr_table.csv")
    with open(csv_path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        for r in result.table:
            w.writerow(r)
    paths.append(csv_path)
    if figures:
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        from .. import plotting

        for name, sc in result.scenarios.items():
            e = result.errors[name]
            title, fname = scenario_figure(name, sc)
            if sc.gps_rate > 0:
                fig = plotting.dr_outage_errors(e["t"], e["filters"], outages=sc.outages, title=title)
            else:
                fig = plotting.dr_position_errors(e["t"], e["filters"], t_switch=sc.t_switch, title=title)
            p = os.path.join(out_dir, fname)
            fig.savefig(p, dpi=110, bbox_inches="tight")
            paths.append(p)
            plt.close(fig)
    return paths


_COUNT_WORDS = ("no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine")


def scenario_figure(name, sc):
    """``(title, file name)`` of a scenario's figure, in words, from its settings.

    >>> from filterwnn.navigation.scenarios import SCENARIOS
    >>> scenario_figure("straight", SCENARIOS["straight"]())
    ('straight road, sensor noise x20 from 150 s', 'dr_straight_road.png')
    >>> scenario_figure("gpsdr", SCENARIOS["gpsdr"]())[1]
    'gps_dr_with_outages.png'
    """
    words, stem = sc.title or str(name), sc.figure or "dr_" + _slug(name)
    if sc.gps_rate > 0:
        k = len(sc.outages)
        if k:
            words += f" with {_COUNT_WORDS[k] if k < len(_COUNT_WORDS) else k} GPS outage{'s' if k > 1 else ''}"
            stem += "_with_outages"
        extra = []
        if sc.odometer_scale != 1:
            extra.append(f"odometer scale {sc.odometer_scale:g}")
        if sc.heading_bias:
            extra.append(f"heading bias {sc.heading_bias:g} deg")
        if extra:
            words += " (" + ", ".join(extra) + ")"
    else:
        if sc.outlier_prob:
            words += (f" ({sc.outlier_prob:.0%} of {sc.outlier_deg:g} deg)" if name == "outliers"
                      else f", {sc.outlier_prob:.0%} heading outliers of {sc.outlier_deg:g} deg")
        if sc.factor != 1:
            words += f", sensor noise x{sc.factor:g} from {sc.t_switch:g} s"
    return words, stem + ".png"


def _slug(text):
    return "".join(c if c.isalnum() else "_" for c in str(text)).strip("_").lower()


def write_real_drive(res, out_dir, figures=True):
    """Write one real drive's table (``real_drive_<name>.md``) and figure; returns the paths."""
    os.makedirs(out_dir, exist_ok=True)
    slug = _slug(res["name"])
    p = os.path.join(out_dir, f"real_drive_{slug}_outage_errors.md")
    with open(p, "w") as fh:
        fh.write(real_drive_table(res))
    paths = [p]
    if figures:
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        from .. import plotting

        fig = plotting.dr_real_drive(res)
        p = os.path.join(out_dir, f"real_drive_{slug}_track_and_outage_end_errors.png")
        fig.savefig(p, dpi=110, bbox_inches="tight")
        plt.close(fig)
        paths.append(p)
    return paths
