"""The WNN study's figures: Figs. 3-4 (test MSE and training time against the number of
particles) and Fig. 5 (the SUPF's convergence), drawn by :mod:`filterwnn.studies.plotting`."""

from __future__ import annotations

import os

__all__ = [
    "write_figures",
]


def _save(fig, out, name, paths):
    p = os.path.join(out, name)
    fig.savefig(p, dpi=120, bbox_inches="tight")
    paths.append(p)


def write_figures(result, out):
    """Write ``fig3_particles_mse.png``, ``fig4_particles_time.png`` (when the result has a sweep),
    ``fig5_supf_convergence.png`` and ``convergence_all.png`` (when it has training curves) into
    ``out``, with matplotlib's Agg backend.

    Returns
    -------
    list of str
        The paths written.
    """
    import matplotlib

    matplotlib.use("Agg")
    from .. import plotting

    paths = []
    if result.sweep:
        for metric, name in (("test_mse_median", "fig3_particles_mse.png"),
                             ("fit_time_median", "fig4_particles_time.png")):
            _save(plotting.wnn_particle_sweep(result.sweep, metric=metric), out, name, paths)
    curves = [r for r in result.runs if r["table"] == "working" and r["curve_train"]]
    for trainer, name in (("supf", "fig5_supf_convergence.png"), (None, "convergence_all.png")):
        sel = [r for r in curves if trainer is None or r["trainer"] == trainer]
        if sel:
            _save(plotting.wnn_convergence(sel), out, name, paths)
    return paths
