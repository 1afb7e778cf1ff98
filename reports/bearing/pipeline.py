"""``ringcontact bearing FILE``: an engineer's ring-pair file to a verified, checksummed contact law.

Stages (each timed, with the load average, into ``timings.json``):

0. ``plane``: plane stress or strain by evidence (:mod:`fem_reference.plane_check`): the 3D ring at zero tilt at
   two penetrations against both 2D assumptions, for a file left at ``plane = "auto"`` (the default; the closer
   plane is used) and for one with a tilt range (its 3D levels are built anyway); a plane stated in a straight-only
   file is used unchecked unless ``plane_check`` (``--plane-check``) asks. The choice, the rule and the 3D numbers
   go into the summary (``plane``), the law file's provenance and the report;
1. ``fem2d``: the 2D reference sweep at the file's penetration points, every point with its
   Richardson error estimate (:mod:`fem_reference.plane.sweep`), one task per point on the local
   pool or a dask cluster, kept in ``<out>/.sweep-fem2d`` so an interrupted run resumes;
2. ``fem3d`` (only when ``[range] tilt_arcmin`` asks for tilt): the 3D tilt sweep of the
   harmonic levels with the finer check level (:mod:`fem_reference.solid.sweep`), resumable
   through its store under the cache;
   ``tilt-grid`` (with tilt): the tilt correction's training and verification grids of 3D points on the same
   cached levels (:mod:`reports.bearing.tilt`), resumable the same way;
3. ``calibrate``: every law family fitted with leave-one-out hold-out (:mod:`contact.calibrate`)
   on the 2D points and, with tilt, on the 3D zero-tilt points; the tilted 3D points are never
   fitted, so they are held out as a whole. With tilt, the tilt correction is fitted on the training grid alone
   and checked, force and moment, on the verification grid and on the 3D reference points
   (:func:`reports.bearing.tilt.correct`); the corrected law is chosen when its cross-validated worst error over
   its bound on the training grid is not larger than the straight law's there;
4. ``report``: the Tables 2-3 style accuracy report of this bearing (:mod:`reports.bearing.report`);
5. the law file ``<name>-law.json``: with tilt the corrected law (or the 3D-calibrated straight law when the
   correction does worse), else the 2D one, with its validity range (penetration, tilt), provenance (the
   ring-pair file's name and sha256, the code version) and the checks made; whole-file sha256. Beside a corrected
   law, ``<name>-law-straight.json``: the same run's straight 3D law, the one a rotor scene can name (the rotor's
   step loops do not evaluate a correction yet).

A law whose held-out error exceeds the FEM point's own stated error by more than
:data:`~reports.bearing.names.LAW_ERROR_BOUND_REL` (or whose family the compiled rotor kernel cannot
evaluate) is still written, flagged in its file, the report and on the terminal.
"""
from __future__ import annotations

import dataclasses
import math
import os
import shutil
import time
from pathlib import Path

import numpy as np

from contact import calibrate as cal
from contact.calibrate.fit import ACCURACY_ADD_REL, ACCURACY_FEM_FACTOR, ACCURACY_RULE, holdout_excess
from contact.dataset import read_dataset, write_dataset
from contact.files import atomic_write_text
from fem_reference.ring_scene import RingScene
from reports.bearing.holds import not_held, part_line
from reports.bearing.names import LAW_ERROR_BOUND_REL, file_names
from reports.bearing.report import write_report
from sweep import utc_stamp

STORE_2D = ".sweep-fem2d"


def _load() -> float:
    return round(os.getloadavg()[0], 2)


class Stages:
    """Wall time and load average of each stage, printed as it ends (``log``)."""

    def __init__(self, log):
        self.log, self.rows = log, []

    def run(self, name: str, what: str, fn):
        self.log(f"[{len(self.rows) + 1}] {name}: {what} ...")
        t0, l0 = time.perf_counter(), _load()
        out = fn()
        row = {"stage": name, "wall_s": time.perf_counter() - t0, "load_average_1min_start": l0,
               "load_average_1min_end": _load()}
        self.rows.append(row)
        self.log(f"[{len(self.rows)}] {name}: done in {row['wall_s']:.1f} s")
        return out


def run_fem2d(rs: RingScene, out: Path, *, workers: int, executor, fresh: bool, progress) -> Path:
    """The 2D reference of the ring pair into ``fem2d-<name>.json`` (resumable store in ``.sweep-fem2d``)."""
    from fem_reference.plane import sweep as plane

    store = out / STORE_2D
    if fresh and store.exists():
        shutil.rmtree(store)
    meta, points = plane.sweep_dataset([rs], penetrations_m=list(rs.penetrations_2d_m), workers=workers,
                                       executor=executor, progress=progress, store=store, per_point=True)
    meta["ring_scene"] = {"name": rs.name, "sha256": rs.sha256, "document": rs.document}
    return write_dataset(out / file_names(rs.name)["fem2d"], meta, plane.COLUMNS, points)


def run_fem3d(rs: RingScene, out: Path, *, workers: int, executor, fresh: bool, progress) -> Path:
    """The 3D tilt reference of the ring pair into ``fem3d-<name>.json`` (resumable under the cache)."""
    from fem_reference.solid import sweep as solid

    meta, points = solid.sweep_dataset(tilts_rad=list(rs.tilts_rad), penetrations_m=list(rs.penetrations_3d_m),
                                       scene=rs.bc_3d, geom=rs.rings_3d(), workers=workers, executor=executor,
                                       progress=progress, resume=not fresh, label=rs.name,
                                       description=rs.scene.description)
    meta["ring_scene"] = {"name": rs.name, "sha256": rs.sha256, "document": rs.document}
    return write_dataset(out / file_names(rs.name)["fem3d"], meta, solid.COLUMNS, points)


def _calibrate(path: Path, name: str):
    ds = read_dataset(path)
    info = cal.dataset_provenance(path, ds)
    info["path"] = path.name               # the run folder travels as a whole
    law, fits = cal.calibrate_scene(ds, name, info, families=cal.FAMILIES)    # the flexible family too
    return ds, law, fits


def calibrate(rs: RingScene, path2: Path, path3: Path | None, tilt_paths: dict | None = None) -> dict:
    """Fit the 2D (and 3D) laws, check the tilted points, flag what exceeds the bound. ``tilt_paths`` (the grids of
    :func:`reports.bearing.tilt.run_grids`): fit the tilt correction and check it held out
    (:func:`reports.bearing.tilt.correct`); the corrected law is then the chosen one when it does better on the
    training grid, and the straight law's own calibration is kept under ``straight``."""
    from reports.accuracy.tilted import table3_rows

    ds2, law2, fits2 = _calibrate(path2, rs.name)
    out = {"ds2": ds2, "law2": law2, "fits2": fits2, "ds3": None, "law3": None, "fits3": None, "rows3": [],
           "zero3": None, "tilt": None, "straight": None}
    if path3 is not None:
        ds3, law3, fits3 = _calibrate(path3, rs.name)
        best3 = next(f for f in fits3 if f.family == law3.family)
        out.update(ds3=ds3, law3=law3, fits3=fits3, rows3=table3_rows(ds3, rs.name, law3),
                   zero3=(best3.holdout_rel_err, cal.scene_points(ds3, rs.name)[2]))
    out["chosen"] = out["law3"] or law2
    _verdict(out, rs.name)
    if tilt_paths is None or path3 is None:
        return out
    from reports.bearing.tilt import correct, rows_held
    tc = correct(rs, out, tilt_paths)
    if not tc["chosen"]:
        out["tilt"] = tc
        return out
    fit = dict(out, tilt=tc, straight=out, chosen=tc["law"],
               rows3=rows_held(table3_rows(out["ds3"], rs.name, tc["law"]), tc["trained"]),
               zero3=(tc["base_fit"].holdout_rel_err, tc["base_fem_error"]))
    _verdict(fit, rs.name)
    return fit


def _verdict(out: dict, name: str) -> None:
    """The chosen law's checks, the excess over the FEM's error, warnings, accuracy and the parts no family holds,
    into ``out``."""
    law2, fits2, ds2 = out["law2"], out["fits2"], out["ds2"]
    best2 = next(f for f in fits2 if f.family == law2.family)
    fem2 = cal.scene_points(ds2, name)[2]
    checks = {"holdout_max_rel_2d": best2.holdout_max, "fem2d_error_max_rel": float(np.max(fem2))}
    # a held-out error counts against the bound only beyond the FEM point's own stated error
    excess = {"holdout_max_rel_2d": holdout_excess(best2.holdout_rel_err, fem2)}
    if out["law3"] is not None:
        _checks_3d(out, checks, excess)
    chosen = out["chosen"]
    warnings = [f"{key} = {100 * checks[key]:.2f} % is {100 * val:.2f} % beyond the FEM's stated error, more than "
                f"the bound {100 * LAW_ERROR_BOUND_REL:g} %: no law family describes this ring pair that well; see the "
                "report's families" for key, val in excess.items() if np.isfinite(val) and val > LAW_ERROR_BOUND_REL]
    if chosen.family not in cal.KERNEL_LAW_CODE:
        warnings.append(f"family {chosen.family!r} is not in the compiled rotor kernel: the law file cannot drive "
                        "a rotor (families the rotor uses: " + ", ".join(cal.KERNEL_LAW_CODE) + ")")
    if out["tilt"] is not None and out["tilt"]["chosen"]:
        warnings += out["tilt"]["warnings"]
    out.update(checks=checks, excess=excess, warnings=warnings)
    out["accuracy"] = accuracy(out, name)
    out["not_held"] = not_held(out, name)


def _checks_3d(out: dict, checks: dict, excess: dict) -> None:
    """The 3D checks of the chosen law into ``checks`` and ``excess``: zero tilt held out (leave-one-out on the
    points it was fitted on), the tilted reference points through the slices (a straight law only: a corrected
    law's slices are what it corrects) and the rotor kernel, the moment verdict."""
    err0, fem0 = out["zero3"]
    rows = out["rows3"]
    ferr = np.array([r["force_error_rel"] for r in rows])
    checks["holdout_max_rel_3d_zero_tilt"] = float(np.max(np.abs(err0)))
    excess["holdout_max_rel_3d_zero_tilt"] = holdout_excess(err0, fem0)
    corrected = out["chosen"] is not out["law3"]
    for key, col in (("tilted_holdout_max_rel_slices", "calibrated-slices_pct"),
                     ("tilted_holdout_max_rel_kernel", "calibrated-kernel_pct")):
        if corrected and key.endswith("slices"):
            continue
        err = _abs_rel(rows, col)
        checks[key] = float(np.nanmax(err)) if np.isfinite(err).any() else math.nan
        excess[key] = holdout_excess(err, ferr)
    out["moment_check"] = moment_check(rows)
    checks["fem3d_error_max_rel"] = float(max(p.get("force_error_rel") or 0.0 for p in out["ds3"].points))


def moment_check(rows: list[dict]) -> dict:
    """The tilted points' moment through the rotor kernel, held out (never fitted), by the law file's rule: the
    largest error, by how much it exceeds the FEM point's stated moment error, and whether that is within
    :data:`~reports.bearing.names.LAW_ERROR_BOUND_REL`. Reported beside the force verdict, not part of the flag that
    refuses a law in the rotor: the bundled pair's law (moment 6.7 % off at 2' and 0.004 mm) would be refused by the
    rotor scenes that name it; that decision belongs to the rotor's owners (issue 37's moment verdict, measured)."""
    err = _abs_rel(rows, "calibrated-kernel_moment_pct")
    fem = np.array([r["moment_error_rel"] if r["moment_error_rel"] is not None else math.nan for r in rows])
    ok = np.isfinite(err) & np.isfinite(fem)
    if not ok.any():
        return {"points": 0}
    beyond = holdout_excess(err[ok], fem[ok])
    return {"points": int(ok.sum()), "holdout_max_rel": float(err[ok].max()), "beyond_fem_error_rel": float(beyond),
            "error_bound_rel": LAW_ERROR_BOUND_REL, "held": bool(beyond <= LAW_ERROR_BOUND_REL)}


def _abs_rel(rows: list[dict], col: str) -> np.ndarray:
    """``|column| / 100`` of the tilted rows (a % column), NaN where a row has no value (a zero FEM moment)."""
    return np.array([abs(r[col]) / 100 if r[col] is not None and np.isfinite(r[col]) else math.nan for r in rows])


def accuracy(fit: dict, name: str) -> list[dict]:
    """Issue 37's accuracy rule (:func:`contact.calibrate.fit.within_accuracy`: every held-out error within 2x the
    FEM point's stated error + 0.2 %) for the chosen law, per reference and quantity: ``reference``, ``quantity``,
    ``points``, ``within`` (how many meet it), ``holds``, ``worst_error_pct``, ``worst_bound_pct`` (at the point
    of largest error − bound: the one missing its bound the most, or, when all meet it, the one nearest its bound,
    which need not be the largest error), ``within_inside`` (zero tilt: of the
    points between the ends, whose hold-out interpolates; None for tilted points). Zero-tilt points: leave-one-out;
    tilted points: never fitted (the law is calibrated at zero tilt)."""
    out = []

    def add(reference, quantity, err, fem, ends_extrapolated=False):
        err, fem = np.abs(np.asarray(err, dtype=float)), np.abs(np.asarray(fem, dtype=float))
        ok = np.isfinite(err) & np.isfinite(fem)
        err, fem = err[ok], fem[ok]
        if not err.size:
            return
        bound = ACCURACY_FEM_FACTOR * fem + ACCURACY_ADD_REL
        within = cal.within_accuracy(err, fem)
        i = int(np.argmax(err - bound))
        out.append({"reference": reference, "quantity": quantity, "points": int(err.size),
                    "within": int(within.sum()), "holds": bool(within.all()),
                    "worst_error_pct": 100 * float(err[i]), "worst_bound_pct": 100 * float(bound[i]),
                    # zero tilt: the two end points are held out by extrapolation beyond the others' range
                    "within_inside": int(within[1:-1].sum()) if ends_extrapolated else None})

    law2 = fit["law2"]
    best2 = next(f for f in fit["fits2"] if f.family == law2.family)
    add("2d", "force", best2.holdout_rel_err, cal.scene_points(fit["ds2"], name)[2], True)
    if fit.get("law3") is not None:
        add("3d zero tilt", "force", *fit["zero3"], True)
        rows = fit["rows3"]
        add("3d tilted (rotor kernel)", "force", _abs_rel(rows, "calibrated-kernel_pct"),
            [r["force_error_rel"] for r in rows])
        add("3d tilted (rotor kernel)", "moment", _abs_rel(rows, "calibrated-kernel_moment_pct"),
            [r["moment_error_rel"] if r["moment_error_rel"] is not None else math.nan for r in rows])
    if fit.get("tilt") is not None and fit["tilt"]["chosen"]:
        from reports.bearing.tilt import accuracy_rows
        out += accuracy_rows(fit["tilt"])
    return out


def law_file(rs: RingScene, fit: dict, range_from: dict | None = None) -> cal.CalibratedLaw:
    """The law to ship: validity range (penetration of the fitted points, the largest tilt checked),
    provenance (ring-pair file, code version, the run the range was widened by) and the checks with their bound."""
    from reports.version import version_line

    tilt_max = max(rs.tilts_rad, default=0.0) if fit["law3"] is not None else 0.0
    tc = fit.get("tilt")
    corrected = tc is not None and tc["chosen"]
    prov = {"ring_scene": {"name": rs.name, "sha256": rs.sha256, "source": rs.source, "document": rs.document},
            "code_version": version_line(), "created_utc": utc_stamp(),
            "reference": _reference(fit, rs),
            "checks": {k: (None if not np.isfinite(v) else float(v)) for k, v in fit["checks"].items()},
            "checks_beyond_fem_error": {k: (None if not np.isfinite(v) else float(v)) for k, v in fit["excess"].items()},
            "error_bound_rel": LAW_ERROR_BOUND_REL, "warnings": list(fit["warnings"]),
            "rotor_kernel": fit["chosen"].family in cal.KERNEL_LAW_CODE and not corrected,
            "not_held": fit["not_held"],
            "accuracy_rule": ACCURACY_RULE, "accuracy": fit["accuracy"]}
    if fit.get("plane") is not None:
        prov["plane"] = fit["plane"]
    if fit.get("moment_check"):
        prov["moment_check"] = fit["moment_check"]
    if range_from is not None:
        prov["range_from"] = range_from
    if tc is not None:
        prov["tilt_correction"] = tc["record"]
    if corrected:
        prov["rotor_note"] = ROTOR_NOTE
    return dataclasses.replace(fit["chosen"], validity_tilt_max_rad=float(tilt_max), provenance=prov)


#: why a law with a tilt correction is written beside its straight law
ROTOR_NOTE = ("the rotor's step loops do not evaluate a tilt correction yet (rotor.dynamics.kernels refuses such a "
              "law with one line): a rotor scene names the straight law written beside this one")


def _reference(fit: dict, rs: RingScene) -> str:
    if fit["law3"] is None:
        return f"2d (plane {rs.scene.plane})"
    if fit.get("tilt") is not None and fit["tilt"]["chosen"]:
        return ("3d (free end faces): zero-tilt fit and tilt correction on the training grid, the verification grid "
                "and the reference points held out")
    return "3d (free end faces), zero-tilt fit, tilted points held out"


def _plane(rs: RingScene, stages: Stages, plane_check: bool | None, **kw) -> tuple[RingScene, dict]:
    """Stage 0: the plane the 2D reference uses, and its evidence (:func:`fem_reference.plane_check.resolve`)."""
    from fem_reference.plane_check import check_penetrations_m, resolve

    runs = plane_check if plane_check is not None else (rs.plane_auto or rs.needs_3d)
    if not runs or rs.bc_3d is None:
        return resolve(rs, run_check=False)
    pens = ", ".join(f"{p * 1e3:.3g}" for p in check_penetrations_m(rs))
    return stages.run("plane", f"3D ring at zero tilt at {pens} mm against plane stress and strain",
                      lambda: resolve(rs, run_check=True, **kw))


def _fem_stages(rs: RingScene, out: Path, stages: Stages, **kw) -> tuple[Path, Path | None, dict | None]:
    """Stages 1-2b: the 2D reference, and with tilt the 3D reference and the tilt correction's two grids."""
    from reports.bearing.tilt import grid_points, run_grids

    n2 = len(rs.penetrations_2d_m)
    path2 = stages.run("fem2d", f"2D reference, {n2} penetrations x 3+ mesh levels", lambda: run_fem2d(rs, out, **kw))
    if not rs.needs_3d:
        return path2, None, None
    n3 = len(rs.penetrations_3d_m) * len(rs.tilts_rad)
    path3 = stages.run("fem3d", f"3D tilt reference, {n3} points (boundary conditions {rs.bc_3d})",
                       lambda: run_fem3d(rs, out, **kw))
    grids = stages.run("tilt-grid", f"3D training and verification grids, {grid_points(rs)} points",
                       lambda: run_grids(rs, out, path3, **kw))
    return path2, path3, grids


def run(rs: RingScene, out: Path, *, workers: int = 2, executor=None, fresh: bool = False,
        progress: bool | None = None, log=print, range_from: dict | None = None,
        plane_check: bool | None = None) -> dict:
    """Every stage for one ring pair into ``out``; returns the summary (also written as ``summary.json``).

    ``range_from``: the note of :func:`reports.bearing.range_from.widened` when ``rs``'s range was widened to a rotor
    run's (into the law's provenance, the report and the summary). ``plane_check``: stage 0 (None: as the module
    docstring says; True: always; False: never, an ``auto`` file then on plane strain, said so)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    stages = Stages(log)
    rs, plane = _plane(rs, stages, plane_check, workers=workers, executor=executor, fresh=fresh, progress=progress)
    log(f"plane {plane['used']}: {plane['why']}")
    path2, path3, tilt_paths = _fem_stages(rs, out, stages, workers=workers, executor=executor, fresh=fresh,
                                           progress=progress)
    what = "law families with hold-out" + (", tilt correction fitted and held out" if tilt_paths else "")
    fit = stages.run("calibrate", what, lambda: calibrate(rs, path2, path3, tilt_paths))
    return _write_outputs(rs, out, fit, stages, (path2, path3, tilt_paths), plane, range_from, log)


def _write_outputs(rs: RingScene, out: Path, fit: dict, stages: Stages, paths: tuple, plane: dict,
                   range_from: dict | None, log, refit_of: str | None = None) -> dict:
    """The law files, the report, ``timings.json`` and ``summary.json`` of a calibrated run into ``out`` (``paths``:
    the 2D and 3D datasets and the tilt grids it was calibrated on; ``refit_of``: the code version of the run whose
    FEM stages a :func:`refit` keeps); returns the summary."""
    import json

    path2, path3, tilt_paths = paths
    names = file_names(rs.name)
    fit["range_from"], fit["plane"] = range_from, plane
    law = law_file(rs, fit, range_from)
    files = [atomic_write_text(out / names["law"], law.to_json())]
    if fit["law3"] is not None:
        files.append(atomic_write_text(out / names["law2d"], fit["law2"].to_json()))
    if fit["straight"] is not None:
        straight = dict(fit["straight"], range_from=range_from, plane=plane)
        files.append(atomic_write_text(out / names["law_straight"], law_file(rs, straight, range_from).to_json()))

    files += stages.run("report", "accuracy report", lambda: write_report(rs, fit, law, out, stages.rows))
    for w in fit["warnings"]:
        log(f"warning: {w}")
    for part in fit["not_held"]:
        log(f"warning: {part_line(part)}")
    for w in plane["warnings"]:
        log(f"warning: plane: {w}")
    summary = {"ring_scene": rs.name, "ring_scene_sha256": rs.sha256, "law_file": names["law"],
               "law_name": law.name, "family": law.family, "parameters": law.parameters,
               "validity_penetration_mm": [v * 1e3 for v in law.validity_penetration_m],
               "validity_tilt_max_arcmin": law.validity_tilt_max_rad / (math.pi / 10800),
               "checks": law.provenance["checks"], "warnings": fit["warnings"], "not_held": fit["not_held"],
               "selection_reason": law.fit.get("selection_reason"), "accuracy": fit["accuracy"],
               "moment_check": fit.get("moment_check"),
               "tilt_correction": law.provenance.get("tilt_correction"),
               "law_straight_file": names["law_straight"] if fit["straight"] is not None else None,
               "range_from": range_from, "plane": plane, "refit_of": refit_of,
               "stages": stages.rows, "files": sorted({Path(f).name for f in files} | {path2.name}
                                                      | ({path3.name} if path3 else set())
                                                      | {Path(p).name for p in (tilt_paths or {}).values()})}
    atomic_write_text(out / names["timings"], json.dumps({"stages": stages.rows}, indent=1) + "\n")
    atomic_write_text(out / names["summary"], json.dumps(summary, indent=1, allow_nan=False) + "\n")
    return summary


def refit(rs: RingScene, out: Path, *, log=print) -> dict:
    """The law-dependent outputs of a kept run folder ``out`` again, from its kept FEM datasets: no FEM point solved.

    For a law family that changed after the run: the calibrate stage on the folder's 2D and 3D datasets (and, when
    the run fitted a tilt correction, its training and verification grids), then the law files, the report and the
    summary as :func:`run` writes them. The plane evidence, ``range_from`` and the FEM stages' timings are the kept
    run's (each such stage row gains ``"kept_from"``: that run's code version, from its law file; the report says
    so); ``calibrate`` and ``report`` are this call's. Returns the summary (its ``refit_of``: the kept run's code
    version).

    Raises
    ------
    InputError
        ``out`` holds no run of ``rs`` (no ``summary.json`` or datasets, or another ring-pair file's).
    """
    import json

    from contact.errors import InputError
    from fem_reference.ring_scene import with_plane
    from reports.bearing.tilt import grid_files

    out, names = Path(out), file_names(rs.name)
    try:
        kept = json.loads((out / names["summary"]).read_text(encoding="utf-8"))
        old_law = json.loads((out / kept["law_file"]).read_text(encoding="utf-8"))
    except (OSError, ValueError, KeyError) as exc:
        raise InputError(f"refit: {out} holds no readable run (summary.json and its law file): "
                         f"{type(exc).__name__}") from None
    if rs.plane_auto and kept.get("plane", {}).get("used") in ("strain", "stress"):
        rs = with_plane(rs, kept["plane"]["used"])            # the kept run's plane check decided it
    if kept.get("ring_scene_sha256") != rs.sha256:
        raise InputError(f"refit: {out} is a run of another ring-pair file (sha256 "
                         f"{str(kept.get('ring_scene_sha256'))[:16]}…, not {rs.sha256[:16]}…)")
    path2 = out / names["fem2d"]
    path3 = out / names["fem3d"] if names["fem3d"] in kept["files"] else None
    grids = ({k: out / v for k, v in grid_files(rs.name).items()} if kept.get("tilt_correction") else None)
    missing = [p.name for p in [path2, path3, *(grids or {}).values()] if p is not None and not p.is_file()]
    if missing:
        raise InputError(f"refit: {out} lacks the kept dataset(s) {', '.join(missing)}")
    version = kept.get("refit_of") or old_law["provenance"]["code_version"]      # the run that solved the FEM
    stages = Stages(log)
    stages.rows = [dict(s, kept_from=s.get("kept_from", version)) for s in kept["stages"]
                   if s["stage"] not in ("calibrate", "report")]
    what = "law families with hold-out on the kept datasets" + (", tilt correction" if grids else "")
    fit = stages.run("calibrate", what, lambda: calibrate(rs, path2, path3, grids))
    return _write_outputs(rs, out, fit, stages, (path2, path3, grids), kept["plane"], kept.get("range_from"), log,
                          refit_of=version)
