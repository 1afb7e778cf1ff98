"""Every ranged option of every job: the parser's range is what the job accepts (issue "Trust under attack").

Measured before the fix: the parsers accepted ``--max-revs`` 1-23 (the steady-state detector needs 24),
100 000-200 000 rpm (the dynamics refused above 1e5 rpm) and 172-600 arcmin of 3D tilt (the small-rotation
model refuses above 0.05 rad), each refused by the job after parsing. Each limit now has one source imported
by both (contact.plausible.top, SteadyStateOptions.min_revs, fem_reference.solid.geometry.MAX_TILT_RAD,
rotor.studies.runup.SHORTEST_DURATION_S).

The walk finds every parser (each job's entry is called with its ``parse_args`` intercepted) and every option
whose ``type=`` carries its bounds (reports/cli/_edge.py: ``quantity``, ``count``), runs the job at each end
of the range in a forked child (tests/reports/bad_inputs.py: ``run_case``) and requires that the job goes past
its checks: it reaches its work-budget check (reports/cli/_budget.py, replaced here by a marker exit 99 so
nothing long starts), finishes, or is still working after the case's time. A refusal with exit status 2 is a
parser range wider than the job's. The full walk (about 200 runs) is slow; the default run takes the cases of
the mismatches measured above.
"""
from __future__ import annotations

import argparse
import importlib

import pytest

from bad_inputs import fill, make_inputs, preload, run_case

REACHED = 99          # the job reached its work-budget check: its inputs were accepted

# a valid command per parser ('@' marks the positional the walk may replace), '{tmp}': the case's folder
BASES = {
    "law": ["law", "--penetration-mm", "0.01"],
    "rotor response": ["rotor", "response", "verify-jeffcott", "--speed-rpm", "3000", "--out", "{tmp}/r"],
    "rotor unbalance": ["rotor", "unbalance", "verify-jeffcott"],
    "rotor critical-speeds": ["rotor", "critical-speeds", "verify-jeffcott"],
    "rotor campbell": ["rotor", "campbell", "verify-jeffcott"],
    "rotor modes": ["rotor", "modes", "verify-jeffcott"],
    "rotor static": ["rotor", "static", "verify-jeffcott"],
    "simulate": ["simulate", "--speed-rpm", "10500", "--out", "{tmp}/o"],
    "fem-point": ["fem-point", "@0.01"],
    "fem-check": ["fem-check"],
    "fem-paper": ["fem-paper", "--quiet", "--out", "{tmp}/o"],
    "fem-vtu": ["fem-vtu", "@0.01", "{tmp}/p.vtu"],
    "fem3d point": ["fem3d", "point", "@0.02"],
    "fem3d sweep": ["fem3d", "sweep", "--out", "{tmp}/d.json"],
    "fem3d check": ["fem3d", "check"],
    "fem3d vtu": ["fem3d", "vtu", "@0.02", "--out", "{tmp}/q.vtu"],
    "bearing": ["bearing", "{ring_good}", "--out", "{tmp}/o"],
    "orbit": ["orbit", "paper-table4", "--speed-rpm", "10500"],
    "branch": ["branch", "paper-table4", "--rpm-start", "10500", "--rpm-end", "11000"],
    "study publish": ["study", "publish", "--cascade", "{dir}", "--out", "{tmp}/o"],
    **{f"study {s}": ["study", s, "--out", "{tmp}/o", "--no-progress"]
       for s in ("map", "runup", "testrig", "params", "point", "cascade", "readings")},
}
#: options that need another one to mean anything (the --steady transient cap)
NEEDS = {("simulate", "--max-revs"): ["--steady", "--revolutions", "1"],
         ("simulate", "--steps-per-rev"): ["--record-per-rev", "1"],     # the samples divide the steps
         ("simulate", "--revolutions"): ["--steps-per-rev", "100000", "--record-per-rev", "1"],   # at least a step
         ("study cascade", "--rpm-min"): ["--rpm-max", "200000", "--points", "1"],  # a range, not a single bound
         # speeds at least 0.1 rpm apart (the points' keys): a range of 0.001 rpm holds one
         **{(f"study {s}", "--rpm-max"): ["--points", "1"] for s in ("cascade", "params", "map")}}
#: options whose range is a resource, not a physical limit: any count in it is taken, and proving it would
#: start that many processes
RESOURCES = {"--workers"}
#: limits that depend on the scene (its clearance, its ring radius), checked by the job with the scene's numbers
SCENE_DEPENDENT = {(job, "penetration_mm") for job in ("fem3d point", "fem3d vtu", "fem-point", "fem-vtu")} | {
    (job, "--h-mm") for job in ("fem-point", "fem-vtu", "fem-paper")}       # the clearance, the rings' thickness
#: shared overrides a command takes (every rotor command parses the same options, reports/cli/_scene_options.py)
#: but cannot apply, so it refuses every value in one line saying why: the linear jobs lock the loose support (no
#: contact, friction or preload; the misalignment offset only in the 2X response), study map and testrig vary
#: the clearance (and the rig its misalignment) themselves. Their refusals are bad-input cases
#: (tests/reports/bad_inputs.py, _scene_option_cases), not a range the parser and the job disagree on.
NOT_APPLICABLE = {(f"rotor {sub}", flag) for sub in ("modes", "campbell", "critical-speeds", "unbalance", "static")
                  for flag in ("--mu", "--preload-N", "--clearance-mm", "--misalignment-mm")} | {
    ("study map", "--clearance-mm"), ("study testrig", "--clearance-mm"), ("study testrig", "--misalignment-mm")}
#: options that need a finished study to be read at all (no limit of their own beyond the parser's)
NEEDS_A_STUDY = {"study publish"}
#: the mismatches measured before the fix: the default run's cases
MEASURED = {("simulate", "--speed-rpm", "high"), ("study cascade", "--max-revs", "low"),
            ("fem3d point", "--tilt-arcmin", "high"), ("study runup", "--duration-s", "low")}


class _Got(Exception):
    pass


def job_parsers() -> list[tuple[str, argparse.ArgumentParser]]:
    """``(name, parser)`` of every job and sub-command (reports.cli.JOBS), found by calling each entry."""
    from reports.cli import JOBS

    found = []

    def grab(self, args=None, namespace=None):
        raise _Got(self)

    orig = argparse.ArgumentParser.parse_args
    argparse.ArgumentParser.parse_args = grab
    try:
        for job, (target, _) in JOBS.items():
            mod, _, fn = target.partition(":")
            entry = getattr(importlib.import_module(mod), fn or "main")
            for sub in (["point", "sweep", "check", "report", "vtu"] if job == "fem3d" else [None]):
                try:
                    entry([sub] if sub else [])
                except _Got as g:
                    found.append((" ".join([job] + ([sub] if sub else [])), g.args[0]))
    finally:
        argparse.ArgumentParser.parse_args = orig
    out, stack = [], list(found)
    while stack:
        name, p = stack.pop()
        out.append((name, p))
        for a in p._actions:
            if isinstance(a, argparse._SubParsersAction):
                stack += [(f"{name} {k}", sp) for k, sp in a.choices.items()]
    return out


def _end(bound: tuple, side: str, other: float):
    value, inclusive = bound
    if inclusive:
        return value
    step = 1e-3 * max(1.0, abs(value))
    return value + step if side == "low" else value - step


def ranged_cases() -> list:
    """``(parser name, option, side, value)`` for both ends of every ranged option."""
    cases = []
    for name, p in job_parsers():
        for a in p._actions:
            t = a.type
            if t is None or not hasattr(t, "low") or set(a.option_strings) & RESOURCES:
                continue
            flag = a.option_strings[0] if a.option_strings else a.dest
            for side, bound, other in (("low", t.low, t.high[0]), ("high", t.high, t.low[0])):
                v = _end(bound, side, other)
                cases.append((name, flag, side, f"{v:d}" if isinstance(v, int) else repr(float(v))))
    return cases


def _argv(name: str, flag: str, value: str) -> list[str]:
    base = BASES[name]
    if not flag.startswith("-"):       # the positional
        return [value if a.startswith("@") else a for a in base]
    argv, skip = [], 0
    for i, a in enumerate(base):
        if skip:
            skip -= 1
            continue
        if a == flag:                  # the base's own value of this option goes
            skip = 1
            continue
        argv.append(a[1:] if a.startswith("@") else a)
    return [*argv, *NEEDS.get((name, flag), []), f"{flag}={value}"]


CASES = ranged_cases()


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    preload()
    return make_inputs(tmp_path_factory.mktemp("ranges"))


def test_the_walk_finds_every_job_and_the_measured_options():
    names = {c[0] for c in CASES}
    assert {"law", "simulate", "orbit", "branch", "rotor campbell", "study cascade", "fem3d point"} <= names
    assert names <= set(BASES), names - set(BASES)           # every ranged parser has a base command
    keys = {(c[0], c[1], c[2]) for c in CASES}
    assert MEASURED <= keys, MEASURED - keys
    assert len(CASES) >= 150


def _params():
    return [pytest.param(*c, id=f"{c[0]} {c[1]} {c[2]}",
                         marks=() if (c[0], c[1], c[2]) in MEASURED else pytest.mark.slow) for c in CASES]


@pytest.mark.parametrize("name, flag, side, value", _params())
def test_a_value_the_parser_accepts_is_accepted_by_the_job(name, flag, side, value, inputs, tmp_path, monkeypatch):
    if name in NEEDS_A_STUDY:
        pytest.skip("needs a finished study directory before its options are read")
    if (name, flag) in SCENE_DEPENDENT:
        pytest.skip("the limit depends on the scene (checked by the job with the scene's numbers)")
    if (name, flag) in NOT_APPLICABLE:
        pytest.skip("an override this command cannot apply: refused for every value, in one line (bad-input cases)")
    from reports.cli import _budget

    def reached(*_a, **_k):
        raise SystemExit(REACHED)
    monkeypatch.setattr(_budget, "check", reached)
    work = tmp_path / "work"
    work.mkdir()
    argv = fill(_argv(name, flag, value), inputs, work)
    res = run_case(argv, tmp_path / "io", timeout_s=6.0, cwd=work)
    if res["outcome"] == "hang":       # still working after the case's time: past every check
        return
    assert res["outcome"] == "exit", res
    assert res["rc"] != 2, f"{' '.join(argv)}: refused by the job although its parser accepts it: {res['stderr']}"
