"""Friction events located inside the step: cost on the Table 4 rotor, accuracy on Den Hartog's oscillator.

Writes ``reports/published/perf-friction-events.md``:

1. One steady-state point of the Table 4 rotor at 10 500 rpm, T/512 (as section 1 of
   ``benchmarks/bench_integrators.py``: :func:`rotor.studies.steady_state.steady_state` from rest, then 64
   revolutions), with ``NewmarkOptions.locate_events`` off and on, alternating in one process, and,
   with ``--baseline DIR``, the code before the change (a source tree of the previous commit, run in a
   subprocess, timed inside it after compilation) and this tree the same way, between them: wall times (median), revolutions,
   1X–5X velocity amplitudes of disk1.y, disk2.y and s.y with events on against off, events located in
   the first 10 revolutions.
2. Den Hartog's (1931) oscillator (tests/rotor/dynamics/dynamics_denhartog.py): steady amplitude error
   against the exact one, events off and on, at T/100 … T/800 (non-stop, damped and undamped) and
   T/400 … T/3200 (stick-slip), with the observed order between successive step halvings.
3. The undamped non-stop cases after 1 500 periods: the state one period apart (m), events off and on.

Run: ``nice -n 0 .venv/bin/python benchmarks/bench_friction_events.py [--baseline DIR]`` (a few minutes).
"""
from __future__ import annotations

import functools
import json
import math
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path
from unittest import mock

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests" / "rotor" / "dynamics"))

from contact.files import atomic_write_text  # noqa: E402
from rotor.dynamics.system import NewmarkOptions  # noqa: E402

OUT = ROOT / "reports" / "published"
RPM = 10500.0
NPER = 512
NAMES = ("disk1.y", "disk2.y", "s.y")
REPEATS = 5


def steady_point(locate: bool):
    """Wall time (s), revolutions, (3, 5) velocity amplitudes (m/s) of the Table 4 point at T/NPER."""
    import rotor.dynamics.production as rp
    from rotor.dynamics.build import system_from_model
    from rotor.dynamics.system import NewmarkOptions
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene
    from rotor.studies.steady_state import SteadyStateOptions, steady_state

    scene = load_scene("paper-table4")
    model = assemble(scene)
    system = system_from_model(model, scene, RPM * 2 * math.pi / 60)
    opts = SteadyStateOptions(steps_per_rev=NPER, spectrum_revs=64, samples_per_rev=NPER)
    extra = {"locate_events": bool(locate)}
    with mock.patch.object(rp, "NewmarkOptions", functools.partial(NewmarkOptions, **extra)):
        t0, c0 = time.perf_counter(), time.process_time()
        res = steady_state(system, model, options=opts)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    sel = [res.channel(c) for c in NAMES]
    return (wall, cpu), res.transient_revs + res.revolutions, res.harmonics("v")[:, sel].T


def baseline_point(tree: str) -> dict:
    """The point with the code of ``tree`` (locate_events does not exist there), in a subprocess."""
    code = ("import sys, json, math, time; sys.path.insert(0, sys.argv[1]);"
            "from rotor.dynamics.build import system_from_model; from rotor.model.assembly import assemble;"
            "from rotor.model.scene import load_scene;"
            "from rotor.studies.steady_state import SteadyStateOptions, steady_state;"
            "sc = load_scene('paper-table4'); m = assemble(sc); s = system_from_model(m, sc, %r * 2 * math.pi / 60);"
            "steady_state(s, m, options=SteadyStateOptions(steps_per_rev=64, min_revs=8, max_revs=16, spectrum_revs=2));"
            "t0, c0 = time.perf_counter(), time.process_time();"
            "r = steady_state(s, m, options=SteadyStateOptions(steps_per_rev=%d, spectrum_revs=64, samples_per_rev=%d));"
            "print(json.dumps({'wall': time.perf_counter() - t0, 'cpu': time.process_time() - c0,"
            "'revs': r.transient_revs + r.revolutions}))"
            % (RPM, NPER, NPER))
    env = dict(os.environ, PYTHONPATH=tree)
    out = subprocess.run([sys.executable, "-c", code, tree], capture_output=True, text=True, env=env, check=True,
                         cwd=tree)
    return json.loads(out.stdout.strip().splitlines()[-1])


def transient_runs() -> dict:
    """The first 10 revolutions of the Table 4 point from rest (T/NPER), events off and on alternating,
    REPEATS times: CPU times (s) and the events located."""
    from rotor.dynamics.build import system_from_model
    from rotor.dynamics.production import prepare, simulate_production
    from rotor.dynamics.system import NewmarkOptions
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene

    scene = load_scene("paper-table4")
    model = assemble(scene)
    omega = RPM * 2 * math.pi / 60
    system = system_from_model(model, scene, omega)
    dt = 2 * math.pi / omega / NPER
    pre = prepare(system, dt)
    out = {"off": [], "on": [], "events": 0}
    for _ in range(REPEATS):
        for name in ("off", "on"):
            c0 = time.process_time()
            tr = simulate_production(system, dt, 10 * NPER, q0=system.offset, check_step=False, prepared=pre,
                                     options=NewmarkOptions(locate_events=name == "on"))
            out[name].append(time.process_time() - c0)
            if name == "on":
                out["events"] = tr.located_events
    return out


def den_hartog_rows() -> list[str]:
    """Amplitude errors against Den Hartog (1931), events off and on, and the observed orders."""
    from dynamics_denhartog import DenHartog
    from dynamics_standin import friction_body
    from test_friction_events import _extreme
    from rotor.dynamics.production import simulate_production
    from rotor.dynamics.system import NewmarkOptions

    rows = ["| case | ζ | ω (rad/s) | steps per period | error, events off | error, events on | order, events on |",
            "|---|---|---|---|---|---|---|"]
    cases = [("non-stop", 0.2, 0.1, 50.0, (100, 200, 400, 800), 60), ("non-stop", 0.2, 0.1, 100.0, (100, 200, 400, 800), 60),
             ("non-stop", 0.2, 0.0, 50.0, (100, 200, 400, 800), 150), ("non-stop", 0.2, 0.0, 100.0, (100, 200, 400, 800), 150),
             ("stick-slip", 0.6, 0.1, 25.0, (400, 800, 1600, 3200), 40)]
    for name, F, zeta, omega, steps, periods in cases:
        s = friction_body(F=F, P0=1.0, omega=omega, zeta=zeta)
        dh = DenHartog(s.M[0, 0], s.C[0, 0], s.K[0, 0], F, 1.0, omega)
        X0 = dh.steady_state()[0]
        prev = None
        for nper in steps:
            errs = []
            for locate in (False, True):
                dt = dh.T / nper
                tr = simulate_production(s, dt, periods * nper, check_step=False,
                                         options=NewmarkOptions(locate_events=locate))
                y, v = tr.q[-nper - 1:, 0], tr.v[-nper - 1:, 0]
                amp = 0.5 * (_extreme(y, v, dt) + _extreme(-y, -v, dt)) if name == "non-stop" else 0.5 * np.ptp(y)
                errs.append(abs(amp - X0) / X0)
            order = f"{math.log2(prev / errs[1]):.2f}" if prev else ""
            prev = errs[1]
            rows.append(f"| {name} | {zeta} | {omega:g} | {nper} | {errs[0]:.2e} | {errs[1]:.2e} | {order} |")
    return rows


def drift_rows() -> list[str]:
    """Undamped non-stop Den Hartog cases, 1 500 periods from rest: the state one period apart at the end."""
    from dynamics_denhartog import DenHartog
    from dynamics_standin import friction_body
    from rotor.dynamics.production import simulate_production
    from rotor.dynamics.system import NewmarkOptions

    rows = ["| ω (rad/s) | steps per period | amplitude X0 (m) | drift per period, events off (m) | "
            "drift per period, events on (m) |", "|---|---|---|---|---|"]
    for omega in (50.0, 100.0):
        s = friction_body(F=0.2, P0=1.0, omega=omega, zeta=0.0)
        dh = DenHartog(s.M[0, 0], s.C[0, 0], s.K[0, 0], 0.2, 1.0, omega)
        X0 = dh.steady_state()[0]
        for nper in (100, 200, 400, 800):
            cells = []
            for locate in (False, True):
                tr = simulate_production(s, dh.T / nper, 1500 * nper, check_step=False, record_every=nper,
                                         options=NewmarkOptions(locate_events=locate))
                d = np.hypot(np.diff(tr.q[-101:, 0]), np.diff(tr.v[-101:, 0]) / omega)   # (y, ẏ/ω), last 100
                cells.append(f"{d.max():.2e}")
            rows.append(f"| {omega:g} | {nper} | {X0:.4e} | {cells[0]} | {cells[1]} |")
    return rows


def main(argv=None) -> int:
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", help="source tree of the code before the change (timed in a subprocess)")
    args = ap.parse_args(argv)
    load0 = os.getloadavg()
    steady_point(False)   # compile (or load from the cache) both variants first
    steady_point(True)
    walls = {"off": [], "on": [], "before": [], "off_sub": []}
    res = {}
    for _ in range(REPEATS):
        for name in ("before", "off_sub", "off", "on"):
            if name in ("before", "off_sub"):
                if args.baseline:
                    b = baseline_point(args.baseline if name == "before" else str(ROOT))
                    walls[name].append((b["wall"], b["cpu"]))
                    res[name] = (b["revs"], None)
                continue
            wall, revs, amps = steady_point(name == "on")
            walls[name].append(wall)
            res[name] = (revs, amps)
    load1 = os.getloadavg()
    tr_runs = transient_runs()
    rel = np.abs(res["on"][1] - res["off"][1]) / np.abs(res["off"][1])
    lines = ["# Friction events located inside the step: cost and accuracy", "",
             f"Generated by `benchmarks/bench_friction_events.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}. "
             f"Machine: 2 shared cores; load average at start {load0[0]:.2f}/{load0[1]:.2f}/{load0[2]:.2f}, "
             f"after section 1 {load1[0]:.2f}/{load1[1]:.2f}/{load1[2]:.2f}.", "",
             f"## 1. Table 4 rotor, {RPM:g} rpm, T/{NPER}: one steady point (transient + 64 revolutions)", "",
             f"Alternating in one run, median of {REPEATS} (min–max), numba compiled beforehand.", "",
             "| variant | wall (s), median (min–max) | CPU (s), median (min–max) | revolutions |", "|---|---|---|---|"]
    default = NewmarkOptions().locate_events
    for name, label in (("before", "before the change (previous commit, subprocess)"),
                        ("off_sub", f"this change, default options (`locate_events = {default}`), subprocess as the "
                                    "line above"),
                        ("off", "this change, `locate_events = False`" + ("" if default else " (default)")),
                        ("on", "this change, `locate_events = True`" + (" (default)" if default else ""))):
        if walls[name]:
            cells = []
            for j in (0, 1):
                w = [x[j] for x in walls[name]]
                cells.append(f"{statistics.median(w):.2f} ({min(w):.2f}–{max(w):.2f})")
            lines.append(f"| {label} | {cells[0]} | {cells[1]} | {res[name][0]} |")
    off, on = statistics.median(tr_runs["off"]), statistics.median(tr_runs["on"])
    ratio = statistics.median([x[0] for x in walls["on"]]) / statistics.median([x[0] for x in walls["off"]])
    lines += ["", f"Wall-time ratio of the steady point, events on / off (medians): {ratio:.2f}.", ""]
    lines += [f"1X–5X velocity amplitudes (mm/s) of the steady point, events off / on:", "",
              "| channel | " + " | ".join(f"{h}X off | {h}X on" for h in range(1, 6)) + " |",
              "|---|" + "---|" * 10]
    for i, name in enumerate(NAMES):
        lines.append(f"| {name} | " + " | ".join(f"{res['off'][1][i, h] * 1e3:.4g} | {res['on'][1][i, h] * 1e3:.4g}"
                                                    for h in range(5)) + " |")
    lines += ["", f"The first 10 revolutions from rest alone ({10 * NPER} steps, the impacts and stick/slip switches of the "
              f"transient), alternating, median of {REPEATS} CPU times: events off {off:.3f} s, on {on:.3f} s "
              f"(ratio {on / off:.2f}); events located: {tr_runs['events']}.", "",
              "Amplitudes of the steady point: "
              f"largest relative change of the 15 1X–5X velocity amplitudes (disk1.y, disk2.y, s.y), on against "
              f"off: {rel.max() * 100:.3g} % ({NAMES[int(np.argmax(rel) // 5)]}, {int(np.argmax(rel) % 5) + 1}X); "
              f"1X: {', '.join(f'{x * 100:.3g} %' for x in rel[:, 0])}.", "",
              "## 2. Den Hartog (1931): steady amplitude error against the exact one", "",
              "F/P0 = 0.2 (non-stop, amplitude from the Hermite-interpolated extremes of the last period) and 0.6 "
              "(stick-slip, half the peak-to-peak of the last period, as tests/rotor/dynamics/test_dynamics_verification.py); "
              "from rest, 60 periods (damped), 150 (undamped), 40 (stick-slip).", ""]
    lines += den_hartog_rows()
    lines += ["", "## 3. Den Hartog, undamped, non-stop (F/P0 = 0.2): periodic?", "",
              "From rest, 1 500 periods; the largest difference of (y, ẏ/ω) one period apart over the last 100 "
              "periods (m). With no damping a free vibration the step leaves behind never decays.", ""]
    lines += drift_rows()
    atomic_write_text(OUT / "perf-friction-events.md", "\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
