"""Friction events inside the step: a slip velocity that reaches zero is located, and the step split there.

Den Hartog's (1931) oscillator shows what the plain step misses: when a face's slip velocity
reverses inside a step, Coulomb's force jumps from ``−μN ŵ`` to ``+μN ŵ`` at that instant, and the
trapezoidal rule of Newmark's average acceleration spreads the jump over the step (impulse
``h (f_n + f_n+1)/2`` instead of the exact one), an error of order ``h`` per reversal: the steady
amplitude then converges at first order only, and, with no viscous damping, a free vibration at
the natural frequency is never damped out. The same holds at a stick onset (the force jumps from
``μN`` to the holding force). A release needs no location: the holding force reaches ``μN`` and
the slip force starts at ``μN`` in the same direction, so the force is continuous there.

The located step (driven by :func:`rotor.dynamics.production_loop.step_loop`), for the faces that slip
at the start of a step and whose velocity reverses or which stick at its end (:func:`_velocity_events`):

1. the step is solved again with those faces' friction held at its start-of-step value
   ``−μN ŵ_n`` (:func:`_held_friction`; the slip continued past the event, a smooth motion);
2. the event time is the root of that step's own velocity polynomial along ``ŵ_n``, the
   quadratic of Newmark's linearly varying acceleration,
   ``s(θh) = s_n + θh s'_n + (θh)² (s'_n+1 − s'_n)/(2h)`` (:func:`_event_time`, :func:`_event_fraction`);
3. the step is split into two Newmark sub-steps at ``θh`` (each with its own factorised matrix,
   :func:`_substep_matrices`): the first with the friction still held, then the friction state is
   switched (:func:`_switch_at_event`: the face sticks if its consistent holding force is within
   ``μN``, else it slips in the direction of that force, with ``μN``), the acceleration is restarted
   from the consistent one (:func:`rotor.dynamics.production_kernels._consistent_acceleration`), and the
   second sub-step runs the plain step with its active-set loop.

One event per step is located (the earliest; faces with the same event time switch together);
a second event in the same step is left to the plain rules.

**Release.** The force is continuous there, but the plain rule (the step-mean holding force past ``μN``)
releases a face up to half a step late. A release is located as the instant the holding force, linear between
the consistent one at the step's start (a function of the start's ``(p, v)``, so the located map stays
differentiable) and the stuck step's end multiplier, reaches ``μN`` (:func:`_release_fraction`), also when the
step-mean stays within ``μN``; the step is redone up to there with the face kept stuck, it is released there with
``μN`` along its holding force, and the rest of the step follows.

**Slow slips** (:func:`rotor.dynamics.production_loop.step_loop`). The regularised force
``−μN w/√(|w|² + w_reg²)`` falls short of Coulomb's where the speed is a few ``w_reg``: right after a release (the
face starts from rest, its force 0 instead of ``μN``: 3e-4 of Den Hartog's stick-slip amplitude, scaling with
√w_reg, at every step size) and just before a stop. So a face at rest whose force is at ``μN`` (just released)
slips with that force held over the step, and a slow rectilinear slip (``w_reg < |w| < RELEASE_HOLD w_reg``, its
acceleration along its velocity to ``RECTILINEAR``) with Coulomb's force along its start-of-step velocity. Both
are decided from the step's start alone. A 2D slow slip keeps the regularised force: holding its start direction
over a step made Table 4's faces switch 10 times as often and the located map jump. With the events located, the
low-speed stick trial (``w_stick``) is kept only below ``w_reg``: a stop is where the velocity reaches zero, and
a threshold on the step grid made the map jump. After a stop located inside a step the rest of the step ends
on the consistent acceleration (the sub-step's own velocity at the event, the root of the held step's
polynomial, is ``O(h³)`` from zero, and the stuck multipliers rang with it).
The rectilinear test is itself a threshold on the step grid, and a 2D slow slip's acceleration can sweep through
its velocity's direction: on Table 4 at 11 000 rpm (T/512, one period after 60 revolutions) a face slipping at
6 w_reg has sin² 5.4e-8 at one step, 2.2e-10 after a 1e-7 perturbation of the period's start, is held there and
stops; the located map jumps (its central differences at 1e-7 and 5e-8 differ by O(1), and at 1e-8 and 1e-9 still do
not settle: a jump of about 1e-7 of the state at the orbit). At 9 600 rpm the map jumps too, and with the test
narrowed to sin² ≤ 1e-24 (exactly rectilinear slips only) its central differences there agree to 2.1e-7, but then
8 400 rpm's differ by O(1), another threshold, and the located monodromy at 9 600 rpm is 2.9e-2 from them: the test
is kept. The monodromy's differencing shrinks past such a threshold (rotor.dynamics.period_map_events).
A stop located from any start speed above ``EVENT_SPEED w_reg`` (rotor.dynamics.production_loop) replaced ``w_reg``
as that threshold for stops (not for reversals): a face creeping to a stop at ~``w_reg`` starts its last step just
above it.

Measured on Den Hartog's (1931) stick-slip oscillator: the amplitude error against the closed form falls at
second order (4.6e-5 … 7.1e-7 at T/400 … T/3200) where it stalled at 3e-4. Switched on by
``NewmarkOptions.locate_events`` (on by default); the tests are in tests/rotor/dynamics/test_friction_events.py.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from contact.compiled_cache import compiled_with
from rotor.dynamics.production_kernels import _consistent_acceleration

compiled_with(__file__, ["rotor.dynamics.production_kernels", "rotor.dynamics.constraints", "rotor.dynamics.kernels",
                         "contact._kernel", "contact._kernel_friction", "contact._kernel_tilt"])

SAME_EVENT = 1e-6   # event fractions closer than this (of the step) are one event


@njit(cache=True)
def _substep_matrices(h, Mr, Dr, Kr, Bt, beta, gamma):
    """``A(h)⁻¹``, ``W = A⁻¹ Btᵀ`` and ``S = Bt W`` of a step of length ``h`` (s), with
    ``A = M + γh D + βh² K`` (reduced coordinates, as :func:`rotor.dynamics.production.prepare`)."""
    Ainv = np.ascontiguousarray(np.linalg.inv(Mr + gamma * h * Dr + beta * h * h * Kr))
    W = np.ascontiguousarray(Ainv @ Bt.T)
    return Ainv, W, np.ascontiguousarray(Bt @ W)


@njit(cache=True)
def _event_fraction(s0, d0, d1, h):
    """Fraction ``θ ∈ (0, 1]`` of the step at which ``s(θh) = s0 + θh d0 + (θh)² (d1 − d0)/(2h)``
    vanishes (velocity along the start direction, m/s; ``d0, d1`` its rates at the ends, m/s²),
    the first root after 0; −1 if ``s`` does not reach zero within the step (``s0 > 0``)."""
    A = 0.5 * h * (d1 - d0)
    B = h * d0
    if s0 + B + A > 0.0:
        return -1.0
    lo = 0.0
    hi = 1.0
    th = s0 / (s0 - (s0 + B + A))
    for _ in range(60):
        f = s0 + th * (B + th * A)
        if f > 0.0:
            lo = th
        else:
            hi = th
        df = B + 2.0 * A * th
        nxt = th - f / df if df != 0.0 else 0.5 * (lo + hi)
        if not (lo < nxt < hi):
            nxt = 0.5 * (lo + hi)
        if abs(nxt - th) <= 1e-15:
            return nxt
        th = nxt
    return th


@njit(cache=True)
def _velocity_events(w0, w1, modes0, modes1, released0, P, n_faces, w_min, ev, mu_N, w_stop):
    """Mark in ``ev`` (2,) the faces slipping at the start of the step, faster than ``w_min`` (m/s; the
    friction regularisation ``w_reg``, below which the slip direction is not defined) and not just
    released (``released0``: they start from rest), whose velocity reversed (``w_n+1 · w_n ≤ 0``) or
    which stuck by its end; returns how many. ``w0``, ``w1``: the condensed velocities ``Bt v`` (NC,) at the
    start and at the end of the step (m/s, rad/s); a face without friction (``mu_N[k]`` 0, N) has no event. A face
    that stuck by the end is an event from the start speed ``w_stop`` (m/s, below ``w_min``) up: a face creeping to a
    stop at ~``w_reg`` starts its last step just above it (rotor.dynamics.production_loop.EVENT_SPEED)."""
    count = 0
    for k in range(2):
        ev[k] = False
        if k >= n_faces or modes0[k] != 0 or released0[k] or mu_N[k] <= 0.0:
            continue
        a0 = P[k, 0] @ w0[:4]
        b0 = P[k, 1] @ w0[:4]
        s2 = a0 * a0 + b0 * b0
        if s2 <= w_stop * w_stop:
            continue
        a1 = P[k, 0] @ w1[:4]
        b1 = P[k, 1] @ w1[:4]
        if modes1[k] == 1 or (s2 > w_min * w_min and a0 * a1 + b0 * b1 <= 0.0):
            ev[k] = True
            count += 1
    return count


@njit(cache=True)
def _switch_at_event(p, v, Q, Minv, Dr, Kr, Bt, WM, SM, P, modes, phi_face, just_released, faces, mu_N, a1, params,
                     w_reg):
    """Friction state of the ``faces`` (bool (2,)) at the event, and the consistent acceleration.

    Each of them is stuck if its consistent holding force is within ``μN``; otherwise it slips with the
    force ``μN`` in that force's direction (held for the acceleration only) and is marked just released.
    ``modes, phi_face, just_released`` are updated in place. Returns ``a``."""
    freeze = np.zeros(2, dtype=np.bool_)
    fdir = np.zeros((2, 2))
    for k in range(2):
        if faces[k]:
            modes[k] = 1
            just_released[k] = False
    phi = phi_face.copy()
    a = np.zeros_like(p)
    for _ in range(3):
        phi[:, :] = phi_face
        a = _consistent_acceleration(p, v, Q, Minv, Dr, Kr, Bt, WM, SM, P, modes, freeze, fdir, mu_N, a1, params,
                                     w_reg, phi)
        changed = False
        for k in range(2):
            if faces[k] and modes[k] == 1:
                nrm = math.sqrt(phi[k, 0] ** 2 + phi[k, 1] ** 2)
                if nrm > mu_N[k] * (1.0 + 1e-12):
                    modes[k] = 0
                    freeze[k] = True
                    fdir[k, 0] = mu_N[k] * phi[k, 0] / nrm
                    fdir[k, 1] = mu_N[k] * phi[k, 1] / nrm
                    just_released[k] = True
                    changed = True
        if not changed:
            break
    phi_face[:, :] = phi
    return a


@njit(cache=True)
def _held_friction(v, alpha, ev, Bt, P, mu_N, e, s0, d0, hold, hold_dir):
    """Start of a located step for the faces marked in ``ev``: the unit slip direction ``e[k]``, the speed
    ``s0[k]`` (m/s) and its rate ``d0[k]`` along ``e[k]`` (m/s², from ``alpha = Bt a``), and the friction
    held over the re-solved step, ``hold_dir[k] = −μN e[k]`` (N), ``hold[k]`` True. Arrays written in place."""
    w0 = Bt @ v
    for k in range(2):
        hold[k] = ev[k]
        if ev[k]:
            for r in range(2):
                e[k, r] = P[k, r] @ w0[:4]
            s0[k] = math.sqrt(e[k, 0] ** 2 + e[k, 1] ** 2)
            e[k, 0] /= s0[k]
            e[k, 1] /= s0[k]
            hold_dir[k, 0] = -mu_N[k] * e[k, 0]
            hold_dir[k, 1] = -mu_N[k] * e[k, 1]
            d0[k] = e[k, 0] * (P[k, 0] @ alpha[:4]) + e[k, 1] * (P[k, 1] @ alpha[:4])


@njit(cache=True)
def _event_time(alpha_held, ev, e, s0, d0, h, P, hold):
    """Event fraction ``θ`` of the step (:func:`_event_fraction` of each face marked in ``ev``, from the held
    step's end rate ``alpha_held = Bt a``), the earliest; ``hold`` (in place) keeps the faces whose event is
    at ``θ`` (within ``SAME_EVENT``). Returns ``θ``, or 2 if no face's velocity reaches zero in the step."""
    th = np.full(2, 2.0)
    theta = 2.0
    for k in range(2):
        if ev[k]:
            d1 = e[k, 0] * (P[k, 0] @ alpha_held[:4]) + e[k, 1] * (P[k, 1] @ alpha_held[:4])
            f = _event_fraction(s0[k], d0[k], d1, h)
            if f >= 0.0:
                th[k] = f
                theta = min(theta, f)
    for k in range(2):
        hold[k] = ev[k] and th[k] <= theta + SAME_EVENT
    return theta


@njit(cache=True)
def _release_fraction(f_start, f_end, released, mu_N, hold):
    """Fraction ``θ ∈ [0, 1]`` of the step at which the holding force of a released face, linear between its start
    ``f_start[k]`` and its stuck end ``f_end[k]`` (N, (2, 2)), reaches ``μN`` in magnitude: the root of
    ``|f_s + θ (f_e − f_s)|² = (μN)²``, the earliest over the faces marked in ``released``; ``hold`` (in place)
    keeps the faces whose release is at ``θ`` (within ``SAME_EVENT``)."""
    th = np.full(2, 2.0)
    theta = 1.0
    for k in range(2):
        if released[k]:
            d0 = f_end[k, 0] - f_start[k, 0]
            d1 = f_end[k, 1] - f_start[k, 1]
            qa = d0 * d0 + d1 * d1
            qb = 2.0 * (f_start[k, 0] * d0 + f_start[k, 1] * d1)
            qc = f_start[k, 0] ** 2 + f_start[k, 1] ** 2 - mu_N[k] ** 2
            if qc >= 0.0 or qa == 0.0:
                f = 0.0
            else:
                f = (-qb + math.sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa)
            th[k] = min(max(f, 0.0), 1.0)
            theta = min(theta, th[k])
    for k in range(2):
        hold[k] = released[k] and th[k] <= theta + SAME_EVENT
    return theta
