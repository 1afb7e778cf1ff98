"""The period map with friction events located inside the step (rotor.dynamics.period_map_events): its monodromy
through stick onsets, releases and slip reversals against central differences of the located map itself.

The oscillator is Den Hartog's (1931) of ``dynamics_standin.friction_body`` (ω_n = 62.8 rad/s, P0 = 1 N, ζ = 0.1):
F = 0.2 N at ω = 50 rad/s moves without stops (two slip reversals per period, located); F = 0.7 N at ω = 30 rad/s
sticks and slips (stick onsets and releases in every period). 200 steps per period, one period from the state after
40 periods. Expected values: central differences of the located map, each state component perturbed by 1e-7 of
its block's largest magnitude over the period (their truncation measured below 1e-7 here)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from dynamics_standin import friction_body
from rotor.dynamics.period_map import period_map, period_map_setup
from rotor.dynamics.system import NewmarkOptions

NPER = 200


def _settled(F, omega, locate=True):
    s = friction_body(F=F, P0=1.0, omega=omega, zeta=0.1)
    pm = period_map_setup(s, 2 * math.pi / omega / NPER, NewmarkOptions(tol=1e-13, locate_events=locate),
                          check_step=False)
    r = period_map(pm, np.zeros(2 * pm.nr), 0.0, 40 * NPER, modes0=(0, 0), jacobian=False)
    return pm, r


def _fd(pm, r, scales, rel=1e-7):
    M = np.zeros((r.state.size, r.state.size))
    for j in range(r.state.size):
        e = np.zeros_like(r.state)
        e[j] = rel * scales[j]
        a, b = (period_map(pm, r.state + d, r.t, NPER, modes0=r.modes, jacobian=False).state for d in (e, -e))
        M[:, j] = (a - b) / (2 * e[j])
    return M


@pytest.mark.parametrize("F,omega,stops", [(0.2, 50.0, False), (0.7, 30.0, True)], ids=["non-stop", "stick-slip"])
def test_located_monodromy_equals_central_differences_through_events(F, omega, stops):
    pm, r = _settled(F, omega)
    res = period_map(pm, r.state, r.t, NPER, modes0=r.modes, record_every=1)
    tr = res.trajectory
    dm = np.diff(tr.modes[:, 0].astype(int))
    if stops:
        assert np.any(dm > 0) and np.any(dm < 0)                 # stick onsets and releases in the period
    else:
        v = tr.v[:, 0]
        assert np.count_nonzero(v[:-1] * v[1:] < 0) == 2 and res.events == 0   # two reversals, no stop
    assert res.replay_mismatch < 1e-10                          # the differenced event steps are the run's own
    nr = pm.nr
    scales = np.concatenate([np.full(nr, np.abs(tr.q).max()), np.full(nr, np.abs(tr.v).max())])
    Ms, Mf = (m * scales[None, :] / scales[:, None] for m in (res.monodromy, _fd(pm, r, scales)))
    assert np.abs(Ms - Mf).max() / np.abs(Mf).max() < 1e-6
    # the event-time derivatives matter: the plain map's monodromy at the same state is another matrix, a thousand
    # times further than the agreement above (measured 0.19 non-stop, 7.2e-3 stick-slip; 0.62 stick-slip before the
    # releases were located and slow slips held, when the located map's orbit carried the regularisation's deficit)
    plain = period_map(period_map_setup(pm.system, pm.dt, NewmarkOptions(tol=1e-13, locate_events=False),
                                        check_step=False), r.state, r.t, NPER, modes0=r.modes)
    assert np.abs(plain.monodromy * scales[None, :] / scales[:, None] - Ms).max() > 1e-3 * np.abs(Mf).max()


# default tier (6 s for the three on an idle machine): the published perf-located-monodromy.md numbers, checked in CI
@pytest.mark.parametrize("rpm", [8400.0, 10500.0, 12000.0])
def test_table4_located_monodromy_through_stick_releases_and_contact_onsets(rpm):
    """Dai et al. (2025) Table 4 rotor, 512 steps per revolution, one period from the state after 60 revolutions from
    the linear one: a stick onset, a release and edge crossings (contact onset and loss, located inside the step) in
    the period. Expected: the Richardson extrapolation of central differences of the located map at 1e-7 and 2e-7 of
    each component's largest magnitude, its convergence checked against the one at 5e-8 and 1e-7 (measured 1.9e-7,
    1.1e-7, 1.1e-7). The located monodromy agrees to 1e-6, the issue's bound (measured 1.2e-7, 6.5e-8, 5.1e-8 with the
    blocks and the ladder of rotor/dynamics/period_map_events.py; 9.9e-7, 2.2e-7, 5.5e-8 before them; 8 400 rpm was
    0.41 before a stop from a creep was located from any start speed, 3.7e-6 with every event step differenced at
    1e-6). Not every Table 4 speed has a smooth map at 1e-7: at 9 600 and
    11 000 rpm these references themselves differ by O(1) (rotor/dynamics/period_map_events.py)."""
    from rotor.dynamics.build import system_from_model
    from rotor.dynamics.initial import linear_initial_state
    from rotor.dynamics.period_map import reduced_state
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene

    n = 512
    scene = load_scene("paper-table4")
    system = system_from_model(assemble(scene), scene, rpm * math.pi / 30.0)
    pm = period_map_setup(system, 2 * math.pi / system.omega_rad_s / n, NewmarkOptions(tol=1e-13, locate_events=True))
    r = period_map(pm, reduced_state(pm, *linear_initial_state(system)), 0.0, 60 * n, jacobian=False)
    res = period_map(pm, r.state, r.t, n, modes0=r.modes, record_every=1)
    tr = res.trajectory
    assert res.replay_mismatch < 1e-9
    dm = np.diff(tr.modes.astype(int), axis=0)
    assert np.any(dm > 0) and np.any(dm < 0)                     # a stick onset and a release
    hl, d0 = 0.5 * pm.params[1], pm.params[0]
    crossings = sum(np.count_nonzero(np.diff(np.sign(np.hypot(tr.u[:, 0] + sg * hl * tr.u[:, 3],
                                                              tr.u[:, 1] - sg * hl * tr.u[:, 2]) - d0)))
                    for sg in (1.0, -1.0))
    assert crossings >= 2                                        # contact onsets and losses
    x = reduced_state(pm, tr.q, tr.v)
    s = np.abs(x).max(axis=0)
    nr = pm.nr
    for part in (slice(0, nr), slice(nr, 2 * nr)):
        s[part] = np.maximum(s[part], 1e-6 * s[part].max())

    def fd(rel):
        M = np.zeros_like(res.monodromy)
        for j in range(r.state.size):
            e = np.zeros_like(r.state)
            e[j] = rel * s[j]
            a, b = (period_map(pm, r.state + d, r.t, n, modes0=r.modes, jacobian=False).state for d in (e, -e))
            M[:, j] = (a - b) / (2 * e[j])
        return M

    def err(M, ref):
        return np.abs((M - ref) * s[None, :] / s[:, None]).max() / np.abs(ref * s[None, :] / s[:, None]).max()

    F = {rel: fd(rel) for rel in (2e-7, 1e-7, 5e-8)}
    ref, ref2 = (4 * F[1e-7] - F[2e-7]) / 3, (4 * F[5e-8] - F[1e-7]) / 3
    assert err(ref, ref2) < 5e-7                                 # the reference converged
    assert err(res.monodromy, ref) < 1e-6


def test_held_step_carried_equals_its_central_differences():
    """Each held step of Den Hartog's stick-slip period (a slow slip held at Coulomb's force along its start velocity,
    or a face at rest held at μN; rotor/dynamics/friction_events.py, "Slow slips") carried analytically
    (rotor.dynamics.period_map_kernels.carry with the held forces' derivative) against the same step's central
    differences from its start (p, v, a) (rotor.dynamics.period_map_events._step_jacobian, Richardson-extrapolated).
    Expected: the differences, to 1e-6 of the largest scaled entry (measured 1.1e-8 over the 18 held slow slips); a
    carry that left out ∂f/∂w of the held force misses them by O(1) (measured 0.97)."""
    from rotor.dynamics import period_map_events as pme
    from rotor.dynamics.period_map_kernels import carry

    pm, r = _settled(0.7, 30.0)
    res = period_map(pm, r.state, r.t, NPER, modes0=r.modes, jacobian=False, record_every=1)
    tr = res.trajectory
    nr = pm.nr
    rec_p, rec_v, rec_a = tr.q @ pm.T, tr.v @ pm.T, tr.a @ pm.T
    block = np.repeat([np.abs(x).max() for x in (rec_p, rec_v, rec_a)], nr)
    scales = np.maximum(np.concatenate([np.ptp(rec_p, 0), np.ptp(rec_v, 0), np.ptp(rec_a, 0)]), 1e-3 * block)
    _, held = pme._split_steps(pm, tr, rec_p, rec_v, rec_a, scales)
    steps = np.flatnonzero(held[:, 0] == 1)
    assert steps.size >= 2                                       # slow slips held in the period (measured 18)
    pre, o = pm.prepared, pm.options
    worst, worst_without = 0.0, 0.0
    for n in steps:
        J = {}
        for label, h in (("with", held[n:n + 2]), ("without", np.zeros((2, 2), dtype=np.int64))):
            Spv = np.hstack([np.eye(2 * nr), np.zeros((2 * nr, nr))])
            Sa = np.hstack([np.zeros((nr, 2 * nr)), np.eye(nr)])
            carry(np.ascontiguousarray(rec_p[n:n + 2]), np.ascontiguousarray(rec_v[n:n + 2]),
                  np.ascontiguousarray(tr.modes[n:n + 2].astype(np.int64)), Spv, Sa, pm.dt, o.beta, o.gamma, pm.AK,
                  pm.AD, pm.MK, pm.MD, pre.Bt, pre.W, pre.S, pre.WM, pre.SM, pre.P, pre.limits, pre.a1, True,
                  pm.params, o.w_reg, bool(o.consistent_stick_onset), np.ascontiguousarray(h),
                  np.ascontiguousarray(tr.face_force[n:n + 2], dtype=float), np.zeros((nr, 3 * nr)))
            J[label] = np.vstack([Spv, Sa])
        x0 = np.concatenate([rec_p[n], rec_v[n], rec_a[n]])
        D = pme._step_jacobian(pm, x0, tr.modes[n], tr.face_force[n], tr.t[n], scales)[0]
        size = np.abs(D * scales[None, :] / scales[:, None]).max()
        worst = max(worst, np.abs((J["with"] - D) * scales[None, :] / scales[:, None]).max() / size)
        worst_without = max(worst_without, np.abs((J["without"] - D) * scales[None, :] / scales[:, None]).max() / size)
    assert worst < 1e-6
    assert worst_without > 1e3 * worst


# benchmarks/bench_monodromy_ladder.py's states: T/256 in the default run, T/2240 slow
@pytest.mark.parametrize("rpm", [7000.0, 9000.0, 12000.0])
def test_ladder_level_by_level_is_as_accurate_as_the_whole_ladder(rpm, monkeypatch):
    """Dai et al. (2025) Table 4 rotor, production options, one revolution (T/256) from the state 24 revolutions after
    the linear start (contact in about half of the period, every onset and loss differenced): the event steps' ladder
    evaluated level by level (rotor/dynamics/period_map_events.py, ``_ladder`` and ``_refine``) against every level
    for every column (``PROGRESSIVE`` False). Expected: the Richardson extrapolation of central differences of the
    whole map at 1e-7 and 2e-7 of each component's largest magnitude (rotor/dynamics/monodromy_check.py), converged to
    5e-7 against the one at 5e-8 and 1e-7. Both monodromies within the issue's 1e-6 of it, the level-by-level one
    no further from it than the whole ladder's plus 1e-7, with at most 0.9 of the replays (measured with
    ``REFINE_TOL`` 1e-8: 0.74 at 7 000 rpm, 0.85 at 9 000 rpm, as in reports/published/perf-monodromy-ladder.md;
    0.57 and 0.72 with 1e-7), the ladder by components (``ALONG_SENSITIVITIES`` False); the default route, level by
    level along the carried sensitivities, within 1e-6 too with at most 1.05 times its replays (measured at T/256:
    1.025 at 7 000 rpm, 1.003 at 9 000, 0.79 at 12 000). The contact steps are differenced here (``EXACT_CONTACT``
    False), as before their exact derivative (rotor/dynamics/contact_step_derivative.py): the ladder still
    differences the friction events and any step that route declines."""
    _check_ladder_routes(rpm, 256, monkeypatch)


@pytest.mark.slow
@pytest.mark.parametrize("rpm", [7000.0, 9000.0, 12000.0])
def test_ladder_level_by_level_is_as_accurate_as_the_whole_ladder_at_2240_steps(rpm, monkeypatch):
    """As :func:`test_ladder_level_by_level_is_as_accurate_as_the_whole_ladder`, at T/2240."""
    _check_ladder_routes(rpm, 2240, monkeypatch)


def _check_ladder_routes(rpm, steps, monkeypatch):
    from rotor.dynamics import period_map_events as pme
    from rotor.dynamics.initial import linear_initial_state
    from rotor.dynamics.monodromy_check import central_differences, scaled_error, state_scales
    from rotor.dynamics.period_map import reduced_state
    from rotor.studies.steady_state import point_system

    _, _, system = point_system("paper-table4", rpm)
    pm = period_map_setup(system, 2 * math.pi / system.omega_rad_s / steps)
    r = period_map(pm, reduced_state(pm, *linear_initial_state(system)), 0.0, 24 * steps, jacobian=False)
    inner, M, replays = pme._differences, {}, {}
    monkeypatch.setattr(pme, "EXACT_CONTACT", False)
    monkeypatch.setattr(pme, "ALONG_SENSITIVITIES", False)     # the ladder by components, as the report measured
    for progressive in (False, True, "along"):
        count = [0]

        def counting(*args, count=count):
            count[0] += 2 * len(args[7]) * len(args[8]) * int(args[6])
            return inner(*args)

        monkeypatch.setattr(pme, "_differences", counting)
        monkeypatch.setattr(pme, "PROGRESSIVE", bool(progressive))
        monkeypatch.setattr(pme, "ALONG_SENSITIVITIES", progressive == "along")
        M[progressive] = period_map(pm, r.state, r.t, steps, modes0=r.modes).monodromy
        replays[progressive] = count[0]
    monkeypatch.setattr(pme, "_differences", inner)
    plain = period_map(pm, r.state, r.t, steps, modes0=r.modes, jacobian=False, record_every=1)
    s = state_scales(pm, plain.trajectory)
    ref, check = central_differences(pm, r.state, r.t, steps, r.modes, s)
    assert scaled_error(ref, check, s) < 5e-7                     # the reference converged
    whole, progressive = scaled_error(M[False], ref, s), scaled_error(M[True], ref, s)
    assert whole < 1e-6 and progressive < 1e-6
    assert progressive <= whole + 1e-7
    assert replays[True] < 0.9 * replays[False]
    along = scaled_error(M["along"], ref, s)
    print(rpm, steps, f"whole {whole:.1e} level by level {progressive:.1e} along the sensitivities {along:.1e}",
          "replays", replays)
    assert along < 1e-6 and replays["along"] <= 1.05 * replays[True]
