"""The law follows the rotor (issue 38, must show 2): ``ringcontact bearing FILE --range-from RUN`` widens the
ring-pair file's range to what a rotor run visited in contact, and the new law's validity covers that run.

Lean tier (seconds): the small 2D-only ring of tests/reports/test_bearing_job.py; the "run" is the validity record
(rotor/model/law_validity.py) of a seeded random sample of edge penetrations reaching below and above its law's
fitted range, written as ``simulate --out`` writes it. The widening itself is checked without FEM on seeded random
visited ranges; the parts no family holds on the same ring with the bound lowered below its fit. The issue's own
case (the Friswell rotor on the steel-in-aluminium law, a real rerun) is the slow test at the end.
"""
from __future__ import annotations

import dataclasses
import json
import math
import re
import shutil
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from contact.calibrate import CalibratedLaw
from contact.units import ARCMIN, MM
from fem_reference import ring_scene
from reports import cli
from reports.bearing.range_from import MARGIN, Visited, _round, widened
from rotor.model.law_validity import record
from rotor.model.loose_support_scene import with_law
from rotor.model.scene import load_scene
from tests.reports.test_bearing_job import SMALL
from tests.seeds import commit_seed

ROOT = Path(__file__).resolve().parents[2]


def _loose(law: CalibratedLaw):
    """A loose support whose law is ``law`` (the record reads only the law and its names)."""
    ls = with_law(load_scene("paper-table4"), "calibrated:clamped-foundation").loose_support
    return dataclasses.replace(ls, calibrated=law)


def _bearing(capsys, *argv) -> tuple[int, str, str]:
    code = cli.main(["bearing", *[str(a) for a in argv]])
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.fixture(scope="module")
def first(tmp_path_factory):
    d = tmp_path_factory.mktemp("follow")
    (d / "small.toml").write_text(SMALL)
    assert cli.main(["bearing", str(d / "small.toml"), "--out", str(d / "out"), "--workers", "1", "--json"]) == 0
    return d, CalibratedLaw.from_json((d / "out" / "small-ring-law.json").read_text())


def test_a_run_beyond_its_law_gives_a_law_that_covers_it(first, capsys):
    d, law = first
    seed = commit_seed()
    print(f"seed {seed}")
    rng = np.random.default_rng(seed)
    lo, hi = law.validity_penetration_m
    pen = np.exp(rng.uniform(math.log(lo / rng.uniform(1.2, 1.8)), math.log(hi * rng.uniform(1.1, 1.5)), 400))
    pen[rng.integers(0, pen.size, 100)] = -1e-6                         # a quarter of the time out of contact
    rec = record(_loose(law), pen, np.zeros(pen.size))
    assert rec["contact_time_share_below"] > 0 and rec["contact_time_share_above"] > 0
    run = d / "run"
    run.mkdir()
    (run / "simulate-summary.json").write_text(json.dumps({"law_validity": rec}))
    code, out, err = _bearing(capsys, d / "small.toml", "--out", d / "out", "--workers", 1, "--range-from", run)
    assert code == 0, err
    assert "range from" in out and "0.004-0.02 ->" in out
    new = CalibratedLaw.from_json((d / "out" / "small-ring-law.json").read_text())
    again = record(_loose(new), pen, np.zeros(pen.size))
    assert again["contact_time_share_inside"] == 1.0 and not again["warnings"], again["warnings"]
    assert new.provenance["warnings"] == []                             # still verified on the wider range
    s = json.loads((d / "out" / "summary.json").read_text())
    assert s["range_from"]["source"] == str(run / "simulate-summary.json") and s["not_held"] == []
    assert new.provenance["range_from"]["visited_penetration_mm"] == pytest.approx(
        [v / MM for v in rec["visited_penetration_range_m"]], rel=1e-12)
    # the old points are kept (read back from the store), the new ones lie outside the old range
    pts = ring_scene.loads((d / "small.toml").read_text()).penetrations_2d_m
    fitted = new.fit["penetration_m"]
    assert set(pts) <= set(fitted) and min(fitted) < lo and max(fitted) > hi
    assert "## Range from a rotor run" in (d / "out" / "accuracy-small-ring.md").read_text()
    # the API takes the run's result (its law_validity) for the same widening
    import ringcontact as rc
    res = rc.bearing(d / "small.toml", d / "out", range_from=SimpleNamespace(law_validity=rec), log=lambda _: None)
    assert res.validity_penetration_m == new.validity_penetration_m
    assert res.summary["range_from"]["penetration_mm"] == s["range_from"]["penetration_mm"]


def test_widening_only_moves_ends_outward_and_says_what_it_cannot_reach():
    """Seeded random visited ranges on the bundled steel-in-aluminium file (tilt to 2'): the new range holds the
    old one and the visited one with its margin, except where a stated limit stops it (the FEM's smallest resolved
    penetration, the small-strain largest, the small-rotation tilt), each such stop a ``not_reached`` sentence. The
    wanted ends are rounded outward to two significant digits before the limits are applied (the module's rule):
    seed 707 drew a low end 0.000329 mm with the margin, rounded to 0.00032, below the smallest resolved 0.000328
    (stated rounded up, 0.00033), a stop that the unrounded end alone would not have shown."""
    rs = ring_scene.load("steel-in-aluminium")
    seed = commit_seed()
    print(f"seed {seed}")
    rng = np.random.default_rng(seed)
    ro, c = 55.0, 0.03
    least = ring_scene.smallest_penetration_mm(c, ro, tilt=True)
    for _ in range(40):
        a, b = sorted(np.exp(rng.uniform(math.log(1e-5), math.log(2.0), 2)))
        tilt = float(np.exp(rng.uniform(math.log(0.01), math.log(100.0))))
        new, note = widened(rs, Visited("run.json", "0" * 64, "law", (a * MM, b * MM), tilt * ARCMIN))
        (p_lo, p_hi), t_hi = note["penetration_mm"]["after"], note["tilt_arcmin"]["after"][1]
        assert new.penetration_range_m == pytest.approx((p_lo * MM, p_hi * MM))
        assert p_lo <= 0.004 and p_hi >= 0.04 and t_hi >= 2.0
        low_stop = _round(a / MARGIN, up=False) < least
        assert (p_lo <= a / MARGIN) or (low_stop and p_lo == _round(least, up=True))
        assert (p_hi >= b * MARGIN) or p_hi == pytest.approx(ring_scene.largest_penetration_mm(ro))
        assert (t_hi >= tilt * MARGIN) or t_hi == 60.0
        says = " ".join(note["not_reached"])
        assert ("below the smallest" in says) == low_stop
        assert ("small-strain" in says) == (b * MARGIN > ring_scene.largest_penetration_mm(ro))
        assert ("small-rotation" in says) == (tilt * MARGIN > 60.0)
        assert set(rs.penetrations_2d_m) <= set(new.penetrations_2d_m)    # the file's points kept
        assert set(rs.tilts_rad) <= set(new.tilts_rad)


def test_a_visited_range_inside_the_file_changes_nothing():
    rs = ring_scene.load("steel-in-aluminium")
    new, note = widened(rs, Visited("run.json", "0" * 64, "law", (0.01 * MM, 0.02 * MM), 1.0 * ARCMIN))
    assert new.document["range"] == rs.document["range"] and note["not_reached"] == []


def test_parts_no_family_holds_are_named(first, capsys, monkeypatch):
    """With the bound made negative (the flexible family's held-out errors fall within the FEM's own error at
    some points, so no positive bound catches every point), every point of the small ring is a part no family
    holds: one part spanning the file's points, named in the summary, report and terminal."""
    from reports.bearing import holds
    d, _ = first
    monkeypatch.setattr(holds, "LAW_ERROR_BOUND_REL", -1.0)
    code, out, err = _bearing(capsys, d / "small.toml", "--out", d / "out", "--workers", 1)   # its points kept
    assert code == 0, err
    s = json.loads((d / "out" / "summary.json").read_text())
    pts = [p / MM for p in ring_scene.loads((d / "small.toml").read_text()).penetrations_2d_m]
    assert [p["reference"] for p in s["not_held"]] == ["2d"]
    assert s["not_held"][0]["penetration_mm"] == pytest.approx([min(pts), max(pts)])
    assert s["not_held"][0]["points"] == len(pts) and s["not_held"][0]["best_family_there"]
    assert "no family holds 2d" in out
    assert "## Parts of the range no family holds" in (d / "out" / "accuracy-small-ring.md").read_text()


@pytest.mark.parametrize("make, says", [
    (lambda d: d / "missing", "does not exist"),
    (lambda d: d, "holds no simulate-summary.json"),
    (lambda d: _write(d / "x.json", "not json"), "not a readable JSON"),
    (lambda d: _write(d / "x.json", json.dumps({"scene": "a"})), "no law_validity"),
    (lambda d: _write(d / "x.json", json.dumps({"law_validity": {}})), "no loose support"),
    (lambda d: _write(d / "x.json", json.dumps({"law_validity": {"visited_penetration_range_m": None}})),
     "never touched"),
    (lambda d: _write(d / "x.json", json.dumps({"law_validity": {"visited_penetration_range_m": [2e-6, -1],
                                                                 "largest_tilt_rad": 0}})), "0 < low <= high"),
])
def test_bad_range_from_is_one_line(tmp_path, capsys, make, says):
    (tmp_path / "small.toml").write_text(SMALL)
    where = make(tmp_path / "in") if "missing" in says else make(_mkdir(tmp_path / "in"))
    code, out, err = _bearing(capsys, tmp_path / "small.toml", "--out", tmp_path / "o", "--range-from", where)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and lines[0].startswith("ringcontact bearing: error: --range-from = ")
    assert says in lines[0] and not (tmp_path / "o").exists()


def test_api_range_from_without_contact_is_refused(tmp_path):
    import ringcontact as rc
    (tmp_path / "small.toml").write_text(SMALL)
    for given, says in ((SimpleNamespace(law_validity={"visited_penetration_range_m": None}), "never touched"),
                        (3, "must be a run folder")):
        with pytest.raises(rc.InputError, match=says) as exc:
            rc.bearing(tmp_path / "small.toml", tmp_path / "o", range_from=given)
        assert str(exc.value).startswith("range_from = ") and "\n" not in str(exc.value)
    assert not (tmp_path / "o").exists()


def _mkdir(p: Path) -> Path:
    p.mkdir(parents=True, exist_ok=True)
    return p


def _write(p: Path, text: str) -> Path:
    p.write_text(text)
    return p


@pytest.mark.slow
def test_the_issues_rotor_rerun_on_the_law_of_its_own_range(tmp_path, capsys):
    """The issue's case end to end: the Friswell rotor with gravity (tests/rotor/dynamics/test_static_start.py) on the
    published steel-in-aluminium law sits below its fitted 4 um with a tilt past its checked 2' (the record says so);
    ``bearing steel-in-aluminium --range-from`` that run gives a law; the same rotor rerun on it stays inside its
    fitted penetrations and checked tilt; a law flagged on the wider range says which parts no family holds.
    Measured 2026-11-30 on the published foundation-spline law: 2.75-2.80 um and 5.18' -> range 0.0021-0.04 mm,
    0-6.5', verified, the law file tilt-corrected (the rotor runs the straight law written beside it); the rerun
    2.72-2.76 um and 5.23', all inside. About 6 min with the 3D points computed (load 4.5), 10 s when the 3D level
    cache holds them."""
    law = ROOT / "reports" / "published" / "bearing-steel-in-aluminium" / "steel-in-aluminium-law.json"
    shutil.copy(law, tmp_path / "my-law.json")
    text = (ROOT / "tests/rotor/scenes/friswell-591-loose-aluminium.toml").read_text(encoding="utf-8")
    text = text.replace('law = "conformal"', 'law = "my-law.json"') + "\n[gravity]\nacceleration_y_m_per_s2 = -9.81\n"
    for key in ("clearance_mm", "ring_width_mm", "bearing_modulus_gpa", "bearing_poisson_ratio", "support_modulus_gpa",
                "support_poisson_ratio"):
        text = re.sub(rf"^{key} = .*\n", "", text, flags=re.M)
    (tmp_path / "scene.toml").write_text(text, encoding="utf-8")
    run = ["simulate", "--scene", tmp_path / "scene.toml", "--speed-rpm", 300, "--revolutions", 2]
    assert cli.main([str(a) for a in [*run, "--out", tmp_path / "before"]]) == 0
    rec = json.loads((tmp_path / "before" / "simulate-summary.json").read_text())["law_validity"]
    assert rec["contact_time_share_below"] > 0 and rec["beyond_tilt_range"] is True
    code, out, err = _bearing(capsys, "steel-in-aluminium", "--out", tmp_path / "bear", "--range-from",
                              tmp_path / "before", "--workers", 2)
    assert code == 0, err
    s = json.loads((tmp_path / "bear" / "summary.json").read_text())
    print(json.dumps({k: s[k] for k in ("law_name", "validity_penetration_mm", "validity_tilt_max_arcmin", "warnings",
                                        "not_held", "range_from")}, indent=1))
    # with a tilt range the law file carries a tilt correction the rotor's step loops refuse: the rotor names the
    # straight law the job writes beside it (reports/bearing/pipeline.py, ROTOR_NOTE)
    shutil.copy(tmp_path / "bear" / (s["law_straight_file"] or s["law_file"]), tmp_path / "my-law.json")
    flagged = ["--allow-flagged-law"] if s["warnings"] else []
    assert cli.main([str(a) for a in [*run, "--out", tmp_path / "after", *flagged]]) == 0
    again = json.loads((tmp_path / "after" / "simulate-summary.json").read_text())["law_validity"]
    print(json.dumps({k: v for k, v in again.items() if k != "warnings"}, indent=1))
    assert again["contact_time_share_inside"] == 1.0 and again["beyond_tilt_range"] is False, again["warnings"]
    assert again["verdict"] == ("flagged" if s["warnings"] else "verified")
    if s["warnings"]:       # flagged: the report names the parts no family holds, or says one family misses them all
        assert s["not_held"] or any("no law family" in w for w in s["warnings"])
