"""Why 0.5 degree heading steps still end phone seed 0 38 m off: the heading bias's gain cut by the correlation
its own error makes (issue 23, stop 45; an experiment, not the filter's code).

Run from the repository root, one BLAS thread (``steps`` or ``analogs``)::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/calibration_gain.py steps > docs/study-outputs/dr/log-faults/calibration_gain_steps.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/calibration_gain.py analogs > docs/study-outputs/dr/log-faults/calibration_gain_analogs.txt
    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/calibration_gain.py analogs 10 30 innovations,default   # and 30 50: calibration_gain_analogs_10_49.txt

With ``correlated_fixes="calibration"`` (the default) the heading bias and the gyro rate bias keep
``1 / gps_correlation`` of their gain, ``gps_correlation`` the integrated autocorrelation time of the accepted
fixes' whitened innovations. A heading bias that is wrong by more than its standard deviation also makes the
innovations correlated (the car drifts sideways, fix after fix), so the gain that would correct it is cut, and
the error stays. Three variants, each set at run time:

* ``innovations`` (the filter before stop 45; ``calibration_error_z=None``): always ``gps_correlation``;
* ``residual always`` (the experiment, patched in): for those two states, the correlation of the innovations
  less what the consistency monitor's errors explain (its nuisance parameters include every calibration
  state's error: ``GPSDRFilter._residual_correlation``) whenever it is smaller;
* ``default`` (stop 45's filter): the residual correlation only while the monitor finds the heading bias or
  the rate bias off (``calibration_error_z``, 3.29).

``steps``: the phone analog, seed 0, exact stops, with the 0.5 degree steps of ``heading_step.py``; per variant,
EKF-8's 20 outage ends (m), their median / max, and every 600th sample the heading bias state against the
measured heading's true offset from the car's course (deg), with ``gps_correlation`` and the mean NIS of
the last 30 fixes. ``analogs [FIRST END [VARIANTS]]``: the three analogs, seeds 0-9 (or ``FIRST`` to ``END - 1``),
EKF-8 median / max per variant (every one, or those named, comma-separated).
"""

import os
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "..", "tests"))
sys.path.insert(0, HERE)

import _held_out_drives as held_out  # noqa: E402
import filterwnn.navigation.gpsdr as gpsdr  # noqa: E402
import heading_step  # noqa: E402
from filterwnn.navigation.drives import read_drive_csv  # noqa: E402
from filterwnn.studies.dr import real_drive_outages  # noqa: E402

DEFAULT = gpsdr.GPSDRFilter._gain_weights
INIT = gpsdr.GPSDRFilter.__init__


def residual_gain_weights(self, gps):
    """The experiment: the heading bias's and rate bias's share of the gain from the monitor's residual correlation."""
    saved = self.gps_correlation
    if self._residual_c is not None and self._theta is not None:
        self.gps_correlation = max(min(saved, self._residual_c), 1.0)
    try:
        return DEFAULT(self, gps)
    finally:
        self.gps_correlation = saved


def without_monitor_gate(self, *a, **k):
    INIT(self, *a, **k)
    self.calibration_error_z = None


#: label: (the gain weights, the constructor)
VARIANTS = {"innovations": (DEFAULT, without_monitor_gate), "residual always": (residual_gain_weights, without_monitor_gate),
            "default": (DEFAULT, INIT)}


def use(variant):
    gpsdr.GPSDRFilter._gain_weights, gpsdr.GPSDRFilter.__init__ = VARIANTS[variant]


def restore():
    gpsdr.GPSDRFilter._gain_weights, gpsdr.GPSDRFilter.__init__ = DEFAULT, INIT


def score(cols, tmp, trace=None):
    path = held_out.write_csv(os.path.join(tmp, "d.csv"), cols)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return real_drive_outages(read_drive_csv(path), filters=("EKF-8",), use_gps_sigma=True, grade="phone")["EKF-8"]


def steps(tmp):
    cols = {k: np.asarray(v, dtype=float) for k, v in held_out.columns("phone", 0, exact_stops=True).items()}
    c = heading_step.stepped(cols, 0.5, 0)
    # the measured heading's true offset from the car's course, where the car moves
    de, dn = np.diff(c["true_east"]), np.diff(c["true_north"])
    offset = np.degrees(np.angle(np.exp(1j * (c["heading"][1:] - np.arctan2(de, dn)))))
    moving = np.hypot(de, dn) / (c["time"][1] - c["time"][0]) > 1.0
    update = gpsdr.GPSDRFilter.update
    for name in VARIANTS:
        seen = []

        def spy(self, *a, **k):
            out = update(self, *a, **k)
            if self.step % 600 == 0 and len(seen) < 15:
                seen.append((self.step, np.degrees(self.x[gpsdr.HEADING_BIAS]),
                             np.degrees(np.sqrt(self.P[gpsdr.HEADING_BIAS, gpsdr.HEADING_BIAS])),
                             self.gps_correlation, float(np.mean(self.nis_accepted[-30:])) if self.nis_accepted else 0.0))
            return out

        use(name)
        gpsdr.GPSDRFilter.update = spy
        try:
            e = score(c, tmp)
        finally:
            restore()
            gpsdr.GPSDRFilter.update = update
        print(f"{name}: EKF-8 {np.median(e):.2f} / {e.max():.2f} | outage ends {' '.join(f'{v:.1f}' for v in e)}")
        for step, hb, sd, corr, nis in seen[1:]:
            true = f"{offset[step - 1]:+.2f}" if moving[step - 1] else "(standing)"
            print(f"    step {step}: heading bias {hb:+.2f} +- {sd:.2f}, true offset {true}, gps_correlation "
                  f"{corr:.2f}, mean NIS {nis:.2f}")


def analogs(tmp, first="0", end="10", variants=None):
    for name in ("phone", "city", "one_hz"):
        for seed in range(int(first), int(end)):
            cols = held_out.columns(name, seed)
            cells = []
            for label in (variants.split(",") if variants else VARIANTS):
                use(label)
                try:
                    e = score(cols, tmp)
                finally:
                    restore()
                cells.append(f"{label} {np.median(e):.2f} / {e.max():.2f}")
            print(f"{name} seed {seed} | EKF-8 " + " | ".join(cells), flush=True)


if __name__ == "__main__":
    with tempfile.TemporaryDirectory() as tmp:
        {"steps": steps, "analogs": analogs}[sys.argv[1]](tmp, *sys.argv[2:])
