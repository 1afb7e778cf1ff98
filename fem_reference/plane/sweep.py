"""Reference points with a Richardson error estimate, sweeps, and the committed dataset.

A reference point is solved on three meshes ``h, h/2, h/4`` of one mesh family (all sizes scale
with the contact size ``h``, :class:`~fem_reference.plane.mesh.MeshSpec`, so halving ``h`` is a uniform
refinement); the finest value is reported together with the observed order and an error estimate
(Richardson 1911; Roache 1998):

* mesh family per point: the bore is at size ``h`` only on the possible contact arc, the
  rigid-overlap half-angle ``arccos(δ0/(δ0+Δr))`` + 3° (Dai et al. 2025, Eq. 7; widened if a solved
  arc reaches beyond it), and coarsens along the bore beyond it (size doubling every 10 mm of arc,
  at most 4 h) and away from the contact circle (doubling every 5 mm);
* levels per point: the first level is the coarsest of 4, 2, 1, 0.5, 0.25 mm with at least
  3 elements across the half-arc measured on the coarsest level that resolves the arc (families
  starting finer than 4 mm have their grading lengths scaled alike); a 4th (5th) level is added
  while the estimate misses 0.1 % and the mesh stays below 80k DOFs;
* error estimate: the larger of Roache's GCI (observed order clipped to [0.5, 2], safety 1.25;
  order 0.5 when the sequence is not monotone) and the finest level's error implied by the two
  coarser levels at the nominal order 2 (see :func:`richardson`).

Measured (dataset of 2026-11-22, 2 shared cores): every committed point ≤ 0.1 % estimated error
in ≤ 3 s from scratch (all its levels meshed, factorised and solved); see
``reports/published/fem2d-reference.md``.

Sweep: one :class:`sweep.Task` per scene (its mesh levels are reused along the scene's
penetrations), run by :func:`sweep.run_sweep` (one worker process by default, so every point is
timed alone as before) into a :class:`sweep.ResultStore`: a temporary one, or a directory given
by the caller, which then resumes an interrupted sweep scene by scene.
"""
from __future__ import annotations

import math
import os
import re
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from contact.dataset import read_dataset, write_dataset
from contact.errors import InputError
from contact.package_data import shipped
from fem_reference.plane.contact_solver import ArcNotResolvedError
from fem_reference.plane.mesh import MeshSpec
from fem_reference.plane.solve import ContactModel
from fem_reference.ring_scene import RingScene, from_document, scene_2d
from fem_reference.scenes import Scene
from sweep import ResultStore, Task, code_revision, machine, package_versions, revision_label, run_sweep, utc_stamp

#: the shipped 2D dataset (read through importlib.resources, see contact.package_data)
DATASET_PATH = shipped("fem_reference", "data", "fem2d-reference.json")
DEFAULT_SCENES = ("clamped", "clamped-stress", "persson-40")
DEFAULT_PENETRATIONS_MM = (0.001, 0.002, 0.003, 0.005, 0.0075, 0.01, 0.015, 0.02, 0.025, 0.03, 0.04, 0.05)
DEFAULT_LEVELS_M = (4e-3, 2e-3, 1e-3, 0.5e-3, 0.25e-3)   # finer ones only where needed (see reference_point)
ARC_ELEMENTS_MIN = 3                              # elements across the half-arc on a point's coarsest level
TARGET_ERROR_REL = 1e-3
MAX_DOFS_EXTRA_LEVEL = 80_000                     # no extra level beyond this size (plate scenes)
DEFAULT_ORDER = 2
SOLVER_TOL = 1e-10
# provenance of the dataset: the packages recorded, the sources whose changes mark the revision dirty
PACKAGES = {"numpy": "numpy", "scipy": "scipy", "scikit-fem": "skfem", "gmsh": "gmsh", "meshio": "meshio"}
SOURCES = ("fem_reference", "contact/dataset.py", "sweep")

COLUMNS = {
    "scene": "-", "plane": "-", "penetration_m": "m", "offset_m": "m", "tilt_rad": "rad",
    "force_n": "N", "force_error_rel": "-", "force_observed_order": "-", "force_extrapolated_n": "N",
    "force_levels_n": "N", "half_angle_rad": "rad", "half_angle_error_rel": "-", "half_angle_levels_rad": "rad",
    "peak_pressure_pa": "Pa", "peak_pressure_levels_pa": "Pa", "arc_phi_rad": "rad", "arc_pressure_pa": "Pa",
    "ndofs": "-", "n_multipliers": "-", "iterations": "-", "lcp_method": "-", "kkt_residual": "-",
    "wall_s": "s", "wall_levels_s": "s", "h_contact_m": "m", "h_levels_m": "m", "element_order": "-",
}


@dataclass(frozen=True)
class Richardson:
    """Richardson estimate from three values on meshes h, h/r, h/r²."""

    value: float
    observed_order: float     # NaN when not monotone
    error_abs: float
    extrapolated: float

    @property
    def error_rel(self) -> float:
        return self.error_abs / abs(self.value) if self.value else 0.0


SAFETY_FACTOR = 1.25      # Roache's GCI factor for three-grid studies
MAX_ORDER = 2.0           # the square-root pressure edge limits the force's order (P1 observed ~2)


def richardson(values, ratio: float = 2.0) -> Richardson:
    """Observed order and a conservative error estimate of the finest of three values (coarse → fine).

    error = max(GCI, nominal): ``GCI = 1.25·|d2|/(r^p − 1)`` with the observed order ``p`` clipped to
    [0.5, 2] (Roache 1998), and ``nominal = |d1|/(r²(r² − 1))``, the finest level's error implied by
    the coarse pair at order 2. The second term catches the arc-edge "lucky" cancellations that make
    ``|d2|`` alone too small (measured: Δr = 0.002 mm, 4-2-1 mm, true error 1.3e-4, ``|d2|`` 3.7e-5).
    ``extrapolated`` uses the unclipped observed order when the sequence is monotone, else = finest.
    """
    f1, f2, f3 = (float(v) for v in values)
    d1, d2 = f1 - f2, f2 - f3
    nominal = abs(d1) / (ratio ** MAX_ORDER * (ratio ** MAX_ORDER - 1))
    if d1 * d2 > 0 and abs(d1) > abs(d2):
        p = math.log(d1 / d2) / math.log(ratio)
        pc = min(max(p, 0.5), MAX_ORDER)
        gci = SAFETY_FACTOR * abs(d2) / (ratio ** pc - 1)
        extrap = f3 - d2 / (ratio ** p - 1)
        return Richardson(f3, p, max(gci, nominal), extrap)
    gci = SAFETY_FACTOR * abs(d2) / (ratio ** 0.5 - 1) if d2 else 0.0
    return Richardson(f3, math.nan, max(gci, nominal) if d2 or d1 else 0.0, f3)


ARC_MARGIN_RAD = math.radians(3.0)   # fine zone = rigid-overlap half-angle + this
ARC_GRADING_LENGTH_M = 10e-3          # beyond the zone the bore's element size doubles every 10 mm of arc
ARC_MAX_FACTOR = 4.0                  # ... up to 4 h
GRADING_LENGTH_M = 5e-3               # away from the contact circle the size doubles every 5 mm


def arc_zone_rad(rings, penetration_m: float) -> float:
    """Half-angle [rad] of the bore meshed at size h: the rigid-overlap half-angle + 3°.

    The rigid overlap of the two circles, ``arccos(δ0/t)`` with ``t = δ0 + Δr`` (Dai et al. 2025,
    Eq. 7; docs/reference/contact-laws.md §3), bounds the elastic contact arc from above in every committed scene
    (measured: clamped 10.6° vs 11.4° at Δr = 0.001 mm, persson-40 41.6° vs 60° at 0.05 mm);
    :func:`reference_point` still checks the solved arc against it and widens the zone if needed.
    """
    t = rings.clearance_m + penetration_m
    eps = math.acos(min(1.0, rings.clearance_m / t)) if t > 0 else 0.0
    return min(math.pi, eps + ARC_MARGIN_RAD)


def spec_for(scene: Scene, h_contact_m: float, order: int = DEFAULT_ORDER,
             arc_zone: float = math.pi, grading_scale: float = 1.0) -> MeshSpec:
    """Mesh settings of the reference: size h on the contact circle within ``arc_zone`` [rad] of the
    load axis, doubling every 5 mm away from the circle and every 10 mm of arc beyond the zone (≤ 4 h);
    both grading lengths times ``grading_scale`` (families starting finer than 4 mm)."""
    return MeshSpec(h_contact_m=h_contact_m, order=order, grading_length_m=GRADING_LENGTH_M * grading_scale,
                    arc_zone_rad=arc_zone, arc_grading_length_m=ARC_GRADING_LENGTH_M * grading_scale,
                    arc_max_factor=ARC_MAX_FACTOR)


class Levels:
    """Mesh levels of one scene, built lazily (coarse → fine).

    With ``graded=True`` (default) the meshes are graded along the bore toward the possible
    contact arc of the point being solved (:func:`arc_zone_rad`), so they are rebuilt for each
    penetration (:meth:`use_family`); with ``graded=False`` the whole bore is at size h and the
    meshes are kept for a whole sweep.
    """

    def __init__(self, scene: Scene, levels_m=DEFAULT_LEVELS_M, order: int = DEFAULT_ORDER, graded: bool = True):
        if len(levels_m) < 3:
            raise InputError(f"levels_m = {levels_m!r} m: need at least three mesh sizes (coarse to fine)")
        if np.any(np.diff(levels_m) >= 0):
            raise InputError(f"levels_m = {levels_m!r} m: mesh sizes must strictly decrease (coarse to fine)")
        self.scene, self.levels_m, self.order, self.graded = scene, tuple(levels_m), order, graded
        self.zone_rad, self.scale = math.pi, 1.0
        self._models: dict[int, ContactModel] = {}
        self.build_log: list[tuple[float, int, float]] = []   # (h, ndofs, build_s) of every mesh built

    def use_family(self, zone_rad: float, scale: float = 1.0) -> None:
        """Mesh the levels for this fine zone [rad] and grading scale [-] from now on (drops meshes
        of another family); ungraded levels ignore both."""
        if not self.graded:
            return
        zone_rad, scale = min(math.pi, float(zone_rad)), float(scale)
        if (zone_rad, scale) != (self.zone_rad, self.scale):
            self.zone_rad, self.scale, self._models = zone_rad, scale, {}

    def model(self, i: int) -> ContactModel:
        if i not in self._models:
            spec = spec_for(self.scene, self.levels_m[i], self.order, self.zone_rad, self.scale)
            m = ContactModel.build(self.scene, spec)
            self._models[i] = m
            self.build_log.append((m.spec.h_contact_m, m.ndofs, m.build_s))
        return self._models[i]

    def can_refine(self, i: int) -> bool:
        """Level ``i`` exists and is built or predicted (~3.6x DOFs per halving from the finest built
        coarser level) to stay within MAX_DOFS_EXTRA_LEVEL."""
        if i >= len(self.levels_m):
            return False
        if i in self._models:
            return True
        coarser = [j for j in self._models if j < i]
        if not coarser:
            return True
        j = max(coarser)
        return self._models[j].ndofs * 3.6 ** (i - j) <= MAX_DOFS_EXTRA_LEVEL

    def built(self) -> list[ContactModel]:
        return [self._models[i] for i in sorted(self._models)]


def _solve_levels(levels: Levels, penetration_m: float, target_rel: float):
    """Three (or more) consecutive levels resolving the arc; returns (first level, solutions, models).

    The first level is the coarsest one with at least ``ARC_ELEMENTS_MIN`` elements across the
    half-arc measured on the coarsest level that resolves it (levels too coarse for a tiny arc
    raise ArcNotResolvedError and are skipped), so every point's sequence starts in the same
    relative resolution; finer levels are added while the estimate misses ``target_rel``.
    Graded levels starting finer than the coarsest level are meshed with grading lengths scaled by
    ``h_first / h_coarsest`` (:meth:`Levels.use_family`), so every point's family has the same
    size gradients on its own first level.
    """
    sizes = levels.levels_m
    i, probe = 0, None
    while probe is None:
        if not levels.can_refine(i):
            raise ArcNotResolvedError(
                f"penetration_m = {penetration_m:g} m: no affordable mesh level of {sizes} m resolves the "
                "contact arc; add finer levels")
        try:
            probe = levels.model(i).solve(penetration_m, tol=SOLVER_TOL)
        except ArcNotResolvedError:
            i += 1
    half_arc_m = levels.scene.rings.bore_radius_m * probe.half_angle_rad
    first = i
    while first + 1 < len(sizes) and sizes[first] > half_arc_m / ARC_ELEMENTS_MIN:
        first += 1
    family = (levels.zone_rad, levels.scale)
    levels.use_family(levels.zone_rad, sizes[first] / sizes[0])
    sols = [probe] if first == i and (levels.zone_rad, levels.scale) == family else []
    while len(sols) < 3:
        k = first + len(sols)
        if not levels.can_refine(k):
            raise ArcNotResolvedError(
                f"penetration_m = {penetration_m:g} m: the contact arc (half-length {half_arc_m:g} m) needs levels "
                f"from {sizes[first]:g} m on, and fewer than three of the affordable mesh levels {sizes} m are "
                "that fine; add finer levels")
        try:
            sols.append(levels.model(k).solve(penetration_m, tol=SOLVER_TOL))
        except ArcNotResolvedError:
            first, sols = k + 1, []
    rf = richardson([s.force_n for s in sols[-3:]])
    while rf.error_rel > target_rel and levels.can_refine(first + len(sols)):
        sols.append(levels.model(first + len(sols)).solve(penetration_m, tol=SOLVER_TOL))
        rf = richardson([s.force_n for s in sols[-3:]])
    return first, sols, [levels.model(first + k) for k in range(len(sols))]


def reference_point(levels: Levels, penetration_m: float, target_rel: float = TARGET_ERROR_REL) -> dict:
    """Solve one penetration on three levels; add a finer one while the estimate misses the target.

    The finest level used is reported, with the Richardson estimate of the last three levels.
    Graded levels are meshed for this point's possible contact arc (:func:`arc_zone_rad`); if a
    solved arc reaches beyond that zone, the zone is widened and the point solved again.
    ``wall_levels_s`` is the whole point from scratch: every mesh built for it, assembly,
    factorisation and all contact solves.
    """
    t_start = time.perf_counter()
    zone = arc_zone_rad(levels.scene.rings, penetration_m)
    while True:
        levels.use_family(zone, 1.0)
        first, sols, used = _solve_levels(levels, penetration_m, target_rel)
        reach = max((float(s.arc_phi_rad[s.arc_pressure_pa > 0].max(initial=0.0)) for s in sols), default=0.0)
        if not levels.graded or levels.zone_rad >= math.pi or reach <= levels.zone_rad:
            break
        zone = min(math.pi, reach + 2 * ARC_MARGIN_RAD)   # the arc left the fine zone: widen it, solve again
    wall_point = time.perf_counter() - t_start
    rf = richardson([s.force_n for s in sols[-3:]])
    fine = sols[-1]
    ra = richardson([s.half_angle_rad for s in sols[-3:]])
    act = np.flatnonzero(fine.arc_pressure_pa > 0)
    keep = slice(0, min(len(fine.arc_phi_rad), (act[-1] + 3) if len(act) else 1))
    scene = levels.scene
    return {
        "scene": scene.name, "plane": scene.plane, "penetration_m": float(penetration_m),
        "offset_m": fine.offset_m, "tilt_rad": 0.0,
        "force_n": fine.force_n, "force_error_rel": rf.error_rel,
        "force_observed_order": None if math.isnan(rf.observed_order) else rf.observed_order,
        "force_extrapolated_n": rf.extrapolated, "force_levels_n": [s.force_n for s in sols],
        "half_angle_rad": fine.half_angle_rad, "half_angle_error_rel": ra.error_rel,
        "half_angle_levels_rad": [s.half_angle_rad for s in sols],
        "peak_pressure_pa": fine.peak_pressure_pa, "peak_pressure_levels_pa": [s.peak_pressure_pa for s in sols],
        "arc_phi_rad": fine.arc_phi_rad[keep], "arc_pressure_pa": fine.arc_pressure_pa[keep],
        "ndofs": fine.ndofs, "n_multipliers": fine.n_multipliers, "iterations": fine.iterations,
        "lcp_method": fine.method, "kkt_residual": fine.kkt_residual,
        "wall_s": fine.wall_s, "wall_levels_s": wall_point,
        "h_contact_m": used[-1].spec.h_contact_m, "h_levels_m": [m.spec.h_contact_m for m in used],
        "element_order": used[-1].spec.order,
    }


def scene_task(scene: str, penetrations_m: list[float], levels_m: list[float], order: int,
               ring_scene: dict | None = None) -> tuple[dict, dict]:
    """All points of one scene as a :class:`sweep.Task` function: ``({}, {"points": [...], "build": {...}})``.

    ``scene`` is a scene name (:func:`fem_reference.ring_scene.scene_2d`) unless ``ring_scene``, the
    normalised document of a ring-pair file (:attr:`~fem_reference.ring_scene.RingScene.document`),
    defines it. The scene's mesh levels are built once (:class:`Levels`) and reused along its penetrations.
    """
    sc = _resolved(from_document(ring_scene, scene)).scene if ring_scene is not None else scene_2d(scene)
    levels = Levels(sc, tuple(levels_m), order)
    points = [reference_point(levels, dr) for dr in penetrations_m]
    log = levels.build_log
    build = {"total_s": sum(b[2] for b in log), "meshes_built": len(log), "largest_ndofs": max(b[1] for b in log)}
    return {}, {"points": points, "build": build}


def _resolved(rs: RingScene) -> RingScene:
    """``rs`` if its plane is set; a file left at ``plane = "auto"`` is refused (its placeholder is not an answer)."""
    if rs.plane_auto:
        raise InputError(f"ring pair {rs.name!r}: plane = 'auto' not resolved: the 2D sweep needs the plane the 3D check "
                         "chose (fem_reference.plane_check.resolve)")
    return rs


def _scene_key(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.+-]", "_", name)


def _row(info: dict) -> dict:
    """A stored point as a dataset row, fields in :data:`COLUMNS` order."""
    rank = {k: i for i, k in enumerate(COLUMNS)}
    return {k: info[k] for k in sorted(info, key=lambda k: rank.get(k, len(rank)))}


def _run_scenes(tasks: list[Task], store, workers: int, executor, progress) -> list[dict]:
    """Run the scene tasks into ``store`` (a temporary directory if None); their stored infos in order."""
    with tempfile.TemporaryDirectory(prefix="fem2d-sweep-") as tmp:
        st = ResultStore(tmp if store is None else store)
        summary = run_sweep(tasks, st, executor=executor, max_workers=workers, progress=progress,
                            label="fem sweep", manifest={"sweep": "fem2d"})
        failed = [t.key for t in tasks if t.key in summary.errors]
        if failed:
            exc = summary.errors[failed[0]]
            kept = "" if store is None else f"; finished scenes kept in {st.root}"
            exc.add_note(f"fem sweep: scenes {failed} failed{kept}")
            raise exc
        return [st.load(t.key, t.params).info for t in tasks]


def sweep_dataset(scene_names=DEFAULT_SCENES, penetrations_m=None, levels_m=DEFAULT_LEVELS_M,
                  order: int = DEFAULT_ORDER, progress: bool | None = None, workers: int = 1, executor=None,
                  store: str | os.PathLike | None = None, per_point: bool = False) -> tuple[dict, list[dict]]:
    """Solve every (scene, penetration); returns (metadata, points).

    ``scene_names``: scene names (bundled ring-pair files or generated names, see
    :func:`fem_reference.ring_scene.scene_2d`) or :class:`~fem_reference.ring_scene.RingScene` objects.

    One task per scene through :func:`sweep.run_sweep`: ``workers`` local processes (default 1:
    every point timed alone), or ``executor`` (a process pool or a dask client; gmsh's Ctrl-C handler
    is installed only from a main thread, so a dask worker's task threads mesh too). ``store``: directory of a
    :class:`sweep.ResultStore` keeping finished scenes, so a repeated call resumes (default: a
    temporary one, nothing kept). ``per_point``: one task per (scene, penetration) instead of one per
    scene (finer resume and progress, points in parallel; the same numbers, since the graded levels
    are meshed for each point anyway).
    """
    if penetrations_m is None:
        penetrations_m = [v * 1e-3 for v in DEFAULT_PENETRATIONS_MM]
    t0 = time.perf_counter()
    load_start = round(os.getloadavg()[0], 2)
    scenes = [_resolved(n).scene if isinstance(n, RingScene) else scene_2d(n) for n in scene_names]
    common = {"penetrations_m": [float(d) for d in penetrations_m], "levels_m": [float(h) for h in levels_m],
              "order": int(order)}
    def params(n, sc, pens):
        return {"scene": sc.name, **common, "penetrations_m": pens,
                **({"ring_scene": n.document} if isinstance(n, RingScene) else {})}

    pens = common["penetrations_m"]
    if per_point:
        tasks = [Task(f"{_scene_key(sc.name)}.p{i:03d}", scene_task, params(n, sc, [d]))
                 for n, sc in zip(scene_names, scenes) for i, d in enumerate(pens)]
    else:
        tasks = [Task(_scene_key(sc.name), scene_task, params(n, sc, pens)) for n, sc in zip(scene_names, scenes)]
    results = _run_scenes(tasks, store, workers, executor, progress)
    points = [_row(p) for r in results for p in r["points"]]
    per_scene = len(results) // len(scenes)
    builds = {}
    for k, sc in enumerate(scenes):
        rs = [r["build"] for r in results[k * per_scene:(k + 1) * per_scene]]
        builds[sc.name] = {"total_s": sum(b["total_s"] for b in rs), "meshes_built": sum(b["meshes_built"] for b in rs),
                           "largest_ndofs": max(b["largest_ndofs"] for b in rs)}
    meta = _metadata(scenes, levels_m, order, load_start)
    meta["timings"] = {"total_s": time.perf_counter() - t0, "build": builds}
    return meta, points


def _metadata(scenes: list[Scene], levels_m, order: int, load_start: float) -> dict:
    return {
        "title": "2D ring-in-ring FEM reference (gmsh + scikit-fem, frictionless mortar contact)",
        "created_utc": utc_stamp(),
        "code_revision": revision_label(code_revision(scope=SOURCES, untracked=True)),
        "package_versions": package_versions(PACKAGES),
        "machine": {**machine(), "load_average_1min_at_start": load_start},
        "scenes": {s.name: s.to_dict() for s in scenes},
        "mesh": {"levels_h_contact_m": list(levels_m), "element_order": order,
                 "extra_levels": f"per point, three consecutive levels from the coarsest with >= {ARC_ELEMENTS_MIN} "
                                 "elements across the half-arc measured on the coarsest level resolving it; a further "
                                 f"level while the 3-level estimate exceeds {TARGET_ERROR_REL:g} and the level stays "
                                 f"below {MAX_DOFS_EXTRA_LEVEL} DOFs",
                 "grading": "per point: size = h·(1+2·max(0,−y)/R)·(1+d/L)·min(4, 1+R·max(0, φ−φz)/La), "
                            f"d = distance from the contact circle (radius R), L = {GRADING_LENGTH_M * 1e3:g} mm, "
                            f"φ = angle from the load axis, φz = rigid-overlap half-angle arccos(δ0/(δ0+Δr)) + "
                            f"{math.degrees(ARC_MARGIN_RAD):g}° (widened if a solved arc reaches beyond it), "
                            f"La = {ARC_GRADING_LENGTH_M * 1e3:g} mm; L and La times h_first/4 mm for points whose "
                            "levels start finer than 4 mm; all sizes scale with h",
                 "model": "half model x >= 0, u_x = 0 on x = 0"},
        "solver": {"method": "mortar (P1 multipliers on the support bore), gap of exact circles for the "
                             "rigid offset; condensed QP solved by primal-dual active set, NNLS fallback",
                   "kkt_tolerance": SOLVER_TOL},
        "definitions": {
            "penetration_m": "Δr = t − δ0, t = drive displacement of the bearing along +y",
            "force_n": "reaction of the driven surface = total contact force, full ring, times width l0",
            "half_angle_rad": "edge of the contact arc from the load axis (p² fit, see contact_solver)",
            "force_error_rel": "Richardson estimate of the finest level's relative error (see sweep.py)",
            "wall_s": "wall time of the finest level's contact solve",
            "wall_levels_s": "wall time of the whole point from scratch: every mesh of all its levels built, "
                             "assembled, factorised and solved",
        },
    }


def regenerate(path, **kw) -> Path:
    """Run the default sweep and write it (atomically) to ``path``."""
    meta, points = sweep_dataset(**kw)
    return write_dataset(path, meta, COLUMNS, points)


def check_against_committed(path=DATASET_PATH, n_points: int = 3, scene_names=None) -> list[dict]:
    """Recompute a few committed points; returns rows with committed/new force and the difference."""
    ds = read_dataset(path)
    levels = tuple(ds.metadata["mesh"]["levels_h_contact_m"])
    order = int(ds.metadata["mesh"]["element_order"])
    rows = []
    for name in scene_names or ds.scenes():
        pts = ds.select(scene=name)
        idx = np.unique(np.linspace(0, len(pts) - 1, n_points).round().astype(int))
        own = ds.metadata.get("ring_scene") or {}       # a ring-pair file's dataset carries its document
        sc = from_document(own["document"], name).scene if own.get("name") == name else scene_2d(name)
        lv = Levels(sc, levels, order)
        for i in idx:
            old = pts[i]
            new = reference_point(lv, old["penetration_m"])
            rows.append({"scene": name, "penetration_m": old["penetration_m"], "committed_force_n": old["force_n"],
                         "new_force_n": new["force_n"], "diff_rel": new["force_n"] / old["force_n"] - 1
                         if old["force_n"] else new["force_n"],
                         "committed_half_angle_rad": old["half_angle_rad"], "new_half_angle_rad": new["half_angle_rad"],
                         "error_estimate_rel": old["force_error_rel"]})
    return rows
