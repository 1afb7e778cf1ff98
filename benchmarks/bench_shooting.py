"""Periodic orbits by shooting against the transient steady state: agreement and time, one run.

Writes ``reports/published/perf-shooting.md`` (+ ``.csv``). Table 4 rotor (``paper-table4``, production
scheme, 256 steps per revolution):

1. **One point, 10 500 rpm**, interleaved ``--repeats`` times, medians, after compilation:

   - *transient*: what ``ringcontact simulate --steady --revolutions 4`` computes
     (:func:`reports.cli.simulate._steady_run`: the steady-state detector of :mod:`rotor.studies.steady_state`
     from the linear periodic start, transient cap 8 000 revolutions, then 4 kept revolutions and their
     1X–5X velocity amplitudes at every station);
   - *shooting*: :func:`rotor.studies.orbit.orbit` (short transient from the same start, Newton on the period
     map with the exact monodromy, Floquet multipliers, 1X–5X over one period);
   - *shooting, warm*: started from the orbit at 10 400 rpm with 2 transient revolutions (what a cascade or a
     continuation does from its previous speed, :func:`rotor.studies.orbit.cascade`);
   - *shooting from the transient's end*: the same, started from the transient's steady end state. A face
     stuck through the whole orbit makes the orbits a continuum (one neutral multiplier per stuck offset,
     :mod:`rotor.periodic.floquet`); this start puts shooting on the continuum member the transient reached.

   1X–5X agreement: the largest difference over every station, direction and harmonic, relative to that
   channel's 1X amplitude.
2. **The Fig. 12 cascade** (the published ``study cascade``: 61 speeds 0–18 000 rpm, 256 steps per
   revolution) by shooting with stability at every speed, on 2 worker processes (each compiled before the
   clock starts), the speeds cut into ``--blocks`` contiguous blocks handed out as workers free up, each block
   by :func:`rotor.studies.orbit.cascade` (every speed started from the previous converged orbit, the first of
   a block and the speed after a failure from the linear periodic solution; a failed warm start is not
   restarted cold); zero speed is the static point. The wall time,
   each speed's orbit, stability and critical multiplier (:func:`rotor.studies.shooting_point.classify`); the
   speeds the published transient cascade (``reports/published/study-cascade.csv``) called non-periodic,
   classified by their multipliers.

Load average at start and end (shared 2-core machine). Run:
``nice .venv/bin/python benchmarks/bench_shooting.py [--repeats 5] [--workers 2]`` (≈ 2–5 minutes).
"""
from __future__ import annotations

import argparse
import csv
import io
import os
import platform
import statistics
import sys
import time
import types
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402
from rotor.dynamics.initial import linear_initial_state  # noqa: E402
from rotor.studies.orbit import orbit  # noqa: E402
from rotor.periodic.shooting import ShootingOptions  # noqa: E402
from rotor.studies.steady_state import point_system  # noqa: E402

OUT = ROOT / "reports" / "published"
SCENE, SPEED_RPM, STEPS = "paper-table4", 10500.0, 256
CASCADE_RPM = np.linspace(0.0, 18000.0, 61)


def transient_point():
    """``simulate --steady --revolutions 4`` at 10 500 rpm: (amplitudes mm/s, end state (q, v), info)."""
    from reports.cli.simulate import _steady_run

    _, model, system = point_system(SCENE, SPEED_RPM)
    args = types.SimpleNamespace(revolutions=4.0, steps_per_rev=STEPS, record_per_rev=64, max_revs=8000)
    names = [f"{s}.{c}" for s in model.response_stations() for c in ("y", "z")]
    tr, _, _, extra = _steady_run(args, system, model, 2 * np.pi / system.omega_rad_s, names,
                                  [model.dof_index(n) for n in names])
    return extra["velocity_amplitudes_mm_s_1X_to_5X"], (tr.q[-1].copy(), tr.v[-1].copy()), extra


def worst_relative(a: dict, b: dict) -> float:
    """Largest |a − b| over channels and harmonics, relative to the channel's 1X of ``a``."""
    return max(float(np.max(np.abs(np.array(a[k]) - np.array(b[k]))) / abs(a[k][0])) for k in a)


def one_point(repeats: int) -> dict:
    """Part 1: interleaved timings and the agreement at 10 500 rpm."""
    times = {"transient": [], "shooting": [], "shooting_warm": [], "shooting_from_transient_end": []}
    prev = orbit(SCENE, 10400.0, steps_per_rev=STEPS)
    warm = ShootingOptions(transient_revs=2)
    for _ in range(repeats):
        t0 = time.perf_counter()
        amp_t, end, info_t = transient_point()
        times["transient"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        o = orbit(SCENE, SPEED_RPM, steps_per_rev=STEPS)
        times["shooting"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        o_warm = orbit(SCENE, SPEED_RPM, steps_per_rev=STEPS, start=(prev.q_m, prev.v_m_s), options=warm)
        times["shooting_warm"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        o_end = orbit(SCENE, SPEED_RPM, steps_per_rev=STEPS, start=end, options=warm)
        times["shooting_from_transient_end"].append(time.perf_counter() - t0)
    amp_s, amp_e = o.velocity_amplitudes_mm_s_1X_to_5X, o_end.velocity_amplitudes_mm_s_1X_to_5X
    return {"times": {k: statistics.median(v) for k, v in times.items()}, "all_times": times,
            "transient_revs": info_t["transient_revs"], "poincare_remaining": info_t["poincare_remaining"],
            "orbit": o, "orbit_end": o_end, "orbit_warm": o_warm,
            "agree_warm": worst_relative(amp_t, o_warm.velocity_amplitudes_mm_s_1X_to_5X),
            "agree_shooting": worst_relative(amp_t, amp_s), "agree_from_end": worst_relative(amp_t, amp_e),
            "agree_1x_shooting": max(abs(amp_t[k][0] - amp_s[k][0]) / amp_t[k][0] for k in amp_t),
            "agree_1x_from_end": max(abs(amp_t[k][0] - amp_e[k][0]) / amp_t[k][0] for k in amp_t)}


def _warm() -> None:
    """Worker initializer: compile (or load) the kernels before the clock starts."""
    orbit(SCENE, SPEED_RPM, steps_per_rev=STEPS)


def _cascade_half(speeds) -> list[dict]:
    """One worker's contiguous speeds by :func:`rotor.studies.orbit.cascade` (zero speed: static)."""
    from rotor.studies.orbit import cascade as orbit_cascade
    from rotor.studies.shooting_point import classify

    rows = [{"speed_rpm": 0.0, "wall_s": 0.0, "classification": "static", "stable": None, "spectral_radius": None,
             "critical_kind": None, "leading_multiplier": None, "period_revs": None, "converged": True,
             "newton_iterations": None, "transient_revs": 0, "residual": None} for s in speeds if s == 0.0]
    res = orbit_cascade(SCENE, [s for s in speeds if s > 0.0])      # steps: 256, more where contact needs
    for r in res:
        rows.append({"speed_rpm": r.speed_rpm, "wall_s": r.wall_s, "classification":
                     classify(r.floquet) if r.converged else "no_orbit_found", "stable": r.stable if r.converged
                     else None, "spectral_radius": r.floquet.spectral_radius, "critical_kind": r.floquet.kind,
                     "leading_multiplier": r.floquet.leading,
                     "period_revs": r.period_revs if r.converged else None, "converged": r.converged,
                     "newton_iterations": r.newton_iterations, "transient_revs": r.transient_revs,
                     "residual": r.residual})
    return rows


def cascade(workers: int, n_blocks: int) -> tuple[list[dict], float]:
    """Part 2: every Fig. 12 speed by shooting, ``n_blocks`` contiguous blocks on ``workers`` processes;
    (rows in speed order, wall s)."""
    blocks = np.array_split(CASCADE_RPM, n_blocks)
    with ProcessPoolExecutor(workers, initializer=_warm) as pool:
        list(pool.map(_warm_probe, range(workers)))            # every worker started and compiled
        t0 = time.perf_counter()
        rows = [r for block in pool.map(_cascade_half, [list(map(float, b)) for b in blocks]) for r in block]
        wall = time.perf_counter() - t0
    return rows, wall


def _warm_probe(_i: int) -> int:
    time.sleep(1.0)                 # held long enough that every worker takes one
    return os.getpid()


def published_nonperiodic() -> list[float]:
    """Speeds the published transient cascade (study-cascade.csv) did not find periodic."""
    with open(OUT / "study-cascade.csv", encoding="utf-8") as fh:
        return [float(r["speed_rpm"]) for r in csv.DictReader(fh) if r["converged"] == "0"]


def report(p1: dict, rows: list[dict], wall: float, load: list, repeats: int, workers: int, blocks: int) -> str:
    """The markdown report."""
    t = p1["times"]
    o = p1["orbit"]
    nonper = published_nonperiodic()
    conv = [r for r in rows if r["converged"]]
    lines = ["# Periodic orbits by shooting against the transient steady state", "",
             f"`benchmarks/bench_shooting.py`, one run. Table 4 rotor (`{SCENE}`, production scheme, {STEPS} steps "
             f"per revolution). Load average at start {load[0][0]:.2f}/{load[0][1]:.2f}/{load[0][2]:.2f}, at end "
             f"{load[1][0]:.2f}/{load[1][1]:.2f}/{load[1][2]:.2f} (shared machine, 2 cores, other jobs running); "
             f"{platform.machine()}, Python {platform.python_version()}.", "",
             f"## One point: 10 500 rpm ({repeats} interleaved repeats, medians, after compilation)", "",
             "| method | wall per point (s) | 1X–5X vs transient (max, rel. to channel 1X) | 1X only |",
             "|---|---|---|---|",
             f"| transient (`simulate --steady`, {p1['transient_revs']} revolutions to the detected steady state) | "
             f"{t['transient']:.2f} | – | – |",
             f"| shooting (`ringcontact orbit`) | {t['shooting']:.2f} | {p1['agree_shooting']:.1e} | "
             f"{p1['agree_1x_shooting']:.1e} |",
             f"| shooting, warm (from the orbit at 10 400 rpm, 2 transient revolutions) | {t['shooting_warm']:.2f} | "
             f"{p1['agree_warm']:.1e} | – |",
             f"| shooting from the transient's end state (2 transient revolutions) | "
             f"{t['shooting_from_transient_end']:.2f} | "
             f"{p1['agree_from_end']:.1e} | {p1['agree_1x_from_end']:.1e} |", "",
             f"Shooting: {o.newton_iterations} Newton iterations after {o.transient_revs} transient revolutions, "
             f"residual {o.residual:.1e}, period {o.period_revs} revolution, stable {o.stable}, spectral radius "
             f"{o.floquet.spectral_radius:.4f} (leading multiplier {o.floquet.leading}), {o.floquet.n_neutral} "
             "neutral multipliers (a face stuck through the orbit: a continuum of orbits; the Newton step keeps the "
             "transient's conserved levels and the orbit is shot once they stop drifting, settled "
             f"{o.shooting.settled}: rotor/periodic/shooting.py). The transient detector stops at a relative "
             f"Poincaré change of 1e-4 with an estimated {p1['poincare_remaining']:.1e} still to decay.", "",
             f"**Must show ≤ 0.5 s per shooting point: cold start {'holds' if t['shooting'] <= 0.5 else 'does NOT hold'} "
             f"({t['shooting']:.2f} s); warm start {'holds' if t['shooting_warm'] <= 0.5 else 'does NOT hold'} "
             f"({t['shooting_warm']:.2f} s).** **1X–5X within 1e-4 of the transient: "
             f"{'holds' if p1['agree_shooting'] <= 1e-4 else 'does NOT hold'}** ({p1['agree_shooting']:.1e}; from "
             f"the transient's end state {p1['agree_from_end']:.1e}).", "",
             f"## The Fig. 12 cascade by shooting ({len(rows)} speeds 0–18 000 rpm, {workers} processes, "
             f"{blocks} contiguous blocks, each speed started from its neighbour's orbit, a failed warm start "
             "not restarted cold; no transient fallback)", "",
             f"Wall {wall:.1f} s ({len(conv)} of {len(rows)} speeds with an orbit; sum of per-speed times "
             f"{sum(r['wall_s'] for r in rows):.1f} s). **Must show ≤ 30 s: "
             f"{'holds' if wall <= 30 else 'does NOT hold'}.** The published transient cascade took 468 s on 2 "
             "processes (reports/published/study-cascade.md, another run).", "",
             "| speed (rpm) | transient (published) | shooting | stable | spectral radius | leading multiplier "
             "| period (rev) | Newton its | transient revs | wall (s) |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        tr = "not periodic" if r["speed_rpm"] in nonper else "periodic"
        sr = "" if r["spectral_radius"] is None else f"{r['spectral_radius']:.4f}"
        if not r["converged"]:           # the last Newton iterate's multipliers: not an orbit's
            sr, crit = f"({sr}, last iterate)", ""
        else:
            crit = r["leading_multiplier"] or ""
        st = "–" if r["stable"] is None else str(r["stable"])
        lines.append(f"| {r['speed_rpm']:.0f} | {tr} | {r['classification']} | {st} | {sr} | {crit} | "
                     f"{r['period_revs'] or ''} | {r['newton_iterations'] or ''} | {r['transient_revs']} | "
                     f"{r['wall_s']:.2f} |")
    by = {}
    for r in rows:
        if r["speed_rpm"] in nonper:
            by.setdefault(r["classification"], []).append(f"{r['speed_rpm']:.0f}")
    lines += ["", "**The speeds the transient called non-periodic, by their multipliers:** "
              + "; ".join(f"{k}: {', '.join(v)} rpm" for k, v in sorted(by.items())) + ".", ""]
    return "\n".join(lines)


def write_csv(rows: list[dict]) -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=list(rows[0]), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    return buf.getvalue()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--blocks", type=int, default=4, help="contiguous speed blocks (warm starts within each)")
    args = ap.parse_args(argv)
    _warm()
    transient_point()                       # compile the production kernels too
    load0 = os.getloadavg()
    p1 = one_point(args.repeats)
    rows, wall = cascade(args.workers, args.blocks)
    load1 = os.getloadavg()
    atomic_write_text(OUT / "perf-shooting.csv", write_csv(rows))
    atomic_write_text(OUT / "perf-shooting.md", report(p1, rows, wall, [load0, load1], args.repeats, args.workers, args.blocks))
    print((OUT / "perf-shooting.md").read_text())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
