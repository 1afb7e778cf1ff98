"""Test helpers for the dynamics tests: a stand-in contact law and small systems.

The stand-in law (a piecewise-linear radial spring with clearance, no tilt
moments) is NOT a law of the suite; it only lets the integrators be verified
independently of ``contact.loose_support``.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from rotor import constraints as cons
from rotor.integrate import HarmonicForce, LooseSupport, RotorSystem, SupportLaw


@njit(cache=True)
def _radial_spring_kernel(u, v, p):
    k, d0, cc = p[0], p[1], p[2]
    f = np.zeros(4)
    Ju = np.zeros((4, 4))
    Jv = np.zeros((4, 4))
    r = math.sqrt(u[0] * u[0] + u[1] * u[1])
    if r <= d0:
        return f, Ju, Jv
    ny, nz = u[0] / r, u[1] / r
    pen = r - d0
    vn = ny * v[0] + nz * v[1]
    damp = 1.0 + cc * vn
    P = k * pen
    f[0] = -P * damp * ny
    f[1] = -P * damp * nz
    # d/du of -k pen damp n: pen' = n, n' = (I - n n^T)/r, vn' = v^T (I - n n^T)/r
    nn = ((ny * ny, ny * nz), (nz * ny, nz * nz))
    vv = (v[0], v[1])
    nvec = (ny, nz)
    for i in range(2):
        for j in range(2):
            proj = (1.0 if i == j else 0.0) - nn[i][j]
            dvn = 0.0
            for m in range(2):
                pm = (1.0 if m == j else 0.0) - nn[m][j]
                dvn += vv[m] * pm / r
            Ju[i, j] = -k * (nvec[j] * damp * nvec[i] + pen * cc * dvn * nvec[i] + pen * damp * proj / r)
            Jv[i, j] = -P * cc * nvec[j] * nvec[i]
    return f, Ju, Jv


def radial_spring_law(k_N_m: float, clearance_m: float, c_c_s_m: float = 0.0) -> SupportLaw:
    params = np.array([k_N_m, clearance_m, c_c_s_m])

    def force(u, v):
        return _radial_spring_kernel(np.asarray(u, float), np.asarray(v, float), params)[0]

    return SupportLaw("standin-radial-spring", clearance_m, force, _radial_spring_kernel, params)


def null_law() -> SupportLaw:
    return radial_spring_law(0.0, 1.0, 0.0)


def friction_body(m=1.0, k=(2 * math.pi * 10) ** 2, zeta=0.1, P0=10.0, F=2.0, omega=50.0, J=1e-3):
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
