"""``ringcontact rotor``: linear analyses of a rotor scene from the command line.

Sub-commands (each takes a scene file path or a bundled scene name)::

    ringcontact rotor scenes                                   # list bundled scenes
    ringcontact rotor modes SCENE [--speed-rpm 0] [--modes 8] [--plot PREFIX] [--json]   # PREFIX-modeshapes.png/.svg
    ringcontact rotor campbell SCENE [--max-rpm R] [--points N] [--damped] [--plot PREFIX] [--json]   # PREFIX-campbell.png/.svg
    ringcontact rotor response SCENE --speed-rpm N [--revolutions R] [--method harmonic|newmark] --out DIR [--json]
    ringcontact rotor critical-speeds SCENE [--max-rpm R] [--orders 1 2] [--json]
    ringcontact rotor unbalance SCENE [--max-rpm R] [--points N] [--nodes disk1 disk2] [--plot PREFIX] [--json]
        # PREFIX-unbalance.png/.svg (--order 2: PREFIX-misalignment.png/.svg)
    ringcontact rotor report [--out reports/published]        # regenerate reports/published/rotor-*

Frequencies are printed in Hz, speeds in rpm, amplitudes in µm; ``--json`` prints the same
numbers as JSON (keys carry the unit). ``--elements N`` overrides the elements per shaft.
The loose support is locked (bearing and support move together) unless ``--open-support``.
Errors (bad scene file, bad option) print one line and exit with status 2.
"""
from __future__ import annotations

import argparse
import json
import math
import sys

import numpy as np

from contact.errors import InputError, RingContactError
from reports.cli import _budget
from reports.cli._edge import COUNTS, PUBLISHED, Parser, count, fail, out_dir, out_prefix, quantity
from reports.cli._scene_options import add_scene_options, finish, linear_scene

RPM = 30 / math.pi


def _load(args, misalignment: bool = False, modal: bool = True):
    """Scene (with ``--misalignment-mm`` where ``misalignment``; the other loose-support overrides refused:
    :func:`reports.cli._scene_options.linear_scene`) and its assembled model; ``modal``: a scene without any
    mass is refused (:func:`_require_mass`)."""
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene
    scene = linear_scene(args, load_scene(args.scene), misalignment=misalignment)
    model = assemble(scene, elements_per_segment=args.elements)
    if modal:
        _require_mass(scene, model)
    return scene, model


def _require_mass(scene, model) -> None:
    """A modal job on a scene with no mass at all (every density and disk mass 0) is refused: it has no
    vibration modes, and an empty table or a Campbell diagram of nulls would say nothing."""
    if not np.any(model.M):
        raise InputError(f"scene {scene.name!r}: no mass anywhere (every material density and disk mass is 0), so "
                         "no vibration modes; give the shaft a density_kg_m3 or a disk a mass_kg")


def _warn_free(model, args) -> None:
    """Modal jobs allow a rotor free to move as a rigid body (a free-free beam is a legitimate test
    piece) but say so on stderr: its 0 Hz rigid-body modes are left out (rotor.model.topology)."""
    from rotor.model.topology import ground_problem
    msg = ground_problem(model, lock_loose_support=not args.open_support)
    if msg is not None:
        print(f"ringcontact rotor: warning: {msg}; rigid-body (0 Hz) modes are left out", file=sys.stderr)


def _stability(args, model, speeds_rad_s, consequence: str) -> dict:
    """The damped linearisation checked over ``speeds_rad_s`` (:mod:`rotor.linear.stability`): a mode with negative
    damping named in one warning line on stderr; the JSON field ``stability`` returned."""
    from rotor.linear.stability import first_unstable, stability_field, warning
    found = first_unstable(model, speeds_rad_s, lock_loose_support=not args.open_support)
    if found is not None:
        print(warning(f"ringcontact rotor {args.cmd}", found, consequence), file=sys.stderr)
    return stability_field(found)


def _max_speed(args, scene) -> float:
    if args.max_rpm is None:
        return scene.analysis.max_speed_rad_s
    if not (args.max_rpm > 0 and math.isfinite(args.max_rpm)):
        raise_input(f"--max-rpm = {args.max_rpm} rpm: must be > 0")
    return args.max_rpm / RPM


def raise_input(msg):
    from contact.errors import InputError
    raise InputError(msg)


def _f(args, f_hz: float) -> float:
    """A frequency (Hz) in the table's unit (``--units``: Hz, or rad/s)."""
    return f_hz * 2 * math.pi if args.units == "rad/s" else f_hz


def _s(args, w_rad_s: float) -> float:
    """A speed (rad/s) in the table's unit (``--units``: rpm, or rad/s)."""
    return w_rad_s if args.units == "rad/s" else w_rad_s * RPM


def _fu(args) -> str:
    return "rad/s" if args.units == "rad/s" else "Hz"


def _su(args) -> str:
    return "rad/s" if args.units == "rad/s" else "rpm"


def _emit(args, data: dict, table: str) -> None:
    print(json.dumps(data, indent=2, ensure_ascii=False) if args.json else table)


def cmd_scenes(args) -> int:
    from rotor.model.scene import bundled_scenes, load_scene
    rows = []
    for name in bundled_scenes():
        s = load_scene(name)
        rows.append({"name": name, "title": s.title})
    _emit(args, {"scenes": rows}, "\n".join(f"{r['name']:<28} {r['title']}" for r in rows))
    return 0


def cmd_modes(args) -> int:
    from rotor.linear.modes import modes
    scene, model = _load(args)
    _warn_free(model, args)
    if not math.isfinite(args.speed_rpm) or args.speed_rpm < 0:
        raise_input(f"--speed-rpm = {args.speed_rpm} rpm: must be finite and >= 0")
    res = modes(model, args.speed_rpm / RPM, n_modes=args.modes or scene.analysis.modes,
                lock_loose_support=not args.open_support,
                damped=args.damped)
    rows = [{"mode": j + 1, "frequency_hz": float(f), "frequency_rpm": float(f * 60),
             "frequency_rad_s": float(f * 2 * math.pi), "whirl": w,
             "forward_fraction": float(r), "damping_ratio": float(z) if args.damped else 0.0}
            for j, (f, w, r, z) in enumerate(zip(res.frequency_hz, res.whirl, res.forward_fraction, res.damping_ratio))]
    lines = [f"{scene.title}", f"modes at {args.speed_rpm:g} rpm ({'damped' if args.damped else 'undamped'}, "
             f"loose support {'open' if args.open_support else 'locked'}, {model.n_dofs} DOFs)",
             f"{'mode':>4} {'freq (' + _fu(args) + ')':>13} {'freq (rpm)':>11} {'whirl':>9} {'fwd frac':>8} {'zeta':>7}"]
    lines += [f"{r['mode']:>4} {_f(args, r['frequency_hz']):>13.3f} {r['frequency_rpm']:>11.1f} {r['whirl']:>9} "
              f"{r['forward_fraction']:>8.3f} {r['damping_ratio']:>7.4f}" for r in rows]
    if args.plot:
        _plot_mode_shapes(args, scene, model, res)
    stab = _stability(args, model, [args.speed_rpm / RPM], "its free vibration grows (--damped shows every zeta)")
    _emit(args, {"scene": scene.name, "speed_rpm": args.speed_rpm, "dofs": model.n_dofs, "modes": rows,
                 "stability": stab}, "\n".join(lines))
    return 0


def _plot_mode_shapes(args, scene, model, res) -> None:
    """``PREFIX-modeshapes.png/.svg``: |y + iz| along the shaft of the first (up to 6) modes."""
    from reports.rotor_plots import mode_shape_figure, save
    picks = [(f"mode {j + 1}: {res.frequency_hz[j]:.2f} Hz, {res.whirl[j]}", res, j)
             for j in range(min(6, len(res.frequency_hz)))]
    title = f"Mode shapes at {args.speed_rpm:g} rpm: {scene.title}"
    for p in save(mode_shape_figure(model, picks, title), f"{args.plot}-modeshapes"):
        print(f"wrote {p}", file=sys.stderr)


def cmd_campbell(args) -> int:
    from rotor.linear.modes import campbell, critical_speeds
    scene, model = _load(args)
    wmax = _max_speed(args, scene)
    speeds = np.linspace(0.0, wmax, args.points or scene.analysis.speed_points)
    n_modes = args.modes or scene.analysis.modes
    _budget.check("ringcontact rotor campbell", _budget.campbell(model.n_dofs, len(speeds)), args.accept_long,
                  f"--points = {len(speeds)} speeds of a {model.n_dofs}-DOF model"
                  + (f" (--elements {args.elements})" if args.elements else ""), "fewer --points or --elements")
    _warn_free(model, args)
    camp = campbell(model, speeds, n_modes=n_modes, lock_loose_support=not args.open_support, damped=args.damped)
    if args.plot:
        from reports.rotor_plots import campbell_figure, save
        crit = critical_speeds(model, wmax, orders=tuple(args.orders), families=_families(args), n_modes=n_modes + 4,
                               lock_loose_support=not args.open_support)
        for p in save(campbell_figure(camp, f"Campbell diagram: {scene.title}", crit, orders=tuple(args.orders)),
                      f"{args.plot}-campbell"):
            print(f"wrote {p}", file=sys.stderr)
    data = {"scene": scene.name, "speed_rpm": (speeds * RPM).tolist(), "speed_rad_s": speeds.tolist(),
            "frequency_hz": [[None if not np.isfinite(v) else float(v) for v in row] for row in camp.frequency_hz],
            "frequency_rad_s": _finite_rows(camp.frequency_hz * 2 * math.pi),
            "whirl": [list(w) for w in camp.whirl], "damped": bool(args.damped),
            "damping_ratio": _finite_rows(camp.damping_ratio), "log_decrement": _finite_rows(camp.log_decrement),
            "stability": _stability(args, model, speeds, "its free vibration grows from that speed on "
                                                          "(--damped shows every zeta)")}
    missing = int(np.sum(~np.isfinite(camp.frequency_hz)))
    if missing:      # said, not left to a reader of the JSON to find as nulls
        print(f"ringcontact rotor campbell: warning: {missing} of {camp.frequency_hz.size} whirl frequencies are "
              f"missing (null in the JSON, blank in the table): fewer than {n_modes} "
              f"{'underdamped ' if args.damped else ''}modes of a kind at some speeds", file=sys.stderr)
    head = f"{'speed (' + _su(args) + ')':>13} " + " ".join(f"{f'mode {j + 1} ({_fu(args)}, zeta)':>23}"
                                                          for j in range(n_modes))
    lines = [scene.title + (" (damped: frequencies and zeta with C)" if args.damped else " (undamped: zeta = 0)"),
             head]
    for i, w in enumerate(speeds):
        cells = [f"{_f(args, camp.frequency_hz[i, j]):>10.3f} {camp.whirl[i][j][:3]:>5} {camp.damping_ratio[i, j]:>6.4f}"
                 for j in range(n_modes)]
        lines.append(f"{_s(args, w):>13.1f} " + " ".join(cells))
    _emit(args, data, "\n".join(lines))
    return 0


def _finite_rows(a) -> list:
    """Rows of ``a`` as JSON lists, non-finite entries (a mode missing at a speed) as null."""
    return [[float(v) if np.isfinite(v) else None for v in row] for row in a]


def cmd_critical(args) -> int:
    from rotor.linear.modes import critical_speeds
    scene, model = _load(args)
    _warn_free(model, args)
    wmax = _max_speed(args, scene)
    crit = critical_speeds(model, wmax, orders=tuple(args.orders), families=_families(args),
                           n_modes=(args.modes or scene.analysis.modes) + 4, lock_loose_support=not args.open_support)
    rows = [{"order": c.order, "speed_rpm": c.speed_rpm, "speed_rad_s": c.speed_rad_s, "frequency_hz": c.frequency_hz,
             "frequency_rad_s": c.frequency_hz * 2 * math.pi, "whirl": c.whirl, "branch": c.branch + 1} for c in crit]
    shown = f"{', '.join(f'{o}X' for o in args.orders)}, {' and '.join(_families(args))} whirl"
    lines = [scene.title, f"critical speeds up to {wmax * RPM:.0f} rpm ({shown}; undamped whirl frequency = order x "
             "speed)", f"{'order':>5} {'speed (' + _su(args) + ')':>14} {'freq (' + _fu(args) + ')':>13} "
             f"{'whirl':>9} {'branch':>6}"]
    lines += [f"{r['order']:>4}X {_s(args, r['speed_rad_s']):>14.1f} {_f(args, r['frequency_hz']):>13.3f} "
              f"{r['whirl']:>9} {r['branch']:>6}" for r in rows]
    _emit(args, {"scene": scene.name, "max_speed_rpm": wmax * RPM, "orders": list(args.orders),
                 "whirl": list(_families(args)), "critical_speeds": rows}, "\n".join(lines))
    return 0


def cmd_unbalance(args) -> int:
    from rotor.linear.unbalance import forced_response
    scene, model = _load(args, misalignment=args.order == 2, modal=False)
    wmax = _max_speed(args, scene)
    speeds = np.linspace(wmax / (args.points or scene.analysis.speed_points), wmax,
                         args.points or scene.analysis.speed_points)
    nodes = args.nodes or [d.name for d in scene.disks] or [scene.stations[0].name]
    for n in nodes:
        model.node_of(n)
    resp = forced_response(model, speeds, order=args.order, lock_loose_support=not args.open_support)
    if args.plot:
        from reports.rotor_plots import response_figure, save
        what = "unbalance" if args.order == 1 else "misalignment"
        for p in save(response_figure(model, resp, nodes, f"Linear {what} response ({args.order}X): {scene.title}"),
                      f"{args.plot}-{what}"):
            print(f"wrote {p}", file=sys.stderr)
    table = {n: resp.orbit(model, n)[0] * 1e6 for n in nodes}
    data = {"scene": scene.name, "order": args.order, "speed_rpm": (speeds * RPM).tolist(),
            "speed_rad_s": speeds.tolist(), "semi_major_um": {n: v.tolist() for n, v in table.items()},
            "phase_reference": PHASE_REFERENCE, **_amplitudes_and_phases(model, resp, nodes),
            "stability": _stability(args, model, speeds, "the steady forced response below is not what the rotor "
                                                         "will do (its free vibration grows)")}
    lines = [scene.title, f"{args.order}X orbit semi-major axis (µm) and phase of y (deg; 0: in step with the load "
             "at +y, negative: lagging)",
             f"{'speed (' + _su(args) + ')':>13} " + " ".join(f"{n + ' um':>12} {'deg':>7}" for n in nodes)]
    ph = data["y_phase_deg"]
    lines += [f"{_s(args, w):>13.1f} " + " ".join(f"{table[n][i]:>12.4g} {ph[n][i]:>7.1f}" for n in nodes)
              for i, w in enumerate(speeds)]
    _emit(args, data, "\n".join(lines))
    return 0


#: what the unbalance phases are measured from
PHASE_REFERENCE = ("x(t) = amplitude cos(order Ω t + phase): phase 0 is in step with the load's cos(order Ω t) term "
                   "(a disk unbalance of phase 0 at +y, the misalignment's F_y: rotor.model.assembly.harmonic_loads), "
                   "negative phases lag it")


def _amplitudes_and_phases(model, resp, nodes) -> dict:
    """``y_amplitude_um``, ``y_phase_deg``, ``z_amplitude_um``, ``z_phase_deg`` per node from the complex amplitudes
    (:class:`rotor.linear.unbalance.ForcedResponse`: ``x(t) = Re(x̂ e^{i order Ω t})``), phases in (−180, 180]."""
    out = {}
    for c in ("y", "z"):
        amp = {n: resp.amplitudes[:, model.dof_index(f"{n}.{c}")] for n in nodes}
        out[f"{c}_amplitude_um"] = {n: (np.abs(a) * 1e6).tolist() for n, a in amp.items()}
        out[f"{c}_phase_deg"] = {n: [float(v if v > -180.0 else v + 360.0) for v in np.degrees(np.angle(a))]
                                 for n, a in amp.items()}
    return out


def cmd_response(args) -> int:
    from reports.rotor_response import run_response, summary_table
    for name, v, unit in (("--speed-rpm", args.speed_rpm, "rpm"), ("--revolutions", args.revolutions, "rev")):
        if not (math.isfinite(v) and v > 0):
            raise_input(f"{name} = {v:g} {unit}: must be finite and > 0")
    stations = None
    if args.stations is not None:
        stations = [x.strip() for x in args.stations.split(",")]
        if not all(stations):
            raise InputError(f"--stations = {args.stations!r}: an empty name in the list; give comma-separated "
                             "station, disk, bearing or support names (or leave --stations out for the default)")
    _response_work(args)
    from rotor.model.scene import load_scene
    scene = linear_scene(args, load_scene(args.scene), misalignment=True)
    summary = run_response(scene, args.speed_rpm, args.revolutions, args.out, method=args.method,
                           stations=stations, steps_per_rev=args.steps_per_rev, record_per_rev=args.record_per_rev,
                           elements=args.elements)
    if summary["stability"]["unstable_mode"] is not None:
        from rotor.linear.stability import UnstableMode, warning
        found = UnstableMode.from_dict(summary["stability"]["unstable_mode"])
        print(warning("ringcontact rotor response", found, "the steady 1X/2X columns are not what the rotor will do "
                      "(its free vibration grows)"), file=sys.stderr)
    _emit(args, summary, summary_table(summary) + f"\nwrote {args.out}/response.csv, response-summary.json")
    return 0


def cmd_static(args) -> int:
    from rotor.linear.static import plausibility, plausibility_warning, static_deflection
    scene, model = _load(args, modal=False)
    st = static_deflection(model)
    check = plausibility(model, st)
    said = plausibility_warning("ringcontact rotor static", check)
    if said:
        print(said, file=sys.stderr)
    total = st.load_N[[i for i, n in enumerate(model.dof_names) if n.endswith(".y")]].sum(), \
        st.load_N[[i for i, n in enumerate(model.dof_names) if n.endswith(".z")]].sum()
    stations = [{"station": n, "y_um": y * 1e6, "z_um": z * 1e6}
                for n in [s.name for s in scene.stations] + [s.name for s in scene.supports]
                for y, z in [st.displacement_m(n)]]
    reactions = [{"element": k, "force_y_N": fy, "force_z_N": fz} for k, (fy, fz) in st.reactions_N.items()]
    data = {"scene": scene.name, "dofs": model.n_dofs, "loose_support": "locked" if scene.loose_support else None,
            "load_on_free_dofs_y_N": float(total[0]), "load_on_free_dofs_z_N": float(total[1]),
            "stations": stations, "reactions": reactions,
            "plausibility": {"plausible": check["plausible"], "station": check["station"],
                             "deflection_mm": 1e3 * check["deflection_m"],
                             "limits_mm": {k: 1e3 * v for k, v in check["limits_m"].items()},
                             "exceeded": check["exceeded"]}}
    lines = [scene.title, f"static deflection under gravity and static loads ({model.n_dofs} DOFs"
             + (", loose support locked: the clearance is a time-integration question)" if scene.loose_support else ")"),
             f"load on the free DOFs: y {total[0]:.6g} N, z {total[1]:.6g} N (loads on fixed DOFs go to ground)",
             f"{'station':>12} {'y (um)':>12} {'z (um)':>12}"]
    lines += [f"{r['station']:>12} {r['y_um']:>12.4f} {r['z_um']:>12.4f}" for r in stations]
    lines += [f"{'element':>12} {'F_y (N)':>12} {'F_z (N)':>12}"]
    lines += [f"{r['element']:>12} {r['force_y_N']:>12.4f} {r['force_z_N']:>12.4f}" for r in reactions]
    _emit(args, data, "\n".join(lines))
    return 0


def _response_work(args) -> None:
    """The run's steps (Newmark) and records against the work budget (:func:`reports.cli._budget.stepping`)."""
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene
    n_dofs = assemble(load_scene(args.scene), elements_per_segment=args.elements).n_dofs
    steps = args.revolutions * args.steps_per_rev if args.method == "newmark" else 0
    est = _budget.stepping(steps, args.revolutions * args.record_per_rev, n_dofs)
    _budget.check("ringcontact rotor response", est, args.accept_long,
                  f"--revolutions = {args.revolutions:g} rev at --steps-per-rev {args.steps_per_rev} and "
                  f"--record-per-rev {args.record_per_rev} ({args.method})", "fewer revolutions, steps or records")


def cmd_report(args) -> int:
    from reports.rotor_linear import build_reports
    for p in build_reports(args.out):
        print(f"wrote {p}", file=sys.stderr)
    return 0


def _crossings(sp, what: str) -> None:
    """``--orders`` and ``--backward``: which crossings of the whirl frequencies are critical speeds."""
    sp.add_argument("--orders", type=count(1, 20), nargs="+", default=[1],
                    help=f"excitation orders 1-20 of the critical speeds {what} (default 1: unbalance; 2 for the "
                         "misalignment's 2X)")
    sp.add_argument("--backward", action="store_true",
                    help=f"also the backward-whirl crossings {what} (default: forward whirl only, the ones an "
                         "unbalance excites)")


def _families(args) -> tuple:
    return ("forward", "backward") if args.backward else ("forward",)


def _parser() -> argparse.ArgumentParser:
    p = Parser(prog="ringcontact rotor", description="Linear analyses of a rotor scene "
                                "(natural frequencies, Campbell diagram, critical speeds, unbalance response).")
    sub = p.add_subparsers(dest="cmd", required=True)

    def common(sp, speed_range=True):
        add_scene_options(sp)
        sp.add_argument("--elements", type=count(*COUNTS["elements"]), default=None, help="elements per shaft segment (override, 1-64)")
        sp.add_argument("--open-support", action="store_true",
                        help="leave the loose-support bearing and support unconnected (default: locked together)")
        sp.add_argument("--modes", type=count(*COUNTS["modes"]), default=None, help="number of modes (1-200)")
        sp.add_argument("--json", action="store_true", help="print JSON instead of a table (frequencies and speeds in "
                        "both units: frequency_hz and frequency_rad_s, speed_rpm and speed_rad_s)")
        sp.add_argument("--units", choices=("hz", "rad/s"), default="hz",
                        help="the table's frequencies in Hz and speeds in rpm (hz, default) or both in rad/s")
        if speed_range:
            sp.add_argument("--max-rpm", type=quantity("rpm_max"), default=None, help="top speed (rpm); default from the scene")

    sp = sub.add_parser("scenes", help="list bundled scenes")
    sp.add_argument("--json", action="store_true", help="print the bundled scenes as JSON")
    sp.set_defaults(func=cmd_scenes)
    sp = sub.add_parser("modes", help="natural (whirl) frequencies and whirl direction at one speed")
    common(sp, speed_range=False)
    sp.add_argument("--speed-rpm", type=quantity("speed_rpm"), default=0.0, help="rotor speed (rpm), default 0")
    sp.add_argument("--damped", action="store_true", help="include viscous damping (damped frequencies)")
    sp.add_argument("--plot", type=out_prefix, default=None, help="write PREFIX-modeshapes.png and .svg (first 6 mode shapes)")
    sp.set_defaults(func=cmd_modes)
    sp = sub.add_parser("campbell", help="whirl frequencies over a speed range")
    common(sp)
    sp.add_argument("--points", type=count(*COUNTS["speeds"]), default=None, help="number of speeds (2-2000)")
    sp.add_argument("--plot", type=out_prefix, default=None, help="write PREFIX-campbell.png and .svg")
    _budget.add_accept_long(sp)
    sp.add_argument("--damped", action="store_true", help="include viscous damping: damped frequencies and each "
                    "mode's damping ratio zeta and log decrement (default undamped, zeta = 0)")
    _crossings(sp, "of the --plot")
    sp.set_defaults(func=cmd_campbell)
    sp = sub.add_parser("critical-speeds", help="intersections of whirl frequencies with 1X, 2X ...")
    common(sp)
    _crossings(sp, "listed")
    sp.set_defaults(func=cmd_critical)
    sp = sub.add_parser("unbalance", help="linear steady-state unbalance (1X) or misalignment (2X) response")
    common(sp)
    sp.add_argument("--points", type=count(*COUNTS["speeds"]), default=None, help="number of speeds (2-2000)")
    sp.add_argument("--nodes", nargs="+", default=None, help="nodes or element names (default: the disks)")
    sp.add_argument("--order", type=int, default=1, choices=(1, 2), help="1: unbalance, 2: misalignment")
    sp.add_argument("--plot", type=out_prefix, default=None,
                    help="write PREFIX-unbalance.png and .svg (--order 2: PREFIX-misalignment.png and .svg)")
    sp.set_defaults(func=cmd_unbalance)
    sp = sub.add_parser("static", help="static deflection and bearing reactions under gravity and static loads")
    add_scene_options(sp)
    sp.add_argument("--elements", type=count(*COUNTS["elements"]), default=None, help="elements per shaft segment (override, 1-64)")
    sp.add_argument("--json", action="store_true", help="print JSON instead of a table")
    sp.set_defaults(func=cmd_static)
    sp = sub.add_parser("response", help="linear time response of the stations (loose support locked), CSV")
    add_scene_options(sp)
    sp.add_argument("--speed-rpm", type=quantity("run_speed_rpm"), required=True, help="spin speed (rpm)")
    sp.add_argument("--revolutions", type=quantity("revolutions"), default=20.0, help="duration in revolutions (default 20)")
    sp.add_argument("--method", choices=("harmonic", "newmark"), default="harmonic",
                    help="harmonic: steady state by superposition (default); newmark: from rest, in time")
    sp.add_argument("--stations", default=None, help="comma-separated station/disk/bearing/support names "
                    "(default: the scene's disks, loose-support bearing, supports and bearings)")
    sp.add_argument("--steps-per-rev", type=count(*COUNTS["steps_per_rev"]), default=256, help="Newmark steps per revolution (default 256)")
    sp.add_argument("--record-per-rev", type=count(*COUNTS["record_per_rev"]), default=64, help="samples per revolution (default 64)")
    sp.add_argument("--elements", type=count(*COUNTS["elements"]), default=None, help="elements per shaft segment (override)")
    sp.add_argument("--json", action="store_true", help="print the summary as JSON")
    sp.add_argument("--out", type=out_dir, default="response-out", help="output directory (default response-out)")
    _budget.add_accept_long(sp)
    sp.set_defaults(func=cmd_response)
    sp = sub.add_parser("report", help="regenerate reports/published/rotor-* (figures and tables)")
    sp.add_argument("--out", type=out_dir, default=PUBLISHED, help=f"output directory (default {PUBLISHED})")
    sp.set_defaults(func=cmd_report)
    return p


def main(argv: list[str] | None = None) -> int:
    p = _parser()
    args = p.parse_args(argv)
    args = finish(p, args, sub=args.cmd)
    for name in ("modes", "points", "elements", "steps_per_rev", "record_per_rev"):
        v = getattr(args, name, None)
        if v is not None and v < 1:
            print(f"ringcontact rotor {args.cmd}: error: --{name.replace('_', '-')} = {v}: must be >= 1", file=sys.stderr)
            return 2
    try:
        return args.func(args)
    except RingContactError as exc:
        return fail(f"ringcontact rotor {args.cmd}", exc)
    except BrokenPipeError:  # output piped into head & co.
        sys.stderr.close()
        return 0


if __name__ == "__main__":
    sys.exit(main())
