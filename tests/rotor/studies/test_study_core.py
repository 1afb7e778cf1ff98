"""Steady-state detection and exact-bin spectra (rotor.studies.steady_state).

Expected values come from closed forms: DFT orthogonality over whole periods (a harmonic
``h f`` recorded over N whole revolutions is exactly bin ``h N``), geometric decay sums, and
the linear steady-state frequency response of the Table 4 rotor (Dai et al. 2025, Eq. 59 with
the loose support stuck, i.e. locked) from :func:`rotor.linear.unbalance.forced_response`.
"""
import math

import numpy as np
import pytest

from contact.errors import InputError
from rotor.studies.steady_state import (SteadyStateOptions, harmonic_amplitudes, poincare_convergence, spectrum,
                         steady_state)


def test_harmonic_amplitudes_exact_bins_no_leakage():
    # closed form: x = 3 cos(θ + 0.2) + 0.5 sin(3θ) + 0.7 cos(θ/2) + 0.1, θ = Ω t, over N = 8 revs
    N, s = 8, 64
    th = 2 * np.pi * np.arange(N * s) / s
    x = 3 * np.cos(th + 0.2) + 0.5 * np.sin(3 * th) + 0.7 * np.cos(th / 2) + 0.1
    a = harmonic_amplitudes(x, N, orders=(1, 2, 3, 4, 5))
    assert abs(a[0] - 3 * np.exp(0.2j)) < 1e-12
    assert abs(a[1]) < 1e-12
    assert abs(a[2] - 0.5 * np.exp(-0.5j * np.pi)) < 1e-12
    assert np.all(np.abs(a[3:]) < 1e-12)
    orders, amp = spectrum(x, N, max_order=4)
    assert orders[0] == pytest.approx(1 / N)
    # the subharmonic f/2 is bin N/2 exactly: amplitude 0.7, nothing leaks to its neighbours
    j = np.argmin(np.abs(orders - 0.5))
    assert amp[j] == pytest.approx(0.7, abs=1e-12)
    assert amp[j - 1] < 1e-12 and amp[j + 1] < 1e-12
    assert amp[np.argmin(np.abs(orders - 3))] == pytest.approx(0.5, abs=1e-12)


def test_harmonic_amplitudes_rejects_partial_revolutions_and_nyquist():
    with pytest.raises(InputError, match="whole number"):
        harmonic_amplitudes(np.zeros(100), 3)
    with pytest.raises(InputError, match="Nyquist"):
        harmonic_amplitudes(np.zeros(8 * 8), 8, orders=(5,))


def _geometric(k, rho, amp=1.0, phase=0.0):
    # once-per-revolution samples of a steady 1X orbit plus a transient decaying by rho per revolution
    n = np.arange(k)
    return np.column_stack([np.full(k, 1e-4) + amp * 1e-4 * rho ** n * np.cos(2.1 * n + phase),
                            np.full(k, -2e-4) + amp * 1e-4 * rho ** n * np.sin(2.1 * n + phase)])


def test_poincare_detects_decayed_transient_only_when_the_rest_is_small():
    scale = 4e-4
    # fast decay (rho 0.5): after 60 revolutions nothing is left -> steady, period 1
    c = poincare_convergence(_geometric(60, 0.5), scale, tol=1e-4)
    assert c.converged and c.period == 1
    # slow decay (rho 0.98): after 450 revolutions the per-revolution change is
    # 1e-4*0.98^450*|e^{2.1i}-1|/4e-4 ~ 5e-5 relative (< tol), but the geometric tail
    # rho/(1-rho) = 49 times that (~2.5e-3) is still to decay
    P = _geometric(450, 0.98)
    d = np.abs(np.diff(P, axis=0)).max(axis=1)[-16:] / scale
    assert d.max() < 1e-4  # the naive per-revolution test would pass ...
    c = poincare_convergence(P, scale, tol=1e-4)
    assert not c.converged  # ... the extrapolated remainder (sum of a geometric series) does not
    assert c.ratio == pytest.approx(0.98, abs=0.005)
    assert c.remaining > 1e-4


def test_poincare_finds_subharmonic_period_and_rejects_quasi_periodic():
    k = np.arange(200)
    period3 = np.column_stack([np.cos(2 * np.pi * k / 3), np.sin(2 * np.pi * k / 3)]) * 1e-5
    c = poincare_convergence(period3, 4e-5, tol=1e-4, max_period=8)
    assert c.converged and c.period == 3
    alpha = (math.sqrt(5) - 1) / 2  # irrational rotation: quasi-periodic, never repeats
    qp = np.column_stack([np.cos(2 * np.pi * alpha * k), np.sin(2 * np.pi * alpha * k)]) * 1e-5
    c = poincare_convergence(qp, 4e-5, tol=1e-4, max_period=8)
    assert not c.converged and c.period == 0


def test_poincare_transient_near_half_speed_is_not_called_subharmonic():
    # transient at ~f/2 decaying: the 2-revolution differences pass before the 1-revolution ones,
    # but a decaying one-revolution difference means "transient", not "period 2"
    n = np.arange(120)
    x = 1e-4 + 3e-8 * 0.93 ** n * np.cos(np.pi * n * 1.001)
    P = np.column_stack([x, x])
    c = poincare_convergence(P, 1e-4, tol=1e-4)
    assert c.period != 2


def test_options_validate():
    with pytest.raises(InputError, match="samples_per_rev"):
        SteadyStateOptions(samples_per_rev=8)
    with pytest.raises(InputError, match="tol"):
        SteadyStateOptions(tol=-1)
    with pytest.raises(InputError, match="min_revs"):
        SteadyStateOptions(min_revs=100, max_revs=50)


@pytest.fixture(scope="module")
def table4():
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene

    scene = load_scene("paper-table4")
    return scene, assemble(scene)


@pytest.fixture(scope="module")
def table4_inertial():
    """The Table 4 rotor under the former reading of Eq. 34 (rotor/scenes/paper-table4-inertial.toml): its
    2X at disk 2 is 20 times smaller than the default's, the size the Richardson bound below was set for."""
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene

    scene = load_scene("paper-table4-inertial")
    return scene, assemble(scene)


def test_steady_state_equals_linear_forced_response_when_support_sticks(table4_inertial):
    """Stuck support + linear coupling: the system is linear, so the detected steady state must
    converge to the closed-form frequency response (1X unbalance, 2X misalignment) of the locked
    rotor at second order in the step: the errors at 448 and 896 steps per revolution fall by 4
    (Newmark's average acceleration), and their Richardson extrapolation matches it to 2e-6.
    (At 448 steps the 2X error alone is up to 1.7e-3 at disk 2, whose 2X comes through a mode
    near 2X: more than the bare phase error (2ΩΔt)²/12 = 7e-5 suggests.)"""
    from rotor.dynamics.build import system_from_model
    from rotor.linear.unbalance import forced_response

    scene, model = table4_inertial
    rpm = 3000.0
    omega = rpm * math.pi / 30
    system = system_from_model(model, scene, omega, nonlinear_coupling=False)
    runs = {}
    for spr in (448, 896):
        res = steady_state(system, model, options=SteadyStateOptions(tol=1e-6, spectrum_revs=8, steps_per_rev=spr))
        assert res.convergence.converged and res.convergence.period == 1 and res.steps_per_rev == spr
        reg = res.regime()
        assert reg["label"] == "stick" and reg["contact_fraction"] == 0.0
        runs[spr] = [harmonic_amplitudes(res.q[:, k] - res.q[:, k].mean(), res.revolutions, (1, 2, 3))
                     for k in range(len(res.channels))]
    closed = [forced_response(model, [omega], order=n).amplitudes[0] for n in (1, 2)]
    scale = [max(abs(a[model.dof_index(c)]) for c in res.channels) for a in closed]
    for k, name in enumerate(res.channels):
        i = model.dof_index(name)
        # the record starts at t = k T (phase 0 of the excitation): complex amplitudes compare directly
        for n, a in enumerate(closed):
            coarse, fine = runs[448][k][n], runs[896][k][n]
            assert 3.8 <= abs(coarse - a[i]) / abs(fine - a[i]) <= 4.2, (name, n + 1)
            assert abs((4 * fine - coarse) / 3 - a[i]) <= 2e-6 * abs(a[i]) + 1e-8 * scale[n], (name, n + 1)
        assert abs(runs[448][k][2]) <= 1e-8 * scale[0]  # linear: no 3X at all
