"""2D FEM console jobs and VTU export (issue 3)."""
from __future__ import annotations

import json

import meshio
import numpy as np
import pytest

from reports.cli.fem import check_main, point_main
from fem_reference.plane.export import write_vtu
from fem_reference.plane.mesh import MeshSpec
from fem_reference.plane.solve import ContactModel
from fem_reference.scenes import clamped
from reports.cli import JOBS


def test_jobs_registered():
    for job in ("fem-point", "fem-sweep", "fem-check", "fem-vtu", "fem-paper", "fem-report"):
        assert job in JOBS


def test_fem_point_json_is_si_and_consistent(capsys):
    assert point_main(["0.01", "--h-mm", "4", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["penetration_m"] == pytest.approx(1e-5)
    assert rec["force_N"] > 0 and 0 < rec["half_angle_rad"] < np.pi / 2
    assert not any(k.endswith(("_n", "_nm", "_pa")) for k in rec), "JSON keys carry the unit symbol: force_N"
    # force = integral of the arc pressure (half model, symmetric): F = 2 l0 R_s ∫ p cos φ dφ
    # (P1 multipliers: trapezoidal rule is exact for p·cos φ up to O(h²))
    phi, p = np.array(rec["arc_phi_rad"]), np.array(rec["arc_pressure_Pa"])
    f = 2 * 0.03 * 0.10005 * np.trapezoid(p * np.cos(phi), phi)
    assert f == pytest.approx(rec["force_N"], rel=5e-3)


def test_fem_point_bad_input_gives_message_and_code(capsys):
    from reports.cli import main
    assert main(["fem-point", "nan", "--h-mm", "4"]) == 2
    assert "penetration_mm = nan mm: must be finite" in capsys.readouterr().err
    assert main(["fem-point", "0.01", "--scene", "nonsense"]) == 2


def test_fem_check_reports_no_change(capsys):
    assert check_main(["--points", "1", "--scene", "clamped"]) == 0
    assert "OK" in capsys.readouterr().out


def test_vtu_export_round_trip(tmp_path):
    m = ContactModel.build(clamped(), MeshSpec(h_contact_m=4e-3))
    s = m.solve(1e-5)
    path = write_vtu(tmp_path / "p.vtu", m, s)
    back = meshio.read(path)
    assert "triangle6" in back.cells_dict
    conn = back.cells_dict["triangle6"]
    assert conn.max() == len(back.points) - 1  # every node used, none out of range
    # mid-side nodes sit at their edge's middle, up to the sag L²/(8R) of curved boundary edges
    # (R >= 90 mm); a wrong numbering would put them anywhere
    pts = back.points[:, :2]
    a, b_, mid = pts[conn[:, 0]], pts[conn[:, 1]], pts[conn[:, 3]]
    L = np.linalg.norm(a - b_, axis=1)
    assert np.all(np.linalg.norm(mid - 0.5 * (a + b_), axis=1) <= 1.01 * L ** 2 / (8 * 0.09) + 1e-12)
    assert back.point_data["contact_pressure_pa"].max() == pytest.approx(s.peak_pressure_pa)
    d = back.point_data["displacement_m"]
    # the bearing's inner surface moved rigidly by t = δ0 + Δr along +y
    r = np.hypot(back.points[:, 0], back.points[:, 1])
    inner = np.abs(r - 0.09) < 1e-9
    assert np.allclose(d[inner, 1], 6e-5) and np.allclose(d[inner, 0], 0)
    assert back.cell_data["von_mises_pa"][0].max() > 0
    assert [p.name for p in tmp_path.iterdir()] == ["p.vtu"]


@pytest.mark.slow
def test_full_sweep_regenerates_identically(tmp_path):
    # the committed dataset is reproducible: regenerate into a temporary file and compare forces
    from contact.dataset import read_dataset
    from fem_reference.plane.sweep import DATASET_PATH, regenerate

    new = read_dataset(regenerate(tmp_path / "d.json", progress=False))
    old = read_dataset(DATASET_PATH)
    assert new.column("force_n") == pytest.approx(old.column("force_n"), rel=1e-7)
