"""Production integrator: the same Newmark/constraint discretisation as :mod:`rotor.dynamics.reference`, fast.

Same equations, same step, same stick/slip logic (:mod:`rotor.dynamics.constraints`), hence the
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
4. **Compiled step loop** (numba ``njit``) with a hand-written Gaussian elimination for the
   ≤ 10×10 Newton system and explicit loops for the small products: measured, one LAPACK
   ``solve`` call costs ≈ 2 µs and a numpy call ≈ 1 µs of overhead, and a step needs
   ~4 Newton iterations of a dozen such operations, while the whole step now takes ≈ 10 µs
   (``benchmarks/bench_integrators.py``; the pure-Python reference runs at ≈ 70 steps/s).

Same safeguards as the reference (see :mod:`rotor.dynamics.reference`): backtracking, stick fallback,
least-residual acceptance counted in ``Trajectory.unconverged_steps``. Same stick-onset rule
(:mod:`rotor.dynamics.constraints`, "Stick onset"): the consistent multipliers and acceleration come from
``M a = Q − D v − K p + Bᵀ g`` at fixed ``(p, v)`` with the stuck faces' relative acceleration
zero, condensed like the step (``W_M = M⁻¹ Bᵀ``, ``S_M = B M⁻¹ Bᵀ``,
:func:`rotor.dynamics.production_kernels._reproject`).

A runtime check records the largest ``ω_c Δt`` met, with ``ω_c² = k_t (B M⁻¹ Bᵀ)_yy`` and
``k_t`` the current radial tangent stiffness of the law, so a too-large step is
reported after the fact as well as refused up front (:func:`rotor.dynamics.system.check_time_step`).

This module prepares the system (:func:`prepare`) and drives the run; the compiled routines
(items 3 and 4) are in :mod:`rotor.dynamics.production_kernels` (forces, Newton) and
:mod:`rotor.dynamics.production_loop` (the step and the loop), the law kernel in :mod:`rotor.dynamics.kernels`. With
``NewmarkOptions.locate_events`` a friction velocity reversal or stick onset is located inside the step
and the step split there (:mod:`rotor.dynamics.friction_events`).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from contact.errors import ConvergenceError, InputError, OutsideDomainError
from contact.loose_support import N_PARAMS
from rotor.dynamics import constraints as cons
from rotor.dynamics.condense import condense, expand
from rotor.dynamics.initial import initial_state
from rotor.dynamics.kernels import contact_kernel
from rotor.dynamics.production_loop import step_loop
from rotor.dynamics.projection_start import projected_branch_modes, projected_modes, projected_start
from rotor.dynamics.system import (NewmarkOptions, RotorSystem, Trajectory, check_inputs, check_time_step, coupling_map,
                                   relative_compliance)


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
    limits: np.ndarray
    n_faces: int
    s_yy: float
    dt: float
    a1: float
    Minv: np.ndarray
    WM: np.ndarray
    SM: np.ndarray
    Mr: np.ndarray


def prepare(system: RotorSystem, dt: float, options: NewmarkOptions | None = None) -> Prepared:
    """Reduce, factorise and condense ``system`` for step ``dt`` (s)."""
    opts = options or NewmarkOptions()
    condensed = condense(system)  # DOFs without mass or inertia: statically condensed (rotor.dynamics.condense)
    system = condensed.system if condensed is not None else system
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
        P, limits, n_faces = sup.faces()
        s_yy = float(relative_compliance(system)[0, 0])
    else:
        B = np.zeros((4, n))
        P, limits, n_faces = np.zeros((2, 2, 4)), np.zeros(2), 0
        s_yy = 0.0
    E = np.vstack([B, coupling_map(system)])
    Bt = E @ T
    W = Ainv @ Bt.T
    S = Bt @ W
    f = system.force
    static = T.T @ (f.static + system.K @ system.offset)
    a1 = float(system.coupling[2]) if system.coupling is not None else 0.0
    # for the consistent acceleration after a stick onset (see _reproject): M⁻¹, W_M, S_M
    Minv = np.linalg.inv(Mr)
    WM = Minv @ Bt.T
    SM = Bt @ WM
    return Prepared(T, Ainv, Dr, Kr, Bt, W, S, static, np.asarray(f.orders, float), f.cos @ T, f.sin @ T,
                    float(f.omega_rad_s), P, limits, n_faces, s_yy, float(dt), a1, Minv, WM, SM, Mr)



def simulate_production(system: RotorSystem, dt: float, n_steps: int, q0=None, v0=None, *, t0: float = 0.0,
                        modes0=(cons.STICK, cons.STICK), options: NewmarkOptions | None = None,
                        record_every: int = 1, check_step: bool = True, prepared: Prepared | None = None) -> Trajectory:
    """Integrate like :func:`rotor.dynamics.reference.simulate_reference`, fast. Same arguments and result.

    The support law must provide a numba ``kernel`` (analytic Jacobian). ``prepared`` reuses
    a :func:`prepare` result for the same system and ``dt``.
    """
    opts = options or NewmarkOptions()
    condensed = condense(system)
    if condensed is not None:  # integrate the massive DOFs, recover the massless ones (rotor.dynamics.condense)
        keep = condensed.keep
        tr = simulate_production(condensed.system, dt, n_steps, None if q0 is None else np.asarray(q0, float)[keep],
                                 None if v0 is None else np.asarray(v0, float)[keep], t0=t0, modes0=modes0,
                                 options=options, record_every=record_every, check_step=check_step, prepared=prepared)
        return expand(condensed, tr)
    n = system.n
    q0 = np.zeros(n) if q0 is None else np.asarray(q0, dtype=float).copy()
    v0 = np.zeros(n) if v0 is None else np.asarray(v0, dtype=float).copy()
    check_inputs(system, dt, n_steps, q0, v0)
    sup = system.support
    if sup is not None:
        if sup.law.kernel is not contact_kernel:
            raise InputError(f"support law {sup.law.name!r}: the production scheme compiles only "
                             "rotor.dynamics.kernels.contact_kernel (any law of contact.loose_support, chosen by its "
                             "law code); use rotor.dynamics.reference.simulate_reference")
        if check_step:
            check_time_step(system, dt)
    pre = prepared if prepared is not None else prepare(system, dt, opts)
    if abs(pre.dt - dt) > 1e-15 * dt:
        raise InputError(f"prepared: made for dt = {pre.dt:g} s, called with dt_s = {dt:g} s")
    if system.lock.shape[0] and np.abs(system.lock @ q0).max() > 1e-12 * (1 + np.abs(q0).max()):
        raise InputError("q0: violates the lock (3a/3b equal displacement) constraint")
    T = pre.T
    params = np.asarray(sup.law.params, dtype=float) if sup is not None else np.zeros(N_PARAMS)
    projected = sup is not None and opts.friction_scheme == "projection"
    if projected:       # the start's acceleration and face forces by the step's own projection (projection_start)
        p, vp = T.T @ q0, T.T @ v0
        modes = projected_modes(pre.n_faces)
        ap, phi_face = projected_start(pre, t0, p, vp, params, opts)
    else:
        a0, modes, phi_face = _initial_faces(system, t0, q0, v0, modes0, opts)
        p, vp, ap = T.T @ q0, T.T @ v0, T.T @ a0
    rec = _records(system, n_steps // record_every + 1, T.shape[1], t0, p, vp, ap, q0, v0, modes, phi_face)
    status = np.zeros(7, dtype=np.int64)
    try:
        done, wdt_max = step_loop(p, vp, ap, modes, phi_face, float(t0), float(dt), int(n_steps), int(record_every),
                                  pre.Ainv, pre.Dr, pre.Kr, pre.Bt, pre.W, pre.S, pre.static, pre.orders, pre.cos,
                                  pre.sin, pre.omega_force, pre.P, pre.limits, pre.n_faces, pre.s_yy, pre.a1, sup is not None,
                                  params, opts.beta, opts.gamma, opts.tol, opts.max_iter, opts.w_reg, opts.w_stick,
                                  opts.max_passes, float(opts.stick_mean_weight), bool(opts.consistent_stick_onset),
                                  pre.Minv, pre.WM, pre.SM, pre.Mr, bool(opts.locate_events) and not projected, True, rec["t"], rec["p"],
                                  rec["v"], rec["a"], rec["u"], rec["w"], rec["fc"], rec["fel"], rec["face"], rec["modes"], rec["its"], rec["passes"], status)
    except OutsideDomainError as e:
        raise OutsideDomainError(
            f"{e} (production run from t = {t0:g} s, dt_s = {dt:.3e} s, {n_steps} steps, clearance "
            f"{sup.law.clearance_m * 1e3:g} mm): the load drives the ring beyond the law's validity; use a larger "
            "clearance, a smaller load, or a law without a neat-fit limit (law 'pereira')") from e
    if status[0] != 0:
        t_fail = t0 + status[1] * dt
        what = "Newton did not converge" if status[0] == 1 else "non-finite state"
        raise ConvergenceError(
            f"production scheme: {what} at step {status[1]}, t = {t_fail:.6g} s (tol = {opts.tol:.1e}, "
            f"max_iter = {opts.max_iter}); largest ω_c·Δt met = {wdt_max:.3g}; reduce dt_s = {dt:.3e} s")
    if projected:       # the modes recorded as the branch each face's projection took, for the record's readers
        rec["modes"] = projected_branch_modes(rec["w"], pre.P, pre.n_faces)
    tr = Trajectory(t=rec["t"], q=rec["p"] @ T.T, v=rec["v"] @ T.T, a=rec["a"] @ T.T, u=rec["u"], w=rec["w"],
                    f_contact=rec["fc"], f_elastic=rec["fel"], face_force=rec["face"], modes=rec["modes"],
                    newton_iters=rec["its"], passes=rec["passes"], omega_dt_max=float(wdt_max),
                    unconverged_steps=int(status[2]), located_events=int(status[4]),
                    scheme="production (condensed, analytic Jacobian, numba)")
    return tr


def warm_up() -> dict:
    """Compile the step loop, or load it from the on-disk cache (:mod:`contact.compiled_cache`), now.

    Runs :func:`rotor.dynamics.production_loop.step_loop` for zero steps on arguments of the
    types :func:`simulate_production` passes, so that a later run times the stepping alone.

    Returns
    -------
    dict
        ``compile_s`` (s, wall time of the compile or cache load; 0 if already done in this
        process) and ``from_cache`` (True if the machine code came from the disk cache).
    """
    if step_loop.signatures:
        return {"compile_s": 0.0, "from_cache": bool(sum(step_loop.stats.cache_hits.values()))}
    f1, f2, f3 = np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2, 4))
    i1 = np.zeros(2, dtype=np.int64)
    rec = [np.zeros(1), f2, f2, f2, f2, f2, f2, f2, f3, np.zeros((1, 2), dtype=np.int8),
           np.zeros(1, dtype=np.int32), np.zeros(1, dtype=np.int32), np.zeros(7, dtype=np.int64)]
    t0 = time.perf_counter()
    step_loop(f1, f1.copy(), f1.copy(), i1, f2.copy(), 0.0, 1.0, 0, 1, f2, f2, f2, f2, f2, f2, f1, f1, f2, f2, 0.0, f3,
              f1, 0, 0.0, 0.0, True, np.zeros(N_PARAMS), 0.25, 0.5, 1e-10, 1, 0.0, 0.0, 1, 0.0, True, f2, f2, f2, f2, False, True, *rec)
    return {"compile_s": time.perf_counter() - t0, "from_cache": bool(sum(step_loop.stats.cache_hits.values()))}


def _initial_faces(system: RotorSystem, t0: float, q0, v0, modes0, opts: NewmarkOptions):
    """``(q̈_0, modes (2,) int64, face forces (2, 2))`` at the start, as the reference: the stick test
    applied to ``modes0`` (:func:`rotor.dynamics.initial.initial_state`), stuck faces carrying ``−λ``."""
    sup = system.support
    n = system.n
    P, limits, n_faces = sup.faces() if sup is not None else (None, None, 0)
    modes = np.array([int(m) for m in modes0][:n_faces] + [cons.SLIP] * (2 - n_faces), dtype=np.int64)
    a0, lam, m0 = initial_state(system, t0, q0, v0, list(modes), opts)
    modes = np.array(m0, dtype=np.int64)
    phi_face = np.zeros((2, 2))
    j = system.lock.shape[0]
    for k in range(n_faces):
        if modes[k] == cons.STICK:
            phi_face[k] = -lam[j:j + 2]
            j += 2
        else:  # as the reference: the slip force at the initial velocity
            wk = P[k] @ (sup.relative_map(n) @ v0)
            phi_face[k] = cons.slip_force(wk, limits[k], opts.w_reg)[0]
    return a0, modes, phi_face


def _records(system: RotorSystem, n_rec: int, nr: int, t0: float, p, vp, ap, q0, v0, modes, phi_face) -> dict:
    """The arrays the compiled loop records into (reduced coordinates, ``nr`` of them), sample 0 filled."""
    rec = dict(t=np.zeros(n_rec), p=np.zeros((n_rec, nr)), v=np.zeros((n_rec, nr)), a=np.zeros((n_rec, nr)),
               u=np.zeros((n_rec, 4)), w=np.zeros((n_rec, 4)), fc=np.zeros((n_rec, 4)), fel=np.zeros((n_rec, 4)),
               face=np.zeros((n_rec, 2, 2)), modes=np.zeros((n_rec, 2), dtype=np.int8),
               its=np.zeros(n_rec, dtype=np.int32), passes=np.zeros(n_rec, dtype=np.int32))
    rec["t"][0] = t0
    rec["p"][0], rec["v"][0], rec["a"][0] = p, vp, ap
    sup = system.support
    if sup is not None:
        B = sup.relative_map(system.n)
        u0, w0 = B @ q0, B @ v0
        rec["u"][0], rec["w"][0] = u0, w0
        rec["fc"][0] = sup.law.force(u0, w0)
        rec["fel"][0] = sup.law.force(u0, np.zeros(4))
        rec["modes"][0] = modes
        rec["face"][0] = phi_face
    return rec
