"""Every job refuses bad input the same way: exit status 2, ONE line, nothing computed, nothing written.

The cases (tests/reports/bad_inputs.py, several hundred across every sub-command) cover wrong units,
signs, NaN/inf/huge values, counts, unwritable outputs (under /proc, a file where a directory is
meant and the reverse, an empty path), malformed CSV/TOML/datasets and files of the wrong kind.
Each runs ``reports.cli.main`` in a forked child of this (warm) process, bounded at 10 s and 4 GiB,
so a hang or a runaway allocation fails its case instead of the suite.
"""
from __future__ import annotations

import pytest

from bad_inputs import CASES, fill, make_inputs, preload, run_case


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    preload()
    return make_inputs(tmp_path_factory.mktemp("bad-inputs"))


def test_the_suite_is_broad():
    jobs = {argv[0] if argv[0] not in ("fem3d", "rotor", "study") else " ".join(argv[:2]) for _, argv, _ in CASES}
    assert len(CASES) >= 300
    for job in ("law", "fem-point", "fem-vtu", "fem-sweep", "fem-check", "fem-report", "fem-paper", "fem3d point",
                "fem3d vtu", "fem3d sweep", "fem3d check", "fem3d report", "calibrate", "rotor modes",
                "rotor campbell", "rotor critical-speeds", "rotor unbalance", "rotor report", "simulate",
                "study cascade", "study point", "study params", "study testrig", "study map", "study runup",
                "study publish", "study sensitivity", "study redraw", "report", "orbit", "branch"):
        assert job in jobs, job


@pytest.mark.parametrize("case_id,argv,echo", CASES, ids=[c[0] for c in CASES])
def test_bad_input_is_refused_in_one_line(case_id, argv, echo, inputs, tmp_path):
    work = tmp_path / "work"
    work.mkdir()
    res = run_case(fill(argv, inputs, work), tmp_path / "io", timeout_s=10.0, cwd=work)
    assert res["outcome"] == "exit", f"{res['outcome']} after {res['wall_s']:.1f} s: {res.get('error')}\n{res['stderr']}"
    lines = [ln for ln in res["stderr"].splitlines() if ln.strip()]
    assert res["rc"] == 2, f"exit status {res['rc']}: {res['stderr']}"
    assert len(lines) == 1, res["stderr"]
    assert lines[0].startswith("ringcontact") and ": error: " in lines[0], lines[0]
    assert "internal error" not in lines[0] and "Traceback" not in res["stderr"]
    if echo:
        assert echo in lines[0], f"{echo!r} not echoed: {lines[0]}"
    assert res["stdout"] == "", res["stdout"]
    assert not any(work.iterdir()), f"wrote {sorted(p.name for p in work.iterdir())} before refusing"
