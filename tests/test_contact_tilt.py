"""Tilted-ring geometry of contact.tilt (Dai et al. 2025 Eqs. 8-19 with the Q8 fix)."""
from __future__ import annotations

import numpy as np
import pytest

from contact import laws, tilt
from contact.units import ARCMIN

D0, L0 = 0.05e-3, 30e-3
MAT = dict(bearing_E_Pa=204e9, bearing_nu=0.3, support_E_Pa=204e9, support_nu=0.3)
PER_WIDTH = laws.force_per_width_function("conformal", clearance_m=D0, **MAT)
GEOM = dict(clearance_m=D0, width_m=L0, force_per_width=PER_WIDTH)


def line_force(pen):
    return laws.conformal_force(pen, clearance_m=D0, width_m=L0, **MAT).force_N


def test_zero_tilt_is_line_contact_not_doubled():
    """At theta = 0 both edges coincide; Dai et al. (2025) Eq. 19 as printed would add both (Q8).
    The force must equal the line-contact law (Eq. 1/5) with l = l0, and no moment."""
    pen = np.array([1e-6, 1e-5, 3e-5])
    res = tilt.tilted_contact(D0 + pen, 0.0, **GEOM)
    assert -res.Fy_N == pytest.approx(line_force(pen), rel=1e-14)
    assert np.all(res.Fz_N == 0) and np.all(res.My_Nm == 0) and np.all(res.Mz_Nm == 0)
    assert np.all(res.contact_width_m == L0)


@pytest.mark.parametrize("direction", [0.0, 0.7, np.pi / 2, 2.5, np.pi])
def test_continuous_across_zero_tilt(direction):
    """Force and moment tend to the line-contact values as |theta| -> 0 from any direction, O(theta)."""
    y, z = D0 + 1e-5, 2e-6
    ref = tilt.tilted_contact(y, z, **GEOM)
    mags = np.array([1e-4, 1e-5, 1e-6, 1e-7, 1e-8])
    for sign in (1, -1):
        th = sign * mags
        res = tilt.tilted_contact(y, z, th * np.cos(direction), th * np.sin(direction), **GEOM)
        dF = np.hypot(res.Fy_N - ref.Fy_N, res.Fz_N - ref.Fz_N) / ref.force_N
        dM = res.moment_Nm
        assert np.all(np.diff(dF) < 0) and dF[-1] < 3e-5          # linear in |theta|: 1e-8 rad -> ~1.6e-5
        assert np.all(dF < 2 * mags * L0 / 2 / 1e-5)        # Lipschitz: edge shift |theta| l0/2 vs 10 um
        assert np.all(dM <= res.force_N * L0 / 2)


def test_continuous_at_first_contact():
    """At Delta r = 0 the force is zero and grows continuously (straight and tilted ring)."""
    pen = np.array([-1e-9, 0.0, 1e-12, 1e-10, 1e-8])
    for th in (0.0, 1 * ARCMIN):
        res = tilt.aligned_tilt_contact(pen - th * L0 / 2, th, clearance_m=D0, width_m=L0, force_per_width=PER_WIDTH)
        F = res.force_N
        assert F[0] == 0 and F[1] == 0
        assert 0 < F[2] < 1e-4 * F[4] and np.all(np.diff(F) >= 0)


@pytest.mark.parametrize("phi", [0.3, 1.0, 2.0, -2.8])
def test_rotating_r_and_theta_together_rotates_force_and_moment(phi):
    """Isotropy of the support: rotate (y, z), (theta_y, theta_z) and the velocities by phi about x;
    force and moment rotate by phi."""
    rng = np.random.default_rng(3)
    n = 200
    ang = rng.uniform(0, 2 * np.pi, n)
    rad = D0 + rng.uniform(-2e-5, 3e-5, n)
    y, z = rad * np.cos(ang), rad * np.sin(ang)
    thy, thz = rng.normal(0, 3 * ARCMIN, n), rng.normal(0, 3 * ARCMIN, n)
    vy, vz, wy, wz = rng.normal(0, 1e-3, (4, n))
    c, s = np.cos(phi), np.sin(phi)
    rot = lambda a, b: (c * a - s * b, s * a + c * b)  # noqa: E731
    kw = dict(GEOM, c_c_s_per_m=100.0)
    a = tilt.tilted_contact(y, z, thy, thz, vy, vz, wy, wz, **kw)
    b = tilt.tilted_contact(*rot(y, z), *rot(thy, thz), *rot(vy, vz), *rot(wy, wz), **kw)
    Fy, Fz = rot(a.Fy_N, a.Fz_N)
    My, Mz = rot(a.My_Nm, a.Mz_Nm)
    scale_F, scale_M = np.max(a.force_N), np.max(a.moment_Nm)
    assert np.max(np.abs(b.Fy_N - Fy)) < 1e-9 * scale_F and np.max(np.abs(b.Fz_N - Fz)) < 1e-9 * scale_F
    assert np.max(np.abs(b.My_Nm - My)) < 1e-9 * scale_M and np.max(np.abs(b.Mz_Nm - Mz)) < 1e-9 * scale_M
    assert scale_M > 0 and np.count_nonzero(a.state) > n // 4


def test_partial_patch_width_and_restoring_moment():
    """2' tilt at an edge penetration of 0.01 mm: l = Delta r/|theta| = 17.2 mm (contact-laws.md section 10).
    Edge 1 (x = +l0/2) pushed +y by theta_z > 0: force -y, moment Mz < 0 restores the tilt."""
    th = 2 * ARCMIN
    edge_pen = 0.01e-3
    res = tilt.tilted_contact(D0 + edge_pen - th * L0 / 2, 0.0, 0.0, th, **GEOM)
    assert res.state == tilt.STATE_EDGE1
    assert res.width_1_m == pytest.approx(edge_pen / th, rel=1e-12)
    assert res.width_1_m * 1e3 == pytest.approx(17.2, abs=0.05)
    l1 = edge_pen / th
    P = PER_WIDTH(edge_pen)[0] * l1
    assert res.Fy_N == pytest.approx(-P, rel=1e-12)
    assert res.Mz_Nm == pytest.approx(-P * (L0 - l1) / 2, rel=1e-12)
    assert res.My_Nm == 0


def test_aligned_tilt_values_of_reference_note():
    """contact-laws.md section 10 point-contact illustration (centre penetration, one-point rule,
    full patch): e.g. 2' at 0.01 mm -> 97 321 N; 0.5' at 0.05 mm -> 301 122 N."""
    pen = np.array([0.01, 0.03, 0.05]) * 1e-3
    expected = {0.5: [61775, 174947, 301122], 1.0: [73454, 188088, 315669], 2.0: [97321, 214825, 345236]}
    for arcmin, vals in expected.items():
        res = tilt.aligned_tilt_contact(pen, arcmin * ARCMIN, clearance_m=D0, width_m=L0, force_per_width=PER_WIDTH)
        assert res.force_N == pytest.approx(vals, abs=1.0)
        assert np.all(res.moment_Nm == 0)          # capped patch: l1 = l0, arm 0


def test_two_point_contact_on_opposite_sides():
    """Centre inside the clearance, large tilt: both edges touch opposite sides (Eq. 19, first case);
    forces cancel in y, the moment resists the tilt and equals the sum of both edge moments."""
    th = 20 * ARCMIN
    edge = th * L0 / 2
    res = tilt.tilted_contact(0.0, 0.0, 0.0, th, **GEOM)
    pen = edge - D0
    assert res.state == tilt.STATE_TWO_POINT
    assert res.penetration_1_m == pytest.approx(pen) and res.penetration_2_m == pytest.approx(pen)
    l = pen / th
    P = PER_WIDTH(pen)[0] * l
    assert res.Fy_N == pytest.approx(0, abs=1e-9 * P)
    assert res.Mz_Nm == pytest.approx(-2 * P * (L0 - l) / 2, rel=1e-12)


def test_one_point_takes_larger_edge_when_centre_penetrates():
    res = tilt.tilted_contact(D0 + 1e-5, 0.0, 0.0, -1 * ARCMIN, **GEOM)
    assert res.state == tilt.STATE_EDGE2
    assert res.weight_1 == 0 and res.weight_2 == 1
    assert res.Mz_Nm == 0 or res.Mz_Nm > 0               # restoring for negative tilt
