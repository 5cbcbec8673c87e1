"""Where the reader's warning of a heading or a speed held or interpolated between the fixes (a receiver's course or
speed given as a dead-reckoning sensor's: ``_plausibility._gps_derived``) fires, on the drives at hand and on other
users' CSVs (stop 64). Per drive and column (speed, heading): the slope test's changes counted while moving, their
share at a fix, and the share of intervals over which the slope held (``-`` where too few), then the warning's
first words where given. Stop 64 made the test read the speed column as given (not each step, a speed times its
stamped interval: seconds since 1970 change every step's last digits) and count no change of slope within a column's
rounding (``GPS_DERIVED_ROUNDING``).

    python docs/study-outputs/dr/log-faults/gps_derived.py 0 > docs/study-outputs/dr/log-faults/gps_derived_0.txt
    python docs/study-outputs/dr/log-faults/gps_derived.py 1 > docs/study-outputs/dr/log-faults/gps_derived_1.txt

``0``/``1``: half the drives at hand each (the tests' drive from rest over seeds 0-19, the analogs' seeds 0-9, the
random drives 0-29 and 200-279 of protocols 2 and 3, the shipped sample and onavdata's two), as the probes read them
(time from 0, values to 4 decimals). ``export 0``/``export 1``: the same drives written as a logger exports them
(time in seconds since 1970 to the millisecond, the speed to 3 decimals and the heading to 2: the rounding the
new tolerance is for). ``files CSV...``: the drive CSVs given (``users_csvs.py`` writes other users' 88); a CSV the
reader refuses is said so.
"""
import csv
import os
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import read_at_hand, scanned  # noqa: E402  (puts tests/ and tests/navigation on the path)
from filterwnn.navigation import _plausibility as pl  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402

EPOCH = 1.7964e9


def exported(path, out):
    """The drive CSV at ``path`` as a logger exports it (see the module docstring), written to ``out``."""
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    head = rows[0]
    fmt = {"time": lambda v: f"{float(v) + EPOCH:.3f}", "speed": lambda v: f"{float(v):.3f}",
           "heading": lambda v: f"{float(v):.2f}"}
    for r in rows[1:]:
        for i, name in enumerate(head):
            if name in fmt and r[i] != "":
                r[i] = fmt[name](r[i])
    with open(out, "w", newline="") as fh:
        csv.writer(fh).writerows(rows)
    return out


class Spy:
    """Records each of the reader's held and slope tests' numbers (changes counted while moving, their share at a
    fix, the share of moving intervals held), whatever its gates, in the order it makes them: the heading's, then the
    speed's (a slope test only where the held one found nothing)."""

    def __init__(self):
        self.seen = []
        self.real = pl._held_at_fixes

    def __call__(self, values, moving, near, least_held=pl.GPS_DERIVED_HELD, tol=1e-9, least_at=pl.GPS_DERIVED_AT_FIX,
                 least=0.0):
        changed = np.abs(np.diff(values)) > np.maximum(tol * (1.0 + np.abs(values[1:])), least)
        n = int(np.sum(changed & moving))
        at = float(np.sum(changed & moving & near)) / max(n, 1)
        kind = "slope" if tol == pl.GPS_DERIVED_SLOPE_TOL else "held"
        self.seen.append(f"{kind} {n} {at:.2f} {1.0 - n / max(int(moving.sum()), 1):.2f}")
        return self.real(values, moving, near, least_held, tol, least_at, least)


def main():
    mode = sys.argv[1]
    drives, keys = scanned(sys.argv[1:])
    fired = []
    with tempfile.TemporaryDirectory() as tmp:
        for key in keys:
            spy = pl._held_at_fixes = Spy()
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                try:
                    obj = drives[key]()
                    if mode == "export" and not hasattr(obj, "z_dr"):
                        src = obj if isinstance(obj, str) else read_at_hand_path(obj, tmp)
                        run = read_drive_csv(exported(src, os.path.join(tmp, "x.csv")))
                    else:
                        run = read_at_hand(obj, tmp)
                except ValueError as exc:
                    print(key, "refused:", str(exc)[:100], flush=True)
                    continue
                finally:
                    pl._held_at_fixes = spy.real
            words = [str(w.message) for w in caught if "where there is a GPS fix" in str(w.message)]
            print(f"{key} fixes {len(run.gps_steps)} tests (changes, at a fix, held): {'; '.join(spy.seen) or '-'}",
                  flush=True)
            if words:
                fired.append(key)
                for w in words:
                    print("   WARNED:", w[:160], flush=True)
    print("DONE", len(keys), "drives; warned:", fired)


def read_at_hand_path(obj, tmp):
    """The CSV path of a drive at hand's columns (:func:`at_hand.read_at_hand` writes them there)."""
    import _held_out_drives as held_out

    return held_out.write_csv(os.path.join(tmp, "d.csv"), obj)


if __name__ == "__main__":
    main()
