"""Which boundary conditions reproduce the paper's FEM loads? (issue 3, the paper set-up study)

Dai et al. (2025) do not state how their FE model was held, loaded or measured. Their Table 2
percentages imply FEM loads of 44.9, 105.2, 169.4, 235.9 and 304.0 kN at Δr = 0.01…0.05 mm
(contact-laws.md §10, recovered from the Pereira column). This module evaluates plausible
readings — plane stress/strain, how the bearing is driven, how the support is held, how the
"relative displacement" is measured, and (as a geometry change) a support embedded in a larger
housing — and writes ``reports/published/fem2d-paper-setup.{md,csv,png,svg}``.

Measurements of Δr for a solved state u (total displacement; δ0 subtracted):
* ``drive``: the imposed displacement t of the bearing's driven surface;
* ``contact-circles``: mean u_y of the bearing's outer circle minus mean u_y of the support bore
  (the least-squares rigid translation of each contact surface);
* ``centroids``: area-mean u_y of the bearing ring minus that of the support ring.

Run: ``ringcontact fem-paper`` (about a minute; h = 2 mm P2, whose force error is ~1e-4 in the
committed sweep, far below the few-percent question asked here).
"""
from __future__ import annotations

import argparse
import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from contact.errors import ConvergenceError
from contact.files import atomic_write_bytes, atomic_write_text
from fem_reference.plane.elasticity import body_mean_weights, circle_mean_weights
from fem_reference.plane.geometry import table1_rings
from fem_reference.plane.mesh import BEARING, SUPPORT, MeshSpec
from fem_reference.plane.solve import ContactModel
from fem_reference.scenes import Scene

PAPER_DR_MM = np.array([0.01, 0.02, 0.03, 0.04, 0.05])
PAPER_FEM_KN = np.array([44.878, 105.247, 169.351, 235.945, 304.036])  # contact-laws.md §10
MEASUREMENTS = ("drive", "contact-circles", "centroids")
REPORT_DIR = Path(__file__).resolve().parent.parent / "reports" / "published"


@dataclass(frozen=True)
class Candidate:
    label: str
    scene: Scene
    measurement: str
    family: str


def candidates(include_housing: bool = True) -> list[Candidate]:
    r = table1_rings()
    out = []
    for plane in ("strain", "stress"):
        for drive in ("rigid-inner", "rigid-inner-y", "coupled-inner"):
            sc = Scene(f"paper-{plane}-{drive}-clamped-outer", r, plane, drive, "clamped-outer")
            for meas in MEASUREMENTS:
                out.append(Candidate(f"{plane}, {drive}, support clamped, Δr by {meas}", sc, meas, "Table 1 rings"))
        sc = Scene(f"paper-{plane}-rigid-inner-clamped-outer-lower", r, plane, "rigid-inner", "clamped-outer-lower")
        out.append(Candidate(f"{plane}, rigid-inner, support clamped on lower half only, Δr by drive", sc, "drive",
                             "Table 1 rings"))
    if include_housing:
        for plane in ("strain", "stress"):
            for ts_mm in (30.0, 100.0, 300.0, 1000.0):
                rr = table1_rings(support_thickness_m=ts_mm * 1e-3)
                sc = Scene(f"housing-{plane}-{ts_mm:g}mm", rr, plane, "rigid-inner", "clamped-outer")
                out.append(Candidate(f"{plane}, rigid-inner, support {ts_mm:g} mm thick (housing), Δr by drive", sc,
                                     "drive", "support as a thicker housing (geometry change)"))
            for rc_mm in (5.0, 10.0, 20.0):
                rr = table1_rings().with_(inner_radius_m=rc_mm * 1e-3)
                sc = Scene(f"solid-bearing-{plane}-{rc_mm:g}mm", rr, plane, "rigid-inner", "clamped-outer")
                out.append(Candidate(f"{plane}, solid bearing driven through a {rc_mm:g} mm shaft, 10 mm support, "
                                     "Δr by drive", sc, "drive", "bearing as a solid disc on a shaft (geometry change)"))
    return out


def _measure(model: ContactModel, u: np.ndarray, measurement: str, offset_m: float) -> float:
    rings = model.scene.rings
    if measurement == "drive":
        return offset_m - rings.clearance_m
    if measurement == "contact-circles":
        wb = circle_mean_weights(model.rmesh, model.basis, rings.outer_radius_m, BEARING)
        ws = circle_mean_weights(model.rmesh, model.basis, rings.bore_radius_m, SUPPORT)
    else:
        wb = body_mean_weights(model.rmesh, model.basis, BEARING)
        ws = body_mean_weights(model.rmesh, model.basis, SUPPORT)
    return float(wb @ u - ws @ u) - rings.clearance_m


def loads_at_paper_points(model: ContactModel, measurement: str) -> np.ndarray:
    """FEM loads [kN] at the measured Δr = 0.01…0.05 mm (interpolated along a drive sweep)."""
    if measurement == "drive":
        return np.array([model.solve(d * 1e-3).force_n for d in PAPER_DR_MM]) / 1e3
    drives, meas, force = [], [], []
    d = 0.0025e-3
    while True:
        try:
            s = model.solve(d)
        except ConvergenceError:   # arc below mesh resolution at the smallest drives: skip them
            d *= 1.35
            if d > 1.0e-3:
                break
            continue
        drives.append(d)
        meas.append(_measure(model, s.u, measurement, s.offset_m))
        force.append(s.force_n)
        if meas[-1] >= PAPER_DR_MM[-1] * 1e-3 * 1.02 or d > 1.0e-3:
            break
        d *= 1.35
    meas, force = np.array(meas), np.array(force)
    if len(meas) < 3 or meas[-1] < PAPER_DR_MM[-1] * 1e-3 or np.any(np.diff(meas) <= 0):
        return np.full(len(PAPER_DR_MM), np.nan)
    # interpolate log F against log Δr (both smooth power-law-like)
    ok = meas > 0
    return np.exp(np.interp(np.log(PAPER_DR_MM * 1e-3), np.log(meas[ok]), np.log(force[ok]))) / 1e3


def run(h_contact_m: float = 2e-3, include_housing: bool = True, progress=print) -> list[dict]:
    rows, models = [], {}
    for c in candidates(include_housing):
        key = c.scene
        if key not in models:
            grading = 10e-3 if c.scene.rings.support_outer_radius_m - c.scene.rings.bore_radius_m > 0.05 else 5e-3
            models[key] = ContactModel.build(c.scene, MeshSpec(h_contact_m=h_contact_m, order=2,
                                                               grading_length_m=grading))
        F = loads_at_paper_points(models[key], c.measurement)
        dev = F / PAPER_FEM_KN - 1
        rows.append({"label": c.label, "family": c.family, "scene": c.scene.name, "plane": c.scene.plane,
                     "drive": c.scene.bearing_drive, "hold": c.scene.support_hold, "measurement": c.measurement,
                     "support_thickness_mm": (c.scene.rings.support_outer_radius_m - c.scene.rings.bore_radius_m) * 1e3,
                     "loads_kn": F, "dev": dev, "max_abs_dev": float(np.nanmax(np.abs(dev))) if np.isfinite(F).all()
                     else math.nan, "shape": float(F[-1] / F[0]) if np.isfinite(F).all() else math.nan})
        progress(f"{c.label}: {np.round(F, 1)} kN, max dev {rows[-1]['max_abs_dev']:.1%}")
    if include_housing:
        for kind in ("housing", "shaft"):
            for plane in ("strain", "stress"):
                rows.append(fit_family(kind, plane, h_contact_m))
                progress(f"{rows[-1]['label']}: {np.round(rows[-1]['loads_kn'], 1)} kN, "
                         f"max dev {rows[-1]['max_abs_dev']:.1%}")
    return rows


def _family_scene(kind: str, plane: str, value_m: float) -> Scene:
    if kind == "housing":
        return Scene(f"housing-{plane}-fit", table1_rings(support_thickness_m=value_m), plane)
    return Scene(f"solid-bearing-{plane}-fit", table1_rings().with_(inner_radius_m=value_m), plane)


def fit_family(kind: str, plane: str, h_contact_m: float = 2e-3) -> dict:
    """One-parameter fit (support thickness, or shaft radius of a solid bearing) minimising the
    largest deviation from the paper over the five points; the other four are then a test."""
    from scipy.optimize import minimize_scalar

    lo, hi = (np.log(20e-3), np.log(2.0)) if kind == "housing" else (np.log(3e-3), np.log(60e-3))

    def loads(logv):
        sc = _family_scene(kind, plane, float(np.exp(logv)))
        grading = 10e-3 if kind == "housing" else 5e-3
        m = ContactModel.build(sc, MeshSpec(h_contact_m=h_contact_m, order=2, grading_length_m=grading))
        return sc, loads_at_paper_points(m, "drive")

    res = minimize_scalar(lambda x: np.max(np.abs(loads(x)[1] / PAPER_FEM_KN - 1)), bounds=(lo, hi),
                          method="bounded", options={"xatol": 0.01})
    sc, F = loads(res.x)
    dev = F / PAPER_FEM_KN - 1
    v = float(np.exp(res.x))
    what = (f"support {v * 1e3:.0f} mm thick" if kind == "housing" else f"solid bearing on a {v * 1e3:.1f} mm shaft")
    return {"label": f"{plane}, rigid-inner, {what} (fitted), Δr by drive",
            "family": "fitted: " + ("support thickness" if kind == "housing" else "shaft radius of a solid bearing"),
            "scene": sc.name, "plane": plane, "drive": "rigid-inner", "hold": "clamped-outer", "measurement": "drive",
            "support_thickness_mm": (sc.rings.support_outer_radius_m - sc.rings.bore_radius_m) * 1e3,
            "fitted_value_m": v, "loads_kn": F, "dev": dev, "max_abs_dev": float(np.max(np.abs(dev))),
            "shape": float(F[-1] / F[0])}


def write_report(rows: list[dict], out_dir: Path = REPORT_DIR) -> None:
    out_dir = Path(out_dir)
    # CSV
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(["family", "plane", "drive", "hold", "measurement", "support_thickness_mm"]
               + [f"F_{d:g}mm_kN" for d in PAPER_DR_MM] + ["max_abs_dev", "F005_over_F001"])
    w.writerow(["paper (implied, Dai 2025 Table 2)", "", "", "", "", ""] + [f"{v:.3f}" for v in PAPER_FEM_KN]
               + ["0", f"{PAPER_FEM_KN[-1] / PAPER_FEM_KN[0]:.3f}"])
    for r in rows:
        w.writerow([r["family"], r["plane"], r["drive"], r["hold"], r["measurement"], f"{r['support_thickness_mm']:g}"]
                   + [f"{v:.3f}" for v in r["loads_kn"]] + [f"{r['max_abs_dev']:.4f}", f"{r['shape']:.3f}"])
    atomic_write_text(out_dir / "fem2d-paper-setup.csv", buf.getvalue())
    # plot
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 5))
    ax.plot(PAPER_DR_MM, PAPER_FEM_KN, "ko-", lw=2.5, label="paper FEM (implied by Table 2)")
    best = sorted([r for r in rows if np.isfinite(r["max_abs_dev"])], key=lambda r: r["max_abs_dev"])[:4]
    show = {id(r): r for r in best}
    for r in rows:
        if r["family"] == "Table 1 rings" and r["measurement"] == "drive" and r["drive"] == "rigid-inner" \
                and r["hold"] == "clamped-outer":
            show[id(r)] = r
    for r in show.values():
        ax.plot(PAPER_DR_MM, r["loads_kn"], "s--", label=r["label"])
    ax.set_yscale("log")
    ax.set_xlabel("penetration Δr (mm)")
    ax.set_ylabel("contact force (kN)")
    ax.set_title("Paper's FEM loads vs plausible 2D boundary conditions")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    for ext in ("png", "svg"):
        b = io.BytesIO()
        fig.savefig(b, format=ext, dpi=120, bbox_inches="tight", metadata={"Date": None} if ext == "svg" else None)
        atomic_write_bytes(out_dir / f"fem2d-paper-setup.{ext}", b.getvalue())
    plt.close(fig)
    # Markdown
    lines = ["# The paper's FEM set-up: which boundary conditions reproduce its loads?", "",
             "Dai et al. (2025) give no FE boundary conditions. Their Table 2 percentages imply FEM loads of "
             + ", ".join(f"{v:.1f}" for v in PAPER_FEM_KN) + " kN at Δr = 0.01…0.05 mm "
             "(contact-laws.md §10). Each row below is a plausible reading, solved with this project's "
             "2D FEM (gmsh + scikit-fem, P2, h = 2 mm on the contact, frictionless mortar contact, gap of the "
             "exact circles; force error ~1e-4 by Richardson in the committed sweep). Generated by "
             "`ringcontact fem-paper`.", "",
             "Two numbers characterise each curve: its **level** (deviation from the paper at each point) and its "
             f"**shape** F(0.05)/F(0.01) (paper: {PAPER_FEM_KN[-1] / PAPER_FEM_KN[0]:.2f}; the closed-form conformal "
             "law: 5.70).", "",
             "| family | plane | bearing drive | support held | Δr measured by | "
             + " | ".join(f"{d:g} mm (kN)" for d in PAPER_DR_MM) + " | max dev | shape |",
             "|" + "---|" * (10 + 0)]
    lines[-1] = "|" + "---|" * (5 + len(PAPER_DR_MM) + 2)
    lines.append("| **paper (implied)** | | | | | " + " | ".join(f"**{v:.1f}**" for v in PAPER_FEM_KN)
                 + f" | 0 | {PAPER_FEM_KN[-1] / PAPER_FEM_KN[0]:.2f} |")
    for r in rows:
        hold = r["hold"] + (f" ({r['support_thickness_mm']:g} mm)" if r["family"] != "Table 1 rings" else "")
        loads = " | ".join("–" if not np.isfinite(v) else f"{v:.1f} ({d:+.0%})" for v, d in zip(r["loads_kn"], r["dev"]))
        md = "–" if not np.isfinite(r["max_abs_dev"]) else f"{r['max_abs_dev']:.1%}"
        sh = "–" if not np.isfinite(r["shape"]) else f"{r['shape']:.2f}"
        lines.append(f"| {r['family']} | {r['plane']} | {r['drive']} | {hold} | {r['measurement']} | {loads} | {md} | {sh} |")
    ok = [r for r in rows if np.isfinite(r["max_abs_dev"]) and r["max_abs_dev"] <= 0.05]
    ok_t1 = [r for r in ok if r["family"] == "Table 1 rings"]
    lines += ["", "## Findings", ""]
    t1 = [r for r in rows if r["family"] == "Table 1 rings" and np.isfinite(r["max_abs_dev"])]
    if t1:
        lo = min(r["loads_kn"][0] for r in t1)
        hi = max(r["loads_kn"][0] for r in t1)
        lines.append(f"* With the Table 1 geometry (90/100 mm bearing ring, 10 mm support), the plausible readings "
                     f"span {lo:.1f}…{hi:.1f} kN at 0.01 mm; {len(ok_t1)} of {len(t1)} come within 5 % of the "
                     "paper at all five points.")
    if ok_t1:
        for r in ok_t1:
            lines.append(f"  * within 5 %: {r['label']} (max deviation {r['max_abs_dev']:.1%}).")
    else:
        lines.append("* **None of the plausible boundary conditions for the stated geometry reproduces the paper's "
                     "loads.** Kinematically driven rings (rigid inner surface, support clamped) are 4–10× too stiff "
                     "whatever the plane assumption or measurement; a deformable (distributing-coupling) drive or a "
                     "support held only on its far half is one to two orders of magnitude too soft and has the wrong "
                     "shape (load ∝ Δr^2–3, ring bending).")
    geo = [r for r in ok if r["family"] != "Table 1 rings"]
    if geo:
        lines.append("* **Making the surroundings more compliant than a clamped 10 mm ring reproduces the loads within "
                     "a few percent, but only with a geometry the paper does not state.** Within 5 % at all five "
                     "points: " + "; ".join(f"{r['label']} (max deviation {r['max_abs_dev']:.1%}, shape "
                                           f"{r['shape']:.2f})" for r in geo) + ".")
        lines.append("* The residual is systematic: these look-alikes have shape 7.2–7.4 against the paper's 6.77 "
                     "(a few percent too soft at 0.01 mm, too stiff at 0.05 mm), so they match the level, not the "
                     "exact curve. A one-parameter fit tested on five points is evidence of the *kind* of set-up "
                     "(a bearing loaded through a shaft or solid body, or a support backed by a large housing), "
                     "not a recovered set-up.")
    lines += ["* The paper's shape F(0.05)/F(0.01) = 6.77 lies between the conformal law (5.70, infinite plate) "
              "and clamped 10 mm rings (8.2): the more compliant the surroundings, the closer to the law.",
              "* Consequence for this project: the `clamped` scene (stated geometry, stated-as-plausible BCs) stays the "
              "reference; comparisons with the paper's Table 2 percentages must say that the paper's FEM is about "
              "7× more compliant than it, and the law calibration should not be tuned to the paper's FEM numbers.",
              "", "Files: `fem2d-paper-setup.csv` (all numbers), `fem2d-paper-setup.png/.svg` (curves)."]
    atomic_write_text(out_dir / "fem2d-paper-setup.md", "\n".join(lines) + "\n")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="ringcontact fem-paper", description=__doc__.splitlines()[0])
    ap.add_argument("--h-mm", type=float, default=2.0, help="contact element size [mm]")
    ap.add_argument("--out", default=str(REPORT_DIR))
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    rows = run(args.h_mm * 1e-3, progress=(lambda *_: None) if args.quiet else print)
    write_report(rows, Path(args.out))
    print(f"wrote {Path(args.out) / 'fem2d-paper-setup.md'}")
    return 0
