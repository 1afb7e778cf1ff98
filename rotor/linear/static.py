"""Static deflection of the linear rotor model under its constant load (gravity and static loads).

Solves ``K q = f`` on the constraint null space (couplings; the loose support locked, as the linear
analyses take it: ``rotor.model.assembly.constraint_basis``), with ``f`` from
:mod:`rotor.model.static_load`. The bearing and support reactions follow from the spring forces
``K_b q`` at their nodes; they balance the load (Σ reactions = Σ loads exactly for a rotor held by
springs only). With a clearance ring, the time integration (``rotor.dynamics``) takes the same load
as the static part of its external force, so the ring settles where contact carries its share.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contact.errors import InputError
from rotor.model.assembly import RotorModel, constraint_basis
from rotor.model.static_load import static_load


@dataclass(frozen=True)
class StaticDeflection:
    """Static state of the linear model.

    ``q_m``: displacements (m, rad) on ``dof_names``; ``load_N``: the load vector (N, N·m);
    ``reactions_N``: ``{element name: (F_y, F_z)}`` forces (N) each bearing and support spring
    carries (the force the rotor puts on it, i.e. ``+K_b q``).
    """
    q_m: np.ndarray
    dof_names: tuple[str, ...]
    load_N: np.ndarray
    reactions_N: dict[str, tuple[float, float]]

    def displacement_m(self, node: str) -> tuple[float, float]:
        """``(y, z)`` of ``node`` (m); 0 for a fixed DOF."""
        idx = {n: i for i, n in enumerate(self.dof_names)}
        return tuple(float(self.q_m[idx[f"{node}.{d}"]]) if f"{node}.{d}" in idx else 0.0 for d in ("y", "z"))


def static_deflection(model: RotorModel, *, lock_loose_support: bool = True) -> StaticDeflection:
    """Deflection of ``model`` under gravity and the scene's static loads (see the module docstring); a
    bearing with a speed table takes its values at rest."""
    f = static_load(model)
    T = constraint_basis(model, lock_loose_support=lock_loose_support)
    Kr = T.T @ model.K_total @ T
    try:
        x = np.linalg.solve(Kr, T.T @ f)
    except np.linalg.LinAlgError:
        raise InputError(f"scene {model.scene.name!r}: the rotor is not held against a static load (a rigid-body "
                         f"mode: add a bearing or a boundary)") from None
    q = T @ x
    if not np.all(np.isfinite(q)):
        raise InputError(f"scene {model.scene.name!r}: static deflection not finite (the rotor is not held)")
    sc = model.scene
    reactions = {}
    for name, station, K2 in ([(b.name, b.station, b.lateral_at(0.0)[0]) for b in sc.bearings]
                              + [(s.name, s.name, s.stiffness_n_m * np.eye(2)) for s in sc.supports]):
        yz = np.array([q[model._index[f"{station}.{d}"]] if f"{station}.{d}" in model._index else 0.0 for d in ("y", "z")])
        fy, fz = K2 @ yz
        reactions[name] = (float(fy), float(fz))
    return StaticDeflection(q_m=q, dof_names=tuple(model.dof_names), load_N=f, reactions_N=reactions)
