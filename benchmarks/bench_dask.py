"""Per-point throughput of a rotor sweep on dask.distributed against the local process pool.

Writes ``reports/published/perf-dask.md`` (+ ``.csv``). Both executors have 2 single-threaded
worker processes on this machine and are warmed up first (each worker has imported the study code
and loaded the compiled step loop from the disk cache, :mod:`contact.compiled_cache`), so what is
compared is the steady cost of a point: the same dozen steady-state points of the paper's Table 4
rotor (``--points`` speeds from 1500 to 18 000 rpm, ``--steps-per-rev`` and ``--max-revs`` kept
small) through :func:`sweep.run_sweep` into a fresh result store, alternating pool and dask
``--repeats`` times. Reported: points per second of sweep wall time (client side: submission,
transfer of the arrays back, checksummed store) and the median compute time of a point on its
worker, medians over the repeats, with the load average at start and end (shared machine).

Run: ``.venv/bin/python benchmarks/bench_dask.py [--repeats 3]`` (about two minutes).
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from contact.files import atomic_write_text  # noqa: E402

OUT = ROOT / "reports" / "published"


def _tasks(points: int, steps_per_rev: int, max_revs: int, prefix: str = "rpm"):
    from rotor.studies.steady_state import sweep_tasks

    speeds = np.linspace(1500.0, 18000.0, points)
    return sweep_tasks("paper-table4", speeds, prefix=prefix, options={"steps_per_rev": steps_per_rev,
                                                                       "max_revs": max_revs})


def _one(executor, tasks, root: Path) -> dict:
    from sweep import run_sweep

    t0 = time.perf_counter()
    s = run_sweep(tasks, root, executor=executor, progress=False)
    wall = time.perf_counter() - t0
    assert not s.failed and len(s.computed) == len(tasks), s.failed
    return {"wall_s": wall, "points_per_s": len(tasks) / wall,
            "point_median_s": statistics.median(s.point_wall_s.values()),
            "point_sum_s": sum(s.point_wall_s.values())}


def measure(points: int, repeats: int, steps_per_rev: int, max_revs: int) -> dict:
    """Warm both executors, then alternate the timed sweeps; returns the runs per executor."""
    from distributed import Client, LocalCluster

    from sweep import local_pool

    tasks = _tasks(points, steps_per_rev, max_revs)
    warm = _tasks(4, steps_per_rev, 40, prefix="warm")
    runs = {"local pool": [], "dask": []}
    with tempfile.TemporaryDirectory(prefix="bench-dask-") as tmp, local_pool(2) as pool, \
            LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
            Client(cluster) as client:
        ex = {"local pool": pool, "dask": client}
        for name, e in ex.items():
            _one(e, warm, Path(tmp) / f"warm-{name}")
        for r in range(repeats):
            for name, e in ex.items():
                runs[name].append(_one(e, tasks, Path(tmp) / f"{name}-{r}"))
    return runs


def report(runs: dict, args, load_start, load_end) -> str:
    med = {n: {k: statistics.median(x[k] for x in rs) for k in rs[0]} for n, rs in runs.items()}
    ratio = med["dask"]["points_per_s"] / med["local pool"]["points_per_s"]
    lines = ["# Sweep throughput: dask.distributed against the local process pool", "",
             f"{args.points} steady-state points of the paper's Table 4 rotor (1500–18 000 rpm, steps_per_rev "
             f"{args.steps_per_rev}, max_revs {args.max_revs}) through `sweep.run_sweep`, 2 single-threaded worker "
             f"processes each, both warmed up (compiled step loop loaded from the disk cache) before timing; "
             f"{args.repeats} alternating repeats, medians. Machine: {platform.node()}, {os.cpu_count()} cores "
             f"(shared); load average {load_start[0]:.2f} at start, {load_end[0]:.2f} at end.", "",
             "| executor | points/s (sweep wall) | sweep wall s | point on its worker, median s | sum of point times s |",
             "|---|---|---|---|---|"]
    for n, m in med.items():
        lines.append(f"| {n} | {m['points_per_s']:.3f} | {m['wall_s']:.2f} | {m['point_median_s']:.3f} | "
                     f"{m['point_sum_s']:.2f} |")
    lines += ["", f"dask / local pool throughput: **{ratio:.3f}** (points per second of sweep wall time); "
              f"per-point compute on the worker: {med['dask']['point_median_s'] / med['local pool']['point_median_s']:.3f}.",
              "", _reading(runs, ratio),
              "", "Each repeat (points/s): " + "; ".join(
                  f"{n} " + ", ".join(f"{x['points_per_s']:.3f}" for x in rs) for n, rs in runs.items()),
              "", "Regenerate: `.venv/bin/python benchmarks/bench_dask.py` (about two minutes).", ""]
    return "\n".join(lines)


def _reading(runs: dict, ratio: float) -> str:
    allv = [x["points_per_s"] for rs in runs.values() for x in rs]
    spread = (max(allv) - min(allv)) / statistics.median(allv)
    verdict = ("dask is within 10 % of the local pool or faster" if ratio >= 0.9 else
               f"dask is {1 / ratio - 1:.0%} slower than the local pool")
    return (f"Reading: {verdict}. The spread between repeats ({min(allv):.2f}–{max(allv):.2f} points/s, "
            f"{spread:.0%} of the median) comes from the shared machine and is "
            f"{'larger' if spread > abs(ratio - 1) else 'smaller'} than the difference between the executors. "
            "Before the compile-once cache each dask worker compiled the step loop itself (1.4–1.6x slower "
            "than the pool, issue 15); warmed workers now load it from disk, like the pool's.")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, default=12)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--steps-per-rev", type=int, default=128)
    ap.add_argument("--max-revs", type=int, default=150)
    ap.add_argument("--out", default=str(OUT))
    args = ap.parse_args(argv)
    load_start = os.getloadavg()
    runs = measure(args.points, args.repeats, args.steps_per_rev, args.max_revs)
    load_end = os.getloadavg()
    out = Path(args.out)
    text = report(runs, args, load_start, load_end)
    atomic_write_text(out / "perf-dask.md", text)
    rows = ["executor,repeat,points_per_s,wall_s,point_median_s,point_sum_s,load_avg_start,load_avg_end"]
    for n, rs in runs.items():
        rows += [f"{n},{i},{x['points_per_s']:.4f},{x['wall_s']:.3f},{x['point_median_s']:.4f},{x['point_sum_s']:.3f},"
                 f"{load_start[0]:.2f},{load_end[0]:.2f}" for i, x in enumerate(rs)]
    atomic_write_text(out / "perf-dask.csv", "\n".join(rows) + "\n")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
