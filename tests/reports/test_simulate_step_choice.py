"""``simulate`` chooses its step as ``orbit`` and the studies do unless told (rotor.studies.steady_state.step_per_rev):
at 1 000 rpm the paper's rotor needs more than 256 steps a revolution for its contact step limit."""
from __future__ import annotations

import json
import math

from rotor.dynamics.system import largest_stable_step


def test_simulate_chooses_a_step_within_the_contact_limit_unless_told(tmp_path, capsys):
    from reports.cli.simulate import _parser, _system, main

    assert main(["--speed-rpm", "1000", "--revolutions", "2", "--out", str(tmp_path / "a")]) == 0
    s = json.loads((tmp_path / "a" / "simulate-summary.json").read_text())
    args = _parser().parse_args(["--speed-rpm", "1000", "--out", str(tmp_path / "x")])
    _, _, system, _ = _system(args)
    dt_max, _ = largest_stable_step(system)
    assert s["steps_per_rev_chosen"] is True and s["steps_per_rev"] == args.steps_per_rev > 256
    assert s["dt_s"] <= dt_max and s["steps_per_rev"] % 64 == 0          # whole record samples (64 a revolution)
    assert math.isclose(s["dt_s"], 60 / 1000 / s["steps_per_rev"], rel_tol=1e-12)
    capsys.readouterr()
    assert main(["--speed-rpm", "1000", "--revolutions", "2", "--steps-per-rev", "256", "--out", str(tmp_path / "b")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "largest stable step" in err[0]
