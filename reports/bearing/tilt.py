"""The bearing job's tilt correction (issue 37): a training grid and a verification grid of tilted 3D points, the
correction fitted on the first alone and checked, force and moment, on points it never saw.

A law calibrated at zero tilt is integrated slice by slice over a tilted patch (Winkler slices); the 3D ring couples
its slices, so the slices' moment is 2-14 % low on the rings measured (reports/published/law-tilt-correction.md) and
no fit of the straight law changes that. With a tilt range, ``ringcontact bearing`` therefore:

1. solves two grids of 3D points on the ring's cached mesh levels (:func:`run_grids`, through
   :func:`fem_reference.solid.sweep.sweep_dataset`, resumable): the **training grid**, :data:`TRAIN_PENETRATIONS`
   mid-plane penetrations geometric over the range times the tilts :data:`TRAIN_TILT_FRACTIONS` of the largest
   tilt, and the **verification grid**, the geometric midpoints between the training penetrations times the
   tilts :data:`VERIFY_TILT_FRACTIONS` (other tilts). The error estimates use the pooled orders of the job's own
   3D reference sweep (the same levels of the same ring), so every 3D point of the run carries the same kind of
   bar; the pressure maps are left out (:data:`DROPPED`);
2. fits the straight law on the training grid's zero-tilt points (``foundation-spline``, the flexible family; every
   family is fitted beside it, leave-one-out, for the report) and the tilt correction
   (:func:`contact.calibrate.tilt_fit.with_tilt_correction`: smoothing by cross-validation on the training points
   alone) on its tilted points;
3. checks the corrected law and, for comparison, the straight law the job chose before (slices alone) on the
   verification grid and on the job's 3D reference points that are not training points (:func:`correct`): the
   zero-tilt force, the tilted force and moment of the compiled kernel, each against issue 37's target (2x the FEM
   point's stated error + 0.2 %, :func:`contact.calibrate.fit.within_accuracy`);
4. ships the corrected law when, on the training grid, its cross-validated worst error over its bound (tilted
   force and moment) is not larger than the straight law's at the same points (decided before any held-out point
   is looked at), flagged when any held-out point misses the target; the straight law is written beside it (the
   rotor's step loops do not evaluate a correction yet, ``rotor.dynamics.kernels``).
"""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np

from contact import calibrate as cal
from contact.calibrate import spline, tilt_fit
from contact.calibrate.fit import ACCURACY_ADD_REL, ACCURACY_FEM_FACTOR, ACCURACY_RULE
from contact.dataset import read_dataset, write_dataset
from contact.units import ARCMIN, MM
from fem_reference.ring_scene import RingScene

#: tilts of the training grid, as fractions of the range's largest tilt (the 20 mm ring's 0-8' grid of
#: reports/published/law-tilt-correction/, where the correction's form was chosen)
TRAIN_TILT_FRACTIONS = (0.0, 1 / 32, 1 / 16, 1 / 8, 3 / 16, 5 / 16, 7 / 16, 5 / 8, 13 / 16, 1.0)
#: mid-plane penetrations of the training grid, geometric over the range (ends included)
TRAIN_PENETRATIONS = 13
#: tilts of the verification grid (fractions of the largest tilt; none of them a training tilt)
VERIFY_TILT_FRACTIONS = (0.0, 3 / 32, 1 / 4, 1 / 2, 7 / 8)
#: columns left out of the grids' datasets (the pressure maps: most of a point's size, not needed to fit or check)
DROPPED = ("pressure_phi_rad", "pressure_x_m", "pressure_map_pa")
QUANTITIES = ("force, zero tilt", "force, tilted", "moment, tilted")


def grid_files(name: str) -> dict[str, str]:
    """The grids' dataset files in the run folder."""
    return {"train": f"fem3d-tilt-train-{name}.json", "verify": f"fem3d-tilt-verify-{name}.json"}


def _sig4(v: float) -> float:
    return float(f"{v:.4g}")


def grids(rs: RingScene) -> dict[str, tuple[list[float], list[float]]]:
    """``{"train": (tilts_rad, penetrations_m), "verify": (...)}``: the two grids of ``rs``'s range (tilt rad,
    mid-plane penetration m, the inner penetrations rounded to 4 significant digits)."""
    lo, hi = rs.penetration_range_m
    t_hi = rs.tilt_range_rad[1]
    ratio = (hi / lo) ** (1.0 / (TRAIN_PENETRATIONS - 1))
    train = [lo] + [_sig4(lo * ratio ** k) for k in range(1, TRAIN_PENETRATIONS - 1)] + [hi]
    verify = [_sig4(lo * ratio ** (k + 0.5)) for k in range(TRAIN_PENETRATIONS - 1)]
    return {"train": ([f * t_hi for f in TRAIN_TILT_FRACTIONS], train),
            "verify": ([f * t_hi for f in VERIFY_TILT_FRACTIONS], verify)}


def grid_points(rs: RingScene) -> int:
    """How many 3D points the two grids of ``rs`` solve."""
    return sum(len(t) * len(p) for t, p in grids(rs).values())


def run_grids(rs: RingScene, out: Path, fem3d_path: Path, *, workers: int, executor, fresh: bool,
              progress) -> dict[str, Path]:
    """Solve both grids (:func:`grids`) into the run folder (:func:`grid_files`); finished points are kept in the
    3D sweep store under the cache, so an interrupted run resumes. Error bars with the orders pooled over the
    job's 3D reference sweep ``fem3d_path``."""
    from fem_reference.solid import sweep as solid
    from fem_reference.solid.richardson import apply_orders

    ref = read_dataset(fem3d_path)
    orders = ref.metadata["error_orders"]
    columns = {k: v for k, v in solid.COLUMNS.items() if k not in DROPPED}
    paths = {}
    for which, (tilts, pens) in grids(rs).items():
        meta, points = solid.sweep_dataset(tilts_rad=tilts, penetrations_m=pens, scene=rs.bc_3d, geom=rs.rings_3d(),
                                           workers=workers, executor=executor, progress=progress, resume=not fresh,
                                           label=rs.name, description=rs.scene.description)
        points = [{k: v for k, v in apply_orders(p, orders).items() if k not in DROPPED} for p in points]
        meta["error_orders"] = orders
        meta["grid"] = {"role": which, "tilts_arcmin": [t / ARCMIN for t in tilts],
                        "penetrations_mm": [p / MM for p in pens], "left_out": list(DROPPED),
                        "error_orders_from": fem3d_path.name, "made_by": "reports/bearing/tilt.py"}
        meta["ring_scene"] = {"name": rs.name, "sha256": rs.sha256, "document": rs.document}
        paths[which] = write_dataset(out / grid_files(rs.name)[which], meta, columns, points)
    return paths


def _key(p: dict) -> tuple[int, int]:
    return round(p["penetration_m"] * 1e12), round(p["tilt_rad"] * 1e12)


def errors(law, points: list[dict]) -> dict[str, tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    """Relative errors (–) of ``law`` at FEM points and their bounds (2x the stated error + 0.2 %), per quantity of
    :data:`QUANTITIES`: ``(error, bound, penetration_m, tilt_rad)``. Zero tilt: the law's force; tilted: force and
    moment of the compiled kernel (:func:`contact.calibrate.tilt_fit.held_out`). NaN errors for a law the kernel
    cannot evaluate."""
    zero = [p for p in points if p["tilt_rad"] == 0 and p["penetration_m"] > 0]
    pen0 = np.array([p["penetration_m"] for p in zero])
    b0 = ACCURACY_FEM_FACTOR * np.array([p.get("force_error_rel") or 0.0 for p in zero]) + ACCURACY_ADD_REL
    e0 = np.asarray(law.force(pen0).force_N) / np.array([p["force_n"] for p in zero]) - 1.0
    out = {QUANTITIES[0]: (e0, b0, pen0, np.zeros(pen0.size))}
    try:
        h = tilt_fit.held_out(law, points)
    except cal.InputError:                                  # a family outside the compiled kernel
        tilted = [p for p in points if p["tilt_rad"] > 0]
        nan = np.full(len(tilted), math.nan)
        pm, t = (np.array([p[k] for p in tilted]) for k in ("penetration_m", "tilt_rad"))
        h = {"force_error": nan, "moment_error": nan, "bound_force": nan, "bound_moment": nan,
             "penetration_m": pm, "tilt_rad": t}
    out[QUANTITIES[1]] = (h["force_error"], h["bound_force"], h["penetration_m"], h["tilt_rad"])
    out[QUANTITIES[2]] = (h["moment_error"], h["bound_moment"], h["penetration_m"], h["tilt_rad"])
    return out


def tally(err: np.ndarray, bound: np.ndarray) -> dict:
    """``points``, ``within`` (the target met), ``worst_ratio`` (largest ``|error| / bound``; inf if any error is not
    finite), ``worst_error_pct`` and ``worst_bound_pct`` at that point."""
    err, bound = np.abs(np.asarray(err, dtype=float)), np.asarray(bound, dtype=float)
    if not err.size:
        return {"points": 0, "within": 0, "worst_ratio": 0.0, "worst_error_pct": None, "worst_bound_pct": None}
    ratio = np.where(np.isfinite(err), err / bound, math.inf)
    i = int(np.argmax(ratio))
    return {"points": int(err.size), "within": int(np.sum(ratio <= 1.0)), "worst_ratio": float(ratio[i]),
            "worst_error_pct": 100 * float(err[i]) if np.isfinite(err[i]) else None,
            "worst_bound_pct": 100 * float(bound[i])}


def _base_law(rs: RingScene, path: Path):
    """The straight law the correction multiplies: ``foundation-spline`` fitted on the training grid's zero-tilt
    points, whatever family the zero-tilt selection rule prefers there (every family is fitted, leave-one-out, for
    the report). Returns (law, every family's fit, the training dataset, why)."""
    train = read_dataset(path)
    info = cal.dataset_provenance(path, train)
    info["path"] = path.name
    preferred, fits = cal.calibrate_scene(train, rs.name, info, families=cal.FAMILIES)
    law, _ = cal.calibrate_scene(train, rs.name, info, families=(spline.FAMILY,))
    rule = (f"the zero-tilt selection rule chooses it here too ({preferred.fit.get('selection_reason', '')})"
            if preferred.family == spline.FAMILY else
            f"the zero-tilt selection rule's choice here would be {preferred.family} "
            f"({preferred.fit.get('selection_reason', '')})")
    why = (f"the flexible family, interpolating the training grid's zero-tilt points: {rule}; the correction's form "
           f"was chosen on {spline.FAMILY} (reports/published/law-tilt-correction.md)")
    law = dataclasses.replace(law, fit={**law.fit, "families": preferred.fit.get("families", []),
                                        "selection_reason": why})
    return law, fits, train, why


def correct(rs: RingScene, fit: dict, paths: dict[str, Path]) -> dict:
    """The tilt correction of the job (module docstring, steps 2-4) against ``fit``'s straight 3D law (``fit``:
    :func:`reports.bearing.pipeline.calibrate`'s dict, with ``ds3`` and ``chosen``).

    Returns a dict: ``law`` (the corrected law), ``straight`` (the job's straight law), ``chosen`` (bool: the
    corrected law is shipped), ``holds`` (every held-out point of the corrected law within the target), ``sets``
    (per held-out set and quantity, :func:`tally` of the corrected and of the straight law), ``reason``, ``warnings``,
    ``trained`` (the training points' keys), ``base_fits`` and ``base_fem_error`` (the zero-tilt fit), ``record``
    (what the law file and the summary keep)."""
    base, base_fits, train, why = _base_law(rs, paths["train"])
    tilted = [p for p in train.points if p["tilt_rad"] > 0 and p["penetration_m"] > 0]
    law = tilt_fit.with_tilt_correction(base, tilted, source=paths["train"].name)
    trained = {_key(p) for p in train.points}
    committed = [p for p in fit["ds3"].points if p.get("scene", rs.name) == rs.name]
    held = [p for p in committed if _key(p) not in trained]
    verify = read_dataset(paths["verify"]).points
    straight = fit["chosen"]
    sets = {}
    for name, pts in (("verification grid", verify), ("3D reference points", held)):
        after, before = errors(law, pts), errors(straight, pts)
        sets[name] = {q: {"corrected": tally(*after[q][:2]), "straight": tally(*before[q][:2]),
                          "misses": _misses(*after[q]), "error": after[q][0], "bound": after[q][1]} for q in QUANTITIES}
    info = law.fit["tilt_correction"]
    # the choice is made on the training grid alone: the correction's cross-validated worst error over its bound
    # against the straight law's at the same tilted points (which that law, fitted at zero tilt, never saw)
    own = errors(straight, tilted)
    cv = info["cross_validation_worst_error_over_bound"]
    worst = {"corrected": cv[tilt_fit.smoothing_label(info["smoothing"])],
             "straight": max(tally(*own[q][:2])["worst_ratio"] for q in QUANTITIES[1:])}
    chosen = worst["corrected"] <= worst["straight"]
    holds = all(sets[s][q]["corrected"]["within"] == sets[s][q]["corrected"]["points"] for s in sets for q in QUANTITIES)
    reason = _reason(law, straight, sets, worst, chosen, len(tilted), info["smoothing"])
    warnings = []
    if chosen and not holds:
        miss = [m for s in sets for q in QUANTITIES for m in sets[s][q]["misses"]]
        warnings.append(f"tilt correction: {len(miss)} held-out point(s) miss issue 37's target ({ACCURACY_RULE}): "
                        + "; ".join(miss[:4]) + ("; …" if len(miss) > 4 else ""))
    record = {"chosen": chosen, "holds": holds, "reason": reason, "base_law": base.name, "base_why": why,
              "training_points": {"zero_tilt": len(train.points) - len(tilted), "tilted": len(tilted)},
              "files": {k: Path(v).name for k, v in paths.items()}, "smoothing": info["smoothing"],
              "cross_validation_worst_error_over_bound": info["cross_validation_worst_error_over_bound"],
              "reference_points_left_out_as_training": len(committed) - len(held),
              "straight_law": straight.name, "target": ACCURACY_RULE,
              "sets": {s: {q: {w: sets[s][q][w] for w in ("corrected", "straight")} for q in QUANTITIES} for s in sets}}
    best = next(f for f in base_fits if f.family == base.family)
    return {"law": law, "straight": straight, "chosen": chosen, "holds": holds, "sets": sets, "reason": reason,
            "warnings": warnings, "trained": trained, "base_fits": base_fits, "base_fit": best,
            "base_fem_error": cal.scene_points(train, rs.name)[2], "record": record}


def _misses(err, bound, pen, tilt) -> list[str]:
    bad = np.flatnonzero(~(np.abs(err) <= bound))
    return [f"{pen[i] / MM * 1e3:.4g} µm, {tilt[i] / ARCMIN:g}′: {100 * err[i]:+.3f} % vs {100 * bound[i]:.3f} %"
            for i in bad]


def _count(sets: dict, who: str, q: str) -> str:
    w = sum(sets[s][q][who]["within"] for s in sets)
    n = sum(sets[s][q][who]["points"] for s in sets)
    return f"{w}/{n}"


def _reason(law, straight, sets, worst, chosen, n_fitted, smoothing) -> str:
    """Why the corrected law is shipped (or not), decided on the training grid, with the held-out counts."""
    why = (f"on the training grid its worst error over its bound, force and moment, is {worst['corrected']:.2f} "
           f"cross-validated against {worst['straight']:.2f} for the straight law `{straight.name}` (slices alone)")
    counts = (f"held out (verification grid and reference points), tilted force within the target at "
              f"{_count(sets, 'corrected', QUANTITIES[1])} points and moment at {_count(sets, 'corrected', QUANTITIES[2])} "
              f"with the correction, {_count(sets, 'straight', QUANTITIES[1])} and "
              f"{_count(sets, 'straight', QUANTITIES[2])} with the straight law")
    what = (f"`{law.name}`: the slices multiplied by a tilt correction fitted on the training grid's {n_fitted} "
            f"tilted points (smoothing {tilt_fit.smoothing_label(smoothing)}, chosen by {tilt_fit.FOLDS}-fold "
            "cross-validation on them alone)")
    return f"{what} is {'shipped' if chosen else 'not shipped, the straight law is'}: {why}; {counts}"


def accuracy_rows(tc: dict) -> list[dict]:
    """Rows of :func:`reports.bearing.pipeline.accuracy` for the corrected law's held-out points that the 3D
    reference rows do not cover: the verification grid (zero tilt, tilted force and moment) and the reference points'
    zero-tilt force (the tilted reference points are the rows of the chosen law's Table 3)."""
    out = []
    for s, q, ref, quantity in (("verification grid", QUANTITIES[0], "3d verification grid, zero tilt", "force"),
                                ("verification grid", QUANTITIES[1], "3d verification grid, tilted", "force"),
                                ("verification grid", QUANTITIES[2], "3d verification grid, tilted", "moment"),
                                ("3D reference points", QUANTITIES[0], "3d zero tilt, reference points", "force")):
        err, bound = np.abs(tc["sets"][s][q]["error"]), tc["sets"][s][q]["bound"]
        if not err.size:
            continue
        within = np.isfinite(err) & (err <= bound)
        i = int(np.argmax(np.where(np.isfinite(err), err - bound, math.inf)))
        out.append({"reference": ref, "quantity": quantity, "points": int(err.size), "within": int(within.sum()),
                    "holds": bool(within.all()), "worst_error_pct": 100 * float(err[i]),
                    "worst_bound_pct": 100 * float(bound[i]), "within_inside": None})
    return out


def rows_held(rows: list[dict], trained: set) -> list[dict]:
    """Table 3 rows (:func:`reports.accuracy.tilted.table3_rows`) of points that are not training points."""
    return [r for r in rows if (round(r["penetration_mm"] * MM * 1e12), round(r["tilt_arcmin"] * ARCMIN * 1e12))
            not in trained]


def report_lines(tc: dict | None) -> list[str]:
    """The report's section on the tilt correction: the held-out table, corrected against straight, and why."""
    if tc is None:
        return []
    rec = tc["record"]
    lines = ["## Tilt correction (fitted on a training grid, checked held out)", "",
             f"Training grid `{rec['files']['train']}`: the straight law `{rec['base_law']}` on its "
             f"{rec['training_points']['zero_tilt']} zero-tilt points ({rec['base_why']}), the correction on its "
             f"{rec['training_points']['tilted']} tilted points. Held out: the verification grid "
             f"`{rec['files']['verify']}` (penetrations between the training ones, other tilts) and the 3D reference "
             f"points that are not training points ({rec['reference_points_left_out_as_training']} coincide and are "
             f"left out). Target: {rec['target']}.", "",
             "| held-out points | quantity | law | within / all | worst error (%) | its bound (%) |",
             "|---|---|---|---|---|---|"]
    for s, per in rec["sets"].items():
        for q, both in per.items():
            for who, label in (("corrected", "with correction"), ("straight", f"straight `{rec['straight_law']}`")):
                t = both[who]
                if not t["points"]:
                    continue
                err = "–" if t["worst_error_pct"] is None else f"{t['worst_error_pct']:.3f}"
                lines.append(f"| {s} | {q} | {label} | {t['within']} / {t['points']} | {err} | "
                             f"{t['worst_bound_pct']:.3f} |")
    verdict = "every held-out point within the target" if rec["holds"] else "**not every held-out point within the target**"
    return lines + ["", f"Why: {rec['reason']}. Verdict of the corrected law: {verdict}.", ""]
