"""reports/published/law-tilt-correction.md (benchmarks/bench_tilt_correction.py): its held-out tables and verdicts,
the smoothing's cross-validation and why it has one weight per direction, recomputed from the committed grids and run
folders by the benchmark's own functions (its kernel times are wall times and are not asserted)."""
from __future__ import annotations

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _bench():
    spec = importlib.util.spec_from_file_location("bench_tilt_correction", ROOT / "benchmarks" /
                                                  "bench_tilt_correction.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_held_out_tables_are_the_published_ones():
    bench = _bench()
    md = (ROOT / "reports" / "published" / "law-tilt-correction.md").read_text(encoding="utf-8")
    rings = {}
    for ring in bench.RINGS:
        fitted = bench.fit_ring(ring, bench.PUBLISHED)
        checked = bench.check_ring(ring, fitted, bench.PUBLISHED)
        rings[ring] = (fitted, checked)
        lines, _ = bench.ring_lines(ring, fitted, checked)
        for line in lines:
            if line.startswith("|") or line.startswith("**"):
                assert line in md, line
        law_file = bench.PUBLISHED / "law-tilt-correction" / f"{fitted['law'].name}-law.json"
        assert law_file.read_text(encoding="utf-8") == fitted["law"].to_json()      # the committed law is this fit
    for miss in bench.misses(rings):
        assert miss in md, miss
    # why one smoothing weight per direction: the one-weight law's misses with each weight swept, and the two rules'
    # nested cross-validation on the training points alone
    direction = [line for line in bench.direction_lines(rings) if line.strip()]
    assert any(line.startswith("  - ") for line in direction)           # the one-weight rule misses a point here
    for line in direction:
        assert line in md, line
    assert all(line in md for line in bench.slice_error_lines("newcomer-20mm", bench.PUBLISHED) if line.startswith("|"))
