"""The ``[loose_support]`` table of a rotor scene and the contact law it names (``law = ...``).

``law`` is one of ``"conformal"`` (default: the paper's law as published, ``contact.loose_support``),
``"pereira"``, ``"calibrated:<name>"`` (a law shipped in ``contact/calibrated/<name>.json``) or the path of
a calibrated-law file (``.json``, schema ``ringcontact/calibrated-law`` v1, read by
:func:`contact.calibrate.store.law_file_record`; a relative path is taken from the scene file's folder).

A calibrated law holds for the geometry it was fitted to (``CalibratedLaw.geometry``): the scene's
clearance, ring width, moduli and Poisson ratios must agree with it (relative 1e-6), else one
:class:`~contact.errors.InputError` names the scene file, the key, both values with their units and what
to do. Those keys may be left out of the scene when it names a calibrated law: they are then the law's.
The table's keys and their parsing are in :mod:`rotor.model.scene` (``_LOOSE``); this module checks and
completes them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from contact.errors import DatasetError, InputError

#: the analytic laws of contact.loose_support a scene may name
ANALYTIC_LAWS = ("conformal", "pereira")
CALIBRATED_PREFIX = "calibrated:"
#: default of a geometry key that a calibrated law may supply (rotor.model.scene._LOOSE)
FROM_LAW = object()
#: relative tolerance of the scene-vs-law geometry check
GEOMETRY_RTOL = 1e-6

# [loose_support] key -> (LooseSupport attribute, SceneGeometry attribute, unit typed, SI per typed unit)
GEOMETRY_KEYS = {
    "clearance_mm": ("clearance_m", "clearance_m", "mm", 1e-3),
    "ring_width_mm": ("ring_width_m", "width_m", "mm", 1e-3),
    "bearing_modulus_gpa": ("bearing_modulus_pa", "bearing_E_Pa", "GPa", 1e9),
    "bearing_poisson_ratio": ("bearing_poisson", "bearing_nu", "", 1.0),
    "support_modulus_gpa": ("support_modulus_pa", "support_E_Pa", "GPa", 1e9),
    "support_poisson_ratio": ("support_poisson", "support_nu", "", 1.0),
}


@dataclass(frozen=True)
class LooseSupport:
    """Parameters of the bearing-in-support clearance (used by the nonlinear integrator) and its contact law."""
    bearing_station: str
    support: str
    clearance_m: float
    ring_width_m: float
    bearing_modulus_pa: float
    bearing_poisson: float
    support_modulus_pa: float
    support_poisson: float
    collision_factor_s_m: float
    friction_coefficient: float
    preload_n: float
    law: str = ANALYTIC_LAWS[0]         # the scene's `law` key as typed
    law_file: str = ""                  # a calibrated law's file as read (resolved path, or the shipped entry)
    law_sha256: str = ""                # its checksum (the file's "sha256" key, verified)
    calibrated: object = field(default=None, compare=False, repr=False)   # its contact.calibrate.law.CalibratedLaw

    @property
    def validity_max_penetration_m(self) -> float | None:
        """Top of the calibrated law's fitted penetration range (m); None for an analytic law."""
        return None if self.calibrated is None else float(self.calibrated.validity_penetration_m[1])

    def law_note(self) -> dict:
        """JSON fields naming a calibrated law's file: ``law_file`` and ``law_sha256`` (empty for an analytic law)."""
        if self.calibrated is None:
            return {}
        return {"law_file": self.law_file, "law_sha256": self.law_sha256}


def law_record(text, base_dir, where: str):
    """The law named by ``text`` as a :class:`contact.calibrate.store.LawFile`; None for an analytic law.

    ``base_dir``: folder a relative path is taken from (None: the working directory). ``where``
    prefixes the message of a bad value (e.g. ``"scene.toml: loose_support.law"``, ``"--law"``).
    """
    if not isinstance(text, str) or not text.strip():
        raise InputError(f"{where} = {text!r}: must be a non-empty string")
    if text in ANALYTIC_LAWS:
        return None
    from contact.calibrate.store import available, law_file_record, shipped_record
    if text.startswith(CALIBRATED_PREFIX):
        name = text[len(CALIBRATED_PREFIX):]
        if not name:
            raise InputError(f"{where} = {text!r}: name the law, calibrated:<name> with <name> one of "
                             f"{', '.join(available())}")
        return shipped_record(name)
    if not text.lower().endswith(".json"):
        raise InputError(f"{where} = {text!r}: must be {' or '.join(ANALYTIC_LAWS)}, calibrated:<name> (one of "
                         f"{', '.join(available())}) or the path of a calibrated-law file (.json)")
    path = Path(text).expanduser()
    if not path.is_absolute():
        path = (Path(base_dir) if base_dir is not None else Path.cwd()) / path
    return law_file_record(path)


def law_label(text: str) -> str:
    """How a message names the law ``text``: ``law file my-law.json`` or ``calibrated law 'clamped-foundation'``."""
    if text.startswith(CALIBRATED_PREFIX):
        return f"calibrated law {text[len(CALIBRATED_PREFIX):]!r}"
    return f"law file {text}"


def geometry_mismatch(values_si: dict, law) -> tuple | None:
    """The first geometry key on which ``values_si`` (LooseSupport attribute -> SI value) and the
    calibrated ``law`` disagree, as ``(key, value typed, law's value typed, unit)``; None if all agree."""
    g = law.geometry
    for key, (attr, gattr, unit, scale) in GEOMETRY_KEYS.items():
        mine, theirs = values_si.get(attr), float(getattr(g, gattr))
        if mine is None or mine is FROM_LAW:
            continue
        if not math.isclose(float(mine), theirs, rel_tol=GEOMETRY_RTOL, abs_tol=0.0):
            return key, float(mine) / scale, theirs / scale, unit


def outside_scene_ranges(law) -> str | None:
    """Why the calibrated ``law`` cannot serve a rotor scene: the first of its geometry values outside the range a
    scene allows for that key (:data:`contact.plausible.RANGES`, the scene's own check); None if all are inside.

    A law file holds any ring a ring-pair file can describe (a 0.1 um ring included); a scene whose ring width
    must be 1-500 mm cannot take such a law's width as its own.
    """
    from contact.plausible import RANGES, inside, range_text
    for key, (_, gattr, unit, scale) in GEOMETRY_KEYS.items():
        if key not in RANGES:
            continue
        si = float(getattr(law.geometry, gattr))
        if not inside(key, si / scale):
            return (f"its geometry.{gattr} = {si:g} is {key} = {_shown(si / scale, unit)}, and a rotor scene's {key} "
                    f"must be {range_text(key)} ({RANGES[key][5]})")
    return None


def _shown(value: float, unit: str) -> str:
    return f"{value:.6g} {unit}".rstrip()


def complete_loose_support(kw: dict, origin: str, base_dir) -> dict:
    """The ``[loose_support]`` fields ``kw`` (as parsed, SI) with the named law loaded and checked.

    Keys given as :data:`FROM_LAW` are the law's values; without a calibrated law they are missing.
    ``origin`` is the scene file's name (messages), ``base_dir`` its folder (relative law paths).
    """
    where = f"{origin}: loose_support"
    text = kw.get("law", ANALYTIC_LAWS[0])
    try:
        rec = law_record(text, base_dir, f"{where}.law")
    except DatasetError as exc:
        raise DatasetError(f"{where}.law = {text!r}: {exc}") from None
    missing = [k for k, (attr, *_) in GEOMETRY_KEYS.items() if kw.get(attr) is FROM_LAW]
    if rec is None:
        if missing:
            unit = GEOMETRY_KEYS[missing[0]][2]
            raise InputError(f"{where}: missing field {missing[0]!r}" + (f" ({unit})" if unit else "")
                             + f" (required unless 'law' names a calibrated law; law = {text!r})")
        return kw
    law = rec.law
    try:
        law.kernel_law()        # a family the compiled loose-support kernel has (not conformal-compliance)
    except InputError as exc:
        raise InputError(f"{where}.law = {text!r}: {exc}") from None
    why = outside_scene_ranges(law)
    if why is not None:
        raise InputError(f"{where}.law = {text!r}: {law_label(text)}: {why}")
    bad = geometry_mismatch(kw, law)
    if bad is not None:
        key, mine, theirs, unit = bad
        raise InputError(f"{key} = {_shown(mine, unit)} in {origin} but {law_label(text)} holds for "
                         f"{_shown(theirs, unit)}: remove {key} from [loose_support] to take the law's value, or "
                         f"name a law calibrated for {_shown(mine, unit)}")
    out = dict(kw)
    for key in missing:
        attr, gattr, *_ = GEOMETRY_KEYS[key]
        out[attr] = float(getattr(law.geometry, gattr))
    out.update(law_file=rec.path, law_sha256=rec.sha256, calibrated=law)
    return out


def with_law(scene, text: str, where: str = "--law"):
    """``scene`` with its ``[loose_support]`` law replaced by ``text`` (as a scene's ``law`` key: an analytic
    law, ``calibrated:<name>`` or a law file, a relative path from the working directory).

    A calibrated law must hold for the scene's clearance, ring width and materials (:func:`geometry_mismatch`);
    ``where`` names the option in the messages (``--law``). A scene without ``[loose_support]`` is refused.
    """
    from dataclasses import replace

    ls = scene.loose_support
    rec = law_record(text, None, where)
    if ls is None:
        raise InputError(f"{where} = {text}: scene {scene.name!r} has no [loose_support] to apply it to")
    if rec is None:
        return replace(scene, loose_support=replace(ls, law=text, law_file="", law_sha256="", calibrated=None))
    try:
        rec.law.kernel_law()        # a family the compiled loose-support kernel has
    except InputError as exc:
        raise InputError(f"{where} = {text}: {exc}") from None
    why = outside_scene_ranges(rec.law)
    if why is not None:
        raise InputError(f"{where} = {text}: {law_label(text)}: {why}")
    bad = geometry_mismatch(vars(ls), rec.law)
    if bad is not None:
        key, mine, theirs, unit = bad
        raise InputError(f"{where} = {text}: {law_label(text)} holds for {key} = {_shown(theirs, unit)} but scene "
                         f"{scene.path or scene.name} has {key} = {_shown(mine, unit)} in [loose_support]: leave out "
                         f"{where} to use the scene's law, or name a law calibrated for {_shown(mine, unit)}")
    return replace(scene, loose_support=replace(ls, law=text, law_file=rec.path, law_sha256=rec.sha256,
                                                calibrated=rec.law))
