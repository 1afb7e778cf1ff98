"""Gravity through a clearance ring: the time integration settles where the ring's contact carries the
rotor's weight, by the statics of a beam on a spring and a ring.

A Jeffcott rotor (massless shaft, 10 kg disk at midspan) on a spring bearing at A and a loose support at
B (clearance ring, conformal law), under gravity with no unbalance: at rest the contact force ``F_y`` and
moment ``M_z`` on the ring satisfy the equilibrium of the rotor (closed form, rigid-body statics):
moments about A ``F_y L + M_z = m_d g L/2 + m_r g L`` and forces ``F_y + F_A = (m_d + m_r + m_hub) g``
with ``F_A = −k_A y_A`` the bearing force. The ring tilts with the shaft's slope, so ``M_z ≠ 0`` and
``F_y`` alone is not the textbook half weight: the check needs both equations.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from rotor.dynamics.build import system_from_model
from rotor.dynamics.initial import linear_initial_state
from rotor.dynamics.production import simulate_production
from rotor.model.assembly import assemble
from rotor.model.scene import loads_scene

TXT = '''schema = "ringcontact.rotor-scene/1"
name = "jeffcott-loose-gravity"
title = "t"
[[materials]]
name = "massless"
density_kg_m3 = 0
youngs_modulus_gpa = 200
poisson_ratio = 0.3
[[stations]]
name = "A"
x_mm = 0
[[stations]]
name = "disk"
x_mm = 400
[[stations]]
name = "B"
x_mm = 800
[[shafts]]
from = "A"
to = "disk"
outer_diameter_mm = 20
material = "massless"
[[shafts]]
from = "disk"
to = "B"
outer_diameter_mm = 20
material = "massless"
[[disks]]
name = "d"
station = "disk"
mass_kg = 10
polar_inertia_kg_m2 = 0
diametral_inertia_kg_m2 = 0.02
[[point_masses]]
name = "ring"
station = "B"
mass_kg = 0.5
diametral_inertia_kg_m2 = 1e-4
[[point_masses]]
name = "hub"
station = "A"
mass_kg = 0.5
diametral_inertia_kg_m2 = 1e-4
[[bearings]]
name = "bA"
station = "A"
stiffness_n_per_m = 2.0e6
damping_n_s_per_m = 200
[[bearings]]
name = "damper"
station = "disk"
stiffness_n_per_m = 0
damping_n_s_per_m = 2000
angular_damping_n_m_s_per_rad = 5
[[supports]]
name = "s"
station = "B"
mass_kg = 5
inertia_kg_m2 = 0.01
stiffness_n_per_m = 1e7
damping_n_s_per_m = 1e3
angular_stiffness_n_m_per_rad = 1e5
angular_damping_n_m_s_per_rad = 10
[loose_support]
bearing_station = "B"
support = "s"
clearance_mm = 0.02
ring_width_mm = 20
bearing_modulus_gpa = 200
bearing_poisson_ratio = 0.3
support_modulus_gpa = 200
support_poisson_ratio = 0.3
collision_factor_s_per_m = 100
[gravity]
acceleration_y_m_per_s2 = -9.81
'''


def test_ring_carries_the_weight_by_statics():
    scene = loads_scene(TXT)
    model = assemble(scene)
    w = 3000 * math.pi / 30
    system = system_from_model(model, scene, w)
    q0, v0 = linear_initial_state(system)
    spr, g, L = 1024, 9.81, 0.8
    tr = simulate_production(system, 2 * math.pi / w / spr, 24 * spr, q0, v0, record_every=spr)
    fy, fz, my, mz = tr.f_contact[-1]
    # after 24 revolutions the settling transient leaves 5e-6 and 8.5e-5 of these (measured): 2e-4 bounds both
    assert fy * L + mz == pytest.approx(10 * g * L / 2 + 0.5 * g * L, rel=2e-4)
    y_a = tr.q[-1, model.dof_index("A.y")]
    assert fy - 2.0e6 * y_a == pytest.approx((10 + 0.5 + 0.5) * g, rel=2e-4)
    assert abs(mz) > 0.01 * abs(fy) * L          # the tilt moment matters (the check above needs it)
    assert fz == pytest.approx(0.0, abs=1e-9) and my == pytest.approx(0.0, abs=1e-9)
    # without gravity the ring floats free: no contact at all
    weightless = loads_scene(TXT.replace("acceleration_y_m_per_s2 = -9.81", ""))
    free = system_from_model(assemble(weightless), weightless, w)
    q1, v1 = linear_initial_state(free)
    tr0 = simulate_production(free, 2 * math.pi / w / spr, 2 * spr, q1, v1, record_every=spr)
    assert np.all(tr0.f_contact == 0.0)


def test_step_limit_of_a_rotor_with_massless_dofs():
    """The contact step limit 2/ω_c of a rotor with massless DOFs (station A here: no hub mass, no damping)
    is the one of its statically condensed system, which the integrators run (rotor.dynamics.condense);
    it used to stop on a singular mass matrix."""
    from rotor.dynamics.condense import condense
    from rotor.dynamics.system import largest_stable_step
    text = TXT.replace('[[point_masses]]\nname = "hub"\nstation = "A"\nmass_kg = 0.5\ndiametral_inertia_kg_m2 = 1e-4\n', "")
    text = text.replace("damping_n_s_per_m = 200\n", "")
    assert text.count("[[point_masses]]") == 1
    scene = loads_scene(text)
    system = system_from_model(assemble(scene), scene, 300.0)
    condensed = condense(system)
    assert condensed is not None and condensed.system.n < system.n
    dt, wc = largest_stable_step(system)
    assert math.isfinite(dt) and wc == pytest.approx(largest_stable_step(condensed.system)[1], rel=1e-9)
