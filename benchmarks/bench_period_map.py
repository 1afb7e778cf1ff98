"""The period map with its exact monodromy against production's run and a finite-difference monodromy.

Writes ``reports/published/perf-period-map.md`` (+ ``.csv``). Table 4 rotor at 10 500 rpm
(``paper-table4``, production scheme), started 20 revolutions after the linear start; one revolution of
``N`` steps (N = 256, 512, 1024), interleaved, ``--repeats`` times each, medians:

- **production**: :func:`rotor.dynamics.production.simulate_production` over the revolution (end state only);
- **map**: :func:`rotor.dynamics.period_map.period_map` without the Jacobian (every step recorded);
- **map + monodromy**: with the exact monodromy (:mod:`rotor.dynamics.period_map_kernels`);
- **FD monodromy**: central differences of the map, ``2 · 2 n_r`` maps (what shooting costs without it;
  N = 512 only; every step recorded to check the perturbed runs keep the switches in their steps).

Compilation is done before timing (:func:`rotor.dynamics.period_map.warm_up`). Load average at start and
end (shared machine). Run: ``.venv/bin/python benchmarks/bench_period_map.py [--repeats 15]`` (≈ 1 minute).
"""
from __future__ import annotations

import argparse
import math
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402
from rotor.dynamics.initial import linear_initial_state  # noqa: E402
from rotor.dynamics.period_map import period_map, period_map_setup, reduced_state, warm_up  # noqa: E402
from rotor.dynamics.production import simulate_production  # noqa: E402
from rotor.studies.steady_state import point_system  # noqa: E402

OUT = ROOT / "reports" / "published"
SPEED_RPM = 10500.0


def _timed(f) -> float:
    t0 = time.perf_counter()
    f()
    return time.perf_counter() - t0


def _fd(pm, x, t, n, modes, scale):
    """Central-difference monodromy, component j perturbed by 1e-8 ``scale[j]``; and how many of the
    perturbed runs met another sequence of face modes than the unperturbed one."""
    ref = period_map(pm, x, t, n, modes0=modes, jacobian=False, record_every=1).trajectory.modes
    cols, moved = [], 0
    for j in range(x.size):
        e = np.zeros_like(x)
        e[j] = 1e-8 * scale[j]
        a = period_map(pm, x + e, t, n, modes0=modes, jacobian=False, record_every=1)
        b = period_map(pm, x - e, t, n, modes0=modes, jacobian=False, record_every=1)
        moved += int(not np.array_equal(a.trajectory.modes, ref)) + int(not np.array_equal(b.trajectory.modes, ref))
        cols.append((a.state - b.state) / (2 * e[j]))
    return np.array(cols).T, moved


def case(n: int, repeats: int, with_fd: bool) -> dict:
    """Timings (s, medians) of one revolution of ``n`` steps, and what the revolution holds."""
    _, _, system = point_system("paper-table4", SPEED_RPM)
    dt = 2 * math.pi / system.omega_rad_s / n
    pm = period_map_setup(system, dt)
    r = period_map(pm, reduced_state(pm, *linear_initial_state(system)), 0.0, 20 * n, jacobian=False)
    x, t, modes = r.state, r.t, tuple(r.modes)
    q, v = pm.T @ x[:pm.nr], pm.T @ x[pm.nr:]
    tr = period_map(pm, x, t, n, modes0=modes, jacobian=False, record_every=1).trajectory
    scale = np.abs(reduced_state(pm, tr.q, tr.v)).max(axis=0)
    scale = np.maximum(scale, 1e-6 * scale.max())
    runs = {
        "production": lambda: simulate_production(pm.reduced, dt, n, q, v, t0=t, modes0=modes, record_every=n,
                                                  check_step=False, prepared=pm.prepared),
        "map": lambda: period_map(pm, x, t, n, modes0=modes, jacobian=False),
        "map_monodromy": lambda: period_map(pm, x, t, n, modes0=modes),
    }
    if with_fd:
        runs["fd_monodromy"] = lambda: _fd(pm, x, t, n, modes, scale)
    times = {k: [] for k in runs}
    for i in range(repeats):
        for k, f in runs.items():
            if k != "fd_monodromy" or i < max(3, repeats // 5):
                times[k].append(_timed(f))
    res = period_map(pm, x, t, n, modes0=modes)
    out = {"steps_per_rev": n, "n_reduced": pm.nr, "events": res.events,
           "largest_multiplier": float(np.abs(np.linalg.eigvals(res.monodromy)).max())}
    out.update({f"{k}_s": statistics.median(v) for k, v in times.items()})
    if with_fd:
        Mfd, out["fd_runs_switch_moved"] = _fd(pm, x, t, n, modes, scale)
        Ms, Mf = (m * scale[None, :] / scale[:, None] for m in (res.monodromy, Mfd))
        out["fd_vs_exact_max_rel"] = float(np.abs(Mf - Ms).max() / np.abs(Ms).max())
    return out


def report(rows: list[dict], load0, load1, repeats: int, compile_info: dict) -> str:
    """The markdown report."""
    lines = [
        "# Period map with its exact monodromy", "",
        "`benchmarks/bench_period_map.py`. Table 4 rotor at 10 500 rpm (`paper-table4`, production scheme), one "
        "revolution from a state 20 revolutions after the linear start. *production*: `simulate_production` "
        "(end state only); *map*: `period_map` without the Jacobian; *map + monodromy*: with the exact "
        "monodromy carried through the steps (`rotor/dynamics/period_map_kernels.py`); *FD monodromy*: central "
        f"differences of the map, 2·2n_r maps. Interleaved, {repeats} repeats (FD: fewer), medians, after "
        f"compilation (warm-up {compile_info['compile_s']:.2f} s, from cache: {compile_info['from_cache']}). "
        f"Load average at start {load0[0]:.2f}/{load0[1]:.2f}/{load0[2]:.2f}, at end "
        f"{load1[0]:.2f}/{load1[1]:.2f}/{load1[2]:.2f} (shared machine, 2 cores); {platform.machine()}, "
        f"Python {platform.python_version()}.", "",
        "| steps/rev | n_r | production (ms) | map (ms) | map + monodromy (ms) | (map + monodromy) / map | FD monodromy (ms) "
        "| FD / exact | stick/slip events | largest multiplier |",
        "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        fd = r.get("fd_monodromy_s")
        fd_ms = "" if fd is None else f"{fd * 1e3:.0f}"
        fd_ratio = "" if fd is None else f"{fd / r['map_monodromy_s']:.0f}×"
        lines.append(
            f"| {r['steps_per_rev']} | {r['n_reduced']} | {r['production_s'] * 1e3:.2f} | {r['map_s'] * 1e3:.2f} | "
            f"{r['map_monodromy_s'] * 1e3:.2f} | {r['map_monodromy_s'] / r['map_s']:.2f} | "
            f"{fd_ms} | {fd_ratio} | {r['events']} | "
            f"{r['largest_multiplier']:.4f} |")
    fdrow = next((r for r in rows if "fd_vs_exact_max_rel" in r), None)
    if fdrow is not None:
        lines += ["", f"At {fdrow['steps_per_rev']} steps the FD monodromy (perturbations 1e-8 of each "
                      "component's largest value along the revolution) differs from the exact one by "
                      f"{fdrow['fd_vs_exact_max_rel']:.1e} of its largest entry in those scaled coordinates, through "
                      f"the revolution's {fdrow['events']} stick/slip switches ({fdrow['fd_runs_switch_moved']} of "
                      f"the {4 * fdrow['n_reduced']} perturbed runs moved a switch to another step)."]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=15)
    args = ap.parse_args(argv)
    info = warm_up()
    load0 = os.getloadavg()
    rows = [case(n, args.repeats, n == 512) for n in (256, 512, 1024)]
    load1 = os.getloadavg()
    keys = list(rows[1].keys())
    csv = ",".join(keys) + "\n" + "\n".join(",".join(str(r.get(k, "")) for k in keys) for r in rows) + "\n"
    atomic_write_text(OUT / "perf-period-map.csv", csv)
    atomic_write_text(OUT / "perf-period-map.md", report(rows, load0, load1, args.repeats, info))
    print((OUT / "perf-period-map.md").read_text())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
