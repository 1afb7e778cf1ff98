"""``ringcontact law``: evaluate an analytic contact law at given points, for people and scripts.

Penetrations in mm and tilts in arcminutes come from the command line (every penetration is
combined with every tilt) or from a CSV file with the columns ``penetration_mm`` and,
optionally, ``tilt_arcmin`` (one point per row). Output is a table, or JSON with
``--json``: force in N, moment in N·m, contact width in m and an explicit
``outside_domain`` flag (force and moment are ``null`` there, never a number).

Tilted points use the tilt geometry of Dai et al. (2025) Eqs. 8–19 (:mod:`contact.tilt`)
with the tilt aligned so that edge 1 penetrates most; ``--penetration-at centre`` (default)
reads the penetration at the ring centre plane, ``edge`` at the leading edge (Q9 of the
reference note).

A calibrated law (:mod:`contact.calibrate`, fitted to a FEM scene) is chosen with
``--law calibrated:<name>`` (``ringcontact calibrate`` lists them in contact/calibrated/), or a law
file by path (``--law my-bearing-law.json``, written by ``ringcontact bearing``). Its geometry and
materials are those of its scene (passing others is an error); tilted points use its slice-integrated
tilt model, and points whose deepest slice lies above the calibration's validity range, or whose tilt
exceeds the tilt a law file was checked at against the 3D reference, are flagged ``outside_domain``
(no extrapolation).

Examples::

    ringcontact law --penetration-mm 0.01 0.02 0.03
    ringcontact law --law johnson --penetration-mm 0.01 0.03 --json
    ringcontact law --penetration-mm 0.01 0.05 --tilt-arcmin 0.5 1 2
    ringcontact law --csv points.csv --clearance-mm 0.05 --width-mm 30 --json
    ringcontact law --law calibrated:clamped-foundation --penetration-mm 0.01 0.02 --tilt-arcmin 0 1
    ringcontact law --law bearing-my-bearing/my-bearing-law.json --penetration-mm 0.01 --tilt-arcmin 0 1 3
"""
from __future__ import annotations

import argparse
import csv
import json
import sys
from pathlib import Path

import numpy as np

from contact import calibrate, laws, tilt
from contact.errors import DatasetError, InputError, RingContactError
from contact.units import ARCMIN, GPA, MM
from reports.cli._edge import Parser, fail, in_file, quantity

#: most points one call evaluates (penetrations x tilts, or CSV rows): more is a batch job for the library
MAX_POINTS = 20000


def build_parser() -> argparse.ArgumentParser:
    p = Parser(
        prog="ringcontact law",
        description="Evaluate an analytic contact law of a bearing ring in its support (Dai et al. 2025). "
                    "Geometry and material defaults are the paper's Table 1 (204 GPa, nu 0.3, l0 30 mm, "
                    "clearance 0.05 mm); a calibrated law brings its own.",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    p.add_argument("--law", default="conformal", metavar="LAW",
                   help="contact law: " + ", ".join(sorted(laws.LAWS)) + ", calibrated:<name> with <name> one of "
                        + ", ".join(calibrate.available()) + ", or a law file (.json) of `ringcontact bearing`")
    src = p.add_mutually_exclusive_group(required=True)
    src.add_argument("--penetration-mm", type=quantity("penetration_mm"), nargs="+", metavar="MM",
                     help="penetration(s) Δr = |r| − δ0 in mm")
    src.add_argument("--csv", type=in_file, metavar="FILE",
                     help=f"CSV with a column penetration_mm and optionally tilt_arcmin (every cell filled; "
                          f"at most {MAX_POINTS} rows)")
    p.add_argument("--tilt-arcmin", type=quantity("tilt_arcmin"), nargs="+", default=[0.0], metavar="ARCMIN",
                   help="relative tilt(s) in arcminutes (combined with every penetration)")
    p.add_argument("--penetration-at", choices=("centre", "edge"), default="centre",
                   help="where a tilted ring's penetration is measured")
    p.add_argument("--clearance-mm", type=quantity("clearance_mm"), default=None, help="radial clearance δ0 (mm)")
    p.add_argument("--width-mm", type=quantity("width_mm"), default=None, help="ring width l0 (mm)")
    p.add_argument("--bearing-E-GPa", type=quantity("E_GPa"), default=None, help="Young's modulus of the ring (GPa)")
    p.add_argument("--bearing-nu", type=quantity("nu"), default=None, help="Poisson's ratio of the ring")
    p.add_argument("--support-E-GPa", type=quantity("E_GPa"), default=None, help="Young's modulus of the support (GPa)")
    p.add_argument("--support-nu", type=quantity("nu"), default=None, help="Poisson's ratio of the support")
    p.add_argument("--modulus", choices=laws.MODULI, default=None,
                   help="2D idealisation (default: plane_stress for conformal, plane_strain otherwise)")
    p.add_argument("--beta-reading", choices=laws.BETA_READINGS, default="zero",
                   help="reading of the conformal law's beta term")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    return p


def _csv_rows(path: Path) -> tuple[list[str], list[list[str]]]:
    try:
        with open(path, newline="", encoding="utf-8") as fh:
            reader = csv.reader(fh)
            header = next(reader, [])
            rows = []
            for row in reader:
                if len(rows) >= MAX_POINTS:
                    raise InputError(f"--csv = {path}: more than {MAX_POINTS} rows (split the file, or call "
                                     "contact.tilt.aligned_tilt_contact from Python)")
                rows.append(row)
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise DatasetError(f"--csv = {path}: cannot read ({exc})") from None
    return [h.strip() for h in header], rows


def read_points_csv(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """Read ``penetration_mm`` and optional ``tilt_arcmin`` columns; raise DatasetError on any problem.

    Every row must have as many cells as the header, every cell of the two columns a number inside
    its plausible range (:mod:`contact.plausible`); an empty cell is an error, not a zero.
    """
    from contact import plausible

    header, rows = _csv_rows(path)
    if "penetration_mm" not in header or not rows:
        raise DatasetError(f"--csv = {path}: needs a header with a column 'penetration_mm' and at least one row")
    names = [h.strip() for h in header]
    twice = sorted({h for h in names if names.count(h) > 1})
    if twice:
        raise DatasetError(f"--csv = {path}: column {twice[0]!r} appears {names.count(twice[0])} times in the header "
                           "(which one is meant?)")
    unknown = [h for h in names if h not in ("penetration_mm", "tilt_arcmin")]
    if unknown:
        raise DatasetError(f"--csv = {path}: column {unknown[0]!r} unknown (the columns are penetration_mm and, "
                           "optionally, tilt_arcmin)")
    cols = [(k, header.index(k)) for k in ("penetration_mm", "tilt_arcmin") if k in header]
    out = {"penetration_mm": [], "tilt_arcmin": []}
    for line, row in enumerate(rows, start=2):
        if len(row) != len(header):
            raise DatasetError(f"--csv = {path}, line {line}: {len(row)} cells, the header has {len(header)}")
        for key, j in cols:
            cell = row[j].strip()
            try:
                value = float(cell)
            except ValueError:
                raise DatasetError(f"--csv = {path}, line {line}: {key} = {cell!r}: not a number") from None
            out[key].append(plausible.check(key, value, cell, label=f"--csv line {line}: {key}"))
    pen = np.array(out["penetration_mm"])
    return pen, np.array(out["tilt_arcmin"]) if out["tilt_arcmin"] else np.zeros_like(pen)


#: the paper's Table 1 (Dai et al. 2025): geometry and materials when none are given
TABLE1_DEFAULTS = {"clearance_mm": 0.05, "width_mm": 30.0, "bearing_E_GPa": 204.0, "bearing_nu": 0.3,
                   "support_E_GPa": 204.0, "support_nu": 0.3}
CALIBRATED_PREFIX = "calibrated:"


def _geometry_of_calibrated(law: calibrate.CalibratedLaw) -> dict:
    g = law.geometry
    return {"clearance_mm": g.clearance_m / MM, "width_mm": g.width_m / MM, "bearing_E_GPa": g.bearing_E_Pa / GPA,
            "bearing_nu": g.bearing_nu, "support_E_GPa": g.support_E_Pa / GPA, "support_nu": g.support_nu}


def resolve_geometry(args: argparse.Namespace) -> calibrate.CalibratedLaw | None:
    """Fill the geometry/material fields of ``args`` in place; return the calibrated law if one is chosen.

    Analytic laws take the paper's Table 1 for anything not given. A calibrated law takes its
    scene's values; a different value given on the command line raises :class:`InputError`.
    """
    is_file = args.law.lower().endswith(".json")
    if args.law.startswith(CALIBRATED_PREFIX) or is_file:
        law = (calibrate.load_law_file(args.law) if is_file
               else calibrate.load_calibrated(args.law[len(CALIBRATED_PREFIX):]))
        own = _geometry_of_calibrated(law)
        for key, val in own.items():
            given = getattr(args, key)
            if given is not None and not np.isclose(given, val, rtol=1e-9, atol=0.0):
                raise InputError(f"--{key.replace('_', '-')} = {given:g}: calibrated law {law.name!r} holds for {key} = {val:g} only "
                                 "(its FEM scene); leave it out or refit for another geometry")
            setattr(args, key, val)
        return law
    if args.law not in laws.LAWS:
        raise InputError(f"--law = {args.law!r}: unknown (have {', '.join(sorted(laws.LAWS))} or "
                         f"{CALIBRATED_PREFIX}<name> with <name> in {', '.join(calibrate.available())})")
    for key, val in TABLE1_DEFAULTS.items():
        if getattr(args, key) is None:
            setattr(args, key, val)
    return None


def _evaluate_calibrated(law: calibrate.CalibratedLaw, pen_mm: np.ndarray, tilt_arcmin: np.ndarray,
                         penetration_at: str) -> list[dict]:
    """Points of a calibrated law: slice-integrated tilt (:meth:`CalibratedLaw.tilted`), validity flagged."""
    width_m = law.geometry.width_m
    top_m = law.validity_penetration_m[1]
    top_tilt = law.validity_tilt_max_rad      # > 0: the tilt the law was checked at against a 3D reference
    points = []
    for pm, ta in zip(pen_mm, tilt_arcmin):
        tilt_rad = abs(float(ta)) * ARCMIN
        centre_m = float(pm) * MM - (0.5 * tilt_rad * width_m if penetration_at == "edge" else 0.0)
        edge_m = centre_m + 0.5 * tilt_rad * width_m
        ok = edge_m <= top_m * (1 + 1e-12) and (top_tilt <= 0 or tilt_rad <= top_tilt * (1 + 1e-9))
        if edge_m > 0.0:
            load, moment, width = law.tilted(centre_m, tilt_rad)
        else:
            load, moment, width = 0.0, 0.0, 0.0
        if edge_m <= 0.0:
            state = "none"
        elif tilt_rad == 0.0:
            state = "line"
        else:
            state = "edge1"
        points.append({"penetration_mm": float(pm), "tilt_arcmin": float(ta),
                       "force_N": float(abs(load)) if ok else None, "moment_Nm": float(abs(moment)) if ok else None,
                       "contact_width_m": float(width), "edge_penetration_mm": float(edge_m / MM),
                       "state": state, "outside_domain": not ok})
    return points


def evaluate(args: argparse.Namespace, pen_mm: np.ndarray, tilt_arcmin: np.ndarray) -> list[dict]:
    """Evaluate the chosen law at the points (SI inside); one dict per point."""
    for name, vals, unit in (("penetration_mm", pen_mm, "mm"), ("tilt_arcmin", tilt_arcmin, "arcmin")):
        bad = ~np.isfinite(vals)
        if np.any(bad):
            raise InputError(f"{name} = {vals[bad][0]} {unit}: must be finite")
    calibrated = resolve_geometry(args)
    if calibrated is not None:
        return _evaluate_calibrated(calibrated, pen_mm, tilt_arcmin, args.penetration_at)
    clearance_m, width_m = args.clearance_mm * MM, args.width_mm * MM
    per_width = laws.force_per_width_function(
        args.law, clearance_m=clearance_m, bearing_E_Pa=args.bearing_E_GPa * GPA, bearing_nu=args.bearing_nu,
        support_E_Pa=args.support_E_GPa * GPA, support_nu=args.support_nu, modulus=args.modulus,
        beta_reading=args.beta_reading)
    laws.check_width(width_m)
    tilt_rad = np.abs(tilt_arcmin) * ARCMIN
    centre_pen_m = pen_mm * MM
    if args.penetration_at == "edge":
        centre_pen_m = centre_pen_m - tilt_rad * width_m / 2
    res = tilt.aligned_tilt_contact(centre_pen_m, tilt_rad, clearance_m=clearance_m, width_m=width_m,
                                    force_per_width=per_width)
    points = []
    for i in range(pen_mm.size):
        ok = bool(res.in_domain[i])
        points.append({
            "penetration_mm": float(pen_mm[i]),
            "tilt_arcmin": float(tilt_arcmin[i]),
            "force_N": float(res.force_N[i]) if ok else None,
            "moment_Nm": float(res.moment_Nm[i]) if ok else None,
            "contact_width_m": float(res.contact_width_m[i]),
            "edge_penetration_mm": float(max(res.penetration_1_m[i], res.penetration_2_m[i]) / MM),
            "state": {0: "none", 1: "edge1", 2: "edge2", 3: "two_point", 4: "line"}[int(res.state[i])],
            "outside_domain": not ok,
        })
    return points


def format_table(law: str, points: list[dict]) -> str:
    head = ["penetration_mm", "tilt_arcmin", "force_N", "moment_Nm", "contact_width_m", "state", "outside_domain"]
    rows = []
    for p in points:
        rows.append([f"{p['penetration_mm']:g}", f"{p['tilt_arcmin']:g}",
                     "outside domain" if p["outside_domain"] else f"{p['force_N']:.6g}",
                     "-" if p["outside_domain"] else f"{p['moment_Nm']:.6g}",
                     f"{p['contact_width_m']:.6g}", p["state"], "yes" if p["outside_domain"] else "no"])
    widths = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(head)]
    lines = [f"law: {law}", "  ".join(h.rjust(w) for h, w in zip(head, widths)),
             "  ".join("-" * w for w in widths)]
    lines += ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in rows]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        if args.csv is not None:
            pen_mm, tilt_arcmin = read_points_csv(args.csv)
        else:
            n = len(args.penetration_mm) * len(args.tilt_arcmin)
            if n > MAX_POINTS:
                raise InputError(f"--penetration-mm x --tilt-arcmin = {n} points: at most {MAX_POINTS} per call")
            pen, tl = np.meshgrid(np.asarray(args.penetration_mm, dtype=float),
                                  np.asarray(args.tilt_arcmin, dtype=float))
            order = np.argsort(tl.ravel(), kind="stable")
            pen_mm, tilt_arcmin = pen.ravel()[order], tl.ravel()[order]
        points = evaluate(args, pen_mm, tilt_arcmin)
    except RingContactError as exc:
        return fail("ringcontact law", exc)
    if args.json:
        params = {"clearance_m": args.clearance_mm * MM, "width_m": args.width_mm * MM,
                  "bearing_E_Pa": args.bearing_E_GPa * GPA, "bearing_nu": args.bearing_nu,
                  "support_E_Pa": args.support_E_GPa * GPA, "support_nu": args.support_nu,
                  "modulus": (args.modulus or ("plane_stress" if args.law == "conformal" else "plane_strain"))
                  if not args.law.startswith(CALIBRATED_PREFIX) else None,
                  "beta_reading": args.beta_reading, "penetration_at": args.penetration_at}
        print(json.dumps({"law": args.law, "parameters": params, "points": points}, indent=2, allow_nan=False))
    else:
        print(format_table(args.law, points))
    return 0


if __name__ == "__main__":   # pragma: no cover
    sys.exit(main())
