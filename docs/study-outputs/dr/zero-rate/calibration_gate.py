"""The calibration's speed gate, moved in memory (issue 23; stops 35 and 66; nothing here is used by the package).

``GPSDRFilter`` lets the odometer scale, the heading bias and the rate bias learn from an accepted fix only while
``motion == "moving"`` (at ``low_speed``, 5 m/s, or more). :func:`patch` makes them learn at ``GATE[0]`` m/s or
more instead (never standing), the DR sample's form still decided by ``low_speed``: ``classify`` keeps each sample's
speed, and ``_held_rows`` reads it. Used by ``calibration_speed_lead.py`` (here) and
``../analog-seeds/calibration_speed_variant.py``.
"""
import numpy as np

from filterwnn.navigation import gpsdr

#: The speed (m/s) from which the calibration learns; a list, so a script may move it between runs.
GATE = [gpsdr.LOW_SPEED]
_classify = gpsdr.GPSDRFilter.classify


def _classify_keeping_speed(self, z_dr):
    self._speed = float(z_dr[1]) / self.model.dt
    return _classify(self, z_dr)


def _held_rows(self, gps):
    if not gps:
        return self.held_states if self.hold_without_gps else np.zeros(0, dtype=int)
    if not self._cal.size:
        return self._cal
    observable = self.motion != "still" and self._speed >= GATE[0] and self.fix_status == "accepted"
    return np.zeros(0, dtype=int) if observable else self._cal


def patch(min_speed=None):
    """Patch ``GPSDRFilter`` in this process; ``min_speed`` sets ``GATE[0]`` (default: leave it)."""
    if min_speed is not None:
        GATE[0] = float(min_speed)
    gpsdr.GPSDRFilter.classify = _classify_keeping_speed
    gpsdr.GPSDRFilter._held_rows = _held_rows
