"""Figures drawn from study results (the studies themselves never plot).

Every function takes a result object or plain arrays, draws with matplotlib's
object-oriented API on a new figure (or a given ``ax``), and returns the figure; saving
is the caller's business. Import matplotlib lazily so the package imports headless.
"""

from __future__ import annotations

__all__ = []


def _figure(ax=None, figsize=(6, 4)):
    """``(fig, ax)``: a new figure, or the given ``ax`` and its figure."""
    if ax is not None:
        return ax.figure, ax
    import matplotlib.pyplot as plt

    return plt.subplots(figsize=figsize)

# --- sigma points and particle filters (issues 3-4) ---

# --- WNN study (issue 5) ---

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
    fig, ax = _figure(ax)
    for trainer in dict.fromkeys(r["trainer"] for r in sweep):
        rows = sorted((r for r in sweep if r["trainer"] == trainer), key=lambda r: r["n_particles"])
        ax.plot([r["n_particles"] for r in rows], [r[metric] for r in rows], "o-", label=trainer.upper())
    ax.set_xlabel("particles")
    if metric == "test_mse_median":
        ax.set_ylabel("test MSE (median over runs)")
        ax.set_yscale("log")
        ax.set_title("Test MSE of the particle-filter trainers (cf. paper Fig. 3)")
    else:
        ax.set_ylabel("training time per run (s, median)")
        ax.set_title("Training time of the particle-filter trainers (cf. paper Fig. 4)")
    ax.grid(True, alpha=0.3)
    ax.legend()
    return fig


def wnn_convergence(runs, ax=None):
    """The first paper's Fig. 5: training (and test) MSE against epochs, median over runs.

    Parameters
    ----------
    runs : list of dict
        ``StudyResult.runs`` entries with ``trainer``, ``curve_train`` and ``curve_test``.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    import numpy as np

    fig, ax = _figure(ax)
    for i, trainer in enumerate(dict.fromkeys(r["trainer"] for r in runs)):
        color = f"C{i % 10}"
        sel = [r for r in runs if r["trainer"] == trainer]
        for key, style, label in (("curve_train", "-", "train"), ("curve_test", "--", "test")):
            curves = [r[key] for r in sel if r[key]]
            if not curves:
                continue
            n = min(len(c) for c in curves)
            med = np.median(np.array([c[:n] for c in curves]), axis=0)
            ax.plot(np.arange(1, n + 1), med, style, color=color, marker="." if n < 40 else None,
                    label=f"{trainer.upper()} {label}")
    ax.set_xlabel("epoch")
    ax.set_ylabel("MSE (median over runs)")
    ax.set_yscale("log")
    ax.set_title("Convergence of WNN training (cf. paper Fig. 5)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return fig


# --- dead-reckoning study (issue 6) ---

import numpy as np  # noqa: E402  (issue 6 section)

__all__ += ["dr_position_errors", "dr_outage_errors"]

_DR_PAPER_PAIR = ("EKF", "NN", "EKF-oracle")


def _dr_colors(names):
    import matplotlib.pyplot as plt

    cyc = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    return {n: cyc[i % len(cyc)] for i, n in enumerate(names)}


def dr_position_errors(t, errors, t_switch=None, title="", single=_DR_PAPER_PAIR, run=0):
    """The second paper's Figs. 4-5: east and north position error against time.

    Parameters
    ----------
    t : ndarray of shape (n_steps,)
    errors : dict of {str: ndarray of shape (n_runs, n_steps, 2)}
        Signed east/north errors per filter (``StudyResult.errors[s]["filters"]``).
    t_switch : float, optional
        Time of the noise increase (a dashed line).
    single : sequence of str
        Filters drawn in the top row (one run, signed error, as in the paper).
    run : int
        The run shown in the top row.

    Returns
    -------
    matplotlib.figure.Figure
        Top row: one run; bottom row: RMS over runs (log scale) with the 10-90 %
        band of the absolute error over runs.
    """
    import matplotlib.pyplot as plt

    names = list(errors)
    col = _dr_colors(names)
    fig, axes = plt.subplots(2, 2, figsize=(12, 7.5), sharex=True)
    for j, axis in enumerate(("east", "north")):
        ax = axes[0, j]
        for n in single:
            if n in errors:
                ax.plot(t, errors[n][run, :, j], color=col[n], lw=1.2,
                        ls="-" if n.startswith("NN") else "--", label=n)
        ax.set_title(f"{axis} position error, run {run}")
        ax.set_ylabel("error [m]")
        ax = axes[1, j]
        for n in names:
            e = np.abs(errors[n][:, :, j])
            rms = np.sqrt(np.mean(e**2, axis=0))
            ax.plot(t, rms, color=col[n], lw=1.3, label=n)
            lo, hi = np.percentile(e, [10, 90], axis=0)
            ax.fill_between(t, np.maximum(lo, 1e-3), hi, color=col[n], alpha=0.08)
        ax.set_yscale("log")
        ax.set_ylim(1e-2, None)
        ax.set_title(f"{axis}: RMS over {errors[names[0]].shape[0]} runs (band: 10-90 % of |error|)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("|error| [m]")
        for ax in axes[:, j]:
            if t_switch is not None:
                ax.axvline(t_switch, color="k", ls=":", lw=1)
            ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    axes[1, 1].legend(fontsize=7, ncol=2)
    fig.suptitle(f"DR position error: {title}")
    fig.tight_layout()
    return fig


def dr_outage_errors(t, errors, outages=(), title=""):
    """GPS/DR horizontal position error against time with the GPS outages shaded.

    Parameters
    ----------
    t : ndarray of shape (n_steps,)
    errors : dict of {str: ndarray of shape (n_runs, n_steps, 2)}
    outages : sequence of (t_start, t_end)

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    names = list(errors)
    col = _dr_colors(names)
    fig, ax = plt.subplots(figsize=(10, 4.8))
    for n in names:
        h = np.hypot(errors[n][..., 0], errors[n][..., 1])
        ax.plot(t, np.sqrt(np.mean(h**2, axis=0)), color=col[n], lw=1.3, label=n)
        lo, hi = np.percentile(h, [10, 90], axis=0)
        ax.fill_between(t, np.maximum(lo, 1e-3), hi, color=col[n], alpha=0.08)
    for i, (a, b) in enumerate(outages):
        ax.axvspan(a, b, color="0.85", zorder=0, label="GPS outage" if i == 0 else None)
    ax.set_yscale("log")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("horizontal error [m]")
    ax.set_title(f"GPS/DR horizontal error, RMS over runs (band 10-90 %): {title}")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    return fig


__all__ += ["dr_real_drive"]


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
        and numbered. Right: the horizontal error at the end of each outage per filter
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
    ax1.set_aspect("equal", adjustable="datalim")
    ax1.set_xlabel("east [m]")
    ax1.set_ylabel("north [m]")
    ax1.set_title("track with the GPS outages (numbered at their end)")
    ax1.legend(fontsize=8)
    ax1.grid(alpha=0.3)
    num = np.arange(1, len(res["starts"]) + 1)
    for n in names:
        ax2.plot(num, np.maximum(res[n], 1e-2), "o-", color=col[n], ms=4, lw=1, label=
                 f"{n} (median {np.median(res[n]):.2f} m)")
    ax2.set_yscale("log")
    ax2.set_xticks(num)
    ax2.set_xlabel("outage number (as on the track)")
    ax2.set_ylabel(f"horizontal error at the outage end [m] (vs {res['reference']})")
    ax2.set_title(f"error at the end of each {res['length']:g} s GPS outage")
    ax2.legend(fontsize=8)
    ax2.grid(alpha=0.3, which="both")
    fig.suptitle(f"GPS/DR on the drive {res['name']}: {len(res['starts'])} outages of {res['length']:g} s")
    fig.tight_layout()
    return fig
