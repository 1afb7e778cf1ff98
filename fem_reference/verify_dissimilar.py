"""Verification studies on geometries and materials the references were not tuned on (SI units).

The suite was verified on one ring pair (Dai et al. 2025 Table 1: steel in steel). These studies
put the 2D and 3D references against closed forms (:mod:`fem_reference.verify`) with dissimilar
materials and other sizes; each returns rows with the closed form, the FEM value, the FEM point's
stated error and the difference, for the tests (tests/fem_reference/test_dissimilar_verification.py)
and the report (benchmarks/verify_dissimilar.py).

The engineers' bearing (:func:`engineer_rings`): a steel ring (E 208 GPa, ν 0.30) of radii
48/55 mm and width 22 mm in an aluminium housing (E 72 GPa, ν 0.33) of outer radius 75 mm with a
radial clearance of 0.03 mm.
"""
from __future__ import annotations

import math
import time

from contact.units import GPA, MM
from fem_reference.plane.geometry import Material, RingPair
from fem_reference.plane.sweep import Levels, reference_point, richardson
from fem_reference.scenes import Scene
from fem_reference.verify import (composite_modulus, conformal_force, conformal_force_beta, dundurs_constants,
                                  shrink_fit_fem, shrink_fit_pressure, winkler_force, winkler_modulus)

STEEL_208 = Material(208.0 * GPA, 0.30)
ALUMINIUM = Material(72.0 * GPA, 0.33)
SHRINK_LEVELS_M = (4e-3, 2e-3, 1e-3)


def _cheap_level(name: str, n_phi: int, n_axial: int, n_radial: int):
    from fem_reference.solid.mesh import MeshLevel3D

    return MeshLevel3D(name, n_phi, n_axial, n_radial, axial_ratio=30.0, radial_ratio=20.0, method="fourier",
                       n_harmonics=2 * n_phi)


def cheap_levels_3d() -> list:
    """Three harmonic levels below and up to Q0 (every count about /sqrt(2) per level, as the Q family of
    :mod:`fem_reference.solid.mesh`): a 3D reference point in ~2 s with a looser stated error."""
    return [_cheap_level("C0", 32, 6, 3), _cheap_level("C1", 45, 8, 4), _cheap_level("Q0", 64, 12, 5)]


def engineer_rings(scale: float = 1.0, clearance_m: float = 0.03 * MM) -> RingPair:
    """The engineers' steel ring in an aluminium housing, every length times ``scale`` [-]."""
    return RingPair(48.0 * MM * scale, 55.0 * MM * scale, clearance_m * scale, 75.0 * MM * scale,
                    22.0 * MM * scale, STEEL_208, ALUMINIUM)


def engineer_rings_3d(scale: float = 1.0):
    """:func:`engineer_rings` as a :class:`~fem_reference.solid.geometry.RingPair3D`."""
    from fem_reference.solid.geometry import RingPair3D

    r = engineer_rings(scale)
    return RingPair3D(r.inner_radius_m, r.outer_radius_m, r.clearance_m, r.support_outer_radius_m - r.bore_radius_m,
                      r.width_m, r.bearing.youngs_modulus_pa, r.support.youngs_modulus_pa,
                      r.bearing.poisson_ratio, r.support.poisson_ratio)


def _row(check: str, closed: float, fem: float, error_abs: float, **extra) -> dict:
    return {"check": check, "closed_form": closed, "fem": fem, "fem_error_abs": error_abs,
            "difference_rel": fem / closed - 1.0, "fem_error_rel": error_abs / abs(fem), **extra}


def shrink_fit_study(interference_m: float = 0.03 * MM, planes=("strain", "stress"),
                     levels_m=SHRINK_LEVELS_M) -> list[dict]:
    """Lamé shrink fit of the engineers' rings (neat-fit mesh, interference δ), far faces fixed.

    FE interface pressure on three levels (coarse → fine) with its Richardson estimate
    (:func:`~fem_reference.plane.sweep.richardson`) against :func:`~fem_reference.verify.shrink_fit_pressure`.
    """
    rings = engineer_rings(clearance_m=0.0)
    rows = []
    for plane in planes:
        t0 = time.perf_counter()
        fem = [shrink_fit_fem(rings, interference_m, h, plane) for h in levels_m]
        rf = richardson([f["pressure_pa"] for f in fem[-3:]])
        closed = shrink_fit_pressure(interference_m, rings.inner_radius_m, rings.outer_radius_m,
                                     rings.support_outer_radius_m, rings.bearing, rings.support, plane)
        fine = fem[-1]
        rows.append(_row(f"shrink fit, plane {plane}", closed, rf.value, rf.error_abs, plane=plane,
                         interference_m=interference_m, levels_m=list(levels_m), ndofs=fine["ndofs"],
                         pressure_spread_rel=(fine["pressure_max_pa"] - fine["pressure_min_pa"]) / rf.value,
                         wall_s=time.perf_counter() - t0))
    return rows


def thin_ring_rings(thickness_ratio: float, radius_m: float = 55.0 * MM, clearance_m: float = 0.03 * MM,
                    width_m: float = 22.0 * MM) -> RingPair:
    """Steel ring in aluminium, both of radial thickness ``thickness_ratio·R`` [-]."""
    h = thickness_ratio * radius_m
    return RingPair(radius_m - h, radius_m, clearance_m, radius_m + clearance_m + h, width_m, STEEL_208, ALUMINIUM)


def winkler_study(thickness_ratios=(0.1, 0.05, 0.025), penetration_m: float = 0.003 * MM) -> list[dict]:
    """Thin rings clamped on their far faces ('clamped' scene) against the Winkler foundation law.

    Mesh levels scale with the ring thickness h: h/2, h/4, h/8, h/16 (the reference point picks
    three or four of them, :func:`~fem_reference.plane.sweep.reference_point`), so every ratio is
    resolved alike through the thickness.
    """
    rows = []
    for q in thickness_ratios:
        rings = thin_ring_rings(q)
        h = q * rings.outer_radius_m
        t0 = time.perf_counter()
        p = reference_point(Levels(Scene(f"thin-{q:g}", rings), tuple(h / k for k in (2, 4, 8, 16))), penetration_m)
        closed = winkler_force(penetration_m, rings.clearance_m, rings.outer_radius_m, rings.width_m,
                               winkler_modulus(rings, "strain"))
        rows.append(_row(f"Winkler, h/R = {q:g}", closed, p["force_n"], p["force_error_rel"] * p["force_n"],
                         thickness_ratio=q, penetration_m=penetration_m, half_angle_deg=math.degrees(p["half_angle_rad"]),
                         ndofs=p["ndofs"], wall_s=time.perf_counter() - t0))
    return rows


def beta_free_support(bearing: Material = STEEL_208, youngs_modulus_pa: float = 72.0 * GPA,
                      plane: str = "strain") -> Material:
    """A support of modulus E whose Poisson ratio makes Dundurs' β vanish against ``bearing``.

    Plane strain: ``μ1(κ2−1) = μ2(κ1−1)`` (ν ≈ 0.437 for E = 72 GPa against steel 208 GPa/0.30), so
    that the conformal law with α alone is exact (docs/reference/contact-laws.md §3.3).
    """
    from scipy.optimize import brentq

    def beta(nu):
        return dundurs_constants(bearing, Material(youngs_modulus_pa, nu), plane)[1]

    return Material(youngs_modulus_pa, brentq(beta, bearing.poisson_ratio, 0.4999, xtol=1e-14))


def persson_rings(plate_ratio: float, support: Material, bearing: Material = STEEL_208) -> RingPair:
    """Persson's pin (R_b = 100 mm, rigid core R_b/50, δ0 = 0.05 mm, l = 30 mm) in a plate of radius ``plate_ratio·R_b``."""
    R_b = 100.0 * MM
    return RingPair(R_b / 50, R_b, 0.05 * MM, plate_ratio * R_b, 30.0 * MM, bearing, support)


def persson_study(support: Material, plate_ratios=(10.0, 20.0, 40.0, 80.0),
                  penetrations_m=(0.012 * MM, 0.05 * MM), plane: str = "strain") -> list[dict]:
    """Load vs measured half-angle on Persson's scene against the conformal law with E* and Dundurs' α.

    Each row: the FE reference point (default levels), the law at the measured angle with α
    (``closed_form``), without α (``law_alpha0_n``) and with α and β (``law_beta_n``, solved
    numerically, :func:`~fem_reference.verify.conformal_force_beta`).
    """
    rows = []
    for ratio in plate_ratios:
        rings = persson_rings(ratio, support)
        alpha, beta = dundurs_constants(rings.bearing, rings.support, plane)
        e_star = composite_modulus(rings.bearing, rings.support, plane)
        levels = Levels(Scene(f"persson-{ratio:g}-dissimilar", rings, plane))
        for dr in penetrations_m:
            t0 = time.perf_counter()
            p = reference_point(levels, dr)
            eps = p["half_angle_rad"]
            law = float(conformal_force(eps, rings.clearance_m, e_star, rings.width_m, alpha))
            rows.append(_row(f"Persson, plate {ratio:g}", law, p["force_n"], p["force_error_rel"] * p["force_n"],
                             plate_ratio=ratio, penetration_m=dr, half_angle_deg=math.degrees(eps),
                             half_angle_error_rel=p["half_angle_error_rel"], alpha=alpha, beta=beta,
                             law_alpha0_n=float(conformal_force(eps, rings.clearance_m, e_star, rings.width_m, 0.0)),
                             law_beta_n=conformal_force_beta(eps, rings.clearance_m, e_star, rings.width_m, alpha, beta),
                             wall_s=time.perf_counter() - t0))
    return rows


def scaling_2d(penetration_m: float = 0.01 * MM, factor: float = 2.0, plane: str = "strain") -> dict:
    """Force at ``factor·Δr`` on the rings times ``factor`` against ``factor²`` times the original.

    Both points are reference points on the default (absolute) mesh levels, so the meshes are not
    similar: the bound is the sum of the two stated errors (scaled like the forces).
    """
    t0 = time.perf_counter()
    p1 = reference_point(Levels(Scene("engineer", engineer_rings(), plane)), penetration_m)
    p2 = reference_point(Levels(Scene("engineer-x2", engineer_rings(factor), plane)), factor * penetration_m)
    k = factor ** 2
    err = k * p1["force_error_rel"] * p1["force_n"] + p2["force_error_rel"] * p2["force_n"]
    return _row(f"2D scaling x{factor:g}, plane {plane}", k * p1["force_n"], p2["force_n"], err, plane=plane,
                penetration_m=penetration_m, force_n=p1["force_n"], wall_s=time.perf_counter() - t0)


def _levels3d(names):
    from fem_reference.solid.mesh import LEVELS

    return [LEVELS[n] if isinstance(n, str) else n for n in names]


def scaling_3d(level_names=("Q0", "Q1", "Q2"), penetration_m: float = 0.01 * MM, tilt_rad: float = math.radians(1 / 60),
               factor: float = 2.0) -> list[dict]:
    """3D 'clamped' scene at a tilted point: rings times ``factor`` → force times factor², moment times factor³.

    The 3D levels are element counts (:class:`~fem_reference.solid.mesh.MeshLevel3D`), so the two
    meshes are similar; the bound is still the sum of the two stated errors.
    """
    from fem_reference.solid.sweep import get_compliance
    from fem_reference.solid.sweep import reference_point as point3d

    t0 = time.perf_counter()
    pts = []
    for s in (1.0, factor):
        comps = [get_compliance(engineer_rings_3d(s), lv, "clamped", use_cache=False) for lv in _levels3d(level_names)]
        if len(comps) == 3:
            pts.append(point3d(comps, s * penetration_m, tilt_rad))
        else:                                         # one level: no estimate, the similarity is checked alone
            from fem_reference.solid.geometry import RigidMotion
            from fem_reference.solid.solve import solve_point

            sol = solve_point(comps[0], RigidMotion.from_penetration(comps[0].geom, s * penetration_m, tilt_rad))
            pts.append({"force_n": sol.force_n, "force_error_rel": 0.0, "moment_nm": sol.moment_z_nm,
                        "moment_error_rel": 0.0})
    wall = time.perf_counter() - t0
    rows = []
    for key, err_key, k in (("force_n", "force_error_rel", factor ** 2), ("moment_nm", "moment_error_rel", factor ** 3)):
        a, b = pts
        err = k * abs(a[err_key] * a[key]) + abs(b[err_key] * b[key])
        rows.append(_row(f"3D scaling x{factor:g}, {key.split('_')[0]}", k * a[key], b[key], err,
                         levels=[lv.name for lv in _levels3d(level_names)], penetration_m=penetration_m,
                         tilt_rad=tilt_rad, wall_s=wall))
    return rows


def plane_strain_3d_study(level_names=("Q0", "Q1", "Q2"), penetrations_m=(0.01 * MM, 0.03 * MM)) -> list[dict]:
    """3D 'clamped-axially-fixed-ends' at zero tilt against the 2D plane-strain 'clamped' reference.

    Both are FE reference points with their stated errors; the bound is their sum. Here the
    closed-form column holds the 2D reference (exact equivalence of the two scenes at zero tilt).
    """
    from fem_reference.solid.sweep import get_compliance
    from fem_reference.solid.sweep import reference_point as point3d

    t0 = time.perf_counter()
    comps = [get_compliance(engineer_rings_3d(), lv, "clamped-axially-fixed-ends", use_cache=False)
             for lv in _levels3d(level_names)]
    build = time.perf_counter() - t0
    levels2d = Levels(Scene("engineer", engineer_rings(), "strain"))
    rows = []
    for dr in penetrations_m:
        p3 = point3d(comps, dr, 0.0)
        p2 = reference_point(levels2d, dr)
        err = p3["force_error_rel"] * p3["force_n"] + p2["force_error_rel"] * p2["force_n"]
        rows.append(_row("3D fixed ends vs 2D plane strain", p2["force_n"], p3["force_n"], err, penetration_m=dr,
                         error_3d_rel=p3["force_error_rel"], error_2d_rel=p2["force_error_rel"],
                         levels=[lv.name for lv in _levels3d(level_names)], build_s=build))
    return rows


def within(row: dict) -> bool:
    """The absolute difference FEM − closed form is within the stated error."""
    return abs(row["fem"] - row["closed_form"]) <= row["fem_error_abs"]
