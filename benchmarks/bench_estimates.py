"""The work estimates of ``ringcontact orbit`` and ``branch`` against their measured wall times (issue 36).

Each case runs the job in this process (``reports.cli.main``, one BLAS thread as the job sets it, the step loop
compiled beforehand: the compile is reported separately by the jobs), with the announcement threshold lowered to
0 s so that the job prints its estimate (reports/cli/_budget.py: "estimated about X (at most Y: …)"); the measured
time runs from that line (the work it estimates) to the job's end; the whole job's time (scene, compile check,
probe) is listed beside it. Reported per case: the typical estimate and its bound, the measured
wall time, their ratio (estimate / measured; the goal is [0.5, 2]), the job's own count (orbits of a branch), and
the load average at start and end (shared 2-core machine: the ratio moves with the load). The fixed cases are followed by
:data:`RANDOM_ROTORS` random Jeffcott-ring rotors of a new seed each run (printed; give one as the argument to
rerun a draw), each branched over its sweep range up and down. Writes ``reports/published/perf-estimates.md``.
Run: ``nice .venv/bin/python benchmarks/bench_estimates.py [SEED]``.
"""
from __future__ import annotations

import contextlib
import io
import json
import os
import random
import re
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from reports.cli import blas_threads  # noqa: E402

blas_threads("branch")                 # before numpy loads, as the jobs do

from contact.files import atomic_write_text  # noqa: E402
from reports.cli import _budget, main  # noqa: E402
from rotor.dynamics.period_map import warm_up  # noqa: E402
from rotor.periodic.jeffcott_scene import random_family, scene_toml  # noqa: E402
from rotor.studies.grazing_family import sweep_range  # noqa: E402

OUT = ROOT / "reports" / "published"
FRISWELL = str(ROOT / "tests" / "rotor" / "scenes" / "friswell-591-loose-aluminium.toml")
UNITS = {"s": 1.0, "min": 60.0, "h": 3600.0}
#: random Jeffcott-ring rotors of a run, each branched up and down
RANDOM_ROTORS = 4
ESTIMATE = re.compile(r"estimated about ([0-9.e+-]+) (s|min|h) \(at most ([0-9.e+-]+) (s|min|h)")


def _cases(jr: str, lo: float, hi: float) -> list:
    """``(label, argv)``: short orbit and branch jobs on a Jeffcott-ring scene, the Friswell rotor at 2 000 N and
    200 N, and Table 4."""
    return [
        ("orbit Jeffcott ring (seed 1) at 700 rpm", ["orbit", jr, "--speed-rpm", f"{lo:.0f}"]),
        ("orbit Jeffcott ring (seed 1) at 2000 rpm", ["orbit", jr, "--speed-rpm", "2000"]),
        (f"branch Jeffcott ring (seed 1) {lo:.0f} -> {hi:.0f} rpm",
         ["branch", jr, "--rpm-start", f"{lo:.0f}", "--rpm-end", f"{hi:.0f}"]),
        (f"branch Jeffcott ring (seed 1) {hi:.0f} -> {lo:.0f} rpm",
         ["branch", jr, "--rpm-start", f"{hi:.0f}", "--rpm-end", f"{lo:.0f}"]),
        ("orbit Friswell 5.9.1 loose Al, 2 000 N, 2570 rpm", ["orbit", FRISWELL, "--speed-rpm", "2570"]),
        ("branch Friswell 5.9.1 loose Al, 2 000 N, 2300 -> 2800 rpm",
         ["branch", FRISWELL, "--rpm-start", "2300", "--rpm-end", "2800"]),
        ("orbit Friswell 5.9.1 loose Al, 200 N, 2570 rpm",
         ["orbit", FRISWELL, "--speed-rpm", "2570", "--preload-N", "200"]),
        ("branch Friswell 5.9.1 loose Al, 200 N, 2300 -> 2800 rpm (restarts: not in the estimate)",
         ["branch", FRISWELL, "--rpm-start", "2300", "--rpm-end", "2800", "--preload-N", "200"]),
        ("orbit paper-table4 at 12000 rpm", ["orbit", "paper-table4", "--speed-rpm", "12000"]),
        ("orbit paper-table4 at 7000 rpm", ["orbit", "paper-table4", "--speed-rpm", "7000"]),
    ]


def _random_cases(seed: int, count: int, folder: Path) -> list:
    """``(label, argv)``: each of ``count`` random Jeffcott-ring rotors (:func:`random_family` of ``seed``) branched
    over its sweep range up and down (the work estimate's grazing prediction on rotors it was not set on)."""
    out = []
    for i, rotor in enumerate(random_family(seed, count)):
        scene = folder / f"jeffcott-ring-{i}.toml"
        scene.write_text(scene_toml(rotor))
        lo, hi = sweep_range(rotor)
        for a, b in ((lo, hi), (hi, lo)):
            out.append((f"branch random Jeffcott ring {i} {a:.0f} -> {b:.0f} rpm",
                        ["branch", str(scene), "--rpm-start", f"{a:.0f}", "--rpm-end", f"{b:.0f}"]))
    return out


def _run(argv: list) -> dict:
    """One job: its estimate (typical, bound; s), wall time (s), exit status and JSON."""
    err, out = _Stamped(), io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        status = main([*argv, "--json", "--accept-long"])
    end = time.perf_counter()
    wall, job = end - (err.announced or t0), end - t0
    m = ESTIMATE.search(err.getvalue())
    if m is None:
        raise RuntimeError(f"{argv}: no estimate in {err.getvalue()!r}")
    typical, bound = float(m[1]) * UNITS[m[2]], float(m[3]) * UNITS[m[4]]
    d = json.loads(out.getvalue())
    count = len(d["points"]) if "points" in d else d.get("transient_revs")
    return {"typical": typical, "bound": bound, "wall": wall, "job": job, "status": status, "count": count}


class _Stamped(io.StringIO):
    """stderr text, and when the estimate was written (the work it estimates starts then)."""

    announced = None

    def write(self, text):
        if self.announced is None and "estimated" in text:
            self.announced = time.perf_counter()
        return super().write(text)


def main_bench(argv=None) -> int:
    seed = int(argv[0]) if argv else random.SystemRandom().randrange(2 ** 32)
    print(f"random Jeffcott-ring rotors: seed {seed}", flush=True)
    _budget.ANNOUNCE_S = 0.0           # every job says its estimate
    load0 = os.getloadavg()[0]
    compile_s = warm_up()["compile_s"]
    rotor = random_family(1, 1)[0]
    lo, hi = sweep_range(rotor)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        jr = str(Path(tmp) / "jeffcott-ring.toml")
        Path(jr).write_text(scene_toml(rotor))
        for label, argv_ in _cases(jr, lo, hi) + _random_cases(seed, RANDOM_ROTORS, Path(tmp)):
            la = os.getloadavg()[0]
            r = _run(argv_)
            r.update(label=label, load=(la, os.getloadavg()[0]))
            print(f"{label}: about {r['typical']:.3g} s (at most {r['bound']:.3g} s), measured {r['wall']:.3g} s, "
                  f"ratio {r['typical'] / r['wall']:.2f}, load {la:.2f}", flush=True)
            rows.append(r)
    load1 = os.getloadavg()[0]
    ratios = [r["typical"] / r["wall"] for r in rows]
    inside = sum(0.5 <= q <= 2.0 for q in ratios)
    lines = [
        "# Work estimates of orbit and branch against their wall times",
        "",
        "benchmarks/bench_estimates.py: each job run in one process (reports.cli.main, one BLAS thread, the step loop "
        f"compiled first: {compile_s:.2f} s), its estimate as it announces it (reports/cli/_budget.py: step costs "
        "measured on the system by a short probe, a branch's orbits counted over its predicted path: its scaled "
        "arclength, and where the free linear orbit reaches the clearance, the grazings and the contact stretch "
        "between them, reports/cli/_branch_path.py) against the "
        "wall time from the announcement to the job's end (the job's whole time beside it). Ratio = typical estimate / measured (goal: 0.5 to 2). "
        f"The fixed cases, then {RANDOM_ROTORS} random Jeffcott-ring rotors (rotor.periodic.jeffcott_scene.random_family, "
        f"seed **{seed}**, a new one each run) each branched over its sweep range up and down. "
        f"Load average {load0:.2f} at start, {load1:.2f} at end (shared 2-core machine).",
        "",
        "| case | estimate about (s) | at most (s) | measured (s) | whole job (s) | ratio | orbits / transient revs | exit | load start / end |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r, q in zip(rows, ratios):
        lines.append(f"| {r['label']} | {r['typical']:.3g} | {r['bound']:.3g} | {r['wall']:.3g} | {r['job']:.3g} | {q:.2f} | "
                     f"{r['count']} | {r['status']} | {r['load'][0]:.2f} / {r['load'][1]:.2f} |")
    lines += ["", f"**{inside} of {len(rows)}** ratios within [0.5, 2] (smallest {min(ratios):.2f}, largest "
              f"{max(ratios):.2f}).", ""]
    OUT.mkdir(parents=True, exist_ok=True)
    atomic_write_text(OUT / "perf-estimates.md", "\n".join(lines))
    print(f"wrote {OUT / 'perf-estimates.md'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main_bench(sys.argv[1:]))
