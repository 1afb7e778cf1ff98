"""Which boundary conditions reproduce the paper's FEM loads? (issue 3, the paper set-up study)

Dai et al. (2025) do not state how their FE model was held, loaded or measured. Their Table 2
percentages imply FEM loads of 44.9, 105.2, 169.4, 235.9 and 304.0 kN at Δr = 0.01…0.05 mm
(docs/reference/contact-laws.md §10, recovered from the Pereira column). This module evaluates plausible
readings — plane stress/strain, how the bearing is driven, how the support is held, how the
"relative displacement" is measured, and (as a geometry change) a support embedded in a larger
housing. :func:`run` returns one row per reading; :mod:`reports.fem2d_paper` writes them as
``reports/published/fem2d-paper-setup.{md,csv,png,svg}``.

Measurements of Δr for a solved state u (total displacement; δ0 subtracted):

* ``drive``: the imposed displacement t of the bearing's driven surface;
* ``contact-circles``: mean u_y of the bearing's outer circle minus mean u_y of the support bore
  (the least-squares rigid translation of each contact surface);
* ``centroids``: area-mean u_y of the bearing ring minus that of the support ring.

Run: ``ringcontact fem-paper`` (about a minute; h = 2 mm P2, whose force error is ~1e-4 in the
committed sweep, far below the few-percent question asked here).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact.errors import ConvergenceError
from fem_reference.plane.elasticity import body_mean_weights, circle_mean_weights
from fem_reference.plane.geometry import table1_rings
from fem_reference.plane.mesh import BEARING, SUPPORT, MeshSpec
from fem_reference.plane.solve import ContactModel
from fem_reference.scenes import Scene

PAPER_DR_MM = np.array([0.01, 0.02, 0.03, 0.04, 0.05])
PAPER_FEM_KN = np.array([44.878, 105.247, 169.351, 235.945, 304.036])  # docs/reference/contact-laws.md §10
MEASUREMENTS = ("drive", "contact-circles", "centroids")


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
