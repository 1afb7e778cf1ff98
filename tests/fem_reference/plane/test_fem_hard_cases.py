"""Hard cases of the 2D FEM reference (issue 3): converge, or fail with a clear message."""
from __future__ import annotations

import numpy as np
import pytest

from contact.errors import InputError
from fem_reference.plane.contact_solver import ArcNotResolvedError
from fem_reference.plane.geometry import Material, RingPair, table1_rings
from fem_reference.plane.mesh import MeshSpec
from fem_reference.plane.solve import ContactModel
from fem_reference.scenes import Scene, clamped
from fem_reference.plane.sweep import Levels, reference_point


def test_tiny_arc_skips_unresolving_levels_and_converges():
    # Δr = 1e-4 mm: rigid-overlap half-angle arccos(0.05/0.0501) = 3.6° (Dai et al. 2025 Eq. 7), an arc
    # of ±5 mm (2.8° measured) that the 4 mm level cannot resolve; the point starts at the first level
    # with >= 3 elements across the half-arc measured on the coarsest resolving level: 1, 0.5, 0.25 mm.
    rec = reference_point(Levels(clamped()), 1e-7)
    assert rec["h_levels_m"][0] == pytest.approx(1e-3)
    assert rec["h_levels_m"][0] <= 100e-3 * rec["half_angle_rad"] / 3
    assert 0 < np.degrees(rec["half_angle_rad"]) < np.degrees(np.arccos(0.05 / 0.0501))
    assert rec["force_error_rel"] < 1e-3
    # small-load stiffness: the force is below the linear extrapolation of the 0.001 mm point
    # (the load-penetration curve stiffens, conformal law, docs/reference/contact-laws.md §3.1)
    assert 0 < rec["force_n"] < 10.76e3 / 10


def test_mesh_too_coarse_for_the_arc_fails_clearly():
    m = ContactModel.build(clamped(), MeshSpec(h_contact_m=8e-3))
    with pytest.raises(ArcNotResolvedError, match=r"h_contact_m = 0.008 m"):
        m.solve(1e-7)


def test_ten_times_the_clearance_converges_below_the_law_pole():
    # Δr = 0.5 mm = 10 δ0: the infinite-plate law has its pole at Δr = 10.09 δ0 (docs/reference/contact-laws.md §3.1);
    # clamped rings are stiffer, so the FE arc stays below the pole angle 84.8°, and converges.
    rec = reference_point(Levels(clamped(), (4e-3, 2e-3, 1e-3)), 0.5e-3)
    assert np.degrees(rec["half_angle_rad"]) < 84.83
    assert rec["force_error_rel"] < 1e-3
    assert rec["peak_pressure_pa"] > 2e9  # far beyond yield: a linear-elastic answer only (documented)


def test_zero_clearance_contact_spans_nearly_the_half_circle():
    # δ0 = 0: the rigid overlap of equal circles offset by Δr is the whole upper half (ε = 90°).
    rec = reference_point(Levels(Scene("zero", table1_rings(clearance_m=0.0)), (4e-3, 2e-3, 1e-3)), 1e-5)
    assert 80.0 < np.degrees(rec["half_angle_rad"]) <= 90.0
    assert rec["force_error_rel"] < 1e-3


def test_one_mm_clearance_is_hertz_like():
    # δ0 = 1 mm, Δr = 0.01 mm: ε = arccos(1/1.01) = 8.1°; a small arc in a stiff clamped pair. The 4 mm
    # level holds only ~3 elements across its half-arc (±12.6 mm), so the default levels go on to
    # 0.5 and 0.25 mm (the 4-2-1 mm sequence alone is not in the asymptotic range: estimate 1.5e-3).
    rec = reference_point(Levels(Scene("c1", table1_rings(clearance_m=1e-3))), 1e-5)
    assert np.degrees(rec["half_angle_rad"]) < 8.1
    assert rec["force_error_rel"] < 1e-3


def test_support_ten_times_stiffer_raises_the_load_but_less_than_tenfold():
    # Series compliances: a 10x stiffer support at most halves the compliance of equal bodies.
    rings = table1_rings()
    stiff = rings.with_(support=Material(10 * rings.support.youngs_modulus_pa, 0.3))
    f_ref = ContactModel.build(clamped(), MeshSpec(h_contact_m=2e-3)).solve(1e-5).force_n
    f_st = ContactModel.build(Scene("stiff", stiff), MeshSpec(h_contact_m=2e-3)).solve(1e-5).force_n
    assert 1.0 < f_st / f_ref < 2.0


@pytest.mark.parametrize("kwargs, name", [
    ({"clearance_m": -5e-5}, "clearance_m"),
    ({"clearance_m": float("nan")}, "clearance_m"),
    ({"outer_radius_m": 100.0e3}, "outer_radius_m"),     # mm typed as m
    ({"inner_radius_m": 0.2}, "inner_radius_m"),
])
def test_bad_geometry_is_rejected_naming_the_parameter(kwargs, name):
    with pytest.raises(InputError, match=name):
        RingPair(**kwargs)


def test_wrong_unit_modulus_rejected():
    with pytest.raises(InputError, match="youngs_modulus_pa"):
        Material(204.0, 0.3)


def test_levels_must_decrease():
    with pytest.raises(InputError, match="levels_m"):
        Levels(clamped(), (2e-3, 2e-3, 1e-3))
