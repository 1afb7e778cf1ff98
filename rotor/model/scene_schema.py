"""JSON Schema of a rotor scene TOML file, generated from the scene parser's own field tables.

The source of truth is :mod:`rotor.model.scene` (each table's field specifications: key, unit, converter,
check, default) and :data:`contact.plausible.RANGES` (the plausible range of a key); the parser enforces
both, and this module writes the same rules as a JSON Schema (draft 2020-12) for editors
(``ringcontact scenes schema rotor``; ``docs/scene.schema.json``, written by docs/_ext/scene_schema.py,
which also draws the rows of the documentation's scene reference from it). What a schema cannot say is
checked by the parser only and listed in :data:`CROSS_CHECKS`.
"""
from __future__ import annotations

import json
import math

from contact.plausible import RANGES
from rotor.model import scene as sc

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
    "gravity": (sc._GRAVITY, sc.Gravity, False),
    "static_loads": (sc._STATIC_LOAD, sc.StaticLoad, True),
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
    "bearings: stiffness_n_per_m is required unless both stiffness_yy_n_per_m and stiffness_zz_n_per_m are given; "
    "the direct terms default to stiffness_n_per_m / damping_n_s_per_m, the cross terms to 0",
    "disks: mass_kg and the inertias, or outer_diameter_mm, width_mm and material (a [[materials]] entry) with an "
    "optional inner_diameter_mm < outer_diameter_mm, never both",
    "static_loads: `station` names a station",
    "names are unique within materials and stations; supports and elements do not reuse a station name",
)


# what a key's value means, where its name and unit do not say it
KEY_TEXT = {
    "law": "contact law: conformal (the paper's, as published), pereira, calibrated:<name> (a law shipped in "
           "contact/calibrated/) or the path of a calibrated-law file (.json, relative to the scene file's folder); "
           "a calibrated law must hold for this table's geometry (rotor/model/loose_support_scene.py)",
    "stiffness_yz_n_per_m": "cross-coupled stiffness: force on y per unit z displacement (sign as typed; a fluid-film "
                            "bearing has k_yz = -k_zy)",
    "stiffness_zy_n_per_m": "cross-coupled stiffness: force on z per unit y displacement",
    "acceleration_y_m_per_s2": "gravity along the rotor's y axis on every mass (e.g. -9.81 with y pointing up)",
    "acceleration_z_m_per_s2": "gravity along the rotor's z axis on every mass",
}
FROM_GEOMETRY_TEXT = ("required unless the disk's geometry is given (outer_diameter_mm, thickness_mm, material, optional "
                      "inner_diameter_mm), never both")
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
        if conv in sc.TABLE_CONVERTERS:          # one value, or one per speed of the bearing's speed table
            prop = {"type": ["number", "array"], **bounds, "items": {"type": "number", **bounds}, "minItems": 2,
                    "maxItems": 200}
    text = [f"unit {unit}" if unit else "", f"read as {attr}" + (" (SI)" if unit else ""), KEY_TEXT.get(key, "")]
    if key in RANGES:
        text.append(f"plausible: {RANGES[key][5]}")
    if default is sc.FROM_LAW:
        text.append(FROM_LAW_TEXT)
    if default is sc.FROM_GEOMETRY:
        text.append(FROM_GEOMETRY_TEXT)
    prop["description"] = "; ".join(t for t in text if t)
    if default not in (sc._REQ, sc.FROM_LAW, sc.FROM_GEOMETRY, None, ()):
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
        "description": "A rotor scene TOML file (rotor/scenes/*.toml), generated by rotor/model/scene_schema.py from "
                       "rotor/model/scene.py and contact/plausible.py. Checked by the parser but not expressible "
                       "here: " + " | ".join(CROSS_CHECKS),
        "type": "object",
        "properties": props,
        "required": ["schema", "name", "title", "stations"],
        "additionalProperties": False,
    }


def schema_text() -> str:
    return json.dumps(scene_schema(), indent=2, ensure_ascii=False) + "\n"
