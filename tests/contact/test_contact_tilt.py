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
    """2' tilt at an edge penetration of 0.01 mm: l = Delta r/|theta| = 17.2 mm (docs/reference/contact-laws.md section 10).
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
    """docs/reference/contact-laws.md section 10 point-contact illustration (centre penetration, one-point rule,
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


# --- edge transition: the regularised one-point selection (Dai et al. 2025 Eqs. 18-19, Q8) ---

def _sharp_rule(rho, p1, p2, d0):
    """Dai et al. (2025) Eqs. 18-19 with the Q8 tie, written out independently of contact.tilt."""
    w1 = np.zeros(p1.shape)
    w2 = np.zeros(p1.shape)
    for i in range(p1.size):
        if p1[i] <= 0 and p2[i] <= 0:
            continue
        if rho[i] <= d0:
            w1[i], w2[i] = float(p1[i] > 0), float(p2[i] > 0)
        elif p1[i] > p2[i]:
            w1[i] = 1.0
        elif p2[i] > p1[i]:
            w2[i] = 1.0
        else:
            w1[i] = w2[i] = 0.5
    return w1, w2


def _near_switch_points(n=3000, seed=5):
    rng = np.random.default_rng(seed)
    rho = D0 + rng.choice([-1, 1], n) * rng.uniform(0, 3 * tilt.EDGE_TRANSITION_M, n)
    p1 = rng.uniform(-2e-7, 2e-6, n)
    p2 = p1 + rng.choice([-1, 1], n) * rng.uniform(0, 3 * tilt.EDGE_TRANSITION_M, n)
    p2[::7] = p1[::7]                                 # exact ties
    rho[::11] = D0                                    # exactly on the clearance circle
    return rho, p1, p2


def test_edge_transition_zero_is_the_papers_sharp_rule_exactly():
    rho, p1, p2 = _near_switch_points()
    w1, w2, state = tilt.selection_weights(rho, p1, p2, D0, edge_transition_m=0.0)
    s1, s2 = _sharp_rule(rho, p1, p2, D0)
    assert np.array_equal(w1, s1) and np.array_equal(w2, s2)
    assert set(np.unique(np.concatenate([w1, w2]))) == {0.0, 0.5, 1.0}
    # the regularised weights equal the sharp ones to the last bit outside the two bands
    eps = tilt.EDGE_TRANSITION_M
    r1, r2, state_r = tilt.selection_weights(rho, p1, p2, D0)
    far = (np.abs(p1 - p2) >= eps / 2) & ((rho <= D0 - eps) | (rho > D0))
    assert far.sum() > 500 and np.array_equal(r1[far], s1[far]) and np.array_equal(r2[far], s2[far])
    assert np.array_equal(state_r, state)             # the reported state is the sharp rule's
    inside_band = ~far & (p1 > 0) & (p2 > 0)
    assert np.any((r1[inside_band] > 0) & (r1[inside_band] < 1))


def test_smooth_step_is_c2_with_the_q8_tie_value():
    hw = 1e-7
    x = np.linspace(-2 * hw, 2 * hw, 40001)
    S, dS = tilt.smooth_step(x, hw)
    assert S[20000] == 0.5 and np.all(S[x <= -hw] == 0) and np.all(S[x >= hw] == 1)
    assert np.all(np.diff(S) >= 0)
    h = x[1] - x[0]
    assert np.max(np.abs(np.gradient(S, h) - dS)) < 1e-6 * dS.max()      # derivative is S'
    d2 = np.gradient(dS, h)
    assert np.max(np.abs(np.diff(d2))) < 1e-3 * np.abs(d2).max()          # S'' has no jump (C2)
    assert tilt.smooth_step(0.0, 0.0)[0] == 0.5 and tilt.smooth_step(-1e-30, 0.0)[0] == 0.0


def _sweep(eps, **kw):
    return tilt.tilted_contact(**kw, clearance_m=D0, width_m=L0, force_per_width=PER_WIDTH, edge_transition_m=eps)


def test_edge_transition_is_continuous_where_the_penetrations_cross():
    """Centre 0.2 um outside the clearance, 1' tilt about y (edges shifted -+4.4 um in z), theta_z sweeping
    through 0: the penetrations cross (0.39 um each, partial patches). The sharp rule flips the loaded edge,
    so Fz and Mz change sign in one sample; the regularised rule passes through the Q8 mean (Fz = Mz = 0)."""
    thz = np.linspace(-1e-5, 1e-5, 4001)
    kw = dict(y_m=D0 + 2e-7, z_m=0.0, theta_y_rad=1 * ARCMIN, theta_z_rad=thz)
    sharp, smooth = _sweep(0.0, **kw), _sweep(tilt.EDGE_TRANSITION_M, **kw)
    assert sharp.penetration_1_m[2000] == sharp.penetration_2_m[2000] > 0
    for a in ("Fz_N", "Mz_Nm"):              # (Fy, My are even in theta_z: no jump)
        jump_sharp = np.abs(np.diff(getattr(sharp, a))).max()
        step_smooth = np.abs(np.diff(getattr(smooth, a))).max()
        assert step_smooth < 0.01 * jump_sharp, a
    assert abs(sharp.Fz_N[1999] - sharp.Fz_N[2001]) > 1.5 * abs(sharp.Fz_N[1999])     # sign flip
    assert smooth.weight_1[2000] == smooth.weight_2[2000] == 0.5 and smooth.Fz_N[2000] == 0.0
    far = np.abs(sharp.penetration_1_m - sharp.penetration_2_m) >= tilt.EDGE_TRANSITION_M / 2
    assert np.array_equal(smooth.Fz_N[far], sharp.Fz_N[far]) and np.array_equal(smooth.Mz_Nm[far], sharp.Mz_Nm[far])


def test_edge_transition_hands_over_smoothly_at_the_clearance_circle():
    """|r| sweeping through delta0 with both edges penetrating (1' tilt about y, r along y): the sharp rule
    goes from the sum of both edges (two-point, |r| <= delta0) to their mean (one-point tie) at |r| = delta0,
    halving the force; the regularised rule hands over within delta0 - eps < |r| < delta0."""
    y = D0 + np.linspace(-4e-7, 1e-7, 5001)
    kw = dict(y_m=y, z_m=0.0, theta_y_rad=1 * ARCMIN, theta_z_rad=0.0)
    sharp, smooth = _sweep(0.0, **kw), _sweep(tilt.EDGE_TRANSITION_M, **kw)
    jump_sharp = np.abs(np.diff(sharp.Fy_N)).max()
    assert jump_sharp > 0.4 * np.abs(sharp.Fy_N).max()
    assert np.abs(np.diff(smooth.Fy_N)).max() < 0.01 * jump_sharp
    outside = y > D0
    assert np.array_equal(smooth.Fy_N[outside], sharp.Fy_N[outside])
    deep = y <= D0 - tilt.EDGE_TRANSITION_M
    assert np.array_equal(smooth.Fy_N[deep], sharp.Fy_N[deep])


def test_edge_transition_leaves_aligned_tilt_values_unchanged():
    """Table 3 set-up (aligned tilt, centre penetration >= 0): the crossing is l0|theta| away (>= 4 um
    at 0.5'), far outside the band, so the regularised law equals the sharp one exactly."""
    pen = np.array([0.0, 1e-6, 0.01e-3, 0.03e-3, 0.05e-3])
    for arcmin in (0.0, 0.5, 1.0, 2.0):
        a = tilt.aligned_tilt_contact(pen, arcmin * ARCMIN, clearance_m=D0, width_m=L0, force_per_width=PER_WIDTH)
        b = tilt.tilted_contact(D0 + pen, 0.0, 0.0, arcmin * ARCMIN, **GEOM, edge_transition_m=0.0)
        assert np.array_equal(a.Fy_N, b.Fy_N) and np.array_equal(a.Mz_Nm, b.Mz_Nm)


def test_edge_transition_negative_is_refused():
    from contact.errors import InputError
    with pytest.raises(InputError, match=r"edge_transition_m = -1e-07 m"):
        tilt.tilted_contact(D0, 0.0, **GEOM, edge_transition_m=-1e-7)
