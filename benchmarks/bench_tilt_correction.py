"""Issue 37, must-show 3, the tilted part: a law with a tilt correction, fitted on one grid of 3D points and checked on
others (force and moment), and its kernel cost against today's foundation law.

    .venv/bin/python benchmarks/bench_tilt_correction.py [--points 20000] [--repeats 9] [--out reports/published]
    .venv/bin/python benchmarks/bench_tilt_correction.py --blind 48 [--seed S]

For each ring (:data:`RINGS`: the 20 mm ring of ``law-family.md`` and the bundled steel-in-aluminium pair):

1. **Fit** on the training grid ``law-tilt-correction/fem3d-tilt-train-<ring>.json`` (benchmarks/fem3d_tilt_grid.py):
   the straight law (``foundation-spline``) on its zero-tilt points, then the tilt correction
   (:func:`contact.calibrate.tilt_fit.with_tilt_correction`, smoothing by cross-validation on these points only) on
   its tilted points with a mid-plane penetration > 0.
2. **Check held out** on points the fit never saw: the ring's committed 3D points (its run folder's
   ``fem3d-<ring>.json``: the points ``law-family.md`` checks; a committed point that is also a training point is
   left out of the check and counted) and the verification grid ``fem3d-tilt-verify-<ring>.json`` (penetrations
   between the training ones, other tilts). Zero tilt: the law's force; tilted: force and moment of the compiled
   kernel (the ring centre at ``y = δ0 + Δr``, tilt about z, as the FEM). Target: every error within 2x the FEM
   point's stated error + 0.2 %. The same points through the published law (slices, no correction) for comparison.
   Verification points with a negative mid-plane penetration (the edge alone in contact; outside the range
   0.0005-0.03 mm) are reported apart, not in the verdict.
3. **Kernel cost** as ``law-family.md`` measures it (:func:`bench_law_family.kernel_cost`'s states and loop):
   today's foundation law (the kernel of 3a38b5f), this kernel's foundation, foundation-spline and the 20 mm ring's
   law with its tilt correction, straight and tilted 0-8'.

Writes ``<out>/law-tilt-correction.md`` and the laws ``<out>/law-tilt-correction/<ring>-tilt-law.json``.

``--blind N`` alone (no fit, no kernel timing): a blind check of the 20 mm ring's committed law on N new tilted points
and N // 8 zero-tilt ones drawn from ``--seed`` (default: a new one each run, printed), solved on the cached 3D levels
(:mod:`tilt_blind`); it writes ``<out>/law-tilt-correction/fem3d-tilt-blind-newcomer-20mm.json`` and replaces the
report's blind section, which a full run recomputes from the kept points with the law it writes (none solved).
"""
from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from contact.threads import set_thread_env  # noqa: E402

set_thread_env(1)     # before numpy loads: one BLAS thread (the 3D points of --blind; a shared 2-core machine)

import numpy as np  # noqa: E402
import bench_law_family as family  # noqa: E402
import tilt_blind  # noqa: E402
import tilt_smoothing_cv  # noqa: E402
from contact import calibrate as cal  # noqa: E402
from contact.calibrate import tilt_fit  # noqa: E402
from contact.calibrate.fit import ACCURACY_RULE  # noqa: E402
from contact.dataset import read_dataset  # noqa: E402
from contact.files import atomic_write_text  # noqa: E402
from contact.loose_support import N_PARAMS, point_force_jacobian  # noqa: E402
from contact.units import ARCMIN  # noqa: E402
from reports.cli._edge import Parser, count, out_dir  # noqa: E402

PUBLISHED = ROOT / "reports" / "published"
#: ring -> its run folder under reports/published and its published law file there
RINGS = {"newcomer-20mm": ("law-family-newcomer-20mm", "newcomer-20mm-law.json"),
         "steel-in-aluminium": ("bearing-steel-in-aluminium", "steel-in-aluminium-law.json")}


def _key(p: dict) -> tuple:
    return round(p["penetration_m"] * 1e12), round(p["tilt_rad"] * 1e12)


def fit_ring(ring: str, out: Path) -> dict:
    """The ring's straight law and its tilt correction fitted on the training grid; wall time (s)."""
    folder = out / "law-tilt-correction"
    path = folder / f"fem3d-tilt-train-{ring}.json"
    train = read_dataset(path)
    t0 = time.perf_counter()
    straight, _ = cal.calibrate_scene(train, ring, cal.dataset_provenance(path, train), families=("foundation-spline",))
    tilted = [p for p in train.points if p["tilt_rad"] > 0 and p["penetration_m"] > 0]
    law = tilt_fit.with_tilt_correction(straight, tilted, source=f"law-tilt-correction/{path.name}")
    return {"law": law, "train": train.points, "fit_s": time.perf_counter() - t0, "tilted_fitted": len(tilted),
            "straight": straight, "tilted": tilted}


def errors(law, points: list[dict]) -> dict:
    """Relative errors of ``law`` against FEM points and their bounds: zero tilt force (the law's), tilted force
    and moment (the compiled kernel's); arrays keyed ``zero_force``, ``tilted_force``, ``tilted_moment``, each with
    ``_bound``, and the tilted points' ``penetration_m``, ``tilt_rad``."""
    zero = [p for p in points if p["tilt_rad"] == 0 and p["penetration_m"] > 0]
    pen0 = np.array([p["penetration_m"] for p in zero])
    f0 = np.array([p["force_n"] for p in zero])
    b0 = 2 * np.array([p.get("force_error_rel") or 0.0 for p in zero]) + 0.002
    out = {"zero_force": np.asarray(law.force(pen0).force_N) / f0 - 1, "zero_force_bound": b0}
    h = tilt_fit.held_out(law, points)
    out.update(tilted_force=h["force_error"], tilted_force_bound=h["bound_force"], tilted_moment=h["moment_error"],
               tilted_moment_bound=h["bound_moment"], penetration_m=h["penetration_m"], tilt_rad=h["tilt_rad"])
    return out


def _row(name: str, err: np.ndarray, bound: np.ndarray) -> str:
    if not err.size:
        return f"| {name} | – | – | – | – |"
    ok = np.abs(err) <= bound
    i = int(np.argmax(np.abs(err) - bound))
    return (f"| {name} | {int(ok.sum())} / {err.size} | {'yes' if ok.all() else 'no'} | {100 * np.max(np.abs(err)):.3f} "
            f"| {100 * abs(err[i]):.3f} vs {100 * bound[i]:.3f} |")


def check_ring(ring: str, fitted: dict, out: Path) -> dict:
    """Held-out errors of the tilt law and of the published law on the committed and the verification points."""
    folder, law_file = RINGS[ring]
    before = cal.CalibratedLaw.from_json((out / folder / law_file).read_text(encoding="utf-8"))
    train = {_key(p) for p in fitted["train"]}
    committed = read_dataset(out / folder / f"fem3d-{ring}.json").points
    held = [p for p in committed if _key(p) not in train]
    verify = read_dataset(out / "law-tilt-correction" / f"fem3d-tilt-verify-{ring}.json").points
    inside = [p for p in verify if p["penetration_m"] > 0]
    beyond = [p for p in verify if p["penetration_m"] <= 0]
    sets = {"committed": held, "verification grid": inside}
    res = {"coincide": len(committed) - len(held), "committed": len(committed), "sets": {}, "beyond": None,
           "points": sets}
    for name, pts in sets.items():
        res["sets"][name] = {"after": errors(fitted["law"], pts), "before": errors(before, pts)}
    if beyond:
        res["beyond"] = {"after": errors(fitted["law"], beyond), "before": errors(before, beyond)}
    res["before_name"] = before.name
    return res


def cv_lines(info: dict) -> list[str]:
    """The cross-validation the smoothing was chosen by: worst held-out error over its bound, force and moment, per
    pair of weights (rows along ξ, columns along ψ)."""
    cv, grid = info["cross_validation_worst_error_over_bound"], tilt_fit.SMOOTHING_GRID
    chosen = tilt_fit.smoothing_label(info["smoothing"])
    lines = ["Cross-validated worst error over its bound (force and moment) per smoothing; rows: along ξ (ln r), "
             "columns: along ψ (φ); the chosen one in bold:", "", "| along ξ ↓, along ψ → | "
             + " | ".join(f"{s:g}" for s in grid) + " |", "|---|" + "---|" * len(grid)]
    for sx in grid:
        keys = [tilt_fit.smoothing_label((sx, sp)) for sp in grid]
        lines.append(f"| {sx:g} | " + " | ".join(f"**{cv[k]:.2f}**" if k == chosen else f"{cv[k]:.2f}" for k in keys)
                     + " |")
    return lines


def ring_lines(ring: str, fitted: dict, checked: dict) -> list[str]:
    law = fitted["law"]
    info = law.fit["tilt_correction"]
    sx, sp = info["smoothing"]
    lines = [f"### {ring}", "",
             f"Fitted on `law-tilt-correction/fem3d-tilt-train-{ring}.json`: the straight law (`foundation-spline`) "
             f"on its zero-tilt points, the tilt correction on its {fitted['tilted_fitted']} tilted points "
             f"({fitted['fit_s']:.1f} s; smoothing {sx:g} along ξ and {sp:g} along ψ, chosen by {tilt_fit.FOLDS}-fold "
             "cross-validation on those points alone: the table below). "
             f"Law file: [{law.name}-law.json](law-tilt-correction/{law.name}-law.json). Checked on points the fit "
             f"never saw: the {checked['committed'] - checked['coincide']} committed 3D points of the ring's run "
             f"folder that are not training points ({checked['coincide']} of {checked['committed']} coincide with "
             "training points and are left out) and the verification grid "
             f"`law-tilt-correction/fem3d-tilt-verify-{ring}.json`. (The published law was fitted on the committed "
             "zero-tilt points, so its zero-tilt rows there are not held out.)", ""] + cv_lines(info) + ["",
             "| held-out points | quantity | law | within / all | holds | largest error (%) | worst: error vs bound (%) |",
             "|---|---|---|---|---|---|---|"]
    for set_name, both in checked["sets"].items():
        for q, label in (("zero_force", "force, zero tilt"), ("tilted_force", "force, tilted"),
                         ("tilted_moment", "moment, tilted")):
            for which, lname in (("before", f"published `{checked['before_name']}` (slices)"),
                                 ("after", f"`{law.name}` (slices + correction)")):
                e = both[which]
                lines.append(_row(f"{set_name} | {label} | {lname}", e[q], e[q + "_bound"]))
    verdict = all(np.all(np.abs(both["after"][q]) <= both["after"][q + "_bound"]) for both in checked["sets"].values()
                  for q in ("zero_force", "tilted_force", "tilted_moment"))
    lines += ["", f"**{ring}: the law with its tilt correction {'meets' if verdict else 'does not meet'} the target "
              "at every held-out point, force and moment.**"]
    if checked["beyond"] is not None:
        b = checked["beyond"]
        lines += ["", f"Beyond the range (verification points with a negative mid-plane penetration, the loaded edge "
                  f"alone in contact; not fitted, not in the verdict): tilted force error "
                  f"{100 * np.max(np.abs(b['after']['tilted_force'])):.1f} % at most with the correction, "
                  f"{100 * np.max(np.abs(b['before']['tilted_force'])):.1f} % without; moment "
                  f"{100 * np.max(np.abs(b['after']['tilted_moment'])):.1f} % and "
                  f"{100 * np.max(np.abs(b['before']['tilted_moment'])):.1f} %."]
    return lines + [""], verdict


def slice_error_lines(ring: str, out: Path) -> list[str]:
    """The published law's (slices') tilted errors over the training grid: the data the correction's form comes from."""
    folder, law_file = RINGS[ring]
    law = cal.CalibratedLaw.from_json((out / folder / law_file).read_text(encoding="utf-8"))
    pts = [p for p in read_dataset(out / "law-tilt-correction" / f"fem3d-tilt-train-{ring}.json").points
           if p["tilt_rad"] > 0 and p["penetration_m"] > 0]
    h = tilt_fit.held_out(law, pts)
    tilts = sorted(set(h["tilt_rad"]))
    pens = sorted(set(h["penetration_m"]))
    lines = []
    for q, label in (("moment_error", "moment"), ("force_error", "force")):
        lines += [f"Slices' (published `{law.name}`) {label} error (%) over the training grid; rows: mid-plane "
                  "penetration (µm), columns: tilt (′):", "",
                  "| Δr (µm) | " + " | ".join(f"{t / ARCMIN:g}" for t in tilts) + " |",
                  "|---|" + "---|" * len(tilts)]
        for pen in pens:
            cells = []
            for t in tilts:
                m = (h["penetration_m"] == pen) & (h["tilt_rad"] == t)
                cells.append(f"{100 * h[q][m][0]:+.2f}" if m.any() else "–")
            lines.append(f"| {pen * 1e6:.3g} | " + " | ".join(cells) + " |")
        lines.append("")
    return lines


def kernel_cost(law_tilt, n: int, repeats: int) -> tuple[dict, tuple]:
    """Median ns per call (point force with its Jacobian in a compiled loop) of today's foundation law and this
    kernel's foundation, foundation-spline and tilt-corrected laws of the 20 mm ring, straight and tilted; load."""
    laws = family.ring_laws(PUBLISHED / RINGS["newcomer-20mm"][0])
    with tempfile.TemporaryDirectory() as tmp:
        old = family.todays_kernel(Path(tmp))
        old_loop, new_loop = family.make_loop(old.point_force_jacobian), family.make_loop(point_force_jacobian)
        p_found = tuple(laws["foundation"].loose_support_params(mu=0.0, preload_N=0.0).kernel_args)
        p_spline = tuple(laws["foundation-spline"].loose_support_params(mu=0.0, preload_N=0.0).kernel_args)
        p_tilt = tuple(law_tilt.loose_support_params(mu=0.0, preload_N=0.0).kernel_args)
        cases = {}
        for tilted in (False, True):
            x = family.states(n, law_tilt.geometry.clearance_m, tilted)
            what = "tilted 0-8'" if tilted else "straight"
            cases[f"foundation, today's kernel ({family.TODAY}), {what}"] = (old_loop, x, p_found[:old.N_PARAMS])
            cases[f"foundation, this kernel, {what}"] = (new_loop, x, p_found)
            cases[f"foundation-spline, this kernel, {what}"] = (new_loop, x, p_spline)
            cases[f"{law_tilt.name} (spline + tilt correction), {what}"] = (new_loop, x, p_tilt)
        for fn, x, p in cases.values():
            fn(x[:10], p)
        l0 = family.load()
        times = {k: [] for k in cases}
        for _ in range(repeats):
            for k, (fn, x, p) in cases.items():
                t0 = time.perf_counter()
                fn(x, p)
                times[k].append((time.perf_counter() - t0) / x.shape[0] * 1e9)
        return {k: (statistics.median(v), min(v), max(v)) for k, v in times.items()}, (l0, family.load())


def cost_lines(cost: dict, loads: tuple, n: int, repeats: int) -> tuple[list[str], float]:
    lines = [f"{n} states per case, {repeats} interleaved repeats (the states and loop of `bench_law_family.py`); time "
             "per call of `point_force_jacobian` (force, moment and their 4x8 Jacobian) in a compiled loop, median "
             f"(min-max); load average {loads[0]:.2f} → {loads[1]:.2f} (2 cores shared).", "",
             "| case | ns per call, median | min-max | / today's foundation |", "|---|---|---|---|"]
    worst = 0.0
    for k, (med, lo, hi) in cost.items():
        ref = next(v[0] for key, v in cost.items() if key.startswith("foundation, today's")
                   and key.endswith(k.rsplit(", ", 1)[1]))
        ratio = med / ref
        if "tilt correction" in k:
            worst = max(worst, ratio)
        lines.append(f"| {k} | {med:.1f} | {lo:.1f}-{hi:.1f} | {ratio:.2f} |")
    return lines + ["", f"Largest ratio of the tilt-corrected law to today's foundation law: {worst:.2f} (target: at "
                    "most 2)."], worst


WHY = """## Why a correction, and why this form

The published law's tilted patch is integrated slice by slice (Winkler slices: each axial slice carries the 2D law of
its own penetration). The 3D ring couples its slices along the axis, which no fit of the straight law changes. The
tables below (the published law through the compiled kernel at the training grid's tilted points) are what the form
was chosen from:

- the **moment** is 2.2-13.6 % low everywhere, and the error depends on both the penetration and the tilt: at small
  tilt it is a property of the ring (the 3D ring's rotational stiffness over the slices': 2.3 % at 0.03 mm, 5 % at
  0.005 mm), and it rises to a plateau of 12-13.6 % once the patch is partial (small penetration, large tilt);
- the **force** is exact at zero tilt (the straight law), up to 4.2 % low for a partial patch at small penetration,
  and up to 0.7 % *high* near the slices' full/partial transition (Δr ≈ (1-2) θ l0/2): not monotone, so a monotone
  correction cannot represent it.

The coordinates that make this smooth are polar ones of the patch: ``r = sqrt(Δr_m² + (θ l0/2)²)`` and
``φ = atan2(θ l0/2, Δr_m)`` (Δr_m the mid-plane penetration): ``φ = 0`` is the straight ring, ``π/4`` the slices'
transition, ``π/2`` a patch from the loaded edge to the mid-plane, and the transition sits at the same ``φ`` at
every ``r``. The correction multiplies the slices' patch load by ``exp(a(ξ, ψ))`` and its moment by ``exp(b(ξ, ψ))``,
``ξ`` = ``ln r`` scaled to [0, 1] over the law's range and ``ψ = φ/(3π/4)``; ``a``, ``b`` are tensor products of
uniform cubic B-splines on 4 x 6 intervals with mirrored end coefficients, fitted by penalised weighted least squares
(P-splines, Eilers & Marx 1996; each point weighted by 1/its bound; one penalty weight along ξ and one along ψ, as
tensor-product P-splines have, chosen by cross-validation on the training points: below). Built in, not fitted: ``a = 0`` at zero tilt
(the straight law is the zero-tilt limit, bit for bit), zero slope across ``φ = 0`` (at a fixed mid-plane
penetration both corrections are even in θ with continuous first and second derivatives through θ = 0, so the force
stays even and the moment odd), the moment zero at zero tilt (it multiplies the slices' moment), C² inside the range,
C¹ and constant beyond it. The kernel evaluates it with its exact derivatives
(contact/_kernel_tilt.py).

Tried in this session and dropped (exploration scripts, not rerun here): (1) surfaces of this kind fitted to the 18
committed tilted points alone: held out (leave-one-out, or alternate points) 0.5-1.6 % worst for the best settings
tried, up to 5 times the bounds (0.2-0.6 %): the committed grid (penetrations a factor 2.3 apart, tilts 2, 4, 8′) is too coarse for the transition
at φ ≈ π/4; hence the training grid (the cached 3D levels solve a point in about 0.5 s); (2) physical few-parameter
corrections of the slices, a shear layer between the slices (Pasternak 1954: a patch shortened by a length and an
edge force, and variants): worst error 5-19 times the bound after a fit on all points, so no such form holds.
"""


DIRECTIONS = """## One smoothing weight per direction

The correction's penalty has one weight along ξ (``ln r``) and one along ψ (``φ``), the pair chosen by the
cross-validation above (the same criterion as before: the worst held-out error over its bound, force and moment, on
the training points alone). The run before this one shared one weight between the directions; the surfaces are not
alike along them: along ψ the moment's correction rises sharply where the slices' patch turns partial
(φ ≈ π/4: the tables above), along ξ it changes slowly, and one weight smooths that rise away. The lines below
recompute, per ring, the law the one-weight rule picks and each point where it misses, with the ξ weight and then
the ψ weight alone swept over the grid.

This rule was adopted after the verification grid had shown the miss, so for the 20 mm ring that grid is no longer
blind. `benchmarks/tilt_smoothing_cv.py` compares the two rules on the training points alone (nested
cross-validation: the rule, its cross-validation included, run without one outer fold and checked on it); see the
sentence after the lines. It also prints the straight law's share in the miss: the slices' moment at the point with the
spline's knots chosen otherwise (written when the spline held 12 knots with PCHIP slopes: another of the 13 training
penetrations dropped, or C² not-a-knot knot slopes instead of PCHIP's; since b832f06 and ebe06fe the straight law has
all 13 as knots with the not-a-knot slopes)."""


def direction_lines(rings: dict) -> list[str]:
    """Per ring: the law the one-weight rule picks (the best of the cross-validation's diagonal), its held-out
    misses, and at each the error with that weight along ψ and each of the grid's along ξ, then with it along ξ and
    each along ψ: which direction's smoothing makes the miss."""
    lines = DIRECTIONS.splitlines() + [""]
    label = tilt_fit.smoothing_label
    for ring, (fitted, checked) in rings.items():
        info = fitted["law"].fit["tilt_correction"]
        cv = info["cross_validation_worst_error_over_bound"]
        one = min(tilt_fit.SMOOTHING_GRID, key=lambda s: cv[label(s)])
        chosen = tuple(info["smoothing"])
        head = (f"- {ring}: one weight picks {one:g} (cross-validated worst {cv[label(one)]:.2f}), one per direction "
                f"{label(chosen)} ({cv[label(chosen)]:.2f})")
        if chosen == (one, one):
            lines.append(head + ": the same law.")
            continue
        pairs = [(g, one) for g in tilt_fit.SMOOTHING_GRID] + [(one, g) for g in tilt_fit.SMOOTHING_GRID if g != one]
        laws = {s: tilt_fit.with_tilt_correction(fitted["straight"], fitted["tilted"], smoothing=s) for s in pairs}
        found = []
        for set_name, pts in checked["points"].items():
            h = {s: tilt_fit.held_out(law, pts) for s, law in laws.items()}
            for q in ("force", "moment"):
                err, bound = h[(one, one)][f"{q}_error"], h[(one, one)][f"bound_{q}"]
                for i in np.flatnonzero(np.abs(err) > bound):
                    sweep = [", ".join(f"{s[k]:g}: {100 * h[s][f'{q}_error'][i]:+.3f} %"
                                       for s in sorted((s for s in pairs if s[1 - k] == one), key=lambda s: s[k]))
                             for k in (0, 1)]
                    found.append(f"  - {set_name}, {q} at {h[(one, one)]['penetration_m'][i] * 1e6:.3g} µm and "
                                 f"{h[(one, one)]['tilt_rad'][i] / ARCMIN:g}′, bound {100 * bound[i]:.3f} %: with "
                                 f"{one:g} along ψ and along ξ {sweep[0]}; with {one:g} along ξ and along ψ "
                                 f"{sweep[1]}")
        lines += [head + f"; with one weight {len(found)} held-out point(s) miss" + (":" if found else ".")] + found
    return lines + [""] + [nested_line(rings)]


def nested_line(rings: dict) -> str:
    """The nested cross-validation of the two rules (``tilt_smoothing_cv.nested``), one sentence."""
    parts = []
    for ring, (fitted, _) in rings.items():
        rows = tilt_smoothing_cv.nested(fitted["straight"], tilt_fit.log_ratios(fitted["straight"], fitted["tilted"]))
        parts.append(f"{ring} " + ", ".join(f"{r['one']['moment_rms']:.3f} → {r['per']['moment_rms']:.3f} "
                                            f"({r['one']['outside']} → {r['per']['outside']} outside)" for r in rows))
    outer = ", ".join(f"{f} folds seed {s}" for f, s in tilt_smoothing_cv.OUTER)
    return ("Nested cross-validation on the training points alone (outer partitions: " + outer + "), one weight → one "
            "per direction: the root mean square of the held-out moment error over its bound (points outside their "
            "bound, force or moment): " + "; ".join(parts) + ".")


def misses(rings: dict) -> list[str]:
    """Every held-out point of a law with its correction outside the target, said with its error and bound."""
    out = []
    for ring, (_, checked) in rings.items():
        for set_name, both in checked["sets"].items():
            e = both["after"]
            for q, label in (("tilted_force", "force"), ("tilted_moment", "moment")):
                bad = np.flatnonzero(np.abs(e[q]) > e[q + "_bound"])
                out += [f"{ring}, {set_name}, {label} at {e['penetration_m'][i] * 1e6:.3g} µm and "
                        f"{e['tilt_rad'][i] / ARCMIN:g}′: {100 * e[q][i]:+.3f} % against a bound of "
                        f"{100 * e[q + '_bound'][i]:.3f} %" for i in bad]
            bad = np.flatnonzero(np.abs(e["zero_force"]) > e["zero_force_bound"])
            out += [f"{ring}, {set_name}, zero-tilt force: {100 * e['zero_force'][i]:+.3f} %" for i in bad]
    return out


def report(rings: dict, cost: tuple, args, wall_s: float) -> tuple[str, bool]:
    lines = ["# The tilted law: Winkler slices with a fitted tilt correction, held out (issue 37, must-show 3)", "",
             f"Generated by `benchmarks/bench_tilt_correction.py --points {args.points} --repeats {args.repeats}` "
             f"({wall_s:.0f} s; re-run it to replace these numbers). Target: {ACCURACY_RULE}.", "",
             "Grids: `benchmarks/fem3d_tilt_grid.py` on the rings' cached 3D levels (Q0-Q2 and the Q3 check level of "
             "their `ringcontact bearing` runs), one core, points in `law-tilt-correction/`.", ""]
    lines += WHY.splitlines() + [""] + slice_error_lines("newcomer-20mm", PUBLISHED) + ["## Held out", ""]
    held = True
    for ring, (fitted, checked) in rings.items():
        rl, ok = ring_lines(ring, fitted, checked)
        lines += rl
        held &= ok
    lines += direction_lines(rings) + [""]
    miss = misses(rings)
    cl, worst = cost_lines(*cost, args.points, args.repeats)
    lines += ["## Kernel cost against today's foundation law", ""] + cl + [""]
    lines += ["## Verdict", "",
              f"Held out on both rings, force and moment: **{'met' if held else 'not met'}**"
              + (f" ({'; '.join(miss)})" if miss else "") + ". Kernel cost: "
              f"**{worst:.2f}x** today's foundation law ({'within' if worst <= 2 else 'beyond'} 2x).", "",
              "Not done here: `ringcontact bearing` does not fit the correction yet (its 20 mm ring law, "
              "`law-family.md`, is still the slices' alone); the rotor's step loops build the law's parameter tuple once, "
              f"as {N_PARAMS} slots (`law_tuple` in rotor/dynamics/production_loop.py and production_kernels.py), so they "
              "would drop a correction: `support_law_from_params` refuses a law with one (tried: sending "
              "rotor.dynamics.kernels.contact_point's long arrays to the long kernel is not enough, a Table 4 run "
              "with and without the correction came out identical; the loops must be compiled for the long tuple); "
              "the generated pairs of `law-family.md` are 2D (no tilt to correct).", ""]
    return "\n".join(lines), held and worst <= 2


def blind(args, out: Path) -> int:
    """``--blind N [--seed S]``: draw, solve and check the blind points; replace the report's blind section."""
    target = out / "law-tilt-correction.md"
    if not target.exists():
        print(f"bench_tilt_correction: error: --blind = {args.blind} points: needs the report {target} (a full run "
              "writes it)", file=sys.stderr)
        return 2
    seed = tilt_blind.new_seed() if args.seed is None else args.seed
    print(f"seed {seed}", file=sys.stderr, flush=True)
    tilt_blind.solve(seed, args.blind, out, log=lambda s: print(s, file=sys.stderr, flush=True))
    lines = tilt_blind.section_lines(out)
    atomic_write_text(target, tilt_blind.spliced(target.read_text(encoding="utf-8"), lines))
    print("\n".join(lines))
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = Parser(prog="bench_tilt_correction", description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=count(1, 10 ** 7, "points"), default=20000)
    ap.add_argument("--repeats", type=count(1, 1000), default=9)
    ap.add_argument("--out", type=out_dir, default=PUBLISHED, help="the report's directory (checked writable first)")
    ap.add_argument("--blind", type=count(8, 480, "points"), default=0, metavar="N",
                    help="only the 20 mm ring's blind check on N new tilted points (and N // 8 at zero tilt)")
    ap.add_argument("--seed", type=count(0, 2 ** 32 - 1), default=None,
                    help="the blind points' seed; default: a new one each run")
    args = ap.parse_args(argv)
    out = Path(args.out)
    if args.seed is not None and not args.blind:
        ap.error(f"--seed = {args.seed}: the seed of --blind's points; give --blind N with it")
    data = out / "law-tilt-correction"
    if not data.is_dir():
        ap.error(f"--out = {args.out}: holds no law-tilt-correction/ folder of 3D points (the committed one is in "
                 f"{PUBLISHED.relative_to(ROOT)})")
    if args.blind:
        return blind(args, out)
    t0 = time.perf_counter()
    rings = {}
    for ring in RINGS:
        fitted = fit_ring(ring, out)
        atomic_write_text(out / "law-tilt-correction" / f"{fitted['law'].name}-law.json", fitted["law"].to_json())
        rings[ring] = (fitted, check_ring(ring, fitted, out))
    cost = kernel_cost(rings["newcomer-20mm"][0]["law"], args.points, args.repeats)
    text, ok = report(rings, cost, args, time.perf_counter() - t0)
    target = out / "law-tilt-correction.md"
    if (out / "law-tilt-correction" / tilt_blind.POINTS_FILE).is_file():      # the kept points, the law just written
        kept = tilt_blind.section_lines(out)
    else:
        kept = tilt_blind.kept_section(target.read_text(encoding="utf-8")) if target.exists() else None
    if kept is not None:
        text = tilt_blind.spliced(text, kept)
    atomic_write_text(target, text)
    print(text)
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
