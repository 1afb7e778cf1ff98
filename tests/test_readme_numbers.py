"""The measured numbers README.md quotes are the ones in the published reports it names.

Each test reads the number from the report (reports/published/), derives what the README says from it (rounded
as the README rounds, or the bound it states) and asserts the README says that. The report's number is guarded by
its own test (tests/claims.py lists which); these tests catch a README left behind when a report is regenerated
(as happened to the cascade cost: 1.7 s per point quoted, 1.4 s published).
"""
from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PUBLISHED = ROOT / "reports" / "published"
README = (ROOT / "README.md").read_text(encoding="utf-8")
WORDS = {1: "one", 2: "two", 3: "three", 4: "four"}


def _md(name: str) -> str:
    return (PUBLISHED / name).read_text(encoding="utf-8")


def _one(pattern: str, text: str) -> re.Match:
    found = list(re.finditer(pattern, text))
    assert len(found) == 1, (pattern, len(found))
    return found[0]


def _spaced(n: float) -> str:
    """An integer with a space between thousands, as the README writes them ("8 744")."""
    return f"{n:,.0f}".replace(",", " ")


def test_table2_agreement_is_the_laws_report_s():
    """README "reproduce the paper's Table 2 percentages to 0.01 points": laws-vs-paper.md's largest difference of
    the conformal law from the paper's percentages (0.009 points) is within it."""
    largest = float(_one(r"largest difference ([\d.]+) points", _md("laws-vs-paper.md")).group(1))
    bound = float(_one(r"reproduce the paper's Table 2 percentages to ([\d.]+) points", README).group(1))
    assert largest <= bound


def test_held_out_error_bound_is_the_accuracy_report_s():
    """README "with the calibrated laws (held-out error ≤ 0.7 %)": every held-out error of accuracy-table2.md's
    must-show lines (three scenes × five Table 2 points; largest 0.661 %, persson-40 at 0.05 mm) is within it."""
    md = _md("accuracy-table2.md")
    lines = [ln for ln in md.splitlines() if re.match(r"- `[\w-]+` \([\w-]+\): 0\.01 mm:", ln)]
    held = [float(x) for ln in lines for x in re.findall(r"mm: ([\d.]+) % <", ln)]
    assert len(lines) == 3 and len(held) == 15
    bound = float(_one(r"with the calibrated laws \(held-out error ≤ ([\d.]+) %\)", README).group(1))
    assert max(held) <= bound


def test_misalignment_ratios_are_the_rotor_misalignment_report_s():
    """README "(2X/1X 0.015 / 0.16 / 0.34 at disk 1 / disk 2 / support)" for inertial-at-joint and "(4.6e-3 at the
    support)" for the opposed pair on the short sleeve: rotor-misalignment.md's ratios, to two digits."""
    md = _md("rotor-misalignment.md")

    def cells(reading: str) -> list[float]:
        row = _one(rf"\| `{reading}` \|[^\n]*", md).group(0)
        return [float(c) for c in row.strip("|").split("|")[-3:]]

    ratios = " / ".join(f"{x:.2g}" for x in cells("inertial-at-joint"))
    assert f"(2X/1X {ratios} at disk 1 / disk 2 / support)" in README
    mantissa, exponent = f"{cells('opposed-at-joint')[2]:.1e}".split("e")
    assert f"({mantissa}e{int(exponent)} at the support)" in README


def test_critical_speed_mesh_numbers_are_the_rotor_mesh_report_s():
    """README "puts the third forward critical speed at 9 608 rpm, +9.9 % on the converged 8 744 rpm; two elements per
    segment are within 0.63 %" and "2 converge the critical speeds to 1 %": rotor-mesh.md's sentence."""
    md = _md("rotor-mesh.md")
    m = _one(r"puts the third forward critical speed at (\d+) rpm, \+([\d.]+) % from the converged (\d+) rpm", md)
    c = _one(r"(\d+) elements per segment bring every critical speed within (\d+) % \(([\d.]+) % worst\)", md)
    n = int(c.group(1))
    assert (f"puts the third forward critical speed at {_spaced(int(m.group(1)))} rpm, +{m.group(2)} % on the converged "
            f"{_spaced(int(m.group(3)))} rpm; {WORDS[n]} elements per segment are within {c.group(3)} %") in README
    assert f"{n} converge the critical speeds to {c.group(2)} %" in README


def test_sweep_cost_follows_from_the_cascade_and_dask_reports():
    """README "a Table 4 cascade point takes a median 1.4 s inside a worker (61 speeds, `study-cascade.md`), about 2 600
    points per core-hour", "(0.999×)" and "A 1e5-point sweep is then about 39 core-hours": study-cascade.md's
    median, perf-dask.md's throughput ratio, and the arithmetic (points per core-hour to two digits)."""
    text = " ".join(README.split())
    cascade = _one(r"(\d+) speeds in \d+ s wall with \d+ worker processes \([\d.]+ s per point on the sweep clock; "
                   r"median ([\d.]+) s per point inside a worker\)", _md("study-cascade.md"))
    median = float(cascade.group(2))
    per_hour = 3600.0 / median
    assert (f"takes a median {cascade.group(2)} s inside a worker ({cascade.group(1)} speeds, `study-cascade.md`), "
            f"about {_spaced(round(per_hour, -2))} points per core-hour") in text
    ratio = _one(r"dask / local pool throughput: \*\*([\d.]+)\*\*", _md("perf-dask.md")).group(1)
    assert f"once workers are warm ({ratio}×)" in text
    assert f"A 1e5-point sweep is then about {1e5 / per_hour:.0f} core-hours" in text


def test_sensitivity_counts_are_the_sensitivity_report_s():
    """README "over about 67 colliding variant–speed pairs 2X rises with δ in 65 of 66, ignoring the tilt lowers 3X–5X
    by ≥ 30 % in 58 of 66, 3X rises with δ in 29 of 66 and the clearance trend holds in 16–18 of 67", "no reading and
    no variant makes all three hold at once" and "(16 min with 1 worker, resumable)": study-sensitivity.md."""
    md = _md("study-sensitivity.md")
    m = _one(r"2X fell with δ0 in (\d+)/(\d+) and 3X in (\d+)/(\d+); 2X rose with δ in (\d+)/(\d+) and 3X in "
             r"(\d+)/(\d+); Σ3X–5X was ≥ 30 % lower without tilt in (\d+)/(\d+)\.", md)
    c2, n2, c3, n3, m2, k2, m3, k3, t, kt = (int(g) for g in m.groups())
    assert n2 == n3
    low, high = sorted((c2, c3))
    assert (f"over about {n2} colliding variant–speed pairs 2X rises with δ in {m2} of {k2}, ignoring the tilt lowers "
            f"3X–5X by ≥ 30 % in {t} of {kt}, 3X rises with δ in {m3} of {k3} and the clearance trend holds in "
            f"{low}–{high} of {n2}") in README
    assert "**All three at once**: **no variant studied makes all three findings hold**" in md
    assert "no reading and no variant makes all three hold at once" in README
    minutes = float(_one(r"Sweep wall time ([\d.]+) min over 1 run\(s\) with 1 worker processes", md).group(1))
    assert f"({minutes:.0f} min with 1 worker, resumable)" in README


# study-findings.md: the README's bullet on the §5 findings, one test per statement. The table's columns after the
# finding and the mesh are the speed bands L1, L2, H1 (9 000–12 000 rpm), H2, H3.
FINDINGS_BULLET = _one(r"- `study-findings\.md`: [^\n]*", README).group(0)
MESHES = {"paper": "paper's mesh", "2/segment": "2 elements/segment"}


def _verdicts(finding: str) -> dict[str, list[str]]:
    """The band verdicts of one finding row of study-findings.md's table, per mesh (``paper``, ``2/segment``)."""
    rows = {}
    for mesh in MESHES:
        row = _one(rf"\| {re.escape(finding)}[^|]* \| {re.escape(mesh)} \|[^\n]*", _md("study-findings.md")).group(0)
        rows[mesh] = [c.strip() for c in row.strip("|").split("|")[2:]]
    assert all(len(cells) == 5 for cells in rows.values()), rows
    return rows


def _findings_csv() -> list[dict]:
    import csv
    with open(PUBLISHED / "study-findings.csv", newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def _rows(finding: str, bands, mesh: str | None = None) -> list[dict]:
    return [r for r in _findings_csv() if r["finding"] == finding and r["band"] in bands
            and (mesh is None or r["mesh"] == mesh)]


def test_findings_that_hold_are_the_findings_report_s():
    """README "Point A and the 3X–5X near the loose support agree on both meshes (61 of 62 high speeds), and 2X rises
    with δ in every band on both meshes": study-findings.md's point A verdicts, its §5.1 and §5.3.2 2X cells, and
    study-findings.csv's per-speed verdicts of §5.1."""
    md = _md("study-findings.md")
    for mesh in ("paper's mesh", "2 elements/segment"):
        assert _one(rf"Point A \(Fig\. 13, 4 500 rpm\), {mesh}: (\w+)", md).group(1) == "agrees"
    assert all(c.startswith("agrees") for cells in _verdicts("§5.1 (Fig. 12): at high speed 3X–5X").values() for c in cells[2:])
    assert all(c.startswith("agrees") for cells in _verdicts("§5.3.2 (Fig. 19): 2X rises").values() for c in cells)
    near = _rows("near_support", ("H1", "H2", "H3"))
    agree = sum(r["verdict"] == "agrees" for r in near)
    assert (f"Point A and the 3X–5X near the loose support agree on both meshes ({agree} of {len(near)} high speeds), "
            "and 2X rises with δ in every band on both meshes") in FINDINGS_BULLET


def test_slip_numbers_are_the_findings_report_s():
    """README "The end faces slip from 5 400 rpm: 12 of the 14 speeds of 4 800–8 700 rpm on each mesh disagree with
    'no relative displacement'": study-findings.csv's §5.3.1 (1) rows of band L2 and the first disagreeing speed."""
    counts = set()
    first = set()
    for mesh in ("paper", "2/segment"):
        rows = _rows("stuck_low", ("L2",), mesh)
        bad = [float(r["speed_rpm"]) for r in rows if r["verdict"] == "disagrees"]
        counts.add((len(bad), len(rows)))
        first.add(min(bad))
    assert len(counts) == 1 and len(first) == 1, (counts, first)
    (k, n), = counts
    assert (f"The end faces slip from {_spaced(first.pop())} rpm: {k} of the {n} speeds of 4 800–8 700 rpm on each "
            "mesh disagree with \"no relative displacement\"") in FINDINGS_BULLET


def test_tilt_numbers_are_the_findings_report_s():
    """README "Above 12 300 rpm ... ignoring the tilt is "no effect" at 37 of 40 speeds there": study-findings.csv's
    §5.2 rows of bands H2 and H3, both meshes, and their share of non-periodic speeds (most)."""
    rows = _rows("tilt", ("H2", "H3"))
    none = sum(r["verdict"] == "no effect" for r in rows)
    assert sum(r["periodic"] == "0" for r in rows) > len(rows) / 2
    assert (f"Above 12 300 rpm the response is mostly not periodic and its 3X–5X lie within the spectral floor: "
            f"ignoring the tilt is \"no effect\" at {none} of {len(rows)} speeds there") in FINDINGS_BULLET


def test_clearance_numbers_are_the_findings_report_s():
    """README "The clearance trend (Fig. 18) disagrees at 9 000–12 000 rpm on both meshes: 2X rises with δ0 by
    0.9–4.7 % at 4 of 6 speeds on each mesh (threshold 0.8 %)": study-findings.md's §5.3.1 (2) 2X cells of band H1
    and study-findings.csv's rows there (the effect is minus the rise)."""
    assert all(cells[2].startswith("disagrees") for cells in _verdicts("§5.3.1 (2, Fig. 18): at high speed 2X falls").values())
    counts, rises, thresholds = set(), [], set()
    for mesh in ("paper", "2/segment"):
        rows = _rows("clearance_2x", ("H1",), mesh)
        bad = [r for r in rows if r["verdict"] == "disagrees"]
        counts.add((len(bad), len(rows)))
        rises += [-100 * float(r["effect"]) for r in bad]
        thresholds |= {f"{100 * float(r['threshold']):.1f}" for r in bad}
    assert len(counts) == 1 and len(thresholds) == 1, (counts, thresholds)
    (k, n), = counts
    assert (f"The clearance trend (Fig. 18) disagrees at 9 000–12 000 rpm on both meshes: 2X rises with δ0 by "
            f"{min(rises):.1f}–{max(rises):.1f} % at {k} of {n} speeds on each mesh (threshold {thresholds.pop()} %)"
            ) in FINDINGS_BULLET


def test_point_b_numbers_are_the_findings_report_s():
    """README "at point B (10 500 rpm) the bearing collides 46 % of the time (56 % on the paper's mesh) and the
    support's 1X is 24.1 mm/s against the paper mesh's 7.71 mm/s": study-findings.md's points A and B table."""
    md = _md("study-findings.md")

    def row(mesh: str) -> tuple[str, str]:
        m = _one(rf"\| {re.escape(mesh)} \| 10500 \| impact \((\d+) % contact, \d+ % stuck\) \| [^|]* \| [^|]* \| "
                 r"([\d.]+) / [^|]* \| yes \|", md)
        return m.group(1), m.group(2)

    (paper_contact, paper_1x), (conv_contact, conv_1x) = row("paper"), row("2/segment")
    assert (f"at point B (10 500 rpm) the bearing collides {conv_contact} % of the time ({paper_contact} % on the "
            f"paper's mesh) and the support's 1X is {conv_1x} mm/s against the paper mesh's {paper_1x} mm/s"
            ) in FINDINGS_BULLET
