"""Whole periods of a detected steady state, recorded at every field: ``simulate --steady`` and the API's
``simulate(..., steady=True)``.

:func:`rotor.studies.steady_state.steady_state` detects the steady state from Poincaré samples and keeps one
spectrum record of its own channels; a time history needs every field (contact force, end-face modes, the full
state). :func:`record_after_steady` integrates the kept revolutions again from the detector's end state, rounded up
to whole periods of the detected orbit so that a DFT over the record falls on exact bins.
"""
from __future__ import annotations

import math

from rotor.dynamics.production import simulate_production
from rotor.studies.steady_state import SteadyResult


def record_after_steady(system, ss: SteadyResult, keep_revs: int, record_per_rev: int):
    """Integrate ``keep_revs`` revolutions (rounded up to whole periods) from the end of a steady-state detection.

    Parameters
    ----------
    system : rotor.dynamics.system.RotorSystem, the system ``ss`` was detected on (spin speed inside, rad/s).
    ss : SteadyResult, from :func:`rotor.studies.steady_state.steady_state` (its step, end state and face modes).
    keep_revs : int, revolutions wanted (≥ 1).
    record_per_rev : int, samples a revolution; divides ``ss.steps_per_rev``.

    Returns
    -------
    (trajectory, dt_s, n_steps, kept_revs): the :class:`rotor.dynamics.system.Trajectory`, the step (s), the
    steps integrated and the revolutions kept (a multiple of the detected period; one revolution a period when
    the detection did not converge).
    """
    conv = ss.convergence
    period = conv.period if conv.converged else 1
    keep = int(math.ceil(keep_revs / period) * period)
    T = 2 * math.pi / system.omega_rad_s
    dt = T / ss.steps_per_rev          # the detector may have refined the step (contact step limit)
    n_steps = keep * ss.steps_per_rev
    tr = simulate_production(system, dt, n_steps, q0=ss.q_end, v0=ss.v_end,
                             t0=(ss.transient_revs + ss.revolutions) * T,
                             modes0=tuple(int(m) for m in ss.modes[-1]),
                             record_every=ss.steps_per_rev // record_per_rev, check_step=False)
    return tr, dt, n_steps, keep
