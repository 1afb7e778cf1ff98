"""``ringcontact bearing`` with a tilt range fits the tilt correction on its training grid and checks it held out
(reports/bearing/tilt.py): the grids, the fit and its verdict on committed data (the steel-in-aluminium run folder and
its grids in reports/published/law-tilt-correction/), the whole job with its FEM stages replaced by those committed
datasets, a correction that misses a held-out point flagged, the rotor's one-line refusal of the corrected law, and
the job on a fresh ring solving its own grids (``slow``)."""
from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from contact.calibrate import CalibratedLaw
from contact.dataset import read_dataset, write_dataset
from contact.units import ARCMIN
from fem_reference import ring_scene
from reports.bearing import pipeline, tilt

ROOT = Path(__file__).resolve().parents[2]
PUB = ROOT / "reports" / "published"
RUN = PUB / "bearing-steel-in-aluminium"
GRIDS = {"train": PUB / "law-tilt-correction" / "fem3d-tilt-train-steel-in-aluminium.json",
         "verify": PUB / "law-tilt-correction" / "fem3d-tilt-verify-steel-in-aluminium.json"}


def _keys(points) -> set:
    return {(round(p["penetration_m"] * 1e12), round(p["tilt_rad"] * 1e12)) for p in points}


def test_grids_span_the_range_and_the_verification_points_are_not_training_points():
    """Training: the range's ends and zero tilt to its largest tilt; verification: penetrations strictly between the
    training ones and tilts that are not training tilts (zero tilt apart). On the 20 mm ring the training grid is
    the one the correction's form was chosen on (reports/published/law-tilt-correction/)."""
    rs = ring_scene.load(str(PUB / "law-family-newcomer-20mm" / "newcomer-20mm.toml"))
    g = tilt.grids(rs)
    (tt, tp), (vt, vp) = g["train"], g["verify"]
    assert (tp[0], tp[-1]) == rs.penetration_range_m and (tt[0], tt[-1]) == (0.0, rs.tilt_range_rad[1])
    assert all(a < b < c for a, b, c in zip(tp, vp, tp[1:]))
    assert set(vt) & set(tt) == {0.0}
    committed = read_dataset(PUB / "law-tilt-correction" / "fem3d-tilt-train-newcomer-20mm.json").points
    assert _keys({"penetration_m": p, "tilt_rad": t} for t in tt for p in tp) == _keys(committed)
    assert tilt.grid_points(rs) == len(tt) * len(tp) + len(vt) * len(vp)


@pytest.fixture(scope="module")
def fitted():
    rs = ring_scene.load("steel-in-aluminium")
    return rs, pipeline.calibrate(rs, RUN / "fem2d-steel-in-aluminium.json", RUN / "fem3d-steel-in-aluminium.json",
                                  GRIDS)


def test_the_correction_is_fitted_on_the_training_grid_and_holds_held_out(fitted):
    """The chosen law carries the correction fitted on the training grid's tilted points alone; held out (the
    verification grid and the reference points that are not training points) it meets issue 37's target, force and
    moment, where the straight law's slices miss the moment at every tilted point."""
    rs, fit = fitted
    tc = fit["tilt"]
    law = fit["chosen"]
    assert tc["chosen"] and law is tc["law"] and fit["straight"]["chosen"] is fit["law3"]
    assert any(k.startswith("tilt_force_") for k in law.parameters)
    train = read_dataset(GRIDS["train"]).points
    n_tilted = sum(1 for p in train if p["tilt_rad"] > 0 and p["penetration_m"] > 0)
    assert law.fit["tilt_correction"]["points"] == n_tilted
    # held out means never fitted: no verification or reference point counted is a training point
    committed = read_dataset(RUN / "fem3d-steel-in-aluminium.json").points
    held = [p for p in committed if (round(p["penetration_m"] * 1e12), round(p["tilt_rad"] * 1e12)) not in _keys(train)]
    sets = tc["record"]["sets"]
    assert sets["3D reference points"]["moment, tilted"]["corrected"]["points"] == sum(1 for p in held if p["tilt_rad"] > 0)
    assert tc["record"]["reference_points_left_out_as_training"] == len(committed) - len(held)
    for s in sets.values():
        for q, both in s.items():
            assert both["corrected"]["within"] == both["corrected"]["points"], (q, both)
        assert s["moment, tilted"]["straight"]["within"] == 0      # the slices' moment, never within
    assert tc["holds"] and not [w for w in fit["warnings"] if w.startswith("tilt correction")]
    # the corrected law's accuracy rows: every held-out set, force and moment
    refs = {(a["reference"], a["quantity"]): a for a in fit["accuracy"]}
    for key in (("3d tilted (rotor kernel)", "moment"), ("3d verification grid, tilted", "moment"),
                ("3d verification grid, tilted", "force"), ("3d verification grid, zero tilt", "force")):
        assert refs[key]["holds"] and refs[key]["points"] > 0


def test_a_correction_that_misses_a_held_out_point_is_flagged(fitted, tmp_path):
    """The verification grid with one tilted point's FEM moment raised by 3 %: the corrected law is still chosen (on
    the training grid, as before), but that point misses the target, so the law is flagged and the point named."""
    rs, _ = fitted
    ds = read_dataset(GRIDS["verify"])
    pts = [dict(p) for p in ds.points]
    i = next(k for k, p in enumerate(pts) if p["tilt_rad"] > 0 and p["penetration_m"] > 0)
    pts[i]["moment_nm"] *= 1.03
    bad = write_dataset(tmp_path / "verify.json", dict(ds.metadata), dict(ds.columns), pts)
    fit = pipeline.calibrate(rs, RUN / "fem2d-steel-in-aluminium.json", RUN / "fem3d-steel-in-aluminium.json",
                             {"train": GRIDS["train"], "verify": bad})
    assert fit["tilt"]["chosen"] and not fit["tilt"]["holds"]
    # the choice is the training grid's: the same words before the held-out counts, whatever the verification says
    assert fit["tilt"]["reason"].split("; held out")[0] == fitted[1]["tilt"]["reason"].split("; held out")[0]
    [w] = [w for w in fit["warnings"] if w.startswith("tilt correction")]
    where = f"{pts[i]['penetration_m'] * 1e6:.4g} µm, {pts[i]['tilt_rad'] / ARCMIN:g}′"
    assert "1 held-out point(s)" in w and where in w
    law = pipeline.law_file(rs, dict(fit, plane=None))
    assert law.provenance["warnings"] == fit["warnings"] and not law.provenance["tilt_correction"]["holds"]


def _copying_stages(monkeypatch):
    """The job's FEM stages replaced by copies of the committed steel-in-aluminium datasets."""
    def copy(src):
        def stage(rs, out, *a, **kw):
            return Path(shutil.copy(src, Path(out) / src.name))
        return stage
    monkeypatch.setattr(pipeline, "run_fem2d", copy(RUN / "fem2d-steel-in-aluminium.json"))
    monkeypatch.setattr(pipeline, "run_fem3d", copy(RUN / "fem3d-steel-in-aluminium.json"))
    monkeypatch.setattr(tilt, "run_grids", lambda rs, out, path3, **kw: {
        k: Path(shutil.copy(v, Path(out) / tilt.grid_files(rs.name)[k])) for k, v in GRIDS.items()})


def test_job_with_tilt_writes_the_corrected_law_its_verdict_and_the_straight_law(tmp_path, monkeypatch, capsys):
    """The command line end to end on the committed data: the law file is the corrected law with its held-out
    verdict, the straight law is written beside it for the rotor, the summary and the report say how many points
    hold and why the correction was chosen."""
    from reports.cli.bearing import main

    _copying_stages(monkeypatch)
    out = tmp_path / "out"
    assert main(["steel-in-aluminium", "--out", str(out), "--no-plane-check", "--workers", "1"]) == 0
    printed = capsys.readouterr().out
    assert "steel-in-aluminium-law-straight.json" in printed
    law = CalibratedLaw.from_json((out / "steel-in-aluminium-law.json").read_text())
    straight = CalibratedLaw.from_json((out / "steel-in-aluminium-law-straight.json").read_text())
    assert law.name.endswith("-tilt") and not any(k.startswith("tilt_") for k in straight.parameters)
    assert not law.provenance["rotor_kernel"] and straight.provenance["rotor_kernel"]
    rec = law.provenance["tilt_correction"]
    assert rec["chosen"] and rec["holds"] and rec["files"] == tilt.grid_files("steel-in-aluminium")
    summary = json.loads((out / "summary.json").read_text())
    got = summary["tilt_correction"]
    assert (got["chosen"], got["holds"], got["reason"], summary["warnings"]) == (True, True, rec["reason"], [])
    assert {(s, q, w): got["sets"][s][q][w]["within"] for s in got["sets"] for q in got["sets"][s]
            for w in ("corrected", "straight")} == {(s, q, w): rec["sets"][s][q][w]["within"] for s in rec["sets"]
                                                   for q in rec["sets"][s] for w in ("corrected", "straight")}
    assert {"fem3d-tilt-train-steel-in-aluminium.json", "steel-in-aluminium-law-straight.json"} <= set(summary["files"])
    md = (out / "accuracy-steel-in-aluminium.md").read_text()
    assert "## Tilt correction" in md and f"Why: {rec['reason']}." in md
    n = sum(rec["sets"][s]["moment, tilted"]["corrected"]["points"] for s in rec["sets"])
    assert f"moment at {n}/{n} with the correction" in rec["reason"]


def test_the_rotor_refuses_the_corrected_law_in_one_line_and_takes_the_straight_one(tmp_path, monkeypatch, capsys):
    """A rotor scene naming the corrected law: one line, exit 2 (the step loops evaluate no correction yet); the
    straight law beside it is the one a scene names: that scene loads."""
    from reports.cli.bearing import main
    from reports.cli.simulate import main as simulate

    _copying_stages(monkeypatch)
    out = tmp_path / "out"
    assert main(["steel-in-aluminium", "--out", str(out), "--no-plane-check", "--workers", "1", "--json"]) == 0
    capsys.readouterr()
    scene = (ROOT / "rotor" / "scenes" / "table4-steel-in-aluminium.toml").read_text()
    for which in ("law", "law-straight"):
        text = scene.replace('law = "laws/steel-in-aluminium-law.json"',
                             f'law = "{(out / f"steel-in-aluminium-{which}.json").as_posix()}"')
        assert text != scene
        (tmp_path / f"{which}.toml").write_text(text)
    rc = simulate(["--scene", str(tmp_path / "law.toml"), "--speed-rpm", "6000", "--revolutions", "2",
                   "--out", str(tmp_path / "s")])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1 and "tilt correction" in err
    from rotor.model.scene import load_scene
    assert load_scene(str(tmp_path / "law-straight.toml")).loose_support.calibrated.name == \
        CalibratedLaw.from_json((out / "steel-in-aluminium-law-straight.json").read_text()).name


@pytest.mark.slow
def test_job_on_a_fresh_ring_solves_its_grids_and_verifies_the_correction(tmp_path, monkeypatch):
    """The job on the bundled steel-in-aluminium file with its own FEM (cache in ``tmp_path``): both grids solved
    and written, the correction fitted on the training grid and verified on the rest."""
    from reports.cli.bearing import main

    monkeypatch.setenv("RINGCONTACT_CACHE", str(tmp_path / "cache"))
    out = tmp_path / "out"
    assert main(["steel-in-aluminium", "--out", str(out), "--workers", "2", "--json"]) == 0
    rs = ring_scene.load("steel-in-aluminium")
    for which, (tilts, pens) in tilt.grids(rs).items():
        ds = read_dataset(out / tilt.grid_files(rs.name)[which])
        assert len(ds.points) == len(tilts) * len(pens)
        assert all(math.isfinite(p["force_error_rel"]) for p in ds.points)
    summary = json.loads((out / "summary.json").read_text())
    rec = summary["tilt_correction"]
    assert rec["chosen"] and rec["holds"], rec
    assert np.isfinite(summary["checks"]["tilted_holdout_max_rel_kernel"])


PERF = PUB / "perf-bearing"


def test_the_benchmark_s_tilted_run_is_recomputed_from_its_kept_datasets():
    """reports/published/perf-bearing.md's tilted run (benchmarks/bench_bearing.py keeps its FEM datasets and laws in
    reports/published/perf-bearing/): its law, and the tilt correction's held-out table, force and moment, recomputed
    from those datasets by the job's own calibrate stage."""
    summary = json.loads((PERF / "summary.json").read_text())
    rs = ring_scene.load(summary["ring_scene"])
    assert summary["ring_scene_sha256"] == rs.sha256
    grids = {k: PERF / v for k, v in tilt.grid_files(rs.name).items()}
    fit = pipeline.calibrate(rs, PERF / f"fem2d-{rs.name}.json", PERF / f"fem3d-{rs.name}.json", grids)
    law = CalibratedLaw.from_json((PERF / summary["law_file"]).read_text())
    assert fit["chosen"].name == law.name == summary["law_name"]
    for k, v in law.parameters.items():
        assert math.isclose(fit["chosen"].parameters[k], v, rel_tol=1e-9, abs_tol=1e-12), k
    # the grids are the job's: every point of both grids, none of the verification points a training point
    for which, (tilts, pens) in tilt.grids(rs).items():
        assert _keys(read_dataset(grids[which]).points) == _keys(
            {"penetration_m": p, "tilt_rad": t} for t in tilts for p in pens)
    md = (PUB / "perf-bearing.md").read_text(encoding="utf-8")
    assert (f"Law of the tilted run: `{law.name}` ({law.family}); checks: holdout_max_rel_2d "
            f"{100 * fit['checks']['holdout_max_rel_2d']:.3f} %") in md
    rec = fit["tilt"]["record"]
    for s, per in rec["sets"].items():
        for q, both in per.items():
            c, st = both["corrected"], both["straight"]
            assert (f"| {s} | {q} | {c['within']} / {c['points']} | {c['worst_error_pct']:.3f} vs "
                    f"{c['worst_bound_pct']:.3f} | {st['within']} / {st['points']} |") in md
    assert f"Why: {rec['reason']}." in md
