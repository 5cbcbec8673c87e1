"""The fixes' latency and the gyro's scale error told once, when a drive ends (stop 62).

The monitor tests the fixes' latency at every fix, against a gate (``LATENCY_Z``, 6.1) that keeps its false alarms
rarer than one fix's. A latency only a whole drive shows stays under it: an OBD-II user's phone app stamped each fix
when it arrived (0.15-0.40 s late), the monitor ended at z 4.4 with an estimate of 0.18 s, and nothing was said
(EKF-8 6.80 / 17.53 m; rerun with ``--gps-latency 0.18``, 5.80 / 13.11). ``GPSDRFilter.end_of_drive`` (which
``batch_filter`` calls) tests it once more against ``LATENCY_END_Z``.
"""

import os
import sys
import warnings

import numpy as np
import pytest

from filterwnn.navigation.dead_reckoning import GPSDRModel
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation.gpsdr import LATENCY_END_Z, LATENCY_Z, SCALE_END_Z, SCALE_ERROR_Z, GPSDRFilter

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import _held_out_drives as held_out  # noqa: E402


def _run(tmp_path, latency, grade="phone", about="the fixes' latency", **kw):
    """The phone analog (seed 0) with its fixes ``latency`` s late (and ``kw`` to its generator), through the grade's
    EKF-8: the filter and its warnings ``about`` that."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(held_out.write_csv(tmp_path / "d.csv",
                                                held_out.columns("phone", 0, gps_latency=latency, **kw)))
    model = GPSDRModel.from_grade(grade, run.scenario.dt)
    f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
    return f, [str(w.message) for w in record if about in str(w.message)]


def test_a_latency_only_the_whole_drive_shows_is_told_when_it_ends(tmp_path):
    """Fixes 0.3 s late on the phone analog: under the test at every fix, past the end's gate; one warning, with the
    estimate and the setting to rerun with, and no state added."""
    f, said = _run(tmp_path, 0.3)
    assert f.latency_added is None and LATENCY_END_Z < f.latency_z < LATENCY_Z
    assert f.latency_at_end == pytest.approx(f.latency_estimate) and 0.2 < f.latency_at_end < 0.5
    assert len(said) == 1 and "over the whole drive" in said[0], said
    assert f"--gps-latency {f.latency_at_end:.2f}" in said[0]
    with warnings.catch_warnings(record=True) as again:
        warnings.simplefilter("always")
        assert f.end_of_drive() == {"latency": f.latency_at_end, "gyro_scale": None}
    assert not again  # told once: called again, it says no more


def test_a_scale_error_only_the_whole_drive_shows_is_told_when_it_ends(tmp_path):
    """The phone analog's gyro turning 0.7 % more than the car: under the scale monitor's test at every fix, past the
    end's gate; one warning, with the estimate and the scale state from the start to rerun with."""
    f, said = _run(tmp_path, 0.0, about="the gyro's scale", gyro_scale=0.007)
    assert f.gyro_scale_added is None and SCALE_END_Z < f.gyro_scale_z < SCALE_ERROR_Z
    assert f.gyro_scale_at_end == pytest.approx(f.gyro_scale_estimate) and 0.005 < f.gyro_scale_at_end < 0.02
    assert len(said) == 1 and "over the whole drive" in said[0] and "--gyro-scale-sd 0.01" in said[0], said
    assert f.latency_at_end is None


def test_honest_fixes_are_not_told_late(tmp_path):
    """The same drive with its fixes on time and its gyro's scale right: no word of a latency or a scale error, at
    any fix or at the end."""
    f, said = _run(tmp_path, 0.0, about="GPSDRFilter, the")
    assert f.latency_at_end is None and f.gyro_scale_at_end is None and not said, said


def test_the_drive_table_says_what_was_told_at_the_end():
    """``filterwnn study dr``'s line under its table for a filter that told the latency at the drive's end."""
    from filterwnn.studies.dr._real import _states_added

    said = _states_added({"latency_at_end": 0.367})
    assert said == "the fixes +0.37 s late over the whole drive (told at its end; rerun with --gps-latency 0.37)"
    assert _states_added({"latency_at_end": None}) == ""
    assert _states_added({"gyro_scale_at_end": 0.0164}) == ("the gyro turning +1.64 % more than the car over the whole "
                                                           "drive (told at its end; rerun with --gyro-scale-sd 0.01)")


def test_the_studys_pass_over_the_drive_makes_the_end_tests():
    """``filterwnn study dr``'s pass with every fix (``_outage_ends``) calls ``end_of_drive`` once, after its last step
    and before the outages, so that its warning and the table's line come from the whole drive."""
    from filterwnn.navigation.scenarios import Scenario, simulate_scenario
    from filterwnn.studies.dr._real import _outage_ends

    run = simulate_scenario(Scenario(name="short", duration=20.0, speed=10.0, gps_rate=1.0), rng=0)
    calls = []

    class Recorder:
        x = np.zeros(8)

        def predict(self):
            calls.append("predict")

        def update(self, *args):
            calls.append("update")

        def end_of_drive(self):
            calls.append("end")

    _outage_ends(Recorder(), "EKF-8", run, [], [], [], run.gps_list(), [None] * len(run.t))
    assert calls.count("end") == 1 and calls[-1] == "end" and calls.count("update") == len(run.t)


def test_fixes_that_read_early_beside_a_late_speed_name_the_speeds_remedy_first(tmp_path):
    """A speed stamped 0.7 s late (the 1 Hz analog's generator on ``default_rng(1)``) reads to the fixes as fixes
    stamped early: the monitor tells the speed's latency and finds the fixes -0.36 s late, adding that state (both at step 313; the command's pass
    tells the speed at step 311, the fixes at 407). The later warning now names the speed's remedy first, which alone
    took the command's EKF-8 from 6.80 / 15.37 m at the outage ends to 1.52 / 6.45 (the fixes' remedy alone 7.44 /
    11.71, both 1.53 / 6.56: ``log-faults/speed_late_fixes_early.txt``, stop 64)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(held_out.write_csv(
            tmp_path / "d.csv", held_out.HELD_OUT["one_hz"](np.random.default_rng(1), odometer_latency=0.7)))
    model = GPSDRModel.from_grade("phone", run.scenario.dt)
    f = GPSDRFilter(model, "ekf", x0=np.r_[run.x0, model.x0[6:]])
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        f.batch_filter(run.z_dr, run.gps_list(), run.gps_sigma_list(), run.gps_offset_list())
    said = {topic: [str(w.message) for w in record if topic in str(w.message)]
            for topic in ("the fixes' latency", "the speed's latency")}
    assert f.latency_added is not None and f.odometer_latency_estimate > 0.3 and f.latency_estimate < 0
    assert [len(v) for v in said.values()] == [1, 1], said
    # told in one step here (the command's pass, the speed's first: step 311, the fixes' at 407): the later one says
    assert "a speed stamped late reads as fixes stamped early" in said["the speed's latency"][0], said
    assert "--odometer-latency 0.6" in said["the speed's latency"][0] and "this remedy first" in said["the speed's latency"][0]


def test_the_end_does_not_tell_fixes_early_beside_a_speed_told_late():
    """Where the speed's latency was told, fixes that read early at the drive's end are its doing: not told (a random
    drive with the speed 0.43 s late was told -0.10 s at the end, and the rerun it named was worse: stop 64). Fixes
    that read late beside it, or early with no speed told, are told as before."""
    model = GPSDRModel.from_grade("phone", 0.1)

    def ended(fixes, speed, speed_told):
        f = GPSDRFilter(model, "ekf", x0=np.r_[np.zeros(6), model.x0[6:]])
        f.latency_estimate, f.latency_z = fixes, 5.0 * np.sign(fixes)
        f.odometer_latency_estimate, f.odometer_latency_z = speed, 9.0 * np.sign(speed)
        if speed_told:
            f._warned_errors.add("odometer_latency")
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            told = f.end_of_drive()["latency"]
        return told, [str(w.message) for w in record]

    assert ended(-0.2, 0.4, True) == (None, [])
    for fixes, speed, speed_told in ((-0.2, 0.4, False), (0.2, 0.4, True), (-0.2, -0.4, True)):
        told, said = ended(fixes, speed, speed_told)
        assert told == fixes and len(said) == 1 and "over the whole drive" in said[0]
