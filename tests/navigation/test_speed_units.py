"""A speed in another unit is named by the unit it is in (stop 65).

The reader measures how many times longer the dead-reckoned track is than the fixes' and names the unit whose
factor that is. It measured the ratio over stretches of a fixed odometer path, which a speed in another unit makes
that many times shorter on the road, so the fixes' noise lengthened them and the ratio read low: on the 250 drives
at hand a speed in ft/s (3.28) was named km/h (3.6) or mph on 222 and never ft/s, one in mph named knots on 56,
one in mm/s or cm/s named no unit (mostly a clock offset between the loggers) on 210 of 500
(``docs/study-outputs/dr/log-faults/speed_units.py``). The ratio is now measured again over stretches that long
on the road (the displacements', which a bend does not lengthen), ft/s is among the units, a second unit that
fits about as well is named beside the first, and a track a unit's factor long is not taken for a clock offset,
which misplaces the stretches but leaves their lengths: ft/s is named first on 244, mph on 247, and no unit on 18
of the 500 in mm/s or cm/s.
"""

import os
import sys

import numpy as np
import pytest

from filterwnn.navigation.drives import read_drive_csv

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _held_out_drives as held_out  # noqa: E402

FT = 1 / 0.3048


def _refusal(tmp_path, name, seed, factor):
    cols = dict(held_out.columns(name, seed))
    cols["speed"] = np.asarray(cols["speed"], dtype=float) * factor
    with pytest.raises(ValueError) as info:
        read_drive_csv(held_out.write_csv(str(tmp_path / "d.csv"), cols))
    return str(info.value).split("(expected", 1)[1]


@pytest.mark.parametrize("name", ["phone", "one_hz"])
def test_a_speed_in_feet_per_second_is_named_so(tmp_path, name):
    cause = _refusal(tmp_path, name, 0, FT)
    said = "speed looks like ft/s (multiply by 0.3048 for m/s, or pass speed_scale=3.281: --speed-scale 3.281)"
    assert said in cause and "km/h" not in cause, cause


@pytest.mark.parametrize("name, factor, unit", [("phone", 3.6, "km/h"), ("one_hz", 3.6, "km/h"),
                                                ("phone", 1 / 0.44704, "mph"), ("one_hz", 1 / 0.514444, "knots")])
def test_a_speed_in_each_unit_names_that_unit_alone(tmp_path, name, factor, unit):
    cause = _refusal(tmp_path, name, 0, factor)
    assert f"speed looks like {unit} (" in cause and "or else" not in cause, cause


@pytest.mark.parametrize("factor, first, other", [(3.6 * 0.955, "km/h", "ft/s"), (FT * 1.03, "ft/s", "km/h"),
                                                  (1 / 0.44704 * 0.935, "mph", "knots")])
def test_a_ratio_between_two_units_names_both_the_nearer_first(tmp_path, factor, first, other):
    # a speed in km/h that reads 4.5 % low is 3.44 times the fixes' distance: as near ft/s (3.28) as km/h
    cause = _refusal(tmp_path, "phone", 0, factor)
    assert f"speed looks like {first} (" in cause and f", or else {other} (" in cause, cause
    assert "the logger's documentation says which" in cause


@pytest.mark.parametrize("factor, unit", [(1000.0, "mm/s"), (100.0, "cm/s")])
@pytest.mark.parametrize("name", ["phone", "city"])
def test_a_speed_a_hundred_or_a_thousand_times_is_not_told_a_clock_offset(tmp_path, name, factor, unit):
    cause = _refusal(tmp_path, name, 0, factor)
    assert f"speed looks like {unit} (" in cause and "clock" not in cause, cause


def test_a_speed_in_knots_that_reads_low_is_read_and_the_warning_names_knots(tmp_path):
    # knots (1.94) reading 10 % low is 1.75 times the fixes' distance, inside the reader's range (0.6-1.8): it is
    # read, and its speed-scale warning named a speed that reads +75 %, which no speedometer does
    cols = dict(held_out.columns("phone", 0))
    cols["speed"] = np.asarray(cols["speed"], dtype=float) / 0.514444 * 0.9
    with pytest.warns(RuntimeWarning, match=r"more than a speed's scale is off: speed looks like knots "
                                            r"\(multiply by 0.514444 for m/s, or pass speed_scale=1.944: "
                                            r"--speed-scale 1.944\); else, if the scale is the sensor's"):
        read_drive_csv(held_out.write_csv(str(tmp_path / "d.csv"), cols))
