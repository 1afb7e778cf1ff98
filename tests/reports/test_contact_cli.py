"""Smoke tests of `ringcontact law` and `ringcontact report`, run in-process."""
from __future__ import annotations

import csv
import json
import re

import pytest

from reports.cli import law as cli
from reports import cli as top_cli
from reports.cli import report as report_main


def run_json(capsys, argv):
    assert cli.main(argv + ["--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_json_has_force_moment_width_and_domain_flag(capsys):
    """Johnson at 0.01/0.03 mm: a value, then 'outside domain' with null force (Dai et al. 2025 Table 2)."""
    out = run_json(capsys, ["--law", "johnson", "--penetration-mm", "0.01", "0.03"])
    p = out["points"]
    assert out["law"] == "johnson" and out["parameters"]["clearance_m"] == pytest.approx(5e-5)
    assert p[0]["force_N"] == pytest.approx(33644, abs=1) and p[0]["outside_domain"] is False
    assert p[1]["force_N"] is None and p[1]["moment_Nm"] is None and p[1]["outside_domain"] is True
    assert p[0]["contact_width_m"] == pytest.approx(0.03)


def test_tilt_grid_and_table_output(capsys):
    assert cli.main(["--penetration-mm", "0.01", "0.05", "--tilt-arcmin", "0", "2"]) == 0
    text = capsys.readouterr().out
    assert "law: conformal" in text and "97320.8" in text and "50271.7" in text
    out = run_json(capsys, ["--penetration-mm", "0.01", "--tilt-arcmin", "2", "--penetration-at", "edge"])
    assert out["points"][0]["contact_width_m"] == pytest.approx(0.0171887, rel=1e-5)   # docs/reference/contact-laws.md 10
    assert out["points"][0]["moment_Nm"] > 0


def test_csv_input(tmp_path, capsys):
    f = tmp_path / "points.csv"
    f.write_text("penetration_mm,tilt_arcmin\n0.01,0\n0.02,0\n0.05,1\n")
    out = run_json(capsys, ["--csv", str(f)])
    assert [p["penetration_mm"] for p in out["points"]] == [0.01, 0.02, 0.05]
    assert out["points"][1]["force_N"] == pytest.approx(104410, abs=1)
    assert out["points"][2]["force_N"] == pytest.approx(315669, abs=1)


@pytest.mark.parametrize("argv,pattern", [
    (["--penetration-mm", "0.01", "--clearance-mm", "-0.05"], r"--clearance-mm = -0.05 mm: must be in \(0, 2\] mm"),
    (["--penetration-mm", "nan"], "--penetration-mm = nan mm: must be finite"),
    (["--penetration-mm", "0.01", "--width-mm", "0"], "--width-mm = 0 mm"),
    (["--penetration-mm", "0.01", "--bearing-E-GPa", "-204"], "--bearing-E-GPa = -204 GPa"),
    (["--penetration-mm", "0.01", "--clearance-mm", "50"], r"--clearance-mm = 50 mm: must be in \(0, 2\] mm"),
])
def test_bad_input_clear_error(capsys, argv, pattern):
    """Values are echoed as typed, with the unit typed (not converted to SI), in one line."""
    assert top_cli.main(["law", *argv]) == 2
    err = capsys.readouterr().err
    assert "ringcontact law: error:" in err
    assert re.search(pattern, err), err


def test_bad_csv_files(tmp_path, capsys):
    missing = tmp_path / "nope.csv"
    assert top_cli.main(["law", "--csv", str(missing)]) == 2
    assert "no such file" in capsys.readouterr().err
    bad = tmp_path / "bad.csv"
    bad.write_text("penetration_mm\n0.01\nabc\n")
    assert cli.main(["--csv", str(bad)]) == 2
    assert "line 3" in capsys.readouterr().err
    nohead = tmp_path / "nohead.csv"
    nohead.write_text("x,y\n1,2\n")
    assert cli.main(["--csv", str(nohead)]) == 2
    assert "penetration_mm" in capsys.readouterr().err
    for text, word in (("penetration_mm,tilt_arcmin\n0.01,1\n0.02\n", "line 3: 1 cells"),       # ragged row
                       ("penetration_mm,tilt_arcmin\n0.01,\n", "tilt_arcmin = '': not a number"),  # empty cell
                       ("penetration_mm\n5\n", "penetration_mm = 5 mm: must be in [-1, 2] mm")):    # 5 mm typed
        bad.write_text(text)
        assert cli.main(["--csv", str(bad)]) == 2
        assert word in capsys.readouterr().err
    bad.write_text("penetration_mm\n" + "0.01\n" * 20001)                                         # too many rows
    assert cli.main(["--csv", str(bad)]) == 2
    assert "more than 20000 rows" in capsys.readouterr().err


def test_top_level_command_dispatches_law(capsys):
    assert top_cli.main(["law", "--penetration-mm", "0.02"]) == 0
    assert "104410" in capsys.readouterr().out


def test_report_builds_law_comparison(tmp_path, capsys):
    """The report's CSV reproduces the paper's Table 2 conformal percentages to +-0.05 points
    (Dai et al. 2025 Table 2; FEM loads implied by the Pereira percentages)."""
    assert report_main.main(["--out", str(tmp_path)]) == 0
    names = {p.name for p in tmp_path.iterdir()}
    assert {"laws-vs-paper.md", "laws-vs-paper.csv", "laws-vs-paper.png", "laws-vs-paper.svg"} <= names
    assert not any(n.endswith(".tmp") for n in names)
    rows = list(csv.DictReader(open(tmp_path / "laws-vs-paper.csv")))
    assert len(rows) == 5
    for r in rows:
        assert abs(float(r["conformal_diff_points"])) <= 0.05
    assert [r["johnson_in_domain"] for r in rows] == ["true", "true", "false", "false", "false"]
    md = (tmp_path / "laws-vs-paper.md").read_text()
    assert "**met**" in md and "NOT met" not in md
    assert (tmp_path / "laws-vs-paper.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_calibrated_law_against_the_3d_fem_points(capsys):
    """`--law calibrated:clamped-3d-foundation` at the paper's Table 3 cells (0.5–2′, 0.01–0.03 mm) of our 3D FEM (dataset
    fem_reference/data/3d/fem3d-reference.json, scene 'clamped'): the slice-integrated calibrated law
    must land within the FEM's own error estimate plus 0.5 % (issue 5 measured ≤ 0.18 % held out),
    while the paper's conformal law misses the same points by far more (Dai 2025 law vs clamped rings)."""
    from contact.dataset import read_dataset
    from contact.units import ARCMIN, MM

    ds = read_dataset("fem_reference/data/3d/fem3d-reference.json")
    pts = [p for p in ds.select(scene="clamped") if 0 < p.get("tilt_rad", 0.0) <= 2.001 * 2.9088820866572e-4 and 1e-5 <= p["penetration_m"] <= 3e-5]
    assert len(pts) >= 4
    for p in pts:
        argv = ["--law", "calibrated:clamped-3d-foundation", "--penetration-mm", repr(p["penetration_m"] / MM),
                "--tilt-arcmin", repr(p["tilt_rad"] / ARCMIN)]
        got = run_json(capsys, argv)["points"][0]
        tol = float(p.get("force_error_rel") or 0.0) + 5e-3
        assert got["outside_domain"] is False
        assert got["force_N"] == pytest.approx(float(p["force_n"]), rel=tol), p
        paper = run_json(capsys, ["--penetration-mm", repr(p["penetration_m"] / MM),
                                  "--tilt-arcmin", repr(p["tilt_rad"] / ARCMIN)])["points"][0]
        assert abs(paper["force_N"] / float(p["force_n"]) - 1) > 10 * tol


def test_calibrated_law_flags_points_beyond_its_validity_and_keeps_its_geometry(capsys):
    """No extrapolation: the deepest slice above the fitted range is 'outside domain' (null force);
    geometry other than the calibration's scene is refused with the parameter named."""
    from contact import calibrate

    law = calibrate.load_calibrated("clamped-foundation")
    top_mm = law.validity_penetration_m[1] / 1e-3
    out = run_json(capsys, ["--law", "calibrated:clamped-foundation", "--penetration-mm",
                            repr(0.5 * top_mm), repr(top_mm), repr(1.2 * top_mm), "--tilt-arcmin", "0", "1"])
    flags = [(p["penetration_mm"], p["tilt_arcmin"], p["outside_domain"], p["force_N"]) for p in out["points"]]
    assert [f[2] for f in flags] == [False, False, True, False, True, True]   # 1′ adds θ l0/2 at the edge
    assert all((f[3] is None) == f[2] for f in flags)
    assert cli.main(["--law", "calibrated:clamped-foundation", "--penetration-mm", "0.01", "--clearance-mm", "0.08"]) == 2
    assert "--clearance-mm = 0.08" in capsys.readouterr().err
    assert cli.main(["--law", "calibrated:no-such-law", "--penetration-mm", "0.01"]) == 2
    assert "available:" in capsys.readouterr().err
