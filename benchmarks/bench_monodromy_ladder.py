"""The event steps' ladder of central differences evaluated level by level against the whole ladder.

Writes ``reports/published/perf-monodromy-ladder.md`` (+ ``.json``). Table 4 rotor (``paper-table4``) at 7 000,
9 000 and 12 000 rpm, 256 and 2 240 steps per revolution, production options (events located), one revolution of
:func:`rotor.dynamics.period_map.period_map` with its monodromy from the state 24 revolutions after
:func:`rotor.dynamics.initial.linear_initial_state` (the state of reports/cli/_budget.py's probe). Side by side,
interleaved, ``--repeats`` times, medians:

- **whole**: every event-step column differenced at every level of
  :data:`rotor.dynamics.period_map_events.LADDER` (``PROGRESSIVE`` False, the earlier route);
- **progressive**: the first levels for every column, then level by level only the columns whose best agreement
  is not yet within ``REFINE_TOL`` of their size (rotor/dynamics/period_map_events.py, ``_ladder``).

Also, per case and route, the single-step replays the ladder and its refinement ran (counted in a separate, untimed
pass), the error against central differences of the whole map (:mod:`rotor.dynamics.monodromy_check`, the
reference of benchmarks/bench_monodromy_random.py) and the two monodromies' distance from each other in the same
scaled norm. Run: ``nice .venv/bin/python benchmarks/bench_monodromy_ladder.py [--repeats 3]`` (a few minutes).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402
from rotor.dynamics import period_map_events as pme  # noqa: E402
from rotor.dynamics.initial import linear_initial_state  # noqa: E402
from rotor.dynamics.monodromy_check import central_differences, scaled_error, state_scales  # noqa: E402
from rotor.dynamics.period_map import period_map, period_map_setup, reduced_state, warm_up  # noqa: E402
from rotor.studies.steady_state import point_system  # noqa: E402

OUT = ROOT / "reports" / "published"
SPEEDS_RPM = (7000.0, 9000.0, 12000.0)
STEPS = (256, 2240)
TRANSIENT_REVS = 24
ROUTES = {"whole": False, "progressive": True}


def _with_route(progressive: bool, f):
    """``f()`` on the route, the contact steps differenced too (``EXACT_CONTACT`` False, as the ladder tests of
    tests/rotor/dynamics/test_period_map_events.py run it): production differentiates them exactly, which leaves 7 000
    rpm with no differenced step at all and nothing for the ladder to do."""
    old = pme.PROGRESSIVE, pme.EXACT_CONTACT
    pme.PROGRESSIVE, pme.EXACT_CONTACT = progressive, False
    try:
        return f()
    finally:
        pme.PROGRESSIVE, pme.EXACT_CONTACT = old


def _replays(progressive: bool, f) -> int:
    """The single-step replays of the ladders and refinements while ``f`` runs on the route."""
    count = [0]
    inner = pme._differences

    def counting(pm, start, modes, phi, t, scales, n_steps, hs, cols):
        count[0] += 2 * len(hs) * len(cols) * int(n_steps)
        return inner(pm, start, modes, phi, t, scales, n_steps, hs, cols)

    pme._differences = counting
    try:
        _with_route(progressive, f)
    finally:
        pme._differences = inner
    return count[0]


def case(rpm: float, steps: int, repeats: int) -> dict:
    """Timings (s, medians), replays and errors of both routes at one speed and step."""
    _, _, system = point_system("paper-table4", rpm)
    pm = period_map_setup(system, 2 * math.pi / system.omega_rad_s / steps)
    r = period_map(pm, reduced_state(pm, *linear_initial_state(system)), 0.0, TRANSIENT_REVS * steps, jacobian=False)
    one = lambda: period_map(pm, r.state, r.t, steps, modes0=r.modes)  # noqa: E731
    times = {k: [] for k in ROUTES}
    for _ in range(repeats):
        for k, prog in ROUTES.items():
            t0 = time.perf_counter()
            _with_route(prog, one)
            times[k].append(time.perf_counter() - t0)
    plain = period_map(pm, r.state, r.t, steps, modes0=r.modes, jacobian=False, record_every=1)
    s = state_scales(pm, plain.trajectory)
    ref, check = central_differences(pm, r.state, r.t, steps, r.modes, s)
    M = {k: _with_route(prog, one).monodromy for k, prog in ROUTES.items()}
    out = {"speed_rpm": rpm, "steps_per_rev": steps, "reference_convergence": scaled_error(ref, check, s),
           "routes_apart": scaled_error(M["progressive"], M["whole"], s)}
    for k, prog in ROUTES.items():
        out[f"{k}_s"] = statistics.median(times[k])
        out[f"{k}_times_s"] = times[k]
        out[f"{k}_replays"] = _replays(prog, one)
        out[f"{k}_error"] = scaled_error(M[k], ref, s)
        out[f"{k}_largest_multiplier"] = float(np.abs(np.linalg.eigvals(M[k])).max())
    return out


def report(rows: list[dict], load0, load1, repeats: int, commit: str) -> str:
    lines = ["# The event steps' ladder, level by level", "",
             f"`benchmarks/bench_monodromy_ladder.py` at commit {commit}. Table 4 rotor (`paper-table4`), production "
             f"options (events located), one revolution of the period map with its monodromy from the state "
             f"{TRANSIENT_REVS} revolutions after the linear start. *whole*: every event-step column differenced at "
             "all 7 levels of the ladder (the earlier route); *progressive*: 3 levels for every column, then level by "
             "level only the columns whose best agreement is not yet within REFINE_TOL of their size "
             "(rotor/dynamics/period_map_events.py, `_ladder`), the refinement's half levels the same way (`_refine`); "
             "the contact steps are differenced on both routes (`EXACT_CONTACT` False, as the ladder tests run it; "
             "production differentiates them exactly). "
             "Replays: single steps the ladders and refinements ran. "
             "Error: against the Richardson extrapolation of central differences of the whole map at 1e-7 and 2e-7 "
             "of each component's largest magnitude (rotor/dynamics/monodromy_check.py), in its scaled norm; "
             "*apart*: the two routes' monodromies from each other in that norm. Interleaved, "
             f"{repeats} repeats, medians (wall time). Load average at start {load0[0]:.2f}/{load0[1]:.2f}/"
             f"{load0[2]:.2f}, at end {load1[0]:.2f}/{load1[1]:.2f}/{load1[2]:.2f} (shared 2-core machine, other "
             f"jobs running); {platform.machine()}, Python {platform.python_version()}.", "",
             "| speed (rpm) | steps/rev | replays whole / progressive | error whole | error progressive | apart | "
             "reference convergence | largest multiplier whole / progressive |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['speed_rpm']:.0f} | {r['steps_per_rev']} | {r['whole_replays']} / "
                     f"{r['progressive_replays']} | {r['whole_error']:.1e} | {r['progressive_error']:.1e} | "
                     f"{r['routes_apart']:.1e} | {r['reference_convergence']:.1e} | "
                     f"{r['whole_largest_multiplier']:.6f} / {r['progressive_largest_multiplier']:.6f} |")
    lines += ["", "Wall time of one period map with its monodromy (medians):", "",
              "| speed (rpm) | steps/rev | whole (s) | progressive (s) | whole / progressive |", "|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['speed_rpm']:.0f} | {r['steps_per_rev']} | {r['whole_s']:.3f} | "
                     f"{r['progressive_s']:.3f} | {r['whole_s'] / r['progressive_s']:.2f}× |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", type=Path, default=OUT / "perf-monodromy-ladder.md")
    args = ap.parse_args(argv)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip() or "unknown"
    warm_up()
    load0 = os.getloadavg()
    rows = []
    for rpm in SPEEDS_RPM:
        for steps in STEPS:
            rows.append(case(rpm, steps, args.repeats))
            print(json.dumps({k: v for k, v in rows[-1].items() if not k.endswith("times_s")}), flush=True)
    load1 = os.getloadavg()
    text = report(rows, load0, load1, args.repeats, commit)
    atomic_write_text(args.out, text)
    atomic_write_text(args.out.with_suffix(".json"), json.dumps({"commit": commit, "load": [list(load0), list(load1)],
                                                                 "rows": rows}, indent=1) + "\n")
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
