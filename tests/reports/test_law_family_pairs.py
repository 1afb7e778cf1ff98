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


def test_the_pair_no_family_holds_is_the_published_row_from_its_committed_points():
    """law-family.md's pair 29 of seed 2755664993 (clamped outer, coupled inner, plane strain; the run's one pair
    outside the target): its 23 FEM points, re-solved and committed
    (reports/published/law-family-pairs/seed-2755664993-pair-29.json), give the published row through the
    benchmark's own fit: the flexible family chosen, 6 of 11 midpoints within the target, 0.511 % at 0.01330 mm,
    no family within it at every midpoint. The force's log slope there rises from 1.4 to 5.8 and falls to 2.5
    over the range (a stiffening the foundation base does not follow: the correction rises by 4 in ln), which
    12 knots do not interpolate to 0.2 %."""
    import json
    from pathlib import Path

    from fem_reference.plane.generated import draw_pair

    bench = _bench()
    path = Path(__file__).resolve().parents[2] / "reports/published/law-family-pairs/seed-2755664993-pair-29.json"
    data = json.loads(path.read_text())
    scene, (low, high) = draw_pair(np.random.default_rng([data["seed"], data["index"]]), data["index"])
    train, mid = bench.pair_grids(low, high)
    sets = [tuple(np.array([p[k] for p in data[name]]) for k in ("penetration_m", "force_N", "error_rel"))
            for name in ("train", "midpoints")]
    assert np.array_equal(sets[0][0], train) and np.array_equal(sets[1][0], mid)
    row = bench.pair_fits(bench.scene_geometry(scene), *sets)
    text = (Path(__file__).resolve().parents[2] / "reports/published/law-family.md").read_text()
    published = next(line for line in text.splitlines() if line.startswith("| 29 | clamped-outer | coupled-inner"))
    cells = [c.strip() for c in published.strip("|").split("|")]
    assert (row["chosen"], f"{row['chosen_holdout_max_pct']:.3f}", f"{row['chosen_within']}/{row['points']}") \
        == (cells[7], cells[8], cells[9])
    assert row["families_meeting"] == [] and cells[11] == "none"
    assert f"{row['spline_worst_mm']:.5f}" == cells[13]
    slope = np.diff(np.log(sets[0][1])) / np.diff(np.log(train))
    assert slope[0] < 1.5 and slope.max() > 5.0 and slope[-1] < 3.0


def test_the_pairs_fem_points_are_written_beside_the_report_and_refit_to_the_same_row(tmp_path):
    """``write_points`` keeps each pair's FEM points (``pair_check``'s ``fem_points``) in
    ``<out>/law-family-pairs/seed-<seed>.json``, so a changed family can be re-checked without solving again: pair 29's
    committed points written through it and read back give the same fit row; rows without points (a failed pair)
    are left out."""
    import json
    from pathlib import Path

    from fem_reference.plane.generated import draw_pair

    bench = _bench()
    data = json.loads((Path(__file__).resolve().parents[2]
                       / "reports/published/law-family-pairs/seed-2755664993-pair-29.json").read_text())
    points = {name: data[name] for name in ("train", "midpoints")}
    path = bench.write_points([{"index": 29, "fem_points": points}, {"index": 3, "failed": "x"}], 7, tmp_path)
    assert path == tmp_path / "law-family-pairs" / "seed-7.json" and oct(path.stat().st_mode & 0o777) == "0o644"
    back = json.loads(path.read_text())
    assert back["seed"] == 7 and [p["index"] for p in back["pairs"]] == [29]
    scene, _ = draw_pair(np.random.default_rng([2755664993, 29]), 29)
    geo = bench.scene_geometry(scene)
    rows = [bench.pair_fits(geo, *[tuple(np.array([p[k] for p in d[name]]) for k in ("penetration_m", "force_N",
                                                                                       "error_rel"))
                                   for name in ("train", "midpoints")]) for d in (data, back["pairs"][0])]
    assert rows[0] == rows[1]


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
