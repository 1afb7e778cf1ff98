"""Periodic orbits of the loose-support rotor by shooting on the production scheme's period map.

The excitation (unbalance 1X, misalignment 2X) has the period of one revolution, ``T_1 = 2π/Ω``. An orbit
of period ``k`` revolutions (``k = 1 … 8``) is a fixed point of the map ``Φ`` over ``k N`` steps of
``Δt = T_1/N`` (a whole number ``N`` of steps per revolution, so that the discrete orbit repeats exactly),
started at phase 0: Newton's method on the periodicity residual ``R(x) = Φ(x) − x`` with the Jacobian
``M − I``, ``M`` the monodromy matrix (:mod:`rotor.studies.period_flow`). The start is the end of a short
transient (:mod:`rotor.studies.steady_state` machinery: the same step choice and Poincaré section).

Scaling and tolerance. Displacements and velocities are measured against the orbit's own scale, the
peak-to-peak range of the reduced displacements and velocities over the last transient revolution
(:func:`orbit_scales`); the orbit has converged when ``max_j |R_j|/s_j < tol``.

Singular directions. A face stuck through the whole orbit leaves its sticking offset free: the orbits form
a continuum, ``M`` has a multiplier exactly 1 and ``M − I`` is singular (:mod:`rotor.studies.floquet`). The
Newton step is therefore the minimum-norm least-squares solution of the scaled system (singular values
below ``rcond`` times the largest are dropped); it moves the state only across the continuum, and the number
of directions dropped is reported (``singular_directions``). A step that does not reduce the 2-norm of the scaled residual is halved
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
from rotor.dynamics import constraints as cons
from rotor.studies.floquet import FloquetResult, floquet
from rotor.studies.period_flow import Flow, advance, block_scales, record, to_reduced
from rotor.studies.steady_state import TRANSIENT_SAMPLES_PER_REV

MAX_PERIOD_REVS = 8


@dataclass(frozen=True)
class ShootingOptions:
    """Newton controls: ``tol`` (relative to the orbit scale, –); ``accept_tol``: a residual at which Newton
    stalls (no step reduces it) still counts as converged if below this — the floor set by the step's own
    Newton tolerance and rounding when the orbit is small beside a large static offset (Table 4 at 300 rpm:
    2e-9 of a 0.24 µm orbit on a 1 mm offset); ``max_iter``, ``rcond`` (relative
    singular-value cut of the minimum-norm step), ``max_halvings`` of a step that does not reduce the
    residual, ``transient_revs`` before shooting, ``multiplier_tol`` (Floquet, –)."""

    tol: float = 1e-9
    accept_tol: float = 1e-7
    max_iter: int = 10
    rcond: float = 1e-9
    max_halvings: int = 4
    transient_revs: int = 16
    max_transient_revs: int = 2000
    periods_per_round: int = 2
    multiplier_tol: float = 1e-6


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
    singular_directions : int, directions of ``M − I`` dropped by the minimum-norm step at the last iteration
    events : int, end-face mode changes over the converged period (with switches the map is only piecewise
        smooth: the multipliers hold while no switch moves by a step, :mod:`rotor.studies.period_flow`)
    scales : (2 n_r,) the orbit scales s_j (m, rad; m/s, rad/s); wall_s : float (s); backend : str
    transient_revs : int, revolutions integrated before the converged Newton (:func:`shoot_from_transient`)
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


def orbit_scales(flow: Flow, p, v) -> np.ndarray:
    """Scales (2 n_r,) from reduced displacement and velocity samples ``p``, ``v`` (rows = samples): the
    largest peak-to-peak range of any displacement component, and of any velocity component, falling
    back to :func:`rotor.studies.period_flow.block_scales` of the last sample for a motionless record."""
    nr = flow.T.shape[1]
    base = block_scales(flow, np.concatenate([p[-1], v[-1]]))
    sp = float(np.ptp(p, axis=0).max()) or base[0]
    sv = float(np.ptp(v, axis=0).max()) or base[-1]
    return np.concatenate([np.full(nr, sp), np.full(nr, sv)])


def min_norm_step(J, rhs, rcond: float) -> tuple[np.ndarray, int]:
    """Minimum-norm least-squares solution of ``J dx = rhs`` and the number of singular values dropped."""
    U, s, Vt = np.linalg.svd(J, full_matrices=False)
    keep = s > rcond * s[0] if s.size and s[0] > 0 else np.zeros_like(s, bool)
    dx = Vt[keep].T @ ((U[:, keep].T @ rhs) / s[keep])
    return dx, int((~keep).sum())


def newton_periodic(flow: Flow, state0, t0_s: float, n_steps: int, modes0, scales, options: ShootingOptions):
    """Newton iterations on ``Φ(x) − x`` over ``n_steps`` steps. Returns
    ``(state, MapResult at state, converged, iterations, residual, singular_directions)``."""
    x = np.asarray(state0, float).copy()
    modes = tuple(modes0)
    r = advance(flow, x, t0_s, n_steps, modes)
    res = float(np.max(np.abs(r.state - x) / scales))
    merit = float(np.linalg.norm((r.state - x) / scales))
    singular = 0
    it = 0
    while res >= options.tol and it < options.max_iter:
        it += 1
        J = (r.monodromy - np.eye(len(x))) * (scales[None, :] / scales[:, None])   # scaled: D (M − I) D⁻¹
        dz, singular = min_norm_step(J, -(r.state - x) / scales, options.rcond)
        lam = 1.0
        for _ in range(options.max_halvings + 1):
            x_try = x + lam * dz * scales
            try:
                r_try = advance(flow, x_try, t0_s, n_steps, modes)
            except (OutsideDomainError, ConvergenceError):   # a trial beyond the law's domain, or a step failed
                lam *= 0.5
                continue
            merit_try = float(np.linalg.norm((r_try.state - x_try) / scales))
            if math.isfinite(merit_try) and merit_try < merit:
                break
            lam *= 0.5
        else:   # no decrease: converged only if stalled at the scheme's noise floor, below accept_tol
            return x, r, res < options.accept_tol, it, res, singular
        x, r, merit = x_try, r_try, merit_try
        res = float(np.max(np.abs(r.state - x) / scales))
    return x, r, res < options.tol, it, res, singular


def shoot(flow: Flow, state0, *, t0_s: float, steps_per_rev: int, period_revs: int = 1, modes0=(cons.SLIP, cons.SLIP),
          scales=None, options: ShootingOptions | None = None) -> ShootingResult:
    """Newton shooting from ``state0`` (reduced, at ``t0_s``) for an orbit of ``period_revs`` revolutions of
    ``steps_per_rev`` steps of ``flow.dt_s``. ``scales`` (2 n_r,): the orbit scale (default: block scales
    of ``state0``)."""
    opts = options or ShootingOptions()
    if not 1 <= int(period_revs) <= MAX_PERIOD_REVS:
        raise ValueError(f"period_revs = {period_revs}: must be 1 to {MAX_PERIOD_REVS} revolutions")
    t_start = time.perf_counter()
    s = block_scales(flow, state0) if scales is None else np.asarray(scales, float)
    n = int(period_revs) * int(steps_per_rev)
    x, r, ok, it, res, singular = newton_periodic(flow, state0, t0_s, n, modes0, s, opts)
    period = n * flow.dt_s
    fl = floquet(r.monodromy, period, tol=opts.multiplier_tol)
    return ShootingResult(x, float(t0_s), period, int(period_revs), int(steps_per_rev), tuple(r.modes), r.monodromy,
                          fl, bool(ok), it, res, singular, int(r.events), s, time.perf_counter() - t_start, flow.backend)


def _poincare_order(P: np.ndarray, max_period: int) -> list[int]:
    """Periods 1..max_period ordered for trial: those whose last Poincaré return ``|P_j − P_{j−k}|`` is
    within 10× the smallest first (shortest period first), then the rest by that difference."""
    ks = [k for k in range(1, max_period + 1) if k < len(P)]
    if not ks:
        return [1]
    d = {k: float(np.abs(P[-1] - P[-1 - k]).max()) for k in ks}
    dmin = min(d.values())
    return sorted(ks, key=lambda k: (d[k] > 10.0 * dmin + 1e-300, d[k] if d[k] > 10.0 * dmin else k))


def transient(flow: Flow, state, t0_s: float, *, steps_per_rev: int, revs: int, modes0=(cons.STICK, cons.STICK)):
    """``revs`` revolutions from the reduced ``state`` at ``t0_s`` (a whole revolution): returns
    ``(state, modes, P, scales)`` — the reduced end state, its face modes, the once-per-revolution reduced
    displacements ``P`` (revs, n_r; the start excluded) and the orbit scales of the last revolution
    (:func:`orbit_scales`)."""
    sub = max(1, steps_per_rev // TRANSIENT_SAMPLES_PER_REV)
    p, v, modes = record_reduced(flow, state, t0_s, steps_per_rev * int(revs), modes0, sub)
    per = steps_per_rev // sub
    end = np.concatenate([p[-1], v[-1]])
    return end, modes, p[per::per], orbit_scales(flow, p[-per - 1:], v[-per - 1:])


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


def shoot_from_transient(flow: Flow, q0, v0, *, steps_per_rev: int, period_revs: int | None = None,
                         options: ShootingOptions | None = None, modes0=(cons.STICK, cons.STICK)) -> ShootingResult:
    """A short transient from the full ``(q0, v0)`` at t = 0, then :func:`shoot`; if Newton fails, more
    transient and Newton again.

    Rounds: ``transient_revs`` revolutions, then twice as many as the round before, until Newton converges
    or ``max_transient_revs`` are spent. Newton's basin on a rotor whose faces stick and slip within the
    period is small (the map is only piecewise smooth), so the transient brings the start into it; a
    failed Newton iterate is discarded and the transient continues from its own end. ``period_revs`` None:
    each round tries the first ``periods_per_round`` periods of 1..8 in the order the Poincaré returns
    suggest (:func:`_poincare_order`). ``wall_s`` includes the transient; ``transient_revs`` in the result.
    """
    opts = options or ShootingOptions()
    t_start = time.perf_counter()
    x, modes, t0 = to_reduced(flow, q0, v0), tuple(modes0), 0.0
    chunk, done, P, res = int(opts.transient_revs), 0, [], None
    while True:
        x, modes, Pc, scales = transient(flow, x, t0, steps_per_rev=steps_per_rev, revs=chunk, modes0=modes)
        t0 += chunk * steps_per_rev * flow.dt_s
        done += chunk
        P.extend(Pc)
        order = [int(period_revs)] if period_revs is not None else \
            _poincare_order(np.array(P), MAX_PERIOD_REVS)[:opts.periods_per_round]
        for k in order:
            res = shoot(flow, x, t0_s=t0, steps_per_rev=steps_per_rev, period_revs=k, modes0=modes, scales=scales,
                        options=opts)
            if res.converged:
                res = _shortest_period(flow, res, opts)
                break
        if res.converged or done >= opts.max_transient_revs:
            break
        chunk = min(2 * chunk, opts.max_transient_revs - done)
    return replace(res, wall_s=time.perf_counter() - t_start, transient_revs=done)
