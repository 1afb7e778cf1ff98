"""``ringcontact scenes``: a user with the installed package only can list and print the bundled scenes and the
two schemas (the same files and schemas the documentation shows: docs/scene.schema.json, docs/ring-scene.schema.json)."""
from __future__ import annotations

import json
from pathlib import Path

from fem_reference import ring_scene
from reports.cli.scenes import main

ROOT = Path(__file__).resolve().parents[2]


def test_list_names_every_bundled_scene(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    names = [p.stem for p in (ROOT / "rotor" / "scenes").glob("*.toml")] + \
            [p.stem for p in (ROOT / "fem_reference" / "ring_scenes").glob("*.toml")]
    assert len(names) >= 9 and all(f"  {n} " in out for n in names)


def test_show_prints_the_file_and_it_loads(capsys):
    assert main(["show", "steel-in-aluminium"]) == 0
    text = capsys.readouterr().out
    assert text == (ROOT / "fem_reference" / "ring_scenes" / "steel-in-aluminium.toml").read_text()
    assert ring_scene.loads(text).sha256 == ring_scene.load("steel-in-aluminium").sha256
    assert main(["show", "paper-table4"]) == 0
    assert capsys.readouterr().out == (ROOT / "rotor" / "scenes" / "paper-table4.toml").read_text()


def test_schemas_are_the_documented_ones(capsys):
    assert main(["schema", "rotor"]) == 0
    assert json.loads(capsys.readouterr().out) == json.loads((ROOT / "docs" / "scene.schema.json").read_text())
    assert main(["schema", "ring"]) == 0
    assert json.loads(capsys.readouterr().out) == json.loads((ROOT / "docs" / "ring-scene.schema.json").read_text())


def test_unknown_name_is_one_line(capsys):
    assert main(["show", "nosuch"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "'nosuch'" in err[0] and "steel-in-aluminium" in err[0]
