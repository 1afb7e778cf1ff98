"""Any user's rotor through `simulate --steady` and `study cascade`: stations come from the scene and
are keyed by its own names (verify-jeffcott: massless shaft, no loose support; a user scene with a
loose support whose stations share no name with the paper's)."""
import json
from pathlib import Path

import pytest

from reports.cli import simulate, study
from rotor.model.assembly import assemble
from rotor.model.scene import load_scene

USER = str(Path(__file__).parent / "scenes" / "user-overhung-loose.toml")


def test_paper_stations_are_the_former_fixed_ones_then_the_bearings():
    """Table 4: the Poincaré section stays on disk1, disk2, 5, s (the studies' numbers do not move)."""
    model = assemble(load_scene("paper-table4"))
    assert model.response_stations(primary_only=True) == ("disk1", "disk2", "5", "s")
    assert model.response_stations() == ("disk1", "disk2", "5", "s", "bearing1", "bearing2")
    user = assemble(load_scene(USER))
    assert user.response_stations() == ("impeller", "rear", "housing", "ball_bearing")


@pytest.mark.parametrize("scene, speed, stations", [
    ("verify-jeffcott", "600", {"d", "bA", "bB"}),
    (USER, "6000", {"impeller", "rear", "housing", "ball_bearing"}),
])
def test_simulate_steady_keys_every_station_by_the_scene_names(tmp_path, capsys, scene, speed, stations):
    rc = simulate.main(["--scene", scene, "--speed-rpm", speed, "--steady", "--revolutions", "4",
                        "--out", str(tmp_path)])
    assert rc == 0, capsys.readouterr().err
    s = json.loads((tmp_path / "simulate-summary.json").read_text())
    amps = s["velocity_amplitudes_mm_s_1X_to_5X"]
    assert {k.rsplit(".", 1)[0] for k in amps} == stations
    first = next(iter(stations - {"bA", "bB", "rear", "housing", "ball_bearing"}))
    assert amps[f"{first}.y"][0] > 0.0                     # the disk moves at 1X
    assert s["compile_s"] >= 0.0 and "run_s" in s


def test_simulate_stations_option_and_unknown_station(tmp_path, capsys):
    rc = simulate.main(["--scene", USER, "--speed-rpm", "6000", "--revolutions", "2", "--stations", "housing",
                        "--out", str(tmp_path)])
    assert rc == 0
    header = (tmp_path / "simulate.csv").read_text().splitlines()[0]
    assert header.startswith("t_s,housing.y_m,housing.z_m,r1_m")
    assert "6000 rpm is beyond scene" in capsys.readouterr().err      # the scene's range is 2 000 rpm: warned
    rc = simulate.main(["--scene", USER, "--speed-rpm", "3000", "--stations", "disk1", "--out", str(tmp_path)])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "disk1" in err[0] and "impeller" in err[0]


@pytest.mark.parametrize("scene, channel", [("verify-jeffcott", "d.y"), (USER, "impeller.y")])
def test_study_cascade_on_any_scene(tmp_path, capsys, scene, channel):
    rc = study.main(["cascade", "--scene", scene, "--rpm-min", "300", "--rpm-max", "900", "--points", "3",
                     "--max-revs", "30", "--workers", "1", "--no-progress", "--out", str(tmp_path)])
    assert rc == 0, capsys.readouterr().err
    rows = (tmp_path / "figures" / "cascade-stations.csv").read_text().splitlines()
    assert len(rows) == 4 and f"{channel}_v1X_mm_s" in rows[0].split(",")
    col = rows[0].split(",").index(f"{channel}_v1X_mm_s")
    assert all(float(r.split(",")[col]) > 0 for r in rows[1:])
