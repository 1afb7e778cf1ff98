"""Starting states: consistent accelerations and multipliers at a given state, and the linear start.

:func:`initial_acceleration` solves the acceleration-level constraints (lock rows and stuck faces)
at fixed ``(q, q̇)``: both schemes start from it (:func:`initial_state`, with the stick test
applied to the requested modes), and it is the stick-onset restart of the reference scheme
(:mod:`rotor.dynamics.constraints`, "Stick onset"). :func:`linear_initial_state` is the periodic
solution of the linear system, a start for steady-state runs.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contact.errors import ConvergenceError, OutsideDomainError
from rotor.dynamics import constraints as cons
from rotor.dynamics.system import NewmarkOptions, RotorSystem, coupling_force, coupling_map, support_forces


def initial_acceleration(system: RotorSystem, t0: float, q0, v0, modes, opts: NewmarkOptions):
    """Consistent ``q̈_0`` and multipliers at ``t0``: lock and stuck faces at acceleration level."""
    n = system.n
    rows = [system.lock]
    if system.support is not None:
        B = system.support.relative_map(n)
        P, _, n_faces = system.support.faces()
        rows += [P[k] @ B for k in range(n_faces) if modes[k] == cons.STICK]
    Phi = np.vstack(rows) if rows else np.zeros((0, n))
    _, _, _, _, gnl = support_forces(system, q0, v0, [cons.SLIP if m == cons.SLIP else cons.STICK for m in modes], np.zeros((2, 2)), opts)
    rhs = system.force(t0) - system.D @ v0 - system.K @ (q0 - system.offset) + gnl + coupling_force(system, q0)
    m = Phi.shape[0]
    A = np.block([[system.M, Phi.T], [Phi, np.zeros((m, m))]])
    z = np.linalg.solve(A, np.concatenate([rhs, np.zeros(m)]))
    return z[:n], z[n:]


def initial_state(system: RotorSystem, t0: float, q0, v0, modes0, opts: NewmarkOptions):
    """``(q̈_0, multipliers, modes)``: like :func:`initial_acceleration`, with the stick test applied
    to the requested initial modes (a face whose holding force exceeds μN starts slipping)."""
    modes = list(modes0)
    n_l = system.lock.shape[0]
    for _ in range(3):
        a0, lam = initial_acceleration(system, t0, q0, v0, modes, opts)
        if system.support is None:
            return a0, lam, modes
        j = n_l
        changed = False
        _, limits, n_faces = system.support.faces()
        for k in range(n_faces):
            if modes[k] == cons.STICK:
                if float(np.hypot(*lam[j:j + 2])) > limits[k] * (1 + 1e-12):
                    modes[k] = cons.SLIP
                    changed = True
                j += 2
        if not changed:
            return a0, lam, modes
    return a0, lam, modes


def linear_initial_state(system: RotorSystem, t0: float = 0.0, lock_support: bool = True):
    """``(q0, v0)``: the exact periodic solution at ``t0`` of the *linear* system with the loose
    support locked (bearing and support moving together, both end faces stuck) or free. With the
    tilt ignored (§5.2) only the lateral relative motion is locked: no moment passes.

    A good start for a steady-state run: the 1X/2X response of the rotor is already there,
    so only the (much smaller) nonlinear correction has to decay. Static part
    ``K (q − Δq_m) = static``, harmonics ``(K − (kΩ)² M + i kΩ D) X_k = c_k − i s_k``.
    """
    n = system.n
    rows = [system.lock]
    if lock_support and system.support is not None:
        rows.append(system.support.relative_map(n)[:2 if system.support.tilt_ignored else 4])
    T = cons.null_space_map(np.vstack(rows))
    Mr, Dr, Kr = T.T @ system.M @ T, T.T @ system.D @ T, T.T @ system.K @ T
    f = system.force
    q = T @ np.linalg.solve(Kr, T.T @ (f.static + system.K @ system.offset))
    v = np.zeros(n)
    for k, c, s in zip(f.orders, f.cos, f.sin):
        wk = k * f.omega_rad_s
        X = T @ np.linalg.solve(Kr - wk * wk * Mr + 1j * wk * Dr, T.T @ (c - 1j * s))
        e = np.exp(1j * wk * t0)
        q += (X * e).real
        v += (1j * wk * X * e).real
    return q, v


#: the share of its friction limit μN a face that could not hold the static load carries at the start
HELD_SHARE = 0.999


@dataclass(frozen=True)
class StaticStart:
    """The static equilibrium a run starts from (:func:`static_equilibrium`).

    ``q_m`` (n,) displacements (m, rad) with the lock rows met; ``modes`` the end faces' start modes (all
    :data:`~rotor.dynamics.constraints.STICK`: a face beyond its friction limit holds at the limit, ``at_limit``);
    ``face_force_N`` (2, 2) each face's force on the bearing; ``contact_force`` (4,) the ring's contact force and
    moment on the bearing (N, N m); ``iterations`` Newton iterations; ``residual_N`` the largest force residual.
    """

    q_m: np.ndarray
    modes: tuple
    at_limit: tuple
    face_force_N: np.ndarray
    contact_force: np.ndarray
    iterations: int
    residual_N: float


def static_equilibrium(system: RotorSystem, *, max_iter: int = 400) -> StaticStart:
    """The static equilibrium of ``system`` under its constant load: gravity, ``[[static_loads]]``, the
    misalignment offset (``K (q − Δq_m) = f_static + …``), with the loose support's contact and end-face friction.

    The end faces are first held where a run from rest starts them (the relative motion of the offset state): a
    linear solve whose face multipliers are the holding forces. A face whose holding force exceeds its limit μN
    slips: it then carries μN against the load (the direction of its holding force) and the ring moves until its
    contact carries the rest: Newton on the equilibrium with the law's analytic Jacobian (the compiled kernel,
    ``SupportLaw.kernel``), the ring's relative motion limited to a quarter of the clearance a step so that the
    stiff law is entered gradually. A face that slipped holds :data:`HELD_SHARE` of its limit at the start (an
    admissible static state: any force up to μN is; at exactly μN the regularised slip of the first steps would let
    the ring creep) and starts stuck; the first step's stick test (:func:`initial_state`) decides whether it stays so.
    """
    n = system.n
    sup = system.support
    offset = np.asarray(system.offset, dtype=float)
    load = system.force.static + system.K @ offset
    if sup is None:
        return StaticStart(_locked_static(system, load), (), (), np.zeros((2, 2)), np.zeros(4), 1, 0.0)
    B = sup.relative_map(n)
    P, limits, n_faces = sup.faces()
    held = list(range(n_faces))
    phi = np.zeros((2, 2))
    q = offset.copy()
    its = 0
    for _ in range(n_faces + 1):              # faces that pass their limit leave the held set, one pass each
        try:
            q, lam, k = _newton(system, load, B, P, held, phi, q, offset, max_iter)
        except OutsideDomainError as exc:
            raise OutsideDomainError(
                f"static equilibrium: the constant load (gravity, static loads, misalignment offset) presses the ring "
                f"past its law's domain ({exc}); a run meets the same load: a larger clearance or a smaller load, or "
                "start from rest anyway (simulate --from-rest, from_rest=True)") from None
        its += k
        over = [f for j, f in enumerate(held) if np.hypot(*lam[2 * j:2 * j + 2]) > limits[f] * (1 + 1e-9)]
        for j, f in enumerate(held):
            phi[f] = -lam[2 * j:2 * j + 2]
        if not over:
            break
        for f in over:                          # slips: its limit against the load it could not hold
            h = np.hypot(*phi[f])
            phi[f] = phi[f] / h * limits[f] * HELD_SHARE if h > 0 else 0.0
        held = [f for f in held if f not in over]
    fc = np.asarray(sup.law.force(B @ q, np.zeros(4)), dtype=float)
    res = cons.null_space_map(system.lock).T @ _residual(system, load, B, P, [], phi, q, fc)   # lock forces internal
    at_limit = tuple(bool(f not in held) for f in range(n_faces))
    return StaticStart(q, tuple([cons.STICK] * 2), at_limit, phi, fc, its, float(np.abs(res).max()))


def _locked_static(system: RotorSystem, load) -> np.ndarray:
    T = cons.null_space_map(system.lock)
    return T @ np.linalg.solve(T.T @ system.K @ T, T.T @ load)


def _residual(system, load, B, P, held, phi, q, fc) -> np.ndarray:
    """``f_static + K Δq_m + Bᵀ(f_c + Σ_slipping Pᵀφ) + coupling − K q`` (N, N m): the force the statics leaves."""
    g = fc.copy()
    for f in range(len(phi)):
        if f not in held:
            g += P[f].T @ phi[f]
    return load + B.T @ g + coupling_force(system, q) - system.K @ q


def _newton(system, load, B, P, held, phi, q, offset, max_iter: int):
    """Newton on the statics with the ``held`` faces fixed at the offset state's relative motion (their
    multipliers returned) and the others carrying ``phi``; ``(q, face multipliers (2 per held face), iterations)``."""
    sup = system.support
    n = system.n
    C = np.vstack([system.lock] + [P[f] @ B for f in held]) if (system.lock.shape[0] or held) else np.zeros((0, n))
    c = np.concatenate([np.zeros(system.lock.shape[0])] + [P[f] @ B @ offset for f in held])
    m, n_l = C.shape[0], system.lock.shape[0]
    step_cap = 0.25 * sup.law.clearance_m
    zero4 = np.zeros(4)
    lam = np.zeros(m)
    scale = max(float(np.abs(load).max()), 1.0)
    k_scale = max(float(np.abs(np.diag(system.K)).max()), 1.0)
    for it in range(1, max_iter + 1):
        u = B @ q
        if sup.law.kernel is not None:
            fc, Ju, _ = sup.law.kernel(u, zero4, sup.law.params)
            fc, Ju = np.asarray(fc, dtype=float), np.asarray(Ju, dtype=float)
        else:
            fc = np.asarray(sup.law.force(u, zero4), dtype=float)
            Ju = np.column_stack([(np.asarray(sup.law.force(u + h, zero4)) - np.asarray(sup.law.force(u - h, zero4)))
                                  / (2e-10) for h in np.eye(4) * 1e-10])
        r = _residual(system, load, B, P, held, phi, q, fc) - C.T @ lam
        # the constraint rows scaled to the stiffness (unit rows beside 1e9 N/m: a singular-looking system)
        A = np.block([[system.K - B.T @ Ju @ B - _coupling_jacobian(system, q), k_scale * C.T],
                      [k_scale * C, np.zeros((m, m))]])
        z = np.linalg.solve(A, np.concatenate([r, k_scale * (c - C @ q)]))
        dq, dlam = z[:n], k_scale * z[n:]
        du = float(np.abs((B @ dq)[:2]).max())
        a = min(1.0, step_cap / du) if du > 0 else 1.0
        q, lam = q + a * dq, lam + a * dlam
        if a == 1.0 and np.abs(r).max() <= 1e-9 * scale and np.all(np.abs(C @ q - c) <= 1e-14 * (1 + np.abs(q).max())):
            return q, lam[n_l:], it
    raise ConvergenceError(f"static equilibrium: Newton did not converge in {max_iter} iterations (largest force "
                           f"residual {np.abs(r).max():.3g} N); start from rest instead (simulate --from-rest)")


def _coupling_jacobian(system: RotorSystem, q) -> np.ndarray:
    """``∂/∂q`` of :func:`rotor.dynamics.system.coupling_force` (n, n): ``−a1 E_cᵀ (|d|² I + 2 d dᵀ) E_c``,
    ``d = E_c q`` (the cubic remainder of the transition shaft's spring; zero without one)."""
    if system.coupling is None or system.coupling[2] == 0.0:
        return np.zeros((system.n, system.n))
    Ec = coupling_map(system)
    d = Ec @ q
    return -float(system.coupling[2]) * Ec.T @ (float(d @ d) * np.eye(2) + 2.0 * np.outer(d, d)) @ Ec


def start_record(system: RotorSystem, start: StaticStart | None) -> dict:
    """The JSON field ``start`` of a run: ``kind`` (``static equilibrium`` or ``rest``: the misalignment offset,
    no load carried) and, from the equilibrium, the loose bearing's static deflection ``bearing_deflection_m``
    ((y, z), m), the ring's contact force ``contact_force_N`` (N), the faces held at their friction limit
    ``faces_at_friction_limit``, ``newton_iterations`` and the largest force residual ``residual_N``."""
    if start is None:
        return {"kind": "rest"}
    out = {"kind": "static equilibrium", "newton_iterations": int(start.iterations),
           "residual_N": float(start.residual_N)}
    if system.support is not None:
        y, z = system.support.bearing_dofs[:2]
        out.update(bearing_deflection_m=[float(start.q_m[y]), float(start.q_m[z])],
                   contact_force_N=float(np.hypot(*start.contact_force[:2])),
                   faces_at_friction_limit=list(start.at_limit))
    return out
