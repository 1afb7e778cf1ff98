"""Massless DOFs in time (rotor.dynamics.condense): the Jeffcott rotor of verify-jeffcott, a central
disk on a massless shaft in two flexible bearings, integrated by the production scheme against its
closed forms (Jeffcott 1919; any rotordynamics text, e.g. Genta, Dynamics of Rotating Systems, §3)."""
import math

import numpy as np
import pytest

from contact.errors import InputError
from rotor.dynamics.build import system_from_model
from rotor.dynamics.condense import condense, massless_dofs
from rotor.dynamics.production import simulate_production
from rotor.model import elements as el
from rotor.model.assembly import assemble
from rotor.model.scene import load_scene

L, D, E, NU, KB, M_DISK, ME = 0.8, 0.02, 200e9, 0.3, 2.0e6, 10.0, 100e-6   # verify-jeffcott.toml


def _k_closed_form() -> float:
    """1/k = L³/(48 EI) + L/(4 κ G A) + 1/(2 k_b): shaft bending, shear and the two bearings in series."""
    A, I = math.pi * D ** 2 / 4, math.pi * D ** 4 / 64
    kappa = el.cowper_shear_coefficient(D, 0.0, NU)
    G = E / (2 * (1 + NU))
    return 1.0 / (L ** 3 / (48 * E * I) + L / (4 * kappa * G * A) + 1.0 / (2 * KB))


def _jeffcott(speed_rad_s):
    sc = load_scene("verify-jeffcott")
    model = assemble(sc)
    return model, system_from_model(model, sc, speed_rad_s)


def test_jeffcott_has_massless_dofs_and_condenses_to_the_disk():
    model, system = _jeffcott(0.0)
    assert massless_dofs(system).size > 0
    c = condense(system)
    kept = set(c.system.dof_names)
    assert {"disk.y", "disk.z"} <= kept and not any(n.startswith(("A.", "B.")) for n in kept)


def test_jeffcott_free_vibration_at_its_closed_form_critical_speed():
    """At rest, released from a disk deflection: the period is 2π/√(k/m) (18.955 Hz, 1137 rpm)."""
    model, system = _jeffcott(0.0)
    fn = math.sqrt(_k_closed_form() / M_DISK) / (2 * math.pi)
    assert fn == pytest.approx(18.955, rel=1e-3)          # the number in the scene file
    q0 = np.zeros(system.n)
    iy = model.dof_index("disk.y")
    q0[iy] = 1e-4
    dt = 1 / fn / 400
    tr = simulate_production(system, dt, 4000, q0=q0)
    y = tr.q[:, iy]
    up = np.flatnonzero((y[:-1] < 0) & (y[1:] >= 0))
    t_up = tr.t[up] - y[up] * dt / (y[up + 1] - y[up])    # linear interpolation of the crossings
    f_meas = (len(t_up) - 1) / (t_up[-1] - t_up[0])
    assert f_meas == pytest.approx(fn, rel=2e-4)
    # the bearing nodes are recovered statically: each carries half the shaft force, y_A = k y_d / (2 k_b) · …
    ia = model.dof_index("A.y")
    assert np.all(np.abs(tr.q[:, ia]) <= np.abs(tr.q[:, iy]) + 1e-18)
    assert np.isfinite(tr.q).all()


def test_jeffcott_unbalance_response_matches_closed_form():
    """Steady 1X amplitude of the disk: m e Ω² / (k − m Ω²) (undamped, below the critical speed)."""
    from rotor.studies.steady_state import SteadyStateOptions, steady_state

    omega = 600 * math.pi / 30
    model, system = _jeffcott(omega)
    # start on the closed-form orbit (no damping: a transient would never decay)
    x = ME * omega ** 2 / (_k_closed_form() - M_DISK * omega ** 2)
    q0, v0 = np.zeros(system.n), np.zeros(system.n)
    q0[model.dof_index("disk.y")] = x
    v0[model.dof_index("disk.z")] = x * omega
    res = steady_state(system, model, options=SteadyStateOptions(min_revs=4, max_revs=8, spectrum_revs=4),
                       q0=q0, v0=v0)
    amp = res.harmonics("q", orders=(1,))[0]
    assert amp[res.channel("d.y")] == pytest.approx(x, rel=2e-3)
    assert amp[res.channel("d.z")] == pytest.approx(x, rel=2e-3)
    assert res.channels[:2] == ("d.y", "d.z")


def test_massless_node_with_damping_is_refused_naming_the_station():
    model, system = _jeffcott(0.0)
    C = system.C.copy()
    ia = model.dof_index("A.y")
    C[ia, ia] = 10.0
    import dataclasses
    with pytest.raises(InputError, match=r"station 'A': its y DOF has no mass or inertia and carries damping"):
        simulate_production(dataclasses.replace(system, C=C), 1e-4, 10)


def test_free_massless_node_is_refused_naming_the_station():
    model, system = _jeffcott(0.0)
    K = system.K.copy()
    ia = model.dof_index("A.y")
    K[ia, :] = 0.0
    K[:, ia] = 0.0
    import dataclasses
    with pytest.raises(InputError, match=r"station 'A': its y DOF has neither mass nor stiffness"):
        simulate_production(dataclasses.replace(system, K=K), 1e-4, 10)
