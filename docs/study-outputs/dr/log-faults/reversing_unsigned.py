"""A car that reverses 14 m (40-48 s) on an unsigned speed, its fixes there all the time (issue 23, stop 52).

Per 8-state kind, phone grade: the step the reversing test decided at and the largest error from 48 s on (m),
with the test (``reversing_test``, the default) and without; a 1 Hz log that stops for an instant, reverses
16 m and drives on with no standing sample (the decisions' steps, the largest error, with and without); then a car that only drives forward, pulling
away slowly (to 2 m/s in 8 s) while its fixes sit JUMP m behind for LENGTH s (a street's multipath): the
stretches taken as reversing and the largest error, with the test and without. Run from the repository root,
one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/reversing_unsigned.py > docs/study-outputs/dr/log-faults/reversing_unsigned.txt
"""
import os
import sys
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "tests", "navigation"))
from test_drives import _errors, _unsigned_reversing_run  # noqa: E402

from filterwnn.navigation.scenarios import DRRun  # noqa: E402


def go(run, kind, after, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        kf, err = _errors(run, kind, **kw)
    return kf, err[after].max()


run = _unsigned_reversing_run()
after = run.t >= 48.0
for kind in ("ekf", "ukf", "sukf"):
    kf, on = go(run, kind, after)
    _, off = go(run, kind, after, reversing_test=False)
    print(f"reversing 14 m | {kind.upper()}-8 decided at step {kf.reversing_steps} | max error from 48 s "
          f"{on:.2f} m (without the test {off:.2f} m)", flush=True)
fine = 0.01 * np.arange(12001)
v_fine = np.interp(fine, [0, 30, 35.5, 37.5, 45.5, 47.5, 55, 120], [10, 10, 0, -2, -2, 0, 10, 10])
e_fine = np.r_[0.0, np.cumsum((v_fine[1:] + v_fine[:-1]) / 2 * 0.01)]
t1 = np.arange(121.0)
v1, e1 = np.interp(t1, fine, v_fine), np.interp(t1, fine, e_fine)
noise = np.random.default_rng(5).normal(0.0, 3.0, (len(t1), 2))
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    one_hz = DRRun.from_arrays(t1, np.full(len(t1), np.pi / 2), speed=np.abs(v1), gps_t=t1, east=e1 + noise[:, 0],
                               north=noise[:, 1], gps_sigma=3.0, truth=np.stack([e1, np.zeros_like(e1)], axis=1))
for kind in ("ekf", "ukf", "sukf"):
    kf, on = go(one_hz, kind, slice(None))
    _, off = go(one_hz, kind, slice(None), reversing_test=False)
    print(f"1 Hz, no standing sample (slowest {np.abs(v1).min():g} m/s) | {kind.upper()}-8 {kf.n_reversing} reversing and "
          f"{kf.n_forward_again} forward again, at steps {kf.reversing_steps} | max error "
          f"{on:.2f} m (without the test {off:.2f} m)", flush=True)
t = 0.1 * np.arange(1201)
speed = np.interp(t, [0, 30, 35, 40, 48, 120], [10, 10, 0, 0, 2, 2])
every = slice(None)
for jump in (10.0, 20.0, 30.0, 40.0, 60.0):
    for length in (5.0, 10.0, 20.0):
        r = _unsigned_reversing_run(offset=np.where((t >= 40.0) & (t < 40.0 + length), -jump, 0.0), speed=speed)
        cells = []
        for kind in ("ekf", "ukf", "sukf"):
            kf, on = go(r, kind, every)
            _, off = go(r, kind, every, reversing_test=False)
            cells.append(f"{kind.upper()}-8 {kf.n_reversing} reversing, max {on:.2f} m (without {off:.2f})")
        print(f"forward, fixes {jump:g} m behind for {length:g} s | " + " | ".join(cells), flush=True)
