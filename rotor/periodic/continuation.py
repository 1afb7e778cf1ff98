"""Branches of periodic orbits by pseudo-arclength continuation in speed or any scalar scene parameter.

Unknowns ``y = (x, λ)``: the reduced state at phase 0 (:mod:`rotor.periodic.shooting`) and the parameter.
Equations ``R(x, λ) = Φ_λ(x) − x = 0`` plus the arclength condition ``τ·(y − y_pred) = 0`` (Keller 1977),
all in scaled variables (``x_j/s_j``, ``λ/λ_s``). The predictor steps ``ds`` along the unit tangent ``τ``;
the corrector is Newton on the bordered system ``[[D(M − I)D⁻¹, D ∂R/∂λ λ_s], [τᵀ]]`` solved in the
minimum-norm sense. A face stuck through the whole period makes the orbits a continuum (multipliers exactly
1, :mod:`rotor.periodic.floquet`): a branch is then a family, not a curve, and its conserved levels (left null
vectors ``u`` of the scaled ``M − I``, singular values below :data:`NEUTRAL_TOL`: the offsets at which the stuck
faces hold) enter as phase conditions ``u·(y − y_prev) = 0`` (:func:`rotor.periodic.corrector.neutral_rows`), so
that each point keeps the previous point's offsets, as a slow change of the parameter does while the faces stay
stuck, and the tangent does not change them. Step control:
``ds`` grows ×1.5 after a corrector of ≤ 3 iterations, shrinks ×0.6 after ≥ 7, is halved and retried on
failure (no convergence, or an iterate the scheme cannot step: beyond the contact law's domain), down to
``ds_min``.

Time scaling. The period depends on the speed, so every orbit keeps ``N`` steps per revolution with
``Δt = 2π/(Ω N)`` (a speed parameter) or the scene's fixed speed (any other parameter). The parameter
derivative ``∂R/∂λ`` is a central finite difference of the map, ``h = 10⁻⁶ |λ|`` (it rebuilds the system,
the step and the load at ``λ ± h``; an analytic derivative would need the period map's sensitivity to Δt
and to the load, which the period map does not carry).

Switches (the Table 4 rotor, friction on the ring's end faces). The corrector stops where the map jumps, as
measured at three stalls of the plain corrector (600–18 000 rpm, 2 240 steps per revolution; the monodromy
agreed there with central differences to 3e-6 of its scale one step back, so the Jacobian was not the cause):
at 3 083 and 3 954 rpm both faces stick through the period (four neutral multipliers) and the phase rows (then
right null vectors, which let the offsets drift along the branch) hold
the orbit at the place of the continuum where face 2's holding force has reached μN (1 499 and 1 496 N of
1 500 N): a parameter step of 4e-4 rpm makes the face slip for a step and the scaled residual jump from 5e-11
to 4e-4 (2.7e-4 at 3 954 rpm), while shooting at fixed speed (no phase rows) finds a stuck orbit 0.1 rpm on,
4e-2 away in the continuum. At 5 179 rpm (19 switches per period) a switch moves by a step: Newton cycles on
residuals 1.7e-4 / 4.4e-5 and, at some speeds of the discrete scheme, no exact fixed point exists (a transient
of 2 000 revolutions ends at 1.6e-5), while 1 rpm on shooting converges to 5e-12. With ``pass_switches``
(:class:`ContinuationOptions`) such a stall is passed by a restart (:func:`rotor.periodic.restarts.restart`): shooting at a fixed
parameter a little further on, from the secant predictor, from a short transient of the last orbit (first in
a stuck continuum: the face slips a little and holds again) or from the linear periodic solution; the point
is marked ``restarted`` and no fold is read across it. ``follow_scales`` renews the state scales with the
orbit's own range (the amplitude grows with the speed squared: with the start's scales the steps creep).

Through switches (issue 24). The maps are those of :class:`Problem` (``locate_events``: friction events
located inside the step, the map continuous through stick onsets and slip reversals; contact onset is not yet
located). The corrector (:func:`rotor.periodic.corrector.correct`) halves a Newton step whose residual grew (a
kink of the map where a switch appears); no step growth across a change of the switches per period; in a
stuck face's continuum the first failed corrector restarts (measured 5 150–5 190 rpm on the scene's default
reading: the iterates made the faces slip, 2 to 34 switches, and cycled at 1e-3, while a transient from the
last orbit 2–5 rpm on converged). Where the corrector fails down to ``ds_min`` and no restart passes, a last
resort (:func:`rotor.periodic.restarts.bridge`) shoots further on (secant predictor, then the linear periodic
solution); only if that fails too does the branch stop. Every stall is kept (``Branch.failures``: where, why,
how it was passed) and each restarted point carries why the corrector failed before it (``BranchPoint.why``).

Bifurcations between consecutive points: a fold where the parameter component of the tangent changes sign and
the secants into and out of the pair confirm the turn (:func:`rotor.periodic.branch_events.confirmed_folds`);
period doubling, Neimark–Sacker, and branch points (a real multiplier through +1 with no turn: a pitchfork)
where the count of multipliers outside the unit circle changes (:func:`rotor.periodic.floquet.crossing`). Each is located by regula falsi on
the arclength between the two points, on its test quantity (``dλ/ds``, or ``|μ| − 1`` of the largest multiplier
of the crossing kind), every trial a corrected orbit. A crossing between two orbits whose switches per period
differ is reported as a ``discontinuous`` bifurcation (Leine & van Campen 2002: the
multiplier jumps across the unit circle at the switch), with both sides in its ``detail``
(:func:`rotor.periodic.branch_events.bifurcations_between`). :func:`switch_period_doubling` starts the doubled-period branch at a period doubling from the
eigenvector of the multiplier −1.
"""
from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from contact.errors import ConvergenceError, InputError, OutsideDomainError
from sweep.progress import report, reporting
from rotor.dynamics import constraints as cons
from rotor.periodic.branch_events import bifurcations_between, confirmed_folds
from rotor.periodic.branch_types import (COLD, GRID, NEUTRAL_TOL, PARAM_REL_STEP, RESCALE_RATIO, RESTART_NAMES,
                                         RESTART_STEP, SECANT, TRANSIENT, Bifurcation, Branch, BranchPoint,
                                         ContinuationOptions, Evaluator, Problem, parameter_problem, speed_problem,
                                         start_modes)
from rotor.periodic.corrector import correct, land, make_point, neutral_rows, rescale, unit_tangent
from rotor.periodic.family_centre import centred
from rotor.periodic.map_jump import jump_across, jump_text
from rotor.periodic.period_flow import advance
from rotor.periodic.restarts import bridge, jump_past_fold, restart, shot
from rotor.periodic.shooting import ShootingOptions, shoot

__all__ = ["COLD", "GRID", "NEUTRAL_TOL", "PARAM_REL_STEP", "RESCALE_RATIO", "RESTART_NAMES", "RESTART_STEP", "SECANT", "TRANSIENT",
           "Bifurcation", "Branch", "BranchPoint", "ContinuationOptions", "Evaluator", "Problem", "continue_branch",
           "parameter_problem", "speed_problem", "start_modes", "switch_period_doubling"]


def _start(problem, ev, state0, lam0, lam_end, opts, tangent0):
    """The first point (shot at fixed ``lam0``), its ``(y, J, phase, tau)``, or None if shooting failed."""
    s = ev.s
    first = shoot(ev.flow(lam0), state0, t0_s=0.0, steps_per_rev=problem.steps_per_rev, period_revs=problem.period_revs,
                  modes0=problem.modes0, scales=s, options=ShootingOptions(tol=opts.tol, rcond=opts.rcond))
    if not first.converged:
        return None
    y = np.concatenate([first.state / s, [lam0 / ev.ls]])
    R, J, M = ev(first.state, lam0)
    guide = np.zeros(len(y))
    guide[-1] = math.copysign(1.0, lam_end - lam0)
    phase = neutral_rows(J)
    if tangent0 is None:
        tau = unit_tangent(J, guide, opts.rcond, phase)
    else:
        tau = np.asarray(tangent0, float) / np.linalg.norm(tangent0)
    return make_point(ev, y, J, M, 0, float(np.max(np.abs(R))), tau, opts), y, J, phase, tau


#: a point this close to the range's end (relative) has reached it: the landing corrector solves λ = λ_end in
#: scaled units, and λ/λ_s·λ_s may come back one rounding short (measured: a Jeffcott-ring branch then landed
#: on the end 330 times over, rotor/periodic/jeffcott_scene.py seed 2301554633, rotor 3)
END_RTOL = 1e-12


def continue_branch(problem: Problem, state0, lam0: float, lam_end: float, *, scales, lam_scale: float | None = None,
                    options: ContinuationOptions | None = None, tangent0=None) -> Branch:
    """Follow the branch through the orbit near ``state0`` at ``lam0`` until the parameter passes ``lam_end``.

    ``scales`` (2 n_r,): state scales (m, rad; m/s, rad/s); ``lam_scale``: parameter scale (default
    ``|lam_end − lam0|/10``). ``tangent0`` (scaled, 2 n_r + 1): start direction instead of the branch's own
    (branch switching). The first point is corrected at fixed ``lam0`` by :func:`rotor.periodic.shooting.shoot`.
    With ``options.pass_switches`` a corrector that fails ``restart_after`` times in a row (the map jumps at a
    stick/slip switch, or the phase conditions hold the orbit at a place of a stuck face's continuum where the
    face starts to slip) is followed by a shooting restart past it (:func:`rotor.periodic.restarts.restart`).
    """
    opts = options or ContinuationOptions()
    t_start = time.perf_counter()
    floor = np.asarray(scales, float)
    ev = Evaluator(problem, floor.copy(), float(lam_scale or abs(lam_end - lam0) / 10.0))
    got = _start(problem, ev, state0, lam0, lam_end, opts, tangent0)
    if got is None:
        return Branch((), (), problem.period_revs, f"no orbit at the start ({problem.name} = {lam0:g})",
                      time.perf_counter() - t_start)
    pt, y, J, phase, tau = got
    points, bifs, restarts, fails, failures, stalls = [pt], [], 0, 0, [], []
    direction = math.copysign(1.0, lam_end - lam0)
    ds, stop, far = opts.ds, "max_points", pt          # far: the point farthest towards lam_end so far
    seen = None                                        # the watch at the last point: (value, scaled point)
    while len(points) < opts.max_points:
        if opts.max_wall_s is not None and time.perf_counter() - t_start > opts.max_wall_s:
            stop = "wall time limit"
            break
        y_prev = y
        side, ahead, seen = _watched(opts, ev, y, tau, ds, seen)
        back = opts.turn_back is not None and (far.parameter / ev.ls - y[-1]) * direction > opts.turn_back
        got = None if ahead or back else _corrected_member(ev, y + ds * tau, tau, opts, phase, y_prev, stalls)
        if ahead or (side is not None and got is not None and (opts.watch(ev, got[0]) > 0.0) != side):
            stop = "grazing"
            break
        guide, why = tau, ""
        if got is None:                    # a stall of the corrector, or run back from a fold by turn_back
            fails += 1
            stalls.append(f"turned back at a fold at {problem.name} = {far.parameter:.6g}, followed "
                          f"{abs(far.parameter - y[-1] * ev.ls):.6g} back" if back else ev.failure)
            got = _past_stall(ev, points, y, tau, ds, phase, direction, fails, opts, far if back else None, stalls)
            if got is None:
                ds = 0.0 if back else 0.5 * ds
                if ds < opts.ds_min:
                    stop = "turned back at a fold, no orbit past it" if back else "step below ds_min"
                    failures.append((float(y[-1] * ev.ls), _stall_text(stalls), "stopped: no restart found"))
                    break
                continue
        if len(got) == 7:                  # a restart: (y, J, M, iterations, residual, how, guide)
            y, J, M, it, res, restarted, guide = got
            why = _stall_text(stalls)
            failures.append((float(points[-1].parameter), why, f"restart ({RESTART_NAMES[restarted]}) at "
                             f"{problem.name} = {y[-1] * ev.ls:.6g}"))
            restarts += 1
            ds = opts.ds
        else:
            (y, J, M, it, res), restarted = got, 0
            if stalls:
                failures.append((float(points[-1].parameter), _stall_text(stalls), f"passed with a step ds = {ds:.3g}"))
        fails, stalls = 0, []
        tau_new = unit_tangent(J, guide, opts.rcond, neutral_rows(J))
        pt = make_point(ev, y, J, M, it, res, tau_new, opts, restarted, why)
        if not back:           # across a jump past a fold the two orbits lie on different branches
            bifs += bifurcations_between(ev, points[-1], pt, len(points), y_prev, tau, ds, opts, phase)
        if (pt.parameter - lam_end) * direction > 0 and (landed := _at_end(ev, y_prev, y, lam_end, opts, phase,
                                                                           failures)):
            y, J, M, it, res, how, end_why = landed        # the last orbit at lam_end itself, not beyond it
            pt = make_point(ev, y, J, M, it, res, tau_new, opts, how or restarted, end_why if how else why)
            restarts, bifs = restarts + (how > 0), before_end(bifs, len(points), lam_end, direction)
        points.append(pt)
        far = pt if (pt.parameter - far.parameter) * direction > 0 else far
        report("branch_point", points=len(points), max_points=opts.max_points, parameter=pt.parameter, start=lam0,
               end=lam_end)
        y, tau, J = rescale(ev, y, tau_new, M, J, floor) if opts.follow_scales else (y, tau_new, J)
        phase = neutral_rows(J)
        ds = ds if restarted else _next_step(ds, it, pt.events != points[-2].events, opts)
        if (stop := _ended(pt.parameter, lam0, lam_end, direction, opts)) != "max_points":
            break
    return Branch(tuple(points), tuple(confirmed_folds(points, bifs, stop == "grazing")), problem.period_revs, stop,
                  time.perf_counter() - t_start, restarts, tuple(failures))


def _watched(opts, ev, y, tau, ds: float, seen):
    """``(side, ahead, seen)``: the side of the watch's zero the point ``y`` is on (None without a watch), whether
    the zero lies within the step ``ds`` ahead, and this point's ``(value, y)`` for the next call. Ahead: the
    predictor is on the other side, or the secant through the last point ``seen`` and this one meets zero
    within the step (a grazing fold turns the branch at the zero: a predictor past it is no orbit's neighbour,
    may touch, and does not see the zero; measured on a Jeffcott scene of rotor/periodic/jeffcott_scene.py,
    where the down sweep then jumped onto the stable contact branch)."""
    if opts.watch is None:
        return None, False, seen
    g_now = opts.watch(ev, y)
    side = g_now > 0.0
    ahead = (opts.watch(ev, y + ds * tau) > 0.0) != side
    if not ahead and seen is not None and (dist := float(np.linalg.norm(y - seen[1]))) > 0.0:
        ahead = (g_now + (g_now - seen[0]) / dist * ds > 0.0) != side
    return side, ahead, (g_now, y)


def before_end(bifs: list, index: int, lam_end: float, direction: float) -> list:
    """``bifs`` without those found between point ``index − 1`` and the orbit past ``lam_end`` that the branch
    landed back from (its point ``index`` is the orbit at ``lam_end``) which lie beyond ``lam_end``: that stretch is
    not on the branch. Measured on Table 4 (run at commit 9feddee): a Neimark-Sacker crossing at 18 054.5 rpm with
    ``--rpm-end 18000``."""
    return [b for b in bifs if b.index != index or (b.parameter - lam_end) * direction <= 0]


def _at_end(ev, y_prev, y, lam_end: float, opts, phase, failures: list):
    """The orbit at exactly ``lam_end`` between the scaled points ``y_prev`` and ``y`` on either side of it, as
    ``(y, J, M, iterations, residual, how, why)``: the corrector on ``λ = lam_end``
    (:func:`rotor.periodic.corrector.land`, ``how`` 0, ``why`` ""); if it fails (``why`` says how), shooting at
    ``lam_end`` from the interpolated state (Newton at fixed parameter, ``how`` 0), then from a transient of
    ``y_prev`` (:data:`TRANSIENT`, a restart), the way it was passed entered in ``failures``. None if all fail
    (the branch ends beyond ``lam_end``, said in ``failures``)."""
    landed = land(ev, y_prev, y, lam_end, opts, phase)
    if landed is not None:
        return (*landed, 0, "")
    why = f"1 corrector failure, last: {ev.failure}"
    y_end = y_prev + (lam_end / ev.ls - y_prev[-1]) / (y[-1] - y_prev[-1]) * (y - y_prev)
    for how in (SECANT, TRANSIENT):
        got = shot(ev, y_end, opts, how, y_prev)
        if got is not None:
            failures.append((lam_end, why, f"{'shot at fixed' if how == SECANT else 'restart (transient) at'} "
                                           f"{ev.pb.name} = {lam_end:.6g}, the end"))
            y_new, J, M, it, res, _ = got
            return y_new, J, M, it, res, 0 if how == SECANT else TRANSIENT, why
    ev.failure = why
    failures.append((float(y[-1] * ev.ls), why,
                     f"no orbit at {ev.pb.name} = {lam_end:.6g}: the last orbit lies beyond"))
    return None


def _corrected_member(ev, y_pred, tau, opts, phase, anchor, stalls: list):
    """:func:`_corrected`, and with ``opts.centre_families`` its point moved to the member of its friction-held
    family farthest from slipping and from the bore (:func:`rotor.periodic.family_centre.centred`; the
    corrector's iteration count kept for the step control)."""
    got = _corrected(ev, y_pred, tau, opts, phase, anchor, stalls)
    if got is None or not opts.centre_families:
        return got
    moved = centred(ev, got[0], got[1], opts)
    return got if moved is None else (*moved[:3], got[3], moved[4])


def _corrected(ev, y_pred, tau, opts, phase, anchor, stalls: list):
    """The corrector from ``y_pred`` (:func:`rotor.periodic.corrector.correct`, the phase rows ``phase`` holding the
    levels of ``anchor``), and where it fails with phase rows, again without them: where the faces slip
    in the next orbit's period (the continuum of the stuck orbits has ended there), that orbit is isolated and the
    phase rows over-determine it, and the least-squares steps stall. Measured on the Friswell rotor in a loose
    aluminium housing at 200 N of preload (tests/rotor/scenes/friswell-591-loose-aluminium.toml, ``--preload-n
    200``, 2 300 -> 2 800 rpm): at 2 407 rpm, the face slipping once a period, the rows' corrector stalled at
    2.3e-3 and this retry converged (a cold restart before); at 2 320, 2 322 and 2 429 rpm both failed (3
    restarts, 4 before). Returns what :func:`rotor.periodic.corrector.correct` returns; the failure with the rows
    is kept in ``stalls`` with how it was passed."""
    if not stalls:
        ev.straddle = None                     # the stall's first corrector: a straddle of its own (map_jump.py)
    got = correct(ev, y_pred, tau, opts, phase, anchor)
    if got is not None:
        return got
    failed, ends = ev.failure, [getattr(ev, "modes_end", None)]
    if len(phase):
        got = correct(ev, y_pred, tau, opts)
        if got is not None:
            stalls.append(f"{failed}; converged without the phase rows (the faces slip: the continuum has ended)")
            return got
        ends.append(getattr(ev, "modes_end", None))
    got = _on_end_modes(ev, y_pred, tau, opts, ends, phase, anchor)
    if got is not None:
        stalls.append(f"{failed}; {got[1]}")
        return got[0]
    ev.failure = failed
    return None


def _on_end_modes(ev, y_pred, tau, opts, ends: list, phase, anchor):
    """The corrector again from ``y_pred``, its maps started from the end-face modes a failed corrector's last
    iterate ended its period in (``ends``, each tried where it differs from ``ev.modes0``: with the phase rows
    ``phase``, then without them), and kept if the orbit it converges on ends its period in the modes it started
    from (a fixed point of the modes as of the state). Returns ``(what correct returns, how)`` with ``ev.modes0``
    the new modes, or None with them kept.

    A stuck face's orbit and a slipping face's are fixed points of different maps (:func:`rotor.periodic.restarts.shot`):
    where a face's mode at phase 0 changes along the branch the corrector from the old modes cannot reach the new
    orbit. Measured on Table 4's branch (reports/published/perf-branch-switches.md, commit b139996): 4 of its 18
    restarts (2 427.6, 2 466.6, 5 139.0 and 9 026.4 rpm) were transients whose orbit started in other modes, one
    skipping 223 rpm. On the Friswell rotor in a loose aluminium housing at 200 N of preload
    (tests/rotor/scenes/friswell-591-loose-aluminium.toml, ``--preload-n 200``) the corrector past 2 407.1 rpm,
    both faces slipping at phase 0, stalled at a residual of 3.0e-6 with the left face sticking once a period and
    stuck at its end; from those modes, with the phase rows, it converges in 5 iterations (1.9e-12), without them
    it does not (a transient restart skipped 47.7 rpm there). On Table 4's branch at this code (600-5 180 rpm,
    benchmarks/bench_branch_switches.py's settings) it never converged: the stalls there lie in the stuck faces'
    continuum, where a face slips under the predictor and holds again at another offset."""
    kept = ev.modes0
    for modes in dict.fromkeys(m for m in ends if m is not None and m != kept):
        ev.modes0 = modes
        for rows in ((phase, None) if len(phase) else (None,)):
            got = correct(ev, y_pred, tau, opts, rows, anchor if rows is not None else None)
            if got is not None and ev.modes_end == modes:
                return got, (f"converged from the modes its iterate ended the period in ({_modes_text(kept)} → "
                             f"{_modes_text(modes)})")
    ev.modes0 = kept
    return None


def _modes_text(modes) -> str:
    """End-face modes at phase 0 in words (right face first)."""
    return ", ".join(f"{side} {'stuck' if m == cons.STICK else 'slipping'}" for side, m in zip(("right", "left"), modes))


def _past_stall(ev, points, y, tau, ds: float, phase, direction: float, fails: int, opts, fold=None, stalls=None):
    """A point past a stall of the corrector, or None (then the step is halved). Past the fold point ``fold``
    (the branch has run back from it by ``turn_back``): the orbit a run-up jumps to
    (:func:`rotor.periodic.restarts.jump_past_fold`), else the last resort from the fold point
    (:func:`rotor.periodic.restarts.bridge`, 5 to 870 rpm further on Table 4). Else, with ``pass_switches``, a
    restart (:func:`rotor.periodic.restarts.restart`) after ``restart_after`` failures in a row, after the first
    in a stuck face's continuum (phase rows) or just after a restart (the predictor has made the face slip,
    which no smaller step of the corrector undoes); the last resort (:func:`rotor.periodic.restarts.bridge`)
    once the next halving would take ``ds`` below ``ds_min``. Before a restart, the last of ``stalls`` (the
    stall's reasons) gets the period map's jump where the corrector rejected a step across a change of the
    switches in the period (:func:`_jump`)."""
    if fold is not None:     # the jump a run-up makes; else the last resort from the fold point, further on
        y_fold = np.concatenate([fold.state / ev.s, [fold.parameter / ev.ls]])
        return jump_past_fold(ev, y_fold, direction, opts) or bridge(ev, [fold], y_fold, direction, opts)
    if not opts.pass_switches:
        return None
    got = None
    if fails == (1 if points[-1].restarted or (len(phase) and not opts.centre_families) else opts.restart_after):
        if stalls:                            # said with the restart's reason: the stall was the map's jump
            stalls[-1] += _jump(ev)
        got = restart(ev, points, y, tau, opts, len(phase) > 0, ds * abs(tau[-1]))
    if got is None and ds * 0.5 < opts.ds_min:
        got = bridge(ev, points, y, direction, opts)
    if got is not None and opts.back_fill and abs(got[0][-1] - y[-1]) > BACK_FILL_MIN:
        got = _back_filled(ev, got, y[-1], opts)
    return got


#: a restart landing farther than this (scaled parameter; 17 rpm with a tenth of 600-18 000 rpm as the scale) is
#: followed back (:func:`_back_filled`)
BACK_FILL_MIN = 0.01
#: most orbits of the branch followed back from a far restart's landing
BACK_FILL_POINTS = 60


def _back_filled(ev, got, lam_last: float, opts):
    """The restart ``got`` (``(y, J, M, iterations, residual, how, guide)``, scaled, landed far from the last orbit
    at the scaled parameter ``lam_last``) moved back along the branch it landed on: that branch is continued from
    the landing towards ``lam_last`` (no restarts, at most :data:`BACK_FILL_POINTS` orbits) up to its fold or
    ``lam_last``, and the restart lands at the orbit reached nearest ``lam_last`` (the branch then goes on from
    there and covers the stretch again). A restart's secant and cold tries step ×4 in the parameter and a new branch
    may begin between two tries. Measured on Table 4 (friction by projection, centred families, benchmarks/
    bench_branch_switches.py at commit e87342c): the last stuck orbit at 5 235.6 rpm, the restart at 5 316.4 rpm;
    followed down from 5 330 rpm that branch reaches a fold at 5 257 rpm. Unchanged where the branch cannot be
    followed back."""
    y, how, guide = got[0], got[5], got[6]
    lam, ls = y[-1] * ev.ls, ev.ls
    with reporting(None):                     # the branch's progress says its own points only
        back = continue_branch(replace(ev.pb, modes0=tuple(ev.modes0)), y[:-1] * ev.s, lam, lam_last * ls,
                               scales=ev.s.copy(), lam_scale=ls,
                               options=replace(opts, pass_switches=False, back_fill=False,
                                               max_points=BACK_FILL_POINTS, turn_back=None, watch=None,
                                               max_wall_s=None))
    run = [back.points[0]]
    for p in back.points[1:]:                       # up to the fold: the parameter moves towards lam_last
        if abs(p.parameter - lam_last * ls) >= abs(run[-1].parameter - lam_last * ls):
            break
        run.append(p)
    # the orbit one before the nearest: at a fold's own neighbour the tangent is nearly normal to the parameter, and
    # the branch going on from it may take the fold's other (unstable) side (measured at 5 254 rpm, same run)
    pt = run[-2] if len(run) > 2 else None
    if pt is None:
        return got
    kept = ev.modes0
    ev.modes0 = pt.modes or kept
    try:
        R, J, M = ev(pt.state, pt.parameter)
    except (OutsideDomainError, ConvergenceError, InputError):
        R = None
    if R is None or not float(np.max(np.abs(R))) < opts.tol:
        ev.modes0 = kept
        return got
    y_near = np.concatenate([pt.state / ev.s, [pt.parameter / ls]])
    return y_near, J, M, pt.iterations, float(np.max(np.abs(R))), how, guide


def _jump(ev) -> str:
    """The jump of the period map across the stall's straddle (:func:`rotor.periodic.map_jump.jump_across`) in
    words, measured with the modes the straddle's maps started from; empty without a straddle or a jump."""
    if getattr(ev, "straddle", None) is None:
        return ""
    y_a, y_b, modes0 = ev.straddle
    found = jump_across(lambda y: ev.residual_switches(y, modes0), y_a, y_b)
    return jump_text(found, ev.pb.name, float(found["at"][-1] * ev.ls) if found else 0.0)


def _next_step(ds: float, iterations: int, switched: bool, opts) -> float:
    """The arclength step after a corrector of ``iterations``: ×1.5 after ≤ 3 (not across a change of the
    switches per period, ``switched``: the next switch may be close), ×0.6 after ≥ 7."""
    if iterations <= 3:
        return min(ds * (1.0 if switched else 1.5), opts.ds_max)
    return max(ds * 0.6, opts.ds_min) if iterations >= 7 else ds


def _ended(lam: float, lam0: float, lam_end: float, direction: float, opts) -> str:
    """Why the branch ends at the parameter ``lam`` ("end reached", "turned back beyond the start"), or
    "max_points" (it goes on unless the points run out)."""
    if (lam - lam_end) * direction >= -END_RTOL * abs(lam_end):     # a landing at lam_end rounds either way
        return "end reached"
    if (lam0 - lam) * direction > opts.back_margin * abs(lam_end - lam0):
        return "turned back beyond the start"
    return "max_points"


def _stall_text(stalls: list) -> str:
    """The corrector failures of one stall in words: how many, and the last one's reason."""
    if not stalls:
        return ""
    return f"{len(stalls)} corrector failure{'s' * (len(stalls) > 1)}, last: {stalls[-1]}"


def switch_period_doubling(problem: Problem, branch: Branch, bif: Bifurcation, lam_end: float, *, scales,
                           lam_scale: float | None = None, options: ContinuationOptions | None = None) -> Branch:
    """The doubled-period branch born at the period doubling ``bif`` of ``branch``.

    At the point after the crossing the monodromy has a real multiplier near −1 with eigenvector ``φ``;
    for the map over two periods it is a multiplier near +1 and the new branch leaves the old one along
    ``(φ, 0)`` (a pitchfork of the doubled map). The continuation of period ``2 period_revs`` starts at the
    old orbit with that tangent made orthogonal to the old branch's secant through the crossing (scaled
    ``(x/s, λ/λ_s)``; ``φ`` alone may lean along the old branch, which then crosses the corrector's hyperplane
    too and takes the corrector back), so its first corrector works on a hyperplane a step ``ds`` away from
    the old branch, where only the new branch crosses; it runs towards ``lam_end``. A first orbit that repeats
    after one period (the corrector fell back onto the old branch, whose orbits solve the doubled problem too) is
    not the new branch: the continuation is started again with a shorter step (:data:`SWITCH_TRIES`).
    """
    pt = branch.points[bif.index]
    mu, vec = np.linalg.eig(_monodromy_at(problem, pt))
    j = int(np.argmin(np.abs(mu + 1.0)))
    s = np.asarray(scales, float)
    ls = float(lam_scale or abs(lam_end - pt.parameter) / 10.0)
    t0 = np.concatenate([np.real(vec[:, j]) / s, [0.0]])
    if bif.index > 0:     # off the old branch: its secant through the crossing removed from the start direction
        prev = branch.points[bif.index - 1]
        sec = np.concatenate([(pt.state - prev.state) / s, [(pt.parameter - prev.parameter) / ls]])
        if np.linalg.norm(sec) > 0:
            sec /= np.linalg.norm(sec)
            t0 = t0 - (t0 @ sec) * sec
    t0 /= np.linalg.norm(t0)
    doubled = replace(problem, period_revs=2 * problem.period_revs, modes0=start_modes(problem, pt))
    # no restarts by shooting on the doubled branch: every orbit of the old branch solves the doubled problem
    # too, and a shot from near the switch lands back on it (measured on Table 4 at 10 628 rpm)
    opts = replace(options or ContinuationOptions(), pass_switches=False)
    for _ in range(SWITCH_TRIES):
        b2 = continue_branch(doubled, pt.state, pt.parameter, lam_end, scales=s, lam_scale=ls, options=opts,
                             tangent0=t0)
        if len(b2.points) < 2 or not _of_one_period(problem, b2.points[1], s):
            return b2
        # the first corrector fell back onto the old branch (an orbit of one period solves the doubled problem):
        # its hyperplane a shorter step away, where the new branch is the nearer solution
        opts = replace(opts, ds=opts.ds * SWITCH_SHRINK)
    return b2


#: tries of the doubled branch's first step (:func:`switch_period_doubling`), each ``SWITCH_SHRINK`` times shorter.
#: Measured on Table 4 (``paper-table4-inertial``, T/2240, step grid) at 10 628 rpm: from the step 0.05 the first
#: orbit was one of the old branch 1 rad/s below the crossing (heading down), from 0.01 a doubled one 4e-5 above it
SWITCH_TRIES = 3
SWITCH_SHRINK = 0.2
#: an orbit whose map over its half period returns within this of its scale is one of the old branch
ONE_PERIOD_TOL = 1e-6


def _of_one_period(problem: Problem, point, scales) -> bool:
    """True if the doubled branch's ``point`` repeats after one period of ``problem`` (to :data:`ONE_PERIOD_TOL`
    of ``scales``): an orbit of the old branch, not a doubled one."""
    fl = problem.flow(point.parameter)
    x1 = advance(fl, point.state, 0.0, problem.n_steps, start_modes(problem, point), jacobian=False).state
    return float(np.max(np.abs(x1 - point.state) / scales)) < ONE_PERIOD_TOL


def _monodromy_at(problem: Problem, pt: BranchPoint) -> np.ndarray:
    return advance(problem.flow(pt.parameter), pt.state, 0.0, problem.n_steps, start_modes(problem, pt)).monodromy

