"""Shooting beside the transient: one Table 4 operating point (Dai et al. 2025) at 10 500 rpm, 256 steps/rev.

Writes ``perf-shooting.md`` (+ ``.csv``) into ``--out`` (default ``reports/published``). In one process, after
compiling every kernel (step loop, period-map sensitivity pass), ``--repeats`` times each, alternating:

- **transient**: :func:`rotor.studies.steady_state.steady_state` from the linear periodic solution (what
  ``simulate --steady`` runs to detect the steady state; its spectrum record included);
- **shooting, cold**: :func:`rotor.studies.orbit.orbit` from the same linear start (transient rounds of 16,
  32, 64 … revolutions until Newton converges; Floquet multipliers and 1X-5X amplitudes included);
- **shooting, warm**: ``orbit`` started from the orbit at 10 400 rpm (what a cascade or a continuation
  does from its previous speed), 2 transient revolutions before Newton;
- **shooting from the transient's end**: ``orbit`` started from the transient's final state (the check that
  the two methods give the same orbit, ``tests/rotor/studies/test_orbit.py``).

Medians, with the load average at start and end (shared machine). Run:
``.venv/bin/python benchmarks/bench_shooting.py [--repeats 3] [--out DIR]`` (about half a minute).
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402


def measure(repeats: int) -> tuple[dict, dict]:
    """Wall times (s) per case, and the counts of the last repeat (revolutions, Newton iterations)."""
    from rotor.dynamics.initial import linear_initial_state
    from rotor.dynamics.production import warm_up
    from rotor.studies.orbit import orbit
    from rotor.studies.shooting import ShootingOptions
    from rotor.studies.steady_state import point_system, steady_state

    warm_up()
    orbit("paper-table4", 9000.0)                         # compiles the period map's kernels
    _, model, system = point_system("paper-table4", 10500.0)
    q0, v0 = linear_initial_state(system, 0.0)
    prev = orbit("paper-table4", 10400.0)
    short = ShootingOptions(transient_revs=2)
    times = {"transient": [], "shooting, cold": [], "shooting, warm": [], "shooting from the transient's end": []}
    counts = {}
    for _ in range(repeats):
        t = time.perf_counter()
        ss = steady_state(system, model, q0=q0, v0=v0)
        times["transient"].append(time.perf_counter() - t)
        counts["transient"] = f"{ss.transient_revs + ss.revolutions} revolutions"
        for name, kw in (("shooting, cold", {}), ("shooting, warm", {"start": (prev.q_m, prev.v_m_s), "options": short}),
                         ("shooting from the transient's end", {"start": (ss.q_end, ss.v_end), "options": short})):
            t = time.perf_counter()
            o = orbit("paper-table4", 10500.0, **kw)
            times[name].append(time.perf_counter() - t)
            counts[name] = (f"{o.transient_revs} revolutions + {o.newton_iterations} Newton iterations, "
                            f"residual {o.residual:.1e}, converged {o.converged}")
    return times, counts


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", type=Path, default=ROOT / "reports" / "published")
    args = ap.parse_args(argv)
    load0 = os.getloadavg()
    times, counts = measure(args.repeats)
    load1 = os.getloadavg()
    med = {k: statistics.median(v) for k, v in times.items()}
    base = med["transient"]
    lines = ["# Shooting beside the transient: Table 4 at 10 500 rpm", "",
             f"Load average (1, 5, 15 min) at start {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f}, "
             f"at end {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}; medians of {args.repeats}; "
             "256 steps per revolution; kernels compiled before timing.", "",
             "| case | median wall (s) | transient / case | work (last repeat) |", "|---|---|---|---|"]
    for k, v in med.items():
        lines.append(f"| {k} | {v:.3f} | {base / v:.1f} | {counts[k]} |")
    lines += ["", "Produced by `benchmarks/bench_shooting.py`."]
    args.out.mkdir(parents=True, exist_ok=True)
    atomic_write_text(args.out / "perf-shooting.md", "\n".join(lines) + "\n")
    csv = ["case,median_wall_s,repeats"] + [f"{k},{v:.6f},{args.repeats}" for k, v in med.items()]
    atomic_write_text(args.out / "perf-shooting.csv", "\n".join(csv) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
