"""`ringcontact fem3d vtu`: the bore's pressure map written for ParaView, checked by reading it back.

Source of the expected values: the same solve's own totals (force on the bearing) — the file
must carry the pressure field that produced them, on the bore radius, and nothing half-written.
"""
from __future__ import annotations

import math

import meshio
import numpy as np
import pytest

from contact.errors import InputError
from reports.cli import fem3d as cli3d
from fem_reference.solid.export import bore_surface, write_pressure_vtu


def test_vtu_pressure_integrates_to_the_solved_force(tmp_path, capsys):
    out = tmp_path / "p.vtu"
    assert cli3d.main(["vtu", "0.02", "--tilt-arcmin", "2", "--level", "Q0", "--no-cache", "--out", str(out)]) == 0
    reported_kN = float(capsys.readouterr().out.split("(")[1].split(" kN")[0])
    m = meshio.read(out)
    p = m.point_data["contact_pressure_pa"]
    phi = np.radians(m.point_data["phi_deg"])
    x = m.point_data["x_mm"] * 1e-3
    r = np.hypot(m.points[:, 1], m.points[:, 2])
    assert np.allclose(r, 0.1 + 0.05e-3, rtol=0, atol=1e-12)        # bore radius R_b + δ0 (Dai 2025 Table 1)
    assert np.allclose(np.arctan2(m.points[:, 2], m.points[:, 1]), phi, atol=1e-12)
    gap = m.point_data["rigid_gap_m"]
    assert np.all(p >= 0) and p.max() > 0
    assert gap[np.argmax(p)] < 0                      # the peak sits in the rigid overlap
    assert np.all(p[gap > 0.2 * 0.05e-3] == 0)        # far from the overlap (> 0.2 δ0 open): no load
    # (nodes open by < 1 µm before deformation may carry load: thin rings ovalise toward each other)
    # load = 2 ∫∫ p cos φ R dφ dx over the half model (trapezoid on the grid); the solve's nodal
    # areas are the same quadrature to O(h²): 2 % is far below the 2′ load's sensitivity to a wrong field
    P = p.reshape(len(np.unique(phi)), -1)
    ph = np.unique(phi)
    xs = np.unique(x)
    load = 2 * np.trapezoid(np.trapezoid(P, xs, axis=1) * np.cos(ph) * r[0], ph)
    assert load == pytest.approx(reported_kN * 1e3, rel=0.02)


def test_bad_input_and_no_partial_file(tmp_path):
    with pytest.raises(InputError, match="phi_grid/x_grid"):
        bore_surface(np.array([0.0]), np.array([0.0, 1.0]), 0.1)

    class R:   # a result carrying a NaN must not produce a file
        phi_grid = np.linspace(0, math.pi, 3)
        x_grid = np.linspace(-0.015, 0.015, 3)
        pressure_pa = np.full((3, 3), np.nan)

    class G:
        support_inner_radius_m = 0.10005

    with pytest.raises(InputError, match="non-finite"):
        write_pressure_vtu(tmp_path / "bad.vtu", R(), G())
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(SystemExit) as exc:
        cli3d.main(["vtu", "0.01", "--level", "L9", "--out", str(tmp_path / "x.vtu")])
    assert exc.value.code == 2


def test_corrupt_cached_level_is_rebuilt(tmp_path):
    """A cached compliance that does not load (truncated) is rebuilt and rewritten, not a traceback."""
    from fem_reference.solid.geometry import RingPair3D
    from fem_reference.solid.mesh import LEVELS
    from fem_reference.solid.sweep import compliance_path, get_compliance

    geom, level = RingPair3D(), LEVELS["Q0"]
    path = compliance_path(geom, level, "clamped", tmp_path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"PK\x03\x04 truncated")
    comp = get_compliance(geom, level, "clamped", cache=tmp_path)
    assert comp.A.shape[0] == comp.A.shape[1] > 0
    assert get_compliance(geom, level, "clamped", cache=tmp_path).A.shape == comp.A.shape   # the rewritten file loads
