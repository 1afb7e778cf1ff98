"""Circumferential harmonics of an elastic ring: one 2D quadratic problem per Fourier order.

The rings are bodies of revolution about x, so a radial load ``f(x) cos(n phi)`` on a ring surface
excites only the harmonic ``n`` (Wilson 1965, AIAA J. 3:2269, "semi-analytical" finite elements;
Zienkiewicz & Taylor, The Finite Element Method, vol. 1, ch. on axisymmetric solids under
non-symmetric load):

    u_r = U(x, r) cos(n phi),   u_phi = V(x, r) sin(n phi),   u_x = W(x, r) cos(n phi).

With these, the strains are

    e_rr = U_r,  e_pp = (U + n V)/r,  e_xx = W_x,  g_rx = U_x + W_r            (times cos n phi)
    g_rp = V_r - V/r - n U/r,  g_px = V_x - n W/r                             (times sin n phi)

so the stiffness of the harmonic per unit of ``int cos^2`` is ``K_n = K0 + n K1 + n^2 K2`` with three
matrices assembled once on the (x, r) section (27 DOFs per 9-node quadratic quadrilateral). For
n = 0 the sin terms carry no energy and V (torsion) decouples; it is held at zero. The section is
meshed with scikit-fem ``MeshQuad2`` (graded toward the ring edges and the contact surface); the
factorisation of each ``K_n`` is small (a few thousand DOFs).

Output: for unit radial tractions ``M_d(x) cos(n phi)`` on the contact surface (``M_d`` the axial
multiplier hats, :mod:`fem_reference.solid.mortar`), the axial compliance matrix
``X_n[e, d] = int M_e u_r dx`` (m/(N/m^2) per unit radius, see :func:`harmonic_compliance`).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, ElementQuad2, MeshQuad, MeshQuad2

from fem_reference.solid.elasticity import lame


def section_basis(x_nodes: np.ndarray, r_nodes: np.ndarray) -> Basis:
    """Quadratic basis on the (x, r) section: coordinates ``p[0] = x``, ``p[1] = r`` (m)."""
    m = MeshQuad2.from_mesh(MeshQuad.init_tensor(np.asarray(x_nodes, float), np.asarray(r_nodes, float)))
    return Basis(m, ElementQuad2(), intorder=6)


def _strain_operators(basis: Basis) -> tuple[np.ndarray, np.ndarray]:
    """``B0, B1`` of shape (6, n_local, 3, n_el, n_q): strain = (B0 + n B1) . (U, V, W) nodal values.

    Strain order: e_rr, e_pp, e_xx, g_rx (cos group), g_rp, g_px (sin group)."""
    nl = len(basis.basis)
    r = basis.global_coordinates().value[1]
    phi = np.stack([basis.basis[a][0].value for a in range(nl)])        # (nl, ne, nq)
    dx = np.stack([basis.basis[a][0].grad[0] for a in range(nl)])
    dr = np.stack([basis.basis[a][0].grad[1] for a in range(nl)])
    B0 = np.zeros((6, nl, 3) + phi.shape[1:])
    B1 = np.zeros_like(B0)
    U, V, W = 0, 1, 2
    B0[0, :, U] = dr
    B0[1, :, U] = phi / r
    B1[1, :, V] = phi / r
    B0[2, :, W] = dx
    B0[3, :, U] = dx
    B0[3, :, W] = dr
    B0[4, :, V] = dr - phi / r
    B1[4, :, U] = -phi / r
    B0[5, :, V] = dx
    B1[5, :, W] = -phi / r
    return B0, B1


def _material(young_pa: float, poisson: float) -> np.ndarray:
    lam, mu = lame(young_pa, poisson)
    C = np.zeros((6, 6))
    C[:3, :3] = lam
    C[np.arange(3), np.arange(3)] += 2 * mu
    C[np.arange(3, 6), np.arange(3, 6)] = mu
    return C


def harmonic_matrices(basis: Basis, young_pa: float, poisson: float) -> tuple[sp.csr_matrix, ...]:
    """``(K0, K1, K2, K0_cos)``: ``K_n = K0 + n K1 + n^2 K2`` for n >= 1 and ``K0_cos`` for n = 0 (N/m
    per unit of int cos^2 dphi; DOFs interleaved (U, V, W) per scalar DOF)."""
    B0, B1 = _strain_operators(basis)
    C = _material(young_pa, poisson)
    r = basis.global_coordinates().value[1]
    w = basis.dx * r                                                    # r dr dx
    cos_only = C.copy()
    cos_only[4:, :] = cos_only[:, 4:] = 0.0

    def local(Ba, Bb, mat):
        return np.einsum("sajeq,st,tbkeq,eq->eajbk", Ba, mat, Bb, w, optimize=True)

    ed = basis.element_dofs
    dofs = (3 * ed.T[:, :, None] + np.arange(3)[None, None, :]).reshape(ed.shape[1], -1)
    n = dofs.shape[1]
    rows, cols = np.repeat(dofs, n, axis=1).ravel(), np.tile(dofs, (1, n)).ravel()

    def glob(Ke):
        return sp.csr_matrix((Ke.reshape(len(dofs), -1).ravel(), (rows, cols)), shape=(3 * basis.N, 3 * basis.N))

    K01 = local(B0, B1, C)
    return (glob(local(B0, B0, C)), glob(K01 + K01.transpose(0, 3, 4, 1, 2)), glob(local(B1, B1, C)),
            glob(local(B0, B0, cos_only)))


def harmonic_compliance(basis: Basis, young_pa: float, poisson: float, held_radius_m: float,
                        contact_radius_m: float, load_x: np.ndarray, n_max: int, radius_m: float,
                        fix_end_faces_axially: bool = False, held_axially: bool = True) -> np.ndarray:
    """``X[n, e, d]`` for n = 0 .. n_max: radial response of the contact surface, weighted by the
    axial multipliers (m^3/N per unit amplitude of the angular factor).

    ``load_x`` (n_lam_x, n_surface_nodes) is ``D_x`` of :mod:`fem_reference.solid.mortar` on the
    contact surface's nodes sorted by x; the traction is applied per unit of the bore's area
    (``radius_m``): ``K_n U = radius_m * D_x^T``, ``X_n = radius_m * D_x U_surface``.

    ``held_axially`` False leaves the held surface free to slide axially (radial and
    circumferential components held): the ring's rigid axial translation (harmonic 0 only) is then
    removed by holding one node's axial component, which carries no reaction since a radial
    pressure has no resultant along the axis.
    """
    K0, K1, K2, Kc = harmonic_matrices(basis, young_pa, poisson)
    loc = basis.doflocs
    tol = 1e-9 * contact_radius_m
    held = np.flatnonzero(np.abs(loc[1] - held_radius_m) < tol)
    surf = np.flatnonzero(np.abs(loc[1] - contact_radius_m) < tol)
    surf = surf[np.argsort(loc[0, surf])]
    if len(surf) != load_x.shape[1]:
        raise ValueError(f"contact surface has {len(surf)} nodes, mortar expects {load_x.shape[1]}")
    fixed = [3 * held, 3 * held + 1] + ([3 * held + 2] if held_axially else [])
    if fix_end_faces_axially:
        ends = np.flatnonzero(np.abs(np.abs(loc[0]) - np.max(np.abs(loc[0]))) < tol)
        fixed.append(3 * ends + 2)
    fixed = np.unique(np.concatenate(fixed))
    rhs_rows = 3 * surf                                                  # U of the surface nodes
    out = np.empty((n_max + 1, load_x.shape[0], load_x.shape[0]))
    for n in range(n_max + 1):
        if n == 0:
            K = Kc
            fix_n = np.union1d(fixed, 3 * np.arange(basis.N) + 1)        # V decouples at n = 0
            if not (held_axially or fix_end_faces_axially):
                fix_n = np.union1d(fix_n, [3 * held[0] + 2])              # the rigid axial translation
        else:
            K = K0 + n * K1 + (n * n) * K2
            fix_n = fixed
        free = np.setdiff1d(np.arange(3 * basis.N), fix_n)
        pos = -np.ones(3 * basis.N, dtype=int)
        pos[free] = np.arange(len(free))
        lu = spla.splu(K[free][:, free].tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
        R = np.zeros((len(free), load_x.shape[0]))
        R[pos[rhs_rows]] = radius_m * load_x.T
        X = lu.solve(R)
        out[n] = radius_m * load_x @ X[pos[rhs_rows]]
    return out
