"""The reference of a piecewise smooth map's derivative (rotor/dynamics/monodromy_check.py ``piece_reference``) on
a map written here with its thresholds where they are wanted: the expected values are the pieces' own matrices
(closed form), not the function's output."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from rotor.dynamics import monodromy_check as mc

X0 = np.array([1.0, -2.0, 0.5, 3.0])
SCALES = np.array([1.0, 2.0, 0.5, 3.0])
A = np.array([[0.9, 0.1, 0.0, 0.2], [0.3, 0.8, 0.1, 0.0], [0.0, 0.2, 0.7, 0.1], [0.1, 0.0, 0.3, 0.6]])
#: the derivative's change across a threshold (a kink) and the map's jump across one (a stick episode born)
KINK, JUMP = np.array([0.5, -0.4, 0.3, 0.2]), np.array([1e-3, 2e-3, -1e-3, 5e-4])


def fake_map(pm, x, t0_s, n_steps, modes0, jacobian):
    """``A x`` plus, per column ``j`` of ``pm.kinks``, a kink ``KINK · max(0, d_j)`` and, per ``pm.jumps``, a jump
    ``JUMP · [d_j > 0]``, ``d_j`` the distance past the threshold in scaled units (``(x_j − X0_j)/s_j − at``)."""
    y = A @ x
    for j, at in pm.kinks:
        y = y + KINK * max(0.0, (x[j] - X0[j]) / SCALES[j] - at)
    for j, at in pm.jumps:
        y = y + JUMP * float((x[j] - X0[j]) / SCALES[j] - at > 0.0)
    return SimpleNamespace(state=y)


@pytest.fixture
def pieces(monkeypatch):
    monkeypatch.setattr(mc, "period_map", fake_map)

    def run(kinks=(), jumps=(), monodromy=A):
        pm = SimpleNamespace(kinks=kinks, jumps=jumps)
        return mc.piece_reference(pm, X0.copy(), 0.0, 1, (1, 1), SCALES, monodromy)
    return run


def test_a_smooth_map_is_its_central_differences(pieces):
    got = pieces()
    assert got["reference_convergence"] < 1e-8 and got["one_sided_columns"] == got["finer_columns"] == 0
    assert got["error"] < 1e-7
    assert np.allclose(got["reference"], A, rtol=0, atol=1e-7)


def test_a_threshold_within_2h_on_one_side_is_read_from_the_other(pieces):
    """Column 0 kinks at +1.5e-7 of its scale (inside the central stencil's 2e-7) and column 2 jumps at −1.2e-7:
    the central differences straddle both; the backward resp. forward differences are the orbit's piece, A."""
    got = pieces(kinks=[(0, 1.5e-7)], jumps=[(2, -1.2e-7)])
    assert got["central_convergence"] > 1e-3
    assert got["one_sided_columns"] == 2 and got["finer_columns"] == 0 and got["on_threshold"] == 0
    assert got["reference_convergence"] < 1e-6 and got["error"] < 1e-6


def test_thresholds_on_both_sides_are_resolved_at_the_finer_step(pieces):
    """Column 1 kinks at +1.5e-7 and jumps at −1.5e-7: no difference at 1e-7 converges, those at 1e-8 do."""
    got = pieces(kinks=[(1, 1.5e-7)], jumps=[(1, -1.5e-7)])
    assert got["finer_columns"] == 1
    assert got["reference_convergence"] < 1e-6 and got["error"] < 1e-6


def test_a_state_on_the_threshold_takes_the_side_nearer_the_monodromy(pieces):
    """Column 3 kinks at the state itself: forward (A + KINK in column 3) and backward (A) both converge; a monodromy
    equal to either side is within the bound, one equal to neither is not."""
    forward = A.copy()
    forward[:, 3] += KINK / SCALES[3]
    for M in (A, forward):
        got = pieces(kinks=[(3, 0.0)], monodromy=M)
        assert got["on_threshold"] == 1 and got["error"] < 1e-6
    assert pieces(kinks=[(3, 0.0)], monodromy=0.5 * (A + forward))["error"] > 1e-2


def test_jumps_within_the_finest_stencil_on_both_sides_leave_no_reference(pieces):
    got = pieces(jumps=[(0, 5e-9), (0, -5e-9)])
    assert got["reference_convergence"] > 1e-3
