"""Console job ``ringcontact fem3d`` of the 3D tilted-ring FEM reference (registered in reports/cli/__init__.py).

    ringcontact fem3d point 0.02 --tilt-arcmin 2 [--tilt-axis z|y] [--level Q2] [--edge-refined] [--json]
    ringcontact fem3d sweep [--out PATH] [--workers 2] [--fresh] [--scheduler ADDRESS]   regenerate the committed dataset
    ringcontact fem3d check [--points 3] [--cached]                recompute a few committed points
    ringcontact fem3d report                                       tables/figures into reports/published/
    ringcontact fem3d vtu 0.02 --tilt-arcmin 2 --out p.vtu [--level Q2]   contact pressure map for ParaView

Engineer units at this edge only (mm, arcmin, kN, kN*m, MPa); everything inside is SI; JSON keys
carry the SI unit symbol (``force_N``, ``moment_Nm``). Mesh levels are cached under
``RINGCONTACT_CACHE`` (default ``~/.cache/ringcontact/fem3d``); a corrupt cached level is rebuilt.
BLAS/OpenMP threads: this process's share of the cores (contact/threads.py), set before numpy
loads; ``RINGCONTACT_THREADS`` overrides it.
Inputs are checked against their plausible ranges (:mod:`contact.plausible`) and outputs checked
writable before anything is computed.
"""
from __future__ import annotations

import json
import math
import sys

from contact.threads import set_thread_env, thread_share

set_thread_env(thread_share(1))      # this process's share of the cores, before numpy loads (contact/threads.py)

from contact.errors import RingContactError  # noqa: E402
from contact.units import ARCMIN, MM  # noqa: E402
from reports.cli._edge import PUBLISHED, Parser, count, fail, in_file, out_dir, out_file, quantity, unit_keys  # noqa: E402

SCENES_3D = ("clamped", "clamped-axially-fixed-ends", "clamped-axially-free-outer", "clamped-axially-free-inner",
             "clamped-axially-free")     # fem_reference.solid.compliance.SCENES (Table 1 rings)
DATASET_OUT = "fem_reference/data/3d/fem3d-reference.json"
SCENE_HELP = ("a ring-pair file (.toml, schema ringcontact.ring-scene/1), a bundled one (steel-in-aluminium), or the "
              "boundary conditions on the Table 1 rings: " + " | ".join(SCENES_3D))


def check_penetration_3d(geom, penetration_mm: float) -> None:
    """The mid-plane penetration (mm) of a 3D point: the bearing moved along +y, so more than −δ0 (a centre
    on the other side is the same contact mirrored, not a negative penetration), and at most 2 % of the
    ring radius (the small-strain model, as the 2D reference)."""
    from contact.errors import InputError
    lo, hi = -geom.clearance_m / MM, 0.02 * geom.bearing_outer_radius_m / MM
    if not lo < penetration_mm <= hi:
        raise InputError(f"penetration_mm = {penetration_mm:g} mm: must be in ({lo:g}, {hi:g}] mm (more than minus the "
                         f"clearance: the ring is moved along +y; at most 2 % of the ring radius: small strain)")


def scene_3d(arg: str):
    """``(RingPair3D, boundary-condition scene, label, ring scene or None)`` of a ``--scene`` value.

    A boundary-condition name of :data:`SCENES_3D` keeps the Table 1 rings (``clamped`` is also the
    bundled Table 1 ring-pair file: the same rings and conditions); anything else is a ring-pair file.
    """
    from fem_reference.ring_scene import is_file_argument, load
    from fem_reference.solid.geometry import RingPair3D

    if arg in SCENES_3D and not is_file_argument(arg):
        return RingPair3D(), arg, arg, None
    rs = load(arg)
    if rs.bc_3d is None:
        raise RingContactError(f"--scene = {arg}: hold = {rs.scene.support_hold!r} with bearing = "
                               f"{rs.scene.bearing_drive!r} has no 3D model (the 3D reference is a body of "
                               "revolution; see fem_reference/ring_scene.py HOLDS_3D)")
    return rs.rings_3d(), rs.bc_3d, rs.name, rs


def _levels():
    from fem_reference.solid.mesh import LEVELS
    return sorted(LEVELS)


def _fmt_point(rec: dict) -> str:
    lines = [
        f"scene            {rec['scene']}",
        f"penetration      {rec['penetration_m'] / MM:.5g} mm at the mid-plane, tilt {rec['tilt_rad'] / ARCMIN:.4g}'"
        + (f" about {rec['tilt_axis']}" if "tilt_axis" in rec else ""),
        f"force            {rec['force_n'] / 1e3:.4f} kN"
        + (f"  (est. error {rec['force_error_rel']:.1e})" if rec.get("force_error_rel") is not None else ""),
        f"moment           {rec['moment_nm'] / 1e3:.5f} kN*m"
        + (f"  (est. error {rec['moment_error_rel']:.1e})" if rec.get("moment_error_rel") is not None else ""),
        f"contact width    {rec['width_m'] / MM:.3f} mm from x = {rec['contact_x_min_m'] / MM:.3f} to "
        f"{rec['contact_x_max_m'] / MM:.3f} mm (law {rec['width_law_m'] / MM:.3f} mm)",
        f"contact          sides {rec['sides']}, edges loaded {rec['edges_loaded']}, "
        f"half-angle {math.degrees(rec['half_angle_rad']):.2f} deg, peak pressure {rec['peak_pressure_pa'] / 1e6:.1f} MPa",
        f"mesh             {rec['ndofs']} DOFs, {rec['n_pairs']} contact pairs ({rec['n_active']} active)",
        f"solver           {rec['iterations']} active-set iterations ({rec['lcp_method']}); levels "
        f"{rec['level_load_s']:.2f} s (cold build {rec['level_build_s']:.2f} s), contact solves {rec['solve_s']:.3f} s",
    ]
    if "force_y_n" in rec:
        lines.append(f"vectors          F on bearing (y, z) = ({rec['force_y_n'] / 1e3:.3f}, {rec['force_z_n'] / 1e3:.3f}) kN,"
                     f" M (y, z) = ({rec['moment_y_nm'] / 1e3:.4f}, {rec['moment_z_nm'] / 1e3:.4f}) kN*m")
    return "\n".join(lines)


def _tilt_arcmin():
    """``--tilt-arcmin`` within the 3D model's small-rotation range (fem_reference.solid.geometry.MAX_TILT_RAD)."""
    from fem_reference.solid.geometry import MAX_TILT_RAD
    top = int(MAX_TILT_RAD / ARCMIN * 10) / 10          # 171.8: rounded down, so the bound is inside the model's
    return quantity("tilt_arcmin", low=-top, high=top, why="the 3D model's small rotations")


def point_main(argv: list[str]) -> int:
    """``fem3d point``: solve one (penetration, tilt) and print it (or JSON with --json)."""
    ap = Parser(prog="ringcontact fem3d point", description="solve one 3D contact point")
    ap.add_argument("penetration_mm", type=quantity("penetration_mm"), help="mid-plane penetration Δr = r − δ0 [mm]")
    ap.add_argument("--tilt-arcmin", type=_tilt_arcmin(), default=0.0, help="tilt [arcmin]")
    ap.add_argument("--tilt-axis", choices=("z", "y"), default="z",
                    help="z: translation along +y, tilt theta_z (canonical); y: translation along +z, tilt theta_y "
                         "(the rotated case: same magnitudes, vectors rotated, see docs/reference/contact-laws.md §1)")
    ap.add_argument("--scene", default="clamped", help=SCENE_HELP)
    ap.add_argument("--level", default=None, choices=_levels(),
                    help="one mesh level (Q0, Q1, Q2, E0…) instead of the three-level estimate")
    ap.add_argument("--edge-refined", action="store_true",
                    help="use the levels E0-E2 graded hard toward the ring edges (edge-only contact, width << l0)")
    ap.add_argument("--check", action="store_true",
                    help="also solve on the finer check level (Q3, or E3 with --edge-refined): force_finer_N, moment_finer_Nm")
    ap.add_argument("--no-cache", action="store_true", help="do not read or write cached mesh levels")
    ap.add_argument("--json", action="store_true", help="print the full record as JSON (SI units)")
    args = ap.parse_args(argv)
    from fem_reference.solid.geometry import reduce_motion, rotate_about_x
    from fem_reference.solid.mesh import CHECK_LEVEL, DEFAULT_LEVELS, EDGE_CHECK_LEVEL, EDGE_LEVELS, LEVELS
    from fem_reference.solid.sweep import _jsonable, get_compliance, reference_point

    try:
        from contact.units import check_finite
        check_finite("penetration_mm", args.penetration_mm, "mm")
        check_finite("tilt_arcmin", args.tilt_arcmin, "arcmin")
        geom, bc, label, _ = scene_3d(args.scene)
        check_penetration_3d(geom, args.penetration_mm)
        r = geom.clearance_m + args.penetration_mm * MM
        tilt = args.tilt_arcmin * ARCMIN
        if args.tilt_axis == "z":
            canon = reduce_motion(r, 0.0, 0.0, tilt)
        else:
            canon = reduce_motion(0.0, r, tilt, 0.0)     # theta_y = tilt: the -x edge is loaded more
        names = [args.level] if args.level else list(EDGE_LEVELS if args.edge_refined else DEFAULT_LEVELS)
        for n in names:
            if n not in LEVELS:
                raise RingContactError(f"level = {n!r}: must be one of {sorted(LEVELS)}")
        comps = [get_compliance(geom, LEVELS[n], bc, use_cache=not args.no_cache) for n in names]
        check = None
        if args.check and not args.level:
            check = get_compliance(geom, LEVELS[EDGE_CHECK_LEVEL if args.edge_refined else CHECK_LEVEL], bc,
                                   use_cache=not args.no_cache)
        m = canon.motion
        if len(comps) == 1:
            comps = comps * 3          # no error estimate from one level: the differences are zero
        rec = reference_point(comps, m.translation_m - geom.clearance_m, m.tilt_rad, check)
        if args.level:
            rec["force_error_rel"] = rec["moment_error_rel"] = None
        fy, fz = rotate_about_x(-rec["force_n"], 0.0, canon.frame_angle_rad)
        # moment vector (M_y, M_z) = (0, M_z) in the canonical frame, rotated with the frame
        my, mz = rotate_about_x(0.0, rec["moment_nm"], canon.frame_angle_rad)
        rec.update({"scene": label, "boundary_conditions": bc, "tilt_axis": args.tilt_axis, "force_y_n": fy, "force_z_n": fz, "moment_y_nm": my,
                    "moment_z_nm": mz})
    except RingContactError as exc:
        return fail("ringcontact fem3d point", exc)
    if args.json:
        print(json.dumps(unit_keys(_jsonable(rec)), indent=1))
    else:
        print(_fmt_point(rec))
    return 0


def sweep_main(argv: list[str]) -> int:
    """``fem3d sweep``: regenerate the 3D dataset through a process pool or a dask cluster (resumable)."""
    from fem_reference.solid.sweep import regenerate
    from sweep.cluster import connect

    ap = Parser(prog="ringcontact fem3d sweep", description="regenerate the 3D FEM reference dataset")
    ap.add_argument("--out", type=out_file, default=DATASET_OUT,
                    help=f"output JSON (default {DATASET_OUT}: the committed copy when run from the repository root)")
    ap.add_argument("--workers", type=count(1, 64, "processes"), default=2, help="processes (1-64)")
    ap.add_argument("--fresh", action="store_true", help="ignore finished points kept from an interrupted run")
    ap.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="run on the dask.distributed cluster at ADDRESS (the dask extra; workers must see the "
                         "same $RINGCONTACT_CACHE)")
    ap.add_argument("--scene", default="clamped",
                    help=SCENE_HELP + "; a ring-pair file brings its own penetrations and tilts")
    args = ap.parse_args(argv)
    try:
        geom, bc, label, rs = scene_3d(args.scene)
        kw = {}
        if rs is not None:
            if not rs.needs_3d:
                raise RingContactError(f"--scene = {args.scene}: its [range] tilt_arcmin is [0, 0] (no 3D work asked)")
            kw = {"tilts_rad": list(rs.tilts_rad), "penetrations_m": list(rs.penetrations_3d_m), "label": label,
                  "description": rs.scene.description}
        with connect(args.scheduler) as client:
            path = regenerate(args.out, workers=args.workers, executor=client, resume=not args.fresh,
                              scene=bc, geom=geom, **kw)
    except RingContactError as exc:
        return fail("ringcontact fem3d sweep", exc)
    print(f"wrote {path}")
    return 0


def check_main(argv: list[str]) -> int:
    """``fem3d check``: recompute a few committed points and report the differences."""
    from contact.dataset import read_dataset
    from fem_reference.solid.sweep import DATASET_PATH, check_against_committed

    ap = Parser(prog="ringcontact fem3d check", description="recompute committed 3D points, compare")
    ap.add_argument("--path", type=in_file, default=DATASET_PATH, help="3D dataset (default: the packaged one)")
    ap.add_argument("--points", type=count(1, 50, "points"), default=3, help="points to recompute (1-50)")
    ap.add_argument("--cached", action="store_true", help="reuse cached mesh levels instead of rebuilding them")
    ap.add_argument("--tol", type=quantity("tol"), default=1e-6, help="relative difference that counts as a change")
    args = ap.parse_args(argv)
    try:
        read_dataset(args.path, kind="3d")
        rows = check_against_committed(args.path, args.points, use_cache=args.cached)
    except RingContactError as exc:
        return fail("ringcontact fem3d check", exc)
    worst = 0.0
    print(f"{'Δr mm':>8}{'tilt′':>7}{'committed kN':>14}{'new kN':>14}{'diff':>10}"
          f"{'committed kN*m':>16}{'new kN*m':>12}{'diff':>10}{'est.err':>9}")
    for r in rows:
        worst = max(worst, abs(r["force_diff_rel"]), abs(r["moment_diff_rel"]))
        print(f"{r['penetration_m'] / MM:>8.4f}{r['tilt_rad'] / ARCMIN:>7.2f}{r['committed_force_n'] / 1e3:>14.3f}"
              f"{r['new_force_n'] / 1e3:>14.3f}{r['force_diff_rel']:>10.1e}{r['committed_moment_nm'] / 1e3:>16.4f}"
              f"{r['new_moment_nm'] / 1e3:>12.4f}{r['moment_diff_rel']:>10.1e}{r['force_error_estimate_rel']:>9.1e}")
    print(f"largest difference {worst:.2e} ({'OK' if worst <= args.tol else 'CHANGED'} at tol {args.tol:g})")
    return 0 if worst <= args.tol else 1


def report_main(argv: list[str]) -> int:
    """``fem3d report``: tables and figures of the committed 3D dataset into reports/published/ (:mod:`reports.fem3d`)."""
    from pathlib import Path

    from contact.dataset import read_dataset
    from fem_reference.solid.sweep import DATASET_PATH
    from reports.fem3d import write_report

    ap = Parser(prog="ringcontact fem3d report", description="report of the committed 3D dataset")
    ap.add_argument("--path", type=in_file, default=DATASET_PATH, help="3D dataset (default: the packaged one)")
    ap.add_argument("--out", "--out-dir", dest="out", type=out_dir, default=PUBLISHED,
                    help=f"output directory (default {PUBLISHED})")
    args = ap.parse_args(argv)
    try:
        ds = read_dataset(args.path, kind="3d")
        md = write_report(ds, args.path.name, Path(args.out))
    except RingContactError as exc:
        return fail("ringcontact fem3d report", exc)
    print(f"wrote {md} (+ .csv, .png, .svg)")
    return 0


def vtu_main(argv: list[str]) -> int:
    """``fem3d vtu``: solve one point on one mesh level and write the bore's pressure map as VTU."""
    ap = Parser(prog="ringcontact fem3d vtu",
                description="contact pressure and rigid gap on the support bore (half ring) as VTU")
    ap.add_argument("penetration_mm", type=quantity("penetration_mm"), help="mid-plane penetration Δr = r − δ0 [mm]")
    ap.add_argument("--tilt-arcmin", type=_tilt_arcmin(), default=0.0, help="tilt about z [arcmin]")
    ap.add_argument("--scene", default="clamped", help=SCENE_HELP)
    ap.add_argument("--level", default="Q2", choices=_levels(), help="mesh level (default Q2, the finest reference level)")
    ap.add_argument("--out", type=out_file, required=True, help="output .vtu file")
    ap.add_argument("--no-cache", action="store_true", help="do not read or write cached mesh levels")
    args = ap.parse_args(argv)
    from contact.units import check_finite
    from fem_reference.solid.export import write_pressure_vtu
    from fem_reference.solid.geometry import RigidMotion, rigid_gap_m
    from fem_reference.solid.mesh import LEVELS
    from fem_reference.solid.solve import solve_point
    from fem_reference.solid.sweep import get_compliance

    try:
        check_finite("penetration_mm", args.penetration_mm, "mm")
        check_finite("tilt_arcmin", args.tilt_arcmin, "arcmin")
        if args.level not in LEVELS:
            raise RingContactError(f"level = {args.level!r}: must be one of {sorted(LEVELS)}")
        geom, bc, _, _ = scene_3d(args.scene)
        check_penetration_3d(geom, args.penetration_mm)
        comp = get_compliance(geom, LEVELS[args.level], bc, use_cache=not args.no_cache)
        motion = RigidMotion.from_penetration(geom, args.penetration_mm * MM, args.tilt_arcmin * ARCMIN)
        res = solve_point(comp, motion)
        gap = rigid_gap_m(geom, motion, comp.lam_phi, comp.lam_x)
        path = write_pressure_vtu(args.out, res, geom, gap)
    except RingContactError as exc:
        return fail("ringcontact fem3d vtu", exc)
    print(f"wrote {path} ({res.force_n / 1e3:.3f} kN, peak {res.peak_pressure_pa / 1e6:.1f} MPa, "
          f"width {res.contact_width_m / MM:.2f} mm, level {args.level})")
    return 0


SUBCOMMANDS = {"point": point_main, "sweep": sweep_main, "check": check_main, "report": report_main,
               "vtu": vtu_main}


def main(argv: list[str] | None = None) -> int:
    """``ringcontact fem3d {point,sweep,check} ...``"""
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] in {"-h", "--help"}:
        print(__doc__.strip())
        return 0
    if argv[0] not in SUBCOMMANDS:
        print(f"ringcontact fem3d: error: sub-command = {argv[0]!r}: must be one of {', '.join(SUBCOMMANDS)}",
              file=sys.stderr)
        return 2
    return int(SUBCOMMANDS[argv[0]](argv[1:]) or 0)


if __name__ == "__main__":
    sys.exit(main())
