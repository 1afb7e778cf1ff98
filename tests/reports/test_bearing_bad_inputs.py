"""``ringcontact bearing``: the bad inputs of issue 40, refused in one line (exit 2) before anything is computed,
and the range up to the documented largest penetration (2 % of R) calibrated to a law without a NaN.

In-process: the parser and the budget refuse before the pipeline starts; the NaN case is the calibration of a
synthetic dataset (forces of the foundation law) beyond the conformal law's neat-fit limit.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from contact.calibrate.families import SceneGeometry, family_force
from contact.calibrate.fit import calibrate_scene
from contact.dataset import ReferenceDataset
from contact.laws import conformal_neat_fit_limit_m
from fem_reference.ring_scene import RING_SCENE_DIR
from reports import cli

BASE = (RING_SCENE_DIR / "steel-in-aluminium.toml").read_text()


def _file(tmp_path, **repl):
    text = BASE
    for key, value in repl.items():
        lines = [ln for ln in text.splitlines() if ln.startswith(f"{key} = ")]
        text = text.replace(lines[0], f"{key} = {value}", 1)
    path = tmp_path / "ring.toml"
    path.write_text(text)
    return str(path)


def _refused(capsys, tmp_path, *argv):
    rc = cli.main(["bearing", *argv])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and err[0].startswith("ringcontact bearing: error: "), (rc, err)
    assert "internal error" not in err[0] and not (tmp_path / "o").exists(), err
    return err[0]


@pytest.mark.parametrize("name", ['"ring\\n"', '"ring\\r"', '"ring\\t"', '"ring/x"', '"../ring"', '""'])
def test_a_name_that_cannot_name_files_is_refused(tmp_path, capsys, name):
    err = _refused(capsys, tmp_path, _file(tmp_path, name=name), "--out", str(tmp_path / "o"))
    assert "name = " in err and "it names files" in err


@pytest.mark.parametrize("out", ["", " ", "\t"])
def test_an_empty_out_is_refused_not_the_default_folder(tmp_path, capsys, monkeypatch, out):
    monkeypatch.chdir(tmp_path)
    err = _refused(capsys, tmp_path, "steel-in-aluminium", "--out", out)
    assert "--out = " in err and "must name a directory" in err
    assert not (tmp_path / "bearing-steel-in-aluminium").exists()


@pytest.mark.parametrize("radii", [(8000.0, 9000.0, 9500.0), (1000.0, 3000.0, 3500.0)])
def test_a_huge_ring_is_refused_by_the_budget_before_meshing(tmp_path, capsys, radii):
    inner, outer, housing = radii
    path = _file(tmp_path, inner_radius_mm=inner, tilt_arcmin="[0, 0]")
    text = open(path).read().replace("outer_radius_mm = 55.0", f"outer_radius_mm = {outer}").replace(
        "outer_radius_mm = 75.0", f"outer_radius_mm = {housing}")
    open(path, "w").write(text)
    err = _refused(capsys, tmp_path, path, "--out", str(tmp_path / "o"))
    assert f"bore radius {outer + 0.03:g} mm" in err and "beyond the budget of 30 min and 2 GiB" in err
    assert "--accept-long" in err and "DOFs" in err


def test_the_budget_counts_the_3d_points(tmp_path, capsys):
    """1 640 3D points (40 penetrations x 40 tilts and the zero tilt) at 3.7 s each: over half an hour on 2 workers."""
    pts = ", ".join(f"{v:.6g}" for v in np.linspace(0.004, 0.04, 40))
    tilts = ", ".join(f"{v:.6g}" for v in np.linspace(0.05, 2, 40))
    path = _file(tmp_path, penetration_mm=f"[0.004, 0.04]\npenetration_points_3d_mm = [{pts}]\n"
                 f"tilt_points_arcmin = [{tilts}]")
    err = _refused(capsys, tmp_path, path, "--out", str(tmp_path / "o"))
    assert "1640 3D points" in err and "beyond the budget" in err, err


def _dataset(pen_m, geo: SceneGeometry, scene="big") -> ReferenceDataset:
    force = family_force("foundation", {"foundation_modulus_Pa_per_m": 3.9e12}, np.asarray(pen_m), geo)
    rings = {"inner_radius_m": geo.radius_m - geo.bearing_thickness_m, "outer_radius_m": geo.radius_m,
             "clearance_m": geo.clearance_m, "width_m": geo.width_m,
             "support_outer_radius_m": geo.radius_m + geo.clearance_m + geo.support_thickness_m,
             "bearing": {"youngs_modulus_pa": geo.bearing_E_Pa, "poisson_ratio": geo.bearing_nu},
             "support": {"youngs_modulus_pa": geo.support_E_Pa, "poisson_ratio": geo.support_nu}}
    pts = tuple({"scene": scene, "penetration_m": float(p), "force_n": float(f), "force_error_rel": 1e-4,
                 "tilt_rad": 0.0} for p, f in zip(pen_m, force))
    return ReferenceDataset({"scenes": {scene: {"rings": rings, "plane": geo.plane}}}, {}, pts)


def test_a_range_to_2_percent_of_r_calibrates_without_a_nan():
    """steel-in-aluminium's rings, penetrations 0.004-1.1 mm (1.1 mm = 2 % of R = 55 mm): the conformal law has
    no value beyond about 10 clearances (0.3 mm), so its family is left out instead of chosen with a NaN."""
    geo = SceneGeometry(clearance_m=3e-5, width_m=0.022, radius_m=0.055, bearing_thickness_m=0.007,
                        support_thickness_m=0.01997, bearing_E_Pa=208e9, bearing_nu=0.29, support_E_Pa=72e9,
                        support_nu=0.33, plane="stress")
    pen = np.geomspace(4e-6, 1.1e-3, 10)
    assert pen[-1] > conformal_neat_fit_limit_m(geo.clearance_m) > pen[0]
    law, fits = calibrate_scene(_dataset(pen, geo), "big")
    assert law.family == "foundation" and law.fit["families_without_a_value"] == ["conformal-scaled"]
    assert all(math.isfinite(v) for v in law.parameters.values())
    assert law.parameters["foundation_modulus_Pa_per_m"] == pytest.approx(3.9e12, rel=1e-9)
    assert "conformal-scaled" not in [f.family for f in fits]
    law.to_json()                          # allow_nan=False: raised "Out of range float values" before
