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


#: a static deflection beyond this share of the shaft's length is not a small deflection: the linear model's
#: answer is implausible (a load or a gravity typed in the wrong unit, a bearing far too soft)
SHAFT_LENGTH_FRACTION = 0.01


def plausibility(model: RotorModel, st: StaticDeflection) -> dict:
    """The largest lateral deflection ``|(y, z)|`` of any station or support node against two limits: the loose
    support's radial clearance (a rotor deflected further than its ring's gap rests on the ring, which the linear
    statics leaves out) and :data:`SHAFT_LENGTH_FRACTION` of the shaft's length (beyond small deflections).

    Returns the JSON field ``{"plausible", "station", "deflection_m", "limits_m": {name: value},
    "exceeded": [names]}``; ``exceeded`` is empty when the deflection is within both limits."""
    sc = model.scene
    names = [s.name for s in sc.stations] + [s.name for s in sc.supports]
    mags = [float(np.hypot(*st.displacement_m(n))) for n in names]
    k = int(np.argmax(mags)) if mags else 0
    xs = [s.x_m for s in sc.stations]
    limits = {}
    if sc.loose_support is not None:
        limits["clearance"] = float(sc.loose_support.clearance_m)
    if xs and max(xs) > min(xs):
        limits["shaft_length_fraction"] = SHAFT_LENGTH_FRACTION * (max(xs) - min(xs))
    worst = mags[k] if mags else 0.0
    exceeded = [name for name, lim in limits.items() if worst > lim]
    return {"plausible": not exceeded, "station": names[k] if names else None, "deflection_m": worst,
            "limits_m": limits, "exceeded": exceeded}


def plausibility_warning(prog: str, field: dict) -> str | None:
    """One stderr line for an implausible static deflection (None when it is plausible): the station, its
    deflection in mm and each limit it exceeds with its value and what follows from it."""
    if field["plausible"]:
        return None
    said = {"clearance": "the loose support's clearance ({} mm: the ring's contact, left out of these statics with "
                         "the support locked, shapes such a state; simulate gives it)",
            "shaft_length_fraction": f"{100 * SHAFT_LENGTH_FRACTION:g} % of the shaft's length ({{}} mm: not a small "
                                     "deflection, a linear model does not hold; check the static loads, the gravity, "
                                     "the bearing stiffnesses and their units)"}
    beyond = " and ".join(said[n].format(f"{1e3 * field['limits_m'][n]:.4g}") for n in field["exceeded"])
    return (f"{prog}: warning: implausible static deflection: station {field['station']!r} moves "
            f"{1e3 * field['deflection_m']:.4g} mm, beyond {beyond}")
