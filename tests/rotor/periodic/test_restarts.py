"""Restarts past a switch (rotor.periodic.restarts.shot) land on an orbit mapped from the end-face modes it has at
phase 0, not from the branch's start modes.

The oscillator is Den Hartog's (1931) of ``dynamics_standin.friction_body`` (ω_n = 62.8 rad/s, P0 = 1 N, ζ = 0.1,
ω = 50 rad/s), continued in its Coulomb force F: at F = 2 N > P0 it rests stuck (both end faces stuck at phase 0,
the branch's start modes); at F = 0.5 N it moves without stops (Den Hartog's non-stop motion), both faces slipping
at phase 0, where a start with both faces stuck holds them for a step: another map. Expected values: Den Hartog's closed-form steady amplitude (``dynamics_denhartog.DenHartog``, no time
stepping), to 1e-3 at 200 steps per period: the scheme's O(h²) error there (second order, below 3e-5 at T/800 in
tests/rotor/dynamics/test_friction_events.py) and the sampled peak-to-peak's (π/200)²/2 = 1.2e-4."""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "dynamics"))

from dynamics_denhartog import DenHartog  # noqa: E402
from dynamics_standin import friction_body  # noqa: E402
from rotor.dynamics import constraints as cons  # noqa: E402
from rotor.periodic.branch_types import COLD, TRANSIENT, ContinuationOptions, Evaluator  # noqa: E402
from rotor.periodic.continuation import parameter_problem  # noqa: E402
from rotor.periodic.period_flow import advance, record  # noqa: E402
from rotor.periodic.restarts import shot  # noqa: E402

OMEGA, NPER = 50.0, 200
# backend "fd": monodromies by central differences of the located map (the exact backend checks the step against
# the stand-in support's contact stiffness, which this body never touches)


def _problem():
    return parameter_problem(lambda F: friction_body(F=F, P0=1.0, omega=OMEGA, zeta=0.1), OMEGA, NPER, "coulomb_N",
                             modes0=(cons.STICK, cons.STICK), locate_events=True, backend="fd")


@pytest.mark.parametrize("how", [TRANSIENT, COLD], ids=["transient from the stuck orbit", "cold"])
def test_a_restart_onto_a_slipping_orbit_maps_it_from_its_own_modes(how):
    """From the stuck branch at F = 2 N (the body at rest, both faces stuck: the branch's modes) a restart at
    F = 0.5 N lands on Den Hartog's non-stop orbit; the branch goes on from both faces slipping at phase 0, and the
    orbit's amplitude is Den Hartog's. The same state mapped from the stuck start modes does not close (measured:
    off by 7.3e-2 in the branch's scales), so with the start's modes the restart was refused."""
    pb = _problem()
    scales = np.concatenate([np.full(4, 1e-3), np.full(4, 5e-2)])       # m, m/s: about the orbit's
    ev = Evaluator(pb, scales.copy(), 1.0)
    opts = ContinuationOptions()
    stuck = np.concatenate([np.zeros(8), [2.0]])                          # at rest at F = 2 N: the stuck orbit
    R, _, _ = ev(stuck[:-1] * ev.s, 2.0, jacobian=False)
    assert np.abs(R).max() < 1e-12 and ev.modes0 == (cons.STICK, cons.STICK)
    got = shot(ev, np.concatenate([stuck[:-1], [0.5]]), opts, how, stuck)
    assert got is not None
    y, J, M, _, res, kind = got
    assert kind == how and res < opts.tol
    assert ev.modes0 == (cons.SLIP, cons.SLIP)
    x = y[:-1] * ev.s
    flow = ev.flow(0.5)
    from_stuck = advance(flow, x, 0.0, NPER, (cons.STICK, cons.STICK), jacobian=False).state
    assert np.abs((from_stuck - x) / ev.s).max() > 1e3 * opts.tol
    dh = DenHartog(1.0, flow.system.C[0, 0], flow.system.K[0, 0], 0.5, 1.0, OMEGA)
    X0, _, t_stick = dh.steady_state()
    assert t_stick == 0.0                                                  # non-stop motion
    tr = record(flow, x, 0.0, NPER, ev.modes0, 1)
    amplitude = 0.5 * np.ptp(tr.q[:, 0])
    assert abs(amplitude - X0) / X0 < 1e-3, (amplitude, X0)             # measured 3.8e-4


def test_a_refused_restart_keeps_the_branch_modes():
    """A restart whose orbit does not close in the branch's scales leaves the branch's modes as they were: here the
    state scales are 1e-12 of the orbit's, so no orbit passes the 1e-9 check."""
    pb = _problem()
    ev = Evaluator(pb, np.full(8, 1e-15), 1.0)
    y = np.concatenate([np.zeros(8), [0.5]])
    assert shot(ev, y, ContinuationOptions(), COLD, y) is None
    assert ev.modes0 == (cons.STICK, cons.STICK)
