"""Unstable rotors are called unstable (issue 40): a cross-coupled bearing ``k_yz = -k_zy`` (a follower force)
feeds one whirl direction; its mode's damping ratio turns negative. Every linear job says so on stderr, names the
mode (its frequency and damping ratio) and puts it in its JSON; ``simulate`` says the divergence is the rotor's,
not the contact law's. The stable control is the same scene without the cross-coupling.
"""
from __future__ import annotations

import json
import re

import pytest
from unstable_scenes import table4_cross_coupled

from reports import cli
from rotor.linear.modes import modes
from rotor.linear.stability import first_unstable, linearisation_unstable, unstable_modes
from rotor.model.assembly import assemble
from rotor.model.scene import load_scene, scene_path

RPM = 3.141592653589793 / 30


def _jeffcott(tmp_path, k_cross: float, name: str = "cc.toml"):
    """verify-jeffcott with damped bearings (200 N·s/m) cross-coupled by k_yz = -k_zy = ``k_cross`` (N/m)."""
    text = scene_path("verify-jeffcott").read_text(encoding="utf-8").replace(
        "stiffness_n_per_m = 2.0e6\n", f"stiffness_n_per_m = 2.0e6\ndamping_n_s_per_m = 200\n"
        f"stiffness_yz_n_per_m = {k_cross:g}\nstiffness_zy_n_per_m = {-k_cross:g}\n")
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_cross_coupling_destabilises_one_whirl_direction(tmp_path):
    for k, whirl in ((1e6, "forward"), (-1e6, "backward")):
        model = assemble(load_scene(_jeffcott(tmp_path, k)))
        bad = unstable_modes(model, 0.0)
        ref = modes(model, 0.0, damped=True)
        assert len(bad) == 1 and bad[0].whirl == whirl, bad
        j = bad[0].mode - 1
        assert bad[0].damping_ratio == ref.damping_ratio[j] < 0 and bad[0].frequency_hz == ref.frequency_hz[j]
        assert bad[0].growth_rate_1_s > 0
    assert not unstable_modes(assemble(load_scene(_jeffcott(tmp_path, 0.0))), 0.0)


def test_first_unstable_looks_over_a_sweep(tmp_path):
    model = assemble(load_scene(_jeffcott(tmp_path, 1e6)))
    found = first_unstable(model, [w * RPM for w in range(0, 3001, 10)])
    assert found is not None and found.speed_rpm == 0.0
    assert first_unstable(assemble(load_scene(_jeffcott(tmp_path, 0.0))), [0.0, 3000 * RPM]) is None


def _run(argv, capsys):
    rc = cli.main([str(a) for a in argv])
    out = capsys.readouterr()
    return rc, out.out, out.err


JOBS = [("modes", []), ("campbell", []), ("unbalance", []),
        ("response", ["--speed-rpm", "1064", "--revolutions", "2", "--out", "{tmp}/r"])]


@pytest.mark.parametrize("job,extra", JOBS, ids=[j for j, _ in JOBS])
def test_every_linear_job_says_unstable_and_names_the_mode(job, extra, tmp_path, capsys):
    scene = _jeffcott(tmp_path, 1e6)
    model = assemble(load_scene(scene))
    ref = unstable_modes(model, 0.0)[0]
    rc, out, err = _run(["rotor", job, scene, "--json", *[a.format(tmp=tmp_path) for a in extra]], capsys)
    assert rc == 0, err
    line = [ln for ln in err.splitlines() if "unstable" in ln]
    assert len(line) == 1 and f"mode {ref.mode} ({ref.frequency_hz:.4g} Hz, forward whirl)" in line[0], err
    assert f"damping ratio {ref.damping_ratio:.3g}" in line[0], line[0]
    stab = json.loads(out)["stability"]
    assert stab["stable"] is False and stab["unstable_mode"]["damping_ratio"] == pytest.approx(ref.damping_ratio,
                                                                                                rel=1e-6)
    if job == "response":         # the summary file says it too
        assert json.loads((tmp_path / "r" / "response-summary.json").read_text())["stability"] == stab
    rc, out, err = _run(["rotor", job, _jeffcott(tmp_path, 0.0, "stable.toml"), "--json",
                         *[a.format(tmp=tmp_path) for a in extra]], capsys)
    assert rc == 0 and "unstable" not in err and json.loads(out)["stability"] == {"stable": True,
                                                                                  "unstable_mode": None}


def test_simulate_says_the_divergence_is_the_rotors(tmp_path, capsys):
    scene = table4_cross_coupled(tmp_path, 1e7)
    found = linearisation_unstable(assemble(load_scene(scene)), 3000 * RPM)
    assert found is not None and found.damping_ratio < 0
    rc, out, err = _run(["simulate", "--scene", scene, "--speed-rpm", "3000", "--revolutions", "40", "--out",
                         tmp_path / "o"], capsys)
    lines = err.strip().splitlines()
    assert "warning: unstable rotor" in lines[0] and f"mode {found.mode}" in lines[0], err
    assert rc != 0 and len(lines) == 2 and "error: the rotor is unstable" in lines[1], err
    assert "whatever the contact law" in lines[1] and "use a larger clearance" not in lines[1], lines[1]
    assert re.search(rf"damping ratio {found.damping_ratio:.3g}", lines[1]) and not (tmp_path / "o").exists()
