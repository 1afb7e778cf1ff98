"""Compile once: a process with the step loop cached on disk against one that compiles it.

Writes ``reports/published/perf-compile.md`` (+ ``.csv``). Alternating, ``--repeats`` times each:

- **uncached**: ``ringcontact simulate --speed-rpm 10500 --revolutions 20`` in a fresh process with an
  empty cache folder (``RINGCONTACT_CACHE`` pointed at a new temporary folder), so numba compiles the
  contact kernel and the step loop (what every process paid before the cache);
- **cached**: the same command again on the folder the uncached run just filled;
- **worker start**: a fresh process that imports the study code, builds the Table 4 system at
  10 500 rpm and loads the step loop (``rotor.dynamics.production.warm_up``), timed from launch to
  ready to step, on the filled cache; this is what a study worker does before its first point.

Wall times are from the parent (launch to exit); ``compile_s`` and ``run_s`` are the summary's own
split (``simulate-summary.json``). Medians, with the load average at start and end (shared machine).
Run: ``.venv/bin/python benchmarks/bench_compile.py [--repeats 3]`` (about two minutes).
"""
from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402

OUT = ROOT / "reports" / "published"
SIMULATE = ["-m", "reports.cli", "simulate", "--speed-rpm", "10500", "--revolutions", "20"]
WORKER = ("import time, sys; t = float(sys.argv[1]); "
          "from rotor.studies.steady_state import point_system; from rotor.dynamics.production import warm_up; "
          "point_system('paper-table4', 10500.0); info = warm_up(); "
          "print(time.time() - t, info['compile_s'], info['from_cache'])")


def _env(cache: Path) -> dict:
    env = dict(os.environ, RINGCONTACT_CACHE=str(cache), OPENBLAS_NUM_THREADS="1", MPLBACKEND="Agg")
    env["PYTHONPATH"] = str(ROOT) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return env


def simulate_once(cache: Path, out: Path) -> dict:
    """One ``simulate`` process: parent wall time (s) and the summary's compile/run split."""
    t0 = time.perf_counter()
    subprocess.run([sys.executable, *SIMULATE, "--out", str(out)], cwd=ROOT, env=_env(cache), check=True,
                   capture_output=True)
    wall = time.perf_counter() - t0
    s = json.loads((out / "simulate-summary.json").read_text())
    return {"wall_s": wall, "compile_s": s["compile_s"], "run_s": s["run_s"], "from_cache": s["compiled_from_cache"]}


def worker_start(cache: Path) -> dict:
    """Launch to ready-to-step of a study worker (s), on ``cache``."""
    r = subprocess.run([sys.executable, "-c", WORKER, repr(time.time())], cwd=ROOT, env=_env(cache), check=True,
                       capture_output=True, text=True)
    ready, comp, hit = r.stdout.split()
    return {"ready_s": float(ready), "compile_s": float(comp), "from_cache": hit == "True"}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    load0 = os.getloadavg()
    rows = []
    with tempfile.TemporaryDirectory(prefix="bench-compile-") as tmp:
        for i in range(args.repeats):
            cache = Path(tmp) / f"cache{i}"
            cold = simulate_once(cache, Path(tmp) / f"cold{i}")
            warm = simulate_once(cache, Path(tmp) / f"warm{i}")
            work = worker_start(cache)
            rows.append((cold, warm, work))
            print(f"repeat {i + 1}: uncached {cold['wall_s']:.2f} s, cached {warm['wall_s']:.2f} s, "
                  f"worker ready {work['ready_s']:.2f} s", flush=True)
    load1 = os.getloadavg()
    med = lambda k, j: statistics.median(r[j][k] for r in rows)  # noqa: E731
    lines = [
        "# Compile once: the step loop cached on disk",
        "",
        "`benchmarks/bench_compile.py`. `ringcontact simulate --speed-rpm 10500 --revolutions 20` (Table 4 rotor, "
        "production scheme, 5 120 steps) in a fresh process, with an empty cache folder (uncached: numba compiles "
        "the contact kernel and the step loop) and again on the folder that run filled (cached); a study worker's "
        "start (imports, Table 4 system at 10 500 rpm, step loop loaded) on the filled cache. "
        f"Alternating, {args.repeats} repeats, medians. Load average at start {load0[0]:.2f}/{load0[1]:.2f}/"
        f"{load0[2]:.2f}, at end {load1[0]:.2f}/{load1[1]:.2f}/{load1[2]:.2f} (shared machine, 2 cores); "
        f"{platform.processor() or platform.machine()}, Python {platform.python_version()}.",
        "",
        "| | uncached (compiles) | cached (loads) | ratio |",
        "|---|---|---|---|",
        f"| process wall, launch to exit (s) | {med('wall_s', 0):.2f} | {med('wall_s', 1):.2f} | "
        f"{med('wall_s', 0) / med('wall_s', 1):.1f}× |",
        f"| compile or load (`compile_s`, s) | {med('compile_s', 0):.2f} | {med('compile_s', 1):.3f} | "
        f"{med('compile_s', 0) / max(med('compile_s', 1), 1e-9):.0f}× |",
        f"| the rest of the run (`run_s`, s; uncached: includes compiling the array form of the law) | {med('run_s', 0):.3f} | {med('run_s', 1):.3f} | |",
        "",
        f"Study worker, launch to ready to step: median {statistics.median(r[2]['ready_s'] for r in rows):.2f} s "
        f"(of which loading the step loop {statistics.median(r[2]['compile_s'] for r in rows):.3f} s; "
        f"from the cache in {sum(r[2]['from_cache'] for r in rows)} of {len(rows)}).",
        "",
        "Every run: " + "; ".join(f"uncached {c['wall_s']:.2f} s (compile {c['compile_s']:.2f}), cached "
                                  f"{w['wall_s']:.2f} s (load {w['compile_s']:.3f}), worker {k['ready_s']:.2f} s"
                                  for c, w, k in rows) + ".",
        "",
        "The cache lives in `$RINGCONTACT_CACHE/numba`, else `$XDG_CACHE_HOME/ringcontact/numba`, else "
        "`~/.cache/ringcontact/numba` (`contact/compiled_cache.py`); an entry is stale when its module or a module "
        "compiled into it changes. The compiled arithmetic is unchanged: the CSV of the run above is byte-identical "
        "to the one the per-process compile wrote.",
        "",
    ]
    csv = ["repeat,uncached_wall_s,uncached_compile_s,cached_wall_s,cached_compile_s,worker_ready_s"]
    csv += [f"{i + 1},{c['wall_s']:.3f},{c['compile_s']:.3f},{w['wall_s']:.3f},{w['compile_s']:.3f},{k['ready_s']:.3f}"
            for i, (c, w, k) in enumerate(rows)]
    atomic_write_text(OUT / "perf-compile.md", "\n".join(lines))
    atomic_write_text(OUT / "perf-compile.csv", "\n".join(csv) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
