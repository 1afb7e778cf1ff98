"""3D geometry: exact tilted-cylinder gap, rigid-motion conventions, mesh grading and pairing."""
from __future__ import annotations

import math

import numpy as np
import pytest

from contact.errors import InputError
from contact.units import ARCMIN, MM
from fem_reference.solid.geometry import (RigidMotion, RingPair3D, edge_penetrations_m, law_contact_width_m,
                                      reduce_motion, rigid_gap_m, rotate_about_x)
from fem_reference.solid.mesh import MeshLevel3D, build_meshes, graded_one_sided, graded_symmetric

GEOM = RingPair3D()


def test_table1_defaults():
    # Dai et al. 2025 Table 1: R_b = 100 mm, 10 mm rings, delta0 = 0.05 mm, l0 = 30 mm, E = 204 GPa
    assert GEOM.support_inner_radius_m == pytest.approx(100.05 * MM)
    assert GEOM.support_outer_radius_m == pytest.approx(110.05 * MM)
    assert GEOM.width_m == pytest.approx(30 * MM)


def test_untilted_gap_is_offset_circles():
    # Law of cosines: the bore point at polar angle phi is at distance
    # sqrt(R_s^2 + r^2 - 2 R_s r cos(phi)) from the shifted bearing centre.
    r = GEOM.clearance_m + 0.02 * MM
    phi = np.linspace(0, math.pi, 181)
    g = rigid_gap_m(GEOM, RigidMotion(r, 0.0), phi, 0.0)
    rs = GEOM.support_inner_radius_m
    exact = np.sqrt(rs ** 2 + r ** 2 - 2 * rs * r * np.cos(phi)) - GEOM.bearing_outer_radius_m
    assert np.max(np.abs(g - exact)) < 1e-15
    assert g[0] == pytest.approx(GEOM.clearance_m - r, abs=1e-15)
    # zero crossing = rigid-overlap half-angle cos(eps) = delta0/(delta0 + dr) (docs/reference/contact-laws.md §2)
    eps = math.acos(GEOM.clearance_m / r)
    crossing = np.interp(0.0, g, phi)
    assert crossing == pytest.approx(eps, abs=2e-3)


def test_tilted_gap_linear_in_x_and_law_width():
    # Dai et al. 2025 Eq. 8: a point at axial x moves by r + theta*x; on the +y generatrix the
    # exact gap to the tilted cylinder is (R_s - r) cos(theta) - x sin(theta) - R_b (distance to
    # the tilted axis), i.e. delta0 - r - theta*x minus R theta^2/2 (17 nm at 2'): the overlap
    # starts at x = -dr/theta and its length is Delta r_1 / theta (Eq. 11), capped at l0.
    theta = 2 * ARCMIN
    motion = RigidMotion.from_penetration(GEOM, 0.002 * MM, theta)
    x = np.linspace(-15, 15, 61) * MM
    g = rigid_gap_m(GEOM, motion, 0.0, x)
    exact = ((GEOM.support_inner_radius_m - motion.translation_m) * math.cos(theta) - x * math.sin(theta)
             - GEOM.bearing_outer_radius_m)
    assert np.max(np.abs(g - exact)) < 1e-15
    lin = GEOM.clearance_m - motion.translation_m - theta * x
    assert np.max(np.abs(g - lin)) < 0.6 * GEOM.bearing_outer_radius_m * theta ** 2
    d1, d2 = edge_penetrations_m(GEOM, motion)
    assert d1 == pytest.approx(0.002 * MM + theta * 15 * MM)
    assert law_contact_width_m(GEOM, motion) == pytest.approx(d1 / math.tan(theta))
    big = RigidMotion.from_penetration(GEOM, 0.05 * MM, theta)
    assert law_contact_width_m(GEOM, big) == GEOM.width_m


def test_reduce_motion_tilt_about_y_is_rotated_canonical():
    # docs/reference/contact-laws.md §1: lateral displacement at x is (y + x theta_z, z - x theta_y). Translation
    # along +z with tilt about -y is the canonical case rotated by +90 deg about x.
    c = reduce_motion(0.0, 1e-4, -3e-4, 0.0)
    assert c.frame_angle_rad == pytest.approx(math.pi / 2)
    assert c.motion.translation_m == pytest.approx(1e-4)
    assert c.motion.tilt_rad == pytest.approx(3e-4)
    fy, fz = rotate_about_x(-1.0, 0.0, c.frame_angle_rad)
    assert (fy, fz) == pytest.approx((0.0, -1.0), abs=1e-15)      # restoring force along -z
    c2 = reduce_motion(-1e-4, 0.0, 0.0, -3e-4)                    # everything mirrored: same canonical
    assert c2.motion.translation_m == pytest.approx(1e-4) and c2.motion.tilt_rad == pytest.approx(3e-4)


def test_reduce_motion_rejects_out_of_plane_motion():
    with pytest.raises(InputError, match="not in one plane"):
        reduce_motion(1e-4, 0.0, 3e-4, 0.0)      # translation along y, tilt about y: full model needed


@pytest.mark.parametrize("kwargs, match", [
    ({"clearance_m": -5e-5}, "clearance_m"),
    ({"clearance_m": 0.05}, "wrong unit"),
    ({"young_bearing_pa": 204.0}, "young"),
    ({"poisson_support": 0.6}, "poisson_support"),
    ({"bearing_inner_radius_m": 0.2}, "bearing_inner_radius_m"),
])
def test_bad_geometry_is_named(kwargs, match):
    with pytest.raises(InputError, match=match):
        RingPair3D(**kwargs)


def test_bad_motion_is_named():
    with pytest.raises(InputError, match="translation_m"):
        RigidMotion(0.05, 0.0)                   # 0.05 "mm" typed as metres
    with pytest.raises(InputError, match="tilt_rad"):
        RigidMotion(1e-4, 2.0)                   # 2 arcmin typed as radians
    with pytest.raises(InputError, match="translation_m"):
        RigidMotion(float("nan"), 0.0)


def test_grading_symmetric_and_monotone():
    x = graded_symmetric(-1.0, 1.0, 12, 3.0)
    assert np.all(np.diff(x) > 0) and np.allclose(x, -x[::-1], atol=1e-15)
    h = np.diff(x)
    assert h[5] / h[0] == pytest.approx(3.0)
    r = graded_one_sided(0.0, 1.0, 4, 3.0)
    assert np.diff(r)[-1] / np.diff(r)[0] == pytest.approx(3.0)


def test_mesh_nodes_on_exact_circles_and_paired():
    # Full isoparametric rings: every one of the 27 nodes of the contact-surface elements lies on its
    # circle (mid-edge and mid-face nodes moved out from the chords), the ring volume is the exact
    # annulus volume pi (R_o^2 - R_i^2) l0 to O(h^4), and both rings share the axial node lines.
    from skfem import Basis, ElementHex2
    lv = MeshLevel3D("t", 16, 6, 2)
    b, s = build_meshes(GEOM, lv)
    for ring in (b, s):
        loc = ring.mesh.doflocs
        rad = np.hypot(loc[1], loc[2])
        on = np.isclose(rad, ring.contact_radius_m, rtol=0, atol=1e-12)
        assert on.sum() == (2 * 2 * lv.n_phi) * (2 * lv.n_axial + 1)
        assert ring.mesh.t.shape == (8, 2 * lv.n_phi * lv.n_axial * lv.n_radial)
        r_in, r_out = sorted((ring.contact_radius_m, ring.held_radius_m))
        vol = Basis(ring.mesh, ElementHex2(), intorder=4).dx.sum()
        assert vol == pytest.approx(math.pi * (r_out ** 2 - r_in ** 2) * GEOM.width_m, rel=1e-5)
    assert np.array_equal(b.x_nodes, s.x_nodes)


def test_bad_level_is_named():
    with pytest.raises(InputError, match="n_phi"):
        MeshLevel3D("bad", 1, 6, 2)
    with pytest.raises(InputError, match="n_axial"):
        MeshLevel3D("bad", 16, 5, 2)
    with pytest.raises(InputError, match="method"):
        MeshLevel3D("bad", 16, 6, 2, method="spectral")
    with pytest.raises(InputError, match="n_harmonics"):
        MeshLevel3D("bad", 16, 6, 2, method="fourier", n_harmonics=2)
    with pytest.raises(InputError, match="order"):
        MeshLevel3D("bad", 16, 6, 2, order=3)
