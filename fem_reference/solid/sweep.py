"""3D reference points with error estimates, executor-based resumable sweeps, the 3D dataset.

A reference point (penetration at the mid-plane, tilt) is solved on the three levels of
:data:`fem_reference.solid.mesh.DEFAULT_LEVELS`; the finest value is reported with an error
estimate from Richardson extrapolation (:mod:`fem_reference.solid.richardson`), and the point is
also solved on the finer check level :data:`fem_reference.solid.mesh.CHECK_LEVEL`
(``force_finer_n``, ``moment_finer_nm``): tests/fem_reference/solid/test_fem3d_dataset.py asserts
that each stated error bounds the difference to that finer solve.

Compute layout: the expensive part of a mesh level (assembly, factorisation, contact compliance,
see solve3d) depends only on the mesh and the scene, so it is built once per level, cached on
disk (``RINGCONTACT_CACHE`` or ``~/.cache/ringcontact/fem3d``) and shared by every point. Points
are independent :class:`sweep.Task` run by :func:`sweep.run_sweep` on a
:class:`concurrent.futures.Executor` (a process pool locally; a ``dask.distributed.Client`` is
such an executor too). Each finished point is kept at once in a checksummed
:class:`sweep.ResultStore` under the cache (``sweeps/<key of the mesh levels>``), so an
interrupted sweep resumes where it stopped.
"""
from __future__ import annotations

import concurrent.futures as cf
import dataclasses
import hashlib
import json
import math
import os
import time
from pathlib import Path

import numpy as np

from contact.dataset import read_dataset, write_dataset
from contact.errors import ConvergenceError, DatasetError, InputError
from contact.package_data import shipped
from contact.units import ARCMIN, MM
from fem_reference.solid.geometry import RigidMotion, RingPair3D
from fem_reference.solid.mesh import CHECK_LEVEL, DEFAULT_LEVELS, LEVELS, MeshLevel3D
from fem_reference.solid.richardson import ASSUMED_ORDERS, apply_orders, pooled_orders, richardson3
from fem_reference.solid.solve import (SCENES, ContactCompliance, build_compliance, load_compliance,
                                       save_compliance, solve_point)
from sweep import (ResultStore, Task, as_executor, code_revision, local_pool, machine, package_versions,
                   revision_label, run_sweep, utc_stamp)
from contact.threads import thread_share

#: the shipped 3D dataset (read through importlib.resources, see contact.package_data)
DATASET_PATH = shipped("fem_reference", "data", "3d", "fem3d-reference.json")
DEFAULT_TILTS_ARCMIN = (0.0, 0.5, 1.0, 2.0, 30.0)
DEFAULT_PENETRATIONS_MM = (0.005, 0.01, 0.02, 0.03, 0.04, 0.05)
CODE_VERSION = "fem3d-2"      # bump when the compliance computation changes (invalidates the cache)
MIN_ACTIVE_LINES = 3          # axial multiplier lines in contact needed for a reference point
# provenance of the dataset: the packages recorded, the sources whose changes mark the revision dirty
PACKAGES = {"numpy": "numpy", "scipy": "scipy", "scikit-fem": "skfem", "gmsh": "gmsh", "meshio": "meshio"}
SOURCES = ("fem_reference", "contact/dataset.py", "sweep")

COLUMNS = {
    "scene": "-", "penetration_m": "m", "offset_m": "m", "tilt_rad": "rad",
    "force_n": "N", "force_error_rel": "-", "force_observed_order": "-", "force_extrapolated_n": "N",
    "force_levels_n": "N",
    "moment_nm": "N*m", "moment_error_rel": "-", "moment_observed_order": "-", "moment_extrapolated_nm": "N*m",
    "moment_levels_nm": "N*m",
    "width_m": "m", "width_levels_m": "m", "width_law_m": "m", "contact_x_min_m": "m", "contact_x_max_m": "m",
    "load_centre_x_m": "m", "edges_loaded": "-", "sides": "-", "force_minus_y_side_n": "N",
    "half_angle_rad": "rad", "peak_pressure_pa": "Pa",
    "pressure_phi_rad": "rad", "pressure_x_m": "m", "pressure_map_pa": "Pa",
    "force_finer_n": "N", "moment_finer_nm": "N*m", "finer_level": "-",
    "ndofs": "-", "ndofs_levels": "-", "n_pairs": "-", "n_active": "-", "iterations": "-", "lcp_method": "-",
    "level_build_s": "s", "level_load_s": "s", "solve_s": "s", "wall_s": "s",
    "levels": "-", "element_order": "-", "method": "-",
}


# ----------------------------------------------------------------------------------------------
# compliance cache

def cache_dir() -> Path:
    """Where mesh-level compliances and finished sweep points are kept."""
    root = os.environ.get("RINGCONTACT_CACHE")
    return Path(root) if root else Path.home() / ".cache" / "ringcontact" / "fem3d"


def _key(obj) -> str:
    return hashlib.sha256(json.dumps(obj, sort_keys=True).encode()).hexdigest()[:16]


def compliance_path(geom: RingPair3D, level: MeshLevel3D, scene: str, cache: Path | None = None) -> Path:
    cache = cache_dir() if cache is None else Path(cache)
    k = _key({"v": CODE_VERSION, "geom": geom.as_dict(), "level": level.as_dict(), "scene": scene})
    return cache / f"compliance-{scene}-{level.name}-{k}.npz"


def get_compliance(geom: RingPair3D, level: MeshLevel3D, scene: str = "clamped", cache: Path | None = None,
                   use_cache: bool = True) -> ContactCompliance:
    """The compliance of one level: from the cache if there and readable, else built (and cached).

    A cached file that does not load (truncated, corrupted, another format) is rebuilt over.
    """
    path = compliance_path(geom, level, scene, cache)
    if use_cache and path.exists():
        try:
            return load_compliance(path)
        except DatasetError:
            pass                         # corrupt cache entry: rebuilt and rewritten below
    comp = build_compliance(geom, level, scene)
    if use_cache:
        save_compliance(comp, path)
    return comp


def _build_task(geom: RingPair3D, level: MeshLevel3D, scene: str, cache: str) -> tuple[str, float]:
    comp = build_compliance(geom, level, scene)
    path = compliance_path(geom, level, scene, Path(cache))
    save_compliance(comp, path)
    return str(path), comp.build_s


_LOADED: dict[str, ContactCompliance] = {}


def _load_cached(path: str) -> ContactCompliance:
    """A level kept in this process's memory (then ``load_s`` = 0), else read from the cache file."""
    if path in _LOADED:
        return dataclasses.replace(_LOADED[path], load_s=0.0)
    if len(_LOADED) > 6:              # a worker keeps at most a few levels in memory
        _LOADED.clear()
    _LOADED[path] = load_compliance(path)
    return _LOADED[path]


# ----------------------------------------------------------------------------------------------
# one reference point

def _edge_resolution_check(comps, sols, penetration_m: float, tilt_rad: float) -> None:
    """ConvergenceError if a level resolves the contact patch by fewer than MIN_ACTIVE_LINES axial lines."""
    for c, s in zip(comps, sols):
        if 0 < s.n_active_lines < MIN_ACTIVE_LINES:
            h_edge = float(c.mortar_x.vertices[1] - c.mortar_x.vertices[0])
            raise ConvergenceError(
                f"contact patch not resolved on level {c.level.name}: {s.n_active_lines} axial line(s) in "
                f"contact (width about {s.contact_width_m * 1e3:.2f} mm, law {s.contact_width_law_m * 1e3:.2f} mm; "
                f"edge element {h_edge * 1e3:.2f} mm; need >= {MIN_ACTIVE_LINES} lines): use the edge-refined "
                f"levels (EDGE_LEVELS, `fem3d point --edge-refined`) for penetration {penetration_m * 1e3:g} mm, "
                f"tilt {tilt_rad / ARCMIN:g} arcmin")


def _solve_levels(comps, motion):
    sols = []
    for c in comps:
        try:
            sols.append(solve_point(c, motion))
        except ConvergenceError as exc:
            raise ConvergenceError(f"level {c.level.name} ({c.n_dofs} DOFs): {exc}") from exc
    return sols


def reference_point(comps: list[ContactCompliance], penetration_m: float, tilt_rad: float,
                    check: ContactCompliance | None = None, orders: dict | None = None) -> dict:
    """Solve one (penetration, tilt) on every level; the finest is reported with its error estimate.

    ``check``, if given, is a finer level solved as well (``force_finer_n``, ``moment_finer_nm``):
    the committed test that the stated errors bound the difference to a finer solve. ``orders``
    (``{"force": p, "moment": p}``) is the convergence order the error estimate assumes
    (default :data:`~fem_reference.solid.richardson.ASSUMED_ORDERS`).

    Raises
    ------
    ConvergenceError
        If any level fails (message names the level), or a level resolves the contact patch by
        fewer than ``MIN_ACTIVE_LINES`` axial multiplier lines (edge-only contact with width << l0
        on levels not refined toward the edges): a number from such a mesh is not a reference.
    """
    geom = comps[-1].geom
    orders = ASSUMED_ORDERS if orders is None else orders
    motion = RigidMotion.from_penetration(geom, penetration_m, tilt_rad)
    sols = _solve_levels(comps, motion)
    _edge_resolution_check(comps, sols, penetration_m, tilt_rad)
    finer = _solve_levels([check], motion)[0] if check is not None else None
    fine = sols[-1]
    nd = [c.n_dofs for c in comps]
    rf = richardson3([s.force_n for s in sols], nd, orders["force"])
    rm = richardson3([s.moment_z_nm for s in sols], nd, orders["moment"])
    rows = np.flatnonzero(fine.pressure_pa.max(axis=1) > 0)
    keep = np.arange(0, 0) if rows.size == 0 else np.unique(np.concatenate(
        [rows, np.clip(rows + 1, 0, len(fine.phi_grid) - 1), np.clip(rows - 1, 0, len(fine.phi_grid) - 1)]))
    force = fine.force_n
    moment_rel = (rm["error_abs"] / abs(rm["value"])) if (tilt_rad != 0 and rm["value"] != 0) else None
    used = list({c.level.name: c for c in comps + ([check] if check is not None else [])}.values())
    solve_s = sum({c.level.name: s.solve_s for c, s in zip(comps, sols)}.values()) + (finer.solve_s if finer else 0.0)
    load_s = sum(c.load_s for c in used)
    return {
        "scene": comps[-1].scene, "penetration_m": float(penetration_m), "offset_m": motion.translation_m,
        "tilt_rad": float(tilt_rad),
        "force_n": force, "force_error_rel": rf["error_abs"] / abs(force) if force else 0.0,
        "force_observed_order": rf["order"], "force_extrapolated_n": rf["extrapolated"],
        "force_levels_n": [s.force_n for s in sols],
        "moment_nm": fine.moment_z_nm, "moment_error_rel": moment_rel, "moment_observed_order": rm["order"],
        "moment_extrapolated_nm": rm["extrapolated"], "moment_levels_nm": [s.moment_z_nm for s in sols],
        "width_m": fine.contact_width_m, "width_levels_m": [s.contact_width_m for s in sols],
        "width_law_m": fine.contact_width_law_m, "contact_x_min_m": fine.contact_x_min_m,
        "contact_x_max_m": fine.contact_x_max_m, "load_centre_x_m": fine.load_centre_x_m,
        "edges_loaded": fine.edges_loaded, "sides": fine.sides, "force_minus_y_side_n": fine.force_minus_y_side_n,
        "half_angle_rad": fine.contact_half_angle_rad, "peak_pressure_pa": fine.peak_pressure_pa,
        "pressure_phi_rad": fine.phi_grid[keep], "pressure_x_m": fine.x_grid,
        "pressure_map_pa": [[float(f"{v:.6g}") for v in row] for row in fine.pressure_pa[keep]],
        "force_finer_n": finer.force_n if finer is not None else None,
        "moment_finer_nm": finer.moment_z_nm if finer is not None else None,
        "finer_level": check.level.name if check is not None else None,
        "ndofs": fine.n_dofs, "ndofs_levels": nd, "n_pairs": fine.n_pairs, "n_active": fine.n_active,
        "iterations": fine.iterations, "lcp_method": fine.lcp_method,
        "level_build_s": sum(c.build_s for c in used), "level_load_s": load_s, "solve_s": solve_s,
        "wall_s": load_s + solve_s,
        "levels": [c.level.name for c in comps], "element_order": comps[-1].level.order,
        "method": comps[-1].level.method,
    }


def point_task(paths: list[str], penetration_m: float, tilt_rad: float, check_path: str | None = None
               ) -> tuple[dict, dict]:
    """One sweep point as a :class:`sweep.Task` function: no arrays, the dataset row as JSON ``info``."""
    check = _load_cached(check_path) if check_path else None
    return {}, _jsonable(reference_point([_load_cached(p) for p in paths], penetration_m, tilt_rad, check))


# ----------------------------------------------------------------------------------------------
# sweep

def _point_key(penetration_m: float, tilt_rad: float) -> str:
    return f"pen{penetration_m * 1e9:.0f}nm-tilt{tilt_rad * 1e9:.0f}nrad"


def point_store(paths: list[Path], cache: Path | None = None) -> ResultStore:
    """The store of finished points of one set of mesh levels (their compliance files) under the cache."""
    cache = cache_dir() if cache is None else Path(cache)
    return ResultStore(cache / "sweeps" / _key({"v": CODE_VERSION, "paths": [Path(p).name for p in paths]}))


def _mesh_levels(level_names) -> list[MeshLevel3D]:
    if len(level_names) != 3:
        raise InputError(f"level_names = {level_names!r}: need exactly three mesh levels (coarse to fine)")
    unknown = [n for n in level_names if not isinstance(n, MeshLevel3D) and n not in LEVELS]
    if unknown:
        raise InputError(f"mesh levels {unknown} unknown: choose from {sorted(LEVELS)}")
    return [n if isinstance(n, MeshLevel3D) else LEVELS[n] for n in level_names]


def _compliances(ex, geom: RingPair3D, levels: list[MeshLevel3D], scene: str, cache: Path):
    """Build (through ``ex``) the levels not cached yet; returns (paths, build seconds per level)."""
    paths = [compliance_path(geom, lv, scene, cache) for lv in levels]
    todo = {ex.submit(_build_task, geom, lv, scene, str(cache)): lv.name
            for lv, p in zip(levels, paths) if not p.exists()}
    builds = {}
    for fut in cf.as_completed(todo):
        builds[todo[fut]] = fut.result()[1]
    for lv, p in zip(levels, paths):
        if lv.name not in builds:
            builds[lv.name] = load_compliance(p).build_s
    return paths, builds


def _failed(summary, tasks: list[Task], store: ResultStore) -> Exception:
    """The first failed point's own exception, noting how many failed and where the rest is kept."""
    keys = [t.key for t in tasks if t.key in summary.errors]
    exc = summary.errors[keys[0]]
    exc.add_note(f"fem3d sweep: {len(keys)} of {len(tasks)} points failed ({', '.join(keys[:5])}); "
                 f"finished points are kept in {store.root}")
    return exc


def sweep_dataset(tilts_rad=None, penetrations_m=None, level_names=DEFAULT_LEVELS, scene: str = "clamped",
                  geom: RingPair3D | None = None, workers: int = 2, executor: cf.Executor | None = None,
                  cache: Path | None = None, progress: bool | None = None, resume: bool = True,
                  check_level="auto", label: str | None = None, description: str | None = None
                  ) -> tuple[dict, list[dict]]:
    """Solve every (tilt, penetration) through an executor; returns (metadata, points).

    Parameters
    ----------
    tilts_rad, penetrations_m : sequences of float
        Defaults :data:`DEFAULT_TILTS_ARCMIN` and :data:`DEFAULT_PENETRATIONS_MM` in SI.
    level_names : sequence of str or MeshLevel3D
        Three levels (coarse -> fine), names from :data:`~fem_reference.solid.mesh.LEVELS`.
    workers : int
        Processes of the local pool (ignored if ``executor`` is given).
    executor : concurrent.futures.Executor, optional
        e.g. a ``dask.distributed.Client``; must see the same cache directory.
    resume : bool
        Reuse finished points kept in the store under the cache (:func:`point_store`) from an
        interrupted run of the same sweep.
    check_level : str, MeshLevel3D or None
        The finer level every point is also solved on (``force_finer_n``, ``moment_finer_nm``);
        "auto": :data:`~fem_reference.solid.mesh.CHECK_LEVEL` for the default levels, else none.
    label, description : str, optional
        The ``scene`` column of every point (default ``scene``, the boundary conditions, which
        ``metadata["boundary_conditions"]`` keeps) and its description, e.g. a ring-pair file's.

    Notes
    -----
    Local workers run with the BLAS/OpenMP threads of their share of the machine
    (:func:`contact.threads.thread_share`), set before numpy loads in them.

    Raises the first failed point's exception once every other point is computed and kept.
    """
    if tilts_rad is None:
        tilts_rad = [t * ARCMIN for t in DEFAULT_TILTS_ARCMIN]
    if penetrations_m is None:
        penetrations_m = [p * MM for p in DEFAULT_PENETRATIONS_MM]
    levels = _mesh_levels(level_names)
    if check_level == "auto":
        check_level = CHECK_LEVEL if tuple(level_names) == DEFAULT_LEVELS else None
    check = None if check_level is None else _mesh_levels([levels[0], levels[1], check_level])[2]
    if scene not in SCENES:
        raise InputError(f"scene = {scene!r}: must be one of {sorted(SCENES)}")
    geom = geom or RingPair3D()
    cache = cache_dir() if cache is None else Path(cache)
    t0 = time.perf_counter()
    own = executor is None
    # local workers die with this process and use their share of the cores for BLAS/OpenMP
    ex = local_pool(workers, threads_per_worker=thread_share(workers)) if own else as_executor(executor)
    try:
        paths, builds = _compliances(ex, geom, levels + ([check] if check else []), scene, cache)
        check_path = str(paths.pop()) if check else None
        store = point_store(paths + ([check_path] if check else []), cache)
        tasks = [Task(_point_key(float(d), float(t)), point_task,
                      {"paths": [str(p) for p in paths], "penetration_m": float(d), "tilt_rad": float(t),
                       "check_path": check_path})
                 for t in tilts_rad for d in penetrations_m]
        summary = run_sweep(tasks, store, executor=ex, progress=progress, label="fem3d sweep", resume=resume,
                            manifest={"sweep": "fem3d", "scene": scene, "geometry": geom.as_dict(),
                                      "levels": [lv.as_dict() for lv in levels],
                                      "check_level": check.as_dict() if check else None})
    finally:
        if own:
            ex.shutdown(wait=True, cancel_futures=True)
    if summary.failed:
        raise _failed(summary, tasks, store)
    points = [_row(store.load(t.key, t.params).info) for t in tasks]
    orders = pooled_orders(points)
    points = [apply_orders(p, orders) for p in points]
    if label is not None:
        points = [{**p, "scene": label} for p in points]
    meta = _metadata(geom, scene, levels, points, tilts_rad, penetrations_m, workers if own else "external executor")
    if label is not None:
        meta["scenes"] = {label: description or SCENES[scene]}
    meta["mesh"]["check_level"] = check.as_dict() if check else None
    meta["error_orders"] = orders
    meta["timings"] = {"total_s": time.perf_counter() - t0, "compliance_build_s": builds}
    return meta, points


def _row(info: dict) -> dict:
    """A stored point as a dataset row, fields in :data:`COLUMNS` order."""
    rank = {k: i for i, k in enumerate(COLUMNS)}
    return {k: info[k] for k in sorted(info, key=lambda k: rank.get(k, len(rank)))}


def _metadata(geom: RingPair3D, scene: str, levels: list[MeshLevel3D], points: list[dict], tilts_rad,
              penetrations_m, workers) -> dict:
    return {
        "title": "3D tilted ring-in-ring FEM reference (circumferential harmonics on quadratic sections, "
                 "frictionless mortar contact)",
        "created_utc": utc_stamp(),
        "code_revision": revision_label(code_revision(scope=SOURCES, untracked=True)),
        "package_versions": package_versions(PACKAGES),
        "machine": machine(),
        "scenes": {scene: SCENES[scene]},
        "boundary_conditions": scene,
        "geometry": geom.as_dict(),
        "mesh": {"levels": [lv.as_dict() for lv in levels], "ndofs_levels": points[0]["ndofs_levels"] if points else [],
                 "model": "full rings of revolution; per level: 9-node quadratic (x, r) sections graded toward the "
                          "ring edges and the contact surfaces, harmonics cos/sin(n phi) for n = 0 .. n_harmonics; "
                          "contact pressure symmetric about z = 0 (half model of the multipliers, phi in [0, pi])"},
        "solver": {"method": "rigid motion split off (strain-free); per level and harmonic one SuperLU factor "
                             "(MMD on A'+A) of the section stiffness; mortar compliance A = sum_n (2/pi_n) J_n J_n^T "
                             "(x) X_n of bilinear pressure multipliers formed once (fem_reference/solid/fourier.py); "
                             "LCP b + A lam >= 0 solved exactly by primal-dual active set (NNLS fallback); "
                             "complementarity verified on all multipliers",
                   "gap": "exact tilted cylinders (geometry.rigid_gap_m) weighted by the multipliers (5-point Gauss "
                          "per element and direction), elastic part linearised radially"},
        "sweep": {"tilts_rad": [float(t) for t in tilts_rad], "penetrations_m": [float(d) for d in penetrations_m],
                  "workers": workers},
        "definitions": {
            "penetration_m": "mid-plane penetration Delta r = r - delta0 (r = bearing translation along +y)",
            "tilt_rad": "tilt theta about +z through the ring centre: a point at axial x moves by r + theta*x",
            "force_n": "load = minus the y-force of the contact on the bearing, full ring",
            "moment_nm": "moment about +z through the ring centre of the contact force on the bearing, full "
                         "ring (docs/reference/contact-laws.md sec. 1: M_z = x F_y; negative for a positive tilt)",
            "width_m": "axial extent of contact on the +y side; open ends from p^2 extrapolated to zero on phi = 0",
            "width_law_m": "Dai et al. 2025 Eq. 11: min(Delta r_edge/|theta|, l0)",
            "sides": "'+y', '-y' or 'both' (two-point contact on opposite generatrices)",
            "edges_loaded": "ring edges (x = +-l0/2) that carry load: 'none', '+x', '-x', 'both'",
            "pressure_map_pa": "contact pressure multipliers (bilinear, Pa) on the support bore, rows = "
                               "pressure_phi_rad (loaded rows only), columns = pressure_x_m",
            "force_error_rel": "1.25 |f2 - f3| / (r32^p - 1): Richardson estimate of the finest level's error with "
                               "the order p pooled over the sweep (metadata error_orders; h = N^-1/3)",
            "force_finer_n": "the same point on the finer check level (finer_level): |force_n - force_finer_n| "
                             "<= force_error_rel*force_n is a committed test",
            "level_build_s": "cold build time of the levels this point uses, check level included (s)",
            "level_load_s": "time the computing process spent obtaining those levels: build, or cache read; 0 when "
                            "already in its memory (s)",
            "solve_s": "contact solves of all levels, check level included (s)",
            "wall_s": "level_load_s + solve_s: the point's wall time in its process (s)",
        },
    }


def _jsonable(row: dict) -> dict:
    out = {}
    for k, v in row.items():
        if isinstance(v, np.ndarray):
            v = v.tolist()
        elif isinstance(v, (np.floating, np.integer)):
            v = v.item()
        out[k] = v
    return out


def regenerate(path, **kw) -> Path:
    """Run the sweep and write the dataset (atomically) to ``path``."""
    meta, points = sweep_dataset(**kw)
    return write_dataset(path, meta, COLUMNS, points)


def check_against_committed(path=DATASET_PATH, n_points: int = 3, use_cache: bool = False) -> list[dict]:
    """Recompute ``n_points`` committed points (compliances rebuilt unless ``use_cache``);
    returns rows with committed and new force and moment and their relative differences."""
    ds = read_dataset(path)
    geom = RingPair3D(**ds.metadata["geometry"])
    levels = [MeshLevel3D(**lv) for lv in ds.metadata["mesh"]["levels"]]
    scene = ds.metadata.get("boundary_conditions", ds.points[0]["scene"])
    comps = [get_compliance(geom, lv, scene, use_cache=use_cache) for lv in levels]
    idx = np.unique(np.linspace(0, len(ds.points) - 1, n_points).round().astype(int))
    rows = []
    for i in idx:
        old = ds.points[i]
        new = reference_point(comps, old["penetration_m"], old["tilt_rad"])
        rows.append({
            "penetration_m": old["penetration_m"], "tilt_rad": old["tilt_rad"],
            "committed_force_n": old["force_n"], "new_force_n": new["force_n"],
            "force_diff_rel": new["force_n"] / old["force_n"] - 1 if old["force_n"] else new["force_n"],
            "committed_moment_nm": old["moment_nm"], "new_moment_nm": new["moment_nm"],
            "moment_diff_rel": (new["moment_nm"] / old["moment_nm"] - 1) if old["moment_nm"] and old["tilt_rad"] else 0.0,
            "force_error_estimate_rel": old["force_error_rel"]})
    return rows
