"""Starting states: consistent accelerations and multipliers at a given state, and the linear start.

:func:`initial_acceleration` solves the acceleration-level constraints (lock rows and stuck faces)
at fixed ``(q, q̇)``: both schemes start from it (:func:`initial_state`, with the stick test
applied to the requested modes), and it is the stick-onset restart of the reference scheme
(:mod:`rotor.dynamics.constraints`, "Stick onset"). :func:`linear_initial_state` is the periodic
solution of the linear system, a start for steady-state runs.
"""
from __future__ import annotations

import numpy as np

from rotor.dynamics import constraints as cons
from rotor.dynamics.system import NewmarkOptions, RotorSystem, coupling_force, support_forces


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


def linear_initial_state(system: RotorSystem, t0: float = 0.0, lock_support: bool = True, static: bool = True):
    """``(q0, v0)``: the exact periodic solution at ``t0`` of the *linear* system with the loose
    support locked (bearing and support moving together, both end faces stuck) or free. With the
    tilt ignored (§5.2) only the lateral relative motion is locked: no moment passes.

    A good start for a steady-state run: the 1X/2X response of the rotor is already there,
    so only the (much smaller) nonlinear correction has to decay. Static part
    ``K (q − Δq_m) = static``, harmonics ``(K − (kΩ)² M + i kΩ D) X_k = c_k − i s_k``. ``static`` False: the
    harmonics alone (the forced response about a static state found otherwise,
    :func:`rotor.dynamics.static_start.forced_start`).
    """
    n = system.n
    rows = [system.lock]
    if lock_support and system.support is not None:
        rows.append(system.support.relative_map(n)[:2 if system.support.tilt_ignored else 4])
    T = cons.null_space_map(np.vstack(rows))
    Mr, Dr, Kr = T.T @ system.M @ T, T.T @ system.D @ T, T.T @ system.K @ T
    f = system.force
    q = T @ np.linalg.solve(Kr, T.T @ (f.static + system.K @ system.offset)) if static else np.zeros(n)
    v = np.zeros(n)
    for k, c, s in zip(f.orders, f.cos, f.sin):
        wk = k * f.omega_rad_s
        X = T @ np.linalg.solve(Kr - wk * wk * Mr + 1j * wk * Dr, T.T @ (c - 1j * s))
        e = np.exp(1j * wk * t0)
        q += (X * e).real
        v += (1j * wk * X * e).real
    return q, v
