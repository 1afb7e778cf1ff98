"""A law's tilt correction fitted to 3D tilted FEM points, and held out: the data side of
:mod:`contact.calibrate.tilt_correction` (what the surfaces are fitted to, a law with its correction).
"""
from __future__ import annotations

import dataclasses
import itertools

import numpy as np

from contact.calibrate import tilt_correction
from contact.calibrate.fit import ACCURACY_ADD_REL, ACCURACY_FEM_FACTOR
from contact.loose_support import loose_support_force


def log_ratios(law, points: list[dict]) -> dict:
    """What a correction of ``law`` is fitted to: at each tilted point (``penetration_m`` mid-plane > 0, ``tilt_rad``
    > 0, ``force_n``, ``moment_nm`` and their stated relative errors) the loaded edge's penetration (m), the tilt
    (rad), ``ln(F_FEM/F_law)`` and ``ln(M_FEM/M_law)`` with the law's kernel *without* a correction (the ring centre
    at ``y = δ0 + Δr``, tilt about z, as the 3D FEM), and each point's accuracy bound (2x its stated error + 0.2 %,
    :func:`contact.calibrate.fit.within_accuracy`'s rule). Arrays keyed by those names."""
    g = law.geometry
    plain = {k: v for k, v in law.parameters.items() if not k.startswith("tilt_")}
    params = dataclasses.replace(law, parameters=plain).loose_support_params()
    pts = [p for p in points if p["tilt_rad"] > 0 and p["penetration_m"] > 0]
    pm = np.array([p["penetration_m"] for p in pts])
    t = np.array([p["tilt_rad"] for p in pts])
    res = loose_support_force(params, g.clearance_m + pm, 0.0, 0.0, t)
    return {"pen_edge_m": pm + 0.5 * g.width_m * t, "tilt_rad": t,
            "force": np.log(np.array([p["force_n"] for p in pts]) / -np.asarray(res.Fy_N)),
            "moment": np.log(np.array([p["moment_nm"] for p in pts]) / np.asarray(res.Mz_Nm)),
            "bound_force": ACCURACY_FEM_FACTOR * np.array([p.get("force_error_rel") or 0.0 for p in pts])
            + ACCURACY_ADD_REL,
            "bound_moment": ACCURACY_FEM_FACTOR * np.array([p.get("moment_error_rel") or 0.0 for p in pts])
            + ACCURACY_ADD_REL}


#: penalty weights the smoothing is chosen from, along ξ and along ψ independently (every pair of them), by
#: cross-validation on the fitted points only
SMOOTHING_GRID = (1e-4, 1e-3, 1e-2, 1e-1)
#: folds of that cross-validation (points sorted by tilt, then penetration; point i in fold i mod FOLDS)
FOLDS = 5


def smoothing_label(smoothing) -> str:
    """A smoothing (one weight, or the pair along ξ and along ψ) as the reports and the fit record write it: one
    number when both directions have it, else ``"<along ξ>/<along ψ>"``."""
    sx, sp = tilt_correction.smoothing_pair(smoothing)
    return f"{sx:g}" if sx == sp else f"{sx:g}/{sp:g}"


def _fit(law, data: dict, idx: np.ndarray, smoothing) -> tilt_correction.TiltCorrection:
    g = law.geometry
    lo = float(np.log(law.validity_penetration_m[0]))
    hi = float(np.log(np.hypot(law.validity_penetration_m[1], 0.5 * g.width_m * max(
        law.validity_tilt_max_rad, float(data["tilt_rad"].max())))))
    return tilt_correction.fit(data["pen_edge_m"][idx], data["tilt_rad"][idx], g.width_m, data["force"][idx],
                               data["moment"][idx], data["bound_force"][idx], data["bound_moment"][idx],
                               log_r_range=(lo, hi), smoothing=smoothing)


def choose_smoothing(law, data: dict) -> tuple[tuple[float, float], dict]:
    """The smoothing, a pair (along ξ, along ψ) of :data:`SMOOTHING_GRID`'s weights, whose :data:`FOLDS`-fold
    cross-validation on ``data`` (the fitted points, :func:`log_ratios`) gives the smallest worst held-out error over
    its bound, force and moment; and that worst ratio per candidate (keyed by :func:`smoothing_label`). On a tie the
    first candidate in the grid's order (the same weight in both directions first) wins."""
    n = data["tilt_rad"].size
    order = np.lexsort((data["pen_edge_m"], data["tilt_rad"]))
    fold = np.empty(n, dtype=int)
    fold[order] = np.arange(n) % FOLDS
    pairs = [(s, s) for s in SMOOTHING_GRID]
    pairs += [p for p in itertools.product(SMOOTHING_GRID, SMOOTHING_GRID) if p[0] != p[1]]
    worst = {}
    for s in pairs:
        w = 0.0
        for k in range(FOLDS):
            c = _fit(law, data, np.flatnonzero(fold != k), s)
            test = fold == k
            a, b = c.evaluate(data["pen_edge_m"][test], data["tilt_rad"][test], law.geometry.width_m)
            w = max(w, float(np.max(np.abs(np.expm1(a - data["force"][test])) / data["bound_force"][test])),
                    float(np.max(np.abs(np.expm1(b - data["moment"][test])) / data["bound_moment"][test])))
        worst[s] = w
    best = min(worst, key=worst.get)
    return best, {smoothing_label(k): v for k, v in worst.items()}


def with_tilt_correction(law, points: list[dict], *, smoothing=None, source: str = ""):
    """``law`` (family foundation or foundation-spline) with a tilt correction fitted to ``points`` (3D tilted FEM
    points, dataset rows; mid-plane penetrations > 0), the smoothing (one weight, or the pair along ξ and along ψ)
    chosen by :func:`choose_smoothing` unless given. The law's name gets ``-tilt``; its ``fit`` records what the
    correction was fitted to (``tilt_correction``; its ``smoothing`` the pair along ξ and along ψ, its
    cross-validation keyed by :func:`smoothing_label`)."""
    plain = dataclasses.replace(law, parameters={k: v for k, v in law.parameters.items() if not k.startswith("tilt_")})
    data = log_ratios(plain, points)
    cv = None
    if smoothing is None:
        smoothing, cv = choose_smoothing(plain, data)
    c = _fit(plain, data, np.arange(data["tilt_rad"].size), smoothing)
    tilt_max = max(law.validity_tilt_max_rad, float(data["tilt_rad"].max()))
    pair = tilt_correction.smoothing_pair(smoothing)
    info = {"points": int(data["tilt_rad"].size), "source": source, "smoothing": list(pair),
            "cross_validation_worst_error_over_bound": cv,
            "surfaces": "tensor-product uniform cubic B-splines, contact.calibrate.tilt_correction"}
    name = law.name if law.name.endswith("-tilt") else f"{law.name}-tilt"
    return dataclasses.replace(plain, name=name, parameters={**plain.parameters, **c.to_parameters()},
                               validity_tilt_max_rad=tilt_max, fit={**law.fit, "tilt_correction": info})


def held_out(law, points: list[dict]) -> dict:
    """The law's kernel (with its correction, if any) at 3D tilted points it was not fitted to (those with a loaded
    edge in contact and a load): per point the mid-plane penetration (m), tilt (rad), relative force and moment
    errors (–) and their bounds (arrays)."""
    g = law.geometry
    pts = [p for p in points if p["tilt_rad"] > 0 and p["force_n"] > 0
           and p["penetration_m"] + 0.5 * g.width_m * p["tilt_rad"] > 0]
    pm = np.array([p["penetration_m"] for p in pts])
    t = np.array([p["tilt_rad"] for p in pts])
    res = loose_support_force(law.loose_support_params(), g.clearance_m + pm, 0.0, 0.0, t)
    return {"penetration_m": pm, "tilt_rad": t,
            "force_error": -np.asarray(res.Fy_N) / np.array([p["force_n"] for p in pts]) - 1.0,
            "moment_error": np.asarray(res.Mz_Nm) / np.array([p["moment_nm"] for p in pts]) - 1.0,
            "bound_force": ACCURACY_FEM_FACTOR * np.array([p.get("force_error_rel") or 0.0 for p in pts])
            + ACCURACY_ADD_REL,
            "bound_moment": ACCURACY_FEM_FACTOR * np.array([p.get("moment_error_rel") or 0.0 for p in pts])
            + ACCURACY_ADD_REL}
