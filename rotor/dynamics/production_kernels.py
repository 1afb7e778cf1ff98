"""The compiled inner routines of the production integrator (:mod:`rotor.dynamics.production`).

numba ``njit`` functions on the condensed step: the contact and coupling forces with their
analytic Jacobian (:func:`_forces`), the residual of the condensed step (:func:`_residual`), its
Newton solve with backtracking (:func:`_solve_support`; all three are :func:`_newton`, which evaluates
the step at one place on packed work arrays, :func:`newton_work`, so that an evaluation costs no
reference counts of array arguments), a hand-written Gaussian elimination for
the ≤ 10×10 Newton systems (:func:`_small_solve`), the matrix-vector product into a given array by
numba's own BLAS call (:func:`matvec_into`), the consistent acceleration after a stick onset
(:func:`_reproject`, and :func:`_consistent_acceleration` with slipping faces' forces held, after a
friction event), and the load at a time (:func:`_load`). The step loop is
:func:`rotor.dynamics.production_loop.step_loop`; the events located inside a step
:mod:`rotor.dynamics.friction_events`. The equations are those of :mod:`rotor.dynamics.production`;
the stick/slip rules are :mod:`rotor.dynamics.constraints`, compiled.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic
from numba.np.arrayobj import make_array
from numba.np.linalg import call_xxgemv, ensure_blas

from contact.compiled_cache import compiled_with
from contact.loose_support import point_force_jacobian
from rotor.dynamics import constraints as cons
from rotor.dynamics.kernels import law_tuple

# The kernels below inline rotor.dynamics.constraints and the law kernel (rotor.dynamics.kernels, which
# inlines contact._kernel): their cache entries are stale when any of those sources changes (numba
# itself only watches this file).
compiled_with(__file__, ["rotor.dynamics.constraints", "rotor.dynamics.kernels", "contact._kernel", "contact._kernel_friction",
                         "contact._kernel_tilt"])

# Caching: the law kernel is not an argument but the one compiled law of the suite,
# rotor.dynamics.kernels.contact_kernel, which picks the law (conformal, Pereira, elastic foundation)
# by the law code in its parameter array. A kernel passed as an argument keys numba's cache by the
# dispatcher's identity, which differs in every process (the cache never hit, its index grew, and
# saving eventually failed); a global one is compiled into the loop, so every function here is cached
# on disk (contact.compiled_cache) and compiled once per machine.

_mode_update = njit(cache=True)(cons.face_mode_update)
_coulomb_projection = njit(cache=True, inline="always")(cons.coulomb_projection)



@njit(cache=True, inline="always")
def _slip_force_scalar(wy, wz, mu_N, w_reg):
    """:func:`rotor.dynamics.constraints.slip_force` of the sliding velocity ``(wy, wz)`` (m/s) on scalars, the
    same operations in the same order (nothing allocated): ``(fy, fz, J00, J01, J10, J11)`` (N; N s/m)."""
    s2 = wy * wy + wz * wz + w_reg * w_reg
    s = np.sqrt(s2)
    c = mu_N / (s2 * s)
    return (-mu_N * wy / s, -mu_N * wz / s, -mu_N / s + c * wy * wy, c * wy * wz, c * wz * wy,
            -mu_N / s + c * wz * wz)


@intrinsic
def matvec_into(typingctx, a, x, out):
    """``out[:] = a @ x`` (float64; ``a`` C-contiguous 2-D, ``x`` and ``out`` contiguous 1-D, shapes the caller's
    care) by the very BLAS call of numba's ``a @ x`` (``numba.np.linalg.dot_3_vm``: ``numba_xxgemv``, transposed,
    α = 1, β = 0), so the same numbers; without that wrapper's compiled call, whose three array arguments and
    returned array cost reference counts (~8 atomic operations a product, ~10 products a step)."""
    if not all(isinstance(t, types.Array) and t.dtype == types.float64 and t.layout == "C" for t in (a, x, out)):
        return None
    if a.ndim != 2 or x.ndim != 1 or out.ndim != 1:
        return None

    def codegen(context, builder, sig, args):
        ensure_blas()
        am = make_array(sig.args[0])(context, builder, args[0])
        xm = make_array(sig.args[1])(context, builder, args[1])
        om = make_array(sig.args[2])(context, builder, args[2])
        shapes = cgutils.unpack_tuple(builder, am.shape)
        zero = context.get_constant(types.intp, 0)
        empty = builder.or_(builder.icmp_signed("==", cgutils.unpack_tuple(builder, xm.shape)[0], zero),
                            builder.icmp_signed("==", shapes[0], zero))
        with builder.if_else(empty, likely=False) as (is_empty, not_empty):
            with is_empty:
                cgutils.memset(builder, om.data, builder.mul(om.itemsize, om.nitems), 0)
            with not_empty:
                call_xxgemv(context, builder, True, sig.args[0], shapes, am.data, xm.data, om.data)
        return context.get_dummy_value()

    return types.void(a, x, out), codegen


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


# Work arrays of the Newton solve (newton_work): rows of `vec` (MX,), slabs of `mat` (MX, MX), columns of `face`.
# One evaluation of the condensed step reads and writes only these (a handful of array arguments: every array
# argument of a compiled call costs a reference-count increment and decrement, which dominated the step).
MX = NC + 4  # Newton unknowns at most: α and two multipliers per stuck face
VX, VR, VR2, VRHS, VXT, VDX, VBEST, VG, VU, VW, VALIN, VUPRE, VWPRE = range(13)   # rows of vec
MJ, MJ2, MJG, MS = range(4)                                   # slabs of mat (MS: S, NC × NC)
F_FROZEN, F_FD0, F_FD1, F_MU, F_PHI0, F_PHI1 = range(6)       # columns of face, one row a face


@njit(cache=True)
def newton_work():
    """The work arrays of the condensed Newton solve, allocated once per step loop: ``(vec (13, MX), mat (4, MX, MX),
    face (2, 6), jac (4, 8))``. Rows of ``vec``: iterate, residual, trial residual, right-hand side, trial iterate,
    Newton step, best iterate, forces g, condensed u, w, and the step's α_lin, u_pre, w_pre; ``mat``: Newton matrix,
    trial matrix, ∂g/∂α, S; ``face`` per face: frozen (1.0/0.0), frozen force (2, N), μN (N), face force
    φ (2, N); ``jac``: the law's Jacobian."""
    return np.zeros((13, MX)), np.zeros((4, MX, MX)), np.zeros((2, 6)), np.zeros((4, 8))


@njit(cache=True, inline="always")
def _projected_rows(vec, mat, face, P, k, j, gdt):
    """Rows ``j, j+1`` of the condensed residual and Newton matrix for face ``k`` solved by projection
    (:func:`rotor.dynamics.constraints.coulomb_projection`): ``R = c (f̄ − proj(f̄ − r w))`` with ``f̄`` the step
    mean of the face force (``face[k, F_FROZEN]`` 1: ``(f_start + f_end)/2``, ``f_start`` in ``face[k, F_FD0:]``;
    0: the end force alone), ``w`` the face's end velocity, ``c`` the face's mean condensed compliance (1/kg) and
    ``r = 1/(c γΔt)``: stuck, the rows are the stuck face's ``P w/(γΔt)``; slipping, ``c (f̄ − μN q̂)``."""
    c = 0.0
    for rr in range(2):
        for a in range(4):
            for b in range(4):
                c += P[k, rr, a] * mat[MS, a, b] * P[k, rr, b]
    c *= 0.5
    r = 1.0 / (c * gdt)
    wm = 0.5 if face[k, F_FROZEN] != 0.0 else 0.0
    fy = (1.0 - wm) * vec[VXT, j] + wm * face[k, F_FD0]
    fz = (1.0 - wm) * vec[VXT, j + 1] + wm * face[k, F_FD1]
    wy = P[k, 0, 0] * vec[VW, 0] + P[k, 0, 1] * vec[VW, 1] + P[k, 0, 2] * vec[VW, 2] + P[k, 0, 3] * vec[VW, 3]
    wz = P[k, 1, 0] * vec[VW, 0] + P[k, 1, 1] * vec[VW, 1] + P[k, 1, 2] * vec[VW, 2] + P[k, 1, 3] * vec[VW, 3]
    py, pz, d00, d01, d11 = _coulomb_projection(fy, fz, wy, wz, face[k, F_MU], r)
    vec[VR2, j] = c * (fy - py)
    vec[VR2, j + 1] = c * (fz - pz)
    for col in range(4):    # ∂R/∂α = D P_k (c r γΔt = 1)
        mat[MJ2, j, col] = d00 * P[k, 0, col] + d01 * P[k, 1, col]
        mat[MJ2, j + 1, col] = d01 * P[k, 0, col] + d11 * P[k, 1, col]
    e = c * (1.0 - wm)      # ∂R/∂f_end = c (1 − wm)(I − D)
    mat[MJ2, j, j] = e * (1.0 - d00)
    mat[MJ2, j, j + 1] = -e * d01
    mat[MJ2, j + 1, j] = -e * d01
    mat[MJ2, j + 1, j + 1] = e * (1.0 - d11)


@njit(cache=True)
def _newton(vec, mat, face, jac, P, modes, params, m, a1, bdt2, gdt, w_reg, tol, max_iter, evaluate_only):
    """Newton on the condensed unknowns [α (NC); φ of stuck faces (2 each)] from ``vec[VX]``, analytic Jacobian,
    with backtracking on |R| when a full step does not decrease it (kinks of the law); the least-residual
    iterate if it does not converge. Leaves the result in ``vec[VX]``, and at it the condensed forces g
    (``vec[VG]``), ∂g/∂α (``mat[MJG]``), u, w (``vec[VU]``, ``vec[VW]``) and the face forces ``face[:, F_PHI0:]``.
    ``evaluate_only``: no Newton, these at ``vec[VX]`` and the residual of the first ``m`` unknowns into
    ``vec[VR2]``, ``mat[MJ2]`` (m = 0: the forces alone). Work arrays of :func:`newton_work`, loaded by
    :func:`_load_work` and :func:`_load_step`. Returns (iterations, converged, |R| of the last evaluation).

    The condensed step is evaluated at one place, in a loop over its stages (the first iterate, the
    line-search trials, the forces at the result): a compiled call with array arguments costs reference
    counts, which dominated the step."""
    for i in range(MX):
        vec[VXT, i] = vec[VX, i]
    pt = law_tuple(params)      # the law's parameters, as rotor.dynamics.kernels.contact_point passes them
    Jn = mat[MJ]
    rhs = vec[VRHS]
    dx = vec[VDX]
    its = 0
    ok = False
    stage = 2 if evaluate_only else 0   # 0: the first iterate, 1: a line-search trial, 2: the forces at the result
    it = 0
    ls = 0
    lam = 1.0
    nR = 0.0
    nR2 = 0.0
    best_n = 0.0
    while True:
        # ---- the condensed step at vec[VXT]: forces, and with m_now > 0 the residual into vec[VR2], mat[MJ2]
        m_now = m if (stage != 2 or evaluate_only) else 0
        for i in range(NC):
            vec[VU, i] = vec[VUPRE, i] + bdt2 * vec[VXT, i]
            vec[VW, i] = vec[VWPRE, i] + gdt * vec[VXT, i]
        f0, f1, f2, f3 = point_force_jacobian(vec[VU, 0], vec[VU, 1], vec[VU, 2], vec[VU, 3], vec[VW, 0], vec[VW, 1],
                                              vec[VW, 2], vec[VW, 3], pt, jac)
        for i in range(NC):
            vec[VG, i] = 0.0
            for j in range(NC):
                mat[MJG, i, j] = 0.0
        vec[VG, 0] = f0
        vec[VG, 1] = f1
        vec[VG, 2] = f2
        vec[VG, 3] = f3
        for i in range(4):
            for j in range(4):
                mat[MJG, i, j] = jac[i, j] * bdt2 + jac[i, 4 + j] * gdt
        if a1 != 0.0:
            d0 = vec[VU, 4]
            d1 = vec[VU, 5]
            s2 = d0 * d0 + d1 * d1
            vec[VG, 4] = -a1 * s2 * d0
            vec[VG, 5] = -a1 * s2 * d1
            mat[MJG, 4, 4] = -a1 * (s2 + 2 * d0 * d0) * bdt2
            mat[MJG, 4, 5] = -a1 * (2 * d0 * d1) * bdt2
            mat[MJG, 5, 4] = mat[MJG, 4, 5]
            mat[MJG, 5, 5] = -a1 * (s2 + 2 * d1 * d1) * bdt2
        j = NC
        for k in range(2):
            if modes[k] >= 1:       # stuck or projected: the face force is an unknown
                face[k, F_PHI0] = vec[VXT, j]
                face[k, F_PHI1] = vec[VXT, j + 1]
                j += 2
            elif face[k, F_FROZEN] != 0.0:
                face[k, F_PHI0] = face[k, F_FD0]
                face[k, F_PHI1] = face[k, F_FD1]
            else:
                wy = (P[k, 0, 0] * vec[VW, 0] + P[k, 0, 1] * vec[VW, 1] + P[k, 0, 2] * vec[VW, 2]
                      + P[k, 0, 3] * vec[VW, 3])
                wz = (P[k, 1, 0] * vec[VW, 0] + P[k, 1, 1] * vec[VW, 1] + P[k, 1, 2] * vec[VW, 2]
                      + P[k, 1, 3] * vec[VW, 3])
                face[k, F_PHI0], face[k, F_PHI1], j00, j01, j10, j11 = _slip_force_scalar(wy, wz, face[k, F_MU],
                                                                                          w_reg)
                # Jg += Pkᵀ Jk Pk γΔt
                for r in range(4):
                    for c in range(4):
                        s = 0.0
                        s += P[k, 0, r] * j00 * P[k, 0, c]
                        s += P[k, 0, r] * j01 * P[k, 1, c]
                        s += P[k, 1, r] * j10 * P[k, 0, c]
                        s += P[k, 1, r] * j11 * P[k, 1, c]
                        mat[MJG, r, c] += s * gdt
            for r in range(4):
                vec[VG, r] += P[k, 0, r] * face[k, F_PHI0] + P[k, 1, r] * face[k, F_PHI1]
        nR2 = 0.0
        if m_now > 0:
            for r in range(m_now):
                for c in range(m_now):
                    mat[MJ2, r, c] = 0.0
            for r in range(NC):
                s = 0.0
                for c in range(NC):
                    s += mat[MS, r, c] * vec[VG, c]
                vec[VR2, r] = vec[VXT, r] - vec[VALIN, r] - s
                for c in range(NC):
                    s = 0.0
                    for k in range(NC):
                        s += mat[MS, r, k] * mat[MJG, k, c]
                    mat[MJ2, r, c] = (1.0 if r == c else 0.0) - s
            j = NC
            for k in range(2):
                if modes[k] == 2:
                    _projected_rows(vec, mat, face, P, k, j, gdt)
                if modes[k] == 1:
                    for rr in range(2):
                        vec[VR2, j + rr] = (P[k, rr, 0] * vec[VW, 0] + P[k, rr, 1] * vec[VW, 1]
                                            + P[k, rr, 2] * vec[VW, 2] + P[k, rr, 3] * vec[VW, 3]) / gdt
                        for c in range(4):
                            mat[MJ2, j + rr, c] = P[k, rr, c]
                if modes[k] >= 1:
                    for r in range(NC):
                        for rr in range(2):
                            s = 0.0
                            for c in range(4):
                                s += mat[MS, r, c] * P[k, rr, c]
                            mat[MJ2, r, j + rr] = -s
                    j += 2
            nr = 0.0
            for i in range(m_now):
                nr += vec[VR2, i] * vec[VR2, i]
            nR2 = math.sqrt(nr)
        # ---- the stage's decision
        if stage == 2:
            break
        if stage == 1 and not (nR2 <= (1.0 - 1e-4 * lam) * nR or nR2 == 0.0) and ls < 39:
            lam *= 0.5      # backtrack
            ls += 1
            for i in range(m):
                vec[VXT, i] = vec[VX, i] - lam * dx[i]
            continue
        for i in range(m):  # the trial is the new iterate
            vec[VX, i] = vec[VXT, i]
            vec[VR, i] = vec[VR2, i]
            for c in range(m):
                Jn[i, c] = mat[MJ2, i, c]
        nR = nR2
        if stage == 0 or nR < best_n:
            best_n = nR
            for i in range(MX):
                vec[VBEST, i] = vec[VX, i]
        if stage == 1 and nR == 0.0:
            ok = True
        stage = 2
        if not ok and it < max_iter:    # the next Newton iteration
            its = it + 1
            it += 1
            for i in range(m):
                rhs[i] = vec[VR, i]
            if _small_solve(Jn, rhs, m, dx):
                nx = 0.0
                nd = 0.0
                for i in range(m):
                    nx += vec[VX, i] * vec[VX, i]
                    nd += dx[i] * dx[i]
                if nd == nd:
                    if math.sqrt(nd) <= tol * (math.sqrt(nx) + 1e-12):
                        for i in range(m):
                            vec[VX, i] -= dx[i]
                        ok = True
                    else:
                        lam = 1.0
                        ls = 0
                        for i in range(m):
                            vec[VXT, i] = vec[VX, i] - lam * dx[i]
                        stage = 1
        if stage == 2:
            if not ok:
                for i in range(MX):
                    vec[VX, i] = vec[VBEST, i]
            for i in range(MX):
                vec[VXT, i] = vec[VX, i]
    return its, ok, nR2


@njit(cache=True)
def _load_work(vec, face, x, u_pre, w_pre, freeze, freeze_dir, mu_N):
    """Copy the inputs of :func:`_newton`'s forces into its work arrays: the iterate ``x`` (into ``vec[VX]``),
    u_pre, w_pre (NC,), the frozen faces' forces and μN."""
    for i in range(MX):
        vec[VX, i] = x[i] if i < x.shape[0] else 0.0
    for i in range(NC):
        vec[VUPRE, i] = u_pre[i]
        vec[VWPRE, i] = w_pre[i]
    for k in range(2):
        face[k, F_FROZEN] = 1.0 if freeze[k] else 0.0
        face[k, F_FD0] = freeze_dir[k, 0]
        face[k, F_FD1] = freeze_dir[k, 1]
        face[k, F_MU] = mu_N[k]


@njit(cache=True)
def _load_step(vec, mat, alpha_lin, S):
    """Copy the inputs of :func:`_newton`'s residual into its work arrays: α_lin (NC,) and S (NC, NC)."""
    for i in range(NC):
        vec[VALIN, i] = alpha_lin[i]
        for c in range(NC):
            mat[MS, i, c] = S[i, c]


@njit(cache=True)
def _forces_out(vec, mat, face, g, Jg, phi, u, w):
    """Copy :func:`_newton`'s forces g, ∂g/∂α, face forces φ and condensed u, w out of its work arrays."""
    for i in range(NC):
        g[i] = vec[VG, i]
        u[i] = vec[VU, i]
        w[i] = vec[VW, i]
        for c in range(NC):
            Jg[i, c] = mat[MJG, i, c]
    for k in range(2):
        phi[k, 0] = face[k, F_PHI0]
        phi[k, 1] = face[k, F_PHI1]


@njit(cache=True)
def _forces(x, u_pre, w_pre, bdt2, gdt, P, modes, freeze, freeze_dir, mu_N, a1, params, w_reg,
            g, Jg, phi, u, w):
    """Condensed forces g (NC,) and ∂g/∂α (NC, NC) at iterate x (stuck-face forces from x[NC:]);
    also leaves the condensed displacement u and velocity w of the iterate."""
    vec, mat, face, jac = newton_work()
    _load_work(vec, face, x, u_pre, w_pre, freeze, freeze_dir, mu_N)
    _newton(vec, mat, face, jac, P, modes, params, 0, a1, bdt2, gdt, w_reg, 0.0, 0, True)
    _forces_out(vec, mat, face, g, Jg, phi, u, w)


@njit(cache=True)
def _residual(x, m, alpha_lin, u_pre, w_pre, S, P, modes, freeze, freeze_dir, mu_N, a1, bdt2, gdt, params,
              w_reg, g, Jg, phi, u, w, R, J):
    """Residual R and analytic Jacobian J (first m rows/cols) of the condensed step at iterate x; returns |R|.
    Also leaves g, ∂g/∂α, the face forces φ and u, w as :func:`_forces`."""
    vec, mat, face, jac = newton_work()
    _load_work(vec, face, x, u_pre, w_pre, freeze, freeze_dir, mu_N)
    _load_step(vec, mat, alpha_lin, S)
    nR = _newton(vec, mat, face, jac, P, modes, params, m, a1, bdt2, gdt, w_reg, 0.0, 0, True)[2]
    _forces_out(vec, mat, face, g, Jg, phi, u, w)
    for i in range(m):
        R[i] = vec[VR2, i]
        for c in range(m):
            J[i, c] = mat[MJ2, i, c]
    return nR


@njit(cache=True)
def _solve_support(alpha, alpha_lin, u_pre, w_pre, S, P, modes, phi_stuck, freeze, freeze_dir, mu_N, a1,
                   bdt2, gdt, params, tol, max_iter, w_reg, vec, mat, face, jac, phi):
    """Newton on the condensed unknowns [α (NC); φ of stuck faces (2 each)], analytic Jacobian,
    with backtracking on |R| when a full step does not decrease it (kinks of the law).
    If it does not converge, the least-residual iterate is returned with ok = False.

    Work arrays from :func:`newton_work`. Leaves the new α in ``vec[VX, :NC]``, the forces g in ``vec[VG, :NC]``
    and the face forces in ``phi`` (2, 2). Returns (iterations, converged). (:func:`_newton` on the loaded work
    arrays.)"""
    n_st = 0
    for k in range(2):
        if modes[k] >= 1:
            n_st += 1
    m = NC + 2 * n_st
    _load_work(vec, face, alpha, u_pre, w_pre, freeze, freeze_dir, mu_N)
    _load_step(vec, mat, alpha_lin, S)
    j = NC
    for k in range(2):
        if modes[k] >= 1:
            vec[VX, j] = phi_stuck[k, 0]
            vec[VX, j + 1] = phi_stuck[k, 1]
            j += 2
    its, ok, _ = _newton(vec, mat, face, jac, P, modes, params, m, a1, bdt2, gdt, w_reg, tol, max_iter, False)
    for k in range(2):
        phi[k, 0] = face[k, F_PHI0]
        phi[k, 1] = face[k, F_PHI1]
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
