"""JSON Schema of a rotor scene TOML file, generated from the scene parser's own field tables.

The source of truth is :mod:`rotor.model.scene` (each table's field specifications: key, unit,
converter, check, default) and :data:`contact.plausible.RANGES` (the plausible range of a key);
the parser enforces both, and this module writes the same rules as a JSON Schema (draft 2020-12)
for editors, and as the rows of the scene reference page of the documentation. What a schema
cannot say (a shaft's ``from``/``to`` must name stations in increasing ``x_mm``, inner diameter
below outer, unique names) is checked by the parser only and listed in :data:`CROSS_CHECKS`.

Run from the repository root::

    python docs/_ext/scene_schema.py           # rewrite docs/scene.schema.json
    python docs/_ext/scene_schema.py --check   # exit 1 if the committed file is out of date

An editor with TOML schema support (e.g. Taplo / "Even Better TOML") picks the schema up from a
first line ``#:schema ./scene.schema.json`` (a path relative to the scene file) or a settings entry.
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from contact.plausible import RANGES  # noqa: E402
from rotor.model import scene as sc  # noqa: E402

SCHEMA_FILE = DOCS / "scene.schema.json"

# TOML table -> (field specifications, dataclass built from it, array of tables?)
TABLES = {
    "materials": (sc._MATERIAL, sc.Material, True),
    "stations": (sc._STATION, sc.Station, True),
    "shafts": (sc._SHAFT, sc.Shaft, True),
    "disks": (sc._DISK, sc.Disk, True),
    "point_masses": (sc._POINT_MASS, sc.PointMass, True),
    "bearings": (sc._BEARING, sc.Bearing, True),
    "supports": (sc._SUPPORT, sc.SupportNode, True),
    "couplings": (sc._COUPLING, sc.Coupling, True),
    "boundaries": (sc._BOUNDARY, sc.Boundary, True),
    "loose_support": (sc._LOOSE, sc.LooseSupport, False),
    "misalignment": (sc._MISALIGN, sc.Misalignment, False),
    "analysis": (sc._ANALYSIS, sc.Analysis, False),
}
TOP_TEXT = {
    "schema": "format name and version; must be exactly this string",
    "name": "short id of the scene (a bundled scene's file name)",
    "title": "one line saying what the scene is",
    "source": "where the numbers come from (paper, table, measurement)",
    "notes": "free text for readers; not read by the parser",
    "assumptions": "free text for readers; not read by the parser",
}
CROSS_CHECKS = (
    "shafts: `from` and `to` name stations, `to` at a larger x_mm than `from`; inner_diameter_mm < outer_diameter_mm; "
    "`material` names a [[materials]] entry",
    "disks, point_masses, bearings, supports, boundaries: `station` names a station",
    "couplings: `node_a` and `node_b` name stations at the same x_mm",
    "loose_support: `bearing_station` names a station, `support` a [[supports]] entry; clearance_mm, ring_width_mm, "
    "the moduli and Poisson ratios are required unless `law` names a calibrated law (then they are the law's, and "
    "must equal it where given)",
    "misalignment: `bearing_station` names a station, `coupling` a [[couplings]] entry",
    "names are unique within materials and stations; supports and elements do not reuse a station name",
)


# what a key's value means, where its name and unit do not say it
KEY_TEXT = {
    "law": "contact law: conformal (the paper's, as published), pereira, calibrated:<name> (a law shipped in "
           "contact/calibrated/) or the path of a calibrated-law file (.json, relative to the scene file's folder); "
           "a calibrated law must hold for this table's geometry (rotor/model/loose_support_scene.py)",
}
FROM_LAW_TEXT = "required unless `law` names a calibrated law, whose value it then takes (and must equal if given)"


def _scale(conv) -> float:
    return conv(1.0)


def _bounds(key: str, check) -> dict:
    """Lower and upper bounds of a numeric key, in the unit typed: the parser's sign check and the
    plausible range, whichever is tighter at each end."""
    lo, lo_in, hi, hi_in = -math.inf, True, math.inf, True
    if check is sc._pos:
        lo, lo_in = 0.0, False
    elif check is sc._nonneg:
        lo, lo_in = 0.0, True
    elif check is sc._nu:
        lo, lo_in, hi, hi_in = -1.0, False, 0.5, False
    if key in RANGES:
        r_lo, r_hi, _, r_lo_in, r_hi_in, _ = RANGES[key]
        if r_lo > lo or (r_lo == lo and not r_lo_in):
            lo, lo_in = float(r_lo), r_lo_in
        if r_hi < hi or (r_hi == hi and not r_hi_in):
            hi, hi_in = float(r_hi), r_hi_in
    out = {}
    if math.isfinite(lo):
        out["minimum" if lo_in else "exclusiveMinimum"] = lo
    if math.isfinite(hi):
        out["maximum" if hi_in else "exclusiveMaximum"] = hi
    return out


def _property(spec) -> dict:
    key, attr, unit, conv, check, default = spec
    if conv is sc._text:
        prop = {"type": "string", "pattern": r"\S"}
        if check is sc._excitation:
            prop = {"type": "string", "enum": list(sc.MISALIGNMENT_EXCITATIONS)}
    elif conv is sc._bool:
        prop = {"type": "boolean"}
    elif conv is sc._dofs:
        prop = {"type": "array", "minItems": 1, "items": {"type": "string", "enum": list(sc._DOF_INPUT)}}
    else:
        bounds = _bounds(key, check)
        if conv is sc._int:          # integer bounds written as integers
            bounds = {k: int(v) if float(v).is_integer() else v for k, v in bounds.items()}
        prop = {"type": "integer" if conv is sc._int else "number", **bounds}
    text = [f"unit {unit}" if unit else "", f"read as {attr}" + (" (SI)" if unit else ""), KEY_TEXT.get(key, "")]
    if key in RANGES:
        text.append(f"plausible: {RANGES[key][5]}")
    if default is sc.FROM_LAW:
        text.append(FROM_LAW_TEXT)
    prop["description"] = "; ".join(t for t in text if t)
    if default not in (sc._REQ, sc.FROM_LAW):
        typed = default / _scale(conv) if conv not in (sc._text, sc._int, sc._bool, sc._dofs) else default
        prop["default"] = round(typed, 12) if isinstance(typed, float) else typed
    return prop


def _table_schema(name: str) -> dict:
    specs, cls, is_array = TABLES[name]
    doc = (cls.__doc__ or "").strip()
    generated = doc.startswith(cls.__name__ + "(")      # dataclass's generated signature, not prose
    item = {"type": "object",
            "description": "" if generated else " ".join(doc.split()),
            "properties": {s[0]: _property(s) for s in specs},
            "required": [s[0] for s in specs if s[5] is sc._REQ],
            "additionalProperties": False}
    if not item["description"]:
        del item["description"]
    if is_array:
        return {"type": "array", "items": item}
    return item


def scene_schema() -> dict:
    """The JSON Schema of a rotor scene document (the parsed TOML)."""
    props = {"schema": {"type": "string", "enum": [sc.SCHEMA], "description": TOP_TEXT["schema"]},
             "name": {"type": "string", "pattern": r"\S", "description": TOP_TEXT["name"]},
             "title": {"type": "string", "pattern": r"\S", "description": TOP_TEXT["title"]},
             "source": {"type": "string", "description": TOP_TEXT["source"]},
             "notes": {"description": TOP_TEXT["notes"]},
             "assumptions": {"description": TOP_TEXT["assumptions"]}}
    for name in TABLES:
        props[name] = _table_schema(name)
    props["stations"]["minItems"] = 1
    return {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": f"ringcontact rotor scene ({sc.SCHEMA})",
        "description": "A rotor scene TOML file (rotor/scenes/*.toml), generated by docs/_ext/scene_schema.py from "
                       "rotor/model/scene.py and contact/plausible.py. Checked by the parser but not expressible "
                       "here: " + " | ".join(CROSS_CHECKS),
        "type": "object",
        "properties": props,
        "required": ["schema", "name", "title", "stations"],
        "additionalProperties": False,
    }


def schema_text() -> str:
    return json.dumps(scene_schema(), indent=2, ensure_ascii=False) + "\n"


# ------------------------------------------------------------------------------------------------
# rows of the documentation's scene reference (docs/_ext/ringcontact_docs.py)
# ------------------------------------------------------------------------------------------------
def _allowed(prop: dict) -> str:
    if "enum" in prop:
        return " | ".join(str(v) for v in prop["enum"])
    if prop.get("type") == "array":
        return "list of " + " | ".join(prop["items"]["enum"])
    lo = ("[" + f"{prop['minimum']:g}") if "minimum" in prop else ("(" + f"{prop['exclusiveMinimum']:g}"
                                                                      if "exclusiveMinimum" in prop else "(-inf")
    hi = (f"{prop['maximum']:g}" + "]") if "maximum" in prop else (f"{prop['exclusiveMaximum']:g}" + ")"
                                                                  if "exclusiveMaximum" in prop else "inf)")
    if prop.get("type") in ("number", "integer"):
        return f"{lo}, {hi}"
    return "non-empty" if prop.get("pattern") else "any"


def key_rows(schema: dict, top: bool = False) -> list[list[str]]:
    """Rows ``key, type, required, meaning`` of the top-level keys that are not tables."""
    rows = []
    for key, prop in schema["properties"].items():
        if prop.get("type") in ("object", "array"):
            continue
        rows.append([key, prop.get("type", "any"), "yes" if key in schema["required"] else "no",
                     prop["description"] + (f": {prop['enum'][0]}" if "enum" in prop else "")])
    return rows


def table_rows(schema: dict) -> list[tuple[str, str, list[list[str]]]]:
    """``(heading, description, rows)`` per TOML table; rows ``key, type/unit, required/default,
    allowed, notes``."""
    out = []
    for name in TABLES:
        prop = schema["properties"][name]
        item = prop["items"] if prop["type"] == "array" else prop
        heading = f"[[{name}]]" if prop["type"] == "array" else f"[{name}]"
        rows = []
        for key, p in item["properties"].items():
            unit = p["description"].split(";")[0].removeprefix("unit ") if p["description"].startswith("unit ") else ""
            need = ("required" if key in item["required"] else "required unless `law` is calibrated"
                    if FROM_LAW_TEXT in p["description"] else f"default {json.dumps(p.get('default'), ensure_ascii=False)}")
            notes = "; ".join(t for t in p["description"].split("; ") if not t.startswith("unit "))
            rows.append([key, p["type"] + (f" [{unit}]" if unit else ""), need, _allowed(p), notes])
        optional = "" if name in schema["required"] else " Optional."
        out.append((heading, (item.get("description", "") + optional).strip(), rows))
    return out


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    text = schema_text()
    if argv == ["--check"]:
        current = SCHEMA_FILE.read_text(encoding="utf-8") if SCHEMA_FILE.exists() else ""
        if current != text:
            print(f"{SCHEMA_FILE.relative_to(ROOT)} is out of date: run python docs/_ext/scene_schema.py",
                  file=sys.stderr)
            return 1
        return 0
    if argv:
        print("usage: python docs/_ext/scene_schema.py [--check]", file=sys.stderr)
        return 2
    tmp = SCHEMA_FILE.with_suffix(".tmp")
    tmp.write_text(text, encoding="utf-8")
    tmp.replace(SCHEMA_FILE)
    print(f"wrote {SCHEMA_FILE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
