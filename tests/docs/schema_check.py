"""A minimal JSON Schema validator for the keywords ``docs/scene.schema.json`` uses (test helper).

Supported: ``type`` (a name or a list of names), ``properties``, ``required``, ``additionalProperties``
(true/false), ``minimum``, ``exclusiveMinimum``, ``maximum``, ``exclusiveMaximum``, ``enum``, ``items``,
``minItems``, ``maxItems``, ``pattern``; annotations (``$schema``, ``$id``, ``title``, ``description``,
``default``) are ignored. Any other keyword raises ``ValueError``: a schema that starts using one
must extend this helper (or the suite must take on the ``jsonschema`` package), never be
validated partially. Semantics follow draft 2020-12 for these keywords; booleans are not numbers.
"""
from __future__ import annotations

import re

ANNOTATIONS = {"$schema", "$id", "title", "description", "default"}
KEYWORDS = {"type", "properties", "required", "additionalProperties", "minimum", "exclusiveMinimum", "maximum",
            "exclusiveMaximum", "enum", "items", "minItems", "maxItems", "pattern"}


def _is_type(value, name) -> bool:
    if isinstance(name, list):
        return any(_is_type(value, n) for n in name)
    if name == "object":
        return isinstance(value, dict)
    if name == "array":
        return isinstance(value, list)
    if name == "string":
        return isinstance(value, str)
    if name == "boolean":
        return isinstance(value, bool)
    if name == "integer":
        return isinstance(value, int) and not isinstance(value, bool) or (isinstance(value, float) and value.is_integer())
    if name == "number":
        return isinstance(value, (int, float)) and not isinstance(value, bool)
    if name == "null":
        return value is None
    raise ValueError(f"unsupported type {name!r}")


def errors(value, schema: dict, where: str = "$") -> list[str]:
    """Every violation of ``schema`` by ``value``, as ``"path: what"`` strings (empty: valid)."""
    unknown = set(schema) - KEYWORDS - ANNOTATIONS
    if unknown:
        raise ValueError(f"{where}: schema keyword(s) {sorted(unknown)} not supported by this validator")
    out: list[str] = []
    if "type" in schema and not _is_type(value, schema["type"]):
        return [f"{where}: {value!r} is not of type {schema['type']}"]
    if "enum" in schema and value not in schema["enum"]:
        out.append(f"{where}: {value!r} not one of {schema['enum']}")
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        for key, bad in (("minimum", lambda v, b: v < b), ("exclusiveMinimum", lambda v, b: v <= b),
                         ("maximum", lambda v, b: v > b), ("exclusiveMaximum", lambda v, b: v >= b)):
            if key in schema and bad(value, schema[key]):
                out.append(f"{where}: {value!r} violates {key} {schema[key]!r}")
    if isinstance(value, str) and "pattern" in schema and not re.search(schema["pattern"], value):
        out.append(f"{where}: {value!r} does not match {schema['pattern']!r}")
    if isinstance(value, list):
        if "minItems" in schema and len(value) < schema["minItems"]:
            out.append(f"{where}: {len(value)} items, fewer than {schema['minItems']}")
        if "maxItems" in schema and len(value) > schema["maxItems"]:
            out.append(f"{where}: {len(value)} items, more than {schema['maxItems']}")
        if "items" in schema:
            for i, item in enumerate(value):
                out += errors(item, schema["items"], f"{where}[{i}]")
    if isinstance(value, dict):
        props = schema.get("properties", {})
        for key in schema.get("required", []):
            if key not in value:
                out.append(f"{where}: missing required {key!r}")
        for key, item in value.items():
            if key in props:
                out += errors(item, props[key], f"{where}.{key}")
            elif schema.get("additionalProperties", True) is False:
                out.append(f"{where}: {key!r} is not allowed")
            elif isinstance(schema.get("additionalProperties"), dict):
                raise ValueError(f"{where}: additionalProperties as a schema is not supported")
    return out


def check_schema_keywords(schema, where: str = "$") -> None:
    """Raise ``ValueError`` if any (nested) schema uses a keyword this validator does not implement."""
    if not isinstance(schema, dict):
        return
    unknown = set(schema) - KEYWORDS - ANNOTATIONS
    if unknown:
        raise ValueError(f"{where}: schema keyword(s) {sorted(unknown)} not supported by this validator")
    for key, sub in schema.get("properties", {}).items():
        check_schema_keywords(sub, f"{where}.properties.{key}")
    if "items" in schema:
        check_schema_keywords(schema["items"], f"{where}.items")
