"""Ring-pair scene files (fem_reference/ring_scene.py): bundled files, normalisation, one-line refusals."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from contact.errors import DatasetError, InputError
from fem_reference import ring_scene
from fem_reference.scenes import clamped, persson

ROOT = Path(__file__).resolve().parents[2]
BUNDLED = ROOT / "fem_reference" / "ring_scenes"

def _docstring_example() -> str:
    """The example file of fem_reference/ring_scene.py's docstring (the issue's keys), as its lines."""
    doc = ring_scene.__doc__
    block = doc[doc.index("::\n\n") + 3:].split("\n\n")[0]
    return "\n".join(line[4:] for line in block.splitlines()) + "\n"


GOOD = _docstring_example()


def test_issue_example_loads_in_si():
    """The example of the issue, verbatim: SI values, default grids inside the range, 3D asked."""
    rs = ring_scene.loads(GOOD, "my.toml")
    r = rs.scene.rings
    assert (r.inner_radius_m, r.outer_radius_m, r.clearance_m, r.support_outer_radius_m, r.width_m) == \
        pytest.approx((0.048, 0.055, 3e-5, 0.075, 0.022))
    assert r.bearing.youngs_modulus_pa == 208e9 and r.support.youngs_modulus_pa == 72e9
    assert r.support.poisson_ratio == 0.33
    assert rs.needs_3d and rs.bc_3d == "clamped"
    assert min(rs.penetrations_2d_m) == pytest.approx(5e-6) and max(rs.penetrations_2d_m) == pytest.approx(5e-5)
    assert len(rs.penetrations_2d_m) >= 4 and len(rs.penetrations_3d_m) >= 4
    assert rs.tilts_rad[0] == 0.0 and max(rs.tilts_rad) == pytest.approx(2 * ring_scene.ARCMIN)


def test_bundled_table1_files_are_the_code_scenes():
    """The named scenes became files: the same rings, plane, drive and hold as the code builds
    (Dai et al. 2025 Table 1 rings; Persson's pin at plate ratio 40)."""
    assert ring_scene.load("clamped").scene == clamped()
    assert ring_scene.load("clamped-stress").scene == clamped(plane="stress")
    assert ring_scene.load("persson-40").scene == persson(40.0)
    from fem_reference.solid.geometry import RingPair3D
    assert ring_scene.load("clamped").rings_3d() == RingPair3D()      # the committed 3D dataset's rings, exactly
    assert set(ring_scene.bundled()) >= {"clamped", "clamped-stress", "persson-40", "steel-in-aluminium"}


def _leaves(d, prefix=""):
    out = {}
    for k, v in d.items():
        if isinstance(v, dict):
            out.update(_leaves(v, f"{prefix}{k}."))
        else:
            out[f"{prefix}{k}"] = v
    return out


def test_second_pair_differs_from_table1_in_every_key():
    """The steel-in-aluminium pair differs from Table 1 in every key the issue lists."""
    import tomllib
    a = _leaves(tomllib.loads((BUNDLED / "clamped.toml").read_text()))
    b = _leaves(tomllib.loads((BUNDLED / "steel-in-aluminium.toml").read_text()))
    keys = set(_leaves(tomllib.loads(GOOD)))
    same = [k for k in keys - {"schema"} if a.get(k) == b.get(k)]
    assert same == []


def test_hash_ignores_comments_and_layout():
    text = GOOD.replace('name = "my-bearing"', '# a comment\nname   =   "my-bearing"')
    assert ring_scene.loads(text).sha256 == ring_scene.loads(GOOD).sha256
    assert ring_scene.loads(GOOD.replace("72.0", "70.0")).sha256 != ring_scene.loads(GOOD).sha256


def test_document_round_trip():
    """The normalised document (what a dataset or law file stores) reads back to the same scene."""
    rs = ring_scene.load("steel-in-aluminium")
    again = ring_scene.from_document(json.loads(json.dumps(rs.document)))
    assert again.scene == rs.scene and again.penetrations_3d_m == rs.penetrations_3d_m and again.sha256 == rs.sha256


BAD = [
    # (change, words the one-line message must hold)
    (("inner_radius_mm = 48.0", "inner_radius_mm = 56.0"), ["[bearing_ring] inner_radius_mm", "56 mm", "cross"]),
    (("outer_radius_mm = 75.0", "outer_radius_mm = 55.0"), ["[housing] outer_radius_mm", "55 mm", "bore"]),
    (("radial_clearance_mm = 0.03", "radial_clearance_mm = 0.0"), ["radial_clearance_mm", "0 mm", "> 0"]),
    (("radial_clearance_mm = 0.03", "radial_clearance_mm = -0.01"), ["radial_clearance_mm", "-0.01 mm", "> 0"]),
    (("poisson_ratio = 0.33", "poisson_ratio = 0.5"), ["[housing] poisson_ratio", "0.5", "(-1, 0.5)"]),
    (("poisson_ratio = 0.30", "poisson_ratio = 0.62"), ["[bearing_ring] poisson_ratio", "0.62"]),
    (("youngs_modulus_gpa = 72.0", "youngs_modulus_gpa = 72e9"), ["[housing] youngs_modulus_gpa", "GPa", "Pa"]),
    (("penetration_mm = [0.005, 0.05]", "penetration_mm = [0.000001, 0.05]"), ["[range] penetration_mm", "resolve"]),
    (("penetration_mm = [0.005, 0.05]", "penetration_mm = [0.005, 5.0]"), ["[range] penetration_mm", "small-strain"]),
    (("penetration_mm = [0.005, 0.05]", "penetration_mm = [0.05, 0.005]"), ["[range] penetration_mm", "low < high"]),
    (("tilt_arcmin = [0, 2]", "tilt_arcmin = [0, 600]"), ["[range] tilt_arcmin", "arcmin"]),
    (("width_mm = 22.0", "width_mm = 22.0\nwidht_mm = 3"), ["[bearing_ring] widht_mm", "unknown key"]),
    (('plane = "strain"', 'plane = "strain"\ncolour = "red"'), ["'colour'", "unknown"]),
    (("[drive]", "[drives]\nx = 1\n[drive]"), ["[drives]", "unknown"]),
    (('plane = "strain"', 'plane = "membrane"'), ["plane", "'membrane'", "strain, stress"]),
    (('hold = "clamped-outer"', 'hold = "glued"'), ["[housing] hold", "'glued'"]),
    (('hold = "clamped-outer"', 'hold = "clamped-outer-lower"'), ["[range] tilt_arcmin", "3D", "clamped-outer-lower"]),
    (('schema = "ringcontact.ring-scene/1"', 'schema = "ringcontact.ring-scene/9"'), ["schema", "ring-scene/9"]),
    (("youngs_modulus_gpa = 208.0\n", ""), ["[bearing_ring] youngs_modulus_gpa", "missing"]),
    (("width_mm = 22.0", 'width_mm = "22"'), ["[bearing_ring] width_mm", "number"]),
    (("width_mm = 22.0", "width_mm = nan"), ["[bearing_ring] width_mm", "finite"]),
]


@pytest.mark.parametrize("change,words", BAD, ids=[c[0][1][:28] for c in BAD])
def test_bad_file_refused_with_one_line_naming_key_and_value(change, words):
    old, new = change
    assert old in GOOD
    with pytest.raises(InputError) as exc:
        ring_scene.loads(GOOD.replace(old, new, 1), "my.toml")
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith("my.toml")
    for w in words:
        assert w in msg, (w, msg)


def test_not_a_file_or_not_toml(tmp_path):
    with pytest.raises(DatasetError, match="does not exist"):
        ring_scene.load(str(tmp_path / "none.toml"))
    with pytest.raises(DatasetError, match="not a regular file"):
        ring_scene.load(str(tmp_path) + "/")
    bad = tmp_path / "b.toml"
    bad.write_text("schema = [[[")
    with pytest.raises(DatasetError, match="not valid TOML"):
        ring_scene.load(str(bad))
    deep = tmp_path / "deep.toml"
    deep.write_text("a = " + "[" * 5000 + "]" * 5000 + "\n")
    with pytest.raises((DatasetError, InputError)):
        ring_scene.load(str(deep))
    big = tmp_path / "big.toml"
    big.write_text("# " + "x" * (ring_scene.MAX_FILE_BYTES + 10))
    with pytest.raises(DatasetError, match="bytes"):
        ring_scene.load(str(big))
    with pytest.raises(InputError, match="no bundled ring-pair file"):
        ring_scene.load("no-such-bearing")


def test_json_schema_committed_matches_the_code():
    """docs/ring-scene.schema.json is generated from ring_scene.KEYS (python docs/_ext/ring_scene_schema.py)."""
    committed = json.loads((ROOT / "docs" / "ring-scene.schema.json").read_text())
    assert committed == ring_scene.json_schema()
    keys = set(committed["properties"]) | {f"{s}.{k}" for s in ("bearing_ring", "housing", "drive", "range")
                                          for k in committed["properties"][s]["properties"]}
    assert {"bearing_ring.inner_radius_mm", "housing.hold", "drive.bearing", "range.tilt_arcmin"} <= keys


def test_fem_point_takes_a_ring_file(tmp_path, capsys):
    """``fem-point --scene FILE`` solves that ring pair; a bad file is one line, exit 2."""
    from reports.cli.fem import point_main
    f = tmp_path / "my.toml"
    f.write_text(GOOD)
    assert point_main(["0.02", "--scene", str(f), "--h-mm", "2", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["scene"] == "my-bearing" and rec["force_N"] > 0
    f.write_text(GOOD.replace("poisson_ratio = 0.33", "poisson_ratio = 0.5"))
    assert point_main(["0.02", "--scene", str(f)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "poisson_ratio" in err[0] and "Traceback" not in err[0]
