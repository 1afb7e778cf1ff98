"""How a study runs its sweep: the overrides and mesh of every point, the work budget, the first compile, the
sweep itself on the local pool or a cluster, and what it says of points that failed or did not settle
(``ringcontact study``, :mod:`reports.cli.study`)."""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from contact.errors import FailedPointsError, InputError, RingContactError
from contact.units import check_positive
from reports.cli import _budget
from reports.cli._scene_options import (max_revs, say_on_terminal, scene_from_args, warm_up_shown,
                                        warn_speeds_beyond_scene)


def overrides(args) -> dict:
    """The scene overrides given (:func:`reports.cli._scene_options.scene_from_args`, SI keywords)."""
    return dict(scene_from_args(args).overrides)


def mesh(args) -> dict:
    """The ``elements_per_segment`` override of every point (empty: the scene's mesh)."""
    if getattr(args, "elements", None) is None:
        return {}
    check_positive("elements", args.elements, "elements per segment", upper=64)
    return {"elements_per_segment": int(args.elements)}


def run_study_sweep(tasks, out: Path, args, description: dict):
    from sweep import point_tasks, run_sweep
    from sweep.cluster import connect
    from rotor.studies.steady_state import _scene_model

    from rotor.model.law_validity import ALLOW_OPTION, check_allowed, law_line
    sc, _ = _scene_model(args.scene, mesh(args).get("elements_per_segment"), overrides(args).get("law"))
    check_allowed(sc.loose_support, getattr(args, "allow_flagged_law", False), ALLOW_OPTION)
    _same_law(out, sc)
    import dataclasses
    scene_doc = dataclasses.asdict(sc)
    if sc.loose_support is not None:
        scene_doc["loose_support"].pop("calibrated", None)     # named by law_file and law_sha256
        if sc.loose_support.calibrated is not None:
            print(f"study {args.study}: law {sc.loose_support.law_file} (sha256 {sc.loose_support.law_sha256})")
    _check_work(tasks, args)
    warn_speeds_beyond_scene(f"study {args.study}", sc, [t.params.get("speed_rpm", 0.0) for t in point_tasks(tasks)])
    say_on_terminal(args, f"study {args.study}: {law_line(sc.loose_support, overrides(args))}")
    manifest = {"study": args.study, "description": description, "scene_name": sc.name, "scene": scene_doc,
                **mesh(args)}
    compile_first(args)
    t0 = time.perf_counter()
    with connect(args.scheduler) as client:
        s = run_sweep(tasks, out, executor=client, max_workers=args.workers, manifest=manifest,
                      progress=False if args.no_progress else None)
    wall = time.perf_counter() - t0
    n_points = len(point_tasks(tasks))
    print(f"study {args.study}: {n_points} points, {len(s.computed)} computed, {len(s.reused)} reused, "
          f"{len(s.recomputed)} recomputed, {len(s.failed)} failed, wall {wall:.1f} s")
    for k, e in s.failed.items():
        print(f"  FAILED {k}: {e}", file=sys.stderr)
    if s.failed:
        raise FailedPointsError(f"{len(s.failed)} of {n_points} points failed (FAILED lines above); no figures "
                                f"written; the finished points stay in {out}, a rerun computes only the rest")
    _say_unsettled(out, point_tasks(tasks), args)
    _law_validity(out, point_tasks(tasks), sc.loose_support, args)
    return s, wall


def compile_first(args) -> None:
    """Compile the step loop here (or load it from the disk cache), its seconds shown on a terminal, so that the
    local workers load it from the disk cache instead of each compiling it unseen (not for a cluster: its
    workers have their own cache)."""
    if args.scheduler is not None:
        return
    if getattr(args, "method", "transient") == "shooting":
        from rotor.dynamics.period_map import warm_up
    else:
        from rotor.dynamics.production import warm_up
    warm_up_shown(f"study {args.study}", argparse.Namespace(progress=False if args.no_progress else None), warm_up)


def _say_unsettled(out: Path, tasks, args) -> None:
    """Count the points whose transient reached no steady state within the cap (``converged`` False) and say so."""
    from sweep.store import ResultStore

    store = ResultStore(out)
    keys = [t.key for t in tasks if not store.info(t.key).get("converged", True)]
    if keys:
        speeds = ", ".join(f"{store.info(k).get('speed_rpm', float('nan')):g}" for k in keys[:8])
        print(f"study {args.study}: {len(keys)} of {len(tasks)} points not converged within --max-revs = "
              f"{max_revs(args)} revolutions (at {speeds}{' …' if len(keys) > 8 else ''} rpm): their amplitudes are "
              "those of the last revolutions, not of a steady state (converged = 0 in the CSV, marked in the "
              "figures); a higher --max-revs, or --method shooting for the periodic orbit")


def _law_validity(out: Path, tasks, loose, args) -> dict:
    """The study's validity record over the recorded revolutions of its points (:mod:`rotor.model.law_validity`)
    into ``<out>/law-validity.json`` (the JSON key ``law_validity``), its warnings on stderr as every rotor job's."""
    import json

    from contact.files import atomic_write_text
    from rotor.model.law_validity import merged, stored_point_record
    from sweep.store import ResultStore

    store = ResultStore(out)
    recs = []
    for t in tasks:
        try:
            pt = store.load(t.key)
        except RingContactError:         # a point kept without its arrays: nothing to say of it
            continue
        clearance = (pt.record.get("info") or {}).get("clearance_m")
        if clearance is not None:
            recs.append(stored_point_record(loose, pt.arrays, float(clearance)))
    rec = merged(recs)
    if rec:
        atomic_write_text(out / "law-validity.json", json.dumps({"law_validity": rec}, indent=1, allow_nan=False) + "\n")
        for line in rec["warnings"]:
            print(f"study {args.study}: warning: {line}", file=sys.stderr)
    return rec


def _check_work(tasks, args) -> None:
    """The sweep's steady-state points against the work budget, before any point starts
    (:func:`reports.cli._budget.steady_points`: at most --max-revs revolutions a point, more steps per
    revolution at low speed)."""
    est = _budget.steady_points(tasks, 1 if args.scheduler else args.workers)
    _budget.check(f"ringcontact study {args.study}", est, args.accept_long,
                  f"--max-revs = {max_revs(args)} rev a point at --steps-per-rev {args.steps_per_rev} or more",
                  "fewer points or --max-revs, or higher speeds (a slow revolution needs many steps)")


def _same_law(out: Path, sc) -> None:
    """Refuse to add to a study whose stored points were computed with another contact law: an analytic law by
    name, a calibrated one by its file's checksum (a refitted law file is another law). The points' parameters
    name the scene file only, so they alone would be reused."""
    from sweep.store import ResultStore

    store = ResultStore(out)
    before = store.read_manifest(required=False)
    if not before or not store.points.is_dir() or not any(store.points.glob("*.json")):
        return
    old = (before.get("scene") or {}).get("loose_support") or {}
    ls = sc.loose_support
    was = old.get("law_sha256") or old.get("law", "conformal")
    now = ("conformal" if ls is None else ls.law_sha256 or ls.law)
    if was != now:
        said = {True: "the law file with sha256 ", False: ""}
        raise InputError(f"--out = {out}: its points were computed with {said[len(was) == 64]}{was}, the scene now "
                         f"names {said[len(now) == 64]}{now}; use another --out (or remove {out}) for this law")
