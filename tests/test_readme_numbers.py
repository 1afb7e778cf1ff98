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
