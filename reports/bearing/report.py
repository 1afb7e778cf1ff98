"""The accuracy report of one ring pair (Tables 2-3 style): every law against this bearing's FEM.

Laws: the paper's conformal law (Dai et al. 2025 Eq. 5, plane-stress modulus as the paper, and plane
strain), Johnson (Eq. 26) and Pereira et al. (2015, Eq. 28), each with the elastic combination its
source defines for two materials (:mod:`contact.laws`), and the calibrated law (fit on all points and
held out, leave-one-out). With tilt: the paper's tilt model (Eqs. 8-19), the calibrated law
slice-integrated and through the compiled rotor kernel, against the 3D FEM's force and moment. Speed
against error: each law's evaluation time per point against the FEM's time per point, and each one's
largest error.

Writes ``accuracy-<name>.md``, ``.csv``, ``-force.png/.svg`` and, with tilt, ``-tilt.png/.svg``, plus
``-speed.png/.svg``.
"""
from __future__ import annotations

import csv
import io
import math
import time
from pathlib import Path

import numpy as np

from contact.files import atomic_write_bytes, atomic_write_text
from contact.units import ARCMIN, MM
from reports.accuracy.common import LAW_LABELS
from reports.accuracy.straight import law_forces
from reports.bearing.names import LAW_ERROR_BOUND_REL, file_names
from reports.bearing.tilt import report_lines as tilt_report_lines


def _fem2d(fit: dict, name: str):
    pts = sorted((p for p in fit["ds2"].select(scene=name) if p["penetration_m"] > 0), key=lambda p: p["penetration_m"])
    return (np.array([p["penetration_m"] for p in pts]), np.array([p["force_n"] for p in pts]),
            np.array([p.get("force_error_rel") or 0.0 for p in pts]),
            np.array([p.get("wall_levels_s") or p.get("wall_s") or math.nan for p in pts]))


def straight_table(fit: dict, name: str) -> dict:
    """Forces and signed % differences of every law at every 2D point."""
    pen, F, err, wall = _fem2d(fit, name)
    law2 = fit["law2"]
    chosen = next(f for f in fit["fits2"] if f.family == law2.family)
    forces = law_forces(law2.geometry, pen)
    forces["calibrated-fit"] = law2.force(pen).force_N
    forces["calibrated-holdout"] = F * (1.0 + chosen.holdout_rel_err)
    pct = {k: 100.0 * (v - F) / F for k, v in forces.items()}
    return {"pen": pen, "F": F, "err": err, "wall": wall, "forces": forces, "pct": pct}


def _timeit(fn, repeats: int = 7) -> float:
    """Median wall time of ``fn()`` over ``repeats`` runs (s)."""
    out = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        out.append(time.perf_counter() - t0)
    return float(np.median(out))


def speed_rows(fit: dict, t2: dict) -> list[dict]:
    """Per method: median time per point (s) and largest absolute error (%) over the 2D points."""
    from contact import laws

    geo = fit["law2"].geometry
    kw = dict(clearance_m=geo.clearance_m, width_m=geo.width_m, bearing_E_Pa=geo.bearing_E_Pa,
              bearing_nu=geo.bearing_nu, support_E_Pa=geo.support_E_Pa, support_nu=geo.support_nu)
    pen = t2["pen"]
    calls = {"conformal-plane-stress": lambda p: laws.conformal_force(p, **kw, modulus="plane_stress"),
             "conformal-plane-strain": lambda p: laws.conformal_force(p, **kw, modulus="plane_strain"),
             "johnson": lambda p: laws.johnson_force(p, **kw), "pereira": lambda p: laws.pereira_force(p, **kw),
             "calibrated-fit": lambda p: fit["law2"].force(p)}
    rows = []
    for key, fn in calls.items():
        per_point = np.median([_timeit(lambda q=q: fn(np.array([q]))) for q in pen[:: max(1, len(pen) // 4)]])
        e = np.abs(t2["pct"][key])
        rows.append({"method": LAW_LABELS[key], "time_per_point_s": float(per_point),
                     "max_abs_error_pct": float(np.nanmax(e)) if np.isfinite(e).any() else math.nan,
                     "points_without_solution": int(np.sum(~np.isfinite(e)))})
    rows.append({"method": "2D FEM (3+ levels, Richardson)", "time_per_point_s": float(np.nanmedian(t2["wall"])),
                 "max_abs_error_pct": float(100 * np.max(t2["err"])), "points_without_solution": 0})
    if fit["ds3"] is not None:
        w3 = [p.get("wall_s") for p in fit["ds3"].points if p.get("wall_s")]
        rows.append({"method": "3D FEM, per point after its levels (Richardson)", "time_per_point_s": float(np.median(w3)),
                     "max_abs_error_pct": float(100 * max(p.get("force_error_rel") or 0 for p in fit["ds3"].points)),
                     "points_without_solution": 0})
    return rows


def _fmt(v: float, nd: int = 2) -> str:
    return "–" if not np.isfinite(v) else f"{v:+.{nd}f}"


def _pair_lines(rs) -> list[str]:
    d = rs.document
    b, h = d["bearing_ring"], d["housing"]
    return ["| | bearing ring | housing |", "|---|---|---|",
            f"| radii (mm) | {b['inner_radius_mm']:g} – {b['outer_radius_mm']:g} | bore {b['outer_radius_mm'] + h['radial_clearance_mm']:g} "
            f"(clearance {h['radial_clearance_mm']:g}) – {h['outer_radius_mm']:g} |",
            f"| width (mm) | {b['width_mm']:g} | {b['width_mm']:g} |",
            f"| E (GPa), ν | {b['youngs_modulus_gpa']:g}, {b['poisson_ratio']:g} | {h['youngs_modulus_gpa']:g}, {h['poisson_ratio']:g} |",
            f"| held / driven | {d['drive']['bearing']} | {h['hold']} |", "",
            f"2D assumption: plane {d['plane']}; range: Δr = {d['range']['penetration_mm'][0]:g} … "
            f"{d['range']['penetration_mm'][1]:g} mm, tilt {d['range']['tilt_arcmin'][0]:g} … "
            f"{d['range']['tilt_arcmin'][1]:g}′."]


def _straight_lines(t2: dict) -> list[str]:
    pen_mm = t2["pen"] / MM
    cols = np.unique(np.linspace(0, len(pen_mm) - 1, min(6, len(pen_mm))).round().astype(int))
    head = "| law | " + " | ".join(f"{pen_mm[j]:.4g} mm" for j in cols) + " |"
    lines = [head, "|---|" + "---|" * len(cols)]
    for key, label in LAW_LABELS.items():
        lines.append(f"| {label} | " + " | ".join(_fmt(t2["pct"][key][j]) for j in cols) + " |")
    lines.append("| FEM force (N) | " + " | ".join(f"{t2['F'][j]:,.0f}".replace(",", " ") for j in cols) + " |")
    lines.append("| FEM error estimate (%) | " + " | ".join(f"{100 * t2['err'][j]:.3f}" for j in cols) + " |")
    return lines


def _tilt_lines(fit: dict) -> list[str]:
    rows = fit["rows3"]
    if not rows:
        return []
    lines = ["| tilt | Δr (mm) | FEM force (N) ± % | paper's tilt model | calibrated, slices | calibrated, rotor kernel "
             "| FEM M_z (N·m) ± % | M_z, slices | M_z, rotor kernel |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        me = r["moment_error_rel"]
        lines.append(f"| {r['tilt_arcmin']:g}′ | {r['penetration_mm']:.4g} | {r['force_fem_N']:,.0f} ± {100 * r['force_error_rel']:.2f} ".replace(",", " ")
                     + f"| {_fmt(r['conformal-paper_pct'])} | {_fmt(r['calibrated-slices_pct'])} | {_fmt(r['calibrated-kernel_pct'])} "
                     + f"| {r['moment_fem_Nm']:.2f} ± {100 * (me or 0):.2f} | "
                     + ("–" if r["calibrated-slices_moment_pct"] is None else _fmt(r["calibrated-slices_moment_pct"], 2))
                     + " | " + ("–" if r["calibrated-kernel_moment_pct"] is None else _fmt(r["calibrated-kernel_moment_pct"], 2))
                     + " |")
    return lines


def _parameters_text(law) -> str:
    """The law's parameters in one line (a spline: its knots' count and penetration range)."""
    if law.family == "foundation-spline":
        n = int(law.parameters["knot_count"])
        lo, hi = (math.exp(law.parameters[f"log_penetration_{k:02d}"]) / MM for k in (0, n - 1))
        return f"{n} knots from {lo:.4g} to {hi:.4g} mm (every knot in the law file's parameters)"
    return ", ".join(f"{k} = {v:.6g} ± {law.parameter_std[k]:.2g} {law.parameter_units[k]}"
                     for k, v in law.parameters.items())


def _family_lines(law, fit: dict) -> list[str]:
    """Every family tried on the law's reference, whether it holds, and why the chosen one won."""
    doc = law.fit or {}
    holds = {d["family"]: d.get("holds") for d in doc.get("families", [])}
    lines = ["Families tried on the law's reference (zero tilt, every point held out in turn):", "",
             "| family | parameters | held-out RMS (%) | held-out max (%) | holds | |", "|---|---|---|---|---|---|"]
    fits = fit["tilt"]["base_fits"] if fit.get("straight") is not None else (fit["fits3"] or fit["fits2"])
    for f in fits:
        lines.append(f"| {f.family} | {f.n_parameters} | {100 * f.holdout_rms:.3f} | {100 * f.holdout_max:.3f} | "
                     f"{'yes' if holds.get(f.family) else 'no'} | {'chosen' if f.family == law.family else ''} |")
    return lines + ["", f"Rule: {doc.get('selection_rule', '')}. Why `{law.family}`: "
                    f"{doc.get('selection_reason', '')}."]


def _moment_lines(law) -> list[str]:
    """The moment verdict (tilted points through the rotor kernel), beside the force verdict above it."""
    m = law.provenance.get("moment_check") or {}
    if not m.get("points"):
        return []
    return [f"- Moment (the {m['points']} tilted points through the rotor kernel, never fitted): largest error "
            f"{100 * m['holdout_max_rel']:.2f} %, {100 * m['beyond_fem_error_rel']:.2f} % beyond the FEM's stated moment "
            f"error: **{'held' if m['held'] else 'not held'}** (bound {100 * m['error_bound_rel']:g} %). The flag above "
            "is decided on the force checks; the moment verdict is reported, not yet a refusal in the rotor "
            "(reports/bearing/pipeline.py: moment_check).", ""]


def _accuracy_lines(law) -> list[str]:
    """Issue 37's accuracy rule for the chosen law, per reference and quantity (force and moment)."""
    rows = law.provenance.get("accuracy") or []
    if not rows:
        return []
    return [f"Accuracy of the chosen law against issue 37's target ({law.provenance.get('accuracy_rule', '')}; "
            "zero tilt held out point by point, tilted points never fitted):", "", *accuracy_table(rows)]


def accuracy_table(rows: list[dict]) -> list[str]:
    """The rows of :func:`reports.bearing.pipeline.accuracy` as a Markdown table."""
    return ["| reference | quantity | points within / all | of them between the ends | holds | worst error (%) "
            "| its bound (%) |", "|---|---|---|---|---|---|---|"] + [
        f"| {r['reference']} | {r['quantity']} | {r['within']} / {r['points']} | "
        + ("–" if r.get("within_inside") is None else f"{r['within_inside']} / {r['points'] - 2}")
        + f" | {'yes' if r['holds'] else 'no'} | {r['worst_error_pct']:.3f} | {r['worst_bound_pct']:.3f} |"
        for r in rows]


def _dundurs(law) -> str:
    """α, β of the pair (plane stress, the paper's) and what the conformal rows do with β."""
    from contact import laws
    g = law.geometry
    a, b = laws.dundurs_constants(g.bearing_E_Pa, g.bearing_nu, g.support_E_Pa, g.support_nu)
    if abs(b) < 1e-12:
        return f"(α = {a:.3f}, β = 0: the law is exact in β)"
    return (f"(α = {a:.3f}, β = {b:.3f}; the rows use the β = 0 reading of the garbled β term, "
            "docs/reference/contact-laws.md Q1: for a steel pin in aluminium the β term moves Persson's load by "
            "2.6-6.2 %, reports/published/fem-verification-dissimilar.md)")


def _plane_lines(fit: dict) -> list[str]:
    """Plane stress or strain: the plane used, why, and the 3D evidence (:mod:`fem_reference.plane_check`)."""
    rec = fit.get("plane")
    if rec is None:
        return []
    lines = ["## Plane stress or strain (3D evidence)", "",
             f"2D assumption used: **plane {rec['used']}** ({rec['why']}; the file says `plane = \"{rec['requested']}\"`)."]
    ev = rec["check"]
    if ev is None:
        lines += ["", "No 3D check was run" + (": " + rec["warnings"][0] if rec["warnings"] else
                                              " (a plane stated in a straight-only file; `--plane-check` runs it).")]
        return lines + [""]
    lines += ["", f"The 3D ring (`{ev['boundary_conditions_3d']}`: the file's hold and drive, free end faces) at zero "
              "tilt, three levels with their Richardson error, against the 2D reference under both assumptions. "
              f"Rule: {ev['rule']}. Closer: plane {ev['closer']} ({'decisive' if ev['decisive'] else 'not decisive'}); "
              f"check wall {ev['wall_s']:.1f} s.", "",
              "| Δr (mm) | 3D force (N) ± % | 2D plane stress (N) ± % | stress − 3D (%) | 2D plane strain (N) ± % "
              "| strain − 3D (%) |", "|---|---|---|---|---|---|"]
    for r in ev["points"]:
        lines.append(f"| {r['penetration_mm']:.4g} | {r['force_3d_N']:,.0f} ± {100 * r['force_3d_error_rel']:.3f} "
                     f"| {r['force_2d_stress_N']:,.0f} ± {100 * r['force_2d_stress_error_rel']:.3f} "
                     f"| {100 * r['stress_minus_3d_rel']:+.2f} "
                     f"| {r['force_2d_strain_N']:,.0f} ± {100 * r['force_2d_strain_error_rel']:.3f} "
                     f"| {100 * r['strain_minus_3d_rel']:+.2f} |".replace(",", " "))
    lines += [""] + [f"- warning: {w}." for w in rec["warnings"]] + ([""] if rec["warnings"] else [])
    return lines


def _followed_lines(fit: dict) -> list[str]:
    """The range taken from a rotor run (``--range-from``) and the parts of the range no family holds."""
    from reports.bearing.holds import part_line
    from reports.bearing.range_from import note_lines

    lines = []
    if fit.get("range_from"):
        lines += ["## Range from a rotor run", "", *[f"- {t}." for t in note_lines(fit["range_from"])], ""]
    if fit.get("not_held"):
        lines += ["## Parts of the range no family holds", "", *[f"- {part_line(p)}." for p in fit["not_held"]], ""]
    return lines


def markdown(rs, fit: dict, law, t2: dict, speed: list[dict], stages: list[dict]) -> str:
    names = file_names(rs.name)
    checks, warn = law.provenance["checks"], law.provenance["warnings"]
    pars = _parameters_text(law)
    ok = not warn
    lines = [f"# Contact law of ring pair `{rs.name}`: laws against its FEM (Tables 2–3 style)", "",
             f"Generated by `ringcontact bearing` from the ring-pair file `{rs.source}` (sha256 {rs.sha256[:16]}…), "
             f"{law.provenance['code_version']}. Do not edit.", "", *_pair_lines(rs), "",
             "## Verdict", "",
             f"- Law file `{names['law']}`: `{law.name}` ({law.family}), {pars}; reference: {law.provenance['reference']}.",
             f"- Valid for Δr = {law.validity_penetration_m[0] / MM:.4g} … {law.validity_penetration_m[1] / MM:.4g} mm"
             + (f", tilt up to {law.validity_tilt_max_rad / ARCMIN:g}′" if law.validity_tilt_max_rad else ", straight ring only") + ".",
             "- Checks: " + "; ".join(f"{k} {100 * v:.3f} %" for k, v in checks.items() if v is not None) + ".",
             f"- Rule: a held-out error may exceed the FEM point's own stated error by at most "
             f"{100 * law.provenance['error_bound_rel']:g} %; beyond it here: " + "; ".join(
                 f"{k} {100 * v:+.3f} %" for k, v in law.provenance["checks_beyond_fem_error"].items() if v is not None) + ".",
             f"- **{'verified' if ok else 'flagged'}**" + ("" if ok else ": " + " ".join(warn)), "",
             *([f"- Rotor: {law.provenance['rotor_note']} (`{names['law_straight']}`).", ""]
               if law.provenance.get("rotor_note") else []),
             *_moment_lines(law), *_accuracy_lines(law), "",
             *_followed_lines(fit), *_plane_lines(fit),
             "## Straight ring (2D, Table 2 style)", "",
             "Cells: `100 (P_law − P_FEM)/P_FEM` in %, signed; '–': the law has no solution there. Conformal law: "
             "composite modulus and Dundurs α of the two materials (Dai et al. 2025 Eq. 5) " + _dundurs(law)
             + "; Johnson and Pereira: plane-strain composite modulus (their sources).", "", *_straight_lines(t2), ""]
    lines += _family_lines(law, fit)
    lines += ["", f"![force]({Path(names['report']).stem}-force.png)", ""]
    if fit["rows3"]:
        corrected = fit.get("straight") is not None
        how = (f"The chosen law `{law.name}` (the slices of `{fit['tilt']['record']['base_law']}` with the tilt "
               "correction: the rotor-kernel columns; the slices columns are the same law without it), the reference "
               "points that are not training points of the correction" if corrected else
               f"Calibrated at zero tilt on the 3D points (`{fit['law3'].name}`)")
        lines += ["## Tilted ring (3D, Table 3 style)", "",
                  f"{how}; every tilted cell is held out. Force and moment differences in %, signed.", "",
                  *_tilt_lines(fit), "", f"![tilt]({Path(names['report']).stem}-tilt.png)", ""]
    lines += tilt_report_lines(fit.get("tilt"))
    lines += ["## Speed against error", "", "| method | time per point | largest error (%) | points without solution |",
              "|---|---|---|---|"]
    lines += [f"| {r['method']} | {r['time_per_point_s']:.3g} s | {r['max_abs_error_pct']:.3g} | {r['points_without_solution']} |"
              for r in speed]
    lines += ["", f"![speed]({Path(names['report']).stem}-speed.png)", "", "## Stages", "", *_stages_lines(stages)]
    lines += ["", f"Data: [{names['csv']}]({names['csv']}), [{names['fem2d']}]({names['fem2d']})"
              + (f", [{names['fem3d']}]({names['fem3d']})" if fit["rows3"] else "") + ".", ""]
    return "\n".join(lines)


def _stages_lines(stages: list[dict]) -> list[str]:
    """The stage table; a stage kept from an earlier run (``kept_from``: its code version, set by
    :func:`reports.bearing.pipeline.refit`) is marked and that run named."""
    earlier = sorted({s["kept_from"] for s in stages if s.get("kept_from")})
    head = ("Wall times of the run that wrote this report; FEM points kept from an earlier run of the same file "
            "are read back, not recomputed (cold times of a new bearing: reports/published/perf-bearing.md).")
    if earlier:
        head = ("The law was refitted from this folder's kept FEM datasets (no FEM point solved): the stages marked "
                "'(kept)' are those of the run that solved them, " + "; ".join(earlier) + "; calibrate and report "
                "are the refit's.")
    return [head, "", "| stage | wall (s) | load average (1 min, start → end) |", "|---|---|---|"] + [
        f"| {s['stage']}{' (kept)' if s.get('kept_from') else ''} | {s['wall_s']:.1f} | "
        f"{s['load_average_1min_start']:.2f} → {s['load_average_1min_end']:.2f} |" for s in stages]


def csv_text(t2: dict, fit: dict) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["reference", "law", "penetration_mm", "tilt_arcmin", "force_fem_N", "fem_error_rel", "force_law_N", "diff_pct"])
    for key in LAW_LABELS:
        for j, p in enumerate(t2["pen"]):
            f = t2["forces"][key][j]
            w.writerow(["2d", key, f"{p / MM:.6g}", "0", f"{t2['F'][j]:.10g}", f"{t2['err'][j]:.4g}",
                        "" if not np.isfinite(f) else f"{f:.10g}", "" if not np.isfinite(f) else f"{t2['pct'][key][j]:.6f}"])
    for r in fit["rows3"]:
        for key in ("conformal-paper", "calibrated-slices", "calibrated-kernel"):
            f = r[f"{key}_N"]
            w.writerow(["3d", key, f"{r['penetration_mm']:.6g}", f"{r['tilt_arcmin']:.6g}", f"{r['force_fem_N']:.10g}",
                        f"{r['force_error_rel']:.4g}", "" if not np.isfinite(f) else f"{f:.10g}",
                        "" if not np.isfinite(f) else f"{r[key + '_pct']:.6f}"])
    return buf.getvalue()


def _save(fig, salt: str) -> tuple[bytes, bytes]:
    import matplotlib.pyplot as plt
    png, svg = io.BytesIO(), io.BytesIO()
    fig.savefig(png, format="png", dpi=110, metadata={"Software": None})
    with plt.rc_context({"svg.hashsalt": salt}):
        fig.savefig(svg, format="svg", metadata={"Date": None, "Creator": None})
    plt.close(fig)
    return png.getvalue(), svg.getvalue()


def force_figure(rs, fit: dict, t2: dict):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(6.4, 7.4), sharex=True)
    pen_mm = t2["pen"] / MM
    grid = np.geomspace(pen_mm.min(), pen_mm.max(), 120)
    curves = law_forces(fit["law2"].geometry, grid * MM)
    curves["calibrated-fit"] = fit["law2"].force(grid * MM).force_N
    styles = {"conformal-plane-stress": ("C0", "-"), "conformal-plane-strain": ("C0", ":"), "johnson": ("C1", "-"),
              "pereira": ("C2", "-"), "calibrated-fit": ("C3", "-")}
    for key, (c, ls) in styles.items():
        ax.plot(grid, curves[key] / 1e3, color=c, ls=ls, label=LAW_LABELS[key])
        ax2.plot(pen_mm, np.abs(t2["pct"][key]), color=c, ls=ls, marker=".")
    ax.errorbar(pen_mm, t2["F"] / 1e3, yerr=t2["err"] * t2["F"] / 1e3, fmt="ks", ms=4, capsize=3, label="2D FEM ± error", zorder=5)
    ax2.plot(pen_mm, np.abs(t2["pct"]["calibrated-holdout"]), "o", color="C3", mfc="none", label="calibrated, held out")
    ax2.plot(pen_mm, 100 * t2["err"], "k--", label="FEM error estimate")
    ax2.axhline(100 * LAW_ERROR_BOUND_REL, color="r", lw=0.8, label="bound")
    from matplotlib.ticker import FuncFormatter
    for a in (ax, ax2):
        a.set_xscale("log")
        a.set_yscale("log")
        a.grid(alpha=0.3, which="both")
        a.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        a.xaxis.set_minor_formatter(FuncFormatter(lambda v, _: f"{v:g}" if str(f"{v:g}")[0] in "25" else ""))
    ax.set_ylabel("contact force (kN)")
    ax2.set_ylabel("|P_law − P_FEM| / P_FEM (%)")
    ax2.set_xlabel("penetration Δr (mm)")
    ax.legend(fontsize=7)
    ax2.legend(fontsize=7)
    ax.set_title(f"ring pair {rs.name} (2D, plane {rs.scene.plane})")
    fig.tight_layout()
    return _save(fig, f"bearing-{rs.name}-force")


def speed_figure(rs, speed: list[dict]):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for k, r in enumerate(speed):
        if np.isfinite(r["max_abs_error_pct"]) and r["max_abs_error_pct"] > 0:
            ax.loglog(r["time_per_point_s"], r["max_abs_error_pct"], "o", color=f"C{k}", label=r["method"])
    ax.axhline(100 * LAW_ERROR_BOUND_REL, color="r", lw=0.8)
    ax.set_xlabel("time per point (s)")
    ax.set_ylabel("largest error against the FEM (%)")
    ax.set_title(f"ring pair {rs.name}: speed against error")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    return _save(fig, f"bearing-{rs.name}-speed")


def write_report(rs, fit: dict, law, out: Path, stages: list[dict]) -> list[Path]:
    """Every report file of one ring pair into ``out``; returns their paths."""
    from reports.accuracy.tilted import make_figure_3d

    names = file_names(rs.name)
    stem = Path(names["report"]).stem
    t2 = straight_table(fit, rs.name)
    speed = speed_rows(fit, t2)
    files = []
    for tag, (png, svg) in [("force", force_figure(rs, fit, t2)), ("speed", speed_figure(rs, speed))] + (
            [("tilt", make_figure_3d({"rows": fit["rows3"]}))] if fit["rows3"] else []):
        files += [atomic_write_bytes(out / f"{stem}-{tag}.png", png), atomic_write_bytes(out / f"{stem}-{tag}.svg", svg)]
    files.append(atomic_write_text(out / names["csv"], csv_text(t2, fit)))
    files.append(atomic_write_text(out / names["report"], markdown(rs, fit, law, t2, speed, stages)))
    return files
