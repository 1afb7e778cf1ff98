"""``rotor static`` says when its answer is implausible (issue 40): a deflection beyond the loose support's
clearance or 1 % of the shaft's length is one stderr line naming the station and the value in mm, and the JSON
field ``plausibility``; a deflection within both limits is said nothing about.

Expected values: the Jeffcott rotor's disk under its weight m a deflects m a (1/k_shaft + 1/(2 k_b)) (massless
shaft, central disk; verify-jeffcott.toml), so 1000 g gives several hundred mm on an 800 mm shaft.
"""
from __future__ import annotations

import json
import math
import re

import pytest

from reports.cli.rotor import main
from rotor.model.scene import scene_path


def _scene(tmp_path, name: str, extra: str):
    path = tmp_path / f"{name}-loaded.toml"
    path.write_text(scene_path(name).read_text() + "\n" + extra + "\n")
    return str(path)


def _run(capsys, *argv):
    rc = main(["static", *argv, "--json"])
    cap = capsys.readouterr()
    return rc, json.loads(cap.out), cap.err.strip().splitlines()


def _largest(out):
    return max(out["stations"], key=lambda s: math.hypot(s["y_um"], s["z_um"]))


def test_1000_g_on_the_jeffcott_rotor_is_called_implausible(tmp_path, capsys):
    rc, out, err = _run(capsys, _scene(tmp_path, "verify-jeffcott", "[gravity]\nacceleration_y_m_per_s2 = -9810"))
    p = out["plausibility"]
    big = _largest(out)
    assert rc == 0 and not p["plausible"] and p["exceeded"] == ["shaft_length_fraction"]
    assert p["station"] == big["station"] == "disk" and p["limits_mm"] == {"shaft_length_fraction": pytest.approx(8.0)}
    assert p["deflection_mm"] == pytest.approx(math.hypot(big["y_um"], big["z_um"]) / 1e3, rel=1e-12)
    assert p["deflection_mm"] > 8.0 * 10        # bending of the 20 mm shaft alone: 98 100 N / 147 kN/m, 0.67 m
    assert len(err) == 1 and err[0].startswith("ringcontact rotor static: warning: implausible static deflection")
    said = re.search(r"station 'disk' moves ([0-9.]+) mm, beyond 1 % of the shaft's length \(8 mm", err[0])
    assert said and float(said.group(1)) == pytest.approx(p["deflection_mm"], rel=1e-3), err


def test_1_gn_on_a_station_is_called_implausible(tmp_path, capsys):
    load = '[[static_loads]]\nname = "absurd"\nstation = "disk"\nforce_z_n = 1e9'
    rc, out, err = _run(capsys, _scene(tmp_path, "verify-jeffcott", load))
    p = out["plausibility"]
    assert rc == 0 and not p["plausible"] and p["station"] == "disk" and p["deflection_mm"] > 1e6   # metres
    assert len(err) == 1 and "station 'disk' moves" in err[0] and " mm, beyond 1 % of the shaft's length" in err[0]


def test_beyond_the_clearance_only(tmp_path, capsys):
    """paper-table4 under 1 g: 0.15 mm at station 5, three times the ring's 0.05 mm clearance, far below 1 % of
    its 2.1 m shaft."""
    rc, out, err = _run(capsys, _scene(tmp_path, "paper-table4", "[gravity]\nacceleration_y_m_per_s2 = -9.81"))
    p = out["plausibility"]
    assert rc == 0 and p["exceeded"] == ["clearance"] and p["limits_mm"]["clearance"] == pytest.approx(0.05)
    assert p["limits_mm"]["clearance"] < p["deflection_mm"] < p["limits_mm"]["shaft_length_fraction"]
    assert len(err) == 1 and f"station {p['station']!r} moves" in err[0] and "clearance (0.05 mm" in err[0], err


def test_a_plausible_deflection_is_said_nothing_about(tmp_path, capsys):
    rc, out, err = _run(capsys, _scene(tmp_path, "verify-jeffcott", "[gravity]\nacceleration_y_m_per_s2 = -9.81"))
    p = out["plausibility"]
    assert rc == 0 and p["plausible"] and p["exceeded"] == [] and err == []
    assert 0 < p["deflection_mm"] < p["limits_mm"]["shaft_length_fraction"]
