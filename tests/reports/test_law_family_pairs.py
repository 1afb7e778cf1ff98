"""The generated pairs of reports/published/law-family.md (benchmarks/bench_law_family.py, issue 37 must-show 3): each
law fitted on a training grid of penetrations and checked at the grid's midpoints, which it never saw.

The slow test re-solves the pair of the run published before this design whose flexible law came closest to its
bound (seed 1141075062's pair 14), by the benchmark's own function."""
from __future__ import annotations

import numpy as np
import pytest
from benchmark_modules import benchmark_module


def _bench():
    return benchmark_module("bench_law_family")


def test_training_grid_holds_the_ends_and_every_point_is_a_knot():
    """The grid's ends are the range's (no near-duplicate of an end, which a rounded grid joined to the exact ends
    made: seed 1141075062's pair 10 had 0.00511695 and 0.00512 mm), all of it knots of the flexible family, and
    every held-out point lies strictly between two training points (interpolation, the law's use)."""
    from contact.calibrate.spline import knot_indices

    bench = _bench()
    low, high = 0.00511695e-3, 0.0301406e-3
    train, mid = bench.pair_grids(low, high)
    assert train[0] == low and train[-1] == pytest.approx(high, rel=1e-14)
    assert np.all(np.diff(np.log(train)) == pytest.approx(np.log(high / low) / (train.size - 1), rel=1e-9))
    assert list(knot_indices(train.size)) == list(range(train.size))
    assert mid.size == train.size - 1 and np.all((train[:-1] < mid) & (mid < train[1:]))


def test_pairs_section_is_replaced_and_nothing_else():
    bench = _bench()
    text = "# t\n\nhead\n\n## Generated pairs (2D, force)\n\nold row\n\n## Kernel cost against today's\n\nkept\n"
    out = bench.replaced_pairs(text, ["new row"], "cmd")
    assert "old row" not in out and "new row" in out and out.startswith("# t\n\nhead\n\n") and out.endswith("kept\n")
    assert bench.replaced_pairs("# t\n\nno sections\n", ["x"], "cmd") is None


@pytest.mark.slow
def test_published_pair_14_holds_at_every_midpoint():
    """Seed 1141075062's pair 14 (clamped-outer-lower, rigid-inner, plane stress, 0.0105-0.094 mm): on the run
    published before this design (5 penetrations and two near-duplicate ends, leave-one-out) the flexible family
    missed by 4.16 % at interior points. Fitted on 12 training penetrations and checked at the 11 midpoints it holds
    the target at all of them; measured while writing this test: worst 0.216 % against a bound of 0.242 %, the
    thinnest margin of six pairs (benchmarks/bench_law_family.py). The analytic families miss there (their
    midpoint errors were percents): the check can fail."""
    bench = _bench()
    row = bench.pair_check(14, 1141075062)
    print(row)
    assert (row["hold"], row["drive"], row["plane"]) == ("clamped-outer-lower", "rigid-inner", "stress")
    assert row["points"] == 11 and row["train_points"] == 12 and row["no_bar"] == 0
    assert row["spline_within"] == 11
    assert row["spline_holdout_max_pct"] < 0.242
    assert row["families_meeting"] == ["foundation-spline"]
