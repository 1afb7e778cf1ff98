"""Mortar coupling of the contact surfaces: bilinear pressure multipliers, weighted gaps.

As in the 2D reference (:mod:`fem_reference.plane.contact_solver`), the contact pressure is
``p = sum_j lam_j M_j`` with piecewise-bilinear multipliers ``M_j`` on the element corners of the
support bore (tensor products of 1D hats in phi and x), for linear and quadratic displacements
alike: P1 multipliers on a P2 trace are inf-sup stable and do not oscillate corner/mid-side at
the edge of the contact patch. The constraints are the weak (weighted) gaps

    g~_j = int M_j g dA = b_j + (D u_r)_j,    b_j = int M_j g0 dA,    D[j, i] = int M_j N_i dA,

with ``g0`` the exact rigid gap of the tilted cylinders (:func:`fem_reference.solid.geometry.rigid_gap_m`)
integrated by Gauss-Legendre quadrature (5 points per element and direction) and ``N_i`` the
displacement shape functions of the contact-surface nodes. Nodal contact forces are ``D^T lam``.
Everything factorises over the two directions (``D = D_phi (x) D_x``), so the condensed operator
``A = D G D^T`` of the nodal compliance ``G`` and the weighted gaps are a few small matrix products.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

_GAUSS = np.polynomial.legendre.leggauss(5)


@dataclass(frozen=True)
class Mortar1D:
    """One direction of the tensor-product mortar (SI units).

    Attributes
    ----------
    vertices : ndarray
        (n_v,) element corners: the multiplier nodes.
    D : ndarray
        (n_v, n_dof) ``int M_a N_i`` along this direction (m or rad).
    W : ndarray
        (n_v, n_q) ``M_a(s_q) w_q``: quadrature weights of the weighted gap.
    points : ndarray
        (n_q,) quadrature points.
    """

    vertices: np.ndarray
    D: np.ndarray
    W: np.ndarray
    points: np.ndarray

    @property
    def weights(self) -> np.ndarray:
        """``int M_a`` of each multiplier (m or rad)."""
        return self.W.sum(axis=1)


def _lagrange(order: int, s: np.ndarray) -> np.ndarray:
    """Shape functions on [0, 1] of order 1 (2 nodes) or 2 (nodes 0, 1/2, 1), shape (order + 1, len(s))."""
    if order == 1:
        return np.vstack([1.0 - s, s])
    return np.vstack([(1 - s) * (1 - 2 * s), 4 * s * (1 - s), s * (2 * s - 1)])


def mortar_1d(vertices: np.ndarray, order: int) -> Mortar1D:
    """Mortar matrices of a 1D line of elements with corners ``vertices`` and displacement ``order``."""
    v = np.asarray(vertices, dtype=float)
    ne, nv = len(v) - 1, len(v)
    xi, wi = _GAUSS
    s = 0.5 * (xi + 1.0)
    hat = _lagrange(1, s)                                   # (2, q)
    shp = _lagrange(order, s)                               # (order + 1, q)
    D = np.zeros((nv, order * ne + 1))
    W = np.zeros((nv, ne * len(s)))
    pts = np.empty(ne * len(s))
    for e in range(ne):
        h = v[e + 1] - v[e]
        w = 0.5 * wi * h
        D[e:e + 2, order * e:order * e + order + 1] += (hat * w) @ shp.T
        W[e:e + 2, e * len(s):(e + 1) * len(s)] = hat * w
        pts[e * len(s):(e + 1) * len(s)] = v[e] + s * h
    return Mortar1D(v, D, W, pts)


def condensed(G: np.ndarray, phi: Mortar1D, x: Mortar1D, radius_m: float) -> np.ndarray:
    """``A = D G D^T`` for ``D = radius * D_phi (x) D_x`` (phi-major ordering on both sides)."""
    npd, nxd = phi.D.shape[1], x.D.shape[1]
    Gr = G.reshape(npd, nxd, npd, nxd)
    t = np.einsum("ap,pxqy->axqy", phi.D, Gr, optimize=True)
    t = np.einsum("bx,axqy->abqy", x.D, t, optimize=True)
    t = np.einsum("cq,abqy->abcy", phi.D, t, optimize=True)
    t = np.einsum("dy,abcy->abcd", x.D, t, optimize=True)
    n = phi.D.shape[0] * x.D.shape[0]
    A = t.reshape(n, n) * radius_m ** 2
    return 0.5 * (A + A.T)


def weighted_gap(g0_q: np.ndarray, phi: Mortar1D, x: Mortar1D, radius_m: float) -> np.ndarray:
    """``b_j = int M_j g0 dA`` from the rigid gap on the quadrature grid ``(phi.points, x.points)`` (m^3)."""
    return (radius_m * phi.W @ g0_q @ x.W.T).ravel()


def angular_integrals(vertices_rad: np.ndarray, n_max: int) -> np.ndarray:
    """``J[a, n] = int_0^pi M_a(phi) cos(n phi) dphi`` of the angular hats on [0, pi] (rad), n = 0 .. n_max.

    Closed form from twice integrating by parts (the hats' second derivatives are point masses):
    interior hat ``-(1/n^2) [cos(n p_-)/h_- - (1/h_- + 1/h_+) cos(n p) + cos(n p_+)/h_+]``; the end
    hats (half hats at 0 and pi) from the same formula with the symmetric image, halved."""
    v = np.asarray(vertices_rad, dtype=float)
    n = np.arange(n_max + 1, dtype=float)[None, :]
    ext = np.concatenate([[-v[1]], v, [2 * v[-1] - v[-2]]])              # mirror images about 0 and pi
    hm, hp = np.diff(ext)[:-1, None], np.diff(ext)[1:, None]
    pm, p0, pp = ext[:-2, None], ext[1:-1, None], ext[2:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        J = -(np.cos(n * pm) / hm - (1 / hm + 1 / hp) * np.cos(n * p0) + np.cos(n * pp) / hp) / n ** 2
    J[:, 0] = 0.5 * (hm + hp)[:, 0]
    J[0] *= 0.5
    J[-1] *= 0.5
    return J
