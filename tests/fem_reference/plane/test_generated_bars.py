"""The error-driven bars on generated ring pairs (issue 37): fem_reference/plane/adapt.py (fitted_bar),
uniform_reference.py (the independent P1 reference on nested uniform refinements), mesh.py
(refined_uniformly) and generated.py (the seeded pairs and their check).

Expected values come from closed forms: the area of the two half annuli (pi/2 (R_o^2 - R_i^2) each), the
order 2 of Richardson's extrapolation for linear triangles, and synthetic sequences F = F_inf + C x^2 (+ noise)
whose limit is known. benchmarks/bench_fem2d_adaptive.py runs the family at full size
(reports/published/fem2d-adaptive.md).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from skfem import Basis, ElementTriP1

from contact.errors import InputError
from fem_reference import ring_scene
from fem_reference.plane.adapt import AdaptiveResult, _combined_bar, adaptive_point, fitted_bar, force_bar, reference_mesh
from fem_reference.plane.generated import check_pair, draw_pair
from fem_reference.plane.mesh import refined_uniformly
from seeds import commit_seed

PAIR = Path(__file__).resolve().parents[1] / "ring_scenes" / "cast-iron-lower-half.toml"
X5 = 0.01 / math.sqrt(2.0) ** np.arange(5)            # five levels' estimated errors, / sqrt(2) each


# ---------------------------------------------------------------------------------------------
# the fitted bar on synthetic sequences


def test_fitted_bar_of_a_noiseless_sequence_is_its_distance_from_the_limit():
    f = 1000.0 + 3e5 * X5 ** 2
    bar = fitted_bar(f, X5)
    assert bar.given and bar.method == "fit" and not bar.asymptotic
    assert bar.extrapolated_n == pytest.approx(1000.0, rel=1e-12)
    true = (f[-1] - 1000.0) / f[-1]
    assert true <= bar.error_rel <= true * (1 + 1e-6)


def test_fitted_bar_covers_the_limit_of_noisy_sequences():
    """F = F_inf + C x^2 + noise, the noise up to 5x the finest level's discretisation error: the bar covers
    |F_n - F_inf| in at least 95 % of 400 draws (its limit's confidence is 95 %, and |F_n - F0| is added)."""
    seed = commit_seed()
    print(f"seed {seed}")
    rng = np.random.default_rng(seed)
    covered = 0
    for _ in range(400):
        c = rng.uniform(-3e5, 3e5)
        sigma = abs(c) * X5[-1] ** 2 * rng.uniform(0.0, 5.0) + 1e-9
        f = 1000.0 + c * X5 ** 2 + rng.normal(0.0, sigma, 5)
        bar = fitted_bar(f, X5)
        covered += abs(f[-1] - 1000.0) <= bar.error_rel * abs(f[-1])
    print(f"covered {covered} of 400")
    assert covered >= 380


def test_fitted_bar_refuses_too_few_levels_or_errors_that_do_not_fall():
    with pytest.raises(InputError, match="4 or more"):
        fitted_bar([1.0, 1.0, 1.0], X5[:3])
    with pytest.raises(InputError, match="must decrease"):
        fitted_bar([1.0] * 5, X5[::-1])


def test_levels_no_order_fits_are_refused_not_an_overflow():
    """Seed 1615165210's generated pair 12 at 0.0463 mm (bench_law_family.py's run): the last three levels' force
    differences -0.4895 and -0.3553 N on estimate ratios 1.7304 and 1.2107. With r21 > r32 the order equation's
    right side is at least ln r21 / ln r32 = 2.87 for every order (Celik et al. 2008, Eq. 3), above d1/d2 = 1.38:
    no order fits, and the fixed point ran away into an OverflowError, which failed the whole pair. Now no
    Richardson bar, with the reason; a monotone sequence with an order in the band still gets one."""
    from fem_reference.plane.adapt import _order

    d1, d2, r21, r32 = -0.4894621131243184, -0.35528679702838417, 1.73041387883024, 1.2107109023801441
    assert math.log(r21) / math.log(r32) > d1 / d2
    assert _order(d1, d2, r21, r32) == math.inf
    x3 = 0.01
    x = [x3 * r32 * r21, x3 * r32, x3]
    f3 = 7000.0
    bar = force_bar([f3 + d2 + d1, f3 + d2, f3], x)
    assert not bar.given and "no order fits" in bar.reason
    good = [f3 + 0.5 * (xi / x3) ** 2 for xi in x]             # F = F_inf + C x^2: order 2 exactly
    assert force_bar(good, x).given and force_bar(good, x).observed_order == pytest.approx(2.0, rel=1e-9)


def test_stated_bar_is_the_larger_of_richardson_and_the_fit_and_refused_without_a_sequence():
    """adapt._combined_bar, the bar of five error-driven levels: the larger of the last three levels' Richardson
    bar (where asymptotic) and the fitted one; the fit alone where Richardson refuses; none where the estimates rise."""
    smooth = 1000.0 + 3e5 * X5 ** 2
    wobbly = smooth + np.array([0.0, 0.4, -0.4, 0.3, -0.2])        # not monotone at the last three
    scattered = smooth + np.array([4.0, -4.0, 0.0, 0.0, 0.0])      # asymptotic last three, a wide scatter
    for f in (smooth, scattered, wobbly):
        bar = _combined_bar(AdaptiveResult(0.0, forces_n=list(f), rel_errors=list(X5)))
        rich, fit = force_bar(f[-3:], X5[-3:]), fitted_bar(f, X5)
        expected = max(rich.error_rel, fit.error_rel) if rich.asymptotic else fit.error_rel
        assert bar.error_rel == pytest.approx(expected, rel=1e-12)
        assert bar.method == ("richardson" if rich.asymptotic and rich.error_rel >= fit.error_rel else "fit")
        assert bar.asymptotic == rich.asymptotic
    assert "no Richardson bar" in _combined_bar(AdaptiveResult(0.0, forces_n=list(wobbly),
                                                               rel_errors=list(X5))).reason
    rising = list(X5)
    rising[1] = rising[0] * 1.1
    refused = _combined_bar(AdaptiveResult(0.0, forces_n=list(smooth), rel_errors=rising))
    assert not refused.given and refused.method == "none" and "do not decrease" in refused.reason


# ---------------------------------------------------------------------------------------------
# nested uniform refinement and the P1 reference


def _area(rmesh):
    return float(Basis(rmesh.mesh, ElementTriP1()).dx.sum())


def test_refined_uniformly_puts_new_boundary_nodes_on_the_circles_and_converges_to_the_area():
    sc = ring_scene.load(str(PAIR)).scene
    r = sc.rings
    exact = math.pi / 2 * (r.outer_radius_m ** 2 - r.inner_radius_m ** 2
                           + r.support_outer_radius_m ** 2 - r.bore_radius_m ** 2)
    meshes = [reference_mesh(sc, 5e-3, order=1)]
    for _ in range(2):
        meshes.append(refined_uniformly(meshes[-1]))
    errs = [abs(_area(m) / exact - 1) for m in meshes]
    print(f"area errors {errs}")
    assert errs[0] / errs[1] > 3.5 and errs[1] / errs[2] > 3.5        # h^2: the chords' sag
    fine = meshes[-1]
    assert fine.mesh.nelements == 16 * meshes[0].mesh.nelements
    for name, radius in (("bearing_inner", r.inner_radius_m), ("support_outer", r.support_outer_radius_m)):
        nodes = np.unique(fine.mesh.facets[:, fine.mesh.boundaries[name]])
        assert len(fine.mesh.boundaries[name]) == 4 * len(meshes[0].mesh.boundaries[name])
        assert np.abs(np.hypot(*fine.mesh.p[:, nodes]) / radius - 1).max() < 1e-12
    with pytest.raises(InputError, match="order 1"):
        refined_uniformly(reference_mesh(sc, 5e-3, order=2))


# ---------------------------------------------------------------------------------------------
# generated pairs: the bar against the reference


def test_reduced_generated_pair_within_its_bar():
    """One generated pair (seed 7, printed), its lower penetration: the reference (P1, a first mesh at the
    thinner ring's thickness / 2, three nested refinements: the benchmark's) converges at order 2 and
    the error-driven force lies within its stated bar of it, the reference's own uncertainty under half
    that bar."""
    rng = np.random.default_rng(7)
    sc, pens = draw_pair(rng, 0)
    pc, = check_pair(sc, pens[:1])
    b, ref = pc.adaptive.bar, pc.reference
    print(f"seed 7: {sc.support_hold}, {sc.bearing_drive}, {sc.plane}, {pens[0] * 1e3:.4f} mm; reference "
          f"{ref.forces_n} -> {ref.force_n:.6f} N (unc. {ref.uncertainty_rel:.1e}, order {ref.observed_order:.2f}); "
          f"error-driven {pc.adaptive.forces_n}, bar {b.method} {b.error_rel:.2e}, difference {pc.difference_rel:+.2e}")
    assert 1.8 < ref.observed_order < 2.2
    assert b.given, b.reason
    assert ref.uncertainty_rel < b.error_rel / 2
    assert pc.verdict == "within"


@pytest.mark.slow
def test_generated_pairs_within_their_bars():
    """The first three pairs of the run published before the bulk-refined levels (seed 2988782516, commit
    b3846fe), both penetrations, at the benchmark's size: every point gets a bar, and none lies outside its bar
    plus the reference's own uncertainty. That run had 9 of 60 points outside the bar itself, pair 1's upper
    point one of them (1.14 times a 4e-6 bar, the reference uncertain by 5e-6); with the bulk-refined levels
    (47facc7) it is within, 5.15e-6 against 5.43e-6; this test passed with them in 1220 s (load 7-10), all
    six points within their bars themselves."""
    seed = 2988782516
    print(f"seed {seed}")
    rng = np.random.default_rng(seed)
    checks = []
    for i in range(3):
        sc, pens = draw_pair(rng, i)
        for pc in check_pair(sc, pens):
            print(f"{i} {sc.support_hold} {sc.bearing_drive} {sc.plane} {pc.penetration_m * 1e3:.4f} mm: "
                  f"{pc.verdict}, bar {pc.adaptive.bar.method} {pc.adaptive.bar.error_rel:.2e}, difference "
                  f"{pc.difference_rel:+.2e}, reference unc. {pc.reference.uncertainty_rel:.1e}")
            checks.append(pc)
    assert all(pc.adaptive.bar.given for pc in checks), [pc.adaptive.bar.reason for pc in checks]
    assert all(abs(pc.difference_rel) <= pc.adaptive.bar.error_rel + pc.reference.uncertainty_rel for pc in checks)


@pytest.mark.slow
def test_previous_seeds_clamped_lower_misses_within_their_bars():
    """Seed 2988782516's pairs 20, 22 and 29 (clamped-outer-lower, rigid-inner), both penetrations, at the
    benchmark's size (fem_reference/plane/generated.py: check_pair): with the levels' largest element kept at
    the first mesh's size, 4 of these 6 points lay outside their bars (1.2-2.2 times), pair 20's and 22's
    by more than the reference's own uncertainty; with the bulk refined level by level
    (fem_reference/plane/adapt.py: refine_bulk) each lies within its bar, every bar at most 0.2 %. On the old
    levels (``refine_bulk=False``) pair 20's lower point is outside its bar again: the test can fail.
    Measured at commit 47facc7: the six bars 7.3e-5 to 5.1e-4, the differences 0.06-0.70 of them; the old
    levels' pair 20 at 0.0206 mm +3.97e-4 against a bar of 1.78e-4."""
    seed = 2988782516
    print(f"seed {seed}")
    rng = np.random.default_rng(seed)
    pairs = [draw_pair(rng, i) for i in range(30)]
    refs = {}
    for i in (20, 22, 29):
        sc, pens = pairs[i]
        assert sc.support_hold == "clamped-outer-lower" and sc.bearing_drive == "rigid-inner"
        checks = check_pair(sc, pens)
        refs[i] = checks[0].reference.force_n
        for pc in checks:
            b, ref = pc.adaptive.bar, pc.reference
            print(f"{i} {pc.penetration_m * 1e3:.4f} mm: {pc.verdict}, bar {b.method} {b.error_rel:.2e}, difference "
                  f"{pc.difference_rel:+.2e}, reference {ref.force_n:.6g} N unc. {ref.uncertainty_rel:.1e}")
            assert b.given, b.reason
            assert b.error_rel <= 2e-3
            assert pc.verdict == "within"
    sc, pens = pairs[20]
    old = adaptive_point(sc, pens[0], refine_bulk=False)
    diff = old.bar.force_n / refs[20] - 1
    print(f"20, old levels: {old.forces_n}, bar {old.bar.error_rel:.2e}, difference {diff:+.2e}")
    assert abs(diff) > old.bar.error_rel


@pytest.mark.slow
def test_reference_passes_over_a_first_mesh_that_does_not_resolve_the_arc():
    """Seed 1928108429's pair 19 at 0.0115 mm (reports/published/fem2d-adaptive.md at b6206be: refused): the reference's
    first P1 mesh, the thinner ring's thickness / 2 (6.55 mm), has one active contact node; the reference now
    starts one refinement finer and ends at the same finest size (fem_reference/plane/uniform_reference.py:
    three levels of the four asked for) and converges there at order 2; with three asked for it still refuses."""
    from fem_reference.plane.contact_solver import ArcNotResolvedError
    from fem_reference.plane.generated import thinner_thickness_m
    from fem_reference.plane.uniform_reference import uniform_reference

    rng = np.random.default_rng(1928108429)
    sc, pens = [draw_pair(rng, i) for i in range(20)][19]
    h0 = thinner_thickness_m(sc) / 2
    ref, = uniform_reference(sc, pens[:1], h0, 4)
    print(f"h0 {h0 * 1e3:.3f} mm -> first level {ref.h0_m * 1e3:.3f} mm; forces {ref.forces_n} N, DOFs {ref.ndofs}, "
          f"order {ref.observed_order:.2f}, unc. {ref.uncertainty_rel:.1e}")
    assert ref.h0_m == pytest.approx(h0 / 2, rel=1e-12)
    assert len(ref.forces_n) == 3
    assert 1.5 < ref.observed_order < 2.5
    with pytest.raises(ArcNotResolvedError):
        uniform_reference(sc, pens[:1], h0, 3)


@pytest.mark.slow
def test_a_fifth_reference_level_settles_the_published_pair_27():
    """Seed 1928108429's pair 27 (clamped-outer, coupled-inner, plane strain), both penetrations: the run
    published before this test (reports/published/fem2d-adaptive.md at b6206be) put both points outside their
    bars, 1.79 and 1.21 times, against a four-level P1 reference uncertain by 5e-4 and 3e-4, more than the bars
    (7.6e-5 and 1.2e-5). A fifth level (253k DOFs, which the dense contact columns used to forbid:
    fem_reference/plane/solve.py `_delassus`) moves the reference, not the error-driven force: 1327.573 to
    1327.386 N at 0.0127 mm, where P2 on near-uniform meshes of the thinner ring's thickness / 4, / 8, / 16 gave
    1327.016, 1327.365, 1327.413 N (measured while writing this test). With it both points lie within their bars,
    and the four-level reference, recomputed from the same levels, still puts them outside: the test can fail.
    Passed at ccfc5da in 1333 s at load 3 (two benchmarks beside it): differences +1.5e-5 and -5.5e-6 against bars
    of 8.4e-5 and 8.8e-6; with four levels -1.3e-4 and -1.2e-5."""
    for pc, four, d4 in _checked_with_four_levels(1928108429, 27, ("clamped-outer", "coupled-inner", "strain")):
        b, ref = pc.adaptive.bar, pc.reference
        assert len(ref.forces_n) == 5
        assert pc.verdict == "within"
        assert abs(d4) > b.error_rel
        assert ref.uncertainty_rel < four.uncertainty_rel


@pytest.mark.slow
def test_a_fifth_level_settles_the_published_pair_18():
    """Seed 627535865's pair 18 (clamped-outer-upper, rigid-inner-y, plane strain), both penetrations: the run
    published at 3826124 (reports/published/fem2d-adaptive.md) put both outside their bars (1.27 and 1.90 times
    bars of 5e-6 and 1e-6) against a four-level reference uncertain by 1e-5, whose fifth level (468k DOFs) the
    400k-DOF cap of the dense contact columns forbade. Solved on the sparse system (fem_reference/plane/active_set.py),
    the fifth level costs about a minute; with it both points lie within their bars, and the four-level reference
    from the same levels still puts them outside: the test can fail. Measured while writing it: the fifth level's
    forces 333168.1229 and 1810930.5368 N."""
    for pc, four, d4 in _checked_with_four_levels(627535865, 18, ("clamped-outer-upper", "rigid-inner-y", "strain")):
        b, ref = pc.adaptive.bar, pc.reference
        assert len(ref.forces_n) >= 5
        assert pc.verdict == "within"
        assert abs(d4) > b.error_rel


def _checked_with_four_levels(seed: int, index: int, setup: tuple) -> list:
    """Pair ``index`` of ``seed`` (its hold, drive and plane asserted to be ``setup``) checked at both penetrations,
    each with the reference of its first four levels alone and that reference's difference; printed."""
    from fem_reference.plane.uniform_reference import _one

    rng = np.random.default_rng(seed)
    sc, pens = [draw_pair(rng, i) for i in range(index + 1)][index]
    assert (sc.support_hold, sc.bearing_drive, sc.plane) == setup
    out = []
    for pc in check_pair(sc, pens):
        b, ref = pc.adaptive.bar, pc.reference
        four = _one(ref.forces_n[:4], ref.ndofs[:4], ref.h0_m, ref.wall_s)
        d4 = b.force_n / four.force_n - 1
        print(f"{index} {pc.penetration_m * 1e3:.4f} mm: levels {ref.forces_n} N ({ref.ndofs} DOFs) -> "
              f"{ref.force_n:.4f} N (unc. {ref.uncertainty_rel:.1e}); error-driven {b.force_n:.4f} N, bar "
              f"{b.error_rel:.2e}, difference {pc.difference_rel:+.2e}; four levels {four.force_n:.4f} N, difference {d4:+.2e}")
        out.append((pc, four, d4))
    return out
