"""Report builder: every analytic law against the FEM reference, Tables 2–3 style, with the calibration.

Table 2 style (straight ring, 2D dataset ``fem_reference/data/fem2d-reference.json``): per
boundary-condition scene, rows = laws, columns = penetrations 0.01 … 0.05 mm, cells =
``100 (P_law − P_FEM)/P_FEM`` (signed), '–' where a law has no solution. Laws:

* the conformal law (Dai et al. 2025 Eq. 5) in each documented reading — plane-stress modulus
  (the paper's) and plane-strain modulus; the β readings coincide here (β = 0, equal materials);
* Johnson (Eq. 26) and Pereira et al. 2015 (Eq. 28);
* the calibrated law of the scene (:mod:`contact.calibrate`), both as stored (fitted on all
  points) and **held out** (each displacement predicted by a fit that never saw it).

The paper's own Table 2 percentages (|law − FEM|/FEM of its law against its own FEM, whose
boundary conditions are not stated) stand beside ours, with one sentence per systematic
difference. Table 3 style (tilted ring) needs the 3D dataset (``fem_reference/data/3d/*.json``);
without one the report says so.

Writes ``accuracy-table2.md``, ``accuracy-table2.csv``, ``accuracy-table3.csv`` (when 3D data
exist), ``accuracy-force-displacement.png/.svg``.
"""
from __future__ import annotations

import csv
import io
import math
from pathlib import Path

import numpy as np

from contact import calibrate as cal
from contact import laws, tilt
from contact.dataset import ReferenceDataset, read_dataset
from contact.files import atomic_write_bytes, atomic_write_text
from contact.loose_support import loose_support_force
from contact.units import ARCMIN, MM

PENETRATIONS_MM = (0.01, 0.02, 0.03, 0.04, 0.05)
# Dai et al. (2025) Table 2: |model − FEM|/FEM in %; None = '-'.
PAPER_TABLE2_PCT = {
    "conformal-plane-stress": (12.01, 0.79, 4.37, 5.59, 5.69),
    "johnson": (28.70, 1.18, None, None, None),
    "pereira": (30.60, 29.74, 27.59, 25.59, 23.72),
}
# Dai et al. (2025) Table 3: conformal law with tilt vs its FEM, |%|; rows 0.5′, 1′, 2′.
PAPER_TABLE3_PCT = {0.5: (10.96, 4.11, 0.60, 1.14, 1.76), 1.0: (2.34, 2.87, 2.02, 1.37, 10.51),
                    2.0: (9.26, 2.94, 0.70, 2.71, 4.92)}
LAW_LABELS = {
    "conformal-plane-stress": "conformal, plane stress (paper)",
    "conformal-plane-strain": "conformal, plane strain",
    "johnson": "Johnson",
    "pereira": "Pereira 2015",
    "calibrated-fit": "calibrated (fit on all points)",
    "calibrated-holdout": "calibrated, held out",
}
DATA_3D_DIR = cal.DATA_3D_DIR


def _law_kwargs(geo: cal.SceneGeometry) -> dict:
    return dict(clearance_m=geo.clearance_m, width_m=geo.width_m, bearing_E_Pa=geo.bearing_E_Pa,
                bearing_nu=geo.bearing_nu, support_E_Pa=geo.support_E_Pa, support_nu=geo.support_nu)


def law_forces(geo: cal.SceneGeometry, pen_m: np.ndarray) -> dict[str, np.ndarray]:
    """Force (N, NaN outside the domain) of every analytic law at penetrations ``pen_m``."""
    kw = _law_kwargs(geo)
    out = {}
    for key, fn, extra in (("conformal-plane-stress", laws.conformal_force, {"modulus": "plane_stress"}),
                           ("conformal-plane-strain", laws.conformal_force, {"modulus": "plane_strain"}),
                           ("johnson", laws.johnson_force, {}), ("pereira", laws.pereira_force, {})):
        r = fn(pen_m, **kw, **extra)
        out[key] = np.where(r.in_domain, r.force_N, np.nan)
    return out


def scene_table(ds: ReferenceDataset, scene: str, dataset_info: dict | None = None) -> dict:
    """All numbers of one scene: FEM, laws, calibration, percentages at the Table 2 penetrations."""
    geo = cal.scene_geometry(ds, scene)
    pen, force, fem_err = cal.scene_points(ds, scene)
    law, fits = cal.calibrate_scene(ds, scene, dataset_info)
    chosen = next(f for f in fits if f.family == law.family)
    idx = []
    for p_mm in PENETRATIONS_MM:
        i = int(np.argmin(np.abs(pen - p_mm * MM)))
        if not math.isclose(pen[i], p_mm * MM, rel_tol=1e-9):
            raise cal.DatasetError(f"scene {scene!r} has no FEM point at penetration {p_mm} mm")
        idx.append(i)
    idx = np.array(idx)
    pen_t, fem_t = pen[idx], force[idx]
    forces = law_forces(geo, pen_t)
    forces["calibrated-fit"] = law.force(pen_t).force_N
    forces["calibrated-holdout"] = fem_t * (1.0 + chosen.holdout_rel_err[idx])
    pct = {k: 100.0 * (v - fem_t) / fem_t for k, v in forces.items()}
    extra = {}
    half = np.array([p.get("half_angle_rad", np.nan) for p in sorted(
        (q for q in ds.select(scene=scene) if float(q.get("tilt_rad", 0.0)) == 0.0 and q["penetration_m"] > 0),
        key=lambda q: q["penetration_m"])])
    pts_sorted = sorted((q for q in ds.select(scene=scene) if float(q.get("tilt_rad", 0.0)) == 0.0 and q["penetration_m"] > 0),
                        key=lambda q: q["penetration_m"])
    half_err = np.array([q.get("half_angle_error_rel", np.nan) for q in pts_sorted], dtype=float)
    if np.all(np.isfinite(half[idx])):
        extra["half_angle_fem_deg"] = np.degrees(half[idx])
        extra["half_angle_fem_err_rel"] = half_err[idx]
        extra["half_angle_law_deg"] = np.degrees(laws.contact_half_angle_rad(pen_t, geo.clearance_m))
        # conformal law evaluated at the FEM's measured contact half-angle (force–angle relation only)
        b2 = np.tan(half[idx] / 2) ** 2
        e_star = geo.e_star_Pa
        p_ang = 2 * np.pi * e_star * geo.clearance_m * b2 * (1 + b2) / laws.conformal_denominator(b2, 0.0) * geo.width_m
        extra["conformal_at_fem_angle_pct"] = 100.0 * (p_ang - fem_t) / fem_t
        eps_all = half
        y = (pen - geo.clearance_m * (1 / np.cos(eps_all) - 1)) / force * np.pi * e_star * geo.width_m
        extra["log_slope"] = tuple(float(v) for v in np.polyfit(np.log(1 / np.sin(eps_all)), y, 1))
    return {"scene": scene, "geometry": geo, "law": law, "fits": fits, "chosen": chosen, "penetration_m": pen,
            "force_fem_N": force, "fem_error_rel": fem_err, "idx": idx, "forces": forces, "pct": pct, **extra}


def _cell(v: float) -> str:
    return "–" if not np.isfinite(v) else f"{v:+.2f}"


def _range(v) -> str:
    v = np.asarray(v)[np.isfinite(v)]
    return f"{v.min():+.1f} … {v.max():+.1f} %" if v.size else "–"


def systematic_sentences(t: dict) -> list[str]:
    """One sentence per systematic difference of the laws in this scene (numbers from the data)."""
    s, pct, geo = t["scene"], t["pct"], t["geometry"]
    out = []
    c = pct["conformal-plane-strain" if geo.plane == "strain" else "conformal-plane-stress"]
    if s.startswith("clamped"):
        out.append(f"Conformal law ({geo.plane} modulus of the scene): {_range(c)} — the law is a pin in an infinite "
                   "plate, whereas here 10 mm rings sit between a rigid shaft and a clamped housing and behave as a thin "
                   "elastic layer (Winkler bed, P ∝ Δr^1.5 at small Δr), several times stiffer and stiffening faster.")
    elif s.startswith("persson"):
        ang = t.get("conformal_at_fem_angle_pct")
        tail = (f"; evaluated at the FEM's measured contact angle the same law is within {np.max(np.abs(ang)):.2f} % "
                "(the force–angle relation is exact, the rigid-overlap angle cos ε = δ0/(δ0+Δr) is what fails)") if ang is not None else ""
        out.append(f"Conformal law: {_range(c)} — the FEM penetration includes the far-field compliance of the "
                   f"finite plate (outer radius {geo.support_thickness_m / geo.radius_m + 1:.0f} R_b, log-divergent "
                   f"in an infinite plate), which the law's rigid-overlap geometry ignores{tail}.")
    ps, pe = pct["conformal-plane-stress"], pct["conformal-plane-strain"]
    ratio = (1 + pe / 100) / (1 + ps / 100)
    out.append(f"Plane strain vs plane stress in the conformal law: a uniform factor {np.nanmean(ratio):.4f} "
               "= 1/(1−ν²) on every load (the paper uses plane stress; the β readings coincide since β = 0).")
    out.append(f"Johnson: {_range(pct['johnson'])} where it exists, '–' beyond Δr = 4δ0/e² = 0.0271 mm exactly "
               "as in the paper (no real solution of Eq. 26).")
    out.append(f"Pereira 2015: {_range(pct['pereira'])} — a power law fitted by Pereira et al. to other "
               "geometries; its exponent n = 1.2475 has no knowledge of this scene's boundary conditions.")
    h = t["chosen"].holdout_rel_err[t["idx"]] * 100
    out.append(f"Calibrated law ({t['law'].family}): held-out {_range(h)}; the residual is the family's shape "
               "error, not FEM noise (FEM error ≤ "
               f"{100 * np.max(t['fem_error_rel'][t['idx']]):.3f} % at these points).")
    return out


def must_show_lines(tables: list[dict]) -> tuple[list[str], bool]:
    paper = PAPER_TABLE2_PCT["conformal-plane-stress"]
    lines, all_ok = [], True
    for t in tables:
        h = np.abs(t["chosen"].holdout_rel_err[t["idx"]]) * 100
        ok = bool(np.all(h < np.array(paper)))
        all_ok &= ok
        cells = ", ".join(f"{p:g} mm: {v:.3f} % < {q:.2f} %" if v < q else f"{p:g} mm: {v:.3f} % ≥ {q:.2f} %"
                          for p, v, q in zip(PENETRATIONS_MM, h, paper))
        lines.append(f"- `{t['scene']}` ({t['law'].name}): {cells} — **{'met' if ok else 'NOT met'}**")
    return lines, all_ok


def write_markdown(tables: list[dict], t3: dict) -> str:
    head = "| law | " + " | ".join(f"{p:g} mm" for p in PENETRATIONS_MM) + " |"
    sep = "|---|" + "---|" * len(PENETRATIONS_MM)
    ms_lines, ms_ok = must_show_lines(tables)
    lines = [
        "# Analytic laws against the FEM reference (Tables 2–3 style) and the calibrated laws",
        "",
        "Generated by `ringcontact report` (builder `accuracy`, module `reports/accuracy.py`) from the committed",
        f"dataset `{tables[0]['law'].dataset.get('path', cal.DATASET_2D.name) if tables[0]['law'].dataset else 'fem_reference/data/fem2d-reference.json'}`"
        + (" and the 3D dataset(s) in `fem_reference/data/3d/` (Table 3)" if t3["have_data"] else "") + ". Do not edit.",
        "",
        "Cells: `100 (P_law − P_FEM)/P_FEM` in % (signed; negative = the law under-predicts), '–' = no solution.",
        "Penetration Δr = drive displacement − δ0 (Table 1 rings: δ0 = 0.05 mm, l0 = 30 mm, R = 100 mm, E = 204 GPa,",
        "ν = 0.3). The held-out row predicts each displacement with a fit that did not see it (leave-one-out).",
        "",
        "## Must show: calibrated law vs FEM below the paper's own error, held-out, every Table 2 point",
        "",
        "Paper (Dai et al. 2025 Table 2, its conformal law vs its FEM): 12.01 %, 0.79 %, 4.37 %, 5.59 %, 5.69 %.",
        "",
        *ms_lines,
        "",
        f"Overall: **{'met' if ms_ok else 'NOT met'}** for the 2D (Table 2) points. Table 3: "
        + ((f"**{'met' if t3['ok'] else 'NOT met'}** — " + "; ".join(
            f"3D scene `{sc}`: largest held-out error {mx:.2f} % over {n} of the paper's {m} cells (paper's smallest "
            f"0.60 %; FEM error estimate up to {fe:.2f} %)" for sc, mx, n, m, fe in t3.get("summary", []))
            + " (details in the last section).") if t3["have_data"]
           else "**not shown — no 3D dataset is committed** (see the last section)."),
        "",
    ]
    for t in tables:
        law, geo = t["law"], t["geometry"]
        lines += [f"## Scene `{t['scene']}` (plane {geo.plane})", ""]
        lines += [head, sep]
        for key, label in LAW_LABELS.items():
            lines.append(f"| {label} | " + " | ".join(_cell(v) for v in t["pct"][key]) + " |")
        if "conformal_at_fem_angle_pct" in t:
            lines.append("| conformal at the FEM's contact angle | "
                         + " | ".join(_cell(v) for v in t["conformal_at_fem_angle_pct"]) + " |")
        lines.append("| FEM force (N) | " + " | ".join(f"{v:,.0f}".replace(",", " ") for v in t["force_fem_N"][t["idx"]]) + " |")
        lines.append("| FEM error estimate (%) | " + " | ".join(f"{100 * v:.3f}" for v in t["fem_error_rel"][t["idx"]]) + " |")
        if "half_angle_fem_deg" in t:
            lines.append("| contact half-angle: FEM ± error (°) | " + " | ".join(
                f"{a:.2f} ± {a * e:.2f}" for a, e in zip(t["half_angle_fem_deg"], t["half_angle_fem_err_rel"])) + " |")
            lines.append("| contact half-angle: laws' rigid overlap, cos ε = δ0/(δ0+Δr) (°, diff %) | " + " | ".join(
                f"{b:.2f} ({100 * (b - a) / a:+.1f})" for a, b in zip(t["half_angle_fem_deg"], t["half_angle_law_deg"])) + " |")
        lines += ["", "Paper's Table 2 beside ours (|%|, paper / ours):", "", head, sep]
        for key, vals in PAPER_TABLE2_PCT.items():
            cells = [f"{'–' if p is None else f'{p:.2f}'} / {'–' if not np.isfinite(o) else f'{abs(o):.2f}'}"
                     for p, o in zip(vals, t["pct"][key])]
            lines.append(f"| {LAW_LABELS[key]} | " + " | ".join(cells) + " |")
        lines += ["", "Systematic differences:", ""]
        lines += [f"- {s}" for s in systematic_sentences(t)]
        pars = ", ".join(f"{k} = {v:.6g} ± {law.parameter_std[k]:.2g} {law.parameter_units[k]}"
                         for k, v in law.parameters.items())
        lines += ["", f"Calibration `{law.name}` (stored in `contact/calibrated/{law.name}.json`): {pars}; "
                  f"valid for Δr = {law.validity_penetration_m[0] / MM:g} … {law.validity_penetration_m[1] / MM:g} mm, "
                  f"zero tilt; {len(t['penetration_m'])} FEM points; held-out RMS {100 * t['chosen'].holdout_rms:.3f} %, "
                  f"max {100 * t['chosen'].holdout_max:.3f} % over the whole range."]
        if law.family == "foundation":
            est = geo.foundation_modulus_estimate_Pa_per_m()
            lines.append(f"The fitted foundation modulus is {law.parameters['foundation_modulus_Pa_per_m'] / est:.4f} × "
                         f"M/(h_b + h_s) = {est:.4g} Pa/m, the constrained modulus of the two rings over their total "
                         "thickness: the physical meaning of the one parameter is confirmed by the data.")
        if law.family == "conformal-compliance":
            lines.append(f"C = {law.parameters['far_field_constant']:.4g} lumps the far field of this support. The "
                         "coefficient 2 of ln(1/sin ε) is not fitted: it is the logarithm of the approach of a 2D contact "
                         "(Johnson 1985 §5.6)" + (f"; regressing the FEM's own (Δr − δ0(sec ε − 1))·πE*l/P on ln(1/sin ε_FEM) "
                         f"gives slope {t['log_slope'][0]:.3f} and intercept {t['log_slope'][1]:.3f}" if "log_slope" in t else "")
                         + ". This family is implicit in Δr, so the compiled rotor kernel does not offer it (a verification "
                         "scene, not a support design).")
        lines += ["", "Families tried (held-out RMS / max over all points):", ""]
        lines += [f"- {f.family} ({f.n_parameters} parameter{'s' if f.n_parameters > 1 else ''}): "
                  f"{100 * f.holdout_rms:.3f} % / {100 * f.holdout_max:.3f} %"
                  + ("  ← chosen" if f.family == law.family else "") for f in t["fits"]]
        lines.append("")
    lines += [f"Selection rule: {tables[0]['law'].fit['selection_rule']}.", "",
              "![force–displacement](accuracy-force-displacement.png)", "",
              "Top: force against penetration, FEM with its Richardson error bar (smaller than the markers). "
              "Bottom: percentage difference of each law, with the FEM error band shaded.", "",
              "About the paper's percentages: they compare the paper's law with the paper's own FEM, whose boundary",
              "conditions are not stated; its implied loads (within −6 … +12 % of the conformal law) sit between our",
              "`persson` (far softer) and `clamped` (far stiffer) scenes. So the paper's and our percentages measure",
              "different set-ups; the comparable statement is the calibrated law's held-out error against the same",
              "FEM that it was calibrated on, above.", ""]
    lines += ["## Table 3 style: tilted ring (3D)", ""]
    lines += t3["lines"]
    if t3["have_data"] and t3["rows"]:
        lines += ["", "![3D force–displacement](accuracy-table3-force-displacement.png)"]
    lines += ["", "Data: [accuracy-table2.csv](accuracy-table2.csv)"
              + (", [accuracy-table3.csv](accuracy-table3.csv)" if t3["have_data"] else "") + ".", ""]
    return "\n".join(lines)


CSV2_COLUMNS = ("scene", "law", "penetration_mm", "force_fem_N", "fem_error_rel", "force_law_N", "diff_pct", "paper_abs_pct")


def table2_csv(tables: list[dict]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(CSV2_COLUMNS)
    for t in tables:
        fem = t["force_fem_N"][t["idx"]]
        err = t["fem_error_rel"][t["idx"]]
        for key in LAW_LABELS:
            paper = PAPER_TABLE2_PCT.get(key, (None,) * len(PENETRATIONS_MM))
            for j, p_mm in enumerate(PENETRATIONS_MM):
                f = t["forces"][key][j]
                w.writerow([t["scene"], key, f"{p_mm:g}", f"{fem[j]:.10g}", f"{err[j]:.4g}",
                            "" if not np.isfinite(f) else f"{f:.10g}",
                            "" if not np.isfinite(t["pct"][key][j]) else f"{t['pct'][key][j]:.6f}",
                            "" if paper[j] is None else f"{paper[j]:.2f}"])
    return buf.getvalue()


# --------------------------------------------------------------------------------------------
# Table 3 (3D): whatever is committed under fem_reference/data/3d/
# --------------------------------------------------------------------------------------------

T3_METHODS = {
    "conformal-paper": "conformal, paper's tilt model (Eqs. 8–19)",
    "calibrated-edge": "calibrated law in the paper's tilt model",
    "calibrated-slices": "calibrated, slice-integrated",
    "calibrated-kernel": "calibrated, compiled kernel (rotor path)",
}


def _rel(path: Path) -> str:
    try:
        return str(Path(path).resolve().relative_to(cal.REPO_ROOT))
    except ValueError:
        return str(path)


def _paper_t3(tilt_arcmin: float, pen_mm: float):
    row = PAPER_TABLE3_PCT.get(round(tilt_arcmin, 6))
    j = next((k for k, p in enumerate(PENETRATIONS_MM) if math.isclose(p, pen_mm, rel_tol=1e-9)), None)
    return None if row is None or j is None else row[j]


def table3_rows(ds: ReferenceDataset, scene: str, law: cal.CalibratedLaw) -> list[dict]:
    """One row per tilted FEM point: FEM force/moment/width and each method's prediction and % error."""
    geo = law.geometry
    per_w = laws.force_per_width_function("conformal", modulus="plane_stress", clearance_m=geo.clearance_m,
                                          bearing_E_Pa=geo.bearing_E_Pa, bearing_nu=geo.bearing_nu,
                                          support_E_Pa=geo.support_E_Pa, support_nu=geo.support_nu)
    try:
        params = law.loose_support_params()
    except cal.InputError:          # an implicit family: no compiled-kernel prediction
        params = None
    rows = []
    for p in sorted(ds.select(scene=scene), key=lambda q: (q["tilt_rad"], q["penetration_m"])):
        th, pen = float(p.get("tilt_rad", 0.0)), float(p["penetration_m"])
        if th == 0.0 or pen <= 0.0:
            continue
        y = geo.clearance_m + pen
        rc = tilt.tilted_contact(y, 0.0, 0.0, th, clearance_m=geo.clearance_m, width_m=geo.width_m, force_per_width=per_w)
        rk = loose_support_force(params, y, 0.0, 0.0, th) if params is not None else None
        fs, ms, ws = law.tilted(pen, th)
        re_ = tilt.tilted_contact(y, 0.0, 0.0, th, clearance_m=geo.clearance_m, width_m=geo.width_m,
                                  force_per_width=lambda d: (law.force_per_length(d), np.ones(np.shape(d), dtype=bool)))
        pred = {"conformal-paper": (-float(rc.Fy_N), float(rc.Mz_Nm), float(rc.width_1_m)),
                "calibrated-edge": (-float(re_.Fy_N), float(re_.Mz_Nm), float(re_.width_1_m)),
                "calibrated-kernel": (-float(rk.Fy_N), float(rk.Mz_Nm), None) if rk is not None else (math.nan, math.nan, None),
                "calibrated-slices": (fs, ms, ws)}
        F, M = float(p["force_n"]), p.get("moment_nm")
        row = {"scene": scene, "tilt_arcmin": th / ARCMIN, "penetration_mm": pen / MM, "force_fem_N": F,
               "force_error_rel": float(p.get("force_error_rel") or 0.0), "moment_fem_Nm": None if M is None else float(M),
               "moment_error_rel": None if p.get("moment_error_rel") is None else float(p["moment_error_rel"]),
               "width_fem_m": p.get("width_m")}
        for key, (f, m, w) in pred.items():
            row[f"{key}_N"] = f
            row[f"{key}_pct"] = 100.0 * (f - F) / F
            row[f"{key}_moment_Nm"] = m
            row[f"{key}_moment_pct"] = (100.0 * (m - M) / M) if (M is not None and M != 0.0) else None
            row[f"{key}_width_m"] = w
        rows.append(row)
    return rows


def table3() -> dict:
    """Table 3-style comparison from every committed 3D dataset (centre penetration, tilt about z)."""
    paths = sorted(DATA_3D_DIR.glob("*.json")) if DATA_3D_DIR.is_dir() else []
    rel = _rel(DATA_3D_DIR)
    if not paths:
        return {"have_data": False, "rows": [], "ok": None, "laws": [], "lines": [
            f"No 3D reference dataset is committed (`{rel}/` " + ("is empty" if DATA_3D_DIR.is_dir() else "does not exist")
            + "). The paper's Table 3 (its conformal law with tilt vs its FEM: 0.5′: 10.96/4.11/0.60/1.14/1.76 %, "
            "1′: 2.34/2.87/2.02/1.37/10.51 %, 2′: 9.26/2.94/0.70/2.71/4.92 %) therefore has no counterpart here "
            "yet, and the calibrated law's tilted accuracy is **not shown**. This section fills itself in when "
            "`fem_reference` commits a 3D dataset (points with `tilt_rad`, `penetration_m`, `force_n`, "
            "`moment_nm`, `width_m`)."]}
    rows, laws_, lines, all_ok, summary = [], [], [], True, []
    for path in paths:
        ds = read_dataset(path)
        info = cal.dataset_provenance(path, ds)
        for scene in ds.scenes():
            try:
                law, fits = cal.calibrate_scene(ds, scene, info)
            except (cal.DatasetError, cal.InputError) as exc:
                lines.append(f"- `{path.name}` scene `{scene}`: no zero-tilt calibration possible ({exc}).")
                continue
            chosen = next(f for f in fits if f.family == law.family)
            laws_.append(law)
            srows = table3_rows(ds, scene, law)
            rows += srows
            tilts = sorted({round(r["tilt_arcmin"], 6) for r in srows})
            pens = sorted({round(r["penetration_mm"], 9) for r in srows})
            pars = ", ".join(f"{k} = {v:.6g} ± {law.parameter_std[k]:.2g} {law.parameter_units[k]}"
                             for k, v in law.parameters.items())
            lines += [f"### `{_rel(path)}`, scene `{scene}`", "",
                      f"Calibrated at zero tilt on this dataset's own {len(chosen.penetration_m)} points: `{law.name}`, "
                      f"{pars} (held-out max {100 * chosen.holdout_max:.3f} % at zero tilt). Every tilted cell below is "
                      "therefore held out. Cells: force difference in %, signed; the paper's |%| in brackets.", "",
                      "| tilt | method | " + " | ".join(f"{p:g} mm" for p in pens) + " |",
                      "|---|---|" + "---|" * len(pens)]

            def find(tl, pm):
                return next((r for r in srows if round(r["tilt_arcmin"], 6) == tl and round(r["penetration_mm"], 9) == pm), None)

            for tl in tilts:
                for key, label in T3_METHODS.items():
                    cells = []
                    for pm in pens:
                        r = find(tl, pm)
                        paper = _paper_t3(tl, pm)
                        cells.append("" if r is None else f"{r[key + '_pct']:+.2f}"
                                     + (f" ({paper:.2f})" if paper is not None and key == "conformal-paper" else ""))
                    lines.append(f"| {tl:g}′ | {label} | " + " | ".join(cells) + " |")
                lines.append(f"| {tl:g}′ | FEM force (N) ± error (%) | " + " | ".join(
                    "" if find(tl, pm) is None else f"{find(tl, pm)['force_fem_N']:,.0f} ± {100 * find(tl, pm)['force_error_rel']:.2f}".replace(",", " ")
                    for pm in pens) + " |")
            lines += ["", "Moment M_z (difference in %, FEM value in N·m) and contact width (FEM / law, mm):", "",
                      "| tilt | quantity | " + " | ".join(f"{p:g} mm" for p in pens) + " |", "|---|---|" + "---|" * len(pens)]
            for tl in tilts:
                for key in ("conformal-paper", "calibrated-slices"):
                    lines.append(f"| {tl:g}′ | M_z, {T3_METHODS[key]} | " + " | ".join(
                        "" if find(tl, pm) is None or find(tl, pm)[key + "_moment_pct"] is None
                        else f"{find(tl, pm)[key + '_moment_pct']:+.1f}" for pm in pens) + " |")
                lines.append(f"| {tl:g}′ | M_z FEM (N·m) | " + " | ".join(
                    "" if find(tl, pm) is None or find(tl, pm)["moment_fem_Nm"] is None
                    else f"{find(tl, pm)['moment_fem_Nm']:.1f}" for pm in pens) + " |")
                lines.append(f"| {tl:g}′ | width FEM / paper law / slices (mm) | " + " | ".join(
                    "" if find(tl, pm) is None else
                    f"{(find(tl, pm)['width_fem_m'] or float('nan')) / MM:.1f} / {find(tl, pm)['conformal-paper_width_m'] / MM:.1f} / "
                    f"{find(tl, pm)['calibrated-slices_width_m'] / MM:.1f}" for pm in pens) + " |")
            lines += ["", "Systematic differences: the paper's tilt model (Eqs. 8–19) loads the whole patch with the "
                      "penetration of its most loaded edge, so it over-predicts the tilted load of a stiff support and "
                      "gives no moment once the patch spans the full width; an elastic bed carries each axial slice at "
                      "its own penetration, which the slice-integrated law does (and the compiled kernel for law code 2). "
                      "The conformal rows are off by the boundary conditions, as in Table 2."]
            # must-show: calibrated (slice-integrated) vs the paper's Table 3 cells
            ms = []
            for tl, paper_row in PAPER_TABLE3_PCT.items():
                for pm, paper in zip(PENETRATIONS_MM, paper_row):
                    r = find(round(tl, 6), round(pm, 9))
                    if r is None:
                        ms.append((tl, pm, None, paper))
                    else:
                        ms.append((tl, pm, abs(r["calibrated-slices_pct"]), paper))
            have = [m for m in ms if m[2] is not None]
            ok = bool(have) and all(v < q for _, _, v, q in have) and len(have) == len(ms)
            all_ok &= ok
            fem_errs = [100 * find(round(tl, 6), round(pm, 9))["force_error_rel"] for tl, pm, v, _ in ms if v is not None]
            summary.append((scene, max(v for _, _, v, _ in have) if have else math.nan, len(have), len(ms),
                            max(fem_errs) if fem_errs else math.nan))
            lines += ["", "Must show (calibrated law, slice-integrated, held out, vs the paper's Table 3): "
                      + "; ".join(f"{tl:g}′/{pm:g} mm: " + ("no FEM point" if v is None else f"{v:.2f} % {'<' if v < q else '≥'} {q:.2f} %")
                                  for tl, pm, v, q in ms) + f" — **{'met' if ok else 'NOT met'}**. The FEM's own error "
                      f"estimate in these cells reaches {summary[-1][4]:.2f} %: where it exceeds the difference, the law "
                      "agrees with the FEM within the FEM's uncertainty.", ""]
    return {"have_data": True, "rows": rows, "ok": all_ok and bool(summary), "laws": laws_, "lines": lines,
            "summary": summary}


T3_CSV_COLUMNS = ("scene", "tilt_arcmin", "penetration_mm", "force_fem_N", "force_error_rel", "moment_fem_Nm",
                  "moment_error_rel", "width_fem_m") + tuple(
    f"{k}_{q}" for k in T3_METHODS for q in ("N", "pct", "moment_Nm", "moment_pct", "width_m"))


def table3_csv(rows: list[dict]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(T3_CSV_COLUMNS)
    for r in rows:
        w.writerow(["" if r.get(c) is None else (f"{r[c]:.10g}" if isinstance(r[c], float) else r[c]) for c in T3_CSV_COLUMNS])
    return buf.getvalue()


def make_figure_3d(t3: dict):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = t3["rows"]
    tilts = sorted({round(r["tilt_arcmin"], 6) for r in rows})
    fig, axes = plt.subplots(1, len(tilts), figsize=(4.2 * len(tilts), 4.2), squeeze=False)
    for ax, tl in zip(axes[0], tilts):
        rr = sorted((r for r in rows if round(r["tilt_arcmin"], 6) == tl), key=lambda r: r["penetration_mm"])
        x = np.array([r["penetration_mm"] for r in rr])
        F = np.array([r["force_fem_N"] for r in rr])
        ax.errorbar(x, F / 1e3, yerr=np.array([r["force_error_rel"] for r in rr]) * F / 1e3, fmt="ks", ms=4, capsize=3,
                    label="3D FEM (Richardson error bar)")
        for k, (key, label) in enumerate(T3_METHODS.items()):
            ax.plot(x, np.array([r[key + "_N"] for r in rr]) / 1e3, marker="o", ms=3, color=f"C{k}", label=label)
        ax.set_title(f"tilt {tl:g}′")
        ax.set_xlabel("centre penetration Δr (mm)")
        ax.set_ylabel("contact force (kN)")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("Tilted ring: laws against the 3D FEM reference")
    fig.tight_layout()
    png, svg = io.BytesIO(), io.BytesIO()
    fig.savefig(png, format="png", dpi=110, metadata={"Software": None})
    with plt.rc_context({"svg.hashsalt": "ringcontact-accuracy-3d"}):
        fig.savefig(svg, format="svg", metadata={"Date": None, "Creator": None})
    plt.close(fig)
    return png.getvalue(), svg.getvalue()


# --------------------------------------------------------------------------------------------
# figure
# --------------------------------------------------------------------------------------------

def make_figure(tables: list[dict]):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(tables)
    fig, axes = plt.subplots(2, n, figsize=(4.6 * n, 7.2), squeeze=False, sharex=True)
    styles = {"conformal-plane-stress": ("C0", "-"), "conformal-plane-strain": ("C0", ":"), "johnson": ("C1", "-"),
              "pereira": ("C2", "-"), "calibrated-fit": ("C3", "-")}
    for k, t in enumerate(tables):
        ax, ax2 = axes[0, k], axes[1, k]
        geo = t["geometry"]
        pen_mm = np.linspace(0.0005, 0.05, 200)
        curves = law_forces(geo, pen_mm * MM)
        curves["calibrated-fit"] = t["law"].force(pen_mm * MM).force_N
        fem_pen = t["penetration_m"] / MM
        fem_f = t["force_fem_N"]
        for key, (c, ls) in styles.items():
            ax.plot(pen_mm, curves[key] / 1e3, color=c, ls=ls, lw=1.4, label=LAW_LABELS[key])
        ax.errorbar(fem_pen, fem_f / 1e3, yerr=t["fem_error_rel"] * fem_f / 1e3, fmt="ks", ms=4, capsize=3,
                    label="FEM (Richardson error bar)", zorder=5)
        ax.set_yscale("log")
        ax.set_ylabel("contact force (kN)")
        ax.set_title(f"scene {t['scene']} (plane {geo.plane})")
        ax.grid(alpha=0.3, which="both")
        if k == 0:
            ax.legend(fontsize=7, loc="lower right")
        # bottom: percentage difference at the FEM points
        fem_laws = law_forces(geo, t["penetration_m"])
        fem_laws["calibrated-fit"] = t["law"].force(t["penetration_m"]).force_N
        for key, (c, ls) in styles.items():
            ax2.plot(fem_pen, 100 * (fem_laws[key] - fem_f) / fem_f, color=c, ls=ls, marker=".", lw=1.2)
        ax2.plot(fem_pen, 100 * t["chosen"].holdout_rel_err, color="C3", ls="none", marker="o", mfc="none",
                 label="calibrated, held out")
        ax2.fill_between(fem_pen, -100 * t["fem_error_rel"], 100 * t["fem_error_rel"], color="k", alpha=0.25,
                         label="FEM error band")
        ax2.set_yscale("symlog", linthresh=1.0)
        ax2.axhline(0, color="k", lw=0.6)
        ax2.set_xlabel("penetration Δr (mm)")
        ax2.set_ylabel("(P_law − P_FEM)/P_FEM (%)")
        ax2.grid(alpha=0.3, which="both")
        if k == 0:
            ax2.legend(fontsize=7, loc="lower right")
    fig.suptitle("Analytic laws against the 2D FEM reference (Table 1 rings)")
    fig.tight_layout()
    png, svg = io.BytesIO(), io.BytesIO()
    fig.savefig(png, format="png", dpi=110, metadata={"Software": None})
    with plt.rc_context({"svg.hashsalt": "ringcontact-accuracy"}):
        fig.savefig(svg, format="svg", metadata={"Date": None, "Creator": None})
    plt.close(fig)
    return png.getvalue(), svg.getvalue()


def compute(dataset_path=cal.DATASET_2D) -> tuple[list[dict], dict]:
    ds = read_dataset(dataset_path)
    info = cal.dataset_provenance(Path(dataset_path), ds)
    tables = []
    for scene in ds.scenes():
        try:
            t = scene_table(ds, scene, info)
        except cal.DatasetError as exc:       # a scene without the Table 2 displacements: say so, go on
            print(f"[accuracy] scene {scene!r} skipped: {exc}")
            continue
        tables.append(t)
    return tables, table3()


def build(out_dir: Path) -> list[Path]:
    """Write the accuracy report files into ``out_dir``; return their paths."""
    out_dir = Path(out_dir)
    tables, t3 = compute()
    png, svg = make_figure(tables)
    files = [atomic_write_text(out_dir / "accuracy-table2.csv", table2_csv(tables))]
    if t3["have_data"]:
        files.append(atomic_write_text(out_dir / "accuracy-table3.csv", table3_csv(t3["rows"])))
        if t3["rows"]:
            png3, svg3 = make_figure_3d(t3)
            files += [atomic_write_bytes(out_dir / "accuracy-table3-force-displacement.png", png3),
                      atomic_write_bytes(out_dir / "accuracy-table3-force-displacement.svg", svg3)]
    files += [atomic_write_bytes(out_dir / "accuracy-force-displacement.png", png),
              atomic_write_bytes(out_dir / "accuracy-force-displacement.svg", svg),
              atomic_write_text(out_dir / "accuracy-table2.md", write_markdown(tables, t3))]
    return files
