"""Report of the sensitivity study (``ringcontact study sensitivity``): findings × variants.

Reads a finished (or partly finished) sweep directory of :mod:`rotor.studies.sensitivity` tasks and writes
``study-sensitivity.csv`` (one row per variant × finding × quantity), ``study-sensitivity.md``
(the table, the ranges and why they are plausible, the conclusion) and
``study-sensitivity.png/.svg`` (the deciding ratio of each finding per variant). Nothing here
computes dynamics. Findings: Dai et al. 2025 §5.2, §5.3.1, §5.3.2 (see :mod:`rotor.studies.sensitivity`).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from contact.errors import InputError
from reports.sensitivity_figure import figure, per_speed_ratios  # noqa: F401 (re-exported)
from reports.studies.common import integrator_text, write_csv
from rotor.studies import sensitivity as sens
from sweep import ResultStore, load_sweep


def tables(out, variants, *, scene: str = "paper-table4", speeds_rpm=sens.SPEEDS_RPM, options=None) -> dict:
    """``{variant name: AmplitudeTable}`` of the variants with at least one verified point in ``out``."""
    res = {}
    for v in variants:
        tasks = sens.variant_tasks(scene, v, speeds_rpm,
                                   options=sens.STUDY_OPTIONS if options is None else options)
        pts = load_sweep(ResultStore(out), tasks)
        if pts:
            res[v.name] = sens.table_from_points(list(pts.values()))
    return res


def _median(xs):
    xs = [x for x in xs if np.isfinite(x)]
    return float(np.median(xs)) if xs else math.nan


def key_ratios(table: sens.AmplitudeTable, *, require_periodic: bool = True) -> dict:
    """The deciding ratios of each finding, median over the speeds where the cases compared are
    periodic (``nan`` where none): clearance 2X, 3X A(0.03 mm)/A(0.08 mm) at disk 2 and the support
    (displacement; > 1 is the paper's direction); misalignment 3X A(2 mm)/A(0.5 mm) (displacement;
    > 1 is the paper's direction) and the 1X spread; tilt Σ3X–5X without/with tilt (velocity;
    ≤ 0.7 is 'markedly lower')."""
    out = {}
    j2, js_ = table.locations.index("disk2.y"), table.locations.index("s.y")

    def ok(cases):
        m = np.ones(len(table.speeds_rpm), bool)
        if require_periodic:
            for c in cases:
                m &= table.ok(c)
        return m

    m = ok(("clear0.03", "base", "clear0.08"))
    a, b = table.amp("q", "clear0.03")[m], table.amp("q", "clear0.08")[m]
    for h in (2, 3):
        out[f"clear_{h}X_disk2"] = _median(a[:, h - 1, j2] / b[:, h - 1, j2])
        out[f"clear_{h}X_support"] = _median(a[:, h - 1, js_] / b[:, h - 1, js_])
    m = ok(("mis0.5", "base", "mis2"))
    a, c, b = table.amp("q", "mis0.5")[m], table.amp("q", "base")[m], table.amp("q", "mis2")[m]
    for h in (2, 3):
        out[f"mis_{h}X_disk2"] = _median(b[:, h - 1, j2] / a[:, h - 1, j2])
        out[f"mis_{h}X_support"] = _median(b[:, h - 1, js_] / a[:, h - 1, js_])
    one = np.stack([a[:, 0, :], c[:, 0, :], b[:, 0, :]])
    out["mis_1X_spread_max"] = float((one.max(axis=0) / one.min(axis=0) - 1).max()) if m.any() else math.nan
    m = ok(("base", "notilt"))
    a, b = table.amp("v", "base")[m], table.amp("v", "notilt")[m]
    out["tilt_disk2"] = _median(b[:, 2:5, j2].sum(axis=1) / a[:, 2:5, j2].sum(axis=1))
    out["tilt_support"] = _median(b[:, 2:5, js_].sum(axis=1) / a[:, 2:5, js_].sum(axis=1))
    base = table.amp("v", "base")
    out["base_3Xto5X_over_1X_disk2"] = _median(base[:, 2:5, j2].sum(axis=1) / base[:, 0, j2])
    return out


def rows(tabs: dict, variants) -> list:
    """CSV rows: variant, factors, finding, quantity, verdicts (periodic speeds, all speeds), ratios."""
    out = []
    for v in variants:
        if v.name not in tabs:
            continue
        t = tabs[v.name]
        per = sens.evaluate(t, require_periodic=True)
        allp = sens.evaluate(t, require_periodic=False)
        coll = sens.evaluate(t, require_contact=True)
        kr = key_ratios(t)
        n_all6 = int(np.all(np.asarray(t.periodic), axis=0).sum())
        for name, f in per.items():
            g = allp[name]
            out.append({"variant": v.name, "factors": ";".join(f"{k}x{x:g}" for k, x in v.factors.items()) or "-",
                        "finding": f.name, "quantity": {"q": "displacement", "v": "velocity"}[f.quantity],
                        "holds_periodic": f.holds, "pass_periodic": f.n_pass, "compared_periodic": f.n_compared,
                        "holds_all": g.holds, "pass_all": g.n_pass, "compared_all": g.n_compared,
                        "holds_collision": coll[name].holds, "pass_collision": coll[name].n_pass,
                        "compared_collision": coll[name].n_compared,
                        "speeds": len(t.speeds_rpm), "base_periodic": int(t.ok("base").sum()),
                        "all_cases_periodic": n_all6, **kr})
    return out


POINT_LOCATIONS = (("disk2.y", "disk2"), ("s.y", "support"))


def point_rows(tabs: dict, variants) -> tuple[list, list]:
    """Header and rows of every (variant, speed, case): periodic, contact fraction, and the 1X–5X
    amplitudes at disk 2 and the support, displacement (µm) and y velocity (mm/s)."""
    header = ["variant", "speed_rpm", "case", "periodic", "contact_fraction"]
    for _, lab in POINT_LOCATIONS:
        header += [f"{lab}_{h}X_um" for h in sens.ORDERS] + [f"{lab}_{h}X_mm_s" for h in sens.ORDERS]
    out = []
    for v in variants:
        t = tabs.get(v.name)
        if t is None:
            continue
        for k, rpm in enumerate(t.speeds_rpm):
            for c in t.cases:
                ci = t.cases.index(c)
                row = [v.name, float(rpm), c, bool(t.periodic[ci, k]),
                       float(np.asarray(t.contact_fraction)[ci, k]) if t.contact_fraction is not None else math.nan]
                for loc, _ in POINT_LOCATIONS:
                    j = t.locations.index(loc)
                    row += [float(x) * 1e6 for x in t.amp("q", c)[k, :, j]]
                    row += [float(x) * 1e3 for x in t.amp("v", c)[k, :, j]]
                out.append(row)
    return header, out


def write_csv_rows(path: Path, rws: list) -> Path:
    if not rws:
        raise InputError("sensitivity report: no finished variants to report")
    header = list(rws[0].keys())
    return write_csv(path, header, [[r[h] for h in header] for r in rws])


def _fmt(x, d=3):
    return "–" if not np.isfinite(x) else f"{x:.{d}g}"


def _regimes(t) -> str:
    """Base-case regime per speed (speeds ascending): '–' no contact (stick or slip), 'I' contact part of
    the time (impacts), 'C' contact throughout; '*' appended when not periodic."""
    letters = []
    cf = np.asarray(t.contact_fraction)[t.cases.index("base")] if t.contact_fraction is not None else None
    for k in range(len(t.speeds_rpm)):
        c = cf[k] if cf is not None else math.nan
        L = "C" if c >= 1 else "I" if c > 0 else "–"
        letters.append(L + ("" if t.ok("base")[k] else "*"))
    return " ".join(letters)


def _cell(f_per, f_all, f_coll, ratio_txt):
    mark = "**holds**" if f_per.holds else "no"
    return (f"{mark} {f_per.n_pass}/{f_per.n_compared} (collision {f_coll.n_pass}/{f_coll.n_compared}; "
            f"all pts {f_all.n_pass}/{f_all.n_compared}); {ratio_txt}")


def note(tabs: dict, variants, *, timing: dict | None = None, code: str = "") -> str:
    """Markdown report: method, ranges, the findings × variants table, the conclusion."""
    L = ["# Sensitivity of the paper's Section 5 findings to the inputs Table 4 does not give", "",
         "Dai et al. 2025 (Actuators 14:422) §5 states three findings over the high-speed range (clearance, Fig. 18; "
         "misalignment, Fig. 19; tilt, Fig. 16) that hold only in part on our Table 4 rotor with the scene's documented "
         f"assumptions (misalignment excitation read as `{_scene_reading()}`, section5-readings.md; tilt ignored without "
         "any moment; per-finding verdicts in `study-findings.md` and `tests/rotor/studies/test_study_paper.py`). This "
         "study asks whether a plausible value of the unstated inputs (`[ASSUMED]` in `rotor/scenes/paper-table4.toml`), "
         "under every reading of Eq. 34 (`rotor.studies.readings`), makes them hold. "
         "Regenerate: `ringcontact study sensitivity --out <dir>` (resumable; `rotor/studies/sensitivity.py`, "
         "`reports/sensitivity.py`).", "",
         "## Method", "",
         f"* Speeds {', '.join(f'{s:.0f}' for s in sens.SPEEDS_RPM)} rpm: the first third of the paper's 'high speed' "
         "range of §5.3.1 (band H1 of study-findings.md), including its point B (10 500 rpm). Above 12 000 rpm the "
         "scene's reading has no periodic steady state within 1 500 revolutions (study-findings.md), so those speeds "
         "decide nothing on periodic states and cost about four times as much (the former study's 13 500 and "
         "15 000 rpm are left out: `rotor.studies.sensitivity.SPEEDS_RPM`).",
         "* Variants (trimmed to about 40 CPU-minutes on the shared machine): every reading of Eq. 34 as it is and "
         "with m_sp ×0.3, ×3 and L ×0.5, ×2 (`reading-<name>…`; the scene's own reading is `base`, `msp-x…`, "
         "`lever-x…`), and, under the scene's reading, the other unstated inputs one factor each side of the scene's "
         "value (`rotor.studies.sensitivity.OTHER_FACTORS`; the former study had 2–4 factors each and combinations, "
         "still available by name with `--variants`).",
         "* At each speed and variant: the reference case (δ0 = 0.05 mm, δ = 1 mm, tilt on) from rest, then "
         "δ0 = 0.03 and 0.08 mm, δ = 0.5 and 2 mm, and tilt ignored, each **continued** from the reference end state "
         "(one branch of solutions, as the tests do). Steady state by the Poincaré detector of `rotor.studies.steady_state` "
         "(tol 1e-4, ≤ 1 500 revolutions), spectra over 16 whole revolutions.",
         "* A finding is checked at a speed only where every compared case is periodic; it **holds** for a variant "
         f"when it holds at ≥ {sens.HOLD_FRACTION:.0%} of those speeds (and at least 2). 'all pts' repeats the check "
         "including non-periodic points (their 16-revolution amplitudes are not on exact bins); 'collision' only at "
         "the periodic speeds where the reference case collides (the paper attributes all three findings to the "
         "collision between bearing and support).",
         "* Clearance (Fig. 18): 2X and 3X of the y **displacement** strictly decrease 0.03 → 0.05 → 0.08 mm at "
         "disk 2 and the 3# bearing support. Misalignment (Fig. 19): 1X within 5 % and 2X, 3X strictly increase "
         "0.5 → 1 → 2 mm at disk 1, disk 2 and the support (displacement). Tilt (Fig. 16 vs 12): Σ3X–5X of the y "
         "**velocity** without tilt ≤ 0.7 × with tilt at disk 2 and the support. Each is also evaluated in the other "
         "quantity (CSV).",
         "* Ratios in the table: medians over the compared speeds — clearance 3X(0.03)/3X(0.08) at disk 2 "
         "(> 1 is the paper's direction), misalignment 3X(2)/3X(0.5) at disk 2 (> 1), tilt Σ3X–5X off/on at disk 2 "
         "(≤ 0.7).",
         "* 'base regime by speed': the reference case at each speed (ascending): '–' no contact (support stuck or "
         "slipping), 'I' contact part of the time (collisions), 'C' contact throughout; '*' not periodic.", ""]
    if code:
        L += [f"Code: {code}.", ""]
    if timing:
        L += [f"**Timing:** {timing.get('text', '')}", ""]
    L += _ranges_lines()
    L += ["## Findings × variants", "",
          "| variant | base regime by speed | clearance (Fig. 18, displacement) | misalignment (Fig. 19, displacement) | tilt (Fig. 16, velocity) "
          "| periodic speeds (base / all 6 cases) |", "|---|---|---|---|---|---|"]
    verdicts = {}
    for v in variants:
        if v.name not in tabs:
            continue
        t = tabs[v.name]
        per, allp = sens.evaluate(t, require_periodic=True), sens.evaluate(t, require_periodic=False)
        coll = sens.evaluate(t, require_contact=True)
        kr = key_ratios(t)
        verdicts[v.name] = per
        n6 = int(np.all(np.asarray(t.periodic), axis=0).sum())
        part = "" if len(t.speeds_rpm) == len(sens.SPEEDS_RPM) else f" (partial: {len(t.speeds_rpm)} speeds)"
        L.append(f"| {v.name}{part} | {_regimes(t)} | {_cell(per['clearance_q'], allp['clearance_q'], coll['clearance_q'], '3X ratio ' + _fmt(kr['clear_3X_disk2']))} "
                 f"| {_cell(per['misalignment_q'], allp['misalignment_q'], coll['misalignment_q'], '3X ratio ' + _fmt(kr['mis_3X_disk2']) + ', 1X spread ' + _fmt(100 * kr['mis_1X_spread_max'], 2) + ' %')} "
                 f"| {_cell(per['tilt_v'], allp['tilt_v'], coll['tilt_v'], 'off/on ' + _fmt(kr['tilt_disk2']))} "
                 f"| {int(t.ok('base').sum())}/{len(t.speeds_rpm)} / {n6}/{len(t.speeds_rpm)} |")
    L += [""] + readings_table(tabs, variants)
    return "\n".join(L), verdicts


def _ranges_lines() -> list[str]:
    """The ranges table of the note: each unstated input, its factors and why they are plausible."""
    return ["## Ranges and why they are plausible for an aero-engine support", "",
          "| input (scene value) | factors | plausible because |", "|---|---|---|",
          "| k_s,θ, c_s,θ support tilt stiffness/damping (1.5e5 N m/rad, 15 N m s/rad) | ×0.01, ×100 (former study also ×0.1, ×10) | "
          "k_s b²: b = 10 mm … 1 m; a squirrel cage or bearing housing frame spans 20–300 mm axially (×0.04–×9); the "
          "extremes bracket a near-pinned and a near-clamped housing |",
          "| J_s support tilt inertia (1.9 kg m²) | ×0.1, ×3 | 100 kg with a radius of gyration of 44–240 mm |",
          "| a0 transition-shaft angular stiffness (5e6 N m/rad) | ×0.01, ×100 (former also ×0.1, ×10) | spline/curvic joints: from a loose "
          "spline (5e4) to solid-shaft-like (5e8) |",
          "| a1 cubic stiffness (1.25e12 N m/rad³) | ×0, ×100 (former also ×10) | from a linear joint to one whose stiffness "
          "doubles at 0.2 mrad |",
          "| k_s, c_s support to ground (= k3, c3: 1.5e7 N/m, 1.5e3 N s/m) | ×0.1, ×10 (former also ×3) | aero-engine support "
          "stiffness 1e6–1e8 N/m (squirrel cage to stiff casing frame) |",
          "| m_sp transition-shaft mass (per reading: 9 kg short sleeve, 25.2 kg long sleeve) | ×0.3, ×3 | 2.7–76 kg "
          "sleeve; 2X force ∝ m_sp L, moment ∝ m_sp L² (Eq. 34) |",
          "| L transition-shaft lever (per reading: 75 mm, 210 mm) | ×0.5, ×2 | 38–420 mm from the sleeve centre to a "
          "centring surface; 2X force ∝ L, 2X moment ∝ L² (Eq. 34) |",
          "| reading of Eq. 34 (where the pair acts, m_sp, L) | the five of `rotor.studies.readings` | the paper gives "
          "the magnitudes, not where they act nor m_sp, L (section5-readings.md) |",
          "| c_c collision factor (100 s/m, Table 4 '100 s/N' read as s/m) | ×0.01 (former also ×0.1, ×10) | a Hunt–Crossley "
          "(1975) factor for steel on steel is ~0.1–0.5 s/m (restitution 0.8–0.95 at 0.1–1 m/s, e ≈ 1 − 2αv/3); "
          "×0.01 brings 100 s/m to 1 s/m, ×10 brackets the other side |",
          "| μN end-face friction limit (0.3 × 5000 N) | ×0.2, ×5 (preload 1 and 25 kN) | only the product "
          "μ·preload enters; μ 0.1–0.5 and a nut preload of 1–15 kN give ×0.07–×5 |",
          ""]


def _scene_reading(scene: str = "paper-table4") -> str:
    from rotor.model.scene import load_scene
    from rotor.studies.readings import scene_reading

    return scene_reading(load_scene(scene)) or "none of rotor.studies.readings"


def readings_table(tabs: dict, variants) -> list[str]:
    """Markdown: per reading of Eq. 34, over its variants (as it is, m_sp and L varied), how many make each
    finding hold (periodic speeds) and the reading's own base regime by speed."""
    groups: dict = {}
    for v in variants:
        if v.name in tabs and (v.reading is not None or v.name == "base" or v.name.split("-x")[0] in ("msp", "lever")):
            groups.setdefault(v.reading or _scene_reading(), []).append(v)
    if not groups:
        return []
    key = {"clearance": "clearance_q", "misalignment": "misalignment_q", "tilt": "tilt_v"}
    L = ["## Per reading of Eq. 34", "", "Variants per reading: as it is, m_sp ×0.3, ×3, L ×0.5, ×2; a finding counts for "
         "a variant when it holds at ≥ 67 % of the periodic speeds (at least 2). Names of the holding variants in the "
         "table above.", "", "| reading | variants | clearance holds | misalignment holds | tilt holds | its base regime "
         "by speed |", "|---|---|---|---|---|---|"]
    for r, vs in groups.items():
        ev = [sens.evaluate(tabs[v.name]) for v in vs]
        base = next((v for v in vs if not v.factors), None)
        cells = [f"{sum(e[k].holds for e in ev)}/{len(vs)}" for k in key.values()]
        L.append(f"| {r}{' (scene)' if r == _scene_reading() else ''} | {len(vs)} | " + " | ".join(cells)
                 + f" | {_regimes(tabs[base.name]) if base else '—'} |")
    return L + [""]


def publish(out, to, variants, *, extra: str = "", timing: dict | None = None, code: str = "",
            scene: str = "paper-table4") -> list:
    """Write study-sensitivity.{csv,md,png,svg} into ``to`` from the sweep in ``out``."""
    from contact.files import atomic_write_text

    to = Path(to)
    tabs = tables(out, variants, scene=scene)
    rws = rows(tabs, variants)
    files = [write_csv_rows(to / "study-sensitivity.csv", rws)]
    files.append(write_csv(to / "study-sensitivity-points.csv", *point_rows(tabs, variants)))
    text, _ = note(tabs, variants, timing=timing, code=code)
    infos = [p.info for p in load_sweep(ResultStore(out)).values()]
    text = text.replace("\n\n## Ranges", "\n\n" + integrator_text(infos, code) + "\n\n## Ranges", 1)
    text += ("\n## Trends at each speed over all variants\n\nCounts over the variants (every reading and "
             "its m_sp, L variants, and the other one-at-a-time inputs) of how often each piece of the paper's findings holds at disk 2, all points (periodic or "
             "not), counting a variant only where every compared case collides at that speed (the paper's "
             "mechanism). It separates what the unstated inputs change from what none of them changes.\n\n"
             + trends_by_speed(tabs) + "\n")
    text += "\n## Conclusion (generated from the verdicts above)\n\n" + conclusion(tabs, variants) + "\n"
    if extra:
        text += "\n" + extra.strip() + "\n"
    files += figure(tabs, variants, to / "study-sensitivity", scene=scene)
    text += "\nFiles: `study-sensitivity.csv` (every variant × finding × quantity, verdicts and ratios), " \
            "`study-sensitivity-points.csv` (every variant × speed × case: periodic, contact fraction, 1X–5X at " \
            "disk 2 and the support in µm and mm/s), `study-sensitivity.png/.svg` (the deciding ratios per " \
            "variant and speed).\n"
    files.append(atomic_write_text(to / "study-sensitivity.md", text))
    return files


def timing_text(out, keys=None) -> dict:
    """Wall times of the study from its store: per (variant, speed) task and per steady state
    (inside a worker, from the point records) and of each sweep run (``timing.json``)."""
    import json

    store = ResultStore(out)
    walls, ss = [], []
    for k in store.keys():
        if keys is not None and k not in keys:
            continue
        try:
            rec = json.loads(store.json_path(k).read_text())
        except (OSError, ValueError):
            continue
        w = rec.get("run", {}).get("wall_s")
        if w is not None:
            walls.append(float(w))
        info = rec.get("info", {})
        ss += [float(info[c]["wall_s"]) for c in info.get("cases", []) if isinstance(info.get(c), dict)]
    from sweep import read_timing

    runs = read_timing(out) or []   # a damaged timing.json is refused by name (DatasetError), not ignored
    if not walls:
        return {}
    total = sum(r.get("wall_s", 0.0) for r in runs)
    txt = (f"{len(walls)} (variant, speed) tasks of 6 steady states each (points of this study's variants); median {np.median(walls):.1f} s per task "
           f"inside a worker (sum {sum(walls) / 60:.1f} CPU-min), median {np.median(ss):.1f} s per steady state "
           f"(max {max(ss):.1f} s: a point that is not periodic runs the full 1 500 revolutions).")
    if runs:
        loads = ", ".join(f"{r['load_avg_end'][0]:.1f}" for r in runs if "load_avg_end" in r)
        txt += (f" Sweep wall time {total / 60:.1f} min over {len(runs)} run(s) with "
                f"{max(r.get('workers', 0) for r in runs)} worker processes on the shared 2-core machine "
                f"(load average at the end of the runs: {loads}).")
    return {"text": txt, "task_median_s": float(np.median(walls)), "steady_median_s": float(np.median(ss)),
            "sweep_wall_s": total}


#: which finding each key ratio decides, and the paper's side of it
_DECIDING = {"clearance": ("clear_3X_disk2", 1.0, "above"), "misalignment": ("mis_3X_disk2", 1.0, "above"),
             "tilt": ("tilt_disk2", sens.MARKEDLY, "below")}


def conclusion(tabs: dict, variants) -> str:
    """Plain-words conclusion from the verdicts: where each finding holds, whether any variant makes
    all three hold, and which input moves each deciding ratio most (one-at-a-time variants)."""
    names = [v.name for v in variants if v.name in tabs]
    if not names:
        return "No finished variants."
    ev = {n: sens.evaluate(tabs[n]) for n in names}
    key = {"clearance": "clearance_q", "misalignment": "misalignment_q", "tilt": "tilt_v"}
    L = []
    for f, k in key.items():
        ok = [n for n in names if ev[n][k].holds]
        txt = []
        for n in ok:
            c = sens.evaluate(tabs[n], require_contact=True)[k]
            txt.append(f"`{n}`" + ("" if c.n_compared else " (only at speeds where the bearing does not collide)"))
        L.append(f"* **{f}**: holds for " + (", ".join(txt) if ok else "**no variant**") + ".")
    allok = [n for n in names if all(ev[n][k].holds for k in key.values())]
    L.append("* **All three at once**: " + (", ".join(f"`{n}`" for n in allok) if allok else
                                           "**no variant studied makes all three findings hold**") + ".")
    _, tot = _trends({n: tabs[n] for n in names})
    if tot["c3"][1]:
        L.append("")
        L.append(f"Over every variant and speed where all compared cases collide (all points, disk 2): 2X fell with "
                 f"δ0 in {tot['c2'][0]}/{tot['c2'][1]} and 3X in {tot['c3'][0]}/{tot['c3'][1]}; 2X rose with δ in "
                 f"{tot['m2'][0]}/{tot['m2'][1]} and 3X in {tot['m3'][0]}/{tot['m3'][1]}; Σ3X–5X was ≥ 30 % lower "
                 f"without tilt in {tot['t'][0]}/{tot['t'][1]}.")
    L.append("")
    L.append("Where each finding comes closest (periodic speeds where the reference case collides, the paper's "
             "mechanism; passes/compared):")
    for f, k in key.items():
        coll = sorted(((sens.evaluate(tabs[n], require_contact=True)[k], n) for n in names),
                      key=lambda x: (-(x[0].n_pass / x[0].n_compared if x[0].n_compared else 0), -x[0].n_compared))
        top = [f"`{n}` {r.n_pass}/{r.n_compared}" for r, n in coll if r.n_pass > 0][:4]
        L.append(f"* {f}: " + (", ".join(top) if top else "at no periodic collision speed of any variant") + ".")
    if "base" in tabs:
        flat = []
        b = tabs["base"]
        for n in names:
            t = tabs[n]
            if n == "base" or len(t.speeds_rpm) != len(b.speeds_rpm):
                continue
            m = t.ok("base") & b.ok("base")
            if not m.any():
                continue
            x, y = t.amp("q", "base")[m, :3], b.amp("q", "base")[m, :3]
            if float(np.max(np.abs(x - y) / np.maximum(y, 1e-12))) <= 0.02:
                flat.append(n)
        L.append("* No effect (reference-case 1X–3X within 2 % of the scene's at every speed where both are periodic): "
                 + (", ".join(f"`{n}`" for n in flat) if flat else "none") + ".")
    return "\n".join(L)


def trends_by_speed(tabs: dict) -> str:
    return _trends(tabs)[0]


def _trends(tabs: dict):
    """Markdown table: per speed, over all variants (all points, periodic or not), in how many the
    pieces of each finding go the paper's way, counting only variants whose compared cases all
    collide at that speed (the paper's mechanism); disk 2, displacement (velocity for tilt)."""
    speeds = sorted({float(s) for t in tabs.values() for s in t.speeds_rpm})
    tot = {k: [0, 0] for k in ("c2", "c3", "m2", "m3", "t")}
    L = ["| speed (rpm) | variants with collision in all compared cases | 2X falls with δ0 (paper) | 3X falls with δ0 "
         "(paper) | 2X rises with δ (paper) | 3X rises with δ (paper) | Σ3X–5X ≥ 30 % lower without tilt (paper) |",
         "|---|---|---|---|---|---|---|"]
    for s in speeds:
        cnt = {k: [0, 0] for k in ("c2", "c3", "m2", "m3", "t")}
        n_coll = 0
        for t in tabs.values():
            if s not in list(t.speeds_rpm) or t.contact_fraction is None:
                continue
            k = list(t.speeds_rpm).index(s)
            cf = {c: float(np.asarray(t.contact_fraction)[t.cases.index(c), k]) for c in t.cases}
            j = t.locations.index("disk2.y")
            A = {c: t.amp("q", c)[k, :, j] for c in t.cases}
            V = {c: t.amp("v", c)[k, :, j] for c in t.cases}
            if all(cf[c] > 0 for c in ("clear0.03", "base", "clear0.08")):
                for h, key in ((2, "c2"), (3, "c3")):
                    a = [A[c][h - 1] for c in ("clear0.03", "base", "clear0.08")]
                    cnt[key][0] += a[0] > a[1] > a[2]
                    cnt[key][1] += 1
            if all(cf[c] > 0 for c in ("mis0.5", "base", "mis2")):
                for h, key in ((2, "m2"), (3, "m3")):
                    a = [A[c][h - 1] for c in ("mis0.5", "base", "mis2")]
                    cnt[key][0] += a[0] < a[1] < a[2]
                    cnt[key][1] += 1
            if all(cf[c] > 0 for c in ("base", "notilt")):
                cnt["t"][0] += V["notilt"][2:5].sum() <= sens.MARKEDLY * V["base"][2:5].sum()
                cnt["t"][1] += 1
            n_coll += all(cf[c] > 0 for c in t.cases)
        L.append(f"| {s:.0f} | {n_coll}/{len(tabs)} | " + " | ".join(f"{a}/{b}" for a, b in cnt.values()) + " |")
        for key, (a, b) in cnt.items():
            tot[key][0] += a
            tot[key][1] += b
    return "\n".join(L), tot
