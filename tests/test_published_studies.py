"""Section 5 study reports (reports/published/study-*.md, section5-readings.md, perf-branch-switches.md) in the
default run.

The studies take minutes to hours whole (``-m slow`` runs the cascade, the per-band findings and the sensitivity
base point). Here, in seconds: the paper's points A and B (4 500 and 10 500 rpm) recomputed on both meshes with
the studies' own settings, which must give the published ``study-point.md`` byte for byte, the published rows of
``study-findings.md`` and two of the 61 rows of ``study-cascade.csv``. Statements that summarise a committed table
(the cascade's 1X share, the map's counts, the sensitivity study's trend counts, the branch's orbit counts) are
recomputed from that table here: these guard the text against its data, the data itself being guarded by the
slow studies or, for the branch (a 40-minute run), by the run's own verification. Each test names the published
values it guards; the registry of claims is tests/claims.py.
"""
from __future__ import annotations

import csv
import json
from collections import Counter
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
PUBLISHED = ROOT / "reports" / "published"
#: the studies' settings (reports/cli/study.py: _options with the published --max-revs 1500)
OPTIONS = {"steps_per_rev": 256, "max_revs": 1500}
POINT_A_B_RPM = (4500.0, 10500.0)
LOCATIONS = ("disk1", "disk2", "support")


def _md(name: str) -> str:
    return (PUBLISHED / name).read_text(encoding="utf-8")


def _csv(name: str) -> list[dict]:
    with open(PUBLISHED / name, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def _points(elements: int | None) -> list:
    """Points A and B of paper-table4 as ``study point`` computes them, in the form the report builders read."""
    from rotor.studies.steady_state import run_point

    out = []
    for rpm in POINT_A_B_RPM:
        arrays, info = run_point("paper-table4", rpm, options=OPTIONS, elements_per_segment=elements)
        out.append(SimpleNamespace(params={"speed_rpm": rpm}, info=info, arrays=arrays))
    return out


@pytest.fixture(scope="module")
def paper_points():
    return _points(None)


def test_study_point_report_is_what_points_a_and_b_give_now(paper_points):
    """study-point.md whole: at 4 500 rpm stick, 0 % contact, 2X/1X 4.60e-03 at disk 1 and 1.01e-01 at the support
    (22.0× larger), max r/δ0 0.443; at 10 500 rpm impact, the ring on the bore 56 % of the time, 2X/1X 1.89e-02 /
    6.11e-01, (3X+4X+5X)/1X 7.79e-03 / 6.18e-02 / 8.01e-02, max r/δ0 1.015 (reports.studies.point.point_note)."""
    from reports.studies.point import point_note

    assert point_note(paper_points) == _md("study-point.md")


def test_cascade_rows_at_points_a_and_b_are_the_recomputed_points(paper_points):
    """study-cascade.csv (the Fig. 12 cascade, 61 speeds; whole it is
    tests/rotor/studies/test_study_slow.py::test_figure12_cascade_61_speeds_two_processes, slow): its 4 500 and
    10 500 rpm rows are these points, 1X–5X velocity amplitudes to the CSV's six digits, the same regime,
    contact fraction and transient length."""
    rows = {float(r["speed_rpm"]): r for r in _csv("study-cascade.csv")}
    for p in paper_points:
        r = rows[p.params["speed_rpm"]]
        assert r["regime"] == p.info["label"] and int(r["transient_revs"]) == p.info["transient_revs"]
        assert float(r["contact_fraction"]) == pytest.approx(p.info["contact_fraction"], rel=1e-5, abs=1e-12)
        ch = list(p.arrays["channels"])
        for loc, name in zip(LOCATIONS, ("disk1.y", "disk2.y", "s.y")):
            amp = np.abs(p.arrays["harm_v"])[:5, ch.index(name)] * 1e3
            got = [float(r[f"{loc}_v{h}X_mm_s"]) for h in range(1, 6)]
            assert got == pytest.approx(amp, rel=1e-5), (p.params["speed_rpm"], loc)


def _findings_rows(tag: str, points) -> None:
    from reports.studies.findings import point_a
    from reports.studies.mesh import _point_rows

    md = _md("study-findings.md")
    for row in _point_rows(tag, points):
        assert row in md, row
    text, verdict = point_a(points)
    assert f"{verdict}: {text}." in md


def test_findings_points_a_and_b_on_the_paper_mesh(paper_points):
    """study-findings.md, the paper's mesh: "Point A (Fig. 13, 4 500 rpm), paper's mesh: agrees: 2X/1X disk 1 0.005,
    disk 2 0.040, support 0.101; end faces stuck 100 % of the time (stick, max r/δ0 0.443, periodic after 266
    revolutions)" and the rows "| paper | 4500 | stick (0 % contact, 100 % stuck) |", "| paper | 10500 | impact (56 %
    contact, 0 % stuck) |" with their 1X / 2X / Σ3X–5X velocities (reports.studies.findings, reports.studies.mesh)."""
    _findings_rows("paper", paper_points)


def test_findings_points_a_and_b_on_the_converged_mesh():
    """study-findings.md, 2 elements per segment: point A "agrees: 2X/1X disk 1 0.005, disk 2 0.038, support 0.101 …
    periodic after 589 revolutions" and "| 2/segment | 10500 | impact (46 % contact, 0 % stuck) |" (the support's 1X
    24.1 mm/s against 7.71 on the paper's mesh)."""
    _findings_rows("2/segment", _points(2))


def test_cascade_statements_follow_from_its_committed_csv():
    """study-cascade.md against study-cascade.csv (what ``study publish`` wrote beside it): "1X is 79.2 % (median
    over speeds and locations) of the 1X–5X sum; lowest 25.0 %", the regime bands "0–5100 rpm stick; 5400–6000 rpm
    contact; 6300–18000 rpm impact" and the 20 speeds without a periodic steady state (reports/studies/cascade.py's
    formulas on the table's values)."""
    rows = _csv("study-cascade.csv")
    rpm = np.array([float(r["speed_rpm"]) for r in rows])
    V = np.array([[[float(r[f"{loc}_v{h}X_mm_s"]) for h in range(1, 6)] for loc in LOCATIONS] for r in rows])
    share = (V[:, :, 0] / np.maximum(V.sum(axis=2), 1e-30))[rpm > 0]
    md = _md("study-cascade.md")
    assert (f"1X is {100 * np.median(share):.1f} % (median over speeds and locations) of the 1X–5X sum; lowest "
            f"{100 * share.min():.1f} %") in md
    bands: list = []
    for r, lab in zip(rpm, (r["regime"] for r in rows)):
        if bands and bands[-1][0] == lab:
            bands[-1][2] = r
        else:
            bands.append([lab, r, r])
    assert "**Loose-support regime by speed:** " + "; ".join(f"{a:.0f}–{b:.0f} rpm {lab}" for lab, a, b in bands) in md
    open_ = [f"{r:.0f}" for r, row in zip(rpm, rows) if row["converged"] != "1"]
    assert "harmonics): " + ", ".join(open_) + " rpm." in md and len(open_) == 20


_PARAM_CASES = {"base": "base", "c0.03mm": "c0.03", "c0.08mm": "c0.08", "d0.5mm": "d0.5", "d2mm": "d2"}


def _tables(suffix: str) -> tuple[dict, dict]:
    """``({rpm: {case: (A, info)}}`` of the cascades' y velocities (m/s), the same of the params study's y
    displacements (m; 1X–3X, 4X–5X NaN)``, from the committed study-cascade*.csv and study-params*.csv."""
    v: dict = {}
    for name, case in ((f"study-cascade{suffix}.csv", "base"), (f"study-cascade-notilt{suffix}.csv", "notilt")):
        for r in _csv(name):
            A = np.array([[float(r[f"{loc}_v{h}X_mm_s"]) * 1e-3 for h in range(1, 6)] for loc in LOCATIONS])
            info = {"converged": r["converged"] == "1", "stick_fraction": float(r["stick_fraction"]),
                    "contact_fraction": float(r["contact_fraction"])}
            v.setdefault(float(r["speed_rpm"]), {})[case] = (A, info)
    q: dict = {}
    for r in _csv(f"study-params{suffix}.csv"):
        case = _PARAM_CASES.get(r["key"].rsplit("-rpm", 1)[0])
        if case:
            A = np.array([[float(r[f"{loc}_{h}X_um"] or "nan") * 1e-6 for h in (1, 2, 3)] + [np.nan] * 2
                          for loc in LOCATIONS])
            q.setdefault(float(r["speed_rpm"]), {})[case] = (A, {"converged": r["converged"] == "1"})
    return v, q


def test_findings_verdicts_follow_from_the_committed_study_tables():
    """study-findings.csv against the study tables ``study publish`` wrote beside it (study-cascade*.csv,
    study-params*.csv, both meshes): at every speed and finding, the effect recomputed from the tables' six digits;
    where every case compared is periodic, the threshold (the step noise) and the verdict too. A non-periodic
    point's threshold adds its spectral floor, which the tables do not carry: there the effect is compared where
    one number decides it (a "within x %" or the stuck share), not where the location deciding a two-location
    finding depends on the thresholds. Every speed of the tables with a record is judged: no speed left without a
    verdict."""
    from rotor.studies.section5 import BANDS, FINDINGS, KINDS, band_verdict

    rows = {(r["mesh"], r["finding"], r["band"], float(r["speed_rpm"])): r for r in _csv("study-findings.csv")}
    seen = 0
    for tag, suffix in (("paper", ""), ("2/segment", "-e2")):
        v, q = _tables(suffix)
        for f in FINDINGS:
            for b in f.bands:
                for s in band_verdict(f, b, v if f.quantity == "v" else q).speeds:
                    r = rows[(tag, f.name, b, s.rpm)]
                    seen += 1
                    assert (r["periodic"] == "1") == s.periodic, r
                    if s.periodic or KINDS[f.name] in ("limit", "state"):
                        assert float(r["effect"]) == pytest.approx(s.effect, rel=1e-4, abs=2e-5), r
                    if s.periodic:
                        assert float(r["threshold"]) == pytest.approx(s.threshold, rel=1e-5), r
                        assert r["verdict"] == s.verdict, (r, s)
    assert seen == len(rows) and set(r["band"] for r in rows.values()) == set(BANDS)


def test_params_statements_follow_from_its_committed_csv():
    """study-params.md against study-params.csv: the median rows at ≥ 9 000 rpm per clearance and misalignment
    ("| 0.08 | 13.6 | 2.33 | 0.335 | 2.41 | 0.397 | 7/16 |" …), the median verdicts "2X decreases, 3X does not
    decrease → does not agree" and "2X increases, 3X does not increase monotonically → does not agree", and "1X
    varies by at most 5.4 % across δ" (the largest 1X change over the speeds where every δ is periodic), with
    reports/studies/params.py's formulas on the table's values."""
    rows = _csv("study-params.csv")
    md = _md("study-params.md")

    def amp(r, loc, h):
        return float(r[f"{loc}_{h}X_um"] or "nan")

    for key, col in (("clearance", "clearance_mm"), ("misalignment", "misalignment_mm")):
        other = "misalignment_mm" if key == "clearance" else "clearance_mm"
        base_other = {"clearance_mm": "0.05", "misalignment_mm": "1"}[other]
        sel = [r for r in rows if r[other] == base_other]
        vals = sorted({float(r[col]) for r in sel})
        med = {}
        for v in vals:
            hi = [r for r in sel if float(r[col]) == v and float(r["speed_rpm"]) >= 9000]
            m = np.array([[np.nanmedian([amp(r, loc, h) for r in hi]) for h in (1, 2, 3)] for loc in LOCATIONS])
            med[v] = m
            nconv = sum(r["converged"] == "1" for r in hi)
            assert (f"| {v:g} | {m[0, 0]:.3g} | {m[1, 1]:.3g} | {m[1, 2]:.3g} | {m[2, 1]:.3g} | {m[2, 2]:.3g} | "
                    f"{nconv}/{len(hi)} |") in md, (key, v)
        lo, top = vals[0], vals[-1]
        if key == "clearance":
            ok2 = med[lo][1:, 1].min() > med[top][1:, 1].max()
            ok3 = med[lo][1:, 2].min() > med[top][1:, 2].max()
            assert (f"2X {'decreases' if ok2 else 'does not decrease'}, 3X {'decreases' if ok3 else 'does not decrease'}"
                    f" → {'agrees' if ok2 and ok3 else 'does not agree'} (medians") in md
        else:
            ok2 = all(med[a][1:, 1].max() < med[b][1:, 1].min() for a, b in zip(vals, vals[1:]))
            ok3 = all(med[a][1:, 2].max() < med[b][1:, 2].min() for a, b in zip(vals, vals[1:]))
            one = np.array([med[v][:, 0] for v in vals])
            spread = (one.max(axis=0) / one.min(axis=0) - 1).max() * 100
            assert (f"1X median spread across δ {spread:.1f} % (largest location), 2X "
                    f"{'increases' if ok2 else 'does not increase monotonically'}, 3X "
                    f"{'increases' if ok3 else 'does not increase monotonically'} → "
                    f"{'agrees' if ok2 and ok3 and spread < 5 else 'does not agree'} (medians") in md
            by: dict = {}
            for r in sel:
                by.setdefault(float(r["speed_rpm"]), {})[float(r[col])] = r
            worst = 0.0
            for rpm, d in by.items():
                if rpm > 0 and len(d) == len(vals) and all(r["converged"] == "1" for r in d.values()):
                    a1 = np.array([[amp(d[v], loc, 1) for loc in LOCATIONS] for v in vals])
                    worst = max(worst, float((a1.max(axis=0) / a1.min(axis=0) - 1).max() * 100))
            assert f"1X varies by at most {worst:.1f} % across δ" in md


def test_clearance_geometry_follows_from_its_committed_csv():
    """study-findings.md's clearance mechanism ("Clearance, where the ring rides …", both meshes) against
    study-clearance-geometry.csv: the bullets are what the CSV gives (reports.studies.clearance_geometry); at
    every speed of 9 000–12 000 rpm on both meshes (where 2X rises with δ0 against Fig. 18) the ring's mean
    offset follows δ0 with the same swing (rotor.studies.section5.offset_follows) and the contact force's 2X
    changes with δ0 by more than the support's 2X displacement; the CSV's support 2X and periodic flags are
    study-params.csv's and study-params-e2.csv's (δ = 1 mm). Fails when a rerun of the study breaks the mechanism."""
    from reports.studies.clearance_geometry import H1, geometry_lines, judged, relative_change

    rows = _csv("study-clearance-geometry.csv")
    md = _md("study-findings.md")
    lines = geometry_lines(rows, 2)
    assert len(lines) == 2 and all(line in md for line in lines)
    j = judged(rows)
    for mesh, name in (("paper", "study-params.csv"), ("2/segment", "study-params-e2.csv")):
        h1 = {rpm: v for (m, rpm), v in j.items() if m == mesh and H1[0] <= rpm <= H1[1]}
        assert len(h1) == 6, (mesh, sorted(h1))
        for rpm, (rs, res) in h1.items():
            assert res["holds"], (mesh, rpm, res)
            assert abs(relative_change(rs, "force_2x_N")) > abs(relative_change(rs, "support_2x_um")), (mesh, rpm)
        params = {(float(r["speed_rpm"]), float(r["clearance_mm"])): r for r in _csv(name)
                  if float(r["misalignment_mm"]) == 1.0}
        geo = {(float(r["speed_rpm"]), float(r["clearance_mm"])): r for r in rows if r["mesh"] == mesh}
        assert set(geo) == set(params), mesh
        for k, r in geo.items():
            assert r["periodic"] == params[k]["converged"], (mesh, k)
            assert float(r["support_2x_um"]) == pytest.approx(float(params[k]["support_2X_um"]), rel=1e-5, abs=1e-9)


def test_findings_reading_counts_of_periodic_speeds_are_the_cascades():
    """study-findings.md's reading: "The tilt-ignored cascades went from 18 to 40 periodic speeds of 61 on the paper's
    mesh ... and from 14 to 18 on the converged; the converged tilt-on cascade from 35 to 39": the new counts are the
    committed cascades' (the former ones are the previous commit's, listed in tests/claims.py UNGUARDED)."""
    md = _md("study-findings.md").replace("\n", " ")
    count = {name: sum(r["converged"] == "1" for r in _csv(name)) for name in
             ("study-cascade-notilt.csv", "study-cascade-notilt-e2.csv", "study-cascade-e2.csv")}
    assert (f"went from 18 to {count['study-cascade-notilt.csv']} periodic speeds of 61 on the paper's mesh") in md
    assert f"from 14 to {count['study-cascade-notilt-e2.csv']} on the converged" in md
    assert f"from 35 to {count['study-cascade-e2.csv']}" in md


def test_study_map_counts_follow_from_its_committed_csv():
    """study-map.md: "Counts: beyond law 2, contact 9, impact 43, stick 11 of 65 points; 27 without a periodic steady
    state", from study-map.csv (reports/studies/regime_map.py's count on the table's regimes)."""
    rows = _csv("study-map.csv")
    c = Counter(r["regime"] for r in rows)
    line = ("Counts: " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())) + f" of {len(rows)} points; "
            f"{sum(r['converged'] != '1' for r in rows)} without a periodic steady state.")
    assert line in _md("study-map.md")


def test_sensitivity_trend_counts_follow_from_the_committed_points():
    """study-sensitivity.md: the trend table by speed and "2X fell with δ0 in 18/67 and 3X in 16/67; 2X rose with δ
    in 65/66 and 3X in 29/66; Σ3X–5X was ≥ 30 % lower without tilt in 58/66", recomputed by reports/sensitivity.py
    from study-sensitivity-points.csv (the points themselves: the slow
    tests/rotor/studies/test_study_sensitivity.py::test_reduced_study_through_the_sweep_reproduces_the_published_base_numbers)."""
    from reports import sensitivity as rep
    from reports.sensitivity_figure import tables_from_points_csv

    tabs, _ = tables_from_points_csv(PUBLISHED / "study-sensitivity-points.csv")
    table, tot = rep._trends(tabs)
    md = _md("study-sensitivity.md")
    assert table in md
    assert (f"2X fell with δ0 in {tot['c2'][0]}/{tot['c2'][1]} and 3X in {tot['c3'][0]}/{tot['c3'][1]}; 2X rose with δ "
            f"in {tot['m2'][0]}/{tot['m2'][1]} and 3X in {tot['m3'][0]}/{tot['m3'][1]}; Σ3X–5X was ≥ 30 % lower without "
            f"tilt in {tot['t'][0]}/{tot['t'][1]}.") in md


def _spaced(n: float) -> str:
    """An integer with a space between thousands, as the hand-written readings write them ("1 202")."""
    return f"{n:,.0f}".replace(",", " ")


def test_branch_reports_agree_with_the_published_branch_data():
    """perf-branch-switches.md and study-bifurcation.md against the run's published data (perf-branch-switches.json,
    study-bifurcation.json; the run itself takes 40 minutes and verifies sampled orbits by independent shooting):
    "| orbits | 788 |", "| stable / unstable orbits | 644 / 144 |", "| corrector stalls | 89 |", the restarts by
    kind; the reading's "It reached 18 000 rpm (788 orbits, 1 911 s", "Restarts: 18", disk 1's "peaks at 148 mm/s at
    4 291 rpm" and the loose support's "peaks at 82 mm/s at 2 443 rpm"; both files from the same orbits."""
    bench = json.loads((PUBLISHED / "perf-branch-switches.json").read_text(encoding="utf-8"))
    (seg,) = json.loads((PUBLISHED / "study-bifurcation.json").read_text(encoding="utf-8"))
    pts = seg["points"]
    assert [p["speed_rpm"] for p in pts] == bench["speeds_rpm"] and [p["stable"] for p in pts] == bench["stable"]
    stable = sum(bench["stable"])
    perf = _md("perf-branch-switches.md")
    for row in (f"| orbits | {len(pts)} |", f"| reached | {max(bench['speeds_rpm']):.1f} rpm |",
                f"| stop | {bench['stop']} |", f"| wall | {bench['wall_s']:.0f} s |",
                "| restarts by kind | " + ", ".join(f"{k} {v}" for k, v in bench["restarts"].items()) + " |",
                f"| corrector stalls | {len(bench['corrector_failures'])} |",
                f"| stable / unstable orbits | {stable} / {len(pts) - stable} |"):
        assert row in perf, row
    assert all(v["residual"] < 1e-8 and v["shoot_converged"] for v in bench["verified"])
    reading = _md("study-bifurcation.md")
    assert (f"It reached {_spaced(max(p['speed_rpm'] for p in pts))} rpm ({_spaced(len(pts))} orbits, "
            f"{_spaced(seg['wall_s'])} s") in reading and seg["stop"] == "end reached"
    assert f"**Restarts: {sum(seg['restarts'].values())}, each reported" in reading
    assert sum(p["restarted"] is not None for p in pts) == sum(seg["restarts"].values())
    flat = " ".join(reading.split())             # the reading's lines wrapped anywhere
    peak = max(pts, key=lambda p: p["velocity_amplitudes_mm_s_1X_to_5X_disk1.y"][0])
    assert (f"the 1X amplitude at disk 1 peaks at {peak['velocity_amplitudes_mm_s_1X_to_5X_disk1.y'][0]:.0f} mm/s at "
            f"{_spaced(peak['speed_rpm'])} rpm") in flat
    peak = max(pts, key=lambda p: p["velocity_amplitudes_mm_s_1X_to_5X_s.y"][0])
    assert (f"At the support the 1X peaks at {peak['velocity_amplitudes_mm_s_1X_to_5X_s.y'][0]:.0f} mm/s at "
            f"{_spaced(peak['speed_rpm'])} rpm") in flat


#: study-testrig.md's settings (reports/cli/study.py: _testrig): (speed rpm, clearance mm, misalignment mm)
TESTRIG_CASES = tuple((rpm, c, d) for rpm in (3600.0, 5500.0) for c, d in ((0.05, 2.0), (0.01, 2.0), (0.05, 1.0),
                                                                          (0.05, 3.0)))


@pytest.mark.slow
def test_testrig_points_reproduce_the_published_table():
    """study-testrig.md: the eight steady states of the Table 5 rig at the paper's steps (3 600 and 5 500 rpm; Table 5's
    δ0 0.05 mm, δ 2 mm; δ0 0.01 mm; δ 1 and 3 mm), each row (regime, contact and stuck shares, periodic, sums of
    2X–5X at disk 2 and the support to four digits; not max r/δ0, round-off of a stuck ring's 1e-12) as published.
    About 20 s a point on the shared machine: slow."""
    from rotor.studies.steady_state import run_point

    md = _md("study-testrig.md")
    for rpm, c_mm, d_mm in TESTRIG_CASES:
        arrays, info = run_point("paper-table5-testrig", rpm, options=OPTIONS, clearance_m=c_mm * 1e-3,
                                 misalignment_m=d_mm * 1e-3)
        ch = list(arrays["channels"])
        s = [np.abs(arrays["harm_v"])[1:5, ch.index(name)].sum() * 1e3 for name in ("disk2.y", "s.y")]
        head = (f"| `paper-table5-testrig` | {rpm:.0f} | {c_mm:g} | {d_mm:g} | {info['label']} | "
                f"{100 * info['contact_fraction']:.0f} | {100 * info['stick_fraction']:.0f} | ")
        tail = f" | {'yes' if info['converged'] else 'no'} | {s[0]:.4g} | {s[1]:.4g} |"   # max r/δ0 between: ~1e-12
        assert any(line.startswith(head) and line.endswith(tail) for line in md.splitlines()), (head, tail)
