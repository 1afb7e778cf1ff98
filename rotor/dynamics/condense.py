"""Static condensation of the DOFs without mass or inertia (a massless shaft's bearing nodes, the
rotations of a disk without inertia), so that the time integrators see a positive definite mass matrix.

A DOF ``d`` whose row and column of ``M`` are zero obeys the static equation
``K_dd q_d + K_dk q_k = f_d(t) + (K Δq_m)_d`` at every instant if it also has no damping, no
gyroscopic coupling, no lock row and no loose-support or coupling force. Eliminating it (Guyan 1965,
exact under those conditions) leaves ``M_kk q̈_k + D_kk q̇_k + K̄ q_k = f̄(t)`` with
``K̄ = K_kk − K_kd K_dd⁻¹ K_dk`` and ``f̄ = f_k − K_kd K_dd⁻¹ f_d`` (static and harmonic parts alike);
the condensed DOFs are recovered afterwards from the same static equation, with their velocities
and accelerations by differentiating it. A massless DOF that breaks a condition, or one without
stiffness either (a free body), is refused in one line naming its station and what is missing.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from contact.errors import InputError
from rotor.dynamics.system import HarmonicForce, RotorSystem, Trajectory


@dataclass(frozen=True)
class Condensed:
    """A system on its massive DOFs ``keep`` and the map back to all DOFs (see the module docstring)."""

    system: RotorSystem
    full: RotorSystem
    keep: np.ndarray
    drop: np.ndarray
    Kdd_inv: np.ndarray


def massless_dofs(system: RotorSystem) -> np.ndarray:
    """Indices of the DOFs whose row and column of ``M`` are exactly zero."""
    M = system.M
    return np.flatnonzero(~(M.any(axis=0) | M.any(axis=1)))


def _refuse(system: RotorSystem, i: int, what: str):
    node, _, dof = system.dof_names[i].rpartition(".")
    raise InputError(f"station {node!r}: its {dof} DOF has no mass or inertia and {what}; give it a mass or "
                     "inertia (point mass, disk inertia, shaft density)")


def condense(system: RotorSystem) -> Condensed | None:
    """The condensed system, or None when every DOF has mass; InputError when it cannot be done."""
    drop = massless_dofs(system)
    if drop.size == 0:
        return None
    keep = np.setdiff1d(np.arange(system.n), drop)
    sup = system.support
    touched = set()
    if sup is not None:
        touched |= set(sup.bearing_dofs) | set(sup.support_dofs or ())
    if system.coupling is not None:
        touched |= set(system.coupling[0]) | set(system.coupling[1])
    for i in drop:
        if i in touched:
            _refuse(system, i, "carries the loose support or the coupling")
        if system.C[i].any() or system.C[:, i].any() or system.G[i].any() or system.G[:, i].any():
            _refuse(system, i, "carries damping or a gyroscopic moment")
        if system.lock[:, i].any():
            _refuse(system, i, "is in a lock (equal displacement) row")
    K = system.K
    Kdd = K[np.ix_(drop, drop)]
    s = np.linalg.svd(Kdd, compute_uv=False) if drop.size else np.zeros(0)
    if s.size and s.min() <= 1e-12 * max(s.max(), 1.0):
        _, _, vt = np.linalg.svd(Kdd)
        i = int(drop[np.argmax(np.abs(vt[-1]))])
        node, _, dof = system.dof_names[i].rpartition(".")
        raise InputError(f"station {node!r}: its {dof} DOF has neither mass nor stiffness (a free body); add a "
                         "bearing, a shaft to it or a boundary condition")
    Kdd_inv = np.linalg.inv(Kdd)
    T = -Kdd_inv @ K[np.ix_(drop, keep)]                  # q_d = T q_k + Kdd⁻¹ f_d(t)
    Kkd = K[np.ix_(keep, drop)]

    def cond(f):                                          # f̄ = f_k − K_kd K_dd⁻¹ f_d (last axis: DOFs)
        return f[..., keep] - (f[..., drop] @ Kdd_inv.T) @ Kkd.T

    Kbar = K[np.ix_(keep, keep)] + Kkd @ T
    f = system.force
    off = system.offset
    static = cond(f.static + K @ off) - Kbar @ off[keep]
    force = HarmonicForce(static, f.orders, cond(f.cos), cond(f.sin), f.omega_rad_s)
    pos = {int(j): k for k, j in enumerate(keep)}
    if sup is not None:
        sup = dataclasses.replace(sup, bearing_dofs=tuple(pos[j] for j in sup.bearing_dofs),
                                  support_dofs=None if sup.support_dofs is None else
                                  tuple(pos[j] for j in sup.support_dofs))
    coupling = system.coupling
    if coupling is not None:
        coupling = (tuple(pos[j] for j in coupling[0]), tuple(pos[j] for j in coupling[1]), coupling[2])
    sub = np.ix_(keep, keep)
    reduced = RotorSystem(system.M[sub], system.C[sub], system.G[sub], Kbar, system.omega_rad_s, force, off[keep],
                          system.lock[:, keep], sup, tuple(system.dof_names[j] for j in keep), coupling)
    return Condensed(reduced, system, keep, drop, Kdd_inv)


def _force_terms(f: HarmonicForce, t: np.ndarray, derivative: int) -> np.ndarray:
    """``d^k Q / dt^k`` at the times ``t`` (rows), k = ``derivative`` ∈ {0, 1, 2}."""
    w = f.orders * f.omega_rad_s
    ph = np.outer(t, w)
    c, s = np.cos(ph), np.sin(ph)
    if derivative == 0:
        return f.static + c @ f.cos + s @ f.sin
    if derivative == 1:
        return (-s * w) @ f.cos + (c * w) @ f.sin
    return (-c * w ** 2) @ f.cos + (-s * w ** 2) @ f.sin


def expand(c: Condensed, tr: Trajectory) -> Trajectory:
    """``tr`` of the condensed system with the condensed DOFs recovered (all DOFs, ``c.full`` order)."""
    full = c.full
    K = full.K
    Kdk = K[np.ix_(c.drop, c.keep)]
    Koff = (K @ full.offset)[c.drop]
    out = {}
    for name, x, k in (("q", tr.q, 0), ("v", tr.v, 1), ("a", tr.a, 2)):
        rhs = _force_terms(full.force, tr.t, k)[:, c.drop] + (Koff if k == 0 else 0.0) - x @ Kdk.T
        y = np.zeros((len(tr.t), full.n))
        y[:, c.keep] = x
        y[:, c.drop] = rhs @ c.Kdd_inv.T
        out[name] = y
    return dataclasses.replace(tr, **out)
