"""The study-bifurcation report: the Table 4 rotor's periodic orbits continued in speed, 600-18 000 rpm, in segments.

Each segment is :func:`rotor.studies.orbit.branch` (what ``ringcontact branch paper-table4 --rpm-start A
--rpm-end 18000 --max-points 80`` computes, the same JSON with each segment's ``restarts`` and each point's
``restarted``); the first starts at 600 rpm, each next one 300 rpm past the highest speed the previous one
reached (the procedure of the published report). Writes ``reports/published/study-bifurcation.{md,json,png,svg}``
through :func:`reports.bifurcation.publish`, and the segments' JSON into ``--segments-dir``.

Run: ``nice .venv/bin/python benchmarks/study_bifurcation.py [--max-points 80] [--segments-dir DIR]``.
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

SCENE, RPM_START, RPM_END, GAP_RPM = "paper-table4", 600.0, 18000.0, 300.0


def segment(rpm_start: float, max_points: int) -> dict:
    """One segment as the ``ringcontact branch --json`` output (with ``restarts``, points by each restart kind)."""
    from rotor.periodic.continuation import ContinuationOptions
    from rotor.studies.orbit import branch

    t0 = time.perf_counter()
    res = branch(SCENE, rpm_start, RPM_END, options=ContinuationOptions(max_points=max_points))
    d = {"scene": SCENE, "rpm_start": rpm_start, "rpm_end": RPM_END, "period_revs": res.start.period_revs,
         "steps_per_rev": res.start.steps_per_rev, **res.as_dict(), "wall_s": round(time.perf_counter() - t0, 3)}
    return d


def main(argv=None) -> int:
    from reports.bifurcation import publish

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-points", type=int, default=80)
    ap.add_argument("--segments-dir", type=Path, default=Path("bifurcation-segments"))
    args = ap.parse_args(argv)
    args.segments_dir.mkdir(parents=True, exist_ok=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout
    load0, t0 = os.getloadavg(), time.perf_counter()
    segments, start = [], RPM_START
    while start < RPM_END:
        seg = segment(start, args.max_points)
        segments.append(seg)
        (args.segments_dir / f"seg-{start:.0f}.json").write_text(json.dumps(seg) + "\n")
        reached = max((p["speed_rpm"] for p in seg["points"]), default=start)
        print(f"segment {start:.0f} rpm: {len(seg['points'])} orbits to {reached:.0f} rpm, {seg['stop']}, "
              f"restarts {seg['restarts']}, {seg['wall_s']:.0f} s", flush=True)
        if seg["stop"] == "end reached":
            break
        start = max(start, reached) + GAP_RPM
    load1, wall = os.getloadavg(), time.perf_counter() - t0
    commands = [f"# computed at commit {commit.strip()}, {time.strftime('%H:%M UTC', time.gmtime())}, "
                f"{len(segments)} segments, {sum(len(s['points']) for s in segments)} orbits, {wall:.0f} s wall, load "
                f"{load0[0]:.2f} at start, {load1[0]:.2f} at end",
                f"nice .venv/bin/python benchmarks/study_bifurcation.py --max-points {args.max_points}",
                "# = ringcontact branch paper-table4 --rpm-start A --rpm-end 18000 "
                f"--max-points {args.max_points} for A = "
                + ", ".join(f"{s['rpm_start']:.0f}" for s in segments)
                + " (each next A 300 rpm past the highest speed the segment before reached)"]
    reading = (ROOT / "reports" / "notes" / "study-bifurcation-reading.md").read_text(encoding="utf-8")
    for f in publish(segments, ROOT / "reports" / "published", commands=commands, reading=reading):
        print("wrote", f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
