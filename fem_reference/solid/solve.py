"""Frictionless contact of the two rings on a ready compliance: one load point.

The expensive part of a mesh level (assembly, factorisation, the contact compliance G of the
half model) is built once per mesh by :mod:`fem_reference.solid.compliance`. A load point
(r, theta) then only changes the rigid gap ``g0`` (computed from the true tilted cylinders,
:func:`fem_reference.solid.geometry.rigid_gap_m`) and the contact problem is the linear
complementarity problem

    g = g0 + G lam >= 0,   lam >= 0,   lam . g = 0

with lam the nodal contact forces (N) of the half model. It is solved exactly (to round-off)
by a primal-dual active-set (semismooth Newton) iteration on the dense SPD matrix G restricted to
candidate pairs, with scipy's NNLS (Lawson-Hanson, finite termination) on the Cholesky factor as
fallback. Complementarity is verified on *all* pairs after the solve (pairs outside the candidate
set must stay open); a violation enlarges the set and re-solves. This is exact frictionless
node-to-node contact for the discrete model: no penalty parameter, no augmentation error.

Totals are doubled for the full ring (the half model about z = 0 carries half of every force;
nodes on the symmetry plane carry half their full-model share). Sign convention (docs/reference/contact-laws.md
§1, §8): the contact force on the bearing is ``-P`` along +y for a +y translation, and its
moment about +z through the ring centre is ``M_z = sum x F_y`` (negative for a positive tilt).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla

from contact.errors import ConvergenceError
from fem_reference.solid.compliance import (SCENES, ContactCompliance, build_compliance, load_compliance,
                                            save_compliance)
from fem_reference.solid.geometry import RigidMotion, law_contact_width_m, rigid_gap_m
from fem_reference.solid.mortar import weighted_gap

__all__ = ["SCENES", "ContactCompliance", "PointResult3D", "build_compliance", "load_compliance",
           "save_compliance", "solve_lcp", "solve_point"]

def solve_lcp(G: np.ndarray, g0: np.ndarray, *, max_iter: int = 100) -> tuple[np.ndarray, int, str]:
    """Solve ``g = g0 + G lam >= 0, lam >= 0, lam.g = 0`` for SPD ``G``.

    Primal-dual active set (semismooth Newton on ``min(lam, g) = 0``), started from the rigid
    overlap; falls back to NNLS on the Cholesky factor if the active set cycles.

    Returns
    -------
    lam : ndarray
        Contact forces (N).
    iterations : int
    method : str
    """
    n = len(g0)
    active = g0 < 0
    lam = np.zeros(n)
    seen = set()
    for it in range(1, max_iter + 1):
        lam = np.zeros(n)
        idx = np.flatnonzero(active)
        if idx.size:
            c, low = sla.cho_factor(G[np.ix_(idx, idx)], check_finite=False)
            lam[idx] = sla.cho_solve((c, low), -g0[idx], check_finite=False)
        g = g0 + G @ lam
        scale = np.max(np.abs(g0)) if n else 1.0
        new_active = np.where(active, lam > 0, g < -1e-12 * scale)
        if np.array_equal(new_active, active):
            return lam, it, "active-set"
        key = new_active.tobytes()
        if key in seen:
            break
        seen.add(key)
        active = new_active
    # fallback: min 1/2 lam^T G lam + g0^T lam, lam >= 0  <=>  NNLS with G = L L^T
    import scipy.optimize as sopt
    L = np.linalg.cholesky(G)
    rhs = -sla.solve_triangular(L, g0, lower=True)
    lam, _ = sopt.nnls(L.T, rhs, maxiter=50 * n)
    return lam, max_iter, "nnls"


@dataclass(frozen=True)
class PointResult3D:
    """One load point on one mesh level (full-ring totals, SI units).

    Attributes
    ----------
    force_n : float
        Load magnitude (N): minus the y-component of the contact force on the bearing.
    moment_z_nm : float
        Moment about +z through the ring centre of the contact force on the bearing (N*m),
        ``sum x*F_y`` (docs/reference/contact-laws.md §1 convention; negative for a positive tilt).
    contact_x_min_m, contact_x_max_m, contact_width_m : float
        Axial extent of the contact on the loaded (+y) side (m): active nodes on any generatrix
        of that side; each open end located by extrapolating the squared pressure on phi = 0 to
        zero (see ``_extent``), or at the ring edge. Zero width when the side is open.
    contact_width_law_m : float
        The law's width ``min(Delta r_1/|theta|, l0)`` (Dai et al. 2025 Eq. 11) for comparison.
    load_centre_x_m : float
        Axial position of the load resultant, ``M_z / F_y`` (m).
    contact_half_angle_rad : float
        Largest polar angle of an active pair on the +y side (rad).
    edges_loaded : str
        Which ring edges carry load: "none", "+x", "-x" or "both".
    sides : str
        "+y", "-y" or "both" (two-point contact on opposite generatrices, Dai et al. 2025 §2.2).
    force_minus_y_side_n : float
        Load carried on the -y side (N, magnitude), nonzero only for two-point contact.
    peak_pressure_pa : float
        Largest contact pressure (Pa).
    n_dofs, n_pairs, n_active, iterations : int
        Degrees of freedom, contact node pairs, active pairs, contact iterations.
    n_active_lines : int
        Axial node lines with contact on the +y side (resolution of the patch length).
    solve_s : float
        Wall time of the contact solve on a ready compliance (s).
    """

    penetration_m: float
    tilt_rad: float
    level: str
    force_n: float
    moment_z_nm: float
    contact_x_min_m: float
    contact_x_max_m: float
    contact_width_m: float
    contact_width_law_m: float
    load_centre_x_m: float
    contact_half_angle_rad: float
    edges_loaded: str
    sides: str
    force_minus_y_side_n: float
    peak_pressure_pa: float
    n_dofs: int
    n_pairs: int
    n_active: int
    n_active_lines: int
    iterations: int
    lcp_method: str
    solve_s: float
    pressure_pa: np.ndarray = field(repr=False, compare=False)   # (n_phi, n_x) map on the support bore
    phi_grid: np.ndarray = field(repr=False, compare=False)
    x_grid: np.ndarray = field(repr=False, compare=False)


def _extent(x_grid: np.ndarray, active_x: np.ndarray, half: float,
            line_pressure: np.ndarray | None = None) -> tuple[float, float]:
    """Axial extent of an active node set on the x line.

    Each open end of the set is placed by extrapolating the square of the pressure along the
    line (``line_pressure``, the pressure on the loaded generatrix) linearly to zero from the last
    two active nodes (pressure ~ sqrt(distance) at the edge of a contact), kept between the last
    active node and its open neighbour; without a usable pressure the end is the mid-point
    between them. An end at a ring edge stays at the edge.
    """
    ix = np.flatnonzero(active_x)
    if ix.size == 0:
        return 0.0, 0.0
    lo, hi = ix.min(), ix.max()

    def end(last: int, inner: int, outer: int) -> float:
        mid = 0.5 * (x_grid[last] + x_grid[outer])
        if line_pressure is None or not (0 <= inner < len(x_grid)):
            return mid
        p2, p1 = line_pressure[last] ** 2, line_pressure[inner] ** 2
        if not (p2 > 0 and p1 > p2):
            return mid
        xe = x_grid[last] + (x_grid[last] - x_grid[inner]) * p2 / (p1 - p2)
        a, b = sorted((x_grid[last], x_grid[outer]))
        return float(min(max(xe, a), b))

    x_lo = -half if lo == 0 else end(lo, lo + 1, lo - 1)
    x_hi = half if hi == len(x_grid) - 1 else end(hi, hi - 1, hi + 1)
    return float(x_lo), float(x_hi)


def _active_set_solve(comp: ContactCompliance, gap_m: np.ndarray, b: np.ndarray, margin_m: float,
                      motion: RigidMotion) -> tuple[np.ndarray, np.ndarray, int, str]:
    """LCP on candidate multipliers (normalised rigid gap below ``margin_m``), enlarged until every
    other multiplier stays open. Returns (lam in Pa, weighted gap in m^3, iterations, method)."""
    geom = comp.geom
    cand = gap_m < margin_m
    lam_all = np.zeros(len(b))
    iters_total, method = 0, "none"
    for _ in range(5):
        idx = np.flatnonzero(cand)
        if idx.size == 0:
            break
        lam, iters, method = solve_lcp(comp.A[np.ix_(idx, idx)], b[idx])
        iters_total += iters
        lam_all[:] = 0.0
        lam_all[idx] = lam
        g_all = b + comp.A[:, idx] @ lam
        viol = (~cand) & (g_all < -1e-9 * geom.clearance_m * comp.weights_m2)
        if not viol.any():
            break
        cand |= viol
    else:
        raise ConvergenceError("contact candidate set kept growing after 5 enlargements (penetration "
                               f"{(motion.translation_m - geom.clearance_m) * 1e3:g} mm, tilt {motion.tilt_rad:g} rad)")
    g_all = b + comp.A @ lam_all if lam_all.any() else b
    return lam_all, g_all, iters_total, method


def solve_point(comp: ContactCompliance, motion: RigidMotion, *, candidate_margin_m: float | None = None
                ) -> PointResult3D:
    """Solve one load point on a ready compliance (see module docstring and :mod:`fem_reference.solid.mortar`).

    Raises
    ------
    ConvergenceError
        If the candidate set keeps growing or complementarity fails after the solve.
    """
    t0 = time.perf_counter()
    geom = comp.geom
    mp, mx = comp.mortar_phi, comp.mortar_x
    rs = geom.support_inner_radius_m
    b = weighted_gap(rigid_gap_m(geom, motion, mp.points[:, None], mx.points[None, :]), mp, mx, rs)
    margin = geom.clearance_m * 0.2 if candidate_margin_m is None else candidate_margin_m
    lam_all, g_all, iters_total, method = _active_set_solve(comp, b / comp.weights_m2, b, margin, motion)
    gtol = 1e-7 * geom.clearance_m
    if (lam_all.min(initial=0.0) < -1e-9 * max(lam_all.max(initial=0.0), 1.0)
            or (g_all / comp.weights_m2).min(initial=0.0) < -gtol):
        raise ConvergenceError(f"contact complementarity not met: min pressure {lam_all.min():g} Pa, min weighted "
                               f"gap {(g_all / comp.weights_m2).min():g} m (tolerance {gtol:g} m)")
    nphi, nx = len(mp.vertices), len(mx.vertices)
    fy_bearing = -2.0 * float(lam_all @ comp.force_weights_m2)
    mz = -2.0 * float(lam_all @ comp.moment_weights_m3)
    pressure = lam_all.reshape(nphi, nx)
    active = pressure > 1e-12 * max(pressure.max(initial=0.0), 1e-300)
    plus = np.cos(mp.vertices) > 0
    act_plus = (active & plus[:, None]).any(axis=0)
    act_minus = (active & ~plus[:, None]).any(axis=0)
    half = 0.5 * geom.width_m
    x_lo, x_hi = _extent(mx.vertices, act_plus, half, pressure[0])
    sides = ("both" if act_plus.any() and act_minus.any() else
             "+y" if act_plus.any() else "-y" if act_minus.any() else "none")
    any_x = act_plus | act_minus
    edges = ("both" if any_x[0] and any_x[-1] else "+x" if any_x[-1] else "-x" if any_x[0] else "none")
    phi_act = np.broadcast_to(mp.vertices[:, None], active.shape)[active & plus[:, None]]
    minus = comp.force_weights_m2 < 0
    f_minus = -2.0 * float(lam_all[minus] @ comp.force_weights_m2[minus]) + 0.0     # no -0.0
    return PointResult3D(
        penetration_m=motion.translation_m - geom.clearance_m, tilt_rad=motion.tilt_rad, level=comp.level.name,
        force_n=-fy_bearing, moment_z_nm=mz,
        contact_x_min_m=x_lo, contact_x_max_m=x_hi, contact_width_m=x_hi - x_lo,
        contact_width_law_m=law_contact_width_m(geom, motion),
        load_centre_x_m=(mz / fy_bearing) if fy_bearing != 0 else 0.0,
        contact_half_angle_rad=float(phi_act.max()) if phi_act.size else 0.0,
        edges_loaded=edges, sides=sides, force_minus_y_side_n=f_minus,
        peak_pressure_pa=float(pressure.max(initial=0.0)), n_dofs=comp.n_dofs, n_pairs=len(b),
        n_active=int(active.sum()), n_active_lines=int(act_plus.sum()), iterations=iters_total, lcp_method=method,
        solve_s=time.perf_counter() - t0, pressure_pa=pressure, phi_grid=mp.vertices, x_grid=mx.vertices)
