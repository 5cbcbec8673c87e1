"""The drives a detector's false-alarm count runs on (``log-faults/reversing_count.py``, stop 52;
``sensor-faults/crawl_count.py``, stop 53): each script passes its own ``go(label, run, **kw)``, which scores one
drive, and :func:`run_set` calls it for every drive of a set:

* ``analogs LO HI [NAMES]``: the analogs of ``tests/_held_out_drives.py`` (``one_hz,phone,city`` unless named),
  seeds LO to HI - 1, every kind;
* ``recorded``: the shipped sample and onavdata's drives, phone and survey grade;
* ``random PROTOCOL LO HI``: ``random-drives/random_drives.py``'s drives, EKF-8;
* ``hard``: ``tests/navigation/test_hard_drives.py``'s five drives, scored as there.

The caller puts the package at ``ROOT`` first on ``sys.path`` (with ``ROOT/tests`` and this folder's
``random-drives``) before importing this module.
"""
import os
import sys
import tempfile
import warnings

import numpy as np

import _held_out_drives as held_out
from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive, read_drive_csv, sample_drive_path

SETS = ("analogs", "recorded", "random", "hard")


def read(tmp, cols):
    """A drive's columns written as a drive CSV in ``tmp`` and read back, as the command reads it."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols))


def run_set(root, which, args, go):
    """Call ``go(label, run, **kw)`` for every drive of the set ``which`` (one of :data:`SETS`, with its
    arguments ``args``: the command line after it)."""
    tmp = tempfile.mkdtemp()
    if which == "analogs":
        names = args[2].split(",") if len(args) > 2 else ("one_hz", "phone", "city")
        for name in names:
            for seed in range(int(args[0]), int(args[1])):
                go(f"{name} {seed}", read(tmp, held_out.columns(name, seed)))
    elif which == "recorded":
        run = read_drive_csv(sample_drive_path())
        go("sample phone", run)
        go("sample survey", run, grade="survey")
        for d in CAR_DRIVES:
            run = load_car_drive(d)
            go(f"{d} phone", run)
            go(f"{d} survey", run, grade="survey")
    elif which == "random":
        import random_drives

        proto = int(args[0])
        for seed in range(int(args[1]), int(args[2])):
            go(f"{proto} {seed}", read(tmp, random_drives.drive(seed, proto)[1]), kinds=("EKF-8",))
    elif which == "hard":
        sys.path.insert(0, root + "/tests/navigation")
        import test_hard_drives as hard

        for make in hard.DRIVES:
            rng = np.random.default_rng(np.random.SeedSequence([23, hard.DRIVES.index(make)]))
            run, grade, first = make(rng)
            go(make.__name__, run, grade=grade, length=30.0, starts=np.linspace(first, run.t[-1] - 32.0, 4))
    else:
        raise SystemExit(f"unknown set {which!r}: one of {', '.join(SETS)}")
