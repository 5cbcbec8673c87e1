"""Shared set-up of ``rowab.py`` and ``neigh.py``: bench_peers' 6-state problem at ``B``, a kept
and a fresh bank (the fresh one with the workspace switched off), and the rotation's neighbours.

These scripts measure the kept-work-array bank of commits e1711f0 / f1fa75c (reverted): run them
from a checkout of f1fa75c, whose bank has ``_workspace``. ``bench_peers.py`` is imported from
this checkout's ``benchmarks/``.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import bench_peers as bp  # noqa: E402


def rotation(B):
    """``(kept_step, fresh_step, neighbours)`` at ``B`` members; each a no-argument callable,
    ``neighbours`` a dict ``loop``, ``floor``, ``dynamax`` (the rotation's other variants)."""
    prob, x, z = bp._six(B)
    pts = bp._merwe6()
    c = np.sqrt(6.0)
    P0 = np.broadcast_to(prob["P0"], (B, 6, 6)).copy()
    kept, fresh = bp._bank(prob, x), bp._bank(prob, x)
    fresh._workspace = lambda: None

    def step(bank):
        def one():
            bank.predict()
            bank.update(z)
        return one

    def loop():
        for i in range(bp.LOOP_SAMPLE):
            f = bp._filterpy_six(prob, x[i])
            f.predict()
            f.update(z[i])

    def floor():
        bp.numpy_ukf_step(x, P0, prob["Q"], prob["R"], z, pts.Wm, pts.Wc, c)

    dyn = bp._dynamax_bank(prob, x, z)["dynamax jit(vmap)"].fn
    return step(kept), step(fresh), {"loop": loop, "floor": floor, "dynamax": dyn}
