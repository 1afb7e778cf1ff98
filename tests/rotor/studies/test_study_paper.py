"""The paper's qualitative findings (Dai et al. 2025, Section 5) checked on our numbers.

Table 4 rotor, the paper's conformal law as published, the scene's documented assumptions
for the inputs the paper does not give (a0, a1, support mass/tilt stiffness …). Each test uses
the fewest steady-state points that make its statement meaningful: 4 500 rpm (the paper's
point A, support stuck to the bearing) and 10 500 rpm (point B, periodic collision).
Amplitudes are of the y velocity, as in the paper's spectra (Figs. 12–14, 16).

Where a finding does NOT hold on our numbers the test still states the paper's claim and is
marked ``xfail(strict=True)`` with the measured numbers in the reason: it documents the
disagreement, and it will flag (XPASS → failure) the day a model change makes the claim hold.

Coexisting steady states: at 10 500 rpm the support has more than one periodic regime (e.g.
δ0 = 0.08 mm slips without contact when started from rest, but keeps colliding 45 % of the time
when continued from the δ0 = 0.05 mm state). Variants here are continued from the scene's own
point at the same speed, so they compare neighbouring states of one branch, as a parameter
study in the paper's spirit would.
"""
import numpy as np
import pytest

from rotor.studies.steady_state import SteadyStateOptions, point_system, steady_state

OPTS = SteadyStateOptions(spectrum_revs=16)
LOC = ("disk1.y", "disk2.y", "s.y")
_CACHE = {}


def point(rpm, **kw):
    """Steady state at ``rpm`` with overrides; cached for the module (several tests share points).

    A variant (overrides) starts from the steady state of the scene's own point at the same speed
    (continuation: a shorter transient, same detection criterion, same answer for a unique
    periodic attractor)."""
    key = (rpm, tuple(sorted(kw.items())))
    if key not in _CACHE:
        start = {}
        if kw:
            base = point(rpm)[0]
            start = {"q0": base.q_end, "v0": base.v_end}
        _, model, system = point_system("paper-table4", rpm, **kw)
        res = steady_state(system, model, options=OPTS, **start)
        assert res.convergence.converged, f"{rpm} rpm {kw}: no periodic steady state ({res.convergence})"
        H = res.harmonics("v")  # (5, channels) m/s
        _CACHE[key] = (res, {c: H[:, res.channel(c)] for c in LOC})
    return _CACHE[key]


def test_2f_from_misalignment_present_with_it_absent_without_it_where_support_sticks():
    """Dai 2025 §5.1, Fig. 13 (4 500 rpm): spectra dominated by f, with 2f 'caused by misalignment';
    the support moves with the rotor (no relative motion); 2f relatively higher at the 3# bearing."""
    res1, h1 = point(4500.0)
    res0, h0 = point(4500.0, misalignment_m=0.0)
    for res in (res1, res0):
        reg = res.regime()
        assert reg["label"] == "stick" and reg["contact_fraction"] == 0.0
    for c in LOC:
        assert h1[c][1] / h1[c][0] > 1e-4, c          # 2f present (measured 2e-4 … 5e-3 of 1f)
        # and absent without it: what is left is leakage of the transient that the steady-state
        # tolerance (1e-4 on the Poincaré section) allows, measured 4e-8 of 1f; 1e-6 is 200x
        # below the smallest 2f/1f with misalignment
        assert h0[c][1] <= 1e-6 * h0[c][0], c
        assert np.all(h0[c][2:] <= 1e-6 * h0[c][0])   # linear stuck support: no higher harmonics either
    assert h1["s.y"][1] / h1["s.y"][0] > 5 * h1["disk1.y"][1] / h1["disk1.y"][0]


def test_high_speed_3f_to_5f_stronger_at_disk2_and_support_than_at_disk1():
    """Dai 2025 §5.1, Figs. 12, 14h–j (10 500 rpm): 3f, 4f, 5f appear, more pronounced closer to the
    loose support; the bearing and support collide periodically (Fig. 15)."""
    res, h = point(10500.0)
    reg = res.regime()
    assert reg["label"] == "impact" and 0.0 < reg["contact_fraction"] < 1.0
    high = {c: float(np.sum(h[c][2:5])) for c in LOC}
    assert high["disk1.y"] > 0
    assert high["disk2.y"] > high["disk1.y"]
    assert high["s.y"] > high["disk1.y"]
    # relative to the 1f of each location the contrast is larger still
    assert high["s.y"] / h["s.y"][0] > 1.5 * high["disk1.y"] / h["disk1.y"][0]


def test_larger_misalignment_raises_2f_while_1f_stays_within_a_few_percent():
    """Dai 2025 §5.3.2, Fig. 19: 'the amplitudes of f remain essentially unchanged, while 2f, 3f
    significantly increase'. The 2f/1f part, at 10 500 rpm, δ = 0.5, 1, 2 mm."""
    hs = [point(10500.0, **({} if d == 1e-3 else {"misalignment_m": d}))[1] for d in (0.5e-3, 1e-3, 2e-3)]
    for c in LOC:
        one = [h[c][0] for h in hs]
        two = [h[c][1] for h in hs]
        assert max(one) / min(one) - 1 < 0.03, c
        assert two[0] < two[1] < two[2], c
        assert two[2] / two[0] > 2.0, c  # the 2f excitation is linear in δ (Eq. 34)


@pytest.mark.xfail(strict=True, reason=(
    "Not on our numbers (10 500 rpm, y-velocity 3f in mm/s for δ = 0.5/1/2 mm): disk 1 0.0154/0.0127/0.0124, "
    "disk 2 0.0276/0.0226/0.0214, support 0.0268/0.0220/0.0207 -- 3f falls slightly as δ grows while 2f "
    "doubles; at 2 mm the bearing is pressed on the support all the time (contact 100 %). No plausible value "
    "of the inputs Table 4 leaves out makes 3f rise with δ where the bearing collides "
    "(reports/published/study-sensitivity.md: 18 of 98 variant-speed pairs)"))
def test_larger_misalignment_raises_3f():
    """Dai 2025 §5.3.2, Fig. 19: 3f increases with the misalignment."""
    hs = [point(10500.0, **({} if d == 1e-3 else {"misalignment_m": d}))[1] for d in (0.5e-3, 1e-3, 2e-3)]
    for c in LOC:
        three = [h[c][2] for h in hs]
        assert three[0] < three[1] < three[2], c


@pytest.mark.xfail(strict=True, reason=(
    "Not on our numbers (10 500 rpm, y-velocity in mm/s for δ0 = 0.03/0.05/0.08 mm): 2f disk 2 "
    "0.1650/0.1648/0.1649 (flat), support 0.1711/0.1695/0.1658 (falls, as the paper says); 3f disk 2 "
    "0.0225/0.0226/0.0174, support 0.0218/0.0220/0.0170 (peaks at 0.05 mm). At 0.03 mm the bearing is "
    "pressed on the support all the time (contact 100 %), at 0.05 and 0.08 mm it collides (45 % of the time). "
    "No plausible value of the unstated inputs reverses it (study-sensitivity.md: 3f falls with δ0 in 22 of 93 "
    "variant-speed pairs with collision, 9 000-15 000 rpm)"))
def test_smaller_clearance_raises_2f_and_3f_at_high_speed():
    """Dai 2025 §5.3.1, Fig. 18: at high speed 2f and 3f decrease as the clearance increases."""
    hs = [point(10500.0, **({} if c == 0.05e-3 else {"clearance_m": c}))[1] for c in (0.03e-3, 0.05e-3, 0.08e-3)]
    for c in ("disk2.y", "s.y"):
        for k in (1, 2):
            amps = [h[c][k] for h in hs]
            assert amps[0] > amps[1] > amps[2], (c, k + 1)


@pytest.mark.xfail(strict=True, reason=(
    "Not on our numbers (10 500 rpm, sum of 3f-5f y-velocity, mm/s, with / without tilt): disk 2 "
    "0.0257/0.0253, support 0.0260/0.0257 (1-2 % lower, not 'markedly'); the relative tilt at the "
    "support is small, 1f 0.009/0.011 mrad (θy/θz), with the scene's assumed support tilt stiffness. "
    "Not a tilt-stiffness artefact: with k_s,theta 100x softer or stiffer (1.5e3 / 1.5e7 N m/rad) ignoring "
    "the tilt RAISES 3f-5f at disk 2 at 13 500 rpm (0.89 -> 1.58 and 1.05 -> 1.70 mm/s). It holds with a stiff frame and a light preload "
    "(scene paper-table4-stiff-frame, tests/rotor/studies/test_study_sensitivity.py), not with the scene as published"))
def test_ignoring_tilt_markedly_lowers_the_harmonics():
    """Dai 2025 §5.2, Fig. 16 vs Fig. 12: 'the harmonic frequency components are markedly reduced when
    the influence of angular deflections is neglected'. 'Markedly' read as at least 30 % lower."""
    _, h = point(10500.0)
    _, h0 = point(10500.0, tilt_ignored=True)
    for c in ("disk2.y", "s.y"):
        assert np.sum(h0[c][2:5]) < 0.7 * np.sum(h[c][2:5]), c
