"""Figures drawn from study results (the studies themselves never plot).

Every function takes a result object or plain arrays, draws with matplotlib's
object-oriented API on a new figure (or a given ``ax``), and returns the figure; saving
is the caller's business. Import matplotlib lazily so the package imports headless.
"""

from __future__ import annotations

__all__ = []

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
    import matplotlib.pyplot as plt

    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 4))
    else:
        fig = ax.figure
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
    import matplotlib.pyplot as plt
    import numpy as np

    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 4))
    else:
        fig = ax.figure
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
