"""The 3D reference point, present code against the previous one, side by side in one run.

    .venv/bin/python benchmarks/bench_fem3d.py [--repeats 3] [--old-rev 98e869e] [--point 0.03 2]

Writes reports/published/fem3d-perf.{md,csv}. The previous code (``--old-rev``: the revision
before issue 17, trilinear hexahedra L0-L2) is exported with ``git archive`` into a temporary
directory; both are run through their own command line, ``ringcontact fem3d point PEN --tilt-arcmin
TILT --json``, in child processes under ``nice -n 5``, alternating old and new:

* cold: an empty level cache (``RINGCONTACT_CACHE`` in a fresh temporary directory): the levels
  are built, then the point is solved;
* cached: the same command again on the filled cache.

Each child is run as its code ships: the previous code with the environment's BLAS threading
(variables removed: the library default, one thread per core), the present code with its
process share (contact/threads.py); a third column runs the previous code with one BLAS
thread, for a like-for-like comparison. Wall times are medians over ``--repeats`` runs, measured
around the child process (interpreter start and imports included); the present code also
reports its level build and contact solve times separately (``level_load_s``, ``solve_s``). The
1-minute load average is recorded before and after: the machine is shared.
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "reports" / "published"
THREAD_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "RINGCONTACT_THREADS")


def export_old(rev: str, dest: Path) -> Path:
    """``git archive`` of the packages the 3D point needs at ``rev`` into ``dest``."""
    blob = subprocess.run(["git", "archive", "--format=tar", rev, "contact", "sweep", "fem_reference", "reports"],
                          cwd=ROOT, capture_output=True, check=True).stdout
    tar = dest / "old.tar"
    tar.write_bytes(blob)
    with tarfile.open(tar) as t:
        t.extractall(dest, filter="data")
    return dest


def run_point(tree: Path, cache: Path, pen_mm: float, tilt_arcmin: float, threads: str | None) -> dict:
    """One ``fem3d point --json`` in ``tree``; returns its record and the wall time around the process."""
    env = {k: v for k, v in os.environ.items() if k not in THREAD_VARS}
    env.update(RINGCONTACT_CACHE=str(cache), PYTHONPATH=str(tree), MPLBACKEND="Agg")
    if threads is not None:
        env.update(OPENBLAS_NUM_THREADS=threads, OMP_NUM_THREADS=threads)
    cmd = ["nice", "-n", "5", sys.executable, "-m", "reports.cli", "fem3d", "point", f"{pen_mm:g}",
           "--tilt-arcmin", f"{tilt_arcmin:g}", "--json"]
    t0 = time.perf_counter()
    out = subprocess.run(cmd, cwd=tree, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if out.returncode != 0:
        raise RuntimeError(f"{tree}: {out.stderr.strip()[-400:]}")
    rec = json.loads(out.stdout)
    rec["wall_process_s"] = wall
    return rec


VARIANTS = (("previous, default BLAS threads", "old", None), ("previous, 1 BLAS thread", "old", "1"),
            ("present (process share)", "new", None))


def measure(repeats: int, pen_mm: float, tilt_arcmin: float, old_tree: Path) -> dict:
    """Cold and cached runs of every variant, interleaved; lists of records per variant."""
    res = {name: {"cold": [], "cached": []} for name, _, _ in VARIANTS}
    for _ in range(repeats):
        for name, which, threads in VARIANTS:
            tree = old_tree if which == "old" else ROOT
            with tempfile.TemporaryDirectory() as cache:
                res[name]["cold"].append(run_point(tree, Path(cache), pen_mm, tilt_arcmin, threads))
                res[name]["cached"].append(run_point(tree, Path(cache), pen_mm, tilt_arcmin, threads))
            print(f"{name}: cold {res[name]['cold'][-1]['wall_process_s']:.1f} s, cached "
                  f"{res[name]['cached'][-1]['wall_process_s']:.2f} s (load {os.getloadavg()[0]:.1f})", flush=True)
    return res


def _med(recs, key):
    vals = [r[key] for r in recs if r.get(key) is not None]
    return statistics.median(vals) if vals else None


def _fmt(v, spec=".2f"):
    return "–" if v is None else format(v, spec)


def write_report(res: dict, args, load_before, load_after, old_rev: str) -> None:
    from contact.dataset import read_dataset
    from contact.files import atomic_write_text
    from contact.units import ARCMIN, MM
    from fem_reference.solid.sweep import DATASET_PATH

    ds = read_dataset(DATASET_PATH)
    ref = next((p for p in ds.points if abs(p["penetration_m"] - args.point[0] * MM) < 1e-12
                and abs(p["tilt_rad"] - args.point[1] * ARCMIN) < 1e-12), None)
    md = ["# 3D tilted-ring reference: one point, present code against the previous one", "",
          f"Generated by `benchmarks/bench_fem3d.py --repeats {args.repeats}` (one command; re-run it on a quiet "
          f"machine to replace these numbers). Point: Δr = {args.point[0]:g} mm, tilt {args.point[1]:g}′, "
          f"`ringcontact fem3d point` with its default three levels (error estimate included), run as a child "
          f"process under `nice -n 5`; the previous code is revision `{old_rev}` (trilinear hexahedra L0-L2, "
          "node-to-node contact), exported with `git archive` and run in the same session, alternating with the "
          "present one (harmonic quadratic sections Q0-Q2, mortar contact).",
          f"Shared 2-core machine: 1-minute load average {load_before:.2f} before, {load_after:.2f} after (other "
          "engineers' jobs running; above 2 the cores are oversubscribed and every time is inflated).", "",
          f"Medians over {args.repeats} runs; 'wall' is measured around the whole process (interpreter start and "
          "imports included, about 0.6 s here); 'levels' and 'solves' are the present code's own split "
          "(`level_load_s`: build or cache read of its three levels, `solve_s`: the contact solves).", "",
          "| variant | cold wall (s) | cached wall (s) | levels, cold (s) | solves (s) | force (kN) | moment (kN·m) "
          "| stated err F | stated err M |", "|---|---|---|---|---|---|---|---|---|"]
    csv = ["variant,run,wall_s,level_load_s,solve_s,force_n,moment_nm,force_error_rel,moment_error_rel,load_before,load_after"]
    for name, _, _ in VARIANTS:
        cold, cached = res[name]["cold"], res[name]["cached"]
        r0 = cold[0]
        md.append(f"| {name} | {_fmt(_med(cold, 'wall_process_s'), '.1f')} | {_fmt(_med(cached, 'wall_process_s'))} | "
                  f"{_fmt(_med(cold, 'level_load_s'), '.1f')} | {_fmt(_med(cached, 'solve_s'), '.3f')} | "
                  f"{r0['force_N'] / 1e3:.2f} | {r0['moment_Nm'] / 1e3:.4f} | {100 * r0['force_error_rel']:.2f} % | "
                  f"{100 * (r0['moment_error_rel'] or 0):.2f} % |")
        for kind, recs in (("cold", cold), ("cached", cached)):
            for r in recs:
                csv.append(",".join(str(v) for v in (name, kind, r["wall_process_s"], r.get("level_load_s"),
                                                      r.get("solve_s"), r["force_N"], r["moment_Nm"],
                                                      r["force_error_rel"], r["moment_error_rel"], load_before,
                                                      load_after)))
    if ref is not None:
        md += ["", f"Committed value of this point (`fem3d-reference.json`, levels {', '.join(ref['levels'])}): "
               f"{ref['force_n'] / 1e3:.2f} kN, {ref['moment_nm'] / 1e3:.4f} kN·m; on the finer check level "
               f"{ref['finer_level']}: {ref['force_finer_n'] / 1e3:.2f} kN, {ref['moment_finer_nm'] / 1e3:.4f} kN·m."]
    md += ["", "Targets (issue 17): a cold point ≤ 20 s on 2 cores, a cached one ≤ 1 s.", ""]
    atomic_write_text(OUT / "fem3d-perf.csv", "\n".join(csv) + "\n")
    atomic_write_text(OUT / "fem3d-perf.md", "\n".join(md) + "\n")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--old-rev", default="98e869e", help="revision of the previous code (default: before issue 17)")
    ap.add_argument("--point", type=float, nargs=2, default=(0.03, 2.0), metavar=("PEN_MM", "TILT_ARCMIN"))
    args = ap.parse_args(argv)
    load_before = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        old_tree = export_old(args.old_rev, Path(tmp))
        res = measure(args.repeats, args.point[0], args.point[1], old_tree)
    load_after = os.getloadavg()[0]
    sys.path.insert(0, str(ROOT))
    write_report(res, args, load_before, load_after, args.old_rev)
    print(f"wrote {OUT / 'fem3d-perf.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
