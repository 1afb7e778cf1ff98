"""The orbit count of a smooth branch (reports/cli/_budget.py: branch_orbits) against the count the
continuation takes (rotor.periodic.continuation.continue_branch) on a rotor that never touches its ring (linear):
the estimate's count model, no wall time."""
from __future__ import annotations

import numpy as np

from reports.cli import _budget
from rotor.periodic.continuation import ContinuationOptions, continue_branch, speed_problem
from rotor.periodic.jeffcott import JeffcottParams, jeffcott_system

#: a Jeffcott rotor whose orbit stays far inside a 10 mm clearance: the map is linear
LINEAR = JeffcottParams(law="conformal", eccentricity_m=1e-6, clearance_m=1e-2)
SCALES = np.concatenate([np.full(4, 1e-6), np.full(4, 1e-3)])


def test_the_counted_orbits_of_a_straight_branch_are_within_1_5x_of_the_continuation_s():
    """Away from the resonance (ω_n 316 rad/s) the branch 500 -> 800 rad/s is nearly straight in its scales:
    the step control's count over 10 speed scales (ds 0.05 growing ×1.5 to 0.5: 25 orbits) is the count
    continue_branch takes, within a factor 1.5 either way; a count of 400 (``max_points``, the former estimate)
    would not be."""
    pb = speed_problem(lambda w: jeffcott_system(LINEAR, w), 64, modes0=(0, 0))
    br = continue_branch(pb, np.zeros(8), 500.0, 800.0, scales=SCALES, lam_scale=30.0,
                         options=ContinuationOptions(pass_switches=False))
    assert br.stop == "end reached", br.stop
    counted = _budget.branch_orbits(10.0)
    assert 20 <= counted <= 30
    assert counted / 1.5 <= len(br.points) <= 1.5 * counted, (len(br.points), counted)


def test_a_longer_path_counts_more_orbits_and_max_points_caps_them():
    """The count grows with the scaled arclength by ``ds_max`` a step once the step has grown, and never passes
    ``max_points``."""
    assert _budget.branch_orbits(20.0) - _budget.branch_orbits(10.0) == 20
    assert _budget.branch_orbits(1e6, ContinuationOptions(max_points=50)) == 50
