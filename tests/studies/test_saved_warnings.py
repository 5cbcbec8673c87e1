"""A drive's saved table keeps what the run warned of: the drive reader's warnings and the filters' (folded), under
the numbers they bear on, while the terminal shows them as before (``filterwnn._warnings.kept_warnings``)."""

import csv
import warnings

import pytest

from filterwnn._warnings import kept_warnings
from filterwnn.cli import main
from filterwnn.navigation.drives import sample_drive_path


def _say(text):
    warnings.warn(text, RuntimeWarning)  # one place in this module, as a library's warning comes from one line


def test_kept_warnings_keep_every_text_and_leave_the_showing_to_the_filters_outside():
    kept = []
    with pytest.warns(RuntimeWarning) as shown:
        with kept_warnings(kept):
            _say("the fixes   read\n0.2 s late")
            _say("a second kind")
    assert kept == ["the fixes read 0.2 s late", "a second kind"]  # one line each
    assert [str(w.message) for w in shown] == ["the fixes   read\n0.2 s late", "a second kind"]
    assert all(w.filename == __file__ for w in shown)  # issued again from where they were given
    kept = []
    with warnings.catch_warnings(record=True) as shown:
        warnings.simplefilter("ignore")  # ignored outside: kept all the same, shown not
        with kept_warnings(kept):
            _say("ignored")
    assert kept == ["ignored"] and shown == []
    kept = []
    with warnings.catch_warnings(record=True) as shown:
        warnings.simplefilter("ignore")
        warnings.filterwarnings("always", module=__name__)  # the filters that name a module still find it
        with kept_warnings(kept):
            _say("by module")
    assert [str(w.message) for w in shown] == ["by module"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # -W error still raises, once the block has ended
        with pytest.raises(RuntimeWarning, match="^raised$"):
            with kept_warnings(kept := []):
                _say("raised")
                done = True
    assert done and kept == ["raised"]


def test_a_refusal_inside_the_block_leaves_its_warnings_shown_and_kept():
    kept = []
    with pytest.warns(RuntimeWarning, match="given before the refusal"):
        with pytest.raises(ValueError, match="refused"):
            with kept_warnings(kept):
                _say("given before the refusal")
                raise ValueError("refused")
    assert kept == ["given before the refusal"]


def _scaled_sample(path, factor):
    """The shipped sample drive with its speed column times ``factor`` (a speedometer reading high)."""
    with open(sample_drive_path(), newline="") as fh:
        rows = list(csv.reader(fh))
    i = rows[0].index("speed")
    for r in rows[1:]:
        r[i] = repr(float(r[i]) * factor)
    with open(path, "w", newline="") as fh:
        csv.writer(fh).writerows(rows)
    return path


def test_the_drive_table_saves_the_readers_and_the_filters_warnings(tmp_path, capsys):
    drive = _scaled_sample(tmp_path / "speedo.csv", 1.10)
    argv = ["study", "dr", "--drive", str(drive), "--filters", "DR-mech,EKF-8", "--outages", "5", "--out",
            str(tmp_path / "out"), "--no-figures", "--no-progress"]
    with warnings.catch_warnings():
        warnings.simplefilter("default")
        assert main(argv) == 0
    out, err = capsys.readouterr()
    printed = [line[len("filterwnn: warning: "):] for line in err.splitlines() if line.startswith("filterwnn: warning: ")]
    assert "| EKF-8 |" in out and "Warnings" not in out  # the table printed alone: the terminal has them above
    saved = (tmp_path / "out" / "real_drive_speedo_outage_errors.md").read_text()
    table, _, told = saved.partition("\n\nWarnings given while the drive was read:\n\n")
    assert "| EKF-8 |" in table and "Warnings" not in table
    read, _, ran = told.partition("\n\nWarnings given while the filters ran (each filter's repeats folded into one "
                                  "line):\n\n")
    read, ran = read.splitlines(), ran.splitlines()
    assert len(read) == 1 and read[0].startswith("- plausibility: ") and "--speed-scale 1.1" in read[0]
    assert ran and all(line.startswith("- EKF-8: ") for line in ran)
    assert any("odometer scale state ran past 3 sigma" in line for line in ran)
    assert printed == [line[2:] for line in read + ran]  # the terminal's lines, in its order, one for one


def test_a_drive_that_warns_of_nothing_saves_its_table_alone(tmp_path):
    # the sample's sensors as they were made (make_sample_drive.py: a heading of 1 degree of white noise, an
    # odometer of 0.02 m a sample; the phone grade's 0.5 degree and 0.01 m are warned of)
    argv = ["study", "dr", "--drive", "sample", "--filters", "DR-mech,EKF-8", "--outages", "3", "--out",
            str(tmp_path), "--no-figures", "--no-progress", "--heading-noise", "1", "--odometer-noise", "0.02"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the sample warns of nothing
        assert main(argv) == 0
    assert "Warnings" not in (tmp_path / "real_drive_sample_drive_outage_errors.md").read_text()
