"""Total loose-support force (contact.loose_support): compiled kernel against the numpy reference,
analytic Jacobian against finite differences, the scalar njit path, and input errors."""
from __future__ import annotations

import numba
import numpy as np
import pytest

from contact import friction, laws, tilt
from contact.errors import InputError, OutsideDomainError
from contact.loose_support import (LooseSupportParams, loose_support_force, loose_support_jacobian,
                                   point_force, point_force_jacobian)
from contact.units import ARCMIN

P4 = LooseSupportParams.paper_table4()          # Dai et al. (2025) Table 4 values


def random_states(n, seed=0, spread=1.0):
    rng = np.random.default_rng(seed)
    ang = rng.uniform(0, 2 * np.pi, n)
    rad = P4.clearance_m + spread * rng.uniform(-3e-5, 3e-5, n)
    return (rad * np.cos(ang), rad * np.sin(ang), rng.normal(0, 3 * ARCMIN, n), rng.normal(0, 3 * ARCMIN, n),
            rng.normal(0, 5e-3, n), rng.normal(0, 5e-3, n), rng.normal(0, 0.2, n), rng.normal(0, 0.2, n))


def reference(params, x):
    """numpy reference: contact.tilt + contact.friction, coded separately from the kernel."""
    per_width = laws.force_per_width_function(params.law, clearance_m=params.clearance_m,
                                              bearing_E_Pa=params.bearing_E_Pa, bearing_nu=params.bearing_nu,
                                              support_E_Pa=params.support_E_Pa, support_nu=params.support_nu,
                                              modulus=params.modulus, beta_reading=params.beta_reading)
    c = tilt.tilted_contact(*x, clearance_m=params.clearance_m, width_m=params.width_m, force_per_width=per_width,
                            c_c_s_per_m=params.c_c_s_per_m, clip_damping_at_zero=params.clip_damping_at_zero,
                            edge_transition_m=params.edge_transition_m)
    f = friction.end_face_friction(*x[4:], width_m=params.width_m, mu=params.mu, preload_N=params.preload_N)
    return np.stack([c.Fy_N + f[0], c.Fz_N + f[1], c.My_Nm + f[2], c.Mz_Nm + f[3]]), c.state


@pytest.mark.parametrize("params", [P4, P4.__class__.paper_table4(law="pereira"),
                                    P4.__class__.paper_table4(clip_damping_at_zero=False, support_E_Pa=70e9,
                                                              support_nu=0.33, beta_reading="minus_4b2_1pb2")])
def test_kernel_agrees_with_numpy_reference(params):
    x = random_states(4000)
    res = loose_support_force(params, *x, with_state=True)
    ref, state = reference(params, x)
    got = np.stack([res.Fy_N, res.Fz_N, res.My_Nm, res.Mz_Nm])
    scale = np.max(np.abs(ref), axis=1, keepdims=True)
    assert np.max(np.abs(got - ref) / scale) < 1e-11
    assert np.array_equal(res.state, state)
    assert set(np.unique(state)) >= {0, 1, 2}


def _jac_error(J, Jfd, F, steps):
    """Largest error relative to the row scale, allowing the finite-difference round-off eps|F|/h."""
    scale = np.max(np.abs(Jfd), axis=1, keepdims=True)
    roundoff = 1e-12 * np.maximum(np.abs(F), 1.0)[:, None] / steps[None, :]
    return np.max(np.abs(J - Jfd) / (scale + roundoff / 1e-5))


def _fd_jacobian(params, x, steps):
    J = np.zeros((4, 8))
    for j in range(8):
        xp, xm = x.copy(), x.copy()
        xp[j] += steps[j]
        xm[j] -= steps[j]
        J[:, j] = (loose_support_jacobian(params, *xp)[0] - loose_support_jacobian(params, *xm)[0]) / (2 * steps[j])
    return J


CASES = {
    # name: (y, z, theta_y, theta_z, vy, vz, wy, wz)
    "edge1_full_patch": (6.2e-5, 1.1e-5, 0.4 * ARCMIN, 1.0 * ARCMIN, 2e-3, -1e-3, 0.05, 0.03),
    "edge2_partial_patch": (5.1e-5, 0.3e-5, -0.5 * ARCMIN, -3.0 * ARCMIN, -1e-3, 4e-3, 0.1, -0.2),
    "two_point": (0.5e-5, -0.2e-5, 8 * ARCMIN, 21 * ARCMIN, 1e-3, 1e-3, -0.3, 0.2),
    "no_contact_sliding": (1e-5, 2e-5, 1 * ARCMIN, -1 * ARCMIN, 3e-3, 1e-3, 0.2, 0.1),
    "damping_clipped": (6e-5, 0.0, 0.0, 0.5 * ARCMIN, -0.05, 0.0, 0.0, 0.0),
}


CASE_STATES = {"edge1_full_patch": 1, "edge2_partial_patch": 2, "two_point": 3, "no_contact_sliding": 0,
               "damping_clipped": 1}


@pytest.mark.parametrize("case", sorted(CASES))
def test_jacobian_matches_finite_differences(case):
    params = LooseSupportParams.paper_table4()
    x = np.array(CASES[case])
    res = loose_support_force(params, *x, with_state=True)
    assert res.state == CASE_STATES[case]
    if case == "edge2_partial_patch":      # the patch-length derivative (l = pen/|theta|) is exercised
        assert 0 < res.penetration_2_m < np.hypot(x[2], x[3]) * params.width_m
    steps = np.array([1e-11, 1e-11, 1e-9, 1e-9, 1e-8, 1e-8, 1e-6, 1e-6])
    F, J = loose_support_jacobian(params, *x)
    Jfd = _fd_jacobian(params, x, steps)
    assert _jac_error(J, Jfd, F, steps) < 1e-5, (J, Jfd)
    if case == "damping_clipped":       # separating at 5 cm/s: 1 + 100*(-0.05) < 0, contact force clipped to 0
        assert F[0] == pytest.approx(2 * 0.3 * 5000) and np.all(J[:, :4] == 0)
    elif case != "no_contact_sliding":
        assert np.all(np.any(J[:2, :4] != 0, axis=1))


def test_jacobian_random_points_pereira_and_smoothed_friction():
    params = LooseSupportParams.paper_table4(law="pereira", friction_smoothing_m_s=1e-3, c_c_s_per_m=20.0)
    xs = np.stack(random_states(40, seed=7))
    steps = np.array([1e-11, 1e-11, 1e-9, 1e-9, 1e-8, 1e-8, 1e-6, 1e-6])
    worst = 0.0
    for k in range(xs.shape[1]):
        x = xs[:, k]
        F, J = loose_support_jacobian(params, *x)
        Jfd = _fd_jacobian(params, x, steps)
        err = _jac_error(J, Jfd, F, steps)
        # skip points within a finite-difference step of a switch of the model (first contact, edge switch)
        st = loose_support_force(params, *(x[:, None] + np.diag(steps * 3)), with_state=True).state
        if len(set(st.tolist())) == 1:
            worst = max(worst, err)
    assert worst < 1e-5


def test_scalar_njit_path_matches_vectorized_and_compiles_into_a_loop():
    params = LooseSupportParams.paper_table4()
    p = params.kernel_args
    xs = np.stack(random_states(50, seed=2))

    @numba.njit
    def loop(xs, p):
        out = np.empty((xs.shape[1], 4))
        jac = np.empty((4, 8))
        acc = 0.0
        for i in range(xs.shape[1]):
            a = point_force(xs[0, i], xs[1, i], xs[2, i], xs[3, i], xs[4, i], xs[5, i], xs[6, i], xs[7, i], p)
            b = point_force_jacobian(xs[0, i], xs[1, i], xs[2, i], xs[3, i], xs[4, i], xs[5, i], xs[6, i],
                                     xs[7, i], p, jac)
            for k in range(4):
                out[i, k] = a[k]
                acc += abs(a[k] - b[k])
        return out, acc

    out, acc = loop(xs, p)
    res = loose_support_force(params, *xs)
    assert acc == 0.0
    assert np.array_equal(out, np.stack([res.Fy_N, res.Fz_N, res.My_Nm, res.Mz_Nm], axis=1))


def test_outside_neat_fit_limit_raises_or_flags():
    params = LooseSupportParams.paper_table4()
    far = params.clearance_m + 1.1 * params.neat_fit_limit_m
    with pytest.raises(OutsideDomainError, match="neat-fit"):
        loose_support_force(params, [6e-5, far], 0.0)
    res = loose_support_force(params, [6e-5, far], 0.0, on_outside="flag", with_state=True)
    assert res.in_domain.tolist() == [True, False]
    assert np.isfinite(res.Fy_N[0]) and np.isnan(res.Fy_N[1])
    with pytest.raises(OutsideDomainError):
        point_force(far, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, params.kernel_args)


def test_displacement_in_mm_by_mistake_is_caught():
    with pytest.raises(OutsideDomainError, match=r"y_m = 0.06 m.*given in mm"):
        loose_support_force(P4, 0.06, 0.0)                 # 0.06 mm typed as m


def test_nan_input_names_the_input():
    with pytest.raises(InputError, match=r"omega_z_rad_s = nan rad/s"):
        loose_support_force(P4, [6e-5, 6e-5], 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, [0.0, float("nan")])


def test_tilt_ignored_is_line_contact_with_translation_friction():
    """The paper's tilt-neglecting model: Eq. 1 at the centre plane, friction -2 mu N v/|v|, no moments."""
    params = LooseSupportParams.paper_table4(tilt_ignored=True, c_c_s_per_m=0.0)
    res = loose_support_force(params, 6e-5, 0.0, 0.0, 5 * ARCMIN, 0.0, 1e-3, 0.0, 0.3)
    line = laws.conformal_force(1e-5, clearance_m=5e-5, width_m=30e-3, bearing_E_Pa=204e9, bearing_nu=0.3,
                                support_E_Pa=204e9, support_nu=0.3).force_N
    assert res.Fy_N == pytest.approx(-line, rel=1e-14)
    assert res.Fz_N == pytest.approx(-2 * 0.3 * 5000, rel=1e-14)
    assert res.My_Nm == 0 and res.Mz_Nm == 0
    F, J = loose_support_jacobian(params, 6e-5, 0.0, 0.0, 5 * ARCMIN, 0.0, 1e-3, 0.0, 0.3)
    assert np.all(J[:, [2, 3, 6, 7]] == 0) and np.all(J[2:] == 0)


def test_forces_act_on_bearing_towards_centre_and_shape_is_kept():
    res = loose_support_force(LooseSupportParams.paper_table4(mu=0.0), np.full((3, 2), 6e-5), 0.0)
    assert res.Fy_N.shape == (3, 2) and np.all(res.Fy_N < 0)
    y = np.full(2, 6e-5)
    y.flags.writeable = False                      # read-only and broadcast inputs are accepted
    res = loose_support_force(P4, y, np.zeros((3, 1)))
    assert res.Fy_N.shape == (3, 2)
    with pytest.raises(InputError, match="do not broadcast"):
        loose_support_force(P4, np.zeros(3), np.zeros(2))


@pytest.mark.parametrize("field,value,pattern", [
    ("clearance_m", -5e-5, r"clearance_m = -5e-05 m"),
    ("clearance_m", 0.05, r"clearance_m = 0.05 m.*wrong unit"),
    ("width_m", 0.0, r"width_m = 0 m"),
    ("support_E_Pa", -1.0, r"support_E_Pa = -1 Pa"),
    ("preload_N", float("nan"), r"preload_N = nan N"),
    ("law", "johnson", r"law = 'johnson'"),
    ("edge_transition_m", -1e-7, r"edge_transition_m = -1e-07 m"),
])
def test_params_validation(field, value, pattern):
    with pytest.raises(InputError, match=pattern):
        LooseSupportParams.paper_table4(**{field: value})


def test_radius_catches_clearance_in_mm():
    with pytest.raises(InputError, match=r"clearance_m = 0.008 m"):
        LooseSupportParams.paper_table4(clearance_m=0.008, radius_m=0.1)


def test_parallel_path_equals_serial_path():
    x = random_states(5000, seed=11)
    a = loose_support_force(P4, *x, with_state=True)
    b = loose_support_force(P4, *x, with_state=True, parallel=True)
    for f in ("Fy_N", "Fz_N", "My_Nm", "Mz_Nm", "state", "in_domain", "penetration_1_m", "penetration_2_m"):
        assert np.array_equal(getattr(a, f), getattr(b, f)), f
    far = P4.clearance_m + 1.1 * P4.neat_fit_limit_m
    with pytest.raises(OutsideDomainError):
        loose_support_force(P4, [6e-5, far], 0.0, parallel=True)
    with pytest.raises(InputError, match=r"vz_m_s = inf m/s"):
        loose_support_force(P4, [6e-5, far, 6e-5], 0.0, 0.0, 0.0, 0.0, [0.0, 0.0, np.inf], parallel=True)


def test_line_contact_stiffness_is_symmetric_and_matches_law_slope():
    """Without damping, friction and tilt the contact force is central, F = -P(|r| - delta0) r/|r|, i.e. the
    gradient of a potential: its stiffness dF/dr is symmetric, with radial value -dP/d(Delta r) and
    tangential value -P/|r| (plane kinematics of a central force)."""
    params = LooseSupportParams.paper_table4(c_c_s_per_m=0.0, mu=0.0)
    ang = 0.6
    rho = params.clearance_m + 1.5e-5
    F, J = loose_support_jacobian(params, rho * np.cos(ang), rho * np.sin(ang))
    K = J[:2, :2]
    assert K[0, 1] == pytest.approx(K[1, 0], rel=1e-12)
    assert np.all(J[:, 4:] == 0)
    e = np.array([np.cos(ang), np.sin(ang)])
    t = np.array([-np.sin(ang), np.cos(ang)])
    kw = dict(clearance_m=5e-5, width_m=30e-3, bearing_E_Pa=204e9, bearing_nu=0.3, support_E_Pa=204e9, support_nu=0.3)
    h = 1e-10
    dP = (laws.conformal_force(1.5e-5 + h, **kw).force_N - laws.conformal_force(1.5e-5 - h, **kw).force_N) / (2 * h)
    P = laws.conformal_force(1.5e-5, **kw).force_N
    assert e @ K @ e == pytest.approx(-dP, rel=1e-6)
    assert t @ K @ t == pytest.approx(-P / rho, rel=1e-12)


# --- edge transition (regularised Eqs. 18-19): kernel = numpy reference, analytic Jacobian = FD ---

def near_switch_states(n, seed=0):
    """States with the centre near the clearance circle and the two edge penetrations nearly equal:
    tilt about an axis along r (edges shifted sideways), plus a small tilt that separates them."""
    rng = np.random.default_rng(seed)
    ang = rng.uniform(0, 2 * np.pi, n)
    rad = P4.clearance_m + rng.uniform(-4e-7, 4e-7, n)
    side = rng.normal(0, 2 * ARCMIN, n)                   # edges shifted along the tangent: equal penetrations
    sep = rng.uniform(-1e-5, 1e-5, n)                     # separates them by ~ l0*sep (up to 0.3 um)
    thy = side * np.cos(ang) - sep * np.sin(ang)
    thz = side * np.sin(ang) + sep * np.cos(ang)
    return (rad * np.cos(ang), rad * np.sin(ang), thy, thz,
            rng.normal(0, 5e-3, n), rng.normal(0, 5e-3, n), rng.normal(0, 0.2, n), rng.normal(0, 0.2, n))


@pytest.mark.parametrize("eps", [0.0, P4.edge_transition_m, 1e-6])
def test_kernel_agrees_with_numpy_reference_near_the_edge_switches(eps):
    params = LooseSupportParams.paper_table4(edge_transition_m=eps)
    x = near_switch_states(4000, seed=3)
    res = loose_support_force(params, *x, with_state=True)
    ref, state = reference(params, x)
    got = np.stack([res.Fy_N, res.Fz_N, res.My_Nm, res.Mz_Nm])
    scale = np.max(np.abs(ref), axis=1, keepdims=True)
    assert np.max(np.abs(got - ref) / scale) < 1e-11
    assert np.array_equal(res.state, state)
    p1, p2 = res.penetration_1_m, res.penetration_2_m
    band = (np.abs(p1 - p2) < 0.5 * P4.edge_transition_m) & (np.maximum(p1, p2) > 0)
    assert band.sum() > 200                                # the bands are really exercised


def test_kernel_edge_transition_zero_is_the_sharp_rule_and_default_differs_only_in_the_bands():
    x = near_switch_states(4000, seed=4)
    sharp = loose_support_force(LooseSupportParams.paper_table4(edge_transition_m=0.0), *x, with_state=True)
    smooth = loose_support_force(P4, *x, with_state=True)
    eps = P4.edge_transition_m
    rho = np.hypot(x[0], x[1])
    p1, p2 = sharp.penetration_1_m, sharp.penetration_2_m
    far = (np.abs(p1 - p2) >= eps / 2) & ((rho <= P4.clearance_m - eps) | (rho > P4.clearance_m))
    for f in ("Fy_N", "Fz_N", "My_Nm", "Mz_Nm"):
        assert np.array_equal(getattr(sharp, f)[far], getattr(smooth, f)[far]), f
        assert not np.array_equal(getattr(sharp, f)[~far], getattr(smooth, f)[~far]), f
    assert np.array_equal(sharp.state, smooth.state)
    # sharp rule outside the clearance: only the edge with the larger penetration, so with the same
    # edge loaded the result equals a state where the other edge is pulled far away from contact
    out = (rho > P4.clearance_m) & (p1 > p2) & (p1 > 0)
    assert out.sum() > 100
    assert np.all(sharp.state[out] == 1)


BAND_CASES = {
    # penetrations cross (|dr1 - dr2| < eps/2), centre outside: moment arm and force direction blend
    "crossing": (5.0e-5 + 2e-7, 0.0, 1 * ARCMIN, 1e-6, 2e-3, -1e-3, 0.05, 0.03),
    "crossing_oblique": (3.0e-5, 4.0e-5 + 1e-7, -0.6 * ARCMIN - 0.8e-6, -0.8 * ARCMIN + 0.6e-6, -1e-3, 2e-3, -0.1, 0.2),
    # centre inside the hand-over band delta0 - eps < |r| < delta0, both edges penetrating
    "hand_over": (5.0e-5 - 1e-7, 0.0, 1 * ARCMIN, 2e-6, 1e-3, 1e-3, -0.3, 0.2),
}


@pytest.mark.parametrize("case", sorted(BAND_CASES))
def test_jacobian_matches_finite_differences_inside_the_edge_transition(case):
    """The analytic Jacobian includes the derivatives of the regularised weights (checked against
    central differences like test_jacobian_matches_finite_differences)."""
    x = np.array(BAND_CASES[case])
    res = loose_support_force(P4, *x, with_state=True)
    p1, p2 = float(res.penetration_1_m), float(res.penetration_2_m)
    assert p1 > 0 and p2 > 0
    rho = np.hypot(x[0], x[1])
    if case == "hand_over":
        assert P4.clearance_m - P4.edge_transition_m < rho < P4.clearance_m
    else:
        assert abs(p1 - p2) < 0.5 * P4.edge_transition_m and rho > P4.clearance_m
    steps = np.array([1e-11, 1e-11, 1e-9, 1e-9, 1e-8, 1e-8, 1e-6, 1e-6])
    F, J = loose_support_jacobian(P4, *x)
    Jfd = _fd_jacobian(P4, x, steps)
    assert _jac_error(J, Jfd, F, steps) < 1e-5, (J, Jfd)
    # the weight derivatives matter here: without them the position columns would be far off
    sharp = LooseSupportParams.paper_table4(edge_transition_m=0.0)
    xs = x.copy()
    F0, J0 = loose_support_jacobian(sharp, *xs)
    assert _jac_error(J0, Jfd, F, steps) > 1e-2
