"""Where the reader's warning of an accuracy in metres given as ``gps_hdop`` (stop 62, ``hdop_as_metres``) fires on the
drives at hand (``at_hand.py``: the analogs' seeds 0-9, the random drives of protocols 2 and 3, seeds 0-29 and
200-279), each written twice with its accuracy in the ``gps_hdop`` column and read at the phone grade's 5 m at HDOP 1:
its HDOP (the sigma over 5 m rounded to 0.1 as GGA writes it, at least 0.5: must not warn) and a phone's 68 % radius
(1.51 times the sigma, rounded to 0.1 m: should warn). Per drive: the median HDOP and the ratio of the sigma it gives
to the fixes' scatter (``_fix_scatter``), then whether each warned. Run from the repository root::

    python docs/study-outputs/dr/log-faults/hdop_as_metres.py > docs/study-outputs/dr/log-faults/hdop_as_metres.txt
"""
import os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import drives_at_hand, held_out
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation._plausibility import _fix_scatter


def read(path):
    """The run and whether the reader warned of an accuracy in metres; a refusal: None and its first words."""
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        try:
            run = read_drive_csv(path, hdop_sigma=5.0)
        except ValueError as e:
            return None, "refused: " + str(e).split(": ", 1)[1][:150]
    return run, any("gps_hdop has a median" in str(w.message) for w in record)


def ratio(run):
    if run is None:
        return float("nan")
    heading = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]]
    found = _fix_scatter(heading, run.z_dr[:, 1], run.gps_steps, run.z_gps)
    return float("nan") if found is None else float(np.median(run.gps_sigma)) / max(found[0], 1.0)


n, false_alarms, missed, ratios = 0, [], [], []
with tempfile.TemporaryDirectory() as tmp:
    for key, make in drives_at_hand().items():
        cols = make()
        s = cols["gps_sigma"]
        path = os.path.join(tmp, "d.csv")
        hdop = dict(cols, gps_sigma=np.where(np.isnan(s), np.nan, np.maximum(0.5, np.round(s / 5.0, 1))))
        run, warned = read(held_out.write_csv(path, hdop, accuracy="gps_hdop"))
        r = ratio(run)
        radius = dict(cols, gps_sigma=np.round(1.51 * s, 1))
        run68, warned68 = read(held_out.write_csv(path, radius, accuracy="gps_hdop"))
        r68 = ratio(run68)
        n += 1
        ratios.append(r)
        false_alarms += [key] if warned is not False else []
        missed += [] if warned68 is True else [key]
        med = float("nan") if run is None else np.median(run.gps_sigma) / 5
        med68 = np.median(np.round(1.51 * s[~np.isnan(s)], 1))
        print(f"{key:10s} HDOP median {med:4.2f} ratio {r:5.2f} warned {warned} | "
              f"68 % radius: median {med68:5.2f} ratio {r68:5.2f} warned {warned68}", flush=True)
print(f"{n} drives; HDOP warned or refused on {len(false_alarms)} {false_alarms}; 68 % radius not warned on {len(missed)} "
      f"{missed}; "
      f"largest HDOP ratio {np.nanmax(ratios):.2f}")
