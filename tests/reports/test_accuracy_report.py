"""The committed accuracy report (reports/published/accuracy-table2.*) against the committed datasets.

Each test recomputes numbers independently of ``reports.accuracy`` (straight from the dataset
file and ``contact.laws``) and compares them with what the committed report prints, so that
the report cannot drift from the data. Expected '–' pattern and paper percentages: Dai et al.
(2025) Tables 2–3.
"""
from __future__ import annotations

import csv
import json
import re
from pathlib import Path

import numpy as np
import pytest

from contact import calibrate as cal
from contact import laws
from contact.package_data import entries
from reports import accuracy
from reports.digits import DIGITS, PCT_DECIMALS

#: what the published CSV holds (reports/digits.py): values to DIGITS significant digits, percentages to
#: PCT_DECIMALS decimals; a cell equals the recomputed value to half a unit in its last written digit
CSV_REL = 0.5 * 10.0 ** (1 - DIGITS)
PCT_ABS = 0.5 * 10.0 ** -PCT_DECIMALS

PUBLISHED = Path(__file__).resolve().parents[2] / "reports" / "published"
TABLE1 = dict(clearance_m=0.05e-3, width_m=30e-3, bearing_E_Pa=204e9, bearing_nu=0.3, support_E_Pa=204e9, support_nu=0.3)


@pytest.fixture(scope="module")
def raw_points():
    return json.loads(cal.DATASET_2D.read_text())["points"]


@pytest.fixture(scope="module")
def csv_rows():
    with open(PUBLISHED / "accuracy-table2.csv", newline="") as fh:
        return list(csv.DictReader(fh))


def _fem(raw_points, scene, pen_mm):
    hit = [p for p in raw_points if p["scene"] == scene and abs(p["penetration_m"] - pen_mm * 1e-3) < 1e-12]
    assert len(hit) == 1
    return hit[0]["force_n"]


def _cell(csv_rows, scene, law, pen_mm):
    hit = [r for r in csv_rows if r["scene"] == scene and r["law"] == law and float(r["penetration_mm"]) == pen_mm]
    assert len(hit) == 1, (scene, law, pen_mm)
    return hit[0]


@pytest.mark.parametrize("scene,law,pen_mm,fn,modulus", [
    ("clamped", "conformal-plane-stress", 0.02, laws.conformal_force, "plane_stress"),
    ("clamped-stress", "conformal-plane-strain", 0.05, laws.conformal_force, "plane_strain"),
    ("persson-40", "johnson", 0.01, laws.johnson_force, "plane_strain"),
    ("persson-40", "pereira", 0.04, laws.pereira_force, "plane_strain"),
])
def test_committed_law_cells_recomputed_from_dataset(raw_points, csv_rows, scene, law, pen_mm, fn, modulus):
    fem = _fem(raw_points, scene, pen_mm)
    p = fn(pen_mm * 1e-3, modulus=modulus, **TABLE1).force_N
    row = _cell(csv_rows, scene, law, pen_mm)
    assert float(row["force_fem_N"]) == pytest.approx(fem, rel=CSV_REL)
    assert float(row["diff_pct"]) == pytest.approx(100 * (p - fem) / fem, abs=PCT_ABS + 2e-6)


def test_johnson_dash_pattern_as_in_paper(csv_rows):
    # Dai et al. (2025) Table 2: Johnson has values at 0.01 and 0.02 mm and '-' beyond.
    for scene in {r["scene"] for r in csv_rows}:
        cells = [_cell(csv_rows, scene, "johnson", p)["diff_pct"] for p in accuracy.PENETRATIONS_MM]
        assert [c != "" for c in cells] == [True, True, False, False, False]


def test_committed_held_out_cells_and_must_show_lines(raw_points, csv_rows):
    # Held-out (leave-one-out) errors recomputed by refitting the foundation law by hand:
    # log k_f = mean(log F − log(R l e (ε − sin ε cos ε))) over the other points.
    md = (PUBLISHED / "accuracy-table2.md").read_text()
    pts = sorted((p for p in raw_points if p["scene"] == "clamped"), key=lambda p: p["penetration_m"])
    pen = np.array([p["penetration_m"] for p in pts])
    F = np.array([p["force_n"] for p in pts])
    d0, R, l = 5e-5, 0.1, 0.03
    e = d0 + pen
    eps = np.arccos(d0 / e)
    shape = R * l * e * (eps - np.sin(eps) * np.cos(eps))
    for pen_mm, paper in zip(accuracy.PENETRATIONS_MM, (12.01, 0.79, 4.37, 5.59, 5.69)):
        i = int(np.argmin(np.abs(pen - pen_mm * 1e-3)))
        keep = np.arange(pen.size) != i
        k = np.exp(np.mean(np.log(F[keep] / shape[keep])))
        held = 100 * (k * shape[i] / F[i] - 1)
        assert float(_cell(csv_rows, "clamped", "calibrated-holdout", pen_mm)["diff_pct"]) == pytest.approx(held, abs=PCT_ABS + 1e-5)
        assert f"{pen_mm:g} mm: {abs(held):.3f} % < {paper:.2f} %" in md
    assert re.search(r"Overall: \*\*met\*\* for the 2D", md)


def test_committed_report_is_what_the_builder_writes_now(tmp_path):
    # The whole Markdown and CSV regenerate byte-identically from the committed data.
    accuracy.build(tmp_path)
    has3d = bool(entries(accuracy.DATA_3D_DIR, ".json"))
    for name in ("accuracy-table2.md", "accuracy-table2.csv") + (("accuracy-table3.csv",) if has3d else ()):
        assert (tmp_path / name).read_text() == (PUBLISHED / name).read_text(), f"{name} is stale: run `ringcontact report`"
    text = (tmp_path / "accuracy-table2.md").read_text()
    assert ("No 3D reference dataset is committed" in text) == (not has3d)


def _winkler_slices(k, pen, th, d0=5e-5, R=0.1, l=0.03):
    """Independent slice integral of a Winkler bed (Johnson 1985 §4.3) with scipy.quad: (load, M_z)."""
    from scipy.integrate import quad

    def h(d):
        if d <= 0:
            return 0.0
        e = d0 + d
        eps = np.arccos(d0 / e)
        return k * R * e * (eps - np.sin(eps) * np.cos(eps))

    brk = [-pen / th] if th and -l / 2 < -pen / th < l / 2 else None
    F = quad(lambda x: h(pen + th * x), -l / 2, l / 2, points=brk, epsabs=0, epsrel=1e-11)[0]
    M = quad(lambda x: -x * h(pen + th * x), -l / 2, l / 2, points=brk, epsabs=1e-6, epsrel=1e-11)[0]
    return F, M


def test_table3_on_a_synthetic_3d_winkler_dataset(tmp_path, monkeypatch):
    # A 3D dataset whose "FEM" is an exact Winkler bed: the zero-tilt calibration must recover k_f and
    # the slice-integrated tilted prediction must reproduce every tilted point (force and moment).
    from contact.dataset import write_dataset
    from contact.units import ARCMIN

    k = 1.25e13
    geom = {"bearing_inner_radius_m": 0.09, "bearing_outer_radius_m": 0.1, "clearance_m": 5e-5,
            "support_thickness_m": 0.01, "width_m": 0.03, "young_bearing_pa": 204e9, "young_support_pa": 204e9,
            "poisson_bearing": 0.3, "poisson_support": 0.3}
    pts = []
    for t in (0.0, 0.5, 1.0, 2.0):
        for pm in (0.005, 0.01, 0.02, 0.03, 0.04, 0.05):
            F, M = _winkler_slices(k, pm * 1e-3, t * ARCMIN)
            pts.append({"scene": "clamped", "penetration_m": pm * 1e-3, "tilt_rad": t * ARCMIN, "force_n": F,
                        "force_error_rel": 1e-4, "moment_nm": M, "width_m": 0.03})
    d3 = tmp_path / "3d"
    write_dataset(d3 / "fem3d-reference.json",
                  {"title": "synthetic", "created_utc": "x", "code_revision": "x", "package_versions": {}, "geometry": geom},
                  {"scene": "-", "penetration_m": "m", "tilt_rad": "rad", "force_n": "N", "force_error_rel": "-",
                   "moment_nm": "N*m", "width_m": "m"}, pts)
    monkeypatch.setattr(accuracy, "DATA_3D_DIR", d3)
    t3 = accuracy.table3()
    assert t3["have_data"] and t3["ok"] is True
    (law,) = t3["laws"]
    assert law.name == "clamped-3d-foundation"
    assert law.parameters["foundation_modulus_Pa_per_m"] == pytest.approx(k, rel=1e-9)
    assert len(t3["rows"]) == 18
    for r in t3["rows"]:
        assert abs(r["calibrated-slices_pct"]) < 1e-6
        assert abs(r["calibrated-kernel_pct"]) < 1e-6          # the rotor's compiled path integrates slices too
        assert r["calibrated-edge_pct"] > 1.0                  # the paper's edge model over-predicts a Winkler bed
        assert r["calibrated-slices_moment_pct"] == pytest.approx(0.0, abs=1e-5)
    assert "**met**" in "\n".join(t3["lines"])
    text = accuracy.table3_csv(t3["rows"])
    assert text.count("\n") == 19


DATA3D = cal.DATA_3D_DIR / "fem3d-reference.json"
needs_3d = pytest.mark.skipif(not DATA3D.is_file(), reason="no committed 3D dataset")


@needs_3d
@pytest.mark.parametrize("tilt_arcmin,pen_mm", [(2.0, 0.03), (0.5, 0.01), (1.0, 0.05)])
def test_committed_table3_cells_recomputed_from_the_3d_dataset(tilt_arcmin, pen_mm):
    # Independent of reports.accuracy: k_f from the 3D zero-tilt points in closed form (mean log ratio),
    # the tilted load by scipy quadrature of the Winkler slices; the paper's model (Dai et al. 2025
    # Eqs. 8-19, full-width patch) as l0 · p_conformal(Δr + θ l0/2).
    from contact.units import ARCMIN

    pts = json.loads(DATA3D.read_text())["points"]
    zero = [p for p in pts if p["tilt_rad"] == 0.0 and p["penetration_m"] > 0]
    d0, R, l = 5e-5, 0.1, 0.03
    pen0 = np.array([p["penetration_m"] for p in zero])
    e = d0 + pen0
    eps = np.arccos(d0 / e)
    k = np.exp(np.mean(np.log(np.array([p["force_n"] for p in zero]) / (R * l * e * (eps - np.sin(eps) * np.cos(eps))))))
    th = tilt_arcmin * ARCMIN
    (p,) = [q for q in pts if abs(q["tilt_rad"] - th) < 1e-12 and abs(q["penetration_m"] - pen_mm * 1e-3) < 1e-12]
    F_slices, _ = _winkler_slices(k, pen_mm * 1e-3, th)
    with open(PUBLISHED / "accuracy-table3.csv", newline="") as fh:
        (row,) = [r for r in csv.DictReader(fh) if abs(float(r["tilt_arcmin"]) - tilt_arcmin) < 1e-9
                  and abs(float(r["penetration_mm"]) - pen_mm) < 1e-9]
    assert float(row["force_fem_N"]) == pytest.approx(p["force_n"], rel=CSV_REL)
    assert float(row["calibrated-slices_pct"]) == pytest.approx(100 * (F_slices / p["force_n"] - 1), abs=1e-4)
    p_edge = laws.conformal_force(pen_mm * 1e-3 + th * l / 2, modulus="plane_stress", **TABLE1).force_N
    assert float(row["conformal-paper_pct"]) == pytest.approx(100 * (p_edge / p["force_n"] - 1), abs=1e-4)


@needs_3d
def test_3d_foundation_modulus_between_plane_stress_and_plane_strain():
    # A 30 mm ring with free end faces is stiffer than plane stress and softer than plane strain:
    # its Winkler modulus must lie between E/(1−ν²)/h and E(1−ν)/((1+ν)(1−2ν))/h, h = 20 mm.
    law = cal.load_calibrated("clamped-3d-foundation")
    k = law.parameters["foundation_modulus_Pa_per_m"]
    assert 204e9 / (1 - 0.09) / 0.02 < k < 204e9 * 0.7 / (1.3 * 0.4) / 0.02
