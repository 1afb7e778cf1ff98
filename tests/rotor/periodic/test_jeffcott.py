"""The Jeffcott verification rotor (rotor.periodic.jeffcott): the scheme's discrete circular orbit is the
closed form with the trapezoidal rule's warped frequency Ω' = Ω tan(π/N)/(π/N) (module docstring)."""
import math

import numpy as np

from rotor.dynamics.production import simulate_production
from rotor.periodic.jeffcott import (JeffcottParams, closed_form_folds, closed_form_radius, closed_form_residual,
                                    closed_form_speeds, contact_force_N, jeffcott_system, warped_frequency)

P = JeffcottParams()
N = 64


def test_long_transient_settles_on_the_warped_closed_form_orbit():
    """At 500 rad/s (lower-left branch, stable) 300 revolutions from rest: radius constant over the last
    revolution and equal to the closed form with Ω' (1e-8), velocity Ω' r, not Ω r."""
    w = 500.0
    sysm = jeffcott_system(P, w)
    tr = simulate_production(sysm, 2 * math.pi / w / N, 300 * N, modes0=(0, 0), record_every=1)
    r = np.hypot(tr.q[-N:, 0], tr.q[-N:, 1])
    speed = np.hypot(tr.v[-N:, 0], tr.v[-N:, 1])
    r_cf = closed_form_radius(P, w, float(r.mean()), N)
    assert np.ptp(r) / r_cf < 1e-8
    assert abs(r.mean() - r_cf) / r_cf < 1e-8
    assert np.allclose(speed, float(warped_frequency(w, N)) * r, rtol=1e-8)
    assert not np.allclose(speed, w * r, rtol=1e-4)          # the warping is visible (tan(π/64)/(π/64) − 1 = 8e-4)
    assert r_cf > P.clearance_m                                # in contact: the law's force enters
    assert abs(closed_form_radius(P, w, r_cf) - r_cf) / r_cf > 1e-5   # unwarped closed form misses it


def test_closed_form_pieces_agree():
    """Ω from r (quadratic in Ω²) and r from Ω are inverse; no contact force inside the clearance."""
    assert contact_force_N(P, 0.5 * P.clearance_m)[0] == 0.0
    assert contact_force_N(P, 3 * P.clearance_m)[0] > 0.0
    for r in (0.5e-5, 5e-5, 3e-4):
        for w in closed_form_speeds(P, r, N):
            assert abs(closed_form_residual(P, r, w, N)) < 1e-9
            assert abs(closed_form_radius(P, w, r * 1.01, N) - r) / r < 1e-9


def test_fold_structure_of_the_default_parameters():
    """Two folds, both in contact: jump-up near 624 rad/s (7.4 δ0), jump-down near 727 rad/s (45 δ0); the
    warping moves them by about 0.1 % at 64 steps per revolution."""
    folds = closed_form_folds(P, N)
    exact = closed_form_folds(P)
    assert len(folds) == 2 and len(exact) == 2
    (w_up, r_up), (w_down, r_down) = folds
    assert 600 < w_up < 650 < 700 < w_down < 750
    assert P.clearance_m < r_up < r_down
    assert 5e-4 < abs(w_up / exact[0][0] - 1) < 2e-3
