"""The compiled inner routines of the production integrator (:mod:`rotor.dynamics.production`).

numba ``njit`` functions on the condensed step: the contact and coupling forces with their
analytic Jacobian (:func:`_forces`), the residual of the condensed step (:func:`_residual`), its
Newton solve with backtracking (:func:`_solve_support`), a hand-written Gaussian elimination for
the ≤ 10×10 Newton systems (:func:`_small_solve`), the consistent acceleration after a stick onset
(:func:`_reproject`, and :func:`_consistent_acceleration` with slipping faces' forces held, after a
friction event), and the load at a time (:func:`_load`). The step loop is
:func:`rotor.dynamics.production_loop.step_loop`; the events located inside a step
:mod:`rotor.dynamics.friction_events`. The equations are those of :mod:`rotor.dynamics.production`;
the stick/slip rules are :mod:`rotor.dynamics.constraints`, compiled.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from contact.compiled_cache import compiled_with
from rotor.dynamics import constraints as cons
from rotor.dynamics.kernels import contact_point_jacobian

# The kernels below inline rotor.dynamics.constraints and the law kernel (rotor.dynamics.kernels, which
# inlines contact._kernel): their cache entries are stale when any of those sources changes (numba
# itself only watches this file).
compiled_with(__file__, ["rotor.dynamics.constraints", "rotor.dynamics.kernels", "contact._kernel"])

# Caching: the law kernel is not an argument but the one compiled law of the suite,
# rotor.dynamics.kernels.contact_kernel, which picks the law (conformal, Pereira, elastic foundation)
# by the law code in its parameter array. A kernel passed as an argument keys numba's cache by the
# dispatcher's identity, which differs in every process (the cache never hit, its index grew, and
# saving eventually failed); a global one is compiled into the loop, so every function here is cached
# on disk (contact.compiled_cache) and compiled once per machine.

_mode_update = njit(cache=True)(cons.face_mode_update)



@njit(cache=True, inline="always")
def _slip_force_scalar(wy, wz, mu_N, w_reg):
    """:func:`rotor.dynamics.constraints.slip_force` of the sliding velocity ``(wy, wz)`` (m/s) on scalars, the
    same operations in the same order (nothing allocated): ``(fy, fz, J00, J01, J10, J11)`` (N; N s/m)."""
    s2 = wy * wy + wz * wz + w_reg * w_reg
    s = np.sqrt(s2)
    c = mu_N / (s2 * s)
    return (-mu_N * wy / s, -mu_N * wz / s, -mu_N / s + c * wy * wy, c * wy * wz, c * wz * wy,
            -mu_N / s + c * wz * wz)


NC = 6  # condensed coordinates: relative support (y, z, θy, θz) + coupling Δθ (y, z)


@njit(cache=True)
def _small_solve(A, b, m, out):
    """Solve A[:m,:m] out = b[:m] by Gaussian elimination with partial pivoting (A, b destroyed).

    Hand-written because LAPACK's call overhead (~2 µs) dominates at m ≤ 10. Returns False if singular."""
    for c in range(m):
        piv = c
        best = abs(A[c, c])
        for r in range(c + 1, m):
            if abs(A[r, c]) > best:
                best = abs(A[r, c])
                piv = r
        if best == 0.0 or not (best == best):
            return False
        if piv != c:
            for k in range(c, m):
                tmp = A[c, k]
                A[c, k] = A[piv, k]
                A[piv, k] = tmp
            tmp = b[c]
            b[c] = b[piv]
            b[piv] = tmp
        inv = 1.0 / A[c, c]
        for r in range(c + 1, m):
            fct = A[r, c] * inv
            if fct != 0.0:
                for k in range(c + 1, m):
                    A[r, k] -= fct * A[c, k]
                b[r] -= fct * b[c]
    for r in range(m - 1, -1, -1):
        s = b[r]
        for k in range(r + 1, m):
            s -= A[r, k] * out[k]
        out[r] = s / A[r, r]
    return True


@njit(cache=True, inline="always")
def _forces_into(x, u_pre, w_pre, bdt2, gdt, P, modes, freeze, freeze_dir, mu_N, a1, params, w_reg,
                 g, Jg, phi, u, w, jac):
    """:func:`_forces` on a caller's law Jacobian ``jac`` (4, 8), written (no array allocated here)."""
    for i in range(NC):
        u[i] = u_pre[i] + bdt2 * x[i]
        w[i] = w_pre[i] + gdt * x[i]
    f0, f1, f2, f3 = contact_point_jacobian(u, w, params, jac)
    for i in range(NC):
        g[i] = 0.0
        for j in range(NC):
            Jg[i, j] = 0.0
    g[0] = f0
    g[1] = f1
    g[2] = f2
    g[3] = f3
    for i in range(4):
        for j in range(4):
            Jg[i, j] = jac[i, j] * bdt2 + jac[i, 4 + j] * gdt
    if a1 != 0.0:
        d0 = u[4]
        d1 = u[5]
        s2 = d0 * d0 + d1 * d1
        g[4] = -a1 * s2 * d0
        g[5] = -a1 * s2 * d1
        Jg[4, 4] = -a1 * (s2 + 2 * d0 * d0) * bdt2
        Jg[4, 5] = -a1 * (2 * d0 * d1) * bdt2
        Jg[5, 4] = Jg[4, 5]
        Jg[5, 5] = -a1 * (s2 + 2 * d1 * d1) * bdt2
    j = NC
    for k in range(2):
        if modes[k] == 1:
            phi[k, 0] = x[j]
            phi[k, 1] = x[j + 1]
            j += 2
        elif freeze[k]:
            phi[k, 0] = freeze_dir[k, 0]
            phi[k, 1] = freeze_dir[k, 1]
        else:
            wy = P[k, 0, 0] * w[0] + P[k, 0, 1] * w[1] + P[k, 0, 2] * w[2] + P[k, 0, 3] * w[3]
            wz = P[k, 1, 0] * w[0] + P[k, 1, 1] * w[1] + P[k, 1, 2] * w[2] + P[k, 1, 3] * w[3]
            phi[k, 0], phi[k, 1], j00, j01, j10, j11 = _slip_force_scalar(wy, wz, mu_N[k], w_reg)
            # Jg += Pkᵀ Jk Pk γΔt
            for r in range(4):
                for c in range(4):
                    s = 0.0
                    s += P[k, 0, r] * j00 * P[k, 0, c]
                    s += P[k, 0, r] * j01 * P[k, 1, c]
                    s += P[k, 1, r] * j10 * P[k, 0, c]
                    s += P[k, 1, r] * j11 * P[k, 1, c]
                    Jg[r, c] += s * gdt
        for r in range(4):
            g[r] += P[k, 0, r] * phi[k, 0] + P[k, 1, r] * phi[k, 1]


@njit(cache=True)
def _forces(x, u_pre, w_pre, bdt2, gdt, P, modes, freeze, freeze_dir, mu_N, a1, params, w_reg,
            g, Jg, phi, u, w):
    """Condensed forces g (NC,) and ∂g/∂α (NC, NC) at iterate x (stuck-face forces from x[NC:]);
    also leaves the condensed displacement u and velocity w of the iterate."""
    _forces_into(x, u_pre, w_pre, bdt2, gdt, P, modes, freeze, freeze_dir, mu_N, a1, params, w_reg,
                 g, Jg, phi, u, w, np.empty((4, 8)))


@njit(cache=True, inline="always")
def _residual_into(x, m, alpha_lin, u_pre, w_pre, S, P, modes, freeze, freeze_dir, mu_N, a1, bdt2, gdt, params,
                   w_reg, g, Jg, phi, u, w, R, J, jac):
    """:func:`_residual` on a caller's law Jacobian ``jac`` (4, 8)."""
    _forces_into(x, u_pre, w_pre, bdt2, gdt, P, modes, freeze, freeze_dir, mu_N, a1, params, w_reg,
                 g, Jg, phi, u, w, jac)
    for r in range(m):
        for c in range(m):
            J[r, c] = 0.0
    for r in range(NC):
        s = 0.0
        for c in range(NC):
            s += S[r, c] * g[c]
        R[r] = x[r] - alpha_lin[r] - s
        for c in range(NC):
            s = 0.0
            for k in range(NC):
                s += S[r, k] * Jg[k, c]
            J[r, c] = (1.0 if r == c else 0.0) - s
    j = NC
    for k in range(2):
        if modes[k] == 1:
            for rr in range(2):
                R[j + rr] = (P[k, rr, 0] * w[0] + P[k, rr, 1] * w[1] + P[k, rr, 2] * w[2] + P[k, rr, 3] * w[3]) / gdt
                for c in range(4):
                    J[j + rr, c] = P[k, rr, c]
            for r in range(NC):
                for rr in range(2):
                    s = 0.0
                    for c in range(4):
                        s += S[r, c] * P[k, rr, c]
                    J[r, j + rr] = -s
            j += 2
    nr = 0.0
    for i in range(m):
        nr += R[i] * R[i]
    return math.sqrt(nr)


@njit(cache=True)
def _residual(x, m, alpha_lin, u_pre, w_pre, S, P, modes, freeze, freeze_dir, mu_N, a1, bdt2, gdt, params,
              w_reg, g, Jg, phi, u, w, R, J):
    """Residual R and analytic Jacobian J (first m rows/cols) of the condensed step at iterate x; returns |R|."""
    return _residual_into(x, m, alpha_lin, u_pre, w_pre, S, P, modes, freeze, freeze_dir, mu_N, a1, bdt2, gdt,
                          params, w_reg, g, Jg, phi, u, w, R, J, np.empty((4, 8)))


MX = NC + 4  # Newton unknowns at most: α and two multipliers per stuck face


@njit(cache=True)
def newton_work():
    """The work arrays of :func:`_solve_support`, allocated once per step loop: ``(vec (10, MX), mat (3, MX, MX),
    jac (4, 8))``; rows of ``vec``: iterate, residual, trial residual, right-hand side, trial iterate, Newton
    step, best iterate, forces g, condensed u, w; ``mat``: Newton matrix, trial matrix, ∂g/∂α."""
    return np.zeros((10, MX)), np.zeros((3, MX, MX)), np.zeros((4, 8))


@njit(cache=True)
def _solve_support(alpha, alpha_lin, u_pre, w_pre, S, P, modes, phi_stuck, freeze, freeze_dir, mu_N, a1,
                   bdt2, gdt, params, tol, max_iter, w_reg, vec, mat, jac, phi):
    """Newton on the condensed unknowns [α (NC); φ of stuck faces (2 each)], analytic Jacobian,
    with backtracking on |R| when a full step does not decrease it (kinks of the law).
    If it does not converge, the least-residual iterate is returned with ok = False.

    Work arrays from :func:`newton_work`. Leaves the new α in ``vec[0, :NC]``, the forces g in ``vec[7, :NC]``
    and the face forces in ``phi`` (2, 2). Returns (iterations, converged)."""
    x, R, R2, rhs, xt, dx, best, g, u, w = vec[0], vec[1], vec[2], vec[3], vec[4], vec[5], vec[6], vec[7], vec[8], vec[9]
    J, J2, Jg = mat[0], mat[1], mat[2]
    n_st = 0
    for k in range(2):
        if modes[k] == 1:
            n_st += 1
    m = NC + 2 * n_st
    vec[:, :] = 0.0
    mat[:, :, :] = 0.0
    phi[:, :] = 0.0
    for i in range(NC):
        x[i] = alpha[i]
    j = NC
    for k in range(2):
        if modes[k] == 1:
            x[j] = phi_stuck[k, 0]
            x[j + 1] = phi_stuck[k, 1]
            j += 2
    its = 0
    ok = False
    nR = _residual_into(x, m, alpha_lin, u_pre, w_pre, S, P, modes, freeze, freeze_dir, mu_N, a1, bdt2, gdt,
                        params, w_reg, g, Jg, phi, u, w, R, J, jac)
    best[:] = x
    best_n = nR
    for it in range(max_iter):
        its = it + 1
        for i in range(m):
            rhs[i] = R[i]
        if not _small_solve(J, rhs, m, dx):
            break
        nx = 0.0
        nd = 0.0
        for i in range(m):
            nx += x[i] * x[i]
            nd += dx[i] * dx[i]
        if not (nd == nd):
            break
        if math.sqrt(nd) <= tol * (math.sqrt(nx) + 1e-12):
            for i in range(m):
                x[i] -= dx[i]
            ok = True
            break
        lam = 1.0
        nR2 = nR
        for ls in range(40):
            for i in range(m):
                xt[i] = x[i] - lam * dx[i]
            nR2 = _residual_into(xt, m, alpha_lin, u_pre, w_pre, S, P, modes, freeze, freeze_dir, mu_N, a1, bdt2,
                                 gdt, params, w_reg, g, Jg, phi, u, w, R2, J2, jac)
            if nR2 <= (1.0 - 1e-4 * lam) * nR or nR2 == 0.0:
                break
            lam *= 0.5
        for i in range(m):
            x[i] = xt[i]
            R[i] = R2[i]
            for c in range(m):
                J[i, c] = J2[i, c]
        nR = nR2
        if nR < best_n:
            best_n = nR
            best[:] = x
        if nR == 0.0:
            ok = True
            break
    if not ok:
        x[:] = best
    _forces_into(x, u_pre, w_pre, bdt2, gdt, P, modes, freeze, freeze_dir, mu_N, a1, params, w_reg, g, Jg, phi,
                 u, w, jac)
    return its, ok


@njit(cache=True)
def _reproject(p, v, Q, Minv, Dr, Kr, Bt, WM, SM, P, modes, mu_N, a1, params, w_reg, phi_face):
    """Consistent acceleration at the end of a step in which a face stuck (the stick-onset
    re-projection of :func:`rotor.dynamics.initial.initial_acceleration`): ``M a = Q − D v − K p + Bᵀ g``
    with the stuck faces' relative acceleration zero, at fixed ``(p, v)``. Linear in the stuck
    faces' forces (2 per face), which it writes into ``phi_face``. Returns ``a``.
    (:func:`_consistent_acceleration` with no slipping face's force frozen.)"""
    return _consistent_acceleration(p, v, Q, Minv, Dr, Kr, Bt, WM, SM, P, modes, np.zeros(2, dtype=np.bool_),
                                    np.zeros((2, 2)), mu_N, a1, params, w_reg, phi_face)


@njit(cache=True)
def _consistent_acceleration(p, v, Q, Minv, Dr, Kr, Bt, WM, SM, P, modes, freeze, freeze_dir, mu_N, a1, params,
                             w_reg, phi_face):
    """:func:`_reproject` with the force of each slipping face ``k`` with ``freeze[k]`` set to
    ``freeze_dir[k]`` (N) instead of the regularised slip force at ``v``: the acceleration a step
    restarts from after a friction event (:mod:`rotor.dynamics.friction_events`), where the face's
    velocity is (nearly) zero and its friction is the limit ``μN`` in the direction the event chose.
    Writes the stuck faces' forces, and the frozen ones, into ``phi_face``. Returns ``a``."""
    u = Bt @ p
    w = Bt @ v
    x = np.zeros(NC + 4)
    g = np.zeros(NC)
    Jg = np.zeros((NC, NC))
    phi = np.zeros((2, 2))
    uu = np.zeros(NC)
    ww = np.zeros(NC)
    # forces at (u, w) with the stuck faces' forces zero (x[NC:] = 0; bdt2 = gdt = 0 keeps u, w)
    _forces(x, u, w, 0.0, 0.0, P, modes, freeze, freeze_dir, mu_N, a1, params, w_reg, g, Jg, phi, uu, ww)
    a = Minv @ (Q - Dr @ v - Kr @ p) + WM @ g
    for k in range(2):
        if modes[k] == 0 and freeze[k]:
            phi_face[k, 0] = freeze_dir[k, 0]
            phi_face[k, 1] = freeze_dir[k, 1]
    alpha = Bt @ a
    m = 0
    idx = np.zeros(2, dtype=np.int64)
    for k in range(2):
        if modes[k] == 1:
            idx[m] = k
            m += 1
    if m == 0:
        return a
    # Σ_j P_k S_M[:4,:4] P_jᵀ φ_j = −P_k α[:4] for the stuck faces k
    A = np.zeros((4, 4))
    b = np.zeros(4)
    sol = np.zeros(4)
    for ik in range(m):
        k = idx[ik]
        for rr in range(2):
            b[2 * ik + rr] = -(P[k, rr, 0] * alpha[0] + P[k, rr, 1] * alpha[1] + P[k, rr, 2] * alpha[2]
                               + P[k, rr, 3] * alpha[3])
            for jk in range(m):
                j = idx[jk]
                for cc in range(2):
                    sacc = 0.0
                    for r in range(4):
                        for c in range(4):
                            sacc += P[k, rr, r] * SM[r, c] * P[j, cc, c]
                    A[2 * ik + rr, 2 * jk + cc] = sacc
    if not _small_solve(A, b, 2 * m, sol):
        return a
    gf = np.zeros(NC)
    for ik in range(m):
        k = idx[ik]
        phi_face[k, 0] = sol[2 * ik]
        phi_face[k, 1] = sol[2 * ik + 1]
        for r in range(4):
            gf[r] += P[k, 0, r] * sol[2 * ik] + P[k, 1, r] * sol[2 * ik + 1]
    return a + WM @ gf


@njit(cache=True)
def _load(t, static, orders, cosm, sinm, omega_f, Q):
    """Reduced load ``Q(t)`` (N) written into ``Q``: static part plus the harmonic orders at time ``t`` (s)."""
    Q[:] = static
    for h in range(orders.shape[0]):
        ph = orders[h] * omega_f * t
        cph = math.cos(ph)
        sph = math.sin(ph)
        for i in range(Q.shape[0]):
            Q[i] += cph * cosm[h, i] + sph * sinm[h, i]
    return Q
