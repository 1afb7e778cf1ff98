"""Periodic orbits of the loose-support rotor by shooting on the production scheme's period map.

The excitation (unbalance 1X, misalignment 2X) has the period of one revolution, ``T_1 = 2π/Ω``. An orbit
of period ``k`` revolutions (``k = 1 … 8``) is a fixed point of the map ``Φ`` over ``k N`` steps of
``Δt = T_1/N`` (a whole number ``N`` of steps per revolution, so that the discrete orbit repeats exactly),
started at phase 0: Newton's method on the periodicity residual ``R(x) = Φ(x) − x`` with the Jacobian
``M − I``, ``M`` the monodromy matrix (:mod:`rotor.periodic.period_flow`). The start is the end of a short
transient (:mod:`rotor.studies.steady_state` machinery: the same step choice and Poincaré section).

Scaling and tolerance. Displacements and velocities are measured against the orbit's own scale, the
peak-to-peak range of the reduced displacements and velocities over the last transient revolution
(:func:`orbit_scales`); the orbit has converged when ``max_j |R_j|/s_j < tol``.

Singular directions. A face stuck through the whole orbit leaves its sticking offset free: the orbits form
a continuum, ``M`` has a multiplier exactly 1 and ``M − I`` is singular (:mod:`rotor.periodic.floquet`). The
scheme holds a stuck face's offset exactly, so the continuum's levels (the left null vectors of ``M − I``,
conserved quantities of the map) are what the transient keeps while the face sticks. The Newton step
(:func:`level_step`) is therefore the least-squares solution of the scaled system (singular values below
``rcond`` times the largest dropped, their number reported as ``singular_directions``) that keeps the levels
of the state Newton started from; and an orbit on a continuum is shot only once the transient's levels have
stopped drifting (:func:`shoot_from_transient`), so that it is the member the transient itself settles on.
A step that does not reduce the 2-norm of the scaled residual is halved
(at most ``max_halvings`` times), and so is a trial state the scheme cannot step (beyond the contact law's
domain, or a step's Newton failing). Every map starts from the end-face modes found at the end of the
transient.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from contact.errors import ConvergenceError, OutsideDomainError
from sweep.progress import report
from rotor.dynamics import constraints as cons
from rotor.periodic.floquet import FloquetResult, floquet
from rotor.periodic.period_flow import Flow, advance, block_scales, record, to_reduced

MAX_PERIOD_REVS = 8
#: samples per revolution kept of a transient (Poincaré points and the amplitude scale); the steady-state
#: detector (rotor/studies/steady_state.py) samples its transients at the same rate
TRANSIENT_SAMPLES_PER_REV = 64


@dataclass(frozen=True)
class ShootingOptions:
    """Newton controls: ``tol`` (relative to the orbit scale, –); ``accept_tol``: a residual at which Newton
    stalls (no step reduces it) still counts as converged if below this — the floor set by the step's own
    Newton tolerance and rounding when the orbit is small beside a large static offset (Table 4 at 300 rpm:
    2e-9 of a 0.24 µm orbit on a 1 mm offset); ``max_iter``, ``rcond`` (relative
    singular-value cut of the Newton step, :func:`level_step`), ``max_halvings`` of a step that does not reduce the
    residual, ``transient_revs`` of the first transient round before shooting, ``round_growth``: each further
    round ``round_growth`` times as long as the one before, until ``max_transient_revs``;
    ``periods_per_round`` (:func:`shoot_from_transient`), ``stall_iterations`` (:func:`newton_periodic`: stalled
    steps before the Levenberg–Marquardt retrials, and as many more before the attempt is given up),
    ``multiplier_tol`` (Floquet, –), ``settle_revs``: the chunk in which the transient continues while the
    levels of a continuum of orbits still drift (:func:`shoot_from_transient`)."""

    tol: float = 1e-9
    accept_tol: float = 1e-7
    max_iter: int = 10
    rcond: float = 1e-9
    max_halvings: int = 4
    transient_revs: int = 24
    max_transient_revs: int = 2000
    periods_per_round: int = 2
    round_growth: float = 1.5
    stall_iterations: int = 2
    multiplier_tol: float = 1e-6
    settle_revs: int = 4


@dataclass(frozen=True)
class ShootingResult:
    """A periodic orbit (or the last Newton iterate when ``converged`` is False).

    Attributes
    ----------
    state : (2 n_r,) reduced state ``[p, v]`` at ``t0_s`` (phase 0 of a revolution)
    t0_s, period_s : float (s); period_revs : int; steps_per_rev : int
    modes : end-face modes at ``t0_s`` (1 stick / 0 slip)
    monodromy : (2 n_r, 2 n_r); floquet : FloquetResult
    converged : bool; newton_iterations : int; residual : float, ``max |R_j|/s_j`` (–)
    singular_directions : int, directions of ``M − I`` dropped by the Newton step at the last iteration (:func:`level_step`)
    events : int, end-face mode changes over the converged period (with switches the map is only piecewise
        smooth: the multipliers hold while no switch moves by a step, :mod:`rotor.periodic.period_flow`)
    scales : (2 n_r,) the orbit scales s_j (m, rad; m/s, rad/s); wall_s : float (s); backend : str
    transient_revs : int, revolutions integrated before the converged Newton (:func:`shoot_from_transient`)
    levels : (2 n_r, k) the scaled conserved directions ``U0`` of the last Newton step (:func:`level_step`;
        k = ``singular_directions``): ``U0ᵀ (x/s)`` is the orbit's place in its continuum
    settled : bool, the transient's levels stopped drifting before the orbit was accepted (always True without
        a continuum; :func:`shoot_from_transient`)
    drifting : bool, Newton stopped because the transient still changed the continuum's levels (:func:`shoot`)
    """

    state: np.ndarray
    t0_s: float
    period_s: float
    period_revs: int
    steps_per_rev: int
    modes: tuple
    monodromy: np.ndarray
    floquet: FloquetResult
    converged: bool
    newton_iterations: int
    residual: float
    singular_directions: int
    events: int
    scales: np.ndarray
    wall_s: float
    backend: str
    transient_revs: int = 0
    levels: np.ndarray | None = None
    settled: bool = True
    drifting: bool = False


def orbit_scales(flow: Flow, p, v) -> np.ndarray:
    """Scales (2 n_r,) from reduced displacement and velocity samples ``p``, ``v`` (rows = samples): the
    largest peak-to-peak range of any displacement component, and of any velocity component, falling
    back to :func:`rotor.periodic.period_flow.block_scales` of the last sample for a motionless record."""
    nr = flow.T.shape[1]
    base = block_scales(flow, np.concatenate([p[-1], v[-1]]))
    sp = float(np.ptp(p, axis=0).max()) or base[0]
    sv = float(np.ptp(v, axis=0).max()) or base[-1]
    return np.concatenate([np.full(nr, sp), np.full(nr, sv)])


def _truncated_svd(J, rcond: float):
    """``(U, s, Vt, keep)``: the SVD of ``J`` and the mask of singular values above ``rcond`` times the largest."""
    U, s, Vt = np.linalg.svd(J, full_matrices=False)
    keep = s > rcond * s[0] if s.size and s[0] > 0 else np.zeros_like(s, bool)
    return U, s, Vt, keep


def min_norm_step(J, rhs, rcond: float) -> tuple[np.ndarray, int]:
    """Minimum-norm least-squares solution of ``J dx = rhs`` and the number of singular values dropped."""
    U, s, Vt, keep = _truncated_svd(J, rcond)
    dx = Vt[keep].T @ ((U[:, keep].T @ rhs) / s[keep])
    return dx, int((~keep).sum())


def level_step(J, rhs, rcond: float, back=None) -> tuple[np.ndarray, int, np.ndarray]:
    """The Newton step of ``J dz = rhs`` that keeps the map's conserved levels: ``(dz, dropped, U0)``.

    Where ``J`` (the scaled ``M − I``) drops singular values (below ``rcond`` times the largest), their left
    singular vectors ``U0`` are conserved quantities of the map (``U0ᵀ J = 0``: ``U0ᵀ z`` is the same after
    a period as before; a face stuck through the period conserves its tangential offset, which the scheme
    holds exactly). The step is the minimum-norm one (:func:`min_norm_step`) plus the null-space component
    ``V0 c`` that sets ``U0ᵀ dz = U0ᵀ back`` (``back``: the scaled way back to the levels to keep, default 0):
    Newton then moves within the level set the transient ended on, which is the member of the continuum
    the transient itself settles on once the face stops slipping. Where ``U0ᵀ V0`` is ill-conditioned
    (reciprocal condition below 1e-6) the minimum-norm step is returned. ``U0`` (n, dropped)."""
    U, s, Vt, keep = _truncated_svd(J, rcond)
    dz = Vt[keep].T @ ((U[:, keep].T @ rhs) / s[keep])
    U0, V0 = U[:, ~keep], Vt[~keep].T
    if U0.shape[1]:
        G = U0.T @ V0
        sg = np.linalg.svd(G, compute_uv=False)
        if sg[-1] > 1e-6 * max(sg[0], 1e-300):
            target = np.zeros(U0.shape[1]) if back is None else U0.T @ back
            dz = dz + V0 @ np.linalg.solve(G, target - U0.T @ dz)
    return dz, int((~keep).sum()), U0


def lm_step(J, rhs, rcond: float, radius: float) -> np.ndarray:
    """The Levenberg–Marquardt step ``dz(μ) = Σ s_i c_i/(s_i² + μ²) v_i`` (``J = U diag(s) Vᵀ``, ``c = Uᵀ rhs``,
    singular values below ``rcond`` times the largest dropped) of 2-norm ``radius``: the trust-region step of
    that radius (Moré 1978; Nocedal & Wright 2006, *Numerical Optimization*, ch. 4), μ by bisection in log μ."""
    U, s, Vt, keep = _truncated_svd(J, rcond)
    sk, c, V = s[keep], U[:, keep].T @ rhs, Vt[keep].T
    lo, hi = math.log(sk[-1]) - 20.0, math.log(sk[0]) + 20.0     # ‖dz(μ)‖ falls monotonically in μ
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if np.linalg.norm(c * sk / (sk * sk + math.exp(2.0 * mid))) > radius:
            lo = mid
        else:
            hi = mid
    return V @ (c * sk / (sk * sk + math.exp(2.0 * hi)))


def newton_periodic(flow: Flow, state0, t0_s: float, n_steps: int, modes0, scales, options: ShootingOptions,
                    undecided=None):
    """Newton iterations on ``Φ(x) − x`` over ``n_steps`` steps. A halved retrial is mapped without its
    monodromy (the sensitivity pass is about 60 % of a map's cost, and most retrials are rejected) and mapped
    again with it once accepted (the iterates are the same as with the monodromy at every trial).

    Not contracting. An accepted step that needed halving and left more than half of the residual counts
    as stalled: the full Newton step keeps crossing a face switch the derivative does not see (the map is
    only piecewise smooth), and halving along the same line converges linearly at best. After
    ``options.stall_iterations`` such steps in a row the retrials follow the Levenberg–Marquardt curve
    (:func:`lm_step`, same norms as the halvings), which turns the step towards the residual's steepest
    descent; after as many more the attempt is given up (the caller's next round or period). Returns
    ``(state, MapResult at state, converged, iterations, residual, singular_directions, levels)``: the steps
    keep the conserved levels of ``state0`` (:func:`level_step`). ``undecided``: a test of the conserved
    directions at the first iterate that has them (``levels -> bool``); True stops Newton there, unconverged (the
    transient that led to ``state0`` still changes those levels: the member of the continuum is not decided
    yet, :func:`shoot_from_transient`)."""
    x = np.asarray(state0, float).copy()
    x0 = x.copy()
    modes = tuple(modes0)
    r = advance(flow, x, t0_s, n_steps, modes)
    res = float(np.max(np.abs(r.state - x) / scales))
    merit = float(np.linalg.norm((r.state - x) / scales))
    singular, it, stalled, levels = 0, 0, 0, np.zeros((len(x), 0))
    while res >= options.tol and it < options.max_iter:
        it += 1
        J = (r.monodromy - np.eye(len(x))) * (scales[None, :] / scales[:, None])   # scaled: D (M − I) D⁻¹
        rhs = -(r.state - x) / scales
        dz, singular, levels = level_step(J, rhs, options.rcond, (x0 - x) / scales)
        if singular and undecided is not None:
            if undecided(levels):
                return x, r, False, it, res, singular, levels
            undecided = None                  # asked once: at the first iterate on a continuum
        lam, step = 1.0, dz
        for trial in range(options.max_halvings + 1):
            if trial:     # a shorter step: on the Newton line, or once stalled on the Levenberg–Marquardt curve
                step = lm_step(J, rhs, options.rcond, lam * float(np.linalg.norm(dz))) \
                    if stalled >= options.stall_iterations else lam * dz
            x_try = x + step * scales
            try:     # a retrial's monodromy only once it is accepted: most retrials are rejected
                r_try = advance(flow, x_try, t0_s, n_steps, modes, jacobian=trial == 0)
                merit_try = float(np.linalg.norm((r_try.state - x_try) / scales))
            except (OutsideDomainError, ConvergenceError):   # a trial beyond the law's domain, or a step failed
                merit_try = math.inf
            if merit_try < merit:
                break
            lam *= 0.5
        else:   # no decrease: converged only if stalled at the scheme's noise floor, below accept_tol
            return x, r, res < options.accept_tol, it, res, singular, levels
        if r_try.monodromy is None:
            r_try = advance(flow, x_try, t0_s, n_steps, modes)
        stalled = stalled + 1 if lam < 1.0 and merit_try > 0.5 * merit else 0
        x, r, merit = x_try, r_try, merit_try
        res = float(np.max(np.abs(r.state - x) / scales))
        report("newton", iteration=it, residual=res)
        if stalled >= 2 * options.stall_iterations and res >= options.tol:
            break             # not contracting on either path: give the round up
    return x, r, res < options.tol, it, res, singular, levels


def shoot(flow: Flow, state0, *, t0_s: float, steps_per_rev: int, period_revs: int = 1, modes0=(cons.SLIP, cons.SLIP),
          scales=None, options: ShootingOptions | None = None, history=None) -> ShootingResult:
    """Newton shooting from ``state0`` (reduced, at ``t0_s``) for an orbit of ``period_revs`` revolutions of
    ``steps_per_rev`` steps of ``flow.dt_s``. ``scales`` (2 n_r,): the orbit scale (default: block scales
    of ``state0``). ``history`` (revs, 2 n_r): once-per-revolution states of the transient that ended at
    ``state0``; where the orbits form a continuum whose levels that transient still changed over its last
    period, Newton stops at its first iteration with ``drifting`` True (:func:`level_drift`)."""
    opts = options or ShootingOptions()
    if not 1 <= int(period_revs) <= MAX_PERIOD_REVS:
        raise ValueError(f"period_revs = {period_revs}: must be 1 to {MAX_PERIOD_REVS} revolutions")
    t_start = time.perf_counter()
    s = block_scales(flow, state0) if scales is None else np.asarray(scales, float)
    n = int(period_revs) * int(steps_per_rev)
    undecided = None
    if history is not None:
        def undecided(levels):
            return _drift(levels, s, int(period_revs), history) >= opts.tol
    x, r, ok, it, res, singular, levels = newton_periodic(flow, state0, t0_s, n, modes0, s, opts, undecided)
    drifting = bool(not ok and undecided is not None and levels.shape[1] and undecided(levels))
    period = n * flow.dt_s
    fl = floquet(r.monodromy, period, tol=opts.multiplier_tol)
    return ShootingResult(x, float(t0_s), period, int(period_revs), int(steps_per_rev), tuple(r.modes), r.monodromy,
                          fl, bool(ok), it, res, singular, int(r.events), s, time.perf_counter() - t_start, flow.backend,
                          levels=levels, drifting=drifting)


def _supported(P: np.ndarray, max_period: int) -> list[int]:
    """Periods 1..max_period the Poincaré returns ``P`` (rows: once-per-revolution reduced displacements)
    support, shortest first: a period ``k`` whose last return ``|P_j − P_{j−k}|`` is within 10× the smallest
    and, for ``k > 1``, below half the return of every period dividing it (a period-j orbit also solves the
    problem of any multiple of j, so a multiple earns a Newton attempt of its own only where the returns
    show it repeating better than its divisors). Never empty: the period of the smallest return, or its
    smallest divisor within a factor 2 of it, qualifies."""
    ks = [k for k in range(1, max_period + 1) if k < len(P)]
    if not ks:
        return [1]
    d = {k: float(np.abs(P[-1] - P[-1 - k]).max()) for k in ks}
    dmin = min(d.values())
    return [k for k in ks if d[k] <= 10.0 * dmin and
            (k == 1 or all(d[k] < 0.5 * d[j] for j in ks if j < k and k % j == 0))]


def transient(flow: Flow, state, t0_s: float, *, steps_per_rev: int, revs: int, modes0=(cons.STICK, cons.STICK)):
    """``revs`` revolutions from the reduced ``state`` at ``t0_s`` (a whole revolution): returns
    ``(state, modes, P, scales, X)`` — the reduced end state, its face modes, the once-per-revolution reduced
    displacements ``P`` (revs, n_r; the start excluded), the orbit scales of the last revolution
    (:func:`orbit_scales`) and the once-per-revolution reduced states ``X`` (revs, 2 n_r; the start excluded)."""
    sub = max(1, steps_per_rev // TRANSIENT_SAMPLES_PER_REV)
    p, v, modes = record_reduced(flow, state, t0_s, steps_per_rev * int(revs), modes0, sub)
    per = steps_per_rev // sub
    end = np.concatenate([p[-1], v[-1]])
    return end, modes, p[per::per], orbit_scales(flow, p[-per - 1:], v[-per - 1:]), \
        np.concatenate([p[per::per], v[per::per]], axis=1)


def record_reduced(flow: Flow, state, t0: float, n_steps: int, modes0, record_every: int):
    """``(p, v, modes_end)``: reduced displacement and velocity samples every ``record_every`` steps (rows)
    and the end-face modes at the end."""
    tr = record(flow, state, t0, n_steps, modes0, record_every)
    red = to_reduced(flow, tr.q, tr.v)
    nr = flow.T.shape[1]
    return red[:, :nr], red[:, nr:], tuple(int(m) for m in tr.modes[-1])


def _shortest_period(flow: Flow, res: ShootingResult, opts: ShootingOptions) -> ShootingResult:
    """The orbit ``res`` re-shot with the shortest period ``j`` dividing its ``k`` revolutions whose return
    after ``j`` revolutions is within 10³ tol of the start (a period-1 orbit also solves the 2-revolution
    problem)."""
    k = res.period_revs
    for j in range(1, k):
        if k % j:
            continue
        x_j = advance(flow, res.state, res.t0_s, j * res.steps_per_rev, res.modes, jacobian=False).state
        if np.max(np.abs(x_j - res.state) / res.scales) < 1e3 * opts.tol:
            short = shoot(flow, res.state, t0_s=res.t0_s, steps_per_rev=res.steps_per_rev, period_revs=j,
                          modes0=res.modes, scales=res.scales, options=opts)
            if short.converged:
                return replace(short, newton_iterations=short.newton_iterations + res.newton_iterations)
    return res


def _round_periods(P: np.ndarray, period_revs, period_hint, opts: ShootingOptions) -> list[int]:
    """The periods one round of :func:`shoot_from_transient` tries: ``period_revs`` if given; else the first
    ``periods_per_round`` periods the Poincaré returns ``P`` support (:func:`_supported`), then
    ``period_hint`` (a neighbouring speed's period) if not among them."""
    if period_revs is not None:
        return [int(period_revs)]
    order = _supported(P, MAX_PERIOD_REVS)[:opts.periods_per_round]
    return order + [int(period_hint)] if period_hint is not None and int(period_hint) not in order else order


def _drift(levels, scales, period_revs: int, X) -> float:
    if levels is None or levels.shape[1] == 0:
        return 0.0
    if len(X) < period_revs + 1:
        return math.inf
    return float(np.abs(levels.T @ ((X[-1] - X[-1 - period_revs]) / scales)).max())


def level_drift(res: ShootingResult, X) -> float:
    """Largest change of the orbit's conserved levels (``res.levels``, scaled) between the transient's
    once-per-revolution states ``X[-1 - k]`` and ``X[-1]`` over the last period ``k`` (revolutions); 0 without
    conserved directions, inf with fewer than ``k + 1`` states."""
    return _drift(res.levels, res.scales, res.period_revs, X)


def shoot_from_transient(flow: Flow, q0, v0, *, steps_per_rev: int, period_revs: int | None = None,
                         options: ShootingOptions | None = None, modes0=(cons.STICK, cons.STICK),
                         period_hint: int | None = None) -> ShootingResult:
    """A short transient from the full ``(q0, v0)`` at t = 0, then :func:`shoot`; if Newton fails, more
    transient and Newton again.

    Rounds: ``transient_revs`` revolutions, then ``round_growth`` times as many as the round before, until
    Newton converges or ``max_transient_revs`` are spent. Newton's basin on a rotor whose faces stick and slip
    within the period is small (the map is only piecewise smooth), so the transient brings the start into it;
    a failed Newton iterate is discarded and the transient continues from its own end. The growth of 1.5
    (rather than 2) overshoots the revolutions a start needs by at most half as much again, at the price of
    more Newton attempts, which the supported-period rule keeps cheap. ``period_revs`` None: each round tries
    the first ``periods_per_round`` periods the Poincaré returns support (:func:`_supported`), then
    ``period_hint`` (a neighbouring speed's period, :func:`rotor.studies.orbit.cascade`) if not among them.
    ``wall_s`` includes the transient; ``transient_revs`` in the result.

    Continuum of orbits (a face stuck through the period: conserved levels, :func:`level_step`). Every member
    is an exact orbit; the transient settles on the one whose levels it holds when the face slips for the last
    time. Newton keeps the levels of the transient's end, so the orbit found is the transient's own once the
    levels stopped drifting over the transient's last period (:func:`level_drift` below ``tol``); while they
    still drift (the face slips a little every revolution as the transient decays: Table 4 at 10 500 rpm,
    up to revolution 246) the transient continues in ``settle_revs`` chunks, watching the drift only, and
    Newton is run once more from its end when the drift has stopped. ``settled`` in the result says whether it
    stopped within ``max_transient_revs`` (if not, the orbit is exact but another member than the transient's).
    """
    opts = options or ShootingOptions()
    t_start = time.perf_counter()
    run = _Run(flow, steps_per_rev, to_reduced(flow, q0, v0), tuple(modes0))
    chunk, res = int(opts.transient_revs), None
    while True:
        run.extend(chunk, opts)
        report("transient", revs=run.done, max_revs=opts.max_transient_revs)
        for k in _round_periods(np.array(run.P), period_revs, period_hint, opts):
            res = run.shoot(k, opts)
            report("attempt", period_revs=int(k), transient_revs=run.done, iterations=int(res.newton_iterations),
                   residual=float(res.residual), converged=bool(res.converged))
            if res.converged:
                res = _shortest_period(flow, res, opts)
                break
            if res.drifting:
                break
        if res.drifting or (res.converged and level_drift(res, run.X) >= opts.tol):
            res = _settle(run, res, opts)
        if res.converged or run.done >= opts.max_transient_revs:
            break
        chunk = min(max(1, int(round(opts.round_growth * chunk))), opts.max_transient_revs - run.done)
    return replace(res, wall_s=time.perf_counter() - t_start, transient_revs=run.done)


class _Run:
    """The transient of :func:`shoot_from_transient` so far: its end state, modes and time, the revolutions
    done, the once-per-revolution displacements ``P`` and states ``X``, the last revolution's scales."""

    def __init__(self, flow, steps_per_rev, x, modes):
        self.flow, self.n, self.x, self.modes = flow, int(steps_per_rev), x, modes
        self.t0, self.done, self.P, self.X, self.scales = 0.0, 0, [], [], None

    def extend(self, revs: int, opts: ShootingOptions):
        self.x, self.modes, Pc, self.scales, Xc = transient(self.flow, self.x, self.t0, steps_per_rev=self.n,
                                                            revs=revs, modes0=self.modes)
        self.t0 += revs * self.n * self.flow.dt_s
        self.done += revs
        self.P.extend(Pc)
        self.X.extend(Xc)

    def shoot(self, period_revs: int, opts: ShootingOptions) -> ShootingResult:
        return shoot(self.flow, self.x, t0_s=self.t0, steps_per_rev=self.n, period_revs=period_revs,
                     modes0=self.modes, scales=self.scales, options=opts,
                     history=np.array(self.X[-period_revs - 1:]))


def _settle(run: _Run, res: ShootingResult, opts: ShootingOptions) -> ShootingResult:
    """A continuum whose levels the transient still changes (``res``: drifting, or converged on a member the
    transient has not settled on): the transient continues in ``settle_revs`` chunks, watching the levels only,
    and Newton runs once more when they have stopped drifting over a period. Returns that orbit; ``res``
    marked ``settled`` False if the budget ran out first; an unconverged result if Newton failed there (the
    rounds go on)."""
    k = res.period_revs
    while run.done < opts.max_transient_revs:
        run.extend(min(max(opts.settle_revs, k), opts.max_transient_revs - run.done), opts)
        if _drift(res.levels, res.scales, k, run.X[-k - 1:]) < opts.tol:
            return run.shoot(k, opts)
    return replace(res, settled=False)
