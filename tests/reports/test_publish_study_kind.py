"""``study publish`` given a finished study of another kind (issue 40: ``--cascade <a runup folder>`` ended in
``internal error: KeyError: 'speed_rpm'``): exit 2, one line naming the flag, the folder, the study it holds
(its sweep.json) and the study the flag publishes; nothing written into ``--to``."""
from __future__ import annotations

import pytest

from reports.cli.study import main


@pytest.fixture(scope="module")
def runup(tmp_path_factory):
    out = tmp_path_factory.mktemp("runup") / "run"
    assert main(["runup", "--duration-s", "0.2", "--rpm-start", "600", "--rpm-end", "900", "--out", str(out),
                 "--no-progress"]) == 0
    return out


@pytest.mark.parametrize("flag,need", [("--cascade", "cascade"), ("--notilt", "cascade"), ("--params", "params"),
                                       ("--point", "point"), ("--testrig", "testrig"), ("--map", "map"),
                                       ("--cascade-converged", "cascade"), ("--point-converged", "point")])
def test_a_runup_folder_is_refused_where_another_study_is_published(runup, tmp_path, capsys, flag, need):
    capsys.readouterr()
    assert main(["publish", flag, str(runup), "--to", str(tmp_path / "pub")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "internal error" not in err[0], err
    assert f"{flag} = {runup}: holds a finished 'runup' study" in err[0] and f"a '{need}' study" in err[0], err
    assert not (tmp_path / "pub").exists()
