"""The constant load of a scene on its rotor model: gravity on every mass and the ``[[static_loads]]``.

Gravity is a uniform acceleration field ``a = (a_y, a_z)`` (m/s²) on the lateral translations; with
the consistent mass matrix its nodal load is ``M u_a`` (the full matrix, fixed nodes included,
assembled once: ``RotorModel.unit_acceleration_load``), where ``u_a`` holds ``a_y`` on every ``y`` DOF
and ``a_z`` on every ``z`` DOF (the load vector of a uniformly accelerated body: the beam's
distributed weight with its end moments ``±wL²/12``, a disk's or point mass's weight at its node,
the support node's weight on its spring). Its lateral sum is the rotor's total weight
``Σm · a`` exactly. A fixed DOF's share goes to ground.

The load enters every time integration as the static part of the external force
(``rotor.dynamics.build.system_from_model``) and the static deflection of the linear model
(``rotor.linear.static``).
"""
from __future__ import annotations

import numpy as np


def gravity_load(model) -> np.ndarray:
    """Nodal load (N, N·m) of the scene's ``[gravity]`` on ``model`` (``rotor.model.assembly.RotorModel``)."""
    g = model.scene.gravity
    if g is None or (g.acceleration_y_m_s2 == 0.0 and g.acceleration_z_m_s2 == 0.0):
        return np.zeros(model.n_dofs)
    return model.unit_acceleration_load @ np.array([g.acceleration_y_m_s2, g.acceleration_z_m_s2])


def point_loads(model) -> np.ndarray:
    """Nodal load (N, N·m) of the scene's ``[[static_loads]]``; a load on a fixed DOF goes to ground."""
    out = np.zeros(model.n_dofs)
    for ld in model.scene.static_loads:
        for dof, value in (("y", ld.force_y_n), ("z", ld.force_z_n), ("θy", ld.moment_y_n_m), ("θz", ld.moment_z_n_m)):
            key = f"{ld.station}.{dof}"
            if value != 0.0 and key in model._index:
                out[model._index[key]] += value
    return out


def static_load(model) -> np.ndarray:
    """Gravity plus the static loads of the scene, on the model's DOFs (N, N·m)."""
    return gravity_load(model) + point_loads(model)
