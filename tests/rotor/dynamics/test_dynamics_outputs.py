"""Support law as the integrators see it, steady-state tool and the ``simulate`` job (issue 7).

Sources: Dai et al. (2025) Eq. 1 (line contact at zero tilt) and Eq. 5 (conformal law,
``contact.laws.conformal_force``); Table 4 c_c = 100 read as s/m (docs/reference/contact-laws.md Q6);
the exact periodic solution of a linear system for the spectrum bins.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from contact import laws
from rotor.dynamics import constraints as cons
from rotor.dynamics.build import system_from_model
from rotor.dynamics.initial import linear_initial_state
from rotor.dynamics.system import HarmonicForce, RotorSystem
from rotor.studies.steady_state import SteadyStateOptions, steady_state


@pytest.fixture(scope="module")
def table4():
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene

    scene = load_scene("paper-table4")
    return scene, assemble(scene)


def _line_force(pen):
    return float(laws.conformal_force(pen, clearance_m=0.05e-3, width_m=0.03, bearing_E_Pa=204e9, bearing_nu=0.3,
                                      support_E_Pa=204e9, support_nu=0.3).force_N)


def test_zero_tilt_force_is_line_contact_not_doubled(table4):
    """Q8: at θ = 0 (Δr1 = Δr2) the paper's rule would add both edges (2×); the integrators get Eq. 5 once."""
    scene, model = table4
    law = system_from_model(model, scene, 1000.0).support.law
    pen = 0.01e-3
    f = law.force(np.array([0.05e-3 + pen, 0, 0, 0.0]), np.zeros(4))
    assert f[0] == pytest.approx(-_line_force(pen), rel=1e-9)
    assert f[2] == 0.0 and f[3] == 0.0


def test_collision_factor_is_per_metre_per_second(table4):
    """Q6: (1 + c_c v_n) with c_c = 100 s/m doubles the force at v_n = 0.01 m/s (a s/N or s/mm
    reading would give a factor of 1e5 or 1e3 different)."""
    scene, model = table4
    law = system_from_model(model, scene, 1000.0).support.law
    u = np.array([0.06e-3, 0, 0, 0.0])
    f0 = law.force(u, np.zeros(4))[0]
    f1 = law.force(u, np.array([0.01, 0, 0, 0.0]))[0]
    assert f1 / f0 == pytest.approx(2.0, rel=1e-12)


def test_tilt_ignored_switch_reaches_the_law(table4):
    scene, model = table4
    u = np.array([0.055e-3, 0, 0, 1e-3])  # tilted: edge contact and a moment unless tilt is ignored
    with_tilt = system_from_model(model, scene, 1000.0).support.law.force(u, np.zeros(4))
    no_tilt = system_from_model(model, scene, 1000.0, tilt_ignored=True).support.law.force(u, np.zeros(4))
    assert no_tilt[3] == 0.0 and with_tilt[3] != 0.0
    assert no_tilt[0] == pytest.approx(-_line_force(0.005e-3), rel=1e-9)


def test_steady_state_of_linear_system_matches_exact_harmonic(table4):
    """No loose support: the periodic solution is known exactly; the steady-state tool must find it
    at once and its 1X bin must give ω|X| to Newmark's O((ωΔt)²) accuracy; 2X–5X vanish."""
    scene, model = table4
    from rotor.model.assembly import harmonic_loads

    omega = 3000 * 2 * math.pi / 60
    n = model.n_dofs
    a1, b1 = harmonic_loads(model, omega)[1]
    f = HarmonicForce(np.zeros(n), np.array([1.0]), a1[None, :], b1[None, :], omega)
    s = RotorSystem(model.M, model.C, model.G, model.K + model.K_c, omega, f, np.zeros(n), np.asarray(model.B, float),
                    None, tuple(model.dof_names))
    idx = [model.dof_index("disk1.y"), model.dof_index("disk2.z")]
    q0, v0 = linear_initial_state(s, 0.0, lock_support=False)
    # Start: the *discrete* periodic solution of the trapezoidal rule (Newmark β = 1/4, γ = 1/2):
    # with z = e^{iωΔt} its recursions give V = iΩ̃X, A = iΩ̃V, Ω̃ = (2/Δt) tan(ωΔt/2), so
    # (K − Ω̃²M + iΩ̃D) X = c − i s. Without the support this rotor has a mode that the model
    # leaves undamped: the exact start's O((ωΔt)²) mismatch would ring for ever, and rotor.studies.steady_state's
    # detector (rightly) never accepts a non-decaying Poincaré plateau.
    dt = 2 * math.pi / omega / 256
    wt = 2 / dt * math.tan(omega * dt / 2)
    Tl = cons.null_space_map(s.lock)
    X = Tl @ np.linalg.solve(Tl.T @ (s.K - wt * wt * s.M + 1j * wt * s.D) @ Tl, Tl.T @ (a1 - 1j * b1))
    qd, vd = X.real, (1j * wt * X).real
    # first Poincaré check after 17 revolutions (the detector's window: 16 differences)
    opts = SteadyStateOptions(steps_per_rev=256, samples_per_rev=64, spectrum_revs=8, min_revs=17,
                              min_chunk_revs=17, max_chunk_revs=17)
    res = steady_state(s, model, options=opts, stations=("disk1", "disk2"), q0=qd, v0=vd)
    assert res.convergence.converged and res.convergence.period == 1 and res.transient_revs == 17
    assert res.steps_per_rev == 256 and res.revolutions == 8
    cols = [res.channel("disk1.y"), res.channel("disk2.z")]
    amplitudes = res.harmonics("v")[:, cols].T  # (dofs, 1X..5X), m/s
    # exact amplitude of the velocity: |X| ω from the complex solution at two phases
    qa, va = linear_initial_state(s, math.pi / 2 / omega, lock_support=False)
    exact = np.hypot(v0[idx], va[idx])
    assert np.allclose(amplitudes[:, 0], exact, rtol=2e-3)  # (ωΔt)²/12 ≈ 5e-5 phase; amplitude tighter
    # started on the discrete periodic solution, nothing leaks into the 2X–5X bins (below 1e-5 of 1X)
    assert np.all(amplitudes[:, 1:] < 1e-5 * exact[:, None])


def test_simulate_job_writes_files_and_rejects_bad_input(tmp_path, capsys):
    from reports.cli import main

    out = tmp_path / "run"
    rc = main(["simulate", "--speed-rpm", "10500", "--revolutions", "2", "--out", str(out)])
    assert rc == 0
    summary = json.loads((out / "simulate-summary.json").read_text())
    assert summary["steps"] == 512 and summary["clearance_mm"] == pytest.approx(0.05)
    header = (out / "simulate.csv").read_text().splitlines()[0].split(",")
    for col in ("t_s", "disk1.y_m", "r1_m", "r2_m", "tilt_y_rad", "stick_right", "contact_edge1"):
        assert col in header
    data = np.loadtxt(out / "simulate.csv", delimiter=",", skiprows=1)
    assert data.shape == (2 * 64 + 1, len(header)) and np.all(np.isfinite(data))
    with np.load(out / "simulate.npz") as z:
        assert z["q"].shape[1] == len(z["dof_names"])
    assert not list(out.glob(".*.tmp"))
    rc = main(["simulate", "--speed-rpm", "10500", "--clearance-mm", "-1", "--out", str(out)])
    assert rc == 2
    assert "--clearance-mm = -1 mm" in capsys.readouterr().err


def test_simulate_steady_record_is_the_detected_steady_state(tmp_path, table4):
    """``simulate --steady`` (rotor.studies.steady_state detector, record re-integrated from its end state): the kept
    record must itself be steady (once-per-revolution displacements of the monitored DOFs repeat to
    the detector's tolerance, 1e-4 of the largest peak-to-peak amplitude, rotor.studies.steady_state.SteadyStateOptions)
    and the summary's 1X–5X velocity amplitudes must be the exact-bin DFT of the velocities written
    to simulate.npz."""
    from reports.cli import main
    from rotor.studies.steady_state import harmonic_amplitudes

    _, model = table4
    out = tmp_path / "steady"
    assert main(["simulate", "--speed-rpm", "10500", "--steady", "--revolutions", "4", "--out", str(out)]) == 0
    summary = json.loads((out / "simulate-summary.json").read_text())
    assert summary["steady_converged"] and summary["period_revs"] == 1 and summary["record_revs"] == 4
    assert summary["poincare_change"] <= 1e-4 and summary["steps"] == 4 * 256
    with np.load(out / "simulate.npz") as z:
        q, v, face_force = z["q"], z["v"], z["face_force"]
    assert q.shape[0] == 4 * 64 + 1 and face_force.shape == (q.shape[0], 2, 2)
    amps = summary["velocity_amplitudes_mm_s_1X_to_5X"]
    idx = [model.dof_index(n) for n in amps]
    for name, j in zip(amps, idx):
        x = v[:-1, j]
        expect = np.abs(harmonic_amplitudes(x - x.mean(), 4)) * 1e3
        assert np.allclose(amps[name], expect, rtol=0, atol=1e-6)  # summary rounded to 1e-6 mm/s
    P = q[::64][:, idx]
    assert np.abs(np.diff(P, axis=0)).max() <= 1e-4 * np.ptp(q[:, idx], axis=0).max()


def test_simulate_with_a_calibrated_law_and_its_validity_flag(tmp_path, capsys):
    """`--law calibrated:<name>`: the rotor runs on the law fitted to the clamped FEM scene (contact/
    calibrated/clamped-foundation.json), the summary says how deep the edges went against the fitted
    range; a clearance other than the calibration's is refused, naming the parameter."""
    from reports.cli import main
    from reports.cli.simulate import validity_summary

    out = tmp_path / "cal"
    rc = main(["simulate", "--speed-rpm", "10500", "--revolutions", "2", "--law", "calibrated:clamped-foundation",
               "--misalignment-mm", "3", "--out", str(out)])
    assert rc == 0
    s = json.loads((out / "simulate-summary.json").read_text())
    assert s["law"] == "clamped-foundation" and s["clearance_mm"] == pytest.approx(0.05)
    assert s["law_validity_max_penetration_mm"] == pytest.approx(0.05)          # the fitted Δr range (FEM data)
    assert s["max_edge_penetration_mm"] == pytest.approx(max(s["max_r1_mm"], s["max_r2_mm"], 0.05) - 0.05, abs=1e-12)
    assert s["beyond_law_validity"] is (s["max_edge_penetration_mm"] > 0.05)
    capsys.readouterr()
    assert main(["simulate", "--speed-rpm", "10500", "--law", "calibrated:clamped-foundation",
                 "--clearance-mm", "0.03", "--out", str(out)]) == 2
    assert "clearance_mm = 0.03 mm" in capsys.readouterr().err
    assert main(["simulate", "--speed-rpm", "10500", "--law", "hertz", "--out", str(out)]) == 2
    assert "law = 'hertz'" in capsys.readouterr().err
    # the flag itself: beyond the range → True, within → False, analytic laws carry no range
    assert validity_summary(6e-5, 5e-5)["beyond_law_validity"] is True
    assert validity_summary(1e-6, 5e-5)["beyond_law_validity"] is False
    assert validity_summary(-1e-6, None) == {"max_edge_penetration_mm": 0.0}
