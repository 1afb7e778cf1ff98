"""Field tables of the rotor scene file: converters to SI, checks, and the parse of one TOML table.

A field is a :data:`Spec` ``(toml key, python attribute, unit shown in messages, converter, check,
default)``; :func:`parse_table` turns one TOML table into the keyword arguments of a dataclass of
:mod:`rotor.model.scene`, naming the file, entry, field, value and unit in every refusal;
:func:`disk_fields` and :func:`bearing_fields` complete an entry whose fields depend on each other.
"""
from __future__ import annotations

import math
from typing import Any, Callable

from contact.errors import InputError
from contact.plausible import check_field as _plausible

_DOF_INPUT = {"y": "y", "z": "z", "θy": "θy", "θz": "θz", "theta_y": "θy", "theta_z": "θz"}

_REQ = object()  # marker: field is required
FROM_GEOMETRY = object()  # marker: required unless the entry's geometry keys give it (a disk's mass and inertias)


def _num(scale: float = 1.0):
    return lambda v: float(v) * scale


_ID, _MM = _num(), _num(1e-3)
_GPA, _DEG = _num(1e9), _num(math.pi / 180)
_MRAD = _num(1e-3)
_GMM = _num(1e-6)        # g·mm -> kg·m
_RPM = _num(math.pi / 30)


def _text(v):
    if not isinstance(v, str) or not v.strip():
        raise TypeError("must be a non-empty string")
    return v


def _int(v):
    if isinstance(v, bool) or not isinstance(v, int):
        raise TypeError("must be an integer")
    return v


def _bool(v):
    if not isinstance(v, bool):
        raise TypeError("must be true or false")
    return v


def _dofs(v):
    if not isinstance(v, list) or not v:
        raise TypeError("must be a non-empty list of 'y', 'z', 'theta_y', 'theta_z'")
    out = []
    for item in v:
        if item not in _DOF_INPUT:
            raise TypeError(f"unknown DOF {item!r} (use 'y', 'z', 'theta_y', 'theta_z')")
        out.append(_DOF_INPUT[item])
    return tuple(out)


# checks on the SI value
def _pos(v):
    return v > 0


def _nonneg(v):
    return v >= 0


def _any(v):
    return True


def _nu(v):
    return -1 < v < 0.5


#: message of each check, by check function (rotor.model.scene adds its own)
CHECK_TEXT = {_pos: "must be > 0", _nonneg: "must be >= 0", _nu: "must be in (-1, 0.5)", _any: ""}

# (toml key, python attribute, unit shown in messages, converter, check, default)
Spec = tuple[str, str, str, Callable[[Any], Any], Callable[[Any], bool], Any]

_UNIT_TOKENS = {"mm", "kg", "gpa", "n", "g", "deg", "mrad", "rpm", "s", "m"}
_IDT, _RPMT = _num(), _num(math.pi / 30)    # the same converters for keys that also take a speed table (a list)
#: converters whose keys take a list (a speed table) as well as one number
TABLE_CONVERTERS = (_IDT, _RPMT)


def _bases(specs: list[Spec]) -> dict[str, str]:
    """Map each field's base name (its key cut at the first unit token) to the full key."""
    out = {}
    for key, _, unit, *_ in specs:
        if not unit:
            continue
        tokens = key.split("_")
        for i, tok in enumerate(tokens):
            if i > 0 and tok in _UNIT_TOKENS:
                out["_".join(tokens[:i])] = key
                break
    return out


def parse_table(raw: Any, specs: list[Spec], where: str, cls):
    if not isinstance(raw, dict):
        raise InputError(f"{where}: must be a table, got {type(raw).__name__}")
    known = {s[0] for s in specs}
    bases = _bases(specs)
    for key in raw:
        if key in known:
            continue
        for base, good in sorted(bases.items(), key=lambda kv: -len(kv[0])):
            if key.startswith(base + "_"):
                raise InputError(f"{where}.{key}: unknown unit {key[len(base) + 1:]!r} for {base!r}; "
                                 f"write it as {good!r}")
        raise InputError(f"{where}.{key}: unknown field; allowed fields are {', '.join(sorted(known))}")
    kwargs = {}
    for key, attr, unit, conv, check, default in specs:
        if key not in raw:
            if default is _REQ:
                raise InputError(f"{where}: missing field {key!r}" + (f" ({unit})" if unit else ""))
            kwargs[attr] = default
            continue
        value = raw[key]
        if isinstance(value, list) and conv in TABLE_CONVERTERS:      # a speed table: each entry checked alike
            if not 2 <= len(value) <= 200:
                raise InputError(f"{where}.{key} = {value!r}: a speed table has 2 to 200 entries")
            kwargs[attr] = tuple(_field_value(where, key, unit, conv, check, v) for v in value)
            continue
        kwargs[attr] = _field_value(where, key, unit, conv, check, value)
    return kwargs


def _field_value(where: str, key: str, unit: str, conv, check, value):
    """One typed value converted to SI and checked (sign, finite, plausible range)."""
    try:
        if conv not in (_text, _int, _bool, _dofs) and (isinstance(value, bool) or not isinstance(value, (int, float))):
            raise TypeError("must be a number")
        si = conv(value)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{where}.{key} = {value!r}: {exc}") from None
    shown = f"{value:g}" if isinstance(value, (int, float)) and not isinstance(value, bool) else repr(value)
    if isinstance(si, float) and not math.isfinite(si):
        raise InputError(f"{where}.{key} = {shown} {unit}: must be finite")
    if not check(si):
        raise InputError(f"{where}.{key} = {shown} {unit}".rstrip() + f": {CHECK_TEXT[check]}")
    _plausible(where, key, value, shown, si)      # inside contact.plausible.RANGES[key]
    return si


def disk_fields(materials: dict):
    """A disk's mass and inertias as given, or from its geometry (``outer_diameter_mm``, ``thickness_mm``,
    ``material``, optional ``inner_diameter_mm``), never both."""
    from rotor.model.elements import disk_properties

    def finish(kw: dict, where: str) -> dict:
        geo = {k: kw.pop(a) for k, a in (("outer_diameter_mm", "outer_diameter_m"), ("inner_diameter_mm", "inner_diameter_m"),
                                        ("thickness_mm", "thickness_m"), ("material", "material"))}
        given = [k for k in ("mass_kg", "polar_inertia_kg_m2", "diametral_inertia_kg_m2") if kw[k] is not FROM_GEOMETRY]
        if any(v is not None for v in geo.values()):
            if given:
                raise InputError(f"{where}.{given[0]}: give either the mass and inertias or the geometry "
                                 f"(outer_diameter_mm, thickness_mm, material), not both")
            for k in ("outer_diameter_mm", "thickness_mm", "material"):
                if geo[k] is None:
                    raise InputError(f"{where}: missing field {k!r} (a disk from geometry needs outer_diameter_mm, "
                                     f"thickness_mm and material; inner_diameter_mm is optional)")
            bore = geo["inner_diameter_mm"] or 0.0
            if bore >= geo["outer_diameter_mm"]:
                raise InputError(f"{where}.inner_diameter_mm = {bore * 1e3:g} mm: must be < outer_diameter_mm = "
                                 f"{geo['outer_diameter_mm'] * 1e3:g} mm")
            if geo["material"] not in materials:
                raise InputError(f"{where}.material = {geo['material']!r}: no such material (have {', '.join(materials)})")
            m, ip, idd = disk_properties(materials[geo["material"]].density_kg_m3, geo["outer_diameter_mm"], bore,
                                         geo["thickness_mm"])
            kw.update(mass_kg=m, polar_inertia_kg_m2=ip, diametral_inertia_kg_m2=idd)
        for k, unit in (("mass_kg", "kg"), ("polar_inertia_kg_m2", "kg·m^2"), ("diametral_inertia_kg_m2", "kg·m^2")):
            if kw[k] is FROM_GEOMETRY:
                raise InputError(f"{where}: missing field {k!r} ({unit}) (or give the disk's geometry: "
                                 f"outer_diameter_mm, thickness_mm, material)")
        return kw
    return finish


def bearing_fields(kw: dict, where: str) -> dict:
    """``stiffness_n_per_m`` is required unless both direct stiffnesses are given; a coefficient given as a
    list follows ``speed_table_rpm`` (ascending, the same length), which is then required."""
    if kw["stiffness_n_m"] is None and (kw["stiffness_yy_n_m"] is None or kw["stiffness_zz_n_m"] is None):
        raise InputError(f"{where}: missing field 'stiffness_n_per_m' (N/m) (or give both stiffness_yy_n_per_m and "
                         f"stiffness_zz_n_per_m)")
    table = kw["speed_table_rad_s"]
    if isinstance(table, float):
        raise InputError(f"{where}.speed_table_rpm = {table * 30 / math.pi:g} rpm: must be a list of speeds (rpm)")
    tables = {k: v for k, v in kw.items() if isinstance(v, tuple) and k != "speed_table_rad_s"}
    if tables and not table:
        raise InputError(f"{where}.{next(iter(tables)).replace('_n_m', '_n_per_m').replace('_n_s_m', '_n_s_per_m')}: "
                         f"a list needs speed_table_rpm (the speeds it is given at, rpm)")
    if table and any(b <= a for a, b in zip(table, table[1:])):
        raise InputError(f"{where}.speed_table_rpm = {[round(w * 30 / math.pi, 6) for w in table]}: must be ascending")
    for k, v in tables.items():
        if len(v) != len(table):
            key = k.replace("_n_m", "_n_per_m").replace("_n_s_m", "_n_s_per_m")
            raise InputError(f"{where}.{key}: {len(v)} values for {len(table)} speeds of speed_table_rpm")
    if table and not tables:
        raise InputError(f"{where}.speed_table_rpm: no coefficient is a list (give e.g. stiffness_yy_n_per_m as one "
                         f"value per speed)")
    return kw
