"""Error-driven 2D meshes and their force bars (issue 37): fem_reference/plane/estimate.py and adapt.py.

The pair is the issue's (tests/fem_reference/ring_scenes/cast-iron-lower-half.toml): a steel ring in a
cast-iron housing clamped on its lower half, where the graded family's Richardson bars were 6-8x
smaller than the true error. The reference is the suite's own solver on near-uniform meshes (the
whole domain at one size, no family), extrapolated in h at the order the clamp's end allows.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from fem_reference import ring_scene
from fem_reference.plane.adapt import adaptive_point, force_bar, initial_mesh
from fem_reference.plane.estimate import recover
from fem_reference.plane.solve import ContactModel

PAIR = Path(__file__).resolve().parents[1] / "ring_scenes" / "cast-iron-lower-half.toml"


def _scene():
    return ring_scene.load(str(PAIR)).scene


# ---------------------------------------------------------------------------------------------
# the bar on synthetic sequences F = F_inf + C x^p


@pytest.mark.parametrize("ratios", [(2.0, 2.0), (1.6, 2.3), (2.5, 1.4)])
def test_bar_bounds_the_error_of_an_asymptotic_sequence(ratios):
    x = np.array([0.1, 0.1 / ratios[0], 0.1 / ratios[0] / ratios[1]])
    f = 1000.0 + 5e3 * x ** 2
    bar = force_bar(f, x)
    assert bar.asymptotic, bar.reason
    assert abs(bar.observed_order - 2.0) < 1e-6
    assert abs(bar.extrapolated_n - 1000.0) < 1e-9 * 1000.0
    assert bar.error_rel * f[-1] >= f[-1] - 1000.0        # a bound: the true error is inside


def test_bar_refused_where_the_order_is_far_from_the_expected():
    x = np.array([0.1, 0.05, 0.025])
    for p in (1.0, 4.0):            # an error the estimate does not see, or a lucky cancellation
        bar = force_bar(1000.0 + 5e2 * x ** p, x)
        assert not bar.asymptotic and math.isnan(bar.error_rel)
        assert "not in their asymptotic range" in bar.reason


def test_bar_refused_where_the_forces_do_not_fall_monotonically():
    x = np.array([0.1, 0.05, 0.025])
    for f in ([1010.0, 1002.0, 1003.0], [1000.0, 1003.0, 1002.0], [1010.0, 1000.0, 1000.0]):
        bar = force_bar(f, x)
        assert not bar.asymptotic and math.isnan(bar.error_rel) and math.isnan(bar.observed_order)
        assert "not monotone" in bar.reason


# ---------------------------------------------------------------------------------------------
# the recovery estimate


def _model(h_m):
    sc = _scene()
    return ContactModel.from_mesh(sc, initial_mesh(sc, h_m))


def test_recovery_is_exact_where_the_stress_is_in_the_space_and_converges_at_order_p():
    """A linear displacement (constant stress) is recovered exactly (eta ~ 0, curved elements included);
    a quartic one's estimate falls like h^2 (P2 energy norm), from 2.5 to 1.25 mm."""
    def field(basis, k):
        x, y = basis.doflocs
        comp = np.zeros(basis.N, dtype=int)
        comp[basis.nodal_dofs[1]] = 1
        comp[basis.facet_dofs[1]] = 1
        s = x / 0.1, y / 0.1
        if k == 1:
            ux, uy = 1e-5 * (s[0] + 0.5 * s[1]), 1e-5 * (s[1] - 0.3 * s[0])
        else:
            ux, uy = 1e-5 * (s[0] ** k + s[0] * s[1]), 1e-5 * (s[1] ** k - s[0] ** 2)
        return np.where(comp == 0, ux, uy)

    m = _model(2.5e-3)
    est = recover(m, field(m.basis, 1))
    assert est.rel_error < 1e-8, est.rel_error
    errs = []
    for h in (2.5e-3, 1.25e-3):
        m = _model(h)
        est = recover(m, field(m.basis, 4))
        assert est.energy == pytest.approx(float(field(m.basis, 4) @ (m.system.K @ field(m.basis, 4))))
        errs.append(est.rel_error)
    order = math.log2(errs[0] / errs[1])
    print(f"estimate {errs}, order {order:.2f}")
    assert 1.6 < order < 2.4


def test_indicators_point_at_the_clamp_end():
    """The largest indicator of the cast-iron pair sits at the clamp's end (95, 0) mm."""
    m = _model(2.5e-3)
    sol = m.solve(1e-5)
    est = recover(m, sol.u)
    c = m.rmesh.mesh.p[:, m.rmesh.mesh.t[:3]].mean(axis=1)
    k = int(np.argmax(est.eta))
    assert math.hypot(c[0, k] - 0.095, c[1, k]) < 5e-3, c[:, k]


# ---------------------------------------------------------------------------------------------
# the cast-iron pair: the bar against near-uniform references


REFERENCE_003_N = 15940.14     # P2 at 0.5 mm graded at the clamp's end, 0.03 mm: its 1 and 0.707 mm levels within 2.7e-6
#                                (reports/published/fem2d-adaptive.md, benchmarks/bench_fem2d_adaptive.py part 1)


def test_reduced_case_new_bar_holds_where_the_graded_family_bar_fails():
    """Δr = 0.03 mm: the graded family's Richardson bar misses the reference by several times (issue 37:
    0.068 % stated, 0.55 % off); the error-driven levels' three-level Richardson bar (``extra_levels=0``)
    holds, at most 0.2 %, against the published P2 reference at 0.5 mm (converged to 2.7e-6, well inside
    the bar; a reference at 2 and 1.414 mm, 3.3e-5 apart, was too coarse for the bar of the bulk-refined
    levels, 1.3e-4)."""
    from fem_reference.plane.sweep import Levels, reference_point

    sc, dr = _scene(), 0.03e-3
    ref, ref_unc = REFERENCE_003_N, 2.7e-6
    old = reference_point(Levels(sc), dr)
    new = adaptive_point(sc, dr, extra_levels=0)
    print(f"reference {ref} N (levels differ by {ref_unc:.2e}); graded family {old['force_n']:.2f} N "
          f"+- {old['force_error_rel']:.2e}; error-driven {new.forces_n} N, {new.ndofs} DOFs, est. {new.rel_errors}, "
          f"bar {new.bar}")
    assert new.bar.given, new.bar.reason
    assert new.bar.error_rel <= 2e-3
    assert ref_unc < new.bar.error_rel / 4              # the reference is converged well inside the bar
    assert abs(new.bar.force_n / ref - 1) <= new.bar.error_rel
    assert abs(old["force_n"] / ref - 1) > 3 * old["force_error_rel"]     # the old bar is not a bound


@pytest.mark.slow
def test_cast_iron_pair_within_its_bar_at_every_penetration():
    """Issue 37's must-show: the five penetrations within their bars (each at most 0.2 %) of an independent
    reference: P1 on nested uniform refinements from 2.5 mm (fem_reference/plane/generated.py: check_pair, the
    generated family's check), its own uncertainty below every bar. With the bulk-refined levels (commit
    47facc7) it passed in 719 s at load 13: bars 0.0045-0.016 %, differences +0.0017 to +0.0083 %; at 0.005 mm
    the reference's uncertainty is 0.63 of the bar (1.0e-4 against 1.6e-4; at commit b3846fe 0.97 of 1.03e-4; a
    fifth level would then have passed check_pair's 200k-DOF cap, 400k since ccfc5da), the most this reference can check (the near-uniform P2
    reference of reports/published/fem2d-adaptive.md is no finer: its levels differ by 9e-5)."""
    from fem_reference.plane.generated import check_pair

    sc = _scene()
    pens = [v * 1e-3 for v in (0.003, 0.005, 0.01, 0.02, 0.03)]
    for pc in check_pair(sc, pens):
        b, ref = pc.adaptive.bar, pc.reference
        print(f"{pc.penetration_m * 1e3:g} mm: {b.force_n:.3f} N vs reference {ref.force_n:.3f} N "
              f"({pc.difference_rel:+.4%}; {len(ref.forces_n)} levels, unc. {ref.uncertainty_rel:.1e}, order "
              f"{ref.observed_order:.2f}), bar {b.method} {b.error_rel:.4%}, DOFs {pc.adaptive.ndofs}")
        assert b.given, b.reason
        assert b.error_rel <= 2e-3
        assert ref.uncertainty_rel < b.error_rel
        assert pc.verdict == "within"
