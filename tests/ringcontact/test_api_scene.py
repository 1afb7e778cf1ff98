"""ringcontact scenes: loaded, built in Python, written back to TOML and read again unchanged, checked as files are."""
from __future__ import annotations

import dataclasses
import math

import pytest

import ringcontact as rc


@pytest.mark.parametrize("name", rc.list_scenes())
def test_every_bundled_scene_survives_its_toml(name):
    """load(to_toml(s)) == s for every shipped scene; the one exception is the ``law`` text of a law named by a
    file, written as the file's resolved path (the file read, ``law_file``, and its checksum stay equal)."""
    s = rc.load_scene(name)
    again = rc.Scene.from_toml(s.to_toml(), path=s.path)
    if s.loose_support is not None and s.loose_support.law_file and not s.loose_support.law.startswith("calibrated:"):
        assert again.loose_support.law == s.loose_support.law_file
        again = dataclasses.replace(again, loose_support=dataclasses.replace(again.loose_support,
                                                                             law=s.loose_support.law))
    assert again == s


def test_numbers_are_written_as_typed():
    """The shortest decimal that converts back: the Table 4 unbalance reads 2000 g·mm, not 2000.0000000000002."""
    text = rc.load_scene("paper-table4").to_toml()
    assert "unbalance_g_mm = 2000.0\n" in text and "clearance_mm = 0.05\n" in text


def _steel():
    return rc.Material("steel", density_kg_m3=7810.0, youngs_modulus_pa=211e9, poisson_ratio=0.3)


def test_disk_from_geometry_is_a_uniform_annulus():
    """m = ρπ(D² − d²)w/4, Ip = m(D² + d²)/8, Id = Ip/2 + m w²/12 (uniform annular cylinder, e.g. Friswell et al.
    2010 §3.3): Friswell's Example 5.9.1 right disk, 350 mm on a 50 mm bore, 70 mm wide."""
    d = rc.disk_from_geometry("d", "A", _steel(), outer_diameter_m=0.35, inner_diameter_m=0.05, width_m=0.07)
    m = 7810.0 * math.pi * (0.35 ** 2 - 0.05 ** 2) * 0.07 / 4
    assert d.mass_kg == pytest.approx(m, rel=1e-14) and d.mass_kg == pytest.approx(51.525, abs=1e-3)
    assert d.polar_inertia_kg_m2 == pytest.approx(m * (0.35 ** 2 + 0.05 ** 2) / 8, rel=1e-14)
    assert d.diametral_inertia_kg_m2 == pytest.approx(d.polar_inertia_kg_m2 / 2 + m * 0.07 ** 2 / 12, rel=1e-14)
    with pytest.raises(rc.InputError, match="inner_diameter_m = 0.05 must be < outer_diameter_m = 0.05"):
        rc.disk_from_geometry("d", "A", _steel(), outer_diameter_m=0.05, inner_diameter_m=0.05, width_m=0.07)


def _two_station_scene(**changes):
    st = (rc.Station("A", 0.0), rc.Station("B", 0.5))
    kw = dict(name="beam", title="a beam", source="test", materials=(_steel(),), stations=st,
              shafts=(rc.Shaft("A", "B", 0.04, 0.0, _steel(), 4),),
              bearings=(rc.Bearing("bA", "A", 1e7), rc.Bearing("bB", "B", 1e7)))
    kw.update(changes)
    return rc.Scene(**kw)


def test_a_scene_built_in_python_is_checked_as_a_file_is():
    s = _two_station_scene().checked()
    assert isinstance(s, rc.Scene) and s.shafts[0].elements == 4
    assert rc.Scene.from_toml(s.to_toml()) == dataclasses.replace(s, path="<string>")
    bad = _two_station_scene(shafts=(rc.Shaft("A", "B", 0.04, 0.05, _steel()),))
    with pytest.raises(rc.InputError, match=r"shafts\[0\].inner_diameter_mm = 50 mm: must be < outer_diameter_mm"):
        bad.checked()
    with pytest.raises(rc.InputError, match="bearings.*no such station"):
        _two_station_scene(bearings=(rc.Bearing("b", "C", 1e7),)).checked()


def test_save_writes_an_editable_file(tmp_path):
    s = _two_station_scene().checked()
    path = s.save(tmp_path / "beam.toml")
    assert rc.load_scene(path) == dataclasses.replace(s, path="beam.toml")
    assert oct(path.stat().st_mode & 0o777) in ("0o644", "0o664")


def test_with_loose_bearing_moves_the_bearing_onto_a_support():
    s = _two_station_scene().with_loose_bearing(
        "bB", support_mass_kg=2.0, support_inertia_kg_m2=0.01, support_angular_stiffness_n_m_rad=1e4,
        clearance_m=3e-5, ring_width_m=0.02, bearing_modulus_pa=208e9, bearing_poisson=0.3, support_modulus_pa=208e9,
        support_poisson=0.3, friction_coefficient=0.2, preload_n=100.0)
    assert [b.name for b in s.bearings] == ["bA"]
    (sp,) = s.supports
    assert (sp.station, sp.stiffness_n_m, sp.mass_kg) == ("B", 1e7, 2.0)
    ls = s.loose_support
    assert (ls.bearing_station, ls.support, ls.clearance_m, ls.law) == ("B", "support", 3e-5, "conformal")
    with pytest.raises(rc.InputError, match="no such bearing"):
        s.with_loose_bearing("nope", support_mass_kg=1, support_inertia_kg_m2=1, support_angular_stiffness_n_m_rad=1)


def test_loose_support_takes_a_calibrated_laws_geometry():
    ls = rc.loose_support("B", "s", law="calibrated:clamped-foundation")
    from contact.calibrate.store import load_calibrated
    g = load_calibrated("clamped-foundation").geometry
    assert (ls.clearance_m, ls.ring_width_m, ls.bearing_modulus_pa) == (g.clearance_m, g.width_m, g.bearing_E_Pa)
    with pytest.raises(rc.InputError, match="clearance_mm"):
        rc.loose_support("B", "s", law="calibrated:clamped-foundation", clearance_m=2 * g.clearance_m)
