"""``ringcontact orbit`` and ``ringcontact branch``: periodic orbits by shooting, their stability, branches.

Examples::

    ringcontact orbit paper-table4 --speed-rpm 10500 --json
    ringcontact orbit paper-table4 --speed-rpm 15000 --period-revs 2 --out orbit.json
    ringcontact branch paper-table4 --rpm-start 9000 --rpm-end 12000 --plot runs/bif --out runs/branch.json

``orbit`` finds the periodic orbit at one speed (:func:`rotor.studies.orbit.orbit`: Newton shooting on the
production scheme's period map from a short transient) and prints its period, Floquet multipliers,
stability, the kind of the critical multiplier (the one that leaves the unit circle first: ``fold`` through
+1, ``period_doubling`` through −1, ``neimark_sacker`` a complex pair), the 1X–5X velocity amplitudes at
every station (``velocity_amplitudes_mm_s_1X_to_5X``, the key and quantity of ``simulate --steady``),
the Newton iterations, the residual and the wall time, and the loose support over one period (the keys of
``simulate``'s summary, :mod:`rotor.dynamics.support_record`: ``peak_contact_force_N`` and its time after
phase 0 ``peak_contact_force_t_s``, ``mean_contact_force_N``, ``peak_contact_moment_Nm``, ``contact_share``,
``separation_share``, ``stick_share_right_face``, ``stick_share_left_face``, ``peak_face_force_N``), which
tell an orbit whose ring stays stuck (contact share 0, stick shares 1) from one that slips and hits.
``branch`` follows the orbit over a speed range by pseudo-arclength continuation
(:func:`rotor.studies.orbit.branch`) and lists each point (with the same support fields) and the
bifurcations met; ``--plot`` draws the bifurcation diagram (:mod:`reports.bifurcation`).

Exit status 1 (one line on stderr, after the results are written) when the orbit did not converge or the
branch stopped before ``--rpm-end``: a failed point never exits 0.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from contact.errors import InputError, RingContactError
from reports.cli import _budget
from reports.cli._edge import Parser, count, fail, out_file, out_prefix, quantity


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("scene", help="scene name or TOML path (e.g. paper-table4)")
    p.add_argument("--steps-per-rev", type=count(16, 100000), default=None,
                   help="time steps per revolution (default: 256, more where the contact step limit needs it)")
    p.add_argument("--clearance-mm", type=quantity("clearance_mm"), default=None, help="radial clearance (mm, default: scene)")
    p.add_argument("--misalignment-mm", type=quantity("misalignment_mm"), default=None,
                   help="misalignment δ (mm, default: scene)")
    p.add_argument("--tilt-ignored", action="store_true", help="line contact, no tilt moments (paper Fig. 16)")
    p.add_argument("--json", action="store_true", help="print the result as JSON (default: a short table)")
    p.add_argument("--out", type=out_file, default=None, help="also write the JSON result to this file")
    _budget.add_accept_long(p)


def _orbit_parser() -> argparse.ArgumentParser:
    p = Parser(prog="ringcontact orbit", description="the periodic orbit at one speed by shooting, with its Floquet "
                                                     "multipliers and 1X-5X velocity amplitudes")
    _common(p)
    p.add_argument("--speed-rpm", type=quantity("run_speed_rpm"), required=True, help="spin speed (rpm)")
    p.add_argument("--period-revs", type=count(1, 8, "revolutions"), default=None,
                   help="period in revolutions, 1 to 8 (default: found from the transient's Poincaré returns; "
                        "an orbit whose shorter period divides it is reported with the shorter period)")
    return p


def _branch_parser() -> argparse.ArgumentParser:
    p = Parser(prog="ringcontact branch", description="follow the periodic orbit over a speed range "
                                                      "(pseudo-arclength continuation), with its bifurcations")
    _common(p)
    p.add_argument("--rpm-start", type=quantity("run_speed_rpm"), required=True, help="first speed (rpm)")
    p.add_argument("--rpm-end", type=quantity("run_speed_rpm"), required=True,
                   help="last speed (rpm; below --rpm-start follows the branch downwards, as a run-down)")
    p.add_argument("--max-points", type=count(2, 5000, "points"), default=400, help="most orbits on the branch (default 400)")
    p.add_argument("--plot", type=out_prefix, default=None, metavar="PREFIX",
                   help="bifurcation diagram PREFIX.png/.svg (1X amplitude at --station against speed)")
    p.add_argument("--station", default=None,
                   help="channel of the diagram, <station>.y or <station>.z (default: the scene's first response station, .y)")
    return p


def _overrides(args) -> dict:
    kw = {"tilt_ignored": bool(args.tilt_ignored)}
    if args.clearance_mm is not None:
        kw["clearance_m"] = args.clearance_mm * 1e-3
    if args.misalignment_mm is not None:
        kw["misalignment_m"] = args.misalignment_mm * 1e-3
    return kw


def _scene(args) -> tuple:
    """The scene's name, response channels and loose support; a bad scene is refused here, before any computing."""
    from rotor.studies.steady_state import _scene_model
    sc, model = _scene_model(args.scene)
    return sc.name, [f"{s}.{c}" for s in model.response_stations() for c in ("y", "z")], sc.loose_support


def _check_work(args, prog: str, rpm: float, points: int = 0) -> None:
    """The shooting work at ``rpm`` (and ``points`` orbits of a branch) against the budget, before it starts
    (:func:`reports.cli._budget.orbit`)."""
    from rotor.studies.steady_state import SteadyStateOptions, point_system, step_per_rev

    system = point_system(args.scene, rpm, **_overrides(args))[2]
    n = int(args.steps_per_rev or step_per_rev(system, SteadyStateOptions()))
    est = _budget.orbit(system, n, getattr(args, "period_revs", None), points)
    cause = (f"--steps-per-rev = {n}" if args.steps_per_rev else
             f"{n} steps per revolution (the contact step limit at {rpm:g} rpm)")
    _budget.check(prog, est, args.accept_long, cause + (f" and --max-points = {points}" if points else ""),
                  "fewer steps per revolution" + (" or --max-points" if points else ""))


def law_fields(loose, max_edge_penetration_m: float, max_tilt_in_contact_arcmin: float | None = None) -> dict:
    """The scene's law in a result: ``law`` (as the scene names it), a calibrated law's ``law_file`` and
    ``law_sha256``, and the validity checks of :func:`reports.cli.simulate.validity_summary` and, for a law
    checked against a 3D reference up to a tilt, :func:`reports.cli.simulate.tilt_validity_summary`."""
    import numpy as np

    from contact.units import ARCMIN
    from reports.cli.simulate import tilt_validity_summary, validity_summary
    if loose is None:
        return {}
    out = {"law": loose.law, **loose.law_note(),
           **validity_summary(max_edge_penetration_m, loose.validity_max_penetration_m)}
    if loose.calibrated is not None and max_tilt_in_contact_arcmin is not None:
        out.update(tilt_validity_summary(np.array([max_tilt_in_contact_arcmin * ARCMIN]), np.array([True]),
                                         float(loose.calibrated.validity_tilt_max_rad)))
        out.pop("max_tilt_in_contact_arcmin", None)      # the orbit's own field says it
    return out


def _emit(args, result: dict, table: str) -> None:
    text = json.dumps(result, indent=2) + "\n"
    if args.out is not None:
        from contact.files import atomic_write_text
        atomic_write_text(Path(args.out), text)
    print(text if args.json else table, end="" if args.json else "\n")


def main(argv: list[str] | None = None) -> int:
    """``ringcontact orbit``."""
    args = _orbit_parser().parse_args(argv)
    try:
        return _orbit(args)
    except RingContactError as e:
        return fail("ringcontact orbit", e)


def branch_main(argv: list[str] | None = None) -> int:
    """``ringcontact branch``."""
    p = _branch_parser()
    args = p.parse_args(argv)
    if args.rpm_end == args.rpm_start:
        p.error(f"argument --rpm-end: = {args.rpm_end:g} rpm: must differ from --rpm-start = {args.rpm_start:g} rpm")
    try:
        return _branch(args)
    except RingContactError as e:
        return fail("ringcontact branch", e)


def orbit_json(res, scene: str) -> dict:
    """The JSON of one orbit (keys with units; multipliers as ``[re, im]``)."""
    d = {"scene": scene, **res.as_dict()}
    f = res.floquet
    d["critical_multiplier"] = [float(f.critical.real), float(f.critical.imag)]   # the one that leaves first
    d["multipliers_outside"] = {"real_above_plus_1": int(f.n_out_real_positive),
                                "real_below_minus_1": int(f.n_out_real_negative), "complex": int(f.n_out_complex)}
    d["wall_s"] = round(float(d["wall_s"]), 4)
    return d


def _orbit_table(d: dict) -> str:
    mult = ", ".join(f"{complex(*m):.4g}" for m in d["multipliers"][:6])
    lines = [f"orbit {d['scene']} at {d['speed_rpm']:g} rpm: period {d['period_revs']} rev = {d['period_s']:.6g} s, "
             f"{'converged' if d['converged'] else 'NOT converged'} in {d['newton_iterations']} Newton iterations "
             f"(residual {d['residual']:.2e}), {d['wall_s']:.2f} s",
             f"  {'stable' if d['stable'] else 'UNSTABLE'}: spectral radius {d['spectral_radius']:.6f}, critical "
             f"multiplier {complex(*d['critical_multiplier']):.4g} ({d['leading_multiplier']}), "
             f"{d['neutral_multipliers']} neutral; largest: {mult}",
             f"  {'channel':<14}" + "".join(f"{k}X mm/s".rjust(12) for k in range(1, 6))]
    for name, amps in d["velocity_amplitudes_mm_s_1X_to_5X"].items():
        lines.append(f"  {name:<14}" + "".join(f"{a:12.5g}" for a in amps))
    if "contact_share" in d:
        lines.append(f"  loose support over the period: {_support_line(d)}")
    return "\n".join(lines)


def _share(x) -> str:
    return "-" if x is None else f"{100 * x:.0f} %"


def _support_line(d: dict) -> str:
    """Contact and stick of one orbit in words (the JSON's ``contact_share``, ``peak_contact_force_N`` …)."""
    return (f"contact {_share(d['contact_share'])} of the time, peak contact force {d['peak_contact_force_N']:.4g} N, "
            f"faces stuck {_share(d['stick_share_right_face'])} (right) / {_share(d['stick_share_left_face'])} (left)")


def _orbit(args) -> int:
    from rotor.studies.orbit import orbit

    name, _, loose = _scene(args)
    _check_work(args, "ringcontact orbit", args.speed_rpm)
    res = orbit(args.scene, args.speed_rpm, steps_per_rev=args.steps_per_rev, period_revs=args.period_revs,
                **_overrides(args))
    d = {**orbit_json(res, name), **law_fields(loose, res.max_edge_penetration_m,
                                              res.contact.get("max_tilt_in_contact_arcmin"))}
    _emit(args, d, _orbit_table(d))
    if not res.converged:
        print(f"ringcontact orbit: error: no periodic orbit of {res.period_revs} revolution(s) at "
              f"{args.speed_rpm:g} rpm: Newton stopped at residual {res.residual:.3g} after {res.newton_iterations} "
              "iterations (the multipliers are those of the last iterate; try --period-revs or another speed)",
              file=sys.stderr)
        return 1
    return 0


def _branch_table(d: dict) -> str:
    lines = [f"branch {d['scene']} {d['rpm_start']:g} -> {d['rpm_end']:g} rpm: {len(d['points'])} orbits, "
             f"period {d['period_revs']} rev, stopped: {d['stop']}, {d['wall_s']:.1f} s",
             f"  {'speed rpm':>10} {'stable':>7} {'radius':>9} {'leading':>13} {'contact':>8} {'peak N':>10}"]
    for p in d["points"]:
        lines.append(f"  {p['speed_rpm']:10.1f} {str(p['stable']):>7} {p['spectral_radius']:9.5f} "
                     f"{p['leading_multiplier']:>13} {_share(p.get('contact_share')):>8} "
                     f"{p.get('peak_contact_force_N', float('nan')):10.4g}")
    lines.append("  bifurcations: " + ("; ".join(f"{b['kind']} at {b['speed_rpm']:.1f} rpm" for b in d["bifurcations"])
                                       or "none"))
    return "\n".join(lines)


def _branch(args) -> int:
    from rotor.studies.continuation import ContinuationOptions
    from rotor.studies.orbit import branch

    name, channels, loose = _scene(args)
    if args.station is not None and not args.station.strip():
        raise InputError(f"--station = {args.station!r}: names nothing; give <station>.y or <station>.z (have "
                         f"{', '.join(channels)}), or leave --station out for {channels[0]}")
    station = args.station or channels[0]
    if station not in channels:
        raise InputError(f"--station = {station}: not a response channel of {name} "
                         f"(have {', '.join(channels)})")
    _check_work(args, "ringcontact branch", min(args.rpm_start, args.rpm_end), int(args.max_points))
    t0 = time.perf_counter()
    res = branch(args.scene, args.rpm_start, args.rpm_end, steps_per_rev=args.steps_per_rev,
                 options=ContinuationOptions(max_points=int(args.max_points)), **_overrides(args))
    d = {"scene": name, "rpm_start": args.rpm_start, "rpm_end": args.rpm_end,
         "period_revs": res.start.period_revs, "steps_per_rev": res.start.steps_per_rev, **res.as_dict(),
         "wall_s": round(time.perf_counter() - t0, 3)}
    deepest_mm = max([p.get("max_edge_penetration_mm", 0.0) for p in d["points"]], default=0.0)
    tilt = max([p.get("max_tilt_in_contact_arcmin", 0.0) for p in d["points"]], default=0.0)
    d.update(law_fields(loose, max(deepest_mm * 1e-3, res.start.max_edge_penetration_m),    # deepest of the branch
                        max(tilt, res.start.contact.get("max_tilt_in_contact_arcmin", 0.0))))
    _emit(args, d, _branch_table(d))
    if args.plot is not None and d["points"]:
        from reports.bifurcation import bifurcation_figure
        for f in bifurcation_figure(d, station, args.plot):
            print(f"  wrote {f}", file=sys.stderr if args.json else sys.stdout)
    if d["stop"] != "end reached":
        print(f"ringcontact branch: error: the branch stopped at "
              f"{d['points'][-1]['speed_rpm'] if d['points'] else args.rpm_start:.1f} rpm before --rpm-end = "
              f"{args.rpm_end:g} rpm ({d['stop']}); the orbits found are in the output", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
