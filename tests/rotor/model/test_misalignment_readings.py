"""Readings of the misalignment excitation (Dai et al. 2025, Eq. 34 and the sentence before it).

Expected values come from Eq. 34 itself (F = 2 m_sp L tan(Δθ/2) Ω², M = m_sp L² tan(Δθ/2) Ω²,
Δθ = δ/(l34 + l45) from Eq. 33) and from statics: a lateral pair on two laterally locked nodes
cancels, so the opposed-at-joint reading must respond exactly as its moment pair alone.
Each model carries a named reading of rotor.studies.readings (placement, m_sp and L).
"""
import dataclasses
import math

import numpy as np
import pytest

from contact.errors import InputError
from rotor.linear.unbalance import forced_response
from rotor.model.assembly import assemble, harmonic_loads, misalignment_angle
from rotor.model.scene import MISALIGNMENT_EXCITATIONS, load_scene, loads_scene, scene_path
from rotor.studies.readings import READINGS, reading_scene, scene_reading

RPM_A = 4500.0                          # the paper's point A (support stuck: linear)
W_A = RPM_A * math.pi / 30


def _model(name: str):
    """The Table 4 rotor under the reading ``name`` (rotor.studies.readings: its placement, m_sp and L)."""
    return assemble(reading_scene(load_scene("paper-table4"), name))


def _eq34(model, w):
    cp = model.couplings[0]
    tt = math.tan(misalignment_angle(model) / 2)
    return 2 * cp.shaft_mass_kg * cp.lever_m * tt * w ** 2, cp.shaft_mass_kg * cp.lever_m ** 2 * tt * w ** 2


def _sum(vec, model, dof):
    return sum(vec[i] for name, i in model._index.items() if name.endswith("." + dof))


def test_default_reading_is_the_opposed_pair_on_the_long_sleeve():
    """Chosen at point B (reports/published/section5-readings.md): the paper's literal opposed pair,
    m_sp = 25.2 kg, L = 210 mm."""
    sc = load_scene("paper-table4")
    assert scene_reading(sc) == "opposed-at-joint-long-sleeve"
    assert sc.misalignment.excitation == "opposed-at-joint"
    assert (sc.couplings[0].shaft_mass_kg, sc.couplings[0].lever_m) == (25.2, 0.21)
    assert {r.excitation for r in READINGS} <= set(MISALIGNMENT_EXCITATIONS)


def test_eq34_magnitudes_and_net_loads_per_reading():
    # Δθ = δ/(l34 + l45) = 1 mm / 1.5 m (Table 4, Eq. 33)
    sc = load_scene("paper-table4")
    for exc in MISALIGNMENT_EXCITATIONS:
        m = assemble(dataclasses.replace(sc, misalignment=dataclasses.replace(sc.misalignment, excitation=exc)))
        assert misalignment_angle(m) == pytest.approx(1e-3 / 1.5, rel=1e-12)
        F, M = _eq34(m, W_A)
        a, b = harmonic_loads(m, W_A)[2]
        net_y, net_z = _sum(a, m, "y"), _sum(b, m, "z")
        if exc == "inertial-at-joint":          # half the shaft's inertia force on each side
            assert net_y == pytest.approx(2 * F) and net_z == pytest.approx(2 * F)
            assert _sum(a, m, "θy") == pytest.approx(0.0, abs=1e-12 * M)   # moments opposed
        else:                                   # an opposed pair: no net force
            assert net_y == pytest.approx(0.0, abs=1e-12 * F) and net_z == pytest.approx(0.0, abs=1e-12 * F)
        if exc == "opposed-at-centring-surfaces":   # net couple 2FL about z from the y forces
            assert _sum(a, m, "θz") == pytest.approx(-2 * F * m.couplings[0].lever_m)
    # magnitude at 10 500 rpm with the short sleeve's m_sp = 9 kg, L = 75 mm: the 544 N of the review
    F_b, _ = _eq34(_model("inertial-at-joint"), 10500 * math.pi / 30)
    assert F_b == pytest.approx(544.0, rel=2e-3)


def _ratio_2x_1x(model, stations=("2", "4", "s")):
    r1 = forced_response(model, [W_A], order=1).amplitudes[0]
    r2 = forced_response(model, [W_A], order=2).amplitudes[0]
    return {s: 2 * abs(r2[model._index[f"{s}.y"]]) / abs(r1[model._index[f"{s}.y"]]) for s in stations}


def test_opposed_reading_acts_only_through_its_moment_pair():
    """+F on 3a and −F on 3b cancel on the locked joint (Eq. 31): the response equals the moments'."""
    m = _model("opposed-at-joint-long-sleeve")
    r_full = forced_response(m, [W_A], order=2).amplitudes[0]
    a, b = harmonic_loads(m, W_A)[2]
    keep = np.array([n.endswith(("θy", "θz")) for n in sorted(m._index, key=m._index.get)])
    import rotor.linear.unbalance as ub
    orig = ub.harmonic_loads
    try:
        ub.harmonic_loads = lambda model, w: {1: orig(model, w)[1], 2: (a * keep, b * keep)}
        r_moments = forced_response(m, [W_A], order=2).amplitudes[0]
    finally:
        ub.harmonic_loads = orig
    assert np.allclose(r_full, r_moments, rtol=1e-9, atol=1e-18)


@pytest.mark.parametrize("name", ["opposed-at-joint-long-sleeve", "inertial-at-joint"])
def test_point_a_2x_shows_most_at_the_support(name):
    """Text of Fig. 13: at point A 2X accompanies f and is relatively highest at the 3# bearing.
    Linear forced response (support stuck), y displacement 2X/1X scaled to velocity: the default
    (issue 25's audit: 0.005 / 0.041 / 0.103) and the former default (0.015 / 0.162 / 0.337) both show it."""
    ratio = _ratio_2x_1x(_model(name))
    assert ratio["s"] >= 0.05 and ratio["s"] > ratio["4"] > ratio["2"]


def test_point_a_2x_invisible_for_the_opposed_pair_on_the_short_sleeve():
    """The moment pair m_sp L² tan(Δθ/2) Ω² of the 150 mm sleeve is 21.95 times smaller: 2X/1X at the
    support below 0.01 (review: 4.6e-3), which is why the opposed pair needs the long sleeve."""
    assert _ratio_2x_1x(_model("opposed-at-joint"))["s"] < 0.01


def test_unknown_reading_refused_with_the_allowed_ones():
    text = (scene_path("paper-table4").read_text()
            .replace('excitation = "opposed-at-joint"', 'excitation = "sideways"'))
    with pytest.raises(InputError, match="excitation = 'sideways'.*must be one of inertial-at-joint"):
        loads_scene(text)
