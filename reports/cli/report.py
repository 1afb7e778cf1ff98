"""``ringcontact report``: rebuild the committed reports under ``reports/published/``.

The report is a list of independent builders, each ``build(out_dir) -> list[Path]`` writing
its own files atomically. Later work (FEM-based Tables 2–3, calibration, rotor studies)
adds one entry to :data:`BUILDERS`; nothing else changes. Builders are imported only when
they run, so one broken optional builder cannot stop ``--help``.
"""
from __future__ import annotations

import importlib
import sys
import time
from pathlib import Path

from contact.errors import RingContactError
from reports.cli._edge import PUBLISHED, Parser, fail, out_dir

DEFAULT_OUT = Path(PUBLISHED)   # relative to the working directory (the repository root in a checkout)

# name -> (module with a build(out_dir) function, one-line description). Order = run order.
BUILDERS: dict[str, tuple[str, str]] = {
    "laws": ("reports.laws_report", "analytic laws vs the paper's Table 2 (laws-vs-paper.md/.csv/.png/.svg)"),
    "accuracy": ("reports.accuracy", "laws and calibrated laws vs the FEM datasets, Tables 2-3 style (accuracy-*.md/.csv/.png/.svg)"),
}


def build_parser() -> Parser:
    p = Parser(prog="ringcontact report",
               description="Build the reports from the committed data into reports/published/.")
    p.add_argument("--out", type=out_dir, default=str(DEFAULT_OUT), help=f"output directory (default {DEFAULT_OUT})")
    p.add_argument("--only", action="append", choices=sorted(BUILDERS), metavar="NAME",
                   help="run only this builder (repeatable); default: all")
    p.add_argument("--list", action="store_true", help="list the builders and exit")
    return p


def run(names: list[str], out_dir: Path) -> list[Path]:
    """Run the named builders in order; return every file written."""
    written: list[Path] = []
    for name in names:
        module, _ = BUILDERS[name]
        t0 = time.perf_counter()
        files = importlib.import_module(module).build(out_dir)
        written += files
        print(f"[{name}] {len(files)} files in {time.perf_counter() - t0:.1f} s: "
              + ", ".join(f.name for f in files))
    return written


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    if args.list:
        for name, (module, desc) in BUILDERS.items():
            print(f"{name:10s} {desc}  [{module}]")
        return 0
    names = args.only or list(BUILDERS)
    try:
        run(names, args.out)
    except RingContactError as exc:
        return fail("ringcontact report", exc)
    print(f"reports written to {args.out}")
    return 0


if __name__ == "__main__":   # pragma: no cover
    sys.exit(main())
