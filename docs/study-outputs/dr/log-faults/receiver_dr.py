"""Where the reader's warning of fixes that move along the dead-reckoned track as the odometer does
(``_plausibility.receiver_dead_reckoning``, stop 63) fires on the drives at hand: the tests' drive from rest
(``FROM_REST``) over seeds 0-19, the analogs' seeds 0-9, the random drives 0-29 and 200-279 of protocols 2 and 3, the
shipped sample and both onavdata drives. Per drive: its fixes, the drive's median misfit (m), its longest run of
steps under ``RECEIVER_DR_FRAC`` of it (the warning needs ``RECEIVER_DR_STEPS``), and the warning's words where
given. Half the drives for ``part`` 0, the other half for 1 (two processes). Run from the repository root::

    python docs/study-outputs/dr/log-faults/receiver_dr.py 0 > docs/study-outputs/dr/log-faults/receiver_dr_0.txt
    python docs/study-outputs/dr/log-faults/receiver_dr.py 1 > docs/study-outputs/dr/log-faults/receiver_dr_1.txt

``receiver_dr.py files CSV...`` does the same for the drive CSVs given (other users' logs, which their own
``run.py`` writes: ``receiver_dr_users.txt``); a CSV the reader refuses is said so.
"""
import os, sys, tempfile, warnings
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import read_at_hand, scanned  # puts tests/ and tests/navigation on the path
from filterwnn.navigation import _plausibility as pl

drives, keys = scanned(sys.argv[1:])
fired = []
with tempfile.TemporaryDirectory() as tmp:
    for key in keys:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            try:
                run = read_at_hand(drives[key](), tmp)
            except ValueError as exc:
                print(key, "refused:", str(exc)[:100], flush=True)
                continue
        words = [str(w.message) for w in caught if "as the odometer does" in str(w.message)]
        found = pl._follow_misfits(run.z_dr[:, 1], run.gps_steps, run.z_gps)
        if found is None:
            print(key, "fixes", len(run.gps_steps), "too few moving steps", flush=True)
            continue
        misfit, spread = found
        longest = max((b - a + 1 for a, b in pl._runs(misfit <= pl.RECEIVER_DR_FRAC * spread, 1)), default=0)
        print(f"{key} fixes {len(run.gps_steps)} median misfit {spread:.3g} m longest run {longest}"
              + (f" WARNED: {words[0]}" if words else ""), flush=True)
        if words:
            fired.append(key)
print("DONE", len(keys), "drives; warned:", fired)
