"""Energy balance of a loose-support run: input, dissipation (damping, friction, impact), storage.

For a trajectory recorded at every step, the work of each force over a step is taken with
the trapezoidal rule, ``ΔW = Δqᵀ (f_n + f_{n+1})/2``. For the average-acceleration Newmark
method (β = ¼, γ = ½) this is the exact discrete counterpart of the energy theorem: with
``Δq = Δt (q̇_n + q̇_{n+1})/2`` the kinetic and strain energies change by exactly
``Δqᵀ`` times the mean of the forces of the two step ends, so the balance below closes
to the Newton tolerance. A gap therefore reveals a force that was used but not booked
(or a step where the equations were not solved), not a quadrature error.

Terms (J, cumulative from the first recorded instant)
-----------------------------------------------------
* ``input``: work of the external loads Q(t) (unbalance, misalignment, static).
* ``damping``: dissipated by C (the gyroscopic ``ωG`` term does no work: G is skew).
* ``friction``: dissipated at the end faces (slip friction and stuck-face constraint forces).
* ``impact``: dissipated by the contact damping factor ``(1 + c_c v_n)`` (force minus its
  zero-velocity part).
* ``stored``: kinetic ``½q̇ᵀMq̇`` + strain ``½(q − Δq_m)ᵀK(q − Δq_m)`` + contact elastic
  (minus the work of the zero-velocity contact force) + cubic coupling ``a1|Δθ|⁴/4``.
* ``residual = Δstored − (input − damping − friction − impact)``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contact.errors import InputError
from rotor.dynamics import constraints as cons
from rotor.dynamics.system import RotorSystem, Trajectory, coupling_map


@dataclass(frozen=True)
class EnergyBalance:
    """Cumulative energy terms (J) at each recorded instant, arrays of shape (N,)."""

    t: np.ndarray
    input: np.ndarray
    damping: np.ndarray
    friction: np.ndarray
    impact: np.ndarray
    kinetic: np.ndarray
    strain: np.ndarray
    contact: np.ndarray
    coupling: np.ndarray

    @property
    def stored(self) -> np.ndarray:
        return self.kinetic + self.strain + self.contact + self.coupling

    @property
    def residual(self) -> np.ndarray:
        return (self.stored - self.stored[0]) - (self.input - self.damping - self.friction - self.impact)

    @property
    def gross_input(self) -> float:
        """Sum of the positive step works of the loads (J): the scale of "input"."""
        d = np.diff(self.input)
        return float(d[d > 0].sum())

    def relative_closure(self) -> float:
        """``max |residual| / gross input`` (–)."""
        gi = self.gross_input
        return float(np.abs(self.residual).max() / gi) if gi > 0 else float(np.abs(self.residual).max())


def energy_balance(system: RotorSystem, tr: Trajectory) -> EnergyBalance:
    """Energy bookkeeping of a trajectory recorded at **every** step (``record_every=1``)."""
    if tr.t.size < 2:
        raise InputError("trajectory: need at least 2 recorded instants")
    dts = np.diff(tr.t)
    if np.ptp(dts) > 1e-9 * dts.mean():
        raise InputError("trajectory: energy balance needs every step recorded (record_every=1)")
    q, v = tr.q, tr.v
    dq = np.diff(q, axis=0)
    Q = np.array([system.force(t) for t in tr.t])
    w_in = np.einsum("ij,ij->i", dq, 0.5 * (Q[1:] + Q[:-1]))
    vbar = 0.5 * (v[1:] + v[:-1])
    w_damp = np.einsum("ij,ij->i", dq, vbar @ system.C.T)
    du = np.diff(tr.u, axis=0)
    fbar = 0.5 * (tr.f_contact[1:] + tr.f_contact[:-1])
    febar = 0.5 * (tr.f_elastic[1:] + tr.f_elastic[:-1])
    w_el = np.einsum("ij,ij->i", du, febar)
    w_imp = np.einsum("ij,ij->i", du, fbar - febar)
    w_fr = np.zeros(len(dq))
    if system.support is not None:
        P = system.support.faces()[0]
        phibar = 0.5 * (tr.face_force[1:] + tr.face_force[:-1])
        for k in range(2):
            w_fr += np.einsum("ij,ij->i", du @ P[k].T, phibar[:, k])
    x = q - system.offset
    kin = 0.5 * np.einsum("ij,ij->i", v, v @ system.M.T)
    strain = 0.5 * np.einsum("ij,ij->i", x, x @ system.K.T)
    coup = np.zeros(len(q))
    if system.coupling is not None:
        d = q @ coupling_map(system).T
        coup = 0.25 * system.coupling[2] * np.einsum("ij,ij->i", d, d) ** 2

    def cum(a):
        return np.concatenate([[0.0], np.cumsum(a)])

    return EnergyBalance(t=tr.t, input=cum(w_in), damping=cum(w_damp), friction=cum(-w_fr), impact=cum(-w_imp),
                         kinetic=kin, strain=strain, contact=-cum(w_el), coupling=coup)
