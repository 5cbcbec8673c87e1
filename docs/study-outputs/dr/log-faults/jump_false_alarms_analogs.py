"""Does the heading-jump detector find steps that are not there? The analogs, seeds ``FIRST``-``LAST``, every kind (stop 46).

Run from the repository root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/jump_false_alarms_analogs.py phone 0 24
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/jump_false_alarms_analogs.py phone 25 49
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/jump_false_alarms_analogs.py one_hz,city 0 49

(``jump_false_alarms_analogs.txt``: the three runs' lines, two cores.)

The analogs of ``tests/_held_out_drives.py`` have no heading step. Each line: the analog and seed, then per
8-state kind its median / max at the ends of the 20 outages of 30 s (``filterwnn study dr --drive FILE --grade
phone``'s placement and settings, the default filter: the same numbers as ``run_gps_scale.py analogs
--windows 0``), and the steps its heading-jump detector found (``heading_jumps``: the step at which it found
each, the onset, the estimate and the z-score). Every one found is a false alarm, or a heading bias the
filter held that far off.
"""

import os
import sys
import tempfile
import warnings

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests"))

import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

KINDS = ("EKF-8", "UKF-8", "SUKF-8")


def main(names, first, last):
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            for seed in range(first, last + 1):
                run = read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), held_out.columns(name, seed)))
                cells = []
                for kind in KINDS:
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        res = real_drive_outages(run, filters=(kind,), use_gps_sigma=True, grade="phone")
                    e, jumps = res[kind], res["integrity"][kind]["heading_jumps"]
                    found = "".join(f" [step {s} from {o}: {np.degrees(t):+.2f} deg, z {z:+.2f}]" for s, o, t, z in jumps)
                    cells.append(f"{kind} {np.median(e):.2f} / {e.max():.2f}, found {len(jumps)}"
                                 + found)
                print(f"{name} seed {seed} | " + " | ".join(cells), flush=True)


if __name__ == "__main__":
    main(sys.argv[1].split(","), int(sys.argv[2]), int(sys.argv[3]))
