"""``ringcontact calibrate [--check]`` (reports.cli.calibrate) on the committed datasets."""
from __future__ import annotations

import pytest

from contact import calibrate as cal
from reports.cli.calibrate import main


def test_calibrate_cli_check_and_errors(tmp_path, capsys):
    assert main(["--check"]) == 0
    assert "up to date" in capsys.readouterr().out
    assert main(["--check", "--out", str(tmp_path)]) == 1          # nothing stored there: drift reported
    assert "not found" in capsys.readouterr().out
    with pytest.raises(SystemExit) as exc:
        main(["--dataset", str(tmp_path / "missing.json")])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "--dataset = " in err and "no such file" in err
    # writing into a fresh directory gives the same files as the committed ones
    assert main(["--out", str(tmp_path)]) == 0
    for name in cal.available():
        assert (tmp_path / f"{name}.json").exists()
    assert cal.check_calibrations(directory=tmp_path) == []
