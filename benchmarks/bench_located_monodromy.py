"""The located period map's monodromy: held slow-slip steps carried analytically against differenced.

Writes ``reports/published/perf-located-monodromy.md`` (+ ``.json``). Table 4 rotor (``paper-table4``) at
8 400, 10 500 and 12 000 rpm, 512 steps per revolution, events located (the default), one revolution from the
state 60 revolutions after the linear start: the speeds and state of
tests/rotor/dynamics/test_period_map_events.py. Timed side by side, interleaved, ``--repeats`` times, medians:

- **map**: :func:`rotor.dynamics.period_map.period_map` without the monodromy (every step recorded);
- **carried**: the located monodromy (:func:`rotor.dynamics.period_map_events.located_monodromy`) as the map
  computes it: the held steps carried analytically, the split steps differenced;
- **differenced**: the same with every held step differenced too (``carry_held=False``, the earlier route).

Accuracy of each against central differences of the whole located map (each state component perturbed by 1e-7
and 2e-7 of its largest magnitude over the revolution, Richardson-extrapolated; the test's reference), in the
test's scaled norm. Run: ``nice .venv/bin/python benchmarks/bench_located_monodromy.py [--repeats 5]`` (about 3
minutes).
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
from rotor.dynamics.initial import linear_initial_state  # noqa: E402
from rotor.dynamics.period_map import period_map, period_map_setup, reduced_state, warm_up  # noqa: E402
from rotor.dynamics.period_map_events import event_steps, located_monodromy  # noqa: E402
from rotor.dynamics.system import NewmarkOptions  # noqa: E402
from rotor.studies.steady_state import point_system  # noqa: E402

OUT = ROOT / "reports" / "published"
SPEEDS_RPM = (8400.0, 10500.0, 12000.0)
STEPS = 512


def _reference(pm, r, s) -> np.ndarray:
    """Richardson extrapolation of central differences of the whole located map at 1e-7 and 2e-7 of ``s``."""
    def fd(rel):
        M = np.zeros((r.state.size, r.state.size))
        for j in range(r.state.size):
            e = np.zeros_like(r.state)
            e[j] = rel * s[j]
            a, b = (period_map(pm, r.state + d, r.t, STEPS, modes0=r.modes, jacobian=False).state for d in (e, -e))
            M[:, j] = (a - b) / (2 * e[j])
        return M
    return (4 * fd(1e-7) - fd(2e-7)) / 3


def case(rpm: float, repeats: int) -> dict:
    """Timings (s, medians) and accuracies at one speed."""
    _, _, system = point_system("paper-table4", rpm)
    pm = period_map_setup(system, 2 * math.pi / system.omega_rad_s / STEPS,
                          NewmarkOptions(tol=1e-13, locate_events=True))
    r = period_map(pm, reduced_state(pm, *linear_initial_state(system)), 0.0, 60 * STEPS, jacobian=False)
    res = period_map(pm, r.state, r.t, STEPS, modes0=r.modes, jacobian=False, record_every=1)
    tr = res.trajectory
    rec_p, rec_v = tr.q @ pm.T, tr.v @ pm.T
    x = reduced_state(pm, tr.q, tr.v)
    s = np.abs(x).max(axis=0)
    for part in (slice(0, pm.nr), slice(pm.nr, 2 * pm.nr)):
        s[part] = np.maximum(s[part], 1e-6 * s[part].max())
    runs = {"map": lambda: period_map(pm, r.state, r.t, STEPS, modes0=r.modes, jacobian=False, record_every=1),
            "carried": lambda: located_monodromy(pm, tr, rec_p, rec_v),
            "differenced": lambda: located_monodromy(pm, tr, rec_p, rec_v, carry_held=False)}
    times = {k: [] for k in runs}
    for _ in range(repeats):
        for k, f in runs.items():
            t0 = time.perf_counter()
            f()
            times[k].append(time.perf_counter() - t0)
    ref = _reference(pm, r, s)

    def err(M):
        return float(np.abs((M - ref) * s[None, :] / s[:, None]).max() / np.abs(ref * s[None, :] / s[:, None]).max())

    out = {"speed_rpm": rpm, "candidate_steps": len(event_steps(pm, tr))}
    for k in ("carried", "differenced"):
        M = located_monodromy(pm, tr, rec_p, rec_v, carry_held=(k == "carried"))[0]
        out[f"{k}_error"] = err(M)
        out[f"{k}_largest_multiplier"] = float(np.abs(np.linalg.eigvals(M)).max())
    out.update({f"{k}_s": statistics.median(v) for k, v in times.items()})
    return out


def report(rows: list[dict], load0, load1, repeats: int, commit: str) -> str:
    lines = ["# The located monodromy: held steps carried analytically", "",
             f"`benchmarks/bench_located_monodromy.py` at commit {commit}. Table 4 rotor (`paper-table4`), "
             f"{STEPS} steps per revolution, events located, one revolution from the state 60 revolutions after the "
             "linear start (the speeds and state of tests/rotor/dynamics/test_period_map_events.py). *map*: the "
             "located map, every step recorded, no monodromy; *carried*: its monodromy with the held slow-slip "
             "steps carried analytically (rotor/dynamics/period_map_events.py, \"Held steps, carried\"); "
             "*differenced*: every held step differenced too, the earlier route. Error: against the Richardson "
             "extrapolation of central differences of the whole located map at 1e-7 and 2e-7, scaled as the test "
             f"scales it. Interleaved, {repeats} repeats, medians. Load average at start "
             f"{load0[0]:.2f}/{load0[1]:.2f}/{load0[2]:.2f}, at end {load1[0]:.2f}/{load1[1]:.2f}/{load1[2]:.2f} "
             f"(shared 2-core machine, other jobs running); {platform.machine()}, Python "
             f"{platform.python_version()}.", "",
             "| speed (rpm) | candidate steps | map (s) | carried (s) | differenced (s) | differenced / carried "
             "| error carried | error differenced | largest multiplier carried / differenced |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['speed_rpm']:.0f} | {r['candidate_steps']} | {r['map_s']:.3f} | {r['carried_s']:.3f} | "
                     f"{r['differenced_s']:.3f} | {r['differenced_s'] / r['carried_s']:.1f}× | "
                     f"{r['carried_error']:.1e} | {r['differenced_error']:.1e} | "
                     f"{r['carried_largest_multiplier']:.6f} / {r['differenced_largest_multiplier']:.6f} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args(argv)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip() or "unknown"
    warm_up()
    load0 = os.getloadavg()
    rows = [case(rpm, args.repeats) for rpm in SPEEDS_RPM]
    load1 = os.getloadavg()
    OUT.mkdir(parents=True, exist_ok=True)
    atomic_write_text(OUT / "perf-located-monodromy.md", report(rows, load0, load1, args.repeats, commit))
    atomic_write_text(OUT / "perf-located-monodromy.json", json.dumps(rows, indent=1) + "\n")
    print(report(rows, load0, load1, args.repeats, commit))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
