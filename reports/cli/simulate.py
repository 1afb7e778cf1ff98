"""``ringcontact simulate``: time histories of a loose-support rotor at one speed.

Example::

    ringcontact simulate --scene paper-table4 --speed-rpm 10500 --revolutions 20 --out runs/b

or, for one steady-state point (transient detected and discarded, then 64 kept revolutions)::

    ringcontact simulate --speed-rpm 10500 --steady --revolutions 64 --out runs/b

writes ``runs/b/simulate.csv`` (time, named DOFs, relative edge offsets r1/r2, relative tilts,
stick/slip of each end face, contact flags, the contact force and moment on the bearing and the end-face
forces), ``runs/b/simulate.npz`` (full state, and the same force columns by the same names) and
``runs/b/simulate-summary.json``, as one unit (:func:`contact.files.write_run_files`): the previous
run's ``simulate.*`` files and summary are removed first, the new files written to temporary names and
renamed, the summary last with the SHA-256 of each file it describes (``"files"``), so an interrupted
run never leaves one run's CSV beside another's summary. Engineer units at the edge (``_rpm``, ``_mm``,
``_n``), SI inside.

The headline answer, how hard the ring hits its support (:mod:`rotor.dynamics.support_record`, which
states the sign conventions; the summary repeats them in ``contact_force_convention``): CSV and NPZ
columns ``contact_force_y_N``, ``contact_force_z_N``, ``contact_force_N`` (magnitude),
``contact_moment_y_Nm``, ``contact_moment_z_Nm``, ``contact_moment_Nm``: the radial contact force and
moment of the support's bore ON the bearing outer ring (the support gets the opposite), in the rotor's
stationary axes, the moment about the ring's mid-plane; ``face_right_force_y_N`` … ``face_left_force_z_N``
(end-face friction on the bearing), ``face_right_stuck``, ``face_left_stuck`` (1 = stuck). Summary:
``peak_contact_force_N`` at ``peak_contact_force_t_s``, ``mean_contact_force_N`` (over the samples in
contact), ``peak_contact_moment_Nm``, ``contact_share``, ``separation_share``, ``stick_share_right_face``,
``stick_share_left_face``, ``peak_face_force_N``, all over the recorded samples. The older keys stay:
``contact_fraction`` (an edge of the tilted ring past the clearance; ``contact_share`` counts the samples
with a force: they differ where the collision damping clips the force to zero on a fast separation and, with
``--tilt-ignored``, where only the tilt the law ignores puts an edge past the clearance) and
``stick_fraction_right``/``_left`` (the same numbers as ``stick_share_*_face``, except that with the tilt
ignored ``stick_share_left_face`` is None: there is one centred face). ``stick_right``/``stick_left`` stay in
the CSV beside ``face_*_stuck``, ``f_contact``/``face_force`` in the NPZ beside the named arrays.

The run starts from the static equilibrium under the scene's gravity, ``[[static_loads]]``, misalignment offset and
preload, the ring's contact and the end faces' friction solved statically
(:func:`rotor.dynamics.static_start.static_equilibrium`), so that a record is not a drop transient; ``--from-rest``
starts at the offset with nothing carried, as before. The summary's ``start`` says which (``--steady``:
:func:`rotor.dynamics.static_start.periodic_start`, the equilibrium with the linear forced response about it under
gravity or static loads the faces cannot hold, else the linear periodic solution) and, from the equilibrium, the
bearing's static deflection.

The law's validity (:mod:`rotor.model.law_validity`, the record every rotor job writes): ``law_validity`` in the
summary names the law, its file and sha256 and its verdict (``verified``, ``flagged``, ``analytic``), its fitted
penetration and checked tilt ranges, the shares of the contact time below, inside and above the fitted penetrations
and the largest tilt in contact; each finding is a warning line on stderr. A law its file flags is refused (exit
2, one line) unless ``--allow-flagged-law``.
"""
from __future__ import annotations

import argparse
import io
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from contact import interrupts, plausible
from contact.errors import ConvergenceError, InputError, OutputError, OutsideDomainError, RingContactError
from contact.files import write_run_files
from contact.units import ARCMIN, check_positive
from reports.cli import _budget
from reports.cli._edge import COUNTS, Parser, count, fail, out_dir, quantity
from reports.cli._scene_options import (add_law_check_option, add_progress_option, add_scene_options, finish,
                                        max_revs, say_on_terminal, scene_from_args, scene_top_rpm,
                                        warm_up_shown, warn_speeds_beyond_scene)
from rotor.dynamics import constraints as cons
from rotor.dynamics.static_start import start_record, static_equilibrium
from rotor.dynamics.support_record import CONVENTION, contact_columns, contact_summary
from rotor.model.law_validity import ALLOW_OPTION, check_allowed, law_line, record


def _parser() -> argparse.ArgumentParser:
    from rotor.studies.steady_state import SteadyStateOptions     # the detector's shortest transient: one bound
    p = Parser(prog="ringcontact simulate", description=__doc__.split("\n\n")[0])
    add_scene_options(p, transient=True)
    add_law_check_option(p)
    p.add_argument("--speed-rpm", type=quantity("run_speed_rpm"), required=True, help="spin speed (rpm)")
    p.add_argument("--revolutions", type=quantity("revolutions"), default=20.0, help="duration in revolutions (default 20)")
    p.add_argument("--steps-per-rev", type=count(*COUNTS["steps_per_rev"]), default=None,
                   help="time steps per revolution (default: chosen as orbit and the studies do, 256 or more where the "
                        "contact step limit needs it, a multiple of --record-per-rev; rotor.studies.steady_state.step_per_rev)")
    p.add_argument("--record-per-rev", type=count(*COUNTS["record_per_rev"]), default=64, help="recorded samples per revolution (default 64)")
    p.add_argument("--scheme", choices=("production", "reference"), default="production",
                   help="production (fast, default) or the paper's reference scheme (slow)")
    p.add_argument("--dofs", default=None,
                   help="comma-separated DOF names written to the CSV and analysed by --steady (default: y and z of "
                        "--stations)")
    p.add_argument("--stations", default=None,
                   help="comma-separated station names (the scene's disk, bearing, support or node names); default: "
                        "the CSV gets the scene's disks, loose-support bearing station and supports (Table 4: disk1, "
                        "disk2, 5, s), --steady analyses every disk, bearing and support station")
    p.add_argument("--steady", action="store_true",
                   help="run to steady state first (rotor.studies.steady_state.steady_state: displacement Poincaré samples "
                        "with the projected tail of the decay, subharmonic periods up to 8 revolutions), then "
                        "--revolutions kept revolutions (rounded up to whole periods) with 1X-5X velocity "
                        "amplitudes of --dofs in the summary")
    p.add_argument("--from-rest", action="store_true",
                   help="start from rest at the misalignment offset, no load carried (before issue 38 the only start); "
                        "default: the static equilibrium under the scene's gravity, static loads, misalignment and "
                        "preload, the ring's contact and end-face friction solved statically "
                        "(rotor.dynamics.static_start.static_equilibrium); the summary's start says which")
    _budget.add_accept_long(p)
    p.add_argument("--out", type=out_dir, default="simulate-out", help="output directory")
    add_progress_option(p)
    return p


# what a run may cost without --accept-long, and the measured step cost it is estimated from: one rule for every
# job (reports/cli/_budget.py)
WORK_BUDGET_S = _budget.WORK_BUDGET_S
MEMORY_BUDGET_BYTES = _budget.MEMORY_BUDGET_BYTES


def work_estimate(n_steps: int, n_records: int, n_dofs: int, scheme: str) -> tuple[float, float]:
    """``(seconds, bytes)`` of a run (:func:`reports.cli._budget.stepping`; the paper's reference scheme about
    200x slower than the production one, reports/published/perf-integrators.md)."""
    est = _budget.stepping(n_steps, n_records, n_dofs, 200.0 if scheme == "reference" else 1.0)
    return est.seconds, est.nbytes


def check_budget(args, n_steps: int, n_records: int, n_dofs: int) -> None:
    """Refuse, before anything is computed, a run estimated beyond the budget unless ``--accept-long``;
    announce a long one (:func:`reports.cli._budget.check`)."""
    est = _budget.stepping(n_steps, n_records, n_dofs, 200.0 if args.scheme == "reference" else 1.0)
    _budget.check("ringcontact simulate", est, args.accept_long,
                  f"--revolutions = {args.revolutions:g} rev at --steps-per-rev {args.steps_per_rev} and "
                  f"--record-per-rev {args.record_per_rev}", "fewer revolutions or records")


def main(argv: list[str] | None = None) -> int:
    p = _parser()
    args = finish(p, p.parse_args(argv))
    try:
        return _run(args)
    except RingContactError as e:
        return fail("ringcontact simulate", e)


def _check_options(args) -> None:
    """Options that contradict each other or name nothing, refused in the user's terms before anything is built."""
    for flag, text in (("--dofs", args.dofs), ("--stations", args.stations)):
        if text is not None and not any(s.strip() for s in text.split(",")):
            raise InputError(f"{flag} = {text!r}: names nothing; give comma-separated names, or leave {flag} out "
                             "for the default")
    if args.from_rest and args.steady:
        raise InputError("--from-rest: --steady starts from the static equilibrium with its forced response, not from "
                         "rest; give one of them")
    if args.max_revs is not None and not args.steady:
        raise InputError(f"--max-revs = {args.max_revs} rev: the transient cap of --steady, which is not given "
                         "(add --steady, or leave --max-revs out)")
    if args.steps_per_rev is not None and args.steps_per_rev % args.record_per_rev:
        n, k = args.steps_per_rev, args.record_per_rev
        raise InputError(f"--record-per-rev = {k}: must divide --steps-per-rev = {n} (a sample every whole number "
                         f"of steps; {n} steps would be recorded at {n // max(1, n // k)} a revolution): e.g. "
                         f"--steps-per-rev {-(-n // k) * k}, or --record-per-rev {max(d for d in range(1, k + 1) if n % d == 0)}")
    from rotor.studies.steady_state import SAMPLES_FOR_5X
    if args.steady and args.record_per_rev < SAMPLES_FOR_5X:
        raise InputError(f"--record-per-rev = {args.record_per_rev}: --steady resolves 1X-5X, which needs at least "
                         f"{SAMPLES_FOR_5X} samples a revolution")
    if args.steady and (args.scheme != "production" or int(round(args.revolutions)) < 1
                        or (args.steps_per_rev is not None and args.steps_per_rev % args.record_per_rev)):
        raise InputError("--steady: needs the production scheme, --revolutions >= 1 and --record-per-rev "
                         "dividing --steps-per-rev")   # refused before building or compiling anything


def _warn_unstable(model, omega_rad_s: float):
    """The unstable mode of the rotor's linearisation (locked and open: :func:`rotor.linear.stability.
    linearisation_unstable`), said in one warning line before the run; None for a stable rotor."""
    from rotor.linear.stability import linearisation_unstable, warning
    found = linearisation_unstable(model, omega_rad_s)
    if found is not None:
        print(warning("ringcontact simulate", found, "a run that grows is the rotor's instability, not the contact "
                      "law"), file=sys.stderr, flush=True)
    return found


def _integrate(args, run, system, model, dt: float, n_steps: int, rec: int, unstable):
    """The run (``--steady``: transient detected, then whole periods) as ``(trajectory, dt, steps, extra fields)``;
    a divergence of an ``unstable`` rotor is said to be the rotor's (:func:`rotor.linear.stability.divergence_message`)."""
    try:
        if args.steady:
            amp_names = _dof_names(args, model, primary_only=False)
            return interrupts.in_thread(_steady_run, args, system, model, amp_names,
                                        [model.dof_index(n) for n in amp_names])
        start = None if args.from_rest else static_equilibrium(system)
        q0, modes0 = (system.offset, (cons.STICK, cons.STICK)) if start is None else (start.q_m, start.modes)
        # in a thread: Ctrl-C is honoured at once, not after the compiled loop (measured: 20 s later)
        tr = interrupts.in_thread(run, system, dt, n_steps, q0=q0, modes0=modes0, record_every=rec)
        return tr, dt, n_steps, {"start": start_record(system, start)}
    except (OutsideDomainError, ConvergenceError) as exc:
        if unstable is None:
            raise
        from rotor.linear.stability import divergence_message
        raise type(exc)(divergence_message(unstable, exc)) from None


def _run(args) -> int:
    from rotor.dynamics.production import simulate_production, warm_up
    from rotor.dynamics.reference import simulate_reference

    _check_options(args)            # contradictions refused before building or compiling anything
    scene, model, system, law_info = _system(args)
    names = _dof_names(args, model, primary_only=True)
    idx = [model.dof_index(n) for n in names]
    omega = args.speed_rpm * 2 * math.pi / 60
    T = 2 * math.pi / omega
    dt = T / args.steps_per_rev
    n_steps = int(round(args.revolutions * args.steps_per_rev))
    if n_steps < 1:
        raise InputError(f"--revolutions = {args.revolutions:g} rev: less than one time step at {args.steps_per_rev} "
                         f"steps a revolution; at least {1 / args.steps_per_rev:.3g} rev")
    rec = max(1, args.steps_per_rev // args.record_per_rev)
    transient = int(args.max_revs or 8000) * args.steps_per_rev if args.steady else 0   # --steady: at most
    check_budget(args, n_steps + transient, n_steps // rec + 1, model.n_dofs)
    # warned once the input is accepted: a refused input says one line, its reason
    beyond = warn_speeds_beyond_scene("ringcontact simulate", scene, [args.speed_rpm])
    unstable = _warn_unstable(model, omega)
    say_on_terminal(args, f"ringcontact simulate: {law_line(scene.loose_support, scene_from_args(args).overrides)}")
    run = simulate_production if args.scheme == "production" else simulate_reference
    # compile or load the step loop now (the --steady detector uses it too), the seconds shown on a terminal
    compiled = warm_up_shown("ringcontact simulate", args, warm_up)
    t0 = time.perf_counter()
    tr, dt, n_steps, extra = _integrate(args, run, system, model, dt, n_steps, rec, unstable)
    run_s = time.perf_counter() - t0
    sup = system.support  # None: a scene without a loose support (no contact, no end faces)
    r1, r2 = cons.edge_offsets(tr.u, sup.width_m) if sup is not None else (np.zeros(len(tr.t)),) * 2
    d0 = sup.law.clearance_m if sup is not None else math.inf
    out = Path(args.out)
    files = _trajectory_files(tr, system, names, idx, r1, r2, d0)
    summary = {"scene": scene.name, "speed_rpm": args.speed_rpm, "revolutions": args.revolutions,
               "scheme": tr.scheme, "dt_s": dt, "steps": n_steps,
               "wall_s": round(compiled["compile_s"] + run_s, 3), "compile_s": round(compiled["compile_s"], 3),
               "run_s": round(run_s, 3), "compiled_from_cache": compiled["from_cache"],
               "law": sup.law.name if sup is not None else None, **law_info["note"],
               "clearance_mm": d0 * 1e3 if sup is not None else None,
               "max_r1_mm": float(r1.max() * 1e3), "max_r2_mm": float(r2.max() * 1e3),
               "contact_fraction": float(np.mean((r1 > d0) | (r2 > d0))),
               "stick_fraction_right": float(tr.modes[:, 0].mean()), "stick_fraction_left": float(tr.modes[:, 1].mean()),
               "least_residual_steps": int(tr.unconverged_steps), "max_omega_c_dt": tr.omega_dt_max,
               "steps_per_rev": args.steps_per_rev, "steps_per_rev_chosen": bool(args.steps_chosen),
               **step_limit_summary(tr.omega_dt_max, args.steps_per_rev),
               **validity_summary(float(max(r1.max(), r2.max()) - d0), law_info["validity_max_m"]),
               **tilt_validity_summary(np.hypot(tr.u[:, 2], tr.u[:, 3]), (r1 > d0) | (r2 > d0),
                                       law_info.get("validity_tilt_rad")),
               **contact_summary(tr.t, tr.f_contact, tr.modes, tr.face_force, sup.faces()[2] if sup is not None else 0),
               "contact_force_convention": CONVENTION,
               "law_validity": record(scene.loose_support, np.maximum(r1, r2) - d0, np.hypot(tr.u[:, 2], tr.u[:, 3])),
               "scene_max_speed_rpm": scene_top_rpm(scene), "speed_beyond_scene_range": beyond is not None,
               **extra}
    # one unit: the old run's files go, the new ones are renamed into place, the summary (with their
    # checksums) comes last; an interrupted run leaves no summary beside another run's CSV
    try:
        write_run_files(out, "simulate", files, summary)
    except OSError as exc:
        raise OutputError(f"--out = {args.out}: the run's files could not be written ({exc.strerror or exc}); "
                          "the folder holds no summary, so no complete run") from None
    print(json.dumps(summary, indent=2))
    if summary.get("step_limit_exceeded"):
        print(f"ringcontact simulate: warning: the contact step limit was crossed during the run (largest ω_c·Δt "
              f"{summary['max_omega_c_dt']:.3g} > {STEP_LIMIT_OMEGA_DT:g}: a contact event took fewer than about three "
              f"steps, impacts are under-resolved); run again with --steps-per-rev about "
              f"{summary['steps_per_rev_for_step_limit']} or more", file=sys.stderr)
    for line in summary["law_validity"].get("warnings", []):
        print(f"ringcontact simulate: warning: {line}", file=sys.stderr)
    return 0


def _dof_names(args, model, primary_only: bool) -> list[str]:
    """``--dofs``, else y and z of ``--stations``, else of the scene's response stations (a list that names
    nothing was refused by :func:`_check_options`)."""
    if args.dofs:
        return [s.strip() for s in args.dofs.split(",") if s.strip()]
    if args.stations:
        stations = [s.strip() for s in args.stations.split(",") if s.strip()]
        for s in stations:
            model.node_of(s)  # an unknown name: one line listing the scene's nodes and elements
    else:
        stations = model.response_stations(primary_only=primary_only)
    return [f"{s}.{c}" for s in stations for c in ("y", "z")]


def _system(args):
    """``(scene, model, system, law info)`` from the checked arguments; law info: ``note`` (summary fields
    naming a calibrated law's file and checksum), ``validity_max_m`` (m) and ``validity_tilt_rad`` (rad) of a
    calibrated law (None for an analytic law). The overrides are those of every rotor job
    (:mod:`reports.cli._scene_options`)."""
    from rotor.dynamics.build import system_from_model
    from rotor.model.assembly import assemble
    from rotor.model.loose_support_scene import with_law
    from rotor.model.scene import load_scene

    check_positive("speed_rpm", args.speed_rpm, "rpm", upper=plausible.top("run_speed_rpm"))
    check_positive("revolutions", args.revolutions, "rev", upper=1e6)
    if args.steps_per_rev is not None:
        check_positive("steps_per_rev", args.steps_per_rev, "steps", upper=1e6)
        check_positive("record_per_rev", args.record_per_rev, "samples", upper=args.steps_per_rev)
    choice = scene_from_args(args)
    kw = dict(choice.overrides)
    scene = load_scene(choice.scene)
    if "law" in kw:
        scene = with_law(scene, kw.pop("law"))
    model = assemble(scene)
    omega = args.speed_rpm * 2 * math.pi / 60
    system = system_from_model(model, scene, omega, tilt_ignored=kw.pop("tilt_ignored", False), mu=kw.pop("mu", None),
                               preload_N=kw.pop("preload_n", None), **kw)
    args.steps_chosen = args.steps_per_rev is None
    if args.steps_chosen:     # as orbit and the studies: the contact step limit with a margin, whole record samples
        from rotor.studies.steady_state import SAMPLES_FOR_5X, SteadyStateOptions, step_per_rev
        k = args.record_per_rev
        n = step_per_rev(system, SteadyStateOptions(samples_per_rev=k if k >= SAMPLES_FOR_5X else None))
        args.steps_per_rev = -(-n // k) * k          # a whole number of steps between samples
    ls = scene.loose_support
    check_allowed(ls, args.allow_flagged_law, ALLOW_OPTION)
    cal = ls.calibrated if ls is not None else None
    info = {"note": ls.law_note() if ls is not None else {},
            "validity_max_m": ls.validity_max_penetration_m if ls is not None else None,
            "validity_tilt_rad": float(cal.validity_tilt_max_rad) if cal is not None else None}
    return scene, model, system, info


def _steady_run(args, system, model, names: list[str], idx: list[int]):
    """``--steady``: detect the steady state, then integrate the kept whole periods from its end state.

    Returns ``(trajectory, dt, n_steps, summary fields)``.
    """
    from rotor.dynamics.static_start import periodic_start
    from rotor.studies.steady_record import record_after_steady
    from rotor.studies.steady_state import SteadyStateOptions, harmonic_amplitudes, steady_state
    from sweep.progress import Events, reporting

    keep = int(round(args.revolutions))   # the options were checked by _run before any work
    # detection by rotor.studies.steady_state (displacement Poincaré samples with the projected tail of the
    # decay, subharmonic periods); its own record is one period only: the kept revolutions are
    # integrated below from its end state so that every field of the trajectory is written
    opts = SteadyStateOptions(steps_per_rev=args.steps_per_rev, samples_per_rev=args.record_per_rev,
                              spectrum_revs=1, max_revs=max_revs(args))
    q_start, v_start, start = periodic_start(system, model, 0.0)
    with reporting(Events("ringcontact simulate --steady", enabled=args.progress)) as events, events:  # on a terminal
        ss = steady_state(system, model, options=opts, q0=q_start, v0=v_start)
    conv = ss.convergence
    tr, dt, n_steps, keep = record_after_steady(system, ss, keep, args.record_per_rev)
    amps = np.abs(harmonic_amplitudes(tr.v[:-1, idx] - tr.v[:-1, idx].mean(axis=0), keep))
    extra = {"start": start,
             "transient_revs": int(ss.transient_revs + ss.revolutions), "steady_converged": bool(conv.converged),
             "period_revs": int(conv.period), "poincare_change": float(conv.change),
             "poincare_remaining": float(conv.remaining), "record_revs": keep,
             "velocity_amplitudes_mm_s_1X_to_5X": {n: [round(float(a) * 1e3, 6) for a in amps[:, j]]
                                                   for j, n in enumerate(names)}}
    return tr, dt, n_steps, extra


def _trajectory_files(tr, system, names: list[str], idx: list[int], r1, r2, d0: float) -> dict[str, bytes]:
    """The contents of ``simulate.csv`` (time, the named DOFs, edge offsets, tilts, stick/slip, contact flags,
    contact force and moment, end-face forces: :func:`rotor.dynamics.support_record.contact_columns`) and
    ``simulate.npz`` (full state and the same force columns by name)."""
    cols = {"t_s": tr.t}
    for n, i in zip(names, idx):
        cols[f"{n}_m" if n.split(".")[-1] in ("y", "z") else f"{n}_rad"] = tr.q[:, i]
    cols.update({"r1_m": r1, "r2_m": r2, "tilt_y_rad": tr.u[:, 2], "tilt_z_rad": tr.u[:, 3],
                 "stick_right": tr.modes[:, 0], "stick_left": tr.modes[:, 1],
                 "contact_edge1": (r1 > d0).astype(int), "contact_edge2": (r2 > d0).astype(int)})
    forces = contact_columns(tr.f_contact, tr.face_force, tr.modes)
    cols.update(forces)
    buf = io.StringIO()
    buf.write(",".join(cols) + "\n")
    np.savetxt(buf, np.column_stack(list(cols.values())), delimiter=",", fmt="%.9g")
    b = io.BytesIO()
    np.savez_compressed(b, t=tr.t, q=tr.q, v=tr.v, u=tr.u, w=tr.w, f_contact=tr.f_contact, face_force=tr.face_force,
                        modes=tr.modes, dof_names=np.array(system.dof_names), **forces)
    return {"simulate.csv": buf.getvalue().encode("utf-8"), "simulate.npz": b.getvalue()}


STEP_LIMIT_OMEGA_DT = 2.0     # ω_c Δt above which a contact event is crossed in fewer than ~3 steps (rotor/dynamics/system.py)


def step_limit_summary(omega_dt_max: float, steps_per_rev: int) -> dict:
    """The contact step limit monitored over the run: the pre-run check (:func:`rotor.dynamics.system.check_time_step`)
    probes the law at 0.2 δ0, a run that penetrates deeper meets a stiffer law; the largest ω_c·Δt met is compared
    with :data:`STEP_LIMIT_OMEGA_DT` and, when crossed, the steps per revolution that would keep it named."""
    if not math.isfinite(omega_dt_max):
        return {}
    out = {"step_limit_omega_c_dt": STEP_LIMIT_OMEGA_DT, "step_limit_exceeded": bool(omega_dt_max > STEP_LIMIT_OMEGA_DT)}
    if out["step_limit_exceeded"]:
        out["steps_per_rev_for_step_limit"] = int(math.ceil(steps_per_rev * omega_dt_max / STEP_LIMIT_OMEGA_DT * 1.25))
    return out


def validity_summary(max_edge_penetration_m: float, validity_max_m: float | None) -> dict:
    """Summary fields on how deep the edges went, and whether a calibrated law left its fitted range."""
    out = {"max_edge_penetration_mm": max(max_edge_penetration_m, 0.0) * 1e3}
    if validity_max_m is not None:
        out["law_validity_max_penetration_mm"] = validity_max_m * 1e3
        out["beyond_law_validity"] = bool(max_edge_penetration_m > validity_max_m)
    return out


def tilt_validity_summary(tilt_rad: np.ndarray, in_contact: np.ndarray, validity_tilt_rad: float | None) -> dict:
    """The largest relative tilt while in contact (arcmin) against a calibrated law's checked tilt range.

    A law checked against a 3D reference up to a tilt (``ringcontact bearing`` with a tilt range) flags a
    run that went beyond it (``beyond_law_tilt_validity``); a law fitted at zero tilt only says so
    (``law_tilt_checked_up_to_arcmin`` = 0) and flags nothing: its tilt model was never compared.
    """
    if validity_tilt_rad is None:
        return {}
    t = np.abs(tilt_rad[in_contact]) if np.any(in_contact) else np.zeros(1)
    worst = float(t.max())
    out = {"max_tilt_in_contact_arcmin": worst / ARCMIN,
           "law_tilt_checked_up_to_arcmin": float(f"{validity_tilt_rad / ARCMIN:.9g}")}
    if validity_tilt_rad > 0:
        out["beyond_law_tilt_validity"] = bool(worst > validity_tilt_rad * (1 + 1e-9))
    return out


if __name__ == "__main__":
    sys.exit(main())
