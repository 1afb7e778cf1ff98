"""Verification of the Newmark/constraint integrators (issue 7, "Must show" 1).

Sources of the expected values:
* Den Hartog, J. P. (1931), Forced vibrations with combined Coulomb and viscous friction,
  Trans. ASME APM-53-9: exact steady state built from closed-form half cycles
  (``dynamics_denhartog.py``, no time stepping).
* Newmark (1959) average acceleration: second-order accurate, conserves the energy of
  undamped linear (also gyroscopic) systems exactly; checked against the exact modal
  (state-space eigen) solution of the same linear rotor.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from dynamics_denhartog import DenHartog
from dynamics_standin import friction_body
from rotor.dynamics import constraints as cons
from rotor.dynamics.energy import energy_balance
from rotor.dynamics.reference import simulate_reference
from rotor.dynamics.system import HarmonicForce, NewmarkOptions, RotorSystem
from rotor.dynamics.production import simulate_production


def _den_hartog_case(F, P0, omega):
    s = friction_body(F=F, P0=P0, omega=omega)
    m, k, c = s.M[0, 0], s.K[0, 0], s.C[0, 0]
    return s, DenHartog(m, c, k, F, P0, omega)


def _last_period_stats(tr, T, dt):
    nper = int(round(T / dt))
    y = tr.q[-nper:, 0]
    stuck = np.all(tr.modes[-nper:] == cons.STICK, axis=1)
    return 0.5 * (y.max() - y.min()), stuck.mean() * T / 2  # amplitude, stick time per half cycle


@pytest.mark.parametrize("locate", [False, True], ids=["plain", "events located"])
@pytest.mark.parametrize("F,P0,omega,regime", [(0.2, 1.0, 50.0, "continuous slip"), (0.6, 1.0, 25.0, "stick-slip")])
def test_den_hartog_steady_state(F, P0, omega, regime, locate):
    """Production scheme from rest to steady state vs Den Hartog's exact amplitude and stop time,
    with the plain step and with friction events located inside the step (NewmarkOptions.locate_events,
    rotor.dynamics.friction_events): the same assertions hold for both."""
    s, dh = _den_hartog_case(F, P0, omega)
    X0, ts, t_stick = dh.steady_state()
    if regime == "continuous slip":
        assert t_stick == 0.0
    else:
        assert t_stick > 0.2 * dh.T / 2  # a genuine stick-slip case
    errs = []
    steps = (400, 800, 1600, 3200)
    for nper_steps in steps:
        dt = dh.T / nper_steps
        # ζ = 0.1: transient < 1e-6 after 40 periods
        tr = simulate_production(s, dt, 40 * nper_steps, check_step=False, options=NewmarkOptions(locate_events=locate))
        amp, stick = _last_period_stats(tr, dh.T, dt)
        errs.append((abs(amp - X0) / X0, abs(stick - t_stick) / (dh.T / 2)))
        assert np.abs(tr.q[:, 1:]).max() < 1e-12 * X0  # motion stays on the forced axis, no tilt
        # no chatter: over the last 20 periods, exactly the physical number of stick/slip switches
        # (2 stops and 2 releases per period in stick-slip, none in continuous slip)
        last = tr.modes[-20 * nper_steps - 1:].astype(int)
        switches = np.abs(np.diff(last, axis=0)).sum(axis=0)
        assert np.all(switches == (4 * 20 if t_stick > 0 else 0)), switches
    errs = np.array(errs)
    # at T/3200: amplitude within 0.1 % and stick time within 0.1 % of a half period
    assert errs[-1, 0] < 1e-3 and errs[-1, 1] < 1e-3, errs
    if t_stick == 0.0:
        # continuous slip: the error falls with the step (log-log slope over the four steps)
        e = errs[:, 0]
        slope = np.polyfit(np.log(steps), np.log(np.maximum(e, 1e-12)), 1)[0]
        assert slope < -0.7, (errs, slope)
    else:
        # stick-slip: the stick time is quantised by the step, at most one step at each end of
        # each stick phase (first order); measured 1.5e-3 .. 3.5e-4 against 5e-3 .. 6.3e-4
        assert np.all(errs[:, 1] <= 2 * (dh.T / np.array(steps)) / (dh.T / 2)), errs
        # the amplitude is within 0.1 % at every step (measured 2.3e-4 .. 3.3e-4; 2.5e-3 at T/400
        # before the consistent stick onset)
        assert np.all(errs[:, 0] < 1e-3), errs
        if locate:
            # with the events located the error is the step's (second order, measured 4.6e-5 .. 7.1e-7; the
            # order is asserted in test_friction_events.py), not the regularisation's
            return
        # plain step: its remaining error is the friction regularisation w_reg, not the step: with w_reg ten
        # times smaller it falls below a quarter (measured 5.5x)
        dt = dh.T / steps[0]
        tr = simulate_production(s, dt, 40 * steps[0], check_step=False,
                                 options=NewmarkOptions(w_reg=1e-7, locate_events=locate))
        amp, _ = _last_period_stats(tr, dh.T, dt)
        assert abs(amp - X0) / X0 < 0.25 * errs[0, 0], (abs(amp - X0) / X0, errs)


def test_den_hartog_reference_scheme_on_exact_orbit():
    """The paper's scheme started on Den Hartog's exact stick-slip orbit stays on it (2 periods)."""
    s, dh = _den_hartog_case(0.6, 1.0, 25.0)
    X0, ts, t_stick = dh.steady_state()
    dt = dh.T / 1600
    q0 = np.zeros(4)
    q0[0] = -X0
    tr = simulate_reference(s, dt, 3200, q0=q0, t0=ts, check_step=False)
    amp, stick = _last_period_stats(tr, dh.T, dt)
    assert abs(amp - X0) / X0 < 2e-3
    assert abs(stick - t_stick) / (dh.T / 2) < 1e-3
    # 4 half cycles, each a stick then a slip phase: at most 8 switches, no chatter
    assert np.all(np.abs(np.diff(tr.modes.astype(int), axis=0)).sum(axis=0) <= 8)
    # the plain step: the paper's scheme has no event location (the same discretisation is compared)
    tp = simulate_production(s, dt, 3200, q0=q0, t0=ts, check_step=False, options=NewmarkOptions(locate_events=False))
    assert np.abs(tp.q - tr.q).max() < 1e-8 * X0  # same discretisation, Newton tolerance apart


# --------------------------------------------------------------------------- linear rotor


@pytest.fixture(scope="module")
def table4():
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene

    scene = load_scene("paper-table4")
    return scene, assemble(scene)


def _linear_rotor(model, omega, damped=True):
    from rotor.model.assembly import harmonic_loads

    n = model.n_dofs
    loads = harmonic_loads(model, omega)
    a1, b1 = loads[1]
    f = HarmonicForce(np.zeros(n), np.array([1.0]), a1[None, :], b1[None, :], omega)
    C = model.C if damped else np.zeros_like(model.C)
    # loose pair locked (bearing and support move together): a linear rotor with 2+4 lock rows
    from rotor.model.assembly import lock_rows
    L = np.vstack([model.B, lock_rows(model)[0]])
    return RotorSystem(model.M, C, model.G, model.K + model.K_c, omega, f, np.zeros(n), L, None, tuple(model.dof_names))


def _particular_state(sys_):
    """Displacement and velocity (n,) of the steady harmonic solution at t = 0."""
    T = cons.null_space_map(sys_.lock)
    Mr, Dr, Kr = T.T @ sys_.M @ T, T.T @ sys_.D @ T, T.T @ sys_.K @ T
    f = sys_.force
    w = f.omega_rad_s
    X = np.linalg.solve(Kr - w * w * Mr + 1j * w * Dr, T.T @ (f.cos[0] - 1j * f.sin[0]))
    return T @ X.real, T @ (1j * w * X).real


def _modal_solution(sys_, t, q0, v0):
    """Exact response of the constrained linear system: state-space eigenvectors (modes) for the
    free part plus the complex-amplitude harmonic part."""
    T = cons.null_space_map(sys_.lock)
    Mr, Dr, Kr = T.T @ sys_.M @ T, T.T @ sys_.D @ T, T.T @ sys_.K @ T
    nr = Mr.shape[0]
    Minv = np.linalg.inv(Mr)
    A = np.block([[np.zeros((nr, nr)), np.eye(nr)], [-Minv @ Kr, -Minv @ Dr]])
    f = sys_.force
    w = f.omega_rad_s
    amp = T.T @ (f.cos[0] - 1j * f.sin[0])  # force = Re(amp e^{iωt})
    X = np.linalg.solve(Kr - w * w * Mr + 1j * w * Dr, amp)
    def part(tt):
        e = np.exp(1j * w * tt)
        return np.real(np.outer(e, X)), np.real(np.outer(1j * w * e, X))
    xp0, vp0 = part(np.array([0.0]))
    lam, V = np.linalg.eig(A)
    c = np.linalg.solve(V, np.concatenate([T.T @ q0 - xp0[0], T.T @ v0 - vp0[0]]))
    free = np.real((V * c) @ np.exp(np.outer(lam, t)))[:nr].T
    xp, _ = part(t)
    return (free + xp) @ T.T


def test_newmark_second_order_against_modal_solution(table4):
    """Error over 1 revolution falls 4x per step halving (Newmark average acceleration, order 2).

    Started on the exact harmonic state: the error is then the scheme's own O(Δt²) error of the
    forced response (plus the O(Δt²) start-up transient it excites), not the saturated phase error
    of unresolved high modes that a start from rest would excite."""
    scene, model = table4
    omega = 4500 * 2 * math.pi / 60
    s = _linear_rotor(model, omega)
    T = 2 * math.pi / omega
    # start on the harmonic solution plus a free vibration in the lowest modes, so that every
    # excited mode is resolved by the steps compared (asymptotic range of the error)
    qp, vp = _particular_state(s)
    errs = []
    for nsteps in (100, 200, 400):
        dt = T / nsteps
        tr = simulate_reference(s, dt, nsteps, q0=qp, v0=vp, record_every=nsteps // 20)
        exact = _modal_solution(s, tr.t, qp, vp)
        errs.append(np.abs(tr.q - exact).max() / np.abs(exact).max())
    ratios = [errs[i] / errs[i + 1] for i in range(2)]
    assert all(3.6 < r < 4.4 for r in ratios), (errs, ratios)
    assert errs[-1] < 1e-3


def test_energy_conserved_undamped_average_acceleration(table4):
    """Undamped gyroscopic rotor, free vibration, 10^4 steps: ½vᵀMv + ½qᵀKq constant to round-off."""
    scene, model = table4
    omega = 10500 * 2 * math.pi / 60
    s = _linear_rotor(model, omega, damped=False)
    s = RotorSystem(s.M, s.C, s.G, s.K, omega, HarmonicForce.zero(s.n, omega), s.offset, s.lock, None, s.dof_names)
    rng = np.random.default_rng(1)
    Tn = cons.null_space_map(s.lock)
    q0 = Tn @ rng.normal(size=Tn.shape[1]) * 1e-4
    v0 = Tn @ rng.normal(size=Tn.shape[1]) * 1e-2
    dt = 2 * math.pi / omega / 64
    tr = simulate_production(s, dt, 10_000, q0=q0, v0=v0)
    E = 0.5 * np.einsum("ij,ij->i", tr.v, tr.v @ s.M.T) + 0.5 * np.einsum("ij,ij->i", tr.q, tr.q @ s.K.T)
    drift = np.abs(E - E[0]).max() / E[0]
    assert drift < 1e-11, drift
    assert np.abs(tr.q).max() > 0  # it did move


def test_energy_balance_closes_on_nonlinear_run(table4):
    """Table 4 rotor at 10 500 rpm with contact, impact damping, stick/slip: balance within 1 % of input."""
    from rotor.dynamics.build import system_from_model

    scene, model = table4
    omega = 10500 * 2 * math.pi / 60
    s = system_from_model(model, scene, omega)
    dt = 2 * math.pi / omega / 256
    tr = simulate_production(s, dt, 256 * 12)
    eb = energy_balance(s, tr)
    r1, r2 = cons.edge_offsets(tr.u, s.support.width_m)
    assert max(r1.max(), r2.max()) > s.support.law.clearance_m  # contact did happen
    assert eb.impact[-1] > 0 and eb.damping[-1] > 0
    assert eb.relative_closure() < 0.01, eb.relative_closure()
