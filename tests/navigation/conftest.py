"""Fixtures of the navigation tests."""

import pytest


@pytest.fixture
def command_passes(monkeypatch, tmp_path):
    """``passes(name, argv)``: run ``filterwnn study dr --drive sample --no-figures *argv`` with the
    ``filterwnn.studies.dr._cli`` function ``name`` (``read_drive_csv``, ``real_drive_outages``) replaced by
    one that records its keyword arguments and stops the command there; those arguments."""
    import filterwnn.studies.dr._cli as dr_cli
    from filterwnn.cli import main

    class Stop(Exception):
        pass

    def passes(name, argv):
        seen = {}

        def record(*args, **kw):
            seen.update(kw)
            raise Stop  # the command turns it into its one-line error

        with monkeypatch.context() as m:
            m.setattr(dr_cli, name, record)
            try:
                main(["study", "dr", "--drive", "sample", "--out", str(tmp_path), "--no-figures", *argv])
            except (Stop, SystemExit):
                pass
        return seen

    return passes
