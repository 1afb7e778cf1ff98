"""Structured isoparametric hexahedral meshes of the two full rings, graded toward the ring edges.

Each ring is a mapped tensor-product mesh in cylindrical coordinates ``(x, rho, phi)`` over the
full circle (``phi`` periodic, uniform steps), mapped by ``(x, rho, phi) -> (x, rho cos phi,
rho sin phi)``. For quadratic elements (27-node Lagrange hexahedra, scikit-fem ``MeshHex2`` /
``ElementHex2``) every higher-order node is placed on its true circle (isoparametric: the rings'
curved surfaces are represented to O(h^3), the volume of a 64-element ring to 2e-7). Both contact
surfaces (bearing outer, support bore) use the same ``phi`` and ``x`` node lines, so each bearing
surface node has a support node at the same ``(phi, x)``: node-to-node pairing across the
clearance is exact and needs no search.

Why uniform in ``phi`` and a full ring: a ring with uniform ``phi`` steps is invariant under a
rotation by one element about its axis, so the contact compliance between any two surface nodes
depends only on their angular offset (and node type and axial positions). One set of solves with
loads on a single generatrix gives the whole compliance (:mod:`fem_reference.solid.compliance`);
the resolution in ``phi`` then costs almost nothing beyond the factorisation, and a mesh graded
toward the contact arc (whose edges move from 20 to 80 degrees over the sweep) is not needed.

Why not gmsh here: a gmsh transfinite extrusion gives the same structured hexes, but building
the mapped tensor mesh directly keeps the rotation invariance and the (phi, x) pairing exact by
construction and takes milliseconds (docs/reference/fem-notes.md, 3D section).

Mesh levels are named; each finer level multiplies the element counts in phi, x and radially,
so Richardson extrapolation applies (:func:`fem_reference.solid.sweep.richardson3`).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import asdict, dataclass

import numpy as np

from contact.errors import InputError
from fem_reference.solid.geometry import RingPair3D


@dataclass(frozen=True)
class MeshLevel3D:
    """Element counts of one mesh level (both rings share phi and x divisions).

    Parameters
    ----------
    name : str
        Level name stored with every result.
    n_phi : int
        Elements over the half circle phi in [0, pi] (the full ring has ``2 n_phi``, uniform).
    n_axial : int
        Elements over the width l0.
    n_radial : int
        Elements through each ring's thickness.
    axial_ratio : float
        Size ratio of the mid-plane element to the edge element (grading toward the edges).
    radial_ratio : float
        Size ratio of the element at the clamped/driven surface to the one at the contact surface.
    order : int
        1 (8-node trilinear hexahedra) or 2 (27-node triquadratic, isoparametric; 9-node sections).
    method : str
        "fourier": circumferential harmonics on a quadratic (x, r) section, ``n_phi`` angular
        multiplier elements over [0, pi] (:mod:`fem_reference.solid.fourier`); "hex": 3D hexahedra,
        ``n_phi`` elements over [0, pi] (:mod:`fem_reference.solid.compliance`).
    n_harmonics : int
        Highest Fourier order kept ("fourier" only).
    """

    name: str
    n_phi: int
    n_axial: int
    n_radial: int
    axial_ratio: float = 2.0
    radial_ratio: float = 3.0
    order: int = 2
    method: str = "hex"
    n_harmonics: int = 0

    def __post_init__(self):
        for f in ("n_phi", "n_axial", "n_radial"):
            v = getattr(self, f)
            if not isinstance(v, (int, np.integer)) or v < 1 or (f != "n_radial" and v < 2):
                raise InputError(f"{f} = {v!r} elements: must be an integer >= {1 if f == 'n_radial' else 2}")
        if self.n_axial % 2:
            raise InputError(f"n_axial = {self.n_axial} elements: must be even (symmetric grading)")
        for f in ("axial_ratio", "radial_ratio"):
            v = getattr(self, f)
            if not (math.isfinite(v) and 0.05 <= v <= 1000.0):
                raise InputError(f"{f} = {v!r} (-): must be in [0.05, 1000]")
        if self.order not in (1, 2):
            raise InputError(f"order = {self.order!r}: must be 1 or 2")
        if self.method not in ("hex", "fourier"):
            raise InputError(f"method = {self.method!r}: must be 'hex' or 'fourier'")
        if self.method == "fourier" and not (isinstance(self.n_harmonics, (int, np.integer))
                                             and 4 <= self.n_harmonics <= 20000):
            raise InputError(f"n_harmonics = {self.n_harmonics!r}: must be an integer in [4, 20000]")

    def refined(self, name: str, factor: float = 2.0) -> "MeshLevel3D":
        """The same grading with every element count multiplied by ``factor`` (rounded; axial even)."""
        return MeshLevel3D(name, max(2, round(self.n_phi * factor)), 2 * max(1, round(self.n_axial * factor / 2)),
                           max(1, round(self.n_radial * factor)), self.axial_ratio, self.radial_ratio, self.order,
                           self.method, round(self.n_harmonics * factor))

    def as_dict(self) -> dict:
        return asdict(self)


def graded_symmetric(a: float, b: float, n: int, ratio: float) -> np.ndarray:
    """``n + 1`` nodes on [a, b], geometric sizes growing from both ends to the middle.

    ``ratio`` is the size of the middle element over the end elements (1 = uniform).
    """
    half = n // 2
    q = ratio ** (1.0 / max(half - 1, 1)) if half > 1 else 1.0
    sizes = q ** np.arange(half)
    sizes = np.concatenate([sizes, sizes[::-1]])
    if n % 2:
        sizes = np.insert(sizes, half, sizes[half - 1] * q)
    cum = np.concatenate([[0.0], np.cumsum(sizes)])
    t = cum / cum[-1]
    t = 0.5 * (t + 1.0 - t[::-1])          # exactly mirror-symmetric (the solver relies on it)
    return 0.5 * (a + b) + (b - a) * (t - 0.5)


def graded_one_sided(a: float, b: float, n: int, ratio: float) -> np.ndarray:
    """``n + 1`` nodes on [a, b], sizes growing geometrically from ``a`` to ``b`` by ``ratio``
    (last over first element)."""
    q = ratio ** (1.0 / max(n - 1, 1))
    sizes = q ** np.arange(n)
    cum = np.concatenate([[0.0], np.cumsum(sizes)])
    return a + (b - a) * cum / cum[-1]


@dataclass(frozen=True)
class RingMesh:
    """One full ring's mesh with the node lines it was built from (SI units).

    ``mesh`` is a scikit-fem MeshHex (order 1) or MeshHex2 (order 2) in Cartesian ``(x, y, z)``;
    ``x_nodes`` and ``rho_nodes`` are the element vertex lines, ``n_phi_full`` the elements around
    the full circle; ``contact_radius_m`` is the radius of the surface that can touch the other
    ring, ``held_radius_m`` that of the driven/clamped surface.
    """

    mesh: object
    x_nodes: np.ndarray
    rho_nodes: np.ndarray
    n_phi_full: int
    contact_radius_m: float
    held_radius_m: float
    order: int


def _periodic_hexes(x_nodes: np.ndarray, rho_nodes: np.ndarray, n_phi_full: int):
    """Trilinear mesh (scikit-fem MeshHex) of the full ring, vertices on their circles, phi periodic (no seam)."""
    from skfem import MeshHex
    nx, nr = len(x_nodes), len(rho_nodes)
    phi = 2.0 * math.pi * np.arange(n_phi_full) / n_phi_full
    gx, gr, gp = (g.ravel() for g in np.meshgrid(np.arange(nx), np.arange(nr), np.arange(n_phi_full), indexing="ij"))
    p = np.vstack([x_nodes[gx], rho_nodes[gr] * np.cos(phi[gp]), rho_nodes[gr] * np.sin(phi[gp])])
    a, b, c = (g.ravel() for g in np.meshgrid(np.arange(nx - 1), np.arange(nr - 1), np.arange(n_phi_full),
                                              indexing="ij"))

    def idx(i, j, k):
        return (i * nr + j) * n_phi_full + (k % n_phi_full)

    # vertex order of scikit-fem's MeshHex.init_tensor on (x, rho, phi); the map has det = rho > 0
    t = np.vstack([idx(a, b, c), idx(a, b + 1, c), idx(a + 1, b, c), idx(a, b, c + 1), idx(a + 1, b + 1, c),
                   idx(a, b + 1, c + 1), idx(a + 1, b, c + 1), idx(a + 1, b + 1, c + 1)])
    return MeshHex(p, t)


def _onto_circles(mesh, n_phi_full: int):
    """Move the mid-edge, mid-face and centre nodes of chords spanning two angles onto their arcs.

    A node built as the mean of vertices at angles phi_k and phi_{k+1} lies at the mean angle
    (exactly, by symmetry) and at radius ``rho cos(dphi/2)``; it is moved out to ``rho``.
    """
    d = mesh.doflocs.copy()
    ang = np.arctan2(d[2], d[1])
    rad = np.hypot(d[1], d[2])
    dphi = 2.0 * math.pi / n_phi_full
    k = 2.0 * ang / dphi
    between = (np.abs(k - np.round(k)) < 1e-6) & (np.round(k).astype(int) % 2 != 0)
    rad = np.where(between, rad / math.cos(0.5 * dphi), rad)
    d[1], d[2] = rad * np.cos(ang), rad * np.sin(ang)
    return dataclasses.replace(mesh, doflocs=d)


def ring_mesh(r_contact: float, r_held: float, x_nodes: np.ndarray, n_phi_full: int, n_radial: int,
              radial_ratio: float, order: int = 2) -> RingMesh:
    """Mesh of the full ring between radii ``r_contact`` and ``r_held``, graded radially toward
    ``r_contact``; ``order`` 2 gives the isoparametric 27-node mesh."""
    rho = graded_one_sided(0.0, 1.0, n_radial, radial_ratio)
    rho_nodes = np.sort(r_contact + (r_held - r_contact) * rho)
    m = _periodic_hexes(np.asarray(x_nodes, dtype=float), rho_nodes, n_phi_full)
    if order == 2:
        from skfem import MeshHex2

        m = _onto_circles(MeshHex2.from_mesh(m), n_phi_full)
    return RingMesh(m, np.asarray(x_nodes, dtype=float), rho_nodes, n_phi_full, r_contact, r_held, order)


def build_meshes(geom: RingPair3D, level: MeshLevel3D) -> tuple[RingMesh, RingMesh]:
    """Bearing and support meshes of one level (full rings, ``2 n_phi`` elements around).

    Returns
    -------
    (bearing, support) : tuple of RingMesh
    """
    half = 0.5 * geom.width_m
    x_nodes = graded_symmetric(-half, half, level.n_axial, level.axial_ratio)
    n_full = 2 * level.n_phi
    bearing = ring_mesh(geom.bearing_outer_radius_m, geom.bearing_inner_radius_m, x_nodes, n_full,
                        level.n_radial, level.radial_ratio, level.order)
    support = ring_mesh(geom.support_inner_radius_m, geom.support_outer_radius_m, x_nodes, n_full,
                        level.n_radial, level.radial_ratio, level.order)
    return bearing, support


def _family(prefix: str, counts, axial_ratio: float, method: str = "fourier", order: int = 2) -> dict:
    """Named levels ``prefix0, prefix1, ...`` from (n_phi, n_axial, n_radial) with 2 n_phi harmonics."""
    return {f"{prefix}{i}": MeshLevel3D(f"{prefix}{i}", n_phi=p, n_axial=a, n_radial=r, axial_ratio=axial_ratio,
                                        radial_ratio=20.0, order=order, method=method,
                                        n_harmonics=2 * p if method == "fourier" else 0)
            for i, (p, a, r) in enumerate(counts)}


# Reference levels (measured, docs/reference/fem-notes.md "3D"): every count grows by about sqrt(2)
# per level (angular multiplier elements over [0, pi], axial and radial section elements, and the
# harmonics kept, 2 n_phi = about 6 per angular hat width: 200 instead of 570 harmonics changed no
# force or moment by 1e-5). Axial grading toward the ring edges 30 (edge element 0.25 mm on Q0,
# 0.10 mm on Q3), radial grading toward the contact surfaces 20 (the high harmonics decay within
# R/n of the surface). Q3 is the finer solve every committed point is checked against.
LEVELS: dict[str, MeshLevel3D] = _family("Q", [(64, 12, 5), (90, 18, 7), (128, 24, 10), (180, 34, 14)], 30.0)
DEFAULT_LEVELS = ("Q0", "Q1", "Q2")
CHECK_LEVEL = "Q3"
# Graded hard toward the ring edges (edge elements 0.05 mm on E0 to 0.02 mm on E3) for edge-only
# contact whose patch (about 0.5 mm at -0.04 mm, 10') is much shorter than l0.
LEVELS.update(_family("E", [(64, 16, 5), (90, 22, 7), (128, 32, 10), (180, 44, 14)], 150.0))
EDGE_LEVELS = ("E0", "E1", "E2")
EDGE_CHECK_LEVEL = "E3"
# 27-node hexahedra (full 3D rings, the same graded section), the independent check of the
# harmonic model on the Table 3 points (reports/published/fem3d-reference.md).
LEVELS.update(_family("H", [(48, 6, 2), (68, 8, 3), (96, 12, 4)], 10.0, method="hex"))
HEX_LEVELS = ("H0", "H1", "H2")
