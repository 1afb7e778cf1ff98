"""What a ``ringcontact bearing`` run will cost, estimated from the ring-pair file before anything is meshed.

The 2D reference meshes each point's levels (:mod:`fem_reference.plane.sweep`): size ``h`` on the bore within the
possible contact arc (:func:`fem_reference.plane.sweep.arc_zone_rad`), ``4 h`` beyond it, doubling every
``GRADING_LENGTH_M`` away from the bore. The elements of such a mesh are about
``Σ_rings R · arc · L / (2 ln 2) · (1 − 4^(−t/L)) / s²`` (arc at size ``s``, ring thickness ``t``); the DOFs are
:data:`DOFS_PER_ELEMENT` times that (P2 triangles, two components; the factor measured: 12.1 on
steel-in-aluminium at 0.004 mm, 12 522 DOFs at h = 0.5 mm, and 13.6 on the same ring scaled to R = 1 m,
68 900 DOFs at h = 1 mm). The finest level is 1 mm, or 0.5 mm where that level stays within
:data:`fem_reference.plane.sweep.MAX_DOFS_EXTRA_LEVEL` (the sweep's own rule). A point's wall time and peak memory
follow its finest DOFs with the exponent and the bytes measured on those two points. The 3D tilt reference
has fixed element counts per level (:mod:`fem_reference.solid.mesh`): a constant cost per point.
"""
from __future__ import annotations

import math

from fem_reference.plane.sweep import GRADING_LENGTH_M, MAX_DOFS_EXTRA_LEVEL, arc_zone_rad
from fem_reference.ring_scene import RingScene
from reports.bearing.tilt import grid_points
from reports.cli._budget import Estimate

#: DOFs per estimated element (measured 12.1 and 13.6, see the module docstring; the larger, rounded up)
DOFS_PER_ELEMENT = 14.0
#: along the bore beyond the contact zone the element size grows to this many h (fem_reference.plane.sweep)
ARC_FACTOR = 4.0
#: one 2D point (all its levels): 1.53 s at 12 522 finest DOFs, 19.5 s at 68 900 (exponent 1.49; fem-point
#: 0.004 mm, 2026-11-29, load average 4)
POINT_2D_S, POINT_2D_DOFS, POINT_2D_EXPONENT = 1.53, 12522, 1.5
#: peak memory of a process solving one 2D point, per finest DOF: 1.06 GB at 68 900 DOFs (interpreter included)
BYTES_PER_DOF_2D = 15.4e3
#: one 3D point, worker time: 44.4 s for the 24 points of steel-in-aluminium on 2 workers, cold level cache
#: (reports/published/perf-bearing.md)
POINT_3D_S = 44.4 * 2 / 24
#: one point of the tilt correction's grids (reports.bearing.tilt), worker time, the levels already cached:
#: 78.6 s for the 117 points of steel-in-aluminium's training grid on one core (0.67 s; the 20 mm ring's 130
#: points took 48.4 s): the training grids' metadata in reports/published/law-tilt-correction/
POINT_GRID_S = 0.7


def _elements(rs: RingScene, zone_rad: float, h_m: float) -> float:
    rings = rs.scene.rings
    r = rings.bore_radius_m
    area = 0.0
    for t in (rings.outer_radius_m - rings.inner_radius_m, rings.support_outer_radius_m - r):
        layers = GRADING_LENGTH_M / (2 * math.log(2)) * (1 - 4 ** (-t / GRADING_LENGTH_M))
        area += r * layers * (zone_rad / h_m ** 2 + (math.pi - zone_rad) / (ARC_FACTOR * h_m) ** 2)
    return area


def dofs_2d(rs: RingScene, penetration_m: float) -> float:
    """The estimated DOFs of the finest 2D level at ``penetration_m`` (m)."""
    zone = arc_zone_rad(rs.scene.rings, penetration_m)
    n1 = DOFS_PER_ELEMENT * _elements(rs, zone, 1e-3)
    return n1 * 3.6 if n1 * 3.6 <= MAX_DOFS_EXTRA_LEVEL else n1


def estimate(rs: RingScene, workers: int) -> Estimate:
    """Wall time on ``workers`` processes and peak memory of the FEM stages of ``rs`` (typical, not a bound)."""
    dofs = [dofs_2d(rs, p) for p in rs.penetrations_2d_m]
    secs = sum(POINT_2D_S * (n / POINT_2D_DOFS) ** POINT_2D_EXPONENT for n in dofs)
    n3 = len(rs.penetrations_3d_m) * len(rs.tilts_rad) if rs.needs_3d else 0
    ng = grid_points(rs) if rs.needs_3d else 0
    secs += n3 * POINT_3D_S + ng * POINT_GRID_S
    w = max(1, int(workers))
    made = (f"{len(dofs)} 2D points of up to {max(dofs):.3g} DOFs, {BYTES_PER_DOF_2D / 1e3:.3g} kB a DOF"
            + (f", {n3} 3D points of {POINT_3D_S:.3g} s and {ng} grid points of {POINT_GRID_S:.3g} s" if n3 else "")
            + f" on {w} worker(s)")
    return Estimate(secs / w, max(dofs) * BYTES_PER_DOF_2D * min(w, len(dofs)), made, bound=False)
