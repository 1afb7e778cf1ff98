"""Exact derivative of the production scheme's steps with the friction solved by projection.

With ``NewmarkOptions(friction_scheme="projection")`` each end face's Coulomb law is one equation of the step's
Newton system, ``c (f̄ − proj(f̄ − r w)) = 0`` (:func:`rotor.dynamics.constraints.coulomb_projection`; ``f̄`` the
step mean of the face force, ``w`` its end velocity), and the face's end force is an unknown like a stuck face's
multiplier. The projection is Lipschitz-continuous and piecewise smooth, so the step map has no jump, and where
no face sits exactly on the disk's edge its derivative is the implicit derivative of the converged system
(:mod:`rotor.dynamics.period_map_kernels` explains the linear Newmark part and the rank-6 correction): inside
the disk the rows are the stuck face's ``P w/(γΔt)``, outside ``c (f̄ − μN q̂)`` with
``∂proj/∂q = μN (I − q̂q̂ᵀ)/|q|``. The start force ``f_n`` of each step enters ``f̄``, so its sensitivity is
carried along with the state's (``Sf``, 4 rows: face 0 (y, z), face 1 (y, z)).

The start of a run (:mod:`rotor.dynamics.projection_start`) is the same equation with ``βΔt² = 0``, the mass's
compliance ``S_M`` and the end force alone; :func:`projected_start_jacobian` differentiates it.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from contact.compiled_cache import compiled_with
from rotor.dynamics.period_map_kernels import (_force_jacobians_held, alpha_rows, force_columns,
                                               predictor_sensitivity)
from rotor.dynamics.production_kernels import NC, _coulomb_projection, _residual

compiled_with(__file__, ["rotor.dynamics.production_kernels", "rotor.dynamics.period_map_kernels",
                         "rotor.dynamics.constraints", "rotor.dynamics.kernels", "contact._kernel",
                         "contact._kernel_friction", "contact._kernel_tilt"])

NY = 3 * NC + 4   # columns of a step's derivative: y = (α_lin, u_pre, w_pre), then the start forces f_n (4)


@njit(cache=True)
def projected_step_jacobian(u, w, phi_end, phi_start, wm, S, P, modes, mu_N, a1, params, w_reg, bdt2, gdt):
    """``(Dg, Dphi)``: derivatives of the converged condensed forces ``g`` (NC × NY) and of the end face forces
    (4 × NY, rows face 0 (y, z), face 1 (y, z)) with respect to ``y = (α_lin, u_pre, w_pre)`` (columns 0-17) and the
    start face forces ``f_n`` (N, columns 18-21), at the step's end state ``(u, w)`` (NC,) with end forces
    ``phi_end`` (2, 2) and start forces ``phi_start``; ``wm`` the start force's weight in ``f̄`` (0.5 in a step,
    0 at the start of a run). Faces with ``modes[k] == 2`` are projected; any other face must be inactive."""
    freeze = np.zeros(2, dtype=np.bool_)
    fdir = np.zeros((2, 2))
    Gu, Gw = _force_jacobians_held(u, w, P, modes, freeze, fdir, mu_N, a1, params, w_reg)
    MX = NC + 4
    x = np.zeros(MX)
    m = NC
    for k in range(2):
        freeze[k] = modes[k] == 2 and wm != 0.0
        if modes[k] == 2:
            x[m] = phi_end[k, 0]
            x[m + 1] = phi_end[k, 1]
            m += 2
    g, Jg, phi, uu, ww = np.zeros(NC), np.zeros((NC, NC)), np.zeros((2, 2)), np.zeros(NC), np.zeros(NC)
    R = np.zeros(MX)
    J = np.zeros((MX, MX))
    # R_x at the converged point (the iterate α = 0 with (u_pre, w_pre) = (u, w) is that point)
    _residual(x, m, np.zeros(NC), u, w, S, P, modes, freeze, phi_start, mu_N, a1, bdt2, gdt, params, w_reg,
              g, Jg, phi, uu, ww, R, J)
    mRy = np.zeros((m, NY))         # −R_y and −R_f
    alpha_rows(mRy, S, Gu, Gw)
    j = NC
    for k in range(2):
        if modes[k] != 2:
            continue
        c = 0.0
        for rr in range(2):
            for a in range(4):
                for b in range(4):
                    c += P[k, rr, a] * S[a, b] * P[k, rr, b]
        c *= 0.5
        fy = (1.0 - wm) * phi_end[k, 0] + wm * phi_start[k, 0]
        fz = (1.0 - wm) * phi_end[k, 1] + wm * phi_start[k, 1]
        wy = P[k, 0, 0] * w[0] + P[k, 0, 1] * w[1] + P[k, 0, 2] * w[2] + P[k, 0, 3] * w[3]
        wz = P[k, 1, 0] * w[0] + P[k, 1, 1] * w[1] + P[k, 1, 2] * w[2] + P[k, 1, 3] * w[3]
        _, _, d00, d01, d11 = _coulomb_projection(fy, fz, wy, wz, mu_N[k], 1.0 / (c * gdt))
        for col in range(4):        # R = c (f̄ − proj(f̄ − r w)): ∂R/∂w_pre = D P_k / (γΔt)
            mRy[j, 2 * NC + col] = -(d00 * P[k, 0, col] + d01 * P[k, 1, col]) / gdt
            mRy[j + 1, 2 * NC + col] = -(d01 * P[k, 0, col] + d11 * P[k, 1, col]) / gdt
        e = c * wm                  # ∂R/∂f_n = c wm (I − D)
        mRy[j, 3 * NC + 2 * k] = -e * (1.0 - d00)
        mRy[j, 3 * NC + 2 * k + 1] = e * d01
        mRy[j + 1, 3 * NC + 2 * k] = e * d01
        mRy[j + 1, 3 * NC + 2 * k + 1] = -e * (1.0 - d11)
        j += 2
    Dx = np.linalg.solve(J[:m, :m], mRy)
    # dg = Gu du + Gw dw + Σ P_kᵀ dφ_k, du = du_pre + βΔt² dα, dw = dw_pre + γΔt dα
    Dg = np.zeros((NC, NY))
    Dphi = np.zeros((4, NY))
    force_columns(Dg, Dx, Gu, Gw, bdt2, gdt)
    j = NC
    for k in range(2):
        if modes[k] == 2:
            for c in range(NY):
                Dphi[2 * k, c] = Dx[j, c]
                Dphi[2 * k + 1, c] = Dx[j + 1, c]
                for r in range(4):
                    Dg[r, c] += P[k, 0, r] * Dx[j, c] + P[k, 1, r] * Dx[j + 1, c]
            j += 2
    return Dg, Dphi


@njit(cache=True)
def projected_start_jacobian(p, v, a, phi0, Bt, MK, MD, WM, SM, P, modes, mu_N, a1, params, w_reg, gdt):
    """``(∂a₀/∂(p₀, v₀) (nr × 2nr), ∂f₀/∂(p₀, v₀) (4 × 2nr))`` of the start of a run
    (:func:`rotor.dynamics.projection_start.projected_start`): ``a₀ = M⁻¹(Q − D v − K p) + W_M g`` with the faces'
    forces ``f₀`` Coulomb's projection at the velocity ``w + γΔt α₀``."""
    nr = p.shape[0]
    u = Bt @ p
    w_end = Bt @ v + gdt * (Bt @ a)
    Dg, Dphi = projected_step_jacobian(u, w_end, phi0, np.zeros((2, 2)), 0.0, SM, P, modes, mu_N, a1, params,
                                       w_reg, 0.0, gdt)
    Af = np.empty((nr, 2 * nr))
    Af[:, :nr] = -MK
    Af[:, nr:] = -MD
    Y = np.zeros((3 * NC, 2 * nr))
    Y[:NC] = Bt @ Af
    Y[NC:2 * NC, :nr] = Bt
    Y[2 * NC:, nr:] = Bt
    Dgy = np.ascontiguousarray(Dg[:, :3 * NC])
    return Af + WM @ (Dgy @ Y), np.ascontiguousarray(Dphi[:, :3 * NC]) @ Y


@njit(cache=True)
def sensitivity_pass_projected(rec_p, rec_v, rec_a, rec_face, modes, dt, beta, gamma, AK, AD, MK, MD, Bt, W, S, WM,
                               SM, P, mu_N, a1, params, w_reg):
    """``∂(p_N, v_N)/∂(p₀, v₀)`` (2nr × 2nr) along a recorded every-step run of the projection scheme
    (``rec_p``, ``rec_v``, ``rec_a`` (N+1, nr), ``rec_face`` (N+1, 2, 2)): the start's derivative
    (:func:`projected_start_jacobian`), then each step's (:func:`projected_step_jacobian`), the start forces'
    sensitivity carried along. ``AK = A⁻¹K``, ``AD = A⁻¹D`` (``A`` the Newmark matrix), ``MK = M⁻¹K``,
    ``MD = M⁻¹D``."""
    nr = rec_p.shape[1]
    ncol = 2 * nr
    n_steps = rec_p.shape[0] - 1
    bdt2 = beta * dt * dt
    gdt = gamma * dt
    c1 = dt * dt * (0.5 - beta)
    c2 = dt * (1.0 - gamma)
    Spv = np.zeros((ncol, ncol))
    for i in range(ncol):
        Spv[i, i] = 1.0
    Sa, Sf = projected_start_jacobian(rec_p[0], rec_v[0], rec_a[0], rec_face[0], Bt, MK, MD, WM, SM, P, modes, mu_N,
                                      a1, params, w_reg, gdt)
    Pre = np.empty((2 * nr, ncol))
    Sal = np.empty((nr, ncol))
    AKD = np.empty((nr, 2 * nr))
    AKD[:, :nr] = AK
    AKD[:, nr:] = AD
    Y = np.empty((NY, ncol))        # ∂y: α_lin = Bt a_lin, u_pre = Bt p_pre, w_pre = Bt v_pre; then ∂f_n
    for n in range(n_steps):
        predictor_sensitivity(Pre, Spv, Sa, dt, c1, c2)
        np.dot(AKD, Pre, Sal)
        np.dot(Bt, Sal, Y[:NC])
        np.dot(Bt, Pre[:nr], Y[NC:2 * NC])
        np.dot(Bt, Pre[nr:], Y[2 * NC:3 * NC])
        for r in range(NC):
            for c in range(ncol):
                Y[r, c] = -Y[r, c]
        Y[3 * NC:] = Sf
        u = Bt @ rec_p[n + 1]
        w = Bt @ rec_v[n + 1]
        Dg, Dphi = projected_step_jacobian(u, w, rec_face[n + 1], rec_face[n], 0.5, S, P, modes, mu_N, a1, params,
                                           w_reg, bdt2, gdt)
        Z = Dg @ Y
        Sf = Dphi @ Y
        Sa = W @ Z - Sal
        for i in range(nr):
            for c in range(ncol):
                Spv[i, c] = Pre[i, c] + bdt2 * Sa[i, c]
                Spv[nr + i, c] = Pre[nr + i, c] + gdt * Sa[i, c]
    return Spv
