"""Table 3 style, tilted ring: the laws against every committed 3D dataset (rows, Markdown lines,
must-show against the paper's Table 3, CSV, figure)."""
from __future__ import annotations

import csv
import io
import math

import numpy as np

from contact import calibrate as cal
from contact import laws, tilt
from contact.dataset import ReferenceDataset, read_dataset
from contact.loose_support import loose_support_force
from contact.package_data import entries, location, shipped_name
from contact.units import ARCMIN, MM
from reports.accuracy.common import PAPER_TABLE3_PCT, PENETRATIONS_MM
from reports.digits import cell, rounded


T3_METHODS = {
    "conformal-paper": "conformal, paper's tilt model (Eqs. 8–19)",
    "calibrated-edge": "calibrated law in the paper's tilt model",
    "calibrated-slices": "calibrated, slice-integrated",
    "calibrated-kernel": "calibrated, compiled kernel (rotor path)",
}


def _rel(path) -> str:
    """A dataset's name in the reports: ``fem_reference/data/…`` when shipped, else the path."""
    return shipped_name(path)


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


def table3(data_dir) -> dict:
    """Table 3-style comparison from every committed 3D dataset (centre penetration, tilt about z).

    ``data_dir``: a folder path or a shipped entry (:data:`contact.calibrate.DATA_3D_DIR`).
    """
    data_dir = location(data_dir)
    paths = entries(data_dir, ".json")
    rel = _rel(data_dir)
    if not paths:
        return {"have_data": False, "rows": [], "ok": None, "laws": [], "lines": [
            f"No 3D reference dataset is committed (`{rel}/` " + ("is empty" if data_dir.is_dir() else "does not exist")
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
            lines += _t3_scene_lines(path, scene, law, chosen, srows)
            ms_lines, ok, item = _t3_must_show(srows, scene)
            all_ok &= ok
            summary.append(item)
            lines += ms_lines
    return {"have_data": True, "rows": rows, "ok": all_ok and bool(summary), "laws": laws_, "lines": lines,
            "summary": summary}


def _find(srows: list[dict], tl: float, pm: float) -> dict | None:
    """The row of a scene at tilt ``tl`` (arcmin, rounded to 6 digits) and penetration ``pm`` (mm, 9 digits)."""
    return next((r for r in srows if round(r["tilt_arcmin"], 6) == tl and round(r["penetration_mm"], 9) == pm), None)


def _t3_scene_lines(path, scene: str, law: cal.CalibratedLaw, chosen, srows: list[dict]) -> list[str]:
    """One 3D scene: its calibration, the force table per tilt and method, moments and widths, systematic notes."""
    tilts = sorted({round(r["tilt_arcmin"], 6) for r in srows})
    pens = sorted({round(r["penetration_mm"], 9) for r in srows})
    pars = ", ".join(f"{k} = {v:.6g} ± {law.parameter_std[k]:.2g} {law.parameter_units[k]}"
                     for k, v in law.parameters.items())
    lines = [f"### `{_rel(path)}`, scene `{scene}`", "",
             f"Calibrated at zero tilt on this dataset's own {len(chosen.penetration_m)} points: `{law.name}`, "
             f"{pars} (held-out max {100 * chosen.holdout_max:.3f} % at zero tilt). Every tilted cell below is "
             "therefore held out. Cells: force difference in %, signed; the paper's |%| in brackets.", "",
             "| tilt | method | " + " | ".join(f"{p:g} mm" for p in pens) + " |",
             "|---|---|" + "---|" * len(pens)]
    for tl in tilts:
        for key, label in T3_METHODS.items():
            cells = []
            for pm in pens:
                r = _find(srows, tl, pm)
                paper = _paper_t3(tl, pm)
                cells.append("" if r is None else f"{r[key + '_pct']:+.2f}"
                             + (f" ({paper:.2f})" if paper is not None and key == "conformal-paper" else ""))
            lines.append(f"| {tl:g}′ | {label} | " + " | ".join(cells) + " |")
        lines.append(f"| {tl:g}′ | FEM force (N) ± error (%) | " + " | ".join(
            "" if _find(srows, tl, pm) is None else f"{_find(srows, tl, pm)['force_fem_N']:,.0f} ± {100 * _find(srows, tl, pm)['force_error_rel']:.2f}".replace(",", " ")
            for pm in pens) + " |")
    lines += ["", "Moment M_z (difference in %, FEM value in N·m) and contact width (FEM / law, mm):", "",
              "| tilt | quantity | " + " | ".join(f"{p:g} mm" for p in pens) + " |", "|---|---|" + "---|" * len(pens)]
    for tl in tilts:
        for key in ("conformal-paper", "calibrated-slices"):
            lines.append(f"| {tl:g}′ | M_z, {T3_METHODS[key]} | " + " | ".join(
                "" if _find(srows, tl, pm) is None or _find(srows, tl, pm)[key + "_moment_pct"] is None
                else f"{_find(srows, tl, pm)[key + '_moment_pct']:+.1f}" for pm in pens) + " |")
        lines.append(f"| {tl:g}′ | M_z FEM (N·m) | " + " | ".join(
            "" if _find(srows, tl, pm) is None or _find(srows, tl, pm)["moment_fem_Nm"] is None
            else f"{_find(srows, tl, pm)['moment_fem_Nm']:.1f}" for pm in pens) + " |")
        lines.append(f"| {tl:g}′ | width FEM / paper law / slices (mm) | " + " | ".join(
            "" if _find(srows, tl, pm) is None else
            f"{(_find(srows, tl, pm)['width_fem_m'] or float('nan')) / MM:.1f} / {_find(srows, tl, pm)['conformal-paper_width_m'] / MM:.1f} / "
            f"{_find(srows, tl, pm)['calibrated-slices_width_m'] / MM:.1f}" for pm in pens) + " |")
    lines += ["", "Systematic differences: the paper's tilt model (Eqs. 8–19) loads the whole patch with the "
              "penetration of its most loaded edge, so it over-predicts the tilted load of a stiff support and "
              "gives no moment once the patch spans the full width; an elastic bed carries each axial slice at "
              "its own penetration, which the slice-integrated law does (and the compiled kernel for law code 2). "
              "The conformal rows are off by the boundary conditions, as in Table 2."]
    return lines


def _t3_must_show(srows: list[dict], scene: str) -> tuple[list[str], bool, tuple]:
    """Calibrated law (slice-integrated) vs the paper's Table 3 cells: lines, met?, summary tuple."""
    ms = []
    for tl, paper_row in PAPER_TABLE3_PCT.items():
        for pm, paper in zip(PENETRATIONS_MM, paper_row):
            r = _find(srows, round(tl, 6), round(pm, 9))
            if r is None:
                ms.append((tl, pm, None, paper))
            else:
                ms.append((tl, pm, abs(r["calibrated-slices_pct"]), paper))
    have = [m for m in ms if m[2] is not None]
    ok = bool(have) and all(v < q for _, _, v, q in have) and len(have) == len(ms)
    fem_errs = [100 * _find(srows, round(tl, 6), round(pm, 9))["force_error_rel"] for tl, pm, v, _ in ms if v is not None]
    item = (scene, max(v for _, _, v, _ in have) if have else math.nan, len(have), len(ms),
            max(fem_errs) if fem_errs else math.nan)
    lines = ["", "Must show (calibrated law, slice-integrated, held out, vs the paper's Table 3): "
             + "; ".join(f"{tl:g}′/{pm:g} mm: " + ("no FEM point" if v is None else f"{v:.2f} % {'<' if v < q else '≥'} {q:.2f} %")
                         for tl, pm, v, q in ms) + f" — **{'met' if ok else 'NOT met'}**. The FEM's own error "
             f"estimate in these cells reaches {item[4]:.2f} %: where it exceeds the difference, the law "
             "agrees with the FEM within the FEM's uncertainty.", ""]
    return lines, ok, item


T3_CSV_COLUMNS = ("scene", "tilt_arcmin", "penetration_mm", "force_fem_N", "force_error_rel", "moment_fem_Nm",
                  "moment_error_rel", "width_fem_m") + tuple(
    f"{k}_{q}" for k in T3_METHODS for q in ("N", "pct", "moment_Nm", "moment_pct", "width_m"))


def table3_csv(rows: list[dict]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(T3_CSV_COLUMNS)
    for r in rows:
        w.writerow(["" if r.get(c) is None else (cell(r[c]) if isinstance(r[c], float) else r[c]) for c in T3_CSV_COLUMNS])
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
            ax.plot(x, rounded([r[key + "_N"] for r in rr]) / 1e3, marker="o", ms=3, color=f"C{k}", label=label)
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
