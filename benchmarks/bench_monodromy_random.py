"""The located monodromy at periodic orbits of speeds nobody chose: seeded random speeds, central differences of
the same map as the reference.

Writes ``reports/published/perf-monodromy-random.md`` (+ ``.json``). For each of ``--speeds`` speeds drawn
uniformly over ``--rpm-min`` .. ``--rpm-max`` (seed printed, a new one each run unless ``--seed`` is given):

1. the periodic orbit as ``ringcontact orbit`` finds it (:func:`rotor.studies.orbit.orbit`, production options,
   the scene's default steps per revolution, events located);
2. the monodromy of its period map (:func:`rotor.dynamics.period_map.period_map`, the located monodromy of
   rotor/dynamics/period_map_events.py);
3. the reference: central differences of the same map, every state component perturbed by ``h`` of its largest
   magnitude over the period, Richardson-extrapolated from ``h`` = 1e-7 and 2e-7; its convergence from the one at
   5e-8 and 1e-7 (a map not smooth at that scale shows here). Column by column where they do not converge: the
   one-sided differences that do (a threshold of the map within 2h of the state on one side), then the same at
   ``h`` = 1e-8 (thresholds on both sides): the derivative of the map's piece the orbit lies on
   (:func:`rotor.dynamics.monodromy_check.piece_reference`); the row says how many columns were taken so and what
   the central differences alone gave.

Where the transient from rest reaches no orbit, the orbit is sought from the nearest drawn speed's orbit (Newton
from its state at phase 0, else a branch from it to the speed, :func:`neighbour_orbit`): an unstable orbit a
transient never settles on is an orbit all the same, and its monodromy is checked like the others. Where no orbit
converges even so (a speed with none of the period tried, or a search that stalls), steps 2 and 3 are done on
the map of one revolution at the state the search ended on (its last iterate), as the default test does at the state
60 revolutions after the linear start: the monodromy is the map's derivative at any state, so every speed drawn is
checked.

Error: the largest entry of the scaled difference over the largest scaled entry of the reference (the norm of
tests/rotor/dynamics/test_period_map_events.py). Run: ``nice .venv/bin/python benchmarks/bench_monodromy_random.py
[--scene paper-table4 --speeds 20 --seed N]`` (about 30-60 s a speed).
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.errors import ConvergenceError, OutsideDomainError  # noqa: E402
from contact.files import atomic_write_text  # noqa: E402
from rotor.dynamics.monodromy_check import piece_reference, state_scales  # noqa: E402
from rotor.dynamics.period_map import period_map  # noqa: E402
from rotor.studies.orbit import orbit  # noqa: E402

OUT = ROOT / "reports" / "published"
#: the bound the issue sets on the located monodromy against central differences of its map
BOUND = 1e-6


def monodromy_error(flow, sh) -> dict:
    """The orbit's located monodromy against central differences of its own map (module docstring)."""
    pm = flow.handle
    n = sh.period_revs * sh.steps_per_rev
    r = period_map(pm, sh.state, sh.t0_s, n, modes0=sh.modes, record_every=1)
    s = state_scales(pm, r.trajectory)
    got = piece_reference(pm, sh.state, sh.t0_s, n, sh.modes, s, r.monodromy, bound=BOUND)
    ref = got.pop("reference")
    return {**got, "largest_multiplier": float(np.abs(np.linalg.eigvals(r.monodromy)).max()),
            "largest_multiplier_reference": float(np.abs(np.linalg.eigvals(ref)).max()),
            "unsmooth_columns": int(r.unsmooth_columns), "replay_mismatch": float(r.replay_mismatch)}


def one_speed(scene: str, rpm: float, neighbour=None, scheme: str = "active-set") -> tuple[dict, object]:
    """The row of one speed and its orbit (None without one): the orbit from the transient (``neighbour`` None),
    or from ``neighbour`` = ``(rpm, OrbitResult)``, a drawn speed's orbit: Newton from its state at phase 0, then
    a branch from it to ``rpm`` (:func:`neighbour_orbit`); ``scheme``: the end-face friction scheme
    (:attr:`rotor.dynamics.system.NewmarkOptions.friction_scheme`)."""
    from rotor.periodic.period_flow import make_flow
    t0 = time.perf_counter()
    try:
        res, route = ((orbit(scene, rpm, friction_scheme=scheme), "transient") if neighbour is None else
                      neighbour_orbit(scene, rpm, *neighbour, scheme=scheme))
    except (OutsideDomainError, ConvergenceError) as exc:     # the transient left the law's domain: no state to check
        return {"speed_rpm": rpm, "converged": False, "no_state": " ".join(str(exc).split())[:160],
                "orbit_s": time.perf_counter() - t0}, None
    sh = res.shooting
    row = {"speed_rpm": rpm, "converged": bool(sh.converged), "period_revs": sh.period_revs, "route": route,
           "steps_per_rev": sh.steps_per_rev, "orbit_s": time.perf_counter() - t0}
    # no orbit: the map of one revolution is checked at the state the search ended on (its last Newton iterate, a
    # state of the run like the default test's; the monodromy there is as much the map's derivative)
    from rotor.studies.steady_state import point_system
    _, _, system = point_system(scene, rpm)
    flow = make_flow(system, sh.period_s / (sh.period_revs * sh.steps_per_rev), friction_scheme=scheme)
    if not sh.converged:
        sh = dataclasses.replace(sh, period_revs=1, steps_per_rev=sh.steps_per_rev)
    if np.all(np.isfinite(sh.state)):
        row.update(monodromy_error(flow, sh))
    return row, (res if res.converged else None)


def neighbour_orbit(scene: str, rpm: float, from_rpm: float, near, scheme: str = "active-set") -> tuple:
    """The orbit at ``rpm`` from the orbit ``near`` found at ``from_rpm``: Newton from its state at phase 0 (same
    period, one revolution of transient), else the orbit where :func:`rotor.studies.orbit.branch` from it lands
    at ``rpm``. Where the transient from rest reaches no orbit (an unstable orbit, a chaotic transient) one may
    still exist: at 16 125.4 rpm on paper-table4 the search from rest stalled, Newton from the orbit at
    15 969.9 rpm converged to 4.9e-14 in 0.14 s. Returns ``(OrbitResult, route)``."""
    from rotor.periodic.period_flow import make_flow, to_full
    from rotor.periodic.shooting import ShootingOptions
    from rotor.studies.orbit import branch
    from rotor.studies.steady_state import point_system
    warm = ShootingOptions(transient_revs=1, round_growth=2.0)
    res = orbit(scene, rpm, start=(near.q_m, near.v_m_s), period_revs=near.period_revs, options=warm,
                friction_scheme=scheme)
    if res.converged:
        return res, f"Newton from {from_rpm:.1f} rpm"
    br = branch(scene, from_rpm, rpm, start=(near.q_m, near.v_m_s), period_revs=near.period_revs, amplitudes=False,
                friction_scheme=scheme)
    last = br.branch.points[-1] if br.branch.points else None
    if br.stop != "end reached" or last is None:
        return res, f"none from {from_rpm:.1f} rpm (Newton; branch: {br.stop})"
    _, _, system = point_system(scene, rpm)
    flow = make_flow(system, 2.0 * np.pi / (system.omega_rad_s * br.start.steps_per_rev), friction_scheme=scheme)
    q, v = to_full(flow, last.state, 0.0)
    got = orbit(scene, rpm, steps_per_rev=br.start.steps_per_rev, start=(q, v), period_revs=near.period_revs,
                options=warm, friction_scheme=scheme)
    return got, (f"branch from {from_rpm:.1f} rpm ({len(br.points)} points, {sum(br.as_dict()['restarts'].values())} restarts)"
                 if got.converged else f"none from {from_rpm:.1f} rpm (branch landed, Newton did not)")


def report(scene, seed, rows, load0, load1, commit, scheme: str = "active-set") -> str:
    ok = [r for r in rows if r.get("error") is not None and r["converged"]]
    smooth = [r for r in ok if r["reference_convergence"] <= BOUND]
    within = sum(r["error"] <= BOUND for r in smooth)
    states = [r for r in rows if r.get("error") is not None and not r["converged"]]
    st_smooth = [r for r in states if r["reference_convergence"] <= BOUND]
    every = smooth + st_smooth
    title = ("# The located monodromy at random speeds" if scheme == "active-set" else
             "# The monodromy at random speeds, friction by projection")
    lines = [title, "",
             (f"Friction scheme `{scheme}` (`rotor.dynamics.system.NewmarkOptions.friction_scheme`). "
              if scheme != "active-set" else "") +
             f"`benchmarks/bench_monodromy_random.py` at commit {commit}, scene `{scene}`, seed **{seed}** "
             f"({len(rows)} speeds drawn uniformly). Orbit as `ringcontact orbit` finds it; error of its "
             f"{'located ' if scheme == 'active-set' else ''}monodromy against the Richardson extrapolation of "
             "central differences of the same map at 1e-7 and "
             "2e-7 of each component's largest magnitude; the reference's own convergence against the one at 5e-8 "
             "and 1e-7. Where a column's central differences do not converge, the one-sided ones that do (a "
             "threshold of the map within 2e-7 on one side), then the same at 1e-8 (thresholds on both sides): the "
             "derivative of the piece the orbit lies on (`rotor.dynamics.monodromy_check.piece_reference`; "
             f"{sum(r.get('one_sided_columns', 0) > 0 or r.get('finer_columns', 0) > 0 for r in rows)} speeds "
             f"needed it). Load average {load0[0]:.2f} at start, {load1[0]:.2f} at end; {platform.machine()}, Python "
             f"{platform.python_version()}.", "",
             f"Within {BOUND:g}: **{within} of {len(smooth)}** orbits whose reference converged to {BOUND:g}; "
             f"{len(ok) - len(smooth)} orbits whose reference did not (no piece's derivative converged at 1e-7 or "
             f"1e-8 of the state there: nothing to compare with); {len(rows) - len(ok)} speeds with no orbit. At those the map of "
             "one revolution is checked at the state the orbit search ended on (its last iterate): within "
             f"{BOUND:g} at **{sum(r['error'] <= BOUND for r in st_smooth)} of {len(st_smooth)}** whose reference "
             f"converged ({len(states) - len(st_smooth)} did not; {sum(1 for r in rows if r.get('no_state'))} left the "
             "law's domain in the transient: no state to check). Together: "
             f"**{sum(r['error'] <= BOUND for r in every)}"
             f" of {len(every)}** speeds. Largest error where the reference converged: "
             f"{max((r['error'] for r in every), default=float('nan')):.1e}.",
             "", f"Where the transient from rest reached no orbit, the nearest drawn speed's orbit was the start (Newton "
             "from its state at phase 0, else a branch from it): "
             f"{sum(1 for r in rows if r.get('route', 'transient') != 'transient' and r['converged'])} orbits found "
             "so (the period column says from where).",
             "", "| speed (rpm) | period (rev) | steps/rev | error | reference convergence (central alone) | "
             "columns one-sided / at 1e-8 / on a threshold | largest multiplier (monodromy / reference) | "
             "unsmooth columns |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r.get("no_state"):
            lines.append(f"| {r['speed_rpm']:.1f} | no orbit, no state: {r['no_state'].split(':')[0]} | | | | | | |")
            continue
        if r.get("error") is None:
            lines.append(f"| {r['speed_rpm']:.1f} | no orbit ({r.get('route', 'transient')}) | | | | | | |")
            continue
        period = f"{r['period_revs']}" if r["converged"] else "no orbit: 1 at the last iterate"
        if r.get("route", "transient") != "transient":
            period += f" ({r['route']}; from rest: {r.get('transient', 'no orbit')})"
        central = r.get("central_convergence", r["reference_convergence"])
        lines.append(f"| {r['speed_rpm']:.1f} | {period} | {r['steps_per_rev']} | {r['error']:.1e} | "
                     f"{r['reference_convergence']:.1e} ({central:.1e}) | {r.get('one_sided_columns', 0)} / "
                     f"{r.get('finer_columns', 0)} / {r.get('on_threshold', 0)} | {r['largest_multiplier']:.6f} / "
                     f"{r['largest_multiplier_reference']:.6f} | {r['unsmooth_columns']} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="paper-table4")
    ap.add_argument("--speeds", type=int, default=20)
    ap.add_argument("--rpm-min", type=float, default=6000.0)
    ap.add_argument("--rpm-max", type=float, default=18000.0)
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--out", type=Path, default=None,
                    help="default: reports/published/perf-monodromy-random.md (-projection.md with that scheme)")
    ap.add_argument("--friction-scheme", default="active-set", choices=("active-set", "projection"))
    ap.add_argument("--from-json", type=Path, default=None,
                    help="render the report again from a run's JSON (nothing recomputed) into --out")
    a = ap.parse_args(argv)
    scheme = a.friction_scheme
    if a.out is None:
        a.out = OUT / ("perf-monodromy-random.md" if scheme == "active-set" else "perf-monodromy-random-projection.md")
    if a.from_json is not None:
        d = json.loads(a.from_json.read_text())
        text = report(d["scene"], d["seed"], d["rows"], (d["load"][0],), (d["load"][1],), d["commit"],
                      d.get("friction_scheme", "active-set"))
        write(a.out, text, d)
        print(text)
        return 0
    seed = a.seed if a.seed is not None else int.from_bytes(os.urandom(4), "little")
    print(f"seed {seed}", flush=True)
    speeds = np.random.default_rng(seed).uniform(a.rpm_min, a.rpm_max, a.speeds).round(1)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    load0 = os.getloadavg()
    rows, found = [], {}
    for rpm in speeds:
        row, res = one_speed(a.scene, float(rpm), scheme=scheme)
        _printed(rows, row, found, res)
    # where the transient reached no orbit, from the nearest drawn speed's orbit (one_speed, neighbour_orbit)
    for i, row in enumerate(list(rows)):
        if row["converged"] or not found:
            continue
        near = min(found, key=lambda f: abs(f - row["speed_rpm"]))
        again, res = one_speed(a.scene, row["speed_rpm"], (near, found[near]), scheme=scheme)
        again["transient"] = "no orbit" if row.get("no_state") is None else "left the law's domain"
        rows[i] = again if again["converged"] or again.get("error") is not None else {**row, "route": again["route"]}
        _printed(None, rows[i], found, res)
    text = report(a.scene, seed, rows, load0, os.getloadavg(), commit, scheme)
    write(a.out, text, {"seed": seed, "scene": a.scene, "commit": commit, "load": [load0[0], os.getloadavg()[0]],
                        "rows": rows, "friction_scheme": scheme})
    print(text)
    return 0


def _printed(rows, r: dict, found: dict, res) -> None:
    """Append row ``r`` to ``rows`` (unless None), its orbit ``res`` to ``found`` by speed, and print it."""
    if rows is not None:
        rows.append(r)
    if res is not None:
        found[r["speed_rpm"]] = res
    rpm, how = r["speed_rpm"], f" [{r['route']}]" if r.get("route", "transient") != "transient" else ""
    if r.get("no_state"):
        print(f"{rpm:8.1f} rpm: no orbit, no state: {r['no_state']}{how}", flush=True)
        return
    print(f"{rpm:8.1f} rpm: " + ("" if r["converged"] else "no orbit, last iterate: ")
          + (f"error {r['error']:.1e} (reference {r['reference_convergence']:.1e}), "
             f"|mu| {r['largest_multiplier']:.5f}" if r.get("error") is not None else "-") + how, flush=True)


def write(out: Path, text: str, data: dict) -> None:
    """The report and its JSON (``rows`` and what :func:`report` needs to render it again)."""
    atomic_write_text(out, text)
    atomic_write_text(out.with_suffix(".json"), json.dumps(data, indent=1) + "\n")


if __name__ == "__main__":
    raise SystemExit(main())
