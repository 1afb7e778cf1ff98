"""Test helpers for the dynamics tests: small systems built on the suite's own support law."""
from __future__ import annotations

import math

import numpy as np
from rotor.dynamics import constraints as cons
from rotor.dynamics.kernels import support_law_from_params
from rotor.dynamics.system import HarmonicForce, LooseSupport, RotorSystem, SupportLaw


def null_law() -> SupportLaw:
    """The suite's loose-support law with a 10 mm clearance: no radial contact for the
    sub-millimetre motions of the friction tests (same compiled kernel as the rotor runs)."""
    from contact.loose_support import LooseSupportParams

    return support_law_from_params(LooseSupportParams(clearance_m=0.01, width_m=0.03, bearing_E_Pa=2e11,
                                                      bearing_nu=0.3, support_E_Pa=2e11, support_nu=0.3))


def friction_body(m=1.0, k=(2 * math.pi * 10) ** 2, zeta=0.1, P0=1.0, F=0.2, omega=50.0, J=1e-3):
    """4-DOF rigid body (y, z, θy, θz) on springs, grounded through a loose support whose
    two end faces each carry μN = F/2, harmonic force P0 cos(ωt) along y.
    In translation the body is Den Hartog's (1931) oscillator with Coulomb force F."""
    n = 4
    c = 2 * zeta * math.sqrt(k * m)
    kt = k * J / m
    ct = 2 * zeta * math.sqrt(kt * J)
    M = np.diag([m, m, J, J])
    K = np.diag([k, k, kt, kt])
    C = np.diag([c, c, ct, ct])
    G = np.zeros((n, n))
    mu = 0.5
    N = F / (2 * mu)
    sup = LooseSupport((0, 1, 2, 3), None, null_law(), 0.03, mu, N)
    cosm = np.zeros((1, n))
    cosm[0, 0] = P0
    force = HarmonicForce(np.zeros(n), np.array([1.0]), cosm, np.zeros((1, n)), omega)
    return RotorSystem(M, C, G, K, 0.0, force, np.zeros(n), np.zeros((0, n)), sup, ("y", "z", "ty", "tz"))
