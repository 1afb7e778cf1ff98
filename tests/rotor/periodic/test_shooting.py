"""Shooting (rotor.periodic.shooting) on the Jeffcott verification rotor, whose orbits are known in closed form
(rotor.periodic.jeffcott), and its minimum-norm Newton step."""
import math

import numpy as np
import pytest

from rotor.periodic.jeffcott import JeffcottParams, closed_form_radius, jeffcott_system, warped_frequency
from rotor.periodic.period_flow import advance, make_flow, monodromy_fd
from rotor.periodic.shooting import ShootingOptions, level_step, min_norm_step, shoot, shoot_from_transient

P = JeffcottParams()
N = 64


def _flow(w, backend="fd"):
    return make_flow(jeffcott_system(P, w), 2 * math.pi / w / N, backend)


@pytest.mark.parametrize("w", [200.0, 500.0, 700.0])
def test_shooting_from_a_short_transient_finds_the_circular_orbit(w):
    """16 revolutions of transient, then Newton: converged to 1e-9 of the orbit scale in a few iterations; the
    radius is the warped closed form's to 1e-9; the orbit is circular (speed Ω' r)."""
    res = shoot_from_transient(_flow(w), np.zeros(4), np.zeros(4), steps_per_rev=N, period_revs=1, modes0=(0, 0))
    assert res.converged and res.residual < 1e-9 and res.newton_iterations <= 8
    r = math.hypot(res.state[0], res.state[1])
    assert abs(closed_form_radius(P, w, r, N) - r) / r < 1e-9
    assert abs(math.hypot(res.state[4], res.state[5]) - float(warped_frequency(w, N)) * r) / (w * r) < 1e-9
    assert res.period_revs == 1 and res.singular_directions == 0


def test_stability_of_the_found_orbits():
    """500 rad/s (below the folds) is stable; at 700 rad/s, between the folds, the orbit the transient leads to
    lies on the lower branch and has lost stability to a complex pair (Neimark-Sacker: the non-synchronous
    whirl of a rotor with a hardening clearance; a long transient from it does not stay on the circle)."""
    stable = shoot_from_transient(_flow(500.0), np.zeros(4), np.zeros(4), steps_per_rev=N, period_revs=1, modes0=(0, 0))
    assert stable.floquet.stable
    ns = shoot_from_transient(_flow(700.0), np.zeros(4), np.zeros(4), steps_per_rev=N, period_revs=1, modes0=(0, 0))
    assert not ns.floquet.stable and ns.floquet.kind == "neimark_sacker" and ns.floquet.n_out_complex == 2
    from rotor.periodic.period_flow import record
    tr = record(_flow(700.0), ns.state * (1 + 1e-6), 0.0, 400 * N, (0, 0), N)
    r = np.hypot(tr.q[:, 0], tr.q[:, 1])
    r0 = math.hypot(ns.state[0], ns.state[1])
    assert np.abs(r / r0 - 1).max() > 1e-2                    # the perturbation grew by > 1e4


def test_period_detection_tries_one_revolution_first_on_a_synchronous_orbit():
    res = shoot_from_transient(_flow(300.0), np.zeros(4), np.zeros(4), steps_per_rev=N, modes0=(0, 0))
    assert res.converged and res.period_revs == 1


def test_shoot_rejects_a_period_beyond_eight_revolutions():
    with pytest.raises(ValueError, match="period_revs"):
        shoot(_flow(300.0), np.ones(8) * 1e-6, t0_s=0.0, steps_per_rev=N, period_revs=9)


def test_min_norm_step_on_a_singular_system():
    """A multiplier exactly 1 (stuck-face continuum) makes M − I singular: the step is the minimum-norm
    least-squares one, orthogonal to the null direction, and the dropped direction is counted."""
    rng = np.random.default_rng(3)
    Q, _ = np.linalg.qr(rng.normal(size=(4, 4)))
    J = Q @ np.diag([2.0, 1.0, 0.5, 0.0]) @ Q.T
    rhs = J @ rng.normal(size=4)                              # consistent right-hand side
    dx, dropped = min_norm_step(J, rhs, 1e-9)
    assert dropped == 1
    assert np.allclose(J @ dx, rhs, atol=1e-13)
    assert abs(Q[:, 3] @ dx) < 1e-13
    assert np.allclose(dx, np.linalg.pinv(J) @ rhs, atol=1e-13)


def test_level_step_keeps_the_conserved_levels():
    """A map with a conserved quantity ``w·x`` (``wᵀ(M − I) = 0``) whose null direction ``v`` is not ``w``
    (a stuck face's offset: the scheme conserves it, the continuum runs along v): the step solves the
    consistent system and sets ``wᵀ dz`` to ``wᵀ back`` exactly, where the minimum-norm step would move it."""
    rng = np.random.default_rng(5)
    n = 5
    v = rng.normal(size=n)
    v /= np.linalg.norm(v)
    w = rng.normal(size=n)
    w /= np.linalg.norm(w)
    B = rng.normal(size=(n, n))
    J = (np.eye(n) - np.outer(w, w)) @ B @ (np.eye(n) - np.outer(v, v))     # left null w, right null v
    rhs = J @ rng.normal(size=n)
    back = rng.normal(size=n)
    dz, dropped, U0 = level_step(J, rhs, 1e-9, back)
    assert dropped == 1 and U0.shape == (n, 1) and abs(abs(U0[:, 0] @ w) - 1.0) < 1e-12
    assert np.allclose(J @ dz, rhs, atol=1e-12)
    assert abs(w @ dz - w @ back) < 1e-12
    mn, _ = min_norm_step(J, rhs, 1e-9)
    assert abs(w @ mn - w @ back) > 1e-3                    # the minimum-norm step does not keep them
    dz0, _, _ = level_step(J, rhs, 1e-9)
    assert abs(w @ dz0) < 1e-12


def test_fd_monodromy_against_the_period_map():
    """Cross-check of the fallback with rotor.dynamics.period_map (exact monodromy from the step Jacobians)."""
    pytest.importorskip("rotor.dynamics.period_map")
    w = 600.0
    res = shoot_from_transient(_flow(w), np.zeros(4), np.zeros(4), steps_per_rev=N, period_revs=1, modes0=(0, 0))
    exact = advance(_flow(w, "exact"), res.state, 0.0, N, (0, 0))
    fd = monodromy_fd(_flow(w), res.state, 0.0, N, (0, 0))
    assert np.allclose(exact.state, advance(_flow(w), res.state, 0.0, N, (0, 0), jacobian=False).state,
                       rtol=0, atol=1e-12 * np.abs(res.state).max())
    assert np.abs(exact.monodromy - fd).max() < 1e-6 * np.abs(exact.monodromy).max()


def test_levenberg_marquardt_step_has_the_asked_norm_and_turns_towards_the_gradient():
    from rotor.periodic.shooting import lm_step
    rng = np.random.default_rng(3)
    J = rng.normal(size=(6, 6)) @ np.diag([10.0, 5.0, 1.0, 0.1, 1e-3, 1e-4])
    rhs = rng.normal(size=6)
    full, _ = min_norm_step(J, rhs, 1e-12)
    step = lm_step(J, rhs, 1e-12, 1e-2 * np.linalg.norm(full))
    assert np.linalg.norm(step) == pytest.approx(1e-2 * np.linalg.norm(full), rel=1e-6)
    # a short LM step points along the steepest descent of ½‖J dz − rhs‖², J^T rhs (Nocedal & Wright 2006, ch. 4)
    tiny = lm_step(J, rhs, 1e-12, 1e-9)
    g = J.T @ rhs
    assert tiny @ g / (np.linalg.norm(tiny) * np.linalg.norm(g)) > 0.999
    # a radius above the full step's norm gives the full step back (μ → 0)
    assert np.allclose(lm_step(J, rhs, 1e-12, 10 * np.linalg.norm(full)), full, rtol=1e-6, atol=1e-9)


def test_poincare_returns_support_a_period_only_where_it_repeats_better_than_its_divisors():
    from rotor.periodic.shooting import _supported
    j = np.arange(40)[:, None]
    # a period-3 sequence approaching its orbit: returns after 3 and 6 revolutions small, others O(1);
    # 6 repeats no better than its divisor 3, so 3 alone
    P = np.hstack([np.cos(2 * np.pi * j / 3), np.sin(2 * np.pi * j / 3)]) + 1e-3 * 0.9 ** j
    assert _supported(P, 8) == [3]
    # a period-1 sequence: no multiple of 1 repeats better than 1 itself, so only 1
    P1 = np.ones((40, 2)) + 0.5 ** j
    assert _supported(P1, 8) == [1]
