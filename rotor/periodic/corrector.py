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
from rotor.periodic.shooting import min_norm_step, orbit_scales, record_reduced

#: halvings of a Newton step whose residual grew (:func:`correct`)
BACKTRACKS = 3


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
    """Newton on ``[R; τ·(y − y_pred); P (y − anchor)]``; returns ``(y, J, M, iterations, residual)`` or None
    (``ev.failure`` then says why, with the end-face switches in the last iterate's period where there were
    any). The phase rows ``P`` (:func:`neutral_rows`) keep the orbit's levels in a stuck face's continuum those
    of ``anchor``.

    A step whose residual is larger than the last iterate's is halved (at most :data:`BACKTRACKS` times, each
    an iteration): where a switch inside the period makes the map's derivative jump (a kink), the full Newton
    step taken with the Jacobian of one side overshoots to the other and the plain iteration cycles."""
    y = y_pred.copy()
    has_phase = phase is not None and len(phase)
    last = None              # (y, dy, residual) of the last accepted iterate
    halvings, trail = 0, []
    for it in range(1, opts.max_iter + 1):
        x, lam = y[:-1] * ev.s, y[-1] * ev.ls
        try:
            R, J, M = ev(x, lam)
        except (OutsideDomainError, ConvergenceError, InputError) as e:   # an iterate the scheme cannot step
            ev.failure = f"iterate {it} outside what the scheme can step ({type(e).__name__})"
            return None
        res = float(np.max(np.abs(R)))
        if not math.isfinite(res):
            ev.failure = f"iterate {it}: residual not finite"
            return None
        trail.append(res)
        if last is not None and res > last[2] and halvings < BACKTRACKS:
            halvings += 1
            y = last[0] + 0.5 ** halvings * last[1]
            continue
        halvings = 0
        A = np.vstack([J, tau[None, :]] + ([phase] if has_phase else []))
        rhs = -np.concatenate([R, [tau @ (y - y_pred)]] + ([phase @ (y - anchor)] if has_phase else []))
        dy, _ = min_norm_step(A, rhs, opts.rcond)
        last = (y, dy, res)
        y = y + dy
        if res < opts.tol and np.max(np.abs(dy)) < 1e3 * opts.tol:
            return y - dy, J, M, it, res
    ev.failure = (f"no convergence in {opts.max_iter} iterations (residuals "
                  + ", ".join(f"{r:.1e}" for r in trail[-4:]) + ")"
                  + (f"; the faces switched {ev.events} times in the last iterate's period" if ev.events > 0 else ""))
    return None


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

