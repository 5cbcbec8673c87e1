"""A counter-clockwise yaw from some zero written as the heading (issue 23, stop 49).

The analogs of ``tests/_held_out_drives.py`` (seed 0 of each) with the heading ``57.3 deg - heading`` (1 rad), as a
yaw angle counter-clockwise from wherever its integration began would be, read by ``read_drive_csv``; each line,
the refusal. Run from the repository root::

    python docs/study-outputs/dr/log-faults/mirrored_yaw.py > docs/study-outputs/dr/log-faults/mirrored_yaw.txt
"""
import os
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "tests"))
import _held_out_drives as h  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402

with tempfile.TemporaryDirectory() as tmp:
    for name in ("phone", "one_hz", "city"):
        c = h.columns(name, 0)
        c["heading"] = np.mod(1.0 - c["heading"], 2 * np.pi)
        path = h.write_csv(os.path.join(tmp, f"{name}.csv"), c)
        try:
            read_drive_csv(path)
            print(f"{name}: read")
        except ValueError as e:
            print(f"{name}: refused: {str(e)[len(path) + 2:]}")
