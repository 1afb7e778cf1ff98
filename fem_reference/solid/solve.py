"""3D linear elasticity of the two rings and frictionless contact through the clearance.

Method (and why)
----------------
Each ring is assembled separately with scikit-fem (hexahedra, order 1 or 2, explicit
``intorder``; docs/reference/fem-notes.md: the default Hex2 rule is needlessly heavy). The bearing's inner
surface moves rigidly (translation r along y, tilt theta about z); an infinitesimal rigid motion
is strain-free, so the displacement is ``u_b = u_rigid + w`` with ``w = 0`` on the driven surface,
and the support's outer surface is clamped (scene ``clamped``). Both elastic problems therefore
have homogeneous Dirichlet data that do not depend on the load point: the stiffness matrices
are factorised **once per mesh** (SuperLU) and the contact compliance (Delassus) matrix

    G = B_b K_b^-1 B_b^T + B_s K_s^-1 B_s^T

of the radial node-to-node pairs on the two contact surfaces is formed once per mesh. (B picks
the radial displacement of a contact node; the meshes pair nodes exactly, see
:mod:`fem_reference.solid.mesh`.)
A load point (r, theta) then only changes the rigid gap ``g0`` (computed from the true tilted
cylinders, :func:`fem_reference.solid.geometry.rigid_gap_m`) and the contact problem is the
linear complementarity problem

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

import math
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.optimize as sopt
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, ElementHex1, ElementHex2, ElementVector, asm
from skfem.models.elasticity import lame_parameters, linear_elasticity

from contact.errors import ConvergenceError, InputError
from fem_reference.solid.geometry import RigidMotion, RingPair3D, edge_penetrations_m, law_contact_width_m, rigid_gap_m
from fem_reference.solid.mesh import MeshLevel3D, RingMesh, build_meshes

SCENES = {
    "clamped": "support outer surface clamped (all displacement components zero); bearing inner surface "
               "moved rigidly (translation r along y + tilt theta about z); symmetry u_z = 0 on z = 0; "
               "ring end faces free; frictionless contact",
    "clamped-axially-fixed-ends": "as 'clamped' but u_x = 0 on both end faces of both rings: at zero tilt "
               "this is exactly the 2D plane-strain 'clamped' scene (verification scene)",
}


@dataclass
class RingOperator:
    """Factorised stiffness of one ring and its contact-surface selection (internal)."""

    n_dofs: int
    contact_phi: np.ndarray        # (n_c,) polar angle of each contact DOF node (rad)
    contact_x: np.ndarray          # (n_c,) axial position (m)
    compliance: np.ndarray         # (n_c, n_c) B K^-1 B^T (m/N)
    factor_s: float
    solve_s: float


@dataclass
class ContactCompliance:
    """Everything a load point needs from one mesh: the pair grid and the compliance G.

    Attributes
    ----------
    scene : str
        Key of :data:`SCENES`.
    level : MeshLevel3D
    geom : RingPair3D
    phi_grid, x_grid : ndarray
        Sorted distinct polar angles (rad) and axial positions (m) of the contact nodes.
    phi, x : ndarray
        (n_c,) coordinates of the node pairs, ordered phi-major (index = i_phi * n_x + i_x).
    area_m2 : ndarray
        (n_c,) tributary area of each pair on the support bore (half model), for pressures.
    G : ndarray
        (n_c, n_c) compliance (m/N), symmetric positive definite.
    n_dofs : int
        Total DOFs of both rings (before Dirichlet condensation).
    build_s : float
        Wall time to mesh, assemble, factorise and form G (s).
    """

    scene: str
    level: MeshLevel3D
    geom: RingPair3D
    phi_grid: np.ndarray
    x_grid: np.ndarray
    phi: np.ndarray
    x: np.ndarray
    area_m2: np.ndarray
    G: np.ndarray
    n_dofs: int
    build_s: float
    timings: dict = field(default_factory=dict)


def _element(order: int):
    return ElementVector(ElementHex1() if order == 1 else ElementHex2())


def _intorder(order: int) -> int:
    # Gauss rule exact for the tensor-product stiffness integrand on an affine hex:
    # degree 2*order per direction -> order+1 points per direction.
    return 2 * order


def _line_weights(nodes: np.ndarray, order: int) -> np.ndarray:
    """Tributary lengths of the DOF points of a 1D line mesh (trapezoid for order 1,
    Simpson per element for order 2). ``nodes`` are the element vertices."""
    h = np.diff(nodes)
    if order == 1:
        w = np.zeros(len(nodes))
        w[:-1] += h / 2
        w[1:] += h / 2
        return w
    w = np.zeros(2 * len(nodes) - 1)
    w[0:-1:2] += h / 6
    w[1::2] += 4 * h / 6
    w[2::2] += h / 6
    return w


def _dof_points(nodes: np.ndarray, order: int) -> np.ndarray:
    if order == 1:
        return np.asarray(nodes, dtype=float)
    mids = 0.5 * (nodes[:-1] + nodes[1:])
    out = np.empty(2 * len(nodes) - 1)
    out[0::2] = nodes
    out[1::2] = mids
    return out


def _facets_where(mesh, vertex_ok: np.ndarray) -> np.ndarray:
    """Facets whose every vertex satisfies the predicate ``vertex_ok`` (bool per mesh vertex).

    Facet mid-points of a faceted cylinder lie inside the circle, so the test is on the
    vertices, which lie on it exactly.
    """
    return np.flatnonzero(np.all(vertex_ok[mesh.facets], axis=0))


def _fixed_dofs(ring: RingMesh, basis: Basis, rtol: float, vr: np.ndarray,
                fix_end_faces_axially: bool) -> np.ndarray:
    """DOFs held at zero: all components on the held surface, u_z on the symmetry plane z = 0
    and, if asked, u_x on both end faces (``vr``: radius of each mesh vertex)."""
    mesh = ring.mesh
    held = _facets_where(mesh, np.abs(vr - ring.held_radius_m) < rtol)
    sym = _facets_where(mesh, np.abs(mesh.p[2]) < rtol)
    fixed = np.union1d(basis.get_dofs(held).all(), basis.get_dofs(sym).all("u^3"))
    if fix_end_faces_axially:
        half = np.max(np.abs(mesh.p[0]))
        ends = _facets_where(mesh, np.abs(np.abs(mesh.p[0]) - half) < rtol)
        fixed = np.union1d(fixed, basis.get_dofs(ends).all("u^1"))
    return fixed


def _contact_dofs(ring: RingMesh, basis: Basis, rtol: float, vr: np.ndarray, phi_grid: np.ndarray,
                  x_grid: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The y- and z-DOFs of the contact surface, paired by location and ordered phi-major like
    ``phi_grid x x_grid``, with the polar angle (in [0, 2 pi)) and axial position of each pair.

    Raises ConvergenceError if the DOF points do not match the grid (mesh pairing broken).
    """
    surf = _facets_where(ring.mesh, np.abs(vr - ring.contact_radius_m) < rtol)
    dview = basis.get_dofs(surf)
    dy = np.sort(dview.all("u^2"))
    dz = np.sort(dview.all("u^3"))
    loc = basis.doflocs
    # pair each y-DOF with the z-DOF at the same location
    def order_of(d):   # phi-major, rounded so that round-off does not break ties
        return np.lexsort((np.round(loc[0, d], 12), np.round(np.arctan2(loc[2, d], loc[1, d]), 10)))

    ky, kz = order_of(dy), order_of(dz)
    dy, dz = dy[ky], dz[kz]
    phi = np.arctan2(loc[2, dy], loc[1, dy])
    phi = np.where(phi < -1e-12, phi + 2 * math.pi, np.maximum(phi, 0.0))
    xs = loc[0, dy]
    n_c = len(phi_grid) * len(x_grid)
    if len(dy) != n_c or len(dz) != n_c:
        raise ConvergenceError(f"contact surface of radius {ring.contact_radius_m:g} m has {len(dy)} DOF points, "
                               f"expected {n_c}: mesh pairing broken")
    want_phi = np.repeat(phi_grid, len(x_grid))
    want_x = np.tile(x_grid, len(phi_grid))
    if (np.max(np.abs(phi - want_phi)) > 1e-9 or np.max(np.abs(xs - want_x)) > 1e-9 * ring.contact_radius_m
            or np.max(np.abs(loc[:, dz] - loc[:, dy])) > 1e-12):
        raise ConvergenceError("contact DOF points do not match the (phi, x) grid: mesh pairing broken")
    return dy, dz, phi, xs


def _radial_selection(dy: np.ndarray, dz: np.ndarray, phi: np.ndarray, n_c: int, n_dofs: int) -> sp.csr_matrix:
    """``B`` (n_c x n_dofs): the outward radial displacement ``u_y cos(phi) + u_z sin(phi)`` of
    each contact pair."""
    rows = np.concatenate([np.arange(n_c), np.arange(n_c)])
    cols = np.concatenate([dy, dz])
    vals = np.concatenate([np.cos(phi), np.sin(phi)])
    return sp.csr_matrix((vals, (rows, cols)), shape=(n_c, n_dofs))


def _factorise(Kff: sp.csc_matrix):
    """Sparse LU of the condensed (SPD) stiffness."""
    # SuperLU with COLAMD ordering and symmetric mode (no pivoting on the SPD matrix). The
    # compliance is dominated by many-right-hand-side solves; side by side on the L2 bearing ring
    # COLAMD was the fastest of COLAMD / MMD(A'+A) / reverse Cuthill-McKee in 3 of 4 interleaved
    # comparisons (MMD has the least fill, but was slower per solve; benchmarks/bench_fem3d.py).
    return spla.splu(Kff, permc_spec="COLAMD", diag_pivot_thresh=0.0, options={"SymmetricMode": True})


def _quadrant_columns(nphi: int, nx: int) -> np.ndarray:
    """Pair indices of the quadrant phi <= pi/2, x >= 0 of the phi-major (nphi, nx) grid."""
    ii, jj = np.meshgrid(np.arange(nphi), np.arange(nx), indexing="ij")
    in_q = (ii <= (nphi - 1) // 2) & (jj >= nx // 2)
    return np.flatnonzero(in_q.ravel())


def _mirror_fill(Gq: np.ndarray, cols: np.ndarray, nphi: int, nx: int) -> np.ndarray:
    """The full (n_c, n_c) compliance from its quadrant columns ``Gq`` (columns ``cols``), by
    the mirror symmetries about y = 0 (phi -> pi - phi) and x = 0."""
    n_c = nphi * nx
    G = np.empty((n_c, n_c))
    pos = -np.ones(n_c, dtype=int)
    pos[cols] = np.arange(len(cols))
    flat = np.arange(n_c).reshape(nphi, nx)
    for perm in (flat, flat[::-1, :], flat[:, ::-1], flat[::-1, ::-1]):
        perm = perm.ravel()              # perm[k] = image of pair k under the mirror
        target = np.flatnonzero(pos[perm] >= 0)
        G[:, target] = Gq[perm][:, pos[perm[target]]]
    return G


def _grid_compliance(lu, Bf: sp.csc_matrix, nphi: int, nx: int, use_mirrors: bool, chunk: int) -> np.ndarray:
    """``Bf K^-1 Bf^T`` (not yet symmetrised) by solves in blocks of ``chunk`` right-hand sides;
    with ``use_mirrors`` only the quadrant columns are solved for."""
    n_c = nphi * nx
    BT = Bf.T.tocsc()
    if use_mirrors:
        # Columns of the quadrant phi <= pi/2, x >= 0 only; the rest follow from the mirror
        # symmetries of rings, supports and mesh about y = 0 (phi -> pi - phi) and x = 0.
        cols = _quadrant_columns(nphi, nx)
    else:
        cols = np.arange(n_c)
    Gq = np.empty((n_c, len(cols)))
    for s in range(0, len(cols), chunk):
        e = min(s + chunk, len(cols))
        X = lu.solve(BT[:, cols[s:e]].toarray())
        Gq[:, s:e] = Bf @ X
    return _mirror_fill(Gq, cols, nphi, nx) if use_mirrors else Gq


def ring_operator(ring: RingMesh, young_pa: float, poisson: float, order: int,
                  phi_grid: np.ndarray, x_grid: np.ndarray, chunk: int = 256,
                  use_mirrors: bool = True, fix_end_faces_axially: bool = False) -> RingOperator:
    """Assemble, condense and factorise one ring; form ``B K^-1 B^T`` on the contact grid.

    The held surface (radius ``ring.held_radius_m``) is fixed (w = 0); the symmetry plane z = 0
    (phi = 0 and phi = pi) has u_z = 0. ``B`` maps displacements to the outward radial
    displacement at each contact DOF point, ordered like ``phi_grid x x_grid`` (phi-major).
    """
    mesh = ring.mesh
    basis = Basis(mesh, _element(order), intorder=_intorder(order))
    lam, mu = lame_parameters(young_pa, poisson)
    K = asm(linear_elasticity(lam, mu), basis).tocsr()
    rtol = 1e-9 * ring.contact_radius_m
    vr = np.hypot(mesh.p[1], mesh.p[2])
    fixed = _fixed_dofs(ring, basis, rtol, vr, fix_end_faces_axially)
    dy, dz, phi, xs = _contact_dofs(ring, basis, rtol, vr, phi_grid, x_grid)
    if use_mirrors and (np.max(np.abs(phi_grid + phi_grid[::-1] - math.pi)) > 1e-12
                        or np.max(np.abs(x_grid + x_grid[::-1])) > 1e-12 * ring.contact_radius_m):
        raise InputError("use_mirrors needs a contact grid symmetric about phi = pi/2 and x = 0")
    B = _radial_selection(dy, dz, phi, len(phi_grid) * len(x_grid), basis.N)
    free = np.setdiff1d(np.arange(basis.N), fixed)
    Kff = K[free][:, free].tocsc()
    Bf = B[:, free].tocsc()
    t0 = time.perf_counter()
    lu = _factorise(Kff)
    t1 = time.perf_counter()
    G = _grid_compliance(lu, Bf, len(phi_grid), len(x_grid), use_mirrors, chunk)
    t2 = time.perf_counter()
    G = 0.5 * (G + G.T)
    return RingOperator(basis.N, phi, xs, G, t1 - t0, t2 - t1)


def build_compliance(geom: RingPair3D, level: MeshLevel3D, scene: str = "clamped") -> ContactCompliance:
    """Mesh, assemble and factorise both rings of ``level`` and form the contact compliance.

    ``scene`` is a key of :data:`SCENES`.
    """
    if scene not in SCENES:
        raise InputError(f"scene = {scene!r}: must be one of {sorted(SCENES)}")
    fix_ends = scene == "clamped-axially-fixed-ends"
    t0 = time.perf_counter()
    bearing, support = build_meshes(geom, level)
    phi_grid = _dof_points(bearing.phi_nodes, level.order)
    x_grid = _dof_points(bearing.x_nodes, level.order)
    ob = ring_operator(bearing, geom.young_bearing_pa, geom.poisson_bearing, level.order, phi_grid, x_grid,
                       fix_end_faces_axially=fix_ends)
    os_ = ring_operator(support, geom.young_support_pa, geom.poisson_support, level.order, phi_grid, x_grid,
                        fix_end_faces_axially=fix_ends)
    G = ob.compliance + os_.compliance
    wphi = _line_weights(bearing.phi_nodes, level.order) * geom.support_inner_radius_m
    wx = _line_weights(bearing.x_nodes, level.order)
    area = np.outer(wphi, wx).ravel()
    build = time.perf_counter() - t0
    return ContactCompliance(scene, level, geom, phi_grid, x_grid, np.repeat(phi_grid, len(x_grid)),
                             np.tile(x_grid, len(phi_grid)), area, G, int(ob.n_dofs + os_.n_dofs), build,
                             {"factor_s": ob.factor_s + os_.factor_s, "compliance_s": ob.solve_s + os_.solve_s})


def save_compliance(comp: ContactCompliance, path) -> None:
    """Write a compliance to ``path`` (.npz, written atomically) for reuse by other processes."""
    import io
    import json

    from contact.files import atomic_write_bytes
    buf = io.BytesIO()
    meta = {"scene": comp.scene, "level": comp.level.as_dict(), "geom": comp.geom.as_dict(),
            "n_dofs": int(comp.n_dofs), "build_s": float(comp.build_s),
            "timings": {k: float(v) for k, v in comp.timings.items()}}
    np.savez(buf, meta=np.array(json.dumps(meta)), phi_grid=comp.phi_grid, x_grid=comp.x_grid,
             area_m2=comp.area_m2, G=comp.G)
    atomic_write_bytes(path, buf.getvalue())


def load_compliance(path) -> ContactCompliance:
    """Read a compliance written by :func:`save_compliance` (DatasetError if unreadable)."""
    import json
    import zipfile

    from contact.errors import DatasetError
    try:
        with np.load(path) as z:
            meta = json.loads(str(z["meta"]))
            phi_grid, x_grid, area, G = z["phi_grid"], z["x_grid"], z["area_m2"], z["G"]
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as exc:   # BadZipFile: a CRC mismatch
        raise DatasetError(f"{path}: cannot read cached 3D compliance ({exc})") from exc
    return ContactCompliance(meta["scene"], MeshLevel3D(**meta["level"]), RingPair3D(**meta["geom"]), phi_grid,
                             x_grid, np.repeat(phi_grid, len(x_grid)), np.tile(x_grid, len(phi_grid)), area, G,
                             int(meta["n_dofs"]), float(meta["build_s"]), meta["timings"])


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


def solve_point(comp: ContactCompliance, motion: RigidMotion, *, candidate_margin_m: float | None = None
                ) -> PointResult3D:
    """Solve one load point on a ready compliance (see module docstring).

    Raises
    ------
    ConvergenceError
        If the active set reaches the edge of the modelled contact surface in a way the half
        model cannot represent, or complementarity fails after the solve.
    """
    t0 = time.perf_counter()
    geom = comp.geom
    g0_all = rigid_gap_m(geom, motion, comp.phi, comp.x)
    margin = geom.clearance_m * 0.2 if candidate_margin_m is None else candidate_margin_m
    cand = g0_all < margin
    lam_all = np.zeros(len(g0_all))
    iters_total = 0
    method = "none"
    for _ in range(5):
        idx = np.flatnonzero(cand)
        if idx.size == 0:
            break
        lam, iters, method = solve_lcp(comp.G[np.ix_(idx, idx)], g0_all[idx])
        iters_total += iters
        lam_all[:] = 0.0
        lam_all[idx] = lam
        g_all = g0_all + comp.G[:, idx] @ lam
        viol = (~cand) & (g_all < -1e-9 * geom.clearance_m)
        if not viol.any():
            break
        cand |= viol
    else:
        raise ConvergenceError("contact candidate set kept growing after 5 enlargements (penetration "
                               f"{(motion.translation_m - geom.clearance_m) * 1e3:g} mm, tilt {motion.tilt_rad:g} rad)")
    g_all = g0_all + comp.G @ lam_all if lam_all.any() else g0_all
    gtol = 1e-7 * geom.clearance_m
    if lam_all.min(initial=0.0) < -1e-9 * max(lam_all.max(initial=0.0), 1.0) or g_all.min(initial=0.0) < -gtol:
        raise ConvergenceError(f"contact complementarity not met: min force {lam_all.min():g} N, min gap "
                               f"{g_all.min():g} m (tolerance {gtol:g} m)")
    nphi, nx = len(comp.phi_grid), len(comp.x_grid)
    active = lam_all > 1e-12 * max(lam_all.max(initial=0.0), 1e-300)
    cosp = np.cos(comp.phi)
    fy_bearing = -2.0 * float(np.sum(lam_all * cosp))
    mz = 2.0 * float(np.sum(comp.x * (-lam_all * cosp)))
    plus = cosp > 0
    act_plus = (active & plus).reshape(nphi, nx).any(axis=0)
    act_minus = (active & ~plus).reshape(nphi, nx).any(axis=0)
    half = 0.5 * geom.width_m
    press_phi0 = (lam_all / comp.area_m2).reshape(nphi, nx)[0]     # loaded generatrix phi = 0
    x_lo, x_hi = _extent(comp.x_grid, act_plus, half, press_phi0)
    sides = ("both" if act_plus.any() and act_minus.any() else
             "+y" if act_plus.any() else "-y" if act_minus.any() else "none")
    any_x = act_plus | act_minus
    edges = ("both" if any_x[0] and any_x[-1] else "+x" if any_x[-1] else "-x" if any_x[0] else "none")
    pressure = (lam_all / comp.area_m2).reshape(nphi, nx)
    phi_act = comp.phi[active & plus]
    f_minus = 2.0 * float(np.sum(lam_all[~plus] * -cosp[~plus]))
    return PointResult3D(
        penetration_m=motion.translation_m - geom.clearance_m, tilt_rad=motion.tilt_rad, level=comp.level.name,
        force_n=-fy_bearing, moment_z_nm=mz,
        contact_x_min_m=x_lo, contact_x_max_m=x_hi, contact_width_m=x_hi - x_lo,
        contact_width_law_m=law_contact_width_m(geom, motion),
        load_centre_x_m=(mz / fy_bearing) if fy_bearing != 0 else 0.0,
        contact_half_angle_rad=float(phi_act.max()) if phi_act.size else 0.0,
        edges_loaded=edges, sides=sides, force_minus_y_side_n=f_minus,
        peak_pressure_pa=float(pressure.max(initial=0.0)), n_dofs=comp.n_dofs, n_pairs=len(g0_all),
        n_active=int(active.sum()), n_active_lines=int(act_plus.sum()), iterations=iters_total, lcp_method=method,
        solve_s=time.perf_counter() - t0, pressure_pa=pressure, phi_grid=comp.phi_grid, x_grid=comp.x_grid)
