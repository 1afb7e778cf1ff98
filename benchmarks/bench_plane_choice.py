"""Plane stress or strain by the 3D ring: the bearing job's choice for the bundled pairs and the newcomer's, and its cost.

    .venv/bin/python benchmarks/bench_plane_choice.py [--workers 2]

Writes reports/published/bearing-plane-choice.md. For every bundled ring-pair file and the newcomer's bearing of
issue 38 (``RING`` of tests/test_wheel_newcomer.py: a steel ring R 40-45 mm, 20 mm wide, in an aluminium housing to
R 65 mm, axially free; its plane left to ``auto``) it runs the bearing job's stage 0
(:func:`fem_reference.plane_check.resolve`) with the check forced, in an empty 3D level cache, and lists the 3D ring's
force at zero tilt against both 2D assumptions, the closer plane and the plane the job uses. Cost: the newcomer's
bearing, straight only (``tilt_arcmin = [0, 0]``), through ``ringcontact bearing`` in a child process, cold (empty
output folder and level cache), with the check (its default for ``auto``) and with ``--no-plane-check``; the 1-minute
load average beside every time (2 shared cores). Target (issue 38): the 2D-only job within 2 minutes on 2 cores.
"""
from __future__ import annotations

import argparse
import ast
import json
import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "reports" / "published" / "bearing-plane-choice.md"
TARGET_S = 120.0


def newcomer_ring() -> str:
    """``RING`` of tests/test_wheel_newcomer.py (read, not imported: that module builds wheels)."""
    tree = ast.parse((ROOT / "tests" / "test_wheel_newcomer.py").read_text(encoding="utf-8"))
    node = next(n for n in tree.body if isinstance(n, ast.Assign) and getattr(n.targets[0], "id", "") == "RING")
    return ast.literal_eval(node.value)


def choices(files: dict, workers: int, cache: Path) -> list[dict]:
    """Stage 0 with the check forced, per ring-pair file; and whether the job checks it by default."""
    os.environ["RINGCONTACT_CACHE"] = str(cache)
    from fem_reference.plane_check import resolve
    from fem_reference.ring_scene import load

    rows = []
    for label, path in files.items():
        rs = load(str(path))
        load0 = os.getloadavg()[0]
        t0 = time.perf_counter()
        _, rec = resolve(rs, run_check=True, workers=workers)
        rows.append({"label": label, "name": rs.name, "document": rs.document, "record": rec,
                     "default_checks": rs.plane_auto or rs.needs_3d, "wall_s": time.perf_counter() - t0,
                     "load": (load0, os.getloadavg()[0])})
        print(f"{label}: {rec['used']} ({rows[-1]['wall_s']:.1f} s)", file=sys.stderr)
    return rows


def job(toml: Path, out: Path, cache: Path, workers: int, *extra: str) -> dict:
    """One cold ``ringcontact bearing`` in a child process (benchmarks/bench_bearing.py's): wall time, load, stages,
    the plane record."""
    from bench_bearing import run_job

    got = run_job(toml, out, cache, workers, *extra)
    return {"wall_s": got["wall_s"], "load": (got["load_start"], got["load_end"]), "stages": got["stages"],
            "plane": got["summary"]["plane"], "extra": " ".join(extra)}


def _choice_lines(rows: list[dict]) -> list[str]:
    lines = ["| ring pair | width / ring thickness | held / driven (3D) | file's plane | Δr (mm) | 3D force (N) ± % "
             "| stress − 3D (%) | strain − 3D (%) | closer | plane the job uses | checked by default | check wall (s), "
             "load |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        d, rec = r["document"], r["record"]
        ev = rec["check"]
        b = d["bearing_ring"]
        ratio = b["width_mm"] / (b["outer_radius_mm"] - b["inner_radius_mm"])
        for i, p in enumerate(ev["points"]):
            head = (f"| {r['label']} | {ratio:.3g} | {ev['boundary_conditions_3d']} | {rec['requested']} "
                    if i == 0 else "| | | | ")
            tail = (f"| {ev['closer']} ({'decisive' if ev['decisive'] else 'not decisive'}) | {rec['used']} "
                    f"| {'yes' if r['default_checks'] else 'no (--plane-check)'} | {r['wall_s']:.1f}, "
                    f"{r['load'][0]:.1f} → {r['load'][1]:.1f} |" if i == 0 else "| | | | |")
            lines.append(head + f"| {p['penetration_mm']:.4g} | {p['force_3d_N']:,.0f} ± "
                         f"{100 * p['force_3d_error_rel']:.3f} | {100 * p['stress_minus_3d_rel']:+.2f} "
                         f"| {100 * p['strain_minus_3d_rel']:+.2f} ".replace(",", " ") + tail)
    warn = [f"- `{r['label']}`: {w}." for r in rows for w in r["record"]["warnings"]]
    return lines + ([""] + ["Warnings of the check (on the terminal and in the summary when the job runs it):", ""]
                    + warn if warn else []) + ["", "Per ring pair:"]


def _reading(rows: list[dict]) -> list[str]:
    """One sentence per ring pair: the closer plane and how far each lies (from the check's numbers)."""
    out = []
    for r in rows:
        ev = r["record"]["check"]
        off = {p: max(abs(q[f"{p}_minus_3d_rel"]) for q in ev["points"]) for p in ("stress", "strain")}
        out.append(f"- `{r['label']}` ({ev['boundary_conditions_3d']}): plane stress within {100 * off['stress']:.2f} %, "
                   f"plane strain within {100 * off['strain']:.2f} % of the 3D ring; the job uses plane "
                   f"{r['record']['used']} ({r['record']['why']}).")
    return out


def _cost_lines(jobs: list[dict]) -> list[str]:
    lines = ["| run | whole job (s) | target (s) | met | load average (start → end) | stages (s) | plane used |",
             "|---|---|---|---|---|---|---|"]
    for j in jobs:
        st = ", ".join(f"{s['stage']} {s['wall_s']:.1f}" for s in j["stages"])
        lines.append(f"| `bearing` straight{' ' + j['extra'] if j['extra'] else ''} | {j['wall_s']:.1f} | "
                     f"{TARGET_S:g} | {'yes' if j['wall_s'] <= TARGET_S else 'NO'} | {j['load'][0]:.2f} → "
                     f"{j['load'][1]:.2f} | {st} | {j['plane']['used']} ({j['plane']['why']}) |")
    return lines


def report(rows: list[dict], jobs: list[dict], workers: int) -> str:
    from fem_reference.plane_check import RULE
    lines = ["# Plane stress or strain: the bearing job's choice by the 3D ring", "",
             "Generated by `benchmarks/bench_plane_choice.py --workers "
             f"{workers}` (one command; re-run it to replace these numbers). The 2D reference of a ring pair needs a "
             "plane assumption; `ringcontact bearing` decides it by the 3D ring (`fem_reference/plane_check.py`, the "
             "job's stage 0): the ring of revolution with the file's hold and drive and free end faces, at zero tilt, "
             "at two penetrations (the range's geometric middle and its top), on the three production levels with "
             "their Richardson error, against the 2D reference under plane stress and plane strain.", "",
             f"Rule: {RULE}. The job runs the check for a file left at `plane = \"auto\"` (the default) and for a "
             "file with a tilt range (its 3D levels are built anyway: the law it ships is then the 3D one); a plane "
             "stated in a straight-only file is used unchecked unless `--plane-check`. Here every file is checked "
             "(forced), in order, in one level cache empty at the start: `clamped` has the rings and holds of "
             "`clamped-stress` and reuses its 3D levels (its check time is the warm cost).", "",
             "Differences `100 (F_2D − F_3D) / F_3D`, signed; the 3D force with its error estimate.", "",
             *_choice_lines(rows), "",
             *_reading(rows), "",
             "## Cost (the newcomer's bearing, straight only, cold)", "",
             "Through `ringcontact bearing` in a child process, an empty output folder and level cache; 2 shared "
             "cores (above a load of 2 every time is inflated).", "", *_cost_lines(jobs), ""]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--data", type=Path, default=None, help="also keep the measured rows as JSON here")
    ap.add_argument("--from-data", type=Path, default=None, help="write the report from such a JSON, measuring nothing")
    args = ap.parse_args(argv)
    if args.from_data is not None:
        got = json.loads(args.from_data.read_text(encoding="utf-8"))
        args.out.write_text(report(got["rows"], got["jobs"], args.workers), encoding="utf-8")
        return 0
    from fem_reference.ring_scene import RING_SCENE_DIR, bundled

    ring = newcomer_ring()
    with tempfile.TemporaryDirectory(prefix="bench-plane-") as tmp:
        tmp = Path(tmp)
        files = {}
        for name in bundled():
            files[name] = tmp / f"{name}.toml"
            files[name].write_bytes(RING_SCENE_DIR.joinpath(f"{name}.toml").read_bytes())
        files["newcomer (issue 38)"] = tmp / "my-bearing.toml"
        files["newcomer (issue 38)"].write_text(ring, encoding="utf-8")
        straight = tmp / "straight.toml"
        straight.write_text(ring.replace("tilt_arcmin = [0, 2]", "tilt_arcmin = [0, 0]"), encoding="utf-8")
        jobs = [job(straight, tmp / f"job-{k}" / "out", tmp / f"job-{k}" / "cache", args.workers, *extra)
                for k, extra in enumerate([(), ("--no-plane-check",)])]
        rows = choices(files, args.workers, tmp / "cache")
    if args.data is not None:
        args.data.write_text(json.dumps({"rows": rows, "jobs": jobs}, indent=1), encoding="utf-8")
    args.out.write_text(report(rows, jobs, args.workers), encoding="utf-8")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
