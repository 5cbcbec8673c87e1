"""A variant not adopted (stop 56), by monkeypatch: the correlation that cuts a fix's calibration gain
(``GPSDRFilter._gain_weights``) measured before the fix enters the whiteness window (``"before"``), or the larger of
the two (``"max"``), in place of the one measured with it (the shipped filter, ``None``). Imported by
``correlation_variant.py``; ``MODE["m"]`` picks the variant."""
import filterwnn.navigation.gpsdr as g

_orig_check, _orig_gain = g.GPSDRFilter._check_fix, g.GPSDRFilter._gain_weights
MODE = {"m": None}


def _check(self, *a, **k):
    self._c_before = self.gps_correlation
    return _orig_check(self, *a, **k)


def _gain(self, gps):
    if MODE["m"] is None or not gps or getattr(self, "_c_before", None) is None:
        return _orig_gain(self, gps)
    after = self.gps_correlation
    self.gps_correlation = self._c_before if MODE["m"] == "before" else max(after, self._c_before)
    try:
        return _orig_gain(self, gps)
    finally:
        self.gps_correlation = after


g.GPSDRFilter._check_fix, g.GPSDRFilter._gain_weights = _check, _gain
