"""The paper's Section 5 findings (Dai et al. 2025) checked on our numbers, on two meshes.

Table 4 rotor, the paper's conformal law as published, the misalignment excitation read as
``inertial-at-joint`` (reports/published/rotor-misalignment.md), the tilt-ignored case without any
moment between bearing and support (§5.2), the scene's documented assumptions for the inputs the
paper does not give. Each finding is checked on the paper's mesh (one element per shaft segment,
``paper``) and on a mesh converged to 1 % at the third critical speed (two elements per segment,
``converged``; reports/published/rotor-mesh.md). Points: 4 500 rpm (the paper's point A) and
10 500 rpm (point B). Amplitudes are of the y velocity, as in the paper's spectra (Figs. 12–16).

Where a finding does NOT hold on our numbers the test still states the paper's claim and is
marked ``xfail(strict=True)`` with the measured numbers in the reason: it documents the
disagreement and flags (XPASS → failure) the day a model change makes the claim hold.

Variants (other clearance, misalignment, tilt ignored) start from the scene's own steady state at
the same speed (continuation), so they compare neighbouring states of one branch. The transient cap
is 8 000 revolutions: at point A the end faces creep by stick-slip for about 2 000 revolutions
before the ring settles, stuck, against the bore.
"""
import numpy as np
import pytest

from rotor.studies.steady_state import SteadyStateOptions, point_system, steady_state

OPTS = SteadyStateOptions(spectrum_revs=16, max_revs=8000)
LOC = ("disk1.y", "disk2.y", "s.y")
MESHES = {"paper": None, "converged": 2}
_CACHE = {}


def point(mesh, rpm, **kw):
    """Steady state at ``rpm`` on ``mesh`` with overrides; cached for the module.

    A state must be periodic, except one that creeps: its Poincaré points still move, but by less
    than the tolerance per revolution (the tilt-ignored state at point B on the paper's mesh slides
    on its end face by 2e-5 of its amplitude per revolution after 8 000 revolutions): its 16 recorded
    revolutions are then a steady state to that accuracy."""
    key = (mesh, rpm, tuple(sorted(kw.items())))
    if key not in _CACHE:
        start = {}
        if kw:
            base = point(mesh, rpm)[0]
            start = {"q0": base.q_end, "v0": base.v_end}
        _, model, system = point_system("paper-table4", rpm, elements_per_segment=MESHES[mesh], **kw)
        res = steady_state(system, model, options=OPTS, **start)
        c = res.convergence
        assert c.converged or c.change < OPTS.tol, f"{mesh} {rpm} rpm {kw}: no steady state ({c})"
        H = res.harmonics("v")  # (5, channels) m/s
        _CACHE[key] = (res, {c: H[:, res.channel(c)] for c in LOC})
    return _CACHE[key]


def _xfail(mesh, reason):
    return pytest.param(mesh, marks=pytest.mark.xfail(strict=True, reason=reason))


@pytest.mark.parametrize("mesh", list(MESHES))
def test_point_a_2X_from_misalignment_highest_at_the_support_which_moves_with_the_rotor(mesh):
    """Dai 2025 §5.1, Fig. 13 (4 500 rpm): spectra dominated by f, with 2X 'caused by misalignment';
    the support moves with the rotor (no relative movement); 2X relatively higher at the 3# bearing."""
    res1, h1 = point(mesh, 4500.0)
    res0, h0 = point(mesh, 4500.0, misalignment_m=0.0)
    assert res1.regime()["stick_fraction"] == 1.0          # both end faces stuck at every sample
    r = {c: h1[c][1] / h1[c][0] for c in LOC}
    assert r["s.y"] >= 0.05 and r["s.y"] > r["disk2.y"] > r["disk1.y"] > 1e-3, r
    for c in LOC:                                          # no misalignment: 2X/1X 1e4 times smaller at least
        assert h0[c][1] / h0[c][0] <= 1e-4 * r[c], c       # (measured 1.9e-6 at the support against 0.34)


@pytest.mark.parametrize("mesh", list(MESHES))
def test_high_speed_3X_to_5X_stronger_at_disk2_and_support_than_at_disk1(mesh):
    """Dai 2025 §5.1, Figs. 12, 14h–j (10 500 rpm): 3X, 4X, 5X appear, more pronounced closer to the
    loose support, where the bearing meets the support."""
    res, h = point(mesh, 10500.0)
    assert res.regime()["contact_fraction"] > 0.0
    high = {c: float(np.sum(h[c][2:5])) for c in LOC}
    assert 0 < high["disk1.y"] < min(high["disk2.y"], high["s.y"])
    assert high["s.y"] / h["s.y"][0] > 1.5 * high["disk1.y"] / h["disk1.y"][0]


def _misalignment(mesh):
    return [point(mesh, 10500.0, **({} if d == 1e-3 else {"misalignment_m": d}))[1] for d in (0.5e-3, 1e-3, 2e-3)]


@pytest.mark.parametrize("mesh", list(MESHES))
def test_larger_misalignment_raises_2X(mesh):
    """Dai 2025 §5.3.2, Fig. 19: 'the amplitudes of the harmonic frequencies 2f, 3f significantly
    increase' with the misalignment δ = 0.5, 1, 2 mm (10 500 rpm): the 2X part."""
    for c in LOC:
        two = [h[c][1] for h in _misalignment(mesh)]
        assert two[0] < two[1] < two[2] and two[2] / two[0] > 2.0, c  # the 2X excitation is linear in δ (Eq. 34)


@pytest.mark.parametrize("mesh", ["paper", _xfail("converged", (
    "Not at disk 1 on the converged mesh (10 500 rpm, 3X y velocity in mm/s for δ = 0.5/1/2 mm): disk 1 "
    "0.0126/0.0157/0.0085 (falls at 2 mm), disk 2 0.247/0.390/0.424 and support 0.365/0.571/0.617 rise"))])
def test_larger_misalignment_raises_3X(mesh):
    """Dai 2025 §5.3.2, Fig. 19 (g–i): 3X increases with the misalignment at disk 1, disk 2 and the 3# bearing."""
    for c in LOC:
        three = [h[c][2] for h in _misalignment(mesh)]
        assert three[0] < three[1] < three[2], (c, three)


@pytest.mark.parametrize("mesh", [
    _xfail("paper", "Not at the support on the paper's mesh (10 500 rpm, 1X y velocity in mm/s for δ = 0.5/1/2 mm): "
                    "disk 1 14.05/14.04/13.71 (2.4 %), disk 2 8.13/8.13/8.36 (2.8 %), support 8.96/8.92/8.06 (11 %): "
                    "at 2 mm the bearing is pressed on the support all the time (contact 100 %)"),
    _xfail("converged", "Not at disk 2 and the support on the converged mesh (10 500 rpm, 1X y velocity in mm/s "
                        "for δ = 0.5/1/2 mm): disk 1 19.14/19.22/19.63 (2.6 %), disk 2 6.36/6.39/6.84 (7.4 %), "
                        "support 23.8/24.2/25.2 (5.9 %)")])
def test_larger_misalignment_leaves_1X_within_a_few_percent(mesh):
    """Dai 2025 §5.3.2, Fig. 19: 'the amplitudes of the rotational frequency f at different positions
    remain essentially unchanged' (read as within 3 %)."""
    for c in LOC:
        one = [h[c][0] for h in _misalignment(mesh)]
        assert max(one) / min(one) - 1 < 0.03, (c, one)


def _clearance(mesh):
    return [point(mesh, 10500.0, **({} if c == 0.05e-3 else {"clearance_m": c}))[1] for c in (0.03e-3, 0.05e-3, 0.08e-3)]


@pytest.mark.parametrize("mesh", list(MESHES))
def test_smaller_clearance_raises_3X_at_high_speed(mesh):
    """Dai 2025 §5.3.1, Fig. 18: at high speed 3X decreases as the clearance grows (0.03, 0.05, 0.08 mm)."""
    for c in ("disk2.y", "s.y"):
        amps = [h[c][2] for h in _clearance(mesh)]
        assert amps[0] > amps[1] > amps[2], (c, amps)


@pytest.mark.parametrize("mesh", [_xfail("paper", (
    "Flat on the paper's mesh (10 500 rpm, 2X y velocity in mm/s for δ0 = 0.03/0.05/0.08 mm): disk 2 "
    "0.4056/0.4023/0.4028, support 0.3904/0.3898/0.3901 (within 1 %, not monotone); 3X does fall with δ0 "
    "(test above)")), "converged"])
def test_smaller_clearance_raises_2X_at_high_speed(mesh):
    """Dai 2025 §5.3.1, Fig. 18: at high speed 2X decreases as the clearance grows."""
    for c in ("disk2.y", "s.y"):
        amps = [h[c][1] for h in _clearance(mesh)]
        assert amps[0] > amps[1] > amps[2], (c, amps)


@pytest.mark.parametrize("mesh", ["paper", _xfail("converged", (
    "Lower, not markedly, on the converged mesh (10 500 rpm, sum of 3X-5X y velocity in mm/s, with / without "
    "tilt): disk 2 0.811/0.633 (-22 %); support 1.14/0.87 (-24 %); the paper's mesh "
    "loses them all (disk 2 0.060 -> < 0.001). Over 9 000-18 000 rpm it is the reverse: median off/on 0.35 at "
    "disk 2 on the converged mesh, 0.91 on the paper's (study-findings.md)"))])
def test_ignoring_tilt_markedly_lowers_the_harmonics(mesh):
    """Dai 2025 §5.2, Fig. 16 vs Fig. 12: 'the harmonic frequency components are markedly reduced when
    the influence of angular deflections is neglected'. 'Markedly' read as at least 30 % lower."""
    _, h = point(mesh, 10500.0)
    _, h0 = point(mesh, 10500.0, tilt_ignored=True)
    for c in ("disk2.y", "s.y"):
        assert np.sum(h0[c][2:5]) < 0.7 * np.sum(h[c][2:5]), (c, np.sum(h0[c][2:5]), np.sum(h[c][2:5]))


def test_simulate_steady_at_point_a_shows_2X_highest_at_the_support(tmp_path):
    """The command an engineer types (issue: `simulate --speed-rpm 4500 --steady` on paper-table4): the
    support's 2X/1X y velocity >= 0.05 and above disk 1's, the steady state periodic, both faces stuck."""
    import json

    from reports.cli import main

    assert main(["simulate", "--speed-rpm", "4500", "--steady", "--out", str(tmp_path)]) == 0
    s = json.loads((tmp_path / "simulate-summary.json").read_text())
    v = s["velocity_amplitudes_mm_s_1X_to_5X"]
    ratio = {k: v[k][1] / v[k][0] for k in ("disk1.y", "disk2.y", "s.y")}
    assert s["steady_converged"] and s["stick_fraction_right"] == s["stick_fraction_left"] == 1.0
    assert ratio["s.y"] >= 0.05 and ratio["s.y"] > ratio["disk1.y"], ratio   # measured 0.336 vs 0.015
