"""Contact compliance of the two rings of one mesh level, from one generatrix of loads.

Method (and why)
----------------
Each full ring is assembled with isoparametric hexahedra (:mod:`fem_reference.solid.elasticity`,
:mod:`fem_reference.solid.mesh`). The bearing's inner surface moves rigidly (translation r
along y, tilt theta about z); an infinitesimal rigid motion is strain-free, so the bearing
displacement is ``u_rigid + w`` with ``w = 0`` on the driven surface, and the support's outer
surface is clamped (scene ``clamped``). Both elastic problems therefore have homogeneous
Dirichlet data that do not depend on the load point: each stiffness is factorised once per mesh
(SuperLU, MMD on A'+A: measured about 10x less fill and factor time than COLAMD on these rings)
and the contact compliance

    C = B_b K_b^-1 B_b^T + B_s K_s^-1 B_s^T

of radial node-to-node pairs on the two contact surfaces is formed once per mesh (B picks the
outward radial displacement of a contact node).

Rotation invariance: with uniform steps in phi a ring is mapped onto itself by a rotation of one
element, so ``C`` between nodes at angle indices ``k_i`` and ``k_j`` depends on ``k_i - k_j``,
the node type ``t = k_j mod order`` (vertex or mid-element angle) and the axial positions only:
``C[(k_i, x_i), (k_j, x_j)] = g_t[k_i - k_j + t, x_i, x_j]``. The kernel ``g`` comes from
``order * n_x`` unit loads on the generatrices phi = 0 (and phi = half an element), half of them
by the mirror symmetry about x = 0, instead of one load per contact node.

Half model: the contact forces are symmetric about the plane z = 0 that holds the load direction
and the axis. A half-model pair at angle index ``k_j`` in [0, pi] stands for the full-ring
forces at ``+-phi_j`` (one force if it lies on the plane, then the half model carries half of
it), so the half-model compliance is ``G[i, j] = C[i, j] + C[i, -j]``.

Contact with quadratic faces: the pairs are all nodes of the 9-node (27-node element) faces; a
nodal contact force is the integral of the pressure against that node's shape function, whose
face integrals (Simpson weights 1/6, 4/6, 1/6 per direction) are all positive, so node-to-node
complementarity on forces is consistent. (The 20-node serendipity face has negative corner
integrals, -1/12 of the face: a uniform pressure would need negative corner forces, which a
node-wise ``lam >= 0`` cannot represent; that element is not used.)
"""
from __future__ import annotations

import io
import json
import math
import time
import zipfile
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse.linalg as spla

from contact.errors import ConvergenceError, DatasetError, InputError
from fem_reference.solid.geometry import RingPair3D
from fem_reference.solid.mesh import MeshLevel3D, RingMesh, build_meshes
from fem_reference.solid.mortar import Mortar1D, angular_integrals, condensed, mortar_1d

SCENES = {
    "clamped": "support outer surface clamped (all displacement components zero); bearing inner surface "
               "moved rigidly (translation r along y + tilt theta about z); ring end faces free; "
               "frictionless contact; half model about z = 0 (contact forces symmetric about the load plane)",
    "clamped-axially-fixed-ends": "as 'clamped' but u_x = 0 on both end faces of both rings: at zero tilt "
               "this is exactly the 2D plane-strain 'clamped' scene (verification scene)",
    "clamped-axially-free-outer": "as 'clamped' but the support outer surface is held radially and "
               "circumferentially only, free to slide along the axis (a housing bore that can slip axially)",
    "clamped-axially-free-inner": "as 'clamped' but the bearing inner surface is moved rigidly in its plane "
               "only, free to slide along the axis (a non-locating ring on its rolling elements)",
    "clamped-axially-free": "both held surfaces free to slide along the axis ('clamped-axially-free-outer' "
               "and '-inner' together)",
}

#: per scene: (end faces held axially, (bearing inner surface held axially, support outer surface held axially))
SCENE_HOLDS = {
    "clamped": (False, (True, True)),
    "clamped-axially-fixed-ends": (True, (True, True)),
    "clamped-axially-free-outer": (False, (True, False)),
    "clamped-axially-free-inner": (False, (False, True)),
    "clamped-axially-free": (False, (False, False)),
}


@dataclass
class ContactCompliance:
    """Everything a load point needs from one mesh level: the multiplier grid and operator A.

    Attributes
    ----------
    scene : str
        Key of :data:`SCENES`.
    level : MeshLevel3D
    geom : RingPair3D
    mortar_phi, mortar_x : Mortar1D
        The two directions of the pressure multipliers (:mod:`fem_reference.solid.mortar`): hats
        on the angles in [0, pi] (rad) and on the axial element corners (m).
    lam_phi, lam_x : ndarray
        (n_lam,) coordinates of the multipliers, phi-major.
    weights_m2 : ndarray
        (n_lam,) ``int M_j dA`` on the support bore (half model) (m^2).
    force_weights_m2, moment_weights_m3 : ndarray
        (n_lam,) ``int M_j cos(phi) dA`` and ``int M_j x cos(phi) dA`` (half model): the load is
        ``2 lam . force_weights`` and the moment ``M_z = -2 lam . moment_weights``.
    kernel : ndarray
        The level's compliance kernel: hex, ``g[t, k, i, j]`` (m/N, :func:`ring_kernel`); fourier,
        ``X[n, e, d]`` (:func:`fem_reference.solid.harmonic.harmonic_compliance`).
    A : ndarray
        (n_lam, n_lam) condensed mortar compliance (m^5/N), symmetric positive definite.
    n_dofs : int
        DOFs of both rings (hex: full 3D rings; fourier: section DOFs times harmonics).
    build_s : float
        Wall time of the level build: mesh, assembly, factorisations, kernel, A (s).
    timings : dict
        Parts of the build (s).
    load_s : float
        Wall time this process spent obtaining the level: the build, or reading it from the cache (s).
    """

    scene: str
    level: MeshLevel3D
    geom: RingPair3D
    mortar_phi: Mortar1D
    mortar_x: Mortar1D
    lam_phi: np.ndarray
    lam_x: np.ndarray
    weights_m2: np.ndarray
    force_weights_m2: np.ndarray
    moment_weights_m3: np.ndarray
    kernel: np.ndarray
    A: np.ndarray
    n_dofs: int
    build_s: float
    timings: dict = field(default_factory=dict)
    load_s: float = 0.0


def dof_points(nodes: np.ndarray, order: int) -> np.ndarray:
    """DOF positions on a 1D line of element vertices (mid-points added for order 2)."""
    if order == 1:
        return np.asarray(nodes, dtype=float)
    out = np.empty(2 * len(nodes) - 1)
    out[0::2] = nodes
    out[1::2] = 0.5 * (nodes[:-1] + nodes[1:])
    return out


def _factorise(Kff):
    """Sparse LU of the condensed (SPD) stiffness, no pivoting (symmetric mode)."""
    return spla.splu(Kff, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})


def _surface_nodes(ring: RingMesh, loc: np.ndarray, x_grid: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Scalar DOFs of the contact surface, their angle index (0 .. order*n_phi_full - 1) and x index."""
    r = np.hypot(loc[1], loc[2])
    nodes = np.flatnonzero(np.abs(r - ring.contact_radius_m) < 1e-9 * ring.contact_radius_m)
    m = ring.order * ring.n_phi_full
    step = 2.0 * math.pi / m
    kf = np.mod(np.arctan2(loc[2, nodes], loc[1, nodes]), 2.0 * math.pi) / step
    k = np.round(kf).astype(int) % m
    ix = np.searchsorted(x_grid, loc[0, nodes] - 1e-9 * ring.contact_radius_m)
    ok = (np.abs(kf - np.round(kf)) < 1e-6) & (ix < len(x_grid))
    ok[ok] &= np.abs(x_grid[ix[ok]] - loc[0, nodes[ok]]) < 1e-9 * ring.contact_radius_m
    if not ok.all() or len(nodes) != m * len(x_grid):
        raise ConvergenceError(f"contact surface of radius {ring.contact_radius_m:g} m: {len(nodes)} nodes, "
                               f"expected {m * len(x_grid)} on the (phi, x) grid: mesh pairing broken")
    return nodes, k, ix


def ring_kernel(ring: RingMesh, young_pa: float, poisson: float, x_grid: np.ndarray,
                fix_end_faces_axially: bool = False) -> tuple[np.ndarray, int, dict]:
    """Rotation-invariant compliance kernel ``g[t, k, i_x, j_x]`` of one full ring (m/N).

    ``g[t, k, i, j]`` is the outward radial displacement of the contact node at angle index ``k``
    and axial index ``i`` under a unit outward radial force on the node at angle index ``t``
    (0: a vertex angle, 1: a mid-element angle) and axial index ``j``. The held surface is fixed
    (all components); with ``fix_end_faces_axially`` also u_x on both end faces.

    Returns ``(g, n_dofs, timings)``.
    """
    from skfem import Basis, ElementHex1, ElementHex2
    t0 = time.perf_counter()
    basis = Basis(ring.mesh, ElementHex1() if ring.order == 1 else ElementHex2(), intorder=2 * ring.order)
    from fem_reference.solid.elasticity import stiffness
    K = stiffness(basis, young_pa, poisson)
    loc = basis.doflocs
    tol = 1e-9 * ring.contact_radius_m
    held = np.flatnonzero(np.abs(np.hypot(loc[1], loc[2]) - ring.held_radius_m) < tol)
    fixed = [3 * held, 3 * held + 1, 3 * held + 2]
    if fix_end_faces_axially:
        fixed.append(3 * np.flatnonzero(np.abs(np.abs(loc[0]) - np.max(np.abs(loc[0]))) < tol))
    free = np.setdiff1d(np.arange(3 * basis.N), np.concatenate(fixed))
    Kff = K[free][:, free].tocsc()
    t1 = time.perf_counter()
    lu = _factorise(Kff)
    t2 = time.perf_counter()
    nodes, k, ix = _surface_nodes(ring, loc, x_grid)
    m, nxg, order = ring.order * ring.n_phi_full, len(x_grid), ring.order
    pos = -np.ones(3 * basis.N, dtype=int)
    pos[free] = np.arange(len(free))
    ang = k * 2.0 * math.pi / m
    cols = [(t, j) for t in range(order) for j in range(nxg // 2, nxg)]     # x >= 0; the rest by mirror
    R = np.zeros((len(free), len(cols)))
    node_at = {(int(kk), int(ii)): int(n) for n, kk, ii in zip(nodes, k, ix)}
    for c, (t, j) in enumerate(cols):
        n = node_at[(t, j)]
        a_t = t * 2.0 * math.pi / m
        R[pos[3 * n + 1], c], R[pos[3 * n + 2], c] = math.cos(a_t), math.sin(a_t)
    X = lu.solve(R)
    ur = np.cos(ang)[:, None] * X[pos[3 * nodes + 1]] + np.sin(ang)[:, None] * X[pos[3 * nodes + 2]]
    g = np.empty((order, m, nxg, nxg))
    for c, (t, j) in enumerate(cols):
        g[t, k, ix, j] = ur[:, c]
        g[t, k, nxg - 1 - ix, nxg - 1 - j] = ur[:, c]     # mirror about x = 0
    t3 = time.perf_counter()
    return g, 3 * basis.N, {"assembly_s": t1 - t0, "factor_s": t2 - t1, "kernel_s": t3 - t2}


def half_model_compliance(kernel: np.ndarray) -> np.ndarray:
    """``G[i, j] = C[i, j] + C[i, -j]`` on the half model's pairs (phi in [0, pi], phi-major), symmetrised."""
    order, m, nxg, _ = kernel.shape
    kk = np.arange(m // 2 + 1)
    t = kk % order
    a = kernel[t[None, :], (kk[:, None] - kk[None, :] + t[None, :]) % m]        # (k_i, k_j, i_x, j_x)
    a += kernel[t[None, :], (kk[:, None] + kk[None, :] + t[None, :]) % m]
    n_c = len(kk) * nxg
    G = np.ascontiguousarray(a.transpose(0, 2, 1, 3)).reshape(n_c, n_c)
    return 0.5 * (G + G.T)


def _assemble(scene, level, geom, x_vertices, kernel, n_dofs, build_s, timings, A=None) -> ContactCompliance:
    """The compliance record of a level from its kernel (hex: ``A`` formed here unless given)."""
    if abs(x_vertices[-1] - 0.5 * geom.width_m) > 1e-12 or len(x_vertices) != level.n_axial + 1:
        raise InputError("cached level: the axial grid does not match the ring width or the level")
    mphi = mortar_1d(np.linspace(0.0, math.pi, level.n_phi + 1), level.order)
    mx = mortar_1d(x_vertices, level.order)
    rs = geom.support_inner_radius_m
    if A is None:
        A = condensed(half_model_compliance(kernel), mphi, mx, rs)
    j1 = angular_integrals(mphi.vertices, 1)[:, 1]
    weights = rs * np.outer(mphi.weights, mx.weights).ravel()
    fw = rs * np.outer(j1, mx.weights).ravel()
    mw = rs * np.outer(j1, mx.W @ mx.points).ravel()
    return ContactCompliance(scene, level, geom, mphi, mx, np.repeat(mphi.vertices, len(mx.vertices)),
                             np.tile(mx.vertices, len(mphi.vertices)), weights, fw, mw, kernel, A, int(n_dofs),
                             float(build_s), timings)


def build_compliance(geom: RingPair3D, level: MeshLevel3D, scene: str = "clamped") -> ContactCompliance:
    """Build one level (``level.method``: "fourier" harmonics or "hex" hexahedra) and its operator A."""
    if scene not in SCENES:
        raise InputError(f"scene = {scene!r}: must be one of {sorted(SCENES)}")
    fix_ends, held_axially = SCENE_HOLDS[scene]
    t0 = time.perf_counter()
    if level.method == "fourier":
        from fem_reference.solid.fourier import build_fourier
        x_nodes, X, A, n_dofs, timings = build_fourier(geom, level, fix_ends, held_axially)
        comp = _assemble(scene, level, geom, x_nodes, X, n_dofs, time.perf_counter() - t0, timings, A)
        comp.load_s = comp.build_s
        return comp
    if not all(held_axially):
        raise InputError(f"scene = {scene!r}: the hexahedral levels model surfaces held in all directions only "
                         "(use the harmonic levels Q*/E*)")
    bearing, support = build_meshes(geom, level)
    x_grid = dof_points(bearing.x_nodes, level.order)
    gb, nb, tb = ring_kernel(bearing, geom.young_bearing_pa, geom.poisson_bearing, x_grid, fix_ends)
    gs, ns, ts = ring_kernel(support, geom.young_support_pa, geom.poisson_support, x_grid, fix_ends)
    timings = {k: tb[k] + ts[k] for k in tb}
    comp = _assemble(scene, level, geom, bearing.x_nodes, gb + gs, nb + ns, time.perf_counter() - t0, timings)
    comp.load_s = comp.build_s
    return comp


def save_compliance(comp: ContactCompliance, path) -> None:
    """Write a level's kernel and condensed operator ``A`` to ``path`` (.npz, written atomically)."""
    from contact.files import atomic_write_bytes
    buf = io.BytesIO()
    meta = {"scene": comp.scene, "level": comp.level.as_dict(), "geom": comp.geom.as_dict(),
            "n_dofs": int(comp.n_dofs), "build_s": float(comp.build_s),
            "timings": {k: float(v) for k, v in comp.timings.items()}}
    np.savez(buf, meta=np.array(json.dumps(meta)), x_vertices=comp.mortar_x.vertices, kernel=comp.kernel, A=comp.A)
    atomic_write_bytes(path, buf.getvalue())


def load_compliance(path) -> ContactCompliance:
    """Read a level written by :func:`save_compliance` (DatasetError if unreadable)."""
    t0 = time.perf_counter()
    try:
        with np.load(path) as z:
            meta = json.loads(str(z["meta"]))
            x_grid, kernel, A = z["x_vertices"], z["kernel"], z["A"]
        level, geom = MeshLevel3D(**meta["level"]), RingPair3D(**meta["geom"])
    except (OSError, ValueError, KeyError, TypeError, EOFError, zipfile.BadZipFile) as exc:
        raise DatasetError(f"{path}: cannot read cached 3D compliance ({exc})") from exc
    comp = _assemble(meta["scene"], level, geom, x_grid, kernel, meta["n_dofs"], meta["build_s"], meta["timings"], A)
    comp.load_s = time.perf_counter() - t0
    return comp
