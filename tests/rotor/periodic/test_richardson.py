"""Richardson extrapolation of a branch in the step (rotor.periodic.richardson) against the continuous-time closed
form of the Jeffcott verification rotor (rotor/periodic/jeffcott.py: ((k − mΩ²) r + f(r − δ0))² + (cΩ r)² =
(m e Ω²)², no frequency warping). The rotor: JeffcottParams defaults (Pereira law, folds near 624 and 727 rad/s),
branch 500 → 800 rad/s with N = 128 steps per revolution, through both folds and the unstable middle branch."""
import math

import numpy as np
import pytest

from rotor.periodic.continuation import ContinuationOptions, continue_branch, speed_problem
from rotor.periodic.jeffcott import JeffcottParams, closed_form_speeds, jeffcott_system
from rotor.periodic.richardson import extrapolate_branch

P = JeffcottParams()
N = 128
SCALES = np.concatenate([np.full(4, 1e-4), np.full(4, 0.06)])


def _distance(lams, states, steps_per_rev):
    """Largest relative speed distance of the orbits (λ, radius of the state) from the closed-form curve with
    ``steps_per_rev`` steps (None: continuous time)."""
    worst = 0.0
    for w, x in zip(lams, states):
        s = closed_form_speeds(P, math.hypot(x[0], x[1]), steps_per_rev)
        worst = max(worst, float(np.min(np.abs(s - w)) / w) if len(s) else math.inf)
    return worst


@pytest.fixture(scope="module")
def run():
    pb = speed_problem(lambda w: jeffcott_system(P, w), N, modes0=(0, 0))
    br = continue_branch(pb, np.zeros(8), 500.0, 800.0, scales=SCALES, lam_scale=100.0,
                         options=ContinuationOptions(ds=0.2, ds_max=0.8))
    return br, extrapolate_branch(pb, br, scales=SCALES, lam_scale=100.0)


def test_extrapolated_orbits_within_1e_6_of_the_continuous_time_closed_form(run):
    br, ex = run
    assert br.stop == "end reached" and [b.kind for b in br.bifurcations][:2] == ["fold", "fold"]
    assert ex.converged.all()                                   # folds included: the hyperplane fixes a state there
    plain = _distance(br.parameters(), [p.state for p in br.points], None)
    assert plain > 1e-4                                         # the scheme's own orbits: the warping's error
    assert _distance(ex.parameters, ex.states, None) < 1e-6     # the must-show bound
    radii = np.hypot(ex.states[:, 0], ex.states[:, 1])
    assert radii.max() > 40 * P.clearance_m and radii.min() < 5 * P.clearance_m     # upper, middle, lower branch


def test_the_fine_orbits_are_orbits_of_the_2n_scheme(run):
    _, ex = run
    assert _distance(ex.fine_parameters, ex.fine_states, 2 * N) < 1e-9           # warped closed form with 2N
