"""The pseudo-arclength corrector and its pieces (:mod:`rotor.periodic.continuation`): the phase rows of a stuck
face's continuum, the unit tangent, Newton on the bordered system, a point's Floquet record, the landing on the
range's end, and the renewal of the state scales.
"""
from __future__ import annotations

import math

import numpy as np

from contact.errors import ConvergenceError, InputError, OutsideDomainError
from rotor.periodic.branch_types import NEUTRAL_TOL, RESCALE_RATIO, BranchPoint, ContinuationOptions, Evaluator
from rotor.periodic.floquet import floquet
from rotor.periodic.shooting import lm_step, min_norm_step, orbit_scales, record_reduced

#: halvings of a corrector step that does not lower the merit (:func:`correct`)
MAX_HALVINGS = 4
#: past ``max_iter`` the corrector goes on, up to this many times as many iterations, while each of its last two
#: iterations lowered the residual by :data:`CONTRACTION` or more (:func:`_contracting`). Measured on Table 4's
#: branch (reports/published/perf-branch-switches.md, commit b139996): 2 of its 18 restarts followed a corrector
#: that stopped at 10 iterations while its residual halved each iteration (6 170.8 rpm: 4.6e-6 to 5.7e-7; 12 606.8
#: rpm: 1.9e-7 to 7.8e-9), an inexact Jacobian's signature
EXTRA_ITERATIONS = 2
CONTRACTION = 0.7
#: stalled corrector steps in a row before the retrials follow the Levenberg–Marquardt curve, and as many more
#: before the corrector gives up (:func:`correct`)
STALL_ITERATIONS = 2


def neutral_rows(J, tol: float = NEUTRAL_TOL) -> np.ndarray:
    """Phase rows ``(k, n + 1)`` of a stuck face's continuum of orbits (singular values of the scaled ``M − I``
    below ``tol`` times the largest), padded with a zero parameter entry: its conserved levels.

    The rows are the left null vectors ``u`` (``uᵀ D(M − I)D⁻¹ = 0``): ``u·y`` is the same after a period as
    before for every state (a face stuck through the period holds its tangential offset exactly), so
    ``u·(y − y_prev) = 0`` keeps the offset at which the faces hold, as a slow change of the parameter does while
    they stay stuck (the levels :func:`rotor.periodic.shooting.level_step` keeps at fixed parameter). Right null
    vectors ``v`` instead (the rows before issue 36) hold a direction without physical meaning and let the
    offset drift along the branch: on the Friswell loose-aluminium scene (tests/rotor/periodic/
    test_friswell_loose_branch.py, 2 000 N preload) the ring's offset went from 0 at 2 300 rpm to 19.8 µm of
    its 20 µm clearance at 2 470 rpm, where the next predictor put it into radial contact, the holding force
    past μN = 200 N, the faces slipping 54 times in the period: a stall. Where ``U0ᵀ V0`` is ill-conditioned
    (reciprocal condition below 1e-6: the levels do not fix the member) the right null vectors are returned."""
    U, s, vt = np.linalg.svd(J[:, :-1])
    null = s < tol * s[0]
    U0, V0 = U[:, null], vt[null].T
    rows = U0.T
    if U0.shape[1]:
        sg = np.linalg.svd(U0.T @ V0, compute_uv=False)
        if not sg[-1] > 1e-6 * max(sg[0], 1e-300):
            rows = V0.T
    return np.hstack([rows, np.zeros((len(rows), 1))])


def unit_tangent(J, prev, rcond, phase=None):
    """Unit tangent: the minimum-norm solution of ``[J; P; prevᵀ] τ = [0; 0; 1]``, normalised (``P`` the
    phase rows: no motion along the continuum)."""
    rows = [J] + ([phase] if phase is not None and len(phase) else []) + [prev[None, :]]
    A = np.vstack(rows)
    b = np.zeros(A.shape[0])
    b[-1] = 1.0
    t, _ = min_norm_step(A, b, rcond)
    return t / np.linalg.norm(t)


def correct(ev: Evaluator, y_pred, tau, opts: ContinuationOptions, phase=None, anchor=None):
    """Newton on ``F(y) = [R; τ·(y − y_pred); P (y − anchor)]``; returns ``(y, J, M, iterations, residual)`` or
    None (``ev.failure`` then says why, with the end-face switches in the last iterate's period where there were
    any). The phase rows ``P`` (:func:`neutral_rows`) keep the orbit's levels in a stuck face's continuum those
    of ``anchor``; ``iterations`` counts the maps evaluated with their Jacobian.

    Globalised as :func:`rotor.periodic.shooting.newton_periodic` is, on the bordered system: a step is taken
    only if it lowers the merit ``‖F‖₂``; else it is halved (at most :data:`MAX_HALVINGS` times), each trial
    mapped without its monodromy (the sensitivity pass and the two parameter-differenced maps are about 3/4 of
    an evaluation's cost, and most retrials are rejected); where no halving lowers it, the retrials follow the
    Levenberg–Marquardt curve (:func:`rotor.periodic.shooting.lm_step`), which turns the step towards the
    merit's steepest descent as it shortens, and they follow it at once after :data:`STALL_ITERATIONS` stalled
    steps in a row (halved, and leaving more than half of the merit). After as many more, or when no trial on
    either path lowers the merit, the corrector gives up (the caller halves the arclength step); past ``max_iter``
    only while it contracts (:data:`EXTRA_ITERATIONS`). At a kink (a switch inside the period) the full Newton step
    overshoots and the plain iteration cycles; one rejected across a change of switches is kept (:func:`_straddled`)."""
    y, has_phase = np.array(y_pred, float), phase is not None and len(phase)

    def bordered(y, R):
        rows = [R, [tau @ (y - y_pred)]] + ([phase @ (y - anchor)] if has_phase else [])
        return np.concatenate(rows)

    def evaluate(y, jacobian: bool):
        """``(R, J, M, F, merit)`` at the scaled ``y``; merit inf where the scheme cannot step or R is not finite."""
        try:
            R, J, M = ev(y[:-1] * ev.s, y[-1] * ev.ls, jacobian=jacobian)
        except (OutsideDomainError, ConvergenceError, InputError):     # an iterate the scheme cannot step
            return None, None, None, None, math.inf
        if not np.all(np.isfinite(R)):
            return None, None, None, None, math.inf
        F = bordered(y, R)
        return R, J, M, F, float(np.linalg.norm(F))

    R, J, M, F, merit = evaluate(y, True)
    if R is None:
        ev.failure = "iterate 1 outside what the scheme can step, or its residual not finite"
        return None
    res, switches = float(np.max(np.abs(R))), ev.events      # the iterate's switches (a straddle: _straddled)
    trail, stalled = [res], 0
    for it in range(1, EXTRA_ITERATIONS * opts.max_iter + 1):
        A = np.vstack([J, tau[None, :]] + ([phase] if has_phase else []))
        dy, _ = min_norm_step(A, -F, opts.rcond)
        if res < opts.tol and np.max(np.abs(dy)) < 1e3 * opts.tol:
            return y, J, M, it, res
        if it >= opts.max_iter and not (it < EXTRA_ITERATIONS * opts.max_iter and _contracting(trail)):
            break
        step, lam, merit_t = None, 1.0, math.inf
        # the Newton line (halved), then, if no step on it lowers the merit or once stalled, the Levenberg–Marquardt
        # curve (its steps turn towards the merit's steepest descent as they shorten)
        paths = (False, True) if stalled < STALL_ITERATIONS else (True,)
        for curve in paths:
            lam = 0.5 if curve and len(paths) == 2 else 1.0        # the full step is the same on both
            for trial in range(MAX_HALVINGS + 1):
                step = lm_step(A, -F, opts.rcond, lam * float(np.linalg.norm(dy))) if curve and lam < 1.0 else lam * dy
                R_t, J_t, M_t, F_t, merit_t = evaluate(y + step, lam == 1.0)
                if merit_t < merit:
                    break
                _straddled(ev, switches, y, step, J_t is not None)
                lam *= 0.5
            if merit_t < merit:
                break
        if not merit_t < merit:
            ev.failure = (f"no step lowered the residual at iterate {it} (residuals "
                          + ", ".join(f"{r:.1e}" for r in trail[-4:]) + ")" + _switches(ev))
            return None
        y = y + step
        if J_t is None:                  # a halved trial accepted: its Jacobian now
            R_t, J_t, M_t, F_t, merit_t = evaluate(y, True)
            if R_t is None:
                ev.failure = f"iterate {it + 1} outside what the scheme can step"
                return None
        stalled = stalled + 1 if lam < 1.0 and merit_t > 0.5 * merit else 0
        R, J, M, F, merit = R_t, J_t, M_t, F_t, merit_t
        res, switches = float(np.max(np.abs(R))), ev.events
        trail.append(res)
        if stalled >= 2 * STALL_ITERATIONS:
            break                         # not contracting on either path
    ev.failure = (f"no convergence in {len(trail)} iterations (residuals "
                  + ", ".join(f"{r:.1e}" for r in trail[-4:]) + ")" + _switches(ev))
    return None


def _straddled(ev, switches: int, y, step, mapped: bool) -> None:
    """Keep ``(y, y + step, modes0)`` as the stall's straddle (``Evaluator.straddle``, the first of the stall) where
    the rejected full step ``y + step``, ``mapped`` with its switches, switches the faces another number of times in
    the period than ``y`` (``switches``): the map may jump between them (rotor/periodic/map_jump.py)."""
    if mapped and ev.events != switches and getattr(ev, "straddle", ()) is None:
        ev.straddle = (y.copy(), y + step, tuple(ev.modes0))


def _contracting(trail) -> bool:
    """True if each of the last two iterations lowered the residual by :data:`CONTRACTION` or more."""
    return len(trail) >= 3 and trail[-1] <= CONTRACTION * trail[-2] and trail[-2] <= CONTRACTION * trail[-3]


def _switches(ev) -> str:
    return f"; the faces switched {ev.events} times in the last iterate's period" if ev.events > 0 else ""


def make_point(ev, y, J, M, it, res, tau, opts, restarted: int = 0, why: str = "") -> BranchPoint:
    """The :class:`BranchPoint` at the scaled ``y`` just evaluated (its switches per period ``ev.events``)."""
    lam = y[-1] * ev.ls
    period = ev.pb.n_steps * ev.flow(lam).dt_s
    return BranchPoint(float(lam), y[:-1] * ev.s, floquet(M, period, tol=opts.multiplier_tol), it, res,
                       float(tau[-1]), restarted, ev.events, why, tuple(ev.modes0))



def land(ev, a, b, lam_end: float, opts, phase):
    """The orbit at exactly ``lam_end``, between the scaled points ``a`` and ``b`` on either side of it: the
    corrector on the hyperplane ``λ = lam_end`` from their linear interpolation; None if it fails."""
    e = np.zeros(len(b))
    e[-1] = 1.0
    return correct(ev, a + (lam_end / ev.ls - a[-1]) / (b[-1] - a[-1]) * (b - a), e, opts, phase, a)


def rescale(ev, y, tau, M, J, floor):
    """Renew the state scales to the orbit's own peak-to-peak range over one period at ``y`` (never below
    ``floor``) when they differ by more than :data:`RESCALE_RATIO`: returns ``(y, tau, J)`` in the new
    scaled variables (``J`` transformed, not recomputed) and sets ``ev.s``."""
    x, lam = y[:-1] * ev.s, y[-1] * ev.ls
    p, v, _ = record_reduced(ev.flow(lam), x, 0.0, ev.pb.n_steps, ev.modes0, max(1, ev.pb.n_steps // 256))
    new = np.maximum(orbit_scales(ev.flow(lam), p, v), floor)
    ratio = new / ev.s
    if max(ratio.max(), 1.0 / ratio.min()) <= RESCALE_RATIO:
        return y, tau, J
    old, ev.s = ev.s, new
    y = np.concatenate([y[:-1] / ratio, y[-1:]])
    tau = np.concatenate([tau[:-1] / ratio, tau[-1:]])
    J = np.hstack([(M - np.eye(len(new))) * (new[None, :] / new[:, None]), (J[:, -1] * old / new)[:, None]])
    return y, tau / np.linalg.norm(tau), J

