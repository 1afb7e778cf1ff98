"""Branches of periodic orbits by pseudo-arclength continuation in speed or any scalar scene parameter.

Unknowns ``y = (x, λ)``: the reduced state at phase 0 (:mod:`rotor.periodic.shooting`) and the parameter.
Equations ``R(x, λ) = Φ_λ(x) − x = 0`` plus the arclength condition ``τ·(y − y_pred) = 0`` (Keller 1977),
all in scaled variables (``x_j/s_j``, ``λ/λ_s``). The predictor steps ``ds`` along the unit tangent ``τ``;
the corrector is Newton on the bordered system ``[[D(M − I)D⁻¹, D ∂R/∂λ λ_s], [τᵀ]]`` solved in the
minimum-norm sense. A face stuck through the whole period makes the orbits a continuum (multipliers exactly
1, :mod:`rotor.periodic.floquet`): a branch is then a family, not a curve, and its null directions (singular
values of the scaled ``M − I`` below :data:`NEUTRAL_TOL`) enter as phase conditions ``v·(y − y_prev) = 0``,
so that each point stays at the previous point's place in the continuum and the tangent has no component
along it. Step control:
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
at 3 083 and 3 954 rpm both faces stick through the period (four neutral multipliers) and the phase rows hold
the orbit at the place of the continuum where face 2's holding force has reached μN (1 499 and 1 496 N of
1 500 N): a parameter step of 4e-4 rpm makes the face slip for a step and the scaled residual jump from 5e-11
to 4e-4 (2.7e-4 at 3 954 rpm), while shooting at fixed speed (no phase rows) finds a stuck orbit 0.1 rpm on,
4e-2 away in the continuum. At 5 179 rpm (19 switches per period) a switch moves by a step: Newton cycles on
residuals 1.7e-4 / 4.4e-5 and, at some speeds of the discrete scheme, no exact fixed point exists (a transient
of 2 000 revolutions ends at 1.6e-5), while 1 rpm on shooting converges to 5e-12. With ``pass_switches``
(:class:`ContinuationOptions`) such a stall is passed by a restart (:func:`_restart`): shooting at a fixed
parameter a little further on, from the secant predictor, from a short transient of the last orbit (first in
a stuck continuum: the face slips a little and holds again) or from the linear periodic solution; the point
is marked ``restarted`` and no fold is read across it. ``follow_scales`` renews the state scales with the
orbit's own range (the amplitude grows with the speed squared: with the start's scales the steps creep).

Bifurcations between consecutive points: a fold where the parameter component of the tangent changes sign and
the secants into and out of the pair confirm the turn (:func:`_confirmed_folds`);
period doubling, Neimark–Sacker, and branch points (a real multiplier through +1 with no turn: a pitchfork)
where the count of multipliers outside the unit circle changes (:func:`rotor.periodic.floquet.crossing`). Each is located by regula falsi on
the arclength between the two points, on its test quantity (``dλ/ds``, or ``|μ| − 1`` of the largest multiplier
of the crossing kind), every trial a corrected orbit. :func:`switch_period_doubling` starts the doubled-period branch at a period doubling from the
eigenvector of the multiplier −1.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from contact.errors import ConvergenceError, InputError, OutsideDomainError
from sweep.progress import report
from rotor.dynamics import constraints as cons
from rotor.dynamics.initial import linear_initial_state
from rotor.periodic.floquet import FloquetResult, crossing, floquet
from rotor.periodic.period_flow import Flow, advance, make_flow, to_full
from rotor.periodic.shooting import (ShootingOptions, min_norm_step, orbit_scales, record_reduced, shoot,
                                    shoot_from_transient)

#: relative step of the parameter finite difference
PARAM_REL_STEP = 1e-6
#: singular values of the scaled ``M − I`` below this fraction of the largest are a continuum's directions
NEUTRAL_TOL = 1e-8
#: shortest parameter step of a restart past a switch (scaled parameter, –)
RESTART_STEP = 1e-4
#: how a restarted point was found (``BranchPoint.restarted``; 0: by the corrector)
SECANT, TRANSIENT, COLD = 1, 2, 3
#: a restart from the linear periodic solution (a new segment's start) is tried this many times, at parameter
#: steps growing ×4 from ``COLD_STEP`` (scaled parameter; with a tenth of 600–18 000 rpm as the scale: 1.7 to 445 rpm)
COLD_TRIES, COLD_STEP = 5, 1e-3
#: most revolutions of the transient of a restart from the last orbit (four times as many from the linear start)
RESTART_TRANSIENT_REVS = 62
#: the state scales are renewed when the orbit's own scale differs from them by more than this factor
RESCALE_RATIO = 2.0


@dataclass(frozen=True)
class Problem:
    """A family of period maps over a scalar parameter λ.

    Attributes
    ----------
    system_at : callable ``λ -> RotorSystem``
    speed_at : callable ``λ -> Ω`` (rad/s): the speed whose revolution sets the period
    steps_per_rev : int; period_revs : int (1..8); backend : "auto", "fd" or "exact"
    modes0 : end-face modes the orbits start from
    name : str, the parameter's name with its unit (``speed_rad_s``, ``clearance_m``)
    """

    system_at: Callable
    speed_at: Callable
    steps_per_rev: int
    period_revs: int = 1
    backend: str = "auto"
    modes0: tuple = (cons.SLIP, cons.SLIP)
    name: str = "speed_rad_s"

    def flow(self, lam: float) -> Flow:
        return make_flow(self.system_at(lam), 2.0 * math.pi / (self.speed_at(lam) * self.steps_per_rev), self.backend)

    @property
    def n_steps(self) -> int:
        return self.steps_per_rev * self.period_revs


def speed_problem(system_at_speed: Callable, steps_per_rev: int, **kw) -> Problem:
    """Continuation in the spin speed (λ = Ω, rad/s): ``system_at_speed(Ω) -> RotorSystem``."""
    return Problem(system_at_speed, lambda w: w, steps_per_rev, **kw)


def parameter_problem(system_at: Callable, speed_rad_s: float, steps_per_rev: int, name: str, **kw) -> Problem:
    """Continuation in a scalar scene parameter λ (``name`` with its unit, e.g. ``clearance_m``,
    ``misalignment_m``) at the fixed spin speed ``speed_rad_s``: ``system_at(λ) -> RotorSystem``."""
    w = float(speed_rad_s)
    return Problem(system_at, lambda lam: w, steps_per_rev, name=name, **kw)


@dataclass(frozen=True)
class BranchPoint:
    """One orbit of a branch: ``parameter`` λ, reduced ``state`` at phase 0, ``floquet``, corrector
    ``iterations``, ``residual`` (scaled, –), ``dlam_ds`` (parameter component of the unit tangent), ``restarted``:
    0 reached by the corrector from the point before, else by a restart past a switch (:func:`_restart`):
    :data:`SECANT`, :data:`TRANSIENT` or :data:`COLD`, how its orbit was shot (:func:`_shot`)."""

    parameter: float
    state: np.ndarray
    floquet: FloquetResult
    iterations: int
    residual: float
    dlam_ds: float
    restarted: int = 0


@dataclass(frozen=True)
class Bifurcation:
    """``kind`` ("fold", "branch_point", "period_doubling", "neimark_sacker") between points ``index − 1`` and ``index``,
    at the interpolated ``parameter``; ``multiplier`` the critical one at point ``index``."""

    kind: str
    index: int
    parameter: float
    multiplier: complex


@dataclass(frozen=True)
class Branch:
    """Points and bifurcations of one branch, ``period_revs``, why it stopped (``stop``), ``wall_s``, and
    ``restarts``: points reached by a shooting restart past a switch (:func:`_restart`)."""

    points: tuple
    bifurcations: tuple
    period_revs: int
    stop: str
    wall_s: float
    restarts: int = 0

    def parameters(self) -> np.ndarray:
        return np.array([p.parameter for p in self.points])


@dataclass(frozen=True)
class ContinuationOptions:
    """``ds`` initial/min/max arclength steps (scaled units), corrector ``tol`` (–) and ``max_iter``,
    ``max_points``, ``back_margin`` (stop when a branch turns back beyond the start by this fraction of the
    range), ``rcond`` of the minimum-norm solves, ``multiplier_tol`` (Floquet).

    ``pass_switches``: after ``restart_after`` failed correctors in a row (one after a restarted point) the
    branch is restarted past the switch by shooting at fixed parameter (:func:`_restart`, ``restart_tries``
    parameter steps growing ×4 from the last one).
    ``follow_scales``: the state scales follow the orbit's own peak-to-peak range (never below the given
    ``scales``) once it differs from them by more than ``RESCALE_RATIO``. Both False: the plain corrector with
    the start's scales.
    ``watch``: None, or ``watch(evaluator, y) -> float`` (a contact measure, :mod:`rotor.periodic.grazing`); the
    branch stops (``stop`` "grazing", the crossing point not taken) before a predictor or a corrected point on
    the other side of its zero than the last point."""

    ds: float = 0.05
    ds_min: float = 1e-5
    ds_max: float = 0.5
    tol: float = 1e-9
    max_iter: int = 10
    max_points: int = 400
    back_margin: float = 0.5
    rcond: float = 1e-10
    multiplier_tol: float = 1e-6
    pass_switches: bool = True
    restart_after: int = 3
    restart_tries: int = 6
    follow_scales: bool = True
    watch: Callable | None = None


class _Evaluator:
    """``R``, ``M`` and ``∂R/∂λ`` at (x, λ) in scaled variables, with the flow cached per λ."""

    def __init__(self, problem: Problem, scales: np.ndarray, lam_scale: float):
        self.pb, self.s, self.ls = problem, scales, lam_scale
        self._flows: dict = {}

    def flow(self, lam):
        if lam not in self._flows:
            if len(self._flows) > 8:
                self._flows.clear()
            self._flows[lam] = self.pb.flow(lam)
        return self._flows[lam]

    def __call__(self, x, lam, jacobian=True):
        r = advance(self.flow(lam), x, 0.0, self.pb.n_steps, self.pb.modes0, jacobian=jacobian)
        R = (r.state - x) / self.s
        if not jacobian:
            return R, None, None
        h = PARAM_REL_STEP * max(abs(lam), 1e-12)
        Rp = advance(self.flow(lam + h), x, 0.0, self.pb.n_steps, self.pb.modes0, jacobian=False).state
        Rm = advance(self.flow(lam - h), x, 0.0, self.pb.n_steps, self.pb.modes0, jacobian=False).state
        Rl = (Rp - Rm) / (2.0 * h) / self.s * self.ls
        J = np.hstack([(r.monodromy - np.eye(len(x))) * (self.s[None, :] / self.s[:, None]), Rl[:, None]])
        return R, J, r.monodromy


def _neutral(J, tol: float = NEUTRAL_TOL) -> np.ndarray:
    """Phase rows ``(k, n + 1)``: the directions ``v`` with ``D(M − I)D⁻¹ v = 0`` (singular values below
    ``tol`` times the largest) padded with a zero parameter entry: a stuck face's continuum of orbits."""
    _, s, vt = np.linalg.svd(J[:, :-1])
    rows = vt[s < tol * s[0]]
    return np.hstack([rows, np.zeros((len(rows), 1))])


def _tangent(J, prev, rcond, phase=None):
    """Unit tangent: the minimum-norm solution of ``[J; P; prevᵀ] τ = [0; 0; 1]``, normalised (``P`` the
    phase rows: no motion along the continuum)."""
    rows = [J] + ([phase] if phase is not None and len(phase) else []) + [prev[None, :]]
    A = np.vstack(rows)
    b = np.zeros(A.shape[0])
    b[-1] = 1.0
    t, _ = min_norm_step(A, b, rcond)
    return t / np.linalg.norm(t)


def _correct(ev: _Evaluator, y_pred, tau, opts: ContinuationOptions, phase=None, anchor=None):
    """Newton on ``[R; τ·(y − y_pred); P (y − anchor)]``; returns ``(y, J, M, iterations, residual)`` or None.
    The phase rows ``P`` keep the orbit's place in a stuck face's continuum that of ``anchor``."""
    y = y_pred.copy()
    has_phase = phase is not None and len(phase)
    for it in range(1, opts.max_iter + 1):
        x, lam = y[:-1] * ev.s, y[-1] * ev.ls
        try:
            R, J, M = ev(x, lam)
        except (OutsideDomainError, ConvergenceError, InputError):   # an iterate the scheme cannot step
            return None
        res = float(np.max(np.abs(R)))
        if not math.isfinite(res):
            return None
        A = np.vstack([J, tau[None, :]] + ([phase] if has_phase else []))
        rhs = -np.concatenate([R, [tau @ (y - y_pred)]] + ([phase @ (y - anchor)] if has_phase else []))
        dy, _ = min_norm_step(A, rhs, opts.rcond)
        y = y + dy
        if res < opts.tol and np.max(np.abs(dy)) < 1e3 * opts.tol:
            return y - dy, J, M, it, res
    return None


def _point(ev, y, J, M, it, res, tau, opts, restarted: int = 0) -> BranchPoint:
    lam = y[-1] * ev.ls
    period = ev.pb.n_steps * ev.flow(lam).dt_s
    return BranchPoint(float(lam), y[:-1] * ev.s, floquet(M, period, tol=opts.multiplier_tol), it, res,
                       float(tau[-1]), restarted)


def _test(kind: str, pt: BranchPoint) -> float:
    """The quantity that changes sign at a bifurcation of ``kind``: ``dλ/ds`` (fold) or ``|μ| − 1`` of the
    largest multiplier of that kind (real negative: period doubling; complex: Neimark–Sacker; real positive:
    branch point)."""
    if kind == "fold":
        return pt.dlam_ds
    mu = pt.floquet.multipliers
    real = np.abs(mu.imag) <= 1e-9 * np.maximum(1.0, np.abs(mu))
    neutral = np.abs(mu - 1.0) <= pt.floquet.tol
    if kind == "period_doubling":
        pick = mu[real & (mu.real < 0)]
    elif kind == "branch_point":
        pick = mu[real & (mu.real > 0) & ~neutral]
    else:
        pick = mu[~real]
    return float(np.abs(pick).max()) - 1.0 if len(pick) else -1.0


def _fold_estimate(a: BranchPoint, b: BranchPoint, ds: float, lam_scale: float) -> float:
    """The parameter at the turn between ``a`` and ``b`` a step ``ds`` apart (scaled), with ``dλ/ds`` taken as
    linear in the arclength from ``a.dlam_ds`` to ``b.dlam_ds``: ``λ_a + λ_s f_a² ds / (2 (f_a − f_b))``, the
    vertex of the parabola ``λ(σ)`` (beyond both points, where a linear interpolation of λ would fall between
    them)."""
    fa, fb = a.dlam_ds, b.dlam_ds
    return a.parameter + lam_scale * fa * fa * ds / (2.0 * (fa - fb))


def _refine(ev, y0, tau0, ds: float, kind: str, a: BranchPoint, b: BranchPoint, opts, phase, n_iter: int = 8) -> float:
    """Parameter of a bifurcation between ``a`` (at ``y0``, tangent ``tau0``) and ``b`` (a step ``ds`` on):
    regula falsi (Illinois) on the arclength ``σ`` in ``[0, ds]``, each trial corrected on the hyperplane
    ``τ0·(y − y0 − σ τ0) = 0``, until the bracket is below 10⁻⁶ ds; if a corrector fails, linear interpolation
    (a fold: :func:`_fold_estimate`, the turning point itself lies beyond both points)."""
    lo, hi, flo, fhi = 0.0, ds, _test(kind, a), _test(kind, b)
    lam = b.parameter
    side = 0
    for _ in range(n_iter):
        if flo == fhi:
            break
        sig = lo - flo * (hi - lo) / (fhi - flo)
        got = _correct(ev, y0 + sig * tau0, tau0, opts, phase, y0)
        if got is None:
            if kind == "fold":
                return _fold_estimate(a, b, ds, ev.ls)
            return a.parameter + (b.parameter - a.parameter) * min(max(-flo / (fhi - flo), 0.0), 1.0)
        y, J, M, it, res = got
        pt = _point(ev, y, J, M, it, res, _tangent(J, tau0, opts.rcond, _neutral(J)), opts)
        lam, f = pt.parameter, _test(kind, pt)
        if f * flo > 0:
            lo, flo = sig, f
            fhi = fhi / 2 if side == -1 else fhi
            side = -1
        else:
            hi, fhi = sig, f
            flo = flo / 2 if side == 1 else flo
            side = 1
        if hi - lo < 1e-6 * ds:
            break
    return float(lam)


def _events(ev, prev: BranchPoint, new: BranchPoint, index: int, y0, tau0, ds, opts, phase) -> list:
    """Bifurcations between ``prev`` and ``new``. A real multiplier through +1 without a turn of the
    parameter is a branch point (a pitchfork: symmetry breaking, e.g. a planar orbit starting to whirl).
    Across a restart (``new.restarted``) the tangents of two pieces of the map are not compared (no fold), and
    a multiplier crossing is placed by linear interpolation of its test quantity (no corrector joins them)."""
    fold = prev.dlam_ds * new.dlam_ds < 0 and not new.restarted
    kinds = ["fold"] if fold else []
    kind = crossing(prev.floquet, new.floquet)
    if kind == "fold" and not fold:
        kind = "branch_point"
    if kind is not None and kind not in kinds:
        kinds.append(kind)
    if new.restarted:
        return [Bifurcation(k, index, _interpolated(k, prev, new), new.floquet.critical) for k in kinds]
    return [Bifurcation(k, index, _refine(ev, y0, tau0, ds, k, prev, new, opts, phase), new.floquet.critical)
            for k in kinds]


def _interpolated(kind: str, a: BranchPoint, b: BranchPoint) -> float:
    """Parameter where the test quantity of ``kind`` crosses zero on the straight line from ``a`` to ``b``."""
    fa, fb = _test(kind, a), _test(kind, b)
    w = 0.5 if fa == fb else min(max(-fa / (fb - fa), 0.0), 1.0)
    return a.parameter + w * (b.parameter - a.parameter)


def _confirmed_folds(points, bifs) -> list:
    """The bifurcations with each fold kept only where the branch truly turns: the parameter components of
    the tangents at points ``i − 1`` and ``i`` have opposite signs *and* the parameter moved along each of them,
    into ``i − 1`` (from ``i − 2``; the first point has no secant in) and out of ``i`` (to ``i + 1``). A fold
    between a branch's last two points, or one the secants contradict (a tangent turned by a switch, the
    next corrector stepping on in the old direction), is not reported."""
    lam = [p.parameter for p in points]
    out = []
    for b in bifs:
        i = b.index
        if b.kind == "fold":
            into = i < 2 or (lam[i - 1] - lam[i - 2]) * points[i - 1].dlam_ds > 0
            onward = i + 1 < len(points) and (lam[i + 1] - lam[i]) * points[i].dlam_ds > 0
            if not (into and onward) or points[i].restarted or (i + 1 < len(points) and points[i + 1].restarted):
                continue
        out.append(b)
    return out


def _restart(ev, points, y, tau, opts, continuum: bool):
    """A point past a switch where the corrector cannot go: shooting (:func:`rotor.periodic.shooting.shoot`,
    Newton with halving and Levenberg–Marquardt retrials, no arclength or phase row) at the fixed parameter
    ``λ_k + 2h`` from the secant predictor of the last two points (the tangent at the first point), ``h``
    the last step's parameter advance (at least :data:`RESTART_STEP`), four times as long after each failure,
    ``restart_tries`` times, at most ``ds_max`` (scaled parameter); then at ``λ_k + 2h`` a transient from the
    last orbit before shooting, then from the linear periodic solution at :data:`COLD_TRIES` steps growing ×4
    (:func:`_shot`). In a stuck face's
    continuum (``continuum``: the last orbit has neutral directions) the transient comes first: the orbit the
    corrector cannot reach lies where the face, having slipped a little, holds again, which a transient
    finds and Newton from the secant (at the offset where the face slips) does not. Returns
    ``(y, J, M, iterations, residual, how, guide)`` or None, ``guide`` the unit parameter direction of travel
    (for the new tangent)."""
    x_k, lam_k = y[:-1] * ev.s, y[-1] * ev.ls
    if len(points) > 1:
        prev = points[-2]
        d = np.concatenate([(x_k - prev.state) / ev.s, [(lam_k - prev.parameter) / ev.ls]])
    else:
        d = tau.copy()
    if abs(d[-1]) < 1e-3 * np.linalg.norm(d):       # at a turn: no direction in the parameter to restart along
        return None
    d = d / np.linalg.norm(d)
    h = max(abs(lam_k - points[-2].parameter) / ev.ls if len(points) > 1 else opts.ds * abs(d[-1]), RESTART_STEP)
    tries = [(SECANT, min(2.0 * h * 4.0 ** k, opts.ds_max)) for k in range(opts.restart_tries)]
    cold = [(COLD, min(COLD_STEP * 4.0 ** k, opts.ds_max)) for k in range(COLD_TRIES)]
    tries = ([(TRANSIENT, 2.0 * h)] + tries if continuum else tries + [(TRANSIENT, 2.0 * h)]) + cold
    for how, step in tries:
        y_pred = y + (step / abs(d[-1])) * d
        got = _shot(ev, y_pred, opts, how, y)
        if got is not None:       # the new tangent points on in the parameter: across a jump the secant need not
            guide = np.zeros(len(y))
            guide[-1] = math.copysign(1.0, d[-1])
            return (*got, guide)
    return None


def _shot(ev, y_pred, opts, how: int, y_last):
    """The orbit at the parameter of ``y_pred``: ``how`` 1 (:data:`SECANT`) :func:`rotor.periodic.shooting.shoot`
    from its state; 2 (:data:`TRANSIENT`) :func:`rotor.periodic.shooting.shoot_from_transient` from the last
    orbit ``y_last`` (rounds of 2, 4, … revolutions, at most :data:`RESTART_TRANSIENT_REVS`); 3 (:data:`COLD`)
    the same from the linear periodic solution (:func:`rotor.dynamics.initial.linear_initial_state`; 24, 36, …
    revolutions, at most 4 :data:`RESTART_TRANSIENT_REVS`: the start of a new segment). ``(y, J, M, iterations, residual, how)`` if the orbit's residual
    with the branch's own start modes is below ``tol``, else None."""
    pb, lam = ev.pb, y_pred[-1] * ev.ls
    flow = ev.flow(lam)
    sopts = ShootingOptions(tol=opts.tol, rcond=opts.rcond, max_iter=2 * opts.max_iter, transient_revs=2,
                            round_growth=2.0, max_transient_revs=RESTART_TRANSIENT_REVS)
    try:
        if how == SECANT:
            sh = shoot(flow, y_pred[:-1] * ev.s, t0_s=0.0, steps_per_rev=pb.steps_per_rev, period_revs=pb.period_revs,
                       modes0=pb.modes0, scales=ev.s, options=sopts)
        else:
            if how == TRANSIENT:
                q, v = to_full(flow, y_last[:-1] * ev.s, 0.0)
            else:
                q, v = linear_initial_state(flow.system, 0.0)
                sopts = ShootingOptions(tol=opts.tol, rcond=opts.rcond, max_transient_revs=4 * RESTART_TRANSIENT_REVS)
            sh = shoot_from_transient(flow, q, v, steps_per_rev=pb.steps_per_rev, period_revs=pb.period_revs,
                                      options=sopts, modes0=pb.modes0)
        if not sh.converged:
            return None
        R, J, M = ev(sh.state, lam)
    except (OutsideDomainError, ConvergenceError, InputError):
        return None
    res = float(np.max(np.abs(R)))
    return (np.concatenate([sh.state / ev.s, [y_pred[-1]]]), J, M, sh.newton_iterations, res, how) \
        if res < opts.tol else None


def _land(ev, a, b, lam_end: float, opts, phase):
    """The orbit at exactly ``lam_end``, between the scaled points ``a`` and ``b`` on either side of it: the
    corrector on the hyperplane ``λ = lam_end`` from their linear interpolation; None if it fails."""
    e = np.zeros(len(b))
    e[-1] = 1.0
    return _correct(ev, a + (lam_end / ev.ls - a[-1]) / (b[-1] - a[-1]) * (b - a), e, opts, phase, a)


def _rescale(ev, y, tau, M, J, floor):
    """Renew the state scales to the orbit's own peak-to-peak range over one period at ``y`` (never below
    ``floor``) when they differ by more than :data:`RESCALE_RATIO`: returns ``(y, tau, J)`` in the new
    scaled variables (``J`` transformed, not recomputed) and sets ``ev.s``."""
    x, lam = y[:-1] * ev.s, y[-1] * ev.ls
    p, v, _ = record_reduced(ev.flow(lam), x, 0.0, ev.pb.n_steps, ev.pb.modes0, max(1, ev.pb.n_steps // 256))
    new = np.maximum(orbit_scales(ev.flow(lam), p, v), floor)
    ratio = new / ev.s
    if max(ratio.max(), 1.0 / ratio.min()) <= RESCALE_RATIO:
        return y, tau, J
    old, ev.s = ev.s, new
    y = np.concatenate([y[:-1] / ratio, y[-1:]])
    tau = np.concatenate([tau[:-1] / ratio, tau[-1:]])
    J = np.hstack([(M - np.eye(len(new))) * (new[None, :] / new[:, None]), (J[:, -1] * old / new)[:, None]])
    return y, tau / np.linalg.norm(tau), J


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
    phase = _neutral(J)
    if tangent0 is None:
        tau = _tangent(J, guide, opts.rcond, phase)
    else:
        tau = np.asarray(tangent0, float) / np.linalg.norm(tangent0)
    return _point(ev, y, J, M, 0, float(np.max(np.abs(R))), tau, opts), y, J, phase, tau


def continue_branch(problem: Problem, state0, lam0: float, lam_end: float, *, scales, lam_scale: float | None = None,
                    options: ContinuationOptions | None = None, tangent0=None) -> Branch:
    """Follow the branch through the orbit near ``state0`` at ``lam0`` until the parameter passes ``lam_end``.

    ``scales`` (2 n_r,): state scales (m, rad; m/s, rad/s); ``lam_scale``: parameter scale (default
    ``|lam_end − lam0|/10``). ``tangent0`` (scaled, 2 n_r + 1): start direction instead of the branch's own
    (branch switching). The first point is corrected at fixed ``lam0`` by :func:`rotor.periodic.shooting.shoot`.
    With ``options.pass_switches`` a corrector that fails ``restart_after`` times in a row (the map jumps at a
    stick/slip switch, or the phase conditions hold the orbit at a place of a stuck face's continuum where the
    face starts to slip) is followed by a shooting restart past it (:func:`_restart`).
    """
    opts = options or ContinuationOptions()
    t_start = time.perf_counter()
    floor = np.asarray(scales, float)
    ev = _Evaluator(problem, floor.copy(), float(lam_scale or abs(lam_end - lam0) / 10.0))
    got = _start(problem, ev, state0, lam0, lam_end, opts, tangent0)
    if got is None:
        return Branch((), (), problem.period_revs, f"no orbit at the start ({problem.name} = {lam0:g})",
                      time.perf_counter() - t_start)
    pt, y, J, phase, tau = got
    points, bifs, restarts, fails = [pt], [], 0, 0
    direction = math.copysign(1.0, lam_end - lam0)
    ds, stop = opts.ds, "max_points"
    while len(points) < opts.max_points:
        y_prev = y
        side = None if opts.watch is None else opts.watch(ev, y) > 0.0
        ahead = side is not None and (opts.watch(ev, y + ds * tau) > 0.0) != side
        got = None if ahead else _correct(ev, y + ds * tau, tau, opts, phase, y_prev)
        if ahead or (side is not None and got is not None and (opts.watch(ev, got[0]) > 0.0) != side):
            stop = "grazing"
            break
        guide = tau
        if got is None:
            fails += 1
            if opts.pass_switches and fails == (1 if points[-1].restarted else opts.restart_after):
                got = _restart(ev, points, y, tau, opts, len(phase) > 0)
            if got is None:
                ds *= 0.5
                if ds < opts.ds_min:
                    stop = "step below ds_min"
                    break
                continue
            y, J, M, it, res, restarted, guide = got
            restarts += 1
            ds = opts.ds
        else:
            y, J, M, it, res = got
            restarted = 0
        fails = 0
        phase_new = _neutral(J)
        tau_new = _tangent(J, guide, opts.rcond, phase_new)
        pt = _point(ev, y, J, M, it, res, tau_new, opts, restarted)
        bifs += _events(ev, points[-1], pt, len(points), y_prev, tau, ds, opts, phase)
        if (pt.parameter - lam_end) * direction > 0 and (landed := _land(ev, y_prev, y, lam_end, opts, phase)):
            y, J, M, it, res = landed        # the last orbit at lam_end itself, not beyond it
            pt = _point(ev, y, J, M, it, res, tau_new, opts, restarted)
        points.append(pt)
        report("branch_point", points=len(points), max_points=opts.max_points, parameter=pt.parameter, start=lam0,
               end=lam_end)
        tau = tau_new
        if opts.follow_scales:
            y, tau, J = _rescale(ev, y, tau, M, J, floor)
        phase = _neutral(J)
        if not restarted:
            ds = min(ds * 1.5, opts.ds_max) if it <= 3 else (max(ds * 0.6, opts.ds_min) if it >= 7 else ds)
        if (pt.parameter - lam_end) * direction >= 0:
            stop = "end reached"
            break
        if (lam0 - pt.parameter) * direction > opts.back_margin * abs(lam_end - lam0):
            stop = "turned back beyond the start"
            break
    return Branch(tuple(points), tuple(_confirmed_folds(points, bifs)), problem.period_revs, stop,
                  time.perf_counter() - t_start, restarts)


def switch_period_doubling(problem: Problem, branch: Branch, bif: Bifurcation, lam_end: float, *, scales,
                           lam_scale: float | None = None, options: ContinuationOptions | None = None) -> Branch:
    """The doubled-period branch born at the period doubling ``bif`` of ``branch``.

    At the point after the crossing the monodromy has a real multiplier near −1 with eigenvector ``φ``;
    for the map over two periods it is a multiplier near +1 and the new branch leaves the old one along
    ``(φ, 0)`` (a pitchfork of the doubled map). The continuation of period ``2 period_revs`` starts at the
    old orbit with that tangent made orthogonal to the old branch's secant through the crossing (scaled
    ``(x/s, λ/λ_s)``; ``φ`` alone may lean along the old branch, which then crosses the corrector's hyperplane
    too and takes the corrector back), so its first corrector works on a hyperplane a step ``ds`` away from
    the old branch, where only the new branch crosses; it runs towards ``lam_end``.
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
    doubled = Problem(problem.system_at, problem.speed_at, problem.steps_per_rev, 2 * problem.period_revs,
                      problem.backend, problem.modes0, problem.name)
    # no restarts by shooting on the doubled branch: every orbit of the old branch solves the doubled problem
    # too, and a shot from near the switch lands back on it (measured on Table 4 at 10 628 rpm)
    opts = replace(options or ContinuationOptions(), pass_switches=False)
    return continue_branch(doubled, pt.state, pt.parameter, lam_end, scales=s, lam_scale=ls, options=opts,
                           tangent0=t0)


def _monodromy_at(problem: Problem, pt: BranchPoint) -> np.ndarray:
    return advance(problem.flow(pt.parameter), pt.state, 0.0, problem.n_steps, problem.modes0).monodromy
