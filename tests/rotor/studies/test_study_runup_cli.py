"""Run-up segment stitching and the ``ringcontact study`` job, end to end on small cases."""
import csv

import numpy as np
import pytest

from rotor.studies.runup import RunupSpec, simulate_runup, stft_cascade


def test_constant_speed_runup_equals_one_constant_speed_run():
    """A 'run-up' with equal start and end speeds is a constant-speed run cut into segments. Each
    segment restarts the integrator with the accumulated rotation angle as its phase and a
    consistent initial acceleration; implicit Newmark satisfies the equation of motion at every
    step, so the stitched run must equal one uninterrupted run to round-off.

    End-face friction off (μ = 0): with friction each restart re-runs the stick test on the
    faces (rotor.dynamics.initial.initial_state), which can take another branch of the stick/slip
    active set than the uninterrupted run did (measured: 0.5 % of the dynamic amplitude after
    0.06 s at 3 000 rpm) -- a path dependence of the non-smooth problem, not of the stitching."""
    from rotor.dynamics.production import simulate_production
    from rotor.studies.steady_state import point_system

    spec = RunupSpec(rpm_start=3000, rpm_end=3000, duration_s=0.06, segment_s=4e-3, sample_rate_hz=5000, mu=0.0)
    r = simulate_runup(spec)
    dt, rec = r["info"]["dt_s"], r["info"]["record_every"]
    _, model, system = point_system("paper-table4", 3000.0, mu=0.0)
    n = r["info"]["steps"]
    tr = simulate_production(system, dt, n, q0=system.offset, record_every=rec, check_step=False)
    idx = [model.dof_index(c) for c in r["arrays"]["channels"]]
    q_one = tr.q[:, idx]
    q_seg = r["arrays"]["q"]
    assert q_seg.shape == q_one.shape
    np.testing.assert_allclose(r["arrays"]["t"], tr.t, rtol=0, atol=1e-12)
    dyn = np.abs(q_one - q_one[0]).max()
    assert np.abs(q_seg - q_one).max() <= 1e-9 * dyn  # measured 1e-10 of dyn (round-off)


def test_stft_amplitude_of_a_sinusoid():
    """Hann-window STFT amplitude-corrected: a 50 Hz sinusoid of amplitude 2 reads ≈ 2 at its bin
    (window an integer number of periods: exact up to the window's DC leakage, < 1e-3)."""
    fs = 5000.0
    t = np.arange(0, 1.0, 1 / fs)
    r = {"t": t, "v": (2 * np.sin(2 * np.pi * 50 * t))[:, None], "channels": np.array(["disk1.y"]),
         "rpm": np.full(t.size, 3000.0)}
    tc, fr, A, rpm = stft_cascade(r, "disk1.y", window_s=0.2)
    j = np.argmin(np.abs(fr - 50))
    assert fr[j] == pytest.approx(50)
    np.testing.assert_allclose(A[:, j], 2.0, rtol=1e-3)


def test_study_cli_cascade_small_then_resume(tmp_path, capsys):
    from reports.cli.study import main

    out = tmp_path / "c"
    argv = ["cascade", "--rpm-min", "0", "--rpm-max", "3000", "--points", "2", "--workers", "1", "--out", str(out),
            "--no-progress"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "2 computed" in text
    rows = list(csv.DictReader(open(out / "figures" / "study-cascade.csv")))
    assert [float(r["speed_rpm"]) for r in rows] == [0.0, 3000.0]
    assert rows[1]["regime"] == "stick" and rows[1]["converged"] == "1"
    assert float(rows[1]["disk1_v1X_mm_s"]) > 0 and float(rows[0]["disk1_v1X_mm_s"]) == 0.0
    for ext in ("png", "svg"):
        assert (out / "figures" / f"study-cascade.{ext}").stat().st_size > 1000
    assert main(argv) == 0
    assert "0 computed, 2 reused" in capsys.readouterr().out


def test_study_cli_bad_input_names_parameter(capsys):
    from reports.cli import main

    assert main(["study", "cascade", "--rpm-max", "-5", "--out", "/tmp/never-written"]) == 2
    err = capsys.readouterr().err
    assert "--rpm-max = -5 rpm" in err and len(err.splitlines()) == 1
