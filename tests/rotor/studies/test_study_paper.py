"""The paper's Section 5 findings (Dai et al. 2025) judged per speed band, on two meshes, as agreements and
disagreements with their measured numbers.

Table 4 rotor, the paper's conformal law as published, the scene's reading of Eq. 34
(rotor/scenes/paper-table4.toml; chosen in reports/published/section5-readings.md), the tilt-ignored case
without any moment between bearing and support (§5.2). Each finding is judged at one speed by
:meth:`rotor.studies.section5.Finding.judge` (the code that writes reports/published/study-findings.md and
study-findings.csv): a verdict from agrees / disagrees / no effect, the effect in the paper's sense and the
threshold of the model's numerical noise. The points are computed as ``ringcontact study cascade`` / ``params``
compute them (:func:`rotor.studies.steady_state.run_point` from rest, 256 steps per revolution, transient cap
1 500 revolutions) on the paper's mesh (one element per shaft segment, ``paper``) and the converged one (two per
segment, ``converged``; reports/published/rotor-mesh.md).

No test here is an expected failure: a disagreement is asserted as a disagreement, with the effect that
study-findings.csv publishes (to its six digits). Each test fails when the model breaks (a point cannot be
computed), when the verdict changes (a disagreement that disappears included) and when the effect moves. In the
default run: one agreement and one disagreement of the low bands and two findings at 9 000 rpm (five points);
with ``-m slow`` every verdict of every band and mesh at the first and last speed where the band has it.
"""
import csv
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from rotor.studies.section5 import finding, in_band, verdict_of
from rotor.studies.steady_state import run_point

ROOT = Path(__file__).resolve().parents[3]
OPTIONS = {"steps_per_rev": 256, "max_revs": 1500}      # as `ringcontact study` (reports/cli/study.py: _options)
MESHES = {"paper": None, "converged": 2}
TAGS = {"paper": "paper", "converged": "2/segment"}       # the mesh column of study-findings.csv
CASES = {"base": {}, "notilt": {"tilt_ignored": True}, "c0.03": {"clearance_m": 0.03e-3},
         "c0.08": {"clearance_m": 0.08e-3}, "d0.5": {"misalignment_m": 0.5e-3}, "d2": {"misalignment_m": 2e-3}}
_CACHE: dict = {}


def published() -> dict:
    """``{(mesh, finding, band, rpm): row}`` of reports/published/study-findings.csv."""
    with open(ROOT / "reports" / "published" / "study-findings.csv", newline="", encoding="utf-8") as fh:
        return {(r["mesh"], r["finding"], r["band"], float(r["speed_rpm"])): r for r in csv.DictReader(fh)}


def point(mesh: str, rpm: float, case: str):
    """``(arrays, info)`` of one point (:func:`rotor.studies.steady_state.run_point`); cached for the module."""
    key = (mesh, float(rpm), case)
    if key not in _CACHE:
        kw = {k: v for k, v in CASES[case].items()}
        _CACHE[key] = run_point("paper-table4", float(rpm), options=OPTIONS, elements_per_segment=MESHES[mesh], **kw)
    return _CACHE[key]


def amplitudes(mesh: str, rpm: float, case: str, quantity: str):
    """``(A (3 stations, 5 orders), info)`` of one point as study-findings.md reads it (a non-periodic point with
    its spectral floor, reports.studies.findings)."""
    from reports.studies.findings import _amps

    arrays, info = point(mesh, rpm, case)
    return _amps(SimpleNamespace(arrays=arrays, info=info), quantity)


def judge(name: str, mesh: str, rpm: float):
    """``(verdict, effect, threshold, periodic)`` of finding ``name`` at ``rpm`` on ``mesh``, computed now."""
    f = finding(name)
    amps = {c: amplitudes(mesh, rpm, c, f.quantity) for c in f.cases}
    v, e, t, _ = f.judge(amps)
    return v, e, t, all(a[1]["converged"] for a in amps.values())


def _assert_as_published(name, mesh, band, rpm, verdict):
    row = published()[(TAGS[mesh], name, band, float(rpm))]
    v, e, t, periodic = judge(name, mesh, float(rpm))
    assert in_band(rpm, band) and row["verdict"] == verdict, row
    assert (v, periodic) == (verdict, row["periodic"] == "1"), (name, mesh, rpm, v, e, t)
    assert e == pytest.approx(float(row["effect"]), rel=1e-4, abs=1e-9), (name, mesh, rpm)
    assert t == pytest.approx(float(row["threshold"]), rel=1e-4, abs=1e-9), (name, mesh, rpm)


#: the default run's share: (finding, mesh, band, rpm, the verdict study-findings.csv publishes there)
DEFAULT = [
    ("stuck_low", "paper", "L1", 4500, "agrees"),              # point A: both faces stuck
    ("stuck_low", "paper", "L2", 5400, "disagrees"),           # the faces slip from 5 400 rpm, in contact
    ("near_support", "paper", "H1", 9000, "agrees"),           # Fig. 12: 3X–5X larger near the loose support
    ("clearance_2x", "paper", "H1", 9000, "disagrees"),        # Fig. 18: 2X does not fall with δ0
]


@pytest.mark.parametrize("name, mesh, band, rpm, verdict", DEFAULT, ids=[f"{d[0]}-{d[1]}-{d[3]}" for d in DEFAULT])
def test_finding_as_published_at_a_few_speeds(name, mesh, band, rpm, verdict):
    """The verdict, effect and threshold study-findings.csv publishes at this speed, recomputed."""
    _assert_as_published(name, mesh, band, rpm, verdict)


def _slow_cases() -> list:
    """Every (finding, mesh, band, verdict) of study-findings.csv at the first and last speed that has it."""
    by: dict = {}
    for (tag, name, band, rpm), r in sorted(published().items(), key=lambda kv: kv[0][3]):
        mesh = next(m for m, t in TAGS.items() if t == tag)
        by.setdefault((name, mesh, band, r["verdict"]), []).append(rpm)
    out = []
    for (name, mesh, band, verdict), speeds in by.items():
        for rpm in sorted({speeds[0], speeds[-1]}):
            out.append(pytest.param(name, mesh, band, rpm, verdict, marks=pytest.mark.slow,
                                    id=f"{name}-{mesh}-{band}-{rpm:.0f}-{verdict.replace(' ', '_')}"))
    return out


@pytest.mark.parametrize("name, mesh, band, rpm, verdict", _slow_cases())
def test_finding_as_published_in_every_band(name, mesh, band, rpm, verdict):
    """Every verdict of every band, both meshes (the full set: -m slow)."""
    _assert_as_published(name, mesh, band, rpm, verdict)


def test_every_published_verdict_follows_from_its_effect_and_threshold():
    """study-findings.csv, every row: the verdict is the one its effect and threshold give
    (rotor.studies.section5.verdict_of), never outside agrees / disagrees / no effect; every threshold of a change
    between two points at least their step noise; and study-findings.md says neither "n/a" nor "partly"."""
    from rotor.studies.section5 import STEP_NOISE, VERDICTS

    rows = published()
    assert rows
    for (tag, name, band, rpm), r in rows.items():
        e, t = float(r["effect"]), float(r["threshold"])
        assert r["verdict"] in VERDICTS and verdict_of(name, e, t) == r["verdict"], r
        # a change between two points carries both points' step noise; the stuck share and the 3X–5X share of 1X
        # (low_harmonics: the ratio times its noise) have their own
        assert name in ("stuck_low", "low_harmonics") or t >= 2 * STEP_NOISE[0] * (1 - 1e-5), r
    md = (ROOT / "reports" / "published" / "study-findings.md").read_text(encoding="utf-8")
    assert "n/a" not in md and "partly" not in md


def test_simulate_steady_at_point_a_shows_2X_highest_at_the_support(tmp_path):
    """The command an engineer types (`simulate --speed-rpm 4500 --steady` on paper-table4), Dai 2025 §5.1,
    Fig. 13: the support's 2X/1X y velocity >= 0.05 and above disk 1's, the steady state periodic, both
    faces stuck (the support moves with the rotor)."""
    import json

    from reports.cli import main

    assert main(["simulate", "--speed-rpm", "4500", "--steady", "--out", str(tmp_path)]) == 0
    s = json.loads((tmp_path / "simulate-summary.json").read_text())
    v = s["velocity_amplitudes_mm_s_1X_to_5X"]
    ratio = {k: v[k][1] / v[k][0] for k in ("disk1.y", "disk2.y", "s.y")}
    assert s["steady_converged"] and s["stick_fraction_right"] == s["stick_fraction_left"] == 1.0
    assert ratio["s.y"] >= 0.05 and ratio["s.y"] > ratio["disk1.y"], ratio   # measured 0.101 vs 0.005


@pytest.mark.slow
def test_a_point_past_the_law_domain_is_recorded_not_failed():
    """Fig. 19's δ = 2 mm at 15 000 rpm on the paper's mesh: the load drives the ring past the conformal law's
    neat-fit limit (D(b) <= 0, Dai et al. 2025 Eq. 5). The point is a measured outcome: no record, NaN
    harmonics, not periodic, the law's message kept (rotor.studies.steady_state.beyond_law_record)."""
    arrays, info = run_point("paper-table4", 15000.0, misalignment_m=2e-3, options=OPTIONS)
    assert "neat-fit" in info["outside_law_domain"] and not info["converged"]
    assert np.isnan(arrays["harm_q"]).all() and arrays["harm_q"].shape == (5, len(arrays["channels"]))


@pytest.mark.slow
def test_clearance_geometry_at_10200_rpm_is_what_the_points_give_now():
    """study-clearance-geometry.csv's rows at 10 200 rpm on the paper's mesh (periodic at δ0 = 0.03 / 0.05 /
    0.08 mm), recomputed: the ring's mean offset and swing, the contact share, the contact force's 1X and 2X and the
    support's 2X to the CSV's digits (reports.studies.clearance_geometry), and the ring's offset follows δ0 with
    the same swing there (rotor.studies.section5.offset_follows)."""
    from reports.studies.clearance_geometry import CASES, HEADER, as_read, geometry_rows, judged

    rpm = 10200.0
    pts = []
    for prefix, d0_mm in CASES:
        arrays, info = point("paper", rpm, {0.03: "c0.03", 0.05: "base", 0.08: "c0.08"}[d0_mm])
        pts.append(SimpleNamespace(key=f"{prefix}{rpm}", params={"speed_rpm": rpm}, info=info, arrays=arrays))
    now = as_read(geometry_rows(pts, "paper"))
    with open(ROOT / "reports" / "published" / "study-clearance-geometry.csv", newline="", encoding="utf-8") as fh:
        pub = [r for r in csv.DictReader(fh) if r["mesh"] == "paper" and float(r["speed_rpm"]) == rpm]
    assert len(now) == len(pub) == 3
    for a, b in zip(now, pub):
        assert (a["clearance_mm"], a["periodic"]) == (b["clearance_mm"], b["periodic"]) == (a["clearance_mm"], "1")
        for col in HEADER[4:]:
            assert float(a[col]) == pytest.approx(float(b[col]), rel=1e-4, abs=1e-9), (a["clearance_mm"], col)
    assert judged(now)[("paper", rpm)][1]["holds"]
