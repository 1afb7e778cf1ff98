"""ringcontact.law gives the numbers of ``ringcontact law``; ringcontact.bearing turns a ring-pair file into a law a
scene can name (slow: FEM)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import ringcontact as rc
from reports.cli import main as cli

ROOT = Path(__file__).resolve().parents[2]


def _cli_points(capsys, *argv) -> list[dict]:
    capsys.readouterr()
    assert cli(["law", *argv, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    return out["points"] if isinstance(out, dict) else out


@pytest.mark.parametrize("name", ["conformal", "pereira", "calibrated:clamped-foundation"])
def test_law_gives_the_numbers_of_ringcontact_law(capsys, name):
    pen_mm, tilt_arcmin = [0.01, 0.02, 0.04], [0.0, 1.0]
    points = _cli_points(capsys, "--law", name, "--penetration-mm", *map(str, pen_mm),
                         "--tilt-arcmin", *map(str, tilt_arcmin))
    p, t = np.meshgrid(np.array(pen_mm) * 1e-3, np.radians(np.array(tilt_arcmin) / 60), indexing="ij")
    r = rc.law(name, p, t)
    by_point = {(round(x["penetration_mm"], 9), round(x["tilt_arcmin"], 9)): x for x in points}
    for i in range(r.force_N.size):
        x = by_point[(round(r.penetration_m[i] * 1e3, 9), round(np.degrees(r.tilt_rad[i]) * 60, 9))]
        assert (r.force_N[i], r.moment_Nm[i], bool(r.in_domain[i])) == pytest.approx(
            (x["force_N"], x["moment_Nm"], not x["outside_domain"]), rel=1e-12), (name, i)
    assert np.all(r.force_N[np.argsort(r.penetration_m)][::2] > 0)
    assert r.plot().get_ylabel() == "radial contact force (kN)"
    import matplotlib.pyplot as plt
    plt.close("all")


def test_a_calibrated_law_refuses_another_geometry():
    with pytest.raises(rc.InputError, match="clearance_mm"):
        rc.law("calibrated:clamped-foundation", 1e-5, clearance_m=1.0e-4)


@pytest.mark.slow
def test_bearing_calibrates_a_law_a_scene_can_name(tmp_path):
    """A small ring-pair file (2D only, four penetrations; the bundled steel-in-aluminium pair renamed) through
    every stage; the law file it writes is the law of a rotor scene's loose support and evaluates as written."""
    text = (ROOT / "fem_reference" / "ring_scenes" / "steel-in-aluminium.toml").read_text(encoding="utf-8")
    text = text.replace('name = "steel-in-aluminium"', 'name = "small-ring"').replace(
        "tilt_arcmin = [0, 2]", "tilt_arcmin = [0, 0]\npenetration_points_mm = [0.004, 0.01, 0.02, 0.04]")
    (tmp_path / "small.toml").write_text(text, encoding="utf-8")
    b = rc.bearing(tmp_path / "small.toml", tmp_path / "brg", workers=1, log=lambda msg: None)
    assert b.law_file.endswith("small-ring-law.json") and Path(b.law_file).is_file()
    lo, hi = b.validity_penetration_m
    r = b.evaluate([hi / 2])
    assert r.in_domain[0] and r.force_N[0] > 0
    ls = rc.loose_support("B", "s", law=b.law_file)
    assert ls.law_file == b.law_file and ls.clearance_m == pytest.approx(r.clearance_m, rel=1e-12)
    assert rc.load_result(b.save(tmp_path / "bearing.json"))["law_name"] == b.law_name
