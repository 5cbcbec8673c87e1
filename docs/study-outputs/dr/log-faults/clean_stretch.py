"""GNSS fixes far cleaner than a drive's others also follow the odometer (stop 63): 120 s (300-420 s) of the analogs'
fixes (seed 0) replaced by the truth, 1 m off, with 0.3, 0.1 or 0.03 m of white noise per axis, their sigma changing
(0.8-1.2 m, to the cm) or held at 1 m, written with it as ``gps_sigma`` or without a sigma column. Per case, what
the reader's ``receiver_dead_reckoning`` says: nothing, the runs as dead reckoning (``drop``), or as either cause
(``either``). Run from the repository root::

    python docs/study-outputs/dr/log-faults/clean_stretch.py > docs/study-outputs/dr/log-faults/clean_stretch.txt
"""
import os, sys, tempfile, warnings
import numpy as np
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import at_hand  # noqa: F401  (puts tests/ on the path)
import _held_out_drives as held_out
from filterwnn.navigation.drives import read_drive_csv

rng = np.random.default_rng(1)
with tempfile.TemporaryDirectory() as tmp:
    for name in ("phone", "one_hz", "city"):
        for noise in (0.3, 0.1, 0.03):
            for sigma in ("changing", "held"):
                cols = {k: v.copy() for k, v in held_out.columns(name, 0).items()}
                t, fix = cols["time"], np.isfinite(cols["gps_east"])
                clean = fix & (t >= 300.0) & (t <= 420.0)
                k = int(clean.sum())
                cols["gps_east"][clean] = cols["true_east"][clean] + 1.0 + rng.normal(0.0, noise, k)
                cols["gps_north"][clean] = cols["true_north"][clean] + 1.0 + rng.normal(0.0, noise, k)
                cols["gps_sigma"][clean] = np.round(rng.uniform(0.8, 1.2, k), 2) if sigma == "changing" else 1.0
                for accuracy in ("gps_sigma", None):
                    if accuracy is None and sigma == "held":
                        continue  # (without the column the sigma is not read)
                    with warnings.catch_warnings(record=True) as caught:
                        warnings.simplefilter("always")
                        read_drive_csv(held_out.write_csv(os.path.join(tmp, "d.csv"), cols, accuracy=accuracy))
                    said = [str(w.message) for w in caught if "as the odometer does" in str(w.message)]
                    what = ("nothing" if not said else "either" if "either a receiver's" in said[0] else "drop")
                    runs = said[0].split(" run(s)")[0].split(" in ")[-1] + " run(s), " if said else ""
                    print(f"{name} noise {noise:g} m, sigma {sigma if accuracy else 'none'}: {what}"
                          + (f" ({runs}{said[0].split('plausibility: ')[1].split(' fixes')[0]} fixes)" if said else ""),
                          flush=True)
