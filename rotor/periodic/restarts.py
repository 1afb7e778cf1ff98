"""Restarts past a switch where the pseudo-arclength corrector cannot go (:mod:`rotor.periodic.continuation`):
shooting at a fixed parameter a little further on, from the secant predictor, from a short transient of the
last orbit, or from the linear periodic solution.
"""
from __future__ import annotations

import math

import numpy as np

from contact.errors import ConvergenceError, InputError, OutsideDomainError
from rotor.dynamics.initial import linear_initial_state
from rotor.periodic.branch_types import (COLD, COLD_STEP, COLD_TRIES, GRID, RESTART_STEP, RESTART_TRANSIENT_REVS,
                                         SECANT, TRANSIENT)
from rotor.periodic.period_flow import make_flow, to_full
from rotor.periodic.shooting import ShootingOptions, shoot, shoot_from_transient

#: parameter steps (scaled) of the last-resort :func:`bridge` past a stretch no restart passes (with a tenth of
#: 600–18 000 rpm as the scale: 5 to 870 rpm)
BRIDGE_STEPS = (3e-3, 1e-2, 3e-2, 0.1, 0.25, 0.5)
#: parameter step (scaled) past a fold of :func:`jump_past_fold` (with a tenth of 600–18 000 rpm: 17 rpm)
JUMP_STEP = 1e-2


def restart(ev, points, y, tau, opts, continuum: bool, step_hint: float = 0.0):
    """A point past a switch where the corrector cannot go: shooting (:func:`rotor.periodic.shooting.shoot`,
    Newton with halving and Levenberg–Marquardt retrials, no arclength or phase row) at the fixed parameter
    ``λ_k + 2h`` from the secant predictor of the last two points (the tangent at the first point), ``h``
    the last step's parameter advance (at least :data:`RESTART_STEP` and half ``step_hint``, the parameter
    advance of the predictor that failed), four times as long after each failure,
    ``restart_tries`` times, at most ``ds_max`` (scaled parameter); then at ``λ_k + 2h`` a transient from the
    last orbit before shooting, then from the linear periodic solution at :data:`COLD_TRIES` steps growing ×4
    (:func:`shot`). In a stuck face's
    continuum (``continuum``: the last orbit has neutral directions) the transient comes first: the orbit the
    corrector cannot reach lies where the face, having slipped a little, holds again, which a transient
    finds and Newton from the secant (at the offset where the face slips) does not. A landing beyond a try that
    found no orbit is bisected back towards it (:func:`nearer`). Returns
    ``(y, J, M, iterations, residual, how, guide)`` or None, ``guide`` the unit parameter direction of travel
    (for the new tangent)."""
    x_k, lam_k = y[:-1] * ev.s, y[-1] * ev.ls
    # the secant of the last two points and its step, not across a restart (measured on Table 4, friction by
    # projection, centred families, 4 950 -> 5 450 rpm: past a fold's jump of 268 rpm a transient restart 2 × 268 rpm
    # on skipped to 5 750 rpm; from the tangent with the start's step ds, 141 rpm on)
    secant = len(points) > 1 and not points[-1].restarted
    if secant:
        prev = points[-2]
        d = np.concatenate([(x_k - prev.state) / ev.s, [(lam_k - prev.parameter) / ev.ls]])
    else:
        d = tau.copy()
    if abs(d[-1]) < 1e-3 * np.linalg.norm(d):       # at a turn: no direction in the parameter to restart along
        return None
    d = d / np.linalg.norm(d)
    last = (abs(lam_k - points[-2].parameter) / ev.ls if secant else 0.0 if len(points) > 1 else
            opts.ds * abs(d[-1]))
    h = max(last, RESTART_STEP, 0.5 * step_hint)
    tries = [(SECANT, min(2.0 * h * 4.0 ** k, opts.ds_max)) for k in range(opts.restart_tries)]
    cold = [(COLD, min(COLD_STEP * 4.0 ** k, opts.ds_max)) for k in range(COLD_TRIES)]
    tries = ([(TRANSIENT, 2.0 * h)] + tries if continuum else tries + [(TRANSIENT, 2.0 * h)]) + cold
    missed = []                                   # the steps that found no orbit
    for how, step in tries:
        y_pred = y + (step / abs(d[-1])) * d
        got = shot(ev, y_pred, opts, how, y)
        if got is None:
            missed.append(step)
        else:                     # the new tangent points on in the parameter: across a jump the secant need not
            if (below := max((m for m in missed if m < step), default=0.0)) > 0.0:
                got = nearer(ev, y, got, below, step, opts)
            guide = np.zeros(len(y))
            guide[-1] = math.copysign(1.0, d[-1])
            return (*got, guide)
    return None


#: bisections of :func:`nearer`
NARROW_TRIES = 3


def nearer(ev, y, got, missed: float, step: float, opts):
    """The restart's orbit ``got`` (found ``step`` on from the last orbit ``y``, scaled, after a shot ``missed`` on
    found none) replaced by the nearest orbit of its branch a bisection of ``(missed, step)`` finds
    (:data:`NARROW_TRIES` Newton shots, each from the nearest orbit found so far, moved to the trial parameter):
    the restart skips as little as it can. The steps grow ×4, so a restart lands up to four times as far as the
    first parameter with an orbit. Measured on Table 4 (benchmarks/bench_branch_switches.py, friction by
    projection, centred families, commit e87342c): from the last stuck orbit at 5 235.6 rpm the shot 20.2 rpm on
    found none and the one 80.8 rpm on did, a skip of 80.8 rpm, while the branch that orbit lies on runs down to a
    fold at 5 257 rpm (that branch followed down from 5 330 rpm)."""
    lo, hi, y_hi = missed, step, got[0]
    for _ in range(NARROW_TRIES):
        mid = 0.5 * (lo + hi)
        y_pred = y_hi.copy()
        y_pred[-1] = y[-1] + (mid / hi) * (y_hi[-1] - y[-1])
        trial = shot(ev, y_pred, opts, SECANT, y)
        if trial is None:
            lo = mid
        else:
            hi, y_hi, got = mid, trial[0], trial
    return got


def bridge(ev, points, y, direction: float, opts):
    """The last resort where both the corrector (down to ``ds_min``) and :func:`restart` failed: shooting at
    parameter steps :data:`BRIDGE_STEPS` (scaled) towards ``direction`` (±1), at each from the secant predictor
    of the last two points (:data:`SECANT`; Newton may land on an unstable orbit, which a transient never
    reaches) and then from the linear periodic solution (:data:`COLD`). Returns what :func:`restart` returns,
    or None; the caller reports the speeds skipped."""
    x_k, lam_k = y[:-1] * ev.s, y[-1] * ev.ls
    d = np.zeros(len(y))
    if len(points) > 1:
        prev = points[-2]
        d = np.concatenate([(x_k - prev.state) / ev.s, [(lam_k - prev.parameter) / ev.ls]])
    slope = d[:-1] / d[-1] if d[-1] * direction > 0 else np.zeros(len(y) - 1)   # state change per parameter
    guide = np.zeros(len(y))
    guide[-1] = direction
    for step in BRIDGE_STEPS:
        for how in (SECANT, COLD):
            y_pred = y + direction * step * np.concatenate([slope, [1.0]])
            got = shot(ev, y_pred, opts, how, y)
            if got is not None:
                return (*got, guide)
    return None


def jump_past_fold(ev, fold_y, direction: float, opts):
    """The orbit a run-up jumps to past a fold: at the fold's parameter plus :data:`JUMP_STEP` (scaled) in
    ``direction``, the transient from the orbit at the fold (``fold_y``, scaled, the farthest point reached),
    then the linear periodic solution, then the step-grid map's orbit (:data:`GRID`: an unstable orbit, which no
    transient of the branch's map reaches; :func:`shot`); what :func:`restart` returns, or None.

    Measured on Table 4 (2 240 steps per revolution, events located, benchmarks/bench_branch_switches.py): the
    branch from 600 rpm folds at 16 930 rpm. At commit 3291749 this jump found no orbit at 16 947 or 16 999 rpm and
    the branch stopped there: the cold try's search did converge at 16 947.2 rpm (residual 2e-13 in the orbit's own
    scales), on an orbit with both faces slipping at phase 0, which :func:`shot` then mapped from the branch's start
    modes (both stuck), missing it by 0.24 of its scale. With each orbit mapped from its own modes (commit
    c245803), the transient of the fold's orbit lands at 16 947.2 rpm (unstable, spectral radius 1.83) and the
    branch goes on to 18 000 rpm."""
    guide = np.zeros(len(fold_y))
    guide[-1] = direction
    for step in (JUMP_STEP, 4.0 * JUMP_STEP):
        y_pred = fold_y.copy()
        y_pred[-1] += direction * step
        for how in (TRANSIENT, COLD, GRID):
            got = shot(ev, y_pred, opts, how, fold_y)
            if got is not None:
                return (*got, guide)
    return None


def shot(ev, y_pred, opts, how: int, y_last):
    """The orbit at the parameter of ``y_pred``: ``how`` 1 (:data:`SECANT`) :func:`rotor.periodic.shooting.shoot`
    from its state; 4 (:data:`GRID`) the step-grid map's orbit from the linear periodic solution's transients, then
    Newton on the branch's map from it; 2 (:data:`TRANSIENT`) :func:`rotor.periodic.shooting.shoot_from_transient` from the last
    orbit ``y_last`` (rounds of 2, 4, … revolutions, at most :data:`RESTART_TRANSIENT_REVS`); 3 (:data:`COLD`)
    the same from the linear periodic solution (:func:`rotor.dynamics.initial.linear_initial_state`; 24, 36, …
    revolutions, at most 4 :data:`RESTART_TRANSIENT_REVS`: the start of a new segment). ``(y, J, M, iterations, residual, how)`` if the orbit's residual
    in the branch's scales, mapped from the end-face modes the orbit itself has at phase 0, is below ``tol``; then
    ``ev.modes0`` holds those modes (the branch goes on with them); else None, ``ev.modes0`` unchanged.

    The modes matter: a stuck face's orbit and a slipping face's are fixed points of different maps (a map that
    starts a slipping face stuck holds it for a step). Measured on Table 4 past the 16 930 rpm fold (2 240 steps per
    revolution, events located): the cold search at 16 947.2 rpm converges on an orbit with both faces slipping
    throughout (residual 2e-13 in its own scales), which the branch's map from its start modes (both stuck)
    misses by 0.24 of the orbit's scale; from its own modes it closes to 1e-13. An orbit found by a transient or on
    the step grid is closed again by Newton in the branch's scales (which may be far below the orbit's own: 1/680
    to 1/30 000 of them with the 600 rpm start's scales there) before that check."""
    pb, lam = ev.pb, y_pred[-1] * ev.ls
    try:
        flow = ev.flow(lam)
    except InputError:      # a parameter the scheme cannot step (its step past the contact limit): no orbit here
        return None
    sopts = ShootingOptions(tol=opts.tol, rcond=opts.rcond, max_iter=2 * opts.max_iter, transient_revs=2,
                            round_growth=2.0, max_transient_revs=RESTART_TRANSIENT_REVS)
    try:
        if how == SECANT:
            sh = shoot(flow, y_pred[:-1] * ev.s, t0_s=0.0, steps_per_rev=pb.steps_per_rev, period_revs=pb.period_revs,
                       modes0=ev.modes0, scales=ev.s, options=sopts)
            own = ev.modes0
        elif how == GRID:
            # the step-grid map's orbit (events on step boundaries) from the linear periodic solution's transients,
            # then Newton on the branch's own map from it (the two differ by the scheme's O(h²))
            plain = make_flow(flow.system, flow.dt_s, flow.backend, locate_events=False,
                              friction_scheme=flow.handle.options.friction_scheme)
            q, v = linear_initial_state(flow.system, 0.0)
            grid = shoot_from_transient(plain, q, v, steps_per_rev=pb.steps_per_rev, period_revs=pb.period_revs,
                                        options=ShootingOptions(tol=opts.tol, rcond=opts.rcond), modes0=pb.modes0)
            if not grid.converged:
                return None
            sh = shoot(flow, grid.state, t0_s=0.0, steps_per_rev=pb.steps_per_rev, period_revs=pb.period_revs,
                       modes0=grid.modes, scales=np.maximum(grid.scales, ev.s), options=sopts)
            own = grid.modes
        else:
            if how == TRANSIENT:
                q, v = to_full(flow, y_last[:-1] * ev.s, 0.0)
                start = ev.modes0
            else:
                q, v = linear_initial_state(flow.system, 0.0)
                sopts = ShootingOptions(tol=opts.tol, rcond=opts.rcond, max_transient_revs=4 * RESTART_TRANSIENT_REVS)
                start = pb.modes0
            sh = shoot_from_transient(flow, q, v, steps_per_rev=pb.steps_per_rev, period_revs=pb.period_revs,
                                      options=sopts, modes0=start)
            own = sh.modes        # where the transient ended: the modes at phase 0 of the orbit Newton closed
        if sh.converged and how != SECANT:      # closed in the orbit's own scales: Newton again in the branch's
            sh = shoot(flow, sh.state, t0_s=0.0, steps_per_rev=pb.steps_per_rev, period_revs=pb.period_revs,
                       modes0=own, scales=ev.s, options=sopts)
        if not sh.converged:
            return None
    except (OutsideDomainError, ConvergenceError, InputError):
        return None
    got = _on_own_modes(ev, sh.state, lam, own, opts.tol)
    if got is None:
        return None
    J, M, res = got
    return np.concatenate([sh.state / ev.s, [y_pred[-1]]]), J, M, sh.newton_iterations, res, how


def _on_own_modes(ev, state, lam: float, modes, tol: float):
    """``(J, M, residual)`` of the branch's map at ``(state, lam)`` started from the end-face ``modes``, which
    ``ev.modes0`` then holds, if its residual (branch's scales) is below ``tol``; else None, ``ev.modes0`` kept."""
    kept, ev.modes0 = ev.modes0, tuple(int(m) for m in modes)
    try:
        R, J, M = ev(state, lam)
    except (OutsideDomainError, ConvergenceError, InputError):
        ev.modes0 = kept
        return None
    res = float(np.max(np.abs(R)))
    if not res < tol:
        ev.modes0 = kept
        return None
    return J, M, res

