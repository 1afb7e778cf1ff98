"""``ringcontact orbit/branch --method hb|shooting|auto``, ``--harmonics`` and ``--richardson`` (reports/cli/orbit.py,
reports/cli/_orbit_hb.py, rotor/studies/orbit_methods.py, rotor/studies/hb_orbit.py).

Case: one Jeffcott rotor in a conformal ring written as a scene (rotor/periodic/jeffcott_scene.py, the commit's
seed), whose synchronous orbit has a closed form both in continuous time (what HB must give) and for the
average-acceleration Newmark scheme at N steps per revolution (what shooting must give: the warped frequency
``Ω' = Ω tan(π/N)/(π/N)`` in inertia and damping, and the scheme's velocity of a whirl ``X e^{iΩt}`` is ``iΩ'X``, the
trapezoidal rule's). So the cross-check's difference between the two methods is known in advance.
"""
from __future__ import annotations

import json
import math

import pytest
from seeds import commit_seed

from reports.cli.orbit import branch_main, main
from rotor.periodic.jeffcott_scene import closed_form_grazing, closed_form_radius, contact_force_N, random_family, scene_toml
from rotor.studies.orbit_methods import auto_choice

TO_RPM = 30.0 / math.pi


@pytest.fixture(scope="module")
def ring(tmp_path_factory):
    rotor = random_family(commit_seed(), 1)[0]
    path = tmp_path_factory.mktemp("scene") / "jeffcott-ring.toml"
    path.write_text(scene_toml(rotor), encoding="utf-8")
    return rotor, str(path)


def _velocity_1x(rotor, speed: float, radius: float, n: int | None) -> dict:
    """Closed-form 1X velocity amplitudes (mm/s) of the disk and the support node: ``D = X − S`` of radius r,
    ``S = g D / B``, ``X = D (1 + g/B)``; the velocity amplitude is ``Ω'|·|`` (``Ω' = Ω`` in continuous time)."""
    w = speed if n is None else speed * math.tan(math.pi / n) / (math.pi / n)
    g = contact_force_N(rotor, radius) / radius
    B = complex(rotor.support_stiffness_N_m - rotor.support_mass_kg * w * w, rotor.support_damping_N_s_m * w)
    return {"d": w * radius * abs(1.0 + g / B) * 1e3, "housing": w * radius * abs(g / B) * 1e3}


def test_auto_is_hb_on_the_frictionless_ring_and_shooting_checks_it_as_the_closed_forms_say(ring, tmp_path):
    rotor, scene = ring
    graze = [w for w, kind in closed_form_grazing(rotor)]
    speed = math.sqrt(graze[0] * graze[1])          # between the grazing and the grazing fold: one orbit, in contact
    out = tmp_path / "o.json"
    assert main([scene, "--speed-rpm", repr(speed * TO_RPM), "--method", "auto", "--richardson", "--out", str(out),
                 "--json"]) == 0
    d = json.loads(out.read_text(encoding="utf-8"))
    assert d["method"] == "hb" and d["harmonics"] == 2 and d["stable"] is None, d["method_choice"]
    assert d["method_choice"]["method"] == "hb" and "spectrum converged" in d["method_choice"]["reason"]
    r = rotor.clearance_m + d["max_edge_penetration_mm"] * 1e-3      # a circular whirl: δ0 + its penetration
    assert d["max_edge_penetration_mm"] > 0.0
    assert closed_form_radius(rotor, speed, r) == pytest.approx(r, rel=1e-10)
    cont = _velocity_1x(rotor, speed, r, None)
    for ch in ("d", "housing"):
        assert d["velocity_amplitudes_mm_s_1X_to_5X"][f"{ch}.y"][0] == pytest.approx(cont[ch], rel=1e-9)
    cc = d["cross_check"]
    n = cc["shooting_steps_per_rev"]
    disc = _velocity_1x(rotor, speed, closed_form_radius(rotor, speed, r, n), n)
    expected = {ch: abs(disc[ch] - cont[ch]) for ch in ("d", "housing")}
    ch = cc["channel"].split(".")[0]
    assert ch in expected, cc
    # shooting's own error (Newton at 1e-9 of the orbit) is below 1e-4 of this O(h²) difference (~5e-5 relative)
    assert cc["largest_1X_difference_mm_s"] == pytest.approx(expected[ch], rel=1e-3), (cc, expected)
    assert cc["largest_1X_difference_mm_s"] >= max(expected.values()) * (1 - 1e-3)
    # Richardson leaves O(h⁴): (π/N)⁴ = 2.2e-8 at N = 256, times the amplitude's sensitivity to the warp (~1)
    assert cc["richardson"]["largest_1X_difference_rel"] < 1e-7, cc


def test_default_method_is_shooting_with_its_keys_unchanged(ring, tmp_path):
    rotor, scene = ring
    out = tmp_path / "o.json"
    speed = 0.5 * closed_form_grazing(rotor)[0][0]     # free orbit: quick
    assert main([scene, "--speed-rpm", repr(speed * TO_RPM), "--out", str(out), "--json"]) == 0
    d = json.loads(out.read_text(encoding="utf-8"))
    assert d["method"] == "shooting" and "cross_check" not in d and "richardson" not in d
    assert {"multipliers", "spectral_radius", "phase0_state", "steps_per_rev", "stable"} <= d.keys()


def test_auto_runs_shooting_where_the_ring_has_end_face_friction_and_says_why(tmp_path):
    pt, choice = auto_choice("paper-table4", 10500.0)
    assert pt is None and choice["method"] == "shooting" and "end-face friction" in choice["reason"]
    assert choice["hb_cpu_s"] is None                     # refused before any HB work


def test_branch_method_hb_reports_the_grazing_of_the_closed_form(ring, tmp_path):
    rotor, scene = ring
    w = closed_form_grazing(rotor)[0][0]
    out = tmp_path / "b.json"
    assert branch_main([scene, "--rpm-start", repr(0.9 * w * TO_RPM), "--rpm-end", repr(1.1 * w * TO_RPM),
                        "--method", "hb", "--harmonics", "1", "--out", str(out)]) == 0
    d = json.loads(out.read_text(encoding="utf-8"))
    assert d["method"] == "hb" and d["harmonics"] == 1 and d["stop"] == "end reached"
    assert all(p["stable"] is None and "velocity_amplitudes_mm_s_1X_to_5X" in p for p in d["points"])
    found = [b["speed_rpm"] for b in d["bifurcations"] if b["kind"] == "grazing"]
    assert len(found) == 1 and found[0] == pytest.approx(w * TO_RPM, rel=1e-3)


@pytest.mark.parametrize("argv, words", [
    (["orbit", "--method", "foo"], ["--method = foo", "shooting, hb, auto"]),
    (["orbit", "--harmonics", "0"], ["--harmonics = 0", "[1, 64]"]),
    (["orbit", "--method", "hb"], ["--method = hb", "end-face friction", "shooting, auto"]),
    (["branch", "--method", "hb"], ["--method = hb", "end-face friction", "shooting, auto"]),
    (["orbit", "--method", "hb", "--mu", "0", "--richardson"], ["--richardson", "--method hb has no step"]),
    (["branch", "--method", "hb", "--mu", "0", "--turn-back-rpm", "500"], ["--turn-back-rpm = 500", "shooting option"]),
])
def test_bad_method_options_are_refused_in_one_line_with_status_2(argv, words, capsys):
    job, *rest = argv
    base = (["paper-table4", "--speed-rpm", "10500"] if job == "orbit" else
            ["paper-table4", "--rpm-start", "10000", "--rpm-end", "11000"])
    run = main if job == "orbit" else branch_main
    try:
        rc = run([*base, *rest])
    except SystemExit as e:          # argparse's own refusals
        rc = e.code
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1, err
    assert err.startswith(f"ringcontact {job}: error: ") and all(w in err for w in words), err
