"""Does the crawl test fire where no car creeps? (issue 23, stop 53)

Stop 53's ``crawl_test`` (``GPSDRFilter``: while the speed reads 0, a generalized likelihood ratio of the fixes,
a constant offset and a crawl along the heading against the offset alone, guarded by an offset that jumps once)
changes nothing where it never decides. Per drive and kind (phone grade unless named, as ``filterwnn study dr
--drive FILE`` scores it, every pass: the one with the fixes and each outage's), its decisions (``crawl``), the
largest statistic it reached without deciding (``glr``, which must pass log(1e9) = 20.7, and then the jump guard,
log(100)), and the outage ends' median / max (m). Run with the package at ``ROOT``, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_count.py ROOT analogs 0 10 > crawl_count_analogs.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_count.py ROOT recorded > crawl_count_recorded.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_count.py ROOT hard > crawl_count_hard.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_count.py ROOT random 1 0 40 > crawl_count_random_1.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/sensor-faults/crawl_count.py ROOT random 2 0 40 > crawl_count_random_2.txt

(``recorded`` needs the ``data`` extra; ``random P LO HI``: ``random_drives.drive(seed, P)``, EKF-8 only; ``hard``:
``tests/navigation/test_hard_drives.py``'s five drives, scored as there; ``analogs LO HI [NAMES]``: the analogs of
``tests/_held_out_drives.py``; ``files CSV ...``: drive CSVs, each with the test and without, ``KINDS`` from the
environment.)
"""
import os
import sys
import tempfile
import warnings

import numpy as np
ROOT = os.path.abspath(sys.argv[1])
sys.path[:0] = [ROOT, ROOT + "/tests", ROOT + "/docs/study-outputs/dr/random-drives"]
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation import gpsdr  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv, sample_drive_path, load_car_drive, CAR_DRIVES  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402
C = {"n": 0, "glr": -np.inf}
orig = gpsdr.GPSDRFilter._test_crawl


def test(self, z_gps, gps_sigma):
    before = self.n_crawl
    out = orig(self, z_gps, gps_sigma)
    if self.n_crawl > before:
        C["n"] += 1
    else:
        C["glr"] = max(C["glr"], self._crawl["glr"])
    return out


gpsdr.GPSDRFilter._test_crawl = test


def go(label, run, kinds=("EKF-8", "UKF-8", "SUKF-8"), grade="phone", sig=True, **kw):
    out = []
    for kd in kinds:
        C["n"], C["glr"] = 0, -np.inf
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = real_drive_outages(run, filters=(kd,), use_gps_sigma=sig and run.gps_sigma is not None, grade=grade,
                                     **kw)
        out.append(f"{kd} {np.median(res[kd]):.2f}/{res[kd].max():.2f} crawl {C['n']} glr {C['glr']:.1f}")
    print(label, "|", " | ".join(out), flush=True)


def read(tmp, cols):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))


which = sys.argv[2]
tmp = tempfile.mkdtemp()
if which == "analogs":
    names = sys.argv[5].split(",") if len(sys.argv) > 5 else ("one_hz", "phone", "city")
    for name in names:
        for seed in range(int(sys.argv[3]), int(sys.argv[4])):
            go(f"{name} {seed}", read(tmp, held_out.columns(name, seed)))
elif which == "files":
    kinds = tuple(os.environ.get("KINDS", "EKF-8,UKF-8,SUKF-8").split(","))
    for f in sys.argv[3:]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = read_drive_csv(f)
        go(os.path.basename(f), run, kinds=kinds)
        go(os.path.basename(f) + " off", run, kinds=kinds, crawl_test=False)
elif which == "recorded":
    run = read_drive_csv(sample_drive_path())
    go("sample phone", run)
    go("sample survey", run, grade="survey")
    for d in CAR_DRIVES:
        run = load_car_drive(d)
        go(f"{d} phone", run)
        go(f"{d} survey", run, grade="survey")
elif which == "random":
    import random_drives  # noqa: E402
    proto = int(sys.argv[3])
    for seed in range(int(sys.argv[4]), int(sys.argv[5])):
        go(f"{proto} {seed}", read(tmp, random_drives.drive(seed, proto)[1]), kinds=("EKF-8",))
elif which == "hard":
    sys.path.insert(0, ROOT + "/tests/navigation")
    import test_hard_drives as hard  # noqa: E402
    for make in hard.DRIVES:
        rng = np.random.default_rng(np.random.SeedSequence([23, hard.DRIVES.index(make)]))
        run, grade, first = make(rng)
        go(make.__name__, run, grade=grade, length=30.0, starts=np.linspace(first, run.t[-1] - 32.0, 4))
