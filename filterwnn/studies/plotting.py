"""Figures drawn from study results (the studies themselves never plot).

Every function takes a result object or plain arrays, draws with matplotlib's
object-oriented API on a new figure (or a given ``ax``), and returns the figure; saving
is the caller's business. Import matplotlib lazily so the package imports headless.
"""

from __future__ import annotations

import numpy as np

__all__ = []


def _figure(ax=None, figsize=(6, 4)):
    """``(fig, ax)``: a new figure, or the given ``ax`` and its figure."""
    if ax is not None:
        return ax.figure, ax
    import matplotlib.pyplot as plt

    return plt.subplots(figsize=figsize)

# --- WNN study ---

__all__ += ["wnn_particle_sweep", "wnn_convergence"]


def wnn_particle_sweep(sweep, metric="test_mse_median", ax=None):
    """The first paper's Figs. 3-4: test MSE or training time against particles.

    Parameters
    ----------
    sweep : list of dict
        ``StudyResult.sweep`` rows of :func:`filterwnn.studies.wnn.run_study`
        (``trainer``, ``n_particles``, ``test_mse_median``, ``fit_time_median``).
    metric : {"test_mse_median", "fit_time_median"}
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = _figure(ax, figsize=(7.2, 4))
    counts = sorted({r["n_particles"] for r in sweep})
    for i, trainer in enumerate(dict.fromkeys(r["trainer"] for r in sweep)):
        rows = sorted((r for r in sweep if r["trainer"] == trainer), key=lambda r: r["n_particles"])
        ax.plot([r["n_particles"] for r in rows], [r[metric] for r in rows], "-",
                marker=_WNN_MARKERS[i % len(_WNN_MARKERS)], label=trainer.upper())
    ax.set_xlabel("particles")
    ax.set_xticks(counts)
    ax.set_xticklabels([str(c) for c in counts])
    if metric == "test_mse_median":
        ax.set_ylabel("test MSE (median over runs)")
        _plain_log_ticks(ax)
        ax.set_title("Test MSE of the particle-filter trainers (cf. paper Fig. 3)")
    else:
        ax.set_ylabel("training time per run (s, median)")
        ax.set_title("Training time of the particle-filter trainers (cf. paper Fig. 4)")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="center left", bbox_to_anchor=(1.02, 0.5), frameon=False)
    fig.tight_layout()
    return fig


_WNN_PANELS = (
    ("single filters and back-propagation", lambda t: t in ("bp", "ekf", "ukf", "sukf")),
    ("Gaussian sums and the EKF ensemble", lambda t: t.startswith("gsf") or t.endswith("ensemble")),
    ("particle methods", lambda t: True),
)
_WNN_MARKERS = ("o", "s", "^", "v", "D", "P", "X")


def _median_curve(sel, key):
    curves = [r[key] for r in sel if r.get(key)]
    if not curves:
        return None
    n = min(len(c) for c in curves)
    return np.median(np.array([c[:n] for c in curves]), axis=0)


def _draw_convergence(ax, runs, trainers, legend_below=True):
    from matplotlib.ticker import MaxNLocator

    tests = {t: _median_curve([r for r in runs if r["trainer"] == t], "curve_test") for t in trainers}
    groups = coincide_groups({t: c for t, c in tests.items() if c is not None})
    twin = {g[0]: g[1:] for g in groups if len(g) > 1}
    hidden = {t for g in groups for t in g[1:]}
    for i, trainer in enumerate(trainers):
        if trainer in hidden:  # drawn once, under the first of its group
            continue
        sel = [r for r in runs if r["trainer"] == trainer]
        color, marker = f"C{i % 10}", _WNN_MARKERS[i % len(_WNN_MARKERS)]
        name = ", ".join(t.upper() for t in [trainer] + twin.get(trainer, []))
        extra = " (coincide)" if trainer in twin else ""
        for med, style, lw, what in ((tests[trainer], "-", 1.8, "test"),
                                     (_median_curve(sel, "curve_train"), ":", 1.2, "train")):
            if med is None:
                continue
            n = len(med)
            ax.plot(np.arange(1, n + 1), med, style, color=color, lw=lw,
                    marker=marker if n <= 5 or what == "test" else None,
                    markevery=max(1, n // 8), ms=5, label=f"{name} {what}{extra if what == 'test' else ''}")
    longest = max((len(c) for c in tests.values() if c is not None), default=1)
    if longest <= 10:
        ax.set_xticks(range(1, longest + 1))
        ax.set_xlim(0.5, longest + 0.5)
    else:
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    _plain_log_ticks(ax)
    lo, hi = ax.get_ylim()
    if hi > 300 * lo:  # more than two and a half decades: one label per decade
        from matplotlib.ticker import LogLocator

        ax.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0,)))
    ax.set_xlabel("epoch")
    ax.grid(True, alpha=0.3)
    if legend_below:
        ax.legend(fontsize="x-small", ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.16), frameon=False)


def wnn_convergence(runs, ax=None):
    """The first paper's Fig. 5: test (solid) and training (dotted) MSE against epochs, median over runs.

    Without ``ax``, one panel per family (single filters and BP; Gaussian sums and the EKF
    ensemble; particle methods), each with a handful of series and its legend below it;
    with ``ax``, every trainer on that one axis.

    Parameters
    ----------
    runs : list of dict
        ``StudyResult.runs`` entries with ``trainer``, ``curve_train`` and ``curve_test``.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    trainers = list(dict.fromkeys(r["trainer"] for r in runs))
    if ax is not None:
        fig, ax = _figure(ax)
        _draw_convergence(ax, runs, trainers, legend_below=False)
        ax.legend(fontsize="x-small", ncol=2)
        ax.set_ylabel("MSE (median over runs)")
        return fig
    groups, left = [], list(trainers)
    for title, member in _WNN_PANELS:
        chosen = [t for t in left if member(t)]
        left = [t for t in left if t not in chosen]
        if chosen:
            groups.append((title, chosen))
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(groups), figsize=(4.6 * len(groups), 4.6), sharey=True, squeeze=False)
    for axis, (title, chosen) in zip(axes[0], groups):
        _draw_convergence(axis, runs, chosen)
        axis.set_title(title, fontsize="medium")
    axes[0][0].set_ylabel("MSE (median over runs)")
    fig.suptitle("Convergence of WNN training (cf. the paper's Fig. 5): test solid, training dotted")
    fig.tight_layout()
    return fig


# --- dead-reckoning study ---


__all__ += ["dr_position_errors", "dr_outage_errors", "coincide_groups", "split_outliers"]

_DR_PAPER_PAIR = ("EKF", "NN", "EKF-oracle")
_DR_STYLES = ("-", "--", "-.", ":")
_DR_MARKERS = ("o", "s", "^", "v", "D", "P", "X", "*")


def _dr_colors(names):
    import matplotlib.pyplot as plt

    cyc = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    return {n: cyc[i % len(cyc)] for i, n in enumerate(names)}


def coincide_groups(curves, rtol=0.02):
    """Group series that agree to within the line width.

    Parameters
    ----------
    curves : dict of {str: ndarray of shape (n_steps,)}
        Positive series (RMS errors), in the order to keep.
    rtol : float
        Largest relative difference, ``|a - b| / max(|a|, |b|)`` at every step, for two series
        to count as one line (2 %: about the width of a line on a log axis that spans two
        decades of a 3-inch panel).

    Returns
    -------
    list of list of str
        Each group in order of its first member; a series joins the first group whose first
        member it matches everywhere (non-finite steps must be non-finite in both).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(1.0, 2.0, 5)
    >>> coincide_groups({"EKF": t, "UKF": t * 1.001, "NN": 3 * t})
    [['EKF', 'UKF'], ['NN']]
    """
    if not (np.isfinite(rtol) and rtol >= 0):
        raise ValueError(f"rtol must be a finite number >= 0, got {rtol!r}")
    groups = []
    for name, c in curves.items():
        c = np.asarray(c, dtype=float)
        for g in groups:
            r = np.asarray(curves[g[0]], dtype=float)
            if r.shape != c.shape:
                continue
            fin = np.isfinite(r) & np.isfinite(c)
            if not np.array_equal(fin, np.isfinite(r) | np.isfinite(c)):
                continue
            scale = np.maximum(np.abs(r[fin]), np.abs(c[fin]))
            diff = np.abs(r[fin] - c[fin])
            if np.all(diff <= rtol * np.where(scale > 0, scale, 1.0)):
                g.append(name)
                break
        else:
            groups.append([name])
    return groups


def _group_label(g):
    return g[0] if len(g) == 1 else f"{', '.join(g)} (coincide)"


def _plain_log_ticks(ax):
    """Log y axis with plain numbers (0.1, 1, 10) instead of powers of ten."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    ax.set_yscale("log")
    ax.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_formatter(NullFormatter())


def _log_limits(t, curves):
    """y limits of a log panel: the curves after their first 2 % of steps, with a margin, at most
    three decades deep (a single run's |error| dips towards zero where the signed error crosses it)."""
    k = max(len(t) // 50, 1)
    vals = np.concatenate([np.asarray(c, dtype=float)[k:] for c in curves.values()])
    vals = vals[np.isfinite(vals) & (vals > 0)]
    if vals.size == 0:
        return 1e-2, 1.0
    hi = vals.max() * 1.6
    return max(vals.min() / 1.6, hi * 1e-3), hi


def _line_rtol(ax, lo, hi, lw=1.6):
    """Relative difference that a line of width ``lw`` (points) covers on a log axis ``lo..hi``."""
    fig = ax.figure
    height_pt = ax.get_position().height * fig.get_figheight() * 72.0
    return 10 ** (lw / height_pt * np.log10(hi / lo)) - 1.0


def _draw_groups(ax, t, curves, style, bands=None, rtol=None):
    """Log panel, one line per group of coinciding curves (colour, style, marker by ``style``).

    ``rtol`` None: the width of a line on this panel (:func:`_line_rtol`). Returns the groups.
    """
    lo, hi = _log_limits(t, curves)
    _plain_log_ticks(ax)
    ax.set_ylim(lo, hi)
    groups = coincide_groups(curves, _line_rtol(ax, lo, hi) if rtol is None else rtol)
    n = len(t)
    every = max(n // 8, 1)
    for g in groups:
        c, ls, mk, k = style[g[0]]
        ax.plot(t, curves[g[0]], color=c, ls=ls, lw=1.6 if len(g) > 1 else 1.3, marker=mk, ms=4.5,
                markevery=(int(k * n / 53) % every, every), label=_group_label(g))
        if bands is not None and g[0] in bands:
            b_lo, b_hi = bands[g[0]]
            ax.fill_between(t, np.maximum(b_lo, lo), np.minimum(b_hi, hi), color=c, alpha=0.15, lw=0)
    return groups


def _styles(names):
    col = _dr_colors(names)
    return {n: (col[n], _DR_STYLES[i % len(_DR_STYLES)], _DR_MARKERS[i % len(_DR_MARKERS)], i)
            for i, n in enumerate(names)}


def split_outliers(curves, factor=10.0):
    """Names of the series whose largest value is ``factor`` times the median of the largest values.

    Such series (the paper's absolute-form NN at ~1e3 m) are drawn in their own panel so the
    range where the other filters differ stays readable.

    >>> import numpy as np
    >>> split_outliers({"EKF": np.ones(3), "UKF": 2 * np.ones(3), "NN-faithful": 1e3 * np.ones(3)})
    ['NN-faithful']
    """
    peaks = {n: np.nanmax(c) if np.isfinite(c).any() else np.inf for n, c in curves.items()}
    if len(peaks) < 3:
        return []
    ref = np.median(list(peaks.values()))
    return [n for n, v in peaks.items() if v > factor * ref]


def dr_position_errors(t, errors, t_switch=None, title="", single=_DR_PAPER_PAIR, run=0, bands=None,
                       rtol=None):
    """The second paper's Figs. 4-5: east and north position error against time.

    Parameters
    ----------
    t : ndarray of shape (n_steps,)
    errors : dict of {str: ndarray of shape (n_runs, n_steps, 2)}
        Signed east/north errors per filter (``StudyResult.errors[s]["filters"]``).
    t_switch : float, optional
        Time of the noise increase (a dotted line).
    title : str
        The scenario in words.
    single : sequence of str
        Filters drawn in the top row (one run, signed error, as in the paper).
    run : int
        The run shown in the top row.
    bands : sequence of str, optional
        Filters (two or three) drawn with the 10-90 % band of the absolute error over runs;
        default the first two of ``single`` when both are in range, else the first (two
        bands of similar filters smear into one colour). Needs more than one run.
    rtol : float, optional
        Series whose RMS agree to within ``rtol`` at every step are drawn as one line labelled
        "A, B (coincide)" (:func:`coincide_groups`); default the relative width of a line on
        the panel, so series a reader could not tell apart are named together.

    Returns
    -------
    matplotlib.figure.Figure
        Top row: one run. Middle row: RMS over runs (log scale), every filter in the range
        where they differ. Bottom row (only when some filter is far off that range,
        :func:`split_outliers`): those filters alone. Legends sit right of the panels.
    """
    import matplotlib.pyplot as plt

    names = list(errors)
    n_runs = errors[names[0]].shape[0]
    style = _styles(names)
    rms = {j: {n: np.sqrt(np.mean(errors[n][:, :, j] ** 2, axis=0)) for n in names} for j in (0, 1)}
    main, out = _main_and_outliers(rms, names)
    bands = _band_names(bands, single, main, names, n_runs)
    n_rows = 3 if out else 2
    fig, axes = plt.subplots(n_rows, 2, figsize=(13.5, 3.3 * n_rows + 0.6), sharex=True, squeeze=False)
    for j, axis in enumerate(("east", "north")):
        _one_run_panel(axes[0, j], t, errors, single, style, run, j, axis)
        band = _percentile_bands(errors, bands, j)
        for row, members in ((1, main), (2, out)):
            if members:
                _rms_panel(axes[row, j], t, {n: rms[j][n] for n in members}, style, band, rtol, n_runs,
                           f"{axis}: " + ("filters far off the scale above" if row == 2 else (
                               "RMS over runs" if n_runs > 1 else "|error|")))
        axes[-1, j].set_xlabel("time [s]")
        for ax in axes[:, j]:
            if t_switch is not None:
                ax.axvline(t_switch, color="k", ls=":", lw=1)
            ax.grid(alpha=0.3)
    _position_legends(axes, bands, t_switch, out)
    fig.suptitle(f"Dead-reckoning position error: {title}")
    fig.tight_layout()
    return fig


def _main_and_outliers(rms, names):
    """The filters in the main range and those far off it on either axis (:func:`split_outliers`),
    each in the order of ``names``."""
    out = sorted(set(split_outliers(rms[0])) | set(split_outliers(rms[1])), key=names.index)
    return [n for n in names if n not in out], out


def _band_names(bands, single, main, names, n_runs):
    """The filters drawn with a 10-90 % band: ``bands`` as given (at most three), else the paper's
    pair when both are in the main range, else the first alone (no smear); none for one run."""
    if bands is None:
        bands = [n for n in single[:2] if n in main]
        bands = bands if len(bands) == 2 else bands[:1]
    return [n for n in bands if n in names][:3] if n_runs > 1 else []


def _percentile_bands(errors, bands, j):
    """``{name: (lo, hi)}``, the 10 and 90 % points over runs of the absolute error along axis ``j``
    (``lo`` floored at 1 mm for the log scale)."""
    band = {}
    for n in bands:
        e = np.abs(errors[n][:, :, j])
        lo, hi = np.percentile(e, [10, 90], axis=0)
        band[n] = (np.maximum(lo, 1e-3), hi)
    return band


def _rms_panel(ax, t, cur, style, band, rtol, n_runs, what):
    """One RMS panel of :func:`dr_position_errors`: the series ``cur`` (coinciding ones as one line)."""
    _draw_groups(ax, t, cur, style, band, rtol)
    ax.set_ylabel("RMS |error| [m]" if n_runs > 1 else "|error| [m]")
    ax.set_title(f"{what} ({n_runs} run{'s' * (n_runs > 1)})")


def _one_run_panel(ax, t, errors, single, style, run, j, axis):
    """The top panel of :func:`dr_position_errors`: the signed error of one run along ``axis``."""
    for n in single:
        if n in errors:
            c, ls, mk, _ = style[n]
            ax.plot(t, errors[n][run, :, j], color=c, lw=1.3, ls=ls, label=n)
    ax.axhline(0, color="0.5", lw=0.8)
    ax.set_title(f"{axis} error, one run (run {run}), signed")
    ax.set_ylabel("error [m]")


def _position_legends(axes, bands, t_switch, out):
    """The legends of :func:`dr_position_errors`, right of the panels, with the band and switch keys."""
    import matplotlib.pyplot as plt

    kw = dict(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    axes[0, 1].legend(**kw)
    h, lab = axes[1, 1].get_legend_handles_labels()
    if bands:
        from matplotlib.patches import Patch

        h.append(Patch(color="0.6", alpha=0.4))
        lab.append(f"shaded: 10-90 % of |error| over runs\n({', '.join(bands)})")
    if t_switch is not None:
        h.append(plt.Line2D([], [], color="k", ls=":", lw=1))
        lab.append(f"noise switch ({t_switch:g} s)")
    axes[1, 1].legend(h, lab, **kw)
    if out:
        axes[2, 1].legend(**kw)


def dr_outage_errors(t, errors, outages=(), title="", bands=None, rtol=None):
    """GPS/DR horizontal position error against time with the GPS outages shaded.

    Parameters
    ----------
    t : ndarray of shape (n_steps,)
    errors : dict of {str: ndarray of shape (n_runs, n_steps, 2)}
    outages : sequence of (t_start, t_end)
    title : str
        The scenario in words.
    bands : sequence of str, optional
        Filters (two or three) drawn with the 10-90 % band over runs; default the first
        filter and the first filter with a different RMS curve.
    rtol : float, optional
        Series that agree to within ``rtol`` at every step share one line labelled
        "(coincide)" (:func:`coincide_groups`); default the relative width of a line on the panel.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    names = list(errors)
    n_runs = errors[names[0]].shape[0]
    style = _styles(names)
    h = {n: np.hypot(errors[n][..., 0], errors[n][..., 1]) for n in names}
    rms = {n: np.sqrt(np.mean(h[n] ** 2, axis=0)) for n in names}
    if bands is None:
        bands = [g[0] for g in coincide_groups(rms, 0.05) if not any(n.startswith("DR") for n in g)][:2]
    bands = [n for n in bands if n in names][:3] if n_runs > 1 else []
    band = {}
    for n in bands:
        lo, hi = np.percentile(h[n], [10, 90], axis=0)
        band[n] = (np.maximum(lo, 1e-3), hi)
    fig, ax = plt.subplots(figsize=(12, 4.8))
    for i, (a, b) in enumerate(outages):
        ax.axvspan(a, b, color="0.88", zorder=0, label="GPS outage" if i == 0 else None)
    _draw_groups(ax, t, rms, style, band, rtol)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("horizontal RMS error [m]")
    ax.set_title(f"{title}: horizontal error, RMS over {n_runs} runs" if n_runs > 1
                 else f"{title}: horizontal error (1 run)")
    ax.grid(alpha=0.3)
    hs, lab = ax.get_legend_handles_labels()
    if bands:
        from matplotlib.patches import Patch

        hs.append(Patch(color="0.6", alpha=0.4))
        lab.append(f"shaded: 10-90 % over runs\n({', '.join(bands)})")
    ax.legend(hs, lab, fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0)
    fig.tight_layout()
    return fig


__all__ += ["dr_real_drive"]


def _rejected_fixes(ax, integrity):
    """Mark the fixes the filters' integrity gate rejected (each filter its own marker)."""
    for i, (name, ig) in enumerate(integrity.items()):
        xy = ig["rejected_xy"]
        if len(xy):
            ax.plot(xy[:, 0], xy[:, 1], ls="none", marker=_DR_MARKERS[i % len(_DR_MARKERS)], mfc="none", ms=5,
                    color="tab:purple", alpha=0.7, label=f"fix rejected by {name} ({len(xy)})")


def dr_real_drive(res, ax=None):
    """A real drive: its track with the GPS outages marked, and each filter's error at the outage ends.

    Parameters
    ----------
    res : dict
        What :func:`filterwnn.studies.dr.real_drive_outages` returns.

    Returns
    -------
    matplotlib.figure.Figure
        Left: the track (east/north, m), each outage drawn over it with its start marked
        and numbered, and the fixes each filter rejected (``res["integrity"]``). Right: the horizontal error at the end of each outage per filter
        (log scale) against the outage's start time.
    """
    import matplotlib.pyplot as plt

    names = [k for k in res["end_xy"]]
    col = _dr_colors(names)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(13, 5.2))
    tr = res["track"]
    t = res["t"]
    ax1.plot(tr[:, 0], tr[:, 1], color="0.6", lw=1.0, label=f"track ({'truth' if res['reference'] == 'truth' else 'GPS'})")
    for j, (a, k1) in enumerate(zip(res["starts"], res["end_steps"])):
        k0 = int(np.searchsorted(t, a))
        ax1.plot(tr[k0:k1 + 1, 0], tr[k0:k1 + 1, 1], color="tab:red", lw=4, alpha=0.12, solid_capstyle="butt",
                 label="GPS outage (overlaps darker)" if j == 0 else None)
        ax1.plot(*tr[k1], "kx", ms=5, label="outage end (scored)" if j == 0 else None)
        ax1.annotate(str(j + 1), tr[k1], xytext=(3, 3), textcoords="offset points", fontsize=7)
    _rejected_fixes(ax1, res.get("integrity", {}))
    ax1.set_aspect("equal", adjustable="datalim")
    ax1.set_xlabel("east [m]")
    ax1.set_ylabel("north [m]")
    ax1.set_title("track with the GPS outages (numbered at their end)")
    ax1.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=3)
    ax1.grid(alpha=0.3)
    num = np.arange(1, len(res["starts"]) + 1)
    for i, n in enumerate(names):   # a marker per filter: equal errors stay visible
        ax2.plot(num, np.maximum(res[n], 1e-2), marker=_DR_MARKERS[i % len(_DR_MARKERS)], ls="-",
                 color=col[n], ms=6 - 1.2 * (i % 3), lw=1, label=
                 f"{n} (median {np.median(res[n]):.2f} m)")
    _plain_log_ticks(ax2)
    ax2.set_xticks(num)
    ax2.set_xlabel("outage number (as on the track)")
    ax2.set_ylabel(f"horizontal error at the outage end [m] (vs {res['reference']})")
    ax2.set_title(f"error at the end of each {res['length']:g} s GPS outage")
    ax2.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=3)
    ax2.grid(alpha=0.3)
    fig.suptitle(f"GPS/DR on the drive {res['name']}: {len(res['starts'])} outages of {res['length']:g} s")
    fig.tight_layout()
    return fig
