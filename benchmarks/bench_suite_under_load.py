"""The README's test command on a fresh clone with CPU hogs beside it: does it pass on a loaded machine?

Writes ``reports/published/perf-test-suite.md``. For each of ``--runs`` runs, in a row: ``--hogs`` busy-loop
processes start, then ``python3 dev.py test`` runs in the clone (the first run also builds its ``.venv``);
the hogs stop when it ends. Recorded per run: exit status, wall time, the pytest summary line, the load
average sampled every 10 s (mean and maximum), and the 15 slowest tests (pytest's ``--durations=15``); each
run's log is ``.suite-run-K.log`` in the clone.

Run: ``python3 benchmarks/bench_suite_under_load.py --clone /tmp/fresh [--runs 2 --hogs 2]`` where the
clone is a fresh ``git clone`` of the commit to measure (about 20-30 min a run at load 4 on 2 cores).
"""
from __future__ import annotations

import argparse
import os
import platform
import re
import subprocess
import sys
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402

HOG = "while True: pass"


def _sample_load(stop: threading.Event, into: list) -> None:
    while not stop.is_set():
        into.append(os.getloadavg()[0])
        stop.wait(10.0)


def one_run(clone: Path, hogs: int, log: Path) -> dict:
    procs = [subprocess.Popen([sys.executable, "-c", HOG]) for _ in range(hogs)]
    loads: list[float] = []
    stop = threading.Event()
    sampler = threading.Thread(target=_sample_load, args=(stop, loads), daemon=True)
    t0 = time.monotonic()
    sampler.start()
    try:
        with open(log, "w") as fh:
            rc = subprocess.run([sys.executable, "dev.py", "test"], cwd=clone, stdout=fh, stderr=subprocess.STDOUT).returncode
    finally:
        wall = time.monotonic() - t0
        stop.set()
        for p in procs:
            p.kill()
            p.wait()
    return {"rc": rc, "wall_s": wall, "load_mean": sum(loads) / max(len(loads), 1),
            "load_max": max(loads, default=float("nan")), **parse_log(log.read_text(errors="replace"))}


def parse_log(text: str) -> dict:
    """The pytest summary line, the 15 slowest tests and the failed ones from a ``dev.py test`` log."""
    summary = [ln for ln in text.splitlines() if re.search(r"\d+ (passed|failed)", ln) and " in " in ln]
    after = text.split("slowest 15 durations", 1)[1].splitlines()[1:] if "slowest 15 durations" in text else []
    slowest = []
    for ln in after:
        if not ln.strip() or ln.startswith(("=", "(")):
            break
        slowest.append(ln)
    failed = [ln for ln in text.splitlines() if ln.startswith(("FAILED", "ERROR"))]
    return {"summary": summary[-1].strip("= ") if summary else "(no summary)", "slowest": slowest, "failed": failed}


def render(runs: list[dict], commit: str, hogs: int) -> str:
    """The report's Markdown for ``runs`` (each :func:`one_run`'s dict) on ``commit`` with ``hogs`` busy loops."""
    lines = ["# The test command under load", "",
             f"`benchmarks/bench_suite_under_load.py` on a fresh clone of commit {commit}: `python3 dev.py test` "
             f"{len(runs)} times in a row, each with {hogs} busy-loop processes beside it (`{HOG}`), on "
             f"{os.cpu_count()} cores ({platform.machine()}, Python {platform.python_version()}). The first run "
             "also creates the clone's `.venv` and installs everything. Load average sampled every 10 s.", "",
             "| run | exit status | wall (min) | load mean / max | pytest summary |", "|---|---|---|---|---|"]
    for k, r in enumerate(runs, 1):
        lines.append(f"| {k} | {r['rc']} | {r['wall_s'] / 60:.1f} | {r['load_mean']:.1f} / {r['load_max']:.1f} | "
                     f"{r['summary']} |")
    for k, r in enumerate(runs, 1):
        lines += ["", f"## Run {k}: the 15 slowest tests", "", "```", *r["slowest"], "```"]
        if r["failed"]:
            lines += ["", "Failed:", "", *[f"- `{f}`" for f in r["failed"]]]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--clone", type=Path, required=True, help="a fresh git clone of the commit to measure")
    ap.add_argument("--runs", type=int, default=2)
    ap.add_argument("--hogs", type=int, default=2)
    ap.add_argument("--out", type=Path, default=ROOT / "reports" / "published" / "perf-test-suite.md")
    a = ap.parse_args(argv)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=a.clone, capture_output=True,
                            text=True).stdout.strip()
    runs = []
    for k in range(a.runs):
        r = one_run(a.clone, a.hogs, a.clone / f".suite-run-{k + 1}.log")     # logs in the clone, not the repo
        runs.append(r)
        print(f"run {k + 1}: rc {r['rc']}, {r['wall_s'] / 60:.1f} min, load mean {r['load_mean']:.1f} max "
              f"{r['load_max']:.1f}: {r['summary']}", flush=True)
    atomic_write_text(a.out, render(runs, commit, a.hogs))
    print(f"wrote {a.out}")
    return 0 if all(r["rc"] == 0 for r in runs) else 1


if __name__ == "__main__":
    sys.exit(main())
