"""The compiled step loop of the production integrator (:func:`rotor.dynamics.production.simulate_production`).

One step: predictor, condensed Newton with the active-set loop (:func:`rotor.dynamics.production_kernels.
_solve_support`, the stick/slip rules of :mod:`rotor.dynamics.constraints`), correction, stick-onset
re-projection. With ``locate_events`` (on by default), a step in which a face's slip velocity reached zero is
redone in three passes of the same step body (:mod:`rotor.dynamics.friction_events`): (1) re-solved with the
event faces' friction held, which gives the event time; (2) the sub-step up to the event, friction
held; the friction state is switched at the event; (3) the sub-step from the event to the end. A release is
redone in passes (2) and (3), its time from the holding force; a slow slip's friction is held over its step
(friction_events, "Release" and "Slow slips"). A step in which an edge penetration of the support changed sign
(contact onset or loss, :mod:`rotor.dynamics.contact_events`) is redone in passes (2) and (3) at the crossing,
with no switch at it (the force is continuous there); with ``locate_events`` off none of this runs.

The step body is written once, inside the loop over the steps: called as a function it cost ~12 % of
the step (measured on the Table 4 rotor: the reference counts of the ~30 arrays it takes, per call).
For the same reason the step allocates nothing and binds no new array names: its vectors are work
arrays made once before the loop and written in place, its matrix-vector products go through
:func:`rotor.dynamics.production_kernels.matvec_into` (numba's own BLAS call of ``a @ x``, so the same
numbers), views are made once. Each array bound or passed is an atomic reference-count increment and
decrement; before these changes they were ~45 % of the step and the temporary arrays another ~10 %
(perf on the Table 4 rotor at 10 500 rpm; ``benchmarks/bench_step_loop.py`` times the step against the
earlier code, ``reports/published/perf-step-loop.md``). The results are bit-identical to that code's.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from contact.compiled_cache import compiled_with
from contact.loose_support import point_force_jacobian
from rotor.dynamics.contact_events import crossing_fraction, edge_crossing
from rotor.dynamics.friction_events import (_event_time, _held_friction, _release_fraction, _substep_matrices,
                                            _switch_at_event, _velocity_events)
from rotor.dynamics.kernels import law_tuple
from rotor.dynamics.production_kernels import (_load, _mode_update, _reproject, _solve_support, NC, VG, VX, matvec_into,
                                               newton_work)

compiled_with(__file__, ["rotor.dynamics.contact_events", "rotor.dynamics.friction_events",
                         "rotor.dynamics.production_kernels",
                         "rotor.dynamics.constraints", "rotor.dynamics.kernels", "contact._kernel",
                         "contact._kernel_friction", "contact._kernel_tilt"])

PLAIN, HELD, TO_EVENT, FROM_EVENT = 0, 1, 2, 3   # passes of a step (module docstring)
RELEASE_HOLD = 1000.0   # slow slips (friction_events, "Slow slips") are held below this many w_reg
RECTILINEAR = 1e-9      # a slow slip is rectilinear where sin² of its velocity-acceleration angle is below this
# a slip slower than this many w_reg at the step's start has no located stop (reversals: w_reg); not w_reg itself:
# a face creeping to a stop at ~w_reg (the regularised force's deficit) starts its last step just above w_reg, and that
# threshold made the located map jump there (Table 4, 8 400 rpm, T/512: start speed 1.007 w_reg, the stick onset
# step's derivative toggled at 1e-6 perturbations, located monodromy 0.41 from central differences)
EVENT_SPEED = 1e-3


@njit(cache=True, nogil=True)
def _faces_from_start(modes, modes0, phi_face, phi0, just_released, jr0):
    """The end faces' state (modes, face forces, released flags) back to the step's start, before a step is redone
    up to an event inside it."""
    modes[:] = modes0
    phi_face[:, :] = phi0
    just_released[:] = jr0


@njit(cache=True, nogil=True)   # nogil: a run in a thread of its own leaves the main thread to honour Ctrl-C
def step_loop(p, v, a, modes, phi_face, t0, dt, n_steps, record_every,
              Ainv, Dr, Kr, Bt, W, S, static, orders, cosm, sinm, omega_f, P, mu_N, n_faces, s_yy, a1,
              has_support, params, beta, gamma, tol, max_iter, w_reg, w_stick, max_passes, stick_mean_weight,
              onset_projection, Minv, WM, SM, Mr, locate_events, split_events,
              rec_t, rec_p, rec_v, rec_a, rec_u, rec_w, rec_fc, rec_fel, rec_face, rec_modes, rec_its, rec_passes,
              status):
    """The ``n_steps`` steps of :func:`rotor.dynamics.production.simulate_production` on the reduced
    coordinates ``p = Tᵀ q``: predictor, condensed Newton with the active-set loop, correction,
    stick-onset re-projection, friction events located if ``locate_events``, recording every
    ``record_every`` steps into ``rec_*``. ``p, v, a, modes, phi_face`` are updated in place. ``split_events``
    False (with ``locate_events``): each step is the located step body's first pass alone, never split at an event
    (the passes replayed one by one for an event step's derivative, rotor/dynamics/contact_step_derivative.py). ``status`` (7,):
    [0 ok / 2 non-finite, failing step, least-residual steps, stick-onset re-projections, located friction
    events, and for each face how its force was held in the last step body (0 not held, 1 a slow slip held at
    Coulomb's force along its start velocity, 2 a face at rest held at its force; friction_events, "Slow slips")].
    Returns ``(steps done, largest ω_c Δt)``."""
    nr = p.shape[0]
    alpha = Bt @ a
    # the step's vectors, written in place (an array expression or a matvec result is an allocation, and
    # every array bound to a new name a reference count)
    p_pre, v_pre, rhs, a_lin, d_v, k_p, pn, vn, an, wg = (np.empty(nr), np.empty(nr), np.empty(nr), np.empty(nr),
                                                        np.empty(nr), np.empty(nr), np.empty(nr), np.empty(nr),
                                                        np.empty(nr), np.empty(nr))
    alpha_lin, u_pre, w_pre, wv, u_new, w_new, w_end = (np.empty(NC), np.empty(NC), np.empty(NC), np.empty(NC),
                                                        np.empty(NC), np.empty(NC), np.empty(NC))
    wdt_max = 0.0
    pt = law_tuple(params)      # the law's parameters, as rotor.dynamics.kernels.contact_point passes them
    freeze = np.zeros(2, dtype=np.bool_)
    freeze_dir = np.zeros((2, 2))
    w_old = np.zeros((2, 2))
    phi_old = np.zeros((2, 2))
    tried = np.zeros(2, dtype=np.bool_)
    stuck0 = np.zeros(2, dtype=np.bool_)
    just_released = np.zeros(2, dtype=np.bool_)
    phi_c = np.zeros((2, 2))
    Q = np.empty(nr)
    vec, mat, face, jac = newton_work()
    phi = np.zeros((2, 2))
    fk, wk, wo, fo = np.empty(2), np.empty(2), np.empty(2), np.empty(2)   # one face's force, velocities, old force
    # views made once (a view made in the loop is a reference count): the faces' maps, the support's velocities
    P_0, P_1, wv4, w_new4, w_old_0, w_old_1 = P[0], P[1], wv[:4], w_new[:4], w_old[0], w_old[1]
    alpha_new = vec[VX, :NC]
    g = vec[VG, :NC]
    # event location: the step's start state, its plain result, the held friction
    locate = locate_events and has_support
    split = locate and split_events
    hold = np.zeros(2, dtype=np.bool_)
    hold_dir = np.zeros((2, 2))
    ev = np.zeros(2, dtype=np.bool_)
    e_dir = np.zeros((2, 2))
    s0 = np.zeros(2)
    d0 = np.zeros(2)
    modes0 = modes.copy()
    phi0 = phi_face.copy()
    jr0 = just_released.copy()
    modes_pl = modes.copy()
    phi_pl = phi_face.copy()
    jr_pl = just_released.copy()
    p_pl, v_pl, a_pl, al_pl = np.empty(nr), np.empty(nr), np.empty(nr), np.empty(NC)
    # a face released (stick -> slip) slips with its release force mu_N (direction of the holding force at the
    # release) until its speed passes RELEASE_HOLD w_reg (friction_events, "Release")
    rel = np.zeros(2, dtype=np.bool_)
    rel_dir = np.zeros((2, 2))
    w_hold = RELEASE_HOLD * w_reg
    # the low-speed stick trial: with the events located a stop is where the velocity reaches zero (a reversal,
    # located), so only a face slower than w_reg (no slip direction) is tried in stick before; the plain rule's
    # w_stick sticks a face a step early and, a threshold on the step grid, makes the located map jump (Table 4 at
    # 10 500 rpm, T/512: 14 switches a period and central differences that do not converge, against 4 and 4.9e-7)
    w_try = min(w_stick, w_reg) if locate else w_stick
    # a release inside the step: the faces released in the plain pass, their holding force at its start and end
    rel_ev = np.zeros(2, dtype=np.bool_)
    rel_fs = np.zeros((2, 2))
    rel_fe = np.zeros((2, 2))
    release_event = False
    stuck_at_event = False      # a face stuck at the located event: the rest of the step ends consistent
    contact_event = False       # an edge penetration crossing zero located in the step (contact_events)
    u_s = np.empty(NC)
    Ai, Wh, Sh = Ainv, W, S
    h = dt
    h1 = 0.0
    phase = PLAIN
    step_its = 0
    step_passes = 0
    step = 1
    while step <= n_steps:
        t = t0 + step * dt
        if phase == TO_EVENT:
            t = t0 + (step - 1) * dt + h1
        if phase == PLAIN and locate:
            for k in range(2):
                modes0[k] = modes[k]
                phi0[k, 0] = phi_face[k, 0]
                phi0[k, 1] = phi_face[k, 1]
                jr0[k] = just_released[k]
                rel_ev[k] = False
        # ---------------------------------------------------------------- the step body, length h
        bdt2 = beta * h * h
        gdt = gamma * h
        cp = h * h * (0.5 - beta)
        cv = h * (1.0 - gamma)
        for i in range(nr):
            p_pre[i] = p[i] + h * v[i] + cp * a[i]
            v_pre[i] = v[i] + cv * a[i]
        _load(t, static, orders, cosm, sinm, omega_f, Q)
        matvec_into(Dr, v_pre, d_v)
        matvec_into(Kr, p_pre, k_p)
        for i in range(nr):
            rhs[i] = Q[i] - d_v[i] - k_p[i]
        matvec_into(Ai, rhs, a_lin)
        total_its = 0
        passes = 0
        onset = False
        wd = 0.0
        if has_support:
            matvec_into(Bt, a_lin, alpha_lin)
            matvec_into(Bt, p_pre, u_pre)
            matvec_into(Bt, v_pre, w_pre)
            matvec_into(Bt, v, wv)
            matvec_into(P_0, wv4, w_old_0)
            matvec_into(P_1, wv4, w_old_1)
            for k in range(2):
                # a slow slip, w_reg < |w| < w_hold: Coulomb's force along the start-of-step slip, held over the
                # step, not the regularised one (its deficit near a stop or after a release is w_reg-sized); a
                # face at rest whose force is at mu_N (just released): that force, held (friction_events, "Slow
                # slips"). Decided from the step's start alone, so a step replayed from its start is the same step.
                rel[k] = False
                held_kind = 0
                sw2 = w_old[k, 0] ** 2 + w_old[k, 1] ** 2
                if locate and modes[k] == 0:
                    fn = math.sqrt(phi_face[k, 0] ** 2 + phi_face[k, 1] ** 2)
                    held = fn >= mu_N[k] * (1.0 - 1e-9) and fn > 0.0
                    if w_reg * w_reg < sw2 < w_hold * w_hold:
                        # a rectilinear slow slip (its acceleration along its velocity: Den Hartog's stops), whose
                        # direction the step keeps: held too
                        ay = P[k, 0, 0] * alpha[0] + P[k, 0, 1] * alpha[1] + P[k, 0, 2] * alpha[2] + P[k, 0, 3] * alpha[3]
                        az = P[k, 1, 0] * alpha[0] + P[k, 1, 1] * alpha[1] + P[k, 1, 2] * alpha[2] + P[k, 1, 3] * alpha[3]
                        cr = w_old[k, 0] * az - w_old[k, 1] * ay
                        held = cr * cr <= RECTILINEAR * sw2 * (ay * ay + az * az)
                    if held and w_reg * w_reg < sw2 < w_hold * w_hold:
                        rel[k] = True
                        sw = math.sqrt(sw2)
                        rel_dir[k, 0] = -mu_N[k] * w_old[k, 0] / sw
                        rel_dir[k, 1] = -mu_N[k] * w_old[k, 1] / sw
                        held_kind = 1
                    elif sw2 <= w_reg * w_reg:
                        if held:
                            rel[k] = True
                            rel_dir[k, 0] = mu_N[k] * phi_face[k, 0] / fn
                            rel_dir[k, 1] = mu_N[k] * phi_face[k, 1] / fn
                            held_kind = 2
                status[5 + k] = held_kind
                # a held face starting from rest: no reversal test (w_old = 0), it slips
                tried[k] = modes[k] == 1 or (rel[k] and sw2 <= w_reg * w_reg)
                stuck0[k] = modes[k] == 1
                freeze[k] = hold[k] or rel[k]
                if hold[k]:
                    freeze_dir[k, 0] = hold_dir[k, 0]
                    freeze_dir[k, 1] = hold_dir[k, 1]
                elif rel[k]:
                    freeze_dir[k, 0] = rel_dir[k, 0]
                    freeze_dir[k, 1] = rel_dir[k, 1]
                phi_old[k, 0] = phi_face[k, 0]
                phi_old[k, 1] = phi_face[k, 1]
                if modes[k] == 2:
                    # a projected face (rotor.dynamics.constraints.coulomb_projection): Coulomb's bound on the step
                    # mean of its force, the start force carried in the freeze slots
                    freeze[k] = True
                    freeze_dir[k, 0] = phi_face[k, 0]
                    freeze_dir[k, 1] = phi_face[k, 1]
            g[:] = 0.0
            while True:
                passes += 1
                its, ok = _solve_support(alpha, alpha_lin, u_pre, w_pre, Sh, P, modes, phi_face, freeze, freeze_dir,
                                         mu_N, a1, bdt2, gdt, params, tol, max_iter, w_reg, vec, mat, face, jac,
                                         phi)
                total_its += its
                if not ok:
                    # slip Newton stalls when the true answer is (near) stick: try stick on the
                    # slipping faces not yet tried in this step, else give up
                    flipped = False
                    for k in range(n_faces):
                        if modes[k] == 0 and not tried[k] and not hold[k] and not rel[k]:
                            modes[k] = 1
                            tried[k] = True
                            phi_face[k] = phi[k]
                            flipped = True
                    if flipped and passes < max_passes + 4:
                        for k in range(2):
                            freeze[k] = hold[k] or rel[k] or modes[k] == 2
                            if rel[k] and not hold[k]:
                                freeze_dir[k, 0] = rel_dir[k, 0]
                                freeze_dir[k, 1] = rel_dir[k, 1]
                        continue
                    # no exact root (e.g. the sharp one-edge selection of the law, edge_transition_m
                    # = 0, where the edge penetrations cross): keep the least-residual iterate, count it
                    status[2] += 1
                    alpha[:] = alpha_new
                    for k in range(2):
                        phi_face[k] = phi[k]
                    break
                alpha[:] = alpha_new
                if ((freeze[0] and modes[0] != 2 and not (hold[0] or rel[0]))
                        or (freeze[1] and modes[1] != 2 and not (hold[1] or rel[1]))):
                    for k in range(2):
                        freeze[k] = hold[k] or rel[k] or modes[k] == 2
                    continue
                for i in range(NC):
                    w_new[i] = w_pre[i] + gdt * alpha[i]
                changed = False
                # a face trying stick in this step (slipping at its start) is tested on its holding
                # force at the end of the step, the consistent multiplier (stick-onset re-projection),
                # not on the trapezoidal one that carries the velocity jump (f_n+1 = 2 f̄ − f_n); the
                # other face, if stuck, on its consistent multiplier too (the one the step will keep)
                use_c = False
                if onset_projection:
                    for k in range(2):
                        if modes[k] == 1 and not stuck0[k]:
                            use_c = True
                if use_c:
                    a_try = a_lin + Wh @ g
                    for k in range(2):
                        phi_c[k, 0] = phi[k, 0]
                        phi_c[k, 1] = phi[k, 1]
                    _reproject(p_pre + bdt2 * a_try, v_pre + gdt * a_try, Q, Minv, Dr, Kr, Bt, WM, SM, P, modes,
                               mu_N, a1, params, w_reg, phi_c)
                for k in range(n_faces):
                    if hold[k] or modes[k] == 2:
                        continue
                    if k == 0:
                        matvec_into(P_0, w_new4, wk)
                    else:
                        matvec_into(P_1, w_new4, wk)
                    if use_c and modes[k] == 1:
                        fk[0] = phi_c[k, 0]
                        fk[1] = phi_c[k, 1]
                    else:
                        fk[0] = phi[k, 0]
                        fk[1] = phi[k, 1]
                    wo[0] = w_old[k, 0]
                    wo[1] = w_old[k, 1]
                    fo[0] = phi_old[k, 0]
                    fo[1] = phi_old[k, 1]
                    nm = _mode_update(modes[k], fk, wk, wo, mu_N[k], 0.0 if (just_released[k] or rel[k]) else w_try,
                                      tried[k], fo, stick_mean_weight if stuck0[k] else 0.0)
                    if locate and phase == PLAIN and nm == 1 and stuck0[k]:
                        # stuck through the step by the impulse bound, but its end holding force past mu_N: the
                        # release is inside this step, located (the plain rule releases it a step late)
                        rel_ev[k] = fk[0] ** 2 + fk[1] ** 2 > (mu_N[k] * (1.0 + 1e-12)) ** 2
                        if rel_ev[k]:
                            rel_fs[k, 0] = fo[0]
                            rel_fs[k, 1] = fo[1]
                            rel_fe[k, 0] = fk[0]
                            rel_fe[k, 1] = fk[1]
                    if nm != modes[k]:
                        changed = True
                        modes[k] = nm
                        if nm == 1:
                            tried[k] = True
                            phi_face[k] = phi[k]
                            rel[k] = False
                            rel_ev[k] = False
                        else:
                            nrm = math.sqrt(fk[0] ** 2 + fk[1] ** 2)
                            freeze[k] = True
                            if nrm > 0:
                                freeze_dir[k, 0] = mu_N[k] * fk[0] / nrm
                                freeze_dir[k, 1] = mu_N[k] * fk[1] / nrm
                            else:
                                freeze_dir[k] = 0.0
                            if locate and stuck0[k] and nrm > 0:
                                rel[k] = True
                                rel_dir[k, 0] = freeze_dir[k, 0]
                                rel_dir[k, 1] = freeze_dir[k, 1]
                                if phase == PLAIN:
                                    rel_ev[k] = True
                                    rel_fs[k, 0] = fo[0]
                                    rel_fs[k, 1] = fo[1]
                                    rel_fe[k, 0] = fk[0]
                                    rel_fe[k, 1] = fk[1]
                if not changed or passes >= max_passes:
                    for k in range(2):
                        phi_face[k] = phi[k]
                    break
            matvec_into(Wh, g, wg)
            for i in range(nr):
                an[i] = a_lin[i] + wg[i]
            if onset_projection:
                for k in range(2):
                    if modes[k] == 1 and not stuck0[k]:
                        onset = True
            if phase == FROM_EVENT and stuck_at_event:
                # the sub-step took the face's velocity at the event (the root of the held step's velocity
                # polynomial, not of this sub-step's: O(h^3) apart) to zero; restarting from the consistent
                # acceleration keeps that jump from ringing in the stuck multipliers
                onset = True
            # largest ω_c Δt met: radial tangent stiffness of the law at the new state
            for i in range(NC):
                u_new[i] = u_pre[i] + bdt2 * alpha[i]
                w_new[i] = w_pre[i] + gdt * alpha[i]
            point_force_jacobian(u_new[0], u_new[1], u_new[2], u_new[3], w_new[0], w_new[1], w_new[2], w_new[3], pt,
                                 jac)
            kt = -(jac[0, 0] + jac[1, 1])
            if kt > 0:
                wd = math.sqrt(kt * s_yy) * h
        else:
            an[:] = a_lin
        for i in range(nr):
            pn[i] = p_pre[i] + bdt2 * an[i]
            vn[i] = v_pre[i] + gdt * an[i]
        for k in range(2):
            just_released[k] = onset_projection and modes[k] == 0 and stuck0[k]
        if onset:
            # a face stuck in this step: restart from the consistent acceleration (positions and
            # velocities of the step kept), so the stuck multiplier does not ring
            an[:] = _reproject(pn, vn, Q, Minv, Dr, Kr, Bt, WM, SM, P, modes, mu_N, a1, params, w_reg, phi_face)
            matvec_into(Bt, an, alpha)
            status[3] += 1
        if wd > wdt_max:
            wdt_max = wd
        step_its += total_its
        step_passes += passes
        # ---------------------------------------------------------------- event location (passes of the step)
        if phase == PLAIN:
            if split:
                matvec_into(Bt, vn, w_end)          # (wv = Bt v, the step's start, from the step body)
            if split and _velocity_events(wv, w_end, modes0, modes, jr0, P, n_faces, w_reg, ev, mu_N,
                                             EVENT_SPEED * w_reg) > 0:
                p_pl[:] = pn                                        # the plain result, kept
                v_pl[:] = vn
                a_pl[:] = an
                al_pl[:] = alpha
                modes_pl[:] = modes
                phi_pl[:, :] = phi_face
                jr_pl[:] = just_released
                _faces_from_start(modes, modes0, phi_face, phi0, just_released, jr0)
                matvec_into(Bt, a, alpha)
                _held_friction(v, alpha, ev, Bt, P, mu_N, e_dir, s0, d0, hold, hold_dir)
                phase = HELD
                continue
            if split and (rel_ev[0] or rel_ev[1]):
                # a release: the step redone up to the instant the holding force reached mu_N, the faces kept
                # stuck (hold), released there (friction_events, "Release")
                # the holding force at the start: the consistent one at the start's (p, v) (a function of the
                # step's start, so that the located map is differentiable there), not the recorded multiplier
                _load(t - dt, static, orders, cosm, sinm, omega_f, Q)
                phi_s = phi0.copy()
                _reproject(p, v, Q, Minv, Dr, Kr, Bt, WM, SM, P, modes0, mu_N, a1, params, w_reg, phi_s)
                for k in range(2):
                    rel_fs[k, 0] = phi_s[k, 0]
                    rel_fs[k, 1] = phi_s[k, 1]
                theta = _release_fraction(rel_fs, rel_fe, rel_ev, mu_N, hold)
                _faces_from_start(modes, modes0, phi_face, phi0, just_released, jr0)
                matvec_into(Bt, a, alpha)
                release_event = True
                h1 = theta * dt
                if h1 > 1e-12 * dt:
                    Ai, Wh, Sh = _substep_matrices(h1, Mr, Dr, Kr, Bt, beta, gamma)
                    h = h1
                    phase = TO_EVENT
                    continue
                h1 = 0.0
                pn[:] = p
                vn[:] = v
                an[:] = a
                phase = TO_EVENT
            if split and phase == PLAIN:
                # contact onset or loss: an edge penetration that changed sign over the step (contact_events); the
                # step redone up to the crossing with the start's friction state, the rest of the step follows
                matvec_into(Bt, p, u_s)
                if edge_crossing(u_s, u_new, params):
                    theta = crossing_fraction(u_s, wv, u_new, w_new, dt, params)
                    if 1e-12 < theta < 1.0 - 1e-12:
                        _faces_from_start(modes, modes0, phi_face, phi0, just_released, jr0)
                        matvec_into(Bt, a, alpha)
                        contact_event = True
                        h1 = theta * dt
                        Ai, Wh, Sh = _substep_matrices(h1, Mr, Dr, Kr, Bt, beta, gamma)
                        h = h1
                        phase = TO_EVENT
                        continue
        elif phase == HELD:
            theta = _event_time(alpha, ev, e_dir, s0, d0, h, P, hold)
            _faces_from_start(modes, modes0, phi_face, phi0, just_released, jr0)
            if theta > 1.0:                     # not reached with the friction held: the plain result stands
                hold[:] = False
                pn[:] = p_pl
                vn[:] = v_pl
                an[:] = a_pl
                alpha[:] = al_pl
                modes[:] = modes_pl
                phi_face[:, :] = phi_pl
                just_released[:] = jr_pl
                phase = PLAIN
            else:
                matvec_into(Bt, a, alpha)
                h1 = theta * dt
                if h1 > 1e-12 * dt:
                    Ai, Wh, Sh = _substep_matrices(h1, Mr, Dr, Kr, Bt, beta, gamma)
                    h = h1
                    phase = TO_EVENT
                    continue
                h1 = 0.0                        # the event at the start of the step
                pn[:] = p
                vn[:] = v
                an[:] = a
                phase = TO_EVENT
        if phase == TO_EVENT:
            # the friction state switched at the event, the consistent acceleration, then the rest of the step
            if not contact_event:
                _load(t0 + (step - 1) * dt + h1, static, orders, cosm, sinm, omega_f, Q)
                an[:] = _switch_at_event(pn, vn, Q, Minv, Dr, Kr, Bt, WM, SM, P, modes, phi_face, just_released, hold,
                                         mu_N, a1, params, w_reg)
            for k in range(2):
                nrm = math.sqrt(phi_face[k, 0] ** 2 + phi_face[k, 1] ** 2)
                if hold[k] and release_event and modes[k] == 1 and nrm > 0:
                    # at the located release the holding force is mu_N to the step's accuracy: released, its
                    # force mu_N along the holding force (held from rest in the rest of the step)
                    modes[k] = 0
                    just_released[k] = True
                    phi_face[k, 0] = mu_N[k] * phi_face[k, 0] / nrm
                    phi_face[k, 1] = mu_N[k] * phi_face[k, 1] / nrm
            stuck_at_event = False
            for k in range(2):
                if hold[k] and modes[k] == 1:
                    stuck_at_event = True
            hold[:] = False
            release_event = False
            contact_event = False
            status[4] += 1
            p[:] = pn
            v[:] = vn
            a[:] = an
            matvec_into(Bt, an, alpha)
            h = dt - h1
            if h > 1e-12 * dt:
                Ai, Wh, Sh = _substep_matrices(h, Mr, Dr, Kr, Bt, beta, gamma)
                phase = FROM_EVENT
                continue
        if phase != PLAIN:                      # the step is complete: back to the plain step's matrices
            Ai, Wh, Sh = Ainv, W, S
            h = dt
            phase = PLAIN
        # ---------------------------------------------------------------- the step is done
        p[:] = pn
        v[:] = vn
        a[:] = an
        fin = True
        for i in range(nr):
            if not (math.isfinite(p[i]) and math.isfinite(v[i])):
                fin = False
        if not fin:
            status[0] = 2
            status[1] = step
            return step - 1, wdt_max
        if step % record_every == 0:
            i = step // record_every
            rec_t[i] = t
            rec_p[i] = p
            rec_v[i] = v
            rec_a[i] = a
            rec_its[i] = step_its
            rec_passes[i] = step_passes
            if has_support:
                matvec_into(Bt, p, u_new)
                matvec_into(Bt, v, w_new)
                for r in range(4):
                    rec_u[i, r] = u_new[r]
                    rec_w[i, r] = w_new[r]
                rec_fc[i, 0], rec_fc[i, 1], rec_fc[i, 2], rec_fc[i, 3] = point_force_jacobian(
                    u_new[0], u_new[1], u_new[2], u_new[3], w_new[0], w_new[1], w_new[2], w_new[3], pt, jac)
                rec_fel[i, 0], rec_fel[i, 1], rec_fel[i, 2], rec_fel[i, 3] = point_force_jacobian(
                    u_new[0], u_new[1], u_new[2], u_new[3], 0.0, 0.0, 0.0, 0.0, pt, jac)
                for k in range(2):
                    rec_face[i, k, 0] = phi_face[k, 0]
                    rec_face[i, k, 1] = phi_face[k, 1]
                rec_modes[i, 0] = modes[0]
                rec_modes[i, 1] = modes[1]
        step_its = 0
        step_passes = 0
        step += 1
    return n_steps, wdt_max
