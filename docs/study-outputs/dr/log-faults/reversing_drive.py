"""A 15-minute drive that parks eight times, reversing 12 m into each space while turning 45 degrees, logged
with an unsigned speed (a CAN bus's), as a user would run it (issue 23, stop 52).

Writes the drive CSV (``tests/_held_out_drives.py``'s ``parking_drive``, seed 52: 10 Hz heading and speed, 1 Hz
fixes of 4 m with their sigma, the truth) to ``CSV`` and runs ``filterwnn study dr --drive CSV --grade phone
--no-figures``, with the reversing test (the default), with ``--no-reversing-test``, and on the same drive logged
with a signed speed; prints each command's drive table and what it warned of reversing. Run from the repository
root, one BLAS thread::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/reversing_drive.py /tmp/parking.csv > docs/study-outputs/dr/log-faults/reversing_drive.txt
"""
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..", "tests"))
import _held_out_drives as held_out  # noqa: E402

path = sys.argv[1]
for signed in (False, True):
    held_out.write_csv(path, held_out.parking_drive(np.random.default_rng(52), signed=signed))
    for extra in ([[]] if signed else [[], ["--no-reversing-test"]]):
        with tempfile.TemporaryDirectory() as out:
            cmd = ["filterwnn", "study", "dr", "--drive", path, "--grade", "phone", "--no-figures", "--out", out] + extra
            proc = subprocess.run(cmd, capture_output=True, text=True)
            print(f"## {'signed' if signed else 'unsigned'} speed: {' '.join(['--drive', 'CSV'] + cmd[5:7] + extra)} "
                  f"(exit {proc.returncode})")
            print("\n".join(ln for ln in proc.stdout.splitlines() if ln.startswith("|")))
            print("\n".join(ln[:300] for ln in proc.stderr.splitlines() if "revers" in ln or "forward again" in ln))
            print(flush=True)
