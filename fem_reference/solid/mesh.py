"""Structured hexahedral meshes of the two rings (half model about z = 0), graded.

Each ring is a mapped tensor-product mesh in cylindrical coordinates ``(x, rho, phi)`` with
``phi`` in [0, pi] (the half model about the plane z = 0 that holds the load direction +y and
the axis x). The map ``(x, rho, phi) -> (x, rho cos phi, rho sin phi)`` places every vertex
exactly on its circle, and both contact surfaces (bearing outer, support bore) use the same
``phi`` and ``x`` node lines, so each bearing surface node has a support node at the same
``(phi, x)``: node-to-node pairing across the clearance is exact and needs no search.

Why not gmsh here: the 2D reference meshes with gmsh; for the 3D rings a gmsh transfinite
extrusion gives the same structured hexes, but a mapped tensor mesh gives the node pairing and
the grading (optionally toward the generatrices phi = 0 and phi = pi, toward the ring edges
x = +-l0/2 and toward the contact surfaces) directly, with no prism/orphan-node risk
(docs/reference/fem-notes.md, gmsh facts). The rings' curvature enters the gap exactly
(:mod:`fem_reference.solid.geometry`), never through the faceted surface.

Mesh levels are named and nested in spirit: each level halves the element size of the previous
one in the contact-relevant directions (phi and x), so Richardson extrapolation applies.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from skfem import MeshHex

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
        Elements over phi in [0, pi].
    phi_ratio : float
        Size ratio of the largest (phi = pi/2) to the smallest (phi = 0 and pi) element.
    n_axial : int
        Elements over the width l0.
    axial_ratio : float
        Size ratio of the mid-plane element to the edge element (grading toward the edges).
    n_radial : int
        Elements through each ring's thickness.
    radial_ratio : float
        Size ratio of the element at the clamped/driven surface to the one at the contact surface.
    order : int
        1 (8-node trilinear hexahedra) or 2 (27-node triquadratic).
    """

    name: str
    n_phi: int
    n_axial: int
    n_radial: int
    phi_ratio: float = 2.0
    axial_ratio: float = 2.0
    radial_ratio: float = 3.0
    order: int = 1

    def __post_init__(self):
        for f in ("n_phi", "n_axial", "n_radial"):
            v = getattr(self, f)
            if not isinstance(v, (int, np.integer)) or v < 2:
                raise InputError(f"{f} = {v!r} elements: must be an integer >= 2")
        if self.n_phi % 2 or self.n_axial % 2:
            raise InputError(f"n_phi = {self.n_phi}, n_axial = {self.n_axial} elements: must be even "
                             "(symmetric grading)")
        for f in ("phi_ratio", "axial_ratio", "radial_ratio"):
            v = getattr(self, f)
            if not (math.isfinite(v) and 0.05 <= v <= 50.0):
                raise InputError(f"{f} = {v!r} (-): must be in [0.05, 50]")
        if self.order not in (1, 2):
            raise InputError(f"order = {self.order!r}: must be 1 or 2")

    def refined(self, name: str, factor: int = 2) -> "MeshLevel3D":
        """The same grading with every element count multiplied by ``factor`` (phi and x),
        and the radial count by ``factor`` as well."""
        return MeshLevel3D(name, self.n_phi * factor, self.n_axial * factor, self.n_radial * factor,
                           self.phi_ratio, self.axial_ratio, self.radial_ratio, self.order)

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
    """One ring's mesh with the node lines it was built from (SI units).

    ``mesh`` is a scikit-fem MeshHex in Cartesian coordinates ``(x, y, z)``; ``x_nodes``,
    ``rho_nodes``, ``phi_nodes`` are the tensor lines; ``contact_radius_m`` is the radius of the
    surface that can touch the other ring, ``held_radius_m`` that of the driven/clamped surface.
    """

    mesh: MeshHex
    x_nodes: np.ndarray
    rho_nodes: np.ndarray
    phi_nodes: np.ndarray
    contact_radius_m: float
    held_radius_m: float


def ring_mesh(r_contact: float, r_held: float, x_nodes: np.ndarray, phi_nodes: np.ndarray,
              n_radial: int, radial_ratio: float) -> RingMesh:
    """Mapped hexahedral mesh of the half ring between radii ``r_contact`` and ``r_held``,
    graded radially toward ``r_contact``."""
    rho = graded_one_sided(0.0, 1.0, n_radial, radial_ratio)
    rho_nodes = r_contact + (r_held - r_contact) * rho
    rho_sorted = np.sort(rho_nodes)
    m = MeshHex.init_tensor(x_nodes, rho_sorted, phi_nodes)
    xs, rh, ph = m.p
    p = np.vstack([xs, rh * np.cos(ph), rh * np.sin(ph)])
    mesh = MeshHex(p, m.t)
    return RingMesh(mesh, np.asarray(x_nodes), rho_sorted, np.asarray(phi_nodes), r_contact, r_held)


def build_meshes(geom: RingPair3D, level: MeshLevel3D) -> tuple[RingMesh, RingMesh]:
    """Bearing and support meshes of one level (half model, phi in [0, pi]).

    Returns
    -------
    (bearing, support) : tuple of RingMesh
    """
    half = 0.5 * geom.width_m
    # grading toward the edges: ratio = mid-plane element / edge element
    x_nodes = graded_symmetric(-half, half, level.n_axial, level.axial_ratio)
    phi_nodes = graded_symmetric(0.0, math.pi, level.n_phi, level.phi_ratio)
    bearing = ring_mesh(geom.bearing_outer_radius_m, geom.bearing_inner_radius_m, x_nodes, phi_nodes,
                        level.n_radial, level.radial_ratio)
    support = ring_mesh(geom.support_inner_radius_m, geom.support_outer_radius_m, x_nodes, phi_nodes,
                        level.n_radial, level.radial_ratio)
    return bearing, support


# Mesh levels of the committed reference: every element count grows by about sqrt(2) per level
# (phi, x and radial), so the effective size ratio is (DOFs ratio)^(1/3) ~ 1.4 (Richardson with
# unequal ratios, fem_reference.solid.sweep.richardson3). Radial layers are generous because
# trilinear hexahedra are too stiff with few layers (measured: 3 -> 6 layers lowers the force by
# 0.7 %, halving the phi or x size changes it by < 0.2 %). Grading: x toward the ring edges (ratio
# 3), radially toward the contact surfaces (ratio 3); phi uniform: the contact-arc edges sweep
# 20-80 deg over the sweep, and grading toward the loaded generatrix (phi = 0, where the pressure
# is smooth) coarsened them - measured: the largest moment error estimate fell from 2.6 % (phi
# ratio 2) to 1.1 % (uniform).
LEVELS: dict[str, MeshLevel3D] = {
    "L0": MeshLevel3D("L0", n_phi=24, n_axial=8, n_radial=4, phi_ratio=1.0, axial_ratio=3.0),
    "L1": MeshLevel3D("L1", n_phi=34, n_axial=12, n_radial=6, phi_ratio=1.0, axial_ratio=3.0),
    "L2": MeshLevel3D("L2", n_phi=48, n_axial=16, n_radial=8, phi_ratio=1.0, axial_ratio=3.0),
}
DEFAULT_LEVELS = ("L0", "L1", "L2")
# Levels graded hard toward the ring edges (edge elements 0.16, 0.12, 0.08 mm) for edge-only
# contact whose patch is much shorter than l0 (issue 4 hard case); about 3x the cost of L0-L2.
LEVELS.update({
    "E0": MeshLevel3D("E0", n_phi=24, n_axial=16, n_radial=4, phi_ratio=1.0, axial_ratio=40.0),
    "E1": MeshLevel3D("E1", n_phi=34, n_axial=22, n_radial=6, phi_ratio=1.0, axial_ratio=40.0),
    "E2": MeshLevel3D("E2", n_phi=48, n_axial=32, n_radial=8, phi_ratio=1.0, axial_ratio=40.0),
})
EDGE_LEVELS = ("E0", "E1", "E2")
