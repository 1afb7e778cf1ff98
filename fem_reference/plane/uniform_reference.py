"""The independent reference of the error-driven bars: linear triangles on nested uniform refinements.

The error-driven levels of :mod:`fem_reference.plane.adapt` are quadratic triangles (P2) on meshes an
error estimate shapes. Their bars are checked against a reference that shares neither choice: linear
triangles (P1) on a first mesh of one size everywhere (graded a priori only at a clamp's end,
:func:`fem_reference.plane.adapt.reference_mesh`), each level that mesh with every triangle split into
four (:func:`fem_reference.plane.mesh.refined_uniformly`), so the sizes halve everywhere and the meshes are
nested. The force of P1 converges like ``h²`` (the energy error like ``h``, the drive's reaction like its
square, as in :mod:`fem_reference.plane.adapt`), and the reference is the finest two levels' Richardson
extrapolation at that order, ``F_n + (F_n − F_{n−1})/3``.

How far the reference can be trusted is measured from its own levels, not assumed: ``uncertainty_rel`` is
the distance between that extrapolation and the one from the two levels below,
``|R(n−1, n) − R(n−2, n−1)|``, and ``observed_order`` the order of the last three levels,
``log2((F_{n−2} − F_{n−1})/(F_{n−1} − F_n))`` (NaN when they are not monotone).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

from contact.errors import InputError
from fem_reference.plane.active_set import solve_active_set
from fem_reference.plane.adapt import reference_mesh
from fem_reference.plane.contact_solver import ArcNotResolvedError
from fem_reference.plane.mesh import refined_uniformly
from fem_reference.plane.solve import ContactModel
from fem_reference.scenes import Scene

P1_ORDER = 2.0      # the force's order in h for linear triangles


@dataclass(frozen=True)
class UniformReference:
    """One penetration on nested uniform P1 levels (coarse to fine) and its extrapolation.

    Attributes
    ----------
    forces_n : tuple of float
        The force of each level [N].
    ndofs : tuple of int
        Each level's number of DOFs [-].
    h0_m : float
        The first mesh's size [m]; level k has ``h0_m / 2**k``.
    force_n : float
        The reference: the finest two levels extrapolated at order 2 [N].
    uncertainty_rel : float
        ``|R(n−1, n) − R(n−2, n−1)| / force_n`` [-] (module docstring).
    observed_order : float
        The last three levels' order in h [-]; NaN when not monotone.
    wall_s : float
        Wall time of all levels and penetrations solved together [s].
    """

    forces_n: tuple
    ndofs: tuple
    h0_m: float
    force_n: float
    uncertainty_rel: float
    observed_order: float
    wall_s: float


def _richardson(coarse: float, fine: float) -> float:
    return fine + (fine - coarse) / (2.0 ** P1_ORDER - 1.0)


def uniform_reference(scene: Scene, penetrations_m, h0_m: float, n_levels: int = 4, *, more=None,
                      max_levels: int | None = None, max_dofs: int | None = None) -> tuple[UniformReference, ...]:
    """The P1 references of the penetrations [m] from a first mesh of size ``h0_m`` [m] and ``n_levels − 1``
    nested refinements (module docstring), one per penetration (each level's model is built once).

    ``more``: given the references so far, whether to add a level; levels are added while it says so, up to
    ``max_levels`` and while the next level (four times the last one's DOFs) stays within ``max_dofs``. No level
    is solved twice.

    Each level is factorised in a nested-dissection order and each point solved by the active-set method on
    the sparse system (:func:`fem_reference.plane.active_set.solve_active_set`), its first set the coarser level's
    contact arc: the same discrete solution as :meth:`ContactModel.solve`, at a 465k-DOF level in 44 s instead of
    about 10 min.

    A first mesh too coarse to resolve a penetration's contact arc (the solver's ArcNotResolvedError) is
    passed over while three levels or more remain: the levels start one refinement finer and end at the same
    finest size, one level fewer, and ``h0_m`` of the result is their first level's size (seed 1928108429's
    pair 19 at 0.0115 mm: one active node at 6.55 mm, the benchmark's run refused the pair).

    Raises
    ------
    InputError
        If ``n_levels`` < 3 (the reference's own uncertainty needs three levels) or ``h0_m`` is not > 0.
    """
    if n_levels < 3:
        raise InputError(f"n_levels = {n_levels!r}: need at least 3 levels (the reference's uncertainty)")
    if not h0_m > 0:
        raise InputError(f"h0_m = {h0_m!r} m: must be > 0")
    t0 = time.perf_counter()
    pens = [float(d) for d in penetrations_m]
    rmesh = reference_mesh(scene, h0_m, order=1)
    forces, dofs, edges = [], [], [None] * len(pens)
    skipped = 0

    def done() -> bool:
        if len(forces) + skipped < n_levels:
            return False
        if more is None or (max_levels is not None and len(forces) + skipped >= max_levels):
            return True
        if max_dofs is not None and 4 * dofs[-1] > max_dofs:
            return True
        return not more(_results(forces, dofs, h0_m / 2 ** skipped, time.perf_counter() - t0))

    while not done():
        if forces or skipped:
            rmesh = refined_uniformly(rmesh)
        model = ContactModel.from_mesh(scene, rmesh, nested_dissection=True)
        try:
            sols = [solve_active_set(model, d, edge_phi_rad=e) for d, e in zip(pens, edges)]
        except ArcNotResolvedError:
            if forces or n_levels - skipped - 1 < 3:
                raise
            skipped += 1          # the arc not resolved at this size: the levels start one refinement finer
            continue
        forces.append([sol.force_n for sol in sols])
        edges = [sol.half_angle_rad for sol in sols]
        dofs.append(model.ndofs)
        del model
    return _results(forces, dofs, h0_m / 2 ** skipped, time.perf_counter() - t0)


def _results(forces: list, dofs: list, h_first: float, wall: float) -> tuple[UniformReference, ...]:
    return tuple(_one(tuple(row[j] for row in forces), tuple(dofs), h_first, wall) for j in range(len(forces[0])))


def _one(forces: tuple, dofs: tuple, h0_m: float, wall_s: float) -> UniformReference:
    f1, f2, f3 = forces[-3:]
    ref = _richardson(f2, f3)
    unc = abs(ref - _richardson(f1, f2)) / abs(ref) if ref else math.inf
    d1, d2 = f1 - f2, f2 - f3
    order = math.log2(d1 / d2) if d1 * d2 > 0 else math.nan
    return UniformReference(forces, dofs, float(h0_m), ref, unc, order, wall_s)
