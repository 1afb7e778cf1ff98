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


def _pair_29():
    """Seed 2755664993's pair 29 and its committed FEM points (reports/published/law-family-pairs/
    seed-2755664993-pair-29.json): the scene's geometry and the (penetrations m, forces N, bars) of its 12 training
    points, its 11 midpoints and its 12 refinement points."""
    import json
    from pathlib import Path

    bench = _bench()
    path = Path(__file__).resolve().parents[2] / "reports/published/law-family-pairs/seed-2755664993-pair-29.json"
    data = json.loads(path.read_text())
    scene, (low, high), _ = bench.pair_scene(data["index"], data["seed"])
    sets = {name: tuple(np.array([p[k] for p in data[name]]) for k in ("penetration_m", "force_N", "error_rel"))
            for name in ("train", "midpoints", "refinement")}
    return bench, scene, (low, high), sets


def test_the_pair_twelve_knots_missed_is_refined_where_its_training_points_doubt_and_then_holds():
    """law-family.md's pair 29 of seed 2755664993 (clamped outer, coupled inner, plane strain; that run's one pair
    outside the target): its force's log slope rises from 1.4 to 5.8 and falls to 2.5 over the range (a stiffening
    the foundation base does not follow). On its 12 training points the flexible family was 0.511 % off at a midpoint
    with PCHIP slopes (published, 6 of 11 within); with the slope rule chosen by leave-one-out it is 0.251 %, 9 of 11.
    The refinement (``refined_training``, from the 12 training points alone) asks for 12 more points, at the thirds of
    the 6 most doubtful intervals; solved by the benchmark's own FEM (committed) and added, the family is within the
    target at all 11 midpoints, which it never saw (measured: 0.147 % worst)."""
    bench, scene, (low, high), sets = _pair_29()
    train, mid = bench.pair_grids(low, high)
    assert np.array_equal(sets["train"][0], train) and np.array_equal(sets["midpoints"][0], mid)
    slope = np.diff(np.log(sets["train"][1])) / np.diff(np.log(train))
    assert slope[0] < 1.5 and slope.max() > 5.0 and slope[-1] < 3.0
    geo = bench.scene_geometry(scene)
    coarse = bench.pair_fits(geo, sets["train"], sets["midpoints"])
    assert (coarse["chosen"], round(coarse["chosen_holdout_max_pct"], 3), coarse["chosen_within"]) == (
        "foundation-spline", 0.251, 9) and coarse["families_meeting"] == []
    extra = bench.refined_training(scene, train, sets["train"][1])
    assert np.allclose(extra, sets["refinement"][0], rtol=1e-12) and extra.size == 12
    assert not np.any(np.isin(extra, mid)) and not np.any(np.isin(extra, train))
    order = np.argsort(np.concatenate([train, extra]))
    refined = tuple(np.concatenate([a, b])[order] for a, b in zip(sets["train"], sets["refinement"]))
    row = bench.pair_fits(geo, refined, sets["midpoints"])
    assert row["train_points"] == 24 and row["chosen"] == "foundation-spline" and row["chosen_within"] == 11
    assert row["chosen_holdout_max_pct"] < 0.2 and "foundation-spline" in row["families_meeting"]


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
    run = {"wall_s": 12.5, "load_average": [1.0, 2.0], "commit": "abc1234"}
    path = bench.write_points([{"index": 29, "fem_points": points, "wall_s": 3.0, "no_bar": 0, "refined": 0},
                               {"index": 3, "failed": "x"}], 7, tmp_path, run)
    assert path == tmp_path / "law-family-pairs" / "seed-7.json" and oct(path.stat().st_mode & 0o777) == "0o644"
    back = json.loads(path.read_text())
    assert back["seed"] == 7 and [p["index"] for p in back["pairs"]] == [29] and back["run"] == run
    assert (back["pairs"][0]["wall_s"], back["pairs"][0]["no_bar"], back["pairs"][0]["refined"]) == (3.0, 0, 0)
    scene, _ = draw_pair(np.random.default_rng([2755664993, 29]), 29)
    geo = bench.scene_geometry(scene)
    rows = [bench.pair_fits(geo, *[tuple(np.array([p[k] for p in d[name]]) for k in ("penetration_m", "force_N",
                                                                                       "error_rel"))
                                   for name in ("train", "midpoints")]) for d in (data, back["pairs"][0])]
    assert rows[0] == rows[1]


def test_the_refit_script_rebuilds_the_pairs_section_from_kept_points(tmp_path):
    """benchmarks/refit_law_family_pairs.py: pair 29's kept points (seed 2755664993) refitted into a copy of
    law-family.md give the row ``pair_fits`` gives, the section names the solving run's commit, nothing else of the
    report changes; a seed without kept points, or a report without the section, is exit 2 with one line."""
    import json
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    bench, scene, _, sets = _pair_29()
    data = json.loads((root / "reports/published/law-family-pairs/seed-2755664993-pair-29.json").read_text())
    (tmp_path / "law-family-pairs").mkdir()
    (tmp_path / "law-family-pairs" / "seed-2755664993.json").write_text(json.dumps(
        {"seed": 2755664993, "run": {"wall_s": 1849.0, "load_average": [1.14, 1.49], "commit": "4ddf541"},
         "pairs": [{"index": 29, "wall_s": 1848.0, "no_bar": 0, "refined": 0, "train": data["train"],
                    "midpoints": data["midpoints"]}]}))
    text = "# t\n\n## Generated pairs (2D, force)\n\nOLD ROW\n\n## Kernel cost against today's\n\nkept\n"
    (tmp_path / "law-family.md").write_text(text)
    script = str(root / "benchmarks" / "refit_law_family_pairs.py")
    run = subprocess.run([sys.executable, script, "--seed", "2755664993", "--out", str(tmp_path)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    out = (tmp_path / "law-family.md").read_text()
    row = bench.pair_fits(bench.scene_geometry(scene), sets["train"], sets["midpoints"])
    assert "OLD ROW" not in out and out.endswith("kept\n") and "the run of commit 4ddf541" in out
    assert (f"| 29 | clamped-outer | coupled-inner | strain | 0.0561 | 0.0122-0.0770 | 0.003 | 12 | "
            f"{row['chosen']} | {row['chosen_holdout_max_pct']:.3f} | {row['chosen_within']}/11 |") in out
    bare = tmp_path / "bare"                                  # kept points, no report to put them in
    (bare / "law-family-pairs").mkdir(parents=True)
    (bare / "law-family-pairs" / "seed-2755664993.json").write_text(
        (tmp_path / "law-family-pairs" / "seed-2755664993.json").read_text())
    for argv, says in ((["--seed", "1"], "--seed 1: no kept points"),
                       (["--seed", "2755664993", "--out", str(bare)], "has no generated-pairs section")):
        bad = subprocess.run([sys.executable, script, *argv], capture_output=True, text=True)
        assert bad.returncode == 2 and says in bad.stderr and len(bad.stderr.strip().splitlines()) == 1, bad.stderr


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


def _kept_runs():
    """The committed points files of law-family.md's generated pairs (one per published run; pair 29's own file of
    seed 2755664993 aside)."""
    from pathlib import Path

    folder = Path(__file__).resolve().parents[2] / "reports/published/law-family-pairs"
    return sorted(p for p in folder.glob("seed-*.json") if "-pair-" not in p.name)


def test_the_published_pairs_table_is_the_refit_of_its_kept_points():
    """law-family.md's generated-pairs section (issue 37, must-show 3: a law for every pair) is what
    benchmarks/refit_law_family_pairs.py makes of the committed FEM points of its run
    (reports/published/law-family-pairs/seed-<seed>.json): every row (chosen family, its worst midpoint error, how
    many midpoints within the target, the families meeting it) and the summary line, refitted here with the code as
    it is; and every pair's chosen law within the target at every held-out midpoint."""
    import json
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    refit = benchmark_module("refit_law_family_pairs")
    md = (root / "reports/published/law-family.md").read_text(encoding="utf-8")
    files = [p for p in _kept_runs() if f"Seed {json.loads(p.read_text())['seed']} " in md]
    assert len(files) == 1, files
    rows, lines = refit.refit(json.loads(files[0].read_text()))
    assert len(rows) >= 30
    for line in lines:
        if line.startswith("| ") and line[2].isdigit() or line.startswith("Pairs solved"):
            assert line in md, line
    assert all(r["chosen_within"] == r["points"] for r in rows), [(r["index"], r["chosen_within"]) for r in rows]
