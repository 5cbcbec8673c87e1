"""A heading (or an odometer) noisier than its grade: what it cost, and the DR noise estimated online (stop 68).

    python docs/study-outputs/dr/dr-noise/dr_noise.py > docs/study-outputs/dr/dr-noise/dr_noise.txt

A. The plainest drive: 120 s, standing 5 s, pulling away to 12 m/s by 15 s on a straight road, 3 m fixes at 1 Hz, a
   heading of 1 degree of white noise and an odometer of 0.02 m a sample (``Scenario``'s defaults), ten seeds; three
   outages of 30 s (from rest at 0 s, then at 44.5 and 89 s at 12 m/s). The EKF-8's median end error per outage over
   the seeds, with the estimate off (``dr_noise_window=0``, the filter before stop 68) and on (the default), for the
   survey grade (0.2 degrees, 1.5 m fixes), the phone grade (0.5 degrees, 0.01 m, 5 m fixes), the survey grade
   with the drive's 3 m fixes (only the heading off) and a grade that fits (that, with 1 degree).
B. The shipped sample (its heading 1 degree, its odometer 0.02 m), ``filterwnn study dr --drive sample``'s outages:
   median / max per 8-state kind, both grades, off and on.
C. Where the sensors are as their grade says or better: the windows' median NIS ratio (the statistic that raises
   the noise past ``DR_NOISE_RAISE`` = 2) over the whole drive with its fixes, the EKF-8, on the three simulated
   analogs of issue 23's drives (seeds 0-2, phone grade), onavdata's two drives (survey grade) and the sample.
"""

import os
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "..", "tests"))

import _held_out_drives as H  # noqa: E402

from filterwnn.navigation import gpsdr  # noqa: E402
from filterwnn.navigation.dead_reckoning import SENSOR_GRADES  # noqa: E402
from filterwnn.navigation.drives import CAR_DRIVES, load_car_drive, read_drive_csv, sample_drive_path  # noqa: E402
from filterwnn.navigation.scenarios import Scenario, simulate_scenario  # noqa: E402
from filterwnn.studies.dr import _real, real_drive_outages  # noqa: E402

warnings.simplefilter("ignore")
GRADES = {"survey": "survey", "phone": "phone", "survey, 3 m fixes": dict(SENSOR_GRADES["survey"], gps_sigma_m=3.0),
          "fits (survey, 3 m, 1 deg)": dict(SENSOR_GRADES["survey"], gps_sigma_m=3.0, heading_noise_deg=1.0)}
STARTS = [0.0, 44.5, 89.0]


def plain(seed):
    return simulate_scenario(Scenario(name="plain", duration=120.0, speed=0.0, heading=60.0,
                                      speed_changes=((5.0, 15.0, 12.0),), gps_rate=1.0), rng=seed)


def part_a():
    print("## A. The plainest drive, ten seeds: EKF-8 median end error per outage (m; outages at 0, 44.5, 89 s)\n")
    print("| grade | estimate off | estimate on | heading noise at the end (on; median, deg) |")
    print("|---|---|---|---|")
    runs = [plain(seed) for seed in range(10)]
    dr = np.median([real_drive_outages(r, starts=STARTS, filters=("DR-mech",))["DR-mech"] for r in runs], axis=0)
    for label, grade in GRADES.items():
        cells, noise = [], []
        for window in (0, gpsdr.DR_NOISE_WINDOW):
            ends = []
            for r in runs:
                res = real_drive_outages(r, starts=STARTS, grade=grade, filters=("EKF-8",), dr_noise_window=window)
                ends.append(res["EKF-8"])
                if window:
                    noise.append(res["integrity"]["EKF-8"]["heading_noise_deg"] or np.nan)
            cells.append(" / ".join(f"{v:.2f}" for v in np.median(ends, axis=0)))
        said = f"{np.nanmedian(noise):.2f} ({np.isfinite(noise).sum()} of 10 raised)"
        print(f"| {label} | {cells[0]} | {cells[1]} | {said} |")
    print(f"\nDead reckoning from the true start: {' / '.join(f'{v:.2f}' for v in dr)} m.\n")


def part_b():
    print("## B. The shipped sample, 20 outages of 30 s: median / max (m)\n")
    run = read_drive_csv(sample_drive_path())
    print("| grade | estimate | DR-mech | EKF-8 | UKF-8 | SUKF-8 |")
    print("|---|---|---|---|---|---|")
    for grade in ("phone", "survey"):
        for window in (0, gpsdr.DR_NOISE_WINDOW):
            res = real_drive_outages(run, grade=grade, use_gps_sigma=True, dr_noise_window=window,
                                     filters=("DR-mech", "EKF-8", "UKF-8", "SUKF-8"))
            cells = [f"{np.median(res[k]):.2f} / {np.max(res[k]):.2f}" for k in ("DR-mech", "EKF-8", "UKF-8", "SUKF-8")]
            print(f"| {grade} | {'on' if window else 'off'} | {' | '.join(cells)} |")
    print()


class Probe(gpsdr.GPSDRFilter):
    """The filter, keeping every moving sample's (heading, odometer) NIS that the estimate sees."""

    def _dr_noise(self):
        y, S = np.asarray(self.kf.y, dtype=float), np.asarray(self.kf.S, dtype=float)
        self.__dict__.setdefault("seen", []).append((y[0] ** 2 / S[0, 0], y[1] ** 2 / S[1, 1]))
        super()._dr_noise()


def _ratios(run, grade, use_sigma):
    f = _real._real_drive_filter("EKF-8", run, grade, None, {}, 0, None)
    f.__class__ = Probe
    f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list() if use_sigma else None, run.gps_offset_list())
    seen = np.array(f.__dict__.get("seen", np.zeros((0, 2))))
    w = gpsdr.DR_NOISE_WINDOW
    windows = [np.median(seen[i:i + w], axis=0) / gpsdr._CHI2_1_MEDIAN for i in range(0, len(seen) - w + 1, w)]
    top = np.max(windows, axis=0) if windows else [np.nan, np.nan]
    raised = [s for s in (f.heading_noise_raised, f.odometer_noise_raised)]
    return len(windows), top, raised


def part_c():
    print("## C. The windows' median NIS ratio over a whole drive with its fixes (EKF-8; raised past 2)\n")
    print("| drive | grade | windows | largest heading ratio | largest odometer ratio | raised at (heading, odometer) |")
    print("|---|---|---|---|---|---|")
    drives = []
    for name in ("phone", "city", "one_hz"):
        for seed in range(3):
            path = os.path.join(tempfile.mkdtemp(), f"{name}{seed}.csv")
            H.write_csv(path, H.columns(name, seed))
            drives.append((f"{name} analog seed {seed}", read_drive_csv(path), "phone"))
    for name in CAR_DRIVES:
        drives.append((name, load_car_drive(name), "survey"))
    sample = read_drive_csv(sample_drive_path())
    drives += [("the shipped sample", sample, "phone"), ("the shipped sample", sample, "survey")]
    for label, run, grade in drives:
        n, top, raised = _ratios(run, grade, run.gps_sigma is not None)
        print(f"| {label} | {grade} | {n} | {top[0]:.2f} | {top[1]:.2f} | {raised[0]}, {raised[1]} |")
    print()


if __name__ == "__main__":
    part_a()
    part_b()
    part_c()
