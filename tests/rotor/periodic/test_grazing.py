"""Continuation through grazing (rotor.periodic.grazing) on the Jeffcott verification rotor in a frictionless
ring with the conformal law (finite contact stiffness at zero penetration), against its closed form
(rotor/periodic/jeffcott.py: ((k − mΩ'²) r + f(r − δ0))² + (cΩ' r)² = (m e Ω²)², Ω' = Ω tan(π/N)/(π/N) the
trapezoidal rule's warped frequency; the grazing speeds solve m e Ω² = δ0 √((k − mΩ'²)² + (cΩ')²)).

The rotor: JeffcottParams defaults (m = 1 kg, k = 1e5 N/m, ζ = 0.05, δ0 = 10 µm, ring 10 mm, E = 10 MPa) with
the conformal law and e = 3 µm = 0.3 δ0, N = 64 steps per revolution. Closed form (warped, N = 64): grazing at
279.5707 rad/s (the speed passes on), grazing fold at 374.3008 rad/s (the speed turns at the corner: the
unstable middle branch starts there), smooth jump-down fold at 445.873 rad/s (r = 4.18 δ0)."""
import dataclasses
import math

import numpy as np
import pytest

from rotor.periodic.continuation import ContinuationOptions, continue_branch, speed_problem
from rotor.periodic.grazing import continue_through_grazing
from rotor.periodic.period_flow import record
from rotor.periodic.jeffcott import (JeffcottParams, closed_form_folds, closed_form_grazing, closed_form_speeds,
                                    jeffcott_system, warped_frequency)

P = JeffcottParams(law="conformal", eccentricity_m=3e-6)
N = 64
SCALES = np.concatenate([np.full(4, 1e-5), np.full(4, 0.005)])     # m, m/s: radii up to ~4.2 δ0
OPTIONS = ContinuationOptions(ds=0.1, ds_max=0.4)                   # restarts allowed: none may be needed


def _problem():
    return speed_problem(lambda w: jeffcott_system(P, w), N, modes0=(0, 0))


@pytest.fixture(scope="module")
def sweeps():
    """Down 500 → 200 rad/s and up 200 → 500 rad/s, each from rest."""
    return {d: continue_through_grazing(_problem(), np.zeros(8), a, b, scales=SCALES, lam_scale=30.0, options=OPTIONS)
            for d, (a, b) in {"down": (500.0, 200.0), "up": (200.0, 500.0)}.items()}


@pytest.fixture(scope="module")
def fold_closed_form():
    (w_fold, _), = closed_form_folds(P, N, r_max_factor=10.0)
    return w_fold


def _radius(pt):
    return math.hypot(pt.state[0], pt.state[1])


def test_closed_form_grazing_speeds_put_the_free_orbit_on_the_clearance():
    w_prime = warped_frequency(np.array([g for g, _ in closed_form_grazing(P, N)]), N)
    w = np.array([g for g, _ in closed_form_grazing(P, N)])
    r_free = P.mass_kg * P.eccentricity_m * w ** 2 / np.hypot(P.stiffness_N_m - P.mass_kg * w_prime ** 2,
                                                              P.damping_N_s_m * w_prime)
    assert np.allclose(r_free, P.clearance_m, rtol=1e-12)
    assert [k for _, k in closed_form_grazing(P, N)] == ["grazing", "grazing_fold"]


def test_plain_continuation_stops_at_the_grazing_fold():
    """What the grazing segments are for: the pseudo-arclength corrector alone (no restart) cannot turn at the
    corner (the issue's 'step below ds_min', 1e-6 from the corner)."""
    corner = closed_form_grazing(P, N)[1][0]
    br = continue_branch(_problem(), np.zeros(8), 500.0, 200.0, scales=SCALES, lam_scale=30.0,
                         options=ContinuationOptions(ds=0.1, ds_max=0.4, pass_switches=False))
    assert br.stop == "step below ds_min"
    assert abs(br.points[-1].parameter / corner - 1) < 1e-4 and _radius(br.points[-1]) <= P.clearance_m


@pytest.mark.parametrize("direction,kinds", [("down", ["grazing_fold", "fold", "grazing"]),
                                             ("up", ["grazing", "fold", "grazing_fold"])])
def test_both_sweeps_pass_every_corner_without_restart(sweeps, direction, kinds):
    br = sweeps[direction]
    assert br.stop == "end reached" and br.restarts == 0
    assert not any(p.restarted for p in br.points)
    assert [b.kind for b in br.bifurcations] == kinds


@pytest.mark.parametrize("direction", ["down", "up"])
def test_grazings_and_fold_match_the_warped_closed_form(sweeps, fold_closed_form, direction):
    got = {b.kind: b.parameter for b in sweeps[direction].bifurcations}
    for w_cf, kind in closed_form_grazing(P, N):
        assert abs(got[kind] / w_cf - 1) < 1e-3                       # the must-show bound (0.1 %)
        assert abs(got[kind] / w_cf - 1) < 1e-8                       # what the located grazing orbits give
    assert abs(got["fold"] / fold_closed_form - 1) < 1e-5
    unwarped = dict((k, w) for w, k in closed_form_grazing(P))
    assert abs(unwarped["grazing_fold"] / got["grazing_fold"] - 1) > 1e-3   # the warping exceeds the bound


@pytest.mark.parametrize("direction", ["down", "up"])
def test_whole_curve_within_1e_6_of_the_warped_closed_form(sweeps, direction):
    br = sweeps[direction]
    worst = 0.0
    for pt in br.points:
        speeds = closed_form_speeds(P, _radius(pt), N)
        worst = max(worst, float(np.min(np.abs(speeds - pt.parameter)) / pt.parameter))
    assert worst < 1e-6
    speed = np.array([math.hypot(p.state[4], p.state[5]) for p in br.points])     # circular: Ω' r
    r = np.array([_radius(p) for p in br.points])
    assert np.allclose(speed, warped_frequency(br.parameters(), N) * r, rtol=1e-6)
    assert r.min() < 0.3 * P.clearance_m and r.max() > 4.1 * P.clearance_m


@pytest.mark.parametrize("direction", ["down", "up"])
def test_middle_branch_reached_and_every_point_on_it_unstable(sweeps, direction):
    br = sweeps[direction]
    idx = {b.kind: b.index for b in br.bifurcations}
    lo, hi = sorted((idx["grazing_fold"], idx["fold"]))
    middle = [p for p in br.points[lo:hi + 1] if _radius(p) > P.clearance_m * (1 + 1e-9)
              and (p.dlam_ds > 0) == (direction == "down")]
    assert len(middle) >= 8
    for p in middle:
        mu = p.floquet.multipliers
        assert not p.floquet.stable
        assert len(mu[(np.abs(mu.imag) < 1e-9) & (mu.real > 1 + 1e-6)]) == 1
    # the multiplier jumps across +1 at the corner: the free orbits beside it are stable
    free = [p for p in br.points if _radius(p) < P.clearance_m]
    assert len(free) >= 5 and all(p.floquet.stable for p in free)


def test_same_branch_up_and_down(sweeps):
    down, up = ({b.kind: b.parameter for b in sweeps[d].bifurcations} for d in ("down", "up"))
    assert abs(down["grazing_fold"] / up["grazing_fold"] - 1) < 1e-9
    assert abs(down["grazing"] / up["grazing"] - 1) < 1e-9
    assert abs(down["fold"] / up["fold"] - 1) < 1e-5


def test_branch_follows_grazing_by_default_only_on_a_frictionless_ring():
    from rotor.studies.orbit import follows_grazing
    ring = jeffcott_system(P, 300.0).support
    assert ring.mu * ring.preload_N == 0.0
    assert follows_grazing(ring, None) and not follows_grazing(ring, False)
    rubbing = dataclasses.replace(ring, mu=0.3, preload_N=100.0)
    assert not follows_grazing(rubbing, None) and follows_grazing(rubbing, True)
    assert not follows_grazing(None, True)


def test_one_point_grazing_of_an_off_centre_orbit_at_the_schemes_closed_form():
    """A static side load F = 0.3 N along y moves the free orbit off centre by F/k = 0.3 δ0, so it touches the
    ring at one phase only, and past the grazing the ring is loaded over part of the period. Free, the scheme's
    orbit is exactly q_n = F/k + X e^{iΩ t_n} with X = m e Ω² / (k − mΩ'² + i cΩ') (the trapezoidal rule's
    warped Ω', as rotor/periodic/jeffcott.py), so the grazing speed of its sampled orbit solves
    max_n |F/k + X e^{2πi n/N}| = δ0: 415.26750464 rad/s."""
    from scipy.optimize import brentq

    from rotor.dynamics.system import HarmonicForce
    from rotor.periodic.grazing import largest_penetration

    side = 0.3

    def system(w):
        s = jeffcott_system(P, w)
        f = s.force
        return dataclasses.replace(s, force=HarmonicForce(np.array([side, 0.0, 0.0, 0.0]), f.orders, f.cos, f.sin,
                                                          f.omega_rad_s))

    def gap(w):
        wp = float(warped_frequency(w, N))
        x = P.mass_kg * P.eccentricity_m * w ** 2 / (P.stiffness_N_m - P.mass_kg * wp ** 2 + 1j * P.damping_N_s_m * wp)
        return np.abs(side / P.stiffness_N_m + x * np.exp(2j * np.pi * np.arange(N) / N)).max() - P.clearance_m

    expected = brentq(gap, 400.0, 430.0, xtol=1e-13)
    pb = speed_problem(system, N, modes0=(0, 0))
    br = continue_through_grazing(pb, np.zeros(8), 500.0, 390.0, scales=SCALES, lam_scale=30.0, options=OPTIONS)
    assert br.stop == "end reached" and br.restarts == 0
    (b,) = br.bifurcations
    assert b.kind == "grazing" and abs(b.parameter / expected - 1) < 1e-9
    past = br.points[-1]
    g, _ = largest_penetration(pb.flow(past.parameter), past.state, N, (0, 0))
    tr = record(pb.flow(past.parameter), past.state, 0.0, N, (0, 0), 1)
    share = float(np.mean(np.hypot(tr.u[:-1, 0], tr.u[:-1, 1]) > P.clearance_m))
    assert g > 0.1 and 0.1 < share < 0.9                       # in contact over part of the period only
