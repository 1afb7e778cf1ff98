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
  right angle: every step the loop may have split, and a few more), the derivative of that one step with
  respect to its start ``(p, v, a)``, by central differences of the compiled step itself (a located step is
  smooth in its start while the event stays inside it: the event time is the root of a polynomial whose
  coefficients are smooth), composed with the carried sensitivities.

So the event-time derivative enters through the differenced step, a few steps per period; the rest is the
analytic pass. Each event step is replayed from its recorded start and must reproduce the recorded end (the
loop's only memory between steps besides ``(p, v, a)``, the modes and the face forces is whether a face was
released in the step before, which the replay starts without): a replay that does not is reported through
``replay_mismatch`` in the result so that a caller can tell.

Measured against central differences of the located map (scaled monodromy, tests/rotor/dynamics/
test_period_map_events.py): Den Hartog's (1931) oscillator, non-stop (two located reversals per period) and
stick-slip (stick onsets and releases), agree to 1e-6. Table 4 (512 steps per revolution, one period after 60
revolutions from the linear state; a stick onset, a release and 2 to 6 edge crossings, contact onsets or losses, in
each period): 9.6e-7, 7.2e-7 and 8.8e-8 at 8 400, 10 500 and 12 000 rpm, against the Richardson extrapolation of
central differences of the whole map at 1e-7 and 2e-7 of each component's largest magnitude over the period, which
agrees with the one at 5e-8 and 1e-7 to 1.9e-7, 1.1e-7, 1.1e-7. Before contact onset and loss were located
(:mod:`rotor.dynamics.contact_events`) 10 500 rpm was 5.2e-6 against plain central differences; before a stop from a
creep was located whatever its start speed (:data:`rotor.dynamics.production_loop.EVENT_SPEED`) 8 400 rpm was 0.41;
with every event step differenced at 1e-6 and extrapolated, 3.7e-6, 3.6e-6, 1.5e-6 (:data:`EVENT_STEP_REL`). Not
every Table 4 speed has a map smooth at that scale: at 9 600 and 11 000 rpm the references at 1e-7 and 5e-8
themselves differ by O(1) (the slow-slip hold's rectilinear test, a threshold, decided differently after a 1e-7
perturbation: :mod:`rotor.dynamics.friction_events`, "Slow slips"); the map jumps there by about 1e-7 of the state
and has no derivative at that scale. The event steps' own differencing then shrinks its step past the threshold
(:func:`_step_jacobian`), so the monodromy is the derivative of the piece the orbit lies on: at 11 000 rpm its
largest multiplier 0.9845, where differencing across the threshold had given 1 257.

**Held steps, carried.** Most candidate steps are not split at all: a slow slip whose friction the loop holds at
Coulomb's force along the start velocity, or a face at rest held at ``μN`` (:mod:`rotor.dynamics.friction_events`,
"Slow slips"). Such a step is decided from its start alone and is smooth in it, so :func:`located_monodromy` replays
each candidate once; where no event was located in it (the loop's ``status[4]``) and it reproduces the record, it is
carried analytically (:func:`rotor.dynamics.period_map_kernels.carry` with the held forces and the slow slip's
``∂f/∂w = −μN (I − ŵŵᵀ)/|w|``), and only the split steps and the edge crossings are differenced. Measured on Table 4
(T/512, the three speeds above, same references): 9.9e-7, 2.2e-7, 5.5e-8 (differenced: 9.6e-7, 7.2e-7, 8.8e-8), 8 of
402 candidate steps differenced at 8 400 rpm, and the located map with its monodromy in 0.19 s instead of 1.1-1.5 s
(medians of 3, load 1). At 11 000 rpm the largest multiplier is then 0.98447 (0.98450 differenced with shrinking).
"""
from __future__ import annotations

import numpy as np

from rotor.dynamics.contact_events import edge_crossing
from rotor.dynamics.event_replays import replay_steps
from rotor.dynamics.period_map_kernels import carry, consistent_acceleration_jacobian
from rotor.dynamics.production_loop import RELEASE_HOLD, step_loop

#: central-difference step of an event step's derivative, relative to each component's range over the run, and the
#: shorter one of a step in which a face changed mode (its stick test and held-slip decisions are thresholds, so it is
#: smooth in its start over a shorter distance). Richardson-extrapolated (:func:`_step_jacobian`), so the steps are as
#: long as that smoothness allows: the round-off of the differenced step's Newton solves grows as the step shrinks.
#: Measured on Table 4 (T/512; located monodromy against the extrapolated central differences of the whole map,
#: tests/rotor/dynamics/test_period_map_events.py): 1e-6 for every event step 3.7e-6 / 3.6e-6 / 1.5e-6 at 8 400 /
#: 10 500 / 12 000 rpm; 3e-6 for every one 1.1e-6 / 1.1e-6 / 4.3e-7; 1e-5 for every one 8.2e-5 at 8 400 rpm (a switch
#: step differenced across its threshold); 1e-5 and 3e-6 for the switch steps 9.6e-7 / 7.2e-7 / 8.8e-8.
EVENT_STEP_REL = 1e-5
SWITCH_STEP_REL = 3e-6
#: an event step's column is extrapolated (Richardson) where its three central differences change in the ratio
#: 1 : 4 to this fraction (:func:`_step_jacobian`)
RICHARDSON_RATIO = 0.25
#: a column whose central differences at ``h/2`` and ``h`` differ by more than this fraction of their size is not
#: smooth at that scale (a threshold of the step, e.g. the slow-slip hold's rectilinear test, decided differently
#: within ``h`` of the recorded start): it is differenced again at ``h/10``, ``h/100``, ... down to
#: :data:`SHRINK_FLOOR` (:func:`_step_jacobian`)
SHRINK_TOL = 1e-2
#: the shortest differencing step of a column, relative to its component's scale (round-off below it)
SHRINK_FLOOR = 1e-9


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
    differenced. With ``carry_held`` False (the earlier route) a candidate is carried only where its plain replay
    (events not located) reproduces the record."""
    cand = np.array(event_steps(pm, tr), dtype=np.int64)
    held = np.zeros((len(rec_p), 2), dtype=np.int64)
    if cand.size == 0:
        return [], held
    starts = np.hstack([rec_p[cand], rec_v[cand], rec_a[cand]])
    ref = np.hstack([rec_p[cand + 1], rec_v[cand + 1], rec_a[cand + 1]])
    modes = np.ascontiguousarray(tr.modes[cand].astype(np.int64))
    phi = np.ascontiguousarray(tr.face_force[cand], dtype=float)
    ts = np.ascontiguousarray(tr.t[cand], dtype=float)
    ends, status = _replays_at(pm, starts, modes, phi, ts, carry_held)
    same = np.max(np.abs(ends - ref) / scales, axis=1) <= 1e-10
    if not carry_held:
        return cand[~same].tolist(), held
    pure = (status[:, 4] == 0) & same
    held[cand[pure]] = status[pure, 5:7]
    return cand[~pure].tolist(), held


def _replays_at(pm, starts, modes, phi, ts, locate: bool):
    """One step from each row of ``starts`` with its own modes, face forces and time, events located (``locate``)
    or not: the ends and statuses (:func:`rotor.dynamics.event_replays.replay_steps`)."""
    pre, opts = pm.prepared, pm.options
    return replay_steps(np.ascontiguousarray(starts, dtype=float), modes, phi, ts, pm.dt, pre.Ainv, pre.Dr, pre.Kr,
                        pre.Bt, pre.W, pre.S, pre.static, pre.orders, pre.cos, pre.sin, pre.omega_force, pre.P,
                        pre.limits, pre.n_faces, pre.s_yy, pre.a1, pm.reduced.support is not None, pm.params,
                        opts.beta, opts.gamma, opts.tol, opts.max_iter, opts.w_reg, opts.w_stick, opts.max_passes,
                        float(opts.stick_mean_weight), bool(opts.consistent_stick_onset), pre.Minv, pre.WM, pre.SM,
                        pre.Mr, bool(locate))


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
              pre.Minv, pre.WM, pre.SM, pre.Mr, bool(locate), rec["t"], rec["p"], rec["v"], rec["a"], rec["u"], rec["w"],
              rec["fc"], rec["fel"], rec["face"], rec["modes"], rec["its"], rec["passes"], status)
    return np.concatenate([p, v, a])


def _replays(pm, starts, modes, phi, t) -> np.ndarray:
    """The ends (rows) of one located step from each row of ``starts`` (``(K, 3 n_r)``, ``(p, v, a)``) at time ``t``
    (s), all with the face ``modes`` and forces ``phi``, in one compiled call (:func:`_replays_at`): the same step as
    :func:`_one_step`'s, without its dispatch per start."""
    k = len(starts)
    return _replays_at(pm, starts, np.tile(np.asarray(modes, dtype=np.int64), (k, 1)),
                       np.tile(np.asarray(phi, dtype=float), (k, 1, 1)), np.full(k, float(t)), True)[0]


def _step_jacobian(pm, start, modes, phi, t, scales, rel) -> tuple[np.ndarray, np.ndarray, int]:
    """``∂(p, v, a)_{n+1}/∂(p, v, a)_n`` (3nr × 3nr) of one located step by central differences, the
    replayed end state, and how many of its columns are not smooth down to :data:`SHRINK_FLOOR`.

    Each column is differenced at ``h/2``, ``h`` and ``2h`` (``h`` = ``rel`` of the component's scale).
    Where the three behave as a smooth function's (the changes ``d(h) − d(h/2)`` and ``d(2h) − d(h)`` in the ratio
    1 : 4 of the central difference's ``c h²`` error, to ``RICHARDSON_RATIO``) the column is extrapolated to zero
    step (Richardson, ``(4 d(h/2) − d(h))/3``): a stick onset after a slow creep has a large curvature (Table 4,
    10 500 rpm, T/512: ``c h²`` 1.5e-4 of the step's derivative at ``h`` = 1e-6, 3e-7 extrapolated). Elsewhere
    ``d(h)``: a step smooth in its start only over a shorter distance (a threshold decided in it) must not be
    extrapolated across two branches.

    Where ``d(h/2)`` and ``d(h)`` differ by more than :data:`SHRINK_TOL` of their size, a threshold of the step lies
    within ``h`` of its start, and ``d(h)`` is a jump over ``h``, not a derivative: the column is differenced again
    at ``h/10``, ``h/100``, ... until two agree (the derivative of the smooth piece the recorded start lies on), or
    counted as not smooth at :data:`SHRINK_FLOOR`. Measured on Table 4 at 11 000 rpm (T/512, one period after 60
    revolutions): four slow-slip steps differenced across the rectilinear test (``d(h/2)`` vs ``d(h)`` 33 to 1.8e5 of
    their size) had made the monodromy's largest entry 1.0e8 and its largest multiplier 1 257; with their columns
    shrunk to 1e-6 and 1e-7, 9.5e4 and 0.9845.

    All replays of a level go through one compiled call (:func:`_replays`)."""
    n3 = 3 * pm.nr
    scales = np.asarray(scales, float)
    # the starts (rows): per column j, per m in (1/2, 1, 2), +m h then −m h; the unperturbed start last
    ms, sgns = np.array([0.5, 1.0, 2.0]), np.array([1.0, -1.0])
    h = rel * scales
    starts = np.tile(start, (6 * n3 + 1, 1))
    cols = np.arange(n3)
    starts[:-1].reshape(n3, 3, 2, n3)[cols, :, :, cols] += sgns[None, None, :] * ms[None, :, None] * h[:, None, None]
    ends = _replays(pm, starts, modes, phi, t)
    e = ends[:-1].reshape(n3, 3, 2, n3)
    d = (e[:, :, 0] - e[:, :, 1]) / (2.0 * ms[None, :] * h[:, None])[:, :, None]     # (column, m, component)
    e1 = np.abs(d[:, 1] - d[:, 0]).max(axis=1)
    e2 = np.abs(d[:, 2] - d[:, 1] - 4.0 * (d[:, 1] - d[:, 0])).max(axis=1)
    smooth = e2 <= RICHARDSON_RATIO * 4.0 * e1
    J = np.where(smooth[:, None], (4.0 * d[:, 0] - d[:, 1]) / 3.0, d[:, 1]).T

    def disagree(half, full):       # (columns, components) -> (columns,)
        return (np.abs((half - full) / scales).max(axis=1)
                > SHRINK_TOL * np.abs(full / scales).max(axis=1))

    todo = np.flatnonzero(disagree(d[:, 0], d[:, 1]))
    r = rel
    while todo.size:
        r /= 10.0
        if r < SHRINK_FLOOR * (1.0 - 1e-9):
            break
        hs = r * scales[todo]
        st = np.tile(start, (4 * todo.size, 1)).reshape(todo.size, 2, 2, n3)
        st[np.arange(todo.size), :, :, todo] += sgns[None, None, :] * np.array([0.5, 1.0])[None, :, None] * hs[:, None, None]
        en = _replays(pm, st.reshape(-1, n3), modes, phi, t).reshape(todo.size, 2, 2, n3)
        dd = (en[:, :, 0] - en[:, :, 1]) / (2.0 * np.array([0.5, 1.0])[None, :] * hs[:, None])[:, :, None]
        ok = ~disagree(dd[:, 0], dd[:, 1])
        J[:, todo[ok]] = dd[ok, 0].T
        todo = todo[~ok]
    return np.ascontiguousarray(J), ends[-1].copy(), int(todo.size)


def located_monodromy(pm, tr, rec_p, rec_v, carry_held: bool = True) -> tuple[np.ndarray, float, int]:
    """``∂(p_N, v_N)/∂(p₀, v₀)`` of a located run (every step recorded in ``tr``, reduced ``rec_p``, ``rec_v``),
    the largest relative mismatch of an event step's replay against the record (–), and the number of event-step
    columns not smooth down to :data:`SHRINK_FLOOR` (:func:`_step_jacobian`: the map has no derivative there at the
    differencing's resolution, and the monodromy is not one). ``carry_held`` False differences the held steps too
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
    for n in differenced + [n_steps]:
        if n > start:
            carry(np.ascontiguousarray(rec_p[start:n + 1]), np.ascontiguousarray(rec_v[start:n + 1]),
                  np.ascontiguousarray(modes[start:n + 1]), Spv, Sa, *args, np.ascontiguousarray(held[start:n + 1]),
                  face[start:n + 1])
        if n == n_steps:
            break
        x0 = np.concatenate([rec_p[n], rec_v[n], rec_a[n]])
        rel = SWITCH_STEP_REL if np.any(modes[n] != modes[n + 1]) else EVENT_STEP_REL
        J, end, bad = _step_jacobian(pm, x0, modes[n], tr.face_force[n], tr.t[n], scales, rel)
        unsmooth += bad
        ref = np.concatenate([rec_p[n + 1], rec_v[n + 1], rec_a[n + 1]])
        mismatch = max(mismatch, float(np.max(np.abs(end - ref) / scales)))
        S = J @ np.vstack([Spv, Sa])
        Spv, Sa = np.ascontiguousarray(S[:2 * nr]), np.ascontiguousarray(S[2 * nr:])
        start = n + 1
    return Spv, mismatch, unsmooth
