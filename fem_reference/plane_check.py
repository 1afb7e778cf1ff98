"""Plane stress or plane strain, decided by the 3D ring: the 2D assumption of a ring-pair file checked by evidence.

A 2D reference of a ring pair needs a plane assumption, and the two differ by the composite modulus: 23 % in force
for a steel ring in aluminium. Which one a real ring of width ``b`` follows depends on how its end faces are held,
not on a ratio alone: measured with this module's check (reports/published/bearing-plane-choice.md), a 20 mm steel
ring in aluminium with axially free faces follows plane stress within 0.04 % (plane strain 23 % stiffer), while for
the Table 1 rings with their radial surfaces clamped (end faces free) plane stress lies 7.5 % below the 3D ring and
plane strain 13.2 % above it. So the check solves the ring itself.

:func:`check` solves the 3D ring (:mod:`fem_reference.solid`, the file's hold and drive as a body of revolution,
free end faces) at zero tilt at two penetrations, the geometric middle of the file's range and its top, on the
three production levels with their Richardson error, and the 2D reference (:mod:`fem_reference.plane.sweep`) at the
same penetrations under both assumptions. :data:`RULE` says how the plane is chosen. The 3D levels are the ones
the tilted reference uses (cached under ``$RINGCONTACT_CACHE``), so with a tilt range the check costs a few
seconds more; alone, the cold level build dominates (measured in reports/published/bearing-plane-choice.md).

:func:`resolve` gives a file's plane: ``auto`` (the default) takes the check's choice; a plane the file states is
kept, and the check, where run, is its evidence (a warning where the other plane lies closer). :func:`scene_2d` is
:func:`fem_reference.ring_scene.scene_2d` with an ``auto`` file resolved (the FEM jobs' ``--scene``).
"""
from __future__ import annotations

import hashlib
import json
import math
import shutil
import time

from contact.units import MM
from fem_reference.ring_scene import RingScene, is_file_argument, load, with_plane
from fem_reference.ring_scene import scene_2d as _scene_2d_of_name

#: how the plane is chosen from the check (the report and the summary quote it)
RULE = ("the plane model whose force lies closer to the 3D ring's at both check penetrations (largest "
        "|F_2D - F_3D| / F_3D); decisive when, at every check penetration, the two distances differ by more than "
        "twice the sum of the FEM error estimates (3D and both 2D); otherwise the file's plane, or plane strain "
        "(the former default) for 'auto'")
#: a plane whose force lies farther than this from the 3D ring's gets a warning (the bearing job's law bound)
AGREEMENT_REL = 0.02
FALLBACK = "strain"


def check_penetrations_m(rs: RingScene) -> list[float]:
    """The two check penetrations (m): the geometric middle of the file's range and its top."""
    lo, hi = rs.penetration_range_m
    return [float(f"{math.sqrt(lo * hi):.3g}"), float(hi)]


def _store_key(rs: RingScene) -> str:
    doc = {k: v for k, v in rs.document.items() if k not in ("name", "description", "plane")}
    return hashlib.sha256(json.dumps(doc, sort_keys=True).encode()).hexdigest()[:16]


def _forces_2d(rs: RingScene, pens: list[float], *, workers: int, executor, fresh: bool, progress) -> dict:
    """2D force and error at ``pens`` under both planes: ``{plane: [(F, err), ...]}``."""
    from fem_reference.plane import sweep as plane
    from fem_reference.solid.sweep import cache_dir

    store = cache_dir() / "plane-check" / _store_key(rs)
    if fresh and store.exists():
        shutil.rmtree(store)
    variants = [with_plane(rs, p, name=f"{rs.name[:46]}.plane-{p}") for p in ("stress", "strain")]
    _, points = plane.sweep_dataset(variants, penetrations_m=pens, workers=workers, executor=executor,
                                    progress=progress, store=store, per_point=True)
    out = {}
    for p, v in zip(("stress", "strain"), variants):
        rows = sorted((r for r in points if r["scene"] == v.name), key=lambda r: r["penetration_m"])
        out[p] = [(float(r["force_n"]), float(r.get("force_error_rel") or 0.0)) for r in rows]
    return out


def _forces_3d(rs: RingScene, pens: list[float], *, workers: int, executor, fresh: bool, progress) -> list:
    """3D zero-tilt force and error at ``pens``: ``[(F, err), ...]`` (the production levels, no check level)."""
    from fem_reference.solid import sweep as solid

    _, points = solid.sweep_dataset(tilts_rad=[0.0], penetrations_m=pens, scene=rs.bc_3d, geom=rs.rings_3d(),
                                    workers=workers, executor=executor, progress=progress, resume=not fresh,
                                    check_level=None, label=rs.name)
    rows = sorted(points, key=lambda r: r["penetration_m"])
    return [(float(r["force_n"]), float(r.get("force_error_rel") or 0.0)) for r in rows]


def _decide(rows: list[dict]) -> tuple[str | None, bool]:
    """(the closer plane, decisive) from the check rows (:data:`RULE`)."""
    dist = {p: max(abs(r[f"{p}_minus_3d_rel"]) for r in rows) for p in ("stress", "strain")}
    closer = min(dist, key=dist.get)
    other = "strain" if closer == "stress" else "stress"
    decisive = all(abs(r[f"{other}_minus_3d_rel"]) - abs(r[f"{closer}_minus_3d_rel"])
                   > 2.0 * (r["force_3d_error_rel"] + r["force_2d_stress_error_rel"] + r["force_2d_strain_error_rel"])
                   for r in rows)
    return closer, decisive


def check(rs: RingScene, *, workers: int = 1, executor=None, fresh: bool = False, progress=None) -> dict:
    """The 3D zero-tilt ring against both 2D assumptions at :func:`check_penetrations_m` (the module docstring).

    Returns the record ``plane_check`` of the bearing job's summary: ``penetration_mm``; per point the 3D and 2D
    forces (N) with their relative error estimates, and ``stress_minus_3d_rel``, ``strain_minus_3d_rel``
    (``(F_2D - F_3D) / F_3D``); ``closer``, ``decisive``, ``boundary_conditions_3d``, ``wall_s``. None where the
    3D reference cannot model the file's hold and drive (not the same all round the ring).
    """
    if rs.bc_3d is None:
        return None
    t0 = time.perf_counter()
    pens = check_penetrations_m(rs)
    kw = dict(workers=workers, executor=executor, fresh=fresh, progress=progress)
    f3 = _forces_3d(rs, pens, **kw)
    f2 = _forces_2d(rs, pens, **kw)
    rows = []
    for i, d in enumerate(pens):
        (F3, e3), (Fs, es), (Fe, ee) = f3[i], f2["stress"][i], f2["strain"][i]
        rows.append({"penetration_mm": d / MM, "force_3d_N": F3, "force_3d_error_rel": e3,
                     "force_2d_stress_N": Fs, "force_2d_stress_error_rel": es,
                     "force_2d_strain_N": Fe, "force_2d_strain_error_rel": ee,
                     "stress_minus_3d_rel": (Fs - F3) / F3, "strain_minus_3d_rel": (Fe - F3) / F3})
    closer, decisive = _decide(rows)
    return {"boundary_conditions_3d": rs.bc_3d, "points": rows, "closer": closer, "decisive": decisive,
            "rule": RULE, "wall_s": time.perf_counter() - t0}


def _used(requested: str, evidence: dict | None, possible: bool = True) -> tuple[str, str]:
    """(the plane used, why) from the file's ``plane`` and the check (``possible``: the 3D reference models the
    file's hold and drive)."""
    if requested != "auto":
        return requested, "the file's plane" + ("" if evidence is not None else " (no 3D check run)")
    if evidence is None:
        return FALLBACK, (f"plane 'auto' with {'the 3D check not run' if possible else 'no 3D check possible'}: "
                          f"plane {FALLBACK} (the former default), unchecked")
    if not evidence["decisive"]:
        return FALLBACK, (f"plane 'auto', the 3D check not decisive (within the FEM errors): plane {FALLBACK} "
                          "(the former default)")
    return evidence["closer"], "plane 'auto': the 3D check's choice"


def _warnings(rs: RingScene, requested: str, used: str, evidence: dict | None) -> list[str]:
    if evidence is None:
        if rs.bc_3d is None:
            return [f"plane {used} unchecked: the 3D reference models only holds the same all round the ring "
                    f"({rs.scene.support_hold} + {rs.scene.bearing_drive} is not one)"]
        return []
    out = []
    off = {p: max(abs(r[f"{p}_minus_3d_rel"]) for r in evidence["points"]) for p in ("stress", "strain")}
    if requested != "auto" and evidence["decisive"] and evidence["closer"] != used:
        out.append(f"the file says plane {used}, but plane {evidence['closer']} lies closer to the 3D ring "
                   f"({100 * off[evidence['closer']]:.1f} % against {100 * off[used]:.1f} %): plane = \"auto\" "
                   "would use it")
    if off[used] > AGREEMENT_REL:
        out.append(f"plane {used} lies {100 * off[used]:.1f} % from the 3D ring (free end faces; bound "
                   f"{100 * AGREEMENT_REL:g} %): a 2D law of this ring carries that difference; the 3D law of a tilt "
                   "range does not")
    return out


def resolve(rs: RingScene, *, run_check: bool | None = None, workers: int = 1, executor=None, fresh: bool = False,
            progress=None) -> tuple[RingScene, dict]:
    """``(rs with its plane set, the record)``: the plane used and why, the check (``plane_check``) and warnings.

    ``run_check`` None: the check runs for an ``auto`` file and for one with a tilt range (its 3D levels are built
    anyway); True: always (where the 3D reference can model the ring); False: never (an ``auto`` file then falls
    back to plane strain, said so)."""
    requested = rs.document["plane"]
    if run_check is None:
        run_check = requested == "auto" or rs.needs_3d
    evidence = check(rs, workers=workers, executor=executor, fresh=fresh, progress=progress) if run_check else None
    used, why = _used(requested, evidence, rs.bc_3d is not None)
    record = {"requested": requested, "used": used, "why": why, "check": evidence,
              "warnings": _warnings(rs, requested, used, evidence)}
    return (with_plane(rs, used) if rs.plane_auto else rs), record


def resolved(rs: RingScene) -> RingScene:
    """``rs`` itself if its plane is stated, else resolved by the 3D check (:func:`resolve`; its levels cached:
    seconds once built)."""
    return resolve(rs, run_check=True)[0] if rs.plane_auto else rs


def scene_2d(name_or_path: str):
    """:func:`fem_reference.ring_scene.scene_2d` with a ring-pair file left at ``plane = "auto"`` resolved
    (:func:`resolved`)."""
    text = str(name_or_path)
    return resolved(load(text)).scene if is_file_argument(text) else _scene_2d_of_name(text)
