"""``ringcontact orbit`` and ``ringcontact branch`` through the command line (reports.cli.main).

Fast cases use a damped Jeffcott rotor (the bundled ``verify-jeffcott`` with a steel shaft and damped
bearings, written to a temporary TOML): a linear rotor with one periodic orbit per speed, so the transient
steady state of ``simulate --steady`` converges to the very orbit shooting finds. The Table 4 must-show of
issue 18 (10 500 rpm, 1X-5X within 1e-4 of ``simulate --steady``) is the slow case at the end.
"""
from __future__ import annotations

import json
import stat
from pathlib import Path

import numpy as np
import pytest

from reports import cli

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def damped_jeffcott(tmp_path_factory) -> Path:
    text = (ROOT / "rotor/scenes/verify-jeffcott.toml").read_text(encoding="utf-8")
    text = text.replace('name = "verify-jeffcott"', 'name = "damped-jeffcott"')
    text = text.replace("density_kg_m3 = 0\n", "density_kg_m3 = 7800\n")
    text = text.replace("stiffness_n_per_m = 2.0e6\n", "stiffness_n_per_m = 2.0e6\ndamping_n_s_per_m = 300\n")
    assert text.count("damping_n_s_per_m = 300") == 2 and "density_kg_m3 = 7800" in text
    path = tmp_path_factory.mktemp("scene") / "damped-jeffcott.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _run(argv, capsys) -> tuple[int, str, str]:
    rc = cli.main([str(a) for a in argv])
    out = capsys.readouterr()
    return rc, out.out, out.err


def _amplitudes_agree(a: dict, b: dict, floor_mm_s: float) -> float:
    """Largest difference of the 1X-5X amplitudes relative to each channel's 1X, asserting the same channels."""
    assert a.keys() == b.keys()
    worst = 0.0
    for k in a:
        x, y = np.array(a[k]), np.array(b[k])
        worst = max(worst, float(np.max(np.abs(x - y)) / max(abs(x[0]), floor_mm_s)))
    return worst


def test_orbit_json_equals_simulate_steady(damped_jeffcott, tmp_path, capsys):
    out = tmp_path / "orbit.json"
    rc, text, err = _run(["orbit", damped_jeffcott, "--speed-rpm", 1500, "--json", "--out", out], capsys)
    assert rc == 0, err
    d = json.loads(text)
    assert json.loads(out.read_text()) == d                        # the file holds what was printed
    assert stat.S_IMODE(out.stat().st_mode) & 0o644 == 0o644
    assert d["converged"] and d["stable"] and d["period_revs"] == 1 and d["residual"] < 1e-9
    assert d["period_s"] == pytest.approx(60.0 / 1500.0, rel=1e-12)
    radii = [abs(complex(*m)) for m in d["multipliers"]]
    assert max(radii) < 1.0 and d["spectral_radius"] == pytest.approx(max(radii))   # damped: all inside
    for key in ("newton_iterations", "wall_s", "critical_kind", "speed_rpm", "steps_per_rev"):
        assert key in d
    assert abs(complex(*d["critical_multiplier"])) == pytest.approx(d["spectral_radius"])
    assert d["multipliers_outside"] == {"real_above_plus_1": 0, "real_below_minus_1": 0, "complex": 0}
    rc, _, err = _run(["simulate", "--scene", damped_jeffcott, "--speed-rpm", 1500, "--steady", "--revolutions", 4,
                       "--out", tmp_path / "sim"], capsys)
    assert rc == 0, err
    sim = json.loads((tmp_path / "sim" / "simulate-summary.json").read_text())
    # the same orbit of the same scheme: simulate rounds to 1e-6 mm/s, its detector stops at a 1e-4 tolerance
    assert _amplitudes_agree(d["velocity_amplitudes_mm_s_1X_to_5X"], sim["velocity_amplitudes_mm_s_1X_to_5X"],
                             1e-3) < 1e-4


def test_orbit_table_and_forced_period(damped_jeffcott, capsys):
    rc, text, err = _run(["orbit", damped_jeffcott, "--speed-rpm", 1500, "--period-revs", 2], capsys)
    assert rc == 0, err
    # a 1-revolution orbit solves the 2-revolution problem: shooting returns the shortest period
    assert text.startswith("orbit damped-jeffcott") and "period 1 rev" in text.splitlines()[0]
    assert "stable" in text and "d.y" in text


def test_branch_points_are_orbits_and_the_plot_is_written(damped_jeffcott, tmp_path, capsys):
    out, plot = tmp_path / "branch.json", tmp_path / "bif"
    rc, text, err = _run(["branch", damped_jeffcott, "--rpm-start", 1500, "--rpm-end", 3000, "--json", "--out", out,
                          "--plot", plot], capsys)
    assert rc == 0, err
    d = json.loads(text)
    assert d["stop"] == "end reached" and len(d["points"]) >= 5
    rpm = np.array([p["speed_rpm"] for p in d["points"]])
    assert rpm[0] == pytest.approx(1500.0) and rpm[-1] == pytest.approx(3000.0, rel=1e-12) and np.all(np.diff(rpm) > 0)
    assert all(p["stable"] for p in d["points"]) and d["bifurcations"] == []   # linear, damped: no bifurcation
    assert (tmp_path / "bif.png").stat().st_size > 1000 and (tmp_path / "bif.svg").exists()
    # a continued point is the orbit the orbit job finds at that speed (both fixed points of the same map)
    p = d["points"][len(d["points"]) // 2]
    rc, text, err = _run(["orbit", damped_jeffcott, "--speed-rpm", repr(p["speed_rpm"]), "--json",
                          "--steps-per-rev", d["steps_per_rev"]], capsys)
    assert rc == 0, err
    o = json.loads(text)
    assert _amplitudes_agree(p["velocity_amplitudes_mm_s_1X_to_5X"], o["velocity_amplitudes_mm_s_1X_to_5X"],
                             1e-3) < 1e-6


def test_branch_downwards_is_a_run_down_to_rpm_end(damped_jeffcott, capsys):
    """--rpm-end below --rpm-start follows the branch downwards (a run-down, the other side of any hysteresis)."""
    rc, text, err = _run(["branch", damped_jeffcott, "--rpm-start", 3000, "--rpm-end", 1500, "--json"], capsys)
    assert rc == 0, err
    d = json.loads(text)
    rpm = np.array([p["speed_rpm"] for p in d["points"]])
    assert d["stop"] == "end reached" and rpm[0] == pytest.approx(3000.0) and rpm[-1] == pytest.approx(1500.0, rel=1e-12)
    assert np.all(np.diff(rpm) < 0)
    # a frictionless ring: a smooth map, every point reached by the corrector, none by a restart past a switch
    assert d["restarts"] == {"secant": 0, "transient": 0, "cold": 0, "step-grid": 0}
    assert all(p["restarted"] is None for p in d["points"])


def test_branch_starts_on_the_orbit_of_an_orbit_out_file_and_its_table_has_amplitudes(damped_jeffcott, tmp_path,
                                                                                       capsys):
    out = tmp_path / "orbit.json"
    rc, _, err = _run(["orbit", damped_jeffcott, "--speed-rpm", 1500, "--steps-per-rev", 64, "--out", out], capsys)
    assert rc == 0, err
    o = json.loads(out.read_text())
    rc, text, err = _run(["branch", damped_jeffcott, "--rpm-start", 1500, "--rpm-end", 1800, "--from-orbit", out,
                          "--json"], capsys)
    assert rc == 0, err
    d = json.loads(text)
    assert d["steps_per_rev"] == 64 and d["start"]["transient_revs"] == 1      # the file's orbit, one revolution on
    assert np.allclose(d["start"]["phase0_state"]["q_m_rad"], o["phase0_state"]["q_m_rad"], rtol=1e-8, atol=1e-15)
    rc, text, err = _run(["branch", damped_jeffcott, "--rpm-start", 1500, "--rpm-end", 1800, "--from-orbit", out],
                         capsys)
    assert rc == 0, err
    rows = text.splitlines()
    assert "1X mm/s" in rows[1] and rows[1].rstrip().endswith("d.y")
    first = rows[2].split()
    assert float(first[0]) == pytest.approx(1500.0, abs=0.05)
    assert float(first[3]) == pytest.approx(o["velocity_amplitudes_mm_s_1X_to_5X"]["d.y"][0], rel=1e-3)
    # a file of another speed is refused before any computing: exit 2, one line naming the option and both speeds
    rc, _, err = _run(["branch", damped_jeffcott, "--rpm-start", 1600, "--rpm-end", 1800, "--from-orbit", out], capsys)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert rc == 2 and len(lines) == 1 and "--rpm-start = 1600 rpm" in lines[0] and "1500" in lines[0]


def test_orbit_from_a_neighbouring_speeds_orbit_finds_the_orbit_the_search_from_rest_finds(tmp_path, capsys):
    """``orbit --from-orbit``: Newton from another speed's orbit. From the unstable orbit at 17 762.7 rpm on
    paper-table4 (the search from rest finds it) to 17 000 rpm: the unstable orbit the search from rest finds there
    after 195 transient revolutions (measured: multipliers equal to 1e-14), here after 31. With ``--method hb``, or a
    file of another scene, it is refused before any computing.

    The case this test had (16 394.5 rpm, where the search from rest found no orbit and Newton from the orbit at
    17 762.7 rpm did: benchmarks/bench_monodromy_random.py, seed 3815215491) lay at the edge of Newton's basin:
    at 95fb1f6 Newton from the orbits at 17 700 and 17 850 rpm found none there, nor from 17 762.7 rpm once the
    located monodromy's blocks changed (rotor/dynamics/period_map_events.py ``MERGE_CONSECUTIVE``; at the orbit
    itself the monodromy is 4.6e-8 from central differences of its map, 2.8e-8 before)."""
    near, far = tmp_path / "near.json", tmp_path / "far.json"
    long = "--accept-long"             # the work budget (reports/cli/_budget.py) is not what this test checks
    rc, _, err = _run(["orbit", "paper-table4", "--speed-rpm", 17000, "--out", far, long], capsys)
    assert rc == 0, err
    rest = json.loads(far.read_text())
    rc, _, err = _run(["orbit", "paper-table4", "--speed-rpm", 17762.7, "--out", near, long], capsys)
    assert rc == 0, err
    got = tmp_path / "found.json"
    rc, _, err = _run(["orbit", "paper-table4", "--speed-rpm", 17000, "--from-orbit", near, "--out", got, long],
                      capsys)
    assert rc == 0, err
    d = json.loads(got.read_text())
    assert d["converged"] and d["started_from_orbit"] == {"file": str(near), "speed_rpm": 17762.7}
    assert rest["converged"] and d["period_revs"] == rest["period_revs"] and not d["stable"]
    assert d["spectral_radius"] == pytest.approx(rest["spectral_radius"], rel=1e-9)
    for extra, words in ((["--method", "hb"], "--method = hb"), ([], "an orbit of scene paper-table4, not of")):
        scene = "paper-table4" if extra else "table4-steel-in-aluminium"
        rc, _, err = _run(["orbit", scene, "--speed-rpm", 16000, "--from-orbit", near, *extra], capsys)
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert rc == 2 and len(lines) == 1 and words in lines[0], err
    # a file whose numbers no option would accept: refused before any computing, one line
    o = json.loads(near.read_text())
    for key, value in (("steps_per_rev", 10 ** 9), ("period_revs", -3)):
        bad = tmp_path / f"bad-{key}.json"
        bad.write_text(json.dumps({**o, key: value}))
        rc, _, err = _run(["orbit", "paper-table4", "--speed-rpm", 16000, "--from-orbit", bad], capsys)
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert rc == 2 and len(lines) == 1 and f"{key} {value}" in lines[0], err


def test_branch_starts_from_the_end_state_of_a_simulate_run_and_refuses_bad_runs(damped_jeffcott, tmp_path, capsys):
    """--from-state DIR: the transient from the last state of a ``simulate --out DIR`` run (phase 0 after whole
    revolutions) reaches the orbit; the state handed over is the run's last sample."""
    import argparse

    from reports.cli._orbit_starts import state_start
    sim = tmp_path / "sim"
    rc, _, err = _run(["simulate", "--scene", damped_jeffcott, "--speed-rpm", 1500, "--revolutions", 6,
                       "--steps-per-rev", 64, "--out", sim], capsys)
    assert rc == 0, err
    z = np.load(sim / "simulate.npz")
    got = state_start(argparse.Namespace(from_state=sim, from_orbit=None, rpm_start=1500.0), "damped-jeffcott",
                       z["q"].shape[1])
    assert np.array_equal(got["start"][0], z["q"][-1]) and np.array_equal(got["start"][1], z["v"][-1])
    rc, text, err = _run(["branch", damped_jeffcott, "--rpm-start", 1500, "--rpm-end", 1800, "--from-state", sim,
                          "--steps-per-rev", 64, "--json"], capsys)
    assert rc == 0, err
    d = json.loads(text)
    rc, text, err = _run(["orbit", damped_jeffcott, "--speed-rpm", 1500, "--steps-per-rev", 64, "--json"], capsys)
    o = json.loads(text)
    # a damped linear rotor has one orbit per speed: the transient from the run's end state reaches the orbit job's
    assert d["start"]["converged"] and d["stop"] == "end reached"
    assert np.allclose(d["start"]["phase0_state"]["q_m_rad"], o["phase0_state"]["q_m_rad"], rtol=1e-7, atol=1e-13)
    rc, _, err = _run(["simulate", "--scene", damped_jeffcott, "--speed-rpm", 1500, "--revolutions", 2.5,
                       "--steps-per-rev", 64, "--out", tmp_path / "half"], capsys)
    assert rc == 0, err
    (tmp_path / "empty").mkdir()
    for argv, words in ((["--rpm-start", 1600, "--from-state", sim], ("--rpm-start = 1600 rpm", "1500")),
                        (["--rpm-start", 1500, "--from-state", tmp_path / "half"], ("2.5 revolutions", "whole")),
                        (["--rpm-start", 1500, "--from-state", tmp_path / "empty"], ("--from-state", "simulate --out")),
                        (["--rpm-start", 1500, "--from-state", tmp_path / "nowhere"], ("--from-state", "no such")),
                        (["--rpm-start", 1500, "--from-state", sim, "--from-orbit", sim / "simulate-summary.json"],
                         ("--from-state", "not both"))):
        rc, _, err = _run(["branch", damped_jeffcott, "--rpm-end", 1800, *argv], capsys)
        lines = [ln for ln in err.splitlines() if ln.strip()]
        assert rc == 2 and len(lines) == 1 and all(w in lines[0] for w in words), (argv, err)


def test_branch_table_marks_restarts_with_the_speeds_skipped_and_bifurcations_between_rows():
    from reports.cli.orbit import _branch_table
    point = {"stable": True, "spectral_radius": 0.9, "leading_multiplier": "complex_pair",
             "velocity_amplitudes_mm_s_1X_to_5X": {"d.y": [1.5, 0, 0, 0, 0]}}
    d = {"scene": "s", "rpm_start": 2000.0, "rpm_end": 3000.0, "period_revs": 1, "stop": "end reached", "wall_s": 1.0,
         "points": [{**point, "speed_rpm": 2000.0, "restarted": None},
                    {**point, "speed_rpm": 2964.0, "restarted": None},
                    {**point, "speed_rpm": 2468.0, "restarted": "transient", "skipped_rpm": [2964.0, 2468.0]}],
         "bifurcations": [{"kind": "fold", "speed_rpm": 2500.0, "after_point": 1}]}
    rows = _branch_table(d, "d.y").splitlines()
    assert rows[2].split()[0] == "2000.0" and rows[3].strip() == "-- fold at 2500.0 rpm --"
    assert rows[5].endswith("restart: transient, skipped 2964.0-2468.0 rpm") and "restart" not in rows[4]
    assert rows[2].split()[3] == "1.5"                                    # the 1X column at the station


def test_branch_that_stops_early_exits_1_with_one_line(damped_jeffcott, capsys):
    rc, text, err = _run(["branch", damped_jeffcott, "--rpm-start", 1500, "--rpm-end", 3000, "--max-points", 2], capsys)
    assert rc == 1
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("ringcontact branch: error:") and "max_points" in lines[0]
    assert "1500" in text          # the orbits found are still shown


def test_table4_orbit_equals_simulate_steady_at_10500_rpm(tmp_path, capsys):
    """Issue 18 must-show: Table 4 at 10 500 rpm, the shooting orbit's 1X-5X equal the transient steady
    state's (``simulate --steady``) within 1e-4 relative (to each channel's 1X). The left end face sticks
    through the orbit (a continuum of orbits): the orbit job shoots once the transient's conserved levels
    stop drifting (rotor/periodic/shooting.py), so it lands on the transient's member. Scene: the former
    reading of Eq. 34 (rotor/scenes/paper-table4-inertial.toml), where that continuum was measured."""
    rc, text, err = _run(["orbit", "paper-table4-inertial", "--speed-rpm", 10500, "--json"], capsys)
    assert rc == 0, err
    d = json.loads(text)
    rc, _, err = _run(["simulate", "--scene", "paper-table4-inertial", "--speed-rpm", 10500, "--steady",
                       "--revolutions", 4, "--out", tmp_path / "s"], capsys)
    assert rc == 0, err
    sim = json.loads((tmp_path / "s" / "simulate-summary.json").read_text())
    assert _amplitudes_agree(d["velocity_amplitudes_mm_s_1X_to_5X"], sim["velocity_amplitudes_mm_s_1X_to_5X"],
                             1e-3) < 1e-4


def test_study_cascade_method_shooting_stores_the_floquet_verdict(damped_jeffcott, tmp_path, capsys):
    from sweep import load_sweep

    out = tmp_path / "casc"
    rc, _, err = _run(["study", "cascade", "--scene", damped_jeffcott, "--method", "shooting", "--rpm-min", 0,
                       "--rpm-max", 2000, "--points", 3, "--workers", 1, "--no-progress", "--out", out], capsys)
    assert rc == 0, err
    pts = load_sweep(out, complete=True)
    got = {round(p.params["speed_rpm"]): (p.info["classification"], p.info["classified_by"]) for p in pts.values()}
    assert got == {0: ("static", "static"), 1000: ("periodic", "multipliers"), 2000: ("periodic", "multipliers")}
    assert all(p.params["method"] == "shooting" for p in pts.values())
