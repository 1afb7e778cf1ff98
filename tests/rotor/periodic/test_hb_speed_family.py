"""A scene's system built once and taken to any speed (rotor/dynamics/build.py: SpeedFamily), the harmonic-domain
pieces as exact functions of the speed (rotor/periodic/hb_aft.py: speed_blocks, hs_at_speed, speed_derivatives) and
the reported contact force in one compiled call (hb_aft.support_forces).

Expected values: the system the scene builder makes at that speed (rotor/studies/steady_state.py: point_system,
every job's path), and its harmonic system (hb_aft.prepare); equal to round-off (1e-12 relative), since the builder's
speed dependence is exactly ``C − ΩG`` and loads ``∝ Ω²`` (rotor/model/assembly.py: harmonic_loads). The speed
derivatives against central differences of the builder's own systems (h = 1e-4 Ω; the load is quadratic and A
linear in Ω at fixed ω, so the difference is exact up to round-off: 1e-7 relative). paper-table4 has all three
speed-dependent parts: disk unbalance (1X), the misalignment excitation (2X) and gyroscopic disks.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from rotor.dynamics.build import SpeedFamily
from rotor.periodic.hb_aft import fourier, hs_at_speed, prepare, speed_blocks, speed_derivatives, support_forces
from rotor.studies.steady_state import point_system

TO_RAD = math.pi / 30.0      # rpm -> rad/s as point_system converts (rpm * pi / 30)


def _rel(a, b) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b)))) / max(float(np.max(np.abs(b))), 1e-300)


def _table4(rpm: float):
    return point_system("paper-table4", rpm, mu=0.0)


def test_the_family_is_the_built_system_at_every_speed():
    _, model, base = _table4(9000.0)
    assert not model.speed_bearings
    fam = SpeedFamily(base)
    assert fam.exact
    assert np.any(base.force.cos[1]) and np.any(base.G)          # 2X and gyroscopic terms are there to scale
    for rpm in (3100.0, 9000.0, 14321.0):
        got, built = fam(rpm * math.pi / 30.0), _table4(rpm)[2]
        assert got.omega_rad_s == built.omega_rad_s
        for name in ("M", "C", "G", "K", "offset", "lock"):
            assert np.array_equal(getattr(got, name), getattr(built, name)), name
        f, g = got.force, built.force
        assert np.array_equal(f.orders, g.orders) and np.array_equal(f.static, g.static)
        assert _rel(f.cos, g.cos) < 1e-12 and _rel(f.sin, g.sin) < 1e-12, rpm
        assert f.omega_rad_s == g.omega_rad_s


def test_a_family_with_a_rebuild_builds_each_speed():
    calls = []
    base = _table4(9000.0)[2]
    fam = SpeedFamily(base, lambda w: calls.append(w) or base)
    assert not fam.exact and fam(123.0) is base and calls == [123.0]


@pytest.mark.parametrize("harmonics", [2, 4])
def test_speed_blocks_are_the_built_harmonic_system(harmonics):
    base = _table4(9000.0)[2]
    f = fourier(harmonics, 4 * harmonics + 2)
    sb = speed_blocks(base, f)
    for rpm in (4000.0, 9000.0, 16000.0):
        got, built = hs_at_speed(sb, rpm * math.pi / 30.0), prepare(_table4(rpm)[2], harmonics)
        assert got.speed_rad_s == built.speed_rad_s and got.omega_rad_s == built.omega_rad_s
        for name in ("A", "dA_domega", "load", "Dr"):
            assert _rel(getattr(got, name), getattr(built, name)) < 1e-12, (rpm, name)


def test_speed_derivatives_are_the_builder_s_central_differences():
    base = _table4(9000.0)[2]
    f = fourier(2, 10)
    sb = speed_blocks(base, f)
    w = 11000.0 * TO_RAD
    h = 1e-4 * w
    lo, hi = prepare(_table4((w - h) / TO_RAD)[2], 2), prepare(_table4((w + h) / TO_RAD)[2], 2)
    # A at fixed ω: remove the harmonics' own frequency change (∂A/∂ω · Δω, exact: A is quadratic in ω)
    hs = prepare(_table4(w / TO_RAD)[2], 2)
    dA_num = (hi.A - lo.A - hs.dA_domega * 2.0 * h) / (2.0 * h)
    dA, dload = speed_derivatives(sb, w)
    assert _rel(dA, dA_num) < 1e-6
    assert _rel(dload, (hi.load - lo.load) / (2.0 * h)) < 1e-7


def test_support_forces_are_the_law_s_row_by_row():
    system = _table4(12000.0)[2]
    law, d0 = system.support.law, system.support.law.clearance_m
    rng = np.random.default_rng(7)
    r, th = np.linspace(0.9, 1.05, 64) * d0, rng.uniform(0.0, 2.0 * math.pi, 64)
    u = np.column_stack([r * np.cos(th), r * np.sin(th), rng.uniform(-1e-7, 1e-7, (64, 2))])
    v = rng.uniform(-0.05, 0.05, (64, 4))
    want = np.array([law.force(a, b) for a, b in zip(u, v)])
    assert np.any(want != 0.0) and np.any(np.all(want == 0.0, axis=1))      # contact and gap rows both
    assert _rel(support_forces(law, u, v), want) < 1e-12
