"""Continuation of the Table 4 rotor across stick/slip switches: before and after, one run.

Writes ``reports/published/perf-branch-switches.md`` (+ ``.json``). The Table 4 rotor (``paper-table4``,
2 240 steps per revolution, the step :func:`rotor.studies.orbit.branch` picks) is followed in speed from
600 rpm towards 18 000 rpm by :func:`rotor.studies.orbit.branch` (one ``ringcontact branch paper-table4
--rpm-start 600 --rpm-end 18000``), twice, in two processes side by side:

* *before*: ``ContinuationOptions(pass_switches=False, follow_scales=False)``, the corrector alone with the
  start orbit's scales (what the branch did before :mod:`rotor.periodic.continuation` passed switches);
* *after*: the defaults (a corrector that stops contracting is given up, restarts past the switch by
  shooting, scales following the orbit).

Each run: points, highest speed reached, why it stopped, restarts (by kind), wall time. The *after* branch is
then verified on a sample of ``--verify`` points: at each point's speed a fresh flow
(:func:`rotor.periodic.period_flow.make_flow`) maps the point's own state over its period
(:func:`rotor.periodic.period_flow.advance`, no derivative): the residual ``max |Φ(x) − x|/s`` relative to the
orbit's own peak-to-peak scale ``s`` (:func:`rotor.periodic.shooting.orbit_scales`, never below the start's)
and an independent :func:`rotor.periodic.shooting.shoot` from that state (converged, Newton iterations,
distance of its orbit from the point).

Load average at start and end (shared 2-core machine). Run:
``nice .venv/bin/python benchmarks/bench_branch_switches.py [--max-points 400] [--verify 16]``.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402

OUT = ROOT / "reports" / "published"
SCENE, RPM_START, RPM_END = "paper-table4", 600.0, 18000.0
TO_RPM = 30.0 / math.pi


def run_branch(mode: str, max_points: int, n_verify: int) -> dict:
    """One branch from 600 rpm (``mode`` "before" or "after") with its summary and, for "after", the sample."""
    from rotor.dynamics.period_map import warm_up
    from rotor.periodic.continuation import ContinuationOptions
    from rotor.studies.orbit import branch

    warm_up()
    plain = mode == "before"
    opts = ContinuationOptions(max_points=max_points, pass_switches=not plain, follow_scales=not plain)
    t0 = time.perf_counter()
    res = branch(SCENE, RPM_START, RPM_END, options=opts, amplitudes=False)
    wall = time.perf_counter() - t0
    br = res.branch
    rpm = [p.parameter * TO_RPM for p in br.points]
    kinds = [int(p.restarted) for p in br.points]
    out = {"mode": mode, "points": len(br.points), "reached_rpm": max(rpm) if rpm else None, "stop": br.stop,
           "wall_s": wall, "restarts": {"secant": kinds.count(1), "transient": kinds.count(2), "cold": kinds.count(3)},
           "bifurcations": [{"kind": b.kind, "speed_rpm": b.parameter * TO_RPM} for b in br.bifurcations],
           "speeds_rpm": rpm}
    if not plain and n_verify:
        out["verified"] = verify(res, n_verify)
    return out


def verify(res, n_verify: int) -> list[dict]:
    """Independent check of ``n_verify`` points spread over the branch (see the module docstring)."""
    from rotor.periodic.period_flow import advance, make_flow
    from rotor.periodic.shooting import ShootingOptions, orbit_scales, record_reduced, shoot
    from rotor.studies.steady_state import point_system

    pts = res.branch.points
    n, modes, floor = res.start.steps_per_rev, res.start.shooting.modes, res.start.shooting.scales
    steps = n * res.branch.period_revs
    rows = []
    for i in sorted(set(np.linspace(0, len(pts) - 1, min(n_verify, len(pts))).round().astype(int))):
        p = pts[i]
        flow = make_flow(point_system(SCENE, p.parameter * TO_RPM)[2], 2.0 * math.pi / (p.parameter * n))
        pv, vv, _ = record_reduced(flow, p.state, 0.0, steps, modes, max(1, steps // 256))
        s = np.maximum(orbit_scales(flow, pv, vv), floor)
        r = advance(flow, p.state, 0.0, steps, modes, jacobian=False)
        sh = shoot(flow, p.state, t0_s=0.0, steps_per_rev=n, period_revs=res.branch.period_revs, modes0=modes,
                   scales=s, options=ShootingOptions())
        rows.append({"index": int(i), "speed_rpm": p.parameter * TO_RPM, "restarted": int(p.restarted),
                     "residual": float(np.max(np.abs(r.state - p.state) / s)), "events": int(r.events),
                     "shoot_converged": bool(sh.converged), "shoot_iterations": int(sh.newton_iterations),
                     "shoot_distance": float(np.max(np.abs(sh.state - p.state) / s))})
    return rows


def report(runs: dict, load: list, max_points: int) -> str:
    b, a = runs["before"], runs["after"]
    lines = ["# Continuation across stick/slip switches (Table 4 rotor), before and after", "",
             f"`benchmarks/bench_branch_switches.py --max-points {max_points}`: one `ringcontact branch paper-table4 "
             "--rpm-start 600 --rpm-end 18000` twice, side by side in two processes (2 240 steps per revolution). "
             f"Load average at start {load[0][0]:.2f}/{load[0][1]:.2f}/{load[0][2]:.2f}, at end "
             f"{load[1][0]:.2f}/{load[1][1]:.2f}/{load[1][2]:.2f} (shared 2-core machine, other jobs running).", "",
             "| | before (corrector alone, start scales) | after (restarts past switches, scales follow) |",
             "|---|---|---|"]
    for key, fmt in (("points", "{}"), ("reached_rpm", "{:.0f}"), ("stop", "{}"), ("wall_s", "{:.0f}")):
        lines.append(f"| {key.replace('_', ' ')} | {fmt.format(b[key])} | {fmt.format(a[key])} |")
    for run in (b, a):
        run["restart_text"] = ", ".join(f"{k} {v}" for k, v in run["restarts"].items())
        run["bif_text"] = "; ".join(f"{x['kind']} {x['speed_rpm']:.0f}" for x in run["bifurcations"]) or "none"
    lines += [f"| restarts (secant, transient, cold) | {b['restart_text']} | {a['restart_text']} |",
              f"| bifurcations | {b['bif_text']} | {a['bif_text']} |", "",
              "Verification of the *after* branch: each sampled point's own state mapped over its period with a fresh "
              "flow (residual relative to the orbit's own peak-to-peak scale, never below the start's), and an "
              "independent shooting from it.", "",
              "| point | speed (rpm) | restarted | residual | face mode changes | shooting converged | iterations | "
              "distance |", "|---|---|---|---|---|---|---|---|"]
    for r in a.get("verified", []):
        lines.append(f"| {r['index']} | {r['speed_rpm']:.1f} | {r['restarted']} | {r['residual']:.1e} | {r['events']} | "
                     f"{r['shoot_converged']} | {r['shoot_iterations']} | {r['shoot_distance']:.1e} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-points", type=int, default=400)
    ap.add_argument("--verify", type=int, default=16)
    args = ap.parse_args(argv)
    load0 = os.getloadavg()
    with ProcessPoolExecutor(2) as pool:
        futs = {m: pool.submit(run_branch, m, args.max_points, args.verify) for m in ("before", "after")}
        runs = {m: f.result() for m, f in futs.items()}
    load1 = os.getloadavg()
    atomic_write_text(OUT / "perf-branch-switches.json", json.dumps(runs, indent=1) + "\n")
    atomic_write_text(OUT / "perf-branch-switches.md", report(runs, [load0, load1], args.max_points))
    print(report(runs, [load0, load1], args.max_points))
    return 0


if __name__ == "__main__":
    sys.exit(main())
