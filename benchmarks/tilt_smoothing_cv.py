"""Why the 20 mm ring's one held-out moment point misses (issue 37): the tilt correction's smoothing against the
cross-validation criteria and the verification grid, printed (nothing written).

    .venv/bin/python benchmarks/tilt_smoothing_cv.py

For each ring of reports/published/law-tilt-correction/ (the committed training and verification grids) and each
smoothing weight: the :data:`contact.calibrate.tilt_fit.FOLDS`-fold cross-validation on the training points that
:func:`contact.calibrate.tilt_fit.choose_smoothing` runs (its criterion: the worst held-out error over its bound;
beside it the root mean square of that ratio and the share above 1), and the law fitted on every training point at that
weight checked on the verification grid (worst error over bound, force and moment, and the misses). Then the missing
point itself: its FEM moment levels, its stated error and the finer check level's moment, and the training points
around it with their fit residuals at the chosen weight.

This is a diagnosis, not a rule: a smoothing rule picked after looking at the verification grid would make that grid
no longer held out for these two rings.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact import calibrate as cal  # noqa: E402
from contact.calibrate import spline, tilt_fit  # noqa: E402
from contact.dataset import read_dataset  # noqa: E402
from contact.units import ARCMIN  # noqa: E402

GRIDS = ROOT / "reports" / "published" / "law-tilt-correction"
WEIGHTS = (1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1)
#: the point of law-tilt-correction.md's verdict that misses (mid-plane penetration m, tilt rad)
MISS = ("newcomer-20mm", 12.78e-6, 7 * ARCMIN)


def _setup(ring: str):
    train = read_dataset(GRIDS / f"fem3d-tilt-train-{ring}.json")
    verify = [p for p in read_dataset(GRIDS / f"fem3d-tilt-verify-{ring}.json").points if p["penetration_m"] > 0]
    base, _ = cal.calibrate_scene(train, ring, {}, families=(spline.FAMILY,))
    tilted = [p for p in train.points if p["tilt_rad"] > 0 and p["penetration_m"] > 0]
    return base, tilted, verify


def cv_ratios(base, data: dict, smoothing: float) -> np.ndarray:
    """Every training point's held-out |error|/bound, force and moment, in choose_smoothing's folds."""
    n = data["tilt_rad"].size
    fold = np.empty(n, dtype=int)
    fold[np.lexsort((data["pen_edge_m"], data["tilt_rad"]))] = np.arange(n) % tilt_fit.FOLDS
    out = []
    for k in range(tilt_fit.FOLDS):
        c = tilt_fit._fit(base, data, np.flatnonzero(fold != k), smoothing)
        t = fold == k
        a, b = c.evaluate(data["pen_edge_m"][t], data["tilt_rad"][t], base.geometry.width_m)
        out += list(np.abs(np.expm1(a - data["force"][t])) / data["bound_force"][t])
        out += list(np.abs(np.expm1(b - data["moment"][t])) / data["bound_moment"][t])
    return np.array(out)


def ring_table(ring: str) -> None:
    base, tilted, verify = _setup(ring)
    data = tilt_fit.log_ratios(base, tilted)
    chosen, _ = tilt_fit.choose_smoothing(base, data)
    print(f"\n{ring}: {len(tilted)} tilted training points, {len(verify)} verification points; "
          f"choose_smoothing picks {chosen:g}")
    print("| smoothing | CV worst | CV rms | CV share > 1 | verify worst moment | verify worst force | misses |")
    print("|---|---|---|---|---|---|---|")
    for s in WEIGHTS:
        r = cv_ratios(base, data, s)
        h = tilt_fit.held_out(tilt_fit.with_tilt_correction(base, tilted, smoothing=s), verify)
        vm, vf = np.abs(h["moment_error"]) / h["bound_moment"], np.abs(h["force_error"]) / h["bound_force"]
        print(f"| {s:g} | {r.max():.3f} | {np.sqrt(np.mean(r ** 2)):.3f} | {np.mean(r > 1):.3f} | {vm.max():.2f} | "
              f"{vf.max():.2f} | {int(np.sum(vm > 1) + np.sum(vf > 1))} |")


def miss_lines() -> None:
    ring, pen, t = MISS
    base, tilted, verify = _setup(ring)
    p = min(verify, key=lambda q: abs(q["penetration_m"] - pen) / pen + abs(q["tilt_rad"] - t) / t)
    print(f"\n{ring}, {p['penetration_m'] * 1e6:.4g} µm, {p['tilt_rad'] / ARCMIN:g}′: FEM moment levels "
          f"{[round(v, 3) for v in p['moment_levels_nm']]} N·m, stated error {100 * p['moment_error_rel']:.4f} %, "
          f"finer check level {p['moment_finer_nm']:.3f} N·m "
          f"({100 * (p['moment_finer_nm'] / p['moment_nm'] - 1):+.4f} % from the finest level)")
    law = tilt_fit.with_tilt_correction(base, tilted)
    h = tilt_fit.held_out(law, tilted)
    near = np.argsort(np.abs(h["penetration_m"] - pen) / pen + np.abs(h["tilt_rad"] - t) / t)[:6]
    print(f"training points around it, fit residuals at the chosen smoothing {law.fit['tilt_correction']['smoothing']:g}:")
    for k in near:
        print(f"  {h['penetration_m'][k] * 1e6:.4g} µm {h['tilt_rad'][k] / ARCMIN:g}′: moment "
              f"{100 * h['moment_error'][k]:+.3f} % (bound {100 * h['bound_moment'][k]:.3f} %)")


def main() -> int:
    for ring in ("newcomer-20mm", "steel-in-aluminium"):
        ring_table(ring)
    miss_lines()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
