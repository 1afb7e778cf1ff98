"""End-face friction of contact.friction (Dai et al. 2025 Eqs. 20-25, 53-58)."""
from __future__ import annotations

import numpy as np
import pytest

from contact import friction
from contact.errors import InputError

L0, MU, N = 30e-3, 0.3, 5000.0   # Dai et al. (2025) Table 4
KW = dict(width_m=L0, mu=MU, preload_N=N)


def test_translation_gives_2muN_and_no_moment():
    """Dai et al. (2025) after Eq. 23: v1 = v2 = v -> f = -2 mu N v/|v|, M_tau = 0."""
    Fy, Fz, My, Mz = friction.end_face_friction(3e-3, -4e-3, **KW)
    assert (Fy, Fz) == pytest.approx((-2 * MU * N * 0.6, 2 * MU * N * 0.8), rel=1e-14)
    assert My == 0 and Mz == 0


def test_pure_rotation_gives_opposing_couple():
    """Rotation omega_z only: faces slide in opposite y directions, net force 0,
    Mz = -2 (l0/2) mu N (each face mu N at arm l0/2), opposing omega_z."""
    Fy, Fz, My, Mz = friction.end_face_friction(0.0, 0.0, 0.0, 2.0, **KW)
    assert Fy == pytest.approx(0, abs=1e-9) and Fz == pytest.approx(0, abs=1e-9)
    assert Mz == pytest.approx(-MU * N * L0, rel=1e-14) and My == pytest.approx(0, abs=1e-12)
    Fy, Fz, My, Mz = friction.end_face_friction(0.0, 0.0, 2.0, 0.0, **KW)
    assert My == pytest.approx(-MU * N * L0, rel=1e-14)


def test_friction_always_dissipates():
    rng = np.random.default_rng(0)
    vy, vz, wy, wz = rng.normal(0, 1e-2, (4, 1000))
    Fy, Fz, My, Mz = friction.end_face_friction(vy, vz, wy, wz, **KW)
    power = Fy * vy + Fz * vz + My * wy + Mz * wz
    assert np.all(power <= 0) and np.all(power < 0)


def test_zero_face_velocity_gives_no_sliding_friction():
    Fy, Fz, My, Mz = friction.end_face_friction(0.0, 0.0, 0.0, 0.0, **KW)
    assert (Fy, Fz, My, Mz) == (0.0, 0.0, 0.0, 0.0)


def test_face_demand_split_recombines_to_force_and_moment():
    """Statics of docs/reference/contact-laws.md section 9: f_l + f_r = F and face forces at x = -+l0/2 give M."""
    rng = np.random.default_rng(1)
    F = rng.normal(0, 1e4, (4, 50))
    ly, lz, ry, rz = friction.face_force_demand(*F, width_m=L0)
    h = L0 / 2
    assert ly + ry == pytest.approx(F[0]) and lz + rz == pytest.approx(F[1])
    assert -h * rz + h * lz == pytest.approx(F[2])       # My = -x Fz summed over the faces
    assert h * ry - h * ly == pytest.approx(F[3])        # Mz = x Fy


def test_stick_test_threshold():
    """A face sticks while its demand is below mu N = 1500 N (Eqs. 57-58)."""
    left, right = friction.stick_test([2000.0, 3200.0, 2999.0], 0.0, 0.0, [0.0, 0.0, 0.0], **KW)
    assert left.tolist() == [True, False, True] and right.tolist() == [True, False, True]
    # a moment loads one face more than the other: Mz = 15 N m -> +-500 N
    left, right = friction.stick_test(2000.0, 0.0, 0.0, 15.0, **KW)
    assert bool(left) and not bool(right)


def test_bad_friction_input():
    with pytest.raises(InputError, match=r"mu = -0.1"):
        friction.end_face_friction(1.0, 0.0, width_m=L0, mu=-0.1, preload_N=N)
    with pytest.raises(InputError, match=r"vy_m_s = nan m/s"):
        friction.end_face_friction(float("nan"), 0.0, **KW)
