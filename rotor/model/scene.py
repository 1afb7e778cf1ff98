"""Rotor scenes: TOML files in engineer units, loaded into frozen dataclasses in SI units.

A scene file names every quantity with its unit (``x_mm``, ``stiffness_n_per_m``, ``unbalance_g_mm``);
:func:`load_scene` converts to SI and validates ranges. Any bad field (missing, negative, inner diameter ≥
outer, unknown unit, unknown name) raises one :class:`~contact.errors.InputError` naming the file, the table
entry, the field, its value and unit. An unreadable or non-TOML file raises :class:`~contact.errors.DatasetError`.

File layout (see ``rotor/scenes/*.toml`` for complete examples)::

    schema = "ringcontact.rotor-scene/1"
    name = "..."            # short id
    title = "..."           # one line
    source = "..."          # where the numbers come from
    [[materials]]  name, density_kg_m3, youngs_modulus_gpa, poisson_ratio
    [[stations]]   name, x_mm                          # one rotor node each, in DOF order
    [[shafts]]     from, to, outer_diameter_mm, inner_diameter_mm, material, elements
    [[disks]]      name, station, mass_kg, polar_inertia_kg_m2, diametral_inertia_kg_m2,
                   unbalance_g_mm, unbalance_phase_deg, skew_mrad, skew_phase_deg
    [[point_masses]] name, station, mass_kg, diametral_inertia_kg_m2
    [[disks]]      ... or from geometry: outer_diameter_mm, inner_diameter_mm, thickness_mm, material
    [[bearings]]   name, station, stiffness_n_per_m, damping_n_s_per_m,
                   angular_stiffness_n_m_per_rad, angular_damping_n_m_s_per_rad,
                   stiffness_{yy,zz,yz,zy}_n_per_m, damping_{yy,zz,yz,zy}_n_s_per_m (anisotropic, cross-coupled)
    [[supports]]   name, station, mass_kg, inertia_kg_m2, stiffness_n_per_m, damping_n_s_per_m,
                   angular_stiffness_n_m_per_rad, angular_damping_n_m_s_per_rad
    [[couplings]]  name, node_a, node_b, a0_n_m_per_rad, a1_n_m_per_rad3, equal_lateral,
                   shaft_mass_kg (m_sp), lever_mm (L)
    [[boundaries]] station, fixed = ["y", "z", ...]
    [loose_support]  bearing_station, support, clearance_mm, ring_width_mm, ..., law (rotor.model.loose_support_scene)
    [misalignment]   coupling, bearing_station, offset_mm, excitation (a reading of Eq. 34)
    [analysis]       max_speed_rpm, speed_points, modes
    [gravity]        acceleration_y_m_per_s2, acceleration_z_m_per_s2 (on every mass; rotor.model.static_load)
    [[static_loads]] name, station, force_y_n, force_z_n, moment_y_n_m, moment_z_n_m
"""
from __future__ import annotations

import math
import os
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from contact.errors import DatasetError, InputError
from contact.package_data import entries, shipped, stem
from rotor.model.loose_support_scene import FROM_LAW, LooseSupport, complete_loose_support
from rotor.model.scene_fields import (_DEG, _DOF_INPUT, _GMM, _GPA, _ID, _IDT, _MM, _MRAD, _REQ, _RPM, _RPMT,  # noqa: F401
                                      FROM_GEOMETRY,
                                      CHECK_TEXT, TABLE_CONVERTERS, Spec, _any, _bool, _dofs, _int, _nonneg, _nu, _pos,
                                      _text)
from rotor.model.scene_fields import bearing_fields, disk_fields
from rotor.model.scene_fields import parse_table as _parse_table

SCENE_DIR = shipped("rotor", "scenes")       # the bundled scenes, through importlib.resources (contact.package_data)
SCHEMA = "ringcontact.rotor-scene/1"


# --------------------------------------------------------------------------------------------
# dataclasses (SI units)
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Material:
    name: str
    density_kg_m3: float
    youngs_modulus_pa: float
    poisson_ratio: float


@dataclass(frozen=True)
class Station:
    """A named rotor node at axial position ``x_m``; the order of stations is the DOF order."""
    name: str
    x_m: float


@dataclass(frozen=True)
class Shaft:
    """Uniform hollow shaft segment between two stations, cut into ``elements`` Timoshenko elements."""
    start: str
    end: str
    outer_diameter_m: float
    inner_diameter_m: float
    material: Material
    elements: int = 1


@dataclass(frozen=True)
class Disk:
    """Rigid disk (Dai et al. 2025, Eqs. 39–40): unbalance ``m·e`` and principal-axis skew ``τ``.

    In a scene file the mass and inertias are given, or computed from the disk's geometry
    (``outer_diameter_mm``, ``inner_diameter_mm``, ``thickness_mm``, ``material``:
    :func:`rotor.model.elements.disk_properties`)."""
    name: str
    station: str
    mass_kg: float
    polar_inertia_kg_m2: float
    diametral_inertia_kg_m2: float
    unbalance_kg_m: float = 0.0
    unbalance_phase_rad: float = 0.0
    skew_rad: float = 0.0
    skew_phase_rad: float = 0.0


@dataclass(frozen=True)
class PointMass:
    """Non-rotating lumped mass moving with a station (e.g. the 3# bearing mass ``m_b``)."""
    name: str
    station: str
    mass_kg: float
    diametral_inertia_kg_m2: float = 0.0


@dataclass(frozen=True)
class Bearing:
    """Linear bearing from a station to ground: isotropic, anisotropic, cross-coupled, speed-dependent.

    The lateral force on the rotor is ``f = −K [y, z] − C [ẏ, ż]`` with ``K = [[k_yy, k_yz], [k_zy, k_zz]]``
    (N/m) and ``C`` alike (N·s/m). The direct terms default to the isotropic ``stiffness_n_m`` /
    ``damping_n_s_m``, the cross terms to 0 (Friswell et al. 2010, §5.9: Examples 5.9.2 anisotropic,
    5.9.4 cross-coupled). ``stiffness_n_m`` may be None only when both direct stiffnesses are given; a
    direct term left None follows the isotropic value (read through :meth:`lateral_at`). With a ``speed_table_rad_s`` (ascending, rad/s) each of the eight lateral coefficients may be a tuple
    of the same length (a fluid-film bearing's table): :meth:`lateral_at` interpolates linearly in the
    speed and holds the end values outside the table.
    """
    name: str
    station: str
    stiffness_n_m: float | None
    damping_n_s_m: float = 0.0
    angular_stiffness_n_m_rad: float = 0.0
    angular_damping_n_m_s_rad: float = 0.0
    stiffness_yy_n_m: float | tuple[float, ...] | None = None
    stiffness_zz_n_m: float | tuple[float, ...] | None = None
    stiffness_yz_n_m: float | tuple[float, ...] = 0.0
    stiffness_zy_n_m: float | tuple[float, ...] = 0.0
    damping_yy_n_s_m: float | tuple[float, ...] | None = None
    damping_zz_n_s_m: float | tuple[float, ...] | None = None
    damping_yz_n_s_m: float | tuple[float, ...] = 0.0
    damping_zy_n_s_m: float | tuple[float, ...] = 0.0
    speed_table_rad_s: tuple[float, ...] = ()

    def __post_init__(self):
        if self.stiffness_n_m is None and (self.stiffness_yy_n_m is None or self.stiffness_zz_n_m is None):
            raise InputError(f"bearing {self.name!r}: stiffness_n_m or both stiffness_yy_n_m and "
                             f"stiffness_zz_n_m must be given (N/m)")

    @property
    def speed_dependent(self) -> bool:
        """True if a coefficient follows the speed table."""
        return any(isinstance(getattr(self, f"{q}_{d}_{u}"), tuple)
                   for q, u in (("stiffness", "n_m"), ("damping", "n_s_m")) for d in ("yy", "yz", "zy", "zz"))

    def lateral_at(self, speed_rad_s: float = 0.0) -> tuple:
        """``(K, C)``: the 2×2 lateral stiffness (N/m) and damping (N·s/m) at ``speed_rad_s`` (rad/s); a direct
        term left None is the isotropic value (so ``dataclasses.replace(b, damping_n_s_m=…)`` changes it)."""
        iso = {"stiffness": self.stiffness_n_m, "damping": self.damping_n_s_m}

        def at(q, d, u):
            v = getattr(self, f"{q}_{d}_{u}")
            v = iso[q] if v is None else v
            return float(np.interp(speed_rad_s, self.speed_table_rad_s, v)) if isinstance(v, tuple) else float(v)
        return tuple(np.array([[at(q, a, u), at(q, b, u)] for a, b in (("yy", "yz"), ("zy", "zz"))])
                     for q, u in (("stiffness", "n_m"), ("damping", "n_s_m")))


@dataclass(frozen=True)
class Gravity:
    """Uniform acceleration field on every mass of the rotor, in the lateral plane (m/s²)."""
    acceleration_y_m_s2: float = 0.0
    acceleration_z_m_s2: float = 0.0


@dataclass(frozen=True)
class StaticLoad:
    """Constant force (N) and moment (N·m) on a station: a weight not in the model, a fluid or gear load.

    ``moment_y_n_m`` acts on the θy DOF, ``moment_z_n_m`` on θz (conventions of rotor.model.elements)."""
    name: str
    station: str
    force_y_n: float = 0.0
    force_z_n: float = 0.0
    moment_y_n_m: float = 0.0
    moment_z_n_m: float = 0.0


@dataclass(frozen=True)
class SupportNode:
    """Extra node of the loose support (Dai et al. 2025, Eq. 52), tied to ground only.

    The support sits at the axial position of ``station``; its contact with the bearing is
    not part of the linear model.
    """
    name: str
    station: str
    mass_kg: float
    inertia_kg_m2: float
    stiffness_n_m: float
    damping_n_s_m: float
    angular_stiffness_n_m_rad: float
    angular_damping_n_m_s_rad: float


@dataclass(frozen=True)
class Coupling:
    """Transition shaft between two coincident stations (Dai et al. 2025, Eqs. 31–32, 34).

    Angular spring ``k_c,θ = a0 + a1 θ²`` on the relative rotation, optional equal lateral
    displacement constraint, and the transition-shaft mass ``m_sp`` and lever ``L`` that set the
    2X misalignment excitation.
    """
    name: str
    node_a: str
    node_b: str
    a0_n_m_rad: float
    a1_n_m_rad3: float
    equal_lateral: bool = True
    shaft_mass_kg: float = 0.0
    lever_m: float = 0.0


@dataclass(frozen=True)
class Boundary:
    station: str
    fixed: tuple[str, ...]


# Readings of Dai et al. 2025 Eq. 34, documented in rotor.model.assembly.harmonic_loads.
MISALIGNMENT_EXCITATIONS = ("inertial-at-joint", "opposed-at-centring-surfaces", "opposed-at-joint")


@dataclass(frozen=True)
class Misalignment:
    """Offset ``δ`` (in +y) of ``bearing_station`` relative to the bearings of the other rotor
    part; the part beyond ``coupling.node_b`` rotates rigidly about ``node_b`` (Eq. 33).
    ``excitation`` names the reading of the 2X excitation (one of ``MISALIGNMENT_EXCITATIONS``)."""
    coupling: str
    bearing_station: str
    offset_m: float
    excitation: str = MISALIGNMENT_EXCITATIONS[0]


@dataclass(frozen=True)
class Analysis:
    max_speed_rad_s: float = 2000 * math.pi / 30
    speed_points: int = 61
    modes: int = 8


@dataclass(frozen=True)
class Scene:
    name: str
    title: str
    source: str
    materials: tuple[Material, ...]
    stations: tuple[Station, ...]
    shafts: tuple[Shaft, ...]
    disks: tuple[Disk, ...] = ()
    point_masses: tuple[PointMass, ...] = ()
    bearings: tuple[Bearing, ...] = ()
    supports: tuple[SupportNode, ...] = ()
    couplings: tuple[Coupling, ...] = ()
    boundaries: tuple[Boundary, ...] = ()
    loose_support: LooseSupport | None = None
    misalignment: Misalignment | None = None
    analysis: Analysis = field(default_factory=Analysis)
    gravity: Gravity | None = None
    static_loads: tuple[StaticLoad, ...] = ()
    path: str = ""

    def station(self, name: str) -> Station:
        for s in self.stations:
            if s.name == name:
                return s
        raise InputError(f"scene {self.name!r}: no station named {name!r}")


# --------------------------------------------------------------------------------------------
# field specifications: name -> (base, unit, converter, check, default)
# --------------------------------------------------------------------------------------------
def _excitation(v):
    return v in MISALIGNMENT_EXCITATIONS


CHECK_TEXT[_excitation] = "must be one of " + ", ".join(MISALIGNMENT_EXCITATIONS)


_MATERIAL: list[Spec] = [
    ("name", "name", "", _text, _any, _REQ),
    ("density_kg_m3", "density_kg_m3", "kg/m^3", _ID, _nonneg, _REQ),
    ("youngs_modulus_gpa", "youngs_modulus_pa", "GPa", _GPA, _pos, _REQ),
    ("poisson_ratio", "poisson_ratio", "", _ID, _nu, _REQ),
]
_STATION: list[Spec] = [
    ("name", "name", "", _text, _any, _REQ),
    ("x_mm", "x_m", "mm", _MM, _any, _REQ),
]
_SHAFT: list[Spec] = [
    ("from", "start", "", _text, _any, _REQ),
    ("to", "end", "", _text, _any, _REQ),
    ("outer_diameter_mm", "outer_diameter_m", "mm", _MM, _pos, _REQ),
    ("inner_diameter_mm", "inner_diameter_m", "mm", _MM, _nonneg, 0.0),
    ("material", "material", "", _text, _any, _REQ),
    ("elements", "elements", "", _int, _pos, 1),
]
_DISK: list[Spec] = [
    ("name", "name", "", _text, _any, _REQ),
    ("station", "station", "", _text, _any, _REQ),
    ("mass_kg", "mass_kg", "kg", _ID, _nonneg, FROM_GEOMETRY),
    ("polar_inertia_kg_m2", "polar_inertia_kg_m2", "kg·m^2", _ID, _nonneg, FROM_GEOMETRY),
    ("diametral_inertia_kg_m2", "diametral_inertia_kg_m2", "kg·m^2", _ID, _nonneg, FROM_GEOMETRY),
    ("outer_diameter_mm", "outer_diameter_m", "mm", _MM, _pos, None),
    ("inner_diameter_mm", "inner_diameter_m", "mm", _MM, _nonneg, None),
    ("thickness_mm", "thickness_m", "mm", _MM, _pos, None),
    ("material", "material", "", _text, _any, None),
    ("unbalance_g_mm", "unbalance_kg_m", "g·mm", _GMM, _nonneg, 0.0),
    ("unbalance_phase_deg", "unbalance_phase_rad", "deg", _DEG, _any, 0.0),
    ("skew_mrad", "skew_rad", "mrad", _MRAD, _any, 0.0),
    ("skew_phase_deg", "skew_phase_rad", "deg", _DEG, _any, 0.0),
]
_POINT_MASS: list[Spec] = [
    ("name", "name", "", _text, _any, _REQ),
    ("station", "station", "", _text, _any, _REQ),
    ("mass_kg", "mass_kg", "kg", _ID, _nonneg, _REQ),
    ("diametral_inertia_kg_m2", "diametral_inertia_kg_m2", "kg·m^2", _ID, _nonneg, 0.0),
]
_BEARING: list[Spec] = [
    ("name", "name", "", _text, _any, _REQ),
    ("station", "station", "", _text, _any, _REQ),
    ("stiffness_n_per_m", "stiffness_n_m", "N/m", _ID, _nonneg, None),
    ("damping_n_s_per_m", "damping_n_s_m", "N·s/m", _ID, _nonneg, 0.0),
    ("angular_stiffness_n_m_per_rad", "angular_stiffness_n_m_rad", "N·m/rad", _ID, _nonneg, 0.0),
    ("angular_damping_n_m_s_per_rad", "angular_damping_n_m_s_rad", "N·m·s/rad", _ID, _nonneg, 0.0),
    ("stiffness_yy_n_per_m", "stiffness_yy_n_m", "N/m", _IDT, _nonneg, None),
    ("stiffness_zz_n_per_m", "stiffness_zz_n_m", "N/m", _IDT, _nonneg, None),
    ("stiffness_yz_n_per_m", "stiffness_yz_n_m", "N/m", _IDT, _any, 0.0),
    ("stiffness_zy_n_per_m", "stiffness_zy_n_m", "N/m", _IDT, _any, 0.0),
    ("damping_yy_n_s_per_m", "damping_yy_n_s_m", "N·s/m", _IDT, _nonneg, None),
    ("damping_zz_n_s_per_m", "damping_zz_n_s_m", "N·s/m", _IDT, _nonneg, None),
    ("damping_yz_n_s_per_m", "damping_yz_n_s_m", "N·s/m", _IDT, _any, 0.0),
    ("damping_zy_n_s_per_m", "damping_zy_n_s_m", "N·s/m", _IDT, _any, 0.0),
    ("speed_table_rpm", "speed_table_rad_s", "rpm", _RPMT, _nonneg, ()),
]
_SUPPORT: list[Spec] = [
    ("name", "name", "", _text, _any, _REQ),
    ("station", "station", "", _text, _any, _REQ),
    ("mass_kg", "mass_kg", "kg", _ID, _pos, _REQ),
    ("inertia_kg_m2", "inertia_kg_m2", "kg·m^2", _ID, _pos, _REQ),
    ("stiffness_n_per_m", "stiffness_n_m", "N/m", _ID, _nonneg, _REQ),
    ("damping_n_s_per_m", "damping_n_s_m", "N·s/m", _ID, _nonneg, _REQ),
    ("angular_stiffness_n_m_per_rad", "angular_stiffness_n_m_rad", "N·m/rad", _ID, _nonneg, _REQ),
    ("angular_damping_n_m_s_per_rad", "angular_damping_n_m_s_rad", "N·m·s/rad", _ID, _nonneg, _REQ),
]
_COUPLING: list[Spec] = [
    ("name", "name", "", _text, _any, _REQ),
    ("node_a", "node_a", "", _text, _any, _REQ),
    ("node_b", "node_b", "", _text, _any, _REQ),
    ("a0_n_m_per_rad", "a0_n_m_rad", "N·m/rad", _ID, _nonneg, _REQ),
    ("a1_n_m_per_rad3", "a1_n_m_rad3", "N·m/rad^3", _ID, _nonneg, 0.0),
    ("equal_lateral", "equal_lateral", "", _bool, _any, True),
    ("shaft_mass_kg", "shaft_mass_kg", "kg", _ID, _nonneg, 0.0),
    ("lever_mm", "lever_m", "mm", _MM, _nonneg, 0.0),
]
_BOUNDARY: list[Spec] = [
    ("station", "station", "", _text, _any, _REQ),
    ("fixed", "fixed", "", _dofs, _any, _REQ),
]
_LOOSE: list[Spec] = [
    ("bearing_station", "bearing_station", "", _text, _any, _REQ),
    ("support", "support", "", _text, _any, _REQ),
    ("clearance_mm", "clearance_m", "mm", _MM, _pos, FROM_LAW),        # FROM_LAW: required unless `law`
    ("ring_width_mm", "ring_width_m", "mm", _MM, _pos, FROM_LAW),      # names a calibrated law, which then
    ("bearing_modulus_gpa", "bearing_modulus_pa", "GPa", _GPA, _pos, FROM_LAW),   # supplies the value
    ("bearing_poisson_ratio", "bearing_poisson", "", _ID, _nu, FROM_LAW),         # (rotor.model.loose_support_scene)
    ("support_modulus_gpa", "support_modulus_pa", "GPa", _GPA, _pos, FROM_LAW),
    ("support_poisson_ratio", "support_poisson", "", _ID, _nu, FROM_LAW),
    ("collision_factor_s_per_m", "collision_factor_s_m", "s/m", _ID, _nonneg, 0.0),
    ("friction_coefficient", "friction_coefficient", "", _ID, _nonneg, 0.0),
    ("preload_n", "preload_n", "N", _ID, _nonneg, 0.0),
    ("law", "law", "", _text, _any, "conformal"),   # conformal, pereira, calibrated:<name> or a law file (.json)
]
_MISALIGN: list[Spec] = [
    ("coupling", "coupling", "", _text, _any, _REQ),
    ("bearing_station", "bearing_station", "", _text, _any, _REQ),
    ("offset_mm", "offset_m", "mm", _MM, _any, _REQ),
    ("excitation", "excitation", "", _text, _excitation, MISALIGNMENT_EXCITATIONS[0]),
]
_GRAVITY: list[Spec] = [
    ("acceleration_y_m_per_s2", "acceleration_y_m_s2", "m/s^2", _ID, _any, 0.0),
    ("acceleration_z_m_per_s2", "acceleration_z_m_s2", "m/s^2", _ID, _any, 0.0),
]
_STATIC_LOAD: list[Spec] = [
    ("name", "name", "", _text, _any, _REQ),
    ("station", "station", "", _text, _any, _REQ),
    ("force_y_n", "force_y_n", "N", _ID, _any, 0.0),
    ("force_z_n", "force_z_n", "N", _ID, _any, 0.0),
    ("moment_y_n_m", "moment_y_n_m", "N·m", _ID, _any, 0.0),
    ("moment_z_n_m", "moment_z_n_m", "N·m", _ID, _any, 0.0),
]
_ANALYSIS: list[Spec] = [
    ("max_speed_rpm", "max_speed_rad_s", "rpm", _RPM, _pos, Analysis.max_speed_rad_s),
    ("speed_points", "speed_points", "", _int, _pos, Analysis.speed_points),
    ("modes", "modes", "", _int, _pos, Analysis.modes),
]


def _list(doc: dict, key: str, where: str) -> list:
    raw = doc.get(key, [])
    if not isinstance(raw, list):
        raise InputError(f"{where}: [[{key}]] must be an array of tables")
    return raw


def _check_header(doc: dict, origin: str) -> None:
    """Only known top-level fields, the right schema, and a name and a title."""
    allowed = {"schema", "name", "title", "source", "materials", "stations", "shafts", "disks", "point_masses",
               "bearings", "supports", "couplings", "boundaries", "loose_support", "misalignment", "analysis",
               "gravity", "static_loads", "notes", "assumptions"}
    for key in doc:
        if key not in allowed:
            raise InputError(f"{origin}: unknown top-level field {key!r}; allowed are {', '.join(sorted(allowed))}")
    if doc.get("schema") != SCHEMA:
        raise InputError(f"{origin}: schema = {doc.get('schema')!r}: must be {SCHEMA!r}")
    for key in ("name", "title"):
        if not isinstance(doc.get(key), str) or not doc[key].strip():
            raise InputError(f"{origin}: missing field {key!r} (text)")


def _parse_named(doc: dict, origin: str, key: str, specs: list[Spec], cls) -> dict:
    """The ``[[key]]`` array of tables as ``{name: cls instance}`` in file order; names unique."""
    out = {}
    for i, raw in enumerate(_list(doc, key, origin)):
        kw = _parse_table(raw, specs, f"{origin}: {key}[{i}]", cls)
        if kw["name"] in out:
            raise InputError(f"{origin}: {key}[{i}].name = {kw['name']!r}: duplicate")
        out[kw["name"]] = cls(**kw)
    return out


def _need_station(names: dict[str, Station], where: str, field_: str, value) -> None:
    if value not in names:
        raise InputError(f"{where}.{field_} = {value!r}: no such station (have {', '.join(names)})")


def _parse_shafts(doc: dict, origin: str, names: dict[str, Station], materials: dict[str, Material]) -> list[Shaft]:
    shafts = []
    for i, raw in enumerate(_list(doc, "shafts", origin)):
        where = f"{origin}: shafts[{i}]"
        kw = _parse_table(raw, _SHAFT, where, Shaft)
        _need_station(names, where, "from", kw["start"])
        _need_station(names, where, "to", kw["end"])
        length_mm = (names[kw["end"]].x_m - names[kw["start"]].x_m) * 1e3
        if length_mm <= 0:
            raise InputError(f"{where}: length = x({kw['end']}) - x({kw['start']}) = {length_mm:g} mm: must be > 0 "
                             f"(stations in increasing x)")
        if kw["inner_diameter_m"] >= kw["outer_diameter_m"]:
            raise InputError(f"{where}.inner_diameter_mm = {kw['inner_diameter_m'] * 1e3:g} mm: must be < "
                             f"outer_diameter_mm = {kw['outer_diameter_m'] * 1e3:g} mm")
        if kw["material"] not in materials:
            raise InputError(f"{where}.material = {kw['material']!r}: no such material (have {', '.join(materials)})")
        kw["material"] = materials[kw["material"]]
        shafts.append(Shaft(**kw))
    return shafts


def _parse_entries(doc: dict, origin: str, names: dict[str, Station], key: str, specs: list[Spec], cls,
                   station_fields=("station",), finish=None) -> tuple:
    """The ``[[key]]`` array of tables as ``cls`` instances; ``station_fields`` must name stations;
    ``finish(fields, where)`` completes the fields before ``cls`` is built."""
    out = []
    for i, raw in enumerate(_list(doc, key, origin)):
        where = f"{origin}: {key}[{i}]"
        kw = _parse_table(raw, specs, where, cls)
        for f in station_fields:
            _need_station(names, where, f, kw[f])
        out.append(cls(**(kw if finish is None else finish(kw, where))))
    return tuple(out)


def _parse_linked_table(doc: dict, origin: str, names: dict[str, Station], key: str, specs: list[Spec], cls,
                        link: str, entries: tuple, entries_key: str, finish=None):
    """The optional ``[key]`` table as ``cls`` (None if absent): its ``bearing_station`` must
    name a station and its field ``link`` one of ``entries`` (the ``[[entries_key]]`` array);
    ``finish(fields)`` completes the fields before ``cls`` is built."""
    if key not in doc:
        return None
    where = f"{origin}: {key}"
    kw = _parse_table(doc[key], specs, where, cls)
    _need_station(names, where, "bearing_station", kw["bearing_station"])
    if kw[link] not in {e.name for e in entries}:
        raise InputError(f"{where}.{link} = {kw[link]!r}: no such [[{entries_key}]] entry")
    return cls(**(finish(kw) if finish is not None else kw))


def parse_scene(doc: dict, *, origin: str = "<scene>", base_dir=None) -> Scene:
    """Validate a parsed TOML document and build a :class:`Scene` (SI units); ``base_dir``: the folder a
    relative law-file path is taken from (None: the working directory)."""
    _check_header(doc, origin)
    source = doc.get("source", "")
    materials = _parse_named(doc, origin, "materials", _MATERIAL, Material)
    names = _parse_named(doc, origin, "stations", _STATION, Station)
    if not names:
        raise InputError(f"{origin}: missing [[stations]] (at least two)")
    stations = list(names.values())
    shafts = _parse_shafts(doc, origin, names, materials)
    disks = _parse_entries(doc, origin, names, "disks", _DISK, Disk, finish=disk_fields(materials))
    point_masses = _parse_entries(doc, origin, names, "point_masses", _POINT_MASS, PointMass)
    bearings = _parse_entries(doc, origin, names, "bearings", _BEARING, Bearing, finish=bearing_fields)
    static_loads = _parse_entries(doc, origin, names, "static_loads", _STATIC_LOAD, StaticLoad)
    gravity = Gravity(**_parse_table(doc["gravity"], _GRAVITY, f"{origin}: gravity", Gravity)) if "gravity" in doc else None
    supports = _parse_entries(doc, origin, names, "supports", _SUPPORT, SupportNode)
    for sp in supports:
        if sp.name in names:
            raise InputError(f"{origin}: supports name {sp.name!r} clashes with a station name")
    couplings = _parse_entries(doc, origin, names, "couplings", _COUPLING, Coupling, ("node_a", "node_b"))
    for i, c in enumerate(couplings):
        if abs(names[c.node_a].x_m - names[c.node_b].x_m) > 1e-12:
            raise InputError(f"{origin}: couplings[{i}]: node_a {c.node_a!r} and node_b {c.node_b!r} must be at the "
                             f"same x_mm")
    boundaries = _parse_entries(doc, origin, names, "boundaries", _BOUNDARY, Boundary)
    loose = _parse_linked_table(doc, origin, names, "loose_support", _LOOSE, LooseSupport, "support", supports,
                                "supports", lambda kw: complete_loose_support(kw, origin, base_dir))
    mis = _parse_linked_table(doc, origin, names, "misalignment", _MISALIGN, Misalignment, "coupling", couplings,
                              "couplings")
    analysis = Analysis(**_parse_table(doc.get("analysis", {}), _ANALYSIS, f"{origin}: analysis", Analysis))
    all_names = [s.name for s in stations] + [s.name for s in supports]
    for group in (disks, point_masses, bearings, static_loads):
        for e in group:
            if e.name in all_names:
                raise InputError(f"{origin}: element name {e.name!r} clashes with a node name")
    return Scene(name=doc["name"], title=doc["title"], source=source, materials=tuple(materials.values()),
                 stations=tuple(stations), shafts=tuple(shafts), disks=disks, point_masses=point_masses,
                 bearings=bearings, supports=supports, couplings=couplings, boundaries=boundaries,
                 loose_support=loose, misalignment=mis, analysis=analysis, gravity=gravity,
                 static_loads=static_loads, path=origin)


def scene_path(path_or_name: str | Path):
    """Resolve a file path, or a bare name of a bundled scene (``"paper-table4"``: a shipped entry)."""
    p = Path(path_or_name)
    if p.suffix == ".toml" or p.exists() or p.parent != Path("."):
        return p
    return SCENE_DIR.joinpath(f"{path_or_name}.toml")


def bundled_scenes() -> list[str]:
    """Names of the scenes shipped in ``rotor/scenes``."""
    return [stem(e) for e in entries(SCENE_DIR, ".toml")]


#: the largest scene file read (bytes): a rotor of thousands of stations is a few hundred KiB
MAX_SCENE_BYTES = 4 * 2 ** 20

def load_scene(path_or_name: str | Path) -> Scene:
    """Read, validate and convert a scene file (or a bundled scene name) to SI.

    Raises
    ------
    DatasetError : the file is missing, unreadable or not valid TOML.
    InputError : a field is missing, out of range, has an unknown unit or name.
    """
    path = scene_path(path_or_name)
    if isinstance(path, Path) and path.exists() and not path.is_file():     # a pipe blocks, a device never ends
        raise DatasetError(f"scene file {str(path)!r}: not a regular file (a folder, pipe or device)")
    if isinstance(path, Path) and path.is_file() and path.stat().st_size > MAX_SCENE_BYTES:
        raise DatasetError(f"scene file {str(path)!r}: {path.stat().st_size / 2 ** 20:.3g} MiB, more than a scene "
                           f"file holds (at most {MAX_SCENE_BYTES // 2 ** 10} KiB)")
    try:
        data = path.read_bytes()
    except OSError as exc:
        hint = f" (bundled scenes: {', '.join(bundled_scenes())})" if path.name != Path(path_or_name).name else ""
        raise DatasetError(f"scene file {str(path)!r}: cannot read: {exc.strerror or exc}{hint}") from None
    try:
        doc = tomllib.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError, RecursionError) as exc:   # Recursion: nested too deeply
        raise DatasetError(f"scene file {str(path)!r}: not valid TOML: {' '.join(str(exc).split())[:160]}") from None
    return parse_scene(doc, origin=path.name, base_dir=path.parent if isinstance(path, os.PathLike) else None)


def loads_scene(text: str, origin: str = "<string>") -> Scene:
    """Parse a scene from TOML text (tests, scripting)."""
    try:
        doc = tomllib.loads(text)
    except (tomllib.TOMLDecodeError, RecursionError) as exc:
        raise DatasetError(f"scene {origin}: not valid TOML: {exc}") from None
    return parse_scene(doc, origin=origin)
