"""Error against cost of the periodic-orbit methods on the seeded family of Jeffcott-ring SCENES (rotor/periodic/
jeffcott_scene.py: random_family, each rotor written as a scene file and built as every job builds it), and HB
against shooting on Table 4 without friction; one run, ratios of CPU from that run.

Family rows, each rotor over rotor/studies/grazing_family.py's sweep_range (through grazing, the jump-down fold and
the grazing fold):

* ``HB``: rotor/studies/hb_orbit.py hb_scene_branch, one harmonic (exact for the circular whirl), 6 AFT samples;
* ``pyHarm-os``: the same rotor and support node in pyHarm-os (benchmarks/pyharm_jeffcott_ring.py, its own venv,
  as benchmarks/bench_hb.py), one harmonic, its FRF continuation (warm second run in its process);
* ``shooting N`` and ``Richardson N/2N``: rotor/studies/orbit.py branch (the ``ringcontact branch`` path) at the
  scene's steps per revolution N (256, more where the contact step limit needs it), the second with
  ``richardson=True`` (every point corrected at 2N and extrapolated), on the first ``--shooting-count`` rotors.

Error of an orbit: its relative distance from the CONTINUOUS closed form (grazing_family.orbit_distance with no
step: the smaller of the speed distance at its radius and the radius distance at its speed); the radius is HB's and
pyHarm's first-harmonic relative radius, shooting's δ0 + its largest edge penetration (contact orbits only: a free
orbit's radius is not in the branch's JSON). CPU: ``time.process_time`` of each branch, everything compiled by a
first rotor beforehand. Table 4 (paper-table4, ``mu = 0``): at each speed the shooting orbit (its ``richardson``
too), then HB from the shooting orbit's spectrum with 8, 16 and 32 harmonics; the largest 1X velocity amplitude
difference over the response channels relative to the largest 1X amplitude. Writes reports/published/
perf-hb-scenes.md and .json. Run: ``nice .venv/bin/python benchmarks/bench_hb_scenes.py``.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

from bench_hb import VENV, ensure_pyharm  # noqa: E402

from contact.files import atomic_write_text  # noqa: E402
from rotor.periodic.jeffcott_scene import random_family, scene_toml  # noqa: E402
from rotor.studies.grazing_family import orbit_distance, sweep_range  # noqa: E402
from rotor.studies.hb_orbit import hb_scene_branch, relative_radius  # noqa: E402
from rotor.studies.orbit import branch  # noqa: E402
from rotor.studies.steady_state import point_system  # noqa: E402

OUT = ROOT / "reports" / "published"
#: a pyHarm-os branch still running after this (s, wall: two runs in its process) is stopped and reported as such
PYHARM_TIMEOUT_S = 120.0
TO_RPM = 30.0 / math.pi


def run_hb(rotor, scene: str, low: float, high: float) -> dict:
    c0 = time.process_time()
    res = hb_scene_branch(scene, low, high, harmonics=1)
    cpu = time.process_time() - c0
    system = point_system(scene, low)[2]
    br = res["branch"]
    err = [orbit_distance(rotor, float(w), relative_radius(system, c), None) for w, c in zip(br.speeds_rad_s, br.coefficients)]
    # CPU of the continuation itself (hb_branch on the scene's system built once), as pyHarm's is its analysis;
    # "with_fields_cpu_s" adds the reported fields (amplitudes, contact summary) of every point
    return {"cpu_s": br.cpu_s, "with_fields_cpu_s": cpu, "points": len(err), "errors": err, "stop": res["stop"]}


def run_shooting(rotor, scene: str, low: float, high: float, richardson: bool) -> dict:
    c0 = time.process_time()
    res = branch(scene, low, high, richardson=richardson)
    cpu = time.process_time() - c0
    err = []
    for p in res.points:
        q = p["richardson"] if richardson else p
        if richardson and not q.get("converged"):
            continue
        pen = q["max_edge_penetration_mm"] * 1e-3
        if pen > 0:
            err.append(orbit_distance(rotor, q.get("speed_rpm", p["speed_rpm"]) / TO_RPM, rotor.clearance_m + pen, None))
    return {"cpu_s": cpu, "points": len(res.points), "errors": err, "stop": res.stop}


def run_pyharm(rotor, low: float, high: float, work: Path) -> dict:
    args = rotor.law_params().kernel_args          # the law's constants, as benchmarks/bench_hb.py passes them
    params = {"mass_kg": rotor.mass_kg, "stiffness_N_m": rotor.stiffness_N_m, "damping_N_s_m": rotor.damping_N_s_m,
              "eccentricity_m": rotor.eccentricity_m, "support_mass_kg": rotor.support_mass_kg,
              "support_stiffness_N_m": rotor.support_stiffness_N_m, "support_damping_N_s_m": rotor.support_damping_N_s_m,
              "n_time": 16, "speed0_rad_s": low / TO_RPM, "speed1_rad_s": high / TO_RPM,
              "ds0": 1.0, "ds_max": 5.0, "repeat": 2,
              "law": {"clearance_m": args[0], "width_m": args[1], "c3": args[3], "alpha": args[4], "beta": args[5]}}
    (work / "params.json").write_text(json.dumps(params))
    try:
        res = subprocess.run([str(VENV / "bin" / "python"), str(ROOT / "benchmarks" / "pyharm_jeffcott_ring.py"),
                              str(work / "params.json"), str(work / "out.json")], capture_output=True, text=True,
                              cwd=work, timeout=PYHARM_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return {"cpu_s": math.nan, "points": 0, "errors": [], "stop": f"not finished in {PYHARM_TIMEOUT_S:g} s wall"}
    if res.returncode != 0:
        return {"cpu_s": math.nan, "points": 0, "errors": [],
                "stop": "failed: " + (res.stderr.strip().splitlines() or ["?"])[-1][:120]}
    out = json.loads((work / "out.json").read_text())
    w = np.array([pt[0] for pt in out["points"]])
    x = np.array([pt[1] for pt in out["points"]])
    r = np.hypot(x[:, 4] - x[:, 6], x[:, 8] - x[:, 10])       # (y of rotor − support), cos and sin rows
    err = [orbit_distance(rotor, float(a), float(b), None) for a, b in zip(w, r)]
    return {"cpu_s": out["cpu_s"], "points": len(w), "errors": err, "stop": f"to {w[-1]:.2f} rad/s",
            "version": out["version"]}


def _sums(rs: list, ph: list) -> tuple[float, float, int]:
    """CPU sums of ``rs`` and of pyHarm-os on the rotors where pyHarm-os finished, and that count."""
    both = [(r["cpu_s"], p["cpu_s"]) for r, p in zip(rs, ph) if math.isfinite(p["cpu_s"])]
    return sum(a for a, _ in both), sum(b for _, b in both), len(both)


def table4(speeds_rpm, harmonics=(8, 16, 32)) -> list[dict]:
    """paper-table4 without friction: shooting (and Richardson) at each speed, then HB from the shooting orbit's
    spectrum; 1X differences relative to the largest 1X amplitude (rotor/studies/orbit_methods.amplitude_difference)."""
    from rotor.periodic.harmonic_balance import hb_orbit
    from rotor.periodic.period_flow import make_flow, record
    from rotor.studies.hb_orbit import orbit_fields, spectrum_tail
    from rotor.studies.orbit import orbit
    from rotor.studies.orbit_methods import amplitude_difference
    rows = []
    for rpm in speeds_rpm:
        _, model, system = point_system("paper-table4", rpm, mu=0.0)
        c0 = time.process_time()
        o = orbit("paper-table4", rpm, mu=0.0, richardson=True)
        row = {"speed_rpm": rpm, "shooting_cpu_s": time.process_time() - c0, "shooting_converged": o.converged,
               "steps_per_rev": o.steps_per_rev, "stable": o.stable, "contact_share": o.contact.get("contact_share"),
               "richardson_change": (o.richardson or {}).get("largest_change_from_N"), "hb": []}
        if o.converged:
            n, P = o.steps_per_rev, o.period_revs
            flow = make_flow(system, 2.0 * math.pi / (system.omega_rad_s * n))
            q = record(flow, o.shooting.state, o.shooting.t0_s, n * P, o.shooting.modes, 1).q[:-1]
            X = np.fft.rfft(q, axis=0) / len(q)
            for H in harmonics:
                c = np.zeros((2 * H + 1, system.n))
                c[0] = X[0].real
                c[1::2], c[2::2] = 2.0 * X[1:H + 1].real, -2.0 * X[1:H + 1].imag
                c0 = time.process_time()
                h = hb_orbit(system, H, 8 * H, period_revs=P, guess=c)
                cpu = time.process_time() - c0
                f = orbit_fields(system, model, h.coefficients, h.speed_rad_s, P)["velocity_amplitudes_mm_s_1X_to_5X"]
                d = amplitude_difference(f, o.velocity_amplitudes_mm_s_1X_to_5X)
                dr = (amplitude_difference(f, o.richardson["velocity_amplitudes_mm_s_1X_to_5X"])
                      if o.richardson and o.richardson.get("converged") else {})
                row["hb"].append({"harmonics": H, "n_time": 8 * H, "converged": h.converged, "cpu_s": cpu,
                                  "tail": spectrum_tail(system, h.coefficients) if h.converged else None,
                                  "vs_shooting": d["largest_1X_difference_rel"],
                                  "vs_richardson": dr.get("largest_1X_difference_rel")})
        rows.append(row)
        print(row, flush=True)
    return rows


def family(seed: int, count: int, shooting_count: int) -> dict:
    rotors = random_family(seed, count)
    work = Path(tempfile.mkdtemp(prefix="bench-hb-scenes-"))
    why_not = ensure_pyharm()
    rows: dict = {"HB": [], "pyHarm-os": [], "shooting N": [], "Richardson N/2N": []}
    for k, rotor in enumerate(rotors):
        scene = work / f"r{k}.toml"
        scene.write_text(scene_toml(rotor), encoding="utf-8")
        low, high = sweep_range(rotor)
        if k == 0:                        # compile (or load) every kernel outside the timings
            run_hb(rotor, str(scene), low, high)
            branch(str(scene), low, 1.05 * low, richardson=True)
        rows["HB"].append(run_hb(rotor, str(scene), low, high))
        if why_not is None:
            rows["pyHarm-os"].append(run_pyharm(rotor, low, high, work))
        if k < shooting_count:
            rows["shooting N"].append(run_shooting(rotor, str(scene), low, high, False))
            rows["Richardson N/2N"].append(run_shooting(rotor, str(scene), low, high, True))
        print(k, {m: (r[-1]["cpu_s"], max(r[-1]["errors"], default=math.nan)) for m, r in rows.items() if len(r) > k},
              flush=True)
    return {"rows": rows, "pyharm_missing": why_not}


def report(seed, count, fam, t4, loads) -> str:
    rows = fam["rows"]
    hb = rows["HB"]
    lines = ["# HB on the Jeffcott-ring scene family and on Table 4 without friction: error against cost", "",
             f"Made by `benchmarks/bench_hb_scenes.py` in one run (one process, CPU time, everything compiled "
             f"beforehand); load average {loads[0][0]:.2f} at start, {loads[1][0]:.2f} at the end (shared 2-core "
             f"machine). Family: `random_family({seed}, {count})` of rotor/periodic/jeffcott_scene.py, each rotor a "
             "scene file, over grazing_family.sweep_range. Error: relative distance of each orbit from the continuous "
             "closed form (shooting and Richardson: contact orbits only).", "",
             "| method | rotors | orbits | largest error | median error | CPU s (sum) | CPU / pyHarm-os (same rotors) |",
             "|---|---|---|---|---|---|---|"]
    ph = rows.get("pyHarm-os") or []
    for name, rs in rows.items():
        if not rs:
            continue
        e = [x for r in rs for x in r["errors"]] or [math.nan]
        cpu = sum(r["cpu_s"] for r in rs)
        a, b, m = _sums(rs, ph) if ph else (math.nan, math.nan, 0)
        lines.append(f"| {name} | {len(rs)} | {sum(r['points'] for r in rs)} | {max(e):.2e} | {np.median(e):.2e} | "
                     f"{cpu:.2f} | {a / b if m else math.nan:.3f} (on {m}) |")
    if ph:
        ratios = [h["cpu_s"] / p["cpu_s"] for h, p in zip(hb, ph) if math.isfinite(p["cpu_s"])] or [math.nan]
        ver = next((p["version"] for p in ph if "version" in p), "?")
        npts = lambda rs: [r["points"] for r in rs if r["points"]]  # noqa: E731
        lines += ["", f"HB / pyHarm-os CPU per rotor: {min(ratios):.2f} to {max(ratios):.2f} (pyHarm-os {ver}, one "
                  "harmonic, 16 time samples, benchmarks/pyharm_jeffcott_ring.py). HB CPU: the continuation "
                  "(hb_branch on the scene's system built once: rotor/dynamics/build.py SpeedFamily, its speed "
                  "dependence exact), events located included; with every point's reported fields "
                  f"{sum(r['with_fields_cpu_s'] for r in hb):.2f} s. Orbits per rotor over the same speed range: HB "
                  f"{min(npts(hb))} to {max(npts(hb))} (median {np.median(npts(hb)):g}; step in scaled arclength, "
                  "grazings, folds and grazing folds each located by their own solves), pyHarm-os "
                  f"{min(npts(ph), default=0)} to {max(npts(ph), default=0)} (median {np.median(npts(ph) or [0]):g}; "
                  "ds0 1, ds_max 5 rad/s, its step doubled after 5 accepted, no event located). Every HB stop: "
                  f"{sorted({r['stop'] for r in hb})}; pyHarm-os stops: {[p['stop'] for p in ph]}."]
    else:
        lines += ["", f"pyHarm-os was not run: {fam['pyharm_missing']}."]
    lines += ["", "## Table 4 without friction (paper-table4 --mu 0)", "",
              "Shooting at the scene's steps per revolution from its transient, Richardson from its 2N orbit; HB "
              "started from the shooting orbit's spectrum (8H AFT samples). Difference: largest 1X velocity amplitude "
              "difference over the response channels over the largest 1X amplitude.", "",
              "| speed rpm | shooting (N, CPU s, stable, contact share) | H | HB converged | HB CPU s | spectrum tail | "
              "HB vs shooting | HB vs Richardson |", "|---|---|---|---|---|---|---|---|"]
    for r in t4:
        head = (f"{r['steps_per_rev']}, {r['shooting_cpu_s']:.1f}, {r['stable']}, {r['contact_share']}"
                if r["shooting_converged"] else "no orbit")
        for h in r["hb"] or [{}]:
            fmt = lambda x: "–" if x is None else f"{x:.1e}"  # noqa: E731
            lines.append(f"| {r['speed_rpm']:g} | {head} | {h.get('harmonics', '–')} | {h.get('converged', '–')} | "
                         f"{h.get('cpu_s', math.nan):.2f} | {fmt(h.get('tail'))} | {fmt(h.get('vs_shooting'))} | "
                         f"{fmt(h.get('vs_richardson'))} |")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=20261129)
    ap.add_argument("--count", type=int, default=10)
    ap.add_argument("--shooting-count", type=int, default=3)
    ap.add_argument("--table4-rpm", type=float, nargs="*", default=[10500.0, 15000.0])
    args = ap.parse_args(argv)
    loads = [os.getloadavg()]
    fam = family(args.seed, args.count, args.shooting_count)
    t4 = table4(args.table4_rpm)
    loads.append(os.getloadavg())
    text = report(args.seed, args.count, fam, t4, loads)
    atomic_write_text(OUT / "perf-hb-scenes.md", text)
    atomic_write_text(OUT / "perf-hb-scenes.json", json.dumps({"loads": loads, "seed": args.seed, "family": fam,
                                                                 "table4": t4}, indent=1, default=float) + "\n")
    print(text)
    return 0


if __name__ == "__main__" and "--probe" not in sys.argv:
    sys.exit(main())
if __name__ == "__main__" and "--probe" in sys.argv:
    rotor = random_family(int(sys.argv[-1]), 1)[0]
    low, high = sweep_range(rotor)
    w = Path(tempfile.mkdtemp())
    print(ensure_pyharm())
    r = run_pyharm(rotor, low, high, w)
    print(r["cpu_s"], r["points"], max(r["errors"]), np.median(r["errors"]))
