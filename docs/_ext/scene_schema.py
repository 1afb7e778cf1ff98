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

from rotor.model.scene_schema import (CROSS_CHECKS, FROM_LAW_TEXT, TABLES, TOP_TEXT, scene_schema,  # noqa: E402,F401
                                      schema_text)

SCHEMA_FILE = DOCS / "scene.schema.json"


# ------------------------------------------------------------------------------------------------
# rows of the documentation's scene reference (docs/_ext/ringcontact_docs.py)
# ------------------------------------------------------------------------------------------------
def _allowed(prop: dict) -> str:
    if "enum" in prop:
        return " | ".join(str(v) for v in prop["enum"])
    if prop.get("type") == ["number", "array"]:            # a value or a speed table of values
        return _allowed({**prop, "type": "number"}) + ", or a list of such (one per speed_table_rpm speed)"
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
            kind = " or ".join(p["type"]) if isinstance(p["type"], list) else p["type"]
            rows.append([key, kind + (f" [{unit}]" if unit else ""), need, _allowed(p), notes])
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
