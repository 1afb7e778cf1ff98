"""Issue 37, must-show 3: the generated pairs' table of ``law-family.md`` refitted from their kept FEM points.

    .venv/bin/python benchmarks/refit_law_family_pairs.py --seed S [--out reports/published]

``benchmarks/bench_law_family.py --pairs-only`` solves each generated pair's FEM points (about two hours on two
cores for 30 pairs) and keeps them in ``<out>/law-family-pairs/seed-<seed>.json`` (its ``write_points``). This script
fits every law family again on those points with the code as it is (``bench_law_family.pair_fits``: trained on the
``train`` points, checked at the ``midpoints``), and replaces the generated-pairs section of ``<out>/law-family.md``;
the section names the commit whose run solved the points. A changed law family is so checked on the same pairs in
seconds; a changed FEM or grid needs the solving run.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import bench_law_family as family  # noqa: E402
from contact.files import atomic_write_text  # noqa: E402
from reports.cli._edge import out_dir  # noqa: E402

KEYS = ("penetration_m", "force_N", "error_rel")


def refit_row(pair: dict, seed: int) -> dict:
    """One kept pair's table row: its head from the seed's draw, every family fitted on its ``train`` points and
    checked at its ``midpoints`` (``bench_law_family.pair_fits``)."""
    scene, _, row = family.pair_scene(pair["index"], seed)
    sets = [tuple(np.array([p[k] for p in pair[name]], dtype=float) for k in KEYS) for name in ("train", "midpoints")]
    errors = np.concatenate([sets[0][2], sets[1][2]])
    return {**row, "wall_s": pair.get("wall_s", float("nan")), "no_bar": pair.get("no_bar", 0),
            "refined": pair.get("refined", 0), "fem_error_max_pct": 100 * float(errors.max()),
            **family.pair_fits(family.scene_geometry(scene), *sets)}


def refit(points: dict) -> tuple[list[dict], list[str]]:
    """Every kept pair's row (by index) and the section's lines."""
    seed, run = points["seed"], points.get("run", {})
    rows = sorted((refit_row(p, seed) for p in points["pairs"]), key=lambda r: r["index"])
    solved = f"the run of commit {run.get('commit', 'unknown')} (fits: benchmarks/refit_law_family_pairs.py)"
    loads = tuple(run.get("load_average", (float("nan"), float("nan"))))
    return rows, family._pair_lines(rows, seed, run.get("wall_s", float("nan")), loads, solved)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, required=True, help="the kept run's seed")
    ap.add_argument("--out", type=out_dir, default=ROOT / "reports" / "published",
                    help="the report's directory (checked writable before the run)")
    args = ap.parse_args(argv)
    path = args.out / "law-family-pairs" / f"seed-{args.seed}.json"
    target = args.out / "law-family.md"
    if not path.is_file():
        print(f"refit_law_family_pairs: --seed {args.seed}: no kept points {path}", file=sys.stderr)
        return 2
    if not target.is_file() or family.replaced_pairs(target.read_text(encoding="utf-8"), [], "") is None:
        print(f"refit_law_family_pairs: --out {args.out}: {target} has no generated-pairs section", file=sys.stderr)
        return 2
    rows, lines = refit(json.loads(path.read_text(encoding="utf-8")))
    text = family.replaced_pairs(target.read_text(encoding="utf-8"), lines,
                                 f"benchmarks/refit_law_family_pairs.py --seed {args.seed}")
    atomic_write_text(target, text)
    print(f"wrote {target}: {len(rows)} pairs of seed {args.seed}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
