"""A calibrated-law document checked as strictly as a scene: every field's type and range, the validity ranges'
consistency, and a law that behaves like a contact law over its validity range.

The checksum (:func:`contact.dataset.check_document_sha256`) only detects accidents: a file edited and its
checksum recomputed is checked here like any other input. Each refusal is one
:class:`~contact.errors.DatasetError` line naming the file, the key, the value as written with its unit and
what is allowed. The ranges are those of :data:`contact.plausible.RANGES` (one table for ring-pair files,
law files and scenes): a law file holds what ``ringcontact bearing`` can make from a ring-pair file; a rotor
scene then checks the law's geometry against its own ranges (:mod:`rotor.model.loose_support_scene`).
"""
from __future__ import annotations

import json
import math

import numpy as np

from contact import plausible
import contact.calibrate.spline as spline
import contact.calibrate.tilt_correction as tilt_correction
from contact.calibrate.families import FAMILIES, PARAMETERS
from contact.errors import DatasetError, InputError

#: geometry key -> (unit in the file, row of contact.plausible.RANGES, SI per unit of that row)
GEOMETRY_FIELDS = {
    "clearance_m": ("m", "ring_length_mm", 1e-3),
    "width_m": ("m", "ring_length_mm", 1e-3),
    "radius_m": ("m", "ring_length_mm", 1e-3),
    "bearing_thickness_m": ("m", "ring_length_mm", 1e-3),
    "support_thickness_m": ("m", "ring_length_mm", 1e-3),
    "bearing_E_Pa": ("Pa", "ring_modulus_gpa", 1e9),
    "bearing_nu": ("", "nu", 1.0),
    "support_E_Pa": ("Pa", "ring_modulus_gpa", 1e9),
    "support_nu": ("", "nu", 1.0),
}
PLANES = ("strain", "stress", "3d")
#: parameter -> (row of contact.plausible.RANGES, unit in the file); None: finite and > 0 only
PARAMETER_ROWS = {
    "stiffness_factor": ("stiffness_factor", "-"),
    "foundation_modulus_Pa_per_m": ("foundation_modulus_pa_per_m", "Pa/m"),
    "coefficient_N_per_m_pow_n_plus_1": (None, "N/m^(n+1)"),
    "exponent": ("law_exponent", "-"),
    "far_field_constant": ("far_field_constant", "-"),
}
#: penetrations (fractions of the validity range) where the law must be finite, > 0 and rising
_PROBES = np.linspace(0.0, 1.0, 9)
#: longest name or scene label of a law (a file name is made from it)
NAME_MAX_CHARS = 200


def _typed(value) -> str:
    """A JSON value as written in the file."""
    try:
        return json.dumps(value, allow_nan=True)[:60]
    except (TypeError, ValueError):
        return repr(value)[:60]


def _number(source: str, key: str, value, unit: str) -> float:
    u = f" ({unit})" if unit and unit != "-" else ""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise DatasetError(f"{source}: {key} = {_typed(value)}: must be a number{u}")
    v = float(value)
    if not math.isfinite(v):
        raise DatasetError(f"{source}: {key} = {_typed(value)}: must be finite{u}")
    return v


def _in_row(source: str, key: str, value, unit: str, row: str, scale: float) -> float:
    v = _number(source, key, value, unit)
    try:
        return plausible.check_scaled(row, v, scale, key, f"{v:g}", "" if unit == "-" else unit)
    except InputError as exc:
        raise DatasetError(f"{source}: {exc}") from None


def _table(source: str, doc: dict, key: str, required: bool = True) -> dict:
    if key not in doc and not required:
        return {}
    value = doc.get(key)
    if not isinstance(value, dict):
        raise DatasetError(f"{source}: {key} = {_typed(value)}: must be a JSON object"
                           + (" (missing)" if key not in doc else ""))
    return value


def _label(source: str, key: str, value) -> str:
    if not isinstance(value, str) or not value.strip() or len(value) > NAME_MAX_CHARS \
            or not value.isprintable():
        raise DatasetError(f"{source}: {key} = {_typed(value)}: must be a one-line text of 1 to "
                           f"{NAME_MAX_CHARS} printable characters")
    return value


def check_geometry(source: str, geometry: dict) -> dict:
    """The ``geometry`` object of a law file, each field typed and in range; returns it in SI (float)."""
    missing = [k for k in (*GEOMETRY_FIELDS, "plane") if k not in geometry]
    if missing:
        raise DatasetError(f"{source}: geometry: missing field {missing[0]!r}")
    unknown = sorted(set(geometry) - set(GEOMETRY_FIELDS) - {"plane"})
    if unknown:
        raise DatasetError(f"{source}: geometry.{unknown[0]}: unknown field; allowed fields are "
                           f"{', '.join([*GEOMETRY_FIELDS, 'plane'])}")
    out = {key: _in_row(source, f"geometry.{key}", geometry[key], unit, row, scale)
           for key, (unit, row, scale) in GEOMETRY_FIELDS.items()}
    if geometry["plane"] not in PLANES:
        raise DatasetError(f"{source}: geometry.plane = {_typed(geometry['plane'])}: must be one of "
                           f"{', '.join(PLANES)}")
    top = plausible.MAX_CLEARANCE_TO_RADIUS * out["radius_m"]
    if out["clearance_m"] > top * (1 + 1e-9):
        raise DatasetError(f"{source}: geometry.clearance_m = {out['clearance_m']:g} m: must be <= "
                           f"{100 * plausible.MAX_CLEARANCE_TO_RADIUS:g} % of geometry.radius_m ({top:g} m): a "
                           "clearance that large is not a bearing seat")
    out["plane"] = geometry["plane"]
    return out


def check_validity(source: str, validity: dict, radius_m: float) -> tuple[float, float, float]:
    """``(penetration_min_m, penetration_max_m, tilt_max_rad)`` of the ``validity`` object, checked.

    0 <= min < max <= 2 % of the contact radius (:data:`contact.plausible.MAX_PENETRATION_TO_RADIUS`);
    ``tilt_rad`` (if given) 0; ``tilt_max_rad`` (if given) in [0, :data:`contact.plausible.MAX_TILT_ARCMIN`].
    """
    lo = _number(source, "validity.penetration_min_m", validity.get("penetration_min_m"), "m")
    hi = _number(source, "validity.penetration_max_m", validity.get("penetration_max_m"), "m")
    top = plausible.MAX_PENETRATION_TO_RADIUS * radius_m
    if lo < 0:
        raise DatasetError(f"{source}: validity.penetration_min_m = {lo:g} m: must be >= 0")
    if not lo < hi:
        raise DatasetError(f"{source}: validity.penetration_max_m = {hi:g} m: must be > validity.penetration_min_m "
                           f"= {lo:g} m (a range of penetrations, low to high)")
    if hi > top * (1 + 1e-9):
        raise DatasetError(f"{source}: validity.penetration_max_m = {hi:g} m: must be <= "
                           f"{100 * plausible.MAX_PENETRATION_TO_RADIUS:g} % of geometry.radius_m ({top:g} m; "
                           "small-strain model)")
    if "tilt_rad" in validity and _number(source, "validity.tilt_rad", validity["tilt_rad"], "rad") != 0.0:
        raise DatasetError(f"{source}: validity.tilt_rad = {_typed(validity['tilt_rad'])} rad: must be 0 (the "
                           "straight-ring range; tilt_max_rad gives the tilt range)")
    tilt = _number(source, "validity.tilt_max_rad", validity.get("tilt_max_rad", 0.0), "rad")
    tilt_top = plausible.MAX_TILT_ARCMIN * math.pi / (180 * 60)
    if not 0.0 <= tilt <= tilt_top * (1 + 1e-9):
        raise DatasetError(f"{source}: validity.tilt_max_rad = {tilt:g} rad ({tilt / tilt_top * plausible.MAX_TILT_ARCMIN:g} "
                           f"arcmin): must be in [0, {plausible.MAX_TILT_ARCMIN:g}] arcmin (small-rotation model)")
    return lo, hi, tilt


def check_parameters(source: str, family: str, doc: dict) -> tuple[dict, dict, dict]:
    """``(parameters, parameter_std, parameter_units)`` of the family, each typed and in range, with a tilt correction's
    ``tilt_*`` parameters (:func:`contact.calibrate.tilt_correction.check_parameters`) if the law has one."""
    params, std, units = (_table(source, doc, k) for k in ("parameters", "parameter_std", "parameter_units"))
    tilt = {k: v for k, v in params.items() if k.startswith("tilt_")}
    if tilt and family not in ("foundation", spline.FAMILY):
        raise DatasetError(f"{source}: parameters.{sorted(tilt)[0]}: a tilt correction is for the slice-integrated "
                           f"families (foundation, {spline.FAMILY}), not {family!r}")
    wrong = tilt_correction.check_parameters(tilt)
    if wrong is not None:
        raise DatasetError(f"{source}: parameters.{wrong} (family {family!r})")
    tilt = {k: float(v) for k, v in tilt.items()}
    params = {k: v for k, v in params.items() if not k.startswith("tilt_")}
    out, out_std, out_units = _family_parameters(source, family, params, std, units)
    return ({**out, **tilt}, {**out_std, **{k: 0.0 for k in tilt}},
            {**out_units, **{k: str(units.get(k, "-")) for k in tilt}})


def _family_parameters(source: str, family: str, params: dict, std: dict, units: dict) -> tuple[dict, dict, dict]:
    """:func:`check_parameters` of the family's own parameters (a tilt correction's taken out)."""
    if family == spline.FAMILY:
        wrong = spline.check_parameters(params)
        if wrong is not None:
            raise DatasetError(f"{source}: parameters.{wrong} (family {family!r})")
        out = {k: float(v) for k, v in params.items() if k == "knot_count" or k.startswith(("log_penetration_",
                                                                                           "log_correction_",
                                                                                           "log_slope_"))}
        return out, {k: 0.0 for k in out}, {k: str(units.get(k, "-")) for k in out}
    out, out_std = {}, {}
    for name, unit in PARAMETERS[family]:
        if name not in params:
            raise DatasetError(f"{source}: parameters: missing {name!r} (family {family!r} has "
                               f"{', '.join(n for n, _ in PARAMETERS[family])})")
        row, shown_unit = PARAMETER_ROWS[name]
        key = f"parameters.{name}"
        if row is None:
            v = _number(source, key, params[name], shown_unit)
            if not v > 0:
                raise DatasetError(f"{source}: {key} = {v:g} {shown_unit}: must be > 0")
            out[name] = v
        else:
            out[name] = _in_row(source, key, params[name], shown_unit, row, 1.0)
        s = _number(source, f"parameter_std.{name}", std.get(name, 0.0), shown_unit)
        if s < 0:
            raise DatasetError(f"{source}: parameter_std.{name} = {s:g}: must be >= 0 (a standard deviation)")
        out_std[name] = s
    if not all(isinstance(v, str) for v in units.values()):
        raise DatasetError(f"{source}: parameter_units: each unit must be a text")
    return out, out_std, dict(units)


def check_document(doc: dict, source: str) -> dict:
    """The fields of a calibrated-law document (schema, version and checksum already checked), in SI.

    Returns the keyword arguments of :class:`contact.calibrate.law.CalibratedLaw` except ``geometry``,
    which is returned as a dict of SI values (``"geometry"``).
    """
    name = _label(source, "name", doc.get("name"))
    scene = _label(source, "scene", doc.get("scene"))
    family = doc.get("family")
    if family not in FAMILIES:
        raise DatasetError(f"{source}: family = {_typed(family)}: must be one of {', '.join(FAMILIES)}")
    geometry = check_geometry(source, _table(source, doc, "geometry"))
    params, std, units = check_parameters(source, family, doc)
    lo, hi, tilt = check_validity(source, _table(source, doc, "validity"), geometry["radius_m"])
    return dict(name=name, scene=scene, family=family, parameters=params, parameter_std=std, parameter_units=units,
                geometry=geometry, validity_penetration_m=(lo, hi), dataset=dict(_table(source, doc, "dataset")),
                fit=dict(_table(source, doc, "fit", required=False)), validity_tilt_max_rad=tilt,
                provenance=dict(_table(source, doc, "provenance", required=False)))


def check_behaviour(law, source: str) -> None:
    """The law's force over its validity range: finite, > 0 and rising (else a contact law it is not)."""
    lo, hi = law.validity_penetration_m
    pen = lo + (hi - lo) * _PROBES
    pen = pen[pen > 0]
    with np.errstate(all="ignore"):
        force = np.asarray(law.force(pen).force_N, dtype=float)
    bad = ~np.isfinite(force) | (force <= 0)
    if np.any(bad):
        i = int(np.argmax(bad))
        raise DatasetError(f"{source}: the law gives {force[i]:g} N at a penetration of {pen[i] * 1e3:g} mm inside "
                           f"its validity range: a contact law's force must be finite and > 0 there (parameters "
                           f"{law.parameters})")
    if np.any(np.diff(force) < 0):
        i = int(np.argmax(np.diff(force) < 0))
        raise DatasetError(f"{source}: the law's force falls from {force[i]:g} N to {force[i + 1]:g} N between "
                           f"{pen[i] * 1e3:g} and {pen[i + 1] * 1e3:g} mm: a contact law's force must rise with "
                           "the penetration")
