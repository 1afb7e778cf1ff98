"""Console jobs of the 2D FEM reference (registered in reports/cli/__init__.py).

    ringcontact fem-point 0.01 [--scene clamped] [--h-mm 1] [--order 2] [--json]
    ringcontact fem-sweep [--out PATH] [--scheduler ADDRESS]   regenerate the committed dataset (progress on a TTY)
    ringcontact fem-check [--points 3]            recompute a few committed points, print differences
    ringcontact fem-report [--path P] [--out D]   report of the committed dataset (reports.fem2d)
    ringcontact fem-paper [--h-mm 2] [--out D]    the paper set-up study and its report (reports.fem2d_paper)
    ringcontact fem-vtu 0.01 out.vtu [--scene clamped]   deformed rings + pressure + stresses for ParaView

Engineer units at this edge only (mm, kN, degrees, MPa); everything inside is SI. JSON keys carry
the SI unit symbol (``force_N``, ``peak_pressure_Pa``). Outputs default to paths relative to the
working directory; every input is checked (plausible ranges: :mod:`contact.plausible`) and every
output is checked writable before anything is computed.
"""
from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from contact.errors import InputError, RingContactError
from contact.units import MM
from reports.cli._edge import PUBLISHED, Parser, count, fail, in_file, out_dir, out_file, quantity, unit_keys

#: where the jobs write by default: relative to the working directory (the repository root in a checkout)
DATASET_OUT = "fem_reference/data/fem2d-reference.json"


def _point_parser(prog: str, help_: str) -> argparse.ArgumentParser:
    ap = Parser(prog=prog, description=help_)
    ap.add_argument("penetration_mm", type=quantity("penetration_mm"), help="penetration Δr = r − δ0 [mm]")
    ap.add_argument("--scene", default="clamped",
                    help="a ring-pair file (.toml, schema ringcontact.ring-scene/1) or a scene name: clamped | "
                         "clamped-stress | persson-40 | steel-in-aluminium (bundled files) | persson-<ratio> | paper-…")
    ap.add_argument("--h-mm", type=quantity("h_mm"), default=None,
                    help="contact element size [mm]; default: Richardson over 4, 2, 1 mm (+0.5 if needed)")
    ap.add_argument("--order", type=int, default=2, choices=(1, 2), help="element order")
    return ap


def point_main(argv: list[str]) -> int:
    """``fem-point``: solve one point and print it (or JSON with --json)."""
    ap = _point_parser("ringcontact fem-point", "solve one 2D contact point")
    ap.add_argument("--json", action="store_true", help="print the full point record as JSON (SI units)")
    args = ap.parse_args(argv)
    from fem_reference.plane.solve import ContactModel
    from fem_reference.plane_check import scene_2d
    from fem_reference.plane.sweep import Levels, arc_zone_rad, reference_point, spec_for

    try:
        scene = scene_2d(args.scene)
        if args.h_mm is None:
            rec = reference_point(Levels(scene, order=args.order), args.penetration_mm * MM)
        else:
            # one level of the reference's mesh family (graded toward this point's possible arc)
            zone = arc_zone_rad(scene.rings, args.penetration_mm * MM)
            m = ContactModel.build(scene, spec_for(scene, args.h_mm * MM, args.order, zone))
            s = m.solve(args.penetration_mm * MM)
            rec = {"scene": scene.name, "plane": scene.plane, "penetration_m": args.penetration_mm * MM,
                   "force_n": s.force_n, "force_error_rel": None, "half_angle_rad": s.half_angle_rad,
                   "peak_pressure_pa": s.peak_pressure_pa, "ndofs": s.ndofs, "iterations": s.iterations,
                   "wall_s": s.wall_s, "h_contact_m": args.h_mm * MM, "element_order": args.order,
                   "arc_phi_rad": s.arc_phi_rad.tolist(), "arc_pressure_pa": s.arc_pressure_pa.tolist()}
    except RingContactError as exc:
        return fail("ringcontact fem-point", exc)
    if args.json:
        print(json.dumps(unit_keys({k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in rec.items()}),
                         indent=1))
        return 0
    err = rec.get("force_error_rel")
    print(f"scene            {rec['scene']} (plane {rec['plane']})")
    print(f"penetration      {rec['penetration_m'] / MM:.5g} mm")
    print(f"force            {rec['force_n'] / 1e3:.4f} kN" + (f"  (est. error {err:.1e})" if err is not None else ""))
    print(f"half-angle       {np.degrees(rec['half_angle_rad']):.3f} deg")
    print(f"peak pressure    {rec['peak_pressure_pa'] / 1e6:.2f} MPa")
    print(f"mesh             h = {rec['h_contact_m'] / MM:g} mm, P{rec['element_order']}, {rec['ndofs']} DOFs")
    print(f"solver           {rec['iterations']} active-set iterations, {rec['wall_s']:.2f} s")
    if "h_levels_m" in rec:
        print(f"levels           {', '.join(f'{h / MM:g}' for h in rec['h_levels_m'])} mm (Richardson), "
              f"{rec['wall_levels_s']:.2f} s for the whole point from scratch")
    if rec["peak_pressure_pa"] > 2e9:
        print(f"note: peak pressure {rec['peak_pressure_pa'] / 1e9:.1f} GPa is beyond the yield of bearing steel; "
              "this is the linear-elastic answer only")
    return 0


def sweep_main(argv: list[str]) -> int:
    """``fem-sweep``: regenerate the committed dataset (locally, or on a dask cluster with ``--scheduler``)."""
    from fem_reference.plane.sweep import regenerate
    from sweep.cluster import connect

    ap = Parser(prog="ringcontact fem-sweep", description="regenerate the 2D FEM reference dataset")
    ap.add_argument("--out", type=out_file, default=DATASET_OUT,
                    help=f"output JSON (default {DATASET_OUT}: the committed copy when run from the repository root)")
    ap.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="run the scenes on the dask.distributed cluster at ADDRESS (the dask extra)")
    ap.add_argument("--scene", action="append", default=None, metavar="SCENE",
                    help="a ring-pair file (.toml) or a scene name, repeatable (default: clamped, clamped-stress, "
                         "persson-40); a ring-pair file's own penetration points are used when it is the only scene")
    args = ap.parse_args(argv)
    try:
        from fem_reference.plane.sweep import DEFAULT_SCENES
        from fem_reference.ring_scene import is_file_argument, load

        from fem_reference.plane_check import resolved

        names = args.scene or list(DEFAULT_SCENES)
        scenes = [resolved(load(n)) if is_file_argument(n) else n for n in names]
        kw = {}
        if len(scenes) == 1 and not isinstance(scenes[0], str):
            kw["penetrations_m"] = list(scenes[0].penetrations_2d_m)
        with connect(args.scheduler) as client:
            path = regenerate(args.out, executor=client, scene_names=scenes, **kw)
    except RingContactError as exc:
        return fail("ringcontact fem-sweep", exc)
    print(f"wrote {path}")
    return 0


def check_main(argv: list[str]) -> int:
    """``fem-check``: recompute a few committed points and report the differences."""
    from contact.dataset import read_dataset
    from fem_reference.plane.sweep import DATASET_PATH, check_against_committed

    ap = Parser(prog="ringcontact fem-check", description="recompute committed points, compare")
    ap.add_argument("--path", type=in_file, default=DATASET_PATH, help="2D dataset (default: the packaged one)")
    ap.add_argument("--points", type=count(1, 50, "points"), default=3, help="points per scene (1-50)")
    ap.add_argument("--scene", action="append", help="only this scene (repeatable)")
    ap.add_argument("--tol", type=quantity("tol"), default=1e-6, help="relative difference that counts as a change")
    args = ap.parse_args(argv)
    try:
        have = read_dataset(args.path, kind="2d").scenes()
        for name in args.scene or []:
            if name not in have:
                raise InputError(f"--scene = {name}: not in {args.path} (have {', '.join(have)})")
        rows = check_against_committed(args.path, args.points, args.scene)
    except RingContactError as exc:
        return fail("ringcontact fem-check", exc)
    worst = 0.0
    print(f"{'scene':<16}{'Δr mm':>9}{'committed kN':>15}{'new kN':>15}{'diff':>11}{'est.err':>10}")
    for r in rows:
        worst = max(worst, abs(r["diff_rel"]))
        print(f"{r['scene']:<16}{r['penetration_m'] / MM:>9.4f}{r['committed_force_n'] / 1e3:>15.4f}"
              f"{r['new_force_n'] / 1e3:>15.4f}{r['diff_rel']:>11.2e}{r['error_estimate_rel']:>10.1e}")
    print(f"largest difference {worst:.2e} ({'OK' if worst <= args.tol else 'CHANGED'} at tol {args.tol:g})")
    return 0 if worst <= args.tol else 1


def report_main(argv: list[str] | None = None) -> int:
    """``fem-report``: report of the committed 2D dataset and its verification (:mod:`reports.fem2d`)."""
    from contact.dataset import read_dataset
    from fem_reference.plane.sweep import DATASET_PATH
    from reports.fem2d import write_report

    ap = Parser(prog="ringcontact fem-report", description="report of the committed 2D FEM dataset")
    ap.add_argument("--path", type=in_file, default=DATASET_PATH, help="2D dataset (default: the packaged one)")
    ap.add_argument("--out", type=out_dir, default=PUBLISHED, help=f"output directory (default {PUBLISHED})")
    args = ap.parse_args(argv)
    try:
        read_dataset(args.path, kind="2d")
        print(f"wrote {write_report(args.path, args.out)}")
    except RingContactError as exc:
        return fail("ringcontact fem-report", exc)
    return 0


def paper_main(argv: list[str] | None = None) -> int:
    """``fem-paper``: run the paper set-up study (:mod:`fem_reference.paper_setup`) and write its report."""
    from fem_reference import paper_setup
    from reports.fem2d_paper import write_report

    ap = Parser(prog="ringcontact fem-paper", description=paper_setup.__doc__.splitlines()[0])
    ap.add_argument("--h-mm", type=quantity("h_mm"), default=2.0, help="contact element size [mm]")
    ap.add_argument("--out", type=out_dir, default=PUBLISHED, help=f"output directory (default {PUBLISHED})")
    ap.add_argument("--quiet", action="store_true", help="no progress lines")
    args = ap.parse_args(argv)
    try:
        rows = paper_setup.run(args.h_mm * 1e-3, progress=(lambda *_: None) if args.quiet else print)
        write_report(rows, Path(args.out))
    except RingContactError as exc:
        return fail("ringcontact fem-paper", exc)
    print(f"wrote {Path(args.out) / 'fem2d-paper-setup.md'}")
    return 0


def vtu_main(argv: list[str]) -> int:
    """``fem-vtu``: write one solved point as VTU."""
    from fem_reference.plane.export import write_vtu
    from fem_reference.plane.solve import ContactModel
    from fem_reference.plane_check import scene_2d
    from fem_reference.plane.sweep import spec_for

    ap = _point_parser("ringcontact fem-vtu", "export a solved point to VTU (ParaView)")
    ap.add_argument("out", type=out_file, nargs="?", default=None, help="output .vtu file (or --out)")
    ap.add_argument("--out", dest="out_flag", type=out_file, default=None, help="output .vtu file")
    ap.add_argument("--scale", type=quantity("scale"), default=1.0, help="displacement magnification stored as 'warp' [-]")
    args = ap.parse_args(argv)
    if args.out is not None and args.out_flag is not None and Path(args.out) != Path(args.out_flag):
        ap.error(f"--out = {args.out_flag}: the output is also given as {args.out}; give it once")
    args.out = args.out_flag or args.out
    if args.out is None:
        ap.error("--out: an output .vtu file is needed (ringcontact fem-vtu 0.01 --out p.vtu)")
    try:
        scene = scene_2d(args.scene)
        m = ContactModel.build(scene, spec_for(scene, (args.h_mm or 2.0) * MM, args.order))
        s = m.solve(args.penetration_mm * MM)
        path = write_vtu(args.out, m, s, warp_scale=args.scale)
    except RingContactError as exc:
        return fail("ringcontact fem-vtu", exc)
    print(f"wrote {path} ({s.force_n / 1e3:.3f} kN)")
    return 0


def main(argv: list[str]) -> int:  # pragma: no cover - dispatch helper
    return point_main(argv)
