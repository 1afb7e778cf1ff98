"""Every worked example of docs/examples/ runs, and its result is checked against its source.

Each example is imported from its file (as the documentation shows it) and its functions are
called; ``main()`` is run too, so the printed walk-through cannot rot. Expected values and where
they come from are named in each test. ``test_every_example_is_tested`` makes a new example fail
until it gets a test here.
"""
from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "docs" / "examples"


def _load(name: str):
    (path,) = EXAMPLES.glob(f"ex[0-9][0-9]_{name}.py")     # files are numbered in reading order
    spec = importlib.util.spec_from_file_location(f"gallery_{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _check_figure(fig) -> None:
    """``main()`` returns the figure the gallery page shows: axes with data and labels."""
    from matplotlib.figure import Figure
    import matplotlib.pyplot as plt
    assert isinstance(fig, Figure) and fig.axes
    for ax in fig.axes:
        assert ax.get_ylabel() and any(len(line.get_xdata()) > 1 for line in ax.get_lines())
    assert fig.axes[-1].get_xlabel()          # shared x axes carry the label on the bottom panel
    plt.close(fig)


TESTED = {"conformal_law", "calibrated_law", "fem_point", "rotor_campbell", "rotor_transient", "your_bearing",
          "your_rotor"}


def test_every_example_is_tested():
    assert {p.stem.split("_", 1)[1] for p in EXAMPLES.glob("*.py")} == TESTED


def test_every_example_has_a_titled_docstring():
    import ast
    for path in EXAMPLES.glob("*.py"):
        doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8")))
        assert doc and "\n\n" in doc and len(doc.splitlines()[0]) < 80, path.name


def test_conformal_law(capsys):
    ex = _load("conformal_law")
    force = ex.straight()
    # Dai et al. (2025) Table 2: the paper's FEM loads as recovered in docs/reference/contact-laws.md §10,
    # and the paper's percentage errors of its law against them (signs: law below FEM from 0.02 mm on)
    fem_implied = np.array([44_878, 105_247, 169_351, 235_945, 304_036])
    paper_percent = np.array([12.01, -0.79, -4.37, -5.59, -5.69])
    assert 100 * (force - fem_implied) / fem_implied == pytest.approx(paper_percent, abs=0.02)
    # tilted, one-point rule: the worked values of docs/reference/contact-laws.md §10 (N)
    c = ex.tilted([0.01, 0.03, 0.05], [0.5, 1.0, 2.0])
    table = np.array([[61_775, 73_454, 97_321], [174_947, 188_088, 214_825], [301_122, 315_669, 345_236]])
    assert np.hypot(c.Fy_N, c.Fz_N) == pytest.approx(table, rel=2e-5)
    assert np.all(c.width_1_m == pytest.approx(ex.WIDTH_M)) and np.all(np.abs(c.Mz_Nm) < 1e-6)  # capped patch
    # a partial patch: Dai et al. (2025) Eq. 11, l1 = Δr1/|θ| with Δr1 = Δr + |θ| l0/2; then a moment appears
    c = ex.tilted([0.002], [2.0])
    theta = math.radians(2 / 60)
    assert float(c.width_1_m[0, 0]) == pytest.approx((0.002e-3 + theta * ex.WIDTH_M / 2) / theta, rel=1e-9)
    assert float(c.Mz_Nm[0, 0]) < -1.0
    _check_figure(ex.main())
    assert "286731" in capsys.readouterr().out


def test_calibrated_law(capsys):
    ex = _load("calibrated_law")
    r = ex.compare()
    law = r["law"]
    assert law.name == "clamped-foundation"
    # Winkler foundation (Johnson 1985, §4.3): P = k_f R l e (ε − sin ε cos ε), e = δ0 + Δr, cos ε = δ0/e
    g, kf = law.geometry, law.parameters["foundation_modulus_Pa_per_m"]
    e = g.clearance_m + ex.PENETRATIONS_M
    eps = np.arccos(g.clearance_m / e)
    assert r["calibrated_N"] == pytest.approx(kf * g.radius_m * g.width_m * e * (eps - np.sin(eps) * np.cos(eps)),
                                              rel=1e-12)
    # reports/published/accuracy-table2.md, scene clamped, "calibrated (fit on all points)": −0.09 … −0.27 %
    err = 100 * (r["calibrated_N"] - r["fem_N"]) / r["fem_N"]
    assert err == pytest.approx([-0.09, -0.19, -0.23, -0.25, -0.27], abs=0.006)
    # same report, "conformal, plane stress (paper)": the paper's law is 84–89 % below these rings
    assert 100 * (r["conformal_N"] - r["fem_N"]) / r["fem_N"] == pytest.approx(
        [-83.73, -86.86, -87.96, -88.46, -88.68], abs=0.006)
    _check_figure(ex.main())
    assert "clamped-foundation" in capsys.readouterr().out


def test_fem_point(capsys):
    from contact.dataset import read_dataset
    from fem_reference.plane.sweep import DATASET_PATH

    ex = _load("fem_point")
    ref = [p for p in read_dataset(DATASET_PATH, kind="2d").select(scene="clamped")
           if abs(p["penetration_m"] - ex.PENETRATION_M) < 1e-15][0]
    assert ref["h_levels_m"][:2] == list(ex.LEVELS_M)
    for h, committed in zip(ex.LEVELS_M, ref["force_levels_n"]):
        s = ex.solve(h)
        # the committed reference's own level on this mesh (fem_reference/data/fem2d-reference.json)
        assert s.force_n == pytest.approx(committed, rel=1e-6)
    # the coarse 2 mm level is within 1e-4 of the extrapolated reference (its Richardson error 3.7e-5)
    assert s.force_n == pytest.approx(ref["force_n"], rel=1e-4)
    _check_figure(ex.main())
    assert "h = 2 mm" in capsys.readouterr().out


def test_rotor_campbell(capsys):
    ex = _load("rotor_campbell")
    # Jeffcott (1919), the closed form in rotor/scenes/verify-jeffcott.toml's header: 1137.3 rpm
    (jeffcott,) = ex.forward_criticals_rpm("verify-jeffcott", 3000)
    assert jeffcott == pytest.approx(1137.3, abs=0.05)
    # reports/published/rotor-mesh.md, paper-table4 forward critical speeds, 1 element per segment
    assert ex.forward_criticals_rpm("paper-table4", 18000) == pytest.approx([2441.4, 4270.5, 9608.2], abs=0.05)
    _check_figure(ex.main())
    out = capsys.readouterr().out
    assert "Campbell diagram" in out and "9608.2 rpm" in out


def test_rotor_transient(capsys):
    """The compiled scheme's first use in a process compiles it or loads it from the numba cache
    (reports/published/perf-compile.md: about 25 s uncached, 0.3 s cached)."""
    from rotor.dynamics import constraints as cons
    from rotor.dynamics.energy import energy_balance

    ex = _load("rotor_transient")
    system, tr = ex.run()
    eb = energy_balance(system, tr)
    r1, r2 = cons.edge_offsets(tr.u, system.support.width_m)
    assert max(r1.max(), r2.max()) > system.support.law.clearance_m        # the bearing hit its support
    assert eb.impact[-1] > 0 and eb.friction[-1] > 0 and eb.damping[-1] > 0
    assert 0 < tr.modes.mean() < 1                                           # stick and slip both happened
    # tests/rotor/dynamics/test_dynamics_verification.py holds the scheme to 1 % of the input work
    assert eb.relative_closure() < 0.01
    assert tr.unconverged_steps == 0
    _check_figure(ex.main())
    assert "balance closes" in capsys.readouterr().out


def test_your_bearing(tmp_path, capsys):
    """The law of the example's ring pair reproduces its own 2D FEM points held out within the job's bound
    (contact.calibrate.fit.HOLDOUT_BOUND_REL), the rotor took the law's clearance and width (the example's
    ring-pair text: 0.03 mm, 22 mm), and the bearing hit its support at 6 000 rpm."""
    import json

    from contact.calibrate.fit import HOLDOUT_BOUND_REL
    from rotor.dynamics import constraints as cons

    ex = _load("your_bearing")
    summary = ex.law_for_my_bearing(tmp_path)
    assert summary["warnings"] == [] and summary["checks"]["holdout_max_rel_2d"] < HOLDOUT_BOUND_REL
    assert json.loads((tmp_path / "my-bearing-law.json").read_text())["name"] == summary["law_name"]
    scene, system, tr = ex.rotor_with_my_bearing(tmp_path)
    ls = scene.loose_support
    assert (ls.clearance_m, ls.ring_width_m) == pytest.approx((3e-5, 0.022))
    r1, r2 = cons.edge_offsets(tr.u, system.support.width_m)
    assert max(r1.max(), r2.max()) > system.support.law.clearance_m
    _check_figure(ex.main())
    assert "in contact" in capsys.readouterr().out


# Friswell, Penny, Garvey & Lees (2010), Dynamics of Rotating Machines, Example 5.9.1 (bored disks): the book's
# whirl frequencies (rad/s) at rest and at 4 000 rpm
FRISWELL_591_AT_REST = [86.66, 86.66, 274.31, 274.31, 716.78, 716.78]
FRISWELL_591_AT_4000_RPM = [85.39, 87.80, 251.78, 294.71, 600.18]


def _contact_fields_in(result) -> dict:
    """The contact summary of a result, and its dict and saved forms say the same."""
    d = result.to_dict()
    return {k: d[k] for k in ("peak_contact_force_N", "contact_share", "stick_share_right_face") if k in d}


def test_your_rotor(capsys):
    """The book rotor built from scratch has the book's frequencies to 0.01 rad/s; the loose rotor's time history
    reports its contact force (the full walk-through, orbit, branch and cascade included, is the slow test)."""
    ex = _load("your_rotor")
    f = ex.frequencies()
    assert f[0.0].frequency_rad_s == pytest.approx(FRISWELL_591_AT_REST, abs=0.01)
    assert f[4000.0].frequency_rad_s[:5] == pytest.approx(FRISWELL_591_AT_4000_RPM, abs=0.01)
    scene = ex.loose_rotor(ex.book_rotor())
    assert scene.loose_support.bearing_station == "N6" and [b.name for b in scene.bearings] == ["left"]
    res = ex.main(full=False)
    s = res["simulate"]
    assert s.peak_contact_force_N > 0 and 0 < s.contact_share <= 1         # the loose ring hits its support
    assert _contact_fields_in(s)["peak_contact_force_N"] == s.peak_contact_force_N
    assert "peak contact force" in capsys.readouterr().out
    _check_figure(ex.gallery())          # what the documentation page shows


@pytest.mark.slow
def test_your_rotor_end_to_end(capsys):
    """Every analysis of the walk-through reports the contact force (about 70 s on 2 shared cores)."""
    ex = _load("your_rotor")
    res = ex.main(full=True)
    out = capsys.readouterr().out
    for key in ("simulate", "orbit", "cascade"):
        fields = _contact_fields_in(res[key])
        assert set(fields) == {"peak_contact_force_N", "contact_share", "stick_share_right_face"}, key
    assert res["orbit"].converged and res["orbit"].peak_contact_force_N > 0
    assert len(res["branch"].speeds_rpm) >= 2 and np.all(res["branch"].peak_contact_force_N > 0)
    c = res["cascade"]       # at 2 500 rpm the ring stays in contact; at 4 000 rpm it settles clear of the bore
    assert c.speeds_rpm.tolist() == [2500.0, 4000.0] and c.peak_contact_force_N[0] > 0 and c.contact_share[0] > 0.5
    assert c.contact_share[1] == 0.0 and c.peak_contact_force_N[1] == 0.0
    assert out.count("peak contact force") == 3 and out.count("peak ") >= 5
