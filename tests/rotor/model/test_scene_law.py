"""``[loose_support] law = ...`` of a rotor scene (rotor/model/loose_support_scene.py) and the law file it names
(contact/calibrate/store.py: load_law_file, law_file_record).

The law file is a copy of the shipped contact/calibrated/clamped-foundation.json (fitted to the clamped 2D FEM
scene: clearance 0.05 mm, ring width 30 mm, steel 204 GPa / 0.3 on both rings, the values of the bundled
paper-table4 scene's [loose_support]); edited copies are re-checksummed with contact.dataset.document_sha256
where the test wants a valid file.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from contact.calibrate import CALIBRATED_DIR, LAW_FILE_MAX_BYTES, load_calibrated, load_law_file
from contact.dataset import document_sha256
from contact.errors import DatasetError, InputError
from rotor.model.scene import load_scene, scene_path

SHIPPED = CALIBRATED_DIR.joinpath("clamped-foundation.json")
GEOMETRY_LINES = ("clearance_mm = 0.05\n", "ring_width_mm = 30\n", "bearing_modulus_gpa = 204\n",
                  "bearing_poisson_ratio = 0.3\n", "support_modulus_gpa = 204\n", "support_poisson_ratio = 0.3\n")


def _scene(folder: Path, law: str | None, *, drop=(), replace=()) -> Path:
    """paper-table4 as ``folder/scene.toml`` with ``law = ...`` in [loose_support], lines dropped or replaced."""
    text = scene_path("paper-table4").read_text(encoding="utf-8")
    for line in drop:
        assert text.count(line) == 1, line
        text = text.replace(line, "")
    for old, new in replace:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    if law is not None:
        text = text.replace("preload_n = 5000\n", f"preload_n = 5000\nlaw = {json.dumps(law)}\n")
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "scene.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _law_copy(path: Path, edit=None, rechecksum: bool = True) -> Path:
    doc = json.loads(SHIPPED.read_text(encoding="utf-8"))
    if edit is not None:
        edit(doc)
    if rechecksum:
        doc["sha256"] = document_sha256(doc)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(doc, indent=1), encoding="utf-8")
    return path


def test_relative_law_path_is_taken_from_the_scene_folder(tmp_path, monkeypatch):
    law = _law_copy(tmp_path / "laws" / "my-law.json")
    scene = _scene(tmp_path / "scenes", "../laws/my-law.json")
    monkeypatch.chdir(tmp_path)                     # from the working directory the path would miss
    assert not Path("../laws/my-law.json").exists()
    ls = load_scene(scene).loose_support
    assert ls.law == "../laws/my-law.json" and Path(ls.law_file) == law.resolve()
    assert ls.law_sha256 == json.loads(law.read_text())["sha256"]       # the file's own verified checksum
    assert ls.calibrated == load_calibrated("clamped-foundation")        # the same law as the shipped one
    assert ls.validity_max_penetration_m == ls.calibrated.validity_penetration_m[1]


def test_geometry_keys_come_from_the_law_when_left_out(tmp_path):
    _law_copy(tmp_path / "my-law.json")
    full = load_scene(_scene(tmp_path / "a", None)).loose_support
    short = load_scene(_scene(tmp_path, "my-law.json", drop=GEOMETRY_LINES)).loose_support
    g = short.calibrated.geometry
    assert (short.clearance_m, short.ring_width_m, short.bearing_modulus_pa, short.support_poisson) == \
        (g.clearance_m, g.width_m, g.bearing_E_Pa, g.support_nu)
    # and they are the values paper-table4 types (the scene the law was fitted for)
    assert short.clearance_m == pytest.approx(full.clearance_m, rel=1e-12)
    assert short.bearing_modulus_pa == pytest.approx(full.bearing_modulus_pa, rel=1e-12)
    with pytest.raises(InputError, match=r"missing field 'clearance_mm' \(mm\).*unless 'law' names a calibrated law"):
        load_scene(_scene(tmp_path / "b", None, drop=GEOMETRY_LINES[:1]))


@pytest.mark.parametrize("old, new, expect", [
    ("clearance_mm = 0.05\n", "clearance_mm = 0.03\n", "clearance_mm = 0.03 mm in scene.toml but law file my-law.json "
                                                       "holds for 0.05 mm"),
    ("support_modulus_gpa = 204\n", "support_modulus_gpa = 210\n", "support_modulus_gpa = 210 GPa in scene.toml but "
                                                                   "law file my-law.json holds for 204 GPa"),
    ("bearing_poisson_ratio = 0.3\n", "bearing_poisson_ratio = 0.29\n", "bearing_poisson_ratio = 0.29 in scene.toml"),
])
def test_geometry_disagreeing_with_the_law_is_refused_in_one_line(tmp_path, old, new, expect):
    _law_copy(tmp_path / "my-law.json")
    with pytest.raises(InputError) as err:
        load_scene(_scene(tmp_path, "my-law.json", replace=[(old, new)]))
    msg = str(err.value)
    assert expect in msg and "remove" in msg and "\n" not in msg


def test_tampered_or_foreign_law_files_are_refused_naming_the_file(tmp_path):
    def modulus(doc):
        doc["parameters"]["foundation_modulus_Pa_per_m"] *= 1.01

    tampered = _law_copy(tmp_path / "tampered.json", modulus, rechecksum=False)
    with pytest.raises(DatasetError, match="checksum mismatch") as err:
        load_scene(_scene(tmp_path, "tampered.json"))
    assert "scene.toml: loose_support.law = 'tampered.json'" in str(err.value) and str(tampered) in str(err.value)
    assert load_law_file(_law_copy(tmp_path / "refit.json", modulus)).parameters["foundation_modulus_Pa_per_m"] == \
        pytest.approx(1.01 * load_calibrated("clamped-foundation").parameters["foundation_modulus_Pa_per_m"])
    bad = {"missing.json": None, "folder.json": "dir", "big.json": b" " * (LAW_FILE_MAX_BYTES + 1),
           "text.json": b"not json", "schema.json": _law_copy(tmp_path / "s", lambda d: d.update(schema="other"))}
    for name, content in bad.items():
        p = tmp_path / name
        if content == "dir":
            p.mkdir()
        elif isinstance(content, bytes):
            p.write_bytes(content)
        elif content is not None:
            p.write_bytes(content.read_bytes())
        with pytest.raises(DatasetError) as err:
            load_law_file(p)
        assert name in str(err.value) and "\n" not in str(err.value), name


def test_law_files_keep_unknown_extra_keys(tmp_path):
    """Optional keys (the bearing job's provenance and validity.tilt_max_rad) and keys of a later version: still
    the same law."""
    def extra(doc):
        doc["provenance"] = {"job": "bearing", "input_sha256": "0" * 64}
        doc["validity"]["tilt_max_rad"] = 1e-3
        doc["a_later_key"] = {"anything": [1, 2]}

    law = load_law_file(_law_copy(tmp_path / "extra.json", extra))
    shipped = load_calibrated("clamped-foundation")
    assert (law.family, law.parameters, law.geometry, law.validity_penetration_m) == \
        (shipped.family, shipped.parameters, shipped.geometry, shipped.validity_penetration_m)


@pytest.mark.parametrize("value, expect", [
    ("hertz", "law = 'hertz': must be conformal or pereira, calibrated:<name>"),
    ("calibrated:", "name the law"),
    ("calibrated:nosuch", "'nosuch' not found"),
    ("calibrated:persson-40-conformal-compliance", "not available in the compiled loose-support kernel"),
])
def test_bad_law_names_are_refused(tmp_path, value, expect):
    with pytest.raises((InputError, DatasetError), match=expect):
        load_scene(_scene(tmp_path, value))


def test_analytic_laws_keep_todays_scene(tmp_path):
    default = load_scene("paper-table4").loose_support
    assert default.law == "conformal" and default.calibrated is None and default.law_note() == {}
    pereira = load_scene(_scene(tmp_path, "pereira")).loose_support
    assert pereira.law == "pereira" and pereira.validity_max_penetration_m is None
