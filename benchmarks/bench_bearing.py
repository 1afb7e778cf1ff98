"""A new bearing through ``ringcontact bearing``, cold, each stage timed: 2D only and with tilt.

    .venv/bin/python benchmarks/bench_bearing.py [--repeats 1] [--scene steel-in-aluminium] [--workers 2]
    .venv/bin/python benchmarks/bench_bearing.py --refit [--scene steel-in-aluminium]

Writes reports/published/perf-bearing.md. The ring pair (default: the bundled ``steel-in-aluminium``,
which the suite was not tuned on) is run twice per repeat through its own command line in a child
process, both cold: an empty output folder and an empty 3D level cache (``RINGCONTACT_CACHE`` in a fresh
temporary directory):

* 2D only: the same file with ``[range] tilt_arcmin = [0, 0]`` (the 2D sweep, calibration, report);
* with tilt: the file as it is (the 3D tilt sweep with its check level added, then the tilt correction's training
  and verification grids on the same levels, the correction fitted on the first and checked held out on the second
  and on the 3D reference points: reports/bearing/tilt.py).

The tilted run's FEM datasets, law files and summary are kept in ``reports/published/perf-bearing/`` (the last
repeat's), so the tilt correction's held-out table below can be recomputed from them
(tests/reports/test_bearing_tilt.py); after a change of a law family, ``--refit`` refits them from those datasets
(:func:`reports.bearing.pipeline.refit`, no FEM solved) and replaces the report's law and tilt-correction lines,
keeping its timings, which it says are the earlier run's. Per stage the job's own ``timings.json`` (wall time, 1-minute load average at its start and end) and
the wall time around the whole process (interpreter start and imports included). Targets (issue
"your bearing, end to end"): 2D only <= 2 min, with tilt cold <= 15 min, on 2 cores. The machine is
shared: the load average is written beside every figure.
"""
from __future__ import annotations

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))       # this checkout's packages (the --refit and report code runs in this process)
OUT = ROOT / "reports" / "published"
TARGET_S = {"2D only": 120.0, "with tilt": 900.0}


def scene_text(name: str) -> str:
    from fem_reference.ring_scene import RING_SCENE_DIR, is_file_argument
    return Path(name).read_text() if is_file_argument(name) else RING_SCENE_DIR.joinpath(f"{name}.toml").read_text()


def run_job(toml: Path, out: Path, cache: Path, workers: int, *extra: str) -> dict:
    """One cold ``ringcontact bearing`` in a child process (``extra``: more options); its stages and the wall time
    around it."""
    env = dict(os.environ, RINGCONTACT_CACHE=str(cache), MPLBACKEND="Agg")
    cmd = [sys.executable, "-m", "reports.cli", "bearing", str(toml), "--out", str(out), "--workers", str(workers),
           *extra]
    load0 = os.getloadavg()[0]
    t0 = time.perf_counter()
    res = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if res.returncode != 0:
        raise SystemExit(f"bench_bearing: the job failed ({res.returncode}): {res.stderr.strip()[-400:]}")
    stages = json.loads((out / "timings.json").read_text())["stages"]
    summary = json.loads((out / "summary.json").read_text())
    return {"wall_s": wall, "load_start": load0, "load_end": os.getloadavg()[0], "stages": stages,
            "summary": summary}


def keep(run: Path, folder: Path, summary: dict) -> None:
    """The tilted run's datasets, law files and summary into ``folder`` (replaced as a whole)."""
    import shutil

    if folder.exists():
        shutil.rmtree(folder)
    folder.mkdir(parents=True)
    for name in sorted(set(summary["files"]) - {n for n in summary["files"] if n.endswith((".png", ".svg", ".md", ".csv"))}
                       | {"summary.json"}):
        shutil.copy(run / name, folder / name)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="steel-in-aluminium", help="ring-pair file or bundled name")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", type=Path, default=OUT / "perf-bearing.md")
    ap.add_argument("--refit", action="store_true",
                    help="no job run: the kept tilted run's laws refitted from its datasets (no FEM solved), the "
                         "report's law and tilt-correction lines replaced, its timings kept")
    args = ap.parse_args(argv)
    if args.refit:
        return refit(args)
    text = scene_text(args.scene)
    flat = re.sub(r"(?m)^tilt_arcmin\s*=.*$", "tilt_arcmin = [0, 0]", text)
    flat = re.sub(r"(?m)^(penetration_points_3d_mm|tilt_points_arcmin)\s*=.*$\n?", "", flat)
    runs = {"2D only": [], "with tilt": []}
    with tempfile.TemporaryDirectory(prefix="bench-bearing-") as tmp:
        tmp = Path(tmp)
        files = {"2D only": tmp / "flat.toml", "with tilt": tmp / "tilt.toml"}
        files["2D only"].write_text(flat)
        files["with tilt"].write_text(text)
        for k in range(args.repeats):
            for variant, f in files.items():
                case = tmp / f"{variant.replace(' ', '-')}-{k}"
                runs[variant].append(run_job(f, case / "out", case / "cache", args.workers))
                print(f"{variant}: {runs[variant][-1]['wall_s']:.1f} s", file=sys.stderr)
        keep(tmp / f"with-tilt-{args.repeats - 1}" / "out", args.out.with_suffix(""), runs["with tilt"][-1]["summary"])
    from contact.files import atomic_write_text
    atomic_write_text(args.out, report(args, runs))
    print(f"wrote {args.out}")
    return 0


def refit(args) -> int:
    """``--refit``: the kept tilted run (``<out>`` without its suffix) refitted from its FEM datasets by
    :func:`reports.bearing.pipeline.refit` in a copy of the folder, kept back as a run's is (:func:`keep`); the
    report's lines from its law on replaced, its timing tables kept and said to be the earlier run's."""
    import shutil

    from contact.errors import InputError
    from contact.files import atomic_write_text
    from fem_reference import ring_scene
    from reports.bearing import pipeline
    from reports.version import version_line

    folder = args.out.with_suffix("")
    text = args.out.read_text(encoding="utf-8") if args.out.is_file() else ""
    cut = text.find("\nLaw of the tilted run:")
    if cut < 0 or not (folder / "summary.json").is_file():
        print(f"bench_bearing: --refit: needs the report {args.out} (with its law line) and the kept run {folder} "
              "(a run without --refit writes both)", file=sys.stderr)
        return 2
    version = version_line()                  # before the run writes: the code it ran, not its own output
    with tempfile.TemporaryDirectory(prefix="bench-bearing-refit-") as tmp:
        run = Path(tmp) / "run"
        shutil.copytree(folder, run)
        try:
            summary = pipeline.refit(ring_scene.load(args.scene), run, log=lambda s: print(s, file=sys.stderr))
        except InputError as exc:
            print(f"bench_bearing: --refit: {exc}", file=sys.stderr)
            return 2
        keep(run, folder, summary)
    note = (f"(From here on: `benchmarks/bench_bearing.py --refit`, {version}: the tilted run's laws refitted "
            f"from its kept datasets in {folder.name}/, no FEM point solved; the timings above are those of the run "
            f"of {summary['refit_of']}.)")
    atomic_write_text(args.out, text[:cut + 1] + "\n".join([note, "", *law_lines(summary), *tilt_lines(summary)]))
    print(f"wrote {args.out} and {folder}")
    return 0


def report(args, runs: dict) -> str:
    first = runs["with tilt"][0]["summary"]
    lines = ["# A new bearing through `ringcontact bearing`: each stage, cold", "",
             f"Generated by `benchmarks/bench_bearing.py --scene {args.scene} --repeats {args.repeats} --workers "
             f"{args.workers}` (one command; re-run it to replace these numbers). Ring pair `{first['ring_scene']}` "
             f"(sha256 {first['ring_scene_sha256'][:16]}…), run through the command line in a child process, cold: an "
             "empty output folder and an empty 3D level cache. '2D only' is the same file with `tilt_arcmin = [0, 0]`. "
             "Medians over the repeats; the 1-minute load average beside each figure (2 shared cores: above 2 the "
             "cores are oversubscribed and every time is inflated). With tilt, `calibrate` includes compiling the "
             "compiled loose-support kernel (the rotor path of the tilted check), for the straight law's 52 slots and "
             "for the tilt-corrected law's 126 (contact/_kernel_tilt.py), into the empty cache; `tilt-grid` solves "
             "the tilt correction's training and verification grids on the 3D levels `fem3d` built "
             "(reports/bearing/tilt.py).", "",
             "| variant | whole job (s) | target (s) | met | load average (start → end) | stages (s) |",
             "|---|---|---|---|---|---|"]
    for variant, rr in runs.items():
        wall = statistics.median(r["wall_s"] for r in rr)
        names = [s["stage"] for s in rr[0]["stages"]]
        per = {n: statistics.median(next(s["wall_s"] for s in r["stages"] if s["stage"] == n) for r in rr) for n in names}
        loads = f"{min(r['load_start'] for r in rr):.2f} → {max(r['load_end'] for r in rr):.2f}"
        lines.append(f"| {variant} | {wall:.1f} | {TARGET_S[variant]:.0f} | {'yes' if wall <= TARGET_S[variant] else 'NO'} "
                     f"| {loads} | " + ", ".join(f"{n} {v:.1f}" for n, v in per.items()) + " |")
    lines += ["", "Per stage, every run (wall s; load average at the stage's start → end):", "",
              "| variant | run | stage | wall (s) | load |", "|---|---|---|---|---|"]
    for variant, rr in runs.items():
        for k, r in enumerate(rr):
            for s in r["stages"]:
                lines.append(f"| {variant} | {k + 1} | {s['stage']} | {s['wall_s']:.1f} | "
                             f"{s['load_average_1min_start']:.2f} → {s['load_average_1min_end']:.2f} |")
    return "\n".join(lines + [""] + law_lines(first) + tilt_lines(first))


def law_lines(summary: dict) -> list[str]:
    """The tilted run's law and its checks (the job's summary)."""
    return [f"Law of the tilted run: `{summary['law_name']}` ({summary['family']}); checks: "
            + "; ".join(f"{k} {100 * v:.3f} %" for k, v in summary["checks"].items() if v is not None)
            + (f"; warnings: {summary['warnings']}" if summary["warnings"] else "; no warnings") + ".", ""]


def tilt_lines(summary: dict) -> list[str]:
    """The tilted run's tilt correction: held out, force and moment, with and without it (the job's own record)."""
    rec = summary.get("tilt_correction")
    if not rec:
        return ["The tilted run fitted no tilt correction.", ""]
    lines = [f"Tilt correction of the tilted run ({'shipped' if rec['chosen'] else 'not shipped'}; "
             f"{'every held-out point within' if rec['holds'] else 'NOT every held-out point within'} the target, "
             f"{rec['target']}): fitted on {rec['training_points']['tilted']} tilted training points, held out:", "",
             "| held-out points | quantity | within / all, corrected | worst (%) vs bound (%) | within / all, straight "
             "(slices) |", "|---|---|---|---|---|"]
    for s, per in rec["sets"].items():
        for q, both in per.items():
            c, st = both["corrected"], both["straight"]
            if c["points"]:
                lines.append(f"| {s} | {q} | {c['within']} / {c['points']} | {c['worst_error_pct']:.3f} vs "
                             f"{c['worst_bound_pct']:.3f} | {st['within']} / {st['points']} |")
    return lines + ["", f"Why: {rec['reason']}.", ""]


if __name__ == "__main__":
    sys.exit(main())
