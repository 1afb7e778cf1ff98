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
* Lamé (1852) shrink fit of two cylinders of different materials, with each far face clamped or
  free (:func:`shrink_fit_pressure`); Shigley's plane-stress press-fit formula (Budynas & Nisbett
  2015, Eq. 3-57) is its free/free special case (:func:`press_fit_pressure_shigley`). The FE side
  is :func:`shrink_fit_fem` (a verification-only entry point: the interference enters the mortar
  gap of a neat-fit mesh, the contact scenes' solver is unchanged).
* Winkler (1867) foundation: rings clamped on their far faces tend, as they get thin, to a
  bed of springs ``k_f = 1/(h_b/M_b + h_s/M_s)`` (M the constrained modulus; Johnson 1985 §5.9),
  ``P = k_f R l e (ε − sin ε cos ε)``, ``cos ε = δ0/e``, ``e = δ0 + Δr`` (:func:`winkler_force`).
* Dundurs (1969) bimaterial constants α, β (:func:`dundurs_constants`); the pin-in-hole load with
  β ≠ 0, which the closed form lacks, solved numerically (:func:`conformal_force_beta`).
"""
from __future__ import annotations

import math

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


def dundurs_constants(bearing: Material, support: Material, plane: str) -> tuple[float, float]:
    """Dundurs (1969) constants (α, β) [-], body 1 = support (hole), body 2 = bearing (pin).

    ``α = [μ1(κ2+1) − μ2(κ1+1)]/[μ1(κ2+1) + μ2(κ1+1)]``,
    ``β = [μ1(κ2−1) − μ2(κ1−1)]/[μ1(κ2+1) + μ2(κ1+1)]``, ``κ = 3 − 4ν`` (plane strain) or
    ``(3 − ν)/(1 + ν)`` (plane stress) (docs/reference/contact-laws.md §4).
    """
    def kappa(m: Material) -> float:
        nu = m.poisson_ratio
        return 3 - 4 * nu if plane == "strain" else (3 - nu) / (1 + nu)

    m1, m2 = support.lame(plane)[1], bearing.lame(plane)[1]
    k1, k2 = kappa(support), kappa(bearing)
    den = m1 * (k2 + 1) + m2 * (k1 + 1)
    return (m1 * (k2 + 1) - m2 * (k1 + 1)) / den, (m1 * (k2 - 1) - m2 * (k1 - 1)) / den


FACES = ("fixed", "free")


def lame_face_compliance(inner_radius_m: float, outer_radius_m: float, material: Material, plane: str,
                         loaded: str, far_face: str) -> float:
    """Radial displacement [m/Pa] of the loaded face of an annulus a < r < b, per unit pressure on it.

    Lamé (1852): ``u = A r + B/r``, ``σ_r = 2(λ+μ)A − 2μ B/r²`` (λ the plane Lamé constant;
    Timoshenko & Goodier 1970 §28). ``loaded`` = 'inner' (pressure p on r = a, the other face
    ``far_face``) or 'outer' (pressure on r = b). The value is the displacement *into* the body
    away from the load: outward (> 0) at a loaded inner face, inward (> 0) at a loaded outer face.
    ``far_face`` = 'fixed' (u = 0) or 'free' (σ_r = 0).
    """
    if loaded not in ("inner", "outer") or far_face not in FACES:
        raise InputError(f"loaded = {loaded!r}, far_face = {far_face!r}: must be 'inner'/'outer' and one of {FACES}")
    a, b = inner_radius_m, outer_radius_m
    lam, mu = material.lame(plane)
    r_load, r_far = (a, b) if loaded == "inner" else (b, a)

    def u_row(r):
        return [r, 1.0 / r]

    def s_row(r):
        return [2 * (lam + mu), -2 * mu / r ** 2]

    M = np.array([s_row(r_load), u_row(r_far) if far_face == "fixed" else s_row(r_far)])
    A, B = np.linalg.solve(M, np.array([-1.0, 0.0]))           # σ_r = −1 Pa on the loaded face
    u = A * r_load + B / r_load
    return float(u if loaded == "inner" else -u)


def shrink_fit_pressure(interference_m: float, inner_radius_m: float, interface_radius_m: float,
                        outer_radius_m: float, inner: Material, outer: Material, plane: str,
                        inner_face: str = "fixed", outer_face: str = "fixed") -> float:
    """Interface pressure [Pa] of a shrink fit of two cylinders (Lamé 1852).

    Inner body a < r < b (far face r = a ``inner_face``), outer body b < r < c (far face r = c
    ``outer_face``), radial interference δ at r = b: ``δ = p (C_i + C_o)`` with each body's
    :func:`lame_face_compliance`. The suite's scenes are ``inner_face = 'fixed'`` (bearing inner
    surface moved rigidly, here not at all) and ``outer_face = 'fixed'`` (support clamped); then
    ``u(a) = 0`` gives ``B = −A a²`` in the inner body and ``u(c) = 0`` ``B = −A c²`` in the outer one, so

        ``p = δ / [ b(b² − a²)/(2(λ_i+μ_i) b² + 2μ_i a²) + b(c² − b²)/(2(λ_o+μ_o) b² + 2μ_o c²) ]``

    (λ the plane Lamé constant: plane strain λ, plane stress 2μλ/(λ+2μ)). With both far faces
    free and plane stress this is Shigley's :func:`press_fit_pressure_shigley`; plane strain is plane
    stress with ``E → E/(1−ν²)``, ``ν → ν/(1−ν)``.
    """
    c_i = lame_face_compliance(inner_radius_m, interface_radius_m, inner, plane, "outer", inner_face)
    c_o = lame_face_compliance(interface_radius_m, outer_radius_m, outer, plane, "inner", outer_face)
    return interference_m / (c_i + c_o)


def press_fit_pressure_shigley(interference_m: float, inner_radius_m: float, interface_radius_m: float,
                               outer_radius_m: float, inner: Material, outer: Material) -> float:
    """Shigley's press-fit pressure [Pa], plane stress, both far faces free (Budynas & Nisbett 2015, Eq. 3-57).

    ``p = δ / [ (b/E_o)((c²+b²)/(c²−b²) + ν_o) + (b/E_i)((b²+a²)/(b²−a²) − ν_i) ]``.
    """
    a, b, c = inner_radius_m, interface_radius_m, outer_radius_m
    Eo, no, Ei, ni = outer.youngs_modulus_pa, outer.poisson_ratio, inner.youngs_modulus_pa, inner.poisson_ratio
    return interference_m / ((b / Eo) * ((c ** 2 + b ** 2) / (c ** 2 - b ** 2) + no)
                             + (b / Ei) * ((b ** 2 + a ** 2) / (b ** 2 - a ** 2) - ni))


def constrained_modulus(material: Material, plane: str) -> float:
    """Constrained (oedometric) modulus M [Pa]: plane strain ``E(1−ν)/((1+ν)(1−2ν)) = λ + 2μ``,
    plane stress ``E/(1−ν²)``."""
    lam, mu = material.lame(plane)
    return lam + 2 * mu


def winkler_modulus(rings, plane: str) -> float:
    """Foundation modulus ``k_f = 1/(h_b/M_b + h_s/M_s)`` [Pa/m] of two rings in series (Winkler 1867)."""
    h_b = rings.outer_radius_m - rings.inner_radius_m
    h_s = rings.support_outer_radius_m - rings.bore_radius_m
    return 1.0 / (h_b / constrained_modulus(rings.bearing, plane) + h_s / constrained_modulus(rings.support, plane))


def winkler_force(penetration_m: float, clearance_m: float, radius_m: float, width_m: float,
                  foundation_modulus_pa_m: float) -> float:
    """Winkler-foundation load [N]: ``P = k_f R l e (ε − sin ε cos ε)``, ``cos ε = δ0/e``, ``e = δ0 + Δr``.

    The springs are compressed by the rigid overlap ``e cos φ − δ0`` for ``|φ| < ε``; integrating
    ``k_f (e cos φ − δ0) cos φ R l dφ`` over the arc gives the form above (0 for Δr ≤ 0).
    """
    if penetration_m <= 0:
        return 0.0
    e = clearance_m + penetration_m
    eps = math.acos(clearance_m / e)
    return foundation_modulus_pa_m * radius_m * width_m * e * (eps - math.sin(eps) * math.cos(eps))


def shrink_fit_fem(rings, interference_m: float, h_contact_m: float, plane: str = "strain",
                   order: int = 2) -> dict:
    """FE interface pressure of a shrink fit in the scenes' boundary conditions (verification only).

    ``rings`` must be a neat fit (``clearance_m = 0``): the bodies are meshed touching at R_b and the
    interference δ enters the mortar weighted gap as ``G − δ·∫M_j ds`` (linear theory: the radii differ
    by δ ≪ R_b, the same linearisation as Lamé's). Bearing inner surface fixed, support outer surface
    clamped (scene 'clamped' at zero drive). The contact QP is solved over the whole bore with the
    solver of the contact scenes (:func:`~fem_reference.plane.contact_solver.solve_lcp`).

    Returns
    -------
    dict
        ``pressure_pa`` (∫p ds/∫ds over the bore), ``pressure_min_pa``, ``pressure_max_pa`` (nodal
        multipliers), ``ndofs``, ``wall_s``.
    """
    import time

    from fem_reference.plane.contact_solver import mortar_operator, solve_lcp
    from fem_reference.plane.mesh import MeshSpec
    from fem_reference.plane.solve import ContactModel
    from fem_reference.scenes import Scene

    if rings.clearance_m != 0:
        raise InputError(f"clearance_m = {rings.clearance_m:g} m: shrink_fit_fem needs a neat-fit mesh (0 m); "
                         "the interference is interference_m")
    if not 0 < interference_m < 0.01 * rings.outer_radius_m:
        raise InputError(f"interference_m = {interference_m:g} m: must be in (0, 1 % of R_b)")
    t0 = time.perf_counter()
    m = ContactModel.build(Scene("shrink-fit", rings, plane, "rigid-inner", "clamped-outer"),
                           MeshSpec(h_contact_m=h_contact_m, order=order))
    mo = mortar_operator(m.slave, m.master, order, m.ndofs, 0.0)
    Df = mo.D[:, m.system.free]
    Z = np.column_stack([m.system.solve_free(col) for col in Df.T.toarray().T])
    A = np.asarray(Df @ Z)
    lcp = solve_lcp(0.5 * (A + A.T), mo.G - interference_m * mo.weight)
    return {"pressure_pa": float(lcp.lam @ mo.weight / mo.weight.sum()), "pressure_min_pa": float(lcp.lam.min()),
            "pressure_max_pa": float(lcp.lam.max()), "ndofs": m.ndofs, "wall_s": time.perf_counter() - t0}



def conformal_force_beta(half_angle_rad: float, clearance_m: float, composite_modulus_pa: float, width_m: float,
                         alpha: float, beta: float, n_terms: int = 16, n_modes: int = 20000) -> float:
    """Pin-in-hole load [N] at contact half-angle ε with both Dundurs constants, solved numerically.

    The closed form (:func:`conformal_force`) drops Dundurs' β (exact for β = 0 only;
    docs/reference/contact-laws.md §3.5). Here the gap closure of Persson's (1964) problem (infinite
    plate, solid pin; Fourier compliances of docs/reference/contact-laws.md §3.3, ``K = 2R/E*``)

        ``δ0 − e cos θ + K[((1−α)/2 + β) a_0 + Σ_{n≥2} (n−β)/(n²−1) a_n cos nθ] = 0``,  ``|θ| < ε``,

    is solved with the pressure ``p = sqrt(1 − x²) Σ_k c_k U_2k(x)``, ``x = θ/ε`` (bounded, square-root
    edges; U the Chebyshev polynomials of the second kind), whose Fourier coefficients are closed:
    ``∫ sqrt(1−x²) U_m(x) cos(ωx) dx = π (m+1) (−1)^(m/2) J_(m+1)(ω)/ω`` over (−1, 1), m even.
    ``n_terms`` coefficients and the rigid approach ``e`` follow from collocation at ``n_terms + 1``
    Chebyshev points of (0, ε); the series is cut at ``n_modes`` (tail ~ n^(−5/2)). The load is
    ``P = π R a_1 l`` (R cancels). Measured: equals :func:`conformal_force` within 1.2e-5 for β = 0
    (ε = 10°–60°, α = 0 and −0.44), and reproduces the ∂D/∂β table of §3.5 to its three decimals.
    """
    from scipy.special import jv

    eps = float(half_angle_rad)
    if not 0 < eps < math.pi / 2:
        raise InputError(f"half_angle_rad = {eps!r} rad: must be in (0, pi/2)")
    n = np.arange(1, n_modes + 1, dtype=float)
    k = np.arange(n_terms)
    a_n = (2 * k + 1) * (-1.0) ** k * jv(2 * k[None, :] + 1, n[:, None] * eps) / n[:, None]   # a_n per c_k
    a_0 = np.zeros(n_terms)
    a_0[0] = eps / 4                                      # (1/2π)∫p dθ of sqrt(1 − x²)
    theta = eps * np.cos(np.pi * (np.arange(n_terms + 1) + 0.5) / (2 * (n_terms + 1)))
    weight = (n[1:] - beta) / (n[1:] ** 2 - 1.0)
    K = 2.0 / composite_modulus_pa                       # per unit radius
    G = K * (((1 - alpha) / 2 + beta) * a_0[None, :] + (np.cos(np.outer(theta, n[1:])) * weight) @ a_n[1:])
    sol = np.linalg.solve(np.column_stack([G, -np.cos(theta)]), np.full(n_terms + 1, -clearance_m))
    return float(np.pi * (a_n[0] @ sol[:-1]) * width_m)
