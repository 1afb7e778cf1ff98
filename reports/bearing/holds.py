"""Which parts of a bearing's range no law family holds: the reference points where every family tried misses.

The rule is the law file's (:data:`~reports.bearing.names.LAW_ERROR_BOUND_REL`, :func:`contact.calibrate.fit.
holdout_excess`): a point is held by a family when its leave-one-out error exceeds the FEM point's own stated error
by at most the bound. At zero tilt every family fitted on that reference is tried (2D points; with tilt the 3D
zero-tilt points as well); the tilted 3D points, force and moment, are checked against the chosen law only (through
the compiled rotor kernel, the way a rotor uses it), since the families are fitted at zero tilt. Neighbouring points that no
family holds form one part: ``[lowest, highest]`` penetration of the run of consecutive points, at one tilt.
"""
from __future__ import annotations

import math

import numpy as np

from contact import calibrate as cal
from contact.units import MM
from reports.bearing.names import LAW_ERROR_BOUND_REL


def _parts(reference: str, tilt_arcmin: float, pen_m, beyond, best: list[str]) -> list[dict]:
    """Runs of consecutive points with ``beyond`` > bound (sorted by penetration) as parts."""
    out, run = [], []
    for k in list(range(len(pen_m))) + [None]:
        if k is not None and beyond[k] > LAW_ERROR_BOUND_REL:
            run.append(k)
            continue
        if run:
            worst = max(run, key=lambda j: beyond[j])
            out.append({"reference": reference, "tilt_arcmin": tilt_arcmin,
                        "penetration_mm": [pen_m[run[0]] / MM, pen_m[run[-1]] / MM], "points": len(run),
                        "smallest_excess_pct": 100 * float(min(beyond[j] for j in run)),
                        "worst_point_mm": pen_m[worst] / MM, "worst_excess_pct": 100 * float(beyond[worst]),
                        "best_family_there": best[worst]})
            run = []
    return out


def _zero_tilt(reference: str, ds, fits, name: str) -> list[dict]:
    pen, _, fem = cal.scene_points(ds, name)
    beyond = np.full(pen.size, math.inf)
    best = [""] * pen.size
    for f in fits:
        err = np.abs(np.asarray(f.holdout_rel_err, dtype=float)) - fem
        for k in range(pen.size):
            if np.isfinite(err[k]) and err[k] < beyond[k]:
                beyond[k], best[k] = float(err[k]), f.family
    return _parts(reference, 0.0, pen, beyond, best)


def _tilted(rows: list[dict], family: str) -> list[dict]:
    """Force, then moment (a row without a FEM moment error or a zero moment is left out of the moment parts)."""
    out = []
    for reference, col, fem in (("3d tilted (chosen law)", "calibrated-kernel_pct", "force_error_rel"),
                                ("3d tilted moment (chosen law)", "calibrated-kernel_moment_pct", "moment_error_rel")):
        for tilt in sorted({r["tilt_arcmin"] for r in rows if r["tilt_arcmin"] > 0}):
            at = sorted((r for r in rows if r["tilt_arcmin"] == tilt and r[col] is not None and r[fem] is not None),
                        key=lambda r: r["penetration_mm"])
            pen = np.array([r["penetration_mm"] * MM for r in at])
            err = np.array([abs(r[col]) / 100 - r[fem] for r in at])
            beyond = np.where(np.isfinite(err), err, math.inf)
            out += _parts(reference, float(tilt), pen, beyond, [family] * len(at))
    return out


def not_held(fit: dict, name: str) -> list[dict]:
    """The parts of the reference no family holds (see the module docstring), 2D first, then 3D by tilt.

    ``fit``: the calibration of :func:`reports.bearing.pipeline.calibrate`; ``name``: the ring pair's name.
    Each part: ``reference``, ``tilt_arcmin``, ``penetration_mm`` ``[low, high]``, ``points``,
    ``smallest_excess_pct`` and ``worst_excess_pct`` (the best family's held-out error beyond the FEM's own, %),
    ``worst_point_mm`` and ``best_family_there``.
    """
    out = _zero_tilt("2d", fit["ds2"], fit["fits2"], name)
    if fit.get("law3") is not None:
        out += _zero_tilt("3d zero tilt", fit["ds3"], fit["fits3"], name)
        out += _tilted(fit["rows3"], fit["chosen"].family)
    return out


def part_line(part: dict) -> str:
    """One part as a sentence."""
    lo, hi = part["penetration_mm"]
    where = f"{lo:.4g} mm" if lo == hi else f"{lo:.4g}-{hi:.4g} mm"
    return (f"no family holds {part['reference']} at {part['tilt_arcmin']:g} arcmin, penetration {where} "
            f"({part['points']} point(s)): "
            + ("the chosen law" if part["reference"].startswith("3d tilted") else "the best family")
            + f" ({part['best_family_there']}) misses by "
            f"{part['worst_excess_pct']:.2f} % beyond the FEM's error at {part['worst_point_mm']:.4g} mm "
            f"(bound {100 * LAW_ERROR_BOUND_REL:g} %)")
