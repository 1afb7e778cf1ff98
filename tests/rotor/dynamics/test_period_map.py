"""The production scheme's period map and its monodromy (rotor.dynamics.period_map).

Checked against: (1) production itself (the map's end state is simulate_production's); (2) a
central finite-difference monodromy of the same map (linear rotors, and the Table 4 scene at
10 500 rpm with stuck, slipping and contacting support, and through stick/slip switches; the
frictionless clearance Jeffcott rotor on its exact discrete circular orbit); (3) on a linear rotor, the closed form of
the average-acceleration Newmark map: the trapezoidal rule's Cayley map
``((1 + λΔt/2)/(1 − λΔt/2))^N`` of the first-order system's eigenvalues λ (Hairer & Wanner 1996,
stability function of the trapezoidal rule), which tends to ``exp(λT)`` at second order in Δt.
"""
import dataclasses
import math

import numpy as np
import pytest

from contact.errors import InputError
from rotor.dynamics.build import system_from_model
from rotor.dynamics.initial import linear_initial_state
from rotor.dynamics.period_map import full_state, period_map, period_map_setup, reduced_state
from rotor.dynamics.production import simulate_production
from rotor.dynamics.system import NewmarkOptions
from rotor.model.assembly import assemble
from rotor.model.scene import load_scene

RPM = 10500.0
STEPS_PER_REV = 512
# Newton converged to round-off, so differences of maps are clean; the plain step (switches on step boundaries,
# the map these tests differentiate; the located map's monodromy is tested in test_period_map_events.py)
TIGHT = NewmarkOptions(tol=1e-13, locate_events=False)


def _system(scene="paper-table4", rpm=RPM, **over):
    sc = load_scene(scene)
    return system_from_model(assemble(sc), sc, rpm * math.pi / 30.0, **over)


def _linear(system):
    """The rotor with the loose support and the coupling removed: a linear system."""
    return dataclasses.replace(system, support=None, coupling=None)


def _first_order_eigenvalues(pm):
    s = pm.reduced
    T = pm.T
    Mr, Dr, Kr = T.T @ s.M @ T, T.T @ s.D @ T, T.T @ s.K @ T
    n = pm.nr
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(Mr, Kr), -np.linalg.solve(Mr, Dr)]])
    return np.linalg.eigvals(A)


def _fd_monodromy(pm, x0, t0, n, modes0, rel):
    """Central differences of the map, each component perturbed by ``rel`` times its scale."""
    scale = _scales(pm, x0, t0, n, modes0)
    M = np.zeros((x0.size, x0.size))
    events = 0
    for j in range(x0.size):
        e = np.zeros_like(x0)
        e[j] = rel * scale[j]
        a = period_map(pm, x0 + e, t0, n, modes0=modes0, jacobian=False)
        b = period_map(pm, x0 - e, t0, n, modes0=modes0, jacobian=False)
        events += a.events + b.events
        M[:, j] = (a.state - b.state) / (2 * e[j])
    return M, scale, events


def _scales(pm, x0, t0, n, modes0):
    """Largest magnitude of each reduced state component along the run (floored at 1e-6 of the largest)."""
    tr = period_map(pm, x0, t0, n, modes0=modes0, jacobian=False, record_every=1).trajectory
    x = reduced_state(pm, tr.q, tr.v)
    s = np.abs(x).max(axis=0)
    nr = pm.nr
    for part in (slice(0, nr), slice(nr, 2 * nr)):
        s[part] = np.maximum(s[part], 1e-6 * s[part].max())
    return s


def _scaled_error(M, Mfd, s):
    """max |D⁻¹(M − M_fd)D| / max |D⁻¹ M D|, D = diag(scales): the monodromy in scaled coordinates."""
    Ms, Mf = M * s[None, :] / s[:, None], Mfd * s[None, :] / s[:, None]
    return float(np.abs(Ms - Mf).max() / np.abs(Ms).max())


def _assert_same_state(pm, x, ref):
    """Equal to round-off: positions and velocities each within 1e-14 of their largest component (the
    recorded full coordinates ``q = T p`` are products of differently shaped arrays, so not bit for bit)."""
    for part in (slice(0, pm.nr), slice(pm.nr, 2 * pm.nr)):
        assert np.abs(x[part] - ref[part]).max() <= 1e-14 * np.abs(ref[part]).max()


# --------------------------------------------------------------------------- linear rotor


@pytest.fixture(scope="module")
def linear_map():
    system = _linear(_system())
    dt = 2 * math.pi / (RPM * math.pi / 30.0) / STEPS_PER_REV
    pm = period_map_setup(system, dt)
    q, v = linear_initial_state(system)
    return system, pm, reduced_state(pm, q, v)


def test_end_state_is_production_end_state_linear(linear_map):
    system, pm, x0 = linear_map
    r = period_map(pm, x0, 0.013, STEPS_PER_REV)
    q, v = full_state(pm, x0)
    tr = simulate_production(system, pm.dt, STEPS_PER_REV, q, v, t0=0.013, record_every=STEPS_PER_REV)
    _assert_same_state(pm, r.state, reduced_state(pm, tr.q[-1], tr.v[-1]))
    assert r.events == 0 and r.t == pytest.approx(0.013 + STEPS_PER_REV * pm.dt, rel=1e-14)


def test_linear_monodromy_equals_finite_differences(linear_map):
    _, pm, x0 = linear_map
    r = period_map(pm, x0, 0.0, STEPS_PER_REV)
    Mfd, s, _ = _fd_monodromy(pm, x0, 0.0, STEPS_PER_REV, None, 1e-3)
    assert _scaled_error(r.monodromy, Mfd, s) < 1e-6


def test_linear_multipliers_are_the_cayley_map_of_the_eigenvalues(linear_map):
    """Average acceleration (β = 1/4, γ = 1/2) is the trapezoidal rule: per step λ ↦ (1 + λΔt/2)/(1 − λΔt/2)."""
    _, pm, x0 = linear_map
    assert (pm.options.beta, pm.options.gamma) == (0.25, 0.5)
    mono = period_map(pm, x0, 0.0, STEPS_PER_REV).monodromy
    mult = np.linalg.eigvals(mono)
    lam = _first_order_eigenvalues(pm)
    z = ((1 + lam * pm.dt / 2) / (1 - lam * pm.dt / 2)) ** STEPS_PER_REV
    assert mult.size == z.size
    for zz in z:  # every predicted multiplier is one of the monodromy's, and vice versa
        assert np.abs(mult - zz).min() <= 1e-8 * max(abs(zz), 1e-3)
    for mm in mult:
        assert np.abs(z - mm).min() <= 1e-8 * max(abs(mm), 1e-3)


def test_linear_multipliers_tend_to_exp_lambda_T_at_second_order():
    system = _linear(_system())
    period = 2 * math.pi / (RPM * math.pi / 30.0)
    errors = []
    for n in (256, 512, 1024):
        pm = period_map_setup(system, period / n)
        lam = _first_order_eigenvalues(pm)
        low = lam[np.argsort(np.abs(lam))[:8]]         # the lowest modes: |λ|Δt ≤ 0.1
        assert np.abs(low).max() * period / n < 0.1
        mult = np.linalg.eigvals(period_map(pm, np.zeros(2 * pm.nr), 0.0, n).monodromy)
        errors.append(max(np.abs(mult - np.exp(v * period)).min() for v in low))
    ratios = [errors[0] / errors[1], errors[1] / errors[2]]
    assert all(3.8 < r < 4.2 for r in ratios), (errors, ratios)


def test_condensed_linear_rotor_maps_and_recovers_full_state():
    """verify-jeffcott: massless shaft, condensed to the disk; the full state maps round trip."""
    system = _system("verify-jeffcott", rpm=900.0)
    dt = 2 * math.pi / (900.0 * math.pi / 30.0) / 128
    pm = period_map_setup(system, dt)
    assert pm.condensed is not None and pm.nr < system.n
    q, v = linear_initial_state(system, t0=0.0)
    x0 = reduced_state(pm, q, v)
    qq, vv = full_state(pm, x0, t=0.0)
    assert np.allclose(qq, q, rtol=0, atol=1e-12 * np.abs(q).max())
    assert np.allclose(vv, v, rtol=0, atol=1e-12 * np.abs(v).max())
    r = period_map(pm, x0, 0.0, 128, record_every=32)
    assert r.trajectory.q.shape == (5, system.n)
    # one Newton step on the periodicity residual (exact for a linear map) finds the scheme's periodic
    # orbit, within the O(Δt²) frequency warping of the exact one (Δt = T/128: (2π/128)²/12 = 2e-4)
    xp = x0 + np.linalg.solve(np.eye(x0.size) - r.monodromy, r.state - x0)
    assert np.abs(period_map(pm, xp, 0.0, 128).state - xp).max() <= 1e-10 * np.abs(xp).max()
    assert 1e-6 < np.abs(xp - x0).max() / np.abs(x0).max() < 1e-3
    Mfd, s, _ = _fd_monodromy(pm, x0, 0.0, 128, None, 1e-3)
    assert _scaled_error(r.monodromy, Mfd, s) < 1e-6


# --------------------------------------------------------------------------- Table 4 scene


def _table4_window(n_steps, **over):
    """``(pm, x0, t0, modes0)`` at 10 500 rpm, 20 revolutions from the linear start, moved to the
    start of the longest run of constant face modes in the next revolution."""
    system = _system(**over)
    dt = 2 * math.pi / system.omega_rad_s / STEPS_PER_REV
    pm = period_map_setup(system, dt, TIGHT)
    q, v = linear_initial_state(system)
    r = period_map(pm, reduced_state(pm, q, v), 0.0, 20 * STEPS_PER_REV, jacobian=False)
    tr = period_map(pm, r.state, r.t, STEPS_PER_REV, modes0=r.modes, jacobian=False, record_every=1).trajectory
    m = tr.modes.astype(int)
    cuts = np.r_[0, np.flatnonzero(np.any(np.diff(m, axis=0) != 0, axis=1)) + 1, len(m)]
    i = int(np.argmax(np.diff(cuts)))
    run = cuts[i + 1] - cuts[i]
    assert run >= n_steps + 1
    s0 = cuts[i] + min(2, run - n_steps - 1)   # a little clear of the last switch when there is room
    return pm, reduced_state(pm, tr.q[s0], tr.v[s0]), float(tr.t[s0]), tuple(m[s0])


@pytest.mark.parametrize("case, over, n_steps, want_modes, rel", [
    ("both faces stuck, whole revolution", dict(mu=10.0), STEPS_PER_REV, (1, 1), 1e-5),
    ("one face stuck, one slipping", {}, 100, (0, 1), 1e-7),
    ("both faces slipping", dict(mu=0.01, clearance_m=5e-5), 100, (0, 0), 1e-6),
    ("ring in contact with the clearance", dict(clearance_m=1e-6), 100, None, 1e-7),
    ("tilt ignored (one face), slipping, contact", dict(clearance_m=1e-6, tilt_ignored=True, mu=0.01), 100, (0, 0),
     1e-7),
])
def test_table4_monodromy_equals_finite_differences(case, over, n_steps, want_modes, rel):
    """Away from stick/slip switches the map is smooth; its finite-difference error falls as rel²
    (measured 1e-5 → 1e-7: 1e-3, 1e-5, 1e-7 in the contact case), so rel is the smallest step above
    the Newton noise."""
    pm, x0, t0, modes0 = _table4_window(n_steps, **over)
    if want_modes is not None:
        assert modes0 == want_modes, case
    r = period_map(pm, x0, t0, n_steps, modes0=modes0, record_every=1)
    assert r.events == 0 and r.unconverged_steps == 0
    if "contact" in case:
        assert np.abs(r.trajectory.f_contact[:, :2]).max() > 1.0
    Mfd, s, events = _fd_monodromy(pm, x0, t0, n_steps, modes0, rel)
    assert events == 0
    assert _scaled_error(r.monodromy, Mfd, s) < 1e-6, case


def test_table4_end_state_is_production_end_state():
    system = _system()
    dt = 2 * math.pi / system.omega_rad_s / STEPS_PER_REV
    pm = period_map_setup(system, dt)
    x0 = reduced_state(pm, *linear_initial_state(system))
    q, v = full_state(pm, x0)
    r = period_map(pm, x0, 0.0, STEPS_PER_REV, record_every=STEPS_PER_REV // 4)
    tr = simulate_production(system, dt, STEPS_PER_REV, q, v, record_every=STEPS_PER_REV // 4)
    assert r.events > 0          # a revolution with stick/slip switches: the stepping is production's
    _assert_same_state(pm, r.state, reduced_state(pm, tr.q[-1], tr.v[-1]))
    assert np.array_equal(r.modes, tr.modes[-1]) and np.array_equal(r.phi_face, tr.face_force[-1])
    assert np.allclose(r.trajectory.q, tr.q, rtol=0, atol=1e-14 * np.abs(tr.q).max()) and np.array_equal(r.trajectory.modes, tr.modes)
    every = simulate_production(system, dt, STEPS_PER_REV, q, v, record_every=1).modes.astype(int)
    assert r.events == np.count_nonzero(np.diff(every, axis=0)) + np.count_nonzero(every[0] != 1)


def test_bad_inputs_are_refused(linear_map):
    _, pm, x0 = linear_map
    with pytest.raises(InputError, match="state0"):
        period_map(pm, x0[:-1], 0.0, 4)
    with pytest.raises(InputError, match="n_steps"):
        period_map(pm, x0, 0.0, 0)
    with pytest.raises(InputError, match="dt_s"):
        period_map_setup(pm.system, -1.0)


# --------------------------------------------------------------------------- Jeffcott rotor in a clearance ring


@pytest.mark.parametrize("speed_rad_s, guess_m", [(500.0, 3e-5), (680.0, 2e-4)])
def test_jeffcott_circular_orbit_is_a_fixed_point_and_its_monodromy_equals_finite_differences(speed_rad_s, guess_m):
    """The frictionless clearance Jeffcott rotor (rotor.periodic.jeffcott) whirls on an exact circle of the
    scheme: radius from the closed form with the trapezoidal rule's warped frequency Ω' = Ω tan(π/N)/(π/N),
    complex amplitude X = m e Ω² / (k − m Ω'² + f(r)/r + i c Ω'). The period map returns it, and its monodromy
    (contact law's Jacobian through every step) equals central differences."""
    from rotor.periodic.jeffcott import JeffcottParams, closed_form_radius, contact_force_N, jeffcott_system

    p, n = JeffcottParams(), 256
    r = closed_form_radius(p, speed_rad_s, guess_m, steps_per_rev=n)
    assert r > 2 * p.clearance_m                                       # in contact all round
    wp = speed_rad_s * math.tan(math.pi / n) / (math.pi / n)
    f = float(contact_force_N(p, r)[0])
    X = p.mass_kg * p.eccentricity_m * speed_rad_s ** 2 / (p.stiffness_N_m - p.mass_kg * wp ** 2 + f / r
                                                            + 1j * p.damping_N_s_m * wp)
    q, v = np.array([X.real, X.imag, 0.0, 0.0]), np.array([(1j * wp * X).real, (1j * wp * X).imag, 0.0, 0.0])
    pm = period_map_setup(jeffcott_system(p, speed_rad_s), 2 * math.pi / speed_rad_s / n, TIGHT)
    x0 = reduced_state(pm, q, v)
    res = period_map(pm, x0, 0.0, n, modes0=(0, 0))
    assert res.events == 0
    assert np.abs(res.state - x0).max() <= 1e-12 * np.abs(x0).max()
    Mfd, s, events = _fd_monodromy(pm, x0, 0.0, n, (0, 0), 1e-6)
    assert events == 0
    assert _scaled_error(res.monodromy, Mfd, s) < 1e-6


def test_warm_up_compiles_the_signature_real_runs_use(linear_map):
    """warm_up's argument types are those of a real run: one signature after both, with and without support."""
    from rotor.dynamics import period_map as pmod
    from rotor.dynamics.period_map_kernels import sensitivity_pass

    info = pmod.warm_up()
    assert info["compile_s"] >= 0.0 and isinstance(info["from_cache"], bool)
    _, pm, x0 = linear_map
    period_map(pm, x0, 0.0, 4)
    system = _system()
    pm4 = period_map_setup(system, 2 * math.pi / system.omega_rad_s / STEPS_PER_REV)
    period_map(pm4, reduced_state(pm4, *linear_initial_state(system)), 0.0, 4)
    assert len(sensitivity_pass.signatures) == 1, sensitivity_pass.signatures


def test_table4_monodromy_through_stick_slip_switches_equals_finite_differences():
    """Switches fall on step boundaries in this scheme, so while a perturbation leaves every switch in its
    step the map is smooth and the monodromy (event steps differentiated with the modes they end in, the
    stick-onset restart included) is its exact derivative; measured scaled error 2.7e-5 at rel 1e-7
    (differencing truncation), 1.1e-6 at 1e-8."""
    system = _system()
    n = STEPS_PER_REV
    pm = period_map_setup(system, 2 * math.pi / system.omega_rad_s / n, TIGHT)
    r = period_map(pm, reduced_state(pm, *linear_initial_state(system)), 0.0, 20 * n, jacobian=False)
    res = period_map(pm, r.state, r.t, n, modes0=r.modes, record_every=1)
    assert res.events >= 2
    modes = res.trajectory.modes
    assert np.any(np.diff(modes[:, 0].astype(int)) > 0) or np.any(np.diff(modes[:, 1].astype(int)) > 0)  # an onset
    s = _scales(pm, r.state, r.t, n, tuple(r.modes))
    Mfd = np.zeros_like(res.monodromy)
    for j in range(r.state.size):
        e = np.zeros_like(r.state)
        e[j] = 1e-8 * s[j]
        a, b = (period_map(pm, r.state + d, r.t, n, modes0=r.modes, jacobian=False, record_every=1) for d in (e, -e))
        assert np.array_equal(a.trajectory.modes, modes) and np.array_equal(b.trajectory.modes, modes)
        Mfd[:, j] = (a.state - b.state) / (2 * e[j])
    assert _scaled_error(res.monodromy, Mfd, s) < 1e-5
