"""The crawl test (``GPSDRFilter(crawl_test=True)``, issue 23, stop 53) on the drives of its tests, and on the
standstills it must leave alone.

* ``crawl``: ``test_drives._crawl_run`` (east at 10 m/s, a 19.5 m crawl at 0.5 m/s from 40 to 80 s whose speed
  reads 0 under a 0.8 m/s cutoff, east again at 85 s; 1 Hz fixes of 3 or 5 m), every 8-state kind (phone grade),
  with the test and without: the crawl's decisions (step, metres moved in all), the error's maximum over 40-90 s
  and after 90 s (m).
* ``wander``: the car standing 120 s with fixes of 5 m whose errors wander together (first-order Gauss-Markov,
  20 s), seeds 0-39, EKF-8: decisions, and the test's largest statistic (which must pass log(1e9) = 20.7).
* ``jump``: a 50 s stop with 3 m fixes that jump 20 or 60 m ahead (or 20 m behind) for 10-40 s (multipath),
  EKF-8, with the test and without; and again with the test's jump guard off (``CRAWL_JUMP_ALPHA`` infinite).

Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_test.py ROOT > crawl_test.txt
"""
import os
import sys
import warnings

import numpy as np

ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/tests/navigation"]
from filterwnn.navigation import gpsdr  # noqa: E402
from test_drives import _crawl_run, _errors  # noqa: E402

BEST = {"glr": 0.0}
orig = gpsdr.GPSDRFilter._test_crawl


def test(self, z_gps, gps_sigma):
    n = self.n_crawl
    orig(self, z_gps, gps_sigma)
    if self.n_crawl == n:
        BEST["glr"] = max(BEST["glr"], self._crawl["glr"])


gpsdr.GPSDRFilter._test_crawl = test


def run(r, kind="ekf", **kw):
    BEST["glr"] = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return _errors(r, kind, **kw)


print("## crawl: kind, sigma | with the test: decisions (step, moved m), max 40-90 s, max after 90 s | without")
for sigma in (3.0, 5.0):
    r = _crawl_run(sigma=sigma)
    seg, after = (r.t >= 40.0) & (r.t <= 90.0), r.t >= 90.0
    for kind in ("ekf", "ukf", "sukf"):
        kf, err = run(r, kind)
        _, off = run(r, kind, crawl_test=False)
        print(f"{kind.upper()}-8 sigma {sigma:.0f} m | {kf.n_crawl} {kf.crawl_steps} {kf.crawl_moved:.1f} m, "
              f"{err[seg].max():.2f}, {err[after].max():.2f} | {off[seg].max():.2f}, {off[after].max():.2f}",
              flush=True)
print()
print("## wander: seed | decisions, largest statistic (bound 20.7), max error with / without the test")
n_dec = 0
for seed in range(40):
    r = _crawl_run(crawl=False, sigma=5.0, tau=20.0, stop=120.0, seed=seed)
    kf, err = run(r)
    glr = BEST["glr"]
    _, off = run(r, crawl_test=False)
    n_dec += kf.n_crawl > 0
    print(f"{seed} | {kf.n_crawl}, {glr:.1f}, {err.max():.2f} / {off.max():.2f}", flush=True)
print(f"stops with a decision: {n_dec} of 40")
for guard in (True, False):
    gpsdr.CRAWL_JUMP_ALPHA = 0.01 if guard else np.inf
    print()
    print(f"## jump{'' if guard else ' (the jump guard off)'}: metres, from, to (s) | decisions (step, moved m), max "
          "error after 40 s with / without the test")
    for jump in (20.0, 60.0, -20.0):
        for length in (10.0, 20.0, 40.0):
            for at in (40.0, 60.0):
                if at + length > 85.0:
                    continue
                r = _crawl_run(crawl=False, jump=(jump, at, at + length))
                kf, err = run(r)
                _, off = run(r, crawl_test=False)
                k = r.t >= 40.0
                print(f"{jump:+.0f} m, {at:.0f}-{at + length:.0f} s | {kf.n_crawl} {kf.crawl_steps} "
                      f"{kf.crawl_moved:.1f} m, {err[k].max():.2f} / {off[k].max():.2f}", flush=True)
