"""Ring-pair scene files: an engineer's bearing ring and housing, as TOML, to the FEM references' scenes.

A ring-pair file (schema ``ringcontact.ring-scene/1``) says what the FEM references need to know about
one bearing: the bearing outer ring, the housing around it with its radial clearance, how the housing
is held and the ring is driven, and the range of penetrations and tilts the law must cover::

    schema = "ringcontact.ring-scene/1"
    name = "my-bearing"
    plane = "strain"                       # 2D assumption: auto (the default, by the 3D ring) | strain | stress
    [bearing_ring]
    inner_radius_mm = 48.0
    outer_radius_mm = 55.0
    width_mm = 22.0
    youngs_modulus_gpa = 208.0
    poisson_ratio = 0.30
    [housing]
    radial_clearance_mm = 0.03
    outer_radius_mm = 75.0
    youngs_modulus_gpa = 72.0
    poisson_ratio = 0.33
    hold = "clamped-outer"
    [drive]
    bearing = "rigid-inner"
    [range]
    penetration_mm = [0.005, 0.05]
    tilt_arcmin = [0, 2]                   # [0, 0]: no 3D work at all

``plane = "auto"`` (the default when the key is left out) leaves the 2D assumption to evidence: ``ringcontact
bearing`` solves the 3D ring (free end faces, the file's hold and drive) at zero tilt at two penetrations and uses the
plane model whose force lies closer (:mod:`fem_reference.plane_check`; the FEM jobs resolve it the same way through
:func:`fem_reference.plane_check.scene_2d`). An ``auto`` file's :attr:`RingScene.scene` carries plane strain only as
a placeholder: :func:`with_plane` gives the resolved one, and the 2D sweep refuses an unresolved file.

Optional keys: ``description``; in ``[range]`` the explicit point lists ``penetration_points_mm`` (2D),
``penetration_points_3d_mm`` and ``tilt_points_arcmin`` (default grids: :func:`default_grid`). The
named scenes (``clamped``, ``clamped-stress``, ``persson-40``, ``steel-in-aluminium``) are bundled
files of this format in ``fem_reference/ring_scenes/``. Every key is checked when read; a bad value is
refused with one line naming the file, the key, the value with its unit and what is allowed
(:class:`~contact.errors.InputError`). The reference documentation is ``docs/ring-scenes.rst``; the
JSON Schema for editors, ``docs/ring-scene.schema.json``, is generated from :data:`KEYS` by
:func:`json_schema`.

Everything returned is SI (m, Pa, rad).
"""
from __future__ import annotations

import hashlib
import json
import math
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

from contact.errors import DatasetError, InputError
from contact.package_data import entries, shipped, stem
from contact.plausible import MAX_CLEARANCE_TO_RADIUS, MAX_PENETRATION_TO_RADIUS, MAX_TILT_ARCMIN, RANGES
from contact.units import ARCMIN, GPA, MM
from fem_reference.plane.geometry import Material, RingPair
from fem_reference.scenes import BEARING_DRIVES, SUPPORT_HOLDS, Scene, by_name

SCHEMA = "ringcontact.ring-scene/1"
#: the bundled ring-pair files (read through importlib.resources, see contact.package_data)
RING_SCENE_DIR = shipped("fem_reference", "ring_scenes")
MAX_FILE_BYTES = 64_000
#: the ``plane`` key's values: ``auto`` (the default) leaves it to the 3D check of fem_reference.plane_check
PLANES = ("auto", "strain", "stress")
_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.+-]{0,59}\Z")     # \Z: no newline after the name

#: 3D boundary-condition scene (fem_reference.solid.compliance.SCENES) of each (hold, drive); the 3D
#: reference is a body of revolution, so only holds that are the same all round the ring exist in 3D
HOLDS_3D = {
    ("clamped-outer", "rigid-inner"): "clamped",
    ("clamped-outer-axially-free", "rigid-inner"): "clamped-axially-free-outer",
    ("clamped-outer", "rigid-inner-axially-free"): "clamped-axially-free-inner",
    ("clamped-outer-axially-free", "rigid-inner-axially-free"): "clamped-axially-free",
}

# 2D mesh levels (fem_reference.plane.sweep.DEFAULT_LEVELS_M): a point needs three consecutive levels
# with >= 3 elements across the contact half-arc, so the half-arc must reach 3 x the third-finest size
_FINEST_FIRST_LEVEL_M = 1e-3
_ARC_ELEMENTS = 3
_ARC_SHRINK = 0.85          # elastic arc / rigid-overlap arc at the smallest penetrations (measured 0.93)
_PHI_ELEMENTS_3D = 64       # angular multiplier elements over [0, pi] on the coarsest 3D level (Q0)


# section -> key -> (unit shown, kind, required); kinds: "len" mm, "mod" GPa, "nu", "text", "pair", "list"
KEYS: dict[str, dict[str, tuple[str, str, bool]]] = {
    "": {"schema": ("", "text", True), "name": ("", "text", True), "plane": ("", "text", False),
         "description": ("", "text", False)},
    "bearing_ring": {"inner_radius_mm": ("mm", "len", True), "outer_radius_mm": ("mm", "len", True),
                     "width_mm": ("mm", "len", True), "youngs_modulus_gpa": ("GPa", "mod", True),
                     "poisson_ratio": ("-", "nu", True)},
    "housing": {"radial_clearance_mm": ("mm", "len", True), "outer_radius_mm": ("mm", "len", True),
                "youngs_modulus_gpa": ("GPa", "mod", True), "poisson_ratio": ("-", "nu", True),
                "hold": ("", "text", False)},
    "drive": {"bearing": ("", "text", False)},
    "range": {"penetration_mm": ("mm", "pair", True), "tilt_arcmin": ("arcmin", "pair", False),
              "penetration_points_mm": ("mm", "list", False), "penetration_points_3d_mm": ("mm", "list", False),
              "tilt_points_arcmin": ("arcmin", "list", False)},
}
# one source with the law files made from a ring-pair file (contact.plausible, contact.calibrate.validate)
MODULUS_RANGE_GPA = RANGES["ring_modulus_gpa"][:2]   # soft polymers to tungsten carbide: 7.2e10 typed here is Pa
LENGTH_RANGE_MM = RANGES["ring_length_mm"][:2]


@dataclass(frozen=True)
class RingScene:
    """One ring-pair file, validated, in SI.

    Attributes
    ----------
    name : str
        The file's ``name``; labels every dataset point and law made from it.
    scene : fem_reference.scenes.Scene
        The 2D scene (rings, plane, drive, hold) of :mod:`fem_reference.scenes`.
    penetration_range_m, tilt_range_rad : tuple of float
        ``[range]``: what the law must cover (m, rad).
    penetrations_2d_m, penetrations_3d_m, tilts_rad : tuple of float
        The reference points (m, m, rad); no 3D points when the tilt range is [0, 0].
    document : dict
        The file's content, normalised (all keys present, SI-free engineer units as typed).
    source : str
        Where it was read from (a path, or ``bundled:<name>``).
    """

    name: str
    scene: Scene
    penetration_range_m: tuple
    tilt_range_rad: tuple
    penetrations_2d_m: tuple
    penetrations_3d_m: tuple
    tilts_rad: tuple
    document: dict
    source: str = ""

    @property
    def needs_3d(self) -> bool:
        """The range asks for tilt: the 3D reference is run."""
        return self.tilt_range_rad[1] > 0.0

    @property
    def plane_auto(self) -> bool:
        """The file leaves the 2D assumption to the 3D check (``plane = "auto"``, the default): not resolved yet."""
        return self.document["plane"] == "auto"

    @property
    def bc_3d(self) -> str | None:
        """The 3D boundary-condition scene of this hold and drive (None: not a body of revolution)."""
        return HOLDS_3D.get((self.scene.support_hold, self.scene.bearing_drive))

    @property
    def sha256(self) -> str:
        """Checksum of the normalised content (what the results depend on; comments and layout excluded)."""
        text = json.dumps(self.document, sort_keys=True, separators=(",", ":"), allow_nan=False)
        return hashlib.sha256(text.encode("utf-8")).hexdigest()

    def rings_3d(self):
        """The 3D reference's :class:`~fem_reference.solid.geometry.RingPair3D` of this pair."""
        from fem_reference.solid.geometry import RingPair3D
        r = self.scene.rings
        # the housing's thickness rounded to 1e-12 m: 110.05 mm - 100.05 mm is 10 mm, not 10 mm - 1.4e-17 m
        return RingPair3D(bearing_inner_radius_m=r.inner_radius_m, bearing_outer_radius_m=r.outer_radius_m,
                          clearance_m=r.clearance_m,
                          support_thickness_m=round(r.support_outer_radius_m - r.bore_radius_m, 12),
                          width_m=r.width_m, young_bearing_pa=r.bearing.youngs_modulus_pa,
                          young_support_pa=r.support.youngs_modulus_pa, poisson_bearing=r.bearing.poisson_ratio,
                          poisson_support=r.support.poisson_ratio)


# ---------------------------------------------------------------------------------------------
# reading

def bundled() -> list[str]:
    """Names of the bundled ring-pair files."""
    return [stem(e) for e in entries(RING_SCENE_DIR, ".toml")]


def is_file_argument(text: str) -> bool:
    """A ``--scene`` value that names a file (a path or ``*.toml``), not a scene name."""
    p = Path(text)
    return p.suffix == ".toml" or p.parent != Path(".")


def load(path_or_name) -> RingScene:
    """Read and validate a ring-pair file, or a bundled one by name (``"clamped"``).

    Raises
    ------
    DatasetError
        The file is missing, not a regular file, too large, unreadable or not TOML.
    InputError
        A key is unknown, missing, of the wrong type or out of range (one line naming it).
    """
    text = str(path_or_name)
    if is_file_argument(text):
        p = Path(text)
        if not p.is_file():
            what = "does not exist" if not p.exists() else "is not a regular file"
            raise DatasetError(f"ring scene file {text!r} {what}")
        if p.stat().st_size > MAX_FILE_BYTES:
            raise DatasetError(f"ring scene file {text!r}: {p.stat().st_size} bytes, more than a ring-pair file "
                               f"holds (at most {MAX_FILE_BYTES})")
        try:
            data = p.read_bytes()
        except OSError as exc:
            raise DatasetError(f"ring scene file {text!r}: cannot read: {exc.strerror or exc}") from None
        return loads(data, text)
    if text not in bundled():
        raise InputError(f"scene = {text!r}: no bundled ring-pair file of that name (bundled: "
                         f"{', '.join(bundled())}; or give a path to a .toml ring-pair file)")
    return loads(RING_SCENE_DIR.joinpath(f"{text}.toml").read_bytes(), f"bundled:{text}")


def loads(data: bytes | str, origin: str = "<string>") -> RingScene:
    """Validate the TOML text of a ring-pair file (``origin`` names it in messages)."""
    try:
        doc = tomllib.loads(data.decode("utf-8") if isinstance(data, bytes) else data)
    except (UnicodeDecodeError, tomllib.TOMLDecodeError, RecursionError) as exc:
        raise DatasetError(f"ring scene file {origin!r}: not valid TOML: {' '.join(str(exc).split())}") from None
    return from_document(doc, origin)


def _where(origin: str, section: str, key: str) -> str:
    return f"{origin}: {'[' + section + '] ' if section else ''}{key}"


def _value(origin: str, section: str, key: str, raw, spec) -> object:
    """One key's value checked by kind (units as typed in messages)."""
    unit, kind, _ = spec
    at = _where(origin, section, key)
    u = f" {unit}" if unit and unit != "-" else ""
    if kind == "text":
        if not isinstance(raw, str):
            raise InputError(f"{at} = {raw!r}: must be a text in quotes")
        return raw
    if kind in ("pair", "list"):
        if not isinstance(raw, list) or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in raw):
            raise InputError(f"{at} = {raw!r}{u}: must be a list of numbers")
        vals = [float(v) for v in raw]
        if not all(math.isfinite(v) for v in vals):
            raise InputError(f"{at} = {raw!r}{u}: must be finite numbers")
        if kind == "pair" and len(vals) != 2:
            raise InputError(f"{at} = {raw!r}{u}: must be [low, high]")
        if kind == "list" and not 1 <= len(vals) <= 40:
            raise InputError(f"{at} = {raw!r}{u}: must list 1 to 40 points")
        return vals
    if not isinstance(raw, (int, float)) or isinstance(raw, bool):
        raise InputError(f"{at} = {raw!r}: must be a number{u}")
    v = float(raw)
    if not math.isfinite(v):
        raise InputError(f"{at} = {raw}{u}: must be finite")
    if kind == "len":
        lo, hi = LENGTH_RANGE_MM
        if not v > 0:
            raise InputError(f"{at} = {raw}{u}: must be > 0" + (" (an interference fit is not modelled: the "
                             "ring must have a radial clearance)" if key == "radial_clearance_mm" else ""))
        if not lo <= v <= hi:
            raise InputError(f"{at} = {raw}{u}: must be in [{lo:g}, {hi:g}] mm (wrong unit? millimetres expected)")
    elif kind == "mod":
        lo, hi = MODULUS_RANGE_GPA
        if not lo <= v <= hi:
            hint = " (a value in Pa or MPa? this key is in GPa, e.g. 72 for aluminium)" if v > hi else ""
            raise InputError(f"{at} = {raw}{u}: must be in [{lo:g}, {hi:g}] GPa{hint}")
    elif kind == "nu":
        if not -1.0 < v < 0.5:
            raise InputError(f"{at} = {raw}: must be in (-1, 0.5) (0.5 is an incompressible solid, which the "
                             "displacement FEM cannot model)")
    return v


def _sections(doc: dict, origin: str) -> dict[str, dict]:
    """Every section's keys checked (unknown, missing, type) into {section: {key: value}}."""
    sections = ", ".join("[" + s + "]" for s in KEYS if s)
    for top, val in doc.items():
        if top in KEYS and top and not isinstance(val, dict):
            raise InputError(f"{origin}: {top} = {val!r}: must be a section [{top}]")
        if isinstance(val, dict) and top not in KEYS:
            raise InputError(f"{origin}: section [{top}] unknown (allowed: {sections})")
        if not isinstance(val, dict) and top not in KEYS[""]:
            raise InputError(f"{origin}: key {top!r} unknown (allowed: {', '.join(KEYS[''])}, and the sections "
                             f"{sections})")
    out = {}
    for section, keys in KEYS.items():
        table = ({k: v for k, v in doc.items() if not isinstance(v, dict)} if section == ""
                 else doc.get(section, {}))
        vals = {}
        for key, raw in table.items():
            if isinstance(raw, dict):
                raise InputError(f"{_where(origin, section, key)}: unknown section (allowed keys: {', '.join(keys)})")
            if key not in keys:
                raise InputError(f"{_where(origin, section, key)}: unknown key (allowed: {', '.join(keys)})")
            vals[key] = _value(origin, section, key, raw, keys[key])
        for key, (_, _, required) in keys.items():
            if required and key not in vals:
                raise InputError(f"{_where(origin, section, key)}: missing (required)")
        out[section] = vals
    return out


def _choice(origin: str, section: str, key: str, value: str, allowed) -> str:
    if value not in allowed:
        raise InputError(f"{_where(origin, section, key)} = {value!r}: must be one of {', '.join(allowed)}")
    return value


def _check_geometry(origin: str, ring: dict, housing: dict) -> None:
    """Radii that do not cross, a clearance a bearing seat can have."""
    ri, ro = ring["inner_radius_mm"], ring["outer_radius_mm"]
    if ri >= ro:
        raise InputError(f"{_where(origin, 'bearing_ring', 'inner_radius_mm')} = {ri:g} mm: must be < "
                         f"[bearing_ring] outer_radius_mm = {ro:g} mm (the radii cross)")
    c = housing["radial_clearance_mm"]
    if c > MAX_CLEARANCE_TO_RADIUS * ro:
        raise InputError(f"{_where(origin, 'housing', 'radial_clearance_mm')} = {c:g} mm: must be <= "
                         f"{100 * MAX_CLEARANCE_TO_RADIUS:g} % of the ring's outer radius "
                         f"({MAX_CLEARANCE_TO_RADIUS * ro:g} mm): a clearance that large is not a bearing seat")
    bore, ho = ro + c, housing["outer_radius_mm"]
    if ho <= bore:
        raise InputError(f"{_where(origin, 'housing', 'outer_radius_mm')} = {ho:g} mm: must be > the bore radius "
                         f"{bore:g} mm (ring outer radius + clearance; the radii cross)")
    if ho > 100 * bore:
        raise InputError(f"{_where(origin, 'housing', 'outer_radius_mm')} = {ho:g} mm: must be <= 100 x the bore "
                         f"radius ({100 * bore:g} mm)")


def default_grid(lo: float, hi: float, n: int) -> list[float]:
    """``n`` points from ``lo`` to ``hi`` (same unit), geometric, rounded to 3 significant digits."""
    if n == 1 or hi == lo:
        return [lo]
    r = (hi / lo) ** (1.0 / (n - 1))
    return sorted({float(f"{lo * r ** k:.3g}") for k in range(n)} | {lo, hi})


def _points(origin: str, key: str, given, lo: float, hi: float, unit: str, default) -> list[float]:
    pts = sorted(given) if given is not None else default
    for v in pts:
        if not lo * (1 - 1e-12) <= v <= hi * (1 + 1e-12):
            raise InputError(f"{_where(origin, 'range', key)}: point {v:g} {unit} is outside the range "
                             f"[{lo:g}, {hi:g}] {unit}")
    if len(set(pts)) != len(pts):
        raise InputError(f"{_where(origin, 'range', key)} = {pts}: points must differ")
    return pts


def smallest_penetration_mm(c_mm: float, ro_mm: float, tilt: bool) -> float:
    """The smallest penetration (mm) whose contact the FEM references resolve for a ring of outer radius ``ro_mm``
    in a bore of radial clearance ``c_mm`` (mm): the 2D meshes' shortest half-arc and, with ``tilt``, the 3D levels'
    smallest half-angle (the checks of :func:`from_document`)."""
    eps = _ARC_ELEMENTS * _FINEST_FIRST_LEVEL_M / MM / (_ARC_SHRINK * (ro_mm + c_mm))
    if tilt:
        eps = max(eps, math.radians(_ARC_ELEMENTS * 180.0 / _PHI_ELEMENTS_3D))
    return c_mm * (1 / math.cos(eps) - 1)


def largest_penetration_mm(ro_mm: float) -> float:
    """The largest penetration (mm) of a ring of outer radius ``ro_mm`` (mm) the small-strain model holds."""
    return MAX_PENETRATION_TO_RADIUS * ro_mm


def _check_resolution(origin: str, c_mm: float, ro_mm: float, pen_lo: float, pen_hi: float, tilt_hi: float) -> None:
    """Refuse a range the FEM meshes cannot resolve (the smallest arc) or the small-strain model cannot hold."""
    if pen_hi > largest_penetration_mm(ro_mm):
        raise InputError(f"{_where(origin, 'range', 'penetration_mm')} = [{pen_lo:g}, {pen_hi:g}] mm: the largest "
                         f"must be <= {100 * MAX_PENETRATION_TO_RADIUS:g} % of the ring radius "
                         f"({MAX_PENETRATION_TO_RADIUS * ro_mm:g} mm; small-strain model)")
    eps = math.acos(c_mm / (c_mm + pen_lo))
    arc_mm = _ARC_SHRINK * (ro_mm + c_mm) * eps
    need_mm = _ARC_ELEMENTS * _FINEST_FIRST_LEVEL_M / MM
    if arc_mm < need_mm:
        lo_ok = smallest_penetration_mm(c_mm, ro_mm, tilt=False)
        raise InputError(f"{_where(origin, 'range', 'penetration_mm')} = [{pen_lo:g}, {pen_hi:g}] mm: at {pen_lo:g} mm "
                         f"the contact half-arc (about {arc_mm:.2g} mm) is too short for the 2D meshes to resolve "
                         f"({need_mm:g} mm at least); the smallest penetration this ring can have is about "
                         f"{lo_ok:.2g} mm")
    if tilt_hi > 0 and math.degrees(eps) < _ARC_ELEMENTS * 180.0 / _PHI_ELEMENTS_3D:
        raise InputError(f"{_where(origin, 'range', 'penetration_mm')} = [{pen_lo:g}, {pen_hi:g}] mm: at {pen_lo:g} mm "
                         f"the contact half-angle ({math.degrees(eps):.2g} deg) is below the 3D levels' resolution "
                         f"({_ARC_ELEMENTS * 180.0 / _PHI_ELEMENTS_3D:.2g} deg); raise the smallest penetration")


def _range_points(origin: str, rng: dict, pen_lo: float, pen_hi: float, t_lo: float, t_hi: float):
    """The 2D penetrations, 3D penetrations and tilts (mm, mm, arcmin): given, or :func:`default_grid`."""
    p2 = _points(origin, "penetration_points_mm", rng.get("penetration_points_mm"), pen_lo, pen_hi, "mm",
                 default_grid(pen_lo, pen_hi, 10))
    if len(p2) < 4:
        raise InputError(f"{_where(origin, 'range', 'penetration_points_mm')} = {p2} mm: need >= 4 points (a fit "
                         "with hold-out)")
    p3, tl = [], []
    if t_hi > 0:
        p3 = _points(origin, "penetration_points_3d_mm", rng.get("penetration_points_3d_mm"), pen_lo, pen_hi, "mm",
                     default_grid(pen_lo, pen_hi, 6))
        tl = _points(origin, "tilt_points_arcmin", rng.get("tilt_points_arcmin"), t_lo, t_hi, "arcmin",
                     sorted({0.0, t_lo, t_hi / 4, t_hi / 2, t_hi} - ({0.0} if t_lo > 0 else set())))
        if 0.0 not in tl:
            tl = [0.0] + tl       # the 3D law is calibrated at zero tilt; the tilted points are held out
        if len(p3) < 4:
            raise InputError(f"{_where(origin, 'range', 'penetration_points_3d_mm')} = {p3} mm: need >= 4 points")
    elif rng.get("penetration_points_3d_mm") or rng.get("tilt_points_arcmin"):
        raise InputError(f"{_where(origin, 'range', 'tilt_arcmin')} = [0, 0] arcmin: no 3D work, so 3D point lists "
                         "must not be given")
    return p2, p3, tl


def from_document(doc: dict, origin: str = "<string>") -> RingScene:
    """A parsed TOML document to a :class:`RingScene` (every key checked)."""
    if not isinstance(doc, dict):
        raise InputError(f"{origin}: not a ring-pair file")
    sec = _sections(doc, origin)
    top = sec[""]
    if top["schema"] != SCHEMA:
        raise InputError(f"{_where(origin, '', 'schema')} = {top['schema']!r}: must be {SCHEMA!r}")
    if not _NAME.match(top["name"]):
        raise InputError(f"{_where(origin, '', 'name')} = {top['name']!r}: use 1-60 letters, digits, '_', '.', "
                         "'+', '-' (it names files)")
    plane = _choice(origin, "", "plane", top.get("plane", "auto"), PLANES)
    ring, housing, rng = sec["bearing_ring"], sec["housing"], sec["range"]
    hold = _choice(origin, "housing", "hold", housing.get("hold", "clamped-outer"), tuple(SUPPORT_HOLDS))
    drive = _choice(origin, "drive", "bearing", sec["drive"].get("bearing", "rigid-inner"), tuple(BEARING_DRIVES))
    _check_geometry(origin, ring, housing)
    pen_lo, pen_hi = rng["penetration_mm"]
    if not 0 < pen_lo < pen_hi:
        raise InputError(f"{_where(origin, 'range', 'penetration_mm')} = [{pen_lo:g}, {pen_hi:g}] mm: must be "
                         "[low, high] with 0 < low < high")
    t_lo, t_hi = rng.get("tilt_arcmin", [0.0, 0.0])
    if not 0 <= t_lo <= t_hi <= MAX_TILT_ARCMIN:
        raise InputError(f"{_where(origin, 'range', 'tilt_arcmin')} = [{t_lo:g}, {t_hi:g}] arcmin: must be [low, high] "
                         f"with 0 <= low <= high <= {MAX_TILT_ARCMIN:g} arcmin (small-rotation model)")
    c_mm, ro_mm = housing["radial_clearance_mm"], ring["outer_radius_mm"]
    _check_resolution(origin, c_mm, ro_mm, pen_lo, pen_hi, t_hi)
    if t_hi > 0 and (hold, drive) not in HOLDS_3D:
        raise InputError(f"{_where(origin, 'range', 'tilt_arcmin')} = [{t_lo:g}, {t_hi:g}] arcmin: tilt needs the 3D "
                         f"reference, which models a ring held the same all round: hold = {hold!r} with bearing = "
                         f"{drive!r} is not one of " + "; ".join(f"{h} + {d}" for h, d in HOLDS_3D)
                         + " (or set tilt_arcmin = [0, 0])")
    p2, p3, tl = _range_points(origin, rng, pen_lo, pen_hi, t_lo, t_hi)
    try:
        rings = RingPair(ring["inner_radius_mm"] * MM, ro_mm * MM, c_mm * MM, housing["outer_radius_mm"] * MM,
                         ring["width_mm"] * MM, Material(ring["youngs_modulus_gpa"] * GPA, ring["poisson_ratio"]),
                         Material(housing["youngs_modulus_gpa"] * GPA, housing["poisson_ratio"]))
    except InputError as exc:
        raise InputError(f"{origin}: {exc}") from None
    name = top["name"]
    said = "auto (decided by the 3D check, fem_reference.plane_check)" if plane == "auto" else plane
    scene = Scene(name, rings, "strain" if plane == "auto" else plane, drive, hold, top.get("description", "") or
                  f"ring pair {name}: {SUPPORT_HOLDS[hold]}; {BEARING_DRIVES[drive]}; plane {said}")
    document = {"schema": SCHEMA, "name": name, "plane": plane, "description": top.get("description", ""),
                "bearing_ring": ring, "housing": {**housing, "hold": hold}, "drive": {"bearing": drive},
                "range": {"penetration_mm": [pen_lo, pen_hi], "tilt_arcmin": [t_lo, t_hi], "penetration_points_mm": p2,
                          **({"penetration_points_3d_mm": p3, "tilt_points_arcmin": tl} if p3 else {})}}
    return RingScene(name=name, scene=scene, penetration_range_m=(pen_lo * MM, pen_hi * MM),
                     tilt_range_rad=(t_lo * ARCMIN, t_hi * ARCMIN), penetrations_2d_m=tuple(v * MM for v in p2),
                     penetrations_3d_m=tuple(v * MM for v in p3), tilts_rad=tuple(v * ARCMIN for v in tl),
                     document=document, source=origin)


def with_plane(rs: RingScene, plane: str, name: str | None = None) -> RingScene:
    """``rs`` with its 2D assumption set to ``plane`` ("strain" or "stress"; and its name to ``name`` if given): the
    resolved file of an ``auto`` one (its checksum is that of the resolved content, what the results depend on)."""
    if plane not in ("strain", "stress"):
        raise InputError(f"plane = {plane!r}: a resolved file has plane 'strain' or 'stress'")
    return from_document({**rs.document, "plane": plane, **({"name": name} if name else {})}, rs.source)


def scene_2d(name_or_path: str) -> Scene:
    """The 2D :class:`fem_reference.scenes.Scene` of a ``--scene`` value: a ring-pair file, a bundled one, or a generated name
    (``persson-<ratio>``, ``paper-…``; :func:`fem_reference.scenes.by_name`)."""
    text = str(name_or_path)
    if is_file_argument(text) or text in bundled():
        rs = load(text)
        if rs.plane_auto:
            raise InputError(f"{text}: plane = 'auto' (the default) is decided by the 3D check: resolve it with "
                             "fem_reference.plane_check.scene_2d, or set plane = \"strain\" or \"stress\"")
        return rs.scene
    try:
        return by_name(text)
    except InputError as exc:
        if ": unknown" not in str(exc):      # a generated name with a bad parameter keeps its own message
            raise
        raise InputError(f"scene = {text!r}: unknown (bundled ring-pair files: {', '.join(bundled())}; generated: "
                         "persson-<plate ratio>, paper-…; or a path to a .toml ring-pair file)") from None


# ---------------------------------------------------------------------------------------------
# documentation

def json_schema() -> dict:
    """JSON Schema (draft 2020-12) of a ring-pair file, from :data:`KEYS` (for editors)."""
    def prop(unit, kind):
        num = {"type": "number"}
        if kind == "text":
            return {"type": "string"}
        if kind == "pair":
            return {"type": "array", "items": num, "minItems": 2, "maxItems": 2, "description": f"[low, high] in {unit}"}
        if kind == "list":
            return {"type": "array", "items": num, "minItems": 1, "maxItems": 40, "description": f"points in {unit}"}
        d = {"type": "number", "description": unit}
        if kind == "mod":
            d.update(minimum=MODULUS_RANGE_GPA[0], maximum=MODULUS_RANGE_GPA[1])
        elif kind == "nu":
            d.update(exclusiveMinimum=-1, exclusiveMaximum=0.5)
        else:
            d.update(exclusiveMinimum=0, maximum=LENGTH_RANGE_MM[1])
        return d

    def obj(section):
        keys = KEYS[section]
        props = {k: prop(u, kind) for k, (u, kind, _) in keys.items()}
        return {"type": "object", "additionalProperties": False, "properties": props,
                "required": [k for k, (_, _, req) in keys.items() if req]}

    root = obj("")
    root["properties"]["schema"] = {"const": SCHEMA}
    root["properties"]["plane"] = {"enum": list(PLANES)}
    for s in KEYS:
        if s:
            root["properties"][s] = obj(s)
    root["properties"]["housing"]["properties"]["hold"] = {"enum": list(SUPPORT_HOLDS)}
    root["properties"]["drive"]["properties"]["bearing"] = {"enum": list(BEARING_DRIVES)}
    root["required"] = ["schema", "name", "bearing_ring", "housing", "range"]
    root.update({"$schema": "https://json-schema.org/draft/2020-12/schema", "title": "ringcontact ring-pair file",
                 "$id": "https://ringcontact.invalid/ring-scene-1.schema.json"})
    return root
