"""Jobs that run the rotor on the law a scene names by file (``[loose_support] law = "<path>.json"``).

The scene is the bundled paper-table4 copied to a temporary folder; its law file is a copy of the shipped
contact/calibrated/clamped-foundation.json, fitted for that scene's clearance, ring width and materials
(rotor/model/loose_support_scene.py checks them). The reference for "the same law" is the shipped law by name
(``--law calibrated:clamped-foundation`` or ``law = "calibrated:clamped-foundation"``): both must give the same
numbers to round-off, and the analytic conformal law different ones (the runs make contact: 3 mm misalignment,
as in tests/rotor/dynamics/test_dynamics_outputs.py).
"""
from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

from contact.calibrate import CALIBRATED_DIR
from contact.dataset import document_sha256
from reports import cli
from rotor.model.scene import scene_path

SHIPPED_LAW = "calibrated:clamped-foundation"


def _write_scene(folder: Path, law: str | None, clearance_mm: str = "0.05") -> Path:
    text = scene_path("paper-table4").read_text(encoding="utf-8").replace("clearance_mm = 0.05\n",
                                                                          f"clearance_mm = {clearance_mm}\n")
    if law is not None:
        text = text.replace("preload_n = 5000\n", f'preload_n = 5000\nlaw = "{law}"\n')
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "scene.toml").write_text(text, encoding="utf-8")
    return folder / "scene.toml"


def _write_law(path: Path, edit=None, rechecksum: bool = True) -> Path:
    doc = json.loads(CALIBRATED_DIR.joinpath("clamped-foundation.json").read_text(encoding="utf-8"))
    if edit is not None:
        edit(doc)
    if rechecksum:
        doc["sha256"] = document_sha256(doc)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(doc), encoding="utf-8")
    return path


def _run(argv, capsys) -> tuple[int, str, str]:
    rc = cli.main([str(a) for a in argv])
    out = capsys.readouterr()
    return rc, out.out, out.err


@pytest.fixture
def law_scene(tmp_path) -> tuple[Path, Path]:
    """(scene naming ``laws/my-law.json`` relative to its folder, that law file)."""
    law = _write_law(tmp_path / "case" / "laws" / "my-law.json")
    return _write_scene(tmp_path / "case", "laws/my-law.json"), law


def _simulate(tmp_path, capsys, name, *args) -> tuple[dict, np.ndarray]:
    out = tmp_path / name
    rc, _, err = _run(["simulate", "--speed-rpm", 10500, "--revolutions", 2, "--misalignment-mm", 3, "--out", out,
                       *args], capsys)
    assert rc == 0, err
    with np.load(out / "simulate.npz") as z:
        return json.loads((out / "simulate-summary.json").read_text()), z["q"]


def test_simulate_on_the_scene_law_file(law_scene, tmp_path, capsys, monkeypatch):
    scene, law = law_scene
    monkeypatch.chdir(tmp_path)                      # the scene's relative path is not the working directory's
    s_file, q_file = _simulate(tmp_path, capsys, "file", "--scene", scene)
    s_name, q_name = _simulate(tmp_path, capsys, "name", "--law", SHIPPED_LAW)
    s_conf, q_conf = _simulate(tmp_path, capsys, "conformal", "--scene", scene, "--law", "conformal")
    assert s_file["max_edge_penetration_mm"] > 0                      # contact: the law matters
    np.testing.assert_allclose(q_file, q_name, rtol=0, atol=1e-12 * np.abs(q_name).max())
    assert np.abs(q_conf - q_name).max() > 1e-6 * np.abs(q_name).max()
    assert s_file["law_file"] == str(law.resolve()) and s_file["law_sha256"] == json.loads(law.read_text())["sha256"]
    assert s_file["law_sha256"] == s_name["law_sha256"] and s_file["beyond_law_validity"] is False
    assert "law_file" not in s_conf and "beyond_law_validity" not in s_conf
    # --law PATH (relative to the working directory) overrides the scene's key: the same law again
    s_path, q_path = _simulate(tmp_path, capsys, "path", "--scene", scene, "--law", law.relative_to(tmp_path))
    assert np.array_equal(q_path, q_file) and s_path["law_file"] == s_file["law_file"]
    # a law whose fitted range ends below this run's deepest penetration: flagged, and said on stderr
    top_m = 0.5 * s_file["max_edge_penetration_mm"] * 1e-3

    def narrow(doc):
        doc["validity"].update(penetration_min_m=0.1 * top_m, penetration_max_m=top_m)

    narrow_law = _write_law(tmp_path / "narrow.json", narrow)
    out = tmp_path / "narrow"
    rc, _, err = _run(["simulate", "--speed-rpm", 10500, "--revolutions", 2, "--misalignment-mm", 3, "--scene", scene,
                       "--law", narrow_law, "--out", out], capsys)
    assert rc == 0, err
    s = json.loads((out / "simulate-summary.json").read_text())
    assert s["beyond_law_validity"] is True and s["law_validity_max_penetration_mm"] == pytest.approx(top_m * 1e3)
    assert "the law was extrapolated" in err


def test_geometry_mismatch_and_tampered_law_exit_2_in_one_line(law_scene, tmp_path, capsys):
    _, law = law_scene
    narrow = _write_scene(tmp_path / "c003", None, clearance_mm="0.03")
    for argv in (["--scene", narrow, "--law", law], ["--scene", narrow, "--law", SHIPPED_LAW]):
        rc, _, err = _run(["simulate", "--speed-rpm", 10500, "--out", tmp_path / "x", *argv], capsys)
        assert rc == 2 and err.count("\n") == 1, err
        assert "holds for clearance_mm = 0.05 mm but scene scene.toml has clearance_mm = 0.03 mm" in err
    rc, _, err = _run(["simulate", "--speed-rpm", 10500, "--out", tmp_path / "x",
                       "--scene", _write_scene(tmp_path / "case2", str(law), clearance_mm="0.03")], capsys)
    assert rc == 2 and err.count("\n") == 1 and "clearance_mm = 0.03 mm in scene.toml but law file" in err

    def edited(doc):
        doc["geometry"]["bearing_E_Pa"] = 210e9

    _write_law(tmp_path / "case3" / "edited.json", edited, rechecksum=False)
    rc, _, err = _run(["orbit", _write_scene(tmp_path / "case3", "edited.json"), "--speed-rpm", 6000], capsys)
    assert rc == 2 and err.count("\n") == 1 and "edited.json" in err and "checksum mismatch" in err


def _orbit(scene, capsys) -> dict:
    """``orbit --json`` at 6 000 rpm; ``--accept-long``: the work budget's bound is measured on the machine (its
    step costs scale with the load), and a CI run at a load of about 6 refused this orbit (bound 15.5 h, over the
    budget's 2 h refusal); these tests are about the law file, not the budget (tests/reports/test_budget.py)."""
    rc, text, err = _run(["orbit", scene, "--speed-rpm", 6000, "--misalignment-mm", 3, "--json", "--accept-long"],
                         capsys)
    assert rc == 0, err
    return json.loads(text)


def test_orbit_on_the_scene_law_file(law_scene, tmp_path, capsys):
    scene, law = law_scene
    by_file = _orbit(scene, capsys)
    by_name = _orbit(_write_scene(tmp_path / "named", SHIPPED_LAW), capsys)
    assert by_file["converged"] and by_file["max_edge_penetration_mm"] > 0
    assert by_file["law"] == "laws/my-law.json" and by_file["law_file"] == str(law.resolve())
    assert by_file["law_sha256"] == by_name["law_sha256"] and by_file["beyond_law_validity"] is False
    np.testing.assert_allclose(by_file["multipliers"], by_name["multipliers"], rtol=0, atol=1e-9)
    for k, amps in by_name["velocity_amplitudes_mm_s_1X_to_5X"].items():
        np.testing.assert_allclose(by_file["velocity_amplitudes_mm_s_1X_to_5X"][k], amps, rtol=1e-9, atol=1e-9)
    # branch: a few continuation steps from that orbit; the summary names the law and its deepest point
    out = tmp_path / "branch.json"
    rc, _, err = _run(["branch", scene, "--rpm-start", 6000, "--rpm-end", 6003, "--misalignment-mm", 3,
                       "--max-points", 4, "--out", out, "--accept-long"], capsys)
    d = json.loads(out.read_text())
    assert rc in (0, 1) and d["points"], err        # 1: stopped at --max-points before 6003 rpm, orbits kept
    assert d["law_file"] == by_file["law_file"] and d["beyond_law_validity"] is False
    assert d["max_edge_penetration_mm"] == max(p["max_edge_penetration_mm"] for p in d["points"] + [d["start"]])


def _cascade(scene, out, capsys) -> list[dict]:
    rc, text, err = _run(["study", "cascade", "--scene", scene, "--rpm-min", 6000, "--rpm-max", 7000, "--points", 2,
                          "--misalignment-mm", 3, "--max-revs", 300, "--workers", 1, "--no-progress", "--out", out],
                         capsys)
    assert rc == 0, err
    assert "law " in text and "sha256" in text
    with open(out / "figures" / "study-cascade.csv", newline="") as fh:
        return list(csv.DictReader(fh))


def test_study_cascade_on_the_scene_law_file(law_scene, tmp_path, capsys):
    scene, law = law_scene
    by_file = _cascade(scene, tmp_path / "file", capsys)
    by_name = _cascade(_write_scene(tmp_path / "named", SHIPPED_LAW), tmp_path / "name", capsys)
    assert [r["speed_rpm"] for r in by_file] == ["6000", "7000"]
    for a, b in zip(by_file, by_name):
        a.pop("wall_s"), b.pop("wall_s")
        assert a == b                                   # written to 6 significant digits: the same law
        assert float(a["max_edge_penetration_mm"]) > 0 and a["beyond_law_validity"] == "0"
    manifest = json.loads((tmp_path / "file" / "sweep.json").read_text())
    ls = manifest["scene"]["loose_support"]
    assert ls["law_file"] == str(law.resolve()) and ls["law_sha256"] == json.loads(law.read_text())["sha256"]
    # the same folder with another law (the bundled scene's conformal): refused, not resumed with the stored points
    rc, _, err = _run(["study", "cascade", "--rpm-min", 6000, "--rpm-max", 7000, "--points", 2, "--misalignment-mm", 3,
                       "--max-revs", 300, "--workers", 1, "--no-progress", "--out", tmp_path / "file"], capsys)
    assert rc == 2 and err.count("\n") == 1 and f"computed with the law file with sha256 {ls['law_sha256']}" in err


def test_a_bearing_job_law_file_runs_the_rotor(tmp_path, capsys):
    """The issue's path end to end: ``ringcontact bearing`` on the small ring pair of
    tests/reports/test_bearing_job.py writes its law file; a rotor scene names it and leaves out the clearance,
    ring width and materials, which are then the pair's (0.02 mm, 12 mm, 210/110 GPa); simulate runs on it."""
    from contact.calibrate import load_law_file
    from rotor.model.scene import load_scene
    from test_bearing_job import SMALL

    (tmp_path / "small.toml").write_text(SMALL, encoding="utf-8")
    rc, _, err = _run(["bearing", tmp_path / "small.toml", "--out", tmp_path / "bearing", "--workers", 1], capsys)
    assert rc == 0, err
    law_path = tmp_path / "bearing" / "small-ring-law.json"
    text = scene_path("paper-table4").read_text(encoding="utf-8")
    for key in ("clearance_mm = 0.05\n", "ring_width_mm = 30\n", "bearing_modulus_gpa = 204\n",
                "bearing_poisson_ratio = 0.3\n", "support_modulus_gpa = 204\n", "support_poisson_ratio = 0.3\n"):
        assert text.count(key) == 1
        text = text.replace(key, "")
    scene = tmp_path / "rotor.toml"
    scene.write_text(text.replace("preload_n = 5000\n", 'preload_n = 5000\nlaw = "bearing/small-ring-law.json"\n'),
                     encoding="utf-8")
    law, ls = load_law_file(law_path), load_scene(scene).loose_support
    assert (ls.clearance_m, ls.ring_width_m, ls.support_modulus_pa) == \
        (law.geometry.clearance_m, law.geometry.width_m, law.geometry.support_E_Pa)
    s, _ = _simulate(tmp_path, capsys, "sim", "--scene", scene)
    assert s["law"] == law.name and s["law_file"] == str(law_path.resolve())
    assert s["clearance_mm"] == pytest.approx(law.geometry.clearance_m * 1e3)
    assert s["law_validity_max_penetration_mm"] == pytest.approx(law.validity_penetration_m[1] * 1e3)
    assert s["max_edge_penetration_mm"] > 0 and s["beyond_law_validity"] is (
        s["max_edge_penetration_mm"] > s["law_validity_max_penetration_mm"])
