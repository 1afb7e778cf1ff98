"""Half-model meshes of the two rings with gmsh, handed to scikit-fem as arrays.

Geometry (built-in gmsh kernel): two half annuli (x >= 0) about the load axis +y.
Element size is ``h_contact_m * g(x, y)`` with a grading function ``g`` that is 1 on the
contact circle, grows linearly with the distance from it (``grading_length_m``: the size
doubles that far away), and is coarser on the unloaded half (y < 0). Every size scales with
``h_contact_m``, so halving it is a uniform refinement (what Richardson extrapolation needs).

Second-order meshes use gmsh's geometry-snapped (curved) 6-node triangles. The gap is *not*
taken from the element geometry anyway: :mod:`fem_reference.plane.contact_solver` computes it
from the exact circles, so straight P1 edges (sag h^2/(8R)) do not bias the contact.

The mesh goes to scikit-fem straight from gmsh's arrays (``MeshTri1``/``MeshTri2``; no file, no
meshio round trip), with the body of each element recorded and named boundaries
(``mesh.boundaries``: bearing_inner, bearing_outer, support_bore, support_outer, symmetry) found
by radius and body (:func:`facets_on_circle`) – what ``from_meshio`` would need on quadratic
meshes anyway, since it ignores gmsh's physical groups there (docs/reference/fem-notes.md).
"""
from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import numpy as np
from skfem import MeshTri1, MeshTri2

from contact.errors import InputError
from contact.units import check_positive
from fem_reference.plane.geometry import RingPair

BEARING, SUPPORT = 0, 1
_GMSH_LOCK = threading.Lock()


@dataclass(frozen=True)
class MeshSpec:
    """How to mesh a :class:`RingPair` (sizes in m).

    Parameters
    ----------
    h_contact_m : float
        Element size on the contact circle [m].
    order : int
        1 (3-node) or 2 (6-node, curved) triangles.
    grading_length_m : float
        Distance from the contact circle over which the element size doubles [m].
    bottom_coarsening : float
        Extra size factor at the bottom (y = -R_b) of the unloaded half [-].
    max_size_factor : float
        Cap of the grading function g [-].
    top_refinement : float
        Size factor (<= 1) at the top contact point (on the load axis), blending linearly to 1
        at ``top_radius_m`` from it: resolves the tiny arcs of small penetrations.
    arc_zone_rad : float
        Half-angle [rad], from the load axis, of the possible contact arc: the size is ``h`` on
        the contact circle only for angles ``phi <= arc_zone_rad``; beyond it, it grows linearly
        with the arc length ``R·(phi − arc_zone_rad)`` and doubles every ``arc_grading_length_m``.
        ``pi`` (default): the whole bore at size ``h``.
    arc_grading_length_m : float
        Arc length beyond the zone over which the size doubles [m].
    arc_max_factor : float
        Cap of that along-the-bore coarsening factor [-] (keeps thin rings resolved through
        their thickness; a multiple of ``h``, so halving ``h`` stays a uniform refinement).
    """

    h_contact_m: float = 2e-3
    order: int = 2
    grading_length_m: float = 5e-3
    bottom_coarsening: float = 2.0
    max_size_factor: float = 400.0
    top_refinement: float = 1.0
    top_radius_m: float = 15e-3
    arc_zone_rad: float = math.pi
    arc_grading_length_m: float = 10e-3
    arc_max_factor: float = 4.0

    def __post_init__(self):
        check_positive("h_contact_m", self.h_contact_m, "m", upper=1.0)
        check_positive("grading_length_m", self.grading_length_m, "m", upper=100.0)
        check_positive("bottom_coarsening", self.bottom_coarsening, "-", allow_zero=True)
        check_positive("max_size_factor", self.max_size_factor, "-")
        check_positive("top_refinement", self.top_refinement, "-", upper=1.0)
        check_positive("top_radius_m", self.top_radius_m, "m", upper=10.0)
        check_positive("arc_zone_rad", self.arc_zone_rad, "rad", upper=math.pi)
        check_positive("arc_grading_length_m", self.arc_grading_length_m, "m", upper=100.0)
        if not self.arc_max_factor >= 1.0:
            raise InputError(f"arc_max_factor = {self.arc_max_factor!r} -: must be >= 1")
        if self.order not in (1, 2):
            raise InputError(f"order = {self.order!r}: must be 1 or 2")


@dataclass(frozen=True)
class RingMesh:
    """A meshed ring pair: scikit-fem mesh + body of each element."""

    mesh: object          # skfem MeshTri1 / MeshTri2, coordinates in m
    body: np.ndarray      # (n_elements,) BEARING or SUPPORT
    rings: RingPair
    spec: MeshSpec

    @property
    def order(self) -> int:
        return self.spec.order


def _half_annulus(geo, r_in: float, r_out: float, h: float) -> int:
    c = geo.addPoint(0, 0, 0, h)
    pi = [geo.addPoint(0, -r_in, 0, h), geo.addPoint(r_in, 0, 0, h), geo.addPoint(0, r_in, 0, h)]
    po = [geo.addPoint(0, r_out, 0, h), geo.addPoint(r_out, 0, 0, h), geo.addPoint(0, -r_out, 0, h)]
    lines = [geo.addCircleArc(pi[0], c, pi[1]), geo.addCircleArc(pi[1], c, pi[2]),
             geo.addLine(pi[2], po[0]),
             geo.addCircleArc(po[0], c, po[1]), geo.addCircleArc(po[1], c, po[2]),
             geo.addLine(po[2], pi[0])]
    loop = geo.addCurveLoop(lines)
    return geo.addPlaneSurface([loop])


def _size_field(rings: RingPair, spec: MeshSpec) -> str:
    """The gmsh MathEval expression of the element size over the plane (m)."""
    R_c = 0.5 * (rings.outer_radius_m + rings.bore_radius_m)
    hc, L = spec.h_contact_m, spec.grading_length_m
    rho = "sqrt(x*x+y*y)"
    # main term: h on the contact circle, doubling every L away from it, coarser at the bottom,
    # refined by spec.top_refinement within spec.top_radius_m of the top contact point (tiny arcs)
    top = (f"({spec.top_refinement!r}+(1-{spec.top_refinement!r})*min(1,sqrt(x*x+(y-{R_c!r})^2)/{spec.top_radius_m!r}))")
    main = (f"{hc!r}*{top}*(1+{spec.bottom_coarsening!r}*max(0,-y)/{R_c!r})*(1+abs({rho}-{R_c!r})/{L!r})")
    if spec.arc_zone_rad < math.pi:
        # coarsen along the bore beyond the possible contact arc (phi from the load axis +y)
        arc = f"{R_c!r}*max(0,acos(y/sqrt(x*x+y*y+1e-30))-{spec.arc_zone_rad!r})"
        main += f"*min({spec.arc_max_factor!r},1+{arc}/{spec.arc_grading_length_m!r})"
    terms = [f"{hc * spec.max_size_factor!r}", main]
    r_core = rings.inner_radius_m
    if r_core < 0.5 * rings.outer_radius_m:
        # a small driven core (solid pin): resolve it proportionally to h as well
        c = min(1.0, 0.2 * r_core / 2e-3)
        terms.append(f"{hc!r}*({c!r}+abs({rho}-{r_core!r})/{L!r})")
    return "min(" + ", ".join(terms) + ")"


def _gmsh_triangles(rings: RingPair, spec: MeshSpec, size_expr: str, size_callback=None):
    """Run gmsh on both half annuli with the size field ``size_expr``.

    ``size_callback(x, y)`` [m -> m], if given, is a further size at each point gmsh asks about (the
    smaller of it and ``size_expr`` is used; :func:`build_mesh_sized`).

    Returns gmsh's node tags and coordinates (flat, 3 per node), and per body (bearing, then
    support) the triangles' node tags and the body code of each triangle.
    """
    import gmsh

    from contact.interrupts import handlers_kept

    hc = spec.h_contact_m
    with _GMSH_LOCK:
        # gmsh installs signal handlers of its own (SIGTERM to its default action, SIGINT when interruptible)
        # and never puts them back: the suite's handlers (contact/interrupts.py) are kept around it, so an
        # interrupted job still ends with one line and no temporaries
        with handlers_kept():
            gmsh.initialize(readConfigFiles=False, interruptible=False)
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.model.add("rings")
            geo = gmsh.model.geo
            s_b = _half_annulus(geo, rings.inner_radius_m, rings.outer_radius_m, hc)
            s_s = _half_annulus(geo, rings.bore_radius_m, rings.support_outer_radius_m, hc)
            geo.synchronize()
            f = gmsh.model.mesh.field.add("MathEval")
            gmsh.model.mesh.field.setString(f, "F", size_expr)
            gmsh.model.mesh.field.setAsBackgroundMesh(f)
            for name in ("Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature",
                         "Mesh.MeshSizeExtendFromBoundary"):
                gmsh.option.setNumber(name, 0)
            gmsh.option.setNumber("Mesh.Algorithm", 6)
            gmsh.option.setNumber("General.NumThreads", 1)
            if size_callback is not None:
                gmsh.model.mesh.setSizeCallback(lambda dim, tag, x, y, z, lc: min(lc, size_callback(x, y)))
            gmsh.model.mesh.generate(2)
            if spec.order == 2:
                gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
                gmsh.model.mesh.setOrder(2)
            tags, coords, _ = gmsh.model.mesh.getNodes()
            etype = 2 if spec.order == 1 else 9
            conn, body = [], []
            for b, s in ((BEARING, s_b), (SUPPORT, s_s)):
                _, ntags = gmsh.model.mesh.getElementsByType(etype, s)
                ntags = np.asarray(ntags, dtype=np.int64).reshape(-1, 3 * spec.order)
                conn.append(ntags)
                body.append(np.full(len(ntags), b, dtype=np.int8))
        finally:
            gmsh.finalize()
    return tags, coords, conn, body


def _skfem_mesh(tags, coords, conn: list[np.ndarray], order: int):
    """``MeshTri1``/``MeshTri2`` from gmsh's arrays: only the nodes used by triangles, numbered
    compactly, every triangle counter-clockwise."""
    tags = np.asarray(tags, dtype=np.int64)
    xy = np.asarray(coords).reshape(-1, 3)[:, :2]
    conn = np.vstack(conn)
    used = np.unique(conn)
    lookup = np.full(tags.max() + 1, -1, dtype=np.int64)
    lookup[tags] = np.arange(len(tags))
    # keep only nodes used by triangles, renumbered compactly
    keep = lookup[used]
    renum = np.full(tags.max() + 1, -1, dtype=np.int64)
    renum[used] = np.arange(len(used))
    t = renum[conn].T
    p = xy[keep].T
    # orient counter-clockwise
    a = p[:, t[1]] - p[:, t[0]]
    b = p[:, t[2]] - p[:, t[0]]
    neg = a[0] * b[1] - a[1] * b[0] < 0
    if order == 1:
        t[:, neg] = t[[0, 2, 1]][:, neg]
        return MeshTri1(np.ascontiguousarray(p), np.ascontiguousarray(t))
    t[:, neg] = t[[0, 2, 1, 5, 4, 3]][:, neg]
    return MeshTri2(np.ascontiguousarray(p), np.ascontiguousarray(t))


def _named_boundaries(mesh, rings: RingPair, body: np.ndarray) -> dict[str, np.ndarray]:
    """The named boundary facets (``mesh.boundaries``), found by radius and body."""
    return {
        "bearing_inner": facets_on_circle(mesh, rings.inner_radius_m, element_mask=body == BEARING),
        "bearing_outer": facets_on_circle(mesh, rings.outer_radius_m, element_mask=body == BEARING),
        "support_bore": facets_on_circle(mesh, rings.bore_radius_m, element_mask=body == SUPPORT),
        "support_outer": facets_on_circle(mesh, rings.support_outer_radius_m, element_mask=body == SUPPORT),
        "symmetry": facets_on_symmetry_line(mesh),
    }


def build_mesh(rings: RingPair, spec: MeshSpec = MeshSpec()) -> RingMesh:
    """Mesh both half annuli with gmsh and return a scikit-fem mesh with element bodies.

    Raises
    ------
    InputError
        If the contact size cannot resolve the clearance geometry (``h_contact_m`` larger
        than the thinner ring's thickness).
    """
    t_b = rings.outer_radius_m - rings.inner_radius_m
    t_s = rings.support_outer_radius_m - rings.bore_radius_m
    if spec.h_contact_m > min(t_b, t_s):
        raise InputError(f"h_contact_m = {spec.h_contact_m:g} m: must be <= the thinner ring's "
                         f"thickness {min(t_b, t_s):g} m (mesh too coarse)")
    tags, coords, conn, body = _gmsh_triangles(rings, spec, _size_field(rings, spec))
    mesh = _skfem_mesh(tags, coords, conn, spec.order)
    body = np.concatenate(body)
    mesh = mesh.with_boundaries(_named_boundaries(mesh, rings, body))
    return RingMesh(mesh=mesh, body=body, rings=rings, spec=spec)


def build_mesh_sized(rings: RingPair, size_callback, h_max_m: float, order: int = 2) -> RingMesh:
    """Mesh both half annuli with the element size ``size_callback(x, y)`` [m] (at most ``h_max_m``).

    The meshes of an error-driven sequence (:mod:`fem_reference.plane.adapt`): the size comes from
    the previous mesh's error indicators, not from a family. ``spec`` of the result records
    ``h_max_m`` as its contact size and the order; its other fields do not apply.
    """
    spec = MeshSpec(h_contact_m=h_max_m, order=order)
    tags, coords, conn, body = _gmsh_triangles(rings, spec, repr(float(h_max_m)), size_callback)
    mesh = _skfem_mesh(tags, coords, conn, order)
    body = np.concatenate(body)
    mesh = mesh.with_boundaries(_named_boundaries(mesh, rings, body))
    return RingMesh(mesh=mesh, body=body, rings=rings, spec=spec)


def facets_on_circle(mesh, radius_m: float, rel_tol: float = 1e-6,
                     element_mask: np.ndarray | None = None) -> np.ndarray:
    """Indices of boundary facets whose end points lie on the circle ``|x| = radius_m``.

    ``element_mask`` (bool per element) keeps only facets of those elements (needed at zero
    clearance, where the bearing's outer and the support's inner circle coincide).
    """
    f = mesh.boundary_facets()
    if element_mask is not None:
        f = f[element_mask[mesh.f2t[0, f]]]
    ends = mesh.p[:, mesh.facets[:, f]]  # (2, 2, nf)
    r = np.sqrt((ends ** 2).sum(axis=0))
    on = np.all(np.abs(r - radius_m) <= rel_tol * radius_m, axis=0)
    return f[on]


def facets_on_symmetry_line(mesh, rel_tol: float = 1e-9) -> np.ndarray:
    """Boundary facets on the symmetry line x = 0."""
    f = mesh.boundary_facets()
    x = mesh.p[0, mesh.facets[:, f]]
    scale = np.abs(mesh.p).max()
    return f[np.all(np.abs(x) <= rel_tol * scale, axis=0)]


def refined_uniformly(rmesh: RingMesh) -> RingMesh:
    """``rmesh`` (linear triangles) with every triangle split into four, the new nodes on the rings'
    circles moved radially onto them.

    The nested uniform refinement of the independent references (:mod:`fem_reference.plane.uniform_reference`):
    the element sizes halve everywhere and any a priori grading of the first mesh is kept. A new node
    on a boundary edge whose two ends lie on one of the four circles goes to that circle (the chord's
    midpoint sags ``h²/(8R)`` inside it), so the polygonal boundary converges to the circle.

    Raises
    ------
    InputError
        If ``rmesh`` is not linear (``order`` 2).
    """
    if rmesh.order != 1:
        raise InputError(f"order = {rmesh.order!r}: uniform refinement is for linear triangles (order 1) only")
    old = rmesh.mesh
    fine = MeshTri1(old.p, old.t).refined()
    p = fine.p.copy()
    f = old.boundary_facets()
    ends = old.p[:, old.facets[:, f]]                          # (2, 2, nf)
    r_ends = np.sqrt((ends ** 2).sum(axis=0))                  # (2, nf)
    mid = old.p.shape[1] + f                                   # skfem numbers facet k's new node n_old + k
    rings = rmesh.rings
    for radius in (rings.inner_radius_m, rings.outer_radius_m, rings.bore_radius_m, rings.support_outer_radius_m):
        on = np.all(np.abs(r_ends - radius) <= 1e-6 * radius, axis=0)
        q = p[:, mid[on]]
        p[:, mid[on]] = q * (radius / np.sqrt((q ** 2).sum(axis=0)))
    fine = MeshTri1(np.ascontiguousarray(p), np.ascontiguousarray(fine.t))
    body = np.tile(rmesh.body, 4)                              # skfem's children: four blocks in element order
    fine = fine.with_boundaries(_named_boundaries(fine, rings, body))
    return RingMesh(mesh=fine, body=body, rings=rings, spec=rmesh.spec)
