"""A user's linear branch (issue 36): Friswell, Penny, Garvey & Lees (2010), Example 5.9.1, with its right bearing
in a loose aluminium housing and 2 000 N of preload (tests/rotor/scenes/friswell-591-loose-aluminium.toml). The
end faces hold the ring through the whole period (μN = 200 N against a holding force of 20-40 N): every orbit is
one of a family held by friction (four neutral multipliers) and the rotor is linear, the ring locked to its
housing at the offset where it stuck.

The branch 2 300 -> 2 800 rpm crosses the second forward whirl (disk 2's 1X velocity peaks near 2 495 rpm). Before
this fix it restarted six times between 2 470 and 2 661 rpm: the phase rows of the stuck continuum were the right
null vectors of M - I, which let the ring's offset drift along the branch (0 at 2 300 rpm, 19.8 µm of its 20 µm
clearance at 2 470 rpm), until the predictor put the ring into radial contact and the holding force past μN
(rotor/periodic/corrector.py, neutral_rows). Expected values and their sources:

* the book's whirl frequencies at rest, 86.66, 274.31 and 716.78 rad/s (Friswell et al. 2010, Example 5.9.1, as
  tests/docs/test_gallery.py checks them for docs/examples/ex07_your_rotor.py), of this file's rotor with the
  support put back as the book's 1 MN/m bearing;
* every orbit's 1X velocity amplitudes: the linear steady state with the loose support locked
  (rotor/dynamics/linear_response.py, harmonic superposition; a stuck ring at a constant offset is that linear
  rotor), to the Newmark scheme's O(Δt²) error (tolerance below);
* the peak: the orbit shot at the peak's speed (rotor/studies/orbit.py, from a transient, no continuation) to 1 %
  (the issue's bound), and the linear response's own peak over the range on a 1 rpm grid to 1 %;
* the last orbit at --rpm-end itself (the issue: a branch that ended at 2 822 rpm).
"""
import math
from pathlib import Path

import numpy as np
import pytest

from rotor.dynamics.linear_response import periodic_response
from rotor.periodic.period_flow import make_flow, to_full
from rotor.studies.orbit import branch, orbit
from rotor.studies.steady_state import harmonic_amplitudes, point_system

SCENE = str(Path(__file__).parents[1] / "scenes" / "friswell-591-loose-aluminium.toml")
RPM_START, RPM_END = 2300.0, 2800.0
#: Friswell et al. (2010), Example 5.9.1: whirl frequencies at rest (rad/s), each twice
BOOK_AT_REST_RAD_S = [86.66, 86.66, 274.31, 274.31, 716.78, 716.78]
#: the channel whose 1X velocity peaks inside the range (the second forward whirl)
PEAK_CHANNEL = "disk2.y"
#: the trapezoidal rule's error in the 1X amplitude is C (π/N)² (O(Δt²)); measured on this rotor at 2 520 rpm,
#: C = 2.6-2.8 at N = 1 024, 2 048 and 4 096 steps per revolution (2.6e-5, 6.5e-6, 1.6e-6: a factor 4 per
#: halving), at most 3.3 over the whole range at N = 2 048 (7.9e-6); the bound takes C = 5
NEWMARK_COEFF = 5.0


@pytest.fixture(scope="module")
def result():
    """The 2 000 N branch 2 300 -> 2 800 rpm at the scene's own steps per revolution (2 048), amplitudes recorded."""
    return branch(SCENE, RPM_START, RPM_END)


def _linear_1x_mm_s(rpm: float, names, n: int) -> dict:
    """1X velocity amplitudes (mm/s) of the linear steady state with the loose support locked at ``rpm``, sampled
    at the branch's ``n`` steps per revolution and reduced as the branch reduces its orbits."""
    _, model, system = point_system(SCENE, rpm)
    t = np.arange(n) * 2.0 * math.pi / (rpm * math.pi / 30.0) / n
    _, v = periodic_response(system, t)
    out = {}
    for name in names:
        col = v[:, [model.dof_index(name)]]
        out[name] = abs(harmonic_amplitudes(col - col.mean(axis=0), 1, (1,))[0, 0]) * 1e3
    return out


def test_the_scene_is_the_books_rotor():
    """With the loose support put back as the book's 1 MN/m bearing (undamped, no unbalance), the scene's rotor
    has the book's whirl frequencies at rest to 0.01 rad/s."""
    import dataclasses

    import ringcontact as rc

    s = rc.load_scene(SCENE)
    assert s.loose_support.preload_n == 2000.0 and s.loose_support.support_modulus_pa == 70e9
    book = s.replace(supports=(), loose_support=None,
                     bearings=tuple(dataclasses.replace(b, damping_n_s_m=0.0) for b in s.bearings)
                     + (rc.Bearing("right", "N6", stiffness_n_m=1e6),),
                     disks=tuple(dataclasses.replace(d, unbalance_kg_m=0.0) for d in s.disks))
    assert rc.modes(book, 0.0).frequency_rad_s == pytest.approx(BOOK_AT_REST_RAD_S, abs=0.01)


def test_the_stuck_branch_has_no_stall_and_ends_at_rpm_end(result):
    """Every orbit reached by the corrector from the one before (no restart, no corrector failure, nothing
    skipped), every one stuck through the period (no face switch, a family: not unique), the last one at
    --rpm-end itself."""
    b = result.branch
    assert result.stop == "end reached" and b.restarts == 0 and b.failures == ()
    assert not any(p.restarted for p in b.points)
    assert all(p["switches_per_period"] == 0 and not p["unique"] for p in result.points)
    assert result.points[-1]["speed_rpm"] == pytest.approx(RPM_END, abs=1e-9)
    assert all(a["speed_rpm"] < b_["speed_rpm"] for a, b_ in zip(result.points, result.points[1:]))


def test_the_ring_keeps_the_offset_it_stuck_at(result):
    """The stuck faces hold the ring's offset from its housing through every period, and the branch keeps it from
    orbit to orbit (the continuum's conserved levels as phase rows): the same to 1e-12 m at every speed (the
    offset is 0 here: the transient from the linear periodic solution starts centred and the faces hold from the
    start)."""
    n = result.start.steps_per_rev
    offsets = []
    for p in result.branch.points:
        system = point_system(SCENE, p.parameter * 30.0 / math.pi)[2]
        q, _ = to_full(make_flow(system, 2.0 * math.pi / (p.parameter * n)), p.state, 0.0)
        offsets.append(system.support.relative_map(system.n) @ q)
    offsets = np.array(offsets)
    assert np.max(np.abs(offsets[:, :2] - offsets[0, :2])) < 1e-12


def test_every_orbit_is_the_locked_linear_response(result):
    """At every orbit of the branch and every response channel, the 1X velocity amplitude equals the linear
    steady state with the support locked within C (π/N)² (module docstring: the trapezoidal rule's O(Δt²))."""
    n = result.start.steps_per_rev
    tol = NEWMARK_COEFF * (math.pi / n) ** 2
    for p in result.points:
        amps = p["velocity_amplitudes_mm_s_1X_to_5X"]
        lin = _linear_1x_mm_s(p["speed_rpm"], amps, n)
        for name, a in amps.items():
            assert a[0] == pytest.approx(lin[name], rel=tol), (p["speed_rpm"], name)


def test_the_peak_is_the_orbits_at_its_speed_and_the_linear_peak(result):
    """The branch's peak of disk 2's 1X velocity equals, to 1 %, the orbit shot at that speed on its own (from a
    transient, as ``ringcontact orbit`` does) and the peak of the linear response over the range (1 rpm grid)."""
    amps = [p["velocity_amplitudes_mm_s_1X_to_5X"][PEAK_CHANNEL][0] for p in result.points]
    k = int(np.argmax(amps))
    assert 0 < k < len(amps) - 1                     # a peak inside the range: the resonance is on the branch
    rpm = result.points[k]["speed_rpm"]
    o = orbit(SCENE, rpm, steps_per_rev=result.start.steps_per_rev)
    assert o.converged
    assert amps[k] == pytest.approx(o.velocity_amplitudes_mm_s_1X_to_5X[PEAK_CHANNEL][0], rel=0.01)
    grid = np.arange(RPM_START, RPM_END + 0.5, 1.0)
    import ringcontact as rc
    u = rc.unbalance_response(rc.load_scene(SCENE), list(grid))
    j = list(u.stations).index(PEAK_CHANNEL.split(".")[0])
    linear_peak_mm_s = float(np.max(u.amplitude_y_m[:, j] * grid * math.pi / 30.0)) * 1e3
    assert amps[k] == pytest.approx(linear_peak_mm_s, rel=0.01)


@pytest.mark.slow
def test_the_command_line_branch_both_ways(tmp_path):
    """``ringcontact branch`` as the user ran it, up (2 300 -> 2 800 rpm) and down (2 800 -> 2 300 rpm): no restart,
    no corrector failure, no skipped speeds, the last orbit at --rpm-end."""
    import json
    import subprocess
    import sys

    for start, end in ((RPM_START, RPM_END), (RPM_END, RPM_START)):
        out = tmp_path / f"branch-{start:g}-{end:g}.json"
        subprocess.run([sys.executable, "-m", "reports.cli", "branch", SCENE, "--rpm-start", f"{start:g}", "--rpm-end",
                        f"{end:g}", "--accept-long", "--json", "--out", str(out)], check=True, capture_output=True)
        d = json.loads(out.read_text())
        assert d["stop"] == "end reached" and not any(d["restarts"].values()) and d["corrector_failures"] == []
        assert not any("skipped_rpm" in p for p in d["points"])
        assert d["points"][-1]["speed_rpm"] == pytest.approx(end, abs=1e-9)


def test_a_failed_landing_is_shot_at_rpm_end_and_said(monkeypatch):
    """Where the corrector on λ = rpm_end fails (forced here), the last orbit is shot at rpm_end itself from the
    interpolated state (Newton at fixed speed), not left beyond it, and the branch says so in its failures; the
    orbit is the locked linear response there (to C (π/N)², as every orbit of the branch)."""
    import rotor.periodic.continuation as cont

    end = 2340.0
    monkeypatch.setattr(cont, "land", lambda *a, **k: None)
    shot = branch(SCENE, RPM_START, end)
    assert shot.points[-1]["speed_rpm"] == pytest.approx(end, abs=1e-9) and shot.branch.restarts == 0
    (lam, why, outcome), = shot.branch.failures
    assert lam == pytest.approx(end * math.pi / 30.0) and outcome.startswith("shot at fixed speed_rad_s")
    amps = shot.points[-1]["velocity_amplitudes_mm_s_1X_to_5X"]
    lin = _linear_1x_mm_s(end, amps, shot.start.steps_per_rev)
    for name, a in amps.items():
        assert a[0] == pytest.approx(lin[name], rel=NEWMARK_COEFF * (math.pi / shot.start.steps_per_rev) ** 2), name


@pytest.fixture(scope="module")
def result_200n():
    """The 200 N branch 2 300 -> 2 800 rpm with the friction solved by projection (``friction_scheme="projection"``,
    rotor/dynamics/constraints.py ``coulomb_projection``): μN = 20 N per face, which the right face's step-mean
    force reaches near the peak (measured at 2 484 rpm: 20.0 N, the face slips there)."""
    return branch(SCENE, RPM_START, RPM_END, preload_n=200.0, friction_scheme="projection")


def test_the_200_n_branch_by_projection_has_no_restart_and_its_peak_is_the_orbits(result_200n):
    """Issue 36's must-show for the 200 N preload: no restart, no corrector failure, the last orbit at --rpm-end
    itself, and the peak of disk 2's 1X velocity inside the range and within 1 % of the orbit shot at that speed on
    its own (from a transient, the same scheme). With the active-set scheme this branch restarted 2 to 16 times by
    where its steps fell (2 300 or 2 300.5 rpm start), at jumps of its map."""
    b = result_200n.branch
    assert result_200n.stop == "end reached" and b.restarts == 0 and b.failures == ()
    assert result_200n.points[-1]["speed_rpm"] == pytest.approx(RPM_END, abs=1e-9)
    amps = [p["velocity_amplitudes_mm_s_1X_to_5X"][PEAK_CHANNEL][0] for p in result_200n.points]
    k = int(np.argmax(amps))
    assert 0 < k < len(amps) - 1
    o = orbit(SCENE, result_200n.points[k]["speed_rpm"], steps_per_rev=result_200n.start.steps_per_rev,
              preload_n=200.0, friction_scheme="projection")
    assert o.converged
    assert amps[k] == pytest.approx(o.velocity_amplitudes_mm_s_1X_to_5X[PEAK_CHANNEL][0], rel=0.01)


@pytest.mark.parametrize("preload_n", [200.0, 2000.0])
def test_the_command_line_branch_by_projection_at_both_preloads(tmp_path, preload_n):
    """``ringcontact branch --friction-scheme projection`` up 2 300 -> 2 800 rpm at 200 N and 2 000 N of preload (the
    issue's two cases): no restart, no corrector failure, the last orbit at --rpm-end, the JSON naming the scheme
    (measured 8-9 s each with the compiled code cached, none restarted)."""
    import json
    import subprocess
    import sys

    out = tmp_path / "branch.json"
    subprocess.run([sys.executable, "-m", "reports.cli", "branch", SCENE, "--rpm-start", f"{RPM_START:g}", "--rpm-end",
                    f"{RPM_END:g}", "--preload-n", f"{preload_n:g}", "--friction-scheme", "projection", "--accept-long",
                    "--json", "--out", str(out)], check=True, capture_output=True)
    d = json.loads(out.read_text())
    assert d["friction_scheme"] == "projection"
    assert d["stop"] == "end reached" and not any(d["restarts"].values()) and d["corrector_failures"] == []
    assert d["points"][-1]["speed_rpm"] == pytest.approx(RPM_END, abs=1e-9)
