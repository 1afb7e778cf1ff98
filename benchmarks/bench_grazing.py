"""Continuation through a grazing fold: the conformal Jeffcott rotor, plain continuation against the grazing segments.

The rotor is the verification rotor of :mod:`rotor.periodic.jeffcott` in a frictionless ring with the conformal law
(finite contact stiffness at zero penetration) and ``e = 0.3 δ0``: its response curve has a grazing at 279.6 rad/s,
a smooth jump-down fold near 446 rad/s and a grazing fold (the speed turns at a corner) near 374.3 rad/s, all in
closed form (:func:`rotor.periodic.jeffcott.closed_form_grazing`, :func:`~rotor.periodic.jeffcott.closed_form_folds`,
with the trapezoidal rule's warped frequency). Each sweep (500 → 200 rad/s and back) is run three ways:

* ``plain``: :func:`rotor.periodic.continuation.continue_branch` without restarts (the corrector alone);
* ``restarts``: the same with its restarts past switches (``pass_switches``, the default of ``ringcontact branch``);
* ``grazing``: :func:`rotor.periodic.grazing.continue_through_grazing`.

Reported per sweep and way: why it stopped, points, restarts, the bifurcations and their distance to the closed
form, the largest distance of a point from the warped closed-form curve (speed at the point's radius), whether
the middle branch was reached (unstable points in contact), and the wall time (median of ``--repeat`` runs, one
process, numba compiled beforehand). Load average at start and end (shared 2-core machine). Writes
``reports/published/perf-grazing.md``. Run: ``nice .venv/bin/python benchmarks/bench_grazing.py [--repeat 3]``.
"""
from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402
from rotor.periodic.continuation import ContinuationOptions, continue_branch, speed_problem  # noqa: E402
from rotor.periodic.grazing import continue_through_grazing  # noqa: E402
from rotor.periodic.jeffcott import (JeffcottParams, closed_form_folds, closed_form_grazing,  # noqa: E402
                                     closed_form_speeds, jeffcott_system)

OUT = ROOT / "reports" / "published"
P = JeffcottParams(law="conformal", eccentricity_m=3e-6)
N = 64
SCALES = np.concatenate([np.full(4, 1e-5), np.full(4, 0.005)])
SWEEPS = {"down": (500.0, 200.0), "up": (200.0, 500.0)}


def _run(way: str, lo_hi: tuple):
    pb = speed_problem(lambda w: jeffcott_system(P, w), N, modes0=(0, 0))
    opts = ContinuationOptions(ds=0.1, ds_max=0.4, pass_switches=(way != "plain"))
    follow = continue_through_grazing if way == "grazing" else continue_branch
    t0 = time.perf_counter()
    br = follow(pb, np.zeros(8), *lo_hi, scales=SCALES, lam_scale=30.0, options=opts)
    return br, time.perf_counter() - t0


def _summary(br, walls: list, closed: dict) -> dict:
    worst = 0.0
    for p in br.points:
        s = closed_form_speeds(P, math.hypot(*p.state[:2]), N)
        worst = max(worst, float(np.min(np.abs(s - p.parameter)) / p.parameter) if len(s) else math.inf)
    middle = [p for p in br.points if math.hypot(*p.state[:2]) > P.clearance_m * (1 + 1e-9) and not p.floquet.stable]
    bifs = [(b.kind, b.parameter, abs(b.parameter / closed[b.kind] - 1) if b.kind in closed else math.nan)
            for b in br.bifurcations]
    return {"stop": br.stop, "points": len(br.points), "restarts": br.restarts, "last_rad_s": br.points[-1].parameter,
            "bifurcations": bifs, "worst_curve": worst, "unstable_in_contact": len(middle),
            "wall_s": statistics.median(walls), "walls": walls}


def report(rows: dict, loads: list, closed: dict, repeat: int) -> str:
    lines = ["# Continuation through a grazing fold (conformal Jeffcott rotor)", "",
             f"Made by `benchmarks/bench_grazing.py` (median of {repeat} runs per row, one process, numba compiled "
             f"beforehand); load average {loads[0][0]:.2f} at start, {loads[1][0]:.2f} at the end (shared 2-core "
             "machine). Rotor: `JeffcottParams(law=\"conformal\", eccentricity_m=3e-6)`, "
             f"{N} steps per revolution. Closed form (warped): grazing {closed['grazing']:.6f} rad/s, grazing fold "
             f"{closed['grazing_fold']:.6f} rad/s, fold {closed['fold']:.6f} rad/s.", "",
             "| sweep | way | stop | points | restarts | last rad/s | bifurcations (rad/s, rel. to closed form) "
             "| worst point vs curve | unstable in contact | wall s (median) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for (sweep, way), r in rows.items():
        bif = "; ".join(f"{k} {w:.6f} ({e:.1e})" for k, w, e in r["bifurcations"]) or "none"
        lines.append(f"| {sweep} | {way} | {r['stop']} | {r['points']} | {r['restarts']} | {r['last_rad_s']:.4f} | "
                     f"{bif} | {r['worst_curve']:.1e} | {r['unstable_in_contact']} | {r['wall_s']:.2f} |")
    lines += ["", "Columns: *unstable in contact* counts orbits in contact with a multiplier outside the unit circle "
              "(the middle branch); *worst point vs curve* is the largest relative speed distance of an orbit from the "
              "warped closed form at its radius. Reading (the run of this commit): the corrector alone stops at the "
              "grazing fold in both directions (\"step below ds_min\"); with the restarts of `ringcontact branch` the "
              "down sweep jumps from the corner onto the stable contact branch, never reaching the middle branch nor "
              "reporting the corner, and the up sweep, restarted at the corner, turns back beyond its start with a "
              "branch point that is not one (the issue's observations); the grazing segments follow the whole curve, "
              "corner and middle branch included, with no restart, at "
              + " and ".join(f"{rows[(d, 'grazing')]['wall_s'] / rows[(d, 'plain')]['wall_s']:.1f} times the plain "
                             f"corrector's wall time {d}" for d in ("down", "up"))
              + " (the plain corrector stops at the corner; the grazing segments go on over the whole curve, and the "
              "penetration watch records each predictor's period).", ""]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    closed = {k: w for w, k in closed_form_grazing(P, N)}
    closed["fold"] = closed_form_folds(P, N, r_max_factor=10.0)[0][0]
    _run("plain", (300.0, 301.0))      # compile (or load) the kernels outside the timings
    loads = [os.getloadavg()]
    rows = {}
    for sweep, lo_hi in SWEEPS.items():
        for way in ("plain", "restarts", "grazing"):
            walls = []
            for _ in range(args.repeat):
                br, wall = _run(way, lo_hi)
                walls.append(round(wall, 3))
            rows[(sweep, way)] = _summary(br, walls, closed)
    loads.append(os.getloadavg())
    text = report(rows, loads, closed, args.repeat)
    atomic_write_text(OUT / "perf-grazing.md", text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
