"""Compiled (numba) Coulomb friction of the ring's end faces; a part of ``contact._kernel`` (moved here unchanged
when that module reached its size limit). Parameter slots as documented in ``contact._kernel``: 1 ring width,
10 μN of one face, 12 the smoothing velocity ε (m/s).
"""
from __future__ import annotations

import math

import numba

from contact.compiled_cache import compiled_with

compiled_with(__file__, [])  # cached in the user's cache folder (contact.compiled_cache)


@numba.njit(cache=True, inline="always")
def _face_friction(sgn, vy, vz, wy, wz, p, jac):
    """Coulomb friction ``(fy, fz, my, mz)`` of end face ``sgn`` (+1 right, −1 left); Jacobian into ``jac``."""
    muN = p[10]
    if muN == 0.0:
        return 0.0, 0.0, 0.0, 0.0
    a = sgn * 0.5 * p[1]
    uy = vy + a * wz
    uz = vz - a * wy
    u2 = uy * uy + uz * uz
    eps = p[12]
    S2 = u2 + eps * eps
    if S2 == 0.0:
        return 0.0, 0.0, 0.0, 0.0   # zero relative velocity: stick, friction set by constraints
    S = math.sqrt(S2)
    c = muN / S
    fy = -c * uy
    fz = -c * uz
    h = 0.5 * p[1]
    if jac is None:
        return fy, fz, sgn * h * (-fz), sgn * h * fy
    S3 = S2 * S
    # d(u/S)/du = (I S² − u uᵀ)/S³
    gyy = (S2 - uy * uy) / S3
    gyz = -uy * uz / S3
    gzz = (S2 - uz * uz) / S3
    duy = (1.0, 0.0, 0.0, a)
    duz = (0.0, 1.0, -a, 0.0)
    for j in range(4):
        dfy = -muN * (gyy * duy[j] + gyz * duz[j])
        dfz = -muN * (gyz * duy[j] + gzz * duz[j])
        jac[0, 4 + j] += dfy
        jac[1, 4 + j] += dfz
        jac[2, 4 + j] += sgn * h * (-dfz)
        jac[3, 4 + j] += sgn * h * dfy
    return fy, fz, sgn * h * (-fz), sgn * h * fy
