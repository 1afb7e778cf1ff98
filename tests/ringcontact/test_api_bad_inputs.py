"""The Python API refuses what the command line refuses, with the command line's own words (issue 40).

Each case calls one function of :mod:`ringcontact` with one bad argument: it must raise the package's own error
(:class:`ringcontact.RingContactError`, never a TypeError, IndexError or NaN result) in one line naming the
keyword. Where the job has the same option, the job is run in-process on the same value and the text of its
one-line refusal (after ``error: ``) must appear in the API's message: one source of ranges. Work beyond the
jobs' budget is refused before it starts, with the keyword that accepts it (``accept_long=True``).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import ringcontact as rc
from reports import cli

ARCMIN = math.pi / 10800
J, T4 = "verify-jeffcott", "paper-table4"
SIM = ["simulate", "--speed-rpm", "3000", "--out", "{tmp}/o"]
ORB = ["orbit", T4, "--speed-rpm", "10500"]
BR = ["branch", T4, "--rpm-start", "10500", "--rpm-end", "11000"]
BUDGET = ("beyond the budget of", "accept_long=True to run it anyway")


def _arg(flag: str, value: str) -> list[str]:
    return [f"{flag}={value}"] if value.startswith("-") else [flag, value]


# (id, call, argv of the job with the same value (or None), words the message must hold)
CASES = []
for v in (-1.0, 5e-3, float("nan"), float("inf"), -2e-3):
    CASES.append((f"law penetration {v}", lambda v=v: rc.law("conformal", v),
                  ["law", *_arg("--penetration-mm", f"{v / 1e-3:.15g}")], ["penetration_m"]))
for v in (700, -700, 1e6):
    CASES.append((f"law tilt {v} arcmin", lambda v=v: rc.law("conformal", 1e-5, v * ARCMIN),
                  ["law", "--penetration-mm", "0.01", *_arg("--tilt-arcmin", f"{v * ARCMIN / ARCMIN:.15g}")],
                  ["tilt_rad"]))
for kw, flag, values, scale in (("clearance_m", "--clearance-mm", (0.0, -1e-5, 0.05, float("nan")), 1e-3),
                                ("width_m", "--width-mm", (0.0, 1e3, -0.03), 1e-3),
                                ("bearing_modulus_pa", "--bearing-E-GPa", (0.0, 2e14, -2e11), 1e9),
                                ("support_modulus_pa", "--support-E-GPa", (1e6,), 1e9),
                                ("bearing_poisson", "--bearing-nu", (0.5, 0.7, -1.5), 1.0),
                                ("support_poisson", "--support-nu", (float("inf"),), 1.0)):
    for v in values:
        CASES.append((f"law {kw} {v}", lambda kw=kw, v=v: rc.law("conformal", 1e-5, **{kw: v}),
                      ["law", "--penetration-mm", "0.01", *_arg(flag, f"{v / scale:.15g}")], [kw]))
CASES += [
    ("law name None", lambda: rc.law(None, 1e-5), None, ["name = None"]),
    ("law name 5", lambda: rc.law(5, 1e-5), None, ["name = 5"]),
    ("law name empty", lambda: rc.law("", 1e-5), ["law", "--law", "", "--penetration-mm", "0.01"], ["''"]),
    ("law penetration text", lambda: rc.law("conformal", "deep"), None, ["penetration_m"]),
    ("law grid too large", lambda: rc.law("conformal", np.full(30000, 1e-5)), None, ["30000 points", "20000"]),
    ("law shapes", lambda: rc.law("conformal", np.ones(3) * 1e-5, np.zeros(4)), None, ["broadcast"]),
    ("law nosuch", lambda: rc.law("nosuch", 1e-5), ["law", "--law", "nosuch", "--penetration-mm", "0.01"],
     ["nosuch"]),
    ("law calibrated traversal", lambda: rc.law("calibrated:../calibrated/clamped-foundation", 1e-5),
     ["law", "--law", "calibrated:../calibrated/clamped-foundation", "--penetration-mm", "0.01"], ["not a path"]),
    ("law calibrated 5 mm", lambda: rc.law("calibrated:clamped-foundation", 5e-3),
     ["law", "--law", "calibrated:clamped-foundation", "--penetration-mm", "5"], ["penetration_m"]),
]
for v in (0, -3, 201, 2.5, True, "3", float("nan")):
    CASES.append((f"modes n_modes {v!r}", lambda v=v: rc.modes(J, n_modes=v),
                  ["rotor", "modes", J, "--modes", str(v)] if isinstance(v, int) and not isinstance(v, bool) else None,
                  ["n_modes"]))
for v in (-1.0, float("nan"), float("inf"), 1e30):
    CASES.append((f"modes speed {v}", lambda v=v: rc.modes(J, v), ["rotor", "modes", J, *_arg("--speed-rpm", f"{v:g}")],
                  ["speed_rpm"]))
for v in (0, 65, -1, 1.5):
    CASES.append((f"modes elements {v}", lambda v=v: rc.modes(J, elements=v),
                  ["rotor", "modes", J, *_arg("--elements", str(v))] if isinstance(v, int) else None, ["elements"]))
CASES += [(f"modes scene {s!r}", lambda s=s: rc.modes(s), None, ["scene"]) for s in (None, 5, "", 3.5, b"x")]
CASES += [
    ("modes scene nosuch", lambda: rc.modes("no-such-scene"), ["rotor", "modes", "no-such-scene"], ["no-such-scene"]),
    ("modes damped text", lambda: rc.modes(J, damped="yes"), None, ["damped = 'yes'"]),
    ("campbell no speed", lambda: rc.campbell(J, []), None, ["0 speeds"]),
    ("campbell 200 000 speeds", lambda: rc.campbell(T4, np.linspace(0, 3000, 200_000)),
     None, ["200000 speeds", "--points = 200000: must be in [1, 2000]"]),
    ("campbell nan speed", lambda: rc.campbell(J, [0.0, float("nan")]), None, ["nan rpm", "must be finite"]),
    ("campbell negative speed", lambda: rc.campbell(J, [-10.0, 100.0]), None, ["-10 rpm"]),
    ("campbell 2-D speeds", lambda: rc.campbell(J, [[0.0, 1.0], [2.0, 3.0]]), None, ["2-D"]),
    ("campbell n_modes 0", lambda: rc.campbell(J, [0, 100], n_modes=0), None, ["n_modes = 0"]),
    ("campbell 64 elements 2000 speeds", lambda: rc.campbell(T4, np.linspace(0, 3000, 2000), elements=64), None,
     ["2000 speeds", *BUDGET]),
    ("unbalance order 3", lambda: rc.unbalance_response(J, [100.0], order=3),
     None, ["order = 3", "must be 1 (unbalance) or 2 (misalignment)"]),
    ("unbalance order True", lambda: rc.unbalance_response(J, [100.0], order=True), None, ["order = True"]),
    ("unbalance no speed", lambda: rc.unbalance_response(J, []), None, ["0 speeds"]),
    ("unbalance station nosuch", lambda: rc.unbalance_response(J, [100.0], stations=["nosuch"]),
     ["rotor", "unbalance", J, "--nodes", "nosuch"], ["nosuch"]),
]
SIM_VALUES = {"speed_rpm": ("--speed-rpm", (0.0, -1.0, float("nan"), 1e6), 1.0),
              "revolutions": ("--revolutions", (0.0, -1.0, 1e6, float("inf")), 1.0),
              "steps_per_rev": ("--steps-per-rev", (0, 15, 10**6), 1.0),
              "record_per_rev": ("--record-per-rev", (0, 10**6), 1.0),
              "mu": ("--mu", (5.0, -0.1, float("nan")), 1.0),
              "preload_n": ("--preload-N", (-1.0, 1e9), 1.0),
              "clearance_m": ("--clearance-mm", (0.0, 0.1, -1e-5), 1e-3),
              "misalignment_m": ("--misalignment-mm", (-1e-3, 1.0), 1e-3)}
for kw, (flag, values, scale) in SIM_VALUES.items():
    for v in values:
        args = {"speed_rpm": 3000.0, kw: v}
        typed = str(v) if isinstance(v, int) else f"{v / scale:g}"
        argv = [*(SIM[:1] + SIM[3:] if kw == "speed_rpm" else SIM), *_arg(flag, typed)]
        CASES.append((f"simulate {kw} {v}", lambda a=args: rc.simulate(T4, **a), argv, [kw]))
CASES += [
    ("simulate steps_per_rev 2.5", lambda: rc.simulate(T4, 3000.0, steps_per_rev=2.5), None, ["steps_per_rev = 2.5"]),
    ("simulate elements 0", lambda: rc.simulate(T4, 3000.0, elements=0), None, ["elements = 0"]),
    ("simulate max_revs 0", lambda: rc.simulate(T4, 3000.0, steady=True, max_revs=0), None, ["max_revs = 0"]),
    ("simulate steady text", lambda: rc.simulate(T4, 3000.0, steady="yes"), None, ["steady = 'yes'"]),
    ("simulate tilt_ignored text", lambda: rc.simulate(T4, 3000.0, tilt_ignored="no"), None, ["tilt_ignored = 'no'"]),
    ("simulate 1e5 rev at 1e5 steps", lambda: rc.simulate(T4, 3000.0, revolutions=1e5, steps_per_rev=100000,
                                                          record_per_rev=1), None, ["revolutions = 100000", *BUDGET]),
    ("simulate accept_long text", lambda: rc.simulate(T4, 3000.0, revolutions=1e5, steps_per_rev=100000,
                                                      record_per_rev=1, accept_long="yes"), None, ["accept_long"]),
    ("simulate scene None", lambda: rc.simulate(None, 3000.0), None, ["scene = None"]),
    ("orbit speed 0", lambda: rc.orbit(T4, 0.0), ["orbit", T4, "--speed-rpm", "0"], ["speed_rpm"]),
    ("orbit speed nan", lambda: rc.orbit(T4, float("nan")), ["orbit", T4, "--speed-rpm", "nan"], ["speed_rpm"]),
    ("orbit steps 10**6", lambda: rc.orbit(T4, 10500.0, steps_per_rev=10**6), [*ORB, "--steps-per-rev", "1000000"],
     ["steps_per_rev"]),
    ("orbit steps 100000", lambda: rc.orbit(T4, 10500.0, steps_per_rev=100000), None, ["steps_per_rev = 100000",
                                                                                       *BUDGET]),
    ("orbit period 0", lambda: rc.orbit(T4, 10500.0, period_revs=0), [*ORB, "--period-revs", "0"], ["period_revs"]),
    ("orbit period 9", lambda: rc.orbit(T4, 10500.0, period_revs=9), [*ORB, "--period-revs", "9"], ["period_revs"]),
    ("orbit period 1.5", lambda: rc.orbit(T4, 10500.0, period_revs=1.5), None, ["period_revs = 1.5"]),
    ("orbit mu 5", lambda: rc.orbit(T4, 10500.0, mu=5.0), [*ORB, "--mu", "5"], ["mu = 5"]),
    ("branch same speeds", lambda: rc.branch(T4, 9000.0, 9000.0), None, ["rpm_end = 9000 rpm"]),
    ("branch rpm_end nan", lambda: rc.branch(T4, 9000.0, float("nan")), [*BR[:4], "--rpm-end", "nan"], ["rpm_end"]),
    ("branch max_points 1", lambda: rc.branch(T4, 10500.0, 11000.0, max_points=1), [*BR, "--max-points", "1"],
     ["max_points"]),
    ("branch max_points 10**6", lambda: rc.branch(T4, 10500.0, 11000.0, max_points=10**6),
     [*BR, "--max-points", "1000000"], ["max_points"]),
    ("branch steps 100000", lambda: rc.branch(T4, 10500.0, 11000.0, steps_per_rev=100000), None,
     ["max_points = 400", *BUDGET]),
    ("cascade no speed", lambda: rc.cascade(T4, []), None, ["0 speeds"]),
    ("cascade speed 0", lambda: rc.cascade(T4, [0.0, 3000.0]), None, ["rpms = 0 rpm"]),
    ("cascade speed nan", lambda: rc.cascade(T4, [float("nan")]), None, ["rpms = nan rpm"]),
    ("cascade 2001 speeds", lambda: rc.cascade(T4, np.linspace(100, 3000, 2001)), None, ["2001 speeds"]),
    ("cascade max_revs 0", lambda: rc.cascade(T4, [3000.0], max_revs=0), None, ["max_revs = 0"]),
    ("cascade steps 1", lambda: rc.cascade(T4, [3000.0], steps_per_rev=1), None, ["steps_per_rev = 1"]),
    ("cascade at a crawl", lambda: rc.cascade(T4, [18.0, 30.0], max_revs=100000), None, ["max_revs = 100000", *BUDGET]),
    ("cascade scene None", lambda: rc.cascade(None, [3000.0]), None, ["scene = None"]),
]


def test_the_cases_are_many_and_distinct():
    assert len(CASES) >= 100 and len({c[0] for c in CASES}) == len(CASES)


def _cli_words(argv, tmp_path, capsys) -> str:
    rc_ = cli.main([a.format(tmp=tmp_path) for a in argv])
    err = capsys.readouterr().err.strip()
    assert rc_ == 2 and err.count("\n") == 0 and ": error: " in err, err
    return err.split(": error: ", 1)[1]


@pytest.mark.parametrize("case_id,call,argv,words", CASES, ids=[c[0] for c in CASES])
def test_the_api_refuses_with_the_jobs_words(case_id, call, argv, words, tmp_path, capsys):
    with pytest.raises(rc.RingContactError) as info:
        call()
    msg = str(info.value)
    assert "\n" not in msg and not msg.startswith(("'", "[")), msg
    for w in words:
        assert w in msg, f"{w!r} not in: {msg}"
    if argv is not None:
        job = _cli_words(argv, tmp_path, capsys)
        assert job.split(" (")[0].split(": ", 1)[-1] in msg, f"the job says {job!r}; the API {msg!r}"
