"""benchmarks/bench_fem2d_adaptive.py --cast-iron-from: the cast-iron section copied from an earlier report says
once that it is a copy, however many runs copied it before (the report of seed 1914227559 said it twice)."""
from __future__ import annotations

from benchmark_modules import benchmark_module


def _bench():
    return benchmark_module("bench_fem2d_adaptive")


def test_a_copied_section_says_once_that_it_is_a_copy(tmp_path):
    bench = _bench()
    first = tmp_path / "a.md"
    first.write_text("# r\n\n## The cast-iron pair (issue 37)\n\n| table |\n\nWithin the bar: 5 of 5.\n\n## Generated pairs\n\nx\n")
    text = "\n".join(["# r", ""])
    for _ in range(3):                                   # three runs, each copying the last one's section
        lines = []
        assert bench.kept_part1(lines, first) is None
        text = "# r\n\n" + "\n".join(lines) + "\n## Generated pairs (seed 1)\n\ny\n"
        first.write_text(text)
    assert text.count(bench.COPY_NOTE) == 1
    assert "Within the bar: 5 of 5." in text and "| table |" in text
    assert "## Generated pairs" not in "\n".join(lines)


def test_a_report_without_the_section_is_refused_in_one_line(tmp_path):
    bench = _bench()
    other = tmp_path / "b.md"
    other.write_text("# nothing here\n")
    why = bench.kept_part1([], other)
    assert why is not None and "no section" in why and "\n" not in why
    assert "cannot read" in bench.kept_part1([], tmp_path / "missing.md")
