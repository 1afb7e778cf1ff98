"""The compiled step loop of the production integrator (:func:`rotor.dynamics.production.simulate_production`).

Each step is :func:`rotor.dynamics.production_kernels._newmark_step`; with ``locate_events`` a step in
which a face's slip velocity reached zero is redone with the event located and the step split there
(:func:`rotor.dynamics.friction_events._split_step`). Records every ``record_every`` steps.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from contact.compiled_cache import compiled_with
from rotor.dynamics.friction_events import _split_step, _velocity_events
from rotor.dynamics.kernels import contact_kernel
from rotor.dynamics.production_kernels import _newmark_step

compiled_with(__file__, ["rotor.dynamics.friction_events", "rotor.dynamics.production_kernels",
                         "rotor.dynamics.constraints", "rotor.dynamics.kernels", "contact._kernel"])


@njit(cache=True)
def step_loop(p, v, a, modes, phi_face, t0, dt, n_steps, record_every,
              Ainv, Dr, Kr, Bt, W, S, static, orders, cosm, sinm, omega_f, P, mu_N, n_faces, s_yy, a1,
              has_support, params, beta, gamma, tol, max_iter, w_reg, w_stick, max_passes, stick_mean_weight,
              onset_projection, Minv, WM, SM, Mr, locate_events,
              rec_t, rec_p, rec_v, rec_a, rec_u, rec_w, rec_fc, rec_fel, rec_face, rec_modes, rec_its, rec_passes,
              status):
    """The ``n_steps`` steps of :func:`rotor.dynamics.production.simulate_production` on the reduced
    coordinates ``p = Tᵀ q``, recording every ``record_every`` steps into ``rec_*``. ``p, v, a,
    modes, phi_face`` are updated in place. ``status``: [0 ok / 2 non-finite, failing step,
    least-residual steps, stick-onset re-projections, located friction events]. Returns
    ``(steps done, largest ω_c Δt)``."""
    nr = p.shape[0]
    alpha = Bt @ a
    wdt_max = 0.0
    zero4 = np.zeros(4)
    no_hold = np.zeros(2, dtype=np.bool_)
    hold_dir = np.zeros((2, 2))
    just_released = np.zeros(2, dtype=np.bool_)
    ev = np.zeros(2, dtype=np.bool_)
    modes0 = modes.copy()
    phi0 = phi_face.copy()
    jr0 = just_released.copy()
    locate = locate_events and has_support
    for step in range(1, n_steps + 1):
        t = t0 + step * dt
        if locate:
            modes0[:] = modes
            phi0[:, :] = phi_face
            jr0[:] = just_released
        pn, vn, an, aln, total_its, passes, wd, _ = _newmark_step(
            p, v, a, alpha, modes, phi_face, just_released, t, dt, Ainv, Dr, Kr, Bt, W, S, static, orders, cosm, sinm,
            omega_f, P, mu_N, n_faces, s_yy, a1, has_support, params, beta, gamma, tol, max_iter, w_reg, w_stick,
            max_passes, stick_mean_weight, onset_projection, Minv, WM, SM, no_hold, hold_dir, status)
        if locate and _velocity_events(v, vn, modes0, modes, jr0, Bt, P, n_faces, w_reg, ev) > 0:
            done, ps, vs, as_, als, its2, passes2, wd2 = _split_step(
                p, v, a, alpha, modes0, phi0, jr0, ev, t, dt, Ainv, Dr, Kr, Bt, W, S, static, orders, cosm, sinm,
                omega_f, P, mu_N, n_faces, s_yy, a1, has_support, params, beta, gamma, tol, max_iter, w_reg, w_stick,
                max_passes, stick_mean_weight, onset_projection, Minv, WM, SM, Mr, status)
            total_its += its2
            passes += passes2
            if done:
                pn, vn, an, aln = ps, vs, as_, als
                modes[:] = modes0
                phi_face[:, :] = phi0
                just_released[:] = jr0
                wd = max(wd, wd2)
                status[4] += 1
        p, v, a, alpha = pn, vn, an, aln
        if wd > wdt_max:
            wdt_max = wd
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
            rec_its[i] = total_its
            rec_passes[i] = passes
            if has_support:
                uu = Bt @ p
                ww = Bt @ v
                rec_u[i] = uu[:4]
                rec_w[i] = ww[:4]
                f, Ju, Jv = contact_kernel(uu[:4], ww[:4], params)
                rec_fc[i] = f
                fe, Ju, Jv = contact_kernel(uu[:4], zero4, params)
                rec_fel[i] = fe
                rec_face[i] = phi_face
                rec_modes[i, 0] = modes[0]
                rec_modes[i, 1] = modes[1]
    return n_steps, wdt_max
