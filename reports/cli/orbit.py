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
bifurcations met (a multiplier that jumps across the unit circle where the switches of the orbit change is a
``discontinuous`` bifurcation, with both sides in its ``detail``); every stall of the corrector is in
``corrector_failures`` (speed, why, how it was passed) and each restarted point has its ``restart_reason``;
``--plot`` draws the bifurcation diagram (:mod:`reports.bifurcation`). The branch starts on the orbit a
transient from :func:`rotor.dynamics.static_start.periodic_start` reaches (the static equilibrium with its linear
forced response under gravity or static loads the faces cannot hold, else the linear periodic solution; the orbit's
``transient_start`` says which), or on a chosen one: ``--from-orbit FILE`` (an ``orbit
--out`` file: that orbit, stable or not) or ``--from-state DIR`` (a ``simulate --out DIR`` run at
``--rpm-start`` ending after whole revolutions: the orbit a transient from its last state reaches)::

    ringcontact simulate --scene paper-table4 --speed-rpm 9000 --revolutions 40 --out runs/s9000
    ringcontact branch paper-table4 --rpm-start 9000 --rpm-end 12000 --from-state runs/s9000

``orbit --from-orbit FILE`` starts Newton on the orbit of an ``orbit --out`` file of the same scene at a
neighbouring speed (its phase-0 state and period, one revolution of transient): an unstable orbit that no
transient from rest settles on is found so (on paper-table4 at 16 394.5 rpm the search from rest ends without an
orbit; from 17 762.7 rpm's orbit Newton finds one, multiplier 2.32: reports/published/perf-monodromy-random.md)::

    ringcontact orbit paper-table4 --speed-rpm 17762.7 --out runs/o17763.json
    ringcontact orbit paper-table4 --speed-rpm 16394.5 --from-orbit runs/o17763.json

Both carry the record of the law's validity over the orbits (``law_validity``, :mod:`rotor.model.law_validity`: the
one ``simulate`` writes; a branch's merged over its orbits) and say its findings on stderr as ``simulate`` does; a
law its file flags is refused unless ``--allow-flagged-law``.

Exit status 1 (one line on stderr, after the results are written) when the orbit did not converge or the
branch stopped before ``--rpm-end``: a failed point never exits 0.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

from contact.errors import ConvergenceError, InputError, OutsideDomainError, RingContactError
from reports.cli import _budget
from reports.cli._branch_path import branch_path
from reports.cli._edge import Parser, count, fail, in_dir, in_file, out_file, out_prefix, quantity
from reports.cli._scene_options import (add_law_check_option, add_progress_option, add_scene_options, finish,
                                        override_words, say_on_terminal, scene_from_args, scene_top_rpm,
                                        warm_up_shown, warn_speeds_beyond_scene)
from reports.cli._orbit_hb import check_method_args, hb_branch_run, hb_branch_table, hb_choice, hb_orbit_table
from reports.cli._orbit_starts import chosen_orbit, orbit_file, state_start


def _method(text: str) -> str:
    """A ``type=`` for ``--method``: shooting, hb or auto."""
    if text not in METHOD_NAMES:
        raise argparse.ArgumentTypeError(f"= {text}: must be one of {', '.join(METHOD_NAMES)}")
    return text


def _friction_scheme(text: str) -> str:
    """A ``type=`` for ``--friction-scheme`` (rotor/dynamics/system.py: FRICTION_SCHEMES)."""
    from rotor.dynamics.system import FRICTION_SCHEMES
    if text not in FRICTION_SCHEMES:
        raise argparse.ArgumentTypeError(f"= {text}: must be one of {', '.join(FRICTION_SCHEMES)}")
    return text


#: ``branch --family-member`` values: which member of a friction-held family each point is
FAMILY_MEMBERS = ("kept", "centred")


def _family_member(text: str) -> str:
    """A ``type=`` for ``branch --family-member`` (:data:`FAMILY_MEMBERS`)."""
    if text not in FAMILY_MEMBERS:
        raise argparse.ArgumentTypeError(f"= {text}: must be one of {', '.join(FAMILY_MEMBERS)}")
    return text


#: ``--method`` values (rotor/studies/orbit_methods.py: METHODS)
METHOD_NAMES = ("shooting", "hb", "auto")


def _common(p: argparse.ArgumentParser) -> None:
    add_scene_options(p)
    add_law_check_option(p)
    p.add_argument("--steps-per-rev", type=count(16, 100000), default=None,
                   help="time steps per revolution (default: 256, more where the contact step limit needs it)")
    p.add_argument("--method", type=_method, default="shooting",
                   help="shooting (default: Newton on the time integration's period map, Floquet stability, "
                        "impacts and stick/slip), hb (harmonic balance: a frictionless ring only, no step error, "
                        "stability not computed) or auto (HB where the ring is frictionless and its spectrum "
                        "converges below shooting's step error, else shooting; the JSON says which ran and why, "
                        "and checks HB against shooting at the speed)")
    p.add_argument("--harmonics", type=count(1, 64, "harmonics"), default=None,
                   help="HB harmonics for --method hb or auto (default: 1, 2, 4 ... 32 until the spectrum's "
                        "highest retained harmonics fall below the bound; ignored by shooting)")
    p.add_argument("--richardson", action="store_true",
                   help="shooting also with twice the steps per revolution, the amplitudes extrapolated to "
                        "continuous time (Richardson; JSON richardson); not with --method hb (no step)")
    p.add_argument("--friction-scheme", type=_friction_scheme, default="active-set",
                   help="shooting's end-face friction: active-set (default: stick/slip modes, events located inside "
                        "the step) or projection (Coulomb's law solved in each step as a projection: no modes and no "
                        "thresholds, so the period map has no jump; events not located)")
    p.add_argument("--json", action="store_true", help="print the result as JSON (default: a short table)")
    p.add_argument("--out", type=out_file, default=None, help="also write the JSON result to this file")
    add_progress_option(p)
    _budget.add_accept_long(p)


def _orbit_parser() -> argparse.ArgumentParser:
    p = Parser(prog="ringcontact orbit", description="the periodic orbit at one speed by shooting, with its Floquet "
                                                     "multipliers and 1X-5X velocity amplitudes")
    _common(p)
    p.add_argument("--speed-rpm", type=quantity("run_speed_rpm"), required=True, help="spin speed (rpm)")
    p.add_argument("--period-revs", type=count(1, 8, "revolutions"), default=None,
                   help="period in revolutions, 1 to 8 (default: found from the transient's Poincaré returns; "
                        "an orbit whose shorter period divides it is reported with the shorter period)")
    p.add_argument("--from-orbit", type=in_file, default=None, metavar="FILE",
                   help="start Newton on the orbit of an `orbit --out` FILE of the same scene at another speed (its "
                        "state at phase 0 and period, one revolution of transient): finds an unstable orbit that no "
                        "transient from rest settles on; --method shooting only")
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
    p.add_argument("--from-orbit", type=in_file, default=None, metavar="FILE",
                   help="start on the orbit of an `orbit --out` FILE (same scene, --rpm-start its speed), stable or not")
    p.add_argument("--turn-back-rpm", type=quantity("run_speed_rpm"), default=None, metavar="RPM",
                   help="after a fold, follow the returning (middle) branch this far back, then jump past the fold "
                        "as a run-up does (a restart, reported); default: follow the branch wherever it goes")
    p.add_argument("--from-state", type=in_dir, default=None, metavar="DIR",
                   help="start on the orbit a transient reaches from the end state of a `simulate --out DIR` run "
                        "(same scene, --rpm-start its speed, a whole number of revolutions)")
    p.add_argument("--family-member", type=_family_member, default="kept",
                   help="where the ring's faces stick through the period (a family of orbits held by friction): kept "
                        "(default: each orbit keeps the offsets the previous one stuck at, until a face slips) or "
                        "centred (each orbit is the family's member farthest from slipping and from the bore, "
                        "rotor/periodic/family_centre.py)")
    p.add_argument("--back-fill", action="store_true",
                   help="a restart that lands more than a hundredth of the range past the last orbit is moved back "
                        "along the branch it found, to the orbit before that branch's fold (fewer speeds skipped)")
    return p


def _overrides(args) -> dict:
    """The scene overrides given (:func:`reports.cli._scene_options.scene_from_args`), ``tilt_ignored`` always."""
    return {"tilt_ignored": False, **scene_from_args(args).overrides}


def _scene(args, prog: str) -> tuple:
    """The scene's name, response channels and loose support (with ``--law``); a bad scene or law, or a flagged law
    without ``--allow-flagged-law``, is refused here, before any computing; the line naming the geometry and law is
    kept for :func:`_say_law`."""
    from rotor.model.law_validity import ALLOW_OPTION, check_allowed, law_line
    from rotor.studies.steady_state import _scene_model
    sc, model = _scene_model(args.scene, None, _overrides(args).get("law"))
    check_allowed(sc.loose_support, args.allow_flagged_law, ALLOW_OPTION)
    args.law_line = f"{prog}: {law_line(sc.loose_support, _overrides(args))}"     # said once the work starts
    speeds = [args.speed_rpm] if hasattr(args, "speed_rpm") else [args.rpm_start, args.rpm_end]
    args.beyond_scene = {"scene_max_speed_rpm": scene_top_rpm(sc), "speed_beyond_scene_range": False}
    args.speeds_of_scene = (sc, speeds)          # warned by _check_work once the request is accepted
    return sc.name, [f"{s}.{c}" for s in model.response_stations() for c in ("y", "z")], sc.loose_support


def _warn_beyond(args, prog: str) -> None:
    """The speed-beyond-the-scene warning, once, after the request is accepted (a refused one says one line)."""
    if getattr(args, "speeds_of_scene", None):
        args.beyond_scene["speed_beyond_scene_range"] = warn_speeds_beyond_scene(prog, *args.speeds_of_scene) is not None
        args.speeds_of_scene = None


def _check_work(args, prog: str, rpm: float, points: int = 0) -> None:
    """The shooting work at ``rpm`` (and ``points`` orbits of a branch) against the budget, before it starts
    (:func:`reports.cli._budget.orbit`: step costs measured on the system after the compile, a branch's orbits
    counted over its scaled arclength)."""
    from rotor.dynamics.period_map import warm_up
    from rotor.studies.steady_state import SteadyStateOptions, point_system, step_per_rev

    ov = _overrides(args)
    _, model, system = point_system(args.scene, rpm, **ov)
    n = int(args.steps_per_rev or step_per_rev(system, SteadyStateOptions()))
    cause = (f"--steps-per-rev = {n}" if args.steps_per_rev else
             f"{n} steps per revolution (the contact step limit at {rpm:g} rpm)")
    cause += f" and --max-points = {points}" if points else ""
    remedy = "fewer steps per revolution" + (" or --max-points" if points else "")
    first = _budget.beyond_at_table4_cost(system, n, getattr(args, "period_revs", None), points)
    if first is not None:                       # refused before the compile and the probe
        _budget.check(prog, first, args.accept_long, cause, remedy)
    warm_up_shown(prog, args, warm_up)          # the compile first, reported on its own: the probe times the steps
    cost = _budget.map_cost(lambda: point_system(args.scene, rpm, **ov)[2], n)
    path = (branch_path(lambda w: point_system(args.scene, w, **ov)[2], args.rpm_start, args.rpm_end)
            if points else None)
    contact = (_budget.map_cost(lambda: point_system(args.scene, path.deepest_rpm, **ov)[2], n)
               if points and path.deepest_rpm is not None else None)
    est = _budget.orbit(system, n, getattr(args, "period_revs", None), points, cost=cost, path=path,
                        contact_cost=contact)
    _budget.check(prog, est, args.accept_long, cause, remedy)
    _warn_beyond(args, prog)
    _warn_unstable(args, prog, model, (args.rpm_start, args.rpm_end) if points else (rpm,))


def _warn_unstable(args, prog: str, model, speeds_rpm) -> None:
    """The first unstable mode of the rotor's linearisation (loose support locked, then open:
    :func:`rotor.linear.stability.linearisation_unstable`) at the speeds (rpm; a branch's ends and middle), said in
    one warning line before the work and kept in ``args.unstable`` for the failure message and the JSON."""
    from rotor.linear.stability import linearisation_unstable, warning

    ends = [float(v) for v in speeds_rpm]
    found = None
    for rpm in (ends if len(ends) == 1 else [ends[0], 0.5 * (ends[0] + ends[-1]), ends[-1]]):
        found = found or linearisation_unstable(model, rpm * math.pi / 30.0)
    args.unstable = found
    if found is not None:
        print(warning(prog, found, "an orbit that grows is the rotor's instability, not the contact law"),
              file=sys.stderr, flush=True)


def _stability(args) -> dict:
    """The JSON field ``stability`` of :func:`rotor.linear.stability.stability_field` for ``args.unstable``."""
    from rotor.linear.stability import stability_field
    return {"stability": stability_field(getattr(args, "unstable", None))}


def law_fields(loose, max_edge_penetration_m: float, max_tilt_in_contact_arcmin: float | None = None,
               records=()) -> dict:
    """The scene's law in a result: ``law`` (as the scene names it), a calibrated law's ``law_file`` and
    ``law_sha256``, the validity checks of :func:`reports.cli.simulate.validity_summary` and, for a law
    checked against a 3D reference up to a tilt, :func:`reports.cli.simulate.tilt_validity_summary`; and
    ``law_validity``, the run's record (:mod:`rotor.model.law_validity`) merged from the orbits' ``records``
    (the law's own fields only where no orbit recorded one: an HB orbit)."""
    import numpy as np

    from contact.units import ARCMIN
    from reports.cli.simulate import tilt_validity_summary, validity_summary
    from rotor.model.law_validity import law_header, merged
    if loose is None:
        return {}
    out = {"law": loose.law, **loose.law_note(), "law_validity": merged(records) or law_header(loose),
           **validity_summary(max_edge_penetration_m, loose.validity_max_penetration_m)}
    if loose.calibrated is not None and max_tilt_in_contact_arcmin is not None:
        out.update(tilt_validity_summary(np.array([max_tilt_in_contact_arcmin * ARCMIN]), np.array([True]),
                                         float(loose.calibrated.validity_tilt_max_rad)))
        out.pop("max_tilt_in_contact_arcmin", None)      # the orbit's own field says it
    return out


def _emit(args, result: dict, table: str) -> None:
    _say_law(args)                  # not said yet where HB ran alone
    result.update(getattr(args, "beyond_scene", {}))
    text = json.dumps(result, indent=2) + "\n"
    if args.out is not None:
        from contact.files import atomic_write_text
        atomic_write_text(Path(args.out), text)
    print(text if args.json else table, end="" if args.json else "\n")
    prog = "ringcontact branch" if hasattr(args, "rpm_start") else "ringcontact orbit"
    for line in result.get("law_validity", {}).get("warnings", []):     # every rotor job alike (simulate's words)
        print(f"{prog}: warning: {line}", file=sys.stderr)


def main(argv: list[str] | None = None) -> int:
    """``ringcontact orbit``."""
    p = _orbit_parser()
    args = finish(p, p.parse_args(argv))
    try:
        return _orbit(args)
    except RingContactError as e:
        return fail("ringcontact orbit", e)


def branch_main(argv: list[str] | None = None) -> int:
    """``ringcontact branch``."""
    p = _branch_parser()
    args = finish(p, p.parse_args(argv))
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
    if d.get("family"):
        lines.append(f"  {d['family']}: {d['neutral_multipliers']} multipliers at +1 (a face stuck through "
                     "the period); this orbit is where the transient settled, another start may settle on another "
                     "member (another contact share)")
    return "\n".join(lines)


def _share(x) -> str:
    return "-" if x is None else f"{100 * x:.0f} %"


def _support_line(d: dict) -> str:
    """Contact and stick of one orbit in words (the JSON's ``contact_share``, ``peak_contact_force_N`` …)."""
    return (f"contact {_share(d['contact_share'])} of the time, peak contact force {d['peak_contact_force_N']:.4g} N, "
            f"faces stuck {_share(d['stick_share_right_face'])} (right) / {_share(d['stick_share_left_face'])} (left)")


def _say_law(args) -> None:
    """The geometry and law of the run on stderr where progress goes, once (when the work starts, after every
    refusal; :func:`reports.cli._scene_options.say_on_terminal`)."""
    line = getattr(args, "law_line", None)
    if line:
        say_on_terminal(args, line)
        args.law_line = None


def _watched(label: str, args, compute):
    """``(compute(), Events)``: the step loop compiled first and the shooting's events shown on a terminal
    (:mod:`sweep.progress`); the events keep the Newton attempts for a failure message."""
    from rotor.dynamics.period_map import warm_up
    from sweep.progress import Events, reporting

    _say_law(args)
    warm_up_shown(label, args, warm_up)
    events = Events(label, parameter_unit=("rpm", 30.0 / math.pi), enabled=args.progress)
    with reporting(events), events:
        try:
            return compute(), events
        except (OutsideDomainError, ConvergenceError) as exc:      # an unstable rotor's divergence is the rotor's
            if getattr(args, "unstable", None) is None:
                raise
            from rotor.linear.stability import divergence_message
            raise type(exc)(divergence_message(args.unstable, exc)) from None


def _tried(attempts: list[dict]) -> str:
    """The Newton attempts in words: how many, after how much transient, their periods and residuals."""
    if not attempts:
        return "no Newton attempt"
    res = ", ".join(f"{a['residual']:.2g}" for a in attempts)
    periods = sorted({a["period_revs"] for a in attempts})
    return (f"{len(attempts)} Newton attempt{'s' * (len(attempts) > 1)} after {attempts[0]['transient_revs']} to "
            f"{attempts[-1]['transient_revs']} transient revolutions, period {', '.join(map(str, periods))} rev, "
            f"residuals {res}")


def no_orbit_text(args, speed_rpm: float, steps_per_rev: int, attempts: list[dict], max_revs: int | None) -> str:
    """What was tried and what to change, for an orbit that did not converge (one short paragraph)."""
    scene = f"--scene {args.scene}{override_words(args)}"
    period = getattr(args, "period_revs", None)
    return (f"no periodic orbit at {speed_rpm:g} rpm: {_tried(attempts)} (at most {max_revs or '?'} transient "
            f"revolutions). What to try: --period-revs K if the response repeats every K revolutions"
            f"{f' (now {period})' if period else ''}; --steps-per-rev {2 * steps_per_rev} (now {steps_per_rev}) if "
            f"contact events are short; a transient start: ringcontact simulate {scene} --speed-rpm {speed_rpm:g} "
            "--steady --revolutions 64 "
            "shows whether the response settles at all (steady_converged false: quasi-periodic or chaotic, no "
            "stable periodic orbit); an unstable orbit no transient settles on: --from-orbit FILE, the `orbit --out` "
            "file of a neighbouring speed's orbit.")


def _orbit(args) -> int:
    from rotor.studies.orbit_methods import cross_check

    name, _, loose = _scene(args, "ringcontact orbit")
    if args.from_orbit is not None:
        if args.method != "shooting":
            raise InputError(f"--method = {args.method}: --from-orbit starts shooting's Newton; give --method shooting")
        orbit_file(args, name)                    # a bad file is refused before any computing
    check_method_args(args, "ringcontact orbit", args.speed_rpm, _overrides(args))
    pt, choice = (None, None) if args.method == "shooting" else hb_choice(args, args.speed_rpm, _overrides(args))
    if pt is not None:
        _warn_beyond(args, "ringcontact orbit")
    if pt is None:                          # shooting: asked for, or chosen by auto (choice says why)
        d, res, events = _shooting_orbit(args, name, loose, choice)
        return _orbit_done(args, d, res, events, name)
    d = {"scene": name, **pt.as_dict(), **law_fields(loose, pt.fields["max_edge_penetration_mm"] * 1e-3),
         "method_choice": choice}
    if args.method == "auto":               # each method checks the other where both apply
        sd, res, _ = _shooting_orbit(args, name, loose, hb=pt)
        d["cross_check"] = (cross_check(d, sd) if res.converged else
                            {"methods": ["hb", "shooting"], "shooting": "no orbit found by shooting at this speed"})
    _emit(args, d, hb_orbit_table(d))
    if not pt.orbit.converged:
        print(f"ringcontact orbit: error: no HB orbit at {args.speed_rpm:g} rpm (Newton stalled at relative residual "
              f"{pt.orbit.residual:.1e} with {pt.orbit.harmonics} harmonics); try --method shooting", file=sys.stderr)
        return 1
    return 0


def _shooting_orbit(args, name: str, loose, choice: dict | None = None, hb=None) -> tuple:
    """``(JSON, OrbitResult, Events)`` of the shooting orbit at ``--speed-rpm`` (``choice``: auto's, why shooting
    ran); ``hb``: an HB point whose orbit shooting starts on (its phase-0 state, one transient revolution, then
    Newton: the same orbit where several coexist, stable or not)."""
    from rotor.studies.orbit import orbit
    from rotor.periodic.shooting import ShootingOptions

    start, steps, began = {}, args.steps_per_rev, {}
    if hb is not None:
        import numpy as np
        st = hb.fields["phase0_state"]
        start = {"start": (np.array(st["q_m_rad"]), np.array(st["v_m_s_rad_s"])), "period_revs": hb.orbit.period_revs,
                 "options": ShootingOptions(transient_revs=1, round_growth=2.0)}
    elif getattr(args, "from_orbit", None) is not None:     # an orbit at another speed: Newton from its state
        got, rpm = orbit_file(args, name)
        steps = got.pop("steps_per_rev")
        start = {**got, "period_revs": args.period_revs or got["period_revs"],
                 "options": ShootingOptions(transient_revs=1, round_growth=2.0)}
        began = {"started_from_orbit": {"file": str(args.from_orbit), "speed_rpm": rpm}}
    _check_work(args, "ringcontact orbit", args.speed_rpm)
    res, events = _watched("ringcontact orbit", args, lambda: orbit(
        args.scene, args.speed_rpm, steps_per_rev=steps, **{"period_revs": args.period_revs, **start},
        richardson=args.richardson, friction_scheme=args.friction_scheme, **_overrides(args)))
    d = {**orbit_json(res, name), "friction_scheme": args.friction_scheme, **law_fields(loose, res.max_edge_penetration_m,
                                              res.contact.get("max_tilt_in_contact_arcmin"),
                                              [res.contact.get("law_validity")]),
         "attempts": events.attempts, "method": "shooting", **({"method_choice": choice} if choice else {}),
         **began, **_stability(args)}
    return d, res, events


def _orbit_done(args, d: dict, res, events, name: str) -> int:
    """Write a shooting orbit's JSON or table; exit 1 with one line where it did not converge."""
    if res.converged:
        _emit(args, d, _orbit_table(d))
        return 0
    why = no_orbit_text(args, args.speed_rpm, res.steps_per_rev, events.attempts, events.max_revs)
    d["advice"] = why
    _emit(args, d, f"orbit {name}: {why}")      # not the amplitudes of an iterate that is no orbit
    print(f"ringcontact orbit: error: no periodic orbit at {args.speed_rpm:g} rpm ({_tried(events.attempts)}); "
          f"{'see above' if not args.json else 'the JSON says what to try'}", file=sys.stderr)
    return 1


def _branch_table(d: dict, station: str) -> str:
    """The branch as a table: one row per orbit with the 1X velocity amplitude at ``station`` and, in the last
    column, how a point past a switch was reached and the speeds it skipped (``restart: secant, skipped …``); a
    row ``-- <kind> at … rpm --``
    between the two orbits a bifurcation lies between."""
    lines = [f"branch {d['scene']} {d['rpm_start']:g} -> {d['rpm_end']:g} rpm: {len(d['points'])} orbits, "
             f"period {d['period_revs']} rev, stopped: {d['stop']}, {d['wall_s']:.1f} s",
             f"  {'speed rpm':>10} {'stable':>7} {'radius':>9} {'1X mm/s':>10} {'leading':>13} {'contact':>8} "
             f"{'peak N':>10}  {station}"]
    between = {}
    for b in d["bifurcations"]:
        between.setdefault(b["after_point"], []).append(f"  -- {b['kind']} at {b['speed_rpm']:.1f} rpm --"
                                                        + (f" ({b['detail']})" if b.get("detail") else ""))
    for i, p in enumerate(d["points"]):
        lines += between.get(i, [])
        amp = p.get("velocity_amplitudes_mm_s_1X_to_5X", {}).get(station, [float("nan")])[0]
        lines.append(f"  {p['speed_rpm']:10.1f} {str(p['stable']):>7} {p['spectral_radius']:9.5f} {amp:10.4g} "
                     f"{p['leading_multiplier']:>13} {_share(p.get('contact_share')):>8} "
                     f"{p.get('peak_contact_force_N', float('nan')):10.4g}"
                     + ("  family held by friction" if p.get("unique") is False else "")
                     + (f"  restart: {p['restarted']}, skipped {p['skipped_rpm'][0]:.1f}-{p['skipped_rpm'][1]:.1f} rpm"
                        if p.get("skipped_rpm") else ""))
    lines.append("  bifurcations: " + ("; ".join(f"{b['kind']} at {b['speed_rpm']:.1f} rpm" for b in d["bifurcations"])
                                       or "none"))
    stalls = d.get("corrector_failures", [])
    if stalls:
        passed = sum(1 for f in stalls if f["outcome"].startswith("passed"))
        lines.append(f"  corrector stalls: {len(stalls)} ({passed} passed with a smaller step, "
                     f"{sum(1 for f in stalls if f['outcome'].startswith('restart'))} by a restart"
                     f"{', the last one stopped the branch' if stalls[-1]['outcome'].startswith('stopped') else ''}; "
                     "corrector_failures in the JSON)")
    return "\n".join(lines)


def _branch(args) -> int:
    from rotor.periodic.continuation import ContinuationOptions
    from rotor.studies.orbit import branch

    name, channels, loose = _scene(args, "ringcontact branch")
    if args.station is not None and not args.station.strip():
        raise InputError(f"--station = {args.station!r}: names nothing; give <station>.y or <station>.z (have "
                         f"{', '.join(channels)}), or leave --station out for {channels[0]}")
    station = args.station or channels[0]
    if station not in channels:
        raise InputError(f"--station = {station}: not a response channel of {name} "
                         f"(have {', '.join(channels)})")
    if args.from_state is not None and args.from_orbit is not None:
        raise InputError(f"--from-state = {args.from_state}: give --from-orbit or --from-state, not both")
    check_method_args(args, "ringcontact branch", min(args.rpm_start, args.rpm_end), _overrides(args))
    pt, choice = (None, None) if args.method == "shooting" else hb_choice(args, args.rpm_start, _overrides(args))
    if pt is not None:
        _warn_beyond(args, "ringcontact branch")
        return _hb_branch(args, name, loose, station, pt, choice)
    chosen = {"steps_per_rev": args.steps_per_rev, **chosen_orbit(args, name)}   # a bad --from-orbit first
    if args.from_state is not None:                                                  # and a bad --from-state
        from rotor.studies.steady_state import point_system
        chosen.update(state_start(args, name, point_system(args.scene, args.rpm_start, **_overrides(args))[2].n))
    _check_work(args, "ringcontact branch", min(args.rpm_start, args.rpm_end), int(args.max_points))
    t0 = time.perf_counter()
    res, events = _watched("ringcontact branch", args, lambda: branch(
        args.scene, args.rpm_start, args.rpm_end, options=ContinuationOptions(
            max_points=int(args.max_points), turn_back=None if args.turn_back_rpm is None else
            args.turn_back_rpm / (abs(args.rpm_end - args.rpm_start) / 10.0),      # the branch's speed scale
            centre_families=args.family_member == "centred", back_fill=args.back_fill),
        richardson=args.richardson, friction_scheme=args.friction_scheme, **chosen, **_overrides(args)))
    d = {"scene": name, "rpm_start": args.rpm_start, "rpm_end": args.rpm_end, "friction_scheme": args.friction_scheme,
         "family_member": args.family_member, "back_fill": args.back_fill, "period_revs": res.start.period_revs,
         "steps_per_rev": res.start.steps_per_rev, **res.as_dict(),
         "wall_s": round(time.perf_counter() - t0, 3), "method": "shooting",
         **({"method_choice": choice} if choice else {}), **_stability(args)}
    deepest_mm = max([p.get("max_edge_penetration_mm", 0.0) for p in d["points"]], default=0.0)
    tilt = max([p.get("max_tilt_in_contact_arcmin", 0.0) for p in d["points"]], default=0.0)
    d.update(law_fields(loose, max(deepest_mm * 1e-3, res.start.max_edge_penetration_m),    # deepest of the branch
                        max(tilt, res.start.contact.get("max_tilt_in_contact_arcmin", 0.0)),
                        [p.get("law_validity") for p in d["points"]] + [res.start.contact.get("law_validity")]))
    _emit(args, d, _branch_table(d, station))
    if args.plot is not None and d["points"]:
        from reports.bifurcation import bifurcation_figure
        for f in bifurcation_figure(d, station, args.plot):
            print(f"  wrote {f}", file=sys.stderr if args.json else sys.stdout)
    if not res.start.converged:
        why = no_orbit_text(args, args.rpm_start, res.start.steps_per_rev, events.attempts, events.max_revs)
        print(f"ringcontact branch: error: no orbit at the start (--rpm-start): {why}", file=sys.stderr)
        return 1
    if d["stop"] != "end reached":
        print(f"ringcontact branch: error: the branch stopped at "
              f"{d['points'][-1]['speed_rpm'] if d['points'] else args.rpm_start:.1f} rpm before --rpm-end = "
              f"{args.rpm_end:g} rpm ({d['stop']}); the orbits found are in the output", file=sys.stderr)
        return 1
    return 0


def _hb_branch(args, name: str, loose, station: str, pt, choice: dict) -> int:
    """The branch by harmonic balance (``--method hb``, or chosen by ``auto`` at ``--rpm-start``); with ``auto``
    the start orbit checked against shooting's at ``--rpm-start``."""
    from rotor.studies.orbit_methods import cross_check

    t0 = time.perf_counter()
    d = hb_branch_run(args, name, pt, choice, _overrides(args))
    if args.method == "auto":
        o = argparse.Namespace(**{**vars(args), "speed_rpm": args.rpm_start, "period_revs": None})
        sd, res, _ = _shooting_orbit(o, name, loose, hb=pt)
        d["cross_check"] = (cross_check(d["start"], sd) if res.converged else
                            {"methods": ["hb", "shooting"], "shooting": "no orbit found by shooting at --rpm-start"})
    d["wall_s"] = round(time.perf_counter() - t0, 3)
    deepest_mm = max([p["max_edge_penetration_mm"] for p in d["points"]], default=0.0)
    d.update(law_fields(loose, deepest_mm * 1e-3))
    _emit(args, d, hb_branch_table(d, station))
    if d["stop"] != "end reached":
        print(f"ringcontact branch: error: the HB branch stopped at {d['points'][-1]['speed_rpm']:.1f} rpm before "
              f"--rpm-end = {args.rpm_end:g} rpm ({d['stop']}); the orbits found are in the output", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
