"""The bank's numbers before and after a change of its step's memory handling, bit for bit.

Runs one script in two source trees (``--a`` and ``--b``, each a checkout of the package),
each in its own subprocess with ``PYTHONPATH`` set to it, and compares the ``.npz`` files
they write: ``x``, ``P`` and the log-likelihoods of an ``UnscentedKalmanFilterBank`` after
each of 30 steps of the 6-state model of ``bench_peers.py``, at B = 1,000 and 10,000,
Merwe and simplex points, every member observed or some missing (NaN rows, a different
set each step), plus a ``dim_z = 1`` case (its own update path). Prints one line per case
and ``identical`` or the first difference; exit status 1 when any differs.

    python benchmarks/bank_buffers_identity.py --a /work/main --b .
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

CASES = [(B, pts, miss, 3) for B in (1000, 10000) for pts in ("merwe", "simplex") for miss in (False, True)]
CASES.append((1000, "merwe", True, 1))
N_STEPS = 30


def _name(case):
    B, pts, miss, m = case
    return f"B{B}-{pts}-{'missing' if miss else 'all'}-z{m}"


def run_cases(out_dir):
    """Write one ``.npz`` per case into ``out_dir`` with the package on ``sys.path``."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import filterwnn
    from bench_particle import DT6, six_fx, six_hx, six_problem
    from filterwnn.kalman.bank import UnscentedKalmanFilterBank
    from filterwnn.kalman.presets import make_points

    print("package:", filterwnn.__file__)
    for case in CASES:
        B, pts, miss, m = case
        g = np.random.default_rng(0)
        prob = six_problem(g, N_STEPS)
        hx = six_hx if m == 3 else (lambda X: six_hx(X)[:, 2:])
        R = prob["R"] if m == 3 else prob["R"][2:, 2:]
        bank = UnscentedKalmanFilterBank(B, 6, m, DT6, hx, six_fx, make_points(pts, 6))
        bank.x = prob["x0"] + g.standard_normal((B, 6)) * np.sqrt(np.diag(prob["P0"]))
        bank.P, bank.Q, bank.R = prob["P0"], prob["Q"], R
        xs, Ps, lls = [], [], []
        for k in range(N_STEPS):
            z = prob["zs"][k][:m] if m == 3 else prob["zs"][k][2:]
            z = z + g.standard_normal((B, m)) * np.sqrt(np.diag(R))
            if miss:
                z[g.random(B) < 0.2] = np.nan
            bank.predict()
            bank.update(z)
            xs.append(bank.x.copy())
            Ps.append(bank.P.copy())
            lls.append(bank.log_likelihood.copy())
        np.savez(Path(out_dir) / f"{_name(case)}.npz", x=np.array(xs), P=np.array(Ps), ll=np.array(lls))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--a", required=True, help="source tree A (e.g. main's checkout)")
    ap.add_argument("--b", required=True, help="source tree B")
    ap.add_argument("--run", help=argparse.SUPPRESS)  # internal: write the cases into this folder
    args = ap.parse_args(argv)
    if args.run:
        run_cases(args.run)
        return 0
    dirs = {}
    with tempfile.TemporaryDirectory() as tmp:
        for key, tree in (("a", args.a), ("b", args.b)):
            d = dirs[key] = Path(tmp) / key
            d.mkdir()
            env = dict(os.environ, PYTHONPATH=str(Path(tree).resolve()))
            subprocess.run([sys.executable, __file__, "--a", args.a, "--b", args.b, "--run", str(d)], env=env,
                           check=True)
        bad = 0
        for case in CASES:
            fa, fb = np.load(dirs["a"] / f"{_name(case)}.npz"), np.load(dirs["b"] / f"{_name(case)}.npz")
            diff = [k for k in ("x", "P", "ll") if not np.array_equal(fa[k], fb[k])]
            bad += bool(diff)
            print(f"{_name(case)}: {'identical' if not diff else 'DIFFERENT in ' + ', '.join(diff)}"
                  f" (x {fa['x'].shape}, P {fa['P'].shape}, ll {fa['ll'].shape})")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
