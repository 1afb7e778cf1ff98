"""The study-bifurcation report: the Table 4 rotor's periodic orbits continued in speed, 600-18 000 rpm, in one run.

One :func:`rotor.studies.orbit.branch` from 600 rpm to 18 000 rpm (what ``ringcontact branch paper-table4
--rpm-start 600 --rpm-end 18000 --json`` computes: each point's ``restarted`` and ``skipped_rpm``, the
``corrector_failures``), no hand-started segment, with the period maps' friction events located inside the
step (``--locate-events on``). ``--branch-json PATH`` draws from a branch already computed (the file
``benchmarks/bench_branch_switches.py --branch-json PATH`` writes, the run whose wall time
``perf-branch-switches.md`` reports) instead of computing it again. Writes
``reports/published/study-bifurcation.{md,json,png,svg}`` through :func:`reports.bifurcation.publish`.

Run: ``nice .venv/bin/python benchmarks/study_bifurcation.py [--max-points 1500] [--branch-json PATH]``.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

SCENE, RPM_START, RPM_END = "paper-table4", 600.0, 18000.0


def compute(max_points: int) -> dict:
    """The branch as the ``ringcontact branch --json`` output."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_branch_switches import run_branch

    return run_branch(max_points, True, 250.0)[1]


def main(argv=None) -> int:
    from reports.bifurcation import publish

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-points", type=int, default=1500)
    ap.add_argument("--branch-json", type=Path, default=None)
    args = ap.parse_args(argv)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout
    load0, t0 = os.getloadavg(), time.perf_counter()
    if args.branch_json is not None:
        d = json.loads(args.branch_json.read_text(encoding="utf-8"))
        how = f"drawn from {args.branch_json.name} (benchmarks/bench_branch_switches.py --branch-json)"
        bench = ROOT / "reports" / "published" / "perf-branch-switches.json"     # the run's own commit, if it wrote it
        if bench.exists():
            commit = json.loads(bench.read_text(encoding="utf-8")).get("commit", commit)
    else:
        d = compute(args.max_points)
        load1 = os.getloadavg()
        how = (f"{time.perf_counter() - t0:.0f} s wall, load {load0[0]:.2f} at start, {load1[0]:.2f} at end")
    reached = max((p["speed_rpm"] for p in d["points"]), default=RPM_START)
    commands = [f"# computed at commit {commit.strip()}, {time.strftime('%H:%M UTC', time.gmtime())}: one branch, "
                f"{len(d['points'])} orbits, {RPM_START:.0f} to {reached:.0f} rpm ({d['stop']}), {how}",
                f"nice .venv/bin/python benchmarks/bench_branch_switches.py --branch-json BRANCH.json && "
                f"nice .venv/bin/python benchmarks/study_bifurcation.py --branch-json BRANCH.json",
                f"# = ringcontact branch {SCENE} --rpm-start {RPM_START:.0f} --rpm-end {RPM_END:.0f} "
                f"--max-points {args.max_points} --turn-back-rpm 250 --json (friction events and contact onsets and losses "
                f"located inside the step)"]
    reading = (ROOT / "reports" / "notes" / "study-bifurcation-reading.md").read_text(encoding="utf-8")
    for f in publish([d], ROOT / "reports" / "published", commands=commands, reading=reading):
        print("wrote", f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
