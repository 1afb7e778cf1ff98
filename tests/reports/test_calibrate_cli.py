"""``ringcontact calibrate [--check]`` (reports.cli.calibrate) on the committed datasets."""
from __future__ import annotations

from contact import calibrate as cal
from reports.cli.calibrate import main


def test_calibrate_cli_check_and_errors(tmp_path, capsys):
    assert main(["--check"]) == 0
    assert "up to date" in capsys.readouterr().out
    assert main(["--check", "--out", str(tmp_path)]) == 1          # nothing stored there: drift reported
    assert "not found" in capsys.readouterr().out
    assert main(["--dataset", str(tmp_path / "missing.json")]) == 2
    assert "cannot read reference dataset" in capsys.readouterr().err
    # writing into a fresh directory gives the same files as the committed ones
    assert main(["--out", str(tmp_path)]) == 0
    for name in cal.available():
        assert (tmp_path / f"{name}.json").exists()
    assert cal.check_calibrations(directory=tmp_path) == []
