"""The steady-state detector (rotor.studies.periodicity): an orbit repeating within tolerance is periodic, a
stuck linear state included; a transient still drifting is not.

Expected values: geometric sequences (a transient mode ``Re(c λ^k)`` added to a fixed point, whose distance to it
is ``|c| ρ^k``) and a small wobble about a fixed point; and one point of the Section 5 study, the tilt-ignored
Table 4 rotor at 7 200 rpm on the paper's mesh (Dai et al. 2025 §5.2; study-cascade-notilt.csv): both faces stuck,
no contact, its once-per-revolution samples scattering by ~5e-6 of the amplitude (tolerance 1e-4) without a
measurable decay, which the former rule (the decay ratio clipped at 0.999, so a plateau counts 1 000 times)
labelled not periodic after 1 500 revolutions.
"""
import math

import numpy as np
import pytest

from rotor.studies import periodicity
from rotor.studies.periodicity import RHO_MAX, poincare_convergence


def _decay_only(monkeypatch):
    """The former rule: the geometric ``decay`` estimate alone (the ``span`` bound switched off)."""
    monkeypatch.setattr(periodicity, "span_remaining", lambda *a: (math.inf, math.inf))


def test_a_wobble_far_below_tolerance_repeats_within_it_the_former_rule_refused_it(monkeypatch):
    """Samples turning about a fixed point by the golden angle a revolution, 2.5e-6 of the amplitude (tolerance
    1e-4): they never repeat exactly and their differences neither grow nor decay (the fitted ratio sits at its clip),
    so the decay estimate counts them 1 000 times; the span bound sees that they stay within 2.5e-6."""
    k = np.arange(600)
    th = np.pi * (math.sqrt(5) - 1)
    P = np.column_stack([1e-4 + 1e-9 * np.cos(th * k), -2e-4 + 1e-9 * np.sin(th * k)])
    c = poincare_convergence(P, 4e-4, tol=1e-4)
    assert c.converged and c.period == 1 and c.rule == "span" and c.remaining < 1e-4
    assert c.ratio == pytest.approx(RHO_MAX)       # no decay to measure: the ratio sits at its clip
    _decay_only(monkeypatch)
    old = poincare_convergence(P, 4e-4, tol=1e-4)
    assert not old.converged and old.change < 1e-4 and old.remaining > 1e-3   # 1 000 x the last differences


@pytest.mark.parametrize("rho", [0.9995, 0.99995])
def test_a_coherent_slow_drift_of_the_same_per_revolution_size_is_not_periodic(rho):
    """A real mode decaying more slowly than the 0.999 the rules allow for, its per-revolution change 5e-6
    (as the plateau's): its distance to the fixed point, 5e-6 ρ/(1 − ρ) = 0.01 / 0.1, is not within 1e-4."""
    k = np.arange(600)
    x = 1e-4 + 4e-4 * 5e-6 / (1 - rho) * rho ** (k - 599)
    c = poincare_convergence(np.column_stack([x, x]), 4e-4, tol=1e-4)
    assert c.change < 1e-4 and not c.converged


def test_a_turning_transient_close_to_the_fixed_point_passes_by_its_span():
    """A complex mode (ρ 0.995, 2.1 rad a revolution) whose distance to the fixed point is 3e-6 of the amplitude:
    its differences do not add up, the span bound accepts it; the decay estimate (ρ/(1 − ρ) = 199 times the
    differences) does not."""
    k = np.arange(1200)
    amp = 3e-6 * 4e-4 / 0.995 ** 1199
    P = np.column_stack([1e-4 + amp * 0.995 ** k * np.cos(2.1 * k), -2e-4 + amp * 0.995 ** k * np.sin(2.1 * k)])
    c = poincare_convergence(P, 4e-4, tol=1e-4)
    assert c.converged and c.rule == "span" and c.remaining >= 3e-6 * 0.99   # a bound: never below the truth


def _spy(monkeypatch):
    import rotor.studies.steady_state as ss

    seen = []

    def spy(P, scale, **kw):
        c = poincare_convergence(P, scale, **kw)
        seen.append((np.array(P), scale, c))
        return c
    monkeypatch.setattr(ss, "poincare_convergence", spy)
    return seen


def test_a_stuck_contact_free_point_of_the_section5_study_is_periodic(monkeypatch):
    """Tilt-ignored Table 4 rotor, 7 200 rpm, paper's mesh, the studies' settings (256 steps/rev, 1 500
    revolutions at most): periodic with period 1 by the span bound, faces stuck, no contact; with the former rule
    the same integration runs to the cap and is labelled not periodic although its samples repeat within 1e-4."""
    from rotor.studies.steady_state import run_point

    opts = {"steps_per_rev": 256, "max_revs": 1500}
    seen = _spy(monkeypatch)
    _, info = run_point("paper-table4", 7200.0, options=opts, tilt_ignored=True)
    assert info["converged"] and info["period_revs"] == 1 and seen[-1][2].rule == "span"
    assert info["label"] == "stick" and info["contact_fraction"] == 0.0 and info["stick_fraction"] == 1.0
    assert info["poincare_change"] < 1e-4 and info["poincare_remaining"] < 1e-4
    assert info["transient_revs"] < 1500
    seen.clear()
    _decay_only(monkeypatch)
    _, old = run_point("paper-table4", 7200.0, options=opts, tilt_ignored=True)
    assert not old["converged"] and old["transient_revs"] == 1500
    P, scale, c = seen[-1]
    assert c.change < 1e-4 and c.ratio == pytest.approx(RHO_MAX)   # repeats within tolerance, no decay measured
    assert np.abs(P[-1] - P[-501]).max() / scale < 1e-4            # and does not drift over 500 revolutions
