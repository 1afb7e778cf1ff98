"""Closed-form cases the FEM is checked against (SI units).

* Lamé (1852) thick cylinder: annulus a < r < b, outer surface clamped, inner pressure p.
* Persson (1964) / Ciavarella & Decuzzi (2001) conformal pin-in-hole law, in the explicit form
  of Yang et al. (2024) / Dai et al. (2025) Eq. 5 (docs/reference/contact-laws.md §3):
  ``P = 2π E* δ0 l b²(1+b²)/D(b)``, ``D = 2 − (1−α)(ln(1+b²) + 2b⁴)``, ``b = tan(ε/2)``,
  with ε the *measured* contact half-angle. Implemented here (not imported from
  ``contact.laws``) because fem_reference may only import contact's errors/units/files/dataset,
  and because the FE check needs the load as a function of the angle, not of the penetration.
* Hertz (1882) line contact of conforming cylinders (Johnson 1985, §4.2): half-width
  ``a² = 4 P' R/(π E*)``, ``R = R_b R_s/(R_s − R_b)``, peak pressure ``p0 = 2P'/(π a)``; the
  small-arc limit of the conformal law.
"""
from __future__ import annotations

import numpy as np

from contact.errors import InputError, OutsideDomainError
from fem_reference.plane.geometry import Material


def composite_modulus(bearing: Material, support: Material, plane: str) -> float:
    """E* [Pa] with ``1/E* = 1/E'_b + 1/E'_s`` (E' = E/(1−ν²) plane strain, E plane stress)."""
    return 1.0 / (1.0 / bearing.plane_modulus(plane) + 1.0 / support.plane_modulus(plane))


def lame_clamped_outer_displacement(inner_radius_m: float, outer_radius_m: float, pressure_pa: float,
                                    material: Material, plane: str) -> float:
    """Radial displacement [m] of the inner surface of an annulus clamped at its outer radius.

    ``u = A r + B/r`` (Lamé); ``u(b) = 0`` and ``σ_r(a) = −p`` give
    ``A = −p/(2(λ+μ) + 2μ b²/a²)``, ``u(a) = A (a − b²/a)`` (λ the plane Lamé constant).
    """
    a, b = inner_radius_m, outer_radius_m
    lam, mu = material.lame(plane)
    A = -pressure_pa / (2 * (lam + mu) + 2 * mu * b ** 2 / a ** 2)
    return A * (a - b ** 2 / a)


def conformal_force(half_angle_rad, clearance_m: float, composite_modulus_pa: float, width_m: float,
                    alpha: float = 0.0):
    """Conformal (Persson) load [N] at contact half-angle ε (vectorised).

    Raises
    ------
    OutsideDomainError
        Where ``D(b) <= 0`` (beyond the neat-fit pole, ε ≈ 84.8° for α = 0).
    """
    eps = np.asarray(half_angle_rad, dtype=float)
    if np.any((eps < 0) | (eps >= np.pi)):
        raise InputError(f"half_angle_rad = {eps!r} rad: must be in [0, pi)")
    b2 = np.tan(eps / 2) ** 2
    D = 2.0 - (1.0 - alpha) * (np.log1p(b2) + 2.0 * b2 ** 2)
    if np.any(D <= 0):
        raise OutsideDomainError(f"half_angle_rad = {np.max(eps):g} rad: beyond the conformal law's pole "
                                 f"(D(b) <= 0)")
    return 2 * np.pi * composite_modulus_pa * clearance_m * width_m * b2 * (1 + b2) / D


def hertz_line_contact(force_per_length_n_m: float, bearing_radius_m: float, bore_radius_m: float,
                       composite_modulus_pa: float) -> tuple[float, float]:
    """Hertz conforming line contact: (half-width a [m], peak pressure p0 [Pa])."""
    R = bearing_radius_m * bore_radius_m / (bore_radius_m - bearing_radius_m)
    a = np.sqrt(4 * force_per_length_n_m * R / (np.pi * composite_modulus_pa))
    return float(a), float(2 * force_per_length_n_m / (np.pi * a))


def lame_fem(h_contact_m: float = 2e-3, order: int = 2, plane: str = "strain",
             pressure_pa: float = 100e6) -> tuple[float, float]:
    """FE vs closed form for the Table 1 support ring, outer surface clamped, bore pressurised.

    Returns ``(u_fe_m, u_exact_m)``: mean radial displacement of the bore nodes and Lamé's value.
    The bearing ring is meshed too (inner surface clamped, unloaded), so this runs the very same
    mesh, assembly and Dirichlet code as the contact scenes.
    """
    from fem_reference.plane.elasticity import (ElasticSystem, circle_dofs, pressure_load, stiffness,
                                          symmetry_dofs, vector_basis)
    from fem_reference.plane.geometry import table1_rings
    from fem_reference.plane.mesh import MeshSpec, build_mesh

    rings = table1_rings()
    rm = build_mesh(rings, MeshSpec(h_contact_m=h_contact_m, order=order))
    basis = vector_basis(rm)
    K = stiffness(rm, basis, plane)
    fixed = np.concatenate([symmetry_dofs(rm, basis), circle_dofs(rm, basis, rings.inner_radius_m).ravel(),
                            circle_dofs(rm, basis, rings.support_outer_radius_m).ravel()])
    system = ElasticSystem.build(K, fixed)
    f = pressure_load(rm, basis, rings.bore_radius_m, pressure_pa)
    # the bearing's outer circle is a free boundary too; pressure only on the support bore
    from fem_reference.plane.mesh import SUPPORT, facets_on_circle

    u = system.solve(f)
    facets = facets_on_circle(rm.mesh, rings.bore_radius_m, element_mask=rm.body == SUPPORT)
    d = basis.get_dofs(facets=facets)
    ux, uy = u[d.all("u^1")], u[d.all("u^2")]
    xy = basis.doflocs[:, d.all("u^1")]
    ur = (ux * xy[0] + uy * xy[1]) / np.hypot(xy[0], xy[1])
    exact = lame_clamped_outer_displacement(rings.bore_radius_m, rings.support_outer_radius_m, pressure_pa,
                                            rings.support, plane)
    return float(ur.mean()), float(exact)


def persson_plate_study(plate_ratios=(5.0, 10.0, 20.0, 40.0, 80.0, 160.0), penetrations_m=(1e-5, 5e-5),
                        h_contact_m: float = 2e-3, plane: str = "strain") -> list[dict]:
    """Pin in plates of growing outer radius: load vs penetration and vs measured angle.

    Returns one row per (plate ratio, penetration): force [N], measured half-angle [rad] and the
    ratio of the force to the conformal law at that measured angle. Persson (1964): the load vs
    *angle* relation converges as the plate grows; the load vs *penetration* does not (the rigid
    approach of an infinite plate is log-divergent, compliance ≈ c0 + c1 ln(R_o/R_b)).
    """
    from fem_reference.plane.mesh import MeshSpec
    from fem_reference.plane.solve import ContactModel
    from fem_reference.scenes import persson

    rows = []
    for ratio in plate_ratios:
        sc = persson(ratio, plane=plane)
        m = ContactModel.build(sc, MeshSpec(h_contact_m=h_contact_m, order=2, grading_length_m=10e-3))
        Es = composite_modulus(sc.rings.bearing, sc.rings.support, plane)
        for d in penetrations_m:
            s = m.solve(d)
            law = float(conformal_force(s.half_angle_rad, sc.rings.clearance_m, Es, sc.rings.width_m))
            rows.append({"plate_ratio": ratio, "penetration_m": d, "force_n": s.force_n,
                         "half_angle_rad": s.half_angle_rad, "force_over_law": s.force_n / law, "ndofs": s.ndofs})
    return rows
