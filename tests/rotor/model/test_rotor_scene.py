"""Scene files: unit conversion at load, and one clear error per bad field."""
from __future__ import annotations

import math
import re

import pytest

from contact.errors import DatasetError, InputError
from rotor.model.scene import bundled_scenes, load_scene, loads_scene

GOOD = """
schema = "ringcontact.rotor-scene/1"
name = "tiny"
title = "two-station test rotor"
[[materials]]
name = "steel"
density_kg_m3 = 7850
youngs_modulus_gpa = 206
poisson_ratio = 0.3
[[stations]]
name = "A"
x_mm = 0
[[stations]]
name = "B"
x_mm = 500
[[shafts]]
from = "A"
to = "B"
outer_diameter_mm = 40
inner_diameter_mm = 10
material = "steel"
elements = 3
[[disks]]
name = "disk1"
station = "B"
mass_kg = 5
polar_inertia_kg_m2 = 0.02
diametral_inertia_kg_m2 = 0.01
unbalance_g_mm = 250
skew_mrad = 0.5
skew_phase_deg = 90
[[bearings]]
name = "b1"
station = "A"
stiffness_n_per_m = 1e7
damping_n_s_per_m = 300
[analysis]
max_speed_rpm = 6000
"""


def test_units_are_converted_to_si_at_load():
    """mm → m, GPa → Pa, g·mm → kg·m, mrad → rad, deg → rad, rpm → rad/s."""
    s = loads_scene(GOOD)
    assert s.stations[1].x_m == pytest.approx(0.5)
    sh = s.shafts[0]
    assert (sh.outer_diameter_m, sh.inner_diameter_m, sh.elements) == (pytest.approx(0.04), pytest.approx(0.01), 3)
    assert sh.material.youngs_modulus_pa == pytest.approx(206e9)
    d = s.disks[0]
    assert d.unbalance_kg_m == pytest.approx(250e-6)
    assert d.skew_rad == pytest.approx(5e-4) and d.skew_phase_rad == pytest.approx(math.pi / 2)
    assert s.analysis.max_speed_rad_s == pytest.approx(6000 * math.pi / 30)


@pytest.mark.parametrize("name", ["paper-table4", "paper-table5-testrig", "verify-jeffcott", "verify-overhung-disk"])
def test_bundled_scenes_load(name):
    assert name in bundled_scenes()
    assert load_scene(name).name == name


def test_table4_scene_holds_the_papers_numbers():
    """Spot checks against Dai et al. 2025, Table 4."""
    s = load_scene("paper-table4")
    assert [st.x_m for st in s.stations] == pytest.approx([0, 0.3, 0.6, 0.6, 2.0, 2.1])   # l12..l45
    assert [sh.outer_diameter_m for sh in s.shafts] == pytest.approx([0.12, 0.14, 0.12, 0.14])
    assert [sh.inner_diameter_m for sh in s.shafts] == pytest.approx([0.08, 0.06, 0.10, 0.10])
    assert [d.mass_kg for d in s.disks] == [150, 120]
    assert [d.unbalance_kg_m for d in s.disks] == pytest.approx([2e-3, 2e-3])             # 2000 g·mm
    assert [b.stiffness_n_m for b in s.bearings] == pytest.approx([1.5e7, 3e7])
    assert s.supports[0].mass_kg == 100 and s.point_masses[0].mass_kg == 10
    assert s.loose_support.clearance_m == pytest.approx(5e-5) and s.misalignment.offset_m == pytest.approx(1e-3)


def _bad(old: str, new: str) -> str:
    assert old in GOOD
    return GOOD.replace(old, new, 1)


@pytest.mark.parametrize("text, pattern", [
    # missing field
    (_bad("outer_diameter_mm = 40\n", ""), r"shafts\[0\]: missing field 'outer_diameter_mm' \(mm\)"),
    (_bad("mass_kg = 5\n", ""), r"disks\[0\]: missing field 'mass_kg' \(kg\)"),
    # negative length (stations out of order) and negative sizes
    (_bad("x_mm = 500", "x_mm = -500"), r"shafts\[0\]: length = x\(B\) - x\(A\) = -500 mm: must be > 0"),
    (_bad("outer_diameter_mm = 40", "outer_diameter_mm = -40"), r"shafts\[0\]\.outer_diameter_mm = -40 mm: must be > 0"),
    (_bad("stiffness_n_per_m = 1e7", "stiffness_n_per_m = -1e7"), r"bearings\[0\]\.stiffness_n_per_m = -1e\+07 N/m: must be >= 0"),
    # inner diameter >= outer
    (_bad("inner_diameter_mm = 10", "inner_diameter_mm = 40"),
     r"shafts\[0\]\.inner_diameter_mm = 40 mm: must be < outer_diameter_mm = 40 mm"),
    (_bad("inner_diameter_mm = 10", "inner_diameter_mm = 55"),
     r"shafts\[0\]\.inner_diameter_mm = 55 mm: must be < outer_diameter_mm = 40 mm"),
    # unknown unit
    (_bad("x_mm = 500", "x_in = 20"), r"stations\[1\]\.x_in: unknown unit 'in' for 'x'; write it as 'x_mm'"),
    (_bad("outer_diameter_mm = 40", "outer_diameter_m = 0.04"),
     r"shafts\[0\]\.outer_diameter_m: unknown unit 'm' for 'outer_diameter'; write it as 'outer_diameter_mm'"),
    (_bad("youngs_modulus_gpa = 206", "youngs_modulus_mpa = 206000"),
     r"materials\[0\]\.youngs_modulus_mpa: unknown unit 'mpa' for 'youngs_modulus'"),
    (_bad("max_speed_rpm = 6000", "max_speed_hz = 100"), r"analysis\.max_speed_hz: unknown unit 'hz'"),
    # other bad values
    (_bad("elements = 3", "elements = 3\ncolour = 'red'"),
     r"shafts\[0\]\.colour: unknown field"),
    (_bad("poisson_ratio = 0.3", "poisson_ratio = 0.7"), r"materials\[0\]\.poisson_ratio = 0.7: must be in \(-1, 0.5\)"),
    (_bad("mass_kg = 5", "mass_kg = nan"), r"disks\[0\]\.mass_kg = nan kg: must be finite"),
    (_bad("mass_kg = 5", 'mass_kg = "5"'), r"disks\[0\]\.mass_kg = '5': must be a number"),
    (_bad("elements = 3", "elements = 2.5"), r"shafts\[0\]\.elements = 2.5: must be an integer"),
    (_bad('station = "B"', 'station = "C"'), r"disks\[0\]\.station = 'C': no such station"),
    (_bad('material = "steel"', 'material = "brass"'), r"shafts\[0\]\.material = 'brass': no such material"),
])
def test_bad_scene_gives_one_clear_error(text, pattern):
    with pytest.raises(InputError) as info:
        loads_scene(text, origin="bad.toml")
    msg = str(info.value)
    assert msg.startswith("bad.toml: "), msg
    assert re.search(pattern, msg), msg
    assert msg.count("\n") == 0


def test_missing_and_unreadable_files_are_dataset_errors(tmp_path):
    with pytest.raises(DatasetError, match="cannot read"):
        load_scene(tmp_path / "nope.toml")
    bad = tmp_path / "broken.toml"
    bad.write_text("schema = [unclosed\n")
    with pytest.raises(DatasetError, match="not valid TOML"):
        load_scene(bad)
    with pytest.raises(DatasetError, match="bundled scenes: .*paper-table4"):
        load_scene("no-such-scene")


def test_wrong_schema_is_rejected():
    with pytest.raises(InputError, match="schema"):
        loads_scene(GOOD.replace("ringcontact.rotor-scene/1", "something-else/9"))
