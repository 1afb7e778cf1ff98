"""A rotor scene back to the TOML file it can be read from (the inverse of :func:`rotor.model.scene.parse_scene`).

:func:`scene_to_toml` writes every table of a :class:`~rotor.model.scene.Scene` with the keys, engineer units
and order of the parser's field tables (``rotor.model.scene._MATERIAL`` …, the one description of the file
format), so a scene built in Python becomes a file an engineer can read and edit, and reading that file gives
the same scene: each number is written as the shortest decimal whose conversion to SI gives back the SI value
bit for bit (``load(to_toml(s)) == s``, apart from ``path``, the file it was read from). A calibrated law named
by a file is written with the file's resolved path, so the TOML can be read from any folder.
"""
from __future__ import annotations

import json
import math

from rotor.model import scene as sc
from rotor.model.loose_support_scene import ANALYTIC_LAWS, CALIBRATED_PREFIX

# the Scene attributes written as [[arrays]] and as [tables] (each named as its TOML key), with their field specs
_ARRAYS = {"materials": sc._MATERIAL, "stations": sc._STATION, "shafts": sc._SHAFT, "disks": sc._DISK,
           "point_masses": sc._POINT_MASS, "bearings": sc._BEARING, "supports": sc._SUPPORT,
           "couplings": sc._COUPLING, "boundaries": sc._BOUNDARY, "static_loads": sc._STATIC_LOAD}
_TABLES = {"loose_support": sc._LOOSE, "misalignment": sc._MISALIGN, "analysis": sc._ANALYSIS, "gravity": sc._GRAVITY}
_DOF_OUTPUT = {"y": "y", "z": "z", "θy": "theta_y", "θz": "theta_z"}


def typed_number(si: float, to_si) -> float:
    """The number to type so that ``to_si(number) == si`` exactly: the shortest decimal of ``si`` divided by the
    unit's scale that converts back, else that quotient moved by the few ulps the division may have lost (the
    closest value when none converts back exactly)."""
    si = float(si)
    x = si / to_si(1.0)
    if not math.isfinite(x):
        return x
    for digits in range(1, 18):         # the shortest decimal first: 2000, not 2000.0000000000002
        y = float(f"{x:.{digits}g}")
        if to_si(y) == si:
            return y
    best = x
    for direction in (math.inf, -math.inf):
        y = x
        for _ in range(4):
            y = math.nextafter(y, direction)
            if to_si(y) == si:
                return y
            if abs(to_si(y) - si) < abs(to_si(best) - si):
                best = y
    return best


def _value(text_key: str, value, conv) -> str:
    """One TOML value: strings as JSON strings (a TOML basic string), booleans, integers, floats by repr."""
    if conv is sc._dofs:
        return json.dumps([_DOF_OUTPUT[d] for d in value], ensure_ascii=False)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, int) and conv is sc._int:
        return str(value)
    number = typed_number(value, conv)
    if not math.isfinite(number):
        raise ValueError(f"{text_key} = {number}: a TOML scene holds finite numbers only")
    return repr(float(number))


def _law_text(loose) -> str:
    """The ``law`` key: an analytic or shipped law as typed, a law file by its resolved path."""
    if loose.law in ANALYTIC_LAWS or loose.law.startswith(CALIBRATED_PREFIX) or not loose.law_file:
        return loose.law
    return str(loose.law_file)


def _entry_lines(entry, specs) -> list[str]:
    lines = []
    for key, attr, _unit, conv, _check, _default in specs:
        if not hasattr(entry, attr):       # an input only (a disk's geometry: its mass and inertias are written)
            continue
        value = getattr(entry, attr)
        if value is None or (isinstance(value, tuple) and not value):      # not given (a bearing's speed table)
            continue
        if key == "material":
            value = value.name
        elif key == "law":
            value = _law_text(entry)
        if isinstance(value, tuple) and conv is not sc._dofs:              # one value per speed of a speed table
            lines.append(f"{key} = [{', '.join(_value(key, v, conv) for v in value)}]")
            continue
        lines.append(f"{key} = {_value(key, value, conv)}")
    return lines


def scene_to_toml(scene: sc.Scene) -> str:
    """The TOML text of ``scene`` (schema ``ringcontact.rotor-scene/1``), readable by :func:`rotor.model.scene.load_scene`.

    Parameters
    ----------
    scene : rotor.model.scene.Scene
        Any scene, read from a file or built in Python (SI units).

    Returns
    -------
    str
        Every field written in the file's engineer units (``x_mm``, ``stiffness_n_per_m``, ``unbalance_g_mm``);
        ``notes`` of the original file are not kept.
    """
    out = [f"schema = {json.dumps(sc.SCHEMA)}", f"name = {json.dumps(scene.name, ensure_ascii=False)}",
           f"title = {json.dumps(scene.title, ensure_ascii=False)}"]
    if scene.source:
        out.append(f"source = {json.dumps(scene.source, ensure_ascii=False)}")
    for key, specs in _ARRAYS.items():
        for entry in getattr(scene, key):
            out += ["", f"[[{key}]]", *_entry_lines(entry, specs)]
    for key, specs in _TABLES.items():
        if getattr(scene, key) is not None:
            out += ["", f"[{key}]", *_entry_lines(getattr(scene, key), specs)]
    return "\n".join(out) + "\n"
