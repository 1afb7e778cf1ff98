"""A law file is checked as strictly as a scene (issue 40): each field's type and range, the validity range's
consistency, a law that behaves like one, and ``calibrated:<name>`` inside its folder only.

Every case edits one field of the shipped ``clamped-foundation`` law and recomputes the checksum (the checksum
detects accidents; an edit made on purpose must still be refused on its content). Each is then loaded by
``ringcontact law --law FILE`` in-process: exit status 2, one stderr line naming the file, the key and the
value as written, nothing on stdout. A subset also goes through a rotor scene that names the law (``rotor
modes``, the keys the law supplies left out of the scene) and through ``--law`` of ``simulate``.
"""
from __future__ import annotations

import json
import re

import pytest

from contact.calibrate import CALIBRATED_DIR, load_law_file
from contact.dataset import document_sha256
from reports import cli
from rotor.model.scene import scene_path

BASE = json.loads(CALIBRATED_DIR.joinpath("clamped-foundation.json").read_text(encoding="utf-8"))
POWER = {"coefficient_N_per_m_pow_n_plus_1": 3.0e13, "exponent": 1.1}


def _set(section, key, value):
    def edit(doc):
        (doc[section] if section else doc)[key] = value
    return edit


def _power(**params):
    def edit(doc):
        doc["family"] = "power"
        doc["parameters"] = {**POWER, **params}
        doc["parameter_std"] = {k: 0.0 for k in POWER}
    return edit


def _drop(section, key):
    def edit(doc):
        del (doc[section] if section else doc)[key]
    return edit


# (id, edit, what the one line must echo: the key and the value as written)
CASES = [(f"geometry.{k}={v!r}", _set("geometry", k, v), [f"geometry.{k}", echo]) for k, v, echo in (
    ("bearing_E_Pa", -2.04e11, "-2.04e+11 Pa"), ("bearing_E_Pa", 0, "0 Pa"), ("bearing_E_Pa", True, "true"),
    ("bearing_E_Pa", "204e9", '"204e9"'), ("bearing_E_Pa", None, "null"), ("bearing_E_Pa", 204.0, "204 Pa"),
    ("bearing_E_Pa", 2.04e21, "2.04e+21 Pa"), ("support_E_Pa", -1.0, "-1 Pa"), ("support_E_Pa", False, "false"),
    ("support_E_Pa", [204e9], "[204000000000.0]"),
    ("bearing_nu", 0.7, "0.7"), ("bearing_nu", 0.5, "0.5"), ("bearing_nu", -1.0, "-1"), ("support_nu", 0.5, "0.5"),
    ("support_nu", "0.3", '"0.3"'), ("clearance_m", -5e-05, "-5e-05 m"), ("clearance_m", 0, "0 m"),
    ("clearance_m", 0.05, "0.05 m"), ("width_m", 1e-9, "1e-09 m"), ("width_m", -0.03, "-0.03 m"),
    ("width_m", 30.0e3, "30000 m"), ("radius_m", 0.0, "0 m"), ("radius_m", 1e5, "100000 m"),
    ("bearing_thickness_m", -0.01, "-0.01 m"), ("support_thickness_m", 0, "0 m"),
    ("plane", "strian", '"strian"'), ("plane", 3, "3"))]
CASES += [(f"geometry.{k} missing", _drop("geometry", k), [f"'{k}'"]) for k in ("clearance_m", "bearing_E_Pa")]
CASES += [("geometry unknown key", _set("geometry", "density_kg_m3", 7800.0), ["geometry.density_kg_m3"])]
CASES += [(f"validity.{k}={v!r}", _set("validity", k, v), [f"validity.{k}", echo]) for k, v, echo in (
    ("penetration_min_m", 1e-4, "5e-05 m"), ("penetration_min_m", -1e-6, "-1e-06 m"),
    ("penetration_max_m", 1e-6, "1e-06 m"), ("penetration_max_m", 5e-3, "0.005 m"),
    ("penetration_max_m", "5e-5", '"5e-5"'), ("tilt_rad", 0.001, "0.001"), ("tilt_max_rad", -0.001, "-0.001 rad"),
    ("tilt_max_rad", 1.0, "1 rad"))]
CASES += [(f"parameters {v!r}", _set("parameters", "foundation_modulus_Pa_per_m", v),
           ["parameters.foundation_modulus_Pa_per_m", echo])
          for v, echo in ((-1e13, "-1e+13 Pa/m"), (0, "0 Pa/m"), (1e30, "1e+30 Pa/m"), ("big", '"big"'))]
CASES += [("parameters missing", _set("", "parameters", {}), ["foundation_modulus_Pa_per_m"]),
          ("parameter_std negative", _set("parameter_std", "foundation_modulus_Pa_per_m", -1.0),
           ["parameter_std.foundation_modulus_Pa_per_m", "-1"]),
          ("power exponent 0", _power(exponent=0.0), ["parameters.exponent", "0"]),
          ("power exponent 50", _power(exponent=50.0), ["parameters.exponent", "50"]),
          ("power coefficient -1", _power(coefficient_N_per_m_pow_n_plus_1=-1.0),
           ["parameters.coefficient_N_per_m_pow_n_plus_1", "-1"]),
          ("family unknown", _set("", "family", "linear"), ["family", '"linear"']),
          ("name with a newline", _set("", "name", "clamped\nfoundation"), ["name"]),
          ("name empty", _set("", "name", ""), ["name", '""']),
          ("scene a number", _set("", "scene", 7), ["scene", "7"]),
          ("dataset a list", _set("", "dataset", []), ["dataset", "[]"]),
          ("geometry a list", _set("", "geometry", [1, 2]), ["geometry"])]


def _law(path, edit):
    doc = json.loads(json.dumps(BASE))
    edit(doc)
    doc["sha256"] = document_sha256(doc)          # the edit is deliberate: the checksum agrees
    path.write_text(json.dumps(doc), encoding="utf-8")
    return path


def _one_line(argv, capsys):
    rc = cli.main([str(a) for a in argv])
    out = capsys.readouterr()
    lines = [ln for ln in out.err.splitlines() if ln.strip()]
    assert rc == 2, out.err
    assert len(lines) == 1 and "internal error" not in lines[0] and "Traceback" not in out.err, out.err
    assert out.out == "", out.out
    return lines[0]


def test_the_cases_are_many_and_distinct():
    assert len(CASES) >= 50 and len({c[0] for c in CASES}) == len(CASES)


@pytest.mark.parametrize("case_id,edit,echo", CASES, ids=[c[0] for c in CASES])
def test_an_edited_law_file_is_refused_by_law_in_one_line(case_id, edit, echo, tmp_path, capsys):
    law = _law(tmp_path / "edited.json", edit)
    line = _one_line(["law", "--law", law, "--penetration-mm", "0.01"], capsys)
    assert str(law) in line, line
    for e in echo:
        assert e in line, f"{e!r} not in: {line}"


def _scene_naming(tmp_path, law_name):
    """paper-table4 naming ``law_name``, without the geometry keys the law supplies."""
    text = scene_path("paper-table4").read_text(encoding="utf-8")
    text = re.sub(r"\n(clearance_mm|ring_width_mm|bearing_modulus_gpa|support_modulus_gpa|bearing_poisson_ratio|"
                  r"support_poisson_ratio) = [^\n]*", "", text)
    text = text.replace("preload_n = 5000\n", f"preload_n = 5000\nlaw = {json.dumps(law_name)}\n")
    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    return path


SCENE_CASES = [c for c in CASES if c[0] in ("geometry.bearing_E_Pa=0", "geometry.bearing_E_Pa=True",
                                            "geometry.clearance_m=-5e-05", "geometry.bearing_nu=0.7",
                                            "validity.penetration_min_m=0.0001", "parameters -1e+13")]


@pytest.mark.parametrize("case_id,edit,echo", SCENE_CASES, ids=[c[0] for c in SCENE_CASES])
def test_an_edited_law_file_is_refused_by_a_rotor_scene(case_id, edit, echo, tmp_path, capsys):
    _law(tmp_path / "edited.json", edit)
    line = _one_line(["rotor", "modes", _scene_naming(tmp_path, "edited.json")], capsys)
    assert "scene.toml: loose_support.law" in line and "edited.json" in line, line
    for e in echo:
        assert e in line, f"{e!r} not in: {line}"


def test_the_good_law_still_runs_the_scene(tmp_path, capsys):
    _law(tmp_path / "edited.json", lambda doc: None)
    assert cli.main(["rotor", "modes", str(_scene_naming(tmp_path, "edited.json"))]) == 0
    capsys.readouterr()


@pytest.mark.parametrize("width_m", [2e-7, 5e-4, 0.8])
def test_a_law_for_a_ring_no_rotor_scene_has_is_refused_by_the_scene(width_m, tmp_path, capsys):
    """The law file holds (a ring-pair file may describe such a ring) but the scene's own range refuses it."""
    def narrow(doc):
        doc["geometry"]["width_m"] = width_m
        doc["geometry"]["radius_m"] = max(doc["geometry"]["radius_m"], width_m)
    law = _law(tmp_path / "narrow.json", narrow)
    assert load_law_file(law).geometry.width_m == width_m
    line = _one_line(["rotor", "modes", _scene_naming(tmp_path, "narrow.json")], capsys)
    assert f"ring_width_mm = {width_m * 1e3:g} mm" in line and "[1, 500] mm" in line, line
    line = _one_line(["simulate", "--speed-rpm", "3000", "--law", law, "--out", tmp_path / "o"], capsys)
    assert f"ring_width_mm = {width_m * 1e3:g} mm" in line and not (tmp_path / "o").exists(), line


TRAVERSAL = ["../../rotor/scenes/laws/steel-in-aluminium-law", "../calibrated/clamped-foundation", "/etc/passwd",
             "clamped-foundation/", ".clamped-foundation", "clamped..foundation", "sub\\name", "clamped foundation",
             "a" * 300]


@pytest.mark.parametrize("name", TRAVERSAL)
def test_a_calibrated_name_is_a_name_inside_its_folder(name, tmp_path, capsys):
    line = _one_line(["law", "--law", f"calibrated:{name}", "--penetration-mm", "0.01"], capsys)
    assert "not a path" in line and repr(name)[1:41] in line, line
    line = _one_line(["rotor", "modes", _scene_naming(tmp_path, f"calibrated:{name}")], capsys)
    assert "not a path" in line and "scene.toml: loose_support.law" in line, line
