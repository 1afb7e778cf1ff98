"""Contact compliance of the two rings from circumferential harmonics (the production 3D reference).

Each ring is a body of revolution: a radial surface traction ``M_a(phi) M_e(x)`` (angular and
axial multiplier hats, :mod:`fem_reference.solid.mortar`) is expanded in ``cos(n phi)`` and each
harmonic is one small 2D quadratic problem on the ring's (x, r) section
(:mod:`fem_reference.solid.harmonic`). For the half model (pressure symmetric about the load
plane z = 0, hats on [0, pi]) the condensed mortar compliance of both rings is

    A[(a, e), (b, d)] = sum_n (2 / pi_n) J[a, n] J[b, n] X_n[e, d],     pi_0 = 2 pi, pi_n = pi,

with ``J[a, n] = int_0^pi M_a cos(n phi) dphi`` (closed form) and ``X_n`` the axial compliance of
harmonic n summed over the bearing and the support. The angular resolution of the contact
(the hats) therefore costs one sum, not a finer 3D mesh; the series is cut at ``n_harmonics``,
well beyond the hat width (the terms fall as n^-5 there: ``J`` ~ n^-2 twice, ``X_n`` ~ n^-1).

This is the same elastic model as the 27-node hexahedra (:mod:`fem_reference.solid.compliance`):
exact geometry of revolution, quadratic displacements in (x, r); only the angular direction is
represented by a Fourier series instead of elements. The hexahedral model serves as the
independent check of the converged values (reports/published/fem3d-reference.md).
"""
from __future__ import annotations

import math
import time

import numpy as np

from contact.errors import InputError
from fem_reference.solid.geometry import RingPair3D
from fem_reference.solid.harmonic import harmonic_compliance, section_basis
from fem_reference.solid.mesh import MeshLevel3D, graded_one_sided, graded_symmetric
from fem_reference.solid.mortar import angular_integrals, mortar_1d


def condensed_fourier(X: np.ndarray, J: np.ndarray) -> np.ndarray:
    """``A`` of the half model from the harmonic axial compliances ``X[n, e, d]`` and ``J[a, n]``."""
    n = X.shape[0]
    scale = np.full(n, 2.0 / math.pi)
    scale[0] = 1.0 / math.pi
    na, ne = J.shape[0], X.shape[1]
    JJ = np.einsum("an,bn->nab", J[:, :n] * scale[None, :], J[:, :n]).reshape(n, na * na)
    A = (JJ.T @ X.reshape(n, ne * ne)).reshape(na, na, ne, ne).transpose(0, 2, 1, 3).reshape(na * ne, na * ne)
    return 0.5 * (A + A.T)


def build_fourier(geom: RingPair3D, level: MeshLevel3D, fix_end_faces_axially: bool = False,
                  held_axially: tuple[bool, bool] = (True, True)):
    """Axial grid, harmonic kernel ``X[n, e, d]`` (both rings), condensed ``A``, DOFs, timings.

    ``held_axially``: (bearing inner surface, support outer surface) held along the axis too
    (True) or free to slide axially (False); see :func:`~fem_reference.solid.harmonic.harmonic_compliance`.
    """
    if level.order != 2:
        raise InputError(f"order = {level.order}: the harmonic model uses quadratic sections (order 2)")
    t0 = time.perf_counter()
    half = 0.5 * geom.width_m
    x_nodes = graded_symmetric(-half, half, level.n_axial, level.axial_ratio)
    mx = mortar_1d(x_nodes, 2)
    rs = geom.support_inner_radius_m
    X = 0.0
    n_dofs = 0
    for r_c, r_h, e, nu, axial in ((geom.bearing_outer_radius_m, geom.bearing_inner_radius_m, geom.young_bearing_pa,
                                    geom.poisson_bearing, held_axially[0]),
                                   (geom.support_inner_radius_m, geom.support_outer_radius_m, geom.young_support_pa,
                                    geom.poisson_support, held_axially[1])):
        rho = graded_one_sided(0.0, 1.0, level.n_radial, level.radial_ratio)
        r_nodes = np.sort(r_c + (r_h - r_c) * rho)
        basis = section_basis(x_nodes, r_nodes)
        X = X + harmonic_compliance(basis, e, nu, r_h, r_c, mx.D, level.n_harmonics, rs, fix_end_faces_axially, axial)
        n_dofs += 3 * basis.N
    t1 = time.perf_counter()
    J = angular_integrals(np.linspace(0.0, math.pi, level.n_phi + 1), level.n_harmonics)
    A = condensed_fourier(X, J)
    t2 = time.perf_counter()
    return x_nodes, X, A, n_dofs * (level.n_harmonics + 1), {"harmonics_s": t1 - t0, "condense_s": t2 - t1}
