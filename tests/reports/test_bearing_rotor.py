"""The second ring pair's law driving a rotor: rotor/scenes/table4-steel-in-aluminium.toml names the law file
that ``ringcontact bearing steel-in-aluminium`` wrote (reports/published/bearing-steel-in-aluminium/), and
simulate, orbit and a small study cascade run on it."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from contact.calibrate import CalibratedLaw
from fem_reference import ring_scene
from rotor.model.scene import load_scene

ROOT = Path(__file__).resolve().parents[2]
LAW = ROOT / "rotor" / "scenes" / "laws" / "steel-in-aluminium-law.json"
SCENE = "table4-steel-in-aluminium"


def test_the_bundled_law_is_the_published_one_for_the_bundled_ring_pair():
    """Provenance chain: ring-pair file -> published run -> the rotor's copy of the law, checksums equal."""
    assert LAW.read_bytes() == (ROOT / "reports/published/bearing-steel-in-aluminium/steel-in-aluminium-law.json").read_bytes()
    law = CalibratedLaw.from_json(LAW.read_text())
    assert law.provenance["ring_scene"]["sha256"] == ring_scene.load("steel-in-aluminium").sha256
    assert law.provenance["warnings"] == [] and law.validity_tilt_max_rad > 0


def test_scene_takes_its_geometry_from_the_law():
    """The scene gives no clearance, width or materials: they are the ring-pair file's
    (fem_reference/ring_scenes/steel-in-aluminium.toml: 0.03 mm, 22 mm, 208 GPa/0.29, 72 GPa/0.33)."""
    ls = load_scene(SCENE).loose_support
    assert (ls.clearance_m, ls.ring_width_m, ls.bearing_modulus_pa, ls.bearing_poisson, ls.support_modulus_pa,
            ls.support_poisson) == pytest.approx((3e-5, 0.022, 208e9, 0.29, 72e9, 0.33))
    assert ls.calibrated.name == "steel-in-aluminium-3d-foundation-spline"


def test_simulate_with_the_law_reports_contact_and_validity(tmp_path, capsys):
    from reports.cli.simulate import main
    assert main(["--scene", SCENE, "--speed-rpm", "6000", "--revolutions", "60", "--out", str(tmp_path / "s")]) == 0
    s = json.loads((tmp_path / "s" / "simulate-summary.json").read_text())
    assert s["law"] == "steel-in-aluminium-3d-foundation-spline" and Path(s["law_file"]).name == LAW.name
    assert s["contact_fraction"] > 0 and s["max_edge_penetration_mm"] > 0
    assert s["beyond_law_validity"] is False and s["law_validity_max_penetration_mm"] == pytest.approx(0.04)
    assert s["law_tilt_checked_up_to_arcmin"] == pytest.approx(2.0) and s["beyond_law_tilt_validity"] is False
    assert 0 < s["max_tilt_in_contact_arcmin"] < 2.0


def test_small_cascade_with_the_law(tmp_path, capsys):
    from reports.cli.study import main
    out = tmp_path / "c"
    assert main(["cascade", "--scene", SCENE, "--rpm-min", "6000", "--rpm-max", "9000", "--points", "2",
                 "--max-revs", "200", "--out", str(out), "--no-progress", "--workers", "1"]) == 0
    rows = (out / "figures" / "study-cascade.csv").read_text().splitlines()
    head = rows[0].split(",")
    assert len(rows) == 3 and "beyond_law_validity" in head
    for r in rows[1:]:
        cells = dict(zip(head, r.split(",")))
        assert float(cells["contact_fraction"]) > 0 and cells["beyond_law_validity"] == "0"


@pytest.mark.slow
def test_orbit_with_the_law(tmp_path, capsys):
    """The periodic orbit at 6000 rpm names the law and its validity. Measured: period 7 revolutions after 195
    transient revolutions with events located (the default since the fourth session of 2026-11-27; 2 revolutions with
    the plain step), 66 s: slow. The law in the rotor stays in the default run through test_small_cascade_with_the_law."""
    from reports.cli.orbit import main
    assert main([SCENE, "--speed-rpm", "6000", "--out", str(tmp_path / "o.json")]) == 0
    d = json.loads((tmp_path / "o.json").read_text())
    assert d["converged"] and Path(d["law_file"]).name == LAW.name
    assert 0 < d["max_edge_penetration_mm"] < 0.04 and d["beyond_law_validity"] is False
    assert 0 < d["max_tilt_in_contact_arcmin"] < 2.0 and d["law_tilt_checked_up_to_arcmin"] == pytest.approx(2.0)
    assert d["beyond_law_tilt_validity"] is False


def test_law_job_evaluates_a_law_file_and_flags_beyond_its_checked_range(capsys):
    """``ringcontact law --law FILE``: the law file's own geometry; at zero tilt its 3D-calibrated force at a
    fitted point within its held-out error of the 3D FEM (reports/published/bearing-steel-in-aluminium/
    fem3d-steel-in-aluminium.json); beyond the fitted penetration or the checked tilt: outside_domain, no number."""
    from contact.dataset import read_dataset
    from reports.cli.law import main
    assert main(["--law", str(LAW), "--penetration-mm", "0.01", "0.05", "--tilt-arcmin", "0", "1", "3", "--json"]) == 0
    pts = json.loads(capsys.readouterr().out)["points"]
    by = {(p["penetration_mm"], p["tilt_arcmin"]): p for p in pts}
    fem = next(p for p in read_dataset(ROOT / "reports/published/bearing-steel-in-aluminium/fem3d-steel-in-aluminium.json").points
               if abs(p["penetration_m"] - 1e-5) < 1e-12 and p["tilt_rad"] == 0.0)
    law = CalibratedLaw.from_json(LAW.read_text())
    held_out = law.provenance["checks"]["holdout_max_rel_3d_zero_tilt"]
    assert abs(by[(0.01, 0.0)]["force_N"] / fem["force_n"] - 1) <= held_out
    assert by[(0.01, 1.0)]["outside_domain"] is False
    assert by[(0.05, 0.0)]["outside_domain"] is True and by[(0.05, 0.0)]["force_N"] is None
    assert by[(0.01, 3.0)]["outside_domain"] is True and by[(0.01, 3.0)]["force_N"] is None


def test_a_run_that_crosses_the_contact_step_limit_says_so(tmp_path, capsys):
    """The numerical guard during a run: 38 steps a revolution pass the pre-run check (the law probed at 0.2 δ0,
    rotor/dynamics/system.py) but the ring at 17 000 rpm penetrates deeper (about 0.33 δ0), where the law is
    stiffer: the run meets ω_c·Δt > 2 (measured 3.21 on the foundation-spline law, 3.39 on the foundation law before
    it). The summary and stderr say so and name a finer step, with which the same run stays below the limit (measured
    1.61 at the 77 steps named; 1.61 at 81 before)."""
    from reports.cli.simulate import STEP_LIMIT_OMEGA_DT, main
    argv = ["--scene", SCENE, "--speed-rpm", "17000", "--revolutions", "200", "--record-per-rev", "1"]
    assert main([*argv, "--steps-per-rev", "38", "--out", str(tmp_path / "coarse")]) == 0
    s = json.loads((tmp_path / "coarse" / "simulate-summary.json").read_text())
    assert s["max_omega_c_dt"] > STEP_LIMIT_OMEGA_DT and s["step_limit_exceeded"] is True
    assert "contact step limit was crossed" in capsys.readouterr().err
    n = s["steps_per_rev_for_step_limit"]
    assert main([*argv, "--steps-per-rev", str(n), "--out", str(tmp_path / "fine")]) == 0
    f = json.loads((tmp_path / "fine" / "simulate-summary.json").read_text())
    assert f["step_limit_exceeded"] is False and f["max_omega_c_dt"] <= STEP_LIMIT_OMEGA_DT
    assert "step limit" not in capsys.readouterr().err


def test_a_run_beyond_the_budget_is_refused_before_it_starts(tmp_path, capsys):
    """Long work announced before it starts: 100 000 revolutions recorded at every step of 256 would hold
    2.56e7 records (tens of GiB); refused at once with the estimate and the flag that accepts it, nothing written.
    The estimate's step cost is the measured one (reports/published/perf-period-map.md)."""
    from reports.cli.simulate import MEMORY_BUDGET_BYTES, work_estimate, main
    assert main(["--speed-rpm", "10500", "--revolutions", "100000", "--record-per-rev", "256",
                 "--out", str(tmp_path / "big")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "GiB of records" in err[0] and "--accept-long" in err[0] and "100000 rev" in err[0]
    assert not (tmp_path / "big").exists() or not any((tmp_path / "big").iterdir())
    secs, nbytes = work_estimate(25_600_000, 25_600_001, 28, "production")
    assert nbytes > MEMORY_BUDGET_BYTES and 60 < secs < 600      # 1.8 min of stepping: the records are the problem
