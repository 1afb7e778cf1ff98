"""The jump of a period map across a change of its switches (rotor/periodic/map_jump.py), on maps written by
hand: a jump placed at a known point of known size, and a map that only kinks there."""
from __future__ import annotations

import numpy as np
import pytest

from rotor.periodic.map_jump import JUMP_FLOOR, jump_across, jump_text

BOUNDARY, SIZE = 0.3141592653, 3.75e-3


def _jumping(y):
    """Two switches below the boundary, four above, the residual 3.75e-3 higher there (the size measured on the
    Friswell rotor at 200 N preload, the module docstring)."""
    x = float(y[0])
    return np.array([x - 1.0 + SIZE * (x > BOUNDARY), 0.5 * x]), 2 if x <= BOUNDARY else 4


def _kinking(y):
    """The same switches, the residual continuous with a change of slope at the boundary."""
    x = float(y[0])
    return np.array([x - 1.0 + 5.0 * max(x - BOUNDARY, 0.0), 0.5 * x]), 2 if x <= BOUNDARY else 4


def test_a_placed_jump_is_found_at_its_place_with_its_size():
    got = jump_across(_jumping, np.array([0.0, 1.0]), np.array([1.0, 1.0]))
    assert got["jump"] == pytest.approx(SIZE, rel=1e-6)
    assert got["switches"] == (2, 4) and got["at"][0] == pytest.approx(BOUNDARY, abs=1e-11)
    assert jump_text(got, "speed_rad_s", 266.2).startswith("; the period map jumps by 3.8e-03 of the orbit's scale "
                                                            "at speed_rad_s = 266.2, where its switches in the "
                                                            "period go from 2 to 4")


def test_a_kink_or_alike_switches_is_no_jump():
    assert jump_across(_kinking, np.array([0.0, 1.0]), np.array([1.0, 1.0])) is None
    assert jump_across(_jumping, np.array([0.0, 1.0]), np.array([0.2, 1.0])) is None      # both ends switch twice
    small = lambda y: (_jumping(y)[0] - np.array([SIZE - 0.1 * JUMP_FLOOR, 0.0]) * (y[0] > BOUNDARY), _jumping(y)[1])
    assert jump_across(small, np.array([0.0, 1.0]), np.array([1.0, 1.0])) is None         # below the floor
    assert jump_text(None, "speed_rad_s", 1.0) == ""


def test_the_stall_s_residual_is_the_corrector_s_map():
    """``Evaluator.residual_switches`` (the map the stall's jump is measured on, rotor/periodic/continuation.py: _jump)
    is the corrector's own residual at the same scaled point and modes, with the switches of its period: on a
    Jeffcott rotor in contact with its ring (rotor/periodic/jeffcott.py), equal to round-off."""
    from rotor.periodic.branch_types import Evaluator, speed_problem
    from rotor.periodic.jeffcott import JeffcottParams, jeffcott_system

    params = JeffcottParams(law="conformal")
    pb = speed_problem(lambda w: jeffcott_system(params, w), 64, modes0=(0, 0))
    scales = np.concatenate([np.full(4, 1e-5), np.full(4, 1e-2)])
    ev = Evaluator(pb, scales, 30.0)
    x = np.array([2e-5, 1e-5, 0.0, 0.0, -3e-3, 6e-3, 0.0, 0.0])
    R, _, _ = ev(x, 320.0, jacobian=True)
    got, switches = ev.residual_switches(np.concatenate([x / scales, [320.0 / 30.0]]), ev.modes0)
    assert np.allclose(got, R, rtol=1e-12, atol=1e-15) and switches == ev.events
