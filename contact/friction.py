"""End-face Coulomb friction of the preloaded bearing ring, its moments, and the stick test.

Dai et al. (2025) Eqs. 20–24 (sliding friction at the two end faces, ideal dry friction of
Den Hartog 1931) and Eqs. 50–58 (stick constraints and the face force demand), with the
signs restored in docs/reference/contact-laws.md §9. Conventions as in :mod:`contact.loose_support`:
relative bearing − support quantities (SI), face 1 = right face at ``x = +l0/2``, face 2 =
left face at ``x = −l0/2``; a force F at x gives ``My = −x Fz``, ``Mz = x Fy``; outputs act
on the bearing. Each face carries the full nut preload N, so it slides at ``μN`` (Q12).
"""
from __future__ import annotations

import numpy as np

from contact import laws
from contact.units import check_finite, check_positive


def face_velocities(vy_m_s, vz_m_s, omega_y_rad_s, omega_z_rad_s, width_m: float):
    """Relative sliding velocities of the right (1) and left (2) end faces (Dai et al. 2025 Eq. 21).

    ``v_1,2 = (vy ± ωz l0/2, vz ∓ ωy l0/2)`` (m/s). Returns ``(v1y, v1z, v2y, v2z)``.
    """
    h = 0.5 * width_m
    return (vy_m_s + h * omega_z_rad_s, vz_m_s - h * omega_y_rad_s,
            vy_m_s - h * omega_z_rad_s, vz_m_s + h * omega_y_rad_s)


def _unit(vy, vz, smoothing_m_s):
    s = np.sqrt(vy * vy + vz * vz + smoothing_m_s ** 2)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(s > 0, vy / np.where(s > 0, s, 1.0), 0.0), np.where(s > 0, vz / np.where(s > 0, s, 1.0), 0.0)


def end_face_friction(vy_m_s, vz_m_s, omega_y_rad_s=0.0, omega_z_rad_s=0.0, *, width_m: float, mu: float,
                      preload_N: float, smoothing_m_s: float = 0.0):
    """Total sliding friction force and moment of both end faces on the bearing (Dai et al. 2025 Eq. 24).

    ``f_k = −μN v_k/|v_k|`` (zero where ``v_k = 0``: stick is decided by :func:`stick_test`),
    ``M_1 = (l0/2) f_1 e^{+iπ/2}``, ``M_2 = (l0/2) f_2 e^{−iπ/2}``.

    Parameters
    ----------
    vy_m_s, vz_m_s, omega_y_rad_s, omega_z_rad_s : array_like
        Relative velocity (m/s) and angular velocity (rad/s), bearing − support.
    width_m : float
        Ring width l0 (m).
    mu : float
        Friction coefficient (–).
    preload_N : float
        Nut preload N on each face (N).
    smoothing_m_s : float
        ε in ``v/sqrt(|v|² + ε²)``; 0 = ideal Coulomb.

    Returns
    -------
    (Fy_N, Fz_N, My_Nm, Mz_Nm) : tuple of ndarray
    """
    laws.check_width(width_m)
    check_positive("mu", mu, "(dimensionless)", allow_zero=True, upper=10.0)
    check_positive("preload_N", preload_N, "N", allow_zero=True)
    check_positive("smoothing_m_s", smoothing_m_s, "m/s", allow_zero=True)
    for name, unit, v in (("vy_m_s", "m/s", vy_m_s), ("vz_m_s", "m/s", vz_m_s),
                          ("omega_y_rad_s", "rad/s", omega_y_rad_s), ("omega_z_rad_s", "rad/s", omega_z_rad_s)):
        check_finite(name, v, unit)
    v1y, v1z, v2y, v2z = np.broadcast_arrays(*[np.asarray(v, dtype=float) for v in
                                               face_velocities(vy_m_s, vz_m_s, omega_y_rad_s, omega_z_rad_s, width_m)])
    muN = mu * preload_N
    e1y, e1z = _unit(v1y, v1z, smoothing_m_s)
    e2y, e2z = _unit(v2y, v2z, smoothing_m_s)
    f1y, f1z, f2y, f2z = -muN * e1y, -muN * e1z, -muN * e2y, -muN * e2z
    h = 0.5 * width_m
    My = -h * f1z + h * f2z
    Mz = h * f1y - h * f2y
    return f1y + f2y, f1z + f2z, My, Mz


def face_force_demand(Fy_N, Fz_N, My_Nm, Mz_Nm, *, width_m: float):
    """Split a total force and moment between the two end faces (Dai et al. 2025 Eqs. 53–56, signs of §9).

    Solves ``f_l + f_r = F`` and ``(l0/2)(f_r − f_l) e^{iπ/2} = M`` for the face forces:
    ``f_l = (Fy/2 − Mz/l0, Fz/2 + My/l0)``, ``f_r = (Fy/2 + Mz/l0, Fz/2 − My/l0)``.

    Returns ``(left_y_N, left_z_N, right_y_N, right_z_N)``.
    """
    laws.check_width(width_m)
    Fy, Fz, My, Mz = (np.asarray(a, dtype=float) for a in (Fy_N, Fz_N, My_Nm, Mz_Nm))
    return Fy / 2 - Mz / width_m, Fz / 2 + My / width_m, Fy / 2 + Mz / width_m, Fz / 2 - My / width_m


def stick_test(Fy_N, Fz_N, My_Nm, Mz_Nm, *, width_m: float, mu: float, preload_N: float):
    """Which end faces can stick: the face force demand below the static limit μN (Dai et al. 2025 Eqs. 57–58).

    ``H(μN − |f_face|)`` with H(0) = 0, so a demand exactly at μN slides.

    Returns
    -------
    (left_sticks, right_sticks) : tuple of bool ndarray
    """
    check_positive("mu", mu, "(dimensionless)", allow_zero=True, upper=10.0)
    check_positive("preload_N", preload_N, "N", allow_zero=True)
    ly, lz, ry, rz = face_force_demand(Fy_N, Fz_N, My_Nm, Mz_Nm, width_m=width_m)
    limit = mu * preload_N
    return np.hypot(ly, lz) < limit, np.hypot(ry, rz) < limit
