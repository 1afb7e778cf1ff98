"""Named boundary-condition scenes. The scene name travels with every reference number.

A scene = ring geometry + plane assumption + how the bearing is driven + how the support is
held. All scenes are half models (x >= 0, u_x = 0 on x = 0) driven by a displacement ``t``
of the bearing along +y; the reported penetration is ``Δr = t − δ0`` (Dai et al. 2025,
Tables 2–3 "relative displacement"; docs/reference/contact-laws.md §10) and the reported force is the
reaction of the driven surface (= total contact force), for the whole ring, times ``l0``.

Scenes
------
``clamped``
    The reference configuration for comparison with other FEM codes: Table 1 rings, support
    outer surface clamped, bearing inner surface moved rigidly (both components) by ``t``,
    plane strain.
``clamped-stress``
    Same, plane stress.
``persson``
    A solid pin (modelled with a rigid core of radius R_b/50 through which it is driven) in a
    plate of outer radius ``plate_ratio × R_b`` clamped at its outer edge: Persson's (1964)
    pin-in-hole problem, for which the conformal law (Ciavarella & Decuzzi 2001; Yang et al.
    2024) is exact as the plate grows. Load vs *measured* contact angle does not depend on the
    plate size; load vs penetration does (the n = 1 term of an infinite plate is log-divergent).

Paper set-up candidates (``paper-*``): see :func:`paper_candidates`.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

from contact.errors import InputError
from contact.units import MM
from fem_reference.plane.geometry import RingPair, table1_rings

BEARING_DRIVES = {
    "rigid-inner": "bearing inner surface moved rigidly by t along +y (u_x = 0, u_y = t)",
    "rigid-inner-y": "bearing inner surface: u_y = t prescribed, u_x free (frictionless shaft fit)",
    "coupled-inner": "bearing inner surface: distributing coupling (RBE3-like): its mean u_y = t, "
                     "load as uniform y-traction, surface free to deform",
    "rigid-inner-axially-free": "bearing inner surface moved rigidly in its plane, free to slide along the axis "
                                "(3D; in 2D the same as rigid-inner)",
}
SUPPORT_HOLDS = {
    "clamped-outer": "support outer surface clamped (u = 0)",
    "clamped-outer-lower": "support outer surface clamped on its lower half only (y <= 0)",
    "clamped-outer-upper": "support outer surface clamped on its upper half only (y >= 0)",
    "clamped-outer-axially-free": "support outer surface held radially and circumferentially, free to slide "
                                  "along the axis (3D; in 2D the same as clamped-outer)",
}
#: the 2D model has no axial displacement: these drives and holds are the 2D ones they name
PLANE_EQUIVALENT = {"rigid-inner-axially-free": "rigid-inner", "clamped-outer-axially-free": "clamped-outer"}


@dataclass(frozen=True)
class Scene:
    """A named boundary-condition scene (see module docstring)."""

    name: str
    rings: RingPair
    plane: str = "strain"
    bearing_drive: str = "rigid-inner"
    support_hold: str = "clamped-outer"
    description: str = ""

    def __post_init__(self):
        if self.plane not in ("strain", "stress"):
            raise InputError(f"plane = {self.plane!r}: must be 'strain' or 'stress'")
        if self.bearing_drive not in BEARING_DRIVES:
            raise InputError(f"bearing_drive = {self.bearing_drive!r}: must be one of {sorted(BEARING_DRIVES)}")
        if self.support_hold not in SUPPORT_HOLDS:
            raise InputError(f"support_hold = {self.support_hold!r}: must be one of {sorted(SUPPORT_HOLDS)}")

    def to_dict(self) -> dict:
        d = asdict(self)
        d["bearing_drive_text"] = BEARING_DRIVES[self.bearing_drive]
        d["support_hold_text"] = SUPPORT_HOLDS[self.support_hold]
        return d


def clamped(rings: RingPair | None = None, plane: str = "strain") -> Scene:
    """The reference scene: clamped support outer surface, rigidly moved bearing inner surface."""
    rings = rings or table1_rings()
    name = "clamped" if plane == "strain" else "clamped-stress"
    return Scene(name, rings, plane, "rigid-inner", "clamped-outer",
                 f"Table 1 rings; {SUPPORT_HOLDS['clamped-outer']}; {BEARING_DRIVES['rigid-inner']}; plane {plane}")


def persson(plate_ratio: float = 20.0, clearance_m: float = 0.05 * MM, plane: str = "strain",
            core_ratio: float = 1 / 50) -> Scene:
    """Pin (R_b = 100 mm, driven through a rigid core of radius ``core_ratio·R_b``) in a plate of
    outer radius ``plate_ratio·R_b``, clamped at its outer edge."""
    if not plate_ratio > 2:
        raise InputError(f"plate_ratio = {plate_ratio!r} -: must be > 2")
    R_b = 100.0 * MM
    rings = RingPair(inner_radius_m=core_ratio * R_b, outer_radius_m=R_b, clearance_m=clearance_m,
                     support_outer_radius_m=plate_ratio * R_b, width_m=30.0 * MM)
    return Scene(f"persson-{plate_ratio:g}", rings, plane, "rigid-inner", "clamped-outer",
                 f"pin in a plate of outer radius {plate_ratio:g} R_b, plane {plane}")


def paper_candidates() -> list[Scene]:
    """Plausible readings of the paper's (unstated) FEM set-up (Dai et al. 2025, §2/Table 2).

    Ring sizes are Table 1's; the variants differ in plane assumption, how the bearing is
    driven and how the support is held.
    """
    r = table1_rings()
    out = []
    for plane in ("strain", "stress"):
        for drive in ("rigid-inner", "rigid-inner-y"):
            for hold in ("clamped-outer", "clamped-outer-lower", "clamped-outer-upper"):
                out.append(Scene(f"paper-{plane}-{drive}-{hold}", r, plane, drive, hold,
                                 f"{BEARING_DRIVES[drive]}; {SUPPORT_HOLDS[hold]}; plane {plane}"))
    return out


def by_name(name: str) -> Scene:
    """Scene from its name: 'clamped', 'clamped-stress', 'persson-<ratio>', 'paper-…'."""
    if name == "clamped":
        return clamped()
    if name == "clamped-stress":
        return clamped(plane="stress")
    if name.startswith("persson-"):
        try:
            ratio = float(name.split("-", 1)[1])
        except ValueError:
            raise InputError(f"scene = {name!r}: expected 'persson-<plate ratio>'") from None
        return persson(ratio)
    for s in paper_candidates():
        if s.name == name:
            return s
    raise InputError(f"scene = {name!r}: unknown (try 'clamped', 'clamped-stress', 'persson-20', "
                     f"or one of the paper-* candidates)")
