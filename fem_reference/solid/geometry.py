"""Geometry of the tilted ring-in-ring problem in 3D: rings, rigid motion, exact gap.

Coordinates (as in Dai et al. 2025 and ``docs/reference/contact-laws.md`` §1): ``x`` along
the shaft (the ring axis), ``y`` the load direction, ``z`` completes a right-handed frame.
A point of a ring surface is addressed by its axial position ``x`` and its polar angle
``phi`` measured from +y towards +z: ``y = R cos(phi)``, ``z = R sin(phi)``.

The bearing's inner surface is moved rigidly: a translation ``r`` along +y and a tilt ``theta``
about +z through the ring centre, so that a point at axial position ``x`` moves by
``r + theta*x`` in y (small-angle form; Dai et al. 2025 Eq. 8: ``y + x*theta_z``).
The penetration quoted everywhere is the one at the mid-plane, ``Delta r = r - delta0``
(Dai et al. 2025 Table 2's "relative displacement", see docs/reference/contact-laws.md §10).

The gap is computed from the true cylinders, never from the faceted mesh: the support bore is
the cylinder of radius ``R_s = R_b + delta0`` about the x axis; the moved bearing surface is the
cylinder of radius ``R_b`` about the moved axis (through ``(0, r, 0)``, direction
``(cos theta, sin theta, 0)``). The rigid gap at a support point ``P`` is
``dist(P, moved axis) - R_b`` (exact for any tilt; negative = overlap).
All values SI (m, rad, Pa).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact.errors import InputError
from contact.units import check_finite, check_positive


@dataclass(frozen=True)
class RingPair3D:
    """Bearing outer ring inside its support ring (Dai et al. 2025 Table 1 defaults).

    Parameters
    ----------
    bearing_inner_radius_m, bearing_outer_radius_m : float
        Radii of the bearing outer ring (m): 90 mm and 100 mm.
    clearance_m : float
        Radial clearance delta0 (m), support bore radius minus bearing outer radius: 0.05 mm.
    support_thickness_m : float
        Radial thickness of the support ring (m): 10 mm.
    width_m : float
        Axial width l0 of both rings (m): 30 mm.
    young_bearing_pa, young_support_pa : float
        Young's moduli (Pa): 204 GPa.
    poisson_bearing, poisson_support : float
        Poisson's ratios (-): 0.3.
    """

    bearing_inner_radius_m: float = 0.090
    bearing_outer_radius_m: float = 0.100
    clearance_m: float = 0.05e-3
    support_thickness_m: float = 0.010
    width_m: float = 0.030
    young_bearing_pa: float = 204e9
    young_support_pa: float = 204e9
    poisson_bearing: float = 0.3
    poisson_support: float = 0.3

    def __post_init__(self):
        check_positive("bearing_inner_radius_m", self.bearing_inner_radius_m, "m", upper=10.0)
        check_positive("bearing_outer_radius_m", self.bearing_outer_radius_m, "m", upper=10.0)
        check_positive("clearance_m", self.clearance_m, "m", upper=0.01)
        check_positive("support_thickness_m", self.support_thickness_m, "m", upper=10.0)
        check_positive("width_m", self.width_m, "m", upper=10.0)
        check_positive("young_bearing_pa", self.young_bearing_pa, "Pa")
        check_positive("young_support_pa", self.young_support_pa, "Pa")
        if self.young_bearing_pa < 1e6 or self.young_support_pa < 1e6:
            raise InputError(f"young modulus = {min(self.young_bearing_pa, self.young_support_pa):g} Pa: "
                             "must be >= 1e6 Pa (wrong unit? Pa expected, not GPa)")
        if self.bearing_inner_radius_m >= self.bearing_outer_radius_m:
            raise InputError(f"bearing_inner_radius_m = {self.bearing_inner_radius_m:g} m: must be < "
                             f"bearing_outer_radius_m = {self.bearing_outer_radius_m:g} m")
        for name in ("poisson_bearing", "poisson_support"):
            nu = getattr(self, name)
            check_finite(name, nu, "-")
            if not -1.0 < nu < 0.5:
                raise InputError(f"{name} = {nu:g} (-): must be in (-1, 0.5)")

    @property
    def support_inner_radius_m(self) -> float:
        """Support bore radius R_b + delta0 (m)."""
        return self.bearing_outer_radius_m + self.clearance_m

    @property
    def support_outer_radius_m(self) -> float:
        """Support outer radius (m)."""
        return self.support_inner_radius_m + self.support_thickness_m

    def as_dict(self) -> dict:
        return {k: float(getattr(self, k)) for k in self.__dataclass_fields__}


@dataclass(frozen=True)
class RigidMotion:
    """Rigid motion of the bearing's inner surface in the canonical frame.

    Parameters
    ----------
    translation_m : float
        Translation r of the ring centre along +y (m).
    tilt_rad : float
        Tilt theta about +z through the ring centre (rad); a point at axial position x moves
        by ``r + theta*x`` in y.
    """

    translation_m: float
    tilt_rad: float = 0.0

    def __post_init__(self):
        check_finite("translation_m", self.translation_m, "m")
        check_finite("tilt_rad", self.tilt_rad, "rad")
        if abs(self.translation_m) > 0.01:
            raise InputError(f"translation_m = {self.translation_m:g} m: must be within +-0.01 m "
                             "(wrong unit? metres expected)")
        if abs(self.tilt_rad) > MAX_TILT_RAD:
            raise InputError(f"tilt_rad = {self.tilt_rad:g} rad: must be within +-{MAX_TILT_RAD:g} rad "
                             "(small-rotation model; wrong unit? radians expected)")

    @classmethod
    def from_penetration(cls, geom: RingPair3D, penetration_m: float, tilt_rad: float = 0.0) -> "RigidMotion":
        """Motion whose mid-plane penetration is ``penetration_m`` (Delta r = r - delta0, m)."""
        check_finite("penetration_m", penetration_m, "m")
        return cls(translation_m=geom.clearance_m + penetration_m, tilt_rad=tilt_rad)


#: the largest tilt of the small-rotation model of :class:`RigidMotion` (rad, 172 arcmin); the 3D jobs' parsers
#: take their ``--tilt-arcmin`` range from it
MAX_TILT_RAD = 0.05


@dataclass(frozen=True)
class CanonicalMotion:
    """A general small rigid motion reduced to the canonical frame by a rotation about x.

    ``motion`` is the canonical motion (translation along +y, tilt about +z); ``frame_angle_rad``
    is the angle psi of the rotation about +x that maps the canonical +y axis onto the actual
    load direction. Vectors computed in the canonical frame are rotated back with
    :func:`rotate_about_x`.
    """

    motion: RigidMotion
    frame_angle_rad: float


def rotate_about_x(vec_y: float, vec_z: float, angle_rad: float) -> tuple[float, float]:
    """Rotate the (y, z) components of a vector by ``angle_rad`` about +x."""
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    return c * vec_y - s * vec_z, s * vec_y + c * vec_z


def reduce_motion(translation_y_m: float, translation_z_m: float,
                  tilt_y_rad: float, tilt_z_rad: float) -> CanonicalMotion:
    """Reduce a general motion (r_y, r_z, theta_y, theta_z) to the canonical half-model frame.

    The relative lateral displacement at axial position x is ``(y + x*theta_z, z - x*theta_y)``
    (docs/reference/contact-laws.md §1, from Dai et al. 2025 Eqs. 13-14). The half model about the plane that
    holds the load direction and the axis applies only if that displacement stays in one plane
    through the axis for every x, i.e. the translation and the "tilt direction"
    ``(theta_z, -theta_y)`` are parallel (or one of them is zero). Then a rotation about x by
    ``psi`` maps the problem onto translation along +y and tilt about +z.

    Raises
    ------
    InputError
        If translation and tilt directions are not parallel: that motion twists the contact
        line out of the symmetry plane and needs a full (360 degree) model, which this
        reference does not build.
    """
    for name, v, unit in (("translation_y_m", translation_y_m, "m"), ("translation_z_m", translation_z_m, "m"),
                          ("tilt_y_rad", tilt_y_rad, "rad"), ("tilt_z_rad", tilt_z_rad, "rad")):
        check_finite(name, v, unit)
    ty, tz = tilt_z_rad, -tilt_y_rad          # lateral slope of the displacement (dy/dx, dz/dx)
    r_norm = math.hypot(translation_y_m, translation_z_m)
    t_norm = math.hypot(ty, tz)
    if r_norm == 0.0 and t_norm == 0.0:
        return CanonicalMotion(RigidMotion(0.0, 0.0), 0.0)
    if r_norm > 0.0:
        psi = math.atan2(translation_z_m, translation_y_m)
    else:
        psi = math.atan2(tz, ty)
    cross = translation_y_m * tz - translation_z_m * ty
    scale = max(r_norm, 1e-12) * max(t_norm, 1e-15)
    if r_norm > 0.0 and t_norm > 0.0 and abs(cross) > 1e-9 * scale:
        raise InputError(
            f"translation (y, z) = ({translation_y_m:g}, {translation_z_m:g}) m and tilt (theta_y, theta_z) = "
            f"({tilt_y_rad:g}, {tilt_z_rad:g}) rad are not in one plane through the axis "
            f"(cross product {cross:g} m*rad): the half model needs the tilt axis perpendicular to the "
            "translation (e.g. translation along y with tilt about z, or along z with tilt about y)")
    c, s = math.cos(psi), math.sin(psi)
    r_canon = c * translation_y_m + s * translation_z_m
    slope_canon = c * ty + s * tz                  # slope along the canonical +y axis
    return CanonicalMotion(RigidMotion(r_canon, slope_canon), psi)


def rigid_gap_m(geom: RingPair3D, motion: RigidMotion, phi_rad, x_m) -> np.ndarray:
    """Exact rigid gap (m) between the support bore and the moved bearing cylinder.

    Parameters
    ----------
    geom : RingPair3D
    motion : RigidMotion
    phi_rad, x_m : array_like
        Polar angle (rad, from +y towards +z) and axial position (m) of points on the
        undeformed support bore.

    Returns
    -------
    ndarray
        ``dist(P, moved bearing axis) - R_b`` for ``P = (x, R_s cos phi, R_s sin phi)``:
        positive = open, negative = overlap (penetration).
    """
    phi = np.asarray(phi_rad, dtype=float)
    x = np.asarray(x_m, dtype=float)
    rs = geom.support_inner_radius_m
    p = np.stack(np.broadcast_arrays(x, rs * np.cos(phi), rs * np.sin(phi)), axis=-1)
    centre = np.array([0.0, motion.translation_m, 0.0])
    axis = np.array([math.cos(motion.tilt_rad), math.sin(motion.tilt_rad), 0.0])
    d = p - centre
    along = d @ axis
    perp = d - along[..., None] * axis
    return np.linalg.norm(perp, axis=-1) - geom.bearing_outer_radius_m


def edge_penetrations_m(geom: RingPair3D, motion: RigidMotion) -> tuple[float, float]:
    """Rigid penetrations at the two ring edges on the loaded side, small-angle form (m).

    Returns ``(Delta r_1, Delta r_2)`` at ``x = +l0/2`` and ``x = -l0/2`` on the +y generatrix,
    ``Delta r_k = r +- theta*l0/2 - delta0`` (docs/reference/contact-laws.md §8). A negative value is open.
    Contact on the opposite (-y) generatrix at edge k happens when ``-(r +- theta*l0/2) > delta0``.
    """
    half = 0.5 * geom.width_m
    y1 = motion.translation_m + motion.tilt_rad * half
    y2 = motion.translation_m - motion.tilt_rad * half
    return y1 - geom.clearance_m, y2 - geom.clearance_m


def law_contact_width_m(geom: RingPair3D, motion: RigidMotion) -> float:
    """Contact width of Dai et al. 2025 Eq. 11 on the loaded (+y) side: ``l = Delta r_1/|theta|``,
    capped at l0, where Delta r_1 is the larger edge penetration (m). Zero when no overlap."""
    d1, d2 = edge_penetrations_m(geom, motion)
    dmax = max(d1, d2)
    if dmax <= 0.0:
        return 0.0
    if motion.tilt_rad == 0.0:
        return geom.width_m
    return min(dmax / abs(math.tan(motion.tilt_rad)), geom.width_m)
