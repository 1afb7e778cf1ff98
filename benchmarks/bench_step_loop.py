"""The production integrator's compiled step loop: this tree against an earlier commit, side by side.

Writes ``reports/published/perf-step-loop.md``: the Table 4 rotor (``paper-table4``) at 10 500 rpm, 250
revolutions of :func:`rotor.dynamics.production.simulate_production` from the linear start
(:func:`rotor.dynamics.initial.linear_initial_state`), at the steady-state study's steps per revolution
(:func:`rotor.studies.steady_state.step_per_rev`), ``NewmarkOptions.locate_events`` off and on, and off with
every step recorded (as :func:`rotor.dynamics.period_map.period_map` runs it; the trajectory's assembly in
Python included). The earlier code is the ``contact`` and ``rotor`` packages of ``--old-ref`` (``git archive``
into a folder under the temporary directory, compiled once into the on-disk cache like any checkout); each
tree runs in its own worker process, which compiles (or loads) the loop first and then times runs on
request, the two asked alternately (the order swapped every repeat), ``--repeats`` times. Medians of the
wall and CPU times, per step; the load average at the start and at the end; whether the two trees' records
are bit-identical, there and on the 64 runs of the hard cases of
``tests/rotor/dynamics/test_dynamics_constraints.py`` (with the sharp edge rule too, events off and on).

Run: ``nice -n 0 .venv/bin/python benchmarks/bench_step_loop.py [--old-ref REF] [--repeats N]`` (about a
minute after the first compilation of the old tree).
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import statistics
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from contact.files import atomic_write_text  # noqa: E402

OUT = ROOT / "reports" / "published" / "perf-step-loop.md"
RPM = 10500.0
REVS = 250
OLD_REF = "291495d"   # the branch point of the step-loop work (before any of it)
CASES = ("off", "on", "every step")   # locate_events off / on (end state recorded), off with every step recorded

# The worker: set the point up, compile or load the loop, then one timed run per request line ("off"/"on").
WORKER = r"""
import hashlib, json, math, sys, time
import numpy as np
from rotor.dynamics.initial import linear_initial_state
from rotor.dynamics.production import prepare, simulate_production
from rotor.dynamics.system import NewmarkOptions
from rotor.studies.steady_state import SteadyStateOptions, point_system, step_per_rev
import rotor
rpm, revs = float(sys.argv[1]), int(sys.argv[2])
_, model, system = point_system("paper-table4", rpm)
n = step_per_rev(system, SteadyStateOptions())
dt = 2 * math.pi / (system.omega_rad_s * n)
q0, v0 = linear_initial_state(system, 0.0)
pre = prepare(system, dt)
t = time.perf_counter()
simulate_production(system, dt, 4, q0, v0, prepared=pre)
print(json.dumps({"ready": True, "first_call_s": time.perf_counter() - t, "package": rotor.__file__,
                  "steps": revs * n, "steps_per_rev": n}), flush=True)


def records_sha256(tr):
    digest = hashlib.sha256()
    for name in ("q", "v", "a", "u", "w", "f_contact", "f_elastic", "face_force", "modes", "newton_iters", "passes"):
        digest.update(np.ascontiguousarray(getattr(tr, name)).tobytes())
    return digest.hexdigest()


def hard_cases():
    # the hard cases of tests/rotor/dynamics/test_dynamics_constraints.py (10 revolutions at T/256 from the
    # centred support and from q = 0), each also with the sharp one-edge rule (edge_transition_m = 0, where
    # Newton stalls and keeps least-residual iterates), events off and on: records hash, least-residual steps
    import dataclasses
    from contact.errors import OutsideDomainError
    from rotor.dynamics.build import system_from_model
    from rotor.model.assembly import assemble
    from rotor.model.scene import load_scene
    scene = load_scene("paper-table4")
    mdl = assemble(scene)
    om = rpm * math.pi / 30.0
    out = {}
    for label, kw in (("clearance 0.001 mm", dict(clearance_m=1e-6)), ("clearance 1 mm", dict(clearance_m=1e-3)),
                      ("misalignment 0", dict(misalignment_m=0.0)), ("misalignment 3 mm", dict(misalignment_m=3e-3)),
                      ("mu 0", dict(mu=0.0)), ("mu 1", dict(mu=1.0)), ("preload 0", dict(preload_N=0.0)),
                      ("tilt ignored", dict(tilt_ignored=True))):
        s = system_from_model(mdl, scene, om, **kw)
        sharp = np.array(s.support.law.params, float)
        sharp[13] = 0.0
        s_sharp = dataclasses.replace(s, support=dataclasses.replace(
            s.support, law=dataclasses.replace(s.support.law, params=sharp)))
        for name, sv in ((label, s), (label + ", sharp edge rule", s_sharp)):
            for start in ("centred", "q=0"):
                for ev in (False, True):
                    q = sv.offset if start == "centred" else np.zeros(sv.n)
                    key = f"{name}, from {start}, events {'on' if ev else 'off'}"
                    try:
                        tr = simulate_production(sv, 2 * math.pi / om / 256, 2560, q0=q, check_step=False,
                                                 options=NewmarkOptions(locate_events=ev))
                        out[key] = [records_sha256(tr), tr.unconverged_steps]
                    except OutsideDomainError as e:
                        out[key] = [str(e), -1]
    return out


for line in sys.stdin:
    case = line.strip()
    if case == "hard":
        print(json.dumps(hard_cases()), flush=True)
        continue
    opts = NewmarkOptions(locate_events=case == "on")
    every = 1 if case == "every step" else revs * n
    w, c = time.perf_counter(), time.process_time()
    tr = simulate_production(system, dt, revs * n, q0, v0, options=opts, record_every=every, prepared=pre)
    c, w = time.process_time() - c, time.perf_counter() - w
    end = records_sha256(tr)
    print(json.dumps({"wall_s": w, "cpu_s": c, "end_sha256": end, "events": tr.located_events}), flush=True)
"""


def old_tree(ref: str) -> Path:
    """The ``contact`` and ``rotor`` packages of ``ref``, extracted once into the temporary directory."""
    sha = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short=12", ref], capture_output=True, text=True,
                         check=True).stdout.strip()
    tree = Path(tempfile.gettempdir()) / f"ringcontact-bench-step-loop-{sha}"
    if not (tree / "rotor").is_dir():
        tmp = Path(tempfile.mkdtemp(dir=tempfile.gettempdir()))
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", "--format=tar", sha, "contact", "rotor"],
                                 capture_output=True, check=True).stdout
        tar_path = tmp / "src.tar"
        tar_path.write_bytes(archive)
        with tarfile.open(tar_path) as tar:
            tar.extractall(tmp / "tree", filter="data")
        os.replace(tmp / "tree", tree)
    return tree


class Worker:
    """One tree's worker process (see ``WORKER``)."""

    def __init__(self, tree: Path):
        env = dict(os.environ, PYTHONPATH=str(tree), OPENBLAS_NUM_THREADS="1")
        self.proc = subprocess.Popen([sys.executable, "-c", WORKER, str(RPM), str(REVS)], cwd=tree, env=env,
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        self.info = json.loads(self.proc.stdout.readline())

    def run(self, case: str) -> dict:
        self.proc.stdin.write(case + "\n")
        self.proc.stdin.flush()
        return json.loads(self.proc.stdout.readline())

    def close(self) -> None:
        self.proc.stdin.close()
        self.proc.wait(timeout=60)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--old-ref", default=OLD_REF, help=f"git commit of the earlier code (default {OLD_REF})")
    ap.add_argument("--repeats", type=int, default=7, help="interleaved repeats (default 7)")
    args = ap.parse_args()
    load0 = os.getloadavg()
    workers = {"old": Worker(old_tree(args.old_ref)), "new": Worker(ROOT)}
    times = {(tree, case): [] for tree in workers for case in CASES}
    ends, events = {}, {}
    for r in range(args.repeats):
        for case in CASES:
            for tree in (("old", "new") if r % 2 == 0 else ("new", "old")):
                res = workers[tree].run(case)
                times[(tree, case)].append((res["wall_s"], res["cpu_s"]))
                ends.setdefault((tree, case), set()).add(res["end_sha256"])
                events[(tree, case)] = res["events"]
    load1 = os.getloadavg()
    hard = {tree: workers[tree].run("hard") for tree in workers}
    for w in workers.values():
        w.close()
    steps = workers["new"].info["steps"]
    lines = report(args, workers, times, ends, events, steps, load0, load1) + hard_lines(hard)
    atomic_write_text(OUT, "\n".join(lines) + "\n")
    print("\n".join(lines))


def report(args, workers, times, ends, events, steps, load0, load1) -> list[str]:
    """The markdown lines of the report."""
    def med(tree, case, k):
        return statistics.median(t[k] for t in times[(tree, case)])

    stamp = datetime.datetime.now(datetime.timezone.utc)
    old, new = workers["old"].info, workers["new"].info
    text = (f"Generated by `benchmarks/bench_step_loop.py` on {stamp:%Y-%m-%d %H:%M} UTC. Table 4 rotor "
            f"(`paper-table4`) at {RPM:g} rpm, {REVS} revolutions of `simulate_production` from the linear start, "
            f"{new['steps_per_rev']} steps per revolution ({steps} steps): `NewmarkOptions.locate_events` off and on "
            "(the end state recorded), and off with every step recorded (as `rotor.dynamics.period_map.period_map` "
            "runs it; building the trajectory in Python included). *before*: the `contact` and `rotor` packages of "
            f"commit `{args.old_ref}`; *after*: this tree. Each tree in its own worker process, compiled or loaded "
            f"from the disk cache first (first call {old['first_call_s']:.2f} s / {new['first_call_s']:.2f} s), then "
            f"asked alternately (the order swapped every repeat), {args.repeats} repeats, medians. Load average at "
            f"start {load0[0]:.2f}/{load0[1]:.2f}/{load0[2]:.2f}, at end {load1[0]:.2f}/{load1[1]:.2f}/{load1[2]:.2f} "
            f"(shared machine, 2 cores); {platform.machine()}, Python {platform.python_version()}. *records "
            "bit-identical*: the recorded samples (q, v, a, u, w, contact and face forces, modes, iterations) of "
            "every run of both trees hash the same.")
    lines = ["# The production step loop: time per step, before and after", "", text, "",
             "| locate_events | before, µs/step (wall) | after, µs/step (wall) | ratio (wall) "
             "| before, µs/step (CPU) | after, µs/step (CPU) | ratio (CPU) | located events "
             "| records bit-identical |",
             "|---|---|---|---|---|---|---|---|---|"]
    labels = {"off": "off", "on": "on", "every step": "off, every step recorded"}
    for case in CASES:
        wo, wn = med("old", case, 0), med("new", case, 0)
        co, cn = med("old", case, 1), med("new", case, 1)
        same = len(ends[("old", case)] | ends[("new", case)]) == 1
        lines.append(f"| {labels[case]} | {wo / steps * 1e6:.2f} | {wn / steps * 1e6:.2f} | {wo / wn:.2f} | "
                     f"{co / steps * 1e6:.2f} | {cn / steps * 1e6:.2f} | {co / cn:.2f} | {events[('new', case)]} | "
                     f"{'yes' if same else 'NO'} |")
    return lines


def hard_lines(hard: dict) -> list[str]:
    """The report's section on the hard cases: records compared between the trees."""
    same = [k for k in hard["new"] if hard["new"][k] == hard["old"].get(k)]
    unconv = sum(v[1] for v in hard["new"].values() if v[1] > 0)
    lines = ["", "## Bit-identity on the hard cases", "",
             f"The {len(hard['new'])} runs of the hard cases of `tests/rotor/dynamics/test_dynamics_constraints.py` "
             "(Table 4 at 10 500 rpm, 10 revolutions at T/256 from the centred support and from q = 0; clearance "
             "0.001 and 1 mm, misalignment 0 and 3 mm, μ = 0 and 1, preload 0, tilt ignored), each also with the "
             "sharp one-edge rule (edge transition 0, where Newton keeps least-residual iterates: "
             f"{unconv} such steps in all), events off and on: records bit-identical before and after in "
             f"{len(same)} of {len(hard['new'])}."]
    differ = [k for k in hard["new"] if k not in same]
    if differ:
        lines += ["", "Differing: " + "; ".join(differ) + "."]
    return lines


if __name__ == "__main__":
    main()
