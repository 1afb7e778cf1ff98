"""The harmonic-balance side of ``ringcontact orbit`` and ``ringcontact branch`` (``--method hb|auto``): the
checks of ``--method``, ``--harmonics`` and ``--richardson`` against the scene, the method chosen
(:func:`rotor.studies.orbit_methods.auto_choice`), the HB branch, and their tables. The JSON keys are those of
the shooting path where they apply (:mod:`rotor.studies.hb_orbit`); stability is not computed by HB."""
from __future__ import annotations

import math

from contact.errors import InputError

#: the options that only the shooting path of ``branch`` has
SHOOTING_ONLY = (("from_orbit", "--from-orbit"), ("from_state", "--from-state"), ("turn_back_rpm", "--turn-back-rpm"),
                 ("plot", "--plot"))


def check_method_args(args, prog: str, rpm: float, overrides: dict) -> None:
    """InputError (exit 2, one line naming the option, the value typed and what is allowed) for: ``--method hb``
    on a scene where HB does not apply (end-face friction); ``--richardson`` with ``--method hb``; with
    ``--method hb`` a shooting-only option of ``branch``."""
    from rotor.studies.orbit_methods import check_method, hb_refusal

    check_method(args.method, prog)
    if args.method != "hb":
        return
    if args.richardson:
        raise InputError("--richardson: extrapolates shooting's time step to continuous time; --method hb has no "
                         "step (its error is the spectrum's tail, spectrum_tail in the JSON); use --method shooting "
                         "or auto with --richardson")
    for attr, flag in SHOOTING_ONLY:
        if getattr(args, attr, None) is not None:
            raise InputError(f"{flag} = {getattr(args, attr)}: a shooting option (HB computes no stability and "
                             "starts from the linear orbit); use --method shooting, or leave it out")
    why = hb_refusal(args.scene, rpm, **overrides)
    if why is not None:
        raise InputError(f"--method = hb: {why} (or --mu 0 for the frictionless ring); allowed here: shooting, auto")


def hb_choice(args, rpm: float, overrides: dict) -> tuple:
    """``(HBPoint or None, choice dict)`` at ``rpm``: ``--method hb`` runs HB (``--harmonics`` or the ladder),
    ``auto`` decides (:func:`rotor.studies.orbit_methods.auto_choice`); None: shooting runs."""
    from rotor.studies.hb_orbit import hb_point
    from rotor.studies.orbit_methods import auto_choice

    period = getattr(args, "period_revs", None) or 1
    if args.method == "hb":
        pt = hb_point(args.scene, rpm, harmonics=args.harmonics, period_revs=period, **overrides)
        return pt, {"method": "hb", "reason": "--method hb", "hb_spectrum_tail": pt.tail, "hb_cpu_s": pt.cpu_s}
    return auto_choice(args.scene, rpm, harmonics=args.harmonics, steps_per_rev=args.steps_per_rev,
                       period_revs=period, **overrides)


def hb_orbit_table(d: dict) -> str:
    """One HB orbit as ``orbit``'s short table (no multipliers: stability not computed)."""
    lines = [f"orbit {d['scene']} at {d['speed_rpm']:g} rpm by harmonic balance ({d['harmonics']} harmonics, "
             f"{d['n_time']} samples): period {d['period_revs']} rev = {d['period_s']:.6g} s, "
             f"{'converged' if d['converged'] else 'NOT converged'} in {d['newton_iterations']} Newton iterations "
             f"(residual {d['residual']:.2e}), spectrum tail {d['spectrum_tail']:.1e}, {d['wall_s']:.2f} s",
             f"  stability: {d['stability']}", f"  why HB: {d['method_choice']['reason']}",
             f"  {'channel':<14}" + "".join(f"{k}X mm/s".rjust(12) for k in range(1, 6))]
    for name, amps in d["velocity_amplitudes_mm_s_1X_to_5X"].items():
        lines.append(f"  {name:<14}" + "".join(f"{a:12.5g}" for a in amps))
    if "contact_share" in d:
        lines.append(f"  loose support over the period: contact {100 * d['contact_share']:.0f} % of the time, peak "
                     f"contact force {d['peak_contact_force_N']:.4g} N")
    cc = d.get("cross_check")
    if cc and cc.get("largest_1X_difference_rel") is not None:
        lines.append(f"  cross-check against shooting ({cc['shooting_steps_per_rev']} steps/rev): largest 1X difference "
                     f"{cc['largest_1X_difference_mm_s']:.3g} mm/s ({cc['largest_1X_difference_rel']:.1e} relative, "
                     f"{cc['channel']}); shooting's step error ~{cc['shooting_step_error']:.1e}"
                     + (f"; Richardson-extrapolated shooting {cc['richardson']['largest_1X_difference_rel']:.1e}"
                        if "richardson" in cc else ""))
    elif cc:
        lines.append(f"  cross-check: {cc.get('shooting')}")
    return "\n".join(lines)


def hb_branch_run(args, name: str, pt, choice: dict, overrides: dict) -> dict:
    """The HB branch's JSON (:func:`rotor.studies.hb_orbit.hb_scene_branch` with the start orbit's harmonics)."""
    from rotor.studies.hb_orbit import hb_scene_branch

    res = hb_scene_branch(args.scene, args.rpm_start, args.rpm_end, harmonics=pt.orbit.harmonics,
                          max_points=int(args.max_points), **overrides)
    res.pop("branch")
    return {"scene": name, "rpm_start": args.rpm_start, "rpm_end": args.rpm_end, "period_revs": 1,
            "steps_per_rev": None, **res, "method_choice": choice}


def hb_branch_table(d: dict, station: str) -> str:
    """The HB branch as ``branch``'s table: one row per orbit (speed, 1X amplitude at ``station``, edge
    penetration, contact share), a row per bifurcation between the orbits it lies between."""
    lines = [f"branch {d['scene']} {d['rpm_start']:g} -> {d['rpm_end']:g} rpm by harmonic balance "
             f"({d['harmonics']} harmonics): {len(d['points'])} orbits, stopped: {d['stop']}, {d['wall_s']:.1f} s; "
             "stability not computed",
             f"  {'speed rpm':>10} {'1X mm/s':>10} {'pen. mm':>10} {'contact':>8}  {station}"]
    between: dict = {}
    for b in d["bifurcations"]:
        between.setdefault(b["after_point"], []).append(f"  -- {b['kind']} at {b['speed_rpm']:.1f} rpm --")
    for i, p in enumerate(d["points"]):
        lines += between.get(i, [])
        amp = p["velocity_amplitudes_mm_s_1X_to_5X"].get(station, [math.nan])[0]
        share = p.get("contact_share")
        lines.append(f"  {p['speed_rpm']:10.1f} {amp:10.4g} {p['max_edge_penetration_mm']:10.3g} "
                     f"{'-' if share is None else f'{100 * share:.0f} %':>8}")
    lines.append("  bifurcations: " + ("; ".join(f"{b['kind']} at {b['speed_rpm']:.1f} rpm" for b in d["bifurcations"])
                                       or "none"))
    return "\n".join(lines)
