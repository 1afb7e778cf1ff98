"""The monodromy of the period map with friction events located inside the step (``locate_events``).

With :attr:`rotor.dynamics.system.NewmarkOptions.locate_events` the production step loop splits a step at a
slip reversal or a stick onset (:mod:`rotor.dynamics.friction_events`), and at a contact onset or loss
(:mod:`rotor.dynamics.contact_events`): the event time moves with the state, so
the map is continuous where the plain step's map jumps when a switch moves by a step. Its derivative needs the
event time's derivative (the discrete form of the saltation matrix, Leine & van Campen 2002; Aizerman &
Gantmacher 1958), which the analytic pass of :mod:`rotor.dynamics.period_map_kernels` does not carry.

:func:`located_monodromy` therefore differentiates the recorded run in pieces:

* plain steps, the analytic pass (:func:`rotor.dynamics.period_map_kernels.carry`), exact as for the plain map;
* each *event step* (a step in which a face changed mode or a slipping face's velocity turned by more than a
  right angle: every step the loop may have split, and a few more), the derivative of that step with respect to
  its start ``(p, v, a)``, by central differences of the compiled step itself on a ladder of steps
  (:func:`_step_jacobian`; a located step is smooth in its start while the event stays inside it: the event time
  is the root of a polynomial whose coefficients are smooth), taken along the carried sensitivities
  (:data:`ALONG_SENSITIVITIES`);
* *blocks*: a step that holds a face at rest at ``μN`` along its start force takes that force's direction from
  the step before, the loop's memory outside ``(p, v, a)``; it is differenced together with the step that set the
  force, one block replayed from that step's start (:func:`blocks`). Measured at the 9 000 rpm orbit of Table 4
  (T/256, production options): the held step carried with its start force fixed put the monodromy 5.3e-2 from
  central differences of the whole map; 2e-6 with the block.

So the event-time derivative enters through the differenced steps, a few steps per period; the rest is the
analytic pass. Each event step is replayed from its recorded start and must reproduce the recorded end (the
loop's only memory between steps besides ``(p, v, a)``, the modes and the face forces is whether a face was
released in the step before, which the replay starts without): a replay that does not is reported through
``replay_mismatch`` in the result so that a caller can tell.

Measured against central differences of the located map (scaled monodromy, tests/rotor/dynamics/
test_period_map_events.py and test_monodromy_random_speeds.py; reports/published/perf-located-monodromy.md and
perf-monodromy-random.md for the current figures): Den Hartog's (1931) oscillator, non-stop and stick-slip, agree
to 1e-6. On Table 4 the differenced steps limit the agreement to about 1e-7 to 2e-6: a stick onset after a slow
creep has a large curvature in its start, and the slow-slip hold's thresholds (:mod:`rotor.dynamics.
friction_events`, "Slow slips") lie within 1e-6 of some starts. Not every Table 4 state has a map smooth at the
reference's scale: at 9 600 and 11 000 rpm, and at 7 of 10 random speeds of a transient state after 60 revolutions
(T/512), central differences at 1e-7 and 5e-8 themselves differ by O(1) (a threshold decided differently after a
1e-7 perturbation): the map jumps there by about 1e-7 of the state and has no derivative at that scale; the
monodromy is then the derivative of the smooth piece the orbit lies on, as far as the ladder resolves it.

**Held steps, carried.** Most candidate steps are not split at all: a slow slip whose friction the loop holds at
Coulomb's force along the start velocity, or a face at rest held at ``μN`` (:mod:`rotor.dynamics.friction_events`,
"Slow slips"). Such a step is decided from its start alone and is smooth in it, so :func:`located_monodromy` replays
each candidate once; where no event was located in it (the loop's ``status[4]``) and it reproduces the record, it is
carried analytically (:func:`rotor.dynamics.period_map_kernels.carry` with the held forces and the slow slip's
``∂f/∂w = −μN (I − ŵŵᵀ)/|w|``), and only the split steps and the edge crossings are differenced. Measured on Table 4
(T/512, 8 400 / 10 500 / 12 000 rpm, before the blocks and the ladder, same references): 9.9e-7, 2.2e-7, 5.5e-8 (differenced: 9.6e-7, 7.2e-7, 8.8e-8), 8 of
402 candidate steps differenced at 8 400 rpm, and the located map with its monodromy in 0.19 s instead of 1.1-1.5 s
(medians of 3, load 1). At 11 000 rpm the largest multiplier is then 0.98447 (0.98450 differenced with shrinking).
"""
from __future__ import annotations

import numpy as np

from rotor.dynamics.contact_events import edge_crossing
from rotor.dynamics.contact_step_derivative import contact_step_plan, contact_step_sensitivity
from rotor.dynamics.event_replays import replay_steps
from rotor.dynamics.period_map_kernels import carry, consistent_acceleration_jacobian
from rotor.dynamics.production_loop import RELEASE_HOLD, step_loop

#: the differencing steps of an event block's derivative (:func:`_step_jacobian`), relative to each component's scale:
#: a ladder from 5.12e-4 down by factors of 4 to 1.25e-7. Each column's derivative is taken where two successive
#: levels agree best. A fixed step fails on speeds nobody tuned it on: a stick onset after a slow creep has a
#: large curvature (its central difference at 1e-5 off by 4e-5 of the step's derivative at 9 000 rpm) and a
#: threshold of the step (the slow-slip hold's rectilinear test, a stick trial) can lie within 1e-6 of the
#: recorded start (columns not smooth at 1e-6 at 9 000 rpm), while at 16 767 rpm a release block needed 1e-6
#: (at 3e-6 the located monodromy was 1.9e-3 from central differences of the whole map; 3e-7 with the ladder).
#: Chosen on nine states: Table 4 (T/512 after 60 revolutions at 8 400, 10 500, 12 000 and 16 767 rpm; the orbits
#: at 6 292, 8 438 and 9 000 rpm) and the steel-in-aluminium scene (orbits at 8 806 and 9 233 rpm). Ladders from
#: 3.2e-5, 6.4e-5 and 1.28e-4 left 2.6e-6, 1.0e-6 and 1.6e-5 at one of them; this one with the refinement
#: (:data:`REFINE_TOL`) 1.2e-7 to 1.7e-6. Checked on speeds drawn at random (tests/rotor/dynamics/
#: test_monodromy_random_speeds.py, benchmarks/bench_monodromy_random.py).
LADDER = tuple(5.12e-4 * 0.25 ** k for k in range(7))
#: a column whose best agreement on :data:`LADDER` is worse than this fraction of its size is differenced again at
#: the steps halfway between (:func:`_step_jacobian`); a column also stops on the ladder once within it
#: (:func:`_ladder`). A step's derivative error is amplified by the steps after it: measured at the orbit of Table 4
#: at 12 241.9 rpm (T/256, drawn by seed 1840347559 of benchmarks/bench_monodromy_random.py; differenced steps
#: 14-25, 112, 123, 143, 172, 248, the error growing from 1e-7 at step 124 to 4.5e-6 at step 256 with no event
#: between), the located monodromy was 4.5e-6 from central differences of the whole map (converged to 7.7e-7) at
#: 1e-7 and 7.7e-7 at 1e-8 (1e-9: 7.9e-7), at 1.6 times the cost (0.58 -> 0.94 s); on 8 transient states of
#: random speeds (seed 4242) the same errors within the reference's convergence at 1.3-1.5 times the cost
REFINE_TOL = 1e-8
#: a column whose best two successive levels still differ by more than this fraction of its size is not smooth at
#: any level of the ladder (a threshold of the step within the smallest step of its start): counted and reported
SHRINK_TOL = 1e-2
#: how many levels of :data:`LADDER` every column is differenced at before any stops (the fewest that give one
#: agreement: two Richardson pairs); see :func:`_ladder`
FIRST_LEVELS = 3
#: the ladder evaluated level by level (:func:`_ladder`), a column stopped once its best agreement is within
#: :data:`REFINE_TOL` of its size; False: every column at every level (the earlier route, kept for side-by-side
#: runs in benchmarks/bench_monodromy_ladder.py)
PROGRESSIVE = True
#: a step split at a contact onset or loss alone is differentiated exactly (rotor/dynamics/contact_step_derivative.py)
#: instead of differenced; False: differenced as every event step (the earlier route, for side-by-side runs)
EXACT_CONTACT = True
#: consecutive differenced steps are one block (:func:`blocks`), differenced together from the first one's start,
#: so that what the step loop carries from one of them to the next beyond ``(p, v, a)`` (the face forces, a released
#: face's slip direction) moves with the perturbation as the loop moves it. Measured on the Table 4 rotor with the
#: steel-in-aluminium bearing at 15 287.5 rpm (T/256, the state 60 revolutions after the linear start; event steps
#: 35-38 differenced one by one): the located monodromy 3.3e-3 from central differences of the whole map (converged
#: to 5e-7), 1.7e-7 as one block; on Table 4 at 12 130.9 rpm (steps 28-30, a release then a rectilinear slow slip):
#: 2.7e-7 one by one, 2.2e-8 as one block. Entering every block one step earlier as well (the earlier route, which
#: merged such steps as a side effect) differenced a plain step whose start lies within the ladder of a threshold:
#: on Table 4 at 6 040.9 rpm (steps 223-227 entered at 223, reference converged to 2.0e-7) 1.58e-6; entered at 224,
#: 2.2e-7; at 222, 1.1e-7. False: every differenced step a block of its own unless :func:`blocks` chains it
MERGE_CONSECUTIVE = True
#: a ladder level whose replays of a column made other discrete decisions than the unperturbed replay (a stick trial,
#: a held slow slip, a located event, an end mode: :func:`_signature`) lies on another smooth piece of the step, and
#: the column is chosen on its other levels (:func:`_best_of_ladder`; at 10 893.9 rpm a narrow band at 2e-6 and
#: 2.5e-7, the pairs touching it left out, left the long levels only: 4.2e-5, 4.4e-7 on the other levels):
#: long levels past a threshold near the start agree with each other on that piece and not with the derivative at
#: the start. Measured on the period-4 orbit of Table 4 at 10 180.3 rpm (T/256, drawn by seed 1503871632 of
#: benchmarks/bench_monodromy_random.py; a release at step 381, the face then slipping slowly near the hold's speed
#: limit): the located monodromy 4.1e-3 from central differences of the whole map (converged to 5.3e-7) with every
#: level counted, 2.4e-7 without the levels off the piece. False: every level counts (the earlier route)
SAME_PIECE = True
#: every step of the run is replayed (one compiled call), not only the candidates of :func:`event_steps`, and a step
#: in which the loop located an event (its ``status[4]``) is differenced even where the record shows none: a plain
#: first pass whose velocity reversed (``w_n+1 · w_n ≤ 0``) is split at the reversal, and the located step may end
#: with its velocity turned by less than a right angle, so the record alone does not reveal it. Measured at the orbit
#: of Table 4 at 16 440.4 rpm (T/256, drawn by seed 1840347559 of benchmarks/bench_monodromy_random.py; step 220, a
#: face slowing from 1 437 to 712 ``w_reg``, turned by 89° at its end): carried as a plain step, the located
#: monodromy was 1.3e-1 from central differences of the whole map (converged to 2.8e-7); differenced, 2.6e-7. The
#: replays of the plain steps cost about one more run of the period. False: the candidates alone (the earlier route)
REPLAY_EVERY_STEP = True
#: a differenced block is differenced along the columns of the carried sensitivities ``∂(p, v, a)/∂(p₀, v₀)`` (each
#: scaled to 1 in the block's scales), giving their image directly, not along each component of ``(p, v, a)``
#: (:func:`_step_jacobian` with ``dirs``): a component the step barely depends on but whose carried sensitivity is large
#: multiplies the replays' noise in its column. Measured on the Table 4 rotor with the steel-in-aluminium bearing at
#: 11 148.3 rpm (T/256, the state 60 revolutions after the linear start; step 178 a release from rest at μN, its start
#: acceleration component 21 moving 9.2e4 of its scale per unit of the state's, the step's derivative in it 6.2e-4 of
#: the step's scale, differenced with noise of 2e-6 of that at the ladder's longest level): the located monodromy
#: 2.1e-6 from central differences of the whole map (converged to 4.1e-7) by components, 3.2e-7 along them; on the
#: 30 Table 4 speeds of seeds 1, 2, 3, 404, 505, 606, 707, 808, 909 and 1111 of tests/rotor/dynamics/
#: test_monodromy_random_speeds.py, 8.3e-9 to 4.5e-7 (by components 1.3e-8 to 4.4e-7, 2.4e-7 at 14 051.4 rpm now 2.5e-8)
#: False: the block's Jacobian by components, then multiplied (the earlier route)
ALONG_SENSITIVITIES = True


def event_steps(pm, tr) -> list[int]:
    """Indices ``n`` of the steps ``n → n+1`` of the every-step record ``tr`` (reduced system) in which a face
    changed mode or a slipping face's velocity turned by more than a right angle."""
    if not pm.n_faces:
        return []
    P = pm.prepared.P
    modes = tr.modes.astype(np.int64)
    out = set(np.flatnonzero(np.any(modes[1:, :pm.n_faces] != modes[:-1, :pm.n_faces], axis=1)).tolist())
    w_reg = pm.options.w_reg
    w_hold = RELEASE_HOLD * w_reg
    mu_N = pm.prepared.limits
    for k in range(pm.n_faces):
        wk = tr.w @ P[k].T                                  # (N+1, 2) the face's relative velocity
        turned = np.einsum("ij,ij->i", wk[:-1], wk[1:]) <= 0.0
        out |= set(np.flatnonzero(turned & (modes[:-1, k] == 0)).tolist())
        if pm.options.locate_events:
            # steps whose face force is held (production_loop: a slow slip, or a face at rest at mu_N)
            speed = np.hypot(wk[:-1, 0], wk[:-1, 1])
            force = np.hypot(tr.face_force[:-1, k, 0], tr.face_force[:-1, k, 1])
            held = (speed > w_reg) & (speed < w_hold) | (speed <= w_reg) & (force >= mu_N[k] * (1 - 1e-9))
            out |= set(np.flatnonzero(held & (modes[:-1, k] == 0)).tolist())
    if pm.options.locate_events and pm.reduced.support is not None:
        # contact onset or loss (rotor.dynamics.contact_events): an edge penetration changed sign over the step
        params = np.asarray(pm.params, dtype=float)
        out |= {n for n in range(len(tr.u) - 1) if edge_crossing(tr.u[n], tr.u[n + 1], params)}
    return sorted(out)


def _split_steps(pm, tr, rec_p, rec_v, rec_a, scales, carry_held: bool = True) -> tuple[list[int], np.ndarray]:
    """The candidate event steps (:func:`event_steps`) to difference, and how each step's friction was held
    (``(N, 2)``, the step loop's ``status[5:7]``, for :func:`rotor.dynamics.period_map_kernels.carry`).

    Each candidate is replayed once, located, from its recorded start (one compiled call for all of them). A step in
    which no event was located (``status[4]`` 0) and whose replay reproduces the record is carried analytically: a
    plain step (a central difference of a step where a face nearly sticks or has just stuck is less accurate:
    measured on Table 4 at 10 500 rpm, 3e-6 and 1e-5 against the analytic pass's 3e-7 at a stick onset and a
    release), or one that held a face's friction (module docstring, "Held steps, carried"). The rest are
    differenced. With :data:`REPLAY_EVERY_STEP` every other step is replayed too, and one in which the loop located an
    event (an event may leave no trace in the record) is a candidate; the rest stay carried as before (a stuck face's
    replay differs from its record at the stuck solve's tolerance: measured on ``paper-table4-inertial`` at 300 rpm,
    4 480 steps per revolution, both faces stuck, 4 409 of 4 480 such steps, which differenced took the orbit from
    1.3 s to 164 s of CPU). With ``carry_held`` False (the earlier route) a candidate is carried only where its plain
    replay (events not located) reproduces the record."""
    cand = np.array(event_steps(pm, tr), dtype=np.int64)
    held = np.zeros((len(rec_p), 2), dtype=np.int64)
    every = REPLAY_EVERY_STEP and carry_held and pm.n_faces
    steps = np.arange(len(rec_p) - 1, dtype=np.int64) if every else cand
    if steps.size == 0:
        return [], held
    ends, status = _replays_at(pm, np.hstack([rec_p[steps], rec_v[steps], rec_a[steps]]),
                               np.ascontiguousarray(tr.modes[steps].astype(np.int64)),
                               np.ascontiguousarray(tr.face_force[steps], dtype=float),
                               np.ascontiguousarray(tr.t[steps], dtype=float), carry_held)
    ref = np.hstack([rec_p[steps + 1], rec_v[steps + 1], rec_a[steps + 1]])
    same = np.max(np.abs(ends - ref) / scales, axis=1) <= 1e-10
    if not carry_held:
        return steps[~same].tolist(), held
    located = status[:, 4] != 0
    listed = np.isin(steps, cand) | located      # a step outside the candidates counts where it located an event
    pure = listed & ~located & same
    held[steps[pure]] = status[pure, 5:7]
    return steps[listed & ~pure].tolist(), held


def _replays_at(pm, starts, modes, phi, ts, locate: bool, n_steps: int = 1):
    """``n_steps`` steps (one block) from each row of ``starts`` with its own modes, face forces and time, events
    located (``locate``) or not: the ends and statuses (:func:`rotor.dynamics.event_replays.replay_steps`)."""
    pre, opts = pm.prepared, pm.options
    return replay_steps(np.ascontiguousarray(starts, dtype=float), modes, phi, ts, int(n_steps), pm.dt, pre.Ainv, pre.Dr, pre.Kr,
                        pre.Bt, pre.W, pre.S, pre.static, pre.orders, pre.cos, pre.sin, pre.omega_force, pre.P,
                        pre.limits, pre.n_faces, pre.s_yy, pre.a1, pm.reduced.support is not None, pm.params,
                        opts.beta, opts.gamma, opts.tol, opts.max_iter, opts.w_reg, opts.w_stick, opts.max_passes,
                        float(opts.stick_mean_weight), bool(opts.consistent_stick_onset), pre.Minv, pre.WM, pre.SM,
                        pre.Mr, bool(locate), True)[:2]


def _one_step(pm, p, v, a, modes, phi, t, locate: bool = True):
    """``(p, v, a)`` after one step of the compiled loop from the given start at time ``t`` (s), friction events
    located (``locate``) or not."""
    pre, opts, nr = pm.prepared, pm.options, pm.nr
    p, v, a, modes, phi = p.copy(), v.copy(), a.copy(), np.array(modes, dtype=np.int64), np.array(phi, float)
    rec = dict(t=np.zeros(2), p=np.zeros((2, nr)), v=np.zeros((2, nr)), a=np.zeros((2, nr)), u=np.zeros((2, 4)),
               w=np.zeros((2, 4)), fc=np.zeros((2, 4)), fel=np.zeros((2, 4)), face=np.zeros((2, 2, 2)),
               modes=np.zeros((2, 2), dtype=np.int8), its=np.zeros(2, dtype=np.int32), passes=np.zeros(2, dtype=np.int32))
    status = np.zeros(7, dtype=np.int64)
    step_loop(p, v, a, modes, phi, float(t), pm.dt, 1, 1, pre.Ainv, pre.Dr, pre.Kr, pre.Bt, pre.W, pre.S, pre.static,
              pre.orders, pre.cos, pre.sin, pre.omega_force, pre.P, pre.limits, pre.n_faces, pre.s_yy, pre.a1,
              pm.reduced.support is not None, pm.params, opts.beta, opts.gamma, opts.tol, opts.max_iter, opts.w_reg,
              opts.w_stick, opts.max_passes, float(opts.stick_mean_weight), bool(opts.consistent_stick_onset),
              pre.Minv, pre.WM, pre.SM, pre.Mr, bool(locate), True, rec["t"], rec["p"], rec["v"], rec["a"], rec["u"], rec["w"],
              rec["fc"], rec["fel"], rec["face"], rec["modes"], rec["its"], rec["passes"], status)
    return np.concatenate([p, v, a])


def _replays(pm, starts, modes, phi, t, n_steps: int = 1) -> np.ndarray:
    """The ends (rows) of ``n_steps`` located steps (one block) from each row of ``starts`` (``(K, 3 n_r)``,
    ``(p, v, a)``) at time ``t`` (s), all with the face ``modes`` and forces ``phi``, in one compiled call
    (:func:`_replays_at`): the same step as :func:`_one_step`'s, without its dispatch per start."""
    k = len(starts)
    return _replays_at(pm, starts, np.tile(np.asarray(modes, dtype=np.int64), (k, 1)),
                       np.tile(np.asarray(phi, dtype=float), (k, 1, 1)), np.full(k, float(t)), True, n_steps)[0]


def _signature(status, modes) -> np.ndarray:
    """The discrete decisions of replays (rows): a non-finite end and its step, least-residual steps, stick-onset
    re-projections, located events, how each face's friction was held in the last step body (the step loop's
    ``status``) and the end modes."""
    return np.hstack([status[:, :7], modes])


def _differences(pm, start, modes, phi, t, scales, n_steps, hs, cols, dirs=None) -> tuple[np.ndarray, np.ndarray]:
    """Central differences ``(level, column, component)`` of the block from ``start`` in the columns ``cols`` at the
    steps ``hs`` (relative to ``scales``), all replays in one compiled call (:func:`_replays_at`), and which of them
    left the start's smooth piece (``(level, column)``: a replay whose decisions, :func:`_signature`, differ from
    the unperturbed replay's; :data:`SAME_PIECE`). ``dirs`` ``(3 n_r, m)``: difference along its columns ``cols``
    instead (each in units of ``scales``), the derivative along ``dirs[:, c] · scales`` (:data:`ALONG_SENSITIVITIES`)."""
    n3 = start.size
    starts = np.tile(start, (2 * hs.size * cols.size + 1, 1))
    pert = starts[1:].reshape(hs.size, cols.size, 2, n3)
    idx = np.arange(cols.size)
    step = None if dirs is None else (dirs[:, cols] * scales[:, None]).T                 # (column, component)
    for li in range(hs.size):
        if step is None:
            pert[li, idx, 0, cols] += hs[li] * scales[cols]
            pert[li, idx, 1, cols] -= hs[li] * scales[cols]
        else:
            pert[li, :, 0] += hs[li] * step
            pert[li, :, 1] -= hs[li] * step
    ends, status, end_modes, _ = replay_steps_tiled(pm, starts, modes, phi, t, n_steps)
    e = ends[1:].reshape(hs.size, cols.size, 2, n3)
    sig = _signature(status, end_modes)
    off = np.any(sig[1:] != sig[0], axis=1).reshape(hs.size, cols.size, 2).any(axis=2)
    unit = scales[cols] if dirs is None else np.ones(cols.size)
    return (e[:, :, 0] - e[:, :, 1]) / (2.0 * hs[:, None, None] * unit[None, :, None]), off & SAME_PIECE


def replay_steps_tiled(pm, starts, modes, phi, t, n_steps):
    """:func:`_replays_at` from each row of ``starts`` with the same ``modes``, forces ``phi`` and time ``t``, events
    located: ends, statuses, end modes and end forces."""
    pre, opts = pm.prepared, pm.options
    k = len(starts)
    return replay_steps(np.ascontiguousarray(starts, dtype=float), np.tile(np.asarray(modes, dtype=np.int64), (k, 1)),
                        np.tile(np.asarray(phi, dtype=float), (k, 1, 1)), np.full(k, float(t)), int(n_steps), pm.dt,
                        pre.Ainv, pre.Dr, pre.Kr, pre.Bt, pre.W, pre.S, pre.static, pre.orders, pre.cos, pre.sin,
                        pre.omega_force, pre.P, pre.limits, pre.n_faces, pre.s_yy, pre.a1,
                        pm.reduced.support is not None, pm.params, opts.beta, opts.gamma, opts.tol, opts.max_iter,
                        opts.w_reg, opts.w_stick, opts.max_passes, float(opts.stick_mean_weight),
                        bool(opts.consistent_stick_onset), pre.Minv, pre.WM, pre.SM, pre.Mr, True, True)


def _best_of_ladder(hs, d, scales, off=None) -> tuple[np.ndarray, np.ndarray]:
    """Per column of ``d`` (central differences at the steps ``hs``, largest first): the Richardson extrapolation of
    the pair of successive levels that agrees best with the next pair, and that agreement (scaled, the largest
    over the components). ``off`` (level, column): levels whose replays left the start's smooth piece; such a
    column is chosen on its other levels alone, successive among themselves (the extrapolation takes any ratio of
    steps), so a narrow band off the piece between two levels does not shut out the levels past it. A column with
    fewer than three levels on the piece is chosen as without ``off``, and its agreement is infinite: refined, and
    counted as not smooth if no level of the refinement is on the piece. Measured on Table 4 at 10 893.9 rpm
    (T/256, the state 60 revolutions after the linear start, drawn by seed 404 in
    tests/rotor/dynamics/test_monodromy_random_speeds.py): the stick onset of step 239 missed in narrow bands at
    2e-6 and 2.5e-7 of column 48's scale, between levels on the piece whose central differences agree to 3e-7
    from 1.25e-7 down; with every pair touching such a band left out, only the long levels 8e-6 and 4e-6 were left
    (5e-5 off, their curvature) and the located monodromy was 4.2e-5 from central differences of the whole map."""
    rich, gap = _ladder_pairs(hs, d, scales)
    best = np.argmin(gap, axis=0)
    idx = np.arange(d.shape[1])
    J, agreement = rich[best + 1, idx], gap[best, idx]
    if off is None or not off.any():
        return J, agreement
    patterns, which = np.unique(np.asarray(off, bool).T, axis=0, return_inverse=True)
    for k, pattern in enumerate(patterns):
        cols = np.flatnonzero(which.ravel() == k)
        if not pattern.any():
            continue
        if np.count_nonzero(~pattern) < 3:
            agreement[cols] = np.inf
            continue
        rich_on, gap_on = _ladder_pairs(hs[~pattern], d[~pattern][:, cols], scales)
        best_on = np.argmin(gap_on, axis=0)
        J[cols], agreement[cols] = rich_on[best_on + 1, np.arange(cols.size)], gap_on[best_on, np.arange(cols.size)]
    return J, agreement


def _ladder_pairs(hs, d, scales) -> tuple[np.ndarray, np.ndarray]:
    """The Richardson extrapolations ``(pair, column, component)`` of the central differences ``d`` at successive
    steps ``hs`` (their ``c h²`` error removed, any ratio of steps) and each pair's agreement with the next
    ``(pair, column)``: scaled by ``scales``, the largest over the components, infinite where a replay diverged."""
    q = (hs[:-1] / hs[1:]) ** 2
    with np.errstate(over="ignore", invalid="ignore"):                               # a diverged replay: inf, nan
        rich = (q[:, None, None] * d[1:] - d[:-1]) / (q[:, None, None] - 1.0)         # (pair, column, component)
        gap = np.abs((rich[1:] - rich[:-1]) / scales[None, None, :]).max(axis=2)    # (pair, column)
    return rich, np.where(np.isnan(gap), np.inf, gap)


def _ladder(pm, start, modes, phi, t, scales, n_steps, progressive: bool = True, dirs=None):
    """The central differences of :data:`LADDER` ``(level, column, component)``, each column's choice on them
    (:func:`_best_of_ladder`) and its agreement: the first part of :func:`_step_jacobian`.

    ``progressive`` False: every column at every level, one compiled call. True: every column at the first
    :data:`FIRST_LEVELS` levels (one call), then level by level (one call each) only the columns whose best agreement
    so far is worse than :data:`REFINE_TOL` of their size; a column stops with the choice of :func:`_best_of_ladder`
    on the levels it has, and one that reaches the last level is chosen on the whole ladder, as before. Rows of ``d``
    at levels a column did not reach are left unset (a column that is refined afterwards has all of them).

    Why a column may stop early: its chosen pair and the next agree within :data:`REFINE_TOL`, the criterion under
    which the whole ladder is accepted without refinement. Measured on Table 4 (the state 24 revolutions after the
    linear start at 7 000 and 12 000 rpm, T/256, 936 event-step columns): with the whole ladder the chosen pair is
    the first (the longest steps) in 734 columns; level by level 609 stop after the first three levels, and the
    same 275 columns as with the whole ladder reach the refinement; single-step replays of the ladders and
    refinements 11 326 -> 7 222 and 5 628 -> 3 684 with :data:`REFINE_TOL` at 1e-7; at 1e-8, 25 424 -> 18 888 and
    12 712 -> 9 532 (reports/published/perf-monodromy-ladder.md, from benchmarks/bench_monodromy_ladder.py, for the
    times and the accuracy against central differences of the whole map).
    """
    hs = np.array(LADDER)
    n3 = start.size
    m = n3 if dirs is None else dirs.shape[1]           # columns: the components, or the directions ``dirs``
    cols = np.arange(m)
    if not progressive:
        d, off = _differences(pm, start, modes, phi, t, scales, n_steps, hs, cols, dirs)
        return (d, off, *_best_of_ladder(hs, d, scales, off))
    d = np.empty((hs.size, m, n3))
    J, gap = np.empty((m, n3)), np.empty(m)
    off = np.zeros((hs.size, m), dtype=bool)
    d[:FIRST_LEVELS], off[:FIRST_LEVELS] = _differences(pm, start, modes, phi, t, scales, n_steps, hs[:FIRST_LEVELS],
                                                        cols, dirs)
    active = cols
    for top in range(FIRST_LEVELS, hs.size + 1):
        J[active], gap[active] = _best_of_ladder(hs[:top], d[:top, active], scales, off[:top, active])
        size = np.maximum(np.abs(J[active] / scales[None, :]).max(axis=1), 1e-300)
        active = active[gap[active] > REFINE_TOL * size]
        if top == hs.size or not active.size:
            break
        got, got_off = _differences(pm, start, modes, phi, t, scales, n_steps, hs[top:top + 1], active, dirs)
        d[top, active], off[top, active] = got[0], got_off[0]
    return d, off, J, gap


def _refine(pm, start, modes, phi, t, scales, n_steps, d, off, redo, progressive: bool = True, dirs=None):
    """The choice (:func:`_best_of_ladder`) and agreement of the columns ``redo`` on the ladder merged with its half
    levels (:data:`LADDER` times 1/2, each between its level and the next), ``d`` their differences at every level
    of :data:`LADDER`: the refinement of :func:`_step_jacobian`.

    ``progressive`` False: every half level for every column, one compiled call. True: the half levels from the
    longest, one call each; after each, a column is chosen on the merged ladder up to the next full level (known)
    and stops there once its best agreement is within :data:`REFINE_TOL` of its size, as in :func:`_ladder`; one
    that reaches the last half level is chosen on the whole merged ladder, as before."""
    hs = np.array(LADDER)
    n3 = start.size
    both = np.empty(2 * hs.size)
    both[0::2], both[1::2] = hs, hs * 0.5
    merged = np.empty((2 * hs.size, redo.size, n3))
    merged[0::2] = d
    moff = np.zeros((2 * hs.size, redo.size), dtype=bool)
    moff[0::2] = off
    if not progressive:
        merged[1::2], moff[1::2] = _differences(pm, start, modes, phi, t, scales, n_steps, hs * 0.5, redo, dirs)
        return _best_of_ladder(both, merged, scales, moff)
    J, gap = np.empty((redo.size, n3)), np.empty(redo.size)
    active = np.arange(redo.size)
    for k in range(hs.size):
        got, got_off = _differences(pm, start, modes, phi, t, scales, n_steps, hs[k:k + 1] * 0.5, redo[active],
                                    dirs)
        merged[2 * k + 1, active], moff[2 * k + 1, active] = got[0], got_off[0]
        top = min(2 * k + 3, both.size)
        J[active], gap[active] = _best_of_ladder(both[:top], merged[:top, active], scales, moff[:top, active])
        size = np.maximum(np.abs(J[active] / scales[None, :]).max(axis=1), 1e-300)
        active = active[gap[active] > REFINE_TOL * size]
        if not active.size:
            break
    return J, gap


def _step_jacobian(pm, start, modes, phi, t, scales, n_steps: int = 1, dirs=None) -> tuple[np.ndarray, np.ndarray,
                                                                                              int]:
    """``∂(p, v, a)_{n+k}/∂(p, v, a)_n`` (3nr × 3nr) of ``k = n_steps`` located steps (one step, or a block whose
    face forces carry over: :func:`blocks`) by central differences, the replayed end state, and how many of its
    columns are not smooth at any level of the ladder.

    Each column is differenced at the levels ``h`` of :data:`LADDER` (relative to its component's scale), from the
    longest, until its best agreement is within :data:`REFINE_TOL` (:func:`_ladder`; every level with
    :data:`PROGRESSIVE` False); the central differences of successive levels are Richardson-extrapolated (their
    ``c h²`` error removed), and the column takes the extrapolation of the pair of successive levels that agrees
    best with the next one (scaled by the components' scales): long enough steps where round-off and the Newton
    solves' tolerance would dominate a short one, short enough where the step's curvature (a stick onset after a
    slow creep) or a threshold decided within ``h`` of the start (the slow-slip hold's rectilinear test) spoils a
    long one. A column whose best agreement is worse than :data:`REFINE_TOL` of its size is differenced again
    halfway between the levels (:data:`LADDER` times 1/2, :func:`_refine`, level by level as the ladder) and chosen
    again on the merged ladder; one whose best agreement is still worse than :data:`SHRINK_TOL` of its size is
    counted as not smooth. ``dirs`` ``(3 n_r, m)``: the derivatives along its columns (in units of ``scales``)
    instead, ``(3 n_r, m)`` (:data:`ALONG_SENSITIVITIES`)."""
    scales = np.asarray(scales, float)
    d, off, J, gap = _ladder(pm, start, modes, phi, t, scales, n_steps, PROGRESSIVE, dirs)
    size = np.maximum(np.nan_to_num(np.abs(J / scales[None, :]), posinf=0.0).max(axis=1), 1e-300)
    redo = np.flatnonzero(gap > REFINE_TOL * size)
    if redo.size:
        J[redo], gap[redo] = _refine(pm, start, modes, phi, t, scales, n_steps, d[:, redo], off[:, redo], redo,
                                     PROGRESSIVE, dirs)
    for c in np.flatnonzero(~np.all(np.isfinite(J), axis=1)):
        # every pair of levels touched a replay that did not end finite: the shortest level whose difference is
        # finite, counted as not smooth (its agreement infinite)
        fin = [k for k in range(len(LADDER) - 1, -1, -1) if np.all(np.isfinite(d[k, c]))]
        J[c], gap[c] = (d[fin[0], c] if fin else 0.0), np.inf
    size = np.maximum(np.abs(J / scales[None, :]).max(axis=1), 1e-300)
    unsmooth = int(np.count_nonzero(gap > SHRINK_TOL * size))
    end = _replays(pm, start[None, :], modes, phi, t, n_steps)[0]
    return np.ascontiguousarray(J.T), end, unsmooth


def located_monodromy(pm, tr, rec_p, rec_v, carry_held: bool = True) -> tuple[np.ndarray, float, int]:
    """``∂(p_N, v_N)/∂(p₀, v₀)`` of a located run (every step recorded in ``tr``, reduced ``rec_p``, ``rec_v``),
    the largest relative mismatch of an event step's replay against the record (–), and the number of event-step
    columns not smooth at any level of :data:`LADDER` (:func:`_step_jacobian`: the map has no derivative there at
    the differencing's resolution, and the monodromy is not one). ``carry_held`` False differences the held steps too
    (the earlier route, kept for benchmarks/bench_located_monodromy.py)."""
    pre, opts, nr = pm.prepared, pm.options, pm.nr
    rec_a = tr.a @ pm.T
    modes = np.ascontiguousarray(tr.modes.astype(np.int64))
    has_support = pm.reduced.support is not None
    args = (pm.dt, opts.beta, opts.gamma, pm.AK, pm.AD, pm.MK, pm.MD, pre.Bt, pre.W, pre.S, pre.WM, pre.SM, pre.P,
            pre.limits, pre.a1, has_support, pm.params, opts.w_reg, bool(opts.consistent_stick_onset))
    Spv = np.eye(2 * nr)
    if has_support:
        Sa = consistent_acceleration_jacobian(rec_p[0], rec_v[0], pre.Bt, pm.MK, pm.MD, pre.WM, pre.SM, pre.P,
                                              modes[0].copy(), pre.limits, pre.a1, pm.params, opts.w_reg)
    else:
        Sa = np.hstack([-pm.MK, -pm.MD])
    # differencing steps from each component's own range over the run, at least 1e-3 of its block's largest
    # magnitude (a static offset in max |p| makes steps from it too long: measured on Table 4, 3e-4 truncation of
    # the located step's derivative at 1e-7 of max |p|; a motionless component needs the floor against round-off)
    block = np.repeat([max(float(np.abs(r).max()), 1e-12) for r in (rec_p, rec_v, rec_a)], nr)
    scales = np.maximum(np.concatenate([np.ptp(rec_p, 0), np.ptp(rec_v, 0), np.ptp(rec_a, 0)]), 1e-3 * block)
    n_steps, start, mismatch, unsmooth = len(rec_p) - 1, 0, 0.0, 0
    # the candidate steps the loop did not split but held a face's friction: smooth in their start, carried
    # analytically with the held forces' derivative (carry's rec_held); the others differenced
    differenced, held = _split_steps(pm, tr, rec_p, rec_v, rec_a, scales, carry_held)
    face = np.ascontiguousarray(tr.face_force, dtype=float)
    zero_load = np.zeros((nr, 2 * nr))
    x_at = lambda n: np.concatenate([rec_p[n], rec_v[n], rec_a[n]])   # noqa: E731
    plans = {}
    if EXACT_CONTACT:     # the contact steps differentiated exactly (contact_step_derivative), the rest differenced
        for first, last in blocks(differenced, held, modes):
            if first == last:
                plan = contact_step_plan(pm, x_at(first), modes[first], face[first], tr.t[first], x_at(first + 1),
                                         scales)
                if plan is not None:
                    plans[first] = plan
    segments = blocks([n for n in differenced if n not in plans], held, modes, MERGE_CONSECUTIVE)
    inside = {n for a, b in segments for n in range(a, b + 1)}
    segments = sorted(segments + [(n, n) for n in plans if n not in inside])
    for first, last in segments + [(n_steps, n_steps)]:
        if first > start:
            carry(np.ascontiguousarray(rec_p[start:first + 1]), np.ascontiguousarray(rec_v[start:first + 1]),
                  np.ascontiguousarray(modes[start:first + 1]), Spv, Sa, *args,
                  np.ascontiguousarray(held[start:first + 1]), face[start:first + 1], zero_load)
        if first == n_steps:
            break
        start = last + 1
        if first in plans and first not in inside:
            Spv, Sa, miss = contact_step_sensitivity(pm, plans[first], Spv, Sa)
            mismatch = max(mismatch, miss)
            continue
        U = np.vstack([Spv, Sa])
        size = np.abs(U / scales[:, None]).max(axis=0)              # each sensitivity column scaled to 1
        size = np.where(size > 0.0, size, 1.0)
        dirs = U / scales[:, None] / size if ALONG_SENSITIVITIES else None
        J, end, bad = _step_jacobian(pm, x_at(first), modes[first], face[first], tr.t[first], scales, last + 1 - first,
                                     dirs)
        unsmooth += bad
        mismatch = max(mismatch, float(np.max(np.abs(end - x_at(last + 1)) / scales)))
        S = J * size if ALONG_SENSITIVITIES else J @ U
        Spv, Sa = np.ascontiguousarray(S[:2 * nr]), np.ascontiguousarray(S[2 * nr:])
    return Spv, mismatch, unsmooth


def blocks(differenced: list[int], held: np.ndarray, modes: np.ndarray | None = None,
           merge_consecutive: bool = False) -> list[tuple[int, int]]:
    """The steps to difference, as blocks ``(first, last)`` of consecutive steps replayed in one call.

    The step loop remembers more than ``(p, v, a)`` from one step to the next: the face forces, and a face just
    released slips with its release force's direction until it is fast (rotor/dynamics/friction_events.py,
    "Release"). A derivative of one step in ``(p, v, a)`` alone (:func:`_step_jacobian` with the recorded forces,
    or :func:`rotor.dynamics.period_map_kernels.carry`, which holds them constant) misses how that memory moves with
    the start, so such steps are differenced together with the step that set it, one block from that step's start:

    * a step that holds a face at rest at ``μN`` along its start force (``held`` 2: the step loop's ``status[5:7]``,
      friction_events "Slow slips") joins the step before it (a release, or a stuck step whose multiplier the force
      is). Measured at the 9 000 rpm orbit of Table 4 (T/256, production options): the end of such a step moves 6e4
      of its scale per unit change of the held force's direction; carried with the force fixed, the monodromy was
      5.3e-2 from central differences of the whole map, 2e-6 with the block;
    * the held steps of a face right after its release (``modes`` 1 then 0 for the face; ``held`` not 0 for it)
      join the release step. Measured on Table 4 at 9 916.2 rpm (T/512, 60 revolutions after the linear start): one
      held slow slip after a release, carried, 6.5e-2; differenced alone, 6.5e-2; in the release's block 1.7e-7.

    With ``merge_consecutive`` (:data:`MERGE_CONSECUTIVE`) consecutive differenced steps are one block.

    Blocks that touch or overlap merge; every other differenced step is a block of its own."""
    held = np.asarray(held)
    marks = set(differenced)
    chained: set[int] = set()
    for n in np.flatnonzero(np.any(held == 2, axis=1)).tolist():
        marks |= {n, n - 1}                 # the step that set the force the held step starts from
        chained.add(n)
    if modes is not None:
        modes = np.asarray(modes)
        for k in range(min(2, modes.shape[1])):
            for n in np.flatnonzero((modes[:-1, k] == 1) & (modes[1:, k] == 0)).tolist():
                marks.add(n)
                m = n + 1
                while m < len(held) and held[m, k] != 0:
                    marks.add(m)
                    chained.add(m)
                    m += 1
    if merge_consecutive:
        chained |= marks
    out: list[list[int]] = []
    for n in sorted(m for m in marks if m >= 0):
        if out and n == out[-1][1] + 1 and n in chained:
            out[-1][1] = n                   # joins the block of the step before it
        elif out and n <= out[-1][1]:
            continue
        else:
            out.append([n, n])
    return [(a, b) for a, b in out]
