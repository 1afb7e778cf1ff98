"""``ringcontact study``: the paper's Section 5/6 studies and what goes past them.

Sub-studies (each resumable: points already in ``--out`` are reused, corrupt ones recomputed)::

    ringcontact study cascade  --out runs/fig12                      # Fig. 12: 61 speeds 0–18 000 rpm
    ringcontact study cascade  --tilt-ignored --out runs/fig16       # Fig. 16
    ringcontact study point    --speed-rpm 10500 --out runs/pointB   # Figs. 13–15 at one speed
    ringcontact study params   --out runs/fig18-19                   # Figs. 18–19: clearances, misalignments
    ringcontact study testrig  --out runs/testrig                    # Table 5 rig, Figs. 27–28 trends
    ringcontact study runup    --out runs/runup                      # run-up with time–frequency cascade
    ringcontact study map      --out runs/map                        # stick/slip/impact over (speed, clearance)
    ringcontact study publish  --cascade runs/fig12 --notilt runs/fig16 …   # study-* into reports/published
    ringcontact study export   runs/fig12 --format netcdf|csv          # speed x station x harmonic dataset
    ringcontact study sensitivity --out runs/sensitivity             # §5 findings vs the unstated inputs (slow)
    ringcontact study readings --out runs/readings                   # points A, B under every reading of Eq. 34
    ringcontact study redraw   [--from reports/published]            # study figures from the committed CSVs

Engineer units at the edge (``_rpm``, ``_mm``); results in SI (see sweep.store for the file
layout). Figures (PNG + SVG) go to ``--figures`` (default: ``<out>/figures``).
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

# one BLAS thread per process (before numpy loads; the sweep's workers inherit it): the matrices
# are a few dozen wide and threaded BLAS on 2 shared cores only adds contention
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from contact import plausible
from contact.errors import InputError, RingContactError
from contact.package_data import shipped
from contact.units import check_positive
from reports.cli import _budget
from reports.cli._edge import PUBLISHED, Parser, count, fail, in_dir, out_dir, out_file, quantity
from reports.cli._study_sweep import compile_first as _compile_first, mesh as _mesh, overrides as _ov
from reports.cli._study_sweep import run_study_sweep
from reports.cli._scene_options import (DEFAULT_SCENE, add_law_check_option, add_scene_options, finish, max_revs,
                                        refuse_overrides, scene_top_rpm)


def _common(p: argparse.ArgumentParser, out: str, scene: str = DEFAULT_SCENE):
    add_scene_options(p, default=scene, transient=True)
    add_law_check_option(p)
    p.add_argument("--out", type=out_dir, default=out, help=f"result directory (default {out})")
    p.add_argument("--figures", type=out_dir, default=None, help="figure directory (default <out>/figures)")
    p.add_argument("--workers", type=count(1, 64, "processes"), default=2, help="worker processes (default 2)")
    _scheduler(p)
    p.add_argument("--steps-per-rev", type=count(16, 100000), default=256,
                   help="minimum time steps per revolution (default 256, more where the contact step limit needs it)")
    p.add_argument("--elements", type=count(1, 64), default=None,
                   help="shaft elements per segment (default: the scene's mesh; paper-table4 has the paper's 1)")
    p.add_argument("--no-progress", action="store_true", help="no progress line")
    _budget.add_accept_long(p)


def _scheduler(p: argparse.ArgumentParser) -> None:
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run on the dask.distributed cluster at ADDRESS (e.g. tcp://10.0.0.5:8786; the dask "
                        "extra) instead of --workers local processes")


def _method(p: argparse.ArgumentParser) -> None:
    p.add_argument("--method", choices=("transient", "shooting"), default="transient",
                   help="transient (default: integrate to the detected steady state) or shooting (the periodic "
                        "orbit by Newton on the period map, with its Floquet multipliers and stability; a point "
                        "where shooting fails falls back to the transient, rotor.studies.shooting_point; speeds in contiguous "
                        "blocks, each from its lower neighbour's orbit, rotor.studies.shooting_block)")


def _tasks(args):
    """The sweep-task builder of ``--method``."""
    if args.method == "shooting":
        from rotor.studies.shooting_block import shooting_block_tasks
        return shooting_block_tasks
    from rotor.studies.steady_state import sweep_tasks
    return sweep_tasks


def _method_note(args) -> dict:
    """The method in a study's description, only when not the default (transient studies stay as they were)."""
    return {"method": args.method} if args.method != "transient" else {}


#: ``--rpm-max``'s help: its default is the scene's
SCENE_RPM_MAX = ("highest speed (rpm; default: the scene's [analysis] max_speed_rpm, its modelled speed range: 18 000 "
                 "for paper-table4, 2 000 where a scene gives none)")


def _parser() -> argparse.ArgumentParser:
    from rotor.studies.runup import SHORTEST_DURATION_S
    p = Parser(prog="ringcontact study", description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="study", required=True)
    c = sub.add_parser("cascade", help="steady-state spectrum cascade over speed (Figs. 12, 16, 17)")
    _common(c, "runs/cascade")
    c.add_argument("--rpm-max", type=quantity("rpm_max"), default=None, help=SCENE_RPM_MAX)
    c.add_argument("--rpm-min", type=quantity("speed_rpm"), default=0.0, help="lowest speed (rpm, default 0)")
    c.add_argument("--points", type=count(1, 2000), default=61, help="number of speeds (default 61)")
    _method(c)
    pt = sub.add_parser("point", help="orbits, deflection, time histories, spectra, r1/r2 at one speed (Figs. 13-15)")
    _common(pt, "runs/point")
    pt.add_argument("--speed-rpm", type=quantity("run_speed_rpm"), action="append", help="speed (rpm), repeatable (default 4500 and 10500)")
    rg = sub.add_parser("readings", help="points B and A under every reading of Eq. 34 (rotor.studies.readings) on the "
                                         "scene's mesh and --elements (default 2): section5-readings.md/.csv")
    _common(rg, "runs/readings")
    rg.add_argument("--to", type=out_dir, default=PUBLISHED, help=f"where section5-readings.* go (default {PUBLISHED})")
    pr = sub.add_parser("params", help="1X/2X/3X vs speed for several clearances and misalignments (Figs. 18-19)")
    _common(pr, "runs/params")
    pr.add_argument("--rpm-max", type=quantity("rpm_max"), default=None, help=SCENE_RPM_MAX)
    pr.add_argument("--points", type=count(1, 2000), default=31, help="speeds per curve (default 31)")
    pr.add_argument("--clearances-mm", default="0.03,0.08", help="comma list besides the scene's (mm)")
    pr.add_argument("--misalignments-mm", default="0.5,2", help="comma list besides the scene's (mm)")
    _method(pr)
    tr = sub.add_parser("testrig", help="Table 5 test rig at 3600/5500 rpm, clearance 0.01/0.05 mm, misalignment 1/2/3 mm, "
                                        "and whether its loose support can slip (stick-margin scan)")
    _common(tr, "runs/testrig", scene="paper-table5-testrig")
    ru = sub.add_parser("runup", help="run-up/run-down with time-varying speed and a time-frequency cascade")
    _common(ru, "runs/runup")
    ru.add_argument("--rpm-start", type=quantity("run_speed_rpm"), default=600.0)
    ru.add_argument("--rpm-end", type=quantity("run_speed_rpm"), default=18000.0)
    ru.add_argument("--duration-s", type=quantity("duration_s", low=SHORTEST_DURATION_S,
                                                  why="two windows of the time-frequency cascade"), default=20.0)
    ru.add_argument("--down", action="store_true", help="run down: from the higher of the two speeds to the lower")
    mp = sub.add_parser("map", help="where the support sticks, slips and impacts over (speed, clearance)")
    _common(mp, "runs/map")
    mp.add_argument("--rpm-max", type=quantity("rpm_max"), default=None, help=SCENE_RPM_MAX)
    mp.add_argument("--points", type=count(1, 2000), default=13, help="speeds (default 13)")
    mp.add_argument("--clearances-mm", default="0.01,0.02,0.05,0.1,0.2", help="comma list (mm)")
    se = sub.add_parser("sensitivity", help="do the paper's Section 5 findings hold for plausible values of the "
                                            "inputs Table 4 does not give? (slow: 16 min with 1 worker on the "
                                            "shared 2-core machine, 16 CPU-minutes)")
    se.add_argument("--scene", default="paper-table4", help="scene name or TOML path (default paper-table4)")
    se.add_argument("--out", type=out_dir, default="runs/sensitivity", help="result directory (default runs/sensitivity)")
    se.add_argument("--workers", type=count(1, 64, "processes"), default=2, help="worker processes (default 2)")
    _scheduler(se)
    se.add_argument("--variants", default=None, help="comma list of variant names (default: the study's, "
                                                     "rotor.studies.sensitivity.study_variants; the former study's "
                                                     "one-at-a-time and combinations by name)")
    se.add_argument("--report-only", action="store_true", help="no computing: report what is in --out")
    se.add_argument("--report-out", "--to", dest="to", type=out_dir, default=PUBLISHED,
                    help=f"where study-sensitivity.{{md,csv,png,svg}} go (default {PUBLISHED})")
    se.add_argument("--no-progress", action="store_true", help="no progress line")
    ex = sub.add_parser("export", help="a study directory (or a FEM reference dataset .json) as one labelled "
                                       "dataset: netCDF or CSV (the xarray extra)")
    ex.add_argument("run", help="result directory of a study, or a FEM dataset such as "
                                "fem_reference/data/fem2d-reference.json")
    ex.add_argument("--format", choices=("netcdf", "csv"), default="netcdf", help="file format (default netcdf)")
    ex.add_argument("--out", type=out_file, default=None, help="output file (default <run>/study.nc|csv, or <dataset name>.nc|csv "
                                                "in the current directory)")
    pb = sub.add_parser("publish", help="figures + notes of finished study directories into reports/published (study-*)")
    for k in ("cascade", "notilt", "params", "point", "testrig", "map", "runup"):
        pb.add_argument(f"--{k}", type=in_dir, default=None, help=f"directory of a finished '{k}' study")
    for k in ("cascade", "notilt", "params", "point"):
        pb.add_argument(f"--{k}-converged", type=in_dir, default=None,
                        help=f"the '{k}' study on the converged mesh (with --elements): study-findings.md")
    pb.add_argument("--elements", type=count(1, 64), default=2, help="elements per segment of the converged-mesh studies")
    pb.add_argument("--out", "--to", dest="to", type=out_dir, default=PUBLISHED, help=f"output directory (default {PUBLISHED})")
    rd = sub.add_parser("redraw", help="the study figures again from the committed CSV tables (no study rerun): "
                                       "study-sensitivity, study-params-*, study-cascade*")
    rd.add_argument("--from", dest="src", type=in_dir, default=PUBLISHED,
                    help=f"folder of the study-*.csv tables (default {PUBLISHED})")
    rd.add_argument("--out", "--to", dest="to", type=out_dir, default=None, help="output directory (default: --from)")
    return p


def main(argv: list[str] | None = None) -> int:
    p = _parser()
    args = p.parse_args(argv)
    args = finish(p, args, sub=args.study)
    try:
        return _run(args)
    except RingContactError as e:
        return fail(f"ringcontact study {args.study}", e)


def _floats(text: str, name: str, unit: str) -> list[float]:
    from contact import plausible
    flag = "--" + name.replace("_", "-")
    try:
        vals = [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise InputError(f"{flag} = {text} {unit}: expected a comma-separated list of numbers") from None
    if not vals:
        raise InputError(f"{flag} = {text} {unit}: expected at least one number")
    single = {"clearances_mm": "clearance_mm", "misalignments_mm": "misalignment_mm"}[name]
    for v, typed in zip(vals, [x.strip() for x in text.split(",") if x.strip()]):
        plausible.check(single, v, typed, label=flag)
        check_positive(name, v, unit)
    return vals


def _options(args) -> dict:
    check_positive("steps_per_rev", args.steps_per_rev, "steps", upper=1e5)
    check_positive("max_revs", max_revs(args), "rev", upper=1e6)
    return {"steps_per_rev": int(args.steps_per_rev), "max_revs": max_revs(args)}


def _run(args) -> int:
    if args.study == "publish":
        return _publish(args)
    if args.study == "redraw":
        from reports.studies.redraw import redraw
        for f in redraw(args.src, args.to if args.to is not None else args.src):
            print(f"  wrote {f}")
        return 0
    if args.study == "export":
        return _export(args)
    if args.study == "sensitivity":
        return _sensitivity(args)
    from rotor.studies.steady_state import _scene_model
    from sweep.store import ResultStore
    ResultStore(args.out).check_layout()   # a damaged or foreign run directory: refused by name, first
    scene, _ = _scene_model(args.scene, None, _ov(args).get("law"))  # a bad scene or law: refused here, not per point
    if hasattr(args, "rpm_max") and args.rpm_max is None:       # the scene's own speed range (18 000 rpm: Table 4)
        args.rpm_max = scene_top_rpm(scene)
    _paper_stations(args, scene)
    _law_clearances(args, scene)
    _warn_unstable(args, scene)
    out = Path(args.out)
    figs = Path(args.figures) if args.figures else out / "figures"
    opts = _options(args)
    study = _STUDIES.get(args.study)
    if study is None:  # pragma: no cover - argparse guards this
        return 2
    for f in study(args, out, figs, opts):
        print(f"  wrote {f}")
    return 0


def _warn_unstable(args, scene) -> None:
    """One warning line when the rotor's linearisation (loose support locked, then open) has a mode of negative
    damping at the study's speeds (its ends and middle: :func:`rotor.linear.stability.linearisation_unstable`):
    its points' answers are then the growth of an unstable rotor, not the contact law's doing (issue 40)."""
    from rotor.linear.stability import linearisation_unstable, warning
    from rotor.model.assembly import assemble
    speeds = [v for k in ("rpm_min", "rpm_max", "rpm_start", "rpm_end") if (v := getattr(args, k, None)) is not None]
    speeds += list(getattr(args, "speed_rpm", None) or [])
    if not speeds:
        return
    lo, hi = min(speeds), max(speeds)
    model = assemble(scene, elements_per_segment=getattr(args, "elements", None))
    for rpm in sorted({lo, 0.5 * (lo + hi), hi}):
        found = linearisation_unstable(model, rpm * 3.141592653589793 / 30.0)
        if found is not None:
            print(warning(f"ringcontact study {args.study}", found, "its points grow with the rotor's instability, "
                                                                    "not by the contact law"), file=sys.stderr)
            return


def _paper_stations(args, scene) -> None:
    """The figures of point, params, testrig and runup are the paper's: disk 1, disk 2 and the support s
    (reports/studies/common.py: LOCATIONS); a scene without those stations is refused before any point
    (``study cascade`` draws any scene's stations)."""
    from reports.studies.common import LOCATIONS
    from rotor.model.assembly import assemble
    if args.study not in ("point", "params", "testrig", "runup"):
        return
    have = assemble(scene, elements_per_segment=getattr(args, "elements", None)).response_stations()
    need = [ch.split(".")[0] for ch, _ in LOCATIONS]
    if not set(need) <= set(have):
        raise InputError(f"--scene = {args.scene}: study {args.study} draws the paper's stations {', '.join(need)}; "
                         f"the scene has {', '.join(have)}: use study cascade (any stations), simulate --steady or "
                         "orbit for this scene")


def _law_clearances(args, scene) -> None:
    """Refuse, before any point, a clearance other than a calibrated law's own (the law holds for its geometry)."""
    ls = scene.loose_support
    if ls is None or ls.calibrated is None:
        return
    own_mm = ls.clearance_m * 1e3
    wanted = {"params": ("--clearances-mm", getattr(args, "clearances_mm", None)),
              "map": ("--clearances-mm", getattr(args, "clearances_mm", None)),
              "testrig": ("the test rig's clearances", "0.01,0.05"),
              "cascade": ("--clearance-mm", None if getattr(args, "clearance_mm", None) is None
                          else str(args.clearance_mm))}.get(args.study)
    if wanted is None or wanted[1] is None:
        return
    for text in wanted[1].split(","):
        try:
            value = float(text)
        except ValueError:
            continue                # a malformed list is refused with its own message later
        if abs(value - own_mm) > 1e-6 * own_mm:
            raise InputError(f"{wanted[0]} = {text.strip()} mm: scene {scene.path} names the calibrated law "
                             f"{ls.law}, which holds for clearance_mm = {own_mm:.6g} mm only (use a scene with an "
                             "analytic law to vary the clearance)")


def _export(args) -> int:
    """``study export``: the points of a study (or a FEM dataset) as one netCDF or CSV file."""
    from contact.errors import InputError
    from sweep.export import fem_to_xarray, write

    src = Path(args.run)
    suffix = {"netcdf": ".nc", "csv": ".csv"}[args.format]
    if src.is_dir():
        from rotor.studies.export import to_xarray
        ds = to_xarray(src)
        out = Path(args.out) if args.out else src / f"study{suffix}"
    elif src.is_file():
        ds = fem_to_xarray(src)
        out = Path(args.out) if args.out else Path(src.stem + suffix)
    else:
        raise InputError(f"run = {str(src)!r}: no such study directory or dataset file")
    dims = " x ".join(f"{d} {n}" for d, n in ds.sizes.items())
    print(f"  wrote {write(ds, out, args.format)} ({dims})")
    return 0


def _publish(args) -> int:
    """``study publish``: figures + notes of finished study directories into ``--to``."""
    from reports.studies import publish

    keys = ("cascade", "notilt", "params", "point", "testrig", "map", "runup") + tuple(
        f"{k}_converged" for k in ("cascade", "notilt", "params", "point"))
    runs = {k: getattr(args, k) for k in keys if getattr(args, k)}
    if not runs:
        raise InputError("nothing to publish: give at least one of --cascade, --notilt, --params, --point, "
                         "--testrig, --map, --runup (a finished study directory)")
    for k, d in runs.items():
        _require_finished(f"--{k.replace('_', '-')}", Path(d))
    if any(k.endswith("_converged") for k in runs):
        runs["elements"] = int(args.elements)
    reading = shipped("reports", "notes", "study-findings-reading.md")
    for f in publish(runs, Path(args.to), findings_extra=reading.read_text(encoding="utf-8") if reading.is_file() else ""):
        print(f"  wrote {f}")
    return 0


def _require_finished(flag: str, d: Path) -> None:
    """Refuse a study directory that is not a finished run (nothing is written over the published reports)."""
    from sweep import run_status
    st = run_status(d)
    if not st["complete"]:
        raise InputError(f"{flag} = {d}: not a finished study ({st['why']}); rerun the study to complete it")
    _require_kind(flag, d)


def _require_kind(flag: str, d: Path) -> None:
    """Refuse a finished study of another kind than ``flag`` publishes (a run-up folder given to ``--cascade``
    ended in ``KeyError: 'speed_rpm'``): the study named in its ``sweep.json`` against the one the flag needs."""
    from sweep.store import ResultStore
    need = flag.removeprefix("--").removesuffix("-converged")
    need = "cascade" if need == "notilt" else need
    held = (ResultStore(d).read_manifest(required=False) or {}).get("study")
    if held is not None and held != need:
        raise InputError(f"{flag} = {d}: holds a finished '{held}' study (its sweep.json), and {flag} publishes a "
                         f"'{need}' study; give the folder of a ringcontact study {need} run")


def _distinct(speeds, args):
    """``speeds`` (rpm), refused when two coincide at the 0.1 rpm of the points' keys
    (:func:`rotor.studies.steady_state.sweep_tasks`): they would be one point twice."""
    keys = {f"{float(s):.1f}" for s in speeds}
    if len(keys) < len(speeds):
        lo, hi = float(speeds[0]), float(speeds[-1])
        most = int(round((hi - lo) / 0.1)) + 1
        raise InputError(f"--points = {args.points}: speeds from {lo:g} to {hi:g} rpm, {(hi - lo) / max(len(speeds) - 1, 1):.3g} "
                         f"rpm apart, coincide at the 0.1 rpm the points are stored by; at most {most} point(s) over "
                         "this range, or a wider range")
    return speeds


def _cascade(args, out: Path, figs: Path, opts: dict) -> list[Path]:
    """``study cascade``: steady state at each speed of a range (Figs. 12, 16, 17)."""
    from reports.studies.cascade import cascade_figures
    from rotor.studies.steady_state import _scene_model
    from sweep import point_tasks

    check_positive("rpm_max", args.rpm_max, "rpm", upper=plausible.top("rpm_max"))
    if args.rpm_min > args.rpm_max:
        raise InputError(f"--rpm-min = {args.rpm_min:g} rpm: must be <= --rpm-max = {args.rpm_max:g} rpm")
    speeds = _distinct(np.linspace(args.rpm_min, args.rpm_max, int(args.points)), args)
    kw = {"tilt_ignored": bool(args.tilt_ignored), "options": opts, **_mesh(args), **_ov(args)}
    tasks = _tasks(args)(args.scene, speeds, **kw)
    s, wall = run_study_sweep(tasks, out, args, {"speeds_rpm": speeds.tolist(), **_method_note(args), **kw})
    _timing(out, s, wall, args)
    _, model = _scene_model(args.scene, _mesh(args).get("elements_per_segment"))
    tasks = point_tasks(tasks)          # what is stored: one point per speed (shooting blocks hold several)
    if not {"disk1", "disk2", "s"} <= set(model.response_stations()):  # not the paper's stations: by the scene's names
        from reports.station_cascade import station_cascade
        return station_cascade(out, figs, tasks=tasks)
    return cascade_figures(out, figs, tasks=tasks)


def _point(args, out: Path, figs: Path, opts: dict) -> list[Path]:
    """``study point``: orbits, deflection, time histories, spectra at one or more speeds (Figs. 13-15)."""
    from reports.studies.point import point_figures
    from rotor.studies.steady_state import sweep_tasks

    speeds = args.speed_rpm or [4500.0, 10500.0]
    tasks = sweep_tasks(args.scene, speeds, options=opts, history_revs=8, **_mesh(args), **_ov(args))
    run_study_sweep(tasks, out, args, {"speeds_rpm": speeds})
    return point_figures(out, figs, tasks=tasks)


def _params(args, out: Path, figs: Path, opts: dict) -> list[Path]:
    """``study params``: 1X/2X/3X vs speed for several clearances and misalignments (Figs. 18-19)."""
    from reports.studies.params import params_figures
    from sweep import point_tasks

    sweep_tasks = _tasks(args)
    speeds = _distinct(np.linspace(0.0, args.rpm_max, int(args.points)), args)
    # the scene's own clearance/misalignment is one shared 'base' curve of both figures
    # (--clearance-mm / --misalignment-mm: the base values, held by the curves that vary the other one)
    mesh = {**_mesh(args), **_ov(args)}
    tasks = sweep_tasks(args.scene, speeds, prefix="base-rpm", options=opts, **mesh)
    for c in _floats(args.clearances_mm, "clearances_mm", "mm"):
        tasks += sweep_tasks(args.scene, speeds, prefix=f"c{c:g}mm-rpm", options=opts,
                             **{**mesh, "clearance_m": c * 1e-3})
    for d in _floats(args.misalignments_mm, "misalignments_mm", "mm"):
        tasks += sweep_tasks(args.scene, speeds, prefix=f"d{d:g}mm-rpm", options=opts,
                             **{**mesh, "misalignment_m": d * 1e-3})
    run_study_sweep(tasks, out, args, {"speeds_rpm": speeds.tolist(), "clearances_mm": args.clearances_mm,
                              "misalignments_mm": args.misalignments_mm, **_method_note(args)})
    return params_figures(out, figs, tasks=point_tasks(tasks))


def _testrig(args, out: Path, figs: Path, opts: dict) -> list[Path]:
    """``study testrig``: the Table 5 rig at 3600/5500 rpm (δ0 0.05/0.01 mm at δ 2 mm, δ 1/3 mm at δ0 0.05 mm), the
    stick-margin scan over the paper's rig data, and the fitted rig (case C) where the scan says its faces slip."""
    from reports.studies.testrig import testrig_figures, write_scan
    from rotor.studies.section6 import STEPS_RPM
    from rotor.studies.steady_state import sweep_tasks
    from rotor.studies.testrig_scan import SCENE, scan, slip_check_speed, write_variant_scene

    refuse_overrides(args, ("--clearance-mm", "--misalignment-mm"), "study testrig runs the rig's own clearances "
                     "(0.01, 0.05 mm) and misalignments (1, 2, 3 mm); the other scene overrides apply")
    ov, tasks = _ov(args), []
    for rpm in STEPS_RPM:
        for c, d in ((0.05, 2.0), (0.01, 2.0), (0.05, 1.0), (0.05, 3.0)):
            tasks += sweep_tasks(args.scene, [rpm], prefix=f"c{c:g}mm-d{d:g}mm-rpm", clearance_m=c * 1e-3,
                                 misalignment_m=d * 1e-3, options=opts, history_revs=8, **ov)
    about = {"speeds_rpm": list(STEPS_RPM), "clearances_mm": [0.01, 0.05], "misalignments_mm": [1, 2, 3]}
    run_study_sweep(tasks, out, args, about)          # the scene's points first: a bad --out is refused before the scan
    if args.scene == SCENE:       # the scan and the fitted rig are readings of the Table 5 scene only
        points = scan(mu=ov.get("mu"), preload_n=ov.get("preload_n"))
        write_scan(points, out)
        fitted, rpm_c = write_variant_scene(out), slip_check_speed(points)
        for c in (0.01, 0.05):
            tasks += sweep_tasks(str(fitted), [rpm_c], prefix=f"C-c{c:g}mm-d2mm-rpm", clearance_m=c * 1e-3,
                                 misalignment_m=2e-3, options=opts, history_revs=8, **ov)
        run_study_sweep(tasks, out, args, {**about, "fitted_rig_rpm": rpm_c})
    return testrig_figures(out, figs, tasks=tasks)


def _map(args, out: Path, figs: Path, opts: dict) -> list[Path]:
    """``study map``: stick/slip/impact regime over (speed, clearance)."""
    from reports.studies.regime_map import map_figures
    from rotor.studies.steady_state import sweep_tasks

    refuse_overrides(args, ("--clearance-mm",), "study map sweeps the clearance itself (--clearances-mm)")
    speeds = _distinct(np.linspace(args.rpm_max / args.points, args.rpm_max, int(args.points)), args)
    tasks = []
    for c in _floats(args.clearances_mm, "clearances_mm", "mm"):
        tasks += sweep_tasks(args.scene, speeds, prefix=f"c{c:g}mm-rpm", clearance_m=c * 1e-3, options=opts,
                             **_ov(args))
    run_study_sweep(tasks, out, args, {"speeds_rpm": speeds.tolist(), "clearances_mm": args.clearances_mm})
    return map_figures(out, figs, tasks=tasks)


def _runup(args, out: Path, figs: Path, opts: dict) -> list[Path]:
    """``study runup``: run-up (or run-down with --down) with a time-frequency cascade."""
    from reports.studies.runup import runup_figures
    from rotor.studies.runup import RunupSpec, run_runup

    a, b = args.rpm_start, args.rpm_end
    if a == b:
        raise InputError(f"--rpm-end = {b:g} rpm: must differ from --rpm-start (one speed: 'study point' or 'simulate')")
    if args.down and a < b:
        a, b = b, a
    spec = RunupSpec(scene=args.scene, rpm_start=a, rpm_end=b, duration_s=args.duration_s,
                     steps_per_rev=int(args.steps_per_rev), **_ov(args))
    from sweep.cluster import connect

    _budget.check("ringcontact study runup", _budget.runup(spec), args.accept_long,
                  f"--duration-s = {args.duration_s:g} s from {a:g} to {b:g} rpm", "a shorter --duration-s")
    _compile_first(args)
    with connect(args.scheduler) as client:
        info = run_runup(spec, out, executor=client)
    print(f"study runup: {info['steps']} steps in {info['wall_s']:.1f} s wall")
    return runup_figures(out, figs)


def _readings(args, out: Path, figs: Path, opts: dict) -> list[Path]:
    """``study readings``: points B and A under every reading of Eq. 34 on two meshes, judged by the paper's text."""
    from reports.studies.readings import LOW_RPM, POINT_A_RPM, POINT_B_RPM, publish_readings
    from rotor.studies.readings import COMPARED_NAMES, reading_tasks

    mesh = int(args.elements or 2)
    args.elements = None                  # _sweep's manifest: the scene's mesh; each task names its own
    tasks = reading_tasks(args.scene, COMPARED_NAMES, [POINT_B_RPM, POINT_A_RPM], (None, mesh), options=opts)
    low = reading_tasks(args.scene, COMPARED_NAMES, LOW_RPM, (None, mesh), options=opts, history_revs=1, prefix="low-")
    run_study_sweep(tasks + low, out, args, {"speeds_rpm": [POINT_B_RPM, POINT_A_RPM], "low_speeds_rpm": list(LOW_RPM),
                                    "readings": list(COMPARED_NAMES), "elements_per_segment": [None, mesh]})
    reading = shipped("reports", "notes", "section5-readings-reading.md")
    return publish_readings(out, Path(args.to), scene=args.scene, tasks=tasks, low_tasks=low,
                            extra=reading.read_text(encoding="utf-8") if reading.is_file() else "")


# sub-study -> function(args, out, figs, options) -> files written (publish and sensitivity have their own)
_STUDIES = {"cascade": _cascade, "point": _point, "params": _params, "testrig": _testrig, "map": _map,
            "runup": _runup, "readings": _readings}


def _sensitivity(args) -> int:
    """Run (resumably) and report the sensitivity study of :mod:`rotor.studies.sensitivity`."""
    from contact.errors import InputError
    from reports import sensitivity as rep
    from rotor.studies import sensitivity as sens
    from sweep import code_revision, run_sweep
    from sweep.cluster import connect

    variants = sens.study_variants()
    if args.variants:
        want = [w.strip() for w in args.variants.split(",") if w.strip()]
        known = {v.name: v for v in sens.all_variants()}
        bad = [w for w in want if w not in known]
        if bad:
            raise InputError(f"variants: unknown {bad}; known: {', '.join(known)}")
        variants = [known[w] for w in want]
    out = Path(args.out)
    if args.report_only:      # no computing: what is stored is reported
        if not any((out / "points").glob("*.json")):
            raise InputError(f"--out = {out}: no stored points to report (run the study without --report-only first)")
    else:
        tasks = sens.study_tasks(variants, scene=args.scene)
        t0 = time.perf_counter()
        with connect(args.scheduler) as client:
            s = run_sweep(tasks, out, executor=client, max_workers=args.workers,
                          progress=False if args.no_progress else None,
                          manifest={"study": "sensitivity", "variants": {v.name: v.factors for v in variants},
                                    "speeds_rpm": list(sens.SPEEDS_RPM)})
        wall = time.perf_counter() - t0
        print(f"study sensitivity: {len(tasks)} tasks, {len(s.computed)} computed, {len(s.reused)} reused, "
              f"{len(s.failed)} failed, wall {wall:.1f} s")
        _timing(out, s, wall, args)
    # the hand-written reading of the published numbers lives in reports/notes/ and is appended, so the
    # published file stays regenerable by this command alone
    reading = shipped("reports", "notes", "study-sensitivity-reading.md")
    files = rep.publish(out, Path(args.to), variants, scene=args.scene,
                        timing=rep.timing_text(out, {t.key for t in sens.study_tasks(variants, scene=args.scene)}),
                        code=_points_code(out, code_revision()),
                        extra=reading.read_text(encoding="utf-8") if reading.is_file() else "")
    for f in files:
        print(f"  wrote {f}")
    return 0


def _points_code(out: Path, current: dict) -> str:
    """Which code computed the points in ``out`` (its sweep.json), else the current revision."""
    try:
        info = json.loads((out / "sweep.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        info = {}
    commit = info.get("git_commit") or info.get("code_snapshot")
    if not commit or commit == "unknown":
        commit = info.get("code_snapshot") or current.get("git_commit", "unknown")
    dirty = info.get("git_dirty", current.get("git_dirty", False))
    return f"points computed at commit {str(commit)[:12]}{' (with uncommitted changes)' if dirty else ''}"


def _timing(out: Path, s, wall: float, args) -> None:
    """Append the wall time of this sweep run (points computed, per-point times) to ``timing.json``
    (a damaged one is set aside with a message, see :func:`sweep.append_timing`)."""
    from sweep import append_timing

    pw = sorted(s.point_wall_s.values())
    append_timing(out, {"workers": args.workers, "scheduler": getattr(args, "scheduler", None),
                        "computed": len(s.computed), "reused": len(s.reused),
                        "wall_s": round(wall, 2), "point_wall_s_median": round(float(np.median(pw)), 3) if pw else None,
                        "point_wall_s_sum": round(float(sum(pw)), 2), "load_avg_end": os.getloadavg(),
                        "finished_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())},
                  say=lambda m: print(m, file=sys.stderr))

if __name__ == "__main__":
    sys.exit(main())
