"""VTU export of a solved 3D point: the contact pressure map on the support bore, for ParaView.

The 3D solve works on the contact compliance ``B K⁻¹ Bᵀ`` (:mod:`fem_reference.solid.solve`), so what
it knows exactly is the contact surface: the pressure and the rigid gap at every contact node of
the support bore. That surface is what this module writes: a quadrilateral surface at the bore
radius over the modelled half ring (polar angle φ from +y to −y through +z, axial x over the ring
width), with point data

* ``contact_pressure_pa`` – normal contact pressure (Pa), from the solved multipliers;
* ``rigid_gap_m`` – gap of the rigid motion before deformation (m), negative = overlap;
* ``phi_deg``, ``x_mm`` – the surface coordinates, for plots over the unrolled bore.

Coordinates are the project's (x axial, y, z lateral; docs/reference/contact-laws.md §1), in metres.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from contact.errors import InputError
from contact.files import atomic_write_via


def bore_surface(phi_grid_rad: np.ndarray, x_grid_m: np.ndarray, radius_m: float):
    """Points (n_phi·n_x, 3) and quads (·, 4) of the bore surface, φ-major like the pressure maps."""
    phi = np.asarray(phi_grid_rad, dtype=float)
    x = np.asarray(x_grid_m, dtype=float)
    if phi.ndim != 1 or x.ndim != 1 or len(phi) < 2 or len(x) < 2:
        raise InputError(f"phi_grid/x_grid: need two 1-D grids of >= 2 nodes, got shapes {phi.shape}, {x.shape}")
    P, X = np.meshgrid(phi, x, indexing="ij")
    pts = np.stack([X.ravel(), radius_m * np.cos(P.ravel()), radius_m * np.sin(P.ravel())], axis=1)
    nx = len(x)
    i, j = np.meshgrid(np.arange(len(phi) - 1), np.arange(nx - 1), indexing="ij")
    a = (i * nx + j).ravel()
    quads = np.stack([a, a + nx, a + nx + 1, a + 1], axis=1)
    return pts, quads


def write_pressure_vtu(path, result, geom, gap_m: np.ndarray | None = None) -> Path:
    """Write the contact pressure map of a :class:`fem_reference.solid.solve.PointResult3D` as VTU.

    Parameters
    ----------
    path : str or Path
        Output file (``.vtu``); written to a temporary name, then renamed.
    result : PointResult3D
        A solved point (``pressure_pa`` on ``phi_grid × x_grid``, Pa).
    geom : RingPair3D
        Geometry of the solve (bore radius).
    gap_m : ndarray, optional
        Rigid gap on the same grid (m); written when given.
    """
    import meshio

    p = np.asarray(result.pressure_pa, dtype=float)
    nphi, nx = len(result.phi_grid), len(result.x_grid)
    if p.shape != (nphi, nx):
        raise InputError(f"pressure_pa: shape {p.shape} does not match the grids ({nphi}, {nx})")
    if not np.all(np.isfinite(p)):
        raise InputError("pressure_pa: contains non-finite values; refusing to write a result file")
    pts, quads = bore_surface(result.phi_grid, result.x_grid, geom.support_inner_radius_m)
    P, X = np.meshgrid(result.phi_grid, result.x_grid, indexing="ij")
    data = {"contact_pressure_pa": p.ravel(), "phi_deg": np.degrees(P.ravel()), "x_mm": X.ravel() * 1e3}
    if gap_m is not None:
        data["rigid_gap_m"] = np.asarray(gap_m, dtype=float).reshape(nphi * nx)
    mesh = meshio.Mesh(pts, [("quad", quads)], point_data=data)
    path = Path(path)
    if path.suffix != ".vtu":
        raise InputError(f"out = {path}: must end in .vtu")
    return atomic_write_via(path, lambda tmp: meshio.write(tmp, mesh, file_format="vtu", binary=True))
