"""Continuation of the Table 4 rotor through stick/slip and contact switches: one branch 600 -> 18 000 rpm.

Writes ``reports/published/perf-branch-switches.md`` (+ ``.json``) and, with ``--branch-json PATH``, the branch
itself as ``ringcontact branch --json`` writes it (amplitudes included), from which
``benchmarks/study_bifurcation.py --branch-json PATH`` draws the published bifurcation diagram.

The Table 4 rotor (``paper-table4``, 2 240 steps per revolution, the step :func:`rotor.studies.orbit.branch`
picks) is followed in speed from 600 rpm to 18 000 rpm by :func:`rotor.studies.orbit.branch` (one
``ringcontact branch paper-table4 --rpm-start 600 --rpm-end 18000``), with the period maps' friction events
located inside the step (``--locate-events on``, :attr:`rotor.dynamics.system.NewmarkOptions.locate_events`;
``off``: switches on step boundaries; ``default``: the scheme's default). Reported: points, highest speed
reached, why it stopped, wall time with the load average at start and end (shared 2-core machine), every
restart (the speeds it skipped, those no orbit covers, how it was shot, why the corrector failed before it),
every corrector stall and how it was passed, the bifurcations (discontinuous ones with both sides), the stable
and unstable stretches.

The branch is then verified on ``--verify`` points spread over it: at each point's speed a fresh flow
(:func:`rotor.periodic.period_flow.make_flow`, the same event location) maps the point's own state over its
period (no derivative): the residual ``max |Φ(x) − x|/s`` relative to the orbit's own peak-to-peak scale ``s``
(:func:`rotor.periodic.shooting.orbit_scales`, never below the start's), and an independent
:func:`rotor.periodic.shooting.shoot` from that state (converged, Newton iterations, distance of its orbit from
the point).

After a fold the branch follows the returning (unstable middle) branch ``--turn-back-rpm`` back and then jumps
past the fold as a run-up does (:func:`rotor.periodic.restarts.jump_past_fold`, a reported restart);
``--max-wall-s`` ends the branch after that long (its stop says so).

Run: ``nice .venv/bin/python benchmarks/bench_branch_switches.py [--max-points 1500] [--verify 12]
[--locate-events on] [--turn-back-rpm 250] [--max-wall-s S] [--branch-json PATH]``; with ``--from-json`` (and
``--branch-json PATH``, the same options) the report is written again from the run's files, nothing computed.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.threads import set_thread_env  # noqa: E402

set_thread_env(1)     # before numpy loads: one BLAS thread, as `ringcontact branch` has it (reports/cli/__init__.py)

import numpy as np  # noqa: E402

from contact.files import atomic_write_text  # noqa: E402

OUT = ROOT / "reports" / "published"
SCENE, RPM_START, RPM_END = "paper-table4", 600.0, 18000.0
TO_RPM = 30.0 / math.pi
LOCATE = {"on": True, "off": False, "default": None}


def run_branch(max_points: int, locate_events: bool | None, turn_back_rpm: float | None = None,
               max_wall_s: float | None = None, friction_scheme: str = "active-set",
               family_member: str = "kept", back_fill: bool = False) -> tuple:
    """The branch (:class:`rotor.studies.orbit.BranchResult`), its ``ringcontact branch --json`` dict and wall time."""
    from rotor.dynamics.period_map import warm_up
    from rotor.periodic.continuation import ContinuationOptions
    from rotor.studies.orbit import branch

    from sweep.progress import reporting

    warm_up()
    t0 = time.perf_counter()

    def progress(kind, fields):      # one line per orbit on stderr, to follow a long run
        if kind == "branch_point":
            print(f"orbit {fields['points']}: {fields['parameter'] * TO_RPM:.1f} rpm, "
                  f"{time.perf_counter() - t0:.0f} s", file=sys.stderr, flush=True)

    with reporting(progress):
        scale = abs(RPM_END - RPM_START) / 10.0         # the branch's speed scale (rpm)
        opts = ContinuationOptions(max_points=max_points, max_wall_s=max_wall_s,
                                   turn_back=None if turn_back_rpm is None else turn_back_rpm / scale,
                                   centre_families=family_member == "centred", back_fill=back_fill)
        res = branch(SCENE, RPM_START, RPM_END, options=opts, locate_events=locate_events, tilt_ignored=False,
                     friction_scheme=friction_scheme)
    wall = time.perf_counter() - t0
    d = {"scene": SCENE, "rpm_start": RPM_START, "rpm_end": RPM_END, "period_revs": res.start.period_revs,
         "steps_per_rev": res.start.steps_per_rev, "locate_events": locate_events, "turn_back_rpm": turn_back_rpm,
         "friction_scheme": friction_scheme, "family_member": family_member, "back_fill": back_fill,
         **res.as_dict(),
         "wall_s": round(wall, 3)}
    return res, d, wall


def verify(res, n_verify: int, locate_events: bool | None, friction_scheme: str = "active-set") -> list[dict]:
    """Independent check of ``n_verify`` points spread over the branch (see the module docstring)."""
    from rotor.periodic.period_flow import advance, make_flow
    from rotor.periodic.shooting import ShootingOptions, orbit_scales, record_reduced, shoot
    from rotor.studies.steady_state import point_system

    pts = res.branch.points
    n, floor = res.start.steps_per_rev, res.start.shooting.scales
    steps = n * res.branch.period_revs
    rows = []
    for i in sorted(set(np.linspace(0, len(pts) - 1, min(n_verify, len(pts))).round().astype(int))):
        p = pts[i]
        modes = p.modes or res.start.shooting.modes       # the end-face modes its map starts from
        flow = make_flow(point_system(SCENE, p.parameter * TO_RPM, tilt_ignored=False)[2],
                         2.0 * math.pi / (p.parameter * n), locate_events=locate_events,
                         friction_scheme=friction_scheme)
        pv, vv, _ = record_reduced(flow, p.state, 0.0, steps, modes, max(1, steps // 256))
        s = np.maximum(orbit_scales(flow, pv, vv), floor)
        r = advance(flow, p.state, 0.0, steps, modes, jacobian=False)
        sh = shoot(flow, p.state, t0_s=0.0, steps_per_rev=n, period_revs=res.branch.period_revs, modes0=modes,
                   scales=s, options=ShootingOptions())
        rows.append({"index": int(i), "speed_rpm": p.parameter * TO_RPM, "restarted": int(p.restarted),
                     "stable": bool(p.floquet.stable), "residual": float(np.max(np.abs(r.state - p.state) / s)),
                     "events": int(r.events), "shoot_converged": bool(sh.converged),
                     "shoot_iterations": int(sh.newton_iterations),
                     "shoot_distance": float(np.max(np.abs(sh.state - p.state) / s))})
    return rows


def isolated_checks(res, locate_events: bool | None, rel_steps=(1e-6, 1e-7), cap: int = 40,
                    friction_scheme: str = "active-set") -> list[dict]:
    """Every orbit whose stability differs from both neighbours' (an isolated spike), checked by central
    differences of the whole map (:func:`rotor.periodic.period_flow.monodromy_fd`, the same event location) at the
    two ``rel_steps``: the largest multiplier of each against the branch's, and the located monodromy's columns
    that did not settle (``unsmooth_columns``). Verdict: *confirmed* where both differences agree (to 1e-3) on the
    branch's stability, *not confirmed* where both agree on the other, *map not smooth* where they disagree."""
    from rotor.periodic.period_flow import advance, make_flow, monodromy_fd
    from rotor.studies.steady_state import point_system

    pts = res.branch.points
    n = res.start.steps_per_rev
    steps = n * res.branch.period_revs
    idx = [i for i in range(1, len(pts) - 1)
           if pts[i].floquet.stable != pts[i - 1].floquet.stable and pts[i].floquet.stable != pts[i + 1].floquet.stable]
    rows = []
    for i in idx[:cap]:
        p = pts[i]
        modes = p.modes or res.start.shooting.modes
        system = point_system(SCENE, p.parameter * TO_RPM, tilt_ignored=False)[2]
        dt = 2.0 * math.pi / (p.parameter * n)
        r = advance(make_flow(system, dt, locate_events=locate_events, friction_scheme=friction_scheme), p.state, 0.0,
                    steps, modes)
        fd_flow = make_flow(system, dt, backend="fd", locate_events=locate_events, friction_scheme=friction_scheme)
        fd = [float(np.abs(np.linalg.eigvals(monodromy_fd(fd_flow, p.state, 0.0, steps, modes, rel_step=h))).max())
              for h in rel_steps]
        agree = abs(fd[0] - fd[1]) <= 1e-3 * max(fd)
        verdict = ("map not smooth" if not agree else
                   "confirmed" if (fd[1] <= 1.0) == bool(p.floquet.stable) else "not confirmed")
        rows.append({"index": int(i), "speed_rpm": p.parameter * TO_RPM, "stable": bool(p.floquet.stable),
                     "largest_multiplier": float(np.abs(p.floquet.multipliers).max()),
                     "located_again": float(np.abs(np.linalg.eigvals(r.monodromy)).max()),
                     "unsmooth_columns": int(r.unsmooth_columns),
                     "fd_largest_multiplier": fd, "verdict": verdict})
    return rows


def stretches(points: list[dict]) -> list[tuple[float, float, bool, int]]:
    """``(from_rpm, to_rpm, stable, points)`` of each run of equal stability along the branch."""
    out = []
    for p in points:
        if out and out[-1][2] == bool(p["stable"]):
            a, _, st, k = out[-1]
            out[-1] = (a, p["speed_rpm"], st, k + 1)
        else:
            out.append((p["speed_rpm"], p["speed_rpm"], bool(p["stable"]), 1))
    return out


def face_limits_N() -> list[float]:
    """The end faces' friction limits μN (N) of the scene (they do not depend on the speed)."""
    from rotor.studies.steady_state import point_system

    sup = point_system(SCENE, RPM_START, tilt_ignored=False)[2].support
    _, limits, n_faces = sup.faces()
    return [float(x) for x in limits[:n_faces]]


def _state_text(p: dict, mu_n: list[float]) -> str:
    """A point's switches, contact and stick in a few words."""
    stuck = [p.get("stick_share_right_face"), p.get("stick_share_left_face")]
    at_limit = p.get("peak_face_force_N") is not None and mu_n and p["peak_face_force_N"] >= 0.99 * max(mu_n)
    return (f"{p['switches_per_period']} switches/period, contact {100 * (p.get('contact_share') or 0):.0f} %, "
            f"faces stuck {100 * (stuck[0] or 0):.0f} / {100 * (stuck[1] or 0):.0f} %"
            + (f", face force at μN ({p['peak_face_force_N']:.0f} of {max(mu_n):.0f} N)" if at_limit else ""))


def _phase0(p: dict) -> str:
    """The end faces' modes at phase 0 that the orbit's period map starts from, in words (run files made before
    the branch recorded them: the start's)."""
    return ", ".join(f"{face} {'stuck' if p.get(f'stuck_at_phase_0_{face}_face', True) else 'slipping'}"
                     for face in ("right", "left"))


def largest_gap(pts) -> float:
    """The widest stretch of speeds (rpm) a restart jumped over that no orbit of the branch covers (0 if none)."""
    return max((abs(p["uncovered_rpm"][1] - p["uncovered_rpm"][0]) for p in pts if p.get("uncovered_rpm")), default=0.0)


def restart_context(pts: list[dict], i: int, mu_n: list[float]) -> str:
    """What the branch did across the restart at point ``i``: the orbits on either side (switches per period,
    contact, stick, whether a stuck face sits at its friction limit) and the jump of the 1X amplitude at disk 2
    against the change along the branch just before it; the kind of stall that reads from them."""
    a, b = pts[i - 1], pts[i]
    amp = lambda p: (p.get("velocity_amplitudes_mm_s_1X_to_5X") or {}).get("disk2.y", [float("nan")])[0]  # noqa: E731
    jump = abs(amp(b) - amp(a))
    usual = abs(amp(a) - amp(pts[i - 2])) if i >= 2 else float("nan")
    stuck = a.get("stick_share_right_face") == 1.0 and a.get("stick_share_left_face") == 1.0 and \
        a["switches_per_period"] == 0
    at_limit = a.get("peak_face_force_N") is not None and mu_n and a["peak_face_force_N"] >= 0.99 * max(mu_n)
    moded = _phase0(a) != _phase0(b)
    kind = ("the jump past a fold a run-up makes: the branch followed the returning branch back from the fold by "
            "--turn-back-rpm, then a transient of the fold's orbit (rotor.periodic.restarts.jump_past_fold)"
            if "turned back at a fold" in b.get("restart_reason", "") else
            f"the end faces' modes at phase 0 change ({_phase0(a)} → {_phase0(b)}): the orbit after is a fixed point of "
            "the map started from other modes, which the corrector (modes kept) cannot reach" if moded else
            "both faces stuck through the period (a continuum of orbits), one at its friction limit: a faster orbit "
            "keeps its stuck offset only until the holding force passes μN, then the face slips to a new offset "
            "(measured at 5 185 rpm: Newton at fixed speed keeping the offset converged 3.1 rpm on, not 7.1 rpm on)"
            if stuck and at_limit else
            "both faces stuck through the period (a continuum of orbits; at 5 150-5 190 rpm the corrector's iterates "
            "were measured to make a face slip)" if stuck else
            "the switches per period change" if a["switches_per_period"] != b["switches_per_period"] else
            "no change of switches per period: the corrector stalled on the map's kinks (a switch moving across a "
            "step)")
    return (f"{kind}; before: {_state_text(a, mu_n)}; after: {_state_text(b, mu_n)}; 1X at disk 2 "
            f"{amp(a):.3g} → {amp(b):.3g} mm/s (jump {jump:.2g}, last step {usual:.2g})")


def report(d: dict, load: list, args, commit: str, verified: list[dict], spikes: list[dict] | None = None,
           mu_n: list[float] | None = None) -> str:
    pts = d["points"]
    reached = max((p["speed_rpm"] for p in pts), default=float("nan"))
    scheme = d.get("friction_scheme", "active-set")
    member = d.get("family_member", "kept")
    fam = ("" if member == "kept" else f" --family-member {member}") + (" --back-fill" if d.get("back_fill") else "")
    lines = ["# Continuation of the Table 4 rotor through stick/slip and contact switches: one branch"
             + ("" if scheme == "active-set" else ", friction by projection")
             + ("" if member == "kept" else ", each friction-held family's centred member")
             + (", far restarts followed back" if d.get("back_fill") else ""), "",
             f"Made by `nice .venv/bin/python benchmarks/bench_branch_switches.py --max-points {args.max_points} "
             f"--verify {args.verify} --locate-events {args.locate_events} --turn-back-rpm {args.turn_back_rpm:g}"
             + (f" --max-wall-s {args.max_wall_s:g}" if args.max_wall_s else "")
             + (f" --friction-scheme {scheme}" if scheme != "active-set" else "") + fam + f"` at commit {commit}: one "
             f"`ringcontact branch {SCENE} --rpm-start {RPM_START:.0f} --rpm-end {RPM_END:.0f} --turn-back-rpm "
             f"{args.turn_back_rpm:g}" + (f" --friction-scheme {scheme}" if scheme != "active-set" else "") + fam + "` "
             + (f"({d['steps_per_rev']} steps per revolution, friction events and contact onsets and losses located "
                f"inside the step: {d['locate_events']})" if scheme == "active-set" else
                f"({d['steps_per_rev']} steps per revolution, the end faces' friction solved by projection: no modes, "
                "no events located)") + ", in one process. Load average at start "
             f"{load[0][0]:.2f}/{load[0][1]:.2f}/{load[0][2]:.2f}, at end {load[1][0]:.2f}/{load[1][1]:.2f}/"
             f"{load[1][2]:.2f} (shared 2-core machine, other jobs running: the wall time is an upper bound).", "",
             "| | |", "|---|---|",
             f"| orbits | {len(pts)} |", f"| reached | {reached:.1f} rpm |", f"| stop | {d['stop']} |",
             f"| wall | {d['wall_s']:.0f} s |",
             "| restarts by kind | " + ", ".join(f"{k} {v}" for k, v in d["restarts"].items()) + " |",
             f"| corrector stalls | {len(d['corrector_failures'])} |",
             f"| largest stretch no orbit covers | {largest_gap(pts):.1f} rpm (past the farthest speed reached before a "
             "restart; a run back from a fold covers the speeds it skips) |",
             f"| stable / unstable orbits | {sum(p['stable'] for p in pts)} / {sum(not p['stable'] for p in pts)} |",
             "", "## Stability along the branch", "",
             "| from (rpm) | to (rpm) | stable | orbits |", "|---|---|---|---|"]
    lines += [f"| {a:.1f} | {b:.1f} | {'yes' if st else 'no'} | {k} |" for a, b, st, k in stretches(pts)]
    lines += ["", "## Bifurcations", "", "| kind | speed (rpm) | detail |", "|---|---|---|"]
    lines += [f"| {b['kind']} | {b['speed_rpm']:.1f} | {b.get('detail', '')} |" for b in d["bifurcations"]] or ["| none | | |"]
    mu_n = mu_n or []
    lines += ["", "## Restarts (the speeds each skipped, how its orbit was shot, why the corrector failed, what the "
              "orbits on either side show)", "",
              "| skipped (rpm) | no orbit covers (rpm) | shot | why the corrector failed before it | across the restart |",
              "|---|---|---|---|---|"]
    rows = [f"| {p['skipped_rpm'][0]:.1f} – {p['skipped_rpm'][1]:.1f} | "
            + (f"{p['uncovered_rpm'][0]:.1f} – {p['uncovered_rpm'][1]:.1f}" if p.get("uncovered_rpm") else "none")
            + f" | {p['restarted']} | "
            f"{p.get('restart_reason', '')} | {restart_context(pts, i, mu_n) if i else ''} |"
            for i, p in enumerate(pts) if p.get("skipped_rpm")]
    lines += rows or ["| none | | | | |"]
    lines += ["", "## Corrector stalls (every one, how it was passed)", "",
              "| at (rpm) | why | outcome |", "|---|---|---|"]
    lines += [f"| {f['speed_rpm']:.1f} | {f['why']} | {f['outcome']} |" for f in d["corrector_failures"]] or ["| none | | |"]
    lines += ["", "## Verification", "",
              "Each sampled point's own state mapped over its period with a fresh flow (residual relative to the "
              "orbit's own peak-to-peak scale, never below the start's), and an independent shooting from it.", "",
              "| point | speed (rpm) | restarted | stable | residual | face mode changes | shooting converged | "
              "iterations | distance |", "|---|---|---|---|---|---|---|---|---|"]
    for r in verified:
        lines.append(f"| {r['index']} | {r['speed_rpm']:.1f} | {r['restarted']} | {r['stable']} | {r['residual']:.1e} | "
                     f"{r['events']} | {r['shoot_converged']} | {r['shoot_iterations']} | {r['shoot_distance']:.1e} |")
    if spikes is not None:
        lines += ["", "## Isolated stability changes, checked by central differences", "",
                  "Every orbit whose stability differs from both neighbours': the largest |multiplier| on the branch, "
                  "of the located monodromy recomputed, and of central differences of the whole map at 1e-6 and "
                  "1e-7 of the block scales (`monodromy_fd`, the same event location); *unsmooth* counts the located "
                  "monodromy's event-step columns that did not settle (rotor/dynamics/period_map_events.py).", "",
                  "| point | speed (rpm) | stable | branch | located again | unsmooth | differences 1e-6 / 1e-7 | "
                  "verdict |", "|---|---|---|---|---|---|---|---|"]
        lines += [f"| {r['index']} | {r['speed_rpm']:.1f} | {r['stable']} | {r['largest_multiplier']:.4g} | "
                  f"{r['located_again']:.4g} | {r['unsmooth_columns']} | {r['fd_largest_multiplier'][0]:.4g} / "
                  f"{r['fd_largest_multiplier'][1]:.4g} | {r['verdict']} |" for r in spikes] or ["| none | | | | | | | |"]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-points", type=int, default=1500)
    ap.add_argument("--verify", type=int, default=12)
    ap.add_argument("--locate-events", choices=sorted(LOCATE), default="on")
    ap.add_argument("--branch-json", type=Path, default=None)
    ap.add_argument("--turn-back-rpm", type=float, default=250.0)
    ap.add_argument("--max-wall-s", type=float, default=None)
    ap.add_argument("--friction-scheme", choices=("active-set", "projection"), default="active-set",
                    help="the end faces' friction (rotor.dynamics.system.NewmarkOptions.friction_scheme); projection "
                         "writes perf-branch-switches-projection.md (+ .json)")
    ap.add_argument("--family-member", choices=("kept", "centred"), default="kept",
                    help="which member of a friction-held family each point is (ringcontact branch --family-member); "
                         "centred adds -centred to the report's name")
    ap.add_argument("--back-fill", action="store_true",
                    help="far restarts moved back along the branch they found (ringcontact branch --back-fill); adds "
                         "-back-fill to the report's name")
    ap.add_argument("--from-json", action="store_true",
                    help="no computing: write the report again from --branch-json and the published .json (the "
                         "run's commit, load and checks kept)")
    args = ap.parse_args(argv)
    stem = ("perf-branch-switches" + ("" if args.friction_scheme == "active-set" else f"-{args.friction_scheme}")
            + ("" if args.family_member == "kept" else f"-{args.family_member}") + ("-back-fill" if args.back_fill else ""))
    if args.from_json:
        try:
            d = json.loads(args.branch_json.read_text())
            slim = json.loads((OUT / f"{stem}.json").read_text())
        except (AttributeError, OSError, ValueError) as e:   # no --branch-json, a missing or damaged file
            print(f"bench_branch_switches: --from-json needs --branch-json PATH of a run and its "
                  f"{OUT / (stem + '.json')}: {type(e).__name__}: {e}", file=sys.stderr)
            return 2
        load = slim["load_average"]
        text = report(d, load, args, slim["commit"], slim["verified"], slim["isolated_checks"], face_limits_N())
        atomic_write_text(OUT / f"{stem}.md", text)
        print(text)
        return 0
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    load0 = os.getloadavg()
    res, d, _ = run_branch(args.max_points, LOCATE[args.locate_events], args.turn_back_rpm, args.max_wall_s,
                           args.friction_scheme, args.family_member, args.back_fill)
    load1 = os.getloadavg()
    if args.branch_json is not None:
        atomic_write_text(args.branch_json, json.dumps(d) + "\n")
    verified = verify(res, args.verify, LOCATE[args.locate_events], args.friction_scheme)
    spikes = isolated_checks(res, LOCATE[args.locate_events], friction_scheme=args.friction_scheme)
    slim = {k: v for k, v in d.items() if k not in ("points", "start")}
    slim["speeds_rpm"] = [p["speed_rpm"] for p in d["points"]]
    slim["stable"] = [p["stable"] for p in d["points"]]
    slim["verified"] = verified
    slim["isolated_checks"] = spikes
    slim["load_average"] = [list(load0), list(load1)]
    slim["commit"] = commit
    atomic_write_text(OUT / f"{stem}.json", json.dumps(slim, indent=1) + "\n")
    text = report(d, [load0, load1], args, commit, verified, spikes, face_limits_N())
    atomic_write_text(OUT / f"{stem}.md", text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
