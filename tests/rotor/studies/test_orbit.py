"""orbit() on the Table 4 rotor (Dai et al. 2025) at 10 500 rpm, against the transient steady state that
``simulate --steady`` reports (rotor.studies.steady_state from the linear periodic solution).

Scene: the Table 4 rotor under the former reading of Eq. 34 (rotor/scenes/paper-table4-inertial.toml),
where these operating points (a stuck face's continuum at 10 500 rpm, switch-free orbits at 11 400-12 000 rpm)
were found and measured."""
import numpy as np
import pytest

from rotor.dynamics.initial import linear_initial_state
from rotor.dynamics.production import warm_up
from rotor.studies.orbit import orbit
from rotor.studies.steady_state import steady_state, point_system

SPEED = 10500.0
SCENE = "paper-table4-inertial"


@pytest.fixture(scope="module")
def transient():
    warm_up()
    _, model, system = point_system(SCENE, SPEED)
    q0, v0 = linear_initial_state(system, 0.0)
    return steady_state(system, model, q0=q0, v0=v0)


def _worst(o, ss):
    h = ss.harmonics("v")
    return max(float(np.max(np.abs(np.array(o.velocity_amplitudes_mm_s_1X_to_5X[n]) * 1e-3 - h[:, j]) / h[:, j]))
               for j, n in enumerate(ss.channels))


def test_shooting_from_the_transient_state_reproduces_its_harmonics(transient):
    """From the transient's end state: Newton converges (1e-9 of the orbit scale) on a period of one
    revolution, and the 1X-5X velocity amplitudes at every station equal the transient's to 1e-4 (measured
    3.5e-5, the transient's own Poincaré tolerance being 1e-4)."""
    assert transient.convergence.converged and transient.convergence.period == 1
    o = orbit(SCENE, SPEED, start=(transient.q_end, transient.v_end))
    assert o.converged and o.residual < 1e-9 and o.period_revs == 1
    assert set(o.velocity_amplitudes_mm_s_1X_to_5X) == set(transient.channels)
    assert _worst(o, transient) < 1e-4
    assert o.stable


def test_a_stuck_face_makes_a_continuum_and_the_cold_orbit_is_the_transients_member(transient):
    """The left face sticks throughout, so its sticking offset is free: two multipliers exactly 1 (n_neutral = 2),
    a continuum of exact orbits. The transient from the linear start settles on one member when the left face
    slips for the last time (revolution 201 with friction events located, measured; 246 with the plain step); the
    cold shot watches the conserved levels and shoots once they stop drifting, so it lands on that member: 1X-5X
    equal ``simulate --steady``'s to 1e-4 (issue 18 must-show; measured 5.8e-6), and the transient it ran is at
    least those 201 revolutions.

    The right face slips throughout the period (no switch): its slip speed dips to 4.8e-6 m/s, above w_reg, and
    rises again (measured at 512 steps per revolution with events located, and with the plain step at w_stick
    1e-6 and 3e-6). The plain step with its default low-speed stick trial (w_stick = 1e-5 m/s, above that dip) had
    stuck it for 3.3 % of the revolution, 4 to 12 switches per period at 256 to 1 024 steps per revolution: an
    artefact of the trial's threshold, which the located step keeps only below w_reg
    (rotor/dynamics/friction_events.py)."""
    o = orbit(SCENE, SPEED)
    assert o.converged and o.residual < 1e-9 and o.period_revs == 1
    assert o.floquet.n_neutral == 2 and o.stable
    assert o.events == 0 and o.as_dict()["stick_share_right_face"] == 0.0
    assert o.shooting.settled and o.transient_revs >= 201
    assert _worst(o, transient) < 1e-4
    d = o.as_dict()
    assert d["stable"] is True and len(d["multipliers"]) == o.shooting.state.size


def test_a_minimum_norm_newton_before_the_levels_settle_lands_on_another_member(transient):
    """The same point with the old rule (Newton accepted as soon as it converges, its steps minimum-norm across the
    continuum): an exact orbit of another member, whose harmonics differ from the transient's by more than 1e-4
    (measured 3.0e-3 with friction events located; 3.3e-4 with the plain step), its 1X by less than 1e-3
    (measured 1.9e-6). With events located its transient ran past the left face's last slip (317 revolutions
    against 201), so the other member comes from the minimum-norm steps, not from shooting before the levels
    settle (with the plain step: 195 revolutions against 246)."""
    from rotor.periodic import shooting as sh

    level_step, settle = sh.level_step, sh._settle
    try:
        sh.level_step = lambda J, rhs, rcond, back=None: (*sh.min_norm_step(J, rhs, rcond), np.zeros((len(rhs), 0)))
        sh._settle = lambda run, res, opts: res
        o = orbit(SCENE, SPEED)
    finally:
        sh.level_step, sh._settle = level_step, settle
    assert o.converged and o.transient_revs > 201
    h = transient.harmonics("v")
    one_x = max(abs(o.velocity_amplitudes_mm_s_1X_to_5X[n][0] * 1e-3 / h[0, j] - 1)
                for j, n in enumerate(transient.channels))
    assert one_x < 1e-3 and _worst(o, transient) > 1e-4


def test_cascade_warm_starts_each_speed_from_the_previous_orbit():
    """Three speeds where the faces keep their modes over the period (a smooth map): every orbit
    converges; after the first, each starts from its neighbour with 2 transient revolutions only."""
    from rotor.studies.orbit import cascade

    res = cascade(SCENE, [11400.0, 11700.0, 12000.0])
    assert all(r.converged and r.period_revs == 1 for r in res)
    assert res[0].transient_revs >= 16 and all(r.transient_revs == 2 for r in res[1:])
    assert all(r.switch_free and r.stable for r in res)


def test_a_small_orbit_on_a_large_offset_converges_at_the_noise_floor():
    """300 rpm: a 0.24 µm orbit on a 1 mm misalignment offset, 4 480 steps per revolution (contact step
    limit). Newton stalls near 2e-9 of the orbit scale, above tol (1e-9) and below accept_tol (1e-7): the
    orbit is accepted and its residual reported; both faces stick throughout (4 neutral multipliers)."""
    o = orbit(SCENE, 300.0, period_revs=1)
    assert o.converged and o.steps_per_rev > 256
    assert o.residual < 1e-7
    assert o.floquet.n_neutral == 4


def test_bad_requests_are_refused_in_one_line():
    from contact.errors import InputError
    from rotor.studies.orbit import branch

    with pytest.raises(InputError, match="speed_rpm"):
        orbit(SCENE, 0.0)
    with pytest.raises(InputError, match="period_revs"):
        orbit(SCENE, 10500.0, period_revs=9)
    with pytest.raises(InputError, match="rpm_end"):
        branch(SCENE, 10500.0, 10500.0)
    with pytest.raises(InputError, match="rpm_start"):
        branch(SCENE, -1.0, 10500.0)


@pytest.mark.slow
def test_an_unstable_orbit_the_located_transients_miss_is_reached_from_the_step_grid_orbit():
    """paper-table4 without friction at 12 000 rpm (256 steps per revolution): the located map's transients find no
    orbit in 2 000 revolutions; the step-grid map's search finds an unstable period-1 orbit and Newton on the
    located map converges from it (rotor.studies.orbit._from_step_grid_orbit). Expected: the located map maps the
    orbit onto itself (1e-9 of its scales) and its largest multiplier equals that of central differences of the
    located map at 1e-7 of the block scales (rotor.periodic.period_flow.monodromy_fd) to 1e-4 (measured 21.05
    both, agreement 5e-7 of the monodromy)."""
    import math
    from rotor.periodic.period_flow import advance, make_flow, monodromy_fd
    from rotor.studies.steady_state import point_system

    o = orbit("paper-table4", 12000.0, mu=0.0, steps_per_rev=256)
    assert o.converged and o.period_revs == 1 and not o.stable
    sh = o.shooting
    system = point_system("paper-table4", 12000.0, mu=0.0)[2]
    flow = make_flow(system, 2 * math.pi / (system.omega_rad_s * 256))
    assert flow.handle.options.locate_events
    r = advance(flow, sh.state, sh.t0_s, 256, sh.modes, jacobian=False)
    assert np.abs((r.state - sh.state) / sh.scales).max() < 1e-9
    fd = np.abs(np.linalg.eigvals(monodromy_fd(flow, sh.state, sh.t0_s, 256, sh.modes, rel_step=1e-7))).max()
    assert abs(np.abs(o.floquet.multipliers).max() / fd - 1) < 1e-4


def test_the_speeds_a_restart_leaves_uncovered_start_at_the_farthest_reached():
    """``uncovered_rpm``: after a run back from a fold (Table 4's branch, reports/published/perf-branch-switches.md
    at b139996: folded at 16 929.8 rpm, ran back to 16 662.6, jumped to 16 947.1) the speeds no orbit covers are
    16 929.8-16 947.1 rpm, not the 284.5 rpm of ``skipped_rpm``; a restart landing within the speeds covered
    leaves none; downwards the same mirrored."""
    from rotor.studies.orbit import uncovered_rpm

    assert uncovered_rpm([16800.0, 16929.8, 16662.6], 16947.1, 1.0) == [16929.8, 16947.1]
    assert uncovered_rpm([16800.0, 16929.8, 16662.6], 16900.0, 1.0) is None
    assert uncovered_rpm([3000.0, 2400.0, 2600.0], 2350.0, -1.0) == [2400.0, 2350.0]
