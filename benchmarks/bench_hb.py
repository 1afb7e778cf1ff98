"""Error against cost of the periodic-orbit methods on the soft Jeffcott ring: harmonic balance, shooting, Richardson
and pyHarm-os (a peer HB code), side by side in one run.

The rotor: the verification rotor of :mod:`rotor.periodic.jeffcott` in a frictionless ring with the conformal law
(E = 10 MPa: the soft ring) and ``e = 0.3 δ0`` (as benchmarks/bench_grazing.py), swept 1 500 → 6 000 rpm from the
free orbit: grazing at 279.7 rad/s, fold near 446.4, grazing fold near 374.7, back out free to 6 000 rpm. Rows:

* ``HB``: :func:`rotor.periodic.harmonic_balance.hb_branch`, one harmonic (exact for this rotor), 6 AFT samples;
* ``shooting N``: :func:`rotor.periodic.grazing.continue_through_grazing` with N steps per revolution (the way of
  ``ringcontact branch`` through grazing), N = 64 and 256;
* ``Richardson N/2N``: that branch with N steps, every point corrected with 2N and extrapolated
  (:func:`rotor.periodic.richardson.extrapolate_branch`), N = 128;
* ``pyHarm-os``: the same rotor written in pyHarm-os (benchmarks/pyharm_jeffcott.py: its own linear elements and
  forcing, the ring as an element against its element API with the same conformal law constants), one harmonic,
  its FRF continuation, run as a subprocess in a venv of its own (installed by this script from PyPI, pinned).

Error of a point: its relative speed distance from the continuous-time closed form at its orbit radius
(:func:`rotor.periodic.jeffcott.closed_form_speeds`, no warping); largest and median over the branch, and the
largest distance of the turning points found from the closed form's. Cost: process CPU time of the branch
(``time.process_time``; pyHarm's measured inside its subprocess around ``Maestro.operate``, the model built and
its kernels compiled by a first run in the same process beforehand), median of ``--repeat`` interleaved rounds;
everything compiled beforehand. Load average at start and end (shared 2-core machine). Writes
``reports/published/perf-hb.md`` and ``perf-hb.json``. Run: ``nice .venv/bin/python benchmarks/bench_hb.py``.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402
from rotor.periodic.continuation import ContinuationOptions, speed_problem  # noqa: E402
from rotor.periodic.grazing import continue_through_grazing  # noqa: E402
from rotor.periodic.harmonic_balance import hb_branch  # noqa: E402
from rotor.periodic.jeffcott import (JeffcottParams, closed_form_folds, closed_form_grazing,  # noqa: E402
                                     closed_form_speeds, jeffcott_system)
from rotor.periodic.richardson import extrapolate_branch  # noqa: E402

OUT = ROOT / "reports" / "published"
P = JeffcottParams(law="conformal", eccentricity_m=3e-6)
W0, W1 = 1500.0 * math.pi / 30.0, 6000.0 * math.pi / 30.0
SCALES = np.concatenate([np.full(4, 1e-5), np.full(4, 0.005)])
PYHARM = "pyHarm-os==1.2.2"
VENV = Path(tempfile.gettempdir()) / "ringcontact-bench-hb" / "pyharm-venv"


def _errors(speeds, radii) -> np.ndarray:
    out = []
    for w, r in zip(speeds, radii):
        s = closed_form_speeds(P, r)
        out.append(float(np.min(np.abs(s - w)) / w) if len(s) else math.inf)
    return np.array(out)


def _turn_error(found: list[float]) -> float:
    """Largest relative distance of the closed form's turning points from the nearest one found (inf if none)."""
    exact = [w for w, _ in closed_form_folds(P, r_max_factor=9.9)] + \
        [w for w, k in closed_form_grazing(P) if k == "grazing_fold"]
    if not found:
        return math.inf
    return max(min(abs(f / x - 1) for f in found) for x in exact)


def run_hb():
    c0 = time.process_time()
    br = hb_branch(lambda w: jeffcott_system(P, w), W0, W1, 1)
    cpu = time.process_time() - c0
    r = np.hypot(br.coefficients[:, 1, 0], br.coefficients[:, 2, 0])
    return {"stop": br.stop, "points": len(r), "errors": _errors(br.speeds_rad_s, r),
            "turns": [e.speed_rad_s for e in br.folds()], "cpu_s": cpu}


def run_shooting(n: int, richardson: bool = False):
    pb = speed_problem(lambda w: jeffcott_system(P, w), n, modes0=(0, 0))
    c0 = time.process_time()
    br = continue_through_grazing(pb, np.zeros(8), W0, W1, scales=SCALES, lam_scale=30.0,
                                  options=ContinuationOptions(ds=0.1, ds_max=0.4))
    turns = [b.parameter for b in br.bifurcations if b.kind in ("fold", "grazing_fold")]
    if not richardson:
        cpu = time.process_time() - c0
        states = [p.state for p in br.points]
        return {"stop": br.stop, "points": len(states), "cpu_s": cpu, "turns": turns,
                "errors": _errors(br.parameters(), [math.hypot(x[0], x[1]) for x in states])}
    ex = extrapolate_branch(pb, br, scales=SCALES, lam_scale=30.0)
    cpu = time.process_time() - c0
    ok = ex.converged
    return {"stop": f"{br.stop}, {int(ok.sum())}/{len(ok)} extrapolated", "points": len(ok), "cpu_s": cpu,
            "turns": turns, "errors": _errors(ex.parameters[ok], np.hypot(ex.states[ok, 0], ex.states[ok, 1])),
            "speeds": ex.parameters[ok]}


def ensure_pyharm() -> str | None:
    """pyHarm-os in a venv of its own (``python3 -m venv`` + pip); None if it could not be installed (the reason
    is then in the returned text)."""
    py = VENV / "bin" / "python"
    if py.exists() and subprocess.run([str(py), "-c", "import pyHarm"], capture_output=True,
                                      cwd=VENV.parent).returncode == 0:
        return None
    VENV.parent.mkdir(parents=True, exist_ok=True)
    for cmd in (["python3", "-m", "venv", str(VENV)], [str(py), "-m", "pip", "install", "-q", PYHARM]):
        res = subprocess.run(cmd, capture_output=True, text=True, cwd=VENV.parent)
        if res.returncode != 0:
            return f"`{' '.join(cmd)}` failed: {(res.stderr or res.stdout).strip().splitlines()[-1:]}"
    return None


def run_pyharm(workdir: Path):
    """The pyHarm model's branch (second run in its process: the first compiles). Errors from its coefficients."""
    p = P.law_params()
    k = p.kernel_args
    params = {"mass_kg": P.mass_kg, "stiffness_N_m": P.stiffness_N_m, "damping_N_s_m": P.damping_N_s_m,
              "eccentricity_m": P.eccentricity_m, "n_time": 16, "speed0_rad_s": W0, "speed1_rad_s": W1,
              "ds0": 1.0, "ds_max": 5.0, "repeat": 2,
              "law": {"clearance_m": k[0], "width_m": k[1], "c3": k[3], "alpha": k[4], "beta": k[5]}}
    (workdir / "params.json").write_text(json.dumps(params))
    res = subprocess.run([str(VENV / "bin" / "python"), str(ROOT / "benchmarks" / "pyharm_jeffcott.py"),
                          str(workdir / "params.json"), str(workdir / "out.json")], capture_output=True, text=True,
                         cwd=workdir)
    if res.returncode != 0:
        raise RuntimeError("pyHarm run failed: " + (res.stderr.strip().splitlines() or ["?"])[-1])
    out = json.loads((workdir / "out.json").read_text())
    w = np.array([pt[0] for pt in out["points"]])
    x = np.array([pt[1] for pt in out["points"]])
    r = np.hypot(x[:, 2], x[:, 4])
    return {"stop": f"{len(w)} accepted points to {w[-1]:.2f} rad/s", "points": len(w), "cpu_s": out["cpu_s"],
            "cold_cpu_s": out["cold_cpu_s"], "turns": out["folds"], "errors": _errors(w, r), "speeds": w,
            "version": out["version"]}


def _table(rows: dict) -> list[str]:
    ref = rows.get("pyHarm-os", {}).get("cpu_s")
    lines = ["| method | stop | points | largest rel. error | median | turning points vs closed form | CPU s (median) "
             "| CPU / pyHarm-os | CPU / HB |", "|---|---|---|---|---|---|---|---|---|"]
    for name, r in rows.items():
        e = r["errors"]
        lines.append(f"| {name} | {r['stop']} | {r['points']} | {e.max():.2e} | {np.median(e):.2e} | "
                     f"{_turn_error(r['turns']):.1e} | {r['cpu_s']:.3f} | "
                     f"{(r['cpu_s'] / ref if ref else math.nan):.3f} | {r['cpu_s'] / rows['HB']['cpu_s']:.1f} |")
    return lines


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    why_not = ensure_pyharm()
    methods = {"HB": run_hb, "shooting 64": lambda: run_shooting(64), "shooting 256": lambda: run_shooting(256),
               "Richardson 128/256": lambda: run_shooting(128, True)}
    work = Path(tempfile.mkdtemp(prefix="bench-hb-"))
    if why_not is None:
        methods["pyHarm-os"] = lambda: run_pyharm(work)
    for f in methods.values():       # compile (or load) every kernel outside the timings
        f()
    loads = [os.getloadavg()]
    runs: dict = {name: [] for name in methods}
    for _ in range(args.repeat):     # interleaved rounds
        for name, f in methods.items():
            runs[name].append(f())
    loads.append(os.getloadavg())
    rows = {}
    for name, rs in runs.items():
        rows[name] = dict(rs[-1], cpu_s=statistics.median(r["cpu_s"] for r in rs), cpus=[r["cpu_s"] for r in rs])
    text = report(rows, loads, args.repeat, why_not)
    atomic_write_text(OUT / "perf-hb.md", text)
    data = {name: {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in r.items()} for name, r in rows.items()}
    atomic_write_text(OUT / "perf-hb.json", json.dumps({"loads": loads, "repeat": args.repeat, "rows": data,
                                                        "pyharm_missing": why_not}, indent=1) + "\n")
    print(text)
    return 0


def report(rows: dict, loads: list, repeat: int, why_not: str | None) -> str:
    hb, ph = rows["HB"], rows.get("pyHarm-os")
    exact = [w for w, _ in closed_form_folds(P, r_max_factor=9.9)] + \
        [w for w, k in closed_form_grazing(P) if k == "grazing_fold"]
    lines = ["# Periodic orbits: error against cost (HB, shooting, Richardson, pyHarm-os)", "",
             f"Made by `benchmarks/bench_hb.py` (CPU time, median of {repeat} interleaved rounds, one process each, "
             f"everything compiled beforehand); load average {loads[0][0]:.2f} at start, {loads[1][0]:.2f} at the end "
             "(shared 2-core machine). Rotor: `JeffcottParams(law=\"conformal\", eccentricity_m=3e-6)` (the soft "
             f"ring), {W0:.4f} → {W1:.4f} rad/s (1 500 → 6 000 rpm) from the free orbit. Error: relative speed "
             "distance of each orbit from the continuous-time closed form at its radius; turning points: largest "
             "relative distance of the closed form's fold and grazing fold ("
             + ", ".join(f"{w:.6f}" for w in sorted(exact)) + " rad/s) from the nearest found.", ""]
    lines += _table(rows)
    lines += ["", "Reading (this run): HB with one harmonic is exact for this rotor (the contact force on a circular "
              f"orbit is a pure first harmonic): its largest error is {hb['errors'].max():.1e}, the Newton "
              "tolerance, where shooting carries the trapezoidal rule's frequency warping (O(h²)) and Richardson "
              "its O(h⁴) remainder."]
    if ph is not None:
        lines[-1] += (f" CPU: HB took {hb['cpu_s'] / ph['cpu_s']:.3f} times pyHarm-os's CPU on the same branch "
                      f"(pyHarm-os {ph['version']}, warm second run in its process; its first run, with jax/numba "
                      f"compilation, took {ph['cold_cpu_s']:.2f} s). Its turning points are the continuation's "
                      "points where the frequency turns (pyHarm-os reports folds, it does not locate them).")
    else:
        lines += ["", f"pyHarm-os was not run: {why_not}."]
    for name in ("pyHarm-os", "Richardson 128/256"):
        r = rows.get(name)
        if r is not None and "speeds" in r:
            off = r["errors"] > 1e-6
            lines += ["", f"{name}: {int(off.sum())} of {len(off)} points more than 1e-6 off the curve, at "
                      + ", ".join(f"{w:.2f}" for w in np.asarray(r["speeds"])[off]) + " rad/s (the grazing fold is at "
                      f"{min(exact):.4f} rad/s; no orbit of the closed form exists below it on the free side); the "
                      f"others within {r['errors'][~off].max():.1e}."]
    lines += ["", "The pyHarm-os model (benchmarks/pyharm_jeffcott.py) omits the Lankarani–Nikravesh factor (1 on a "
              "circular orbit, so the same one-harmonic solution) and uses 16 time samples; HB here uses 6 (4H + 2).",
              ""]
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
