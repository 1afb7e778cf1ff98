"""FEM and contact-law reports against the committed datasets, in the default run.

The builders of ``fem2d-reference.md`` and ``fem3d-reference.md`` (reports/fem2d.py, reports/fem3d.py) write their
dataset sections from the committed datasets alone: those sections are rebuilt here and must be in the published
files. Their solved sections (plate growth, Hex27 check) take minutes; the cheap ones are recomputed (the Lamé
ring with P2 elements). ``bearing-table1-reproduction.md`` (the Table 1 ring file through ``ringcontact bearing``)
is checked on one 2D point, the ``steel-in-aluminium`` law by refitting it from its committed FEM datasets, and
``fem2d-paper-setup.md``'s headline ratios from the laws and the committed 2D dataset. Each test names the
published values it guards; the registry of claims is tests/claims.py.
"""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from contact import laws
from contact.calibrate.fit import DATA_3D_DIR, DATASET_2D
from contact.dataset import read_dataset

ROOT = Path(__file__).resolve().parents[1]
PUBLISHED = ROOT / "reports" / "published"
DATASET_3D = DATA_3D_DIR / "fem3d-reference.json"
TABLE1 = dict(clearance_m=0.05e-3, width_m=30e-3, bearing_E_Pa=204e9, bearing_nu=0.3, support_E_Pa=204e9,
              support_nu=0.3)
TABLE2_PEN_M = np.array([0.01, 0.02, 0.03, 0.04, 0.05]) * 1e-3
PEREIRA_PCT = np.array([30.60, 29.74, 27.59, 25.59, 23.72])     # Dai et al. (2025) Table 2, Pereira column


def _md(name: str) -> str:
    return (PUBLISHED / name).read_text(encoding="utf-8")


def test_fem2d_reference_tables_are_what_the_builder_writes():
    """fem2d-reference.md's dataset sections (every committed point; "Largest estimated force error 8.5e-04
    (12/12 points ≤ 0.1 %)" for `clamped`; the Persson check "largest |FE/law − 1| = 0.67% over 9 points") as
    reports/fem2d.py writes them from fem_reference/data/fem2d-reference.json, and the CSV beside it."""
    from reports.fem2d import _header_lines, _persson_section, _scene_tables

    ds = read_dataset(DATASET_2D)
    tables, csv_text = _scene_tables(ds)
    block = "\n".join(_header_lines(ds.metadata) + tables + _persson_section(ds))
    assert _md("fem2d-reference.md").startswith(block), "fem2d-reference.md is stale: run `ringcontact fem-report`"
    assert (PUBLISHED / "fem2d-reference.csv").read_bytes() == csv_text.encode("utf-8")


def test_lame_ring_p2_within_the_published_error():
    """fem2d-reference.md, Lamé thick ring with P2 elements at h = 2 mm: "| P2 | strain | 2 | 3.60711 | 3.60712 |
    -3.5e-06 |" and plane stress -2.8e-06, recomputed (tests/fem_reference/plane/test_fem_solver.py asserts the
    P1 and P2 rings at 0.5 %; the published P2 error is asserted here, to its printed digits)."""
    from fem_reference.verify import lame_fem

    md = _md("fem2d-reference.md")
    for plane in ("strain", "stress"):
        fe, ex = lame_fem(2e-3, 2, plane)
        assert abs(fe / ex - 1) < 1e-5
        assert f"| P2 | {plane} | 2 | {fe * 1e6:.5f} | {ex * 1e6:.5f} | {fe / ex - 1:+.1e} |" in md


def test_fem3d_reference_point_table_is_what_the_builder_writes():
    """fem3d-reference.md's table of the committed points and its summary ("Largest stated error: force 1.51 %,
    moment 0.61 % (acceptance: 2 %)", the 15 Table 3 points at 0.23 % and 0.44 %, every stated error bounding
    the finer check level) as reports/fem3d.py writes them from the committed 3D dataset, and the CSV."""
    from reports.fem3d import _points_section

    md, csv_lines = _points_section(read_dataset(DATASET_3D), DATASET_3D.name)
    assert "\n".join(md) in _md("fem3d-reference.md"), "fem3d-reference.md is stale: run `ringcontact fem3d report`"
    assert (PUBLISHED / "fem3d-reference.csv").read_text(encoding="utf-8") == "\n".join(csv_lines) + "\n"


def test_fem3d_perf_point_is_the_committed_one():
    """fem3d-perf.md: "Committed value of this point (`fem3d-reference.json`, levels Q0, Q1, Q2): 1193.37 kN,
    -2.1005 kN·m; on the finer check level Q3: 1192.98 kN, -2.0996 kN·m" (Δr = 0.03 mm, tilt 2′), read from the
    committed 3D dataset; the finer level within the point's stated errors."""
    arcmin = np.pi / (180 * 60)
    p = next(q for q in read_dataset(DATASET_3D).points
             if abs(q["penetration_m"] - 0.03e-3) < 1e-12 and abs(q["tilt_rad"] - 2 * arcmin) < 1e-12)
    line = (f"Committed value of this point (`fem3d-reference.json`, levels Q0, Q1, Q2): {p['force_n'] / 1e3:.2f} kN, "
            f"{p['moment_nm'] / 1e3:.4f} kN·m; on the finer check level Q3: {p['force_finer_n'] / 1e3:.2f} kN, "
            f"{p['moment_finer_nm'] / 1e3:.4f} kN·m.")
    assert line in _md("fem3d-perf.md")
    assert abs(p["force_finer_n"] / p["force_n"] - 1) <= p["force_error_rel"]
    assert abs(p["moment_finer_nm"] / p["moment_nm"] - 1) <= p["moment_error_rel"]


def test_table1_ring_file_reproduces_a_committed_2d_point():
    """bearing-table1-reproduction.md: "| 2D force, scene clamped | 12 | 0.00e+00 | 4.53e-04 | 0 |": the bundled
    Table 1 ring file (fem_reference/ring_scenes/clamped.toml) read as ``ringcontact bearing`` reads it, one of its
    points solved on the reference levels, equals the committed `clamped` point (the full job over every 2D and
    3D point is tests/reports/test_bearing_job.py::test_table1_through_the_job_reproduces_the_committed_data,
    slow)."""
    from fem_reference.plane.sweep import Levels, reference_point
    from fem_reference.ring_scene import load

    old = next(p for p in read_dataset(DATASET_2D).points
               if p["scene"] == "clamped" and abs(p["penetration_m"] - 1e-5) < 1e-12)
    new = reference_point(Levels(load("clamped").scene), 1e-5)
    assert abs(new["force_n"] / old["force_n"] - 1) <= 1e-12
    assert "| 2D force, scene clamped | 12 | 0.00e+00 |" in _md("bearing-table1-reproduction.md")


def test_steel_in_aluminium_law_refits_from_its_committed_fem():
    """bearing-steel-in-aluminium/accuracy-steel-in-aluminium.md: the law of the second ring pair
    refitted from its committed 2D and 3D FEM datasets (reports.bearing.pipeline.calibrate, the job's own stage) is
    the committed law file: steel-in-aluminium-3d-foundation-spline, 6 knots over 0.004-0.04 mm, chosen by issue 37's
    target (foundation, one parameter, missed it: 0.997 % held out); checks holdout_max_rel_2d 0.062 %,
    fem2d_error_max_rel 0.074 %, holdout_max_rel_3d_zero_tilt 0.130 %, tilted 0.398 %, fem3d_error_max_rel 0.076 %;
    no warning (verified). Numbers from the folder's refit (reports.bearing.pipeline.refit) on these datasets with the
    spline's slope rule chosen by leave-one-out (the not-a-knot slopes here; 0.146 % and 0.395 % with PCHIP's)."""
    from contact.calibrate import CalibratedLaw
    from fem_reference.ring_scene import load
    from reports.bearing.pipeline import calibrate

    folder = PUBLISHED / "bearing-steel-in-aluminium"
    fit = calibrate(load("steel-in-aluminium"), folder / "fem2d-steel-in-aluminium.json",
                    folder / "fem3d-steel-in-aluminium.json")
    assert fit["warnings"] == []
    checks = "; ".join(f"{k} {100 * v:.3f} %" for k, v in fit["checks"].items())
    report = (folder / "accuracy-steel-in-aluminium.md").read_text(encoding="utf-8")
    assert f"- Checks: {checks}." in report and "- **verified**" in report
    law = fit["chosen"]
    assert (law.name, law.family) == ("steel-in-aluminium-3d-foundation-spline", "foundation-spline")
    assert law.fit["selection_reason"].startswith("foundation-spline met the target") and \
        "foundation (0.997 %)" in law.fit["selection_reason"]
    assert f"`{law.name}` ({law.family}), {law.parameters['knot_count']:.0f} knots from 0.004 to 0.04 mm" in report
    committed = CalibratedLaw.from_json((folder / "steel-in-aluminium-law.json").read_text(encoding="utf-8"))
    assert committed.parameters.keys() == law.parameters.keys()
    assert all(abs(committed.parameters[k] - v) <= 1e-10 * max(abs(v), 1.0) for k, v in law.parameters.items())


def test_paper_implied_loads_and_the_clamped_rings_stiffness_ratio():
    """fem2d-paper-setup.md: the paper's implied FEM loads (Pereira's force over 1 − its Table 2 percentage) have
    "shape F(0.05)/F(0.01) (paper: 6.77; the closed-form conformal law: 5.70)", and kinematically driven Table 1
    rings (the committed `clamped` and `clamped-stress` scenes) "are 4–10× too stiff" at all five points; "0 of
    20" readings of the stated geometry come within 5 % at all five points (its CSV)."""
    implied = laws.pereira_force(TABLE2_PEN_M, **TABLE1).force_N / (1 - PEREIRA_PCT / 100)
    conformal = laws.conformal_force(TABLE2_PEN_M, **TABLE1).force_N
    md = _md("fem2d-paper-setup.md")
    assert f"(paper: {implied[4] / implied[0]:.2f}; the closed-form conformal law: {conformal[4] / conformal[0]:.2f})" in md
    ds = read_dataset(DATASET_2D)
    for scene in ("clamped", "clamped-stress"):
        fem = {round(p["penetration_m"], 12): p["force_n"] for p in ds.select(scene=scene)}
        ratio = np.array([fem[round(x, 12)] for x in TABLE2_PEN_M]) / implied
        assert np.all((4 < ratio) & (ratio < 10)), (scene, ratio)
    assert "Kinematically driven rings (rigid inner surface, support clamped) are 4–10× too stiff" in md
    with open(PUBLISHED / "fem2d-paper-setup.csv", newline="", encoding="utf-8") as fh:
        stated = [r for r in csv.DictReader(fh) if r["family"] == "Table 1 rings"]
    within = [r for r in stated if float(r["max_abs_dev"]) <= 0.05]
    assert f"{len(within)} of {len(stated)} come within 5 % of the paper at all five points" in md
