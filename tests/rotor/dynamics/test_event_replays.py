"""One step replayed from many starts in one compiled call (rotor.dynamics.event_replays) against the same step
replayed one start at a time through the step loop's Python entry (rotor.dynamics.period_map_events._one_step).

Den Hartog's (1931) stick-slip oscillator of ``dynamics_standin.friction_body`` (F = 0.7 N at ω = 30 rad/s, P0 = 1 N,
ζ = 0.1; 200 steps per period, stick onsets and releases located in every period), the period after 40 from rest.
Expected: the one-by-one replays bit for bit (the same compiled step from the same start), at the event steps the
located monodromy differences, from starts perturbed as its central differences perturb them."""
from __future__ import annotations

import math

import numpy as np

from dynamics_standin import friction_body
from rotor.dynamics import period_map_events as pme
from rotor.dynamics.period_map import period_map, period_map_setup
from rotor.dynamics.production import simulate_production
from rotor.dynamics.system import NewmarkOptions

NPER = 200


def test_batched_replays_equal_one_by_one_replays_at_located_events():
    omega = 30.0
    s = friction_body(F=0.7, P0=1.0, omega=omega, zeta=0.1)
    pm = period_map_setup(s, 2 * math.pi / omega / NPER, NewmarkOptions(tol=1e-13, locate_events=True),
                          check_step=False)
    r = period_map(pm, np.zeros(2 * pm.nr), 0.0, 40 * NPER, modes0=(0, 0), jacobian=False)
    nr = pm.nr
    tr = simulate_production(pm.reduced, pm.dt, NPER, pm.T @ r.state[:nr], pm.T @ r.state[nr:], t0=r.t,
                             modes0=tuple(r.modes), options=pm.options, record_every=1, check_step=False,
                             prepared=pm.prepared)
    rec_p, rec_v, rec_a = tr.q @ pm.T, tr.v @ pm.T, tr.a @ pm.T
    block = np.repeat([np.abs(x).max() for x in (rec_p, rec_v, rec_a)], nr)   # as located_monodromy's scales
    scales = np.maximum(np.concatenate([np.ptp(rec_p, 0), np.ptp(rec_v, 0), np.ptp(rec_a, 0)]), 1e-3 * block)
    split, held = pme._split_steps(pm, tr, rec_p, rec_v, rec_a, scales)
    assert len(split) >= 2                                  # located events in the period (differenced; 4 measured)
    assert np.count_nonzero(held.any(axis=1)) >= 2          # held steps, carried (18 measured)
    # the candidate steps' replays batched with a start, modes, face forces and time each: the one-by-one ones
    cand = np.array(pme.event_steps(pm, tr))
    starts = np.hstack([rec_p[cand], rec_v[cand], rec_a[cand]])
    for locate in (False, True):
        ends, status = pme._replays_at(pm, starts, tr.modes[cand].astype(np.int64), tr.face_force[cand],
                                       tr.t[cand].astype(float), locate)
        for i, n in enumerate(cand):
            one = pme._one_step(pm, rec_p[n], rec_v[n], rec_a[n], tr.modes[n], tr.face_force[n], tr.t[n], locate)
            assert np.array_equal(ends[i], one)
        if locate:
            assert np.array_equal(status[np.isin(cand, np.flatnonzero(held.any(axis=1))), 4],
                                  np.zeros(np.count_nonzero(held.any(axis=1)), dtype=np.int64))   # carried: not split
    rng = np.random.default_rng(3)
    for n in split:
        x0 = np.concatenate([rec_p[n], rec_v[n], rec_a[n]])
        starts = x0 + rng.standard_normal((5, 3 * nr)) * 1e-5 * scales
        starts[0] = x0
        got = pme._replays(pm, starts, tr.modes[n], tr.face_force[n], tr.t[n])
        for k, x in enumerate(starts):
            one = pme._one_step(pm, x[:nr], x[nr:2 * nr], x[2 * nr:], tr.modes[n], tr.face_force[n], tr.t[n])
            assert np.array_equal(got[k], one)
        # the unperturbed replay is the run's own located step
        assert np.abs(got[0] - np.concatenate([rec_p[n + 1], rec_v[n + 1], rec_a[n + 1]])).max() <= 1e-10 * \
            np.abs(np.concatenate([rec_p, rec_v, rec_a], axis=1)).max()
