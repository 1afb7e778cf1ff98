"""Production integrator: the same Newmark/constraint discretisation as :mod:`rotor.integrate`, fast.

Same equations, same step, same stick/slip logic (:mod:`rotor.constraints`), hence the
same answer to the Newton tolerance. What makes it fast:

1. **Lock eliminated exactly.** ``q = T p`` with ``T`` an orthonormal basis of
   ``{L q = 0}`` (3a/3b equal displacement), so no multipliers for the lock.
2. **Linear part factorised once per (Δt, ω).** ``A = M + γΔt (C − ωG) + βΔt² K`` is
   inverted once (dense; the model has a few dozen DOFs) in :func:`prepare`.
3. **Condensation to the four relative support coordinates.** The nonlinear forces act
   only through ``u = B q`` (bearing minus support, 4 DOFs), so with
   ``W = A⁻¹ Bᵀ`` and ``S = B A⁻¹ Bᵀ`` (4×4) the step reduces to
   ``α = α_lin + S g(u(α), w(α), φ)`` for the relative acceleration ``α`` (4 unknowns),
   plus two multipliers per stuck face, solved by Newton with the **analytic Jacobian**
   of the contact law (``SupportLaw.kernel``) and of the slip force.
   The full acceleration is then ``q̈ = q̈_lin + W g``.
4. **Compiled step loop** (numba ``njit``): measured in ``benchmarks/bench_integrators.py``;
   the same loop in numpy costs tens of µs per step in call overhead alone, while the
   5-s target for one steady-state point needs a few µs per step.

A runtime check records the largest ``ω_c Δt`` met, with ``ω_c² = k_t (B M⁻¹ Bᵀ)_yy`` and
``k_t`` the current radial tangent stiffness of the law, so a too-large step is
reported after the fact as well as refused up front (:func:`rotor.integrate.check_time_step`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from contact.errors import ConvergenceError, InputError
from rotor import constraints as cons
from rotor.integrate import (NewmarkOptions, RotorSystem, Trajectory, _allocate, _check_inputs, check_time_step,
                             initial_acceleration, relative_compliance)

_slip_force = njit(cache=True)(cons.slip_force)
_mode_update = njit(cache=True)(cons.face_mode_update)


@njit(cache=True)
def _null_kernel(u, v, p):
    return np.zeros(4), np.zeros((4, 4)), np.zeros((4, 4))


@dataclass(frozen=True)
class Prepared:
    """Everything the compiled loop needs for one (system, Δt) pair."""

    T: np.ndarray
    Ainv: np.ndarray
    Dr: np.ndarray
    Kr: np.ndarray
    Bt: np.ndarray
    W: np.ndarray
    S: np.ndarray
    static: np.ndarray
    orders: np.ndarray
    cos: np.ndarray
    sin: np.ndarray
    omega_force: float
    P: np.ndarray
    mu_N: float
    s_yy: float
    dt: float


def prepare(system: RotorSystem, dt: float, options: NewmarkOptions | None = None) -> Prepared:
    """Reduce, factorise and condense ``system`` for step ``dt`` (s)."""
    opts = options or NewmarkOptions()
    n = system.n
    T = cons.null_space_map(system.lock)
    Mr = T.T @ system.M @ T
    Dr = T.T @ system.D @ T
    Kr = T.T @ system.K @ T
    A = Mr + opts.gamma * dt * Dr + opts.beta * dt * dt * Kr
    Ainv = np.linalg.inv(A)
    sup = system.support
    if sup is not None:
        B = sup.relative_map(n)
        P = np.stack(cons.face_maps(sup.width_m))
        mu_N = sup.mu_N
        s_yy = float(relative_compliance(system)[0, 0])
    else:
        B = np.zeros((4, n))
        P = np.zeros((2, 2, 4))
        mu_N = 0.0
        s_yy = 0.0
    Bt = B @ T
    W = Ainv @ Bt.T
    S = Bt @ W
    f = system.force
    static = T.T @ (f.static + system.K @ system.offset)
    return Prepared(T, Ainv, Dr, Kr, Bt, W, S, static, np.asarray(f.orders, float), f.cos @ T, f.sin @ T,
                    float(f.omega_rad_s), P, float(mu_N), s_yy, float(dt))


@njit(cache=True)
def _solve_support(alpha, alpha_lin, u_pre, w_pre, S, P, modes, phi_stuck, freeze, freeze_dir, mu_N,
                   bdt2, gdt, kernel, params, tol, max_iter, w_reg):
    """Newton on the condensed unknowns [α (4); φ of stuck faces (2 each)].

    Returns (alpha, g, phi (2,2), iterations, converged)."""
    n_st = 0
    for k in range(2):
        if modes[k] == 1:
            n_st += 1
    m = 4 + 2 * n_st
    x = np.zeros(m)
    x[:4] = alpha
    j = 4
    for k in range(2):
        if modes[k] == 1:
            x[j] = phi_stuck[k, 0]
            x[j + 1] = phi_stuck[k, 1]
            j += 2
    phi = np.zeros((2, 2))
    g = np.zeros(4)
    its = 0
    ok = False
    for it in range(max_iter):
        its = it + 1
        al = x[:4]
        u = u_pre + bdt2 * al
        w = w_pre + gdt * al
        f, Ju, Jv = kernel(u, w, params)
        g[:] = f
        Jg = Ju * bdt2 + Jv * gdt
        R = np.zeros(m)
        J = np.zeros((m, m))
        j = 4
        for k in range(2):
            Pk = P[k]
            if modes[k] == 1:
                phi[k, 0] = x[j]
                phi[k, 1] = x[j + 1]
                # dα-part: -S Pkᵀ ; constraint rows Pk w / gdt
                wk = Pk @ w
                R[j] = wk[0] / gdt
                R[j + 1] = wk[1] / gdt
                for c in range(4):
                    J[j, c] = Pk[0, c]
                    J[j + 1, c] = Pk[1, c]
                SPt = S @ Pk.T
                for r in range(4):
                    J[r, j] = -SPt[r, 0]
                    J[r, j + 1] = -SPt[r, 1]
                j += 2
            elif freeze[k]:
                phi[k, 0] = freeze_dir[k, 0]
                phi[k, 1] = freeze_dir[k, 1]
            else:
                fk, Jk = _slip_force(Pk @ w, mu_N, w_reg)
                phi[k, 0] = fk[0]
                phi[k, 1] = fk[1]
                Jg += (Pk.T @ Jk @ Pk) * gdt
            g += Pk.T @ phi[k]
        Rf = al - alpha_lin - S @ g
        R[:4] = Rf
        Jaa = np.eye(4) - S @ Jg
        J[:4, :4] = Jaa
        dx = np.linalg.solve(J, R)
        x -= dx
        nx = 0.0
        nd = 0.0
        for i in range(m):
            nx += x[i] * x[i]
            nd += dx[i] * dx[i]
        if not (nd == nd):
            break
        if math.sqrt(nd) <= tol * (math.sqrt(nx) + 1e-12):
            ok = True
            break
    # final consistent forces at the converged iterate
    al = x[:4]
    u = u_pre + bdt2 * al
    w = w_pre + gdt * al
    f, Ju, Jv = kernel(u, w, params)
    g[:] = f
    j = 4
    for k in range(2):
        if modes[k] == 1:
            phi[k, 0] = x[j]
            phi[k, 1] = x[j + 1]
            j += 2
        elif freeze[k]:
            phi[k, 0] = freeze_dir[k, 0]
            phi[k, 1] = freeze_dir[k, 1]
        else:
            fk, Jk = _slip_force(P[k] @ w, mu_N, w_reg)
            phi[k, 0] = fk[0]
            phi[k, 1] = fk[1]
        g += P[k].T @ phi[k]
    return x[:4].copy(), g, phi, its, ok


@njit(cache=True)
def _loop(p, v, a, modes, phi_face, t0, dt, n_steps, record_every,
          Ainv, Dr, Kr, Bt, W, S, static, orders, cosm, sinm, omega_f, P, mu_N, s_yy,
          has_support, kernel, params, beta, gamma, tol, max_iter, w_reg, w_stick, max_passes,
          rec_t, rec_p, rec_v, rec_a, rec_u, rec_w, rec_fc, rec_fel, rec_face, rec_modes, rec_its, rec_passes,
          status):
    nr = p.shape[0]
    bdt2 = beta * dt * dt
    gdt = gamma * dt
    H = orders.shape[0]
    alpha = Bt @ a
    wdt_max = 0.0
    zero4 = np.zeros(4)
    freeze = np.zeros(2, dtype=np.bool_)
    freeze_dir = np.zeros((2, 2))
    for step in range(1, n_steps + 1):
        t = t0 + step * dt
        p_pre = p + dt * v + dt * dt * (0.5 - beta) * a
        v_pre = v + dt * (1.0 - gamma) * a
        Q = static.copy()
        for h in range(H):
            ph = orders[h] * omega_f * t
            Q += math.cos(ph) * cosm[h] + math.sin(ph) * sinm[h]
        rhs = Q - Dr @ v_pre - Kr @ p_pre
        a_lin = Ainv @ rhs
        total_its = 0
        passes = 0
        if has_support:
            alpha_lin = Bt @ a_lin
            u_pre = Bt @ p_pre
            w_pre = Bt @ v_pre
            w_old = np.zeros((2, 2))
            wv = Bt @ v
            tried = np.zeros(2, dtype=np.bool_)
            for k in range(2):
                w_old[k] = P[k] @ wv
                tried[k] = modes[k] == 1
                freeze[k] = False
            g = np.zeros(4)
            while True:
                passes += 1
                alpha_new, g, phi, its, ok = _solve_support(alpha, alpha_lin, u_pre, w_pre, S, P, modes, phi_face,
                                                            freeze, freeze_dir, mu_N, bdt2, gdt, kernel, params,
                                                            tol, max_iter, w_reg)
                total_its += its
                if not ok:
                    status[0] = 1
                    status[1] = step
                    return step - 1, wdt_max
                alpha = alpha_new
                if freeze[0] or freeze[1]:
                    freeze[0] = False
                    freeze[1] = False
                    continue
                w_new = w_pre + gdt * alpha
                changed = False
                for k in range(2):
                    wk = P[k] @ w_new
                    nm = _mode_update(modes[k], phi[k], wk, w_old[k], mu_N, w_stick, tried[k])
                    if nm != modes[k]:
                        changed = True
                        modes[k] = nm
                        if nm == 1:
                            tried[k] = True
                            phi_face[k] = phi[k]
                        else:
                            nrm = math.sqrt(phi[k, 0] ** 2 + phi[k, 1] ** 2)
                            freeze[k] = True
                            if nrm > 0:
                                freeze_dir[k] = mu_N * phi[k] / nrm
                            else:
                                freeze_dir[k] = 0.0
                if not changed or passes >= max_passes:
                    for k in range(2):
                        phi_face[k] = phi[k]
                    break
            a = a_lin + W @ g
            # largest ω_c Δt met: radial tangent stiffness of the law at the new state
            u_new = u_pre + bdt2 * alpha
            w_new = w_pre + gdt * alpha
            f, Ju, Jv = kernel(u_new, w_new, params)
            kt = -(Ju[0, 0] + Ju[1, 1])
            if kt > 0:
                wd = math.sqrt(kt * s_yy) * dt
                if wd > wdt_max:
                    wdt_max = wd
        else:
            a = a_lin
        p = p_pre + bdt2 * a
        v = v_pre + gdt * a
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
                u = Bt @ p
                w = Bt @ v
                rec_u[i] = u
                rec_w[i] = w
                f, Ju, Jv = kernel(u, w, params)
                rec_fc[i] = f
                fe, Ju, Jv = kernel(u, zero4, params)
                rec_fel[i] = fe
                rec_face[i] = phi_face
                rec_modes[i, 0] = modes[0]
                rec_modes[i, 1] = modes[1]
    return n_steps, wdt_max


def simulate_production(system: RotorSystem, dt: float, n_steps: int, q0=None, v0=None, *, t0: float = 0.0,
                        modes0=(cons.STICK, cons.STICK), options: NewmarkOptions | None = None,
                        record_every: int = 1, check_step: bool = True, prepared: Prepared | None = None) -> Trajectory:
    """Integrate like :func:`rotor.integrate.simulate_reference`, fast. Same arguments and result.

    The support law must provide a numba ``kernel`` (analytic Jacobian). ``prepared`` reuses
    a :func:`prepare` result for the same system and ``dt``.
    """
    opts = options or NewmarkOptions()
    n = system.n
    q0 = np.zeros(n) if q0 is None else np.asarray(q0, dtype=float).copy()
    v0 = np.zeros(n) if v0 is None else np.asarray(v0, dtype=float).copy()
    _check_inputs(system, dt, n_steps, q0, v0)
    sup = system.support
    if sup is not None:
        if sup.law.kernel is None:
            raise InputError(f"support law {sup.law.name!r}: has no compiled kernel with analytic Jacobian; "
                             "use rotor.integrate.simulate_reference")
        if check_step:
            check_time_step(system, dt)
    pre = prepared if prepared is not None else prepare(system, dt, opts)
    if abs(pre.dt - dt) > 1e-15 * dt:
        raise InputError(f"prepared: made for dt = {pre.dt:g} s, called with dt_s = {dt:g} s")
    if system.lock.shape[0] and np.abs(system.lock @ q0).max() > 1e-12 * (1 + np.abs(q0).max()):
        raise InputError("q0: violates the lock (3a/3b equal displacement) constraint")
    n_faces = 2 if sup is not None else 0
    modes = np.array([int(m) for m in modes0][:n_faces] + [cons.SLIP] * (2 - n_faces), dtype=np.int64)
    a0, lam = initial_acceleration(system, t0, q0, v0, list(modes), opts)
    phi_face = np.zeros((2, 2))
    j = system.lock.shape[0]
    for k in range(n_faces):
        if modes[k] == cons.STICK:
            phi_face[k] = -lam[j:j + 2]
            j += 2
    T = pre.T
    p, vp, ap = T.T @ q0, T.T @ v0, T.T @ a0
    n_rec = n_steps // record_every + 1
    nr = T.shape[1]
    rec = dict(t=np.zeros(n_rec), p=np.zeros((n_rec, nr)), v=np.zeros((n_rec, nr)), a=np.zeros((n_rec, nr)),
               u=np.zeros((n_rec, 4)), w=np.zeros((n_rec, 4)), fc=np.zeros((n_rec, 4)), fel=np.zeros((n_rec, 4)),
               face=np.zeros((n_rec, 2, 2)), modes=np.zeros((n_rec, 2), dtype=np.int8),
               its=np.zeros(n_rec, dtype=np.int32), passes=np.zeros(n_rec, dtype=np.int32))
    rec["t"][0] = t0
    rec["p"][0], rec["v"][0], rec["a"][0] = p, vp, ap
    if sup is not None:
        B = sup.relative_map(n)
        u0, w0 = B @ q0, B @ v0
        rec["u"][0], rec["w"][0] = u0, w0
        rec["fc"][0] = sup.law.force(u0, w0)
        rec["fel"][0] = sup.law.force(u0, np.zeros(4))
        rec["modes"][0] = modes
        rec["face"][0] = phi_face
    kernel = sup.law.kernel if sup is not None else _null_kernel
    params = np.asarray(sup.law.params, dtype=float) if sup is not None else np.zeros(1)
    status = np.zeros(2, dtype=np.int64)
    done, wdt_max = _loop(p, vp, ap, modes, phi_face, float(t0), float(dt), int(n_steps), int(record_every),
                          pre.Ainv, pre.Dr, pre.Kr, pre.Bt, pre.W, pre.S, pre.static, pre.orders, pre.cos, pre.sin,
                          pre.omega_force, pre.P, pre.mu_N, pre.s_yy, sup is not None, kernel, params,
                          opts.beta, opts.gamma, opts.tol, opts.max_iter, opts.w_reg, opts.w_stick, opts.max_passes,
                          rec["t"], rec["p"], rec["v"], rec["a"], rec["u"], rec["w"], rec["fc"], rec["fel"],
                          rec["face"], rec["modes"], rec["its"], rec["passes"], status)
    if status[0] != 0:
        t_fail = t0 + status[1] * dt
        what = "Newton did not converge" if status[0] == 1 else "non-finite state"
        raise ConvergenceError(
            f"production scheme: {what} at step {status[1]}, t = {t_fail:.6g} s (tol = {opts.tol:.1e}, "
            f"max_iter = {opts.max_iter}); largest ω_c·Δt met = {wdt_max:.3g}; reduce dt_s = {dt:.3e} s")
    tr = Trajectory(t=rec["t"], q=rec["p"] @ T.T, v=rec["v"] @ T.T, a=rec["a"] @ T.T, u=rec["u"], w=rec["w"],
                    f_contact=rec["fc"], f_elastic=rec["fel"], face_force=rec["face"], modes=rec["modes"],
                    newton_iters=rec["its"], passes=rec["passes"], omega_dt_max=float(wdt_max),
                    scheme="production (condensed, analytic Jacobian, numba)")
    return tr
