"""Assembled model: DOF map, constraints, coupling spring, misalignment and unbalance loads,
linear forced response, CLI."""
from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from contact.errors import InputError
from reports.cli import rotor as cli
from rotor.model.assembly import (assemble, constraint_basis, coupling_moment, harmonic_loads, lock_rows,
                         misalignment_force, misalignment_offset, unbalance_force)
from rotor.model.scene import SCENE_DIR, load_scene, loads_scene
from rotor.linear.unbalance import forced_response


@pytest.fixture(scope="module")
def table4():
    return assemble(load_scene("paper-table4"))


def test_dof_order_is_the_papers_generalized_coordinate(table4):
    """Dai et al. 2025, Eq. 30: q = [y1 z1 θ1y θ1z, y2 …, 3a, 3b, 4, 5, s] (28 DOFs)."""
    nodes = ["1", "2", "3a", "3b", "4", "5", "s"]
    assert table4.dof_names == tuple(f"{n}.{d}" for n in nodes for d in ("y", "z", "θy", "θz"))
    assert table4.dof_index("disk1.y") == 4 and table4.dof_index("disk2.θz") == 19
    assert table4.dof_index("s.tz") == 27 and table4.dof_index("bearing2.z") == 9
    assert table4.loose_pair.bearing == (20, 21, 22, 23) and table4.loose_pair.support == (24, 25, 26, 27)
    with pytest.raises(InputError, match="no node or element named 'disk9'"):
        table4.dof_index("disk9.y")


def test_matrices_symmetry_and_mass(table4):
    m = table4
    assert np.allclose(m.M, m.M.T) and np.allclose(m.K, m.K.T) and np.allclose(m.G, -m.G.T)
    assert np.allclose(m.C, m.C.T) and np.allclose(m.K_c, m.K_c.T)
    # total translating mass in y: shafts (Table 4 geometry and densities) + disks + m_b + m_s
    shafts = sum(sh.material.density_kg_m3 * math.pi / 4 * (sh.outer_diameter_m ** 2 - sh.inner_diameter_m ** 2)
                 * (load_scene("paper-table4").station(sh.end).x_m - load_scene("paper-table4").station(sh.start).x_m)
                 for sh in m.scene.shafts)
    ey = np.zeros(m.n_dofs)
    ey[[i for i, n in enumerate(m.dof_names) if n.endswith(".y")]] = 1.0
    assert ey @ m.M @ ey == pytest.approx(shafts + 150 + 120 + 10 + 100, rel=1e-12)
    # subdivision keeps the mass and adds interior nodes after the paper's nodes
    fine = assemble(m.scene, elements_per_segment=4)
    assert fine.dof_names[:28] == m.dof_names and fine.n_dofs == 28 + 4 * 3 * 4
    ey = np.zeros(fine.n_dofs)
    ey[[i for i, n in enumerate(fine.dof_names) if n.endswith(".y")]] = 1.0
    assert ey @ fine.M @ ey == pytest.approx(shafts + 380, rel=1e-12)


def test_support_node_and_coupling_in_linear_matrices(table4):
    """Support ground springs/damper/mass (Eq. 52) and the a0 spring between θ(3a) and θ(3b)."""
    m, s = table4, table4.loose_pair.support
    sp = m.scene.supports[0]
    assert np.allclose(np.diag(m.K)[list(s)], [sp.stiffness_n_m] * 2 + [sp.angular_stiffness_n_m_rad] * 2)
    assert np.allclose(np.diag(m.C)[list(s)], [sp.damping_n_s_m] * 2 + [sp.angular_damping_n_m_s_rad] * 2)
    assert np.allclose(np.diag(m.M)[list(s)], [sp.mass_kg] * 2 + [sp.inertia_kg_m2] * 2)
    # nothing couples bearing node 5 to the support node in the linear model
    b = m.loose_pair.bearing
    for X in (m.M, m.C, m.G, m.K, m.K_c):
        assert not np.any(X[np.ix_(b, s)])
    a0 = m.scene.couplings[0].a0_n_m_rad
    ia, ib = m.dof_index("3a.θy"), m.dof_index("3b.θy")
    assert m.K_c[ia, ia] == a0 and m.K_c[ia, ib] == -a0 and np.count_nonzero(m.K_c) == 8
    # equal lateral displacement constraint rows
    assert m.B.shape == (2, 28)
    assert m.B[0, m.dof_index("3a.y")] == 1 and m.B[0, m.dof_index("3b.y")] == -1
    T = constraint_basis(m, lock_loose_support=True)
    assert T.shape == (28, 22)
    assert np.allclose(np.vstack([m.B, lock_rows(m)[0]]) @ T, 0)


def test_coupling_moment_law_and_jacobian(table4):
    """M_c = (a0 + a1|Δθ|²)Δθ, −M_c on 3a, +M_c on 3b (Eqs. 32, 44); Jacobian = finite differences."""
    m = table4
    cp = m.couplings[0]
    rng = np.random.default_rng(1)
    q = rng.normal(scale=1e-3, size=m.n_dofs)
    f, J = coupling_moment(m, q)
    d = q[[cp.a[2], cp.a[3]]] - q[[cp.b[2], cp.b[3]]]
    g = cp.a1_n_m_rad3 * (d @ d) * d
    assert np.allclose(f[[cp.a[2], cp.a[3]]], -g) and np.allclose(f[[cp.b[2], cp.b[3]]], g)
    assert np.count_nonzero(f) == 4
    ft, _ = coupling_moment(m, q, include_linear=True)
    assert np.allclose(ft, f - m.K_c @ q)
    h = 1e-9
    Jfd = np.column_stack([(coupling_moment(m, q + h * e)[0] - coupling_moment(m, q - h * e)[0]) / (2 * h)
                           for e in np.eye(m.n_dofs)])
    assert np.allclose(J, Jfd, rtol=1e-6, atol=1e-6 * np.abs(J).max())


def test_misalignment_offset_is_eq33(table4):
    """Eq. 33 with δ = 1 mm, l34 = 1400, l45 = 100 mm: Δy4 = 14/15 δ, Δy5 = Δys = δ, Δθz = δ/1.5 m."""
    dq = misalignment_offset(table4)
    i = table4.dof_index
    tilt = 1e-3 / 1.5
    expected = {"3b.θz": tilt, "4.y": 1.4 / 1.5 * 1e-3, "4.θz": tilt, "5.y": 1e-3, "5.θz": tilt, "s.y": 1e-3,
                "s.θz": tilt}
    for name, v in expected.items():
        assert dq[i(name)] == pytest.approx(v, rel=1e-12)
    assert np.count_nonzero(dq) == len(expected)
    # relative bearing-support coordinates unaffected
    lp = table4.loose_pair
    assert np.allclose(dq[list(lp.bearing)], dq[list(lp.support)])


def test_misalignment_excitation_is_eq34(table4):
    """Eq. 34: F = 2 m_sp L tan(Δθ/2) Ω² (cos 2Ωt, sin 2Ωt), M = m_sp L² tan(Δθ/2) Ω² (…); the
    scene's reading "opposed-at-joint": F and M on 3a, −F and −M on 3b (the other readings:
    tests/rotor/model/test_misalignment_readings.py)."""
    W, t = 1000.0, 0.0123
    cp = table4.scene.couplings[0]
    tt = math.tan(1e-3 / 1.5 / 2)
    F = 2 * cp.shaft_mass_kg * cp.lever_m * tt * W ** 2
    Mm = cp.shaft_mass_kg * cp.lever_m ** 2 * tt * W ** 2
    f = misalignment_force(table4, t, W)
    i = table4.dof_index
    c, s = math.cos(2 * W * t), math.sin(2 * W * t)
    assert [f[i("3a.y")], f[i("3a.z")], f[i("3a.θy")], f[i("3a.θz")]] == pytest.approx([F * c, F * s, Mm * c, Mm * s])
    assert [f[i("3b.y")], f[i("3b.z")], f[i("3b.θy")], f[i("3b.θz")]] == pytest.approx([-F * c, -F * s, -Mm * c, -Mm * s])
    assert np.count_nonzero(f) == 8
    assert misalignment_force(table4, np.array([t, 2 * t]), W).shape == (2, 28)


def test_unbalance_load_is_eq39_40():
    """Eqs. 39–40: (m e Ω² cos, m e Ω² sin, (Ip−Id)τΩ² cos(Ωt+φ), (Ip−Id)τΩ² sin(Ωt+φ))."""
    scene = load_scene("paper-table4")
    disks = (replace(scene.disks[0], skew_rad=2e-4, skew_phase_rad=0.7),) + scene.disks[1:]
    m = assemble(replace(scene, disks=disks))
    W, t = 800.0, 0.37
    q = unbalance_force(m, t, W)
    i = m.dof_index
    u = 2e-3 * W ** 2
    tm = (10 - 8) * 2e-4 * W ** 2
    assert [q[i("disk1.y")], q[i("disk1.z")]] == pytest.approx([u * math.cos(W * t), u * math.sin(W * t)])
    assert [q[i("disk1.θy")], q[i("disk1.θz")]] == pytest.approx([tm * math.cos(W * t + 0.7), tm * math.sin(W * t + 0.7)])
    assert [q[i("disk2.y")], q[i("disk2.z")]] == pytest.approx([u * math.cos(W * t), u * math.sin(W * t)])
    assert q[i("disk2.θy")] == 0 and np.count_nonzero(q) == 6


DAMPED_JEFFCOTT = """
schema = "ringcontact.rotor-scene/1"
name = "sdof"
title = "Jeffcott rotor with a damper at the disk, rigid pinned supports"
[[materials]]
name = "massless"
density_kg_m3 = 0
youngs_modulus_gpa = 200
poisson_ratio = 0.3
[[stations]]
name = "A"
x_mm = 0
[[stations]]
name = "D"
x_mm = 400
[[stations]]
name = "B"
x_mm = 800
[[shafts]]
from = "A"
to = "D"
outer_diameter_mm = 20
material = "massless"
[[shafts]]
from = "D"
to = "B"
outer_diameter_mm = 20
material = "massless"
[[disks]]
name = "disk"
station = "D"
mass_kg = 10
polar_inertia_kg_m2 = 0
diametral_inertia_kg_m2 = 0
unbalance_g_mm = 100
unbalance_phase_deg = 30
[[bearings]]
name = "damper"
station = "D"
stiffness_n_per_m = 0
damping_n_s_per_m = 150
[[boundaries]]
station = "A"
fixed = ["y", "z"]
[[boundaries]]
station = "B"
fixed = ["y", "z"]
"""


def test_unbalance_response_of_damped_jeffcott_rotor():
    """Steady state ŷ = m e Ω² e^{iφ}/(k − mΩ² + icΩ), ẑ = −i ŷ (forward circular orbit)
    (Jeffcott 1919; e.g. Genta 2005, Dynamics of Rotating Systems, §4.2)."""
    model = assemble(loads_scene(DAMPED_JEFFCOTT))
    E, d, L, nu = 200e9, 0.02, 0.8, 0.3
    from rotor.model.elements import cowper_shear_coefficient
    A, I = math.pi / 4 * d * d, math.pi / 64 * d ** 4
    k = 1 / (L ** 3 / (48 * E * I) + L / (4 * cowper_shear_coefficient(d, 0, nu) * E / (2 * (1 + nu)) * A))
    speeds = np.sqrt(k / 10) * np.array([0.5, 1.0, 1.7])
    resp = forced_response(model, speeds)
    iy, iz = model.dof_index("disk.y"), model.dof_index("disk.z")
    for j, W in enumerate(speeds):
        yhat = 1e-4 * W ** 2 * np.exp(1j * math.pi / 6) / (k - 10 * W ** 2 + 1j * 150 * W)
        assert resp.amplitudes[j, iy] == pytest.approx(yhat, rel=1e-9)
        assert resp.amplitudes[j, iz] == pytest.approx(-1j * yhat, rel=1e-9)
    major, minor = resp.orbit(model, "disk")
    assert np.allclose(major, minor)                              # circular orbit
    assert np.allclose(forced_response(model, speeds, order=2).amplitudes, 0)   # no misalignment → no 2X


def test_cli_json_and_errors(capsys, tmp_path):
    assert cli.main(["critical-speeds", "verify-jeffcott", "--orders", "1", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    fwd = [c for c in data["critical_speeds"] if c["whirl"] == "forward"]
    assert fwd and fwd[0]["speed_rpm"] == pytest.approx(fwd[0]["frequency_hz"] * 60, rel=1e-9)
    assert cli.main(["modes", "paper-table4", "--speed-rpm", "3000", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {m["whirl"] for m in data["modes"]} <= {"forward", "backward", "mixed"} and len(data["modes"]) == 8
    bad = tmp_path / "bad.toml"
    good = (SCENE_DIR / "verify-jeffcott.toml").read_text()
    bad.write_text(good.replace("outer_diameter_mm = 20", "outer_diameter_mm = 20\ninner_diameter_mm = 25", 1))
    assert cli.main(["modes", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "bad.toml: shafts[0].inner_diameter_mm = 25 mm: must be < outer_diameter_mm = 20 mm" in err
    assert err.count("\n") == 1


def test_damped_modes_of_jeffcott_rotor():
    """Single-DOF per direction: λ = −ζω_n ± iω_n√(1−ζ²), ζ = c/(2√(km)) (e.g. Rao 2011, Mechanical
    Vibrations, Eq. 2.72); forward and backward whirl share it (no gyroscopic term)."""
    from rotor.model.elements import cowper_shear_coefficient
    from rotor.linear.modes import modes
    model = assemble(loads_scene(DAMPED_JEFFCOTT))
    E, d, L, nu, m, c = 200e9, 0.02, 0.8, 0.3, 10.0, 150.0
    A, I = math.pi / 4 * d * d, math.pi / 64 * d ** 4
    k = 1 / (L ** 3 / (48 * E * I) + L / (4 * cowper_shear_coefficient(d, 0, nu) * E / (2 * (1 + nu)) * A))
    wn, zeta = math.sqrt(k / m), c / (2 * math.sqrt(k * m))
    res = modes(model, 300.0, damped=True)
    assert res.frequency_hz == pytest.approx([wn * math.sqrt(1 - zeta ** 2) / (2 * math.pi)] * 2, rel=1e-9)
    assert res.damping_ratio == pytest.approx([zeta] * 2, rel=1e-9)
    assert sorted(res.whirl) == ["backward", "forward"]


def test_cli_writes_plots(tmp_path, capsys):
    prefix = tmp_path / "camp"
    assert cli.main(["campbell", "verify-overhung-disk", "--points", "4", "--plot", str(prefix)]) == 0
    capsys.readouterr()
    for ext in ("png", "svg"):
        data = (tmp_path / f"camp-campbell.{ext}").read_bytes()
        assert len(data) > 1000
    assert b"<svg" in (tmp_path / "camp-campbell.svg").read_bytes()
    assert not list(tmp_path.glob(".*.tmp"))          # atomic write left no temporary file


def test_plot_prefix_shared_by_every_rotor_figure(tmp_path, capsys):
    """One --plot PREFIX for campbell, unbalance (1X and 2X) and modes: each figure its own files, none overwritten."""
    prefix = str(tmp_path / "r")
    runs = [["campbell", "--points", "4"], ["unbalance", "--points", "4"], ["unbalance", "--points", "4", "--order", "2"],
            ["modes"]]
    for argv in runs:
        assert cli.main([argv[0], "paper-table4", *argv[1:], "--plot", prefix]) == 0
    capsys.readouterr()
    svgs = {p.name: p.read_text(encoding="utf-8") for p in tmp_path.glob("*.svg")}
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        f"r-{what}.{ext}" for what in ("campbell", "unbalance", "misalignment", "modeshapes") for ext in ("png", "svg"))
    assert "Campbell diagram" in svgs["r-campbell.svg"]          # the first figure survived the later runs
    assert "unbalance response (1X)" in svgs["r-unbalance.svg"]
    assert "misalignment response (2X)" in svgs["r-misalignment.svg"]


def test_misalignment_offset_on_a_subdivided_mesh():
    """Eq. 33 as a rigid rotation about 3b: interior nodes of 3b–4 and 4–5 lie on the same line."""
    m = assemble(load_scene("paper-table4"), elements_per_segment=3)
    dq = misalignment_offset(m)
    tilt = 1e-3 / 1.5
    checked = 0
    for node, x in zip(m.node_names, m.node_x_m):
        if node.startswith(("3b~4#", "4~5#")):
            assert dq[m.dof_index(f"{node}.y")] == pytest.approx(tilt * (x - 0.6), rel=1e-12)
            assert dq[m.dof_index(f"{node}.θz")] == pytest.approx(tilt, rel=1e-12)
            checked += 1
        elif node.startswith(("1~", "2~")):
            assert not np.any(dq[list(m.node_dofs(node))])
    assert checked == 4
