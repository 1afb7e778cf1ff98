"""``ringcontact rotor static``: deflection and reactions under gravity and static loads.

Expected values: statics of a beam on two bearings (the reactions add up to the loads; symmetric
gravity splits equally; a midspan load splits equally) and the midspan deflection of a pinned beam
carrying a central point load P, P L³ / (48 E I) + P L / (4 κ G A) (Timoshenko & Gere 1961), plus the
bearing's own compliance.
"""
from __future__ import annotations

import json
import math

import pytest

from reports.cli.rotor import main
from rotor.model import elements as el

SCENE = '''schema = "ringcontact.rotor-scene/1"
name = "beam"
title = "beam on two bearings"
[[materials]]
name = "steel"
density_kg_m3 = 7810
youngs_modulus_gpa = 211
poisson_ratio = 0.3
[[stations]]
name = "A"
x_mm = 0
[[stations]]
name = "M"
x_mm = 500
[[stations]]
name = "B"
x_mm = 1000
[[shafts]]
from = "A"
to = "M"
outer_diameter_mm = 50
material = "steel"
[[shafts]]
from = "M"
to = "B"
outer_diameter_mm = 50
material = "steel"
[[bearings]]
name = "bA"
station = "A"
stiffness_n_per_m = 1e7
[[bearings]]
name = "bB"
station = "B"
stiffness_yy_n_per_m = 1e7
stiffness_zz_n_per_m = 2e7
[[static_loads]]
name = "gear"
station = "M"
force_z_n = 1000
[gravity]
acceleration_y_m_per_s2 = -9.81
'''


def test_rotor_static_json(tmp_path, capsys):
    path = tmp_path / "beam.toml"
    path.write_text(SCENE)
    assert main(["rotor", "static", str(path), "--json"][1:]) == 0
    out = json.loads(capsys.readouterr().out)
    r = {x["element"]: x for x in out["reactions"]}
    weight = 7810 * math.pi * 0.05 ** 2 / 4 * 1.0 * 9.81
    assert r["bA"]["force_y_N"] + r["bB"]["force_y_N"] == pytest.approx(-weight, rel=1e-12)
    assert r["bA"]["force_y_N"] == pytest.approx(r["bB"]["force_y_N"], rel=1e-9)
    assert r["bA"]["force_z_N"] == pytest.approx(500.0, rel=1e-9) and r["bB"]["force_z_N"] == pytest.approx(500.0, rel=1e-9)
    st = {x["station"]: x for x in out["stations"]}
    assert st["A"]["z_um"] == pytest.approx(500 / 1e7 * 1e6, rel=1e-9)      # each bearing's own compliance
    assert st["B"]["z_um"] == pytest.approx(500 / 2e7 * 1e6, rel=1e-9)
    E, nu, d, L = 211e9, 0.3, 0.05, 1.0
    A, I = math.pi * d * d / 4, math.pi * d ** 4 / 64
    kappa = el.cowper_shear_coefficient(d, 0.0, nu)
    bend = 1000 * L ** 3 / (48 * E * I) + 1000 * L / (4 * kappa * E / (2 * (1 + nu)) * A)
    mid_rigid = (st["A"]["z_um"] + st["B"]["z_um"]) / 2
    assert st["M"]["z_um"] - mid_rigid == pytest.approx(bend * 1e6, rel=1e-9)


def test_rotor_static_table_and_bad_scene(tmp_path, capsys):
    assert main(["static", "verify-jeffcott"]) == 0
    assert "bA" in capsys.readouterr().out
    bad = tmp_path / "bad.toml"
    bad.write_text(SCENE.replace("acceleration_y_m_per_s2 = -9.81", "acceleration_y_m_per_s2 = 1e9"))
    assert main(["static", str(bad)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "gravity.acceleration_y_m_per_s2 = 1e+09 m/s^2: must be in" in err[0]
