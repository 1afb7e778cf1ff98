"""Compiled derivative of the production scheme's steps (:mod:`rotor.dynamics.period_map`).

The step of :func:`rotor.dynamics.production_kernels.step_loop` maps ``(p, v, a)`` to the next
``(p, v, a)``: a constant linear Newmark part, plus the support through the six condensed
coordinates ``α`` (and two multipliers per stuck face) that the step solves by Newton. At the
converged step ``R(x; α_lin, u_pre, w_pre) = 0`` (:func:`rotor.dynamics.production_kernels._residual`),
so by the implicit function theorem ``dx = −R_x⁻¹ R_y dy`` with ``y = (α_lin, u_pre, w_pre)``
(18 numbers, projections ``B`` of the predictor), and the full acceleration changes by
``W dg`` (``g`` the 6 condensed forces): a rank-6 correction of the linear step. The sensitivity
of the state to the 2 nr initial values is carried as ``∂(p, v)`` (2nr × 2nr) and ``∂a`` (nr × 2nr);
a step costs one ``nr × 2nr × 2nr`` product (the linear part, ``A⁻¹[K D]`` on the predictor) and
``O(18 · nr · 2nr)`` for the correction (measured on the Table 4 rotor, nr = 26: the monodromy
costs about 1.5 times the map itself, ``reports/published/perf-period-map.md``).

The forces' partial Jacobians ``∂g/∂u`` and ``∂g/∂w`` come from the same compiled
:func:`rotor.dynamics.production_kernels._forces` (called with ``βΔt² = 1, γΔt = 0`` and
``βΔt² = 0, γΔt = 1``), the Newton matrix ``R_x`` from ``_residual``, so the derivative uses the
support law's analytic Jacobian (:mod:`rotor.dynamics.kernels`) and nothing is differenced.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from contact.compiled_cache import compiled_with
from rotor.dynamics.production_kernels import NC, _forces, _residual, _small_solve

compiled_with(__file__, ["rotor.dynamics.production_kernels", "rotor.dynamics.constraints",
                         "rotor.dynamics.kernels", "contact._kernel", "contact._kernel_friction",
                         "contact._kernel_tilt"])


@njit(cache=True)
def _scratch():
    """Work arrays of ``_forces``/``_residual``: iterate, freeze flags and directions, forces, Jacobian,
    face forces, condensed displacement and velocity."""
    return (np.zeros(NC + 4), np.zeros(2, dtype=np.bool_), np.zeros((2, 2)), np.zeros(NC), np.zeros((NC, NC)),
            np.zeros((2, 2)), np.zeros(NC), np.zeros(NC))


@njit(cache=True)
def force_jacobians(u, w, P, modes, mu_N, a1, params, w_reg):
    """``(∂g/∂u, ∂g/∂w)`` (NC × NC each) of the condensed forces at relative displacement ``u``
    and velocity ``w`` (NC,), stuck faces' forces held (they are unknowns of their own)."""
    x, freeze, fdir, g, Gu, phi, uu, ww = _scratch()
    return _force_jacobians_held(u, w, P, modes, freeze, fdir, mu_N, a1, params, w_reg)


@njit(cache=True)
def _force_jacobians_held(u, w, P, modes, freeze, fdir, mu_N, a1, params, w_reg):
    """:func:`force_jacobians` with the friction of each slipping face ``k`` with ``freeze[k]`` held at
    ``fdir[k]`` (N): no derivative of that face's force with respect to ``u`` or ``w``."""
    x, _, _, g, Gu, phi, uu, ww = _scratch()
    Gw = np.zeros((NC, NC))
    _forces(x, u, w, 1.0, 0.0, P, modes, freeze, fdir, mu_N, a1, params, w_reg, g, Gu, phi, uu, ww)
    _forces(x, u, w, 0.0, 1.0, P, modes, freeze, fdir, mu_N, a1, params, w_reg, g, Gw, phi, uu, ww)
    return Gu, Gw


@njit(cache=True)
def consistent_acceleration_jacobian(p, v, Bt, MK, MD, WM, SM, P, modes, mu_N, a1, params, w_reg):
    """``∂a/∂(p, v)`` (nr × 2nr) of the consistent acceleration of
    :func:`rotor.dynamics.production_kernels._reproject` (and of the initial state,
    :func:`rotor.dynamics.initial.initial_state`): ``a = M⁻¹(Q − D v − K p + Bᵀ g) + W_M Pᵀ φ`` with
    the stuck faces' multipliers ``φ`` making their relative acceleration zero. ``MK = M⁻¹K``,
    ``MD = M⁻¹D`` (reduced)."""
    nr = p.shape[0]
    u = Bt @ p
    w = Bt @ v
    Gu, Gw = force_jacobians(u, w, P, modes, mu_N, a1, params, w_reg)
    Af = np.empty((nr, 2 * nr))
    Af[:, :nr] = -MK + WM @ (Gu @ Bt)
    Af[:, nr:] = -MD + WM @ (Gw @ Bt)
    # stuck faces: P_k Bt a = 0, i.e. (P S_M Pᵀ) φ = −P Bt a_free, P the stuck faces' maps stacked
    Pall = np.zeros((4, NC))
    m2 = 0
    for k in range(2):
        if modes[k] == 1:
            Pall[m2:m2 + 2, :4] = P[k]
            m2 += 2
    if m2 == 0:
        return Af
    Pm = Pall[:m2].copy()
    A = Pm @ SM @ Pm.T
    C = Pm @ (Bt @ Af)
    dphi = np.zeros((m2, 2 * nr))
    col = np.zeros(m2)
    for j in range(2 * nr):
        A2 = A.copy()
        b = -C[:, j].copy()
        _small_solve(A2, b, m2, col)
        dphi[:, j] = col
    return Af + WM @ (Pm.T @ dphi)


@njit(cache=True, inline="always")
def predictor_sensitivity(Pre, Spv, Sa, dt, c1, c2):
    """The Newmark predictor's sensitivity ``Pre`` (2nr × ncol, rows p then v) from the state's ``Spv`` and the
    acceleration's ``Sa``: ``p + Δt v + c1 a``, ``v + c2 a`` (``c1 = Δt²(1/2 − β)``, ``c2 = Δt(1 − γ)``)."""
    nr = Sa.shape[0]
    for i in range(nr):
        for c in range(Sa.shape[1]):
            sa = Sa[i, c]
            Pre[i, c] = Spv[i, c] + dt * Spv[nr + i, c] + c1 * sa
            Pre[nr + i, c] = Spv[nr + i, c] + c2 * sa


@njit(cache=True)
def alpha_rows(mRy, S, Gu, Gw):
    """The condensed rows of ``−R_y`` (into ``mRy[:NC, :3NC]``): ``R_α = α − α_lin − S g(u_pre + βΔt² α, w_pre +
    γΔt α)``, so ``I`` on ``α_lin`` and ``S ∂g/∂u``, ``S ∂g/∂w`` on ``u_pre``, ``w_pre``."""
    for r in range(NC):
        mRy[r, r] = 1.0
        for c in range(NC):
            su = 0.0
            sw = 0.0
            for k in range(NC):
                su += S[r, k] * Gu[k, c]
                sw += S[r, k] * Gw[k, c]
            mRy[r, NC + c] = su
            mRy[r, 2 * NC + c] = sw


@njit(cache=True)
def force_columns(Dg, Dx, Gu, Gw, bdt2, gdt):
    """``dg = Gu du + Gw dw`` with ``du = du_pre + βΔt² dα``, ``dw = dw_pre + γΔt dα`` into ``Dg`` (NC × the columns
    of ``Dx``, whose first NC rows are ``dα``): the direct ``u_pre``, ``w_pre`` columns and every column through
    ``dα`` (the faces' force unknowns are the caller's)."""
    for r in range(NC):
        for c in range(NC):
            Dg[r, NC + c] = Gu[r, c]
            Dg[r, 2 * NC + c] = Gw[r, c]
        for c in range(Dx.shape[1]):
            s = 0.0
            for k in range(NC):
                s += (bdt2 * Gu[r, k] + gdt * Gw[r, k]) * Dx[k, c]
            Dg[r, c] += s


@njit(cache=True)
def _step_support_jacobian_held(u, w, S, P, modes, freeze, fdir, mu_N, a1, params, w_reg, bdt2, gdt):
    """``∂g/∂(y, f)`` (NC × 22) of the converged condensed forces with respect to ``y = (α_lin, u_pre, w_pre)``
    (columns 0-17) and to the held forces ``f = (f_0, f_1)`` (N, columns 18-21) of the faces marked in ``freeze``
    (held at ``fdir``; a face not held has zero columns), at the step's end state ``(u, w)`` and ``modes``."""
    Gu, Gw = _force_jacobians_held(u, w, P, modes, freeze, fdir, mu_N, a1, params, w_reg)
    m = NC   # unknowns: α and two multipliers per stuck face
    for k in range(2):
        if modes[k] == 1:
            m += 2
    MX = NC + 4
    x, _, _, g, Jg, phi, uu, ww = _scratch()
    alpha_lin = np.zeros(NC)
    R = np.zeros(MX)
    J = np.zeros((MX, MX))
    # R_x at the converged point: the iterate α = 0 with (u_pre, w_pre) = (u, w) is that point
    _residual(x, m, alpha_lin, u, w, S, P, modes, freeze, fdir, mu_N, a1, bdt2, gdt, params, w_reg,
              g, Jg, phi, uu, ww, R, J)
    # −R_y: R_α = α − α_lin − S g(u_pre + βΔt² α, w_pre + γΔt α), R_stuck = P_k w / (γΔt)
    mRy = np.zeros((m, 3 * NC))
    alpha_rows(mRy, S, Gu, Gw)
    j = NC
    for k in range(2):
        if modes[k] == 1:
            for rr in range(2):
                for c in range(4):
                    mRy[j + rr, 2 * NC + c] = -P[k, rr, c] / gdt
            j += 2
    Dx = np.linalg.solve(J[:m, :m], mRy)
    # dg = Gu du + Gw dw + Σ_stuck P_kᵀ dφ_k, du = du_pre + βΔt² dα, dw = dw_pre + γΔt dα
    Dgf = np.zeros((NC, 3 * NC + 4))
    Dg = Dgf[:, :3 * NC]
    force_columns(Dg, Dx, Gu, Gw, bdt2, gdt)
    j = NC
    for k in range(2):
        if modes[k] == 1:
            for r in range(4):
                for c in range(3 * NC):
                    Dg[r, c] += P[k, 0, r] * Dx[j, c] + P[k, 1, r] * Dx[j + 1, c]
            j += 2
    held = False
    for k in range(2):
        held = held or (freeze[k] and modes[k] == 0)
    if not held:          # a plain step (every step of the plain map): no held-force columns to solve for
        return Dgf
    # the held forces f: g holds P_kᵀ f_k (its first four rows), so R_α = ... − S P_kᵀ f_k
    mRf = np.zeros((m, 4))
    for k in range(2):
        if freeze[k] and modes[k] == 0:
            for r in range(NC):
                for rr in range(2):
                    s = 0.0
                    for c in range(4):
                        s += S[r, c] * P[k, rr, c]
                    mRf[r, 2 * k + rr] = s
    Dxf = np.linalg.solve(J[:m, :m], mRf)
    # the held forces' columns: P_kᵀ directly, and through α and the stuck multipliers
    for k in range(2):
        if freeze[k] and modes[k] == 0:
            for r in range(4):
                Dgf[r, 3 * NC + 2 * k] += P[k, 0, r]
                Dgf[r, 3 * NC + 2 * k + 1] += P[k, 1, r]
    for r in range(NC):
        for c in range(4):
            s = 0.0
            for k in range(NC):
                s += (bdt2 * Gu[r, k] + gdt * Gw[r, k]) * Dxf[k, c]
            Dgf[r, 3 * NC + c] += s
    j = NC
    for k in range(2):
        if modes[k] == 1:
            for r in range(4):
                for c in range(4):
                    Dgf[r, 3 * NC + c] += P[k, 0, r] * Dxf[j, c] + P[k, 1, r] * Dxf[j + 1, c]
            j += 2
    return Dgf


@njit(cache=True)
def sensitivity_pass(rec_p, rec_v, rec_modes, dt, beta, gamma, AK, AD, MK, MD, Bt, W, S, WM, SM, P, mu_N,
                     a1, has_support, params, w_reg, onset_projection):
    """Carry ``∂(p, v, a)/∂(p₀, v₀)`` along a recorded run of ``step_loop`` (every step recorded:
    ``rec_p``, ``rec_v`` (N+1, nr), ``rec_modes`` (N+1, 2)), starting from the consistent initial
    acceleration's ``∂a₀/∂(p₀, v₀)`` (:func:`consistent_acceleration_jacobian` with the modes after the
    initial stick test, ``rec_modes[0]``). ``AK = A⁻¹K``, ``AD = A⁻¹D`` (``A`` the Newmark matrix), ``MK = M⁻¹K``, ``MD = M⁻¹D``.

    Each step is differentiated with the modes it ended in (no saltation at mode changes); a
    step in which a face stuck is followed, as in ``step_loop``, by the consistent-acceleration
    restart, differentiated too. Returns the ``(2nr × 2nr)`` monodromy ``∂(p_N, v_N)/∂(p₀, v₀)``."""
    nr = rec_p.shape[1]
    ncol = 2 * nr
    # Spv = ∂(p, v)/∂x0 (rows: p then v), Sa = ∂a/∂x0
    Spv = np.zeros((ncol, ncol))
    for i in range(ncol):
        Spv[i, i] = 1.0
    modes = np.zeros(2, dtype=np.int64)
    if has_support:
        modes[0] = rec_modes[0, 0]
        modes[1] = rec_modes[0, 1]
        Sa = consistent_acceleration_jacobian(rec_p[0], rec_v[0], Bt, MK, MD, WM, SM, P, modes, mu_N, a1, params,
                                              w_reg)
    else:
        Sa = np.empty((nr, ncol))
        Sa[:, :nr] = -MK
        Sa[:, nr:] = -MD
    carry(rec_p, rec_v, rec_modes, Spv, Sa, dt, beta, gamma, AK, AD, MK, MD, Bt, W, S, WM, SM, P, mu_N, a1,
          has_support, params, w_reg, onset_projection, np.zeros((rec_p.shape[0], 2), dtype=np.int64),
          np.zeros((rec_p.shape[0], 2, 2)), np.zeros((nr, ncol)))
    return Spv


@njit(cache=True)
def carry(rec_p, rec_v, rec_modes, Spv, Sa, dt, beta, gamma, AK, AD, MK, MD, Bt, W, S, WM, SM, P, mu_N, a1,
          has_support, params, w_reg, onset_projection, rec_held, rec_face, dload):
    """Carry the sensitivities ``Spv = ∂(p, v)/∂x0`` (2nr × ncol) and ``Sa = ∂a/∂x0`` (nr × ncol), given at the
    record's first sample, along its plain steps (in place; arguments as :func:`sensitivity_pass`). The
    located period map (:mod:`rotor.dynamics.period_map_events`) runs it between its event steps.

    ``rec_held`` (N, 2): how each face's friction was held over step ``n`` (the step loop's ``status[5:7]``,
    :func:`rotor.dynamics.production_loop.step_loop`): 0 not held; 1 a slow slip, Coulomb's force
    ``f = −μN w/|w|`` along the face's slip velocity ``w = P_k Bt v_n`` at the step's start, differentiated
    (``∂f/∂w = −μN (I − ŵŵᵀ)/|w|``); 2 a face at rest held at ``μN`` along its start force ``rec_face[n, k]``
    (N), a constant of the step. Such a step is smooth in its start (the hold is decided from the start alone),
    so it is carried here, not differenced.

    ``dload`` (nr × ncol): ``A⁻¹ ∂Q`` of each column, added to the sensitivity of every step's linear acceleration
    ``a_lin = A⁻¹(Q − D v_pre − K p_pre)``; zeros, except for the derivative of a step with respect to its length
    (rotor/dynamics/contact_step_derivative.py), in which the load's time moves with the step's end."""
    nr = rec_p.shape[1]
    n_steps = rec_p.shape[0] - 1
    ncol = Spv.shape[1]
    bdt2 = beta * dt * dt
    gdt = gamma * dt
    c1 = dt * dt * (0.5 - beta)
    c2 = dt * (1.0 - gamma)
    modes = np.zeros(2, dtype=np.int64)
    # Pre = the predictor's sensitivity
    Pre = np.empty((2 * nr, ncol))
    Sal = np.empty((nr, ncol))
    AKD = np.empty((nr, 2 * nr))
    AKD[:, :nr] = AK
    AKD[:, nr:] = AD
    Y = np.empty((3 * NC, ncol))      # ∂y: α_lin = Bt a_lin, u_pre = Bt p_pre, w_pre = Bt v_pre
    Z = np.empty((NC, ncol))
    freeze = np.zeros(2, dtype=np.bool_)
    fdir = np.zeros((2, 2))
    dF = np.zeros((4, ncol))          # ∂f of the held forces (face 0, face 1)
    Wv = np.empty((NC, ncol))
    for n in range(n_steps):
        held = False
        if has_support:
            for k in range(2):
                freeze[k] = rec_held[n, k] != 0
                held = held or freeze[k]
        if held:
            # the held forces and their sensitivity, from the step's start velocity (before Spv moves on)
            np.dot(Bt, Spv[nr:], Wv)
            dF[:, :] = 0.0
            for k in range(2):
                if rec_held[n, k] == 1:
                    wy = 0.0
                    wz = 0.0
                    for c in range(4):
                        wb = 0.0
                        for i in range(nr):
                            wb += Bt[c, i] * rec_v[n, i]
                        wy += P[k, 0, c] * wb
                        wz += P[k, 1, c] * wb
                    sw = np.sqrt(wy * wy + wz * wz)
                    ey = wy / sw
                    ez = wz / sw
                    fdir[k, 0] = -mu_N[k] * ey
                    fdir[k, 1] = -mu_N[k] * ez
                    cf = -mu_N[k] / sw
                    d00 = cf * (1.0 - ey * ey)
                    d01 = -cf * ey * ez
                    d11 = cf * (1.0 - ez * ez)
                    for c in range(ncol):
                        dwy = 0.0
                        dwz = 0.0
                        for r in range(4):
                            dwy += P[k, 0, r] * Wv[r, c]
                            dwz += P[k, 1, r] * Wv[r, c]
                        dF[2 * k, c] = d00 * dwy + d01 * dwz
                        dF[2 * k + 1, c] = d01 * dwy + d11 * dwz
                elif rec_held[n, k] == 2:
                    fn = np.sqrt(rec_face[n, k, 0] ** 2 + rec_face[n, k, 1] ** 2)
                    fdir[k, 0] = mu_N[k] * rec_face[n, k, 0] / fn
                    fdir[k, 1] = mu_N[k] * rec_face[n, k, 1] / fn
        predictor_sensitivity(Pre, Spv, Sa, dt, c1, c2)
        np.dot(AKD, Pre, Sal)
        Sal -= dload
        if has_support:
            modes[0] = rec_modes[n + 1, 0]
            modes[1] = rec_modes[n + 1, 1]
            u = Bt @ rec_p[n + 1]
            w = Bt @ rec_v[n + 1]
            Dgf = _step_support_jacobian_held(u, w, S, P, modes, freeze, fdir, mu_N, a1, params, w_reg, bdt2, gdt)
            Dg = np.ascontiguousarray(Dgf[:, :3 * NC])
            np.dot(Bt, Sal, Y[:NC])
            np.dot(Bt, Pre[:nr], Y[NC:2 * NC])
            np.dot(Bt, Pre[nr:], Y[2 * NC:])
            for r in range(NC):
                for c in range(ncol):
                    Y[r, c] = -Y[r, c]
            np.dot(Dg, Y, Z)
            if held:
                Z += np.ascontiguousarray(Dgf[:, 3 * NC:]) @ dF
            np.dot(W, Z, Sa)
            for i in range(nr):
                for c in range(ncol):
                    Sa[i, c] -= Sal[i, c]
        else:
            for i in range(nr):
                for c in range(ncol):
                    Sa[i, c] = -Sal[i, c]
        for i in range(nr):
            for c in range(ncol):
                Spv[i, c] = Pre[i, c] + bdt2 * Sa[i, c]
                Spv[nr + i, c] = Pre[nr + i, c] + gdt * Sa[i, c]
        if has_support and onset_projection:
            onset = False
            for k in range(2):
                if rec_modes[n + 1, k] == 1 and rec_modes[n, k] != 1:
                    onset = True
            if onset:
                Ra = consistent_acceleration_jacobian(rec_p[n + 1], rec_v[n + 1], Bt, MK, MD, WM, SM, P, modes, mu_N,
                                                      a1, params, w_reg)
                np.dot(Ra, Spv, Sa)
