"""What the drive reader says of the phone analog (seed 0) with its fixes stamped 18 s late, with its truth and
without (issue 23, stop 48): the refusal, or each warning. Run with the package to look at installed::

    python docs/study-outputs/dr/log-faults/clock_offset_reader.py    # clock_offset_reader.txt (stop 48)

``clock_offset_reader_before.txt`` is its output on a checkout of 7030b35 (before the check), ``PYTHONPATH`` set to it.
"""
import os
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "tests"))
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402

cols = held_out.columns("phone", 0, gps_latency=18.0)
untrue = dict(cols, true_east=np.full(len(cols["time"]), np.nan), true_north=np.full(len(cols["time"]), np.nan))
with tempfile.TemporaryDirectory() as tmp:
    for label, c in (("with its truth", cols), ("without a truth", untrue)):
        path = held_out.write_csv(os.path.join(tmp, "late.csv"), c)
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            try:
                read_drive_csv(path)
                said = "read"
            except ValueError as exc:
                said = "refused: " + str(exc).replace(path, "FILE")
        print(f"# {label}: {said}")
        for w in record:
            if "plausibility" in str(w.message):
                print("warning: " + str(w.message).replace(path, "FILE"))
