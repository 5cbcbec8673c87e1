"""Where a city analog's worst outage starts: the EKF-8's error when it starts against when it ends (stop 57).

    python docs/study-outputs/dr/analog-seeds/worst_outage_start.py 61 62 65 66 > worst_outage_start_61_66.txt

Each seed's city analog (``tests/_held_out_drives.py``), read and scored as ``filterwnn study dr --drive FILE
--grade phone`` does (20 outages of 30 s, every fix with its reported sigma): the median / max at the outage ends,
the worst outage's error at its start and its end, the medians over the outages of the error at the start and of
its growth, and dead reckoning's from the true start over that worst outage.
"""
import pathlib
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[4] / "tests"))
import _held_out_drives as held_out  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

warnings.simplefilter("ignore")
for seed in [int(a) for a in sys.argv[1:]]:
    with tempfile.TemporaryDirectory() as d:
        run = read_drive_csv(held_out.write_csv(pathlib.Path(d) / "c.csv", held_out.columns("city", seed)))
        res = real_drive_outages(run, filters=("DR-mech", "EKF-8"), grade="phone", use_gps_sigma=True)
    e, s = np.asarray(res["EKF-8"]), np.asarray(res["start_err"]["EKF-8"])
    i = int(np.argmax(e))
    print(f"city {seed}: EKF-8 {np.median(e):.2f} / {e.max():.2f}; worst outage {i + 1}: start {s[i]:.2f} m, end "
          f"{e[i]:.2f}; median start over outages {np.median(s):.2f}, median growth {np.median(e - s):.2f}; DR-mech "
          f"worst-outage end {np.asarray(res['DR-mech'])[i]:.2f}", flush=True)
