"""Linear time response of a rotor with the loose support locked (bearing and support move together).

The system of :func:`rotor.dynamics.build.system_from_model` without the contact: the loose-support
pair is tied by four rows ``q_bearing − q_support = 0`` (two with the tilt ignored, Dai et al. 2025
§5.2), added to the 3a/3b lock rows, and the end faces and their preload are left out. What remains,
``M q̈ + (C − ΩG) q̇ + K (q − Δq_m) = Q(t)`` on ``L q = 0`` with the 1X unbalance and 2X
misalignment loads, is solved two ways:

``harmonic``
    the exact steady state, by superposition of the static part and each harmonic:
    ``K_r q_s = T ᵀ(s + K Δq_m)`` and ``(K_r − (kΩ)² M_r + i kΩ D_r) X_k = Tᵀ(c_k − i s_k)`` on the
    constraint null space ``q = T p`` (the same equations as :func:`rotor.linear.unbalance.forced_response`
    and :func:`rotor.dynamics.initial.linear_initial_state`); ``q(t) = q_s + Σ Re(X_k e^{ikΩt})``.
``newmark``
    the start-up from rest at the static deflection (``q = q_s``, ``q̇ = 0``), integrated by the
    production scheme (:func:`rotor.dynamics.production.simulate_production`, average acceleration,
    massless DOFs condensed): the transient decays with the modal damping and the run tends to the
    ``harmonic`` answer (an undamped mode never settles).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from contact.errors import InputError
from rotor.dynamics import constraints as cons
from rotor.dynamics.system import RotorSystem

METHODS = ("harmonic", "newmark")


@dataclass(frozen=True)
class LinearResponse:
    """Displacements ``q[i, j]`` (m, rad) of DOF ``dof_names[j]`` at time ``t_s[i]`` (s), and how they were got."""

    t_s: np.ndarray
    q: np.ndarray
    dof_names: tuple[str, ...]
    method: str
    dt_s: float
    speed_rad_s: float


def locked_system(system: RotorSystem) -> RotorSystem:
    """``system`` with the loose support replaced by lock rows (no contact, no end faces, no preload)."""
    sup = system.support
    if sup is None:
        return system
    rows = sup.relative_map(system.n)[:2 if sup.tilt_ignored else 4]
    return dataclasses.replace(system, lock=np.vstack([system.lock, rows]), support=None)


def periodic_response(system: RotorSystem, t_s) -> tuple[np.ndarray, np.ndarray]:
    """``(q, v)`` at the times ``t_s`` (rows) of the steady state of the linear ``system`` (support locked).

    Raises
    ------
    InputError : the stiffness on the constraint null space is singular (a free rotor), or a
        harmonic meets an undamped resonance.
    """
    lin = locked_system(system)
    t = np.atleast_1d(np.asarray(t_s, dtype=float))
    T = cons.null_space_map(lin.lock)
    Mr, Dr, Kr = T.T @ lin.M @ T, T.T @ lin.D @ T, T.T @ lin.K @ T
    f = lin.force
    try:
        qs = T @ np.linalg.solve(Kr, T.T @ (f.static + lin.K @ lin.offset))
        q = np.tile(qs, (len(t), 1))
        v = np.zeros_like(q)
        for k, c, s in zip(f.orders, f.cos, f.sin):
            wk = k * f.omega_rad_s
            X = T @ np.linalg.solve(Kr - wk * wk * Mr + 1j * wk * Dr, T.T @ (c - 1j * s))
            e = np.exp(1j * wk * t)
            q += np.outer(e, X).real
            v += np.outer(1j * wk * e, X).real
    except np.linalg.LinAlgError:
        raise InputError(f"linear response singular at {f.omega_rad_s * 30 / math.pi:.6g} rpm: a free rotor or an "
                         "undamped resonance at a harmonic of the speed; add damping or move the speed") from None
    return q, v


def linear_response(system: RotorSystem, revolutions: float, *, steps_per_rev: int = 256, record_per_rev: int = 64,
                    method: str = "harmonic") -> LinearResponse:
    """Time response over ``revolutions`` of the spin, the loose support locked (module docstring).

    Parameters
    ----------
    system : a system of :func:`rotor.dynamics.build.system_from_model` at spin speed Ω > 0.
    revolutions : duration in revolutions of the spin (–), > 0.
    steps_per_rev : Newmark steps per revolution (``newmark`` only).
    record_per_rev : samples per revolution; must divide ``steps_per_rev``.
    method : ``"harmonic"`` (steady state) or ``"newmark"`` (start-up from rest, in time).
    """
    if method not in METHODS:
        raise InputError(f"method = {method!r}: must be one of {', '.join(METHODS)}")
    W = system.omega_rad_s
    if not (W > 0 and math.isfinite(W)):
        raise InputError(f"speed = {W * 30 / math.pi:g} rpm: must be > 0 for a time response")
    if not (revolutions > 0 and math.isfinite(revolutions)):
        raise InputError(f"revolutions = {revolutions!r} rev: must be > 0")
    if steps_per_rev < 1 or record_per_rev < 1 or steps_per_rev % record_per_rev:
        raise InputError(f"record_per_rev = {record_per_rev}: must be >= 1 and divide steps_per_rev = {steps_per_rev}")
    period = 2 * math.pi / W
    dt = period / steps_per_rev
    n_steps = int(round(revolutions * steps_per_rev))
    every = steps_per_rev // record_per_rev
    if method == "harmonic":
        t = np.arange(0, n_steps + 1, every) * dt
        q, _ = periodic_response(system, t)
        return LinearResponse(t, q, system.dof_names, method, dt, W)
    from rotor.dynamics.production import simulate_production

    lin = locked_system(system)
    rest = dataclasses.replace(lin.force, orders=lin.force.orders[:0], cos=lin.force.cos[:0], sin=lin.force.sin[:0])
    q0, _ = periodic_response(dataclasses.replace(lin, force=rest), [0.0])   # static deflection, at rest
    tr = simulate_production(lin, dt, n_steps, q0=q0[0], v0=np.zeros(lin.n), record_every=every)
    return LinearResponse(tr.t, tr.q, system.dof_names, method, dt, W)
