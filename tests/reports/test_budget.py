"""Long work announced before it starts, refused above the budget unless --accept-long (reports/cli/_budget.py).

The refusals of each long job (orbit, branch, simulate, study runup and cascade, rotor campbell and response) are
bad-input cases (tests/reports/bad_inputs.py: ``_trust_cases``); here: the rule itself, and the step counts the
estimates are made of against the jobs' own counts.
"""
from __future__ import annotations

import pytest

from reports.cli import _budget


def test_work_above_a_minute_is_announced_and_above_the_budget_refused_unless_accepted(capsys):
    _budget.check("ringcontact x", _budget.Estimate(30.0, 1e6, "3e5 steps"), False, "--n = 3", "fewer")
    assert capsys.readouterr().err == ""                                   # short work: not a word
    _budget.check("ringcontact x", _budget.Estimate(120.0, 1e6, "1e6 steps"), False, "--n = 9", "fewer")
    err = capsys.readouterr().err.splitlines()
    assert err == ["ringcontact x: estimated at most 2 min of computing and 0.000931 GiB of records (1e6 steps); "
                   "starting"]
    long = _budget.Estimate(2 * _budget.WORK_BUDGET_S, 1e6, "2e9 steps")
    with pytest.raises(_budget.WorkBudgetError) as info:
        _budget.check("ringcontact x", long, False, "--n = 99", "fewer n")
    text = str(info.value)
    assert text.startswith("--n = 99: estimated at most 60 min") and "--accept-long" in text and "fewer n" in text
    big = _budget.Estimate(10.0, 1.5 * _budget.MEMORY_BUDGET_BYTES, "records")
    with pytest.raises(_budget.WorkBudgetError, match="3 GiB of records"):
        _budget.check("ringcontact x", big, False, "--r = 1", "fewer records")
    _budget.check("ringcontact x", long, True, "--n = 99", "fewer n")      # accepted: announced, then run
    assert "estimated at most 60 min" in capsys.readouterr().err


def test_the_runup_estimate_counts_the_steps_the_runup_takes():
    """The default run-up took 1 536 340 steps (reports/published/study-runup.md): the estimate's step count
    (duration over the job's step, rotor.studies.runup.simulate_runup) is that count, to its segment rounding."""
    from rotor.studies.runup import RunupSpec
    est = _budget.runup(RunupSpec())
    steps = est.seconds / _budget.RUNUP_STEP_COST_S
    assert steps == pytest.approx(1_536_340, rel=2e-3)


def test_a_cascade_at_a_crawl_is_refused_for_its_steps_and_memory():
    """Issue 27 measured 3 GB in 30 s for ``study cascade --rpm-max 18 --points 2``; measured here before the
    constant was set: one 18 rpm point of 24 revolutions, 73 792 steps a revolution (the contact step limit),
    3.5 GB (reports/cli/_budget.py). The estimate: beyond both budgets; the default cascade (61 points to
    18 000 rpm, 468 s measured, reports/published/study-cascade.md) within them."""
    from rotor.studies.steady_state import sweep_tasks
    crawl = _budget.steady_points(sweep_tasks("paper-table4", [0.0, 18.0]), workers=2)
    assert crawl.seconds > _budget.WORK_BUDGET_S and crawl.nbytes > _budget.MEMORY_BUDGET_BYTES
    import numpy as np
    default = _budget.steady_points(sweep_tasks("paper-table4", np.linspace(0, 18000, 61)), workers=2)
    assert 468 / 4 < default.seconds < _budget.WORK_BUDGET_S and default.nbytes < _budget.MEMORY_BUDGET_BYTES


def test_the_campbell_estimate_is_its_measured_eigenproblem_scaled_with_the_cube_of_the_dofs():
    assert _budget.campbell(_budget.EIG_COST_DOFS, 1).seconds == pytest.approx(_budget.EIG_COST_S)
    assert _budget.campbell(2 * _budget.EIG_COST_DOFS, 10).seconds == pytest.approx(80 * _budget.EIG_COST_S)
