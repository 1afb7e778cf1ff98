"""Branches through grazing on a seeded family of Jeffcott-ring rotor scenes nobody tuned, up and down.

Each rotor of :func:`rotor.periodic.jeffcott_scene.random_family` (a new seed each run unless ``--seed``,
printed) is written as a scene and followed by :func:`rotor.studies.orbit.branch` (what ``ringcontact branch``
runs) over :func:`rotor.studies.grazing_family.sweep_range`, both ways; each sweep is measured by
:func:`rotor.studies.grazing_family.check_branch` against the scheme-consistent closed form. Writes
reports/published/perf-grazing-family.md and .json (``--out``), or renders a run's JSON again (``--from-json``).
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import os
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402
from rotor.periodic.jeffcott_scene import random_family  # noqa: E402
from rotor.studies.grazing_family import check_branch, sweep_range  # noqa: E402

OUT = ROOT / "reports" / "published" / "perf-grazing-family.md"
#: the issue's bounds
EVENT_RTOL, DISTANCE_BOUND = 1e-3, 1e-6


def _passes(c: dict) -> bool:
    return (c["stop"] == "end reached" and c["restarts"] == 0 and len(c["expected"]) == 3
            and max(c["fold_errors"]) < EVENT_RTOL and c["middle_points"] >= 1
            and c["middle_unstable"] == c["middle_points"] and c["worst_distance"] < DISTANCE_BOUND)


def _events(pairs) -> str:
    return "; ".join(f"{k} {s:.3f}" for k, s in pairs) or "none"


def report(d: dict) -> str:
    rows = d["rows"]
    ok = sum(_passes(r["check"]) for r in rows)
    lines = [
        "# Branches through grazing on rotor scenes nobody tuned",
        "",
        f"`benchmarks/bench_grazing_family.py` at commit {d['commit']}, seed **{d['seed']}** ({d['count']} rotors of "
        "`rotor.periodic.jeffcott_scene.random_family`: a disk on a massless shaft, its ring loose in a 2 GPa "
        "conformal clearance against a sprung support node; random mass, shaft, damping, clearance, unbalance and "
        "support). Each is written as a scene and followed by `rotor.studies.orbit.branch` (what `ringcontact "
        "branch` runs) from 0.8 times its first grazing speed to past its jump-down fold, up and down. Expected: "
        "the exact discrete whirl of the scheme (warped closed form at the branch's steps per revolution). "
        f"Load average {d['load'][0][0]:.2f} at start, {d['load'][1][0]:.2f} at end; {d['machine']}.",
        "",
        f"Sweeps meeting every bound (each closed-form grazing, grazing fold and fold found within 0.1 %, every "
        f"middle-branch orbit unstable, every orbit within 1e-6 of the closed form, no restart, the end reached): "
        f"**{ok} of {len(rows)}**. Largest event error {max(max(r['check']['fold_errors']) for r in rows):.1e}, "
        f"largest orbit distance {max(r['check']['worst_distance'] for r in rows):.1e}.",
        "",
        "| rotor | range (rpm) | sweep | steps/rev | expected (rpm) | largest event error | middle branch "
        "(unstable/points) | worst orbit distance | restarts | stop | CPU s |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        c = r["check"]
        lines.append(f"| {r['rotor']} | {r['low_rpm']:.1f}-{r['high_rpm']:.1f} | {c['direction']} | "
                     f"{c['steps_per_rev']} | {_events(c['expected'])} | {max(c['fold_errors']):.1e} | "
                     f"{c['middle_unstable']}/{c['middle_points']} | {c['worst_distance']:.1e} | {c['restarts']} | "
                     f"{c['stop']} | {c['cpu_s']:.1f} |")
    lines += ["", "Orbit distance: the smaller of the relative speed distance at the orbit's radius and the relative "
              "radius distance at its speed, from the closed form of rotor/periodic/jeffcott_scene.py.", ""]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--count", type=int, default=10)
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--from-json", type=Path, default=None)
    a = ap.parse_args(argv)
    if a.from_json is not None:
        atomic_write_text(a.out, report(json.loads(a.from_json.read_text(encoding="utf-8"))))
        return 0
    seed = a.seed if a.seed is not None else int.from_bytes(os.urandom(4), "little")
    print(f"seed {seed}", flush=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    load0 = os.getloadavg()
    rows = []
    for i, rotor in enumerate(random_family(seed, a.count)):
        low, high = sweep_range(rotor)
        for direction in ("up", "down"):
            with tempfile.TemporaryDirectory() as tmp:
                c = dataclasses.asdict(check_branch(rotor, low, high, direction, tmp))
            rows.append({"rotor": i, "low_rpm": low, "high_rpm": high, "parameters": dataclasses.asdict(rotor),
                         "check": c})
            print(i, direction, c["stop"], c["restarts"], max(c["fold_errors"]), c["worst_distance"], flush=True)
    d = {"seed": seed, "count": a.count, "commit": commit, "load": [load0, os.getloadavg()],
         "machine": f"{platform.machine()}, Python {platform.python_version()}", "rows": rows}
    atomic_write_text(a.out.with_suffix(".json"), json.dumps(d, indent=1))
    atomic_write_text(a.out, report(d))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
